//! Validity of a 3D boundary (Veltkamp 1992, §4.2 "Boundary construction 3D": a simple closed
//! polyhedron through all vertices): no two triangles may meet except in their shared
//! vertices/edge.
//!
//! [`self_intersections`] tests, with exact `orient3d`/`orient2d` only, every pair of triangles
//! whose bounding boxes share a cell of a uniform grid:
//! - pairs with no common vertex: full closed triangle–triangle test (non-coplanar: some edge of
//!   one meets the other closed triangle — the intersection of two triangles in different planes
//!   is a segment whose ends lie on edges; coplanar: 2D test in an exact non-degenerate axis
//!   projection);
//! - pairs with one common vertex v: the edge opposite v of each must not meet the other
//!   triangle, and for coplanar pairs the projected triangles must not overlap beyond v;
//! - pairs with a common edge ab (triangles abc, abd): they meet beyond the edge iff they are
//!   coplanar (`orient3d(a, b, c, d) == 0`) and c, d lie on the same side of line ab in that
//!   plane (exact `orient2d` in a non-degenerate axis projection) — a fold onto itself — or one
//!   of them is degenerate (c or d on line ab);
//! - the same triangle twice (three common vertices) always counts as an intersection.
//!
//! Expected O(n) for meshes of evenly sized triangles, O(n²) worst case.

use super::validity::segments_intersect;
use crate::geom::predicates::raw::{orient2d, orient3d};

type P = [f64; 3];

fn proj(p: P, axis: usize) -> [f64; 2] {
    match axis {
        0 => [p[1], p[2]],
        1 => [p[2], p[0]],
        _ => [p[0], p[1]],
    }
}

/// An axis whose projection keeps triangle abc non-degenerate (exact), if any.
fn good_axis(a: P, b: P, c: P) -> Option<usize> {
    (0..3).find(|&ax| orient2d(proj(a, ax), proj(b, ax), proj(c, ax)) != 0.0)
}

/// Triangle abc is degenerate (its corners are collinear; exact).
pub fn degenerate(a: P, b: P, c: P) -> bool {
    good_axis(a, b, c).is_none()
}

fn point_in_tri2(p: [f64; 2], a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> bool {
    let o = orient2d(a, b, c);
    let s = |u, v| orient2d(u, v, p) * o;
    s(a, b) >= 0.0 && s(b, c) >= 0.0 && s(c, a) >= 0.0
}

fn tri_tri_2d(t: [[f64; 2]; 3], u: [[f64; 2]; 3]) -> bool {
    for i in 0..3 {
        for j in 0..3 {
            if segments_intersect(t[i], t[(i + 1) % 3], u[j], u[(j + 1) % 3]) {
                return true;
            }
        }
    }
    point_in_tri2(t[0], u[0], u[1], u[2]) || point_in_tri2(u[0], t[0], t[1], t[2])
}

/// Closed segment pq meets closed triangle abc (exact; abc non-degenerate).
pub fn segment_meets_triangle(p: P, q: P, a: P, b: P, c: P) -> bool {
    let sp = orient3d(a, b, c, p);
    let sq = orient3d(a, b, c, q);
    if (sp > 0.0 && sq > 0.0) || (sp < 0.0 && sq < 0.0) {
        return false;
    }
    if sp == 0.0 && sq == 0.0 {
        let Some(ax) = good_axis(a, b, c) else {
            return false;
        };
        let (a2, b2, c2) = (proj(a, ax), proj(b, ax), proj(c, ax));
        let (p2, q2) = (proj(p, ax), proj(q, ax));
        return point_in_tri2(p2, a2, b2, c2)
            || segments_intersect(p2, q2, a2, b2)
            || segments_intersect(p2, q2, b2, c2)
            || segments_intersect(p2, q2, c2, a2);
    }
    let s1 = orient3d(p, q, a, b);
    let s2 = orient3d(p, q, b, c);
    let s3 = orient3d(p, q, c, a);
    (s1 >= 0.0 && s2 >= 0.0 && s3 >= 0.0) || (s1 <= 0.0 && s2 <= 0.0 && s3 <= 0.0)
}

/// Closed triangles t and u (no common vertex) intersect (exact).
pub fn triangles_intersect(t: [P; 3], u: [P; 3]) -> bool {
    let su: [f64; 3] = u.map(|x| orient3d(t[0], t[1], t[2], x));
    if su.iter().all(|&s| s > 0.0) || su.iter().all(|&s| s < 0.0) {
        return false;
    }
    let st: [f64; 3] = t.map(|x| orient3d(u[0], u[1], u[2], x));
    if st.iter().all(|&s| s > 0.0) || st.iter().all(|&s| s < 0.0) {
        return false;
    }
    if su.iter().all(|&s| s == 0.0) {
        let Some(ax) = good_axis(t[0], t[1], t[2]) else {
            return false;
        };
        return tri_tri_2d(t.map(|x| proj(x, ax)), u.map(|x| proj(x, ax)));
    }
    (0..3).any(|i| segment_meets_triangle(t[i], t[(i + 1) % 3], u[0], u[1], u[2]))
        || (0..3).any(|i| segment_meets_triangle(u[i], u[(i + 1) % 3], t[0], t[1], t[2]))
}

/// Triangles t, u sharing exactly the vertex at positions (it, iu) meet elsewhere (exact).
pub fn meet_beyond_vertex(t: [P; 3], it: usize, u: [P; 3], iu: usize) -> bool {
    let (t1, t2) = (t[(it + 1) % 3], t[(it + 2) % 3]);
    let (u1, u2) = (u[(iu + 1) % 3], u[(iu + 2) % 3]);
    if segment_meets_triangle(t1, t2, u[0], u[1], u[2])
        || segment_meets_triangle(u1, u2, t[0], t[1], t[2])
    {
        return true;
    }
    let coplanar = orient3d(t[0], t[1], t[2], u1) == 0.0 && orient3d(t[0], t[1], t[2], u2) == 0.0;
    if !coplanar {
        return false;
    }
    // coplanar wedges at the shared vertex v: they overlap beyond v iff an edge from v of one
    // lies inside the other's wedge, or the wedges coincide along an edge direction
    let Some(ax) = good_axis(t[0], t[1], t[2]) else {
        return false;
    };
    let v = proj(t[it], ax);
    let (a, b) = (proj(t1, ax), proj(t2, ax));
    let (c, d) = (proj(u1, ax), proj(u2, ax));
    let inside = |x: [f64; 2], p: [f64; 2], q: [f64; 2]| -> bool {
        // x strictly inside wedge (p, q) at v, or along one of its rays
        let o = orient2d(v, p, q);
        let s1 = orient2d(v, p, x) * o;
        let s2 = orient2d(v, x, q) * o;
        let along = |r: [f64; 2]| {
            orient2d(v, r, x) == 0.0
                && ((r[0] - v[0]) * (x[0] - v[0]) + (r[1] - v[1]) * (x[1] - v[1])) > 0.0
        };
        (s1 > 0.0 && s2 > 0.0) || along(p) || along(q)
    };
    // (a wedge containing the other has the other's edges inside it)
    inside(c, a, b) || inside(d, a, b) || inside(a, c, d) || inside(b, c, d)
}

/// Triangles abc and abd (common edge ab, positions given) meet beyond the edge (exact; see
/// the module documentation).
pub fn meet_beyond_edge(a: P, b: P, c: P, d: P) -> bool {
    if orient3d(a, b, c, d) != 0.0 {
        return false;
    }
    // coplanar: project along an axis that keeps one of the two triangles non-degenerate
    let Some(ax) = good_axis(a, b, c).or_else(|| good_axis(a, b, d)) else {
        return true; // both degenerate (a, b, c, d collinear)
    };
    let (a2, b2) = (proj(a, ax), proj(b, ax));
    let sc = orient2d(a2, b2, proj(c, ax));
    let sd = orient2d(a2, b2, proj(d, ax));
    // in the plane, the projection preserves sidedness of ab (the plane is not parallel to ax)
    sc == 0.0 || sd == 0.0 || (sc > 0.0) == (sd > 0.0)
}

/// Pairs of triangles (indices into `tris`) that intersect although they must not (see the
/// module documentation); at most `limit` are returned.
pub fn self_intersections(pos: &[P], tris: &[[u32; 3]], limit: usize) -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    if tris.is_empty() {
        return out;
    }
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    let mut lens = Vec::with_capacity(3 * tris.len());
    for t in tris {
        let q = t.map(|v| pos[v as usize]);
        for k in 0..3 {
            for x in &q {
                lo[k] = lo[k].min(x[k]);
                hi[k] = hi[k].max(x[k]);
            }
        }
        for k in 0..3 {
            let (a, b) = (q[k], q[(k + 1) % 3]);
            lens.push(
                ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt(),
            );
        }
    }
    // cell: twice the median edge length (the mean is dominated by a few long edges)
    let mid = lens.len() / 2;
    let mut cell = 2.0 * *lens.select_nth_unstable_by(mid, f64::total_cmp).1;
    let ext = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
    while cell > 0.0
        && ext.iter().map(|e| (e / cell) as u64 + 1).product::<u64>() > 8 * tris.len() as u64 + 64
    {
        cell *= 1.5;
    }
    if !(cell > 0.0 && cell.is_finite()) {
        cell = 1.0;
    }
    let cidx = |x: f64, k: usize| ((x - lo[k]) / cell).floor().max(0.0) as u64;
    let mut grid: super::constrict3::IdMap<(u64, u64, u64), Vec<u32>> = Default::default();
    let bbox = |t: &[u32; 3]| -> ([f64; 3], [f64; 3]) {
        let q = t.map(|v| pos[v as usize]);
        (
            std::array::from_fn(|k| q[0][k].min(q[1][k]).min(q[2][k])),
            std::array::from_fn(|k| q[0][k].max(q[1][k]).max(q[2][k])),
        )
    };
    // triangles spanning many cells are tested against everything by bounding boxes instead
    let mut big: Vec<u32> = Vec::new();
    for (i, t) in tris.iter().enumerate() {
        let (bl, bh) = bbox(t);
        let mn: [u64; 3] = std::array::from_fn(|k| cidx(bl[k], k));
        let mx: [u64; 3] = std::array::from_fn(|k| cidx(bh[k], k));
        let span: u64 = (0..3).map(|k| mx[k] - mn[k] + 1).product();
        if span > 512 {
            big.push(i as u32);
            continue;
        }
        for x in mn[0]..=mx[0] {
            for y in mn[1]..=mx[1] {
                for z in mn[2]..=mx[2] {
                    grid.entry((x, y, z)).or_default().push(i as u32);
                }
            }
        }
    }
    let boxes: Vec<([f64; 3], [f64; 3])> = tris.iter().map(bbox).collect();
    let overlap = |a: u32, b: u32| {
        let ((al, ah), (bl, bh)) = (boxes[a as usize], boxes[b as usize]);
        (0..3).all(|k| al[k] <= bh[k] && bl[k] <= ah[k])
    };
    let bad = |a: u32, b: u32| pair_meets(pos, tris[a as usize], tris[b as usize]);
    let mut pairs: Vec<(u32, u32)> = Vec::new();
    let mut bad_pairs: Vec<(u32, u32)> = Vec::new();
    for (&cell, ids) in &grid {
        for (a_i, &a) in ids.iter().enumerate() {
            for &b in &ids[a_i + 1..] {
                if !overlap(a, b) {
                    continue;
                }
                // each pair once: in the cell of the low corner of the boxes' intersection
                let ((al, _), (bl, _)) = (boxes[a as usize], boxes[b as usize]);
                let own = (
                    cidx(al[0].max(bl[0]), 0),
                    cidx(al[1].max(bl[1]), 1),
                    cidx(al[2].max(bl[2]), 2),
                );
                if own == cell && bad(a, b) {
                    bad_pairs.push((a.min(b), a.max(b)));
                }
            }
        }
    }
    // big triangles: against each other by boxes, against the grid through the cells their
    // plane passes (floating-point culling with a generous margin; the exact test decides)
    for (i, &a) in big.iter().enumerate() {
        for &b in &big[i + 1..] {
            if overlap(a, b) {
                pairs.push((a.min(b), a.max(b)));
            }
        }
    }
    for &a in &big {
        let q = tris[a as usize].map(|v| pos[v as usize]);
        let e1 = [q[1][0] - q[0][0], q[1][1] - q[0][1], q[1][2] - q[0][2]];
        let e2 = [q[2][0] - q[0][0], q[2][1] - q[0][1], q[2][2] - q[0][2]];
        let n = [
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0],
        ];
        // dominant axis w: the plane is a function of the two other coordinates
        let w = (0..3)
            .max_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
            .unwrap_or(2);
        let (u, v) = ((w + 1) % 3, (w + 2) % 3);
        let (bl, bh) = boxes[a as usize];
        let mn: [u64; 3] = std::array::from_fn(|k| cidx(bl[k], k));
        let mx: [u64; 3] = std::array::from_fn(|k| cidx(bh[k], k));
        let nw = n[w];
        let slope = if nw != 0.0 {
            (n[u].abs() + n[v].abs()) / nw.abs()
        } else {
            f64::INFINITY
        };
        let margin = 1e-9 * (0..3).map(|k| ext[k].abs()).sum::<f64>() + cell * 1e-6;
        let mut cand: Vec<u32> = Vec::new();
        for cu in mn[u]..=mx[u] {
            for cv in mn[v]..=mx[v] {
                // w-range of the plane over this column (cell centre ± half extent · slope)
                let (wlo, whi) = if slope.is_finite() {
                    let xu = lo[u] + (cu as f64 + 0.5) * cell;
                    let xv = lo[v] + (cv as f64 + 0.5) * cell;
                    let wc = q[0][w] - (n[u] * (xu - q[0][u]) + n[v] * (xv - q[0][v])) / nw;
                    let half = 0.5 * cell * slope + margin;
                    (
                        cidx((wc - half).max(bl[w]), w).max(mn[w]),
                        cidx((wc + half).min(bh[w]), w).min(mx[w]),
                    )
                } else {
                    (mn[w], mx[w])
                };
                for cw in wlo..=whi {
                    let mut key = [0u64; 3];
                    key[u] = cu;
                    key[v] = cv;
                    key[w] = cw;
                    if let Some(ids) = grid.get(&(key[0], key[1], key[2])) {
                        cand.extend(ids.iter().copied().filter(|&b| overlap(a, b)));
                    }
                }
            }
        }
        cand.sort_unstable();
        cand.dedup();
        pairs.extend(cand.into_iter().map(|b| (a.min(b), a.max(b))));
    }
    pairs.sort_unstable();
    pairs.dedup();
    for (a, b) in pairs {
        if bad(a, b) {
            bad_pairs.push((a, b));
        }
    }
    bad_pairs.sort_unstable();
    bad_pairs.dedup();
    bad_pairs.truncate(limit);
    out.extend(bad_pairs);
    out
}

/// The exact test of one pair by its number of common vertices (see the module documentation).
fn pair_meets(pos: &[P], ta: [u32; 3], tb: [u32; 3]) -> bool {
    let mut shared = [(0usize, 0usize); 3];
    let mut ns = 0;
    for i in 0..3 {
        for j in 0..3 {
            if ta[i] == tb[j] && ns < 3 {
                shared[ns] = (i, j);
                ns += 1;
            }
        }
    }
    let (pa, pb) = (ta.map(|v| pos[v as usize]), tb.map(|v| pos[v as usize]));
    match ns {
        0 => triangles_intersect(pa, pb),
        1 => meet_beyond_vertex(pa, shared[0].0, pb, shared[0].1),
        2 => {
            let (i0, i1) = (shared[0].0, shared[1].0);
            let (j0, j1) = (shared[0].1, shared[1].1);
            let (c, d) = (3 - i0 - i1, 3 - j0 - j1);
            meet_beyond_edge(pa[i0], pa[i1], pa[c], pb[d])
        }
        _ => true,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossing_and_separate_triangles() {
        let t = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]];
        let piercing = [[0.5, 0.5, -1.0], [0.5, 0.5, 1.0], [3.0, 3.0, 0.5]];
        assert!(triangles_intersect(t, piercing));
        let above = [[0.5, 0.5, 0.1], [0.5, 0.6, 1.0], [3.0, 3.0, 0.5]];
        assert!(!triangles_intersect(t, above));
        // coplanar overlap and coplanar disjoint
        let co = [[1.0, 1.0, 0.0], [3.0, 1.0, 0.0], [1.0, 3.0, 0.0]];
        assert!(triangles_intersect(t, co));
        let co2 = [[1.5, 1.5, 0.0], [3.0, 1.5, 0.0], [1.5, 3.0, 0.0]];
        assert!(!triangles_intersect(t, co2));
        // touching at a point of an edge
        let touch = [[1.0, 1.0, 0.0], [1.0, 1.0, 1.0], [2.0, 2.0, 1.0]];
        assert!(triangles_intersect(t, touch));
    }

    #[test]
    fn closed_tetrahedron_surface_is_clean_and_a_pierced_one_is_not() {
        let pos = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        let tris = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];
        assert!(self_intersections(&pos, &tris, 10).is_empty());
        let mut pos2 = pos.to_vec();
        pos2.extend([[0.2, 0.2, -0.5], [0.2, 0.2, 0.5], [0.3, 0.25, 2.0]]);
        let mut tris2 = tris.to_vec();
        tris2.push([4, 5, 6]);
        assert!(!self_intersections(&pos2, &tris2, 10).is_empty());
        // shared vertex, coplanar overlapping wedges
        let pos3 = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 2.0, 0.0],
            [2.0, 1.0, 0.0],
            [1.0, 2.0, 0.0],
        ];
        assert!(!self_intersections(&pos3, &[[0, 1, 2], [0, 3, 4]], 10).is_empty());
    }

    /// Brute-force oracle for triangles abc, abd with a common edge on integer points: they
    /// meet beyond ab iff abd is degenerate or the point m + (c − m)/K (m the midpoint of ab,
    /// K large) lies in the closed triangle abd — near m, abc and abd are half-discs (i128
    /// arithmetic, no predicates).
    fn fold_oracle(a: [i64; 3], b: [i64; 3], c: [i64; 3], d: [i64; 3]) -> bool {
        let k: i128 = 1_000_000;
        let s = |x: [i64; 3]| x.map(|v| 2 * k * v as i128);
        let (aa, bb, dd) = (s(a), s(b), s(d));
        let p: [i128; 3] =
            std::array::from_fn(|i| (k - 1) * (a[i] as i128 + b[i] as i128) + 2 * c[i] as i128);
        let sub = |x: [i128; 3], y: [i128; 3]| [x[0] - y[0], x[1] - y[1], x[2] - y[2]];
        let cr = |x: [i128; 3], y: [i128; 3]| {
            [
                x[1] * y[2] - x[2] * y[1],
                x[2] * y[0] - x[0] * y[2],
                x[0] * y[1] - x[1] * y[0],
            ]
        };
        let dt = |x: [i128; 3], y: [i128; 3]| x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
        let deg = |x: [i64; 3], y: [i64; 3], z: [i64; 3]| {
            let w = |v: [i64; 3]| v.map(|q| q as i128);
            cr(sub(w(y), w(x)), sub(w(z), w(x))) == [0, 0, 0]
        };
        if deg(a, b, c) || deg(a, b, d) {
            return true;
        }
        let n = cr(sub(bb, aa), sub(dd, aa));
        if dt(n, sub(p, aa)) != 0 {
            return false;
        }
        [(aa, bb), (bb, dd), (dd, aa)]
            .iter()
            .all(|&(u, v)| dt(cr(sub(v, u), sub(p, u)), n) >= 0)
    }

    #[test]
    fn folds_along_a_common_edge() {
        let f = |v: [f64; 3]| v;
        let (a, b) = (f([0.0, 0.0, 0.0]), f([2.0, 0.0, 0.0]));
        // coplanar, same side: a fold onto itself
        assert!(meet_beyond_edge(a, b, [1.0, 1.0, 0.0], [0.5, 3.0, 0.0]));
        // coplanar, opposite sides: a flat pair of neighbours
        assert!(!meet_beyond_edge(a, b, [1.0, 1.0, 0.0], [0.5, -3.0, 0.0]));
        // different planes
        assert!(!meet_beyond_edge(a, b, [1.0, 1.0, 0.0], [1.0, 1.0, 1e-300]));
        // degenerate second triangle
        assert!(meet_beyond_edge(a, b, [1.0, 1.0, 0.0], [5.0, 0.0, 0.0]));
        // through self_intersections: a closed tetrahedron surface plus a folded flap
        let pos = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.3, 0.3, 0.0],
        ];
        let tris = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];
        assert!(self_intersections(&pos, &tris, 10).is_empty());
        let mut t2 = tris.to_vec();
        t2.push([0, 1, 4]); // lies inside face 0 2 1, common edge 0 1
        assert_eq!(self_intersections(&pos, &t2, 10), vec![(0, 4)]);
        // the same triangle twice
        let mut t3 = tris.to_vec();
        t3.push([1, 2, 3]);
        assert_eq!(self_intersections(&pos, &t3, 10), vec![(2, 4)]);
    }

    #[test]
    fn common_edge_test_matches_the_oracle() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(21);
        let (mut hits, mut coplanar) = (0, 0);
        for it in 0..4000 {
            // points of a small integer plane mapped into 3D by an integer matrix, or free
            let m: [[i64; 3]; 3] =
                std::array::from_fn(|_| std::array::from_fn(|_| rng.gen_range(-3..=3)));
            let plane = it % 4 != 0;
            let pt = |rng: &mut rand_chacha::ChaCha8Rng| -> [i64; 3] {
                let (u, v, w) = (
                    rng.gen_range(-4..=4),
                    rng.gen_range(-4..=4),
                    if plane { 0 } else { rng.gen_range(-4..=4) },
                );
                std::array::from_fn(|i| m[i][0] * u + m[i][1] * v + m[i][2] * w)
            };
            let (a, b, c, d) = (pt(&mut rng), pt(&mut rng), pt(&mut rng), pt(&mut rng));
            if a == b {
                continue;
            }
            let fl = |x: [i64; 3]| x.map(|q| q as f64);
            let got = meet_beyond_edge(fl(a), fl(b), fl(c), fl(d));
            assert_eq!(got, fold_oracle(a, b, c, d), "{a:?} {b:?} {c:?} {d:?}");
            hits += got as usize;
            coplanar += (orient3d(fl(a), fl(b), fl(c), fl(d)) == 0.0) as usize;
        }
        assert!(hits > 200 && coplanar > 1000, "{hits} {coplanar}");
    }

    #[test]
    fn big_triangles_are_tested_through_the_cells_of_their_plane() {
        // a fine flat grid mesh on z = 0 and big triangles spanning it
        let m = 60;
        let mut pos: Vec<P> = Vec::new();
        for j in 0..=m {
            for i in 0..=m {
                pos.push([i as f64 / m as f64, j as f64 / m as f64, 0.0]);
            }
        }
        let id = |i: usize, j: usize| (j * (m + 1) + i) as u32;
        let mut tris = Vec::new();
        for j in 0..m {
            for i in 0..m {
                tris.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                tris.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        let n0 = pos.len() as u32;
        // vertical, slanted big triangle piercing the sheet along a segment
        pos.extend([[0.013, 0.021, -1.0], [0.977, 0.963, -1.0], [0.5, 0.4, 1.0]]);
        // a big one parallel above it, and a big one crossing the first
        pos.extend([[0.0, 0.0, 0.5], [1.0, 0.0, 0.5], [0.0, 1.0, 0.5]]);
        let nt = tris.len() as u32;
        tris.push([n0, n0 + 1, n0 + 2]);
        tris.push([n0 + 3, n0 + 4, n0 + 5]);
        let found = self_intersections(&pos, &tris, usize::MAX);
        // brute force over every pair involving the two big triangles
        let mut expect = Vec::new();
        for big in [nt, nt + 1] {
            let pb = tris[big as usize].map(|v| pos[v as usize]);
            for (k, t) in tris.iter().enumerate() {
                let k = k as u32;
                if k == big || (k > nt + 1) || (k == nt && big == nt + 1) {
                    continue;
                }
                if triangles_intersect(t.map(|v| pos[v as usize]), pb) {
                    expect.push((k.min(big), k.max(big)));
                }
            }
        }
        expect.sort_unstable();
        expect.dedup();
        assert!(expect.len() >= 40, "{}", expect.len());
        assert_eq!(found, expect);
    }
}
