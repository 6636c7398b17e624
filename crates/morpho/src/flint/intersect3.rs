//! Intersection of two closed triangle meshes by descending their 3D flintstone trees
//! (Veltkamp 1992, §7.4 with Lemma 6.1; reading notes A.8), and its brute-force oracle.
//!
//! **Descent.** Start with the pair (root A, root B). A node pair whose flintstones provably do
//! not meet is pruned; otherwise the node with the larger flintstone (smaller of its filter
//! balls' radii; ties: more triangles) is replaced by its children and every child pair is
//! tested — V descends "with the next level of the deepest subtree", here the larger volume is
//! opened, which is the same rule on balanced trees and prunes earlier on unbalanced ones. At
//! two leaves (input triangles) the exact test decides ([`triangles_intersect`], closed
//! triangles, orient3d/orient2d only). Each pair of leaves is reached along exactly one path,
//! so every intersecting triangle pair is reported once; the output is sorted by
//! `(triangle of A, triangle of B)` whatever the schedule. Below the first few hundred pairs
//! (found breadth-first) the subtrees run in parallel (rayon); [`intersects3`] stops at the
//! first intersecting leaf pair (the count of visited pairs then depends on the schedule).
//!
//! **The filter, and why it is conservative.** V's pair tests (notes A.8, cases 1–3) combine the
//! two balls of each stone. Here each node carries the *convex* `f64` supersets of its
//! flintstone that the point queries use (`ball.rs`): for a ∩ stone its two side balls, for a
//! cap its ball, for a flat stone the circumdisc's ball, always a ball around the node's
//! vertices; the root keeps its enclosing ball and a leaf a ball around its triangle. Every
//! radius is the largest *computed* distance to a vertex of the node's open polyhedron (and its
//! paths) inflated by a relative 1e-12, so each ball holds those vertices, hence (being convex)
//! every triangle below the node. A pair is pruned only when some ball of A and some ball of B
//! are disjoint, decided as `|c_A − c_B|² > (r_A + r_B)² · (1 + 1e-9)` in `f64`: both sides are
//! computed with a relative error below 1e-14 (a few roundings each; subnormal squares add at
//! most 3·2⁻¹⁰⁷⁴, far below the margin on radii of at least `sqrt(f64::MIN_POSITIVE)`), so a
//! pruned pair has truly disjoint closed balls and no common point — never a false negative.
//! This is V's case 1 (∩ against ∩: all ball pairs must meet) on the convex parts; a ∪ stone
//! (V's cases 2–3) is **not** used with its two balls, because the union is not convex: its
//! open polyhedron's vertices lie in it but a triangle joining the two sides can leave it, so
//! only its hull ball filters it (a documented deviation, the one `query3.rs` makes too). A cap's
//! half-space and unbounded stones filter nothing beyond the hull ball. Trees whose coordinates
//! turn pruning off (beyond about 1e±150, see `tree3.rs`) have no balls: the descent is then
//! exhaustive but still exact.
//!
//! **Contacts.** Triangles are closed: pairs that only touch (a shared vertex or edge position,
//! a vertex on a face, meshes that only touch) are reported, and so are coplanar overlaps. A mesh
//! against itself reports every triangle with itself and with every triangle it shares a vertex
//! with (plus any real self-intersection), because the two meshes' vertex ids are unrelated; use
//! [`crate::mesh::validity`] for self-intersection beyond shared vertices.
//!
//! **Geometry** ([`triangle_meet`]): every decision (which edges meet the other triangle, which
//! vertices lie in it, coplanarity) is exact; the points are then computed in `f64` — on an edge
//! crossing the other plane, at the parameter given by the two orient3d values; coplanar crossings
//! from the orient2d values in an axis projection. A non-coplanar pair meets in a segment (its two
//! extreme candidate points; equal for a touching point); a coplanar pair in a convex polygon, the
//! hull of the candidate points (vertices of one in the other and edge crossings), reported as its
//! boundary edges.
//!
//! [`intersect3_brute`] is the oracle: every pair of triangles whose bounding boxes meet (exact
//! coordinate comparisons, a sort-and-sweep along x) gets the same exact test.

use super::ball::Filter;
use super::tree3::FlintTree3;
use crate::geom::intersect::{
    good_axis, on_segment, point_in_triangle, proj, segment_meets_triangle, segments_intersect,
    triangles_intersect,
};
use crate::geom::predicates::raw::{orient2d, orient3d};
use crate::geom::vec::{dist2, lerp};
use crate::util::NONE;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

type P = [f64; 3];

/// Counts of one tree–tree descent.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct IntersectStats3 {
    /// Node pairs examined (filter tests), the root pair included.
    pub visited: usize,
    /// Node pairs that passed the filter.
    pub passed: usize,
    /// Exact triangle–triangle tests (leaf pairs that passed).
    pub leaf_tests: usize,
    /// Triangle pairs a brute-force test would make (`|A| · |B|`).
    pub brute_pairs: usize,
}

impl IntersectStats3 {
    fn add(&mut self, o: &IntersectStats3) {
        self.visited += o.visited;
        self.passed += o.passed;
        self.leaf_tests += o.leaf_tests;
    }
}

/// Where two closed triangles meet (see [`triangle_meet`]).
#[derive(Debug, Clone, PartialEq)]
pub struct TriangleMeet {
    /// The triangles are coplanar (exact).
    pub coplanar: bool,
    /// Non-coplanar: the two end points of the common segment (equal for a single point).
    /// Coplanar: the vertices of the common convex polygon in order (1 point, 2 for a segment).
    pub points: Vec<P>,
}

impl TriangleMeet {
    /// The intersection as segments: one for a non-coplanar pair, the boundary edges of a
    /// coplanar overlap (one segment for a 2-point overlap, a zero-length one for a point).
    pub fn segments(&self) -> Vec<[P; 2]> {
        let p = &self.points;
        match p.len() {
            0 => Vec::new(),
            1 => vec![[p[0], p[0]]],
            2 => vec![[p[0], p[1]]],
            n => (0..n).map(|i| [p[i], p[(i + 1) % n]]).collect(),
        }
    }
}

/// A node as the descent reads it: its filter balls, size, children and (leaf) triangle.
#[derive(Debug, Clone, Copy)]
struct Vol {
    balls: [(P, f64); 3],
    n: u8,
    /// Smallest squared radius of the balls (∞ without balls): the larger one is opened.
    size: f64,
    tris: u32,
    first: u32,
    count: u32,
    /// Input triangle of a leaf, else NONE.
    tri: u32,
}

/// The tree flattened for the descent: index 0 is the root, node `i` is index `i + 1`.
struct Vols {
    v: Vec<Vol>,
    kids: Vec<u32>,
}

fn vol_of(f: &Filter, tris: u32, first: u32, count: u32, tri: u32) -> Vol {
    let n = f.count;
    let balls = f.balls;
    let size = balls[..n as usize]
        .iter()
        .map(|b| b.1)
        .fold(f64::INFINITY, f64::min);
    Vol {
        balls,
        n,
        size,
        tris,
        first,
        count,
        tri,
    }
}

impl Vols {
    fn of(t: &FlintTree3) -> Vols {
        let mut v = Vec::with_capacity(t.nodes.len() + 1);
        let mut kids = Vec::with_capacity(t.nodes.len());
        let mut root = Filter::none();
        if t.prune && t.root.reach2.is_finite() {
            root.balls[0] = (t.root.center, t.root.reach2);
            root.count = 1;
        }
        kids.extend(t.root.children.iter().map(|&c| c + 1));
        v.push(vol_of(
            &root,
            t.tris.len() as u32,
            0,
            t.root.children.len() as u32,
            NONE,
        ));
        for nd in &t.nodes {
            let first = kids.len() as u32;
            kids.extend(nd.children.iter().map(|&c| c + 1));
            let f = match &nd.stone {
                Some(s) => s.filter,
                // a leaf: a ball around its triangle
                None => Filter::hull(&t.pos, &nd.corners, t.prune),
            };
            let tri = if nd.is_leaf() { nd.triangle } else { NONE };
            v.push(vol_of(
                &f,
                nd.range[1] - nd.range[0],
                first,
                nd.children.len() as u32,
                tri,
            ));
        }
        Vols { v, kids }
    }

    fn children(&self, i: u32) -> &[u32] {
        let n = &self.v[i as usize];
        &self.kids[n.first as usize..(n.first + n.count) as usize]
    }
}

/// The two closed balls `(c, r²)` are certainly disjoint (see the module doc for the margin).
#[inline]
fn apart((ca, ra2): (P, f64), (cb, rb2): (P, f64)) -> bool {
    let s = ra2.sqrt() + rb2.sqrt();
    dist2(ca, cb) > s * s * (1.0 + 1e-9)
}

/// The pair filter: false only when some ball of `a` and some ball of `b` are disjoint.
#[inline]
fn may_meet(a: &Vol, b: &Vol) -> bool {
    for &ba in &a.balls[..a.n as usize] {
        for &bb in &b.balls[..b.n as usize] {
            if apart(ba, bb) {
                return false;
            }
        }
    }
    true
}

struct Walk<'a> {
    a: &'a FlintTree3,
    b: &'a FlintTree3,
    va: Vols,
    vb: Vols,
    stop: Option<&'a AtomicBool>,
}

impl Walk<'_> {
    fn new<'a>(a: &'a FlintTree3, b: &'a FlintTree3, stop: Option<&'a AtomicBool>) -> Walk<'a> {
        Walk {
            a,
            b,
            va: Vols::of(a),
            vb: Vols::of(b),
            stop,
        }
    }

    fn corners(t: &FlintTree3, tri: u32) -> [P; 3] {
        t.tris[tri as usize].map(|v| t.pos[v as usize])
    }

    /// Examines one node pair: prunes it, tests two leaves, or pushes the child pairs.
    fn step(
        &self,
        (i, j): (u32, u32),
        stack: &mut Vec<(u32, u32)>,
        out: &mut Vec<[u32; 2]>,
        st: &mut IntersectStats3,
    ) {
        st.visited += 1;
        let (a, b) = (&self.va.v[i as usize], &self.vb.v[j as usize]);
        if !may_meet(a, b) {
            return;
        }
        st.passed += 1;
        let open_a = match (a.tri != NONE, b.tri != NONE) {
            (true, true) => {
                st.leaf_tests += 1;
                let (ta, tb) = (Self::corners(self.a, a.tri), Self::corners(self.b, b.tri));
                if triangles_intersect(ta, tb) {
                    out.push([a.tri, b.tri]);
                    if let Some(s) = self.stop {
                        s.store(true, Ordering::Relaxed);
                    }
                }
                return;
            }
            (true, false) => false,
            (false, true) => true,
            (false, false) => a.size > b.size || (a.size == b.size && a.tris >= b.tris),
        };
        if open_a {
            stack.extend(self.va.children(i).iter().map(|&c| (c, j)));
        } else {
            stack.extend(self.vb.children(j).iter().map(|&c| (i, c)));
        }
    }

    fn stopped(&self) -> bool {
        self.stop.is_some_and(|s| s.load(Ordering::Relaxed))
    }

    /// The whole descent: breadth-first until enough pairs for the threads, then in parallel.
    fn run(&self) -> (Vec<[u32; 2]>, IntersectStats3) {
        let mut st = IntersectStats3 {
            brute_pairs: self.a.tris.len() * self.b.tris.len(),
            ..Default::default()
        };
        let mut out = Vec::new();
        let mut front = std::collections::VecDeque::from([(0u32, 0u32)]);
        let want = 64 * rayon::current_num_threads().max(1);
        let mut next = Vec::new();
        while front.len() < want {
            let Some(p) = front.pop_front() else { break };
            self.step(p, &mut next, &mut out, &mut st);
            front.extend(next.drain(..));
            if self.stopped() {
                return (out, st);
            }
        }
        let front: Vec<(u32, u32)> = front.into();
        let parts: Vec<(Vec<[u32; 2]>, IntersectStats3)> = front
            .into_par_iter()
            .map(|p| {
                let mut o = Vec::new();
                let mut s = IntersectStats3::default();
                let mut stack = vec![p];
                while let Some(q) = stack.pop() {
                    if self.stopped() {
                        break;
                    }
                    self.step(q, &mut stack, &mut o, &mut s);
                }
                (o, s)
            })
            .collect();
        for (o, s) in parts {
            out.extend(o);
            st.add(&s);
        }
        out.sort_unstable();
        (out, st)
    }
}

/// Every pair `[triangle of A, triangle of B]` of closed triangles that have a point in common,
/// sorted, by descending the two trees (exact at the leaves; see the module doc).
///
/// ```
/// use morpho::flint::{intersect3, FlintTree3};
/// use morpho::geom::Point3;
/// use morpho::mesh::generate;
/// let a = generate::cube();
/// let mut b = a.clone();
/// for p in &mut b.positions { *p = Point3::new(p.x + 1.0, p.y + 1.0, p.z + 1.0); } // shares one vertex
/// let (ta, tb) = (FlintTree3::from_mesh(&a).unwrap(), FlintTree3::from_mesh(&b).unwrap());
/// let (pairs, stats) = intersect3(&ta, &tb);
/// assert!(!pairs.is_empty() && stats.leaf_tests < stats.brute_pairs);
/// ```
pub fn intersect3(a: &FlintTree3, b: &FlintTree3) -> (Vec<[u32; 2]>, IntersectStats3) {
    Walk::new(a, b, None).run()
}

/// Whether the two meshes have a point in common, stopping at the first intersecting triangle
/// pair found (exact; the counts depend on the thread schedule).
pub fn intersects3(a: &FlintTree3, b: &FlintTree3) -> (bool, IntersectStats3) {
    let stop = AtomicBool::new(false);
    let (out, st) = Walk::new(a, b, Some(&stop)).run();
    (!out.is_empty(), st)
}

/// The brute-force oracle of [`intersect3`]: every pair of triangles whose closed bounding
/// boxes overlap (exact comparisons; sort-and-sweep along x) gets the exact
/// [`triangles_intersect`]; sorted pairs `[triangle of A, triangle of B]`.
pub fn intersect3_brute(
    pa: &[[f64; 3]],
    ta: &[[u32; 3]],
    pb: &[[f64; 3]],
    tb: &[[u32; 3]],
) -> Vec<[u32; 2]> {
    let boxes = |p: &[[f64; 3]], t: &[[u32; 3]]| -> Vec<(P, P)> {
        t.iter()
            .map(|tr| {
                let c = tr.map(|v| p[v as usize]);
                let lo = std::array::from_fn(|k| c[0][k].min(c[1][k]).min(c[2][k]));
                let hi = std::array::from_fn(|k| c[0][k].max(c[1][k]).max(c[2][k]));
                (lo, hi)
            })
            .collect()
    };
    let (ba, bb) = (boxes(pa, ta), boxes(pb, tb));
    // sweep events: (min x, side, index)
    let mut ev: Vec<(f64, u8, u32)> = ba
        .iter()
        .enumerate()
        .map(|(i, b)| (b.0[0], 0, i as u32))
        .chain(bb.iter().enumerate().map(|(i, b)| (b.0[0], 1, i as u32)))
        .collect();
    ev.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)).then(x.2.cmp(&y.2)));
    let mut active: [Vec<u32>; 2] = [Vec::new(), Vec::new()];
    let mut out = Vec::new();
    for (x, side, i) in ev {
        let (mine, other) = if side == 0 { (&ba, &bb) } else { (&bb, &ba) };
        let o = &mut active[1 - side as usize];
        o.retain(|&j| other[j as usize].1[0] >= x);
        let bi = mine[i as usize];
        for &j in o.iter() {
            let bj = other[j as usize];
            let overlap = (1..3).all(|k| bi.0[k] <= bj.1[k] && bj.0[k] <= bi.1[k]);
            if !overlap {
                continue;
            }
            let (ia, ib) = if side == 0 { (i, j) } else { (j, i) };
            let ca = ta[ia as usize].map(|v| pa[v as usize]);
            let cb = tb[ib as usize].map(|v| pb[v as usize]);
            if triangles_intersect(ca, cb) {
                out.push([ia, ib]);
            }
        }
        active[side as usize].push(i);
    }
    out.sort_unstable();
    out
}

/// Where the closed, non-degenerate triangles `t` and `u` meet: `None` when they do not
/// (exact, [`triangles_intersect`]); else the common segment or, for coplanar triangles, the
/// common convex polygon, with points computed in `f64` from exact decisions (module doc).
///
/// ```
/// use morpho::flint::triangle_meet;
/// let t = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]];
/// let u = [[0.5, 0.5, -1.0], [0.5, 0.5, 1.0], [3.0, 0.5, 0.0]];
/// let m = triangle_meet(t, u).unwrap();
/// assert!(!m.coplanar);
/// let [p, q] = m.segments()[0];
/// assert!(((p[0] - q[0]).abs() - 1.0).abs() < 1e-12); // from x = 0.5 to x = 1.5 at y = 0.5
/// ```
pub fn triangle_meet(t: [P; 3], u: [P; 3]) -> Option<TriangleMeet> {
    if !triangles_intersect(t, u) {
        return None;
    }
    let su = t.map(|x| orient3d(u[0], u[1], u[2], x));
    let st = u.map(|x| orient3d(t[0], t[1], t[2], x));
    let coplanar = su.iter().all(|&s| s == 0.0) && st.iter().all(|&s| s == 0.0);
    let mut pts = Vec::new();
    if coplanar {
        let Some(ax) = good_axis(t[0], t[1], t[2]) else {
            return Some(TriangleMeet {
                coplanar,
                points: pts,
            });
        };
        let (t2, u2) = (t.map(|x| proj(x, ax)), u.map(|x| proj(x, ax)));
        for k in 0..3 {
            if point_in_triangle(t2[k], u2[0], u2[1], u2[2]) {
                pts.push(t[k]);
            }
            if point_in_triangle(u2[k], t2[0], t2[1], t2[2]) {
                pts.push(u[k]);
            }
        }
        for i in 0..3 {
            for j in 0..3 {
                let (a, b) = (t[i], t[(i + 1) % 3]);
                let (c, d) = (u[j], u[(j + 1) % 3]);
                crossing_points(a, b, c, d, ax, &mut pts);
            }
        }
        let points = hull(pts, ax);
        return Some(TriangleMeet { coplanar, points });
    }
    edge_points(t, u, su, &mut pts);
    edge_points(u, t, st, &mut pts);
    // the common segment's ends are the two candidates farthest apart
    let mut best = (0, 0, -1.0);
    for i in 0..pts.len() {
        for j in i..pts.len() {
            let d = dist2(pts[i], pts[j]);
            if d > best.2 {
                best = (i, j, d);
            }
        }
    }
    let points = if pts.is_empty() {
        pts
    } else {
        vec![pts[best.0], pts[best.1]]
    };
    Some(TriangleMeet { coplanar, points })
}

/// Points where the edges of `t` meet triangle `u`; `s[k] = orient3d(u, t[k])`.
fn edge_points(t: [P; 3], u: [P; 3], s: [f64; 3], pts: &mut Vec<P>) {
    for i in 0..3 {
        let k = (i + 1) % 3;
        let (a, b, oa, ob) = (t[i], t[k], s[i], s[k]);
        if oa == 0.0 && ob == 0.0 {
            // the edge lies in u's plane: its end points in u and its crossings with u's edges
            let Some(ax) = good_axis(u[0], u[1], u[2]) else {
                continue;
            };
            let u2 = u.map(|x| proj(x, ax));
            for x in [a, b] {
                if point_in_triangle(proj(x, ax), u2[0], u2[1], u2[2]) {
                    pts.push(x);
                }
            }
            for j in 0..3 {
                crossing_points(a, b, u[j], u[(j + 1) % 3], ax, pts);
            }
        } else if (oa > 0.0 && ob > 0.0) || (oa < 0.0 && ob < 0.0) {
            continue;
        } else if segment_meets_triangle(a, b, u[0], u[1], u[2]) {
            pts.push(if oa == 0.0 {
                a
            } else if ob == 0.0 {
                b
            } else {
                lerp(a, b, (oa / (oa - ob)).clamp(0.0, 1.0))
            });
        }
    }
}

/// Common points of the coplanar segments ab and cd (projected along `ax`): the crossing, or
/// the end points of a collinear overlap.
fn crossing_points(a: P, b: P, c: P, d: P, ax: usize, pts: &mut Vec<P>) {
    let (a2, b2, c2, d2) = (proj(a, ax), proj(b, ax), proj(c, ax), proj(d, ax));
    if !segments_intersect(a2, b2, c2, d2) {
        return;
    }
    let (o1, o2) = (orient2d(c2, d2, a2), orient2d(c2, d2, b2));
    if o1 == 0.0 && o2 == 0.0 {
        for (x, x2) in [(a, a2), (b, b2)] {
            if on_segment(c2, d2, x2) {
                pts.push(x);
            }
        }
        for (x, x2) in [(c, c2), (d, d2)] {
            if on_segment(a2, b2, x2) {
                pts.push(x);
            }
        }
    } else {
        pts.push(lerp(a, b, (o1 / (o1 - o2)).clamp(0.0, 1.0)));
    }
}

/// The convex hull of coplanar points (in their projection along `ax`), in order; repeated
/// points removed.
fn hull(mut pts: Vec<P>, ax: usize) -> Vec<P> {
    pts.sort_by(|p, q| {
        let (a, b) = (proj(*p, ax), proj(*q, ax));
        a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1]))
    });
    pts.dedup_by(|p, q| proj(*p, ax) == proj(*q, ax));
    if pts.len() < 3 {
        return pts;
    }
    let mut h: Vec<P> = Vec::with_capacity(2 * pts.len());
    for pass in 0..2 {
        let start = h.len();
        let it: Box<dyn Iterator<Item = &P>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in it {
            while h.len() >= start + 2
                && orient2d(
                    proj(h[h.len() - 2], ax),
                    proj(h[h.len() - 1], ax),
                    proj(p, ax),
                ) <= 0.0
            {
                h.pop();
            }
            h.push(p);
        }
        h.pop();
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Point3;
    use crate::mesh::{generate, TriMesh};

    fn shifted(m: &TriMesh, d: [f64; 3]) -> TriMesh {
        let mut m = m.clone();
        for p in &mut m.positions {
            *p = Point3::new(p.x + d[0], p.y + d[1], p.z + d[2]);
        }
        m
    }

    /// Parent of every vol (root: NONE).
    fn parents(v: &Vols) -> Vec<u32> {
        let mut par = vec![NONE; v.v.len()];
        for i in 0..v.v.len() as u32 {
            for &c in v.children(i) {
                par[c as usize] = i;
            }
        }
        par
    }

    fn chain(v: &Vols, par: &[u32], tri: u32) -> Vec<u32> {
        let leaf = v.v.iter().position(|x| x.tri == tri).unwrap() as u32;
        let mut out = vec![leaf];
        let mut i = leaf;
        while par[i as usize] != NONE {
            i = par[i as usize];
            out.push(i);
        }
        assert_eq!(*out.last().unwrap(), 0, "the chain ends at the root");
        out
    }

    #[test]
    fn every_ancestor_pair_of_meeting_leaves_passes_the_filter() {
        let ico = generate::icosphere(3);
        let cases = [
            (ico.clone(), shifted(&ico, [0.9, 0.35, -0.2])),
            (
                generate::cube(),
                shifted(&generate::cube(), [0.5, 0.5, 0.0]),
            ),
            (
                generate::torus(2.0, 0.6, 24, 12),
                shifted(&generate::torus(2.0, 0.6, 24, 12), [0.3, 2.5, 0.1]),
            ),
        ];
        for (k, (ma, mb)) in cases.iter().enumerate() {
            let ta = FlintTree3::from_mesh(ma).unwrap();
            let tb = FlintTree3::from_mesh(mb).unwrap();
            let w = Walk::new(&ta, &tb, None);
            let (pa, pb) = (parents(&w.va), parents(&w.vb));
            let brute = intersect3_brute(&ta.pos, &ta.tris, &tb.pos, &tb.tris);
            assert!(brute.len() > 10, "case {k}: {} pairs", brute.len());
            for &[x, y] in &brute {
                for &i in &chain(&w.va, &pa, x) {
                    for &j in &chain(&w.vb, &pb, y) {
                        assert!(
                            may_meet(&w.va.v[i as usize], &w.vb.v[j as usize]),
                            "case {k}: triangles {x}, {y} meet but ancestors {i}, {j} were pruned"
                        );
                    }
                }
            }
            // and the filter does prune: far fewer leaf tests than brute force (not on the
            // 12-triangle cubes, which overlap almost everywhere)
            let (_, st) = w.run();
            assert!(
                k == 1 || st.leaf_tests * 4 < st.brute_pairs,
                "case {k}: {st:?} (a filter that never prunes)"
            );
        }
    }

    #[test]
    fn every_ball_holds_the_vertices_below_it() {
        let t = FlintTree3::from_mesh(&generate::torus(2.0, 0.6, 24, 12)).unwrap();
        let v = Vols::of(&t);
        // the triangles below each vol, gathered from its leaves
        fn below(v: &Vols, i: u32, out: &mut Vec<u32>) {
            if v.v[i as usize].tri != NONE {
                out.push(v.v[i as usize].tri);
            }
            for &c in v.children(i) {
                below(v, c, out);
            }
        }
        for i in 0..v.v.len() as u32 {
            let mut tris = Vec::new();
            below(&v, i, &mut tris);
            assert_eq!(tris.len() as u32, v.v[i as usize].tris, "vol {i}");
            let vol = &v.v[i as usize];
            for &tr in &tris {
                for &x in &t.tris[tr as usize] {
                    for &(c, r2) in &vol.balls[..vol.n as usize] {
                        assert!(dist2(t.pos[x as usize], c) <= r2, "vol {i}, vertex {x}");
                    }
                }
            }
        }
    }

    #[test]
    fn meet_geometry_of_simple_pairs() {
        let t = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]];
        // coplanar overlap: a square's worth of hull
        let u = [[0.5, 0.5, 0.0], [3.0, 0.5, 0.0], [0.5, 3.0, 0.0]];
        let m = triangle_meet(t, u).unwrap();
        assert!(m.coplanar);
        assert_eq!(m.points.len(), 3, "{:?}", m.points);
        for p in [[0.5, 0.5, 0.0], [1.5, 0.5, 0.0], [0.5, 1.5, 0.0]] {
            assert!(m.points.contains(&p), "{p:?} in {:?}", m.points);
        }
        // touching at one vertex
        let v = [[2.0, 0.0, 0.0], [3.0, 1.0, 1.0], [3.0, -1.0, 1.0]];
        let m = triangle_meet(t, v).unwrap();
        assert_eq!(m.points, vec![[2.0, 0.0, 0.0]; 2]);
        // an edge lying in t's plane, crossing it
        let w = [[-1.0, 0.5, 0.0], [3.0, 0.5, 0.0], [1.0, 0.5, 2.0]];
        let m = triangle_meet(t, w).unwrap();
        assert!(!m.coplanar);
        let mut p = m.points.clone();
        p.sort_by(|a, b| a[0].total_cmp(&b[0]));
        assert_eq!(p, vec![[0.0, 0.5, 0.0], [1.5, 0.5, 0.0]]);
        assert!(triangle_meet(t, [[5.0; 3], [6.0, 5.0, 5.0], [5.0, 6.0, 5.0]]).is_none());
    }
}
