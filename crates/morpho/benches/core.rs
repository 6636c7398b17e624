//! Criterion benchmarks of morpho's core pieces. Peer comparisons live in `bench/`.
use criterion::{black_box, criterion_group, criterion_main, Criterion};
use morpho::geom::{orient2d, Point2};

fn predicates(c: &mut Criterion) {
    let pts: Vec<Point2> = (0..3000)
        .map(|i| {
            let t = i as f64 * 0.001;
            Point2::new(t.cos(), t.sin())
        })
        .collect();
    c.bench_function("orient2d 1000 near-degenerate triples", |b| {
        b.iter(|| {
            let mut s = 0.0;
            for w in pts.chunks_exact(3) {
                s += orient2d(&w[0], &w[1], &w[2]).signum();
            }
            black_box(s)
        })
    });
}

criterion_group!(benches, predicates);
criterion_main!(benches);
