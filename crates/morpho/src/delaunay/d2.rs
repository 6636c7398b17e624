//! 2D Delaunay triangulation, exact on every input (Veltkamp 1992, §2.2.8 Def. 2.10 convex hull,
//! §2.2.9 Def. 2.11 Delaunay triangulation; Dorgerloh et al. §2, Property 1).
//!
//! Size (over 800 lines): one algorithm — the flip engine, generic over its two exact kernels
//! (floating-point and integer), with the queries on its result; about 170 lines are unit tests.
//!
//! # What it computes
//! [`triangulate`] returns the Delaunay triangulation of the distinct input points: counter-
//! clockwise triangles whose circumcircles contain no vertex in their interior, with neighbour
//! adjacency, and the convex hull as a vertex cycle (Veltkamp Def. 2.10: the hull edges are the
//! triangulation edges with a triangle on one side only, `CH ⊆ DT`).
//!
//! # Algorithm
//! Incremental insertion (Lawson's flip algorithm, which replaces the cavity step (b)–(d) of
//! Dorgerloh's *SimpleDelaunay* by local edge flips) in a spatially coherent order:
//! 1. the points are scaled by an exact power of two, sorted along a Hilbert curve (ties broken by
//!    the lexicographic order of the coordinates) and exact duplicates are merged — the resulting
//!    vertex order is a function of the point *set*, not of the input order;
//! 2. the first non-degenerate triangle found in that order starts the triangulation; the outside
//!    is covered by *ghost triangles* (one per hull edge, with an infinite vertex), so a point
//!    outside the current hull is inserted exactly like a point inside a triangle;
//! 3. the insertion order is a biased randomized insertion order (BRIO, rounds of geometrically
//!    growing size, each in Hilbert order; the "random" choice is a fixed hash of the canonical
//!    vertex index, so it is deterministic);
//! 4. each point is located by a visibility walk (exact `orient2d`) starting from a triangle
//!    incident to the nearest (by distance) of three inserted vertices: the previously inserted
//!    one and the inserted vertices just before and after the point in Hilbert order (a
//!    vertex→triangle map kept exact by the splits and flips) — on points along a curve the
//!    Hilbert curve's jumps between blocks otherwise made walks ~3× longer than on uniform
//!    points; the containing triangle (or edge) is split, and the new
//!    edges are legalised by Lawson flips using the exact, symbolically perturbed in-circle test
//!    [`incircle_sos`] (the floating-point filter, then an allocation-free exact expansion when
//!    the coordinate differences are exact: [`crate::geom::predicates::incircle_sign`]); a ghost
//!    triangle is "in conflict" when the point lies strictly outside its hull edge.
//!
//! Expected time O(n log n) (the sort; walks and flips are O(1) amortised for points with bounded
//! density), worst case O(n²); memory ≈ 100 bytes per point during construction.
//!
//! # Degeneracies
//! - **Duplicates** (bit-identical coordinates after `-0.0 → 0.0`) are merged; `vertex_of_input`
//!   maps every input index to its vertex and `duplicates` counts the merged inputs.
//! - **Cocircular points** are resolved by symbolic perturbation (Edelsbrunner–Mücke "simulation of
//!   simplicity", in the form of Devillers & Teillaud for Delaunay): each vertex is lifted to the
//!   paraboloid `z = x² + y²` plus an infinitesimal `ε_v`, where `ε_u ≫ ε_v` when `u` is
//!   lexicographically greater (`x`, then `y`) than `v`. The result is the unique Delaunay
//!   triangulation of the perturbed points, which is one of the Delaunay triangulations of the
//!   input and does not depend on the input order. See [`incircle_sos`].
//! - **Collinear points on the hull** are all hull vertices (the hull cycle contains them).
//! - **All points collinear** (or a single distinct point): `Ok` with no triangles,
//!   `collinear == true`, and `hull` lists every vertex once, sorted lexicographically, i.e. from
//!   one end of the line to the other.
//!
//! # Exactness and valid coordinate range
//! All decisions use the exact predicates of [`crate::geom::predicates::raw`], except when every
//! (scaled) coordinate is a multiple of 2⁻²⁷ — integer grids and other power-of-two lattices,
//! where most in-circle tests are exactly zero and Shewchuk's adaptive stages would be slow —
//! in which case the same predicates are evaluated exactly in `i64`/`i128` integer arithmetic
//! (coordinates < 2²⁸ in magnitude, so no overflow). Shewchuk's predicates are exact as
//! long as no intermediate result over- or underflows. Before any test the coordinates are
//! multiplied by a power of two (exact) so that the largest magnitude `M` becomes ≈ 1, so nothing
//! overflows at any absolute scale (1e-300 … 1e+300, including large offsets such as
//! 1e300 + k·ulp). Nothing underflows when every non-zero coordinate is at least 2⁻¹⁸⁰·M
//! (≈ 6.5e-55·M) in magnitude: then every coordinate difference is a multiple of 2⁻²³², every
//! term of the degree-4 in-circle expansion a multiple of 2⁻⁹²⁸, above the smallest normal
//! double. Inputs outside this range are rejected with an error instead of risking an inexact
//! decision; as a second safety net the walk and the flip loop have bounds that can only be hit
//! with inconsistent predicates, and hitting them is also an error.
//! Constructions (circumcentres) are ordinary floating point.

use super::DelaunayError;
use crate::geom::exact::{incircle_i128, orient2d_i64};
use crate::geom::predicates::incircle_sign;
use crate::geom::predicates::raw::orient2d;
use crate::geom::predicates::stats;
use crate::geom::{Point2, Vector2};
use crate::util::hilbert::{hilbert2, HILBERT2_BITS};
use crate::util::NONE;
use crate::util::{Rng, Rng32};

type Result<T, E = DelaunayError> = std::result::Result<T, E>;

/// The infinite vertex of ghost triangles (construction only).
pub(super) const INF: u32 = u32::MAX;

/// A 2D Delaunay triangulation (see the module documentation).
#[derive(Debug, Clone)]
pub struct Delaunay2 {
    /// The distinct points (vertices), in Hilbert-curve order (a function of the point set).
    pub points: Vec<Point2>,
    /// For every input index, its vertex.
    pub vertex_of_input: Vec<u32>,
    /// For every vertex, the smallest input index at that position.
    pub input_of_vertex: Vec<u32>,
    /// Counter-clockwise triangles (vertex indices).
    pub triangles: Vec<[u32; 3]>,
    /// `neighbors[t][i]` is the triangle across the edge opposite corner `i` of `t`, or [`NONE`].
    pub neighbors: Vec<[u32; 3]>,
    /// The convex hull as a counter-clockwise vertex cycle (first vertex not repeated), starting
    /// at the lexicographically smallest vertex; collinear points on hull edges are included.
    /// When `collinear`, all vertices sorted lexicographically (from one end of the line to the
    /// other).
    pub hull: Vec<u32>,
    /// One incident triangle per vertex ([`NONE`] when there are no triangles). For a hull vertex
    /// it is the triangle on the hull edge leaving the vertex counter-clockwise, so that turning
    /// counter-clockwise from it visits all incident triangles.
    pub vertex_tri: Vec<u32>,
    /// Number of input points merged into an earlier vertex (exact duplicates).
    pub duplicates: usize,
    /// True when all distinct points are collinear (or there is only one): no triangles.
    pub collinear: bool,
    /// Exact power of two applied to coordinates before predicates.
    scale: f64,
}

/// Where a query point lies relative to a [`Delaunay2`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Location {
    /// Strictly inside triangle `t`.
    InTriangle(u32),
    /// On the relative interior of the edge opposite corner `corner` of triangle `tri`.
    OnEdge {
        /// A triangle on the edge.
        tri: u32,
        /// The corner of `tri` opposite the edge (0, 1 or 2).
        corner: u8,
    },
    /// At vertex `v`.
    OnVertex(u32),
    /// Outside the convex hull, strictly beyond the hull edge opposite corner `corner` of `tri`.
    Outside {
        /// The hull triangle whose edge separates the query from the hull.
        tri: u32,
        /// The corner of `tri` opposite that hull edge.
        corner: u8,
    },
    /// The triangulation has no triangles (collinear input), or the query is not finite.
    Nowhere,
}

/// Exact in-circle test with symbolic perturbation: the sign of "`d` is inside the circle through
/// the counter-clockwise `a, b, c`", never zero for four distinct points with `a, b, c` not
/// collinear.
///
/// When the exact [`incircle`](crate::geom::predicates::incircle) is 0, each point `v` is
/// thought lifted to `x² + y² + ε_v` with `ε_u ≫ ε_v` whenever `u` is lexicographically (x,
/// then y) greater than `v`. Expanding the lifted determinant, the coefficient of `ε_a` is
/// `orient2d(d, b, c)`, of `ε_b` is `orient2d(a, d, c)`, of `ε_c` is `orient2d(a, b, d)` and
/// of `ε_d` is `−orient2d(a, b, c)`; the sign is that of the first non-zero coefficient taken
/// from the lexicographically greatest point down. Returns +1 (inside), −1 (outside) or 0 (only
/// for repeated points / collinear `a, b, c`).
pub fn incircle_sos(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> i32 {
    let s = incircle_sign(a, b, c, d);
    if s != 0 {
        return s;
    }
    stats::count(stats::INCIRCLE_SOS);
    incircle_tiebreak(a, b, c, d)
}

fn incircle_tiebreak(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> i32 {
    sos_tiebreak([a, b, c, d], FloatKernel::orient, lex_cmp)
}

/// Lexicographic order of points (x, then y).
#[inline]
pub fn lex_cmp(p: [f64; 2], q: [f64; 2]) -> std::cmp::Ordering {
    p[0].total_cmp(&q[0]).then(p[1].total_cmp(&q[1]))
}

/// Computes the Delaunay triangulation of `points` (facade name
/// [`triangulate_2d`](crate::delaunay::triangulate_2d)).
///
/// Counter-clockwise triangles whose circumcircles contain no vertex, neighbour adjacency and the
/// convex hull as a vertex cycle. Exact duplicates are merged ([`Delaunay2::vertex_of_input`]);
/// co-circular ties are broken by symbolic perturbation, so the result depends on the point set
/// only (not on the input order); all-collinear input gives no triangles and
/// [`Delaunay2::collinear`]. Lawson flips in a biased randomized Hilbert order with exact
/// predicates at any scale: expected O(n log n) time, O(n²) worst case; about 100 bytes per
/// point while building. One thread: the two-thread split of `delaunay/par2.rs` (the halves in
/// parallel, the seam re-triangulated exactly) is reached through [`triangulate_split`]; it
/// gave only 1.10–1.16× on two idle cores for 1.5× the CPU and 1.3× the memory (bench/README,
/// 2D Delaunay), so it is not the default.
///
/// Errors: no points ([`DelaunayError::NoPoints`]), a NaN or infinite coordinate
/// ([`DelaunayError::NonFinite`]), a non-zero coordinate below 2⁻¹⁸⁰ times the largest
/// ([`DelaunayError::CoordinateTooSmall`]).
///
/// ```rust
/// use morpho::delaunay::triangulate_2d;
/// use morpho::geom::Point2;
/// let p = [Point2::new(0.0, 0.0), Point2::new(1.0, 0.0), Point2::new(0.0, 1.0), Point2::new(1.0, 1.0)];
/// let d = triangulate_2d(&p).unwrap();
/// assert_eq!(d.triangles.len(), 2);
/// assert_eq!(d.hull.len(), 4);
/// ```
pub fn triangulate(points: &[Point2]) -> Result<Delaunay2> {
    build(points, None, Split::Never)
}

/// Whether [`triangulate`] uses the two-thread split path of `delaunay/par2.rs`.
#[doc(hidden)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Split {
    /// The split path when rayon has more than one thread, there are at least
    /// `par2::MIN_SPLIT` (50 000) distinct points and a sample predicts a narrow seam (not on
    /// points along curves).
    Auto,
    /// The split path whenever both halves have a triangle, even where a sample predicts a
    /// wide seam (tests, benches).
    Always,
    /// The sequential engine only: what [`triangulate`] does.
    Never,
    /// The divide and conquer of `delaunay/merge2.rs` (both halves in parallel, Guibas–Stolfi's
    /// exact zipper merge) whenever both halves have a triangle; the sequential engine where it
    /// does not apply.
    Merge,
}

/// As [`triangulate`], with the choice of the sequential or the split (parallel) path made
/// explicit. Both give the same triangles as a set; the split path's triangle order is the same
/// for every thread count, and differs from the sequential one (see `delaunay/par2.rs`).
#[doc(hidden)]
pub fn triangulate_split(points: &[Point2], split: Split) -> Result<Delaunay2> {
    build(points, None, split)
}

/// As [`triangulate`], but inserts the vertices in a pseudo-random order drawn from `seed`
/// instead of the Hilbert order. Slow; exists so that tests can check that the result does not
/// depend on the insertion order.
#[doc(hidden)]
pub fn triangulate_with_insertion_seed(points: &[Point2], seed: u64) -> Result<Delaunay2> {
    build(points, Some(seed), Split::Never)
}

/// Exact predicates on the construction's vertex coordinates.
pub(super) trait Kernel: Send + Sync + Sized {
    type P: Copy;
    fn p(&self, v: u32) -> Self::P;
    /// The exact coordinates of vertex `v` as `f64` (scaled; integers for [`IntKernel`]).
    fn xy(&self, v: u32) -> [f64; 2];
    /// The kernel of the vertices `ids` (vertex `i` of the result is `ids[i]` of `self`).
    fn subset(&self, ids: &[u32]) -> Self;
    /// Sign of orient2d (+1 counter-clockwise).
    fn orient(a: Self::P, b: Self::P, c: Self::P) -> i32;
    /// Squared distance, rounded (only to choose where a walk starts).
    fn dist2(a: Self::P, b: Self::P) -> f64;
    /// Sign of the perturbed in-circle test ([`incircle_sos`]).
    fn incircle_sos(a: Self::P, b: Self::P, c: Self::P, d: Self::P) -> i32;
}

/// Floating-point coordinates, Shewchuk's adaptive predicates.
pub(super) struct FloatKernel(pub(super) Vec<[f64; 2]>);

impl Kernel for FloatKernel {
    type P = [f64; 2];
    #[inline]
    fn p(&self, v: u32) -> [f64; 2] {
        self.0[v as usize]
    }
    #[inline]
    fn xy(&self, v: u32) -> [f64; 2] {
        self.0[v as usize]
    }
    fn subset(&self, ids: &[u32]) -> Self {
        FloatKernel(ids.iter().map(|&v| self.0[v as usize]).collect())
    }
    #[inline]
    fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> i32 {
        let o = orient2d(a, b, c);
        (o > 0.0) as i32 - (o < 0.0) as i32
    }
    #[inline]
    fn dist2(a: [f64; 2], b: [f64; 2]) -> f64 {
        let (x, y) = (a[0] - b[0], a[1] - b[1]);
        x * x + y * y
    }
    #[inline]
    fn incircle_sos(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> i32 {
        incircle_sos(a, b, c, d)
    }
}

/// Integer coordinates with |x| < 2^28 (inputs on a power-of-two lattice, e.g. integer grids):
/// orient2d in i64 and in-circle in i128 are exact and need no adaptive stages, which matters
/// because such inputs make most in-circle tests exactly zero.
struct IntKernel(Vec<[i64; 2]>);

/// Bound on |coordinate| for [`IntKernel`]: differences < 2^29, lifts < 2^59, products < 2^118.
const INT_LIMIT: f64 = (1u64 << 28) as f64;

impl Kernel for IntKernel {
    type P = [i64; 2];
    #[inline]
    fn p(&self, v: u32) -> [i64; 2] {
        self.0[v as usize]
    }
    #[inline]
    fn xy(&self, v: u32) -> [f64; 2] {
        // |x| < 2^28: exact
        self.0[v as usize].map(|x| x as f64)
    }
    fn subset(&self, ids: &[u32]) -> Self {
        IntKernel(ids.iter().map(|&v| self.0[v as usize]).collect())
    }
    #[inline]
    fn orient(a: [i64; 2], b: [i64; 2], c: [i64; 2]) -> i32 {
        orient2d_i64(a, b, c).signum() as i32
    }
    #[inline]
    fn dist2(a: [i64; 2], b: [i64; 2]) -> f64 {
        let (x, y) = ((a[0] - b[0]) as f64, (a[1] - b[1]) as f64);
        x * x + y * y
    }
    #[inline]
    fn incircle_sos(a: [i64; 2], b: [i64; 2], c: [i64; 2], d: [i64; 2]) -> i32 {
        let det = incircle_i128(a, b, c, d);
        if det != 0 {
            return det.signum() as i32;
        }
        sos_tiebreak([a, b, c, d], Self::orient, |p, q| p.cmp(&q))
    }
}

/// The symbolic-perturbation decision of [`incircle_sos`] for an exactly cocircular quadruple.
#[cold]
fn sos_tiebreak<P: Copy>(
    pts: [P; 4],
    orient: impl Fn(P, P, P) -> i32,
    lex: impl Fn(P, P) -> std::cmp::Ordering,
) -> i32 {
    let [a, b, c, d] = pts;
    let coef = |k: usize| match k {
        0 => orient(d, b, c),
        1 => orient(a, d, c),
        2 => orient(a, b, d),
        _ => -orient(a, b, c),
    };
    // the greatest point decides unless its coefficient vanishes (never for four distinct
    // cocircular points with a, b, c not collinear)
    let mut top = 0;
    for k in 1..4 {
        if lex(pts[k], pts[top]).is_gt() {
            top = k;
        }
    }
    let s = coef(top);
    if s != 0 {
        return s;
    }
    let mut order = [0usize, 1, 2, 3];
    order.sort_by(|&i, &j| lex(pts[j], pts[i])); // greatest first
    order
        .iter()
        .map(|&k| coef(k))
        .find(|&s| s != 0)
        .unwrap_or(0)
}

struct Builder<K: Kernel> {
    /// Vertex coordinates and predicates.
    k: K,
    /// Triangle corners, `INF` for the infinite vertex.
    tv: Vec<[u32; 3]>,
    /// `th[t][i]` = twin half-edge `3u + j` of the edge opposite corner i of t (j opposite in u).
    th: Vec<[u32; 3]>,
    stack: Vec<u32>,
    /// For every inserted vertex, a triangle (possibly a ghost) incident to it, kept exact by
    /// `fan` and `legalize`: the start of the walks of points inserted near it.
    vt: Vec<u32>,
    /// Set when a safety bound is hit (only possible if the predicates were inexact).
    failed: bool,
    rng: Rng32,
}

enum Found {
    /// The walk did not terminate within its bound.
    Lost,
    Inside(u32),
    OnEdge(u32, usize),
    OnVertex,
    Ghost(u32),
}

impl<K: Kernel> Builder<K> {
    #[inline]
    fn next_rand(&mut self) -> u32 {
        self.rng.next_u32()
    }

    /// Asks the processor to load triangle `t`'s corners and twins into the cache: the legalising
    /// tests read the triangle across each new edge, and on points along a curve that triangle
    /// (a long one spanning the shape) is rarely in the cache. A hint only.
    #[inline(always)]
    fn prefetch(&self, t: u32) {
        #[cfg(target_arch = "x86_64")]
        #[allow(unused_unsafe)]
        if let (Some(v), Some(h)) = (self.tv.get(t as usize), self.th.get(t as usize)) {
            use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
            // SAFETY: prefetching is a hint, valid for any address; these are live references.
            unsafe {
                _mm_prefetch::<_MM_HINT_T0>(v.as_ptr() as *const i8);
                _mm_prefetch::<_MM_HINT_T0>(h.as_ptr() as *const i8);
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        let _ = t;
    }

    /// Records `t` as a triangle incident to `v` (nothing for the infinite vertex).
    #[inline]
    fn set_vt(&mut self, v: u32, t: u32) {
        if v != INF {
            self.vt[v as usize] = t;
        }
    }

    #[inline]
    fn link(&mut self, a: u32, b: u32) {
        self.th[(a / 3) as usize][(a % 3) as usize] = b;
        self.th[(b / 3) as usize][(b % 3) as usize] = a;
    }

    fn new_tri(&mut self) -> u32 {
        let t = self.tv.len() as u32;
        self.tv.push([INF; 3]);
        self.th.push([NONE; 3]);
        t
    }

    /// Visibility walk from triangle `t` towards `p`.
    fn walk(&mut self, mut t: u32, p: K::P) -> Found {
        if let Some(i) = self.tv[t as usize].iter().position(|&v| v == INF) {
            t = self.th[t as usize][i] / 3;
        }
        let mut from = NONE;
        // a visibility walk in a Delaunay triangulation visits each triangle at most once
        let mut budget = self.tv.len() + 8;
        'walk: loop {
            if budget == 0 {
                return Found::Lost;
            }
            budget -= 1;
            stats::count(stats::WALK_STEPS);
            let v = self.tv[t as usize];
            if v[0] == INF || v[1] == INF || v[2] == INF {
                return Found::Ghost(t);
            }
            let nb = self.th[t as usize];
            let r = (self.next_rand() % 3) as usize;
            let mut zeros = 0;
            let mut zero_edge = 0;
            for k in 0..3 {
                let e = (r + k) % 3;
                let n = nb[e] / 3;
                if n == from {
                    continue;
                }
                let o = K::orient(self.k.p(v[(e + 1) % 3]), self.k.p(v[(e + 2) % 3]), p);
                if o < 0 {
                    from = t;
                    t = n;
                    continue 'walk;
                }
                if o == 0 {
                    zeros += 1;
                    zero_edge = e;
                }
            }
            return match zeros {
                0 => Found::Inside(t),
                1 => Found::OnEdge(t, zero_edge),
                _ => Found::OnVertex,
            };
        }
    }

    /// Replaces the triangles around the new vertex `p` by the fan (p, v_k, v_{k+1}) over the
    /// boundary edges `(v_k, ext_k)` (counter-clockwise cycle), reusing `slots`, and legalises.
    fn fan(&mut self, p: u32, bnd: &[(u32, u32)], slots: &[u32]) -> u32 {
        let m = bnd.len();
        for k in 0..m {
            let t = slots[k];
            let (a, ext) = bnd[k];
            self.tv[t as usize] = [p, a, bnd[(k + 1) % m].0];
            self.link(3 * t, ext);
            self.set_vt(a, t);
            self.prefetch(ext / 3);
        }
        self.vt[p as usize] = slots[0];
        for k in 0..m {
            let t = slots[k];
            let tn = slots[(k + 1) % m];
            self.link(3 * t + 1, 3 * tn + 2);
        }
        for k in 0..m {
            self.stack.push(slots[k]);
        }
        self.legalize(p);
        slots[0]
    }

    /// Is the (finite) new point `p` in conflict with triangle `u` = (d, b, a) seen across the
    /// edge `a b`? `t_ghost` says whether the triangle (p, a, b) on this side is a ghost.
    #[inline]
    fn conflict(&self, d: u32, b: u32, a: u32, p: u32, t_ghost: bool) -> bool {
        if t_ghost {
            // both are ghosts; u's hull edge (x, y) has the outside on its left
            let (x, y) = if d == INF {
                (b, a)
            } else if b == INF {
                (a, d)
            } else {
                (d, b)
            };
            K::orient(self.k.p(x), self.k.p(y), self.k.p(p)) > 0
        } else if d == INF {
            false
        } else {
            K::incircle_sos(self.k.p(d), self.k.p(b), self.k.p(a), self.k.p(p)) > 0
        }
    }

    /// Lawson flips of the triangles on the stack: each has `p` at corner 0 and its edge
    /// opposite `p` is tested.
    fn legalize(&mut self, p: u32) {
        // every flip raises the degree of p by one, and its degree is below the vertex count
        let mut budget = self.tv.len() + 8;
        while let Some(t) = self.stack.pop() {
            let [_, a, b] = self.tv[t as usize];
            let o = self.th[t as usize][0];
            let u = o / 3;
            let j = (o % 3) as usize;
            let d = self.tv[u as usize][j];
            let t_ghost = a == INF || b == INF;
            if !self.conflict(d, b, a, p, t_ghost) {
                continue;
            }
            if budget == 0 {
                self.failed = true;
                self.stack.clear();
                return;
            }
            budget -= 1;
            stats::count(stats::FLIPS);
            let a_ext = self.th[u as usize][(j + 1) % 3];
            let b_ext = self.th[u as usize][(j + 2) % 3];
            let t1_ext = self.th[t as usize][1];
            // t = (p, a, d), u = (p, d, b)
            self.tv[t as usize] = [p, a, d];
            self.tv[u as usize] = [p, d, b];
            self.link(3 * t, a_ext);
            self.link(3 * t + 1, 3 * u + 2);
            self.link(3 * u, b_ext);
            self.link(3 * u + 1, t1_ext);
            self.set_vt(a, t);
            self.set_vt(d, t);
            self.set_vt(b, u);
            // the next tests read the triangles across the new edges opposite p
            self.prefetch(a_ext / 3);
            self.prefetch(b_ext / 3);
            self.stack.push(t);
            self.stack.push(u);
        }
    }

    /// Inserts vertex `p`, walking from `start`; returns a triangle incident to `p`.
    fn insert(&mut self, p: u32, start: u32) -> u32 {
        let pc = self.k.p(p);
        match self.walk(start, pc) {
            Found::Inside(t) | Found::Ghost(t) => {
                let v = self.tv[t as usize];
                let h = self.th[t as usize];
                let bnd = [(v[0], h[2]), (v[1], h[0]), (v[2], h[1])];
                let t1 = self.new_tri();
                let t2 = self.new_tri();
                self.fan(p, &bnd, &[t, t1, t2])
            }
            Found::OnEdge(t, i) => {
                let v = self.tv[t as usize];
                let h = self.th[t as usize];
                let (c, a, bv) = (v[i], v[(i + 1) % 3], v[(i + 2) % 3]);
                let o = h[i];
                let u = o / 3;
                let j = (o % 3) as usize;
                let d = self.tv[u as usize][j];
                let hu = self.th[u as usize];
                let bnd = [
                    (bv, h[(i + 1) % 3]),
                    (c, h[(i + 2) % 3]),
                    (a, hu[(j + 1) % 3]),
                    (d, hu[(j + 2) % 3]),
                ];
                let t1 = self.new_tri();
                let t2 = self.new_tri();
                self.fan(p, &bnd, &[t, t1, u, t2])
            }
            Found::OnVertex | Found::Lost => {
                // impossible with exact predicates and distinct points
                self.failed = true;
                start
            }
        }
    }
}

fn build(points: &[Point2], order_seed: Option<u64>, split: Split) -> Result<Delaunay2> {
    if points.is_empty() {
        return Err(DelaunayError::NoPoints { dim: 2 });
    }
    if points.len() >= u32::MAX as usize / 4 {
        return Err(DelaunayError::TooManyPoints {
            found: points.len(),
            dim: 2,
        });
    }
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for (i, p) in points.iter().enumerate() {
        if !p.x.is_finite() || !p.y.is_finite() {
            return Err(DelaunayError::NonFinite {
                index: i,
                coords: vec![p.x, p.y],
            });
        }
        lo[0] = lo[0].min(p.x);
        lo[1] = lo[1].min(p.y);
        hi[0] = hi[0].max(p.x);
        hi[1] = hi[1].max(p.y);
    }
    let m = lo[0]
        .abs()
        .max(lo[1].abs())
        .max(hi[0].abs())
        .max(hi[1].abs());
    let scale = crate::geom::exact::power_of_two_scale(m);
    let n_in = points.len();

    // Hilbert keys on the bounding box (computed on halves to avoid overflow of hi - lo).
    let cell = |k: usize, v: f64| -> u32 {
        let ext = 0.5 * hi[k] - 0.5 * lo[k];
        if ext <= 0.0 {
            return 0;
        }
        let t = ((0.5 * v - 0.5 * lo[k]) / ext).clamp(0.0, 1.0);
        (t * ((1u32 << HILBERT2_BITS) - 1) as f64) as u32
    };
    let key =
        |(i, p): (usize, &Point2)| ((hilbert2(cell(0, p.x), cell(1, p.y)) as u64) << 32) | i as u64;
    let mut keys: Vec<u64>;
    if split_wanted(split, n_in, order_seed) {
        // the keys are distinct (they hold the input index): the same order on any schedule
        use rayon::prelude::*;
        keys = points.par_iter().enumerate().map(key).collect();
        keys.par_sort_unstable();
    } else {
        keys = points.iter().enumerate().map(key).collect();
        keys.sort_unstable();
    }
    // Canonical order: Hilbert key, then coordinates, then input index.
    let norm = |i: usize| [points[i].x + 0.0, points[i].y + 0.0];
    let mut s = 0;
    while s < keys.len() {
        let k = keys[s] >> 32;
        let mut e = s + 1;
        while e < keys.len() && keys[e] >> 32 == k {
            e += 1;
        }
        if e - s > 1 {
            keys[s..e].sort_unstable_by(|&x, &y| {
                let (i, j) = ((x & 0xffff_ffff) as usize, (y & 0xffff_ffff) as usize);
                lex_cmp(norm(i), norm(j)).then(i.cmp(&j))
            });
        }
        s = e;
    }
    // Merge duplicates.
    let mut vertex_of_input = vec![0u32; n_in];
    let mut input_of_vertex: Vec<u32> = Vec::with_capacity(n_in);
    let mut c: Vec<[f64; 2]> = Vec::with_capacity(n_in);
    let mut points_out: Vec<Point2> = Vec::with_capacity(n_in);
    let mut last: Option<[f64; 2]> = None;
    for &k in &keys {
        let i = (k & 0xffff_ffff) as usize;
        let p = norm(i);
        if last != Some(p) {
            input_of_vertex.push(i as u32);
            c.push([p[0] * scale, p[1] * scale]);
            points_out.push(Point2::new(p[0], p[1]));
            last = Some(p);
        }
        vertex_of_input[i] = (input_of_vertex.len() - 1) as u32;
    }
    drop(keys);
    let n = c.len();
    let duplicates = n_in - n;
    if duplicates > 0 {
        c.shrink_to_fit();
        points_out.shrink_to_fit();
        input_of_vertex.shrink_to_fit();
    }

    // Initial triangle: vertex 0, vertex 1, and the first vertex not collinear with them.
    let third = if n >= 3 {
        (2..n).find(|&k| orient2d(c[0], c[1], c[k]) != 0.0)
    } else {
        None
    };
    let Some(k0) = third else {
        let mut hull: Vec<u32> = (0..n as u32).collect();
        hull.sort_by(|&a, &b| lex_cmp(c[a as usize], c[b as usize]));
        return Ok(Delaunay2 {
            points: points_out,
            vertex_of_input,
            input_of_vertex,
            triangles: Vec::new(),
            neighbors: Vec::new(),
            hull,
            vertex_tri: vec![NONE; n],
            duplicates,
            collinear: true,
            scale,
        });
    };
    // Power-of-two lattice inputs (integer grids, …) use the integer kernel.
    let int_scale = (1u64 << 27) as f64;
    let lattice = c.iter().all(|p| {
        p.iter().all(|&x| {
            let y = x * int_scale;
            y.fract() == 0.0 && y.abs() < INT_LIMIT
        })
    });
    let tv = if lattice {
        let ci = c
            .iter()
            .map(|p| [(p[0] * int_scale) as i64, (p[1] * int_scale) as i64])
            .collect();
        drop(c);
        run_kernel(IntKernel(ci), n, k0, order_seed, split)?
    } else {
        // Shewchuk's expansions stay above the underflow threshold when no non-zero scaled
        // coordinate is below 2^-180 (the largest is ≈ 1).
        let tiny = 2f64.powi(-180);
        if let Some(v) = c
            .iter()
            .position(|p| p.iter().any(|&x| x != 0.0 && x.abs() < tiny))
        {
            let p = points_out[v];
            return Err(DelaunayError::CoordinateTooSmall { point: [p.x, p.y] });
        }
        run_kernel(FloatKernel(c), n, k0, order_seed, split)?
    };
    Ok(finish(
        tv,
        points_out,
        vertex_of_input,
        input_of_vertex,
        duplicates,
        scale,
    ))
}

/// The sequential insertion, or the split path of [`super::par2`] when `split` asks for it
/// (it falls back to the sequential insertion where it does not apply, e.g. a collinear half).
fn run_kernel<K: Kernel>(
    k: K,
    n: usize,
    k0: usize,
    order_seed: Option<u64>,
    split: Split,
) -> Result<Arrays> {
    if split_wanted(split, n, order_seed) {
        let merged = if split == Split::Merge {
            super::merge2::insert_merge(&k, n)?
        } else {
            super::par2::insert_split(&k, n, split == Split::Auto)?
        };
        if let Some(a) = merged {
            return Ok(a);
        }
    }
    run_insertion(k, n, k0, order_seed)
}

/// Does `split` ask for the split path for `n` points?
fn split_wanted(split: Split, n: usize, order_seed: Option<u64>) -> bool {
    order_seed.is_none()
        && match split {
            Split::Never => false,
            Split::Always | Split::Merge => true,
            Split::Auto => rayon::current_num_threads() > 1 && n >= super::par2::MIN_SPLIT,
        }
}

/// The first vertex `k ≥ 2` not collinear with vertices 0 and 1 (the initial triangle), if any.
pub(super) fn first_noncollinear<K: Kernel>(k: &K, n: usize) -> Option<usize> {
    if n < 3 {
        return None;
    }
    let (a, b) = (k.p(0), k.p(1));
    (2..n).find(|&i| K::orient(a, b, k.p(i as u32)) != 0)
}

/// Biased randomized insertion order (Amenta, Choi & Rote 2003) over the Hilbert-sorted
/// vertices: vertex `v` belongs to round `min(tz(hash(v)), 24)` (so each round holds about half
/// of the remaining points), rounds are inserted from the sparsest to the densest, each in
/// Hilbert order. The hash is a fixed function of the canonical vertex index, so the order is
/// deterministic. Compared with the plain Hilbert order this keeps the new point inside the
/// already triangulated region most of the time, which saves about a third of the flips.
/// Vertices 0, 1 and `k0` (the initial triangle) are left out.
fn brio_order(n: usize, k0: usize) -> Vec<u32> {
    const ROUNDS: usize = 25;
    let level = |v: u32| -> usize {
        // splitmix64 finaliser
        let mut h = (v as u64).wrapping_add(0x9e37_79b9_7f4a_7c15);
        h = (h ^ (h >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        h = (h ^ (h >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        h ^= h >> 31;
        (h.trailing_zeros() as usize).min(ROUNDS - 1)
    };
    let keep = |v: u32| v as usize != k0 && v > 1;
    let mut start = [0usize; ROUNDS + 1];
    for v in (0..n as u32).filter(|&v| keep(v)) {
        start[ROUNDS - 1 - level(v) + 1] += 1;
    }
    for r in 0..ROUNDS {
        start[r + 1] += start[r];
    }
    let mut order = vec![0u32; start[ROUNDS]];
    for v in (0..n as u32).filter(|&v| keep(v)) {
        let r = ROUNDS - 1 - level(v);
        order[start[r]] = v;
        start[r] += 1;
    }
    order
}

/// Triangle corners and twin half-edges (ghosts included).
pub(super) type Arrays = (Vec<[u32; 3]>, Vec<[u32; 3]>);

/// Runs the insertion with kernel `k`, starting from the triangle (0, 1, k0); returns the
/// corner and twin arrays (ghosts included).
pub(super) fn run_insertion<K: Kernel>(
    k: K,
    n: usize,
    k0: usize,
    order_seed: Option<u64>,
) -> Result<Arrays> {
    run_insertion_vt(k, n, k0, order_seed).map(|(a, _)| a)
}

/// [`run_insertion`], also returning one incident triangle (possibly a ghost) per vertex.
pub(super) fn run_insertion_vt<K: Kernel>(
    k: K,
    n: usize,
    k0: usize,
    order_seed: Option<u64>,
) -> Result<(Arrays, Vec<u32>)> {
    let mut bld = Builder {
        k,
        tv: Vec::with_capacity(2 * n + 4),
        th: Vec::with_capacity(2 * n + 4),
        stack: Vec::with_capacity(64),
        vt: vec![NONE; n],
        rng: Rng32::new(0x9e37_79b9),
        failed: false,
    };
    let (a, b, cc) = if K::orient(bld.k.p(0), bld.k.p(1), bld.k.p(k0 as u32)) > 0 {
        (0u32, 1u32, k0 as u32)
    } else {
        (1u32, 0u32, k0 as u32)
    };
    // t0 = (a, b, c); ghosts (b, a, INF), (c, b, INF), (a, c, INF)
    for _ in 0..4 {
        bld.new_tri();
    }
    bld.tv[0..4].copy_from_slice(&[[a, b, cc], [b, a, INF], [cc, b, INF], [a, cc, INF]]);
    // edge opposite corner 2 of t0 = (a,b) ↔ ghost 1 edge (b,a) opposite corner 2
    bld.link(2, 5);
    bld.link(0, 8); // (b,c) ↔ ghost 2 (c,b)
    bld.link(1, 11); // (c,a) ↔ ghost 3 (a,c)
                     // ghost edges through INF: ghost1 (b,a,INF): corner0 opp (a,INF), corner1 opp (INF,b)
    bld.link(3, 10); // g1 (a,INF) ↔ g3 (INF,a): g3 = (a,c,INF) corner 1 opp (INF,a)
    bld.link(4, 6); // g1 (INF,b) ↔ g2 (b,INF): g2 = (c,b,INF) corner 0 opp (b,INF)
    bld.link(7, 9); // g2 (INF,c) ↔ g3 (c,INF)
    let mut order = brio_order(n, k0);
    if let Some(seed) = order_seed {
        let mut rng = Rng::new(seed | 1);
        for i in (1..order.len()).rev() {
            order.swap(i, rng.below(i as u64 + 1) as usize);
        }
    }
    for (v, t) in [(a, 0), (b, 0), (cc, 0)] {
        bld.vt[v as usize] = t;
    }
    let mut inserted = Inserted::new(n);
    for v in [a, b, cc] {
        inserted.set(v);
    }
    let mut last_v = cc;
    for &v in &order {
        let start = if order_seed.is_some() {
            bld.vt[last_v as usize]
        } else {
            bld.vt[nearest_start(&bld.k, v, last_v, &inserted) as usize]
        };
        bld.insert(v, start);
        if bld.failed {
            return Err(DelaunayError::InconsistentPredicates);
        }
        inserted.set(v);
        last_v = v;
    }
    Ok(((bld.tv, bld.th), bld.vt))
}

/// Where the walk to vertex `v` starts: at the one of the last inserted vertex and the inserted
/// vertices next to `v` in Hilbert order (the nearest before and after it, mostly from earlier
/// BRIO rounds) that is closest to `v`. Within a round consecutive points jump wherever the
/// Hilbert curve leaves a block; on points along a curve (a 1D set meets every block boundary
/// of the 2D Hilbert curve) these jumps made the walks ~3× longer than on uniform points, while
/// one of `v`'s Hilbert neighbours is almost always on the same stretch of the curve.
#[inline]
fn nearest_start<K: Kernel>(k: &K, v: u32, last_v: u32, inserted: &Inserted) -> u32 {
    let p = k.p(v);
    let mut best = last_v;
    let mut dbest = K::dist2(p, k.p(last_v));
    for w in [inserted.before(v), inserted.after(v)]
        .into_iter()
        .flatten()
    {
        let d = K::dist2(p, k.p(w));
        if d < dbest {
            best = w;
            dbest = d;
        }
    }
    best
}

/// The set of inserted vertices as a bitmap, with the nearest member before and after an index.
struct Inserted(Vec<u64>);

impl Inserted {
    fn new(n: usize) -> Self {
        Inserted(vec![0; n.div_ceil(64)])
    }
    #[inline]
    fn set(&mut self, v: u32) {
        self.0[(v / 64) as usize] |= 1 << (v % 64);
    }
    /// The greatest member < v.
    #[inline]
    fn before(&self, v: u32) -> Option<u32> {
        let mut w = (v / 64) as usize;
        let mut bits = self.0[w] & ((1u64 << (v % 64)) - 1);
        loop {
            if bits != 0 {
                return Some(w as u32 * 64 + 63 - bits.leading_zeros());
            }
            if w == 0 {
                return None;
            }
            w -= 1;
            bits = self.0[w];
        }
    }
    /// The least member > v.
    #[inline]
    fn after(&self, v: u32) -> Option<u32> {
        let mut w = (v / 64) as usize;
        let sh = v % 64;
        let mut bits = if sh == 63 {
            0
        } else {
            self.0[w] & (!0u64 << (sh + 1))
        };
        loop {
            if bits != 0 {
                return Some(w as u32 * 64 + bits.trailing_zeros());
            }
            w += 1;
            if w >= self.0.len() {
                return None;
            }
            bits = self.0[w];
        }
    }
}

fn finish(
    (mut tv, mut th): Arrays,
    points: Vec<Point2>,
    vertex_of_input: Vec<u32>,
    input_of_vertex: Vec<u32>,
    duplicates: usize,
    scale: f64,
) -> Delaunay2 {
    let n = points.len();
    let nt_all = tv.len();
    let xy = |p: &Point2| [p.x, p.y];
    let mut new_id = vec![NONE; nt_all];
    let mut count = 0u32;
    for (t, v) in tv.iter().enumerate() {
        if !v.contains(&INF) {
            new_id[t] = count;
            count += 1;
        }
    }
    let mut vertex_tri = vec![NONE; n];
    let mut next_ccw = vec![NONE; n];
    // ghosts first: hull successor and the triangle on each vertex's outgoing hull edge
    for (v, h) in tv.iter().zip(&th) {
        if let Some(i) = v.iter().position(|&w| w == INF) {
            // ghost (x, y, INF): the hull runs y -> x counter-clockwise
            let x = v[(i + 1) % 3];
            let y = v[(i + 2) % 3];
            next_ccw[y as usize] = x;
            vertex_tri[y as usize] = new_id[(h[i] / 3) as usize];
        }
    }
    // compact the real triangles in place
    for t in 0..nt_all {
        let id = new_id[t];
        if id == NONE {
            continue;
        }
        let v = tv[t];
        let h = th[t];
        tv[id as usize] = v;
        th[id as usize] = h.map(|e| new_id[(e / 3) as usize]);
        for &w in &v {
            if vertex_tri[w as usize] == NONE {
                vertex_tri[w as usize] = id;
            }
        }
    }
    drop(new_id);
    tv.truncate(count as usize);
    th.truncate(count as usize);
    tv.shrink_to_fit();
    th.shrink_to_fit();
    // hull cycle from the lexicographically smallest hull vertex
    let mut start = NONE;
    for v in 0..n {
        if next_ccw[v] != NONE
            && (start == NONE || lex_cmp(xy(&points[v]), xy(&points[start as usize])).is_lt())
        {
            start = v as u32;
        }
    }
    let mut hull = Vec::new();
    if start != NONE {
        let mut v = start;
        loop {
            hull.push(v);
            v = next_ccw[v as usize];
            if v == start || v == NONE || hull.len() > n {
                break;
            }
        }
    }
    Delaunay2 {
        points,
        vertex_of_input,
        input_of_vertex,
        triangles: tv,
        neighbors: th,
        hull,
        vertex_tri,
        duplicates,
        collinear: false,
        scale,
    }
}

/// Iterator over the triangles around a vertex, counter-clockwise (see
/// [`Delaunay2::triangles_around`]).
pub struct TrianglesAround<'a> {
    d: &'a Delaunay2,
    v: u32,
    first: u32,
    next: u32,
}

impl Iterator for TrianglesAround<'_> {
    type Item = u32;
    fn next(&mut self) -> Option<u32> {
        let t = self.next;
        if t == NONE {
            return None;
        }
        let tri = self.d.triangles[t as usize];
        let i = tri.iter().position(|&w| w == self.v)?;
        let n = self.d.neighbors[t as usize][(i + 1) % 3];
        self.next = if n == self.first { NONE } else { n };
        Some(t)
    }
}

impl Delaunay2 {
    /// The scaled coordinates of vertex `v` (used by the exact predicates).
    #[inline]
    fn sc(&self, v: u32) -> [f64; 2] {
        let p = &self.points[v as usize];
        [p.x * self.scale, p.y * self.scale]
    }

    /// Locates `p` by a visibility walk with exact `orient2d`, starting at triangle `start`
    /// (or triangle 0 when `start` is out of range). O(√n) expected steps from a random start
    /// on evenly spread points, O(1) from a nearby triangle.
    ///
    /// ```rust
    /// use morpho::delaunay::{triangulate_2d, Location};
    /// use morpho::geom::Point2;
    /// let p = [[0., 0.], [4., 0.], [0., 4.]].map(|[x, y]| Point2::new(x, y));
    /// let d = triangulate_2d(&p).unwrap();
    /// assert_eq!(d.locate_from(Point2::new(1.0, 1.0), 0), Location::InTriangle(0));
    /// assert!(matches!(d.locate(Point2::new(2.0, 2.0)), Location::OnEdge { tri: 0, .. }));
    /// assert!(matches!(d.locate(Point2::new(5.0, 5.0)), Location::Outside { .. }));
    /// assert_eq!(d.locate(Point2::new(f64::NAN, 0.0)), Location::Nowhere);
    /// ```
    pub fn locate_from(&self, p: Point2, start: u32) -> Location {
        if self.triangles.is_empty() || !p.x.is_finite() || !p.y.is_finite() {
            return Location::Nowhere;
        }
        let q = [p.x * self.scale, p.y * self.scale];
        let mut t = if (start as usize) < self.triangles.len() {
            start
        } else {
            0
        };
        let mut from = NONE;
        let mut rng = Rng32::new(0x2545_f491);
        'walk: loop {
            let v = self.triangles[t as usize];
            let r = (rng.next_u32() % 3) as usize;
            let mut zeros = [false; 3];
            for k in 0..3 {
                let e = (r + k) % 3;
                let nb = self.neighbors[t as usize][e];
                if nb == from && nb != NONE {
                    continue;
                }
                let o = orient2d(self.sc(v[(e + 1) % 3]), self.sc(v[(e + 2) % 3]), q);
                if o < 0.0 {
                    if nb == NONE {
                        return Location::Outside {
                            tri: t,
                            corner: e as u8,
                        };
                    }
                    from = t;
                    t = nb;
                    continue 'walk;
                }
                zeros[e] = o == 0.0;
            }
            let nz = zeros.iter().filter(|&&z| z).count();
            return match nz {
                0 => Location::InTriangle(t),
                1 => Location::OnEdge {
                    tri: t,
                    corner: zeros.iter().position(|&z| z).unwrap_or(0) as u8,
                },
                _ => {
                    // on the vertex shared by the two zero edges: the corner whose both
                    // adjacent edges vanish, i.e. the one whose opposite edge is not zero
                    let c = zeros.iter().position(|&z| !z).unwrap_or(0);
                    Location::OnVertex(v[c])
                }
            };
        }
    }

    /// Locates `p` (see [`Delaunay2::locate_from`]).
    pub fn locate(&self, p: Point2) -> Location {
        self.locate_from(p, 0)
    }

    /// One triangle incident to vertex `v` ([`NONE`] if none).
    pub fn vertex_triangle(&self, v: u32) -> u32 {
        self.vertex_tri.get(v as usize).copied().unwrap_or(NONE)
    }

    /// The triangles around vertex `v` in counter-clockwise order (for a hull vertex, from the
    /// triangle on its outgoing hull edge to the one on its incoming hull edge). O(degree).
    ///
    /// ```rust
    /// use morpho::delaunay::triangulate_2d;
    /// use morpho::geom::Point2;
    /// // a square with its centre (input 4): the centre has four triangles around it
    /// let p = [[0., 0.], [2., 0.], [2., 2.], [0., 2.], [1., 1.]].map(|[x, y]| Point2::new(x, y));
    /// let d = triangulate_2d(&p).unwrap();
    /// let centre = d.vertex_of_input[4];
    /// assert_eq!(d.triangles_around(centre).count(), 4);
    /// ```
    pub fn triangles_around(&self, v: u32) -> TrianglesAround<'_> {
        let t = self.vertex_triangle(v);
        TrianglesAround {
            d: self,
            v,
            first: t,
            next: t,
        }
    }

    /// The triangles on the two sides of edge `a b`: `[left, right]` where `left` has `a → b`
    /// counter-clockwise; a missing side is [`NONE`]. `None` when `a b` is not an edge.
    /// O(degree of `a`).
    ///
    /// ```rust
    /// use morpho::delaunay::triangulate_2d;
    /// use morpho::geom::Point2;
    /// use morpho::util::NONE;
    /// let p = [[0., 0.], [2., 0.], [2., 2.], [0., 2.], [1., 1.]].map(|[x, y]| Point2::new(x, y));
    /// let d = triangulate_2d(&p).unwrap();
    /// let v = |i: usize| d.vertex_of_input[i];
    /// let [l, r] = d.edge_triangles(v(0), v(4)).unwrap(); // interior edge: two triangles
    /// assert!(l != NONE && r != NONE && l != r);
    /// let [_, outside] = d.edge_triangles(v(0), v(1)).unwrap(); // hull edge, counter-clockwise
    /// assert_eq!(outside, NONE);
    /// assert_eq!(d.edge_triangles(v(0), v(2)), None); // the diagonal is not an edge
    /// ```
    pub fn edge_triangles(&self, a: u32, b: u32) -> Option<[u32; 2]> {
        for t in self.triangles_around(a) {
            let tri = self.triangles[t as usize];
            let i = tri.iter().position(|&w| w == a)?;
            if tri[(i + 1) % 3] == b {
                // edge a->b is opposite corner i+2
                return Some([t, self.neighbors[t as usize][(i + 2) % 3]]);
            }
            if tri[(i + 2) % 3] == b {
                return Some([self.neighbors[t as usize][(i + 1) % 3], t]);
            }
        }
        None
    }

    /// Every undirected edge once, as `[a, b]`. For collinear input: the consecutive pairs of the
    /// sorted vertex line (the degenerate Delaunay graph). O(n).
    ///
    /// ```rust
    /// use morpho::delaunay::triangulate_2d;
    /// use morpho::geom::Point2;
    /// // a 4 × 4 grid (co-circular everywhere): Euler's relation V − E + T = 1 still holds,
    /// // and E = 3V − 3 − h with h = 12 hull vertices
    /// let p: Vec<Point2> = (0..16).map(|i| Point2::new((i % 4) as f64, (i / 4) as f64)).collect();
    /// let d = triangulate_2d(&p).unwrap();
    /// let (v, e, t) = (d.points.len(), d.edges().len(), d.triangles.len());
    /// assert_eq!(v as i64 - e as i64 + t as i64, 1);
    /// assert_eq!(d.hull.len(), 12);
    /// assert_eq!(e, 3 * v - 3 - d.hull.len());
    /// ```
    pub fn edges(&self) -> Vec<[u32; 2]> {
        if self.collinear {
            return self.hull.windows(2).map(|w| [w[0], w[1]]).collect();
        }
        let mut e = Vec::with_capacity(self.points.len() * 3);
        for (t, tri) in self.triangles.iter().enumerate() {
            for i in 0..3 {
                let nb = self.neighbors[t][i];
                if nb == NONE || nb as usize > t {
                    e.push([tri[(i + 1) % 3], tri[(i + 2) % 3]]);
                }
            }
        }
        e
    }

    /// Circumcentre of triangle `t` (floating-point construction, relative to the first corner).
    pub fn circumcenter(&self, t: u32) -> Point2 {
        let [a, b, c] = self.triangles[t as usize];
        circumcenter(
            &self.points[a as usize],
            &self.points[b as usize],
            &self.points[c as usize],
        )
    }

    /// The triangles in input indices (each vertex replaced by its first input index).
    pub fn to_input_indices(&self) -> Vec<[u32; 3]> {
        self.triangles
            .iter()
            .map(|t| t.map(|v| self.input_of_vertex[v as usize]))
            .collect()
    }

    /// Exact orientation of three vertices (sign as [`orient2d`]), with the internal scaling.
    pub fn orient(&self, a: u32, b: u32, c: u32) -> f64 {
        orient2d(self.sc(a), self.sc(b), self.sc(c))
    }

    /// The exact, symbolically perturbed in-circle sign of four vertices: +1 when `d` is
    /// inside the circle through the counter-clockwise `a, b, c`, −1 outside; 0 only for
    /// repeated vertices or collinear `a, b, c`. Co-circular ties are broken as in the
    /// construction, so every triangle is empty in this sense.
    ///
    /// ```rust
    /// use morpho::delaunay::triangulate_2d;
    /// use morpho::geom::Point2;
    /// // the empty-circle property, co-circular points included
    /// let p: Vec<Point2> = (0..9).map(|i| Point2::new((i % 3) as f64, (i / 3) as f64)).collect();
    /// let d = triangulate_2d(&p).unwrap();
    /// for &[a, b, c] in &d.triangles {
    ///     for v in 0..d.points.len() as u32 {
    ///         assert!(v == a || v == b || v == c || d.incircle_sos(a, b, c, v) < 0);
    ///     }
    /// }
    /// ```
    pub fn incircle_sos(&self, a: u32, b: u32, c: u32, d: u32) -> i32 {
        incircle_sos(self.sc(a), self.sc(b), self.sc(c), self.sc(d))
    }
}

/// Circumcentre of the triangle (a, b, c), computed relative to `a`.
pub fn circumcenter(a: &Point2, b: &Point2, c: &Point2) -> Point2 {
    let (bx, by) = (b.x - a.x, b.y - a.y);
    let (cx, cy) = (c.x - a.x, c.y - a.y);
    let bl = bx * bx + by * by;
    let cl = cx * cx + cy * cy;
    let dd = 2.0 * (bx * cy - by * cx);
    let ux = (cy * bl - by * cl) / dd;
    let uy = (bx * cl - cx * bl) / dd;
    a + Vector2::new(ux, uy)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pts(v: &[[f64; 2]]) -> Vec<Point2> {
        v.iter().map(|p| Point2::new(p[0], p[1])).collect()
    }

    #[test]
    fn square_and_duplicates() {
        let d = triangulate(&pts(&[
            [0.0, 0.0],
            [1.0, 0.0],
            [1.0, 1.0],
            [0.0, 1.0],
            [0.0, 0.0],
            [-0.0, 1.0],
        ]))
        .unwrap();
        assert_eq!(d.triangles.len(), 2);
        assert_eq!(d.duplicates, 2);
        assert_eq!(d.vertex_of_input[4], d.vertex_of_input[0]);
        assert_eq!(d.vertex_of_input[5], d.vertex_of_input[3]);
        assert_eq!(d.hull.len(), 4);
        // cocircular square: the perturbation rule picks the diagonal deterministically
        let e = d.edges();
        assert_eq!(e.len(), 5);
    }

    #[test]
    fn errors_and_collinear() {
        assert!(triangulate(&[]).is_err());
        assert!(triangulate(&pts(&[[0.0, f64::NAN]])).is_err());
        assert!(triangulate(&pts(&[[0.0, f64::INFINITY]])).is_err());
        let d = triangulate(&pts(&[[2.0, 2.0], [0.0, 0.0], [1.0, 1.0], [3.0, 3.0]])).unwrap();
        assert!(d.collinear && d.triangles.is_empty());
        let h: Vec<Point2> = d.hull.iter().map(|&v| d.points[v as usize]).collect();
        assert_eq!(h[0], Point2::new(0.0, 0.0));
        assert_eq!(h[3], Point2::new(3.0, 3.0));
        assert_eq!(d.edges().len(), 3);
        let one = triangulate(&pts(&[[1.0, 1.0], [1.0, 1.0]])).unwrap();
        assert!(one.collinear && one.duplicates == 1 && one.hull == vec![0]);
    }

    #[test]
    fn sos_is_antisymmetric_under_swaps() {
        // four cocircular points: the perturbed sign must be that of a determinant, so swapping
        // two of a, b, c (making them clockwise) flips it.
        let a = [1.0, 0.0];
        let b = [0.0, 1.0];
        let c = [-1.0, 0.0];
        let d = [0.0, -1.0];
        let s = incircle_sos(a, b, c, d);
        assert_ne!(s, 0);
        assert_eq!(incircle_sos(b, a, c, d), -s);
        assert_eq!(incircle_sos(b, c, a, d), s);
        // flipping the quad: exactly one of the two diagonals is locally Delaunay
        let s2 = incircle_sos(b, c, d, a);
        assert_eq!(s2, -s);
    }

    #[test]
    fn integer_kernel_agrees_with_float_kernel() {
        let mut s = Rng::new(12345);
        let mut next = |m: i64| s.below(2 * m as u64 + 1) as i64 - m;
        for k in 0..4000 {
            // small ranges give many exact ties; large ones test the i128 range
            let m = if k % 2 == 0 { 3 } else { (1 << 27) - 1 };
            let q: Vec<[i64; 2]> = (0..4).map(|_| [next(m), next(m)]).collect();
            let f: Vec<[f64; 2]> = q.iter().map(|p| [p[0] as f64, p[1] as f64]).collect();
            assert_eq!(
                IntKernel::orient(q[0], q[1], q[2]),
                FloatKernel::orient(f[0], f[1], f[2])
            );
            if q.iter().enumerate().any(|(i, a)| q[..i].contains(a)) {
                continue;
            }
            assert_eq!(
                IntKernel::incircle_sos(q[0], q[1], q[2], q[3]),
                incircle_sos(f[0], f[1], f[2], f[3]),
                "{q:?}"
            );
        }
    }

    /// 4×4 determinant of rows (x, y, z, 1), exact in i128.
    fn det4(r: [[i128; 4]; 4]) -> i128 {
        fn det3(m: [[i128; 3]; 3]) -> i128 {
            m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
                - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
        }
        let mut s = 0;
        for col in 0..4 {
            let mut m = [[0i128; 3]; 3];
            for (i, row) in r.iter().skip(1).enumerate() {
                let mut k = 0;
                for (j, &v) in row.iter().enumerate() {
                    if j != col {
                        m[i][k] = v;
                        k += 1;
                    }
                }
            }
            let sign = if col % 2 == 0 { 1 } else { -1 };
            s += sign * r[0][col] * det3(m);
        }
        s
    }

    #[test]
    fn perturbation_matches_an_explicitly_lifted_determinant() {
        // Independent check of the coefficients in `sos_tiebreak`: lift every point to
        // x² + y² + B^rank (rank = lexicographic rank among the four). The determinant is linear
        // in the lifts, so for a cocircular quadruple it equals the perturbation sum exactly,
        // and with B large its sign is that of the greatest point's coefficient.
        let circle: Vec<[i64; 2]> = {
            let mut v = Vec::new();
            for x in -25i64..=25 {
                for y in -25i64..=25 {
                    if x * x + y * y == 25 * 25 {
                        v.push([x, y]);
                    }
                }
            }
            v
        };
        assert!(circle.len() >= 12);
        let lifted = |q: [[i64; 2]; 4], bump: bool| -> i128 {
            let mut rank = [0u32; 4];
            for i in 0..4 {
                rank[i] = (0..4).filter(|&j| q[j] < q[i]).count() as u32;
            }
            let b: i128 = 1 << 30;
            let rows = [0, 1, 2, 3].map(|i| {
                let (x, y) = (q[i][0] as i128, q[i][1] as i128);
                let eps = if bump { b.pow(rank[i]) } else { 0 };
                [x, y, x * x + y * y + eps, 1]
            });
            det4(rows)
        };
        // calibrate the sign convention on a point strictly inside
        let inside = [[25, 0], [0, 25], [-25, 0], [1, 2]];
        let s0 = lifted(inside, false).signum() as i32
            * IntKernel::incircle_sos(inside[0], inside[1], inside[2], inside[3]);
        assert!(s0 == 1 || s0 == -1);
        let mut checked = 0;
        for i in 0..circle.len() {
            for j in 0..circle.len() {
                for k in 0..circle.len() {
                    let (a, b, c) = (circle[i], circle[j], circle[k]);
                    if IntKernel::orient(a, b, c) <= 0 {
                        continue;
                    }
                    for &d in &circle {
                        if d == a || d == b || d == c {
                            continue;
                        }
                        let q = [a, b, c, d];
                        assert_eq!(lifted(q, false), 0);
                        let want = s0 * lifted(q, true).signum() as i32;
                        assert_eq!(IntKernel::incircle_sos(a, b, c, d), want, "{q:?}");
                        let f = q.map(|p| [p[0] as f64, p[1] as f64]);
                        assert_eq!(incircle_sos(f[0], f[1], f[2], f[3]), want);
                        checked += 1;
                    }
                }
            }
        }
        assert!(checked > 1000);
    }
}
