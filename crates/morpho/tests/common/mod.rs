//! What the integration tests of both crates share: where the real data lives.
//!
//! The data folder is, in order: `$MORPHO_DATA` when set (the name the Python tests use too);
//! `../shared/data` beside the repository (a clone, CI); or one level further up (a git worktree
//! in `<root>/wt/<name>`). Tests that need it skip with a note when it is absent, so a machine
//! without the data runs everything else. `morpho-cli`'s tests include this file by path.
#![allow(dead_code)] // each test binary uses part of it

use std::path::PathBuf;

/// The shared data folder, or `None` (with a note on stderr) when it is absent.
pub fn data_dir() -> Option<PathBuf> {
    let found = match std::env::var_os("MORPHO_DATA") {
        Some(d) => Some(PathBuf::from(d)).filter(|d| d.is_dir()),
        None => [
            concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/data"),
            concat!(env!("CARGO_MANIFEST_DIR"), "/../../../../shared/data"),
        ]
        .into_iter()
        .map(PathBuf::from)
        .find(|d| d.is_dir()),
    };
    if found.is_none() {
        eprintln!(
            "note: the shared data folder (../shared/data or $MORPHO_DATA) is absent; skipping"
        );
    }
    found
}

/// A file or folder inside the data folder, or `None` (with a note) when it is absent.
pub fn data(rel: &str) -> Option<PathBuf> {
    let p = data_dir()?.join(rel);
    if !p.exists() {
        eprintln!("note: {} is absent; skipping", p.display());
        return None;
    }
    Some(p)
}
