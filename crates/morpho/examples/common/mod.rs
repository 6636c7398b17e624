//! Helpers shared by the `bench_*` examples (`mod common;`): where the shared data lives, the
//! process's CPU time and peak memory, and the generated 2D inputs of the Delaunay benches. Not
//! an example itself (cargo builds `examples/*.rs` only).
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

/// Peak resident memory of this process (VmHWM) in KiB, from /proc/self/status.
pub fn vm_hwm_kib() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// The `grid` input of the 2D Delaunay benches: the ⌊√n⌉² integer lattice points.
pub fn grid_2d(n: usize) -> Vec<morpho::geom::Point2> {
    let side = (n as f64).sqrt().round() as usize;
    (0..side * side)
        .map(|k| morpho::geom::Point2::new((k % side) as f64, (k / side) as f64))
        .collect()
}

/// The `curve` input of the 2D Delaunay benches: `n` points along the flower
/// `r = 1 + 0.3 sin 5t`, each coordinate jittered by up to ±1e-9 (ChaCha8, seed 7).
pub fn flower_curve(n: usize) -> Vec<morpho::geom::Point2> {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    let tau = std::f64::consts::TAU;
    (0..n)
        .map(|k| {
            let t = tau * k as f64 / n as f64;
            let r = 1.0 + 0.3 * (5.0 * t).sin();
            let jx = (rng.gen::<f64>() - 0.5) * 2e-9;
            let jy = (rng.gen::<f64>() - 0.5) * 2e-9;
            morpho::geom::Point2::new(r * t.cos() + jx, r * t.sin() + jy)
        })
        .collect()
}

/// `n` query points uniform in the box `b`, from a fixed xorshift64 seed: the same points on
/// every run and in every example that uses it (`bench_flint3`, `bench_baselines3`).
pub fn box_points3(b: &morpho::geom::Aabb3, n: usize) -> Vec<morpho::geom::Point3> {
    let mut s: u64 = 0x2545_f491_4f6c_dd1d;
    let mut unit = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..n)
        .map(|_| {
            morpho::geom::Point3::new(
                b.min[0] + (b.max[0] - b.min[0]) * unit(),
                b.min[1] + (b.max[1] - b.min[1]) * unit(),
                b.min[2] + (b.max[2] - b.min[2]) * unit(),
            )
        })
        .collect()
}
