//! Tests of the 2D Delaunay triangulation and its Voronoi dual against definitions:
//! brute-force oracles (empty circumcircles by the exact predicate against every vertex, the
//! symbolically perturbed triangle set from its definition), invariants (CCW, symmetric
//! neighbours, Euler relation, hull convexity, area), degenerate and real inputs.

mod common;
use morpho::delaunay::{triangulate_2d, Delaunay2, Location};
use morpho::delaunay::{voronoi_2d, VoronoiEdge};
use morpho::geom::predicates::raw::{incircle, orient2d};
use morpho::geom::Point2;
use morpho::internals::delaunay::{incircle_sos, lex_cmp};
use morpho::util::NONE;
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use std::collections::BTreeSet;

fn pts(v: &[[f64; 2]]) -> Vec<Point2> {
    v.iter().map(|p| Point2::new(p[0], p[1])).collect()
}

fn rng(seed: u64) -> rand_chacha::ChaCha8Rng {
    rand_chacha::ChaCha8Rng::seed_from_u64(seed)
}

/// Coordinates scaled by the exact power of two that brings them near 1, as the library does,
/// so that the oracle's predicates are exact for any absolute scale.
fn scaled(d: &Delaunay2) -> Vec<[f64; 2]> {
    let s = scale_of(d);
    d.points.iter().map(|p| [p.x * s, p.y * s]).collect()
}

fn scale_of(d: &Delaunay2) -> f64 {
    let m = d
        .points
        .iter()
        .fold(0.0f64, |m, p| m.max(p.x.abs()).max(p.y.abs()));
    if m > 0.0 {
        let e = m.log2().round() as i32;
        2f64.powi(-e / 2) * 2f64.powi(-e - (-e / 2))
    } else {
        1.0
    }
}

/// All invariants; `brute` enables the O(T·n) empty-circle check against every vertex.
fn check(input: &[Point2], d: &Delaunay2, brute: bool) {
    let n = d.points.len();
    let c = scaled(d);
    // every input maps to a vertex at the same position; vertices are distinct
    assert_eq!(d.vertex_of_input.len(), input.len());
    for (i, p) in input.iter().enumerate() {
        let v = d.vertex_of_input[i] as usize;
        assert!(v < n);
        assert_eq!(d.points[v], *p, "input {i} maps to a different position");
        assert!(d.input_of_vertex[v] as usize <= i);
    }
    for (v, &i) in d.input_of_vertex.iter().enumerate() {
        assert_eq!(d.vertex_of_input[i as usize] as usize, v);
    }
    let mut sorted: Vec<[f64; 2]> = c.clone();
    sorted.sort_by(|a, b| lex_cmp(*a, *b));
    assert!(
        sorted.windows(2).all(|w| w[0] != w[1]),
        "duplicate vertices"
    );
    assert_eq!(d.duplicates, input.len() - n);
    let h = d.hull.len();
    let hull_set: BTreeSet<u32> = d.hull.iter().copied().collect();
    assert_eq!(hull_set.len(), h, "hull repeats a vertex");
    if d.collinear {
        assert!(d.triangles.is_empty());
        assert_eq!(h, n);
        for w in d.hull.windows(3) {
            let (a, b, cc) = (c[w[0] as usize], c[w[1] as usize], c[w[2] as usize]);
            assert_eq!(orient2d(a, b, cc), 0.0);
            assert!(lex_cmp(a, b).is_lt() && lex_cmp(b, cc).is_lt());
        }
        return;
    }
    let nt = d.triangles.len();
    // Euler relation for a triangulated convex polygon with h boundary vertices
    assert_eq!(nt, 2 * n - 2 - h, "Euler relation");
    let mut boundary = 0;
    let mut incident = vec![false; n];
    for (t, tri) in d.triangles.iter().enumerate() {
        let [a, b, cc] = tri.map(|v| c[v as usize]);
        assert!(orient2d(a, b, cc) > 0.0, "triangle {t} not CCW");
        for i in 0..3 {
            incident[tri[i] as usize] = true;
            let nb = d.neighbors[t][i];
            let (p, q) = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
            if nb == NONE {
                boundary += 1;
                assert!(hull_set.contains(&p) && hull_set.contains(&q));
                continue;
            }
            let o = d.triangles[nb as usize];
            let j = (0..3)
                .find(|&j| o[(j + 1) % 3] == q && o[(j + 2) % 3] == p)
                .expect("neighbour shares the edge reversed");
            assert_eq!(d.neighbors[nb as usize][j], t as u32, "asymmetric");
            // locally Delaunay under the perturbed rule, hence globally
            assert!(
                incircle_sos(a, b, cc, c[o[j] as usize]) < 0,
                "edge {p}-{q} not locally Delaunay"
            );
        }
    }
    assert!(incident.iter().all(|&x| x), "a vertex is in no triangle");
    assert_eq!(boundary, h, "boundary edges vs hull size");
    // hull: convex, CCW, every vertex on or left of every hull edge, edges are boundary edges
    let mut hull_area = 0.0;
    // sum of |terms|, for the rounding-error bound of the area comparison
    let mut magnitude = 0.0;
    for k in 0..h {
        let (a, b) = (d.hull[k], d.hull[(k + 1) % h]);
        let nb = d.edge_triangles(a, b).expect("hull edge is an edge");
        assert!(
            nb[0] != NONE && nb[1] == NONE,
            "hull edge {a}-{b} sides {nb:?}"
        );
        let (pa, pb, pc) = (
            c[a as usize],
            c[b as usize],
            c[d.hull[(k + 2) % h] as usize],
        );
        assert!(orient2d(pa, pb, pc) >= 0.0, "hull not convex");
        let o = c[d.hull[0] as usize];
        let (x, y) = (
            (pa[0] - o[0]) * (pb[1] - o[1]),
            (pa[1] - o[1]) * (pb[0] - o[0]),
        );
        hull_area += x - y;
        magnitude += x.abs() + y.abs();
        if brute || n < 2000 {
            for &q in &c {
                assert!(orient2d(pa, pb, q) >= 0.0, "point outside the hull");
            }
        }
    }
    let mut tri_area = 0.0;
    for t in &d.triangles {
        let [a, b, cc] = t.map(|v| c[v as usize]);
        let (x, y) = (
            (b[0] - a[0]) * (cc[1] - a[1]),
            (b[1] - a[1]) * (cc[0] - a[0]),
        );
        tri_area += x - y;
        magnitude += x.abs() + y.abs();
    }
    // equal up to rounding (a missing or doubly covered triangle breaks this for all but
    // slivers, which the Euler relation and the CCW test catch)
    assert!(
        (tri_area - hull_area).abs() <= 1e-12 * magnitude,
        "area {tri_area} vs hull {hull_area}"
    );
    if brute {
        for t in &d.triangles {
            let [a, b, cc] = t.map(|v| c[v as usize]);
            for q in &c {
                assert!(incircle(a, b, cc, *q) <= 0.0, "circumcircle not empty");
            }
        }
    }
}

/// The triangle set of the perturbed Delaunay triangulation from its definition (O(n⁴)).
fn oracle(c: &[[f64; 2]]) -> BTreeSet<[u32; 3]> {
    let n = c.len();
    let mut s = BTreeSet::new();
    for a in 0..n {
        for b in 0..n {
            for cc in 0..n {
                if !(a < b && a < cc) || b == cc || orient2d(c[a], c[b], c[cc]) <= 0.0 {
                    continue;
                }
                if (0..n).all(|q| {
                    q == a || q == b || q == cc || incircle_sos(c[a], c[b], c[cc], c[q]) < 0
                }) {
                    s.insert([a as u32, b as u32, cc as u32]);
                }
            }
        }
    }
    s
}

fn normalized(tris: &[[u32; 3]]) -> BTreeSet<[u32; 3]> {
    tris.iter()
        .map(|t| {
            let k = (0..3).min_by_key(|&i| t[i]).unwrap_or(0);
            [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
        })
        .collect()
}

/// Triangles as sets of coordinates (independent of vertex numbering).
fn geometric(d: &Delaunay2) -> BTreeSet<[(u64, u64); 3]> {
    d.triangles
        .iter()
        .map(|t| {
            let mut v = t.map(|v| {
                let p = d.points[v as usize];
                (p.x.to_bits(), p.y.to_bits())
            });
            v.sort();
            v
        })
        .collect()
}

fn full_check(input: &[Point2]) -> Delaunay2 {
    let d = triangulate_2d(input).expect("triangulate");
    let small = d.points.len() <= 400;
    check(input, &d, small);
    if d.points.len() <= 40 && !d.collinear {
        assert_eq!(
            normalized(&d.triangles),
            oracle(&scaled(&d)),
            "differs from oracle"
        );
    }
    d
}

fn shuffled(input: &[Point2], seed: u64) -> Vec<Point2> {
    let mut v = input.to_vec();
    let mut r = rng(seed);
    for i in (1..v.len()).rev() {
        v.swap(i, r.gen_range(0..=i));
    }
    v
}

fn assert_order_independent(input: &[Point2]) {
    let d = triangulate_2d(input).unwrap();
    let g = geometric(&d);
    for seed in 1..4 {
        let s = triangulate_2d(&shuffled(input, seed)).unwrap();
        assert_eq!(geometric(&s), g, "shuffled input changed the triangulation");
        let r = morpho::internals::delaunay::triangulate_with_insertion_seed(input, seed).unwrap();
        check(input, &r, false);
        assert_eq!(
            geometric(&r),
            g,
            "insertion order changed the triangulation"
        );
    }
}

#[test]
fn random_small_sets_match_oracle() {
    let mut r = rng(1);
    for n in [3, 4, 5, 6, 8, 10, 15, 20, 30, 40] {
        for _ in 0..4 {
            let p: Vec<Point2> = (0..n)
                .map(|_| Point2::new(r.gen_range(-1.0..1.0), r.gen_range(-1.0..1.0)))
                .collect();
            full_check(&p);
        }
    }
}

#[test]
fn random_medium_brute_force() {
    let mut r = rng(2);
    let p: Vec<Point2> = (0..300)
        .map(|_| Point2::new(r.gen::<f64>() * 100.0, r.gen::<f64>() * 3.0))
        .collect();
    full_check(&p);
    assert_order_independent(&p);
}

#[test]
fn integer_grids() {
    for (w, h) in [(2, 2), (3, 3), (5, 4), (6, 6), (1, 7)] {
        let p: Vec<Point2> = (0..w * h)
            .map(|k| Point2::new((k % w) as f64, (k / w) as f64))
            .collect();
        let d = full_check(&p);
        assert_eq!(d.collinear, w == 1 || h == 1);
        assert_order_independent(&p);
    }
    let p: Vec<Point2> = (0..900)
        .map(|k| Point2::new((k % 30) as f64, (k / 30) as f64))
        .collect();
    let d = full_check(&p);
    assert_eq!(d.triangles.len(), 2 * 29 * 29);
    assert_order_independent(&p);
    // the same kind of grid plus one point off the power-of-two lattice: the floating-point
    // kernel (Shewchuk's predicates) now resolves the exact ties
    for extra in [[0.1, -3.3], [2.5, 2.7]] {
        let mut p: Vec<Point2> = (0..36)
            .map(|k| Point2::new((k % 6) as f64, (k / 6) as f64))
            .collect();
        p.push(Point2::new(extra[0], extra[1]));
        full_check(&p);
        assert_order_independent(&p);
    }
}

#[test]
fn cocircular_integer_points() {
    // all 12 integer points with x² + y² = 25, and the 36 with x² + y² = 5525 (= 5²·13·17)
    for r2 in [25i64, 5525] {
        let r = (r2 as f64).sqrt() as i64;
        let mut p = Vec::new();
        for x in -r..=r {
            for y in -r..=r {
                if x * x + y * y == r2 {
                    p.push(Point2::new(x as f64, y as f64));
                }
            }
        }
        let d = full_check(&p);
        assert_eq!(d.hull.len(), p.len());
        assert_eq!(d.triangles.len(), p.len() - 2);
        assert_order_independent(&p);
        // with the centre as well
        p.push(Point2::new(0.0, 0.0));
        full_check(&p);
        assert_order_independent(&p);
    }
}

#[test]
fn collinear_and_almost_collinear() {
    let line: Vec<Point2> = (0..20)
        .map(|k| Point2::new(3.0 - k as f64 * 0.5, 1.0 + k as f64))
        .collect();
    let d = full_check(&line);
    assert!(d.collinear && d.triangles.is_empty() && d.hull.len() == 20);
    assert_eq!(d.edges().len(), 19);
    // all but one collinear: a fan of n-1 triangles
    let mut p = line.clone();
    p.push(Point2::new(10.0, 10.0));
    let d = full_check(&p);
    assert_eq!(d.triangles.len(), 19);
    assert_order_independent(&p);
    // all but two, on both sides
    let mut p: Vec<Point2> = (0..25).map(|k| Point2::new(k as f64, 0.0)).collect();
    p.push(Point2::new(7.5, 3.0));
    p.push(Point2::new(30.0, -1.0));
    full_check(&p);
    assert_order_independent(&p);
    // the first points in any order collinear, then a point far away
    let mut p: Vec<Point2> = (0..10).map(|k| Point2::new(0.0, k as f64)).collect();
    p.push(Point2::new(-1e-3, 4.5));
    full_check(&p);
}

#[test]
fn duplicates_are_merged() {
    let mut r = rng(3);
    let base: Vec<Point2> = (0..30)
        .map(|_| Point2::new(r.gen_range(0..5) as f64, r.gen_range(0..5) as f64))
        .collect();
    let d = full_check(&base);
    assert!(d.duplicates > 0);
    assert_order_independent(&base);
    let same = vec![Point2::new(1.0, 2.0); 10];
    let d = full_check(&same);
    assert_eq!((d.points.len(), d.duplicates), (1, 9));
    assert!(d.collinear);
}

#[test]
fn extreme_scales() {
    let mut r = rng(4);
    let unit: Vec<Point2> = (0..200)
        .map(|_| Point2::new(r.gen::<f64>(), r.gen::<f64>()))
        .collect();
    let grid: Vec<Point2> = (0..100)
        .map(|k| Point2::new((k % 10) as f64, (k / 10) as f64))
        .collect();
    for s in [1e-300, 1e-150, 1e-9, 1e9, 1e150, 1e300] {
        for base in [&unit, &grid] {
            let p: Vec<Point2> = base.iter().map(|q| Point2::new(q.x * s, q.y * s)).collect();
            full_check(&p);
        }
    }
    // huge offsets: 1e300 + k ulp (coordinates differ only in the last bits)
    let o = 1e300f64;
    let ulp = |k: i64| f64::from_bits((o.to_bits() as i64 + k) as u64);
    let p: Vec<Point2> = (0..64)
        .map(|k| Point2::new(ulp(k % 8), ulp(k / 8 - 3)))
        .collect();
    let d = full_check(&p);
    assert_eq!(d.triangles.len(), 2 * 7 * 7);
    // tiny offsets around zero, including subnormal-adjacent values
    let p: Vec<Point2> = (0..49)
        .map(|k| Point2::new((k % 7) as f64 * 1e-300, (k / 7) as f64 * 1e-300 - 3e-300))
        .collect();
    full_check(&p);
}

fn data_dir() -> Option<std::path::PathBuf> {
    common::data("delaunay/mapbox_delaunator")
}

fn load(dir: &std::path::Path, name: &str) -> Vec<Point2> {
    let text = std::fs::read_to_string(dir.join(name)).expect("read fixture");
    let v: Vec<[f64; 2]> = serde_json::from_str(&text).expect("parse fixture");
    pts(&v)
}

#[test]
fn mapbox_delaunator_fixtures() {
    let Some(dir) = data_dir() else { return };
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".json"))
        .collect();
    names.sort();
    assert!(names.len() >= 11);
    for name in &names {
        let p = load(&dir, name);
        let d = triangulate_2d(&p).unwrap_or_else(|e| panic!("{name}: {e}"));
        check(&p, &d, p.len() <= 1000);
        assert_eq!(d.collinear, name.starts_with("collinear"), "{name}");
        if name == "issue13.json" {
            assert_eq!(d.hull.len(), 17);
            assert_eq!(d.triangles.len(), 15);
            assert_order_independent(&p);
        }
    }
    let r1 = load(&dir, "robustness1.json");
    for s in [1e-9, 1e-2, 1e2, 1e9] {
        let p: Vec<Point2> = r1.iter().map(|q| Point2::new(q.x * s, q.y * s)).collect();
        full_check(&p);
    }
    let r2 = load(&dir, "robustness2.json");
    full_check(&r2[..100]);
    assert_order_independent(&load(&dir, "robustness4.json"));
    let u = load(&dir, "ukraine.json");
    let d = triangulate_2d(&u).unwrap();
    assert_eq!(d.points.len(), 867);
}

#[test]
fn locate_agrees_with_brute_force() {
    let mut r = rng(5);
    let p: Vec<Point2> = (0..100)
        .map(|k| Point2::new((k % 10) as f64, (k / 10) as f64))
        .collect();
    let d = triangulate_2d(&p).unwrap();
    let c = scaled(&d);
    for k in 0..400 {
        let q = if k % 2 == 0 {
            Point2::new(r.gen_range(-2.0..11.0), r.gen_range(-2.0..11.0))
        } else {
            // grid-snapped half-integers: many on edges and vertices
            Point2::new(
                r.gen_range(-2..22) as f64 * 0.5,
                r.gen_range(-2..22) as f64 * 0.5,
            )
        };
        let qa = [q.x * scale_of(&d), q.y * scale_of(&d)];
        let inside_hull = (0..d.hull.len()).all(|i| {
            let (a, b) = (d.hull[i], d.hull[(i + 1) % d.hull.len()]);
            orient2d(c[a as usize], c[b as usize], qa) >= 0.0
        });
        match d.locate_from(q, (k * 7 % d.triangles.len()) as u32) {
            Location::InTriangle(t) => {
                let [a, b, cc] = d.triangles[t as usize].map(|v| c[v as usize]);
                assert!(orient2d(a, b, qa) > 0.0 && orient2d(b, cc, qa) > 0.0);
                assert!(orient2d(cc, a, qa) > 0.0);
            }
            Location::OnEdge { tri, corner } => {
                let tr = d.triangles[tri as usize];
                let (a, b) = (tr[(corner as usize + 1) % 3], tr[(corner as usize + 2) % 3]);
                assert_eq!(orient2d(c[a as usize], c[b as usize], qa), 0.0);
                assert!(inside_hull);
            }
            Location::OnVertex(v) => assert_eq!(d.points[v as usize], q),
            Location::Outside { tri, corner } => {
                assert!(!inside_hull);
                let tr = d.triangles[tri as usize];
                assert_eq!(d.neighbors[tri as usize][corner as usize], NONE);
                let (a, b) = (tr[(corner as usize + 1) % 3], tr[(corner as usize + 2) % 3]);
                assert!(orient2d(c[a as usize], c[b as usize], qa) < 0.0);
            }
            Location::Nowhere => panic!("nowhere"),
        }
    }
    assert_eq!(d.locate(Point2::new(f64::NAN, 0.0)), Location::Nowhere);
}

#[test]
fn adjacency_queries() {
    let mut r = rng(6);
    let p: Vec<Point2> = (0..200)
        .map(|_| Point2::new(r.gen::<f64>(), r.gen::<f64>()))
        .collect();
    let d = triangulate_2d(&p).unwrap();
    let n = d.points.len();
    // triangles_around visits exactly the triangles containing v
    let mut count = vec![0usize; n];
    for t in &d.triangles {
        for &v in t {
            count[v as usize] += 1;
        }
    }
    for v in 0..n as u32 {
        let around: Vec<u32> = d.triangles_around(v).collect();
        assert_eq!(around.len(), count[v as usize]);
        assert!(around.iter().all(|&t| d.triangles[t as usize].contains(&v)));
        let set: BTreeSet<u32> = around.iter().copied().collect();
        assert_eq!(set.len(), around.len());
        assert!(d.triangles[d.vertex_triangle(v) as usize].contains(&v));
    }
    // edges: each once, 3n - 3 - h, and edge_triangles finds both sides
    let e = d.edges();
    assert_eq!(e.len(), 3 * n - 3 - d.hull.len());
    let set: BTreeSet<[u32; 2]> = e.iter().map(|&[a, b]| [a.min(b), a.max(b)]).collect();
    assert_eq!(set.len(), e.len());
    for &[a, b] in &e {
        let [l, rr] = d.edge_triangles(a, b).expect("edge");
        let [l2, r2] = d.edge_triangles(b, a).expect("edge");
        assert_eq!((l, rr), (r2, l2));
        assert!(l != NONE || rr != NONE);
    }
    assert!(d.edge_triangles(0, 0).is_none());
    // input indices
    for (t, ti) in d.triangles.iter().zip(d.to_input_indices()) {
        for k in 0..3 {
            assert_eq!(d.points[t[k] as usize], p[ti[k] as usize]);
        }
    }
    // circumcentres are equidistant
    for t in 0..d.triangles.len() as u32 {
        let cc = d.circumcenter(t);
        let r: Vec<f64> = d.triangles[t as usize]
            .iter()
            .map(|&v| (d.points[v as usize] - cc).norm())
            .collect();
        assert!((r[0] - r[1]).abs() <= 1e-9 * r[0] && (r[0] - r[2]).abs() <= 1e-9 * r[0]);
    }
}

#[test]
fn voronoi_dual() {
    let mut r = rng(7);
    for pset in 0..3 {
        let p: Vec<Point2> = (0..150)
            .map(|k| match pset {
                0 => Point2::new(r.gen::<f64>(), r.gen::<f64>()),
                1 => Point2::new((k % 12) as f64, (k / 12) as f64),
                _ => Point2::new(r.gen_range(0..8) as f64, r.gen_range(0..8) as f64),
            })
            .collect();
        let d = triangulate_2d(&p).unwrap();
        let v = voronoi_2d(&d);
        assert_eq!(v.vertices.len(), d.triangles.len());
        for (t, cc) in v.vertices.iter().enumerate() {
            let rr: Vec<f64> = d.triangles[t]
                .iter()
                .map(|&w| (d.points[w as usize] - cc).norm())
                .collect();
            let tol = 1e-9 * rr[0].max(1.0);
            assert!((rr[0] - rr[1]).abs() <= tol && (rr[0] - rr[2]).abs() <= tol);
        }
        let finite = v
            .edges
            .iter()
            .filter(|e| matches!(e, VoronoiEdge::Segment { .. }))
            .count();
        let rays = v
            .edges
            .iter()
            .filter(|e| matches!(e, VoronoiEdge::Ray { .. }))
            .count();
        let h = d.hull.len();
        assert_eq!(rays, h);
        assert_eq!(finite, d.edges().len() - h);
        for e in &v.edges {
            if let VoronoiEdge::Ray {
                dual: [a, b],
                from,
                direction,
            } = *e
            {
                // the ray points away from the triangle's third vertex
                let t = d.triangles[from as usize];
                let third = t.iter().find(|&&w| w != a && w != b).copied().unwrap();
                let m = d.points[a as usize] + (d.points[b as usize] - d.points[a as usize]) * 0.5;
                assert!(direction.dot(&(d.points[third as usize] - m)) < 0.0);
            }
        }
        for s in 0..d.points.len() as u32 {
            let cell = v.cell(&d, s);
            assert_eq!(cell.rays.is_some(), d.hull.contains(&s));
            assert_eq!(cell.vertices, d.triangles_around(s).collect::<Vec<_>>());
        }
    }
    let line = triangulate_2d(&pts(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]])).unwrap();
    let v = voronoi_2d(&line);
    assert_eq!(v.edges.len(), 2);
    assert!(matches!(v.edges[0], VoronoiEdge::Line { .. }));
}

fn arb_points() -> impl Strategy<Value = Vec<Point2>> {
    let random = prop::collection::vec((-1e3f64..1e3, -1e3f64..1e3), 1..60);
    let grid = prop::collection::vec((0i32..6, 0i32..6), 1..60);
    let line = prop::collection::vec((0i32..30, 0i32..2), 1..40);
    // integer grid points plus one point off the lattice (floating-point kernel with ties)
    let grid_float = prop::collection::vec((0i32..6, 0i32..6), 1..40);
    prop_oneof![
        random.prop_map(|v| v.into_iter().map(|(x, y)| Point2::new(x, y)).collect()),
        grid.prop_map(|v| v
            .into_iter()
            .map(|(x, y)| Point2::new(x as f64 * 0.25, y as f64 * 0.5))
            .collect()),
        grid_float.prop_map(|v| v
            .into_iter()
            .map(|(x, y)| Point2::new(x as f64, y as f64))
            .chain(std::iter::once(Point2::new(0.1, 7.3)))
            .collect()),
        line.prop_map(|v| v
            .into_iter()
            .map(|(x, y)| Point2::new(x as f64 * 0.1, x as f64 * 0.3 + (y * y * 7) as f64))
            .collect()),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn prop_valid_and_order_independent(p in arb_points(), seed in 0u64..1000) {
        let d = full_check(&p);
        let s = triangulate_2d(&shuffled(&p, seed)).unwrap();
        prop_assert_eq!(geometric(&s), geometric(&d));
    }
}

/// For random points in general position the triangle set equals Qhull's (scipy), when python3
/// with scipy is available; skipped otherwise.
#[test]
fn matches_qhull_when_available() {
    let mut r = rng(8);
    let p: Vec<Point2> = (0..500)
        .map(|_| Point2::new(r.gen::<f64>(), r.gen::<f64>()))
        .collect();
    let json = serde_json::to_string(&p.iter().map(|q| [q.x, q.y]).collect::<Vec<_>>()).unwrap();
    let script = "import sys, json\nfrom scipy.spatial import Delaunay\n\
                  p = json.load(sys.stdin)\nprint(json.dumps(Delaunay(p).simplices.tolist()))\n";
    let child = std::process::Command::new("python3")
        .args(["-c", script])
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::null())
        .spawn();
    let Ok(mut child) = child else {
        eprintln!("note: python3 not available, skipping the Qhull comparison");
        return;
    };
    {
        use std::io::Write;
        let mut stdin = child.stdin.take().unwrap();
        stdin.write_all(json.as_bytes()).unwrap();
    }
    let out = child.wait_with_output().unwrap();
    if !out.status.success() {
        eprintln!("note: scipy not available, skipping the Qhull comparison");
        return;
    }
    let simplices: Vec<[u32; 3]> = serde_json::from_slice(&out.stdout).unwrap();
    let d = triangulate_2d(&p).unwrap();
    let sort = |t: [u32; 3]| {
        let mut t = t;
        t.sort();
        t
    };
    let ours: BTreeSet<[u32; 3]> = d.to_input_indices().into_iter().map(sort).collect();
    let qhull: BTreeSet<[u32; 3]> = simplices.into_iter().map(sort).collect();
    assert_eq!(ours, qhull);
}

#[test]
fn out_of_range_coordinates_are_an_error_not_a_wrong_answer() {
    // four points within 1e-200 of each other next to points of size 1: the in-circle
    // expansions would underflow, so the input is rejected
    let p = pts(&[
        [0.0, 0.0],
        [1e-200, 0.0],
        [0.0, 1e-200],
        [1e-200, 1e-200],
        [1.0, 1.0],
    ]);
    assert!(triangulate_2d(&p).is_err());
    // the four tiny points alone are fine (the power-of-two scaling brings them to ≈ 1)
    let r: Vec<Point2> = p[..4].to_vec();
    let d = full_check(&r);
    assert_eq!(d.triangles.len(), 2);
}
