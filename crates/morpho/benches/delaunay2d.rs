//! Criterion benchmark of the 2D Delaunay triangulation (uniform random points, an integer
//! grid, points along a closed curve). Peer comparisons (delaunator, spade, scipy) live in `bench/` and
//! `examples/bench_delaunay2d.rs`.
use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion};
use morpho::delaunay::triangulate_2d;
use morpho::geom::Point2;
use rand::{Rng, SeedableRng};

fn delaunay2d(c: &mut Criterion) {
    let mut g = c.benchmark_group("delaunay2d");
    g.sample_size(10);
    for n in [10_000usize, 100_000] {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(n as u64);
        let uniform: Vec<Point2> = (0..n)
            .map(|_| Point2::new(rng.gen::<f64>(), rng.gen::<f64>()))
            .collect();
        g.bench_with_input(BenchmarkId::new("uniform", n), &uniform, |b, p| {
            b.iter(|| black_box(triangulate_2d(p).map(|d| d.triangles.len())))
        });
        let side = (n as f64).sqrt() as usize;
        let grid: Vec<Point2> = (0..side * side)
            .map(|k| Point2::new((k % side) as f64, (k / side) as f64))
            .collect();
        g.bench_with_input(BenchmarkId::new("grid", n), &grid, |b, p| {
            b.iter(|| black_box(triangulate_2d(p).map(|d| d.triangles.len())))
        });
        // the `curve` input of examples/bench_delaunay2d.rs: r = 1 + 0.3 sin 5t, jitter ±1e-9
        let tau = std::f64::consts::TAU;
        let curve: Vec<Point2> = (0..n)
            .map(|k| {
                let t = tau * k as f64 / n as f64;
                let r = 1.0 + 0.3 * (5.0 * t).sin();
                let jx = (rng.gen::<f64>() - 0.5) * 2e-9;
                let jy = (rng.gen::<f64>() - 0.5) * 2e-9;
                Point2::new(r * t.cos() + jx, r * t.sin() + jy)
            })
            .collect();
        g.bench_with_input(BenchmarkId::new("curve", n), &curve, |b, p| {
            b.iter(|| black_box(triangulate_2d(p).map(|d| d.triangles.len())))
        });
    }
    g.finish();
}

criterion_group!(benches, delaunay2d);
criterion_main!(benches);
