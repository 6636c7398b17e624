//! One 2D Delaunay run per process, for the thread-count comparison of issue 23 item 3 (the
//! split path of `delaunay/par2.rs`). Run by `bench/par2d.sh`, which alternates thread counts:
//!
//! ```text
//! RAYON_NUM_THREADS=1|2 cargo run --release --example bench_delaunay2d_par -p morpho -- \
//!     DIST [N] [--split auto|always|never|merge]
//! ```
//!
//! DIST is `uniform` (N points in the unit square, ChaCha8 seed 42), `grid` (√N × √N integers)
//! or `curve` (the jittered flower of `bench_delaunay2d.rs`). `--split auto` (default) is what
//! `triangulate_2d` does: the split path on more than one rayon thread; `--split merge` is the
//! divide and conquer with the exact zipper merge of `delaunay/merge2.rs`. Prints one line: wall and
//! CPU seconds (user + system of this process, from /proc/self/stat) of the triangulation call,
//! the peak resident memory (VmHWM) of the process, the triangle count, a digest of the sorted
//! triangle set (equal across paths and thread counts) and the 1-minute load average.

mod common;

use common::{cpu_seconds, flower_curve, grid_2d, vm_hwm_kib};
use morpho::geom::Point2;
use morpho::internals::delaunay::{triangulate_split, Split};
use rand::{Rng, SeedableRng};
use std::time::Instant;

fn points(dist: &str, n: usize) -> Vec<Point2> {
    match dist {
        "uniform" => {
            let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(42);
            (0..n)
                .map(|_| Point2::new(rng.gen::<f64>(), rng.gen::<f64>()))
                .collect()
        }
        "grid" => grid_2d(n),
        "curve" => flower_curve(n),
        d => panic!("unknown DIST {d} (uniform, grid, curve)"),
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let dist = args.first().cloned().unwrap_or_else(|| "uniform".into());
    let mut n = 1_000_000;
    let mut split = Split::Auto;
    let mut i = 1;
    while i < args.len() {
        match args[i].as_str() {
            "--split" => {
                split = match args.get(i + 1).map(String::as_str) {
                    Some("always") => Split::Always,
                    Some("never") => Split::Never,
                    Some("merge") => Split::Merge,
                    _ => Split::Auto,
                };
                i += 1;
            }
            a => n = a.parse().expect("N must be an integer"),
        }
        i += 1;
    }
    let p = points(&dist, n);
    let c0 = cpu_seconds();
    let t0 = Instant::now();
    let d = triangulate_split(&p, split).expect("triangulate");
    let wall = t0.elapsed().as_secs_f64();
    let cpu = cpu_seconds() - c0;
    let mut canon: Vec<[u32; 3]> = d
        .triangles
        .iter()
        .map(|t| {
            let k = (0..3).min_by_key(|&i| t[i]).unwrap();
            [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
        })
        .collect();
    canon.sort_unstable();
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    for w in canon.iter().flatten() {
        h = (h ^ *w as u64).wrapping_mul(0x100_0000_01b3);
    }
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!(
        "{dist:8} threads {} split {split:?} wall {wall:.3} s cpu {cpu:.2} s peak {:.0} MiB triangles {} digest {h:016x} load {}",
        rayon::current_num_threads(),
        vm_hwm_kib().unwrap_or(0) as f64 / 1024.0,
        d.triangles.len(),
        load.split_whitespace().next().unwrap_or("?"),
    );
}
