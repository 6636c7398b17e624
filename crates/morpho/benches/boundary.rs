//! Boundary constriction (issue 5): time of `boundary_2d` (Delaunay + γ constriction) against
//! the Delaunay triangulation alone, for points sampled from a smooth closed curve (the chalice
//! outline), shuffled. The target: total within 3× of the Delaunay time.
use criterion::{black_box, criterion_group, criterion_main, Criterion};
use morpho::boundary::{boundary_2d, Options2};
use morpho::geom::Point2;
use rand::seq::SliceRandom;
use rand::SeedableRng;

fn curve(n: usize) -> Vec<Point2> {
    let mut p = morpho::samples::chalice_outline(n, 0.0, 1);
    p.shuffle(&mut rand_chacha::ChaCha8Rng::seed_from_u64(5));
    p
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("boundary_2d");
    g.sample_size(10);
    // 1M points: set MORPHO_BENCH_BOUNDARY_1M=1 (about a minute per sample on a loaded machine)
    let mut sizes = vec![100_000usize];
    if std::env::var_os("MORPHO_BENCH_BOUNDARY_1M").is_some() {
        sizes.push(1_000_000);
    }
    for n in sizes {
        let pts = curve(n);
        g.bench_function(format!("delaunay {n}"), |b| {
            b.iter(|| {
                black_box(
                    morpho::delaunay::triangulate_2d(&pts)
                        .unwrap()
                        .triangles
                        .len(),
                )
            })
        });
        g.bench_function(format!("gamma boundary {n}"), |b| {
            b.iter(|| {
                let r = boundary_2d(&pts, &Options2::default()).unwrap();
                assert!(r.all_on_boundary);
                black_box(r.polygon.len())
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
