//! Point-in-mesh on the 3D flintstone tree (issue 18, "Numbers": 10⁶ queries against the horse,
//! target ≥ 1M queries/s per core): build time, then N random queries in the mesh's bounding
//! box (seeded) on one thread and on all threads, with the mean nodes visited per query.
//!
//! `cargo run --release -p morpho --example bench_flint3 [mesh file name] [queries]`
//! (default: horse.obj.gz, 1 000 000).
//!
//! Measured 2026-12-06 (release, 2 cores shared with other jobs, load average 4–6, so times
//! ±50 %): horse (96 966 triangles) build 1.65 s, 162 372 nodes, depth 40, 6 130 fallback
//! nodes (4 929 of them ≤ 3 triangles); 10⁶ queries (111 521 inside): one thread 165 000–
//! 200 000 queries/s, two threads no faster under that load; 57.4 nodes visited per query on
//! average. The target (≥ 10⁶ queries/s per core) is **not** met: the walk is exact
//! (orient3d/insphere-free filters, but exact ray–triangle tests for each replaced node and
//! the fills of its three paths), and ∪ stones (9 551 here) prune only by their hull ball.
//!
//! Then the cached classification (`CellCache3`, `flint/locate3.rs`; third argument: cells,
//! default 2²²): 2026-12-07, load 10–12, 10⁶ queries answered as the walk on one thread in
//! 0.49–0.50 CPU s (2.0 M queries per CPU second), grid build 0.07 CPU s.

mod common;

use morpho::flint::{Containment, FlintTree3};
use std::time::Instant;

fn main() -> morpho::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let name = args.get(1).map_or("horse.obj.gz", |s| s.as_str());
    let n: usize = args
        .get(2)
        .and_then(|s| s.parse().ok())
        .unwrap_or(1_000_000);
    let Some(dir) = common::data_dir() else {
        eprintln!("shared/data not found");
        return Ok(());
    };
    let m = morpho::io::read_mesh(&dir.join("meshes").join(name))?;
    let t0 = Instant::now();
    let t = FlintTree3::from_mesh(&m)?;
    let build = t0.elapsed().as_secs_f64();
    println!(
        "{name}: {} triangles, build {build:.2} s, {} nodes, depth {}, fallbacks {}",
        m.triangles.len(),
        t.node_count(),
        t.depth(),
        t.fallbacks()
    );
    let mut hist = [0usize; 5];
    for (id, nd) in t.nodes.iter().enumerate() {
        if nd.patched {
            let k = t.node_triangles(id as u32).len();
            hist[match k {
                0..=2 => 0,
                3 => 1,
                4..=8 => 2,
                9..=64 => 3,
                _ => 4,
            }] += 1;
        }
    }
    println!("fallback nodes by triangles (≤2, 3, 4–8, 9–64, >64): {hist:?}");
    let q = common::box_points3(&m.bbox(), n);
    let t1 = Instant::now();
    let mut inside = 0usize;
    let mut visits = 0usize;
    for x in &q {
        let (c, v) = t.locate_counted(*x)?;
        inside += usize::from(c == Containment::Inside);
        visits += v;
    }
    let one = t1.elapsed().as_secs_f64();
    let t2 = Instant::now();
    let all = t.contains_batch(&q)?;
    let par = t2.elapsed().as_secs_f64();
    assert_eq!(
        all.iter().filter(|&&c| c == Containment::Inside).count(),
        inside
    );
    println!(
        "{n} queries ({inside} inside): 1 thread {:.0} queries/s ({:.2} s), {} threads {:.0} queries/s ({:.2} s); mean nodes visited {:.1}",
        n as f64 / one,
        one,
        rayon::current_num_threads(),
        n as f64 / par,
        par,
        visits as f64 / n as f64
    );
    // the cached classification (locate3.rs): grid build, then the same queries
    let cells = args
        .get(3)
        .and_then(|s| s.parse().ok())
        .unwrap_or(morpho::flint::DEFAULT_CELLS);
    let c0 = common::cpu_seconds();
    let t3 = Instant::now();
    let g = t.cell_cache(cells);
    let gbuild = t3.elapsed().as_secs_f64();
    let gcpu = common::cpu_seconds() - c0;
    let [out, inn, near] = g.label_counts();
    println!(
        "cell cache: {:?} cells ({out} outside, {inn} inside, {near} near), {} components, build {gbuild:.3} s ({gcpu:.3} CPU s)",
        g.dims(),
        g.components()
    );
    let c1 = common::cpu_seconds();
    let t4 = Instant::now();
    let mut same = 0usize;
    for (x, want) in q.iter().zip(&all) {
        same += usize::from(g.contains(*x)? == *want);
    }
    let one = t4.elapsed().as_secs_f64();
    let one_cpu = common::cpu_seconds() - c1;
    assert_eq!(same, n, "the cache must answer as the walk");
    let c2 = common::cpu_seconds();
    let t5 = Instant::now();
    let cached = g.contains_batch(&q)?;
    let par = t5.elapsed().as_secs_f64();
    let par_cpu = common::cpu_seconds() - c2;
    assert_eq!(cached, all);
    println!(
        "cached: 1 thread {:.0} queries/s ({one:.3} s, {one_cpu:.3} CPU s: {:.0} per CPU s); {} threads {:.0} queries/s ({par:.3} s, {par_cpu:.3} CPU s: {:.0} per CPU s)",
        n as f64 / one,
        n as f64 / one_cpu,
        rayon::current_num_threads(),
        n as f64 / par,
        n as f64 / par_cpu
    );
    Ok(())
}
