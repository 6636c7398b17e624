//! Tests of the constrained Delaunay triangulation (`delaunay::cdt`) against definitions:
//! a brute-force visibility oracle (no vertex inside a triangle's circumcircle is visible from its
//! interior, constraints blocking sight, all tests exact), local Delaunay-ness of every
//! unconstrained edge, every constraint present as a chain of constrained edges and no other
//! edge constrained, Euler relation, area coverage of the hull; polygon interiors (n − 2
//! triangles, shoelace area) on random and real polygons; degenerate inputs; proptest.

mod common;
use common::data_dir;
use morpho::delaunay::triangulate_2d;
use morpho::delaunay::{triangulate_constrained_2d, triangulate_polygon_2d, Cdt2};
use morpho::geom::predicates::raw::{incircle, orient2d};
use morpho::geom::Point2;
use morpho::util::NONE;
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use std::collections::HashSet;

fn rng(seed: u64) -> rand_chacha::ChaCha8Rng {
    rand_chacha::ChaCha8Rng::seed_from_u64(seed)
}

fn xy(p: &Point2) -> [f64; 2] {
    [p.x, p.y]
}

/// Do the segments `p q` and `r s` cross properly (a single common point interior to both)?
fn cross_properly(p: [f64; 2], q: [f64; 2], r: [f64; 2], s: [f64; 2]) -> bool {
    let o1 = orient2d(p, q, r);
    let o2 = orient2d(p, q, s);
    let o3 = orient2d(r, s, p);
    let o4 = orient2d(r, s, q);
    o1 * o2 < 0.0 && o3 * o4 < 0.0
}

/// Is `x` on the closed segment `a b` (exact)?
fn on_segment(a: [f64; 2], b: [f64; 2], x: [f64; 2]) -> bool {
    orient2d(a, b, x) == 0.0
        && x[0] >= a[0].min(b[0])
        && x[0] <= a[0].max(b[0])
        && x[1] >= a[1].min(b[1])
        && x[1] <= a[1].max(b[1])
}

/// Every invariant of a CDT of `input` with `segs` (input indices); `brute` enables the
/// O(T·n·C) visibility oracle.
fn check_cdt(input: &[Point2], segs: &[[u32; 2]], c: &Cdt2, brute: bool) {
    let p: Vec<[f64; 2]> = c.points().iter().map(xy).collect();
    let n = p.len();
    if c.collinear() {
        assert!(c.triangles.is_empty());
        return;
    }
    let nt = c.triangles.len();
    assert_eq!(c.neighbors.len(), nt);
    assert_eq!(c.constrained.len(), nt);
    // counter-clockwise, symmetric neighbours with a common edge and equal flags
    let mut hull_edges = 0;
    for (t, tri) in c.triangles.iter().enumerate() {
        let [a, b, cc] = tri.map(|v| p[v as usize]);
        assert!(
            orient2d(a, b, cc) > 0.0,
            "triangle {t} not counter-clockwise"
        );
        for i in 0..3 {
            let nb = c.neighbors[t][i];
            let (u, v) = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
            if nb == NONE {
                hull_edges += 1;
                continue;
            }
            let o = c.triangles[nb as usize];
            let j = o
                .iter()
                .position(|&w| w != u && w != v)
                .expect("neighbour shares the edge");
            assert!(
                o.contains(&u) && o.contains(&v),
                "neighbour {nb} of {t} lacks the edge"
            );
            assert_eq!(
                c.neighbors[nb as usize][j], t as u32,
                "asymmetric neighbours"
            );
            assert_eq!(
                c.is_constrained(t as u32, i),
                c.is_constrained(nb, j),
                "constrained flag differs on the two sides"
            );
        }
    }
    // Euler relation, hull edges
    let h = c.hull().len();
    assert_eq!(nt, 2 * n - h - 2, "Euler relation");
    assert_eq!(hull_edges, h);
    // area: the triangles cover the hull
    let area: f64 = c
        .triangles
        .iter()
        .map(|t| {
            let [a, b, cc] = t.map(|v| p[v as usize]);
            0.5 * ((b[0] - a[0]) * (cc[1] - a[1]) - (b[1] - a[1]) * (cc[0] - a[0]))
        })
        .sum();
    let hull_area = shoelace(&c.hull().iter().map(|&v| p[v as usize]).collect::<Vec<_>>());
    assert!(
        (area - hull_area).abs() <= 1e-9 * hull_area.abs().max(1e-300),
        "area {area} vs hull {hull_area}"
    );
    // constraints: every piece between consecutive vertices on a segment is a constrained edge,
    // and every constrained edge lies on a segment
    let edge_set: HashSet<(u32, u32)> = c
        .edges()
        .iter()
        .map(|(e, _)| (e[0].min(e[1]), e[0].max(e[1])))
        .collect();
    let cons: HashSet<(u32, u32)> = c
        .constrained_edges()
        .iter()
        .map(|e| (e[0].min(e[1]), e[0].max(e[1])))
        .collect();
    let mut want = HashSet::new();
    for s in segs {
        let (a, b) = (
            c.vertex_of_input()[s[0] as usize],
            c.vertex_of_input()[s[1] as usize],
        );
        if a == b {
            continue;
        }
        let (pa, pb) = (p[a as usize], p[b as usize]);
        let mut on: Vec<u32> = (0..n as u32)
            .filter(|&v| on_segment(pa, pb, p[v as usize]))
            .collect();
        let key = |v: &u32| {
            let q = p[*v as usize];
            ((q[0] - pa[0]) * (pb[0] - pa[0]) + (q[1] - pa[1]) * (pb[1] - pa[1])).abs()
        };
        on.sort_by(|x, y| key(x).total_cmp(&key(y)));
        assert_eq!(on.first(), Some(&a));
        assert_eq!(on.last(), Some(&b));
        for w in on.windows(2) {
            let e = (w[0].min(w[1]), w[0].max(w[1]));
            assert!(
                edge_set.contains(&e),
                "constraint piece {e:?} is not an edge"
            );
            assert!(cons.contains(&e), "constraint piece {e:?} is not flagged");
            want.insert(e);
        }
    }
    assert_eq!(
        cons, want,
        "constrained edges differ from the constraint pieces"
    );
    // local Delaunay property of every unconstrained interior edge (exact, ties allowed)
    for (t, tri) in c.triangles.iter().enumerate() {
        for i in 0..3 {
            let nb = c.neighbors[t][i];
            if nb == NONE || c.is_constrained(t as u32, i) {
                continue;
            }
            let o = c.triangles[nb as usize];
            let d = *o.iter().find(|w| !tri.contains(w)).unwrap();
            let [a, b, cc] = tri.map(|v| p[v as usize]);
            assert!(
                incircle(a, b, cc, p[d as usize]) <= 0.0,
                "edge opposite corner {i} of triangle {t} is not locally Delaunay"
            );
        }
    }
    if !brute {
        return;
    }
    // visibility oracle: a vertex strictly inside a circumcircle must be hidden from the
    // triangle's interior (tested from the centroid when it is strictly inside)
    let cons_segs: Vec<([f64; 2], [f64; 2])> = want
        .iter()
        .map(|&(u, v)| (p[u as usize], p[v as usize]))
        .collect();
    for tri in &c.triangles {
        let [a, b, cc] = tri.map(|v| p[v as usize]);
        let g = [(a[0] + b[0] + cc[0]) / 3.0, (a[1] + b[1] + cc[1]) / 3.0];
        if !(orient2d(a, b, g) > 0.0 && orient2d(b, cc, g) > 0.0 && orient2d(cc, a, g) > 0.0) {
            continue;
        }
        for (v, &q) in p.iter().enumerate() {
            if tri.contains(&(v as u32)) || incircle(a, b, cc, q) <= 0.0 {
                continue;
            }
            let hidden = cons_segs
                .iter()
                .any(|&(s0, s1)| cross_properly(g, q, s0, s1));
            assert!(
                hidden,
                "vertex {v} is visible inside the circumcircle of {tri:?}"
            );
        }
    }
    let _ = input;
}

fn shoelace(r: &[[f64; 2]]) -> f64 {
    let m = r.len();
    let mut s = 0.0;
    for k in 0..m {
        let (a, b) = (r[k], r[(k + 1) % m]);
        s += a[0] * b[1] - a[1] * b[0];
    }
    0.5 * s
}

/// Random segments between the points that cross no earlier accepted one (they may pass
/// through points and overlap collinearly).
fn noncrossing_segments(p: &[Point2], tries: usize, r: &mut impl Rng) -> Vec<[u32; 2]> {
    let mut out: Vec<[u32; 2]> = Vec::new();
    for _ in 0..tries {
        let i = r.gen_range(0..p.len()) as u32;
        let j = r.gen_range(0..p.len()) as u32;
        let (a, b) = (xy(&p[i as usize]), xy(&p[j as usize]));
        if out
            .iter()
            .all(|s| !cross_properly(a, b, xy(&p[s[0] as usize]), xy(&p[s[1] as usize])))
        {
            out.push([i, j]);
        }
    }
    out
}

fn random_points(n: usize, grid: Option<i32>, r: &mut impl Rng) -> Vec<Point2> {
    (0..n)
        .map(|_| match grid {
            Some(g) => Point2::new(r.gen_range(0..g) as f64, r.gen_range(0..g) as f64),
            None => Point2::new(r.gen::<f64>(), r.gen::<f64>()),
        })
        .collect()
}

#[test]
fn random_sets_against_the_visibility_oracle() {
    let mut r = rng(7);
    for case in 0..60 {
        let n = 5 + case % 40;
        let grid = if case % 3 == 0 { Some(6) } else { None };
        let p = random_points(n, grid, &mut r);
        let segs = noncrossing_segments(&p, 3 + case % 12, &mut r);
        let c = triangulate_constrained_2d(&p, &segs).unwrap();
        check_cdt(&p, &segs, &c, true);
    }
}

#[test]
fn no_constraints_is_the_delaunay_triangulation() {
    let mut r = rng(11);
    let p = random_points(300, None, &mut r);
    let d = triangulate_2d(&p).unwrap();
    let c = triangulate_constrained_2d(&p, &[]).unwrap();
    let set = |t: &[[u32; 3]]| {
        let mut v: Vec<[u32; 3]> = t
            .iter()
            .map(|x| {
                let mut y = *x;
                y.sort_unstable();
                y
            })
            .collect();
        v.sort_unstable();
        v
    };
    assert_eq!(set(&d.triangles), set(&c.triangles));
    assert!(c.constrained_edges().is_empty());
}

#[test]
fn long_segments_through_many_triangles() {
    let mut r = rng(3);
    let p = random_points(2000, None, &mut r);
    // random pairs among 2000 points: long segments crossing dozens of triangles each
    let segs = noncrossing_segments(&p, 60, &mut r);
    assert!(segs.len() > 10);
    let c = triangulate_constrained_2d(&p, &segs).unwrap();
    check_cdt(&p, &segs, &c, false);
}

#[test]
fn grid_with_constraints_along_grid_lines() {
    let g = 9;
    let mut p = Vec::new();
    for y in 0..g {
        for x in 0..g {
            p.push(Point2::new(x as f64, y as f64));
        }
    }
    let id = |x: usize, y: usize| (y * g + x) as u32;
    // full rows and columns (each passes through g − 2 vertices), a diagonal, duplicates,
    // reversed duplicates, an overlapping sub-segment
    let segs = vec![
        [id(0, 2), id(8, 2)],
        [id(8, 2), id(0, 2)],
        [id(3, 0), id(3, 8)],
        [id(0, 0), id(8, 8)],
        [id(1, 1), id(5, 5)],
        [id(2, 6), id(7, 6)],
        [id(2, 6), id(7, 6)],
        [id(0, 8), id(2, 7)],
        [id(4, 4), id(4, 4)],
    ];
    let c = triangulate_constrained_2d(&p, &segs).unwrap();
    check_cdt(&p, &segs, &c, true);
    assert_eq!(c.skipped, 1);
    assert!(c.splits >= 7 + 7 + 7);
    // a row of constraints crossing the column: error names both segments
    let bad = vec![[id(0, 2), id(8, 2)], [id(1, 0), id(2, 8)]];
    let e = triangulate_constrained_2d(&p, &bad)
        .unwrap_err()
        .to_string();
    assert!(e.contains("0 (") && e.contains("1 ("), "{e}");
}

#[test]
fn collinear_constraint_through_vertices_and_touching() {
    // points on a line plus two off the line; the constraint runs through all line points
    let mut p: Vec<Point2> = (0..10)
        .map(|k| Point2::new(k as f64 * 0.5, k as f64 * 0.25))
        .collect();
    p.push(Point2::new(1.0, 3.0));
    p.push(Point2::new(3.0, -2.0));
    // (1, 3)-(3, -2) meets the line at x = 11/6, not a vertex: a crossing
    let e = triangulate_constrained_2d(&p, &[[0, 9], [10, 11]])
        .unwrap_err()
        .to_string();
    assert!(e.contains("segments 0 (0, 9) and 1 (10, 11) cross"), "{e}");
    // the line constraint passes through 8 vertices; the others touch it at vertices
    let segs = vec![[0, 9], [10, 4], [11, 6], [10, 10], [2, 7]];
    let c = triangulate_constrained_2d(&p, &segs).unwrap();
    check_cdt(&p, &segs, &c, true);
    assert_eq!(c.skipped, 1);
    assert_eq!(c.splits, 8 + 4);
}

#[test]
fn crossing_and_invalid_segments_are_errors() {
    let p: Vec<Point2> = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0], [1.0, 3.0]]
        .iter()
        .map(|q| Point2::new(q[0], q[1]))
        .collect();
    let e = triangulate_constrained_2d(&p, &[[0, 2], [1, 3]])
        .unwrap_err()
        .to_string();
    assert!(e.contains("segments 0 (0, 2) and 1 (1, 3) cross"), "{e}");
    assert!(triangulate_constrained_2d(&p, &[[0, 7]]).is_err());
    // after an error the triangulation is intact and accepts further segments
    let mut c = triangulate_constrained_2d(&p, &[[0, 2]]).unwrap();
    assert!(c.insert_input_segments(&[[1, 3]]).is_err());
    check_cdt(&p, &[[0, 2]], &c, true);
    c.insert_input_segments(&[[2, 4]]).unwrap();
    check_cdt(&p, &[[0, 2], [2, 4]], &c, true);
    // segments that share an endpoint or touch at a vertex are fine
    let c = triangulate_constrained_2d(&p, &[[0, 2], [2, 4], [0, 1], [1, 2], [3, 4]]).unwrap();
    check_cdt(&p, &[[0, 2], [2, 4], [0, 1], [1, 2], [3, 4]], &c, true);
    // duplicate points: a segment between two copies is skipped
    let mut q = p.clone();
    q.push(Point2::new(0.0, 0.0));
    let c = triangulate_constrained_2d(&q, &[[0, 5], [5, 2]]).unwrap();
    assert_eq!(c.skipped, 1);
    check_cdt(&q, &[[0, 5], [5, 2]], &c, true);
    // collinear input: no triangles, constraints validated
    let l: Vec<Point2> = (0..4).map(|k| Point2::new(k as f64, 0.0)).collect();
    let c = triangulate_constrained_2d(&l, &[[0, 3]]).unwrap();
    assert!(c.triangles.is_empty() && c.collinear());
    assert!(triangulate_constrained_2d(&l, &[[0, 4]]).is_err());
}

/// A star-shaped polygon: `n` points at distinct angles (sorted) and random radii.
fn star_polygon(n: usize, r: &mut impl Rng) -> Vec<Point2> {
    let mut a: Vec<f64> = (0..n)
        .map(|k| (k as f64 + r.gen_range(0.05..0.95)) / n as f64 * std::f64::consts::TAU)
        .collect();
    a.sort_by(f64::total_cmp);
    a.iter()
        .map(|&t| {
            let rad = r.gen_range(0.2..1.0);
            Point2::new(rad * t.cos(), rad * t.sin())
        })
        .collect()
}

fn check_interior(p: &[Point2], cyc: &[u32], tris: &[[u32; 3]]) {
    let n = cyc.len();
    assert_eq!(tris.len(), n - 2);
    let ring: Vec<[f64; 2]> = cyc.iter().map(|&i| xy(&p[i as usize])).collect();
    let want = shoelace(&ring).abs();
    let mut area = 0.0;
    let mut edges: HashSet<(u32, u32)> = HashSet::new();
    for t in tris {
        let [a, b, c] = t.map(|v| xy(&p[v as usize]));
        assert!(orient2d(a, b, c) > 0.0);
        area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
        for i in 0..3 {
            let (u, v) = (t[i], t[(i + 1) % 3]);
            assert!(edges.insert((u, v)), "directed edge used twice");
        }
    }
    assert!(
        (area - want).abs() <= 1e-9 * want,
        "interior area {area} vs shoelace {want}"
    );
    // each polygon edge is used by exactly one triangle (in one direction)
    for k in 0..n {
        let (u, v) = (cyc[k], cyc[(k + 1) % n]);
        assert!(
            edges.contains(&(u, v)) ^ edges.contains(&(v, u)),
            "polygon edge {k} not on exactly one triangle"
        );
    }
}

#[test]
fn random_star_polygons() {
    let mut r = rng(5);
    for case in 0..30 {
        let n = 3 + case * 7;
        let p = star_polygon(n, &mut r);
        let mut cyc: Vec<u32> = (0..n as u32).collect();
        let t = triangulate_polygon_2d(&p, &cyc).unwrap();
        check_interior(&p, &cyc, &t);
        cyc.reverse();
        let t = triangulate_polygon_2d(&p, &cyc).unwrap();
        check_interior(&p, &cyc, &t);
    }
    // large: the old ear clipping returned nothing above 5000 vertices
    let p = star_polygon(12000, &mut r);
    let cyc: Vec<u32> = (0..12000).collect();
    let t = morpho::boundary::triangulate_polygon(&p.iter().map(xy).collect::<Vec<_>>(), &cyc);
    check_interior(&p, &cyc, &t);
}

#[test]
fn polygon_interior_errors() {
    let sq: Vec<Point2> = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0], [1.0, 0.0]]
        .iter()
        .map(|q| Point2::new(q[0], q[1]))
        .collect();
    // bow tie
    assert!(triangulate_polygon_2d(&sq, &[0, 1, 3, 2]).is_err());
    // repeated vertex
    assert!(triangulate_polygon_2d(&sq, &[0, 1, 2, 0, 3]).is_err());
    // vertex 4 lies on edge 0-1
    let e = triangulate_polygon_2d(&sq, &[0, 1, 2, 3, 4]).unwrap_err();
    assert!(e.to_string().contains("passes through"), "{e}");
    assert!(triangulate_polygon_2d(&sq, &[0, 1, 2, 4]).is_err());
    assert!(triangulate_polygon_2d(&sq, &[0, 1]).is_err());
    assert!(triangulate_polygon_2d(&sq, &[0, 1, 9]).is_err());
    assert!(triangulate_polygon_2d(&sq, &[0, 4, 1]).is_err()); // collinear
    let t = triangulate_polygon_2d(&sq, &[0, 4, 1, 2, 3]).unwrap();
    check_interior(&sq, &[0, 4, 1, 2, 3], &t);
}

/// Two-column CSV with a header (extra columns: the last two are x, y).
fn read_xy(path: &std::path::Path) -> Vec<Point2> {
    let s = std::fs::read_to_string(path).unwrap();
    s.lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let f: Vec<f64> = l.split(',').map(|x| x.trim().parse().unwrap()).collect();
            Point2::new(f[f.len() - 2], f[f.len() - 1])
        })
        .collect()
}

#[test]
fn real_polygons() {
    let Some(dir) = data_dir() else { return };
    let poly = dir.join("polygons");
    for (name, simple) in [
        ("coast_great_britain_ne10m.csv", true),
        ("coast_ireland_ne10m.csv", true),
        ("benelux_mainland_ne50m.csv", true),
        ("meuse_riv.csv", true),
        ("coast_iceland_ne10m.csv", false),
        ("benelux_mainland_ne10m.csv", false),
    ] {
        let mut p = read_xy(&poly.join(name));
        if p.first() == p.last() {
            p.pop();
        }
        let cyc: Vec<u32> = (0..p.len() as u32).collect();
        let r = triangulate_polygon_2d(&p, &cyc);
        if simple {
            let t = r.unwrap_or_else(|e| panic!("{name}: {e}"));
            check_interior(&p, &cyc, &t);
        } else {
            let e = r.expect_err(name).to_string();
            assert!(e.contains("cross"), "{name}: {e}");
        }
    }
    // closed ground-truth curves sampled in order (y down: clockwise or not, both work)
    for name in [
        "blob2_samples.csv",
        "simple_samples.csv",
        "spiral_samples.csv",
        "spiral_samples_sparse.csv",
    ] {
        let p = read_xy(&dir.join("curves2d/svg_groundtruth").join(name));
        let cyc: Vec<u32> = (0..p.len() as u32).collect();
        let t = triangulate_polygon_2d(&p, &cyc).unwrap_or_else(|e| panic!("{name}: {e}"));
        check_interior(&p, &cyc, &t);
    }
    // earcut fixtures: outer rings
    for (name, ok) in [
        ("hilbert.json", true),
        ("dude.json", true),
        ("building.json", true),
        ("collinear-diagonal.json", false), // repeats vertices
        ("water.json", false),              // vertex 2392 repeats an earlier one
        ("degenerate.json", false),
        ("hourglass.json", false),
    ] {
        let s = std::fs::read_to_string(dir.join("polygons/mapbox_earcut").join(name)).unwrap();
        let v: Vec<Vec<[f64; 2]>> = serde_json::from_str(&s).unwrap();
        let mut p: Vec<Point2> = v[0].iter().map(|q| Point2::new(q[0], q[1])).collect();
        if p.len() > 1 && p.first() == p.last() {
            p.pop();
        }
        let cyc: Vec<u32> = (0..p.len() as u32).collect();
        let r = triangulate_polygon_2d(&p, &cyc);
        if ok {
            let t = r.unwrap_or_else(|e| panic!("{name}: {e}"));
            check_interior(&p, &cyc, &t);
        } else {
            assert!(r.is_err(), "{name}");
        }
    }
}

#[test]
fn polygon_with_holes_by_depth() {
    // square with a square hole: the constraints of both rings, odd depth = inside
    let p: Vec<Point2> = [
        [0.0, 0.0],
        [4.0, 0.0],
        [4.0, 4.0],
        [0.0, 4.0],
        [1.0, 1.0],
        [3.0, 1.0],
        [3.0, 3.0],
        [1.0, 3.0],
    ]
    .iter()
    .map(|q| Point2::new(q[0], q[1]))
    .collect();
    let segs = [
        [0, 1],
        [1, 2],
        [2, 3],
        [3, 0],
        [4, 5],
        [5, 6],
        [6, 7],
        [7, 4],
    ];
    let c = triangulate_constrained_2d(&p, &segs).unwrap();
    check_cdt(&p, &segs, &c, true);
    let d = c.depths();
    let pts = c.points();
    let area: f64 = c
        .triangles
        .iter()
        .zip(&d)
        .filter(|(_, &k)| k % 2 == 1)
        .map(|(t, _)| {
            let [a, b, cc] = t.map(|v| pts[v as usize]);
            0.5 * (b - a).perp(&(cc - a))
        })
        .sum();
    assert_eq!(area, 12.0);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, .. ProptestConfig::default() })]

    #[test]
    fn prop_random_cdt(seed in any::<u64>(), n in 3usize..40, m in 0usize..25, grid in prop::option::of(2i32..8)) {
        let mut r = rng(seed);
        let p = random_points(n, grid, &mut r);
        let segs = noncrossing_segments(&p, m, &mut r);
        match triangulate_constrained_2d(&p, &segs) {
            Ok(c) => check_cdt(&p, &segs, &c, true),
            Err(e) => prop_assert!(false, "{e}"),
        }
    }

    #[test]
    fn prop_star_polygon(seed in any::<u64>(), n in 3usize..200) {
        let mut r = rng(seed);
        let p = star_polygon(n, &mut r);
        let cyc: Vec<u32> = (0..n as u32).collect();
        let t = triangulate_polygon_2d(&p, &cyc).unwrap();
        check_interior(&p, &cyc, &t);
    }
}

#[test]
fn boundary_interior_in_the_general_engine() {
    // c < 0 runs the general constriction engine, whose interior comes from
    // `triangulate_polygon`: always n − 2 triangles with the polygon's area
    use morpho::boundary::{boundary_2d, CParam, Options2};
    let mut r = rng(21);
    for _ in 0..15 {
        let n = r.gen_range(5..60);
        let p = random_points(n, None, &mut r);
        let o = Options2 {
            method: morpho::boundary::Method2::Gamma {
                c: CParam::Fixed(-0.3),
                keep: Vec::new(),
            },
        };
        let b = boundary_2d(&p, &o).unwrap();
        check_interior(&p, &b.polygon, &b.interior);
        assert!(
            (b.area
                - shoelace(
                    &b.polygon
                        .iter()
                        .map(|&i| xy(&p[i as usize]))
                        .collect::<Vec<_>>()
                ))
            .abs()
                < 1e-12
        );
    }
}

#[test]
fn real_polygons_with_holes_by_depth_parity() {
    // earcut fixtures with holes: all ring edges as constraints; odd depth = inside, whose
    // area must be |outer| − Σ|holes| (water2.json is left out: its first hole runs along the
    // outer ring, where one constrained edge stands for two ring edges and parity fails).
    // water.json's outer ring is not simple: its edges 1 and 3 cross (exact integer check:
    // orient signs 424, −9 and −337, 96), which must be reported.
    let Some(dir) = data_dir() else { return };
    let load = |name: &str| -> Vec<Vec<[f64; 2]>> {
        let s = std::fs::read_to_string(dir.join("polygons/mapbox_earcut").join(name)).unwrap();
        serde_json::from_str(&s).unwrap()
    };
    let water = load("water.json");
    let p: Vec<Point2> = water[0].iter().map(|q| Point2::new(q[0], q[1])).collect();
    let m = p.len() as u32;
    let segs: Vec<[u32; 2]> = (0..m).map(|i| [i, (i + 1) % m]).collect();
    let e = triangulate_constrained_2d(&p, &segs)
        .unwrap_err()
        .to_string();
    assert!(e.contains("segments 1 (1, 2) and 3 (3, 4) cross"), "{e}");
    for name in ["dude.json"] {
        let rings = load(name);
        let mut p = Vec::new();
        let mut segs = Vec::new();
        let mut want = 0.0;
        for (k, ring) in rings.iter().enumerate() {
            let mut ring = ring.clone();
            if ring.len() > 1 && ring.first() == ring.last() {
                ring.pop();
            }
            let a = shoelace(&ring).abs();
            want += if k == 0 { a } else { -a };
            let base = p.len() as u32;
            let m = ring.len() as u32;
            for (i, q) in ring.iter().enumerate() {
                p.push(Point2::new(q[0], q[1]));
                segs.push([base + i as u32, base + (i as u32 + 1) % m]);
            }
        }
        let c = triangulate_constrained_2d(&p, &segs).unwrap_or_else(|e| panic!("{name}: {e}"));
        check_cdt(&p, &segs, &c, false);
        let d = c.depths();
        let pts = c.points();
        let area: f64 = c
            .triangles
            .iter()
            .zip(&d)
            .filter(|(_, &k)| k % 2 == 1)
            .map(|(t, _)| {
                let [a, b, cc] = t.map(|v| pts[v as usize]);
                0.5 * (b - a).perp(&(cc - a))
            })
            .sum();
        assert!(
            (area - want).abs() <= 1e-9 * want,
            "{name}: inside area {area} vs {want}"
        );
    }
}

/// Long stress run of the oracle (`cargo test --test cdt -- --ignored`): 20 000 random sets,
/// half on a 5 × 5 grid (many collinear and cocircular cases, segments through vertices).
#[test]
#[ignore]
fn stress_random_cdt() {
    for seed in 0..20000u64 {
        let mut r = rng(seed);
        let n = 4 + (seed % 30) as usize;
        let grid = if seed % 2 == 0 { Some(5) } else { None };
        let p = random_points(n, grid, &mut r);
        let segs = noncrossing_segments(&p, 3 + (seed % 10) as usize, &mut r);
        let c =
            triangulate_constrained_2d(&p, &segs).unwrap_or_else(|e| panic!("seed {seed}: {e}"));
        check_cdt(&p, &segs, &c, true);
    }
}
