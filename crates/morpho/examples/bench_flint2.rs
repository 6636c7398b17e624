//! Point-in-polygon on the 2D flintstone tree (issue 18, "Numbers"): the Great Britain coast
//! upsampled to about V vertices (points inserted along each edge, as `bench/flint_peers.py`
//! does), tree build against the Douglas–Peucker baseline on the same polygon, then Q uniform
//! queries in the polygon's box (seeded): a loop of single `contains` calls, and
//! `contains_batch` on 1 and on 2 rayon threads. Wall time and process CPU time per phase.
//!
//! `cargo run --release -p morpho --example bench_flint2 [vertices] [queries]`
//! (default 100 000, 1 000 000).

mod common;

use morpho::flint::{baseline, Baseline, Containment, FlintTree2, Target};
use morpho::geom::Point2;
use std::time::Instant;

fn timed<T>(name: &str, f: impl FnOnce() -> T) -> (T, f64) {
    let (w, c) = (Instant::now(), common::cpu_seconds());
    let r = f();
    let (w, c) = (w.elapsed().as_secs_f64(), common::cpu_seconds() - c);
    println!("{name:28} wall {w:.3} s  cpu {c:.3} s");
    (r, w)
}

fn main() -> morpho::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let v: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(100_000);
    let q: usize = args
        .get(2)
        .and_then(|s| s.parse().ok())
        .unwrap_or(1_000_000);
    let Some(dir) = common::data_dir() else {
        println!("no ../shared/data");
        return Ok(());
    };
    let s = morpho::io::read_shapes2(&dir.join("polygons/coast_great_britain_ne10m.csv"))?;
    let ring = &s.polygons[0].rings[0];
    let k = (v / ring.len()).max(1);
    let mut up = Vec::with_capacity(ring.len() * k);
    for (i, a) in ring.iter().enumerate() {
        let b = ring[(i + 1) % ring.len()];
        for s in 0..k {
            let t = s as f64 / k as f64;
            up.push(Point2::new(
                a.x * (1.0 - t) + b.x * t,
                a.y * (1.0 - t) + b.y * t,
            ));
        }
    }
    println!("{} vertices, {q} queries", up.len());
    let (t, _) = timed("build (flintstone tree)", || FlintTree2::new(&up, true));
    let t = t.expect("simple");
    let _ = timed("Douglas–Peucker 1e-3", || {
        baseline(&up, true, Baseline::DouglasPeucker, Target::Error(1e-3))
    });
    let (lo, hi) = up
        .iter()
        .fold(([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]), |(l, h), p| {
            (
                [l[0].min(p.x), l[1].min(p.y)],
                [h[0].max(p.x), h[1].max(p.y)],
            )
        });
    let mut seed = 18u64;
    let mut unit = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let xs: Vec<Point2> = (0..q)
        .map(|_| {
            Point2::new(
                lo[0] + unit() * (hi[0] - lo[0]),
                lo[1] + unit() * (hi[1] - lo[1]),
            )
        })
        .collect();
    let (single, ws) = timed("single contains, loop", || {
        xs.iter()
            .map(|&x| t.contains(x).unwrap())
            .collect::<Vec<_>>()
    });
    let mut rates = vec![q as f64 / ws / 1e6];
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let (b, w) = timed(&format!("contains_batch, {threads} thread(s)"), || {
            pool.install(|| t.contains_batch(&xs).unwrap())
        });
        assert_eq!(b, single, "batch answers differ");
        rates.push(q as f64 / w / 1e6);
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let (h, _) = timed("Hilbert-sorted batch, 1 thread", || {
        pool.install(|| t.contains_batch_hilbert(&xs).unwrap())
    });
    assert_eq!(h, single, "sorted batch answers differ");
    let inside = single.iter().filter(|&&c| c == Containment::Inside).count();
    println!(
        "{inside} inside; M queries/s: loop {:.2}, batch 1 thread {:.2}, 2 threads {:.2}",
        rates[0], rates[1], rates[2]
    );
    Ok(())
}
