//! Contour phase of Dorgerloh et al. (after triangulation and rating) on jittered grid
//! triangulations from 10k to 1M triangles: the time per triangle should stay constant (O(n)).
//!
//! `cargo bench -p morpho --bench contour`
use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use morpho::contour::simplex_neighbors;
use morpho::contour::{
    boundary_regions, classify, external_contour_with, rate_triangles, ContourOptions, Rating,
};
use morpho::geom::Point2;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::time::Duration;

/// A jittered (n+1)² lattice, each cell split along a random diagonal, and a smooth field.
fn grid(n: usize) -> (Vec<Point2>, Vec<[u32; 3]>, Vec<f64>) {
    let mut rng = ChaCha8Rng::seed_from_u64(n as u64);
    let mut pts = Vec::with_capacity((n + 1) * (n + 1));
    for j in 0..=n {
        for i in 0..=n {
            pts.push(Point2::new(
                i as f64 + rng.gen_range(-0.2..0.2),
                j as f64 + rng.gen_range(-0.2..0.2),
            ));
        }
    }
    let v = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut tri = Vec::with_capacity(2 * n * n);
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1));
            if rng.gen_bool(0.5) {
                tri.push([a, b, c]);
                tri.push([a, c, d]);
            } else {
                tri.push([a, b, d]);
                tri.push([b, c, d]);
            }
        }
    }
    let values = pts
        .iter()
        .map(|p| (p.x / 7.0).sin() * (p.y / 5.0).cos() + 0.5 * ((p.x + p.y) / 11.0).sin())
        .collect();
    (pts, tri, values)
}

fn contour(c: &mut Criterion) {
    let mut g = c.benchmark_group("contour");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    for n in [71usize, 224, 707] {
        let (pts, tri, values) = grid(n);
        let nb = simplex_neighbors(&tri, pts.len()).unwrap();
        let ratings = rate_triangles(&tri, &pts, &values, Rating::Mean).unwrap();
        let black = classify(&ratings, 0.2, false);
        let opts = ContourOptions::default();
        g.throughput(Throughput::Elements(tri.len() as u64));
        g.bench_with_input(BenchmarkId::new("external", tri.len()), &n, |b, _| {
            b.iter(|| black_box(external_contour_with(&tri, Some(&nb), &pts, &black, &opts)))
        });
        g.bench_with_input(
            BenchmarkId::new("external+neighbours", tri.len()),
            &n,
            |b, _| b.iter(|| black_box(external_contour_with(&tri, None, &pts, &black, &opts))),
        );
        g.bench_with_input(BenchmarkId::new("holes", tri.len()), &n, |b, _| {
            b.iter(|| black_box(boundary_regions(&tri, Some(&nb), &pts, &black, &opts)))
        });
        g.bench_with_input(BenchmarkId::new("rating", tri.len()), &n, |b, _| {
            b.iter(|| black_box(rate_triangles(&tri, &pts, &values, Rating::Mean)))
        });
    }
    g.finish();
}

criterion_group!(benches, contour);
criterion_main!(benches);
