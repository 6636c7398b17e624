//! The γ-neighborhood graph (Veltkamp 1992, ch. 3: Defs. 3.1–3.3, Lemmas 3.1–3.3, Thms 3.1–3.2;
//! paper "2D Computational Morphology" §2).
//!
//! # The neighbourhood as an interval of ball centres
//! For a (k−1)-simplex σ in kD (an edge in 2D, a triangle in 3D) let `m` be the centre and `r`
//! the radius of its smallest touching ball, and `n` a normal of its hyperplane. Every ball
//! touching σ's vertices has its centre at `m + s·n` for a signed offset `s` and radius
//! `√(r² + s²)`; the parameter c of Def. 3.1 and the offset are related by
//! `|c| = 1 − r/√(r² + s²)` (s = ±∞ is a half-space, |c| = 1).
//!
//! A point x with height `h = (x − m)·n` and power `q = |x − m|² − r²` lies strictly inside the
//! ball of offset s iff `q < 2·s·h`. So a point above the hyperplane (h > 0) blocks the offsets
//! `s > τ(x) = q / 2h`, a point below blocks `s < τ(x)`, and a point in the hyperplane blocks every
//! finite ball when q < 0 (and every neighbourhood when it lies in the closed simplex, which is
//! part of each neighbourhood). Hence the balls touching σ that are empty are exactly those with
//! offset in one interval `[lo, hi]`, `hi = min τ` over the points above and `lo = max τ` below
//! ([`CenterInterval`]). Every γ-neighbourhood of σ is empty or not according to this interval:
//! - union neighbourhoods (c₁ ≥ 0) are empty iff both balls' offsets lie in `[lo, hi]`;
//! - intersection neighbourhoods (c₁ < 0) are empty iff the offsets of the two balls span an
//!   interval that meets `[lo, hi]` (when `lo > hi`: that covers the gap `[hi, lo]`).
//!
//! The *γ-values* (c₀′, c₁′) of σ — the largest parameters whose neighbourhood is empty
//! (Def. 3.3) — follow from the interval's two ends (see [`CenterInterval::gamma_values`]), and
//! σ ∈ γ(c₀, c₁) is then decided by Lemmas 3.1 and 3.2 ([`in_gamma`]) and
//! σ ∈ γ(\[c₀,c₁\],\[c₂,c₃\]) by Def. 3.3 ([`in_gamma_range`]).
//!
//! Sidedness (the sign of h) is decided by the exact orientation predicates. The offsets τ are
//! computed in floating point from the differences to a corner with a proven running error
//! bound (`geom::bounded`); a binding point's τ is kept when the bound certifies it to a
//! relative [`TAU_TOL`] of |τ| + r/|n| and is otherwise recomputed from exact expansions
//! ([`exact_offset`], [`exact_offset_2d`]) — points nearly in the hyperplane, e.g. nearly on
//! the circumcircle of a nearly cospherical (cocircular) set, where q and h are both
//! rounding-sized and the float quotient meaningless. The ends' order is decided by exact
//! in-circle/in-sphere tests, so the regime of the γ-values is exact. The floats are what the
//! γ-values report; the *decisions* are exact: c₁′ ≥ c ([`TriFrame::c1_at_least`],
//! [`EdgeFrame::c1_at_least`]) by the sign of τ² (1 − |c|)² − ρ₀² |c| (2 − |c|) for the binding
//! points, from the proven bounds when they decide it, else in big integers
//! (`geom::exact::offset_reach_sign_3d`, `offset_reach_sign_2d`); and every comparison of c₀′
//! or c₁′ with a parameter ([`CenterInterval::cmp_gamma_by`], [`EdgeFrame::cmp_gamma`],
//! [`TriFrame::cmp_gamma`]) by the same signs plus the exact side of the smallest touching
//! ball at the binding points, hence σ ∈ γ(c₀, c₁) and σ ∈ γ(\[c₀,c₁\],\[c₂,c₃\])
//! ([`EdgeFrame::in_gamma`], [`EdgeFrame::in_gamma_range`] and the [`TriFrame`] ones), which
//! the graph builders use (`morpho graph --kind gamma | gamma-range`). Still in floating point:
//! [`CenterInterval::neighborhood_empty`] and [`CenterInterval::ball_empty`] (the α-shapes;
//! tests), [`in_gamma`] / [`in_gamma_range`] on given rounded γ-values, the gap case of
//! [`CenterInterval::witness_offset`], and the brute-force oracles [`def_contains_2d`],
//! [`def_contains_3d`].
//!
//! Complexity: one simplex against N points costs O(N) ([`center_interval_2d`],
//! [`center_interval_3d`]); the brute-force graphs of Thm 3.1 cost O(N^{k+1}).

use crate::geom::bounded::Bounded;
use crate::geom::distance::dot_sign;
use crate::geom::near_sphere::{Lift, NearSphere};
use crate::geom::predicates::{incircle_sign, raw};
use crate::geom::vec::{cross, dot, sub};
use std::cmp::Ordering;

/// The offsets (in units of the simplex's unnormalised normal) of the empty balls touching a
/// simplex: exactly the balls with offset in `[lo, hi]` are empty (`lo > hi`: none is).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CenterInterval {
    /// Largest τ over points below the hyperplane (−∞ if none).
    pub lo: f64,
    /// Smallest τ over points above the hyperplane (+∞ if none).
    pub hi: f64,
    /// The radius of the smallest touching ball divided by the length of the normal used, so
    /// that an offset s corresponds to |c| = 1 − ρ₀/√(ρ₀² + s²).
    pub r_over_n: f64,
    /// Some point in the hyperplane lies strictly inside the smallest touching ball but outside
    /// the closed simplex (possible in 3D only): every finite ball is blocked.
    pub finite_blocked: bool,
    /// Some point lies in the closed simplex (other than its vertices): every neighbourhood is
    /// blocked.
    pub all_blocked: bool,
    /// The point that fixes `lo` (a point below whose ball is the largest empty one), if any.
    pub lo_at: Option<[f64; 3]>,
    /// The point that fixes `hi`, if any.
    pub hi_at: Option<[f64; 3]>,
    /// τ of `lo_at` and `hi_at` as computed, before [`CenterInterval::settle`] adjusted the
    /// ends to their exact order: a new binding point on one side restores the other end from
    /// here instead of recomputing its offset.
    lo_raw: f64,
    hi_raw: f64,
}

/// |c| of the ball with offset `s` (in normal units) for a simplex with `r_over_n`.
#[inline]
pub fn abs_c(s: f64, r_over_n: f64) -> f64 {
    if s.is_infinite() {
        return 1.0;
    }
    // 1 − r/ρ = s²/(ρ(ρ + r)) without cancellation, and without overflow for the huge
    // offsets of points that are nearly in the hyperplane: in terms of the smaller ratio
    // u = min(|s|, r)/max(|s|, r), with √(1 + u²) ≤ √2
    let (s, r) = (s.abs(), r_over_n.abs());
    if s == 0.0 {
        return 0.0;
    }
    if s <= r {
        let u = s / r;
        let w = (1.0 + u * u).sqrt();
        u * u / (w * (w + 1.0))
    } else {
        let u = r / s;
        let w = (1.0 + u * u).sqrt();
        1.0 / (w * (w + u))
    }
}

/// Offset (in normal units, ≥ 0) of a ball with parameter |c| (as ρ₀ √(k² − 1): 0 for
/// |c| < 2⁻⁵³; [`offset_ratio`] is accurate there).
#[inline]
pub fn offset_of(c_abs: f64, r_over_n: f64) -> f64 {
    if c_abs >= 1.0 {
        return f64::INFINITY;
    }
    let k = 1.0 / (1.0 - c_abs);
    r_over_n * (k * k - 1.0).max(0.0).sqrt()
}

/// √(k² − 1) for k = 1/(1 − |c|) (the offset of the balls with parameter ±|c| over ρ₀),
/// computed as √(|c| (2 − |c|)) / (1 − |c|) to a few ulps: k² − 1 cancels for tiny |c| (for
/// |c| < 2⁻⁵³, 1 − |c| rounds to 1 and k² − 1 to 0, though the offset is ≈ ρ₀ √(2|c|)).
/// ∞ for |c| ≥ 1.
#[inline]
pub fn offset_ratio(c_abs: f64) -> f64 {
    if c_abs >= 1.0 {
        return f64::INFINITY;
    }
    (c_abs * (2.0 - c_abs)).max(0.0).sqrt() / (1.0 - c_abs)
}

impl CenterInterval {
    /// The interval of a simplex with no other point: every ball empty.
    pub fn new(r_over_n: f64) -> Self {
        CenterInterval {
            lo: f64::NEG_INFINITY,
            hi: f64::INFINITY,
            r_over_n,
            finite_blocked: false,
            all_blocked: false,
            lo_at: None,
            hi_at: None,
            lo_raw: f64::NEG_INFINITY,
            hi_raw: f64::INFINITY,
        }
    }

    /// Makes x, with offset τ, the point binding `hi`; restores `lo` to its computed value.
    fn bind_hi(&mut self, tau: f64, x: [f64; 3]) {
        (self.hi, self.hi_raw, self.hi_at) = (tau, tau, Some(x));
        self.lo = self.lo_raw;
    }
    /// Makes x, with offset τ, the point binding `lo`; restores `hi` to its computed value.
    fn bind_lo(&mut self, tau: f64, x: [f64; 3]) {
        (self.lo, self.lo_raw, self.lo_at) = (tau, tau, Some(x));
        self.hi = self.hi_raw;
    }

    /// Makes the float ends agree with the exact relation `rel` between them (< 0: lo < hi,
    /// 0: lo = hi, > 0: lo > hi) decided by an exact in-circle/in-sphere test.
    fn settle(&mut self, rel: f64) {
        if rel == 0.0 || (rel < 0.0 && self.lo > self.hi) {
            let mid = 0.5 * (self.lo + self.hi);
            self.lo = mid;
            self.hi = mid;
        } else if rel > 0.0 && self.lo <= self.hi {
            self.lo = self.hi + self.hi.abs() * 4.0 * f64::EPSILON + f64::MIN_POSITIVE;
        }
    }

    /// True when a point blocks everything or an end is certainly beyond ±`f` (f ≥ 0): the ends
    /// are accurate to a relative [`TAU_TOL`] of |τ| + r/|n| (allowed for twice here). For
    /// f ≥ s(c) (the offset of the balls with parameter ±c), c₁′ < c for c < 0 then whatever
    /// points are added, since the ends only move inwards — the early end of the searches
    /// beyond the triangulations.
    pub fn past(&self, f: f64) -> bool {
        let tol = |t: f64| 2.0 * TAU_TOL * (t.abs() + self.r_over_n);
        self.all_blocked || self.lo - tol(self.lo) > f || self.hi + tol(self.hi) < -f
    }

    /// True when the ball with offset `s` (±∞ = half-space) is empty.
    pub fn ball_empty(&self, s: f64) -> bool {
        if self.all_blocked || (self.finite_blocked && s.is_finite()) {
            return false;
        }
        self.lo <= s && s <= self.hi
    }

    /// True when the neighbourhood N_γ(c₀, c₁) with the larger ball's centre on the side
    /// `side` (+1 or −1) is empty, by Def. 3.1 applied to the interval.
    pub fn neighborhood_empty(&self, c0: f64, c1: f64, side: f64) -> bool {
        if self.all_blocked {
            return false;
        }
        let s1 = side * offset_of(c1.abs(), self.r_over_n);
        let f0 = offset_of(c0.abs(), self.r_over_n);
        let s0 = if c0 * c1 < 0.0 { side * f0 } else { -side * f0 };
        let s0 = if c0 == 0.0 { 0.0 } else { s0 };
        if c1 >= 0.0 {
            self.ball_empty(s0) && self.ball_empty(s1)
        } else {
            // intersection of the two balls: a point above (h > 0) is inside both iff
            // min(s0, s1) > τ; below iff max(s0, s1) < τ.
            let (a, b) = if s0 <= s1 { (s0, s1) } else { (s1, s0) };
            if self.finite_blocked && a.is_finite() && b.is_finite() {
                return false;
            }
            a <= self.hi && b >= self.lo
        }
    }

    /// The γ-values (c₀′, c₁′) of Def. 3.3: the largest parameters whose neighbourhood is
    /// empty; `None` when no neighbourhood at all is empty (a point lies in the closed simplex).
    ///
    /// - `lo ≤ hi` (some ball is empty; the simplex is in γ(\[-1,1\],\[0,1\]) = DT in general
    ///   position): c₁′ = |c| of the end farther from the smallest ball, c₀′ = |c| of the
    ///   nearer end, positive when the ends lie on opposite sides (c₀c₁ > 0), negative when on
    ///   the same side.
    /// - `lo > hi` (no ball is empty): only intersections can be empty; the smallest symmetric
    ///   pair covering the gap has offset max(|lo|, |hi|): c₁′ = −|c| of it, and c₀′ = ±|c| of
    ///   the gap's nearer end, positive when on the same side as the farther end.
    pub fn gamma_values(&self) -> Option<(f64, f64)> {
        if self.all_blocked {
            return None;
        }
        let (lo, hi) = (self.lo, self.hi);
        let c = |s: f64| abs_c(s, self.r_over_n);
        if self.finite_blocked {
            // only half-spaces can be empty
            return match (hi == f64::INFINITY, lo == f64::NEG_INFINITY) {
                (true, true) => Some((1.0, 1.0)),
                (true, false) | (false, true) => Some((-1.0, 1.0)),
                (false, false) => None,
            };
        }
        if lo <= hi {
            let (near, far) = if lo.abs() <= hi.abs() {
                (lo, hi)
            } else {
                (hi, lo)
            };
            let opposite = lo <= 0.0 && hi >= 0.0;
            let c0 = if opposite { c(near) } else { -c(near) };
            Some((c0, c(far)))
        } else {
            let (near, far) = if lo.abs() <= hi.abs() {
                (lo, hi)
            } else {
                (hi, lo)
            };
            let same = near * far > 0.0;
            let c0 = if same || near == 0.0 {
                c(near)
            } else {
                -c(near)
            };
            Some((c0, -c(far)))
        }
    }

    /// c₁′ ≥ c, decided exactly given `reach(x, |c|)`: the exact sign of |τ(x)| − s(|c|) for a
    /// binding point x, s(|c|) the offset of the balls with parameter ±|c| (0 ≤ |c| < 1) —
    /// [`TriFrame::c1_at_least`], [`EdgeFrame::c1_at_least`]. The regime (`lo ≤ hi` or not) is
    /// exact already (the ends' order is settled by exact in-circle/in-sphere tests), and so
    /// are the blocked flags. With both ends' balls empty-or-not as in [`Self::gamma_values`]:
    /// - `lo ≤ hi`: c₁′ = |c| of the farther end ≥ 0, so c₁′ ≥ c iff c ≤ 0 or some end reaches
    ///   s(c) (an end without a binding point is at infinity: |c| = 1);
    /// - `lo > hi`: c₁′ = −(|c| of the farther end) < 0, so c₁′ ≥ c iff c < 0 and neither end
    ///   reaches beyond s(|c|) (c ≤ −1: always).
    pub fn c1_at_least_by(&self, c: f64, reach: impl Fn([f64; 3], f64) -> i32) -> bool {
        if self.all_blocked || c > 1.0 || c.is_nan() {
            return false;
        }
        let open_end = self.lo_at.is_none() || self.hi_at.is_none();
        if self.finite_blocked {
            // (1, 1) or (−1, 1) with an open end, no γ-values without one
            return open_end;
        }
        if self.lo <= self.hi {
            if c <= 0.0 || open_end {
                return true;
            }
            if c >= 1.0 {
                return false;
            }
            [self.lo_at, self.hi_at]
                .into_iter()
                .flatten()
                .any(|x| reach(x, c) >= 0)
        } else {
            if c >= 0.0 {
                return false;
            }
            if c <= -1.0 {
                return true;
            }
            [self.lo_at, self.hi_at]
                .into_iter()
                .flatten()
                .all(|x| reach(x, -c) <= 0)
        }
    }

    /// The γ-values (c₀′, c₁′) compared with c, exactly: (c₀′ vs c, c₁′ vs c), given
    /// `reach(x, |c|)` (the exact sign of |τ(x)| − s(|c|) for a binding point x and
    /// 0 ≤ |c| < 1, as in [`Self::c1_at_least_by`]) and `q_sign(x)` (the exact sign of
    /// q = |x − m|² − r²: whether x is outside the smallest touching ball). `None` when there
    /// are no γ-values ([`Self::gamma_values`]). The same as comparing [`Self::gamma_values`]
    /// with c, but for rounding.
    ///
    /// With A, B the |c| of the two ends (1 for an end without a binding point), c₁′ = ±max(A,
    /// B) and c₀′ = ±min(A, B) (see [`Self::gamma_values`]), so each comparison is the min or
    /// max of the two ends' exact comparisons with |c|, and the signs are exact too: the ends'
    /// offsets have the signs of −q (below) and q (above), so
    /// - `lo ≤ hi` (exact, see [`Self::c1_at_least_by`]): c₁′ ≥ 0; c₀′ ≥ 0 iff lo ≤ 0 ≤ hi,
    ///   i.e. q ≥ 0 at both binding points;
    /// - `lo > hi`: c₁′ < 0; c₀′ < 0 iff hi < 0 < lo, i.e. q < 0 at both binding points.
    ///
    /// (When an end's offset is 0, min(A, B) = 0 and the sign of c₀′ does not matter.)
    pub fn cmp_gamma_by(
        &self,
        c: f64,
        reach: impl Fn([f64; 3], f64) -> i32,
        q_sign: impl Fn([f64; 3]) -> i32,
    ) -> Option<(Ordering, Ordering)> {
        use Ordering::*;
        if self.all_blocked || c.is_nan() {
            return None;
        }
        let (lo_at, hi_at) = (self.lo_at, self.hi_at);
        if self.finite_blocked {
            // only half-spaces: (1, 1) or (−1, 1), no γ-values without an open end
            let c0 = match (lo_at.is_none(), hi_at.is_none()) {
                (true, true) => 1.0,
                (true, false) | (false, true) => -1.0,
                (false, false) => return None,
            };
            return Some((cmp_f64(c0, c), cmp_f64(1.0, c)));
        }
        let t = c.abs();
        // |c| of an end against |c|
        let end = |x: Option<[f64; 3]>| match x {
            None => cmp_f64(1.0, t),
            Some(_) if t >= 1.0 => Less,
            Some(x) => reach(x, t).cmp(&0),
        };
        let (a, b) = (end(lo_at), end(hi_at));
        let (near, far) = (a.min(b), a.max(b));
        // ±M against c for M ≥ 0 with M vs |c| = m
        let signed = |positive: bool, m: Ordering| match (positive, c) {
            (true, c) if c < 0.0 => Greater,
            (true, _) => m,
            (false, c) if c > 0.0 => Less,
            (false, _) => m.reverse(),
        };
        if self.lo <= self.hi {
            let outside = |x: Option<[f64; 3]>| x.map_or(true, |x| q_sign(x) >= 0);
            let c0_pos = outside(lo_at) && outside(hi_at);
            Some((signed(c0_pos, near), signed(true, far)))
        } else {
            let inside = |x: Option<[f64; 3]>| x.is_some_and(|x| q_sign(x) < 0);
            let c0_neg = inside(lo_at) && inside(hi_at);
            Some((signed(!c0_neg, near), signed(false, far)))
        }
    }

    /// The offset s of a ball B(s) touching the simplex that holds an empty neighbourhood of
    /// γ(\[-1,1\],\[c,1\]) (c ≤ 0) among the points added so far: while no point lies strictly
    /// inside B(s), the simplex is in γ(\[-1,1\],\[c,1\]) — so once every point inside B(s) has
    /// been added and s is still the offset named, the farther points cannot change that.
    /// `None` when no such neighbourhood is empty so far (c₁′ < c), when c > 0, or when only
    /// half-spaces are left (`finite_blocked`).
    ///
    /// With `a = min(lo, hi)`, `b = max(lo, hi)`, s = clamp(0, a, b):
    /// - `lo ≤ hi`: B(s) itself is empty, so the final interval keeps s and c₁′ ≥ 0 ≥ c;
    /// - `lo > hi`: B(hi) ∩ B(lo) is empty (a point above is in both iff hi > τ, below iff
    ///   lo < τ), and it contains the intersection neighbourhood of the γ-values (c₀′, c₁′),
    ///   so with c₁′ ≥ c the simplex stays in γ while it stays empty. It lies in B(s): for
    ///   hi ≤ 0 ≤ lo in B(0) (q < 2·hi·h ≤ 0 above, q < 2·lo·h ≤ 0 below), otherwise in the
    ///   ball of the end nearer to 0 (the smaller one on that side).
    pub fn witness_offset(&self, c: f64) -> Option<f64> {
        if c > 0.0 || self.all_blocked || self.finite_blocked {
            return None;
        }
        if self.lo > self.hi && !self.gamma_values().is_some_and(|g| g.1 >= c) {
            return None;
        }
        let s = 0f64.clamp(self.lo.min(self.hi), self.lo.max(self.hi));
        s.is_finite().then_some(s)
    }
}

/// σ ∈ γ(c₀, c₁) given σ's γ-values, by Lemma 3.1 (c₁ ≥ 0) and Lemma 3.2 (c₁ < 0).
/// Requires |c₀| ≤ |c₁|. O(1): filter a γ graph's simplices ([`crate::graphs::Graph::gamma`])
/// at other parameters without rebuilding. The γ-values given are rounded (to ~1e-10), so a
/// parameter that close to a γ-value may be decided differently from the exact graph; the
/// builders decide on the simplex's interval exactly ([`EdgeFrame::in_gamma`],
/// [`TriFrame::in_gamma`]).
///
/// ```rust
/// use morpho::graphs::{graph_2d, in_gamma, Kind};
/// use morpho::geom::Point2;
/// let p: Vec<Point2> = (0..12).map(|i| {
///     let t = i as f64 * 0.5;
///     Point2::new(t.cos() * (1.0 + 0.1 * t), t.sin() * (1.0 + 0.1 * t))
/// }).collect();
/// let g0 = graph_2d(&p, Kind::Gamma(0.0, 0.0)).unwrap();
/// // γ(0, 1) is γ(0, 0) filtered by the γ-values of its edges
/// let g01 = graph_2d(&p, Kind::Gamma(0.0, 1.0)).unwrap();
/// let filtered: Vec<[u32; 2]> = g0.edges.iter().zip(&g0.gamma)
///     .filter(|(_, g)| in_gamma((g[0], g[1]), 0.0, 1.0))
///     .map(|(e, _)| *e)
///     .collect();
/// assert_eq!(filtered, g01.edges);
/// ```
pub fn in_gamma(values: (f64, f64), c0: f64, c1: f64) -> bool {
    let (a, b) = values;
    if c1 >= 0.0 {
        a >= c0 && b >= c1
    } else {
        (a >= c0 && b >= c1) || (a >= c1 && b >= c0.abs())
    }
}

/// σ ∈ γ(\[c₀,c₁\],\[c₂,c₃\]) given σ's γ-values (Def. 3.3). O(1). On the rounded values
/// (see [`in_gamma`]); exact on the interval: [`EdgeFrame::in_gamma_range`],
/// [`TriFrame::in_gamma_range`].
///
/// ```rust
/// use morpho::graphs::in_gamma_range;
/// assert!(in_gamma_range((0.2, 0.9), [0.0, 0.5, 0.5, 1.0]));
/// assert!(!in_gamma_range((0.6, 0.9), [0.0, 0.5, 0.5, 1.0]));
/// ```
pub fn in_gamma_range(values: (f64, f64), range: [f64; 4]) -> bool {
    let (a, b) = values;
    range[0] <= a && a <= range[1] && range[2] <= b && b <= range[3]
}

/// σ ∈ γ(c₀, c₁) by Lemmas 3.1 (c₁ ≥ 0) and 3.2 (c₁ < 0), as [`in_gamma`], on exact
/// comparisons `cmp(c)` = (c₀′ vs c, c₁′ vs c) of σ's γ-values (`None`: no γ-values) —
/// [`EdgeFrame::cmp_gamma`], [`TriFrame::cmp_gamma`]. Requires |c₀| ≤ |c₁|.
pub fn in_gamma_exact(cmp: impl Fn(f64) -> Option<(Ordering, Ordering)>, c0: f64, c1: f64) -> bool {
    use Ordering::Less;
    let ge0 = |c: f64| cmp(c).is_some_and(|o| o.0 != Less);
    let ge1 = |c: f64| cmp(c).is_some_and(|o| o.1 != Less);
    (ge0(c0) && ge1(c1)) || (c1 < 0.0 && ge0(c1) && ge1(c0.abs()))
}

/// σ ∈ γ(\[c₀,c₁\],\[c₂,c₃\]) (Def. 3.3), as [`in_gamma_range`], on exact comparisons `cmp(c)`
/// of σ's γ-values (see [`in_gamma_exact`]).
pub fn in_gamma_range_exact(
    cmp: impl Fn(f64) -> Option<(Ordering, Ordering)>,
    range: [f64; 4],
) -> bool {
    use Ordering::{Greater, Less};
    let is = |c: f64, k: usize, not: Ordering| cmp(c).is_some_and(|o| [o.0, o.1][k] != not);
    is(range[0], 0, Less)
        && is(range[1], 0, Greater)
        && is(range[2], 1, Less)
        && is(range[3], 1, Greater)
}

/// a vs b for non-NaN floats.
#[inline]
fn cmp_f64(a: f64, b: f64) -> Ordering {
    a.partial_cmp(&b).unwrap_or(Ordering::Less)
}

/// −1, 0 or +1 (unlike `f64::signum`, 0 for zero).
#[inline]
pub fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// The frame of a 2D edge (a, b) for computing its [`CenterInterval`] point by point.
#[derive(Debug, Clone, Copy)]
pub struct EdgeFrame {
    pa: [f64; 2],
    pb: [f64; 2],
    m: [f64; 2],
    nrm: [f64; 2],
    r2: f64,
}

impl EdgeFrame {
    /// Frame of the edge a→b; the normal is the left normal of a→b (unnormalised).
    pub fn new(pa: [f64; 2], pb: [f64; 2]) -> Self {
        let m = [0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])];
        let d = [pb[0] - pa[0], pb[1] - pa[1]];
        EdgeFrame {
            pa,
            pb,
            m,
            nrm: [-d[1], d[0]],
            r2: 0.25 * (d[0] * d[0] + d[1] * d[1]),
        }
    }
    /// The interval before any point is added: every ball empty.
    pub fn start(&self) -> CenterInterval {
        let nlen = (self.nrm[0] * self.nrm[0] + self.nrm[1] * self.nrm[1]).sqrt();
        CenterInterval::new(self.r2.sqrt() / nlen)
    }
    /// Side (+1 left, −1 right, 0 on the line; exact) and offset τ of point x.
    pub fn tau(&self, x: [f64; 2]) -> (f64, f64) {
        let side = sign(raw::orient2d(self.pa, self.pb, x));
        if side == 0.0 {
            let dx = [x[0] - self.m[0], x[1] - self.m[1]];
            return (0.0, dx[0] * dx[0] + dx[1] * dx[1] - self.r2);
        }
        (side, self.offset(side, x))
    }
    /// The offset τ = q / 2h of x off the line (exact side `side`), accurate to a relative
    /// [`TAU_TOL`] of |τ| + 1/2 (r/|n| = 1/2 for an edge): the floating-point value when its
    /// proven error bound certifies that, else the rounded quotient of exact expansions
    /// ([`exact_offset_2d`]) — for a point nearly on the line, e.g. nearly on the circle of a
    /// rounded cocircular set, q and h are both tiny and the float quotient meaningless.
    fn offset(&self, side: f64, x: [f64; 2]) -> f64 {
        if let Some((t, h)) = self.offset_bounded(x) {
            if (h > 0.0) == (side > 0.0) && t.certified() <= TAU_TOL * (t.v.abs() + 0.5) {
                return t.v;
            }
        }
        exact_offset_2d(self.pa, self.pb, x)
    }
    /// τ(x) with a proven error bound: q = (x − a)·(x − b) (= |x − m|² − r²), h = orient2d(a,
    /// b, x) (= (x − m)·n), τ = q / 2h; `None` when h is not certainly nonzero; with τ, the
    /// float h.
    fn offset_bounded(&self, x: [f64; 2]) -> Option<(Bounded, f64)> {
        let (a, b) = (self.pa, self.pb);
        let wa = [0, 1].map(|k| Bounded::diff(x[k], a[k]));
        let wb = [0, 1].map(|k| Bounded::diff(x[k], b[k]));
        let d = [0, 1].map(|k| Bounded::diff(b[k], a[k]));
        let q = wa[0].times(wb[0]).plus(wa[1].times(wb[1]));
        let h = d[0].times(wa[1]).minus(d[1].times(wa[0]));
        Some((q.over(h.scale2(2.0))?, h.v))
    }
    /// The exact sign of |τ(x)| − s(c) for 0 ≤ `c_abs` < 1 (see [`TriFrame::reach_sign`]; here
    /// ρ₀ = 1/2): the proven bounds when they decide it, else big integers
    /// ([`crate::geom::exact::offset_reach_sign_2d`]).
    fn reach_sign(&self, x: [f64; 2], c_abs: f64) -> i32 {
        if let Some((t, _)) = self.offset_bounded(x) {
            let k1 = Bounded::diff(1.0, c_abs);
            let kk = Bounded::exact(c_abs).times(Bounded::diff(2.0, c_abs));
            let e = t.times(t).times(k1.times(k1)).minus(kk.scale2(0.25));
            if let Some(s) = e.sign() {
                return s;
            }
        }
        crate::geom::exact::offset_reach_sign_2d(self.pa, self.pb, x, c_abs)
    }
    /// c₁′ ≥ c for the interval `iv` of this edge, decided exactly (see
    /// [`CenterInterval::c1_at_least_by`]).
    pub fn c1_at_least(&self, iv: &CenterInterval, c: f64) -> bool {
        iv.c1_at_least_by(c, |x, ca| self.reach_sign([x[0], x[1]], ca))
    }
    /// The γ-values of the interval `iv` of this edge compared with c, exactly (see
    /// [`CenterInterval::cmp_gamma_by`]); the side of the diametral disc by [`dot_sign`].
    pub fn cmp_gamma(&self, iv: &CenterInterval, c: f64) -> Option<(Ordering, Ordering)> {
        iv.cmp_gamma_by(
            c,
            |x, ca| self.reach_sign([x[0], x[1]], ca),
            |x| dot_sign(&self.pa, &self.pb, &[x[0], x[1]]),
        )
    }
    /// σ ∈ γ(c₀, c₁) for the interval `iv` of this edge, exactly ([`in_gamma_exact`]).
    pub fn in_gamma(&self, iv: &CenterInterval, c0: f64, c1: f64) -> bool {
        in_gamma_exact(|c| self.cmp_gamma(iv, c), c0, c1)
    }
    /// σ ∈ γ(\[c₀,c₁\],\[c₂,c₃\]) for the interval `iv` of this edge, exactly
    /// ([`in_gamma_range_exact`]).
    pub fn in_gamma_range(&self, iv: &CenterInterval, range: [f64; 4]) -> bool {
        in_gamma_range_exact(|c| self.cmp_gamma(iv, c), range)
    }
    /// The interval of a Delaunay edge from the apexes of the triangles on its two sides
    /// (`left` strictly left of a→b, `right` strictly right; `None` on the hull side), with
    /// `rel` the exact sign of incircle(a, b, left, right). Equal to [`EdgeFrame::add`]ing
    /// the two apexes, without re-deciding their sides.
    pub fn two_apexes(
        &self,
        left: Option<[f64; 2]>,
        right: Option<[f64; 2]>,
        rel: f64,
    ) -> CenterInterval {
        let mut iv = self.start();
        let tau = |x: [f64; 2], side: f64| self.offset(side, x);
        if let Some(x) = left {
            iv.bind_hi(tau(x, 1.0), [x[0], x[1], 0.0]);
        }
        if let Some(y) = right {
            iv.bind_lo(tau(y, -1.0), [y[0], y[1], 0.0]);
            if left.is_some() {
                iv.settle(rel);
            }
        }
        iv
    }
    /// The interval that [`EdgeFrame::add`] reaches when `left` (strictly left of a→b) is the
    /// first point added on the left of all those with the smallest τ there, and `right` the
    /// first on the right with the largest τ — and the two lie on one circle with a and b: the
    /// chord of a cocircular group (V §3.3), whose group points on each side are all tied
    /// (`add` keeps the first of equal points, and its final state depends only on the two
    /// binding points). Equal to adding `left` and then `right`, without the exact in-circle
    /// test that finds them cocircular (slow on exact ties).
    pub fn cocircular_ends(
        &self,
        left: Option<[f64; 2]>,
        right: Option<[f64; 2]>,
    ) -> CenterInterval {
        let mut iv = self.start();
        if let Some(x) = left {
            iv.bind_hi(self.tau(x).1, [x[0], x[1], 0.0]);
        }
        if let Some(y) = right {
            iv.bind_lo(self.tau(y).1, [y[0], y[1], 0.0]);
            if left.is_some() {
                iv.settle(0.0);
            }
        }
        iv
    }
    /// Narrows `iv` by point x (not a or b). Which point binds each end, and whether the ends
    /// are equal or in which order, is decided by exact in-circle tests: τ(x) < τ(y) for points
    /// above ⇔ x lies inside the circle through a, b, y.
    pub fn add(&self, iv: &mut CenterInterval, x: [f64; 2]) {
        // τ only for the points that become binding ends
        let side = sign(raw::orient2d(self.pa, self.pb, x));
        let xy = |p: [f64; 3]| [p[0], p[1]];
        if side > 0.0 {
            let better = match iv.hi_at {
                None => true,
                Some(y) => incircle_sign(self.pa, self.pb, xy(y), x) > 0,
            };
            if better {
                iv.bind_hi(self.offset(side, x), [x[0], x[1], 0.0]);
                if let Some(l) = iv.lo_at {
                    iv.settle(incircle_sign(self.pa, self.pb, x, xy(l)) as f64);
                }
            }
        } else if side < 0.0 {
            let better = match iv.lo_at {
                None => true,
                Some(y) => incircle_sign(self.pb, self.pa, xy(y), x) > 0,
            };
            if better {
                iv.bind_lo(self.offset(side, x), [x[0], x[1], 0.0]);
                if let Some(h) = iv.hi_at {
                    iv.settle(incircle_sign(self.pa, self.pb, xy(h), x) as f64);
                }
            }
        } else {
            // on the line: blocks everything when on the closed segment ab, i.e. when
            // (x − a)·(b − a) ≥ 0 and (x − b)·(a − b) ≥ 0 (exact signs)
            if dot_sign(&x, &self.pb, &self.pa) >= 0 && dot_sign(&x, &self.pa, &self.pb) >= 0 {
                iv.all_blocked = true;
            }
        }
    }
}

/// The interval of empty-ball offsets of the 2D edge (a, b) among `points` (the edge's own
/// vertices excluded). Normal: the left normal of a→b, unnormalised. O(N).
pub fn center_interval_2d(points: &[[f64; 2]], a: usize, b: usize) -> CenterInterval {
    let f = EdgeFrame::new(points[a], points[b]);
    let mut iv = f.start();
    for (i, &x) in points.iter().enumerate() {
        if i != a && i != b {
            f.add(&mut iv, x);
        }
    }
    iv
}

/// Circumcentre of triangle (a, b, c) in its plane, its squared radius, and the unnormalised
/// normal (b − a) × (c − a). `None` for collinear corners.
pub fn triangle_circle(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> Option<([f64; 3], f64, [f64; 3])> {
    let u = sub(b, a);
    let v = sub(c, a);
    let n = cross(u, v);
    let nn = dot(n, n);
    if nn == 0.0 || !nn.is_finite() {
        return None;
    }
    // circumcentre = a + (|u|² (v × n) + |v|² (n × u)) / (2 |n|²)
    let uu = dot(u, u);
    let vv = dot(v, v);
    let t1 = cross(v, n);
    let t2 = cross(n, u);
    let off = [
        (uu * t1[0] + vv * t2[0]) / (2.0 * nn),
        (uu * t1[1] + vv * t2[1]) / (2.0 * nn),
        (uu * t1[2] + vv * t2[2]) / (2.0 * nn),
    ];
    let m = [a[0] + off[0], a[1] + off[1], a[2] + off[2]];
    Some((m, dot(off, off), n))
}

/// The offset τ = q / 2h of x for the triangle (a, b, c) (normal (b − a) × (c − a)) from exact
/// expansions, rounded once at the end (relative error a few ε): with u = b − a, v = c − a,
/// w = x − a, n = u × v, the circumcentre is a + (|u|² v×n + |v|² n×u) / 2|n|², so
/// h = w·n and τ = (|w|²|n|² − w·(|u|² v×n + |v|² n×u)) / (2|n|²·w·n). Computed on the
/// differences scaled by a power of two (exact) so that nothing over- or underflows; x must not
/// lie in the plane. ±f64::MAX when the quotient overflows.
pub fn exact_offset(t: [[f64; 3]; 3], x: [f64; 3]) -> f64 {
    use crate::geom::exact::power_of_two_scale;
    use crate::geom::expansion::{cross as xcross, dot as xdot, Expansion};
    let [a, b, c] = t;
    let diff = |p: [f64; 3]| [0, 1, 2].map(|k| Expansion::diff(p[k], a[k]));
    let (u, v, w) = (diff(b), diff(c), diff(x));
    let big = [u.clone(), v.clone(), w.clone()]
        .iter()
        .flatten()
        .flat_map(|e| e.0.iter().copied())
        .fold(0.0f64, |m, y| m.max(y.abs()));
    let s = power_of_two_scale(big);
    let sc = |e: [Expansion; 3]| e.map(|y| y.scale(s));
    let (u, v, w) = (sc(u), sc(v), sc(w));
    let n = xcross(&u, &v);
    let nn = xdot(&n, &n);
    let (uu, vv, ww) = (xdot(&u, &u), xdot(&v, &v), xdot(&w, &w));
    let (t1, t2) = (xcross(&v, &n), xcross(&n, &u));
    let num = ww
        .mul(&nn)
        .sub(&xdot(&w, &t1).mul(&uu))
        .sub(&xdot(&w, &t2).mul(&vv));
    let den = xdot(&w, &n).mul(&nn).scale(2.0);
    let est = |e: &Expansion| e.0.iter().sum::<f64>();
    // τ is homogeneous of degree −1: τ(p) = s·τ(s·p)
    let tau = est(&num) / est(&den) * s;
    if tau.is_nan() {
        0.0
    } else {
        tau.clamp(-f64::MAX, f64::MAX)
    }
}

/// The 2D offset τ = q / 2h of x for the edge (a, b) (left normal of b − a) from exact
/// expansions, rounded once at the end: q = (x − a)·(x − b), h = orient2d(a, b, x), on the
/// differences scaled by a power of two (exact) so that nothing over- or underflows; x must not
/// lie on the line. τ is homogeneous of degree 0. ±f64::MAX when the quotient overflows.
pub fn exact_offset_2d(a: [f64; 2], b: [f64; 2], x: [f64; 2]) -> f64 {
    use crate::geom::exact::power_of_two_scale;
    use crate::geom::expansion::Expansion;
    let diff = |p: [f64; 2], o: [f64; 2]| [0, 1].map(|k| Expansion::diff(p[k], o[k]));
    let (wa, wb, d) = (diff(x, a), diff(x, b), diff(b, a));
    let big = [&wa, &wb, &d]
        .iter()
        .flat_map(|v| v.iter())
        .flat_map(|e| e.0.iter().copied())
        .fold(0.0f64, |m, y| m.max(y.abs()));
    let s = power_of_two_scale(big);
    let sc = |e: [Expansion; 2]| e.map(|y| y.scale(s));
    let (wa, wb, d) = (sc(wa), sc(wb), sc(d));
    let q = wa[0].mul(&wb[0]).add(&wa[1].mul(&wb[1]));
    let h = d[0].mul(&wa[1]).sub(&d[1].mul(&wa[0]));
    let est = |e: &Expansion| e.0.iter().sum::<f64>();
    let tau = est(&q) / (2.0 * est(&h));
    if tau.is_nan() {
        0.0
    } else {
        tau.clamp(-f64::MAX, f64::MAX)
    }
}

/// The frame of a 3D triangle (a, b, c) for computing its [`CenterInterval`] point by point.
#[derive(Debug, Clone, Copy)]
pub struct TriFrame {
    t: [[f64; 3]; 3],
    m: [f64; 3],
    r2: f64,
    n: [f64; 3],
    /// A sphere the points lie near, with the corners' lifts: in-sphere tests through
    /// [`NearSphere::insphere`] (same signs, fewer exact evaluations on nearly cospherical sets).
    near: Option<(NearSphere, [Lift; 3])>,
    /// r/|n| (the scale of [`TAU_TOL`]).
    r_over_n: f64,
    /// The normal n = (b − a) × (c − a) and the circumcentre's offset o = m − a with proven
    /// error bounds, and ρ₀² = |o|²/|n|² (see [`TriFrame::offset_bounded`]); `None` when |n|²
    /// is not certainly nonzero (then every offset is exact).
    frame: Option<BoundedFrame>,
    /// Whether an offset the floating-point stage does not certify goes through the
    /// double-double stage ([`TriFrame::offset_dd`]) before the exact expansions
    /// ([`TriFrame::with_dd_stage`]).
    dd: bool,
}

/// The floating-point frame of [`TriFrame`] with running error bounds.
#[derive(Debug, Clone, Copy)]
struct BoundedFrame {
    n: [Bounded; 3],
    o: [Bounded; 3],
    rho2: Bounded,
    /// The per-component weights of the side filter ([`TriFrame::side_filter`]):
    /// gₖ = (certified error of nₖ + 4ε|nₖ|)(1 + 10⁻¹²).
    side_g: [f64; 3],
}

impl BoundedFrame {
    /// n = u × v, o = (|u|² v × n + |v|² n × u) / 2|n|², ρ₀² = |o|²/|n|² for u = b − a,
    /// v = c − a.
    fn new(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> Option<Self> {
        let u = [0, 1, 2].map(|k| Bounded::diff(b[k], a[k]));
        let v = [0, 1, 2].map(|k| Bounded::diff(c[k], a[k]));
        let n = Bounded::cross3(u, v);
        let nn = Bounded::dot3(n, n);
        let (uu, vv) = (Bounded::dot3(u, u), Bounded::dot3(v, v));
        let (t1, t2) = (Bounded::cross3(v, n), Bounded::cross3(n, u));
        let den = nn.scale2(2.0);
        let mut o = [Bounded::exact(0.0); 3];
        for k in 0..3 {
            o[k] = uu.times(t1[k]).plus(vv.times(t2[k])).over(den)?;
        }
        let rho2 = Bounded::dot3(o, o).over(nn)?;
        let side_g = n.map(|x| (x.certified() + 4.0 * f64::EPSILON * x.v.abs()) * (1.0 + 1e-12));
        Some(BoundedFrame { n, o, rho2, side_g })
    }
}

/// Relative accuracy (against |τ| + r/|n|) a floating-point offset τ must be certified to by
/// its proven error bound ([`TriFrame::offset`], [`EdgeFrame::offset`]); otherwise it is
/// recomputed from exact expansions.
pub const TAU_TOL: f64 = 1e-10;

impl TriFrame {
    /// Frame of the triangle; normal (b − a) × (c − a). `None` when the corners are collinear.
    pub fn new(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> Option<Self> {
        let (m, r2, n) = triangle_circle(a, b, c)?;
        Some(TriFrame {
            t: [a, b, c],
            m,
            r2,
            n,
            near: None,
            r_over_n: (r2 / dot(n, n)).sqrt(),
            frame: BoundedFrame::new(a, b, c),
            dd: false,
        })
    }
    /// The frame with a second, double-double stage for the offsets the floating-point stage
    /// does not certify ([`TriFrame::offset_dd`]), before the exact expansions: the same
    /// decisions (every offset is accurate to [`TAU_TOL`] either way, and the decisions are
    /// exact), no allocation for most of those points, but offsets that may differ from the
    /// expansions' in their last bits — so the γ-values a graph reports could too; the
    /// boundary's γ decisions (`boundary::d3::augment`) use it, the graph builders do not.
    pub fn with_dd_stage(mut self) -> Self {
        self.dd = true;
        self
    }
    /// The frame with in-sphere tests filtered by the reference sphere `s` (see
    /// [`NearSphere`]); the results are identical.
    pub fn with_near(mut self, s: Option<NearSphere>) -> Self {
        self.near = s.map(|s| (s, self.t.map(|x| s.lift(x))));
        self
    }
    /// `insphere` of the corners (as (b, a, c) when `swap`, else (a, b, c)), y and x.
    #[inline]
    fn insphere_at(&self, swap: bool, y: [f64; 3], x: [f64; 3]) -> f64 {
        let [a, b, c] = self.t;
        let (p, q) = if swap { (b, a) } else { (a, b) };
        match &self.near {
            None => raw::insphere(p, q, c, y, x),
            Some((s, l)) => {
                let (lp, lq) = if swap { (l[1], l[0]) } else { (l[0], l[1]) };
                s.insphere(
                    [p, q, c, y, x],
                    [Some(lp), Some(lq), Some(l[2]), None, None],
                )
            }
        }
    }
    /// The interval before any point is added.
    pub fn start(&self) -> CenterInterval {
        CenterInterval::new((self.r2 / dot(self.n, self.n)).sqrt())
    }
    /// Side (+1 along the normal, −1 against, 0 in the plane; exact) and offset τ of x.
    pub fn tau(&self, x: [f64; 3]) -> (f64, f64) {
        let side = self.side(x);
        if side == 0.0 {
            let dx = sub(x, self.m);
            return (0.0, dot(dx, dx) - self.r2);
        }
        (side, self.offset(side, x))
    }
    /// Side of x: +1 along the normal, −1 against, 0 in the plane (exact).
    #[inline]
    pub(crate) fn side(&self, x: [f64; 3]) -> f64 {
        if let Some((h, bound)) = self.side_filter(x) {
            if h > bound {
                return 1.0;
            }
            if h < -bound {
                return -1.0;
            }
        }
        let [a, b, c] = self.t;
        // orient3d(a, b, c, x) > 0 when x is below, i.e. on the side opposite to n
        sign(-raw::orient3d(a, b, c, x))
    }
    /// h = (x − a)·n in floating point and a bound B of its error against the exact
    /// (x − a)·((b − a) × (c − a)) — the side is sign(h) when |h| > B; the filter before
    /// `orient3d` in [`TriFrame::side`] (the same sign: orient3d(a, b, c, x) = −(x − a)·n).
    /// With wₖ = fl(xₖ − aₖ) (|Wₖ − wₖ| ≤ ε|wₖ|/2, W exact), nₖ the float normal with its
    /// certified bound eₖ ≥ |Nₖ − nₖ| ([`BoundedFrame`]) and h = fl(Σ wₖnₖ) (three products,
    /// two sums: off by at most γ₃ Σ|wₖnₖ| ≤ 2ε Σ|wₖnₖ| from Σ wₖnₖ):
    /// |Σ WₖNₖ − h| ≤ Σ |wₖ| (eₖ + ε(|nₖ| + eₖ) + 2ε|nₖ|) ≤ Σ |wₖ| gₖ with
    /// gₖ = (eₖ + 4ε|nₖ|)(1 + 10⁻¹²) (εeₖ ≤ 10⁻¹²eₖ). B is that sum, inflated by 10⁻¹² for
    /// its own five roundings on nonnegative terms, plus 4η for products that underflow.
    /// `None` without a bounded frame.
    #[inline]
    fn side_filter(&self, x: [f64; 3]) -> Option<(f64, f64)> {
        let f = self.frame.as_ref()?;
        let a = self.t[0];
        let w = [x[0] - a[0], x[1] - a[1], x[2] - a[2]];
        let h = w[0] * f.n[0].v + w[1] * f.n[1].v + w[2] * f.n[2].v;
        let g = f.side_g;
        let bound = (w[0].abs() * g[0] + w[1].abs() * g[1] + w[2].abs() * g[2]) * (1.0 + 1e-12)
            + 4.0 * 5e-324;
        Some((h, bound))
    }
    /// The offset τ = q / 2h of x off the plane (exact side `side`), accurate to a relative
    /// [`TAU_TOL`] of |τ| + r/|n|: the floating-point value when its proven error bound
    /// ([`TriFrame::offset_bounded`]) certifies that, else the rounded quotient of exact
    /// expansions ([`exact_offset`]). For a point nearly in the plane (on nearly cospherical
    /// sets: a point nearly on the circumcircle) q and h are both tiny and the float quotient
    /// can be meaningless.
    fn offset(&self, side: f64, x: [f64; 3]) -> f64 {
        // (h's sign is certified, so it is the exact side; checked all the same)
        let ok = |(t, h): &(Bounded, f64)| {
            (*h > 0.0) == (side > 0.0) && t.certified() <= TAU_TOL * (t.v.abs() + self.r_over_n)
        };
        if let Some(t) = self.offset_bounded(x).filter(ok) {
            return t.0.v;
        }
        if self.dd {
            if let Some(t) = self.offset_dd(x).filter(ok) {
                return t.0.v;
            }
        }
        exact_offset(self.t, x)
    }
    /// τ(x) = num / den in double-double arithmetic with a proven error bound
    /// ([`crate::geom::bounded::BoundedDd`]), from the differences to corner a, by the
    /// polynomial formula of [`exact_offset`]: u = b − a, v = c − a, w = x − a, n = u × v,
    /// num = |w|²|n|² − |u|² w·(v × n) − |v|² w·(n × u), den = 2|n|² w·n. The differences
    /// are exact and every product and sum carries about 2⁻¹⁰⁶ of its magnitudes, so the
    /// cancellations that defeat [`TriFrame::offset_bounded`] (a skinny triangle, a point
    /// nearly in its plane) cost 2⁵³ times less accuracy; the quotient is the rounded `hi`
    /// parts', bounded by [`Bounded::over`]. `None` when the bound does not certify den ≠ 0;
    /// with τ, den's leading part (the sign of h, as |n|² > 0).
    fn offset_dd(&self, x: [f64; 3]) -> Option<(Bounded, f64)> {
        use crate::geom::bounded::BoundedDd as D;
        let [a, b, c] = self.t;
        let d = |p: [f64; 3]| [0, 1, 2].map(|k| D::diff(p[k], a[k]));
        let (u, v, w) = (d(b), d(c), d(x));
        let n = D::cross3(u, v);
        let nn = D::dot3(n, n);
        let num = D::dot3(w, w)
            .times(nn)
            .minus(D::dot3(w, D::cross3(v, n)).times(D::dot3(u, u)))
            .minus(D::dot3(w, D::cross3(n, u)).times(D::dot3(v, v)));
        let den = D::dot3(w, n).times(nn).scale2(2.0).to_bounded();
        Some((num.to_bounded().over(den)?, den.v))
    }
    /// τ(x) in floating point with a proven error bound, from the differences to corner a:
    /// with w = x − a, h = w·n and q = |w|² − 2 w·o (= |x − m|² − r²), τ = q / 2h. `None` when
    /// the bound does not certify h ≠ 0 (x nearly in the plane); with τ, the float h.
    fn offset_bounded(&self, x: [f64; 3]) -> Option<(Bounded, f64)> {
        let f = self.frame.as_ref()?;
        let a = self.t[0];
        let w = [0, 1, 2].map(|k| Bounded::diff(x[k], a[k]));
        let h = Bounded::dot3(w, f.n);
        let q = Bounded::dot3(w, w).minus(Bounded::dot3(w, f.o).scale2(2.0));
        Some((q.over(h.scale2(2.0))?, h.v))
    }
    /// The exact sign of |τ(x)| − s(c) for 0 ≤ `c_abs` < 1, s(c) = ρ₀ √(k² − 1) with
    /// k = 1/(1 − |c|) the offset of the balls with parameter ±|c| (x off the plane): +1 when
    /// x's ball is beyond them (|c(τ)| > |c|), 0 on them, −1 within. The sign of
    /// τ² (1 − |c|)² − ρ₀² |c| (2 − |c|), from the proven bounds when they decide it, else in
    /// big integers ([`crate::geom::exact::offset_reach_sign_3d`]).
    fn reach_sign(&self, x: [f64; 3], c_abs: f64) -> i32 {
        if let (Some(f), Some((t, _))) = (self.frame.as_ref(), self.offset_bounded(x)) {
            let k1 = Bounded::diff(1.0, c_abs);
            let kk = Bounded::exact(c_abs).times(Bounded::diff(2.0, c_abs));
            let e = t.times(t).times(k1.times(k1)).minus(f.rho2.times(kk));
            if let Some(s) = e.sign() {
                return s;
            }
        }
        crate::geom::exact::offset_reach_sign_3d(self.t, x, c_abs)
    }
    /// c₁′ ≥ c for the interval `iv` of this triangle, decided exactly (see
    /// [`CenterInterval::c1_at_least_by`]); the same as comparing the second of
    /// [`CenterInterval::gamma_values`] with c, but for rounding.
    pub fn c1_at_least(&self, iv: &CenterInterval, c: f64) -> bool {
        iv.c1_at_least_by(c, |x, ca| self.reach_sign(x, ca))
    }
    /// The exact sign of q = |x − m|² − r² (+1: x outside the triangle's diametral sphere):
    /// from the proven bound of q = |w|² − 2 w·o (w = x − a) when it decides, else in big
    /// integers ([`crate::geom::exact::diametral_side_exact`]).
    fn q_sign(&self, x: [f64; 3]) -> i32 {
        if let Some(f) = self.frame.as_ref() {
            let a = self.t[0];
            let w = [0, 1, 2].map(|k| Bounded::diff(x[k], a[k]));
            let q = Bounded::dot3(w, w).minus(Bounded::dot3(w, f.o).scale2(2.0));
            if let Some(s) = q.sign() {
                return s;
            }
        }
        let [a, b, c] = self.t;
        crate::geom::exact::diametral_side_exact(a, b, c, x)
    }
    /// The γ-values of the interval `iv` of this triangle compared with c, exactly (see
    /// [`CenterInterval::cmp_gamma_by`]).
    pub fn cmp_gamma(&self, iv: &CenterInterval, c: f64) -> Option<(Ordering, Ordering)> {
        iv.cmp_gamma_by(c, |x, ca| self.reach_sign(x, ca), |x| self.q_sign(x))
    }
    /// σ ∈ γ(c₀, c₁) for the interval `iv` of this triangle, exactly ([`in_gamma_exact`]).
    pub fn in_gamma(&self, iv: &CenterInterval, c0: f64, c1: f64) -> bool {
        in_gamma_exact(|c| self.cmp_gamma(iv, c), c0, c1)
    }
    /// σ ∈ γ(\[c₀,c₁\],\[c₂,c₃\]) for the interval `iv` of this triangle, exactly
    /// ([`in_gamma_range_exact`]).
    pub fn in_gamma_range(&self, iv: &CenterInterval, range: [f64; 4]) -> bool {
        in_gamma_range_exact(|c| self.cmp_gamma(iv, c), range)
    }
    /// The 3D analogue of [`EdgeFrame::cocircular_ends`]: `above` (on the normal's side) and
    /// `below` the binding points, on one sphere with the corners (a triple of a cospherical
    /// group). Equal to adding `above` and then `below`, without the exact in-sphere test.
    pub fn cospherical_ends(
        &self,
        above: Option<[f64; 3]>,
        below: Option<[f64; 3]>,
    ) -> CenterInterval {
        let mut iv = self.start();
        if let Some(x) = above {
            iv.bind_hi(self.tau(x).1, x);
        }
        if let Some(y) = below {
            iv.bind_lo(self.tau(y).1, y);
            if above.is_some() {
                iv.settle(0.0);
            }
        }
        iv
    }
    /// The interval with the binding points `above` (on the normal's side) and `below`: the
    /// same as adding them (in any order) and then points that bind nothing — for a triple of
    /// a cocircular group, whose binding points are those of every other triple of its circle
    /// (`fast::CircleGroup`). The order of the ends by the exact in-sphere test, as in
    /// [`TriFrame::add`].
    pub fn ends(&self, above: Option<[f64; 3]>, below: Option<[f64; 3]>) -> CenterInterval {
        let mut iv = self.start();
        if let Some(x) = above {
            iv.bind_hi(self.offset(1.0, x), x);
        }
        if let Some(y) = below {
            iv.bind_lo(self.offset(-1.0, y), y);
            if let Some(x) = above {
                iv.settle(self.insphere_at(true, x, y));
            }
        }
        iv
    }
    /// Narrows `iv` by point x (not a corner); binding points and the order of the ends are
    /// decided by exact in-sphere tests (see [`EdgeFrame::add`]).
    pub fn add(&self, iv: &mut CenterInterval, x: [f64; 3]) {
        // τ only for the points that become binding ends
        let side = self.side(x);
        if side > 0.0 {
            // above: (b, a, c, y) is positively oriented
            let better = match iv.hi_at {
                None => true,
                Some(y) => self.insphere_at(true, y, x) > 0.0,
            };
            if better {
                iv.bind_hi(self.offset(side, x), x);
                if let Some(l) = iv.lo_at {
                    iv.settle(self.insphere_at(true, x, l));
                }
            }
        } else if side < 0.0 {
            let better = match iv.lo_at {
                None => true,
                Some(y) => self.insphere_at(false, y, x) > 0.0,
            };
            if better {
                iv.bind_lo(self.offset(side, x), x);
                if let Some(h) = iv.hi_at {
                    iv.settle(self.insphere_at(true, h, x));
                }
            }
        } else {
            let [a, b, c] = self.t;
            if in_closed_triangle_3d(a, b, c, x, self.n) {
                iv.all_blocked = true;
            } else if in_circumcircle_3d(a, b, c, x, self.n) {
                iv.finite_blocked = true;
            }
        }
    }
}

/// The interval of empty-ball offsets of triangle (a, b, c) among 3D `points`; normal
/// (b − a) × (c − a). `None` for a degenerate (collinear) triangle, for which no touching
/// ball is defined (Def. 3.1 requires the vertices not to lie in a line). O(N).
pub fn center_interval_3d(
    points: &[[f64; 3]],
    a: usize,
    b: usize,
    c: usize,
) -> Option<CenterInterval> {
    let f = TriFrame::new(points[a], points[b], points[c])?;
    let mut iv = f.start();
    for (i, &x) in points.iter().enumerate() {
        if i != a && i != b && i != c {
            f.add(&mut iv, x);
        }
    }
    Some(iv)
}

/// Whether x (coplanar with triangle abc, normal n) lies in the closed triangle, by exact 2D
/// orientation tests in the coordinate plane where the triangle's projection is largest.
pub fn in_closed_triangle_3d(
    a: [f64; 3],
    b: [f64; 3],
    c: [f64; 3],
    x: [f64; 3],
    n: [f64; 3],
) -> bool {
    let k = if n[0].abs() >= n[1].abs() && n[0].abs() >= n[2].abs() {
        0
    } else if n[1].abs() >= n[2].abs() {
        1
    } else {
        2
    };
    let p = |v: [f64; 3]| match k {
        0 => [v[1], v[2]],
        1 => [v[2], v[0]],
        _ => [v[0], v[1]],
    };
    let (a, b, c, x) = (p(a), p(b), p(c), p(x));
    let s = raw::orient2d(a, b, c).signum();
    let o1 = raw::orient2d(a, b, x) * s;
    let o2 = raw::orient2d(b, c, x) * s;
    let o3 = raw::orient2d(c, a, x) * s;
    o1 >= 0.0 && o2 >= 0.0 && o3 >= 0.0
}

/// True when x, coplanar with the triangle (a, b, c) (normal ≈ `n`), lies strictly inside its
/// circumcircle — exactly: the circle is the trace of every sphere through a, b, c, so with a
/// point d off the plane, x is inside the circle iff it is inside the sphere through a, b, c, d
/// (`insphere` times the orientation of (a, b, c, d) is positive).
pub fn in_circumcircle_3d(a: [f64; 3], b: [f64; 3], c: [f64; 3], x: [f64; 3], n: [f64; 3]) -> bool {
    circumcircle_side_3d(a, b, c, x, n) > 0.0
}

/// For x coplanar with the triangle (a, b, c) (normal ≈ `n`): > 0 when x lies strictly inside
/// its circumcircle, 0 on it, < 0 outside (exact, see [`in_circumcircle_3d`]); 0 for collinear
/// corners.
pub fn circumcircle_side_3d(
    a: [f64; 3],
    b: [f64; 3],
    c: [f64; 3],
    x: [f64; 3],
    n: [f64; 3],
) -> f64 {
    let k = if n[0].abs() >= n[1].abs() && n[0].abs() >= n[2].abs() {
        0
    } else if n[1].abs() >= n[2].abs() {
        1
    } else {
        2
    };
    // d = a moved along the axis the plane is most transverse to; d ≠ a in that coordinate
    let mut d = a;
    d[k] = a[k] + (1.0 + a[k].abs());
    let o = raw::orient3d(a, b, c, d);
    if o == 0.0 {
        return 0.0; // collinear corners: no circle
    }
    raw::insphere(a, b, c, d, x) * o
}

/// Whether `x` lies in the neighbourhood N_γ(c₀, c₁) of the 2D edge (a, b), with the larger
/// ball's centre on side `side` (+1: left of a→b), computed literally from Def. 3.1: explicit
/// discs (or half-planes for |c| = 1), their union (c₁ ≥ 0) or intersection (c₁ < 0), plus the
/// open segment. This is the brute-force oracle for [`CenterInterval::neighborhood_empty`].
pub fn def_contains_2d(a: [f64; 2], b: [f64; 2], c0: f64, c1: f64, side: f64, x: [f64; 2]) -> bool {
    let o = raw::orient2d(a, b, x);
    let d = [b[0] - a[0], b[1] - a[1]];
    let dd = d[0] * d[0] + d[1] * d[1];
    if o == 0.0 && dot_sign(&x, &b, &a) > 0 && dot_sign(&x, &a, &b) > 0 {
        return true; // open segment
    }
    // Ball with centre m + t·N (N = unnormalised left normal, |N| = |d|) and radius² r² + t²|N|²:
    // x is strictly inside iff |x − m|² − 2t (x − m)·N < r², evaluated without square roots so
    // that ties on the boundary circle stay exact for small integer inputs.
    let r2 = 0.25 * dd;
    let m = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
    let nn = [-d[1], d[0]];
    let xm = [x[0] - m[0], x[1] - m[1]];
    let q = xm[0] * xm[0] + xm[1] * xm[1] - r2;
    let h = xm[0] * nn[0] + xm[1] * nn[1];
    let r_over_n = 0.5;
    let in_ball = |c: f64, sd: f64| -> bool {
        if c.abs() >= 1.0 {
            return o * sd > 0.0; // open half-plane on side sd
        }
        if c == 0.0 {
            // the diametral disc, exactly: (a − x)·(b − x) < 0
            return dot_sign(&a, &b, &x) < 0;
        }
        let t = sd * offset_of(c.abs(), r_over_n);
        q < 2.0 * t * h
    };
    let side0 = if c0 * c1 < 0.0 { side } else { -side };
    let in1 = in_ball(c1, side);
    let in0 = in_ball(c0, side0);
    if c1 >= 0.0 {
        in0 || in1
    } else {
        in0 && in1
    }
}

/// The 3D analogue of [`def_contains_2d`] for triangle (a, b, c); `side` +1 is the side of the
/// normal (b − a) × (c − a). The closed triangle (but its corners) always belongs to the
/// neighbourhood.
pub fn def_contains_3d(t: [[f64; 3]; 3], c0: f64, c1: f64, side: f64, x: [f64; 3]) -> bool {
    let [a, b, c] = t;
    let Some((m, r2, n)) = triangle_circle(a, b, c) else {
        return true;
    };
    let o = -raw::orient3d(a, b, c, x);
    if o == 0.0 && in_closed_triangle_3d(a, b, c, x, n) {
        return true;
    }
    let r_over_n = (r2 / dot(n, n)).sqrt();
    let xm = sub(x, m);
    let q = dot(xm, xm) - r2;
    let h = dot(xm, n);
    let in_ball = |cc: f64, sd: f64| -> bool {
        if cc.abs() >= 1.0 {
            return o * sd > 0.0;
        }
        let t = sd * offset_of(cc.abs(), r_over_n);
        q < 2.0 * t * h
    };
    let side0 = if c0 * c1 < 0.0 { side } else { -side };
    let in1 = in_ball(c1, side);
    let in0 = in_ball(c0, side0);
    if c1 >= 0.0 {
        in0 || in1
    } else {
        in0 && in1
    }
}

#[cfg(test)]
mod dd_stage_tests {
    use super::*;
    use crate::geom::exact::{big_cross, big_dot, float_parts};
    use num_bigint::BigInt;
    use rand::{Rng, SeedableRng};

    /// The sign of y − τ(x) for triangle t, exactly: τ = 2ᵏ N / D on the coordinates scaled
    /// to integers X = x·2ᵏ (τ is homogeneous of degree −1), N and D the polynomials of
    /// [`exact_offset`] in big integers; y a float. (x off the plane: D ≠ 0.)
    fn cmp_tau(t: [[f64; 3]; 3], x: [f64; 3], y: f64) -> Ordering {
        let all = [t[0], t[1], t[2], x];
        let emin = all
            .iter()
            .flatten()
            .filter(|v| **v != 0.0)
            .map(|&v| float_parts(v).1)
            .min()
            .unwrap_or(0);
        let big = |p: [f64; 3]| {
            p.map(|v| {
                let (m, e) = float_parts(v);
                BigInt::from(m) << ((e - emin) as usize)
            })
        };
        let [a, b, c, xx] = all.map(big);
        let d = |p: &[BigInt; 3]| -> [BigInt; 3] { std::array::from_fn(|k| &p[k] - &a[k]) };
        let (u, v, w) = (d(&b), d(&c), d(&xx));
        let n = big_cross(&u, &v);
        let nn = big_dot(&n, &n);
        let num = big_dot(&w, &w) * &nn
            - big_dot(&w, &big_cross(&v, &n)) * big_dot(&u, &u)
            - big_dot(&w, &big_cross(&n, &u)) * big_dot(&v, &v);
        let den = BigInt::from(2) * &nn * big_dot(&w, &n);
        assert!(den != BigInt::from(0));
        // y·D against 2^(−emin)·N, both scaled by 2^s so that the exponents are integers ≥ 0
        let (m, e) = float_parts(y);
        let k = -emin;
        let base = e.min(k);
        let lhs = (BigInt::from(m) * &den) << ((e - base) as usize);
        let rhs = num << ((k - base) as usize);
        let o = lhs.cmp(&rhs);
        if den < BigInt::from(0) {
            o.reverse()
        } else {
            o
        }
    }

    /// Near-degenerate triangles and points: skinny triangles (the third corner 10⁻³ … 10⁻⁹
    /// off the line of the other two) and points 10⁻⁴ … 10⁻¹³ off the plane, at coordinates
    /// near 0.1 (the dragon's) and near 1.
    fn cases(seed: u64, count: usize) -> Vec<([[f64; 3]; 3], [f64; 3])> {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let mut out = Vec::new();
        while out.len() < count {
            let scale = [0.1, 1.0, 3e-4][rng.gen_range(0..3)];
            let base: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
            let pt = |rng: &mut rand_chacha::ChaCha8Rng| -> [f64; 3] {
                std::array::from_fn(|k| base[k] + scale * rng.gen_range(-1.0..1.0))
            };
            let (a, b) = (pt(&mut rng), pt(&mut rng));
            let skinny = [1e-1, 1e-3, 1e-6, 1e-9][rng.gen_range(0..4)];
            let s = rng.gen_range(-0.5..1.5);
            let jitter: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
            let c: [f64; 3] =
                std::array::from_fn(|k| a[k] + s * (b[k] - a[k]) + skinny * scale * jitter[k]);
            let Some(f) = TriFrame::new(a, b, c) else {
                continue;
            };
            // a point in the plane (by the float normal), then off it by a tiny height
            let (p, q) = (rng.gen_range(-2.0..2.0), rng.gen_range(-2.0..2.0));
            let nl = dot(f.n, f.n).sqrt();
            let off = [1e-4, 1e-7, 1e-10, 1e-13][rng.gen_range(0..4)] * rng.gen_range(-1.0..1.0);
            let x: [f64; 3] = std::array::from_fn(|k| {
                a[k] + p * (b[k] - a[k]) + q * (c[k] - a[k]) + off * scale * f.n[k] / nl
            });
            if f.side(x) != 0.0 {
                out.push(([a, b, c], x));
            }
        }
        out
    }

    /// The double-double stage's bound holds against the exact τ (big integers) on
    /// near-degenerate cases, the sign it reports is the exact side, it certifies to
    /// [`TAU_TOL`] most of the points the floating-point stage does not, and the bound is
    /// not vacuous: a millionth of it fails on some case.
    #[test]
    fn dd_offsets_are_within_their_bound_of_the_exact_ones() {
        let (mut checked, mut rescued, mut missed_f64, mut sharp) = (0, 0, 0, 0);
        for ([a, b, c], x) in cases(41, 4000) {
            let f = TriFrame::new(a, b, c).unwrap();
            let side = f.side(x);
            let Some((t, h)) = f.offset_dd(x) else {
                continue;
            };
            assert_eq!(h > 0.0, side > 0.0, "{a:?} {b:?} {c:?} {x:?}");
            let e = t.certified();
            if !e.is_finite() {
                continue;
            }
            assert_ne!(cmp_tau([a, b, c], x, t.v - e), Ordering::Greater);
            assert_ne!(cmp_tau([a, b, c], x, t.v + e), Ordering::Less);
            checked += 1;
            let tol = TAU_TOL * (t.v.abs() + f.r_over_n);
            let f64_ok = f.offset_bounded(x).is_some_and(|(tb, hb)| {
                (hb > 0.0) == (side > 0.0) && tb.certified() <= TAU_TOL * (tb.v.abs() + f.r_over_n)
            });
            if !f64_ok {
                missed_f64 += 1;
                rescued += usize::from(e <= tol);
            }
            let tight = e / 1e6;
            if cmp_tau([a, b, c], x, t.v - tight) == Ordering::Greater
                || cmp_tau([a, b, c], x, t.v + tight) == Ordering::Less
            {
                sharp += 1;
            }
        }
        eprintln!("dd stage: checked {checked}, missed by the f64 stage {missed_f64}, rescued {rescued}, sharp {sharp}");
        assert!(checked > 3500, "{checked}");
        assert!(
            missed_f64 > 300 && rescued * 10 > missed_f64 * 9,
            "{missed_f64} {rescued}"
        );
        assert!(sharp > 0, "the bound is 10⁶ times too loose on every case");
    }

    /// The side filter ([`TriFrame::side_filter`]) against the exact `orient3d`, on the
    /// near-degenerate cases and on exactly coplanar points whose float evaluation rounds
    /// (integer coordinates up to 2²⁷: the normal's products pass 2⁵³): when it decides, the
    /// sign is orient3d's, and [`TriFrame::side`] always is. The bound is not vacuous: a
    /// millionth of it would claim a side for some exactly coplanar point.
    #[test]
    fn side_filter_agrees_with_orient3d() {
        let mut all = cases(47, 3000);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(49);
        let r = 1i64 << 26;
        for _ in 0..3000 {
            let p = |rng: &mut rand_chacha::ChaCha8Rng| -> [f64; 3] {
                std::array::from_fn(|_| rng.gen_range(-r..=r) as f64)
            };
            let (a, b, c) = (p(&mut rng), p(&mut rng), p(&mut rng));
            let (s, t) = (
                rng.gen_range(-2i64..=2) as f64,
                rng.gen_range(-2i64..=2) as f64,
            );
            let x = std::array::from_fn(|k| a[k] + s * (b[k] - a[k]) + t * (c[k] - a[k]));
            all.push(([a, b, c], x));
        }
        let (mut decided, mut coplanar, mut wrong_tight) = (0, 0, 0);
        for ([a, b, c], x) in all {
            let Some(f) = TriFrame::new(a, b, c) else {
                continue;
            };
            let exact = sign(-raw::orient3d(a, b, c, x));
            assert_eq!(f.side(x), exact, "{a:?} {b:?} {c:?} {x:?}");
            coplanar += usize::from(exact == 0.0);
            if let Some((h, bound)) = f.side_filter(x) {
                if h.abs() > bound {
                    decided += 1;
                    assert_eq!(h.signum(), exact);
                }
                if h.abs() > bound / 1e6 && h.signum() != exact {
                    wrong_tight += 1;
                }
            }
        }
        assert!(
            decided > 1500 && coplanar > 1000 && wrong_tight > 0,
            "{decided} {coplanar} {wrong_tight}"
        );
    }

    /// With the stage, [`TriFrame::offset`] stays within [`TAU_TOL`] of the exact τ, and the
    /// intervals built point by point decide c₁′ ≥ c as without it (the offsets only feed the
    /// floats; the decisions are exact).
    #[test]
    fn dd_stage_keeps_the_offsets_and_the_decisions() {
        let all = cases(43, 3000);
        for ([a, b, c], x) in &all {
            let f = TriFrame::new(*a, *b, *c).unwrap().with_dd_stage();
            let side = f.side(*x);
            let tau = f.offset(side, *x);
            let tol = TAU_TOL * (tau.abs() + f.r_over_n);
            assert_ne!(cmp_tau([*a, *b, *c], *x, tau - tol), Ordering::Greater);
            assert_ne!(cmp_tau([*a, *b, *c], *x, tau + tol), Ordering::Less);
        }
        // one triangle against groups of the points (the near-degenerate ones of `cases`
        // relative to their own triangles, so here: arbitrary points near it)
        for chunk in all.chunks(30) {
            let [a, b, c] = chunk[0].0;
            let (plain, dd) = (
                TriFrame::new(a, b, c).unwrap(),
                TriFrame::new(a, b, c).unwrap().with_dd_stage(),
            );
            let (mut i0, mut i1) = (plain.start(), dd.start());
            for (_, x) in chunk {
                plain.add(&mut i0, *x);
                dd.add(&mut i1, *x);
            }
            assert_eq!((i0.lo_at, i0.hi_at), (i1.lo_at, i1.hi_at));
            for cc in [-0.9, -0.5, -0.1, 0.0, 0.3, 0.9] {
                assert_eq!(plain.c1_at_least(&i0, cc), dd.c1_at_least(&i1, cc));
            }
        }
    }
}
