//! Helpers shared by the `bench_*` examples (`mod common;`): where the shared data lives and
//! the process's CPU time. Not an example itself (cargo builds `examples/*.rs` only).
#![allow(dead_code)] // each example uses what it needs

/// `shared/data` beside the repository (`../shared/data` from the checkout, or one level
/// further up from a worktree), if it exists.
pub fn data_dir() -> Option<std::path::PathBuf> {
    for d in [
        concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/data"),
        concat!(env!("CARGO_MANIFEST_DIR"), "/../../../../shared/data"),
    ] {
        let p = std::path::PathBuf::from(d);
        if p.is_dir() {
            return Some(p);
        }
    }
    None
}

/// CPU seconds (user + system) of this process so far, from /proc/self/stat (0 elsewhere).
pub fn cpu_seconds() -> f64 {
    let Ok(s) = std::fs::read_to_string("/proc/self/stat") else {
        return 0.0;
    };
    let Some(rest) = s.rsplit_once(')').map(|(_, r)| r) else {
        return 0.0;
    };
    let f: Vec<&str> = rest.split_whitespace().collect();
    let tick = |k: usize| f.get(k).and_then(|v| v.parse::<f64>().ok()).unwrap_or(0.0);
    // fields 14 and 15 of stat (utime, stime) are 12 and 13 after the command name
    (tick(11) + tick(12)) / 100.0
}
