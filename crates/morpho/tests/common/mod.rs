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

/// Marsaglia's 64-bit xorshift, shifts (13, 7, 17): reproducible test inputs (the flint tests'
/// queries and perturbations).
pub struct XorShift(pub u64);

impl XorShift {
    /// The next state.
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// Uniform in [0, 1): the top 53 bits of the next state.
    pub fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// The next state modulo `n` (`n > 0`).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// The mesh `meshes/NAME` of the shared data folder, or `None` when the folder is absent.
pub fn real_mesh(name: &str) -> Option<morpho::mesh::TriMesh> {
    let p = data(&format!("meshes/{name}"))?;
    Some(morpho::io::read_mesh(&p).expect("read mesh"))
}
