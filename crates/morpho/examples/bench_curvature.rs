//! Times `morpho::curvature::surface_curvature` on one mesh in this process (issue 20, speed):
//! the thesis's method (1-ring paraboloid, area normals), the default for estimated normals
//! (the cubic jet's curvature over the 2-ring) and the previous default (jet normals + 1-ring
//! paraboloid), each on a rayon pool of 1 and of 2 threads, alternately,
//! `--rounds` times; prints wall and process CPU seconds of each call and the 1-minute load
//! average before it (the machine may be shared).
//!
//! ```text
//! cargo run --release -p morpho --example bench_curvature -- MESH [--rounds 3]
//! ```
use morpho::curvature::{surface_curvature, SurfaceOptions};
use std::time::Instant;

fn cpu_seconds() -> f64 {
    // utime + stime of this process, in clock ticks (fields 14 and 15 of /proc/self/stat)
    let s = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let rest = s.rsplit(')').next().unwrap_or("");
    let f: Vec<&str> = rest.split_whitespace().collect();
    let t = |i: usize| f.get(i).and_then(|x| x.parse::<f64>().ok()).unwrap_or(0.0);
    (t(11) + t(12)) / 100.0
}

fn load1() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .unwrap_or_default()
        .split_whitespace()
        .next()
        .unwrap_or("?")
        .to_string()
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let path = args
        .get(1)
        .expect("usage: bench_curvature MESH [--rounds N]");
    let rounds = args
        .iter()
        .position(|a| a == "--rounds")
        .and_then(|i| args.get(i + 1))
        .and_then(|s| s.parse().ok())
        .unwrap_or(3);
    let mesh = morpho::io::read_mesh(std::path::Path::new(path)).expect("a readable mesh");
    println!(
        "{path}: {} vertices, {} triangles",
        mesh.positions.len(),
        mesh.triangles.len()
    );
    let methods = [
        ("thesis", SurfaceOptions::default()),
        ("default", SurfaceOptions::estimated_normals()),
        ("jetparab", SurfaceOptions::jet_normals_paraboloid()),
    ];
    let pools: Vec<_> = [1, 2]
        .iter()
        .map(|&n| {
            (
                n,
                rayon::ThreadPoolBuilder::new()
                    .num_threads(n)
                    .build()
                    .expect("a thread pool"),
            )
        })
        .collect();
    for round in 0..rounds {
        for (name, opts) in &methods {
            for (threads, pool) in &pools {
                let load = load1();
                let (t, c) = (Instant::now(), cpu_seconds());
                let r = pool
                    .install(|| surface_curvature(&mesh, opts))
                    .expect("curvature");
                let (wall, cpu) = (t.elapsed().as_secs_f64(), cpu_seconds() - c);
                println!(
                    "round {round} {name:8} threads {threads}: wall {wall:.3} s, cpu {cpu:.2} s, \
                     undetermined {}, load {load}",
                    r.undetermined
                );
            }
        }
    }
}
