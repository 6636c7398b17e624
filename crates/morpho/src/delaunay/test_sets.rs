//! Point sets shared by the two-thread split tests of [`super::par2`] and [`super::merge2`]:
//! each path must give the sequential engine's triangle set on them (the tests' own `same`
//! checks). Test-only.

use super::d2::{triangulate_split, Split};
use crate::geom::Point2;
use crate::util::Rng;

/// `n` uniform points in the unit square.
pub(super) fn uniform(n: usize, seed: u64) -> Vec<Point2> {
    let mut r = Rng::new(seed);
    (0..n).map(|_| Point2::new(r.unit(), r.unit())).collect()
}

/// 20 clusters of 500 points, of very different density.
pub(super) fn clusters() -> Vec<Point2> {
    let mut r = Rng::new(7);
    let mut p = Vec::new();
    for c in 0..20 {
        let (cx, cy, s) = (r.unit(), r.unit(), 1e-4 * (1 + c) as f64);
        for _ in 0..500 {
            p.push(Point2::new(cx + s * r.unit(), cy + s * r.unit()));
        }
    }
    p
}

/// Points along curves: a spiral and a sine, `n` each.
pub(super) fn curves(n: usize) -> [Vec<Point2>; 2] {
    let spiral = (0..n)
        .map(|i| {
            let t = i as f64 * 0.01;
            Point2::new((1.0 + 0.1 * t) * t.cos(), (1.0 + 0.1 * t) * t.sin())
        })
        .collect();
    let sine = (0..n)
        .map(|i| {
            let x = i as f64 / n as f64;
            Point2::new(x, (40.0 * x).sin())
        })
        .collect();
    [spiral, sine]
}

/// The integer points on the circle of radius 5⁴ (many exactly cocircular), and 1000
/// floating-point points of the unit circle with its centre (one vertex of degree n).
pub(super) fn circles() -> [Vec<Point2>; 2] {
    let r = 625i64;
    let mut circ = Vec::new();
    for x in -r..=r {
        let y2 = r * r - x * x;
        let y = (y2 as f64).sqrt() as i64;
        if y * y == y2 {
            circ.push(Point2::new(x as f64, y as f64));
            circ.push(Point2::new(x as f64, -y as f64));
        }
    }
    let mut c2: Vec<Point2> = (0..1000)
        .map(|i| {
            let a = i as f64 * std::f64::consts::TAU / 1000.0;
            Point2::new(a.cos(), a.sin())
        })
        .collect();
    c2.push(Point2::new(0.0, 0.0));
    [circ, c2]
}

/// Random subsets of `m × m` lattices scaled by `s`, with duplicates, one per `(n, m, s)`.
pub(super) fn lattice_subsets(cases: &[(usize, u64, f64)]) -> Vec<Vec<Point2>> {
    let mut r = Rng::new(11);
    cases
        .iter()
        .map(|&(n, m, s)| {
            (0..n)
                .map(|_| Point2::new(r.below(m) as f64 * s, r.below(m) as f64 * s))
                .collect()
        })
        .collect()
}

/// A 60 × 60 triangular lattice (sheared): cocircular hexagons, not on a power-of-two lattice.
pub(super) fn triangular_lattice() -> Vec<Point2> {
    (0..60 * 60)
        .map(|i| {
            let (a, b) = ((i % 60) as f64, (i / 60) as f64);
            Point2::new(a + 0.5 * b, b * 0.866_025_403_784_438_6)
        })
        .collect()
}

/// The split path `split` gives the same triangulation (triangles, neighbours, vertex map) on
/// one thread and on two.
pub(super) fn same_for_every_thread_count(split: Split) {
    let p = uniform(30_000, 21);
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| triangulate_split(&p, split).unwrap())
    };
    let (a, b) = (run(1), run(2));
    assert_eq!(a.triangles, b.triangles);
    assert_eq!(a.neighbors, b.neighbors);
    assert_eq!(a.vertex_tri, b.vertex_tri);
}

/// Triangles as a canonical set: each rotated to start at its smallest vertex, sorted.
pub(super) fn canonical(tris: &[[u32; 3]]) -> Vec<[u32; 3]> {
    let mut t: Vec<[u32; 3]> = tris
        .iter()
        .map(|&[a, b, c]| {
            if a < b && a < c {
                [a, b, c]
            } else if b < c {
                [b, c, a]
            } else {
                [c, a, b]
            }
        })
        .collect();
    t.sort_unstable();
    t
}
