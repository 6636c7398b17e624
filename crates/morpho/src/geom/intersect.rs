//! Exact intersection tests between segments and triangles (2D and 3D), built on the exact
//! `orient2d`/`orient3d` of [`super::predicates`] only — the tests behind polygon and mesh
//! validity ([`crate::mesh::validity`]) and the boundary engines.
//!
//! All tests are on *closed* sets unless the name says otherwise ([`segments_cross_properly`]).
//! Degenerate input has a defined answer everywhere: a degenerate triangle (collinear
//! corners, or repeated vertex ids in [`triangles_meet_beyond_shared`]) counts as the segment
//! it covers. In 3D, the tests for triangles that share vertices ([`meet_beyond_vertex`],
//! [`meet_beyond_edge`], [`triangles_meet_beyond_shared`]) decide whether they meet anywhere
//! *else* than in what they share — the condition for a valid triangulated surface.
//!
//! Exact as long as no predicate over- or underflows (coordinates within about 2^±120 of 1;
//! callers rescale by a power of two first).

use super::predicates::raw::{orient2d, orient3d};
use super::vec::{dot, sub};

/// True when the closed segments ab and cd have a point in common (exact; a segment may be a
/// single point, a = b).
///
/// ```
/// use morpho::geom::intersect::segments_intersect;
/// assert!(segments_intersect([0.0, 0.0], [2.0, 2.0], [0.0, 2.0], [2.0, 0.0])); // crossing
/// assert!(segments_intersect([0.0, 0.0], [2.0, 0.0], [1.0, 0.0], [1.0, 5.0])); // touching
/// assert!(!segments_intersect([0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 0.0])); // collinear apart
/// ```
pub fn segments_intersect(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> bool {
    let o1 = orient2d(a, b, c);
    let o2 = orient2d(a, b, d);
    let o3 = orient2d(c, d, a);
    let o4 = orient2d(c, d, b);
    if ((o1 > 0.0 && o2 < 0.0) || (o1 < 0.0 && o2 > 0.0))
        && ((o3 > 0.0 && o4 < 0.0) || (o3 < 0.0 && o4 > 0.0))
    {
        return true;
    }
    (o1 == 0.0 && on_segment(a, b, c))
        || (o2 == 0.0 && on_segment(a, b, d))
        || (o3 == 0.0 && on_segment(c, d, a))
        || (o4 == 0.0 && on_segment(c, d, b))
}

/// True when the open segments ab and cd cross at one point interior to both (exact): a
/// touching, a shared end point or a collinear overlap is not a proper crossing.
///
/// ```
/// use morpho::geom::intersect::segments_cross_properly;
/// assert!(segments_cross_properly([0.0, 0.0], [2.0, 2.0], [0.0, 2.0], [2.0, 0.0]));
/// assert!(!segments_cross_properly([0.0, 0.0], [2.0, 0.0], [1.0, 0.0], [1.0, 5.0]));
/// ```
pub fn segments_cross_properly(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> bool {
    let o1 = orient2d(a, b, c);
    let o2 = orient2d(a, b, d);
    if !((o1 > 0.0 && o2 < 0.0) || (o1 < 0.0 && o2 > 0.0)) {
        return false;
    }
    let o3 = orient2d(c, d, a);
    let o4 = orient2d(c, d, b);
    (o3 > 0.0 && o4 < 0.0) || (o3 < 0.0 && o4 > 0.0)
}

/// For p collinear with ab: p lies on the closed segment ab (exact: coordinate comparisons;
/// the caller establishes collinearity, e.g. `orient2d(a, b, p) == 0`).
pub fn on_segment(a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> bool {
    a[0].min(b[0]) <= p[0]
        && p[0] <= a[0].max(b[0])
        && a[1].min(b[1]) <= p[1]
        && p[1] <= a[1].max(b[1])
}

/// A 3D point.
type P = [f64; 3];

/// The projection of p along `axis` (dropping that coordinate, the other two in cyclic order).
pub(crate) fn proj(p: P, axis: usize) -> [f64; 2] {
    match axis {
        0 => [p[1], p[2]],
        1 => [p[2], p[0]],
        _ => [p[0], p[1]],
    }
}

/// An axis whose projection keeps triangle abc non-degenerate (exact), if any.
pub(crate) fn good_axis(a: P, b: P, c: P) -> Option<usize> {
    (0..3).find(|&ax| orient2d(proj(a, ax), proj(b, ax), proj(c, ax)) != 0.0)
}

/// Triangle abc is degenerate: its corners are collinear (or coincide). Exact.
///
/// ```
/// use morpho::geom::intersect::degenerate_triangle;
/// assert!(degenerate_triangle([0.0; 3], [1.0, 1.0, 1.0], [3.0, 3.0, 3.0]));
/// assert!(!degenerate_triangle([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]));
/// ```
pub fn degenerate_triangle(a: P, b: P, c: P) -> bool {
    good_axis(a, b, c).is_none()
}

/// The 2D point p lies in the closed triangle abc (exact; either orientation). A degenerate
/// triangle is the union of its edges.
///
/// ```
/// use morpho::geom::intersect::point_in_triangle;
/// let (a, b, c) = ([0.0, 0.0], [4.0, 0.0], [0.0, 4.0]);
/// assert!(point_in_triangle([1.0, 1.0], a, b, c));
/// assert!(point_in_triangle([2.0, 2.0], a, c, b)); // on the hypotenuse, clockwise triangle
/// assert!(!point_in_triangle([3.0, 3.0], a, b, c));
/// ```
pub fn point_in_triangle(p: [f64; 2], a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> bool {
    let o = orient2d(a, b, c);
    if o == 0.0 {
        // a degenerate triangle is the union of its edges
        return segments_intersect(a, b, p, p)
            || segments_intersect(b, c, p, p)
            || segments_intersect(c, a, p, p);
    }
    let s = |u, v| orient2d(u, v, p) * o;
    s(a, b) >= 0.0 && s(b, c) >= 0.0 && s(c, a) >= 0.0
}

/// The closed 2D triangles t and u have a point in common (exact; either orientation; a
/// degenerate triangle is the union of its edges).
///
/// ```
/// use morpho::geom::intersect::triangles_intersect_2d;
/// let t = [[0.0, 0.0], [2.0, 0.0], [0.0, 2.0]];
/// assert!(triangles_intersect_2d(t, [[1.0, 1.0], [3.0, 1.0], [1.0, 3.0]])); // touching
/// assert!(!triangles_intersect_2d(t, [[1.5, 1.5], [3.0, 1.5], [1.5, 3.0]]));
/// ```
pub fn triangles_intersect_2d(t: [[f64; 2]; 3], u: [[f64; 2]; 3]) -> bool {
    for i in 0..3 {
        for j in 0..3 {
            if segments_intersect(t[i], t[(i + 1) % 3], u[j], u[(j + 1) % 3]) {
                return true;
            }
        }
    }
    point_in_triangle(t[0], u[0], u[1], u[2]) || point_in_triangle(u[0], t[0], t[1], t[2])
}

/// The closed segment pq meets the closed triangle abc (exact; abc non-degenerate — for a
/// degenerate abc the answer is `false` when p, q lie in its line, use
/// [`segments_intersect`] on its edges then).
///
/// ```
/// use morpho::geom::intersect::segment_meets_triangle;
/// let (a, b, c) = ([0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]);
/// assert!(segment_meets_triangle([0.5, 0.5, -1.0], [0.5, 0.5, 1.0], a, b, c)); // piercing
/// assert!(segment_meets_triangle([0.5, 0.5, 0.0], [0.5, 0.5, 1.0], a, b, c)); // touching
/// assert!(!segment_meets_triangle([3.0, 3.0, -1.0], [3.0, 3.0, 1.0], a, b, c));
/// ```
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
        return point_in_triangle(p2, a2, b2, c2)
            || segments_intersect(p2, q2, a2, b2)
            || segments_intersect(p2, q2, b2, c2)
            || segments_intersect(p2, q2, c2, a2);
    }
    let s1 = orient3d(p, q, a, b);
    let s2 = orient3d(p, q, b, c);
    let s3 = orient3d(p, q, c, a);
    (s1 >= 0.0 && s2 >= 0.0 && s3 >= 0.0) || (s1 <= 0.0 && s2 <= 0.0 && s3 <= 0.0)
}

/// The closed triangles t and u (no common vertex) intersect (exact). A degenerate triangle
/// (collinear corners) counts as the segment it covers when the other one is not degenerate;
/// two degenerate triangles are reported as not intersecting.
///
/// Non-coplanar pairs: the intersection of two triangles in different planes is a segment
/// whose ends lie on edges, so some edge of one meets the other ([`segment_meets_triangle`]);
/// coplanar pairs: the 2D test in an axis projection that keeps t non-degenerate.
///
/// ```
/// use morpho::geom::intersect::triangles_intersect;
/// let t = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]];
/// assert!(triangles_intersect(t, [[0.5, 0.5, -1.0], [0.5, 0.5, 1.0], [3.0, 3.0, 0.5]]));
/// assert!(!triangles_intersect(t, [[0.5, 0.5, 0.1], [0.5, 0.6, 1.0], [3.0, 3.0, 0.5]]));
/// ```
pub fn triangles_intersect(t: [P; 3], u: [P; 3]) -> bool {
    let su: [f64; 3] = u.map(|x| orient3d(t[0], t[1], t[2], x));
    if su.iter().all(|&s| s > 0.0) || su.iter().all(|&s| s < 0.0) {
        return false;
    }
    // (a degenerate t has no plane: every su is 0)
    if su.iter().all(|&s| s == 0.0) && degenerate_triangle(t[0], t[1], t[2]) {
        return !degenerate_triangle(u[0], u[1], u[2]) && triangles_intersect(u, t);
    }
    let st: [f64; 3] = t.map(|x| orient3d(u[0], u[1], u[2], x));
    if st.iter().all(|&s| s > 0.0) || st.iter().all(|&s| s < 0.0) {
        return false;
    }
    if su.iter().all(|&s| s == 0.0) {
        let Some(ax) = good_axis(t[0], t[1], t[2]) else {
            return false;
        };
        return triangles_intersect_2d(t.map(|x| proj(x, ax)), u.map(|x| proj(x, ax)));
    }
    (0..3).any(|i| segment_meets_triangle(t[i], t[(i + 1) % 3], u[0], u[1], u[2]))
        || (0..3).any(|i| segment_meets_triangle(u[i], u[(i + 1) % 3], t[0], t[1], t[2]))
}

/// Triangles t, u sharing exactly the vertex at positions (it, iu) meet elsewhere (exact;
/// symmetric in t and u). A degenerate triangle counts as the segment it covers when the
/// other one is not degenerate; two degenerate triangles are reported as not meeting.
///
/// The edge opposite the shared vertex of each must not meet the other triangle, and coplanar
/// wedges at the vertex must not overlap.
///
/// ```
/// use morpho::geom::intersect::meet_beyond_vertex;
/// let t = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]];
/// // a fan neighbour in another plane, and a coplanar triangle overlapping t's wedge
/// assert!(!meet_beyond_vertex(t, 0, [[0.0, 0.0, 0.0], [-1.0, 0.0, 1.0], [0.0, -2.0, 1.0]], 0));
/// assert!(meet_beyond_vertex(t, 0, [[0.0, 0.0, 0.0], [2.0, 1.0, 0.0], [1.0, 2.0, 0.0]], 0));
/// ```
pub fn meet_beyond_vertex(t: [P; 3], it: usize, u: [P; 3], iu: usize) -> bool {
    if degenerate_triangle(t[0], t[1], t[2]) {
        // the coplanarity test below needs t's plane
        return !degenerate_triangle(u[0], u[1], u[2]) && meet_beyond_vertex_planar(u, iu, t, it);
    }
    meet_beyond_vertex_planar(t, it, u, iu)
}

/// [`meet_beyond_vertex`] for a non-degenerate t.
fn meet_beyond_vertex_planar(t: [P; 3], it: usize, u: [P; 3], iu: usize) -> bool {
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
        let along = |r: [f64; 2]| orient2d(v, r, x) == 0.0 && dot(sub(r, v), sub(x, v)) > 0.0;
        (s1 > 0.0 && s2 > 0.0) || along(p) || along(q)
    };
    // (a wedge containing the other has the other's edges inside it)
    inside(c, a, b) || inside(d, a, b) || inside(a, c, d) || inside(b, c, d)
}

/// Triangles abc and abd (common edge ab) meet beyond the edge (exact): iff they are coplanar
/// and c, d lie on the same side of line ab in that plane (a fold onto itself), or one of them
/// is degenerate (c or d on line ab).
///
/// ```
/// use morpho::geom::intersect::meet_beyond_edge;
/// let (a, b) = ([0.0, 0.0, 0.0], [2.0, 0.0, 0.0]);
/// assert!(meet_beyond_edge(a, b, [1.0, 1.0, 0.0], [0.5, 3.0, 0.0])); // folded
/// assert!(!meet_beyond_edge(a, b, [1.0, 1.0, 0.0], [0.5, -3.0, 0.0])); // flat neighbours
/// assert!(!meet_beyond_edge(a, b, [1.0, 1.0, 0.0], [1.0, 1.0, 1.0])); // a dihedral angle
/// ```
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

/// Triangles with vertex ids `ta`, `tb` and corners `pa`, `pb` meet anywhere else than in the
/// vertices they share by id (exact; symmetric in the two): by the number of distinct shared
/// ids, [`triangles_intersect`] (none), [`meet_beyond_vertex`] (one), [`meet_beyond_edge`]
/// (two), always for the same triangle (three).
///
/// A triangle with a repeated id (`[a, a, b]`, a face with no area) is the segment ab, or the
/// point a: its distinct ids are matched once, and it is tested as the degenerate triangle it
/// is — like one with distinct collinear corners (so on a common edge it is reported as
/// meeting its neighbour; sharing one vertex v, it meets the other triangle beyond v iff the
/// segment from v does).
///
/// ```
/// use morpho::geom::intersect::triangles_meet_beyond_shared;
/// let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
/// let corners = |t: [u32; 3]| t.map(|v| p[v as usize]);
/// // two faces of a tetrahedron share the edge 0–1 and nothing else
/// let (t, u) = ([0, 2, 1], [0, 1, 3]);
/// assert!(!triangles_meet_beyond_shared(t, corners(t), u, corners(u)));
/// // the face 0 0 1 (a segment on that edge) folds onto it
/// let d = [0, 0, 1];
/// assert!(triangles_meet_beyond_shared(t, corners(t), d, corners(d)));
/// ```
pub fn triangles_meet_beyond_shared(ta: [u32; 3], pa: [P; 3], tb: [u32; 3], pb: [P; 3]) -> bool {
    // (position in ta, position in tb) of each distinct shared id: the first position of the
    // id in each (so that positions are distinct even when a triangle repeats an id)
    let mut shared = [(0usize, 0usize); 3];
    let mut ns = 0;
    for i in 0..3 {
        if ta[..i].contains(&ta[i]) {
            continue;
        }
        if let Some(j) = (0..3).find(|&j| tb[j] == ta[i]) {
            shared[ns] = (i, j);
            ns += 1;
        }
    }
    match ns {
        0 => triangles_intersect(pa, pb),
        1 => {
            let (i, j) = shared[0];
            match (fan_form(ta, pa, i), fan_form(tb, pb, j)) {
                // a triangle that is the shared point itself has nothing beyond it
                (None, _) | (_, None) => false,
                (Some((pa, i)), Some((pb, j))) => meet_beyond_vertex(pa, i, pb, j),
            }
        }
        2 => {
            let (i0, i1) = (shared[0].0, shared[1].0);
            let (j0, j1) = (shared[0].1, shared[1].1);
            let (c, d) = (3 - i0 - i1, 3 - j0 - j1);
            meet_beyond_edge(pa[i0], pa[i1], pa[c], pb[d])
        }
        _ => true,
    }
}

/// The corners of triangle `t` (ids) for [`meet_beyond_vertex`] at its corner `i`: `(p, i)`
/// unchanged when the ids are distinct; for repeated ids, the segment from the shared vertex v
/// to the other id's position b as the degenerate triangle (v, b, b) with v at position 0 — so
/// that the edge opposite v is the point b, not the segment vb, which contains v and would
/// always meet the other triangle there; `None` when every id is v's.
fn fan_form(t: [u32; 3], p: [P; 3], i: usize) -> Option<([P; 3], usize)> {
    if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
        return Some((p, i));
    }
    let k = (0..3).find(|&k| t[k] != t[i])?;
    Some(([p[i], p[k], p[k]], 0))
}

/// The sign of `orient2d(p, q, r + (ε, ε²))` for an infinitesimal ε > 0 (exact): the exact
/// sign when it is not 0, else the sign of the perturbation's leading term. 0 only when p = q.
#[inline]
fn side_perturbed(p: [f64; 2], q: [f64; 2], r: [f64; 2]) -> i32 {
    let o = orient2d(p, q, r);
    if o != 0.0 {
        return if o > 0.0 { 1 } else { -1 };
    }
    // orient2d(p, q, r + (ε, ε²)) = 0 − (q₁ − p₁) ε + (q₀ − p₀) ε²
    if q[1] != p[1] {
        return if p[1] > q[1] { 1 } else { -1 };
    }
    if q[0] != p[0] {
        return if q[0] > p[0] { 1 } else { -1 };
    }
    0
}

/// Does the ray from `x` towards +`axis` cross the closed triangle abc, with `x` moved
/// symbolically by (ε, ε²) along the two other axes (in cyclic order: axis+1, axis+2)? Exact.
///
/// The perturbation makes every ray generic (Simulation of Simplicity on the query point
/// only): it never passes through an edge or a vertex, a triangle parallel to the ray (zero
/// projected area, degenerate triangles included) is never crossed, and two triangles on
/// either side of a shared edge see the edge with opposite signs. So the crossing parity over
/// a closed (mod 2) surface is 1 exactly when the perturbed point is enclosed — the point-in-
/// polyhedron parity, for every `x` *not on* the surface (decide that first, e.g. with
/// [`segment_meets_triangle`]`(x, x, a, b, c)`).
///
/// ```
/// use morpho::geom::intersect::ray_crosses_triangle;
/// let (a, b, c) = ([1.0, 0.0, 0.0], [1.0, 2.0, 0.0], [1.0, 0.0, 2.0]);
/// assert!(ray_crosses_triangle([0.0, 0.5, 0.5], 0, a, b, c));
/// assert!(!ray_crosses_triangle([2.0, 0.5, 0.5], 0, a, b, c)); // behind
/// // through the edge b–c, or the vertex a: decided by the perturbation, once per surface
/// let d = [1.0, 2.0, 2.0];
/// assert_ne!(ray_crosses_triangle([0.0, 1.0, 1.0], 0, a, b, c), ray_crosses_triangle([0.0, 1.0, 1.0], 0, b, d, c));
/// ```
pub fn ray_crosses_triangle(x: P, axis: usize, a: P, b: P, c: P) -> bool {
    let (pa, pb, pc, px) = (proj(a, axis), proj(b, axis), proj(c, axis), proj(x, axis));
    for k in 0..2 {
        // (x + (ε, ε²)) is beyond every corner on this projected axis, or before every one
        if (pa[k] < px[k] && pb[k] < px[k] && pc[k] < px[k])
            || (pa[k] > px[k] && pb[k] > px[k] && pc[k] > px[k])
        {
            return false;
        }
    }
    let u = axis;
    if a[u] < x[u] && b[u] < x[u] && c[u] < x[u] {
        return false;
    }
    let o = orient2d(pa, pb, pc);
    if o == 0.0 {
        return false;
    }
    let want = if o > 0.0 { 1 } else { -1 };
    if side_perturbed(pa, pb, px) != want
        || side_perturbed(pb, pc, px) != want
        || side_perturbed(pc, pa, px) != want
    {
        return false;
    }
    if a[u] > x[u] && b[u] > x[u] && c[u] > x[u] {
        return true;
    }
    // the plane is crossed ahead iff orient3d(a, b, c, x') has the sign of n_u = o, where
    // orient3d(a, b, c, x') = orient3d(a, b, c, x) − ε n_v − ε² n_w, n = (b − a) × (c − a)
    let f = orient3d(a, b, c, x);
    let s = if f != 0.0 {
        if f > 0.0 {
            1
        } else {
            -1
        }
    } else {
        let (v, w) = ((axis + 1) % 3, (axis + 2) % 3);
        let nv = orient2d(proj(a, v), proj(b, v), proj(c, v));
        let nw = orient2d(proj(a, w), proj(b, w), proj(c, w));
        let n = if nv != 0.0 { nv } else { nw };
        if n > 0.0 {
            -1
        } else if n < 0.0 {
            1
        } else {
            0
        }
    };
    s == want
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    // Oracles: the separating axis theorem in exact integer arithmetic. Two compact convex
    // sets are disjoint iff some axis separates their projections strictly; for the convex
    // hulls of two finite point sets it suffices to try the directions of the edges of their
    // Minkowski difference and its face normals: the differences d within each set and between
    // the sets, their pairwise cross products, and (for flat differences) the cross products
    // of those with a d again. An independent method: no orientation-sign case analysis.

    type I3 = [i128; 3];

    fn isub(a: I3, b: I3) -> I3 {
        [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
    }
    fn idot(a: I3, b: I3) -> i128 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }
    fn icross(a: I3, b: I3) -> I3 {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }

    /// The convex hulls of the point sets `p` and `q` (3D integers) have a point in common.
    fn hulls_meet(p: &[I3], q: &[I3]) -> bool {
        let mut dirs: Vec<I3> = Vec::new();
        for s in [p, q] {
            for i in 0..s.len() {
                for j in i + 1..s.len() {
                    dirs.push(isub(s[j], s[i]));
                }
            }
        }
        for &a in p {
            for &b in q {
                dirs.push(isub(b, a));
            }
        }
        dirs.retain(|d| *d != [0, 0, 0]);
        let mut axes = dirs.clone();
        for &d in &dirs {
            for &e in &dirs {
                let n = icross(d, e);
                if n != [0, 0, 0] {
                    axes.push(n);
                    for &f in &dirs {
                        axes.push(icross(n, f));
                    }
                }
            }
        }
        !axes.iter().any(|&ax| {
            let range = |s: &[I3]| {
                let v: Vec<i128> = s.iter().map(|&x| idot(ax, x)).collect();
                (*v.iter().min().unwrap(), *v.iter().max().unwrap())
            };
            let ((plo, phi), (qlo, qhi)) = (range(p), range(q));
            phi < qlo || qhi < plo
        })
    }

    fn i3(p: [i64; 3]) -> I3 {
        p.map(|x| x as i128)
    }
    fn f3(p: [i64; 3]) -> P {
        p.map(|x| x as f64)
    }
    fn lift(p: [i64; 2]) -> [i64; 3] {
        [p[0], p[1], 0]
    }

    /// Random small integer points, often on a common plane or line (many exact touchings).
    fn points(rng: &mut rand_chacha::ChaCha8Rng, n: usize, flat: bool) -> Vec<[i64; 3]> {
        let m: [[i64; 3]; 3] =
            std::array::from_fn(|_| std::array::from_fn(|_| rng.gen_range(-2..=2)));
        (0..n)
            .map(|_| {
                let (u, v, w) = (
                    rng.gen_range(-3..=3),
                    rng.gen_range(-3..=3),
                    if flat { 0 } else { rng.gen_range(-3..=3) },
                );
                std::array::from_fn(|i| m[i][0] * u + m[i][1] * v + m[i][2] * w)
            })
            .collect()
    }

    #[test]
    fn segment_tests_match_the_separating_axis_oracle() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
        let (mut hit, mut proper, mut touch) = (0, 0, 0);
        for _ in 0..20_000 {
            let q: Vec<[i64; 2]> = (0..4)
                .map(|_| [rng.gen_range(-3..=3), rng.gen_range(-3..=3)])
                .collect();
            let f = |p: [i64; 2]| p.map(|x| x as f64);
            let (a, b, c, d) = (f(q[0]), f(q[1]), f(q[2]), f(q[3]));
            let want = hulls_meet(
                &[i3(lift(q[0])), i3(lift(q[1]))],
                &[i3(lift(q[2])), i3(lift(q[3]))],
            );
            assert_eq!(segments_intersect(a, b, c, d), want, "{q:?}");
            assert_eq!(segments_intersect(c, d, b, a), want, "{q:?}");
            // proper: meeting, no end point on the other segment, not collinear
            let o = |x: [f64; 2], y: [f64; 2], z: [f64; 2]| orient2d(x, y, z);
            let on =
                |x: [f64; 2], y: [f64; 2], p: [f64; 2]| o(x, y, p) == 0.0 && on_segment(x, y, p);
            let want_proper = want && !(on(a, b, c) || on(a, b, d) || on(c, d, a) || on(c, d, b));
            assert_eq!(segments_cross_properly(a, b, c, d), want_proper, "{q:?}");
            hit += want as usize;
            proper += want_proper as usize;
            touch += (want && !want_proper) as usize;
        }
        assert!(
            hit > 3000 && proper > 1000 && touch > 1000,
            "{hit} {proper} {touch}"
        );
    }

    #[test]
    fn point_in_triangle_and_2d_overlap_match_the_oracle() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(2);
        let (mut inside, mut overlap) = (0, 0);
        for _ in 0..10_000 {
            let q: Vec<[i64; 2]> = (0..6)
                .map(|_| [rng.gen_range(-3..=3), rng.gen_range(-3..=3)])
                .collect();
            let f = |p: [i64; 2]| p.map(|x| x as f64);
            let t: Vec<I3> = q[..3].iter().map(|&p| i3(lift(p))).collect();
            let u: Vec<I3> = q[3..].iter().map(|&p| i3(lift(p))).collect();
            let want = hulls_meet(&[u[0]], &t);
            assert_eq!(
                point_in_triangle(f(q[3]), f(q[0]), f(q[1]), f(q[2])),
                want,
                "{q:?}"
            );
            inside += want as usize;
            let tt = [f(q[0]), f(q[1]), f(q[2])];
            let uu = [f(q[3]), f(q[4]), f(q[5])];
            let want = hulls_meet(&t, &u);
            assert_eq!(triangles_intersect_2d(tt, uu), want, "{q:?}");
            assert_eq!(triangles_intersect_2d(uu, tt), want, "{q:?}");
            overlap += want as usize;
        }
        assert!(inside > 1000 && overlap > 3000, "{inside} {overlap}");
    }

    #[test]
    fn triangle_tests_match_the_separating_axis_oracle() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let (mut meet, mut coplanar, mut seg) = (0, 0, 0);
        for it in 0..20_000 {
            let q = points(&mut rng, 6, it % 3 == 0);
            let (t, u) = ([q[0], q[1], q[2]], [q[3], q[4], q[5]]);
            let (tf, uf) = (t.map(f3), u.map(f3));
            let (ti, ui) = (t.map(i3), u.map(i3));
            // segment pq against a non-degenerate triangle
            if !degenerate_triangle(tf[0], tf[1], tf[2]) {
                let want = hulls_meet(&[ui[0], ui[1]], &ti);
                assert_eq!(
                    segment_meets_triangle(uf[0], uf[1], tf[0], tf[1], tf[2]),
                    want
                );
                seg += want as usize;
            }
            // triangles: the oracle decides for non-degenerate pairs (the documented rule for
            // a degenerate one is "the segment it covers", checked against the oracle too)
            let (dt, du) = (
                degenerate_triangle(tf[0], tf[1], tf[2]),
                degenerate_triangle(uf[0], uf[1], uf[2]),
            );
            if t.iter().any(|x| u.contains(x)) || (dt && du) {
                continue;
            }
            let want = hulls_meet(&ti, &ui);
            assert_eq!(triangles_intersect(tf, uf), want, "{t:?} {u:?}");
            assert_eq!(triangles_intersect(uf, tf), want, "{t:?} {u:?}");
            meet += want as usize;
            coplanar +=
                (want && (0..3).all(|k| orient3d(tf[0], tf[1], tf[2], uf[k]) == 0.0)) as usize;
        }
        assert!(
            meet > 2000 && coplanar > 300 && seg > 1000,
            "{meet} {coplanar} {seg}"
        );
    }

    /// Triangles sharing one vertex v meet beyond it iff t with a tiny corner at v cut off
    /// meets u, or u with its corner cut off meets t (on integer points the intersection, a
    /// convex set containing v, reaches far beyond any corner of size 1/K, K = 10⁶).
    #[test]
    fn meet_beyond_vertex_matches_the_corner_cut_oracle() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(4);
        let k: i128 = 1_000_000;
        let cut = |t: [I3; 3], i: usize| -> Vec<I3> {
            // t scaled by K, without the corner at t[i]: the quadrilateral
            // v + (a − v)/K, a, b, v + (b − v)/K (times K)
            let (v, a, b) = (t[i], t[(i + 1) % 3], t[(i + 2) % 3]);
            let s = |x: I3| x.map(|c| c * k);
            let near = |x: I3| std::array::from_fn(|c| v[c] * (k - 1) + x[c]);
            vec![near(a), s(a), s(b), near(b)]
        };
        let (mut meet, mut clear) = (0, 0);
        for it in 0..20_000 {
            let mut q = points(&mut rng, 5, it % 2 == 0);
            q.insert(3, q[0]); // u's first corner is t's first
            let (t, u) = ([q[0], q[1], q[2]], [q[3], q[4], q[5]]);
            let (tf, uf) = (t.map(f3), u.map(f3));
            if q[1..3].iter().chain(&q[4..]).any(|x| *x == q[0])
                || q[4..].iter().any(|x| t.contains(x))
            {
                continue;
            }
            if degenerate_triangle(tf[0], tf[1], tf[2]) || degenerate_triangle(uf[0], uf[1], uf[2])
            {
                continue;
            }
            let (ti, ui) = (t.map(i3), u.map(i3));
            let scale = |x: [I3; 3]| x.map(|p| p.map(|c| c * k)).to_vec();
            let want = hulls_meet(&cut(ti, 0), &scale(ui)) || hulls_meet(&cut(ui, 0), &scale(ti));
            assert_eq!(meet_beyond_vertex(tf, 0, uf, 0), want, "{t:?} {u:?}");
            assert_eq!(meet_beyond_vertex(uf, 0, tf, 0), want, "{t:?} {u:?}");
            // rotations of the corner order do not matter
            let (tr, ur) = ([tf[1], tf[2], tf[0]], [uf[2], uf[0], uf[1]]);
            assert_eq!(meet_beyond_vertex(tr, 2, ur, 1), want);
            meet += want as usize;
            clear += (!want) as usize;
        }
        assert!(meet > 1000 && clear > 1000, "{meet} {clear}");
    }

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
    }

    #[test]
    fn common_edge_test_matches_the_oracle() {
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

    /// The issue-17 reproducer at the level of the pair test: faces with a repeated id (`f 1 1
    /// 2` in an OBJ) against every face of a tetrahedron and against each other — no panic,
    /// symmetric, and the answers of the degenerate triangle with distinct ids that covers the
    /// same segment when the ids are shared alike.
    #[test]
    fn repeated_ids_are_degenerate_triangles() {
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.5, 0.0, 0.0],
        ];
        let c = |t: [u32; 3]| t.map(|v| p[v as usize]);
        let faces = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];
        let degenerate = [
            [0, 0, 1],
            [0, 1, 1],
            [1, 0, 0],
            [2, 2, 2],
            [3, 0, 3],
            [0, 0, 4],
        ];
        for &d in &degenerate {
            for &t in faces.iter().chain(&degenerate) {
                let m = triangles_meet_beyond_shared(d, c(d), t, c(t));
                assert_eq!(
                    m,
                    triangles_meet_beyond_shared(t, c(t), d, c(d)),
                    "{d:?} {t:?}"
                );
            }
        }
        // 0 0 1 is the edge 0–1: it folds onto both faces on that edge, and touches the two
        // others only in a shared vertex
        let d = [0, 0, 1];
        assert!(triangles_meet_beyond_shared(d, c(d), faces[0], c(faces[0])));
        assert!(triangles_meet_beyond_shared(d, c(d), faces[1], c(faces[1])));
        assert!(!triangles_meet_beyond_shared(
            d,
            c(d),
            faces[2],
            c(faces[2])
        ));
        assert!(!triangles_meet_beyond_shared(
            d,
            c(d),
            faces[3],
            c(faces[3])
        ));
        // with distinct ids, 0 4 1 covers the same segment and gets the same answers
        let e = [0, 4, 1];
        for f in faces {
            assert_eq!(
                triangles_meet_beyond_shared(e, c(e), f, c(f)),
                triangles_meet_beyond_shared(d, c(d), f, c(f)),
                "{f:?}"
            );
        }
    }
}
