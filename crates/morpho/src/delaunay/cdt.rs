//! 2D constrained Delaunay triangulation (CDT), exact on every input, and the triangulation of
//! the interior of a simple polygon of any size.
//!
//! Size (over 800 lines): one algorithm (cavity insertion of segments) and its use for polygon
//! interiors; about 120 lines are unit tests.
//!
//! # What it computes
//! [`Cdt2`] starts from a [`Delaunay2`] and inserts constraint segments (pairs of vertices).
//! The result is the constrained Delaunay triangulation (Chew 1989; Shewchuk & Brown 2015):
//! every constraint is a union of triangulation edges, and every triangle's circumcircle
//! contains no vertex that is visible from the triangle's interior, where constraints block
//! visibility — equivalently, every non-constrained edge is locally Delaunay. It extends the
//! Delaunay triangulation of Veltkamp 1992, §2.2.9 (Def. 2.11) and Dorgerloh et al. §2, Property
//! 1, by edges that must be present, as the constrained constriction of Veltkamp §5.7 needs
//! them (edges known to lie on the boundary). [`triangulate_polygon_interior`] gives the region
//! a boundary polygon encloses as `n − 2` triangles.
//!
//! # Algorithm
//! Each segment `a b` is inserted by the cavity method (Anglada 1997; Shewchuk & Brown 2015,
//! §3): starting from `a`, the triangle around `a` whose wedge contains the direction of `b` is
//! found with exact `orient2d`; the walk then visits every triangle the open segment crosses,
//! collecting the vertices left and right of `a b` into two chains; those triangles are deleted
//! and each of the two pseudo-polygons (the segment plus one chain) is re-triangulated by
//! recursively choosing, for a base edge, the chain vertex whose circle through the base edge
//! contains no other chain vertex (exact, symbolically perturbed in-circle test
//! [`crate::delaunay::d2::incircle_sos`], so ties are broken as in the unconstrained
//! triangulation). The recursion is an explicit stack (no deep call chains). The cavity need not
//! be a simple polygon: an uncrossed edge can hang into it with deleted triangles on both sides
//! (a "slit"; its far vertex then lies inside the new triangle fan); the chain lists such a
//! vertex twice, the empty-circle choice never takes a triangle containing it, and the two new
//! triangles that receive the slit's two sides are linked to each other.
//!
//! Cases:
//! - the segment is already an edge: it is only flagged as constrained;
//! - duplicate segments and segments overlapping earlier ones are merged the same way;
//! - a segment through another vertex `v` (exactly, by `orient2d == 0`) is split at `v`: both
//!   parts are inserted (counted in [`Cdt2::splits`]); no new points are ever created;
//! - a segment crossing an earlier constraint is a [`DelaunayError::CrossingSegments`] naming both segments
//!   (no Steiner points are invented);
//! - a segment whose two ends are the same vertex (also: two duplicate input points) is
//!   skipped and counted in [`Cdt2::skipped`].
//!
//! Inside/outside of constraint cycles is found by a 0-1 breadth-first search from the hull
//! ([`Cdt2::depths`]): the depth of a triangle is the least number of constraints crossed on a
//! path from outside the hull; odd depth = inside (nested polygons and holes included).
//!
//! # Complexity
//! Inserting a segment that crosses `k` triangles takes O(k) for the walk and O(k log k)
//! expected (O(k²) worst case) for the re-triangulation; finding the first triangle costs the
//! degree of `a`. [`triangulate_polygon_interior`] costs the Delaunay triangulation of the
//! polygon vertices (O(n log n) expected) plus the insertion of its `n` edges, i.e. the number
//! `K` of Delaunay triangles they cross: `K = O(n)` when most polygon edges are (nearly)
//! Delaunay edges, as for sampled curves and the boundaries of [`crate::boundary`], and
//! measured 3–4 × the Delaunay time for a random star-shaped polygon of 10⁶ vertices
//! (`examples/bench_cdt.rs`); adversarial polygons (combs of long parallel edges) can make
//! `K` quadratic.
//!
//! # Preconditions
//! Those of [`crate::delaunay::d2::triangulate`] (finite coordinates in the exact range). For
//! collinear input (no triangles) constraints are validated but there is nothing to triangulate.

use super::DelaunayError;
use crate::delaunay::d2::{triangulate, Delaunay2};
use crate::geom::Point2;
use crate::util::NONE;
use std::collections::VecDeque;

type Result<T, E = DelaunayError> = std::result::Result<T, E>;

/// A constrained Delaunay triangulation (see the module documentation).
#[derive(Debug, Clone)]
pub struct Cdt2 {
    /// The underlying Delaunay triangulation; its `triangles`, `neighbors` and `vertex_tri` were
    /// moved into the `Cdt2` (they are empty here), points, vertex maps and hull are unchanged.
    base: Delaunay2,
    /// Counter-clockwise triangles (vertex indices).
    pub triangles: Vec<[u32; 3]>,
    /// `neighbors[t][i]` is the triangle across the edge opposite corner `i`, or [`NONE`].
    pub neighbors: Vec<[u32; 3]>,
    /// Bit `i` of `constrained[t]` is set when the edge opposite corner `i` of `t` is (part of)
    /// a constraint.
    pub constrained: Vec<u8>,
    /// One incident triangle per vertex ([`NONE`] when there are no triangles).
    vertex_tri: Vec<u32>,
    /// The segments inserted so far (vertex pairs as given) with their labels (the caller's
    /// names for them, used in error messages).
    segs: Vec<([u32; 2], [u32; 2])>,
    /// Number of times a segment was split at a vertex lying exactly on it.
    pub splits: usize,
    /// Number of zero-length segments skipped (both ends the same vertex).
    pub skipped: usize,
    /// Number of triangles deleted and re-created by segment insertions (the sum of the
    /// cavity sizes; a measure of the insertion work).
    pub retriangulated: usize,
}

/// The first step of a segment from its start vertex.
enum Step {
    /// The segment runs along the edge opposite `corner` of `tri` to vertex `to` (which is the
    /// segment's end or lies on it).
    Edge { tri: u32, corner: usize, to: u32 },
    /// The segment enters triangle `tri` (start vertex at `corner`) and crosses the opposite
    /// edge.
    Cross { tri: u32, corner: usize },
}

/// A cavity boundary edge: the triangle outside the cavity (or [`NONE`] on the hull) and whether
/// the edge is constrained.
#[derive(Clone, Copy)]
struct Ext {
    tri: u32,
    flag: bool,
}

impl Cdt2 {
    /// A CDT without constraints (the Delaunay triangulation itself), to insert constraints
    /// into step by step ([`Cdt2::insert_input_segments`], [`Cdt2::insert_segment`]). O(1).
    ///
    /// ```rust
    /// use morpho::delaunay::{triangulate_2d, Cdt2};
    /// use morpho::geom::Point2;
    /// let p = [[0., 0.], [2., 0.], [2., 2.], [0., 2.]].map(|[x, y]| Point2::new(x, y));
    /// let mut c = Cdt2::new(triangulate_2d(&p).unwrap());
    /// c.insert_input_segments(&[[0, 2]]).unwrap();
    /// // a second, crossing diagonal is refused; the CDT keeps the first
    /// assert!(c.insert_input_segments(&[[1, 3]]).is_err());
    /// assert_eq!(c.constrained_edges().len(), 1);
    /// ```
    pub fn new(mut d: Delaunay2) -> Cdt2 {
        let triangles = std::mem::take(&mut d.triangles);
        let neighbors = std::mem::take(&mut d.neighbors);
        let vertex_tri = std::mem::take(&mut d.vertex_tri);
        let nt = triangles.len();
        Cdt2 {
            base: d,
            triangles,
            neighbors,
            constrained: vec![0; nt],
            vertex_tri,
            segs: Vec::new(),
            splits: 0,
            skipped: 0,
            retriangulated: 0,
        }
    }

    /// Inserts segments given as pairs of input indices (see [`triangulate_constrained_2d`]);
    /// error messages name a segment by its position in `segments` and its input indices.
    pub fn insert_input_segments(&mut self, segments: &[[u32; 2]]) -> Result<()> {
        let n_in = self.base.vertex_of_input.len();
        for (k, &[i, j]) in segments.iter().enumerate() {
            if i as usize >= n_in || j as usize >= n_in {
                return Err(DelaunayError::SegmentOutOfRange {
                    segment: k,
                    ends: [i, j],
                    points: n_in,
                });
            }
            let (a, b) = (
                self.base.vertex_of_input[i as usize],
                self.base.vertex_of_input[j as usize],
            );
            self.insert_labeled(a, b, k as u32, [i, j])?;
        }
        Ok(())
    }

    /// Inserts the segment between vertices `a` and `b` (vertex indices of [`Cdt2::points`]).
    ///
    /// Errors: a vertex index out of range, or the segment crosses an earlier one (the error
    /// names both; segments are numbered in insertion order). After an error the triangulation
    /// is still a valid CDT of the constraints inserted before, possibly plus the part of the
    /// failing segment up to the last vertex it passed through before the crossing.
    pub fn insert_segment(&mut self, a: u32, b: u32) -> Result<()> {
        let n = self.base.points.len();
        if a as usize >= n || b as usize >= n {
            return Err(DelaunayError::VertexOutOfRange {
                ends: [a, b],
                vertices: n,
            });
        }
        let k = self.segs.len() as u32;
        let ia = self.base.input_of_vertex[a as usize];
        let ib = self.base.input_of_vertex[b as usize];
        self.insert_labeled(a, b, k, [ia, ib])
    }

    /// The vertices (distinct input points, in the order of the underlying [`Delaunay2`]).
    pub fn points(&self) -> &[Point2] {
        &self.base.points
    }

    /// For every input index, its vertex.
    pub fn vertex_of_input(&self) -> &[u32] {
        &self.base.vertex_of_input
    }

    /// For every vertex, the smallest input index at its position.
    pub fn input_of_vertex(&self) -> &[u32] {
        &self.base.input_of_vertex
    }

    /// The convex hull cycle (as [`Delaunay2::hull`]).
    pub fn hull(&self) -> &[u32] {
        &self.base.hull
    }

    /// True when all points are collinear (no triangles).
    pub fn collinear(&self) -> bool {
        self.base.collinear
    }

    /// Number of merged duplicate input points.
    pub fn duplicates(&self) -> usize {
        self.base.duplicates
    }

    /// Is the edge opposite corner `i` of triangle `t` constrained?
    #[inline]
    pub fn is_constrained(&self, t: u32, i: usize) -> bool {
        self.constrained[t as usize] >> i & 1 == 1
    }

    /// Every undirected edge once, with its constrained flag.
    pub fn edges(&self) -> Vec<([u32; 2], bool)> {
        let mut e = Vec::with_capacity(self.triangles.len() * 3 / 2 + 2);
        for (t, tri) in self.triangles.iter().enumerate() {
            for i in 0..3 {
                let nb = self.neighbors[t][i];
                if nb == NONE || nb as usize > t {
                    e.push((
                        [tri[(i + 1) % 3], tri[(i + 2) % 3]],
                        self.is_constrained(t as u32, i),
                    ));
                }
            }
        }
        e
    }

    /// The constrained edges (vertex pairs), each once.
    pub fn constrained_edges(&self) -> Vec<[u32; 2]> {
        self.edges()
            .into_iter()
            .filter(|e| e.1)
            .map(|e| e.0)
            .collect()
    }

    /// The triangles in input indices (each vertex replaced by its first input index).
    pub fn to_input_indices(&self) -> Vec<[u32; 3]> {
        self.triangles
            .iter()
            .map(|t| t.map(|v| self.base.input_of_vertex[v as usize]))
            .collect()
    }

    /// Exact orientation sign of three vertices (as [`Delaunay2::orient`]).
    #[inline]
    pub fn orient(&self, a: u32, b: u32, c: u32) -> f64 {
        self.base.orient(a, b, c)
    }

    /// For every triangle, the least number of constrained edges crossed by a path from outside
    /// the convex hull to it (0-1 breadth-first search). Odd depth = inside the constraint
    /// cycles (holes of polygons have even depth). O(n).
    ///
    /// ```rust
    /// use morpho::delaunay::triangulate_constrained_2d;
    /// use morpho::geom::Point2;
    /// // a diamond constraint cycle inside a square: its two triangles have depth 1
    /// let p = [[0., 0.], [4., 0.], [4., 4.], [0., 4.], [2., 1.], [3., 2.], [2., 3.], [1., 2.]]
    ///     .map(|[x, y]| Point2::new(x, y));
    /// let c = triangulate_constrained_2d(&p, &[[4, 5], [5, 6], [6, 7], [7, 4]]).unwrap();
    /// let inside = c.depths().iter().filter(|&&d| d % 2 == 1).count();
    /// assert_eq!(inside, 2);
    /// ```
    pub fn depths(&self) -> Vec<u32> {
        let nt = self.triangles.len();
        let mut depth = vec![u32::MAX; nt];
        let mut q: VecDeque<(u32, u32)> = VecDeque::new();
        for t in 0..nt {
            for i in 0..3 {
                if self.neighbors[t][i] == NONE {
                    let d = self.is_constrained(t as u32, i) as u32;
                    if d < depth[t] {
                        depth[t] = d;
                        if d == 0 {
                            q.push_front((t as u32, d));
                        } else {
                            q.push_back((t as u32, d));
                        }
                    }
                }
            }
        }
        while let Some((t, d)) = q.pop_front() {
            if depth[t as usize] != d {
                continue;
            }
            for i in 0..3 {
                let nb = self.neighbors[t as usize][i];
                if nb == NONE {
                    continue;
                }
                let w = self.is_constrained(t, i) as u32;
                let nd = d + w;
                if nd < depth[nb as usize] {
                    depth[nb as usize] = nd;
                    if w == 0 {
                        q.push_front((nb, nd));
                    } else {
                        q.push_back((nb, nd));
                    }
                }
            }
        }
        depth
    }

    /// Sets the constrained flag of the edge opposite `corner` of `t` on both sides.
    fn mark(&mut self, t: u32, corner: usize) {
        self.constrained[t as usize] |= 1 << corner;
        let nb = self.neighbors[t as usize][corner];
        if nb != NONE {
            let tri = self.triangles[t as usize];
            let (p, q) = (tri[(corner + 1) % 3], tri[(corner + 2) % 3]);
            let j = opposite_corner(&self.triangles[nb as usize], p, q);
            self.constrained[nb as usize] |= 1 << j;
        }
    }

    /// Does vertex `x` lie strictly inside the segment `a b` (exact)?
    fn strictly_between(&self, a: u32, b: u32, x: u32) -> bool {
        if x == a || x == b || self.orient(a, b, x) != 0.0 {
            return false;
        }
        let p = &self.base.points;
        let (pa, pb, px) = (p[a as usize], p[b as usize], p[x as usize]);
        px.x >= pa.x.min(pb.x)
            && px.x <= pa.x.max(pb.x)
            && px.y >= pa.y.min(pb.y)
            && px.y <= pa.y.max(pb.y)
    }

    /// Finds how the segment `a → b` leaves `a` (rotating around `a` both ways from its
    /// triangle, so hull vertices work too).
    fn first_step(&self, a: u32, b: u32) -> Result<Step> {
        let t0 = self.vertex_tri[a as usize];
        if t0 == NONE {
            return Err(lost());
        }
        let mut t = t0;
        let mut ccw = true;
        let mut budget = self.triangles.len() + 4;
        loop {
            if budget == 0 {
                return Err(lost());
            }
            budget -= 1;
            let tri = self.triangles[t as usize];
            let i = tri.iter().position(|&v| v == a).ok_or_else(lost)?;
            let (x, y) = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
            // edge a-x is opposite corner i+2, edge a-y opposite corner i+1
            if x == b || self.strictly_between(a, b, x) {
                return Ok(Step::Edge {
                    tri: t,
                    corner: (i + 2) % 3,
                    to: x,
                });
            }
            if y == b || self.strictly_between(a, b, y) {
                return Ok(Step::Edge {
                    tri: t,
                    corner: (i + 1) % 3,
                    to: y,
                });
            }
            if self.orient(a, x, b) > 0.0 && self.orient(a, y, b) < 0.0 {
                return Ok(Step::Cross { tri: t, corner: i });
            }
            let n = if ccw {
                self.neighbors[t as usize][(i + 1) % 3]
            } else {
                self.neighbors[t as usize][(i + 2) % 3]
            };
            if n == NONE {
                if !ccw {
                    return Err(lost());
                }
                ccw = false;
                t = t0;
                continue;
            }
            if n == t0 {
                return Err(lost());
            }
            t = n;
        }
    }

    fn insert_labeled(&mut self, a: u32, b: u32, k: u32, label: [u32; 2]) -> Result<()> {
        if a == b {
            self.skipped += 1;
            return Ok(());
        }
        if self.base.collinear || self.triangles.is_empty() {
            self.segs.push(([a, b], label));
            return Ok(());
        }
        let mut cur = a;
        let mut budget = self.base.points.len() + 2;
        while cur != b {
            if budget == 0 {
                return Err(lost());
            }
            budget -= 1;
            let next = match self.first_step(cur, b)? {
                Step::Edge { tri, corner, to } => {
                    self.mark(tri, corner);
                    to
                }
                Step::Cross { tri, corner } => self.dig(cur, b, tri, corner, k, label)?,
            };
            if next != b {
                self.splits += 1;
            }
            cur = next;
        }
        self.segs.push(([a, b], label));
        Ok(())
    }

    /// The error for a segment crossing the constrained edge `l r`.
    fn crossing_error(&self, l: u32, r: u32, k: u32, label: [u32; 2]) -> DelaunayError {
        let other = self
            .segs
            .iter()
            .enumerate()
            .find(|(_, (s, _))| {
                let on = |v: u32| v == s[0] || v == s[1] || self.strictly_between(s[0], s[1], v);
                on(l) && on(r)
            })
            .map(|(j, (_, lab))| (j, *lab));
        match other {
            Some((j, lab)) => DelaunayError::CrossingSegments {
                first: j as u32,
                first_ends: lab,
                second: k,
                second_ends: label,
            },
            None => DelaunayError::CrossesConstraint {
                segment: k,
                ends: label,
            },
        }
    }

    /// Inserts the part of `a → b` that starts by crossing the edge opposite `corner` of `t0`,
    /// up to `b` or the first vertex exactly on the segment; returns that vertex.
    fn dig(
        &mut self,
        a: u32,
        b: u32,
        t0: u32,
        corner: usize,
        k: u32,
        label: [u32; 2],
    ) -> Result<u32> {
        let tri = self.triangles[t0 as usize];
        let i = corner;
        let (x, y) = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
        let ext = |s: &Self, t: u32, c: usize| Ext {
            tri: s.neighbors[t as usize][c],
            flag: s.is_constrained(t, c),
        };
        // chains from a: left (y side) and right (x side)
        let mut left = vec![a, y];
        let mut left_ext = vec![ext(self, t0, (i + 1) % 3)];
        let mut right = vec![a, x];
        let mut right_ext = vec![ext(self, t0, (i + 2) % 3)];
        let mut dead = vec![t0];
        let (mut l, mut r) = (y, x);
        let mut cur = t0;
        let mut cc = i;
        let mut budget = self.triangles.len() + 2;
        let end = loop {
            if budget == 0 {
                return Err(lost());
            }
            budget -= 1;
            if self.is_constrained(cur, cc) {
                return Err(self.crossing_error(l, r, k, label));
            }
            let u = self.neighbors[cur as usize][cc];
            if u == NONE {
                return Err(lost());
            }
            let tu = self.triangles[u as usize];
            let jl = tu.iter().position(|&w| w == l).ok_or_else(lost)?;
            let jr = tu.iter().position(|&w| w == r).ok_or_else(lost)?;
            let jv = 3 - jl - jr;
            let v = tu[jv];
            dead.push(u);
            let o = if v == b { 0.0 } else { self.orient(a, b, v) };
            if o == 0.0 {
                left.push(v);
                left_ext.push(ext(self, u, jr));
                right.push(v);
                right_ext.push(ext(self, u, jl));
                break v;
            }
            if o > 0.0 {
                left.push(v);
                left_ext.push(ext(self, u, jr));
                l = v;
                cc = jl;
            } else {
                right.push(v);
                right_ext.push(ext(self, u, jl));
                r = v;
                cc = jr;
            }
            cur = u;
        };
        // the pseudo-polygons: base a → end with the left chain on its left; base end → a with
        // the (reversed) right chain on its left
        right.reverse();
        right_ext.reverse();
        // A chain edge can have deleted triangles on both sides (an edge of the cavity that the
        // segment does not cross, hanging into it from one chain): such "slit" edges are linked
        // between the two new triangles that receive its two sides.
        self.retriangulated += dead.len();
        let mut dead_sorted = dead.clone();
        dead_sorted.sort_unstable();
        let mut slots = dead;
        let mut slit = Vec::new();
        let top_l = self.fill(&left, &left_ext, &mut slots, &dead_sorted, &mut slit)?;
        let top_r = self.fill(&right, &right_ext, &mut slots, &dead_sorted, &mut slit)?;
        if !slots.is_empty() || slit.len() % 2 != 0 {
            return Err(lost());
        }
        slit.sort_unstable();
        for w in slit.chunks_exact(2) {
            let ((e0, t0, c0), (e1, t1, c1)) = (w[0], w[1]);
            if e0 != e1 {
                return Err(lost());
            }
            self.neighbors[t0 as usize][c0] = t1;
            self.neighbors[t1 as usize][c1] = t0;
        }
        // both tops have their base edge opposite corner 2
        self.neighbors[top_l as usize][2] = top_r;
        self.neighbors[top_r as usize][2] = top_l;
        self.constrained[top_l as usize] |= 1 << 2;
        self.constrained[top_r as usize] |= 1 << 2;
        Ok(end)
    }

    /// Triangulates the pseudo-polygon `c[0] → c[last]` (base) with the chain `c[1..last]` on
    /// its left; `ext[k]` is the outside of the polygon edge `c[k] c[k+1]`. Uses the triangle
    /// slots in `slots`; returns the triangle on the base edge (base opposite corner 2).
    /// Chain edges whose outside is a deleted triangle (listed in `dead`, sorted) are added to
    /// `slit` as (undirected edge, new triangle, corner) for the caller to pair.
    fn fill(
        &mut self,
        c: &[u32],
        ext: &[Ext],
        slots: &mut Vec<u32>,
        dead: &[u32],
        slit: &mut Vec<([u32; 2], u32, usize)>,
    ) -> Result<u32> {
        let last = c.len() - 1;
        if last < 2 {
            return Err(lost());
        }
        let mut top = NONE;
        // (lo, hi, parent triangle, parent corner)
        let mut stack: Vec<(usize, usize, u32, usize)> = vec![(0, last, NONE, 0)];
        while let Some((lo, hi, pt, pc)) = stack.pop() {
            if hi == lo + 1 {
                let e = ext[lo];
                self.neighbors[pt as usize][pc] = e.tri;
                if e.flag {
                    self.constrained[pt as usize] |= 1 << pc;
                }
                if e.tri != NONE && dead.binary_search(&e.tri).is_ok() {
                    let (p, q) = (c[lo], c[hi]);
                    slit.push(([p.min(q), p.max(q)], pt, pc));
                } else if e.tri != NONE {
                    let j = opposite_corner(&self.triangles[e.tri as usize], c[lo], c[hi]);
                    self.neighbors[e.tri as usize][j] = pt;
                }
                continue;
            }
            let (a, b) = (c[lo], c[hi]);
            // the empty-circle vertex; a repeated occurrence of a base vertex (possible with
            // slits) is never a candidate
            let mut m = NONE as usize;
            for v in lo + 1..hi {
                let w = c[v];
                if w == a || w == b {
                    continue;
                }
                if m == NONE as usize || self.base.incircle_sos(a, b, c[m], w) > 0 {
                    m = v;
                }
            }
            if m == NONE as usize {
                return Err(lost());
            }
            let t = slots.pop().ok_or_else(lost)?;
            let cm = c[m];
            if self.orient(a, b, cm) <= 0.0 {
                return Err(lost());
            }
            self.triangles[t as usize] = [a, b, cm];
            self.neighbors[t as usize] = [NONE; 3];
            self.constrained[t as usize] = 0;
            for v in [a, b, cm] {
                self.vertex_tri[v as usize] = t;
            }
            if pt == NONE {
                top = t;
            } else {
                self.neighbors[t as usize][2] = pt;
                self.neighbors[pt as usize][pc] = t;
            }
            // edge c[m] → a is opposite corner 1, edge b → c[m] opposite corner 0
            stack.push((lo, m, t, 1));
            stack.push((m, hi, t, 0));
        }
        Ok(top)
    }
}

/// The corner of `tri` that is neither `p` nor `q`.
#[inline]
fn opposite_corner(tri: &[u32; 3], p: u32, q: u32) -> usize {
    tri.iter().position(|&w| w != p && w != q).unwrap_or(0)
}

fn lost() -> DelaunayError {
    DelaunayError::Internal {
        what: "constrained Delaunay: inconsistent triangulation (internal error)",
    }
}

/// The constrained Delaunay triangulation of `points` with the constraint `segments` (pairs of
/// input indices) inserted in order (see the module documentation for the cases: a segment
/// through a vertex is split there, repeated and zero-length segments are merged or skipped).
///
/// Errors: those of [`triangulate`](crate::delaunay::triangulate_2d), a segment index out of
/// range ([`DelaunayError::SegmentOutOfRange`]), two crossing segments
/// ([`DelaunayError::CrossingSegments`]). Cost: the Delaunay triangulation plus O(k log k)
/// expected per segment crossing k triangles.
///
/// ```rust
/// use morpho::delaunay::triangulate_constrained_2d;
/// use morpho::geom::Point2;
/// // a square and a point below its diagonal 0–2: the unconstrained triangulation uses 1–3
/// let p = [[0., 0.], [2., 0.], [2., 2.], [0., 2.]].map(|[x, y]| Point2::new(x, y));
/// let c = triangulate_constrained_2d(&p, &[[1, 3]])?;
/// assert_eq!(c.triangles.len(), 2);
/// assert_eq!(c.constrained_edges().len(), 1);
/// // crossing constraints are refused, naming both
/// let e = triangulate_constrained_2d(&p, &[[0, 2], [1, 3]]).unwrap_err();
/// assert_eq!(e.to_string(), "constraint segments 0 (0, 2) and 1 (1, 3) cross");
/// # Ok::<(), morpho::delaunay::DelaunayError>(())
/// ```
pub fn triangulate_constrained_2d(points: &[Point2], segments: &[[u32; 2]]) -> Result<Cdt2> {
    let mut c = Cdt2::new(triangulate(points)?);
    c.insert_input_segments(segments)?;
    Ok(c)
}

/// Triangulates the interior of the simple polygon `cycle` (indices into `points`, either
/// orientation, first vertex not repeated): the constrained Delaunay triangulation of its
/// vertices with its edges as constraints, restricted to the inside. Returns `n − 2`
/// counter-clockwise triangles (indices into `points`).
///
/// Errors (the polygon is not simple): fewer than 3 vertices, an index out of range, a repeated
/// vertex (same index or same coordinates), all vertices collinear, two crossing edges, a
/// vertex lying on an edge; and the inputs of [`triangulate`]. Cost: see the module
/// documentation.
///
/// Facade name: [`triangulate_polygon_2d`](crate::delaunay::triangulate_polygon_2d).
///
/// ```rust
/// use morpho::delaunay::triangulate_polygon_2d as triangulate_polygon_interior;
/// use morpho::geom::Point2;
/// // an L-shaped hexagon, clockwise
/// let p: Vec<Point2> = [[0., 0.], [0., 2.], [1., 2.], [1., 1.], [2., 1.], [2., 0.]]
///     .iter().map(|q| Point2::new(q[0], q[1])).collect();
/// let t = triangulate_polygon_interior(&p, &[0, 1, 2, 3, 4, 5]).unwrap();
/// assert_eq!(t.len(), 4);
/// assert!(triangulate_polygon_interior(&p, &[0, 2, 1, 3, 4, 5]).is_err()); // not simple
/// ```
pub fn triangulate_polygon_interior(points: &[Point2], cycle: &[u32]) -> Result<Vec<[u32; 3]>> {
    let n = cycle.len();
    if n < 3 {
        return Err(DelaunayError::PolygonTooFewVertices {
            found: n,
            needed: 3,
        });
    }
    let mut local = Vec::with_capacity(n);
    for (k, &i) in cycle.iter().enumerate() {
        match points.get(i as usize) {
            Some(p) => local.push(*p),
            None => {
                return Err(DelaunayError::PolygonVertexOutOfRange {
                    vertex: k,
                    point: i,
                    points: points.len(),
                })
            }
        }
    }
    let d = triangulate(&local)?;
    if d.duplicates > 0 {
        let (k, _) = d
            .vertex_of_input
            .iter()
            .enumerate()
            .find(|(k, &v)| d.input_of_vertex[v as usize] as usize != *k)
            .unwrap_or((0, &0));
        return Err(DelaunayError::PolygonRepeatedVertex {
            vertex: k,
            point: cycle[k],
        });
    }
    if d.collinear {
        return Err(DelaunayError::PolygonCollinear);
    }
    let mut cdt = Cdt2::new(d);
    for k in 0..n {
        let k1 = (k + 1) % n;
        let (a, b) = (cdt.base.vertex_of_input[k], cdt.base.vertex_of_input[k1]);
        cdt.insert_labeled(a, b, k as u32, [cycle[k], cycle[k1]])
            .map_err(|e| DelaunayError::PolygonEdgesCross(Box::new(e)))?;
        if cdt.splits > 0 {
            return Err(DelaunayError::PolygonEdgeThroughVertex {
                edge: k,
                ends: [cycle[k], cycle[k1]],
            });
        }
    }
    let depth = cdt.depths();
    let out: Vec<[u32; 3]> = cdt
        .triangles
        .iter()
        .zip(&depth)
        .filter(|(_, &dp)| dp % 2 == 1)
        .map(|(t, _)| t.map(|v| cycle[cdt.base.input_of_vertex[v as usize] as usize]))
        .collect();
    if out.len() != n - 2 {
        return Err(DelaunayError::PolygonNotSimple {
            found: out.len(),
            expected: n - 2,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pts(v: &[[f64; 2]]) -> Vec<Point2> {
        v.iter().map(|p| Point2::new(p[0], p[1])).collect()
    }

    /// Structural invariants: counter-clockwise triangles, symmetric neighbours and flags,
    /// Euler relation, `vertex_tri` incident.
    fn check(c: &Cdt2) {
        let n = c.points().len();
        for (t, tri) in c.triangles.iter().enumerate() {
            assert!(
                c.orient(tri[0], tri[1], tri[2]) > 0.0,
                "triangle {t} is not CCW"
            );
            for i in 0..3 {
                let nb = c.neighbors[t][i];
                if nb == NONE {
                    continue;
                }
                let (p, q) = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
                let o = c.triangles[nb as usize];
                assert!(o.contains(&p) && o.contains(&q));
                let j = opposite_corner(&o, p, q);
                assert_eq!(c.neighbors[nb as usize][j], t as u32);
                assert_eq!(c.is_constrained(t as u32, i), c.is_constrained(nb, j));
            }
        }
        assert_eq!(c.triangles.len(), 2 * n - c.hull().len() - 2);
        for (v, &t) in c.vertex_tri.iter().enumerate() {
            assert!(c.triangles[t as usize].contains(&(v as u32)));
        }
    }

    #[test]
    fn constraint_forces_the_other_diagonal() {
        // a flat rhombus: Delaunay takes the short diagonal 1-3, the constraint 0-2 replaces it
        let p = pts(&[[0.0, 0.0], [2.0, -0.3], [4.0, 0.0], [2.0, 0.3]]);
        let c = triangulate_constrained_2d(&p, &[]).unwrap();
        let has = |c: &Cdt2, a: u32, b: u32| {
            c.edges().iter().any(|(e, _)| {
                let (x, y) = (
                    c.input_of_vertex()[e[0] as usize],
                    c.input_of_vertex()[e[1] as usize],
                );
                (x, y) == (a, b) || (x, y) == (b, a)
            })
        };
        assert!(has(&c, 1, 3) && !has(&c, 0, 2));
        let c = triangulate_constrained_2d(&p, &[[0, 2]]).unwrap();
        check(&c);
        assert!(has(&c, 0, 2) && !has(&c, 1, 3));
        assert_eq!(c.constrained_edges().len(), 1);
        // inserting it again changes nothing
        let mut c2 = c.clone();
        c2.insert_segment(c.vertex_of_input()[2], c.vertex_of_input()[0])
            .unwrap();
        assert_eq!(c2.triangles, c.triangles);
        assert_eq!(c2.constrained, c.constrained);
    }

    #[test]
    fn cavity_with_a_slit_edge() {
        // found by the random tests: the segment 3-6 crosses both edges 0-4 and 0-2 (in input
        // indices) of vertex 0 and the fan of vertex 1, so the edge 0-1 hangs into the cavity
        let p = pts(&[
            [0.7209027674256375, 0.485803545411819],
            [0.5327979730391228, 0.529309203456447],
            [0.45755574044212644, 0.7143716899321997],
            [0.11035673103209775, 0.07169004523282096],
            [0.23201469171228506, 0.31769056942231144],
            [0.6190284083279118, 0.9837345166213834],
            [0.7625860763323129, 0.9457637740873854],
            [0.347624160354426, 0.9756050518134698],
            [0.9298819835587695, 0.4851208476488845],
            [0.2806311353060852, 0.5080042100283657],
        ]);
        let c = triangulate_constrained_2d(&p, &[[7, 9], [2, 9], [3, 6]]).unwrap();
        check(&c);
        assert_eq!(c.constrained_edges().len(), 3);
        // and with the slit edge itself constrained first
        let c = triangulate_constrained_2d(&p, &[[0, 1], [7, 9], [2, 9], [3, 6]]).unwrap();
        check(&c);
        assert_eq!(c.constrained_edges().len(), 4);
        // the same through vertex indices
        let d = triangulate(&p).unwrap();
        let v = |i: usize| d.vertex_of_input[i];
        let segs = [[v(0), v(1)], [v(7), v(9)], [v(2), v(9)], [v(3), v(6)]];
        let mut c2 = Cdt2::new(d);
        for s in segs {
            c2.insert_segment(s[0], s[1]).unwrap();
        }
        assert_eq!(c2.triangles, c.triangles);
        assert_eq!(c2.constrained, c.constrained);
    }

    #[test]
    fn depths_of_nested_squares() {
        let mut v = Vec::new();
        for s in [1.0, 2.0, 3.0] {
            v.extend_from_slice(&[[-s, -s], [s, -s], [s, s], [-s, s]]);
        }
        let p = pts(&v);
        let mut segs = Vec::new();
        for r in 0..3u32 {
            for k in 0..4u32 {
                segs.push([4 * r + k, 4 * r + (k + 1) % 4]);
            }
        }
        let c = triangulate_constrained_2d(&p, &segs).unwrap();
        check(&c);
        let d = c.depths();
        // hull = outer square, its edges are constrained: every triangle is inside it
        let mut area = [0.0f64; 4];
        for (t, tri) in c.triangles.iter().enumerate() {
            let [a, b, cc] = tri.map(|w| c.points()[w as usize]);
            area[d[t] as usize] += 0.5 * (b - a).perp(&(cc - a));
        }
        assert_eq!(area, [0.0, 36.0 - 16.0, 16.0 - 4.0, 4.0]);
    }
}
