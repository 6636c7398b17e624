//! Benchmark of the 3D Delaunay tetrahedralization on N uniform random points in the unit cube.
//!
//! ```text
//! cargo run --release -p morpho --example bench_delaunay3d -- [N] [--seed S] [--sphere] [--grid G] [--write points.f64] [--tets tets.u32]
//! ```
//! `--sphere`: N points uniform on the unit sphere (normalized Gaussian triples, rounded to
//! doubles) — the near-cospherical case where the in-sphere filter fails often (issue 23).
//! Prints points/second and the peak resident memory (VmHWM) per point. `--write` stores the
//! points as little-endian f64 triples, `--tets` the tetrahedra (input indices, little-endian u32
//! quadruples) for `bench/delaunay3d_qhull.py` (scipy/Qhull timing and tetrahedron-set check).
//! `--engine auto|seq|split`: the facade's choice (default; the split-and-merge path with more
//! than one rayon thread on large inputs), the one-thread engine, or the split path forced
//! (its counters are printed). Thread count from `RAYON_NUM_THREADS`; the load average is
//! printed with every run (`bench/delaunay3d_threads.sh` takes turns 1 vs 2 threads).

mod common;

use common::{cpu_seconds, vm_hwm_kib};
use morpho::delaunay::triangulate_3d;
use morpho::geom::Point3;
use rand::{Rng, SeedableRng};
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut n = 1_000_000usize;
    let mut seed = 1u64;
    let mut write: Option<String> = None;
    let mut tets: Option<String> = None;
    let mut grid = 0usize;
    let mut check = false;
    let mut sphere = false;
    let mut engine = String::from("auto");
    let mut i = 0;
    while i < args.len() {
        match args[i].as_str() {
            "--seed" => {
                i += 1;
                seed = args[i].parse().expect("seed");
            }
            "--grid" => {
                i += 1;
                grid = args[i].parse().expect("grid size");
            }
            "--check" => check = true,
            "--sphere" => sphere = true,
            "--engine" => {
                i += 1;
                engine = args[i].clone();
            }
            "--tets" => {
                i += 1;
                tets = Some(args[i].clone());
            }
            "--write" => {
                i += 1;
                write = Some(args[i].clone());
            }
            a => n = a.parse().expect("N"),
        }
        i += 1;
    }
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let pts: Vec<Point3> = if grid > 0 {
        // integer lattice grid³ (maximally cospherical), in a shuffled order
        use rand::seq::SliceRandom;
        let mut v: Vec<Point3> = (0..grid * grid * grid)
            .map(|i| {
                Point3::new(
                    (i % grid) as f64,
                    ((i / grid) % grid) as f64,
                    (i / grid / grid) as f64,
                )
            })
            .collect();
        v.shuffle(&mut rng);
        v
    } else if sphere {
        (0..n)
            .map(|_| loop {
                // Marsaglia: a uniform direction from a point of the unit ball, normalized
                let v: [f64; 3] = [
                    rng.gen::<f64>() * 2.0 - 1.0,
                    rng.gen::<f64>() * 2.0 - 1.0,
                    rng.gen::<f64>() * 2.0 - 1.0,
                ];
                let r2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
                if r2 > 1e-4 && r2 <= 1.0 {
                    let r = r2.sqrt();
                    break Point3::new(v[0] / r, v[1] / r, v[2] / r);
                }
            })
            .collect()
    } else {
        (0..n)
            .map(|_| Point3::new(rng.gen(), rng.gen(), rng.gen()))
            .collect()
    };
    let n = pts.len();
    if let Some(path) = write {
        let bytes: Vec<u8> = pts
            .iter()
            .flat_map(|p| [p.x, p.y, p.z])
            .flat_map(f64::to_le_bytes)
            .collect();
        std::fs::write(&path, bytes).expect("write points");
    }
    let before = vm_hwm_kib().unwrap_or(0);
    use morpho::internals::predicate_stats as ps;
    ps::reset();
    let c0 = cpu_seconds();
    let t = Instant::now();
    let mut split_stats = None;
    let d = match engine.as_str() {
        "auto" => triangulate_3d(&pts).expect("triangulate"),
        "seq" => morpho::internals::delaunay::triangulate_3d_sequential(&pts).expect("triangulate"),
        "split" => {
            let (d, st) =
                morpho::internals::delaunay::triangulate_3d_split_stats(&pts).expect("triangulate");
            split_stats = Some(st);
            d
        }
        e => panic!("unknown engine {e} (auto, seq, split)"),
    };
    let secs = t.elapsed().as_secs_f64();
    let cpu = cpu_seconds() - c0;
    let hwm = vm_hwm_kib().unwrap_or(0);
    println!(
        "points {n}  tets {}  hull {}  wall {secs:.3} s  {:.0} points/s  cpu {cpu:.2} s  {:.0} points/cpu-s",
        d.tets.len(),
        d.hull.len(),
        n as f64 / secs,
        n as f64 / cpu.max(0.01)
    );
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!(
        "engine {engine}  threads {}  load {}",
        rayon::current_num_threads(),
        load.split_whitespace()
            .take(3)
            .collect::<Vec<_>>()
            .join(" ")
    );
    if let Some(st) = split_stats {
        println!("split: {st:?}");
    }
    let k = ps::snapshot();
    let calls: u64 = k[7..10].iter().sum();
    if calls > 0 {
        // built with --features morpho/predicate-stats; the small-integer kernel (lattices) and
        // the out-of-range kernel do not go through the counted cascade
        let share = |x: u64| 100.0 * x as f64 / calls as f64;
        println!(
            "insphere calls {calls}: filter {:.2} %, integer {:.3} %, full cascade {:.4} %",
            share(k[7]),
            share(k[8]),
            share(k[9])
        );
    }
    if check {
        let t = Instant::now();
        d.check_topology().expect("topology");
        d.check_delaunay_local().expect("local Delaunay");
        println!(
            "check: topology and local Delaunay certificate OK ({:.2} s)",
            t.elapsed().as_secs_f64()
        );
    }
    if let Some(path) = tets {
        let bytes: Vec<u8> = d
            .to_input_indices()
            .iter()
            .flatten()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        std::fs::write(&path, bytes).expect("write tets");
    }
    println!(
        "peak memory (VmHWM) {:.1} MiB = {:.0} bytes/point (before triangulate: {:.1} MiB, input 24 bytes/point)",
        hwm as f64 / 1024.0,
        hwm as f64 * 1024.0 / n as f64,
        before as f64 / 1024.0
    );
}
