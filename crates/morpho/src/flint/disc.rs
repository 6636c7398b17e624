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
use crate::geom::predicates::raw::{incircle, orient2d};
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

/// The positions `from..to` of a polygon (wrapping) with their points, in order, without a
/// division per vertex.
fn positions(
    points: &[[f64; 2]],
    from: usize,
    to: usize,
) -> impl Iterator<Item = (usize, [f64; 2])> + '_ {
    let n = points.len();
    let start = from % n;
    (from..to).zip(points[start..].iter().chain(points.iter().cycle()).copied())
}

/// True when `x` lies in the closed disc through `a`, `b`, `v` (exact; `v` off line ab).
#[inline]
pub(crate) fn in_closed_disc(a: [f64; 2], b: [f64; 2], v: [f64; 2], x: [f64; 2]) -> bool {
    let o = orient2d(a, b, v);
    let ic = incircle(a, b, v, x);
    if o > 0.0 {
        ic >= 0.0
    } else {
        ic <= 0.0
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
        let (a, b) = (at(points, lo), at(points, hi));
        let n = points.len();
        // positions lo+1..hi as (position, point) without a division per vertex
        let interior = || positions(points, lo + 1, hi);
        let (mut best_l, mut best_r): (Option<usize>, Option<usize>) = (None, None);
        let mut unbounded = false;
        // an empty range (never in the window) when there is no window
        let [w_lo, w_hi] = window.unwrap_or([1, 0]);
        let (mut far, mut far_o) = (window.map(|[l, h]| l + (h - l) / 2), 0.0f64);
        for (p, x) in interior() {
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
                    // the current vertex q is on the same side as x (orient2d(a, b, q) has
                    // the sign of o): x replaces q iff strictly outside the circle a, b, q
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
        // conservative reaches: every polyline vertex in f64 distance (squares compared, one
        // square root at the end)
        let m = midpoint(a, b);
        let mut hull2: f64 = 0.0;
        let mut reach2 = [0.0f64; 2];
        for (_, x) in positions(points, lo, hi + 1) {
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
