//! Discs with signed radius, half-planes and the ± operator; the flintstone of one polyline
//! (Veltkamp 1992, §7.2.1, Defs. 7.1–7.4; reading notes A.2–A.3).
//!
//! A polyline `v_p … v_s` is approximated by its chord `v_p v_s`. On each side of the chord
//! line the vertex `v_q` whose disc `D(v_p, v_s; v_q)` contains every vertex of that side is the
//! one of largest centre parameter `t` (notes A.2); it is found **exactly**: a candidate replaces
//! the current one iff it lies strictly outside the current circle (`incircle`, oriented by
//! `orient2d`). The flintstone is then `(D_q ∩ H_q) ∪ (D_r ∩ H_r)` — each disc restricted to its
//! own side — which is Def. 7.2's `D_q ± D_r`: an intersection iff `v_r` lies in the closed disc
//! `D_q` (⇔ `t_q + t_r ≤ 0`), else a union. One side empty gives a *cap* `D_q ∩ H_q` (the other
//! "disc" is the half-plane of radius −∞).
//!
//! Degenerate cases (notes A.3): a vertex on the chord, inside the closed segment, lies in every
//! disc through the chord ends and is skipped; all interior vertices on the chord give the
//! *segment* flintstone (widths 0); a vertex on the chord line outside the segment is in no
//! disc through the ends, and the flintstone is then *unbounded* (treated as the whole plane, so
//! queries always descend: correct, never faster). Membership ([`Flintstone::contains`]) is
//! exact. Centres, radii and widths are constructed in `f64` for reports and filters only.
//!
//! Widths (Def. 7.4, with the notes' correction `h_1 = sqrt(R_1² − r_1²)`): on a side with
//! parameter `t`, `w = t + sqrt(r² + t²)` (`r` = half the chord), evaluated without
//! cancellation. The split rule (Alg. 7.1) picks the cap vertex, else the larger signed radius
//! (⇔ larger `t`, ties to the left side); that is a choice of vertex, not a geometric decision
//! whose error could make a result wrong, so it is made on the constructed `t`.
//! Cost: O(k) for a polyline of k vertices.

use crate::geom::intersect::on_segment;
use crate::geom::predicates::incircle_sign;
use crate::geom::predicates::raw::orient2d;
use crate::geom::vec::{dist, dist2, dot, midpoint, perp, scale, sub};

/// The disc of one side of a chord: through both chord ends and its defining vertex.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SideDisc {
    /// Position of the defining vertex along the (unwrapped) polygon.
    pub pos: usize,
    /// Centre parameter `t` (signed distance of the centre from the chord midpoint, positive
    /// towards the vertex's side).
    pub t: f64,
    /// Centre of the disc.
    pub center: [f64; 2],
    /// Signed radius (Def. 7.1): negative when the centre and the vertex are on opposite sides.
    pub radius: f64,
    /// Width of the flintstone on this side (Def. 7.4, corrected).
    pub width: f64,
    /// A radius about `center` that covers every vertex of the polyline in `f64` (≥ |radius|):
    /// the conservative disc of the intersection filters.
    pub reach: f64,
}

/// What Def. 7.2 makes of the two sides.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StoneKind {
    /// Every vertex on one side: `D_q ∩ H_q`.
    Cap,
    /// `D_q ∩ D_r` (the only case V claims for 2D).
    Intersection,
    /// `D_q ∪ D_r` (supported although V says it cannot occur in 2D).
    Union,
    /// Every interior vertex on the chord segment: the flintstone is the segment itself.
    Segment,
    /// A vertex on the chord line outside the segment: no disc through the ends holds it.
    Unbounded,
}

impl StoneKind {
    /// Lower-case name, as written in reports and JSON.
    pub fn name(self) -> &'static str {
        match self {
            StoneKind::Cap => "cap",
            StoneKind::Intersection => "intersection",
            StoneKind::Union => "union",
            StoneKind::Segment => "segment",
            StoneKind::Unbounded => "unbounded",
        }
    }
}

/// The flintstone of the polyline between two chord ends (positions `lo < hi`).
#[derive(Debug, Clone, PartialEq)]
pub struct Flintstone {
    /// Position of the first chord end.
    pub lo: usize,
    /// Position of the last chord end.
    pub hi: usize,
    /// Disc of the vertices left of `lo → hi` (`orient2d > 0`), if any.
    pub left: Option<SideDisc>,
    /// Disc of the vertices right of `lo → hi`, if any.
    pub right: Option<SideDisc>,
    /// ∩, ∪, cap, segment or unbounded.
    pub kind: StoneKind,
    /// Centre and radius of one conservative disc covering the whole polyline (the chord
    /// midpoint and the largest vertex distance from it), for filters of ∪/segment/unbounded.
    pub hull: ([f64; 2], f64),
}

/// The vertex at position `p` of a polygon of `n` vertices (positions wrap).
#[inline]
pub(crate) fn at(points: &[[f64; 2]], p: usize) -> [f64; 2] {
    points[p % points.len()]
}

/// Calls `f(position, point)` for the positions `from..to` of a polygon (wrapping; `to − from`
/// at most the vertex count), in order, as at most two contiguous slices: no division and no
/// chained iterator per vertex.
#[inline]
fn for_positions(points: &[[f64; 2]], from: usize, to: usize, mut f: impl FnMut(usize, [f64; 2])) {
    let n = points.len();
    debug_assert!(to <= from + n);
    let start = from % n;
    let first = (to - from).min(n - start);
    for (k, &x) in points[start..start + first].iter().enumerate() {
        f(from + k, x);
    }
    let rest = to - from - first;
    for (k, &x) in points[..rest].iter().enumerate() {
        f(from + first + k, x);
    }
}

/// u = 2⁻⁵³, the unit roundoff.
const U: f64 = f64::EPSILON / 2.0;
/// Shewchuk's stage-A bound of the floating-point in-circle determinant,
/// `(10 + 96u)·u` (the constant of `robust::incircle` and
/// [`crate::geom::predicates::incircle_sign`]).
const ICC_ERRBOUND_A: f64 = (10.0 + 96.0 * U) * U;

/// The current widest-disc vertex of one side of a chord `a b`, with the parts of the in-circle
/// determinant that do not depend on the candidate precomputed.
///
/// [`Widest::outside`] evaluates Shewchuk's stage-A in-circle filter for the points
/// `(b, q, x; a)` — translated by `a`: `B = b − a`, `Q = q − a`, `X = x − a` — with every
/// floating-point operation in the order of `robust::incircle` /
/// [`crate::geom::predicates::incircle_sign`] on those arguments, so the determinant and the
/// permanent it computes are bit for bit theirs and Shewchuk's bound
/// `|det − exact| ≤ ICC_ERRBOUND_A · permanent` applies unchanged (the stored products are the
/// same roundings of the same operands, only computed once per widest vertex instead of once per
/// candidate). Within the bound the sign is left to the exact [`incircle_sign`]. So the decision
/// equals main's exact `incircle(a, b, q, x)` on every input (lockstep test
/// `widest_filter_equals_the_exact_incircle_loop`).
#[derive(Clone, Copy)]
struct Widest {
    pos: usize,
    q: [f64; 2],
    // B = b − a, |B|², Q = q − a, |Q|², and the B×Q products with their difference
    bx: f64,
    by: f64,
    alift: f64,
    qx: f64,
    qy: f64,
    blift: f64,
    adxbdy: f64,
    bdxady: f64,
    // the determinant as a quadratic in X, `X·G + |X|²·k` (`G = (gx, gy)`, `k = B×Q`), and the
    // same expression on the absolute values of its monomials, `|X|·P + |X|²·pk`
    gx: f64,
    gy: f64,
    k: f64,
    px: f64,
    py: f64,
    pk: f64,
    /// Every coordinate of the polyline's points is at most [`SMALL`] in magnitude: the
    /// quadratic filter's bound holds (else only Shewchuk's filter is used).
    quad: bool,
}

/// The largest coordinate magnitude for which [`Widest::outside`]'s quadratic filter is used:
/// 2¹⁰⁰ (no product of its evaluation can overflow, and an underflowing one is off by far less
/// than [`QUAD_TINY`]).
const SMALL: f64 = 1.2676506002282294e30;
/// The quadratic filter's bound per unit of the permanent: 13u (its evaluation has at most 11
/// roundings on the path of any monomial; see [`Widest::outside`]).
const QUAD_ERRBOUND: f64 = 13.0 * U;
/// The quadratic filter's absolute floor, 2⁻⁸⁶⁰: covers the underflow of its products.
const QUAD_TINY: f64 = 1.3007796349561859e-259;

/// True when every coordinate of `points` is at most 2¹⁰⁰ in magnitude (NaN: false): the
/// precondition of the quadratic in-circle filter of [`Flintstone::scan`].
pub(crate) fn small_coordinates(points: &[[f64; 2]]) -> bool {
    points
        .iter()
        .all(|p| p[0].abs() <= SMALL && p[1].abs() <= SMALL)
}

impl Widest {
    #[inline]
    fn new(a: [f64; 2], b: [f64; 2], q: [f64; 2], pos: usize, quad: bool) -> Widest {
        let (bx, by) = (b[0] - a[0], b[1] - a[1]);
        let (qx, qy) = (q[0] - a[0], q[1] - a[1]);
        let alift = bx * bx + by * by;
        let blift = qx * qx + qy * qy;
        let (adxbdy, bdxady) = (bx * qy, qx * by);
        Widest {
            pos,
            q,
            bx,
            by,
            alift,
            qx,
            qy,
            blift,
            adxbdy,
            bdxady,
            gx: blift * by - alift * qy,
            gy: alift * qx - blift * bx,
            k: adxbdy - bdxady,
            px: blift * by.abs() + alift * qy.abs(),
            py: alift * qx.abs() + blift * bx.abs(),
            pk: adxbdy.abs() + bdxady.abs(),
            quad,
        }
    }

    /// True when `x`, on the same side of `a → b` as this vertex (`left`: `orient2d(a, b, x) >
    /// 0`), lies strictly outside the circle through `a`, `b` and this vertex (exact).
    ///
    /// Inlined into the scan (a call per visit was a fifth of the build's CPU); the exact
    /// fallback is a cold function of its own.
    ///
    /// First the quadratic filter: with `X = x − a` (rounded), the determinant below is
    /// `X·G + |X|²·k`, `G = (|Q|²B_y − |B|²Q_y, |B|²Q_x − |Q|²B_x)` and `k = B×Q` precomputed
    /// per widest vertex — the sign of `|X|² − 2C·X` about the circle's centre `C = −G/2k`,
    /// scaled by `k` so that nothing is divided. Expanded in the exact differences, it is a sum
    /// of degree-4 monomials, and along the path of each the evaluation rounds at most 11 times
    /// (4 differences, 7 products and sums: `qx·qx`, `+ qy·qy`, `·by`, `−`, `·cx`, two sums;
    /// the `|X|²·k` monomials likewise), so, without underflow, `|det − exact| ≤ γ₁₁·Σ|monomials|`
    /// (Higham 2002, Lemma 3.3). `perm`, the same expression on the absolute values, is
    /// `Σ|monomials|` up to a factor `(1 ± u)¹¹`, so `13u·perm` (rounded) covers the error
    /// with room. With every coordinate at most 2¹⁰⁰ in magnitude (`quad`, checked once per
    /// tree), no product overflows, and an underflowing product (absolute error ≤ 2⁻¹⁰⁷⁵)
    /// passes through at most factors of 2²⁰³ more: 17 products, ≤ 2⁻⁸⁶⁷ in all, which the
    /// floor [`QUAD_TINY`] = 2⁻⁸⁶⁰ covers. When `|det|` is not above that bound, Shewchuk's
    /// stage A decides, then the exact [`incircle_sign`]: the decision is always the exact
    /// one (lockstep test `quadratic_filter_equals_shewchuk_and_the_exact_loop`).
    #[inline(always)]
    fn outside(&self, a: [f64; 2], b: [f64; 2], x: [f64; 2], left: bool) -> bool {
        match self.quad_sign(a, x) {
            // the sign convention of `outside_shewchuk` (the same determinant, nonzero here)
            Some(positive) => positive == left,
            None => self.outside_shewchuk(a, b, x, left),
        }
    }

    /// The quadratic filter of [`Widest::outside`]: `Some(det > 0)` when it decides, `None`
    /// when `|det|` is within its bound or the coordinates are out of its range.
    #[inline(always)]
    fn quad_sign(&self, a: [f64; 2], x: [f64; 2]) -> Option<bool> {
        self.quad_sign_with(a, x, QUAD_ERRBOUND)
    }

    /// [`Widest::quad_sign`] with the bound per unit of the permanent as a parameter (the
    /// tests show that a smaller one decides wrongly).
    #[inline(always)]
    fn quad_sign_with(&self, a: [f64; 2], x: [f64; 2], per_unit: f64) -> Option<bool> {
        let (cdx, cdy) = (x[0] - a[0], x[1] - a[1]);
        let clift = cdx * cdx + cdy * cdy;
        let det = (cdx * self.gx + cdy * self.gy) + clift * self.k;
        let perm = (cdx.abs() * self.px + cdy.abs() * self.py) + clift * self.pk;
        let errbound = per_unit * perm + QUAD_TINY;
        (self.quad && det.abs() > errbound).then_some(det > 0.0)
    }

    /// Shewchuk's stage-A filter in robust's order (see the type's doc), then the exact sign.
    #[inline]
    fn outside_shewchuk(&self, a: [f64; 2], b: [f64; 2], x: [f64; 2], left: bool) -> bool {
        // Shewchuk's incircle(pa, pb, pc, pd) with (pa, pb, pc, pd) = (b, q, x, a):
        // adx = B, bdx = Q, cdx = X
        let (cdx, cdy) = (x[0] - a[0], x[1] - a[1]);
        let bdxcdy = self.qx * cdy;
        let cdxbdy = cdx * self.qy;
        let cdxady = cdx * self.by;
        let adxcdy = self.bx * cdy;
        let clift = cdx * cdx + cdy * cdy;
        let det = self.alift * (bdxcdy - cdxbdy)
            + self.blift * (cdxady - adxcdy)
            + clift * (self.adxbdy - self.bdxady);
        let permanent = (bdxcdy.abs() + cdxbdy.abs()) * self.alift
            + (cdxady.abs() + adxcdy.abs()) * self.blift
            + (self.adxbdy.abs() + self.bdxady.abs()) * clift;
        let errbound = ICC_ERRBOUND_A * permanent;
        // (b, q, x, a) is an odd permutation of (a, b, q, x): this determinant is
        // −incircle(a, b, q, x), positive when x is outside the circle a, b, q taken
        // counter-clockwise; on the right side (a, b, q clockwise) outside is negative
        let s = if det > errbound {
            1
        } else if -det > errbound {
            -1
        } else {
            exact_incircle_sign(b, self.q, x, a)
        };
        if left {
            s > 0
        } else {
            s < 0
        }
    }
}

/// The running state of [`Flintstone::scan`] (one visit per interior vertex).
struct Scan {
    a: [f64; 2],
    b: [f64; 2],
    m: [f64; 2],
    hull2: f64,
    /// The widest vertex so far of the left (0) and the right (1) side.
    best: [Option<Widest>; 2],
    unbounded: bool,
    w_lo: usize,
    w_hi: usize,
    far: Option<usize>,
    far_o: f64,
    outer: [[f64; 2]; 2],
    outer2: [f64; 2],
    /// The quadratic in-circle filter may be used ([`small_coordinates`]).
    quad: bool,
}

impl Scan {
    /// One vertex `x` at position `p`: the same decisions, in the same order, as main's loop
    /// (`of_windowed_reference` in the tests), plus the two `outer` distances.
    #[inline(always)]
    fn visit(&mut self, p: usize, x: [f64; 2]) {
        self.hull2 = self.hull2.max(dist2(self.m, x));
        self.outer2[0] = self.outer2[0].max(dist2(self.outer[0], x));
        self.outer2[1] = self.outer2[1].max(dist2(self.outer[1], x));
        let o = orient2d(self.a, self.b, x);
        if p >= self.w_lo && p <= self.w_hi && o.abs() > self.far_o {
            (self.far, self.far_o) = (Some(p), o.abs());
        }
        if o == 0.0 {
            self.unbounded |= !on_segment(self.a, self.b, x);
            return;
        }
        let left = o > 0.0;
        let best = &mut self.best[!left as usize];
        // the current vertex is on the same side as x: x replaces it iff x lies strictly
        // outside the circle through a, b and it
        let replace = match best {
            None => true,
            Some(w) => w.outside(self.a, self.b, x, left),
        };
        if replace {
            *best = Some(Widest::new(self.a, self.b, x, p, self.quad));
        }
    }
}

/// [`incircle_sign`] out of line: the rare case of [`Widest::outside`] whose filter cannot
/// decide.
#[cold]
#[inline(never)]
fn exact_incircle_sign(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> i32 {
    incircle_sign(a, b, c, d)
}

/// True when `x` lies in the closed disc through `a`, `b`, `v` (exact; `v` off line ab).
#[inline]
pub(crate) fn in_closed_disc(a: [f64; 2], b: [f64; 2], v: [f64; 2], x: [f64; 2]) -> bool {
    let o = orient2d(a, b, v);
    let ic = incircle_sign(a, b, v, x);
    if o > 0.0 {
        ic >= 0
    } else {
        ic <= 0
    }
}

/// Width `t + sqrt(r² + t²)` without cancellation for negative `t`.
fn width(r: f64, t: f64) -> f64 {
    let s = (r * r + t * t).sqrt();
    if t >= 0.0 {
        t + s
    } else {
        r * r / (s - t)
    }
}

/// Constructs the side disc of vertex `x` (position `pos`) for the chord `a b`.
fn side_disc(a: [f64; 2], b: [f64; 2], x: [f64; 2], pos: usize) -> SideDisc {
    let m = midpoint(a, b);
    let r = dist(a, b) / 2.0;
    let u = scale(sub(b, a), 0.5 / r);
    let nrm = perp(u);
    let d = sub(x, m);
    let along = dot(d, u);
    let h_signed = dot(d, nrm);
    let h = h_signed.abs();
    let t = (along * along + h * h - r * r) / (2.0 * h);
    let side = if h_signed > 0.0 { 1.0 } else { -1.0 };
    let center = [m[0] + side * t * nrm[0], m[1] + side * t * nrm[1]];
    let rad = (r * r + t * t).sqrt();
    SideDisc {
        pos,
        t,
        center,
        radius: if t < 0.0 { -rad } else { rad },
        width: width(r, t),
        reach: rad,
    }
}

impl Flintstone {
    /// The flintstone of the polyline at positions `lo..=hi` (`hi ≥ lo + 2`) of `points`
    /// (positions taken modulo `points.len()`). The chord ends must differ.
    pub fn of(points: &[[f64; 2]], lo: usize, hi: usize) -> Flintstone {
        Flintstone::of_windowed(points, lo, hi, None).0
    }

    /// [`Flintstone::of`], and in the same pass the position in the closed position range
    /// `window` (inside `lo + 1..=hi − 1`, non-empty) farthest from the chord line (largest
    /// `|orient2d|` as constructed — a choice, not a decision; ties to the first, all on the
    /// line: the window's middle). `None` without a window. The balanced split of
    /// `tree2.rs` (the depth budget) takes it when Alg. 7.1's vertex would leave a part too
    /// large.
    pub(crate) fn of_windowed(
        points: &[[f64; 2]],
        lo: usize,
        hi: usize,
        window: Option<[usize; 2]>,
    ) -> (Flintstone, Option<usize>) {
        let mut quad = true;
        for_positions(points, lo, hi + 1, |_, x| {
            quad &= small_coordinates(&[x]);
        });
        Flintstone::of_windowed_with(points, lo, hi, window, quad)
    }

    /// [`Flintstone::of_windowed`] with the quadratic in-circle filter allowed or not (`quad`:
    /// every coordinate of `lo..=hi` is at most 2¹⁰⁰ in magnitude, [`small_coordinates`];
    /// `false` is always allowed and leaves every in-circle test to Shewchuk's filter and the
    /// exact sign).
    pub(crate) fn of_windowed_with(
        points: &[[f64; 2]],
        lo: usize,
        hi: usize,
        window: Option<[usize; 2]>,
        quad: bool,
    ) -> (Flintstone, Option<usize>) {
        // the reach pass left out of the scan: the vertices' largest distances from this
        // stone's own side centres, folded in here (the tree folds them into the children's
        // scans instead, `FlintTree2::build`)
        let (mut stone, far, _) = Flintstone::scan(points, lo, hi, window, [[0.0; 2]; 2], quad);
        let c = stone.centres();
        let mut reach2 = [0.0f64; 2];
        for_positions(points, lo, hi + 1, |_, x| {
            reach2[0] = reach2[0].max(dist2(c[0], x));
            reach2[1] = reach2[1].max(dist2(c[1], x));
        });
        stone.finish_reach(reach2);
        (stone, far)
    }

    /// The side centres `[left, right]` as the reach accumulators of [`Flintstone::scan`] and
    /// [`Flintstone::finish_reach`] index them (`[0, 0]` for an absent side: its accumulator
    /// is ignored).
    #[inline]
    pub(crate) fn centres(&self) -> [[f64; 2]; 2] {
        [self.left, self.right].map(|d| d.map_or([0.0; 2], |d| d.center))
    }

    /// Sets each side disc's `reach` to `max(|radius|, sqrt(reach2[k]))`, `reach2[k]` being
    /// the largest squared `f64` distance of the polyline's vertices `lo..=hi` from that
    /// side's centre (`k` = 0 left, 1 right) — the conservative reach of [`SideDisc::reach`].
    /// A maximum does not depend on the order in which the vertices were seen, so the reach is
    /// the same whichever passes gathered `reach2`.
    pub(crate) fn finish_reach(&mut self, reach2: [f64; 2]) {
        for (k, d) in [&mut self.left, &mut self.right].into_iter().enumerate() {
            if let Some(d) = d {
                d.reach = d.reach.max(reach2[k].sqrt());
            }
        }
    }

    /// The one scan of [`Flintstone::of_windowed`] over the interior positions `lo + 1..hi`:
    /// the side discs, the kind, the hull, the window's farthest position, and — for the tree,
    /// which passes its parent's side centres as `outer` — the largest squared `f64` distance
    /// of these interior vertices from each of `outer` (the parent's reach, gathered here
    /// instead of in a pass of its own). The side discs' `reach` is only `|radius|`: the
    /// caller completes it with [`Flintstone::finish_reach`]. `quad`: every coordinate of the
    /// points scanned is at most 2¹⁰⁰ in magnitude ([`small_coordinates`]), so that the
    /// quadratic in-circle filter of [`Widest::outside`] may be used.
    pub(crate) fn scan(
        points: &[[f64; 2]],
        lo: usize,
        hi: usize,
        window: Option<[usize; 2]>,
        outer: [[f64; 2]; 2],
        quad: bool,
    ) -> (Flintstone, Option<usize>, [f64; 2]) {
        let (a, b) = (at(points, lo), at(points, hi));
        // an empty range (never in the window) when there is no window
        let [w_lo, w_hi] = window.unwrap_or([1, 0]);
        // the chord midpoint's largest squared vertex distance (the `hull`), folded into the
        // same pass: a maximum, so the order of the vertices does not matter
        let m = midpoint(a, b);
        let mut s = Scan {
            a,
            b,
            m,
            hull2: dist2(m, a).max(dist2(m, b)),
            best: [None, None],
            unbounded: false,
            w_lo,
            w_hi,
            far: window.map(|[l, h]| l + (h - l) / 2),
            far_o: 0.0,
            outer,
            outer2: [0.0; 2],
            quad,
        };
        // the positions lo + 1..hi as at most two contiguous slices, one loop each with the
        // visit inlined
        let n = points.len();
        let (from, to) = (lo + 1, hi);
        debug_assert!(to <= from + n);
        let start = from % n;
        let first = (to - from).min(n - start);
        for (k, &x) in points[start..start + first].iter().enumerate() {
            s.visit(from + k, x);
        }
        for (k, &x) in points[..to - from - first].iter().enumerate() {
            s.visit(from + first + k, x);
        }
        let [best_l, best_r] = s.best.map(|w| w.map(|w| w.pos));
        let left = best_l.map(|q| side_disc(a, b, at(points, q), q));
        let right = best_r.map(|q| side_disc(a, b, at(points, q), q));
        let kind = match (best_l, best_r) {
            _ if s.unbounded => StoneKind::Unbounded,
            (None, None) => StoneKind::Segment,
            (Some(_), None) | (None, Some(_)) => StoneKind::Cap,
            (Some(q), Some(r)) => {
                if in_closed_disc(a, b, at(points, q), at(points, r)) {
                    StoneKind::Intersection
                } else {
                    StoneKind::Union
                }
            }
        };
        let stone = Flintstone {
            lo,
            hi,
            left,
            right,
            kind,
            hull: (m, s.hull2.sqrt()),
        };
        (stone, s.far, s.outer2)
    }

    /// The flintstone error `max{w_1, w_2}` (Def. 7.4; 0 for a segment, ∞ when unbounded).
    pub fn error(&self) -> f64 {
        if self.kind == StoneKind::Unbounded {
            return f64::INFINITY;
        }
        let w = |d: &Option<SideDisc>| d.map_or(0.0, |d| d.width);
        w(&self.left).max(w(&self.right))
    }

    /// The two widths `(w_1, w_2)` (left, right; 0 for an empty side).
    pub fn widths(&self) -> (f64, f64) {
        let w = |d: &Option<SideDisc>| d.map_or(0.0, |d| d.width);
        (w(&self.left), w(&self.right))
    }

    /// The split vertex of Alg. 7.1: the cap's vertex, else the one of larger signed radius
    /// (ties: left); `None` when no disc exists (segment, or unbounded without discs).
    pub fn split(&self) -> Option<usize> {
        match (self.left, self.right) {
            (Some(l), Some(r)) => Some(if r.t > l.t { r.pos } else { l.pos }),
            (Some(d), None) | (None, Some(d)) => Some(d.pos),
            (None, None) => None,
        }
    }

    /// Exact membership of `x` in the closed flintstone `(D_q ∩ H_q) ∪ (D_r ∩ H_r)` ∪ chord
    /// (always true when unbounded).
    pub fn contains(&self, points: &[[f64; 2]], x: [f64; 2]) -> bool {
        if self.kind == StoneKind::Unbounded {
            return true;
        }
        let (a, b) = (at(points, self.lo), at(points, self.hi));
        let o = orient2d(a, b, x);
        let side = if o > 0.0 {
            &self.left
        } else if o < 0.0 {
            &self.right
        } else {
            return on_segment(a, b, x);
        };
        match side {
            Some(d) => in_closed_disc(a, b, at(points, d.pos), x),
            None => false,
        }
    }

    /// Conservative discs `(centre, radius)` each of which contains the whole polyline and
    /// chord (in `f64`, with the vertices' distances folded in): the two full discs of an
    /// intersection, the disc of a cap, else one disc about the chord midpoint. A flintstone
    /// meets another only if every disc of one meets every disc of the other.
    pub fn filter_discs(&self) -> smallvec::SmallVec<[([f64; 2], f64); 2]> {
        let mut v = smallvec::SmallVec::new();
        match self.kind {
            StoneKind::Intersection | StoneKind::Cap => {
                for d in [self.left, self.right].into_iter().flatten() {
                    v.push((d.center, d.reach));
                }
            }
            _ => v.push(self.hull),
        }
        v
    }
}

/// True when two closed discs may meet (`f64`, with a relative slack so that rounding never
/// turns a meeting pair into a miss). A disc with an infinite or NaN centre or radius (the side
/// disc of a vertex a subnormal distance off its chord: `t` overflows) always may: the test is
/// written so that NaN never rejects.
#[inline]
pub(crate) fn discs_meet(a: ([f64; 2], f64), b: ([f64; 2], f64)) -> bool {
    let d = dist(a.0, b.0);
    let slack = 1e-12 * (a.1 + b.1 + a.0[0].abs() + a.0[1].abs() + b.0[0].abs() + b.0[1].abs());
    // NaN compares as `None`: "may meet"
    d.partial_cmp(&(a.1 + b.1 + slack)) != Some(std::cmp::Ordering::Greater)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::predicates::raw::incircle;

    #[test]
    fn cap_intersection_and_degenerate_kinds() {
        // arch above the chord: a cap through the apex
        let p = [[0.0, 0.0], [1.0, 1.0], [2.0, 1.5], [3.0, 1.0], [4.0, 0.0]];
        let f = Flintstone::of(&p, 0, 4);
        assert_eq!(f.kind, StoneKind::Cap);
        assert_eq!(f.split(), Some(2));
        assert!(p.iter().all(|&x| f.contains(&p, x)));
        assert!(!f.contains(&p, [2.0, -0.01]));
        // zig-zag: both sides, intersection
        let z = [[0.0, 0.0], [1.0, 0.5], [3.0, -0.5], [4.0, 0.0]];
        let g = Flintstone::of(&z, 0, 3);
        assert_eq!(g.kind, StoneKind::Intersection);
        let (w1, w2) = g.widths();
        assert!(w1 >= 0.5 && w2 >= 0.5, "{w1} {w2}");
        // straight run
        let s = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]];
        assert_eq!(Flintstone::of(&s, 0, 2).kind, StoneKind::Segment);
        assert_eq!(Flintstone::of(&s, 0, 2).error(), 0.0);
        // a vertex beyond the chord end on its line
        let u = [[0.0, 0.0], [3.0, 0.0], [2.0, 0.0]];
        assert_eq!(Flintstone::of(&u, 0, 2).kind, StoneKind::Unbounded);
    }

    /// Main's selection loop before the precomputed filter (robust's `incircle` per candidate,
    /// hull and reaches in one second pass): the oracle of the lockstep test below.
    fn of_windowed_reference(
        points: &[[f64; 2]],
        lo: usize,
        hi: usize,
        window: Option<[usize; 2]>,
    ) -> (Flintstone, Option<usize>) {
        let n = points.len();
        let (a, b) = (at(points, lo), at(points, hi));
        let (mut best_l, mut best_r): (Option<usize>, Option<usize>) = (None, None);
        let mut unbounded = false;
        let [w_lo, w_hi] = window.unwrap_or([1, 0]);
        let (mut far, mut far_o) = (window.map(|[l, h]| l + (h - l) / 2), 0.0f64);
        for p in lo + 1..hi {
            let x = points[p % n];
            let o = orient2d(a, b, x);
            if p >= w_lo && p <= w_hi && o.abs() > far_o {
                (far, far_o) = (Some(p), o.abs());
            }
            if o == 0.0 {
                unbounded |= !on_segment(a, b, x);
                continue;
            }
            let best = if o > 0.0 { &mut best_l } else { &mut best_r };
            match *best {
                None => *best = Some(p),
                Some(q) => {
                    let ic = incircle(a, b, points[q % n], x);
                    if (o > 0.0 && ic < 0.0) || (o < 0.0 && ic > 0.0) {
                        *best = Some(p);
                    }
                }
            }
        }
        let mut left = best_l.map(|q| side_disc(a, b, at(points, q), q));
        let mut right = best_r.map(|q| side_disc(a, b, at(points, q), q));
        let kind = match (best_l, best_r) {
            _ if unbounded => StoneKind::Unbounded,
            (None, None) => StoneKind::Segment,
            (Some(_), None) | (None, Some(_)) => StoneKind::Cap,
            (Some(q), Some(r)) => {
                if in_closed_disc(a, b, at(points, q), at(points, r)) {
                    StoneKind::Intersection
                } else {
                    StoneKind::Union
                }
            }
        };
        let m = midpoint(a, b);
        let mut hull2: f64 = 0.0;
        let mut reach2 = [0.0f64; 2];
        for p in lo..=hi {
            let x = points[p % n];
            hull2 = hull2.max(dist2(m, x));
            for (k, d) in [&left, &right].into_iter().enumerate() {
                if let Some(d) = d {
                    reach2[k] = reach2[k].max(dist2(d.center, x));
                }
            }
        }
        for (k, d) in [&mut left, &mut right].into_iter().enumerate() {
            if let Some(d) = d {
                d.reach = d.reach.max(reach2[k].sqrt());
            }
        }
        let stone = Flintstone {
            lo,
            hi,
            left,
            right,
            kind,
            hull: (m, hull2.sqrt()),
        };
        (stone, far)
    }

    /// The precomputed in-circle filter and the one-slice-or-two walk against the plain loop
    /// with robust's `incircle`, on inputs where the filter is and is not conclusive: points on
    /// a circle rounded to `f64` (every in-circle determinant within rounding of 0, so a filter
    /// with a wrong bound or a sign slip picks another vertex), exactly cocircular integer
    /// points, collinear runs, repeated points, random walks; wrapping ranges and windows.
    #[test]
    fn widest_filter_equals_the_exact_incircle_loop() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(18);
        let mut sets: Vec<Vec<[f64; 2]>> = Vec::new();
        for n in [7usize, 64, 1000] {
            // a circle, rounded; one with a random phase and radius; a far-off-origin circle
            let r: f64 = rng.gen_range(0.5..3.0);
            let ph: f64 = rng.gen_range(0.0..1.0);
            for (c, s) in [(0.0, 1.0), (1e6, r), (-3.7, r)] {
                sets.push(
                    (0..n)
                        .map(|k| {
                            let t = (k as f64 + ph) * std::f64::consts::TAU / n as f64;
                            [c + s * t.cos(), c + s * t.sin()]
                        })
                        .collect(),
                );
            }
            // random walk; a walk on a coarse grid (collinear and cocircular ties)
            let mut p = [0.0f64, 0.0];
            sets.push(
                (0..n)
                    .map(|_| {
                        p = [
                            p[0] + rng.gen_range(-1.0..1.0),
                            p[1] + rng.gen_range(-1.0..1.0),
                        ];
                        p
                    })
                    .collect(),
            );
            sets.push(
                (0..n)
                    .map(|_| [rng.gen_range(-3..=3) as f64, rng.gen_range(-3..=3) as f64])
                    .collect(),
            );
        }
        // exactly cocircular integer points (radius 25), in circle order
        let mut c5: Vec<[f64; 2]> = (-25i32..=25)
            .flat_map(|x| (-25i32..=25).map(move |y| (x, y)))
            .filter(|&(x, y)| x * x + y * y == 625)
            .map(|(x, y)| [x as f64, y as f64])
            .collect();
        c5.sort_by(|p, q| p[1].atan2(p[0]).total_cmp(&q[1].atan2(q[0])));
        sets.push(c5);
        let mut checked = 0;
        for pts in &sets {
            let n = pts.len();
            for _ in 0..40 {
                let lo = rng.gen_range(0..n);
                let len = rng.gen_range(2..n.max(3));
                let hi = lo + len;
                if pts[lo % n] == pts[hi % n] {
                    continue;
                }
                let window = rng.gen_bool(0.5).then(|| {
                    let l = rng.gen_range(lo + 1..hi);
                    [l, rng.gen_range(l..hi)]
                });
                let got = Flintstone::of_windowed(pts, lo, hi, window);
                let want = of_windowed_reference(pts, lo, hi, window);
                assert_eq!(got, want, "n {n} lo {lo} hi {hi} window {window:?}");
                checked += 1;
            }
        }
        assert!(checked > 400, "{checked}");
    }

    /// The quadratic in-circle filter against the exact sign, candidate by candidate: random
    /// chords and widest vertices at scales from 1e-150 (every product underflows: the floor
    /// must refuse) through 1e-70 (monomials subnormal) to 1e25 (near the 2¹⁰⁰ limit) and 1e35
    /// (beyond it: the filter is off), far from and near the origin, candidates random or on
    /// the circle rounded to `f64` (within rounding of the circle, where a bound too small
    /// decides wrongly). Every answer of `outside`, of Shewchuk's filter and of the quadratic
    /// filter where it decides equals the exact sign; the quadratic filter decides most random
    /// candidates (else it would be dead weight).
    #[test]
    fn quadratic_filter_equals_shewchuk_and_the_exact_loop() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(71);
        let (mut total, mut decided, mut random, mut random_decided) = (0, 0, 0, 0);
        let mut wrong_unbounded = 0;
        // the constants are the powers of two their docs say
        assert_eq!((SMALL, QUAD_TINY), (2f64.powi(100), 2f64.powi(-860)));
        for scale in [1e-150, 1e-70, 1e-60, 1e-6, 1.0, 1e6, 1e25, 1e35] {
            for off in [0.0, 3.0, 1e4] {
                let pt = |rng: &mut rand_chacha::ChaCha8Rng| -> [f64; 2] {
                    [
                        (off + rng.gen_range(-1.0..1.0)) * scale,
                        (off + rng.gen_range(-1.0..1.0)) * scale,
                    ]
                };
                for _ in 0..3000 {
                    let (a, b, q) = (pt(&mut rng), pt(&mut rng), pt(&mut rng));
                    let oq = orient2d(a, b, q);
                    if oq == 0.0 {
                        continue;
                    }
                    let left = oq > 0.0;
                    let on_circle = rng.gen_bool(0.5);
                    let x = if on_circle {
                        // the circumcentre and radius in f64, a point on that circle
                        let (bx, by) = (b[0] - a[0], b[1] - a[1]);
                        let (qx, qy) = (q[0] - a[0], q[1] - a[1]);
                        let d = 2.0 * (bx * qy - by * qx);
                        let (bb, qq) = (bx * bx + by * by, qx * qx + qy * qy);
                        let ux = (qy * bb - by * qq) / d;
                        let uy = (bx * qq - qx * bb) / d;
                        let r = (ux * ux + uy * uy).sqrt();
                        let t: f64 = rng.gen_range(0.0..std::f64::consts::TAU);
                        [a[0] + ux + r * t.cos(), a[1] + uy + r * t.sin()]
                    } else {
                        pt(&mut rng)
                    };
                    let o = orient2d(a, b, x);
                    if o == 0.0 || (o > 0.0) != left || !x.iter().all(|c| c.is_finite()) {
                        continue;
                    }
                    let w = Widest::new(a, b, q, 0, small_coordinates(&[a, b, q, x]));
                    // the exact sign (robust's `incircle` is wrong where its expansions
                    // underflow, at the 1e-150 scale)
                    let ic = incircle_sign(a, b, q, x);
                    let exact = if left { ic < 0 } else { ic > 0 };
                    assert_eq!(w.outside(a, b, x, left), exact, "{a:?} {b:?} {q:?} {x:?}");
                    assert_eq!(w.outside_shewchuk(a, b, x, left), exact);
                    total += 1;
                    // the scales where the filter applies and no monomial is below its floor
                    let applies = (1e-60..=1e25).contains(&scale);
                    random += (!on_circle && applies) as usize;
                    if let Some(pos) = w.quad_sign(a, x) {
                        assert!(applies, "decided at {scale}");
                        assert_eq!(pos == left, exact, "{a:?} {b:?} {q:?} {x:?}");
                        decided += 1;
                        random_decided += (!on_circle && applies) as usize;
                    }
                    // the mutation check built in: no relative bound at all decides some
                    // near-circle candidates wrongly
                    if let Some(pos) = w.quad_sign_with(a, x, 0.0) {
                        wrong_unbounded += ((pos == left) != exact) as usize;
                    }
                }
            }
        }
        assert!(total > 20_000, "{total}");
        assert!(
            decided > 0 && random_decided * 10 > random * 9,
            "{random_decided} of {random}"
        );
        assert!(
            wrong_unbounded > 0,
            "a filter without its bound was never wrong"
        );
    }

    #[test]
    fn width_of_half_disc_is_radius() {
        // semicircle apex: t = 0, width = r
        let p = [[-1.0, 0.0], [0.0, 1.0], [1.0, 0.0]];
        let f = Flintstone::of(&p, 0, 2);
        assert!((f.error() - 1.0).abs() < 1e-15);
        assert!((f.left.unwrap().radius - 1.0).abs() < 1e-15);
        // a shallow bump: negative signed radius, width = bump height
        let q = [[-1.0, 0.0], [0.0, 0.1], [1.0, 0.0]];
        let g = Flintstone::of(&q, 0, 2);
        assert!(g.left.unwrap().radius < 0.0);
        assert!((g.error() - 0.1).abs() < 1e-15);
    }
}
