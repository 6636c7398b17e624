//! Criterion benchmark of the 3D (and a small d-dimensional) Delaunay triangulation.
//! `cargo bench -p morpho --bench delaunay3d`; the 1M-point number comes from
//! `cargo run --release -p morpho --example bench_delaunay3d`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use morpho::delaunay::{triangulate_3d, triangulate_nd};
use morpho::geom::Point3;
use rand::{Rng, SeedableRng};

fn points(n: usize) -> Vec<Point3> {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
    (0..n)
        .map(|_| Point3::new(rng.gen(), rng.gen(), rng.gen()))
        .collect()
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("delaunay3d");
    g.sample_size(10);
    for n in [10_000usize, 100_000] {
        let p = points(n);
        g.throughput(Throughput::Elements(n as u64));
        g.bench_with_input(BenchmarkId::new("uniform", n), &p, |b, p| {
            b.iter(|| triangulate_3d(p).unwrap())
        });
    }
    let mut grid = Vec::new();
    for i in 0..20 {
        for j in 0..20 {
            for k in 0..20 {
                grid.push(Point3::new(i as f64, j as f64, k as f64));
            }
        }
    }
    g.throughput(Throughput::Elements(grid.len() as u64));
    g.bench_with_input(BenchmarkId::new("grid", grid.len()), &grid, |b, p| {
        b.iter(|| triangulate_3d(p).unwrap())
    });
    let flat: Vec<f64> = points(500).iter().flat_map(|p| [p.x, p.y, p.z]).collect();
    g.bench_function("dd_3d_500", |b| {
        b.iter(|| triangulate_nd(&flat, 3).unwrap())
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
