//! Tests of the external contour (Dorgerloh et al. §3) against brute-force oracles built from the
//! definitions, special configurations, and property tests over random colourings.
//!
//! 2D oracle: S = all edges between a black triangle and a white triangle or the exterior
//! (found by brute-force search), directed with black on the left; cycles are traced by turning,
//! at each vertex, into the next edge of S counter-clockwise around the white side, and each
//! closed walk is cut at repeated vertices into simple cycles; a cycle is enclosed when an
//! edge of it lies inside another cycle (exact point-in-polygon / exact cone test); the
//! external contour is the set of cycles not enclosed.
//!
//! 3D oracle: S = faces between black and white/exterior tetrahedra, oriented outwards; faces
//! are joined into closed surfaces around each edge by turning through the white side (exact
//! angular order around the edge with orient3d); a surface is enclosed when a point of one of
//! its faces is inside another surface (exact ray parity with orient3d); the union of the
//! non-enclosed surfaces must equal the algorithm's faces.

mod common;
use morpho::contour::{
    boundary_regions, classify, external_contour, external_contour_with, external_surface,
    rate_triangles, Contour2, ContourOptions, Rating,
};
use morpho::geom::{orient2d, orient3d, Point2, Point3};
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::{BTreeSet, HashMap};

// ---------------------------------------------------------------- triangulations for testing

/// A jittered (nx+1)×(ny+1) lattice, each cell split in two along a random diagonal.
fn grid(nx: usize, ny: usize, jitter: f64, seed: u64) -> (Vec<Point2>, Vec<[u32; 3]>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut pts = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            let (dx, dy) = if jitter > 0.0 {
                (
                    rng.gen_range(-jitter..jitter),
                    rng.gen_range(-jitter..jitter),
                )
            } else {
                (0.0, 0.0)
            };
            pts.push(Point2::new(i as f64 + dx, j as f64 + dy));
        }
    }
    let v = |i: usize, j: usize| (j * (nx + 1) + i) as u32;
    let mut tri = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let (a, b, c, d) = (v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1));
            if jitter == 0.0 || rng.gen_bool(0.5) {
                tri.push([a, b, c]);
                tri.push([a, c, d]);
            } else {
                tri.push([a, b, d]);
                tri.push([b, c, d]);
            }
        }
    }
    (pts, tri)
}

/// Delaunay triangulation by brute force: every counter-clockwise triple whose circumcircle is
/// empty (random points, so no four are cocircular).
fn brute_delaunay(n: usize, seed: u64) -> (Vec<Point2>, Vec<[u32; 3]>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let pts: Vec<Point2> = (0..n)
        .map(|_| Point2::new(rng.gen_range(0.0..1.0), rng.gen_range(0.0..1.0)))
        .collect();
    let mut tri = Vec::new();
    for a in 0..n {
        for b in a + 1..n {
            for c in b + 1..n {
                let o = orient2d(&pts[a], &pts[b], &pts[c]);
                if o == 0.0 {
                    continue;
                }
                let (b2, c2) = if o > 0.0 { (b, c) } else { (c, b) };
                let empty = (0..n).all(|d| {
                    d == a
                        || d == b
                        || d == c
                        || morpho::geom::incircle(&pts[a], &pts[b2], &pts[c2], &pts[d]) < 0.0
                });
                if empty {
                    tri.push([a as u32, b2 as u32, c2 as u32]);
                }
            }
        }
    }
    (pts, tri)
}

fn ccw(tri: &[[u32; 3]], pts: &[Point2]) -> Vec<[u32; 3]> {
    tri.iter()
        .map(|&[a, b, c]| {
            if orient2d(&pts[a as usize], &pts[b as usize], &pts[c as usize]) > 0.0 {
                [a, b, c]
            } else {
                [a, c, b]
            }
        })
        .collect()
}

// ---------------------------------------------------------------- exact 2D helpers

/// Orders directions around `c`, counter-clockwise from the reference direction `c→r`:
/// the key compares (half, then orientation). Returns true when `w1` comes before `w2`.
fn ccw_before(c: &Point2, r: &Point2, w1: &Point2, w2: &Point2) -> bool {
    let half = |w: &Point2| -> u8 {
        let o = orient2d(c, r, w);
        if o > 0.0 {
            0
        } else if o < 0.0 {
            2
        } else {
            let same = (w.x - c.x).signum() == (r.x - c.x).signum()
                && (w.y - c.y).signum() == (r.y - c.y).signum();
            if same {
                3
            } else {
                1
            }
        }
    };
    let (h1, h2) = (half(w1), half(w2));
    if h1 != h2 {
        return h1 < h2;
    }
    if h1 == 0 || h1 == 2 {
        orient2d(c, w1, w2) > 0.0
    } else {
        false
    }
}

/// Exact point-in-polygon (crossing parity) for a point not on the polygon.
fn point_in_ring(q: &Point2, ring: &[u32], pts: &[Point2]) -> bool {
    let n = ring.len();
    let mut inside = false;
    for i in 0..n {
        let a = &pts[ring[i] as usize];
        let b = &pts[ring[(i + 1) % n] as usize];
        if (a.y > q.y) != (b.y > q.y) {
            let o = orient2d(a, b, q);
            assert!(o != 0.0, "query point on the ring");
            if (b.y > a.y) == (o > 0.0) {
                inside = !inside;
            }
        }
    }
    inside
}

fn ring_ccw(ring: &[u32], pts: &[Point2]) -> bool {
    let n = ring.len();
    let mut m = 0;
    for i in 1..n {
        let (p, q) = (pts[ring[i] as usize], pts[ring[m] as usize]);
        if p.x < q.x || (p.x == q.x && p.y < q.y) {
            m = i;
        }
    }
    let p = |i: usize| &pts[ring[i % n] as usize];
    orient2d(p(m + n - 1), p(m), p(m + 1)) > 0.0
}

/// True when cycle `a` is enclosed by the (simple) cycle `b`: its first edge lies inside `b`.
fn enclosed(a: &[u32], b: &[u32], pts: &[Point2]) -> bool {
    let (u, w) = (a[0], a[1]);
    match b.iter().position(|&x| x == u) {
        None => point_in_ring(&pts[u as usize], b, pts),
        Some(k) => {
            let n = b.len();
            let (prev, next) = (b[(k + n - 1) % n], b[(k + 1) % n]);
            let c = &pts[u as usize];
            // Interior of b at u: counter-clockwise sweep from u→next to u→prev (CCW ring), or
            // from u→prev to u→next (CW ring).
            let (r1, r2) = if ring_ccw(b, pts) {
                (next, prev)
            } else {
                (prev, next)
            };
            ccw_before(c, &pts[r1 as usize], &pts[w as usize], &pts[r2 as usize])
        }
    }
}

fn segments_intersect(p1: &Point2, p2: &Point2, q1: &Point2, q2: &Point2) -> bool {
    let d1 = orient2d(q1, q2, p1);
    let d2 = orient2d(q1, q2, p2);
    let d3 = orient2d(p1, p2, q1);
    let d4 = orient2d(p1, p2, q2);
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    let on = |a: &Point2, b: &Point2, p: &Point2| {
        p.x >= a.x.min(b.x) && p.x <= a.x.max(b.x) && p.y >= a.y.min(b.y) && p.y <= a.y.max(b.y)
    };
    (d1 == 0.0 && on(q1, q2, p1))
        || (d2 == 0.0 && on(q1, q2, p2))
        || (d3 == 0.0 && on(p1, p2, q1))
        || (d4 == 0.0 && on(p1, p2, q2))
}

/// Asserts that the ring is a simple polygon (exact segment intersection tests).
fn assert_simple(ring: &[u32], pts: &[Point2]) {
    let n = ring.len();
    assert!(n >= 3, "ring with {n} vertices");
    let set: BTreeSet<u32> = ring.iter().copied().collect();
    assert_eq!(set.len(), n, "ring repeats a vertex: {ring:?}");
    for i in 0..n {
        for j in i + 1..n {
            let adjacent = j == i + 1 || (i == 0 && j == n - 1);
            let (a, b) = (&pts[ring[i] as usize], &pts[ring[(i + 1) % n] as usize]);
            let (c, d) = (&pts[ring[j] as usize], &pts[ring[(j + 1) % n] as usize]);
            if adjacent {
                // Sharing one endpoint: they must not overlap (fold back).
                let (s, x, y) = if j == i + 1 { (b, a, d) } else { (a, b, c) };
                let o = orient2d(x, s, y);
                let same_ray = (y.x - s.x).signum() == (x.x - s.x).signum()
                    && (y.y - s.y).signum() == (x.y - s.y).signum();
                assert!(!(o == 0.0 && same_ray), "edges fold back: {ring:?}");
            } else {
                assert!(!segments_intersect(a, b, c, d), "ring not simple: {ring:?}");
            }
        }
    }
}

fn normalize(c: &[u32]) -> Vec<u32> {
    let m = (0..c.len()).min_by_key(|&i| c[i]).unwrap();
    c[m..].iter().chain(c[..m].iter()).copied().collect()
}

// ---------------------------------------------------------------- 2D oracles

/// Directed boundary edges a→b (black on the left) with the black triangle's index.
fn brute_s(tri: &[[u32; 3]], black: &[bool]) -> Vec<(u32, u32, usize)> {
    let mut s = Vec::new();
    for (t, tr) in tri.iter().enumerate() {
        if !black[t] {
            continue;
        }
        for k in 0..3 {
            let (a, b) = (tr[k], tr[(k + 1) % 3]);
            let other =
                (0..tri.len()).find(|&u| u != t && tri[u].contains(&a) && tri[u].contains(&b));
            if other.map_or(true, |u| !black[u]) {
                s.push((a, b, t));
            }
        }
    }
    s
}

/// Follows S from each unused edge, choosing at a vertex the next edge by `pick`.
fn trace_walks(
    s: &[(u32, u32, usize)],
    pts: &[Point2],
    allowed: impl Fn(usize, usize) -> bool,
) -> Vec<Vec<u32>> {
    let mut out_of: HashMap<u32, Vec<usize>> = HashMap::new();
    for (i, e) in s.iter().enumerate() {
        out_of.entry(e.0).or_default().push(i);
    }
    let mut used = vec![false; s.len()];
    let mut walks = Vec::new();
    for start in 0..s.len() {
        if used[start] {
            continue;
        }
        let mut walk = Vec::new();
        let mut e = start;
        loop {
            used[e] = true;
            walk.push(s[e].0);
            let (a, b) = (s[e].0, s[e].1);
            let cands = &out_of[&b];
            let mut best: Option<usize> = None;
            for &f in cands {
                if !allowed(e, f) {
                    continue;
                }
                let w = &pts[s[f].1 as usize];
                best = match best {
                    None => Some(f),
                    Some(g) => {
                        if ccw_before(&pts[b as usize], &pts[a as usize], w, &pts[s[g].1 as usize])
                        {
                            Some(f)
                        } else {
                            Some(g)
                        }
                    }
                };
            }
            e = best.expect("no outgoing edge");
            if e == start {
                break;
            }
            assert!(!used[e], "walk re-uses an edge");
        }
        walks.push(walk);
    }
    walks
}

/// Cuts a closed walk at repeated vertices into simple cycles.
fn split_walk(walk: &[u32]) -> Vec<Vec<u32>> {
    let mut out = Vec::new();
    let mut stack: Vec<u32> = Vec::new();
    for &v in walk {
        if let Some(p) = stack.iter().position(|&x| x == v) {
            out.push(stack.split_off(p));
        }
        stack.push(v);
    }
    out.push(stack);
    out
}

/// The external contour by the definition, as normalised cycles.
fn oracle_external(tri: &[[u32; 3]], pts: &[Point2], black: &[bool]) -> BTreeSet<Vec<u32>> {
    let tri = ccw(tri, pts);
    let s = brute_s(&tri, black);
    let walks = trace_walks(&s, pts, |_, _| true);
    let cycles: Vec<Vec<u32>> = walks.iter().flat_map(|w| split_walk(w)).collect();
    let mut out = BTreeSet::new();
    for (i, c) in cycles.iter().enumerate() {
        let enc = cycles
            .iter()
            .enumerate()
            .any(|(j, d)| i != j && enclosed(c, d, pts));
        if !enc {
            out.insert(normalize(c));
        }
    }
    out
}

/// The complete boundary by the definition: per edge-connected black set, its rings.
/// Returns polygons as (outer, sorted holes), normalised.
fn oracle_regions(
    tri: &[[u32; 3]],
    pts: &[Point2],
    black: &[bool],
) -> BTreeSet<(Vec<u32>, Vec<Vec<u32>>)> {
    let tri = ccw(tri, pts);
    let n = tri.len();
    // Union-find over black triangles sharing an edge.
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(p: &mut [usize], x: usize) -> usize {
        let mut x = x;
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    for t in 0..n {
        for u in t + 1..n {
            if black[t] && black[u] && tri[t].iter().filter(|v| tri[u].contains(v)).count() == 2 {
                let (a, b) = (find(&mut parent, t), find(&mut parent, u));
                parent[a] = b;
            }
        }
    }
    let comp: Vec<usize> = (0..n).map(|t| find(&mut parent, t)).collect();
    let s = brute_s(&tri, black);
    let walks = trace_walks(&s, pts, |e, f| comp[s[e].2] == comp[s[f].2]);
    type Rings = (Option<Vec<u32>>, Vec<Vec<u32>>);
    let mut by: HashMap<usize, Rings> = HashMap::new();
    for w in walks {
        let c = comp[s.iter().find(|e| e.0 == w[0] && e.1 == w[1]).unwrap().2];
        let entry = by.entry(c).or_default();
        assert_simple(&w, pts);
        if ring_ccw(&w, pts) {
            assert!(entry.0.is_none(), "two outer rings");
            entry.0 = Some(normalize(&w));
        } else {
            entry.1.push(normalize(&w));
        }
    }
    by.into_values()
        .map(|(o, mut h)| {
            h.sort();
            (o.expect("no outer ring"), h)
        })
        .collect()
}

fn regions_of(c: &Contour2) -> BTreeSet<(Vec<u32>, Vec<Vec<u32>>)> {
    c.regions
        .iter()
        .map(|r| {
            let mut h: Vec<Vec<u32>> = r
                .holes
                .iter()
                .map(|&i| normalize(&c.cycles[i as usize]))
                .collect();
            h.sort();
            (normalize(&c.cycles[r.outer as usize]), h)
        })
        .collect()
}

fn external_set(c: &Contour2) -> BTreeSet<Vec<u32>> {
    c.cycles.iter().map(|x| normalize(x)).collect()
}

/// Runs both algorithms and both oracles on one coloured triangulation and compares.
fn check_all(tri: &[[u32; 3]], pts: &[Point2], black: &[bool]) -> (Contour2, Contour2) {
    let ext = external_contour(tri, pts, black).unwrap();
    let want = oracle_external(tri, pts, black);
    assert_eq!(
        external_set(&ext),
        want,
        "external contour differs from the oracle"
    );
    assert_eq!(ext.cycles.len(), ext.regions.len());
    for c in &ext.cycles {
        assert_simple(c, pts);
        assert!(ring_ccw(c, pts));
    }
    let full = boundary_regions(tri, None, pts, black, &ContourOptions::default()).unwrap();
    assert_eq!(regions_of(&full), oracle_regions(tri, pts, black));
    let black_area: f64 = tri
        .iter()
        .zip(black)
        .filter(|(_, &b)| b)
        .map(|(t, _)| {
            let [a, b, c] = t.map(|v| pts[v as usize]);
            0.5 * (b - a).perp(&(c - a)).abs()
        })
        .sum();
    let region_area: f64 = full.regions.iter().map(|r| r.area).sum();
    assert!((black_area - region_area).abs() < 1e-9 * (1.0 + black_area));
    for r in &full.regions {
        assert!(ring_ccw(&full.cycles[r.outer as usize], pts));
        for &h in &r.holes {
            assert!(!ring_ccw(&full.cycles[h as usize], pts));
            assert_simple(&full.cycles[h as usize], pts);
        }
        assert_simple(&full.cycles[r.outer as usize], pts);
    }
    // Regions that are external are exactly those whose outer ring touches the external contour.
    let ext_edges: BTreeSet<(u32, u32)> = ext
        .cycles
        .iter()
        .flat_map(|c| (0..c.len()).map(move |i| (c[i], c[(i + 1) % c.len()])))
        .collect();
    for r in &full.regions {
        let o = &full.cycles[r.outer as usize];
        let touches = (0..o.len()).any(|i| ext_edges.contains(&(o[i], o[(i + 1) % o.len()])));
        assert_eq!(touches, r.external);
    }
    (ext, full)
}

// ---------------------------------------------------------------- colourings

fn random_colours(n: usize, p: f64, seed: u64) -> Vec<bool> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n).map(|_| rng.gen_bool(p)).collect()
}

fn by_centroid(tri: &[[u32; 3]], pts: &[Point2], f: impl Fn(f64, f64) -> bool) -> Vec<bool> {
    tri.iter()
        .map(|t| {
            let c = t
                .iter()
                .fold(Point2::origin(), |s, &v| s + pts[v as usize].coords / 3.0);
            f(c.x, c.y)
        })
        .collect()
}

// ---------------------------------------------------------------- tests

#[test]
fn random_grids_match_oracle() {
    for seed in 0..40u64 {
        let (pts, tri) = grid(9, 8, 0.2, seed);
        let p = [0.3, 0.5, 0.6, 0.75][seed as usize % 4];
        let black = random_colours(tri.len(), p, 1000 + seed);
        check_all(&tri, &pts, &black);
    }
}

#[test]
fn random_delaunay_match_oracle() {
    for seed in 0..12u64 {
        let (pts, tri) = brute_delaunay(36, seed);
        assert_eq!(tri.len(), morpho_hull_tri_count(&pts));
        for (k, p) in [0.3, 0.55, 0.8].iter().enumerate() {
            let black = random_colours(tri.len(), *p, seed * 7 + k as u64);
            check_all(&tri, &pts, &black);
        }
    }
}

/// Number of triangles of any triangulation of the points: 2n − 2 − h (h hull vertices, by
/// brute force), a check that the brute-force Delaunay is complete.
fn morpho_hull_tri_count(pts: &[Point2]) -> usize {
    let n = pts.len();
    let h = (0..n)
        .filter(|&i| {
            // i is a hull vertex when some line through it has all others on one side.
            (0..n).any(|j| {
                j != i
                    && (0..n).all(|k| k == i || k == j || orient2d(&pts[i], &pts[j], &pts[k]) > 0.0)
            })
        })
        .count();
    2 * n - 2 - h
}

#[test]
fn all_white_and_all_black() {
    let (pts, tri) = brute_delaunay(30, 3);
    let c = external_contour(&tri, &pts, &vec![false; tri.len()]).unwrap();
    assert!(c.cycles.is_empty());
    assert_eq!(c.components, 0);
    let c = external_contour(&tri, &pts, &vec![true; tri.len()]).unwrap();
    assert_eq!(c.cycles.len(), 1);
    // The cycle is the convex hull, counter-clockwise.
    let hull = &c.cycles[0];
    let n = hull.len();
    for i in 0..n {
        let (a, b) = (&pts[hull[i] as usize], &pts[hull[(i + 1) % n] as usize]);
        for (k, q) in pts.iter().enumerate() {
            if k as u32 != hull[i] && k as u32 != hull[(i + 1) % n] {
                assert!(orient2d(a, b, q) > 0.0, "not the convex hull");
            }
        }
    }
    assert_eq!(n, 2 * pts.len() - 2 - tri.len());
    assert_eq!(c.black, tri.len());
}

#[test]
fn component_touching_the_hull() {
    let (pts, tri) = grid(10, 10, 0.0, 0);
    let black = by_centroid(&tri, &pts, |x, y| x < 4.0 && y < 3.0);
    let (ext, full) = check_all(&tri, &pts, &black);
    assert_eq!(ext.cycles.len(), 1);
    assert_eq!(ext.cycles[0].len(), 14);
    assert!((ext.regions[0].area - 12.0).abs() < 1e-12);
    assert_eq!(full.regions.len(), 1);
}

/// Cells of a regular grid (diagonals from (i,j) to (i+1,j+1)) as black.
fn cells(
    nx: usize,
    ny: usize,
    black_cells: &[(usize, usize)],
) -> (Vec<Point2>, Vec<[u32; 3]>, Vec<bool>) {
    let (pts, tri) = grid(nx, ny, 0.0, 0);
    let mut black = vec![false; tri.len()];
    for &(i, j) in black_cells {
        let c = j * nx + i;
        black[2 * c] = true;
        black[2 * c + 1] = true;
    }
    (pts, tri, black)
}

#[test]
fn components_touching_at_a_vertex_are_split_there() {
    // Two squares touching at vertex (2,2): two simple cycles sharing that vertex.
    let (pts, tri, black) = cells(5, 5, &[(1, 1), (2, 2)]);
    let (ext, full) = check_all(&tri, &pts, &black);
    assert_eq!(ext.cycles.len(), 2);
    let shared = 2 * 6 + 2;
    assert!(ext
        .cycles
        .iter()
        .all(|c| c.len() == 4 && c.contains(&shared)));
    assert_eq!(full.regions.len(), 2);
    // Same with single triangles touching at a vertex.
    let (pts, tri) = grid(4, 4, 0.0, 0);
    let mut black = vec![false; tri.len()];
    black[2 * 5 + 1] = true; // cell (1,1) upper: (1,1),(2,2),(1,2)
    black[2 * 10] = true; // cell (2,2) lower: (2,2),(3,2),(3,3)
    let (ext, _) = check_all(&tri, &pts, &black);
    assert_eq!(ext.cycles.len(), 2);
    assert!(ext.cycles.iter().all(|c| c.len() == 3));
}

#[test]
fn arms_touching_at_a_vertex_enclose_a_pocket() {
    // A ring of 8 cells around the white cell (2,2), without the corner cell (1,1): the arms
    // (2,1) and (1,2) touch at vertex (2,2), the centre cell is an enclosed white pocket.
    let ring: Vec<(usize, usize)> =
        [(2, 1), (3, 1), (3, 2), (3, 3), (2, 3), (1, 3), (1, 2)].to_vec();
    let (pts, tri, black) = cells(5, 5, &ring);
    let (ext, full) = check_all(&tri, &pts, &black);
    assert_eq!(ext.cycles.len(), 1);
    let pinch = 2 * 6 + 2;
    assert_eq!(ext.cycles[0].iter().filter(|&&v| v == pinch).count(), 1);
    assert!(
        (ext.regions[0].area - 8.0).abs() < 1e-12,
        "pocket belongs to the region"
    );
    assert_eq!(full.regions.len(), 1);
    assert_eq!(full.regions[0].holes.len(), 1);
    let hole = &full.cycles[full.regions[0].holes[0] as usize];
    assert_eq!(hole.len(), 4);
    assert!(hole.contains(&pinch));
    assert!((full.regions[0].area - 7.0).abs() < 1e-12);
}

#[test]
fn nested_rings() {
    // Black ring, white ring inside it, black disc inside that.
    let (pts, tri) = grid(12, 12, 0.15, 5);
    let black = by_centroid(&tri, &pts, |x, y| {
        let r = ((x - 6.0).powi(2) + (y - 6.0).powi(2)).sqrt();
        r < 1.6 || (3.2..5.2).contains(&r)
    });
    let (ext, full) = check_all(&tri, &pts, &black);
    assert_eq!(ext.cycles.len(), 1);
    assert_eq!(full.regions.len(), 2);
    let outer = full.regions.iter().find(|r| r.external).unwrap();
    assert_eq!(outer.holes.len(), 1);
    let inner = full.regions.iter().find(|r| !r.external).unwrap();
    assert!(inner.holes.is_empty());
    // The disc is enclosed: it is not part of the external contour.
    assert!(!ext
        .cycles
        .iter()
        .any(|c| normalize(c) == normalize(&full.cycles[inner.outer as usize])));
}

#[test]
fn ring_of_touching_squares_is_one_component() {
    // Four 3×3 blocks touching at corners around a white centre block holding a black island:
    // one external cycle (the paper's component includes the enclosed centre), four plus one
    // regions in the complete boundary, the island not external.
    let mut bc = Vec::new();
    for &(bi, bj) in &[(1usize, 0usize), (0, 1), (2, 1), (1, 2)] {
        for di in 0..3 {
            for dj in 0..3 {
                bc.push((3 * bi + di, 3 * bj + dj));
            }
        }
    }
    bc.push((4, 4));
    let (pts, tri, black) = cells(9, 9, &bc);
    let (ext, full) = check_all(&tri, &pts, &black);
    assert_eq!(ext.cycles.len(), 1);
    assert_eq!(ext.cycles[0].len(), 4 * 9);
    assert_eq!(full.regions.len(), 5);
    assert_eq!(full.regions.iter().filter(|r| r.external).count(), 4);
}

#[test]
fn min_area_drops_small_regions() {
    let (pts, tri, black) = cells(8, 8, &[(1, 1), (4, 4), (5, 4), (4, 5), (5, 5)]);
    let opts = ContourOptions { min_area: 2.0 };
    let c = external_contour_with(&tri, None, &pts, &black, &opts).unwrap();
    assert_eq!(c.cycles.len(), 1);
    assert_eq!(c.dropped, 1);
    assert!((c.regions[0].area - 4.0).abs() < 1e-12);
    let c = boundary_regions(&tri, None, &pts, &black, &opts).unwrap();
    assert_eq!(c.regions.len(), 1);
    assert_eq!(c.dropped, 1);
}

#[test]
fn given_neighbors_and_clockwise_input() {
    let (pts, tri) = grid(7, 6, 0.2, 9);
    let black = random_colours(tri.len(), 0.5, 4);
    let a = external_contour(&tri, &pts, &black).unwrap();
    // Clockwise triangles give the same result.
    let cw: Vec<[u32; 3]> = tri.iter().map(|&[a, b, c]| [a, c, b]).collect();
    let b = external_contour(&cw, &pts, &black).unwrap();
    assert_eq!(external_set(&a), external_set(&b));
    let nb = morpho::contour::simplex_neighbors(&tri, pts.len()).unwrap();
    let c =
        external_contour_with(&tri, Some(&nb), &pts, &black, &ContourOptions::default()).unwrap();
    assert_eq!(a, c);
    // Bad inputs are errors, not panics.
    assert!(external_contour(&tri, &pts, &black[1..]).is_err());
    assert!(external_contour(&[[0, 1, 99]], &pts, &[true]).is_err());
    let flat = [
        Point2::new(0.0, 0.0),
        Point2::new(1.0, 1.0),
        Point2::new(2.0, 2.0),
    ];
    assert!(external_contour(&[[0, 1, 2]], &flat, &[true]).is_err());
    let mut bad = nb.clone();
    bad[0][0] = 5;
    assert!(
        external_contour_with(&tri, Some(&bad), &pts, &black, &ContourOptions::default()).is_err()
    );
}

#[test]
fn rated_samples_threshold_above_and_below() {
    let (pts, tri) = grid(10, 10, 0.2, 2);
    let values: Vec<f64> = pts
        .iter()
        .map(|p| (p.x * 0.7).sin() + (p.y * 0.5).cos())
        .collect();
    for rating in [
        Rating::Mean,
        Rating::Min,
        Rating::Max,
        Rating::Median,
        Rating::AreaMean,
    ] {
        let r = rate_triangles(&tri, &pts, &values, rating).unwrap();
        for below in [false, true] {
            let black = classify(&r, 0.3, below);
            check_all(&tri, &pts, &black);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn prop_random_colourings(nx in 2usize..9, ny in 2usize..9, seed in 0u64..1000, p in 0.0f64..1.0, jitter in prop::sample::select(vec![0.0, 0.2])) {
        let (pts, tri) = grid(nx, ny, jitter, seed);
        let black = random_colours(tri.len(), p, seed ^ 0xabcdef);
        check_all(&tri, &pts, &black);
    }
}

// ---------------------------------------------------------------- 3D

/// A jittered lattice of n³ cubes, 6 tetrahedra per cube (Kuhn subdivision along the diagonal).
fn cube_lattice(n: usize, jitter: f64, seed: u64) -> (Vec<Point3>, Vec<[u32; 4]>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let m = n + 1;
    let mut pts = Vec::new();
    for k in 0..m {
        for j in 0..m {
            for i in 0..m {
                let mut d = || rng.gen_range(-jitter..=jitter);
                pts.push(Point3::new(i as f64 + d(), j as f64 + d(), k as f64 + d()));
            }
        }
    }
    let v = |i: usize, j: usize, k: usize| ((k * m + j) * m + i) as u32;
    let perms = [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ];
    let mut tets = Vec::new();
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                for p in &perms {
                    let mut c = [i, j, k];
                    let mut t = [v(i, j, k); 4];
                    for (s, &ax) in p.iter().enumerate() {
                        c[ax] += 1;
                        t[s + 1] = v(c[0], c[1], c[2]);
                    }
                    tets.push(t);
                }
            }
        }
    }
    (pts, tets)
}

fn oriented_face(f: [u32; 3], opp: u32, pts: &[Point3]) -> [u32; 3] {
    let p = |v: u32| &pts[v as usize];
    let o = orient3d(p(f[0]), p(f[1]), p(f[2]), p(opp));
    assert!(o != 0.0);
    if o > 0.0 {
        f
    } else {
        [f[0], f[2], f[1]]
    }
}

fn norm_face(f: [u32; 3]) -> [u32; 3] {
    let m = (0..3).min_by_key(|&i| f[i]).unwrap();
    [f[m], f[(m + 1) % 3], f[(m + 2) % 3]]
}

/// Exact ray parity: is `q` inside the closed surface `faces`?
fn point_in_surface(q: &Point3, faces: &[[u32; 3]], pts: &[Point3], rng: &mut ChaCha8Rng) -> bool {
    'retry: loop {
        let far = Point3::new(
            q.x + rng.gen_range(-1.0..1.0) * 1e3 + 1e3,
            q.y + rng.gen_range(-1.0..1.0) * 1e3,
            q.z + rng.gen_range(-1.0..1.0) * 1e3,
        );
        let mut inside = false;
        for f in faces {
            let [a, b, c] = f.map(|v| &pts[v as usize]);
            let s1 = orient3d(a, b, c, q);
            let s2 = orient3d(a, b, c, &far);
            if s1 == 0.0 || s2 == 0.0 {
                continue 'retry;
            }
            if (s1 > 0.0) == (s2 > 0.0) {
                continue;
            }
            let e1 = orient3d(q, &far, a, b);
            let e2 = orient3d(q, &far, b, c);
            let e3 = orient3d(q, &far, c, a);
            if e1 == 0.0 || e2 == 0.0 || e3 == 0.0 {
                continue 'retry;
            }
            if (e1 > 0.0) == (e2 > 0.0) && (e2 > 0.0) == (e3 > 0.0) {
                inside = !inside;
            }
        }
        return inside;
    }
}

fn oracle_surface(tets: &[[u32; 4]], pts: &[Point3], black: &[bool]) -> BTreeSet<[u32; 3]> {
    // S: faces of black tetrahedra not shared with another black one, oriented outwards.
    let mut s: Vec<[u32; 3]> = Vec::new();
    for (t, tt) in tets.iter().enumerate() {
        if !black[t] {
            continue;
        }
        for k in 0..4 {
            let f: Vec<u32> = (0..4).filter(|&i| i != k).map(|i| tt[i]).collect();
            let other = (0..tets.len()).find(|&u| u != t && f.iter().all(|v| tets[u].contains(v)));
            if other.map_or(true, |u| !black[u]) {
                s.push(oriented_face([f[0], f[1], f[2]], tt[k], pts));
            }
        }
    }
    // Join faces around each directed edge by turning through the white side.
    let mut parent: Vec<usize> = (0..s.len()).collect();
    fn find(p: &mut [usize], x: usize) -> usize {
        let mut x = x;
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    let mut by_edge: HashMap<(u32, u32), Vec<(usize, u32)>> = HashMap::new();
    for (i, f) in s.iter().enumerate() {
        for k in 0..3 {
            let (a, b, c) = (f[k], f[(k + 1) % 3], f[(k + 2) % 3]);
            by_edge
                .entry((a.min(b), a.max(b)))
                .or_default()
                .push((i, c));
        }
    }
    for (i, f) in s.iter().enumerate() {
        for k in 0..3 {
            let (a, b, c) = (f[k], f[(k + 1) % 3], f[(k + 2) % 3]);
            let p = |v: u32| &pts[v as usize];
            // Angle from face i towards its white side (orient3d(a,b,c,w) < 0).
            let half = |w: u32| {
                if orient3d(p(a), p(b), p(c), p(w)) < 0.0 {
                    0
                } else {
                    2
                }
            };
            let mut best: Option<(usize, u32)> = None;
            for &(j, w) in &by_edge[&(a.min(b), a.max(b))] {
                if j == i {
                    continue;
                }
                best = match best {
                    None => Some((j, w)),
                    Some((g, x)) => {
                        let (hw, hx) = (half(w), half(x));
                        let before = if hw != hx {
                            hw < hx
                        } else {
                            orient3d(p(a), p(b), p(w), p(x)) < 0.0
                        };
                        if before {
                            Some((j, w))
                        } else {
                            Some((g, x))
                        }
                    }
                };
            }
            let (j, _) = best.expect("open surface");
            // The partner runs along b→a.
            let g = s[j];
            assert!(
                (0..3).any(|m| g[m] == b && g[(m + 1) % 3] == a),
                "partner misoriented"
            );
            let (x, y) = (find(&mut parent, i), find(&mut parent, j));
            parent[x] = y;
        }
    }
    let mut surfaces: HashMap<usize, Vec<[u32; 3]>> = HashMap::new();
    for (i, &f) in s.iter().enumerate() {
        let r = find(&mut parent, i);
        surfaces.entry(r).or_default().push(f);
    }
    let surfaces: Vec<Vec<[u32; 3]>> = surfaces.into_values().collect();
    let mut rng = ChaCha8Rng::seed_from_u64(77);
    let mut out = BTreeSet::new();
    for (i, x) in surfaces.iter().enumerate() {
        let f = x[0];
        let q = Point3::from(
            (pts[f[0] as usize].coords + pts[f[1] as usize].coords + pts[f[2] as usize].coords)
                / 3.0,
        );
        let enc = surfaces
            .iter()
            .enumerate()
            .any(|(j, y)| i != j && point_in_surface(&q, y, pts, &mut rng));
        if !enc {
            out.extend(x.iter().map(|&f| norm_face(f)));
        }
    }
    out
}

fn check_3d(tets: &[[u32; 4]], pts: &[Point3], black: &[bool]) -> morpho::contour::Surface3 {
    let s = external_surface(tets, pts, black).unwrap();
    let got: BTreeSet<[u32; 3]> = s.triangles.iter().map(|&f| norm_face(f)).collect();
    assert_eq!(got.len(), s.triangles.len());
    assert_eq!(
        got,
        oracle_surface(tets, pts, black),
        "external surface differs"
    );
    // Each component is a closed oriented surface.
    for c in 0..s.components as u32 {
        let mut bal: HashMap<(u32, u32), i32> = HashMap::new();
        for (f, _) in s
            .triangles
            .iter()
            .zip(&s.component)
            .filter(|(_, &k)| k == c)
        {
            for k in 0..3 {
                let (a, b) = (f[k], f[(k + 1) % 3]);
                *bal.entry((a.min(b), a.max(b))).or_default() += if a < b { 1 } else { -1 };
            }
        }
        assert!(bal.values().all(|&v| v == 0), "component {c} not closed");
    }
    s
}

#[test]
fn surface_3d_matches_oracle() {
    for seed in 0..6u64 {
        let (pts, tets) = cube_lattice(3, 0.12, seed);
        let p = [0.3, 0.5, 0.7][seed as usize % 3];
        let black = random_colours(tets.len(), p, 50 + seed);
        check_3d(&tets, &pts, &black);
    }
}

#[test]
fn surface_3d_special_cases() {
    let (pts, tets) = cube_lattice(4, 0.1, 1);
    let cent = |t: &[u32; 4]| {
        Point3::from(
            t.iter()
                .map(|&v| pts[v as usize].coords)
                .sum::<nalgebra::Vector3<f64>>()
                / 4.0,
        )
    };
    // All white: nothing. All black: the hull (4·4·6 squares → 2 triangles each).
    let s = check_3d(&tets, &pts, &vec![false; tets.len()]);
    assert!(s.triangles.is_empty());
    let s = check_3d(&tets, &pts, &vec![true; tets.len()]);
    assert_eq!(s.triangles.len(), 6 * 16 * 2);
    assert_eq!(s.components, 1);
    let m = s.to_trimesh(&pts);
    assert!(m.signed_volume() > 0.0);
    // Nested shells: black shell, white gap, black core → only the shell's outside surface.
    let black: Vec<bool> = tets
        .iter()
        .map(|t| {
            let c = cent(t);
            let d = (c.x - 2.0)
                .abs()
                .max((c.y - 2.0).abs())
                .max((c.z - 2.0).abs());
            d < 0.5 || (1.0..1.8).contains(&d)
        })
        .collect();
    let s = check_3d(&tets, &pts, &black);
    assert_eq!(s.components, 1);
    assert!(s.to_trimesh(&pts).signed_volume() > 0.0);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]
    #[test]
    fn prop_random_colourings_3d(n in 1usize..4, seed in 0u64..1000, p in 0.0f64..1.0) {
        let (pts, tets) = cube_lattice(n, 0.12, seed);
        let black = random_colours(tets.len(), p, seed ^ 0x5eed);
        check_3d(&tets, &pts, &black);
    }
}

// ---------------------------------------------------------------- real data and larger sets

fn delaunay_of(pts: &[Point2]) -> Vec<[u32; 3]> {
    let dp: Vec<delaunator::Point> = pts
        .iter()
        .map(|p| delaunator::Point { x: p.x, y: p.y })
        .collect();
    let t = delaunator::triangulate(&dp);
    t.triangles
        .chunks_exact(3)
        .map(|c| [c[0] as u32, c[1] as u32, c[2] as u32])
        .collect()
}

/// Reads columns `cx`, `cy`, `cv` of a CSV file with a header (plain comma-separated numbers).
fn read_csv(path: &std::path::Path, cx: &str, cy: &str, cv: &str) -> (Vec<Point2>, Vec<f64>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let head: Vec<&str> = lines
        .next()
        .unwrap()
        .split(',')
        .map(|s| s.trim_matches('"'))
        .collect();
    let col = |n: &str| head.iter().position(|h| *h == n).unwrap();
    let (ix, iy, iv) = (col(cx), col(cy), col(cv));
    let mut pts = Vec::new();
    let mut vals = Vec::new();
    for l in lines.filter(|l| !l.trim().is_empty()) {
        let f: Vec<&str> = l.split(',').collect();
        pts.push(Point2::new(f[ix].parse().unwrap(), f[iy].parse().unwrap()));
        vals.push(f[iv].parse().unwrap());
    }
    (pts, vals)
}

#[test]
fn real_samples_meuse_zinc_and_jura_cadmium() {
    let Some(dir) = common::data("geostat") else {
        return;
    };
    for (file, cx, cy, cv, thr) in [
        ("meuse.csv", "x", "y", "zinc", 500.0),
        ("jura_pred.csv", "Xloc", "Yloc", "Cd", 0.8),
        ("jura_val.csv", "Xloc", "Yloc", "Cd", 0.8),
    ] {
        let (pts, vals) = read_csv(&dir.join(file), cx, cy, cv);
        let tri = delaunay_of(&pts);
        for rating in [Rating::Mean, Rating::Max, Rating::AreaMean] {
            let r = rate_triangles(&tri, &pts, &vals, rating).unwrap();
            for below in [false, true] {
                let black = classify(&r, thr, below);
                let (ext, _) = check_all(&tri, &pts, &black);
                assert!(ext.black == 0 || !ext.cycles.is_empty(), "{file}");
            }
        }
    }
}

#[test]
fn larger_random_delaunay_match_oracle() {
    let mut rng = ChaCha8Rng::seed_from_u64(2024);
    let pts: Vec<Point2> = (0..600)
        .map(|_| Point2::new(rng.gen_range(0.0..100.0), rng.gen_range(0.0..100.0)))
        .collect();
    let tri = delaunay_of(&pts);
    for (k, p) in [0.45, 0.6].iter().enumerate() {
        let black = random_colours(tri.len(), *p, 99 + k as u64);
        check_all(&tri, &pts, &black);
    }
}

/// 3D Delaunay by brute force: every positively oriented 4-subset whose circumsphere is empty.
fn brute_delaunay_3d(n: usize, seed: u64) -> (Vec<Point3>, Vec<[u32; 4]>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let pts: Vec<Point3> = (0..n)
        .map(|_| Point3::new(rng.gen(), rng.gen(), rng.gen()))
        .collect();
    let mut tets = Vec::new();
    for a in 0..n {
        for b in a + 1..n {
            for c in b + 1..n {
                for d in c + 1..n {
                    let o = orient3d(&pts[a], &pts[b], &pts[c], &pts[d]);
                    if o == 0.0 {
                        continue;
                    }
                    let (c2, d2) = if o > 0.0 { (c, d) } else { (d, c) };
                    let empty = (0..n).all(|e| {
                        [a, b, c, d].contains(&e)
                            || morpho::geom::insphere(&pts[a], &pts[b], &pts[c2], &pts[d2], &pts[e])
                                < 0.0
                    });
                    if empty {
                        tets.push([a as u32, b as u32, c2 as u32, d2 as u32]);
                    }
                }
            }
        }
    }
    (pts, tets)
}

/// Volume of the convex hull by brute force (facets with all other points strictly on one side).
fn hull_volume(pts: &[Point3]) -> f64 {
    let n = pts.len();
    let mut vol = 0.0;
    for a in 0..n {
        for b in a + 1..n {
            for c in b + 1..n {
                let sides: Vec<f64> = (0..n)
                    .filter(|&k| k != a && k != b && k != c)
                    .map(|k| orient3d(&pts[a], &pts[b], &pts[c], &pts[k]))
                    .collect();
                let (pa, pb, pc) = (pts[a].coords, pts[b].coords, pts[c].coords);
                let v = pa.dot(&pb.cross(&pc)) / 6.0;
                // orient3d > 0 for all others: others below (a, b, c) seen counter-clockwise,
                // so (a, b, c) is outward.
                if sides.iter().all(|&s| s > 0.0) {
                    vol += v;
                } else if sides.iter().all(|&s| s < 0.0) {
                    vol -= v;
                }
            }
        }
    }
    vol
}

#[test]
fn random_delaunay_3d_match_oracle() {
    for seed in 0..4u64 {
        let (pts, tets) = brute_delaunay_3d(22, seed);
        let tet_vol: f64 = tets
            .iter()
            .map(|t| {
                let [a, b, c, d] = t.map(|v| pts[v as usize].coords);
                (b - a).cross(&(c - a)).dot(&(d - a)).abs() / 6.0
            })
            .sum();
        assert!(
            (tet_vol - hull_volume(&pts)).abs() < 1e-9,
            "brute-force tetrahedrization incomplete"
        );
        for (k, p) in [0.35, 0.6, 0.85].iter().enumerate() {
            let black = random_colours(tets.len(), *p, seed * 3 + k as u64);
            check_3d(&tets, &pts, &black);
        }
        // All black: the convex hull.
        let s = check_3d(&tets, &pts, &vec![true; tets.len()]);
        assert!((s.to_trimesh(&pts).signed_volume() - hull_volume(&pts)).abs() < 1e-9);
    }
}

#[test]
fn pipeline_and_geojson_on_meuse() {
    use morpho::contour::{
        contour_triangulated_2d, select_samples, SampleOptions, SampleTriangulation2,
    };
    use morpho::io::geojson::contour_value as geojson_value;
    use morpho::mesh::{Column, PointSet};
    let Some(file) = common::data("geostat/meuse.csv") else {
        return;
    };
    let (pts, zinc) = read_csv(&file, "x", "y", "zinc");
    // Add a duplicate of sample 0 with another value and a sample without a value.
    let mut all = pts.clone();
    all.push(pts[0]);
    all.push(Point2::new(0.0, 0.0));
    let mut vals = zinc.clone();
    vals.push(zinc[0] + 100.0);
    vals.push(f64::NAN);
    let mut ps = PointSet::from_points2(&all);
    ps.columns.push(Column {
        name: "zinc".into(),
        values: vals,
    });
    let sel = select_samples(&ps, Some("zinc")).unwrap();
    assert_eq!(sel.skipped, 1);
    // The triangulation of the distinct positions; the duplicate maps to vertex 0.
    let tri = delaunay_of(&pts);
    let mut voi: Vec<u32> = (0..pts.len() as u32).collect();
    voi.push(0);
    let ioi: Vec<u32> = (0..pts.len() as u32).collect();
    for holes in [false, true] {
        let opts = SampleOptions {
            value: Some("zinc".into()),
            threshold: 500.0,
            holes,
            ..Default::default()
        };
        let t = SampleTriangulation2 {
            points: &pts,
            vertex_of_input: &voi,
            input_of_vertex: &ioi,
            triangles: &tri,
            neighbors: None,
        };
        let r = contour_triangulated_2d(sel.clone(), t, &opts).unwrap();
        assert_eq!(r.values[0], zinc[0] + 50.0);
        let mut vals = zinc.clone();
        vals[0] += 50.0;
        let black = classify(
            &rate_triangles(&tri, &pts, &vals, Rating::Mean).unwrap(),
            500.0,
            false,
        );
        assert_eq!(r.black, black);
        let want = if holes {
            boundary_regions(&tri, None, &pts, &black, &ContourOptions::default()).unwrap()
        } else {
            external_contour(&tri, &pts, &black).unwrap()
        };
        assert_eq!(r.contour, want);
        // GeoJSON: closed rings, outer counter-clockwise, holes clockwise.
        let g = geojson_value(&r, 500.0, false);
        let feats = g["features"].as_array().unwrap();
        assert_eq!(feats.len(), r.contour.regions.len());
        for f in feats {
            assert_eq!(f["properties"]["threshold"], 500.0);
            for (k, ring) in f["geometry"]["coordinates"]
                .as_array()
                .unwrap()
                .iter()
                .enumerate()
            {
                let ring: Vec<(f64, f64)> = ring
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|p| (p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
                    .collect();
                assert_eq!(ring.first(), ring.last());
                let a: f64 = ring
                    .windows(2)
                    .map(|w| w[0].0 * w[1].1 - w[1].0 * w[0].1)
                    .sum();
                assert_eq!(a > 0.0, k == 0, "ring orientation");
            }
        }
    }
}

/// `contour_samples` trusts the Delaunay triangulation it makes (no re-validation, no copies):
/// its result must equal the checked path — the same triangulation handed to
/// `contour_triangulated_2d/3d`, with and without its neighbour array — on inputs with
/// duplicates, skipped samples, cocircular / cospherical grids and both colourings.
#[test]
fn trusted_delaunay_path_equals_the_checked_path() {
    use morpho::contour::{
        contour_samples, contour_triangulated_2d, contour_triangulated_3d, select_samples,
        SampleContour, SampleOptions, SampleTriangulation2, SampleTriangulation3,
    };
    use morpho::delaunay::{triangulate_2d, triangulate_3d};
    use morpho::mesh::{Column, PointSet};
    let mut rng = ChaCha8Rng::seed_from_u64(23);
    let mut cases_2d: Vec<Vec<Point2>> = Vec::new();
    // uniform, with exact duplicates
    let mut p: Vec<Point2> = (0..3000)
        .map(|_| Point2::new(rng.gen(), rng.gen()))
        .collect();
    for k in 0..200 {
        p.push(p[k * 7]);
    }
    cases_2d.push(p);
    // integer grid (every cell cocircular)
    cases_2d.push(
        (0..40 * 40)
            .map(|k| Point2::new((k % 40) as f64, (k / 40) as f64))
            .collect(),
    );
    for (c, pts) in cases_2d.iter().enumerate() {
        let mut ps = PointSet::from_points2(pts);
        let values: Vec<f64> = pts
            .iter()
            .enumerate()
            .map(|(i, q)| {
                if i % 97 == 5 {
                    f64::NAN // skipped
                } else if i % 101 == 7 {
                    -0.0 // the vertex value keeps its sign bit on both paths
                } else {
                    (q.x * 0.37).sin() + (q.y * 0.23).cos() + (i % 3) as f64 * 0.1
                }
            })
            .collect();
        ps.columns.push(Column {
            name: "value".into(),
            values,
        });
        for (holes, below) in [(false, false), (true, false), (false, true), (true, true)] {
            let opts = SampleOptions {
                threshold: 1.0,
                holes,
                below,
                ..Default::default()
            };
            let SampleContour::Plane(fast) = contour_samples(&ps, &opts).unwrap() else {
                panic!("2D samples")
            };
            let sel = select_samples(&ps, None).unwrap();
            let kept: Vec<Point2> = sel.input.iter().map(|&i| pts[i as usize]).collect();
            let d = triangulate_2d(&kept).unwrap();
            for nb in [Some(&d.neighbors[..]), None] {
                let t = SampleTriangulation2 {
                    points: &d.points,
                    vertex_of_input: &d.vertex_of_input,
                    input_of_vertex: &d.input_of_vertex,
                    triangles: &d.triangles,
                    neighbors: nb,
                };
                let slow = contour_triangulated_2d(sel.clone(), t, &opts).unwrap();
                assert_eq!(fast, slow, "case {c}, holes {holes}, below {below}");
                // bit for bit, −0 included
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&fast.values), bits(&slow.values));
                assert_eq!(bits(&fast.ratings), bits(&slow.ratings));
            }
            assert!(
                !fast.contour.cycles.is_empty(),
                "case {c}: nothing to compare"
            );
        }
    }
    // 3D: uniform with duplicates, and an integer grid (cospherical cubes)
    let mut p3: Vec<Point3> = (0..1500)
        .map(|_| Point3::new(rng.gen(), rng.gen(), rng.gen()))
        .collect();
    for k in 0..100 {
        p3.push(p3[k * 5]);
    }
    let g3: Vec<Point3> = (0..8 * 8 * 8)
        .map(|k| Point3::new((k % 8) as f64, ((k / 8) % 8) as f64, (k / 64) as f64))
        .collect();
    for (c, pts) in [p3, g3].iter().enumerate() {
        let mut ps = PointSet::from_points3(pts);
        ps.columns.push(Column {
            name: "value".into(),
            values: pts
                .iter()
                .enumerate()
                .map(|(i, q)| {
                    if i % 89 == 3 {
                        f64::NAN
                    } else {
                        (q.x * 0.9).sin() + (q.y * 0.7).cos() * (q.z * 0.5).sin()
                    }
                })
                .collect(),
        });
        let opts = SampleOptions {
            threshold: 0.5,
            ..Default::default()
        };
        let SampleContour::Space(fast) = contour_samples(&ps, &opts).unwrap() else {
            panic!("3D samples")
        };
        let sel = select_samples(&ps, None).unwrap();
        let kept: Vec<Point3> = sel.input.iter().map(|&i| pts[i as usize]).collect();
        let d = triangulate_3d(&kept).unwrap();
        for nb in [Some(&d.neighbors[..]), None] {
            let t = SampleTriangulation3 {
                points: &d.points,
                vertex_of_input: &d.vertex_of_input,
                input_of_vertex: &d.input_of_vertex,
                tets: &d.tets,
                neighbors: nb,
            };
            let slow = contour_triangulated_3d(sel.clone(), t, &opts).unwrap();
            assert_eq!(fast, slow, "3D case {c}");
        }
        assert!(
            !fast.surface.triangles.is_empty(),
            "3D case {c}: nothing to compare"
        );
    }
}
