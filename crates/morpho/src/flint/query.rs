//! Hierarchical queries on 2D flintstone trees (Veltkamp 1992, §7.4, Lemma 6.1; reading notes
//! A.8): point-in-polygon and intersection of two boundaries.
//!
//! **Point in polygon.** Outside the root disc ⇒ outside. Otherwise the crossing parity of a
//! ray from X (towards +x) is counted over a mixed boundary: at a node whose flintstone does not
//! contain X, its chord stands in for its polyline (Lemma 6.1: the polyline and chord lie in the
//! convex flintstone, X outside it, so their crossing counts have the same parity); otherwise
//! the node is opened. Leaves are the original edges, where "on the boundary" is decided.
//! Every decision is exact (`orient2d`, `incircle`); a ∪ or unbounded flintstone (not convex) is
//! always opened. Expected O(log N) nodes per query on well-behaved boundaries; O(N) worst.
//! [`contains_brute`] is the all-edges oracle.
//!
//! **Intersection.** Pairs of pieces (node subtrees or single edges) are filtered by their
//! conservative discs (every disc of one must meet every disc of the other, notes A.8 case 1,
//! in `f64` with slack: never a false negative); the piece with more vertices is opened; two
//! edges are tested exactly ([`crate::geom::intersect::segments_intersect`]). A meeting is
//! reported per edge pair: a proper crossing (its point constructed in `f64`), a touching (an
//! input vertex on the other edge, exact) or a collinear overlap (both ends, input vertices).
//! [`intersect_counted`] also returns the pairs visited, against the `edges(A) · edges(B)`
//! pairs of brute force. [`intersect_brute`] is the all-pairs oracle.

use super::disc::{at, discs_meet};
use super::tree2::FlintTree2;
use super::FlintError;
use crate::geom::intersect::{on_segment, segments_cross_properly, segments_intersect};
use crate::geom::predicates::raw::orient2d;
use crate::geom::vec::dist;
use crate::geom::Point2;
use crate::util::NONE;

/// Where a point is relative to a polygon.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Containment {
    /// Strictly outside.
    Outside = 0,
    /// Strictly inside.
    Inside = 1,
    /// On an edge or a vertex.
    Boundary = 2,
}

/// Does the ray from `x` towards +x cross edge `a b`? (half-open rule, exact).
#[inline]
pub(crate) fn crosses(a: [f64; 2], b: [f64; 2], x: [f64; 2]) -> bool {
    if (a[1] > x[1]) == (b[1] > x[1]) {
        return false;
    }
    let o = orient2d(a, b, x);
    if b[1] > a[1] {
        o > 0.0
    } else {
        o < 0.0
    }
}

/// On the closed edge `a b`? (exact)
#[inline]
pub(crate) fn on_edge(a: [f64; 2], b: [f64; 2], x: [f64; 2]) -> bool {
    orient2d(a, b, x) == 0.0 && on_segment(a, b, x)
}

/// Point in polygon by crossing parity over every edge (the oracle; exact).
pub fn contains_brute(points: &[[f64; 2]], x: [f64; 2]) -> Containment {
    let n = points.len();
    let mut inside = false;
    for i in 0..n {
        let (a, b) = (points[i], points[(i + 1) % n]);
        if on_edge(a, b, x) {
            return Containment::Boundary;
        }
        inside ^= crosses(a, b, x);
    }
    if inside {
        Containment::Inside
    } else {
        Containment::Outside
    }
}

impl FlintTree2 {
    /// Where `x` is relative to the polygon (hierarchical, exact). Err for an open polyline.
    ///
    /// ```
    /// use morpho::flint::{Containment, FlintTree2};
    /// use morpho::geom::Point2;
    /// let sq = [(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)].map(|(x, y)| Point2::new(x, y));
    /// let t = FlintTree2::new(&sq, true).unwrap();
    /// assert_eq!(t.contains(Point2::new(1.0, 1.0)).unwrap(), Containment::Inside);
    /// assert_eq!(t.contains(Point2::new(2.0, 1.0)).unwrap(), Containment::Boundary);
    /// assert_eq!(t.contains(Point2::new(3.0, 1.0)).unwrap(), Containment::Outside);
    /// ```
    pub fn contains(&self, x: Point2) -> Result<Containment, FlintError> {
        if !self.closed {
            return Err(FlintError::NotClosed);
        }
        if !(x.x.is_finite() && x.y.is_finite()) {
            return Err(FlintError::NonFiniteQuery);
        }
        Ok(self.locate([x.x, x.y]))
    }

    /// [`Self::contains`] for many points, in input order, located in parallel (rayon) on the
    /// flat layout of `locate.rs` (deterministic: the answers do not depend on the threads).
    pub fn contains_batch(&self, xs: &[Point2]) -> Result<Vec<Containment>, FlintError> {
        self.batch(xs, false)
    }

    /// [`Self::contains_batch`] visiting the points sorted along a Hilbert curve (for the
    /// benchmark; same answers).
    #[doc(hidden)]
    pub fn contains_batch_hilbert(&self, xs: &[Point2]) -> Result<Vec<Containment>, FlintError> {
        self.batch(xs, true)
    }

    fn batch(&self, xs: &[Point2], hilbert: bool) -> Result<Vec<Containment>, FlintError> {
        if !self.closed {
            return Err(FlintError::NotClosed);
        }
        if xs.iter().any(|x| !(x.x.is_finite() && x.y.is_finite())) {
            return Err(FlintError::NonFiniteQuery);
        }
        let xs: Vec<[f64; 2]> = xs.iter().map(|x| [x.x, x.y]).collect();
        Ok(self.flat.locate_batch(&self.points, &xs, hilbert))
    }

    /// [`Self::contains`] and the number of pieces (nodes and leaf edges) the walk examined
    /// (0 outside the root disc): the measure compared with the baselines'
    /// [`super::BaselineTree::locate_counted`].
    pub fn locate_counted(&self, x: Point2) -> Result<(Containment, usize), FlintError> {
        if !self.closed {
            return Err(FlintError::NotClosed);
        }
        if !(x.x.is_finite() && x.y.is_finite()) {
            return Err(FlintError::NonFiniteQuery);
        }
        Ok(self.walk([x.x, x.y]))
    }

    /// The hierarchical walk on the flat layout (closed polygon, finite `x`; `locate.rs`).
    pub(crate) fn locate(&self, x: [f64; 2]) -> Containment {
        self.flat
            .locate(&self.points, x, &mut Vec::with_capacity(64))
    }

    /// The plain Lemma 6.1 walk over the flintstones alone (no box filter), counting visits.
    fn walk(&self, x: [f64; 2]) -> (Containment, usize) {
        let r = &self.root;
        // outside the root disc (with slack: the disc is constructed in f64) ⇒ outside
        let slack = 1e-12 * (r.radius + r.center[0].abs() + r.center[1].abs());
        if dist(x, r.center) > r.radius + slack {
            return (Containment::Outside, 0);
        }
        let n = self.len();
        let p = &self.points;
        let (mut inside, mut visits) = (false, 0);
        // (lo, hi, node): the polyline lo..=hi, node NONE for one edge
        let mut stack: Vec<(usize, usize, u32)> = Vec::with_capacity(64);
        let [i, j] = r.chord;
        stack.push((i, j, r.children[0]));
        stack.push((j, i + n, r.children[1]));
        while let Some((lo, hi, id)) = stack.pop() {
            visits += 1;
            let (a, b) = (at(p, lo), at(p, hi));
            if id == NONE {
                if on_edge(a, b, x) {
                    return (Containment::Boundary, visits);
                }
                inside ^= crosses(a, b, x);
                continue;
            }
            let nd = &self.nodes[id as usize];
            let convex = matches!(
                nd.stone.kind,
                super::StoneKind::Cap | super::StoneKind::Intersection | super::StoneKind::Segment
            );
            if convex && !nd.stone.contains(p, x) {
                inside ^= crosses(a, b, x);
                continue;
            }
            stack.push((nd.vertex, hi, nd.children[1]));
            stack.push((lo, nd.vertex, nd.children[0]));
        }
        let c = if inside {
            Containment::Inside
        } else {
            Containment::Outside
        };
        (c, visits)
    }
}

/// One meeting of an edge of A with an edge of B.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Crossing {
    /// Input index of the first vertex of A's edge (the edge joins it to the next).
    pub a: usize,
    /// Input index of the first vertex of B's edge.
    pub b: usize,
    /// A common point: the crossing for a proper crossing (constructed in `f64`), else an end
    /// point that lies on the other edge (an input vertex, exact).
    pub point: [f64; 2],
    /// For two collinear edges that overlap in a segment of positive length: its other end
    /// (an input vertex; the overlap is `point`–`overlap`). `None` for a single common point.
    pub overlap: Option<[f64; 2]>,
}

/// What the intersection descent did, against the `edges_a × edges_b` pairs of brute force.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct IntersectStats {
    /// Pairs of pieces (node subtrees or edges) whose filter was evaluated.
    pub pairs_visited: usize,
    /// Pairs that passed the filter and were opened or tested exactly.
    pub pairs_passed: usize,
    /// Edge–edge pairs tested exactly at the leaves.
    pub leaf_tests: usize,
    /// The edge pairs brute force tests (`edges(A) · edges(B)`).
    pub brute_pairs: usize,
}

/// The meeting of two edges that intersect (exact decisions): the common point, and for a
/// collinear overlap of positive length its other end. The ends of an overlap are the end
/// points of either edge that lie on the other (at most two distinct ones).
fn meeting(a0: [f64; 2], a1: [f64; 2], b0: [f64; 2], b1: [f64; 2]) -> ([f64; 2], Option<[f64; 2]>) {
    let p = meet_point(a0, a1, b0, b1);
    if orient2d(a0, a1, b0) != 0.0 || orient2d(a0, a1, b1) != 0.0 {
        return (p, None);
    }
    let other = [
        (a0, (b0, b1)),
        (a1, (b0, b1)),
        (b0, (a0, a1)),
        (b1, (a0, a1)),
    ]
    .into_iter()
    .find(|&(q, (u, v))| q != p && on_edge(u, v, q))
    .map(|(q, _)| q);
    (p, other)
}

fn meet_point(a0: [f64; 2], a1: [f64; 2], b0: [f64; 2], b1: [f64; 2]) -> [f64; 2] {
    if segments_cross_properly(a0, a1, b0, b1) {
        let (d1, d2) = (
            [a1[0] - a0[0], a1[1] - a0[1]],
            [b1[0] - b0[0], b1[1] - b0[1]],
        );
        let den = d1[0] * d2[1] - d1[1] * d2[0];
        let s = ((b0[0] - a0[0]) * d2[1] - (b0[1] - a0[1]) * d2[0]) / den;
        return [a0[0] + s * d1[0], a0[1] + s * d1[1]];
    }
    for (q, (u, v)) in [
        (a0, (b0, b1)),
        (a1, (b0, b1)),
        (b0, (a0, a1)),
        (b1, (a0, a1)),
    ] {
        if on_edge(u, v, q) {
            return q;
        }
    }
    a0
}

/// Edges of a tree: (first vertex index, a, b).
fn edges_of(t: &FlintTree2) -> impl Iterator<Item = (usize, [f64; 2], [f64; 2])> + '_ {
    let n = t.len();
    let m = if t.closed { n } else { n - 1 };
    (0..m).map(move |i| (i, t.points[i], t.points[(i + 1) % n]))
}

/// All meetings of the boundaries of `a` and `b` by testing every edge pair (the oracle),
/// sorted by `(a, b)`.
pub fn intersect_brute(a: &FlintTree2, b: &FlintTree2) -> Vec<Crossing> {
    let mut out = Vec::new();
    for (i, a0, a1) in edges_of(a) {
        for (k, b0, b1) in edges_of(b) {
            if segments_intersect(a0, a1, b0, b1) {
                let (point, overlap) = meeting(a0, a1, b0, b1);
                out.push(Crossing {
                    a: i,
                    b: k,
                    point,
                    overlap,
                });
            }
        }
    }
    out
}

/// A piece of a tree in the intersection descent.
#[derive(Clone, Copy)]
struct Piece {
    lo: usize,
    hi: usize,
    node: u32,
}

/// The top pieces (one or two) of a tree.
pub(crate) fn tops(t: &FlintTree2) -> Vec<(usize, usize, u32)> {
    let [i, j] = t.root.chord;
    let mut v = vec![(i, j, t.root.children[0])];
    if t.closed {
        v.push((j, i + t.len(), t.root.children[1]));
    }
    v
}

/// Conservative discs of a piece: for an edge, the disc about its midpoint; for a node, its
/// flintstone's filter discs (the side discs of ∩ and caps, which may be huge or — for a vertex
/// a subnormal distance off the chord — infinite) and always the hull disc about the chord
/// midpoint, which is finite and about half the chord wide: two nearly flat pieces side by side
/// are told apart by their hulls, not by their side discs.
fn discs(t: &FlintTree2, pc: Piece) -> smallvec::SmallVec<[([f64; 2], f64); 3]> {
    if pc.node == NONE {
        let (a, b) = (at(&t.points, pc.lo), at(&t.points, pc.hi));
        let m = crate::geom::vec::midpoint(a, b);
        let r = dist(m, a).max(dist(m, b));
        smallvec::smallvec![(m, r)]
    } else {
        let stone = &t.nodes[pc.node as usize].stone;
        let mut v: smallvec::SmallVec<[([f64; 2], f64); 3]> = stone
            .filter_discs()
            .into_iter()
            .filter(|(c, r)| c[0].is_finite() && c[1].is_finite() && r.is_finite())
            .collect();
        if !v.contains(&stone.hull) {
            v.push(stone.hull);
        }
        v
    }
}

/// May two pieces meet? (every disc of one meets every disc of the other)
fn may_meet(ta: &FlintTree2, pa: Piece, tb: &FlintTree2, pb: Piece) -> bool {
    let (da, db) = (discs(ta, pa), discs(tb, pb));
    da.iter().all(|&x| db.iter().all(|&y| discs_meet(x, y)))
}

fn children(t: &FlintTree2, pc: Piece) -> [Piece; 2] {
    let nd = &t.nodes[pc.node as usize];
    [
        Piece {
            lo: pc.lo,
            hi: nd.vertex,
            node: nd.children[0],
        },
        Piece {
            lo: nd.vertex,
            hi: pc.hi,
            node: nd.children[1],
        },
    ]
}

/// Every meeting of the boundaries of `a` and `b` (hierarchical; equal to [`intersect_brute`]),
/// sorted by `(a, b)`; with `first_only`, stops at the first one found (detection).
///
/// ```
/// use morpho::flint::{intersect, FlintTree2};
/// use morpho::geom::Point2;
/// let sq = |x: f64| [(x, 0.0), (x + 2.0, 0.0), (x + 2.0, 2.0), (x, 2.0)].map(|(x, y)| Point2::new(x, y));
/// let (a, b) = (FlintTree2::new(&sq(0.0), true).unwrap(), FlintTree2::new(&sq(2.0), true).unwrap());
/// let m = intersect(&a, &b, false);
/// // the shared side x = 2: one collinear overlap, and touchings at its two ends
/// assert!(m.iter().any(|c| c.overlap.is_some()));
/// assert!(m.iter().all(|c| c.point[0] == 2.0));
/// ```
pub fn intersect(a: &FlintTree2, b: &FlintTree2, first_only: bool) -> Vec<Crossing> {
    intersect_counted(a, b, first_only).0
}

/// [`intersect`] with the counts of what the descent visited.
pub fn intersect_counted(
    a: &FlintTree2,
    b: &FlintTree2,
    first_only: bool,
) -> (Vec<Crossing>, IntersectStats) {
    let edges = |t: &FlintTree2| t.len() - usize::from(!t.closed);
    let mut st = IntersectStats {
        brute_pairs: edges(a) * edges(b),
        ..Default::default()
    };
    let root_a = (a.root.center, a.root.radius);
    let root_b = (b.root.center, b.root.radius);
    let mut out = Vec::new();
    st.pairs_visited += 1;
    if !discs_meet(root_a, root_b) {
        return (out, st);
    }
    st.pairs_passed += 1;
    let mut stack: Vec<(Piece, Piece)> = Vec::new();
    for &(lo, hi, node) in &tops(a) {
        for &(lo2, hi2, node2) in &tops(b) {
            stack.push((
                Piece { lo, hi, node },
                Piece {
                    lo: lo2,
                    hi: hi2,
                    node: node2,
                },
            ));
        }
    }
    while let Some((pa, pb)) = stack.pop() {
        st.pairs_visited += 1;
        if !may_meet(a, pa, b, pb) {
            continue;
        }
        st.pairs_passed += 1;
        if pa.node == NONE && pb.node == NONE {
            let (a0, a1) = (at(&a.points, pa.lo), at(&a.points, pa.hi));
            let (b0, b1) = (at(&b.points, pb.lo), at(&b.points, pb.hi));
            st.leaf_tests += 1;
            if segments_intersect(a0, a1, b0, b1) {
                let (point, overlap) = meeting(a0, a1, b0, b1);
                out.push(Crossing {
                    a: pa.lo % a.len(),
                    b: pb.lo % b.len(),
                    point,
                    overlap,
                });
                if first_only {
                    break;
                }
            }
            continue;
        }
        let open_a = pb.node == NONE || (pa.node != NONE && pa.hi - pa.lo >= pb.hi - pb.lo);
        if open_a {
            for c in children(a, pa) {
                stack.push((c, pb));
            }
        } else {
            for c in children(b, pb) {
                stack.push((pa, c));
            }
        }
    }
    out.sort_by_key(|c| (c.a, c.b));
    (out, st)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The pieces from the top down to the edge starting at position `e` (unwrapped).
    fn path(t: &FlintTree2, e: usize) -> Vec<Piece> {
        let n = t.len();
        let mut out = Vec::new();
        for (lo, hi, node) in tops(t) {
            // the edge (e, e+1) lies in lo..=hi for e or e + n
            let Some(e) = [e, e + n].into_iter().find(|&x| lo <= x && x < hi) else {
                continue;
            };
            let mut pc = Piece { lo, hi, node };
            out.push(pc);
            while pc.node != NONE {
                let [l, r] = children(t, pc);
                pc = if e < l.hi { l } else { r };
                out.push(pc);
            }
            assert_eq!((pc.lo, pc.hi), (e, e + 1));
        }
        out
    }

    /// Property (notes A.8): whenever two edges meet, every pair of their ancestors passes the
    /// disc filter (so the descent has no false negative).
    #[test]
    fn every_ancestor_pair_of_meeting_edges_passes_the_filter() {
        let mut rng = crate::util::Rng::new(0x2545_f491_4f6c_dd1d);
        let mut unit = move || rng.unit();
        let mut checked = 0;
        for round in 0..40 {
            let mk = |unit: &mut dyn FnMut() -> f64, n: usize, dx: f64| {
                let mut a: Vec<f64> = (0..n).map(|_| unit() * std::f64::consts::TAU).collect();
                a.sort_by(f64::total_cmp);
                a.iter()
                    .map(|&t| {
                        let r = 0.3 + unit();
                        Point2::new(r * t.cos() + dx, r * t.sin())
                    })
                    .collect::<Vec<_>>()
            };
            let a = mk(&mut unit, 20 + round, 0.0);
            let b = mk(&mut unit, 25 + round, 0.4);
            let (Ok(ta), Ok(tb)) = (FlintTree2::new(&a, true), FlintTree2::new(&b, true)) else {
                continue;
            };
            for c in intersect_brute(&ta, &tb) {
                let (pa, pb) = (path(&ta, c.a), path(&tb, c.b));
                assert!(!pa.is_empty() && !pb.is_empty());
                for &x in &pa {
                    for &y in &pb {
                        assert!(may_meet(&ta, x, &tb, y));
                        checked += 1;
                    }
                }
            }
        }
        assert!(checked > 1000, "{checked}");
    }

    /// A vertex a subnormal distance off its chord puts the side disc's centre at infinity
    /// (`t = (…)/2h` overflows, and `∞ · 0` makes a coordinate NaN): such a disc says nothing
    /// and must never reject a pair. Before the fix, two such discs (or one NaN centre) gave a
    /// NaN distance and the pair was dropped — crossings of the upsampled Great Britain coast
    /// with a turned copy were missed this way (9 of 556).
    #[test]
    fn discs_at_infinity_never_hide_a_meeting() {
        let p = |v: &[(f64, f64)]| {
            v.iter()
                .map(|&(x, y)| Point2::new(x, y))
                .collect::<Vec<_>>()
        };
        for tiny in [1e-320, 5e-324, 1e-310, -1e-320] {
            // A's bottom side is bent by `tiny` at x = 0.5 and x = 1.5
            let a = p(&[
                (0.0, 0.0),
                (0.5, tiny),
                (1.0, 0.0),
                (1.5, tiny),
                (2.0, 0.0),
                (2.0, 2.0),
                (0.0, 2.0),
            ]);
            // B crosses that side, its own bottom bent the same way
            for dx in [0.0, 0.3, 0.7, 1.1] {
                let b = p(&[
                    (dx + 0.2, -1.0),
                    (dx + 0.6, 1.0 + tiny),
                    (dx + 0.8, 1.0),
                    (dx + 0.9, 1.0 + tiny),
                    (dx + 1.0, 1.0),
                    (dx + 0.7, -1.0),
                ]);
                let (ta, tb) = (
                    FlintTree2::new(&a, true).unwrap(),
                    FlintTree2::new(&b, true).unwrap(),
                );
                let key = |v: Vec<Crossing>| v.into_iter().map(|c| (c.a, c.b)).collect::<Vec<_>>();
                let brute = key(intersect_brute(&ta, &tb));
                assert!(!brute.is_empty());
                assert_eq!(
                    key(intersect(&ta, &tb, false)),
                    brute,
                    "tiny {tiny:e}, dx {dx}"
                );
                assert_eq!(key(intersect(&tb, &ta, false)).len(), brute.len());
            }
        }
        // two discs whose centres are infinite in opposite directions
        let inf = ([f64::INFINITY, -f64::INFINITY], f64::INFINITY);
        let nan = ([f64::NAN, f64::NEG_INFINITY], f64::INFINITY);
        assert!(discs_meet(
            inf,
            ([f64::NEG_INFINITY, -f64::INFINITY], f64::INFINITY)
        ));
        assert!(discs_meet(nan, ([0.0, 0.0], 1.0)));
        assert!(discs_meet(([0.0, 0.0], 1.0), nan));
    }
}
