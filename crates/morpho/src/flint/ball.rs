//! Balls with signed radius, half-spaces and the ± operator in 3D; the flintstone of one open
//! polyhedron (Veltkamp 1992, §7.3.1, Def. 7.5; widths Def. 7.6; reading notes A.2–A.3, A.7).
//!
//! An open polyhedron P is approximated by the triangle of its three corners `c0 c1 c2`. On
//! each side of the triangle's plane the vertex `v_q` whose ball `B(c0, c1, c2; v_q)` holds
//! every vertex of that side is found **exactly**: a candidate replaces the current one iff it
//! lies strictly outside the current sphere (`insphere`, oriented by `orient3d`). The flintstone
//! is `(B_q ∩ H_q) ∪ (B_r ∩ H_r)` — each ball on its own side — which is Def. 7.2's `B_q ± B_r`
//! (notes A.2, the same pencil-of-spheres argument as in 2D): an intersection iff `v_r` lies in
//! the closed ball `B_q`, else a union (which V says occurs in 3D). One side empty gives a
//! *cap* `B_q ∩ H_q`.
//!
//! Degenerate cases: a vertex in the plane inside the closed circumcircle of the corners lies in
//! every ball through them and is skipped; all vertices so: the *flat* stone (kind
//! [`StoneKind::Segment`], the circumdisc, widths 0); a vertex in the plane outside the
//! circumcircle is in no ball through the corners — V's "half-space ∪ ball" — and the stone is
//! [`StoneKind::Unbounded`] (deviation: treated as the whole space for the invariant and the
//! error, so queries only use its conservative hull ball). Corners that are collinear or
//! coalesce (V's degenerate triangles) have no plane: also `Unbounded`. Coplanar tests use the
//! circumsphere through the corners and an off-plane apex (its trace on the plane is the
//! circumcircle), so they are exact too.
//!
//! Widths (Def. 7.6 with the notes' correction `h = sqrt(R² − r²)`): with `r` the corners'
//! circumradius and `t` the signed offset of the ball centre from the plane towards its vertex,
//! `w = t + sqrt(r² + t²)` (evaluated without cancellation). Centres, radii and widths are `f64`
//! constructions; membership ([`Flintstone3::contains`]) is exact.
//!
//! **Query filter.** For the point queries each stone also keeps up to three `f64` balls
//! (centre, squared radius inflated by a relative 1e-12 above the largest *computed* squared
//! distance to a vertex of P or of its boundary paths) and, for a cap, its empty side. Each is
//! a convex set holding every such vertex (rounding of a squared distance is far below the
//! inflation), so their intersection is a convex superset of the flintstone: a point outside
//! one of them is certainly outside the convex hull of P, its paths and its triangle — the
//! condition Lemma 6.1 needs. A ∪ or unbounded stone is not convex and keeps only its hull ball.
//! Cost: O(k) for k vertices.

use super::disc::StoneKind;
use crate::geom::predicates::raw::{insphere, orient3d};
use crate::geom::vec::{add_scaled, cross, dist2, dot, norm, sub};

/// The ball of one side of the corners' plane: through the three corners and its vertex.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SideBall {
    /// Input index of the defining vertex.
    pub vertex: u32,
    /// Signed offset of the centre from the plane, positive towards the vertex's side.
    pub t: f64,
    /// Centre of the ball.
    pub center: [f64; 3],
    /// Signed radius (Def. 7.1 in 3D): negative when centre and vertex are on opposite sides.
    pub radius: f64,
    /// Width of the flintstone on this side (Def. 7.6, corrected).
    pub width: f64,
}

/// The flintstone of an open polyhedron with corners `corners` (Def. 7.5).
#[derive(Debug, Clone, PartialEq)]
pub struct Flintstone3 {
    /// The three corners (input indices).
    pub corners: [u32; 3],
    /// Ball of the vertices with `orient3d(c0, c1, c2, x) > 0` (below the counter-clockwise
    /// corners), if any.
    pub below: Option<SideBall>,
    /// Ball of the vertices with `orient3d(c0, c1, c2, x) < 0` (above), if any.
    pub above: Option<SideBall>,
    /// ∩, ∪, cap, flat (`Segment`) or unbounded.
    pub kind: StoneKind,
    /// The conservative query filter (see the module doc).
    pub(crate) filter: Filter,
}

/// Convex `f64` supersets of a flintstone: balls `(centre, inflated r²)` and, for a cap, the
/// side sign (of `orient3d`) that holds no vertex.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Filter {
    pub balls: [([f64; 3], f64); 3],
    pub count: u8,
    pub empty_side: i8,
}

impl Filter {
    /// The filter that excludes nothing.
    pub fn none() -> Filter {
        Filter {
            balls: [([0.0; 3], f64::INFINITY); 3],
            count: 0,
            empty_side: 0,
        }
    }

    /// A filter of one ball about `center` holding `verts` (never excludes when `prune` is off).
    pub fn hull(pos: &[[f64; 3]], verts: &[u32], prune: bool) -> Filter {
        let mut f = Filter {
            balls: [([0.0; 3], f64::INFINITY); 3],
            count: 0,
            empty_side: 0,
        };
        if prune {
            let (lo, hi) = crate::geom::vec::bounds(
                &verts.iter().map(|&v| pos[v as usize]).collect::<Vec<_>>(),
            );
            let c = std::array::from_fn(|k| 0.5 * (lo[k] + hi[k]));
            f.push(c, reach2(pos, verts, c));
        }
        f
    }

    fn push(&mut self, c: [f64; 3], r2: f64) {
        if (self.count as usize) < 3 && c.iter().all(|x| x.is_finite()) && r2.is_finite() {
            self.balls[self.count as usize] = (c, r2);
            self.count += 1;
        }
    }

    /// True when `x` is certainly outside the flintstone (outside one convex superset);
    /// `corners` (the corners' positions) is read only for a cap's empty side.
    #[inline]
    pub fn excludes(&self, x: [f64; 3], corners: impl FnOnce() -> [[f64; 3]; 3]) -> bool {
        for &(c, r2) in &self.balls[..self.count as usize] {
            if dist2(x, c) > r2 {
                return true;
            }
        }
        if self.empty_side != 0 {
            let [a, b, c] = corners();
            let o = orient3d(a, b, c, x);
            if (self.empty_side > 0 && o > 0.0) || (self.empty_side < 0 && o < 0.0) {
                return true;
            }
        }
        false
    }
}

/// The largest computed squared distance from `c` to a vertex, inflated (relative 1e-12, plus
/// the smallest normal number) so that it bounds every true squared distance.
pub(crate) fn reach2(pos: &[[f64; 3]], verts: &[u32], c: [f64; 3]) -> f64 {
    let m = verts
        .iter()
        .map(|&v| dist2(pos[v as usize], c))
        .fold(0.0, f64::max);
    m * (1.0 + 1e-12) + f64::MIN_POSITIVE
}

/// True when `x` lies in the closed ball through `a, b, c, v` (exact; `v` off the plane abc).
#[inline]
pub(crate) fn in_closed_ball(
    a: [f64; 3],
    b: [f64; 3],
    c: [f64; 3],
    v: [f64; 3],
    x: [f64; 3],
) -> bool {
    let o = orient3d(a, b, c, v);
    let i = insphere(a, b, c, v, x);
    if o > 0.0 {
        i >= 0.0
    } else {
        i <= 0.0
    }
}

/// [`in_closed_ball`] when the sign of `orient3d(a, b, c, v)` is known: `positive` iff it is
/// > 0 (it must not be 0). The same exact answer with one predicate less.
#[inline]
pub(crate) fn in_closed_ball_side(
    positive: bool,
    a: [f64; 3],
    b: [f64; 3],
    c: [f64; 3],
    v: [f64; 3],
    x: [f64; 3],
) -> bool {
    let i = insphere(a, b, c, v, x);
    if positive {
        i >= 0.0
    } else {
        i <= 0.0
    }
}

/// Circumcentre and circumradius of the triangle abc (`f64`; `None` when degenerate).
pub(crate) fn circumcircle(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> Option<([f64; 3], f64)> {
    let (u, v) = (sub(b, a), sub(c, a));
    let w = cross(u, v);
    let ww = dot(w, w);
    if ww.is_nan() || ww <= 0.0 {
        return None;
    }
    // C = a + (|u|² (v × w) + |v|² (w × u)) / (2 |w|²)
    let num = add_scaled(cross(v, w).map(|x| x * dot(u, u)), dot(v, v), cross(w, u));
    let cc = add_scaled(a, 0.5 / ww, num);
    let r = dist2(cc, a).sqrt();
    cc.iter().all(|x| x.is_finite()).then_some((cc, r))
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

impl Flintstone3 {
    /// The flintstone of the vertices `verts` (the open polyhedron's vertices and those of its
    /// boundary paths) for the corners `corners`. `prune = false` disables the query filter
    /// (coordinates whose squares would over- or underflow).
    pub fn of(pos: &[[f64; 3]], corners: [u32; 3], verts: &[u32], prune: bool) -> Flintstone3 {
        let [a, b, c] = corners.map(|v| pos[v as usize]);
        let mut stone = Flintstone3 {
            corners,
            below: None,
            above: None,
            kind: StoneKind::Unbounded,
            filter: Filter::hull(pos, verts, prune),
        };
        let Some((cc, r)) = circumcircle(a, b, c) else {
            return stone;
        };
        let n = cross(sub(b, a), sub(c, a));
        let nn = norm(n);
        let nh = n.map(|x| x / nn);
        // an apex off the plane: its sphere with the corners traces the circumcircle
        let apex = add_scaled(cc, r.max(f64::MIN_POSITIVE), nh);
        if orient3d(a, b, c, apex) == 0.0 || nn.is_nan() || nn <= 0.0 {
            return stone;
        }
        let (mut best_b, mut best_a): (Option<u32>, Option<u32>) = (None, None);
        let mut unbounded = false;
        for &x in verts {
            let px = pos[x as usize];
            // a corner (or a vertex at a corner's position) is in the plane and on every
            // sphere through the corners, so in the closed ball of the apex: it changes
            // nothing, and skipping it saves two exact (fully degenerate) predicates
            if px == a || px == b || px == c {
                continue;
            }
            let o = orient3d(a, b, c, px);
            if o == 0.0 {
                unbounded |= !in_closed_ball(a, b, c, apex, px);
                continue;
            }
            let below = o > 0.0;
            let best = if below { &mut best_b } else { &mut best_a };
            match *best {
                None => *best = Some(x),
                Some(q) => {
                    // q is on x's side: orient3d(a, b, c, q) has the sign of `o`
                    if !in_closed_ball_side(below, a, b, c, pos[q as usize], px) {
                        *best = Some(x);
                    }
                }
            }
        }
        // side: +1 above (along n, orient3d < 0), −1 below (exact, from orient3d)
        let ball = |v: u32, side: f64| -> SideBall {
            let pv = pos[v as usize];
            let h = dot(sub(pv, cc), nh).abs().max(f64::MIN_POSITIVE);
            let t = (dist2(pv, cc) - r * r) / (2.0 * h);
            let center = add_scaled(cc, side * t, nh);
            let rad = (r * r + t * t).sqrt();
            SideBall {
                vertex: v,
                t,
                center,
                radius: if t < 0.0 { -rad } else { rad },
                width: width(r, t),
            }
        };
        stone.below = best_b.map(|v| ball(v, -1.0));
        stone.above = best_a.map(|v| ball(v, 1.0));
        stone.kind = match (best_b, best_a) {
            _ if unbounded => StoneKind::Unbounded,
            (None, None) => StoneKind::Segment,
            (Some(_), None) | (None, Some(_)) => StoneKind::Cap,
            (Some(q), Some(r)) => {
                if in_closed_ball(a, b, c, pos[q as usize], pos[r as usize]) {
                    StoneKind::Intersection
                } else {
                    StoneKind::Union
                }
            }
        };
        if prune {
            match stone.kind {
                StoneKind::Intersection => {
                    for d in [stone.below, stone.above].into_iter().flatten() {
                        stone.filter.push(d.center, reach2(pos, verts, d.center));
                    }
                }
                StoneKind::Cap => {
                    let (d, empty) = match (stone.below, stone.above) {
                        (Some(d), None) => (d, -1),
                        (None, Some(d)) => (d, 1),
                        _ => unreachable!("a cap has one side"),
                    };
                    stone.filter.push(d.center, reach2(pos, verts, d.center));
                    stone.filter.empty_side = empty;
                }
                StoneKind::Segment => {
                    // flat: the circumcircle's ball holds every vertex
                    stone.filter.push(cc, reach2(pos, verts, cc));
                }
                _ => {}
            }
        }
        stone
    }

    /// The flintstone error `max{w_1, w_2}` (Def. 7.6; 0 when flat, ∞ when unbounded).
    pub fn error(&self) -> f64 {
        if self.kind == StoneKind::Unbounded {
            return f64::INFINITY;
        }
        let (w1, w2) = self.widths();
        w1.max(w2)
    }

    /// The two widths `(below, above)` (0 for an empty side).
    pub fn widths(&self) -> (f64, f64) {
        let w = |d: &Option<SideBall>| d.map_or(0.0, |d| d.width);
        (w(&self.below), w(&self.above))
    }

    /// The split vertex by V's rule: the cap's vertex, else the one of larger signed radius
    /// (larger `t`; ties: below). `None` without balls.
    pub fn split(&self) -> Option<u32> {
        match (self.below, self.above) {
            (Some(l), Some(r)) => Some(if r.t > l.t { r.vertex } else { l.vertex }),
            (Some(d), None) | (None, Some(d)) => Some(d.vertex),
            (None, None) => None,
        }
    }

    /// Exact membership of `x` in the closed flintstone (always true when unbounded).
    pub fn contains(&self, pos: &[[f64; 3]], x: [f64; 3]) -> bool {
        if self.kind == StoneKind::Unbounded {
            return true;
        }
        let [a, b, c] = self.corners.map(|v| pos[v as usize]);
        let o = orient3d(a, b, c, x);
        if o == 0.0 {
            // the trace of every ball through the corners: the closed circumdisc
            let Some((cc, r)) = circumcircle(a, b, c) else {
                return true;
            };
            let n = cross(sub(b, a), sub(c, a));
            let apex = add_scaled(cc, r / norm(n), n);
            return orient3d(a, b, c, apex) == 0.0 || in_closed_ball(a, b, c, apex, x);
        }
        let side = if o > 0.0 { &self.below } else { &self.above };
        match side {
            Some(d) => in_closed_ball(a, b, c, pos[d.vertex as usize], x),
            None => false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The per-vertex loop of [`Flintstone3::of`] as first written (no corner skip, the
    /// candidate's side recomputed by `orient3d`): the oracle of the lockstep test.
    fn best_reference(
        pos: &[[f64; 3]],
        corners: [u32; 3],
        verts: &[u32],
    ) -> Option<(Option<u32>, Option<u32>, bool)> {
        let [a, b, c] = corners.map(|v| pos[v as usize]);
        let (cc, r) = circumcircle(a, b, c)?;
        let n = cross(sub(b, a), sub(c, a));
        let nn = norm(n);
        let apex = add_scaled(cc, r.max(f64::MIN_POSITIVE), n.map(|x| x / nn));
        if orient3d(a, b, c, apex) == 0.0 || nn.is_nan() || nn <= 0.0 {
            return None;
        }
        let (mut bb, mut ba, mut unb) = (None, None, false);
        for &x in verts {
            let px = pos[x as usize];
            let o = orient3d(a, b, c, px);
            if o == 0.0 {
                unb |= !in_closed_ball(a, b, c, apex, px);
                continue;
            }
            let best: &mut Option<u32> = if o > 0.0 { &mut bb } else { &mut ba };
            match *best {
                None => *best = Some(x),
                Some(q) if !in_closed_ball(a, b, c, pos[q as usize], px) => *best = Some(x),
                _ => {}
            }
        }
        Some((bb, ba, unb))
    }

    /// Lockstep: the same side vertices and kind as the reference loop on point sets holding
    /// the corners (also repeated, and duplicated at another index), exactly coplanar points
    /// inside and outside the circumcircle, cospherical points (ties) and random points.
    #[test]
    fn side_vertices_equal_the_reference_loop() {
        let mut r = crate::util::Rng::new(3);
        let mut kinds = [0usize; 5];
        for round in 0..400 {
            let mut pos: Vec<[f64; 3]> = Vec::new();
            let g = |r: &mut crate::util::Rng| (r.below(9) as f64) - 4.0;
            // corners on z = 0 (integers: coplanar tests are exact)
            for _ in 0..3 {
                pos.push([g(&mut r), g(&mut r), 0.0]);
            }
            let corners = [0, 1, 2];
            pos.push(pos[1]); // a duplicate of a corner at another index
            for k in 0..12 {
                let z = match (round + k) % 4 {
                    0 => 0.0,
                    1 => g(&mut r),
                    _ => r.unit() * 2.0 - 1.0,
                };
                pos.push([g(&mut r) * 0.7, g(&mut r) * 0.5, z]);
            }
            let mut verts: Vec<u32> = (0..pos.len() as u32).collect();
            verts.extend([2, 0, 1]);
            let st = Flintstone3::of(&pos, corners, &verts, true);
            let Some((bb, ba, unb)) = best_reference(&pos, corners, &verts) else {
                assert_eq!(st.kind, StoneKind::Unbounded);
                continue;
            };
            assert_eq!(st.below.map(|d| d.vertex), bb, "round {round}");
            assert_eq!(st.above.map(|d| d.vertex), ba, "round {round}");
            assert_eq!(st.kind == StoneKind::Unbounded, unb, "round {round}");
            kinds[st.kind as usize] += 1;
        }
        assert!(
            kinds.iter().filter(|&&k| k > 0).count() >= 3,
            "kinds {kinds:?}"
        );
    }

    #[test]
    fn cap_and_intersection_contain_their_vertices() {
        // a pyramid over the triangle: a cap through the apex
        let pos = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 2.0, 0.0],
            [0.5, 0.5, 1.0],
            [0.4, 0.4, 0.3],
        ];
        let f = Flintstone3::of(&pos, [0, 1, 2], &[0, 1, 2, 3, 4], true);
        assert_eq!(f.kind, StoneKind::Cap);
        assert_eq!(f.split(), Some(3));
        for p in pos {
            assert!(f.contains(&pos, p));
            assert!(!f.filter.excludes(p, || [pos[0], pos[1], pos[2]]));
        }
        assert!(!f.contains(&pos, [0.5, 0.5, -0.01]));
        assert!(f
            .filter
            .excludes([0.5, 0.5, -0.01], || [pos[0], pos[1], pos[2]]));
        // a vertex on each side: intersection
        let mut q = pos.to_vec();
        q[4] = [0.3, 0.3, -0.2];
        let g = Flintstone3::of(&q, [0, 1, 2], &[0, 1, 2, 3, 4], true);
        assert_eq!(g.kind, StoneKind::Intersection);
        let (w1, w2) = g.widths();
        assert!(w1 >= 0.2 - 1e-12 && w2 >= 1.0 - 1e-12, "{w1} {w2}");
        // a vertex in the plane outside the circumcircle: unbounded
        q[4] = [5.0, 5.0, 0.0];
        let u = Flintstone3::of(&q, [0, 1, 2], &[0, 1, 2, 3, 4], true);
        assert_eq!(u.kind, StoneKind::Unbounded);
        assert!(u.error().is_infinite());
    }

    #[test]
    fn hemisphere_width_is_the_radius() {
        // corners on the unit circle, apex at the pole: t = 0, width = r = 1
        let s = 3f64.sqrt() / 2.0;
        let pos = [
            [1.0, 0.0, 0.0],
            [-0.5, s, 0.0],
            [-0.5, -s, 0.0],
            [0.0, 0.0, 1.0],
        ];
        let f = Flintstone3::of(&pos, [0, 1, 2], &[0, 1, 2, 3], true);
        assert!((f.error() - 1.0).abs() < 1e-12, "{}", f.error());
        // shallow bump: negative signed radius, width = height
        let p2 = [pos[0], pos[1], pos[2], [0.0, 0.0, 0.1]];
        let g = Flintstone3::of(&p2, [0, 1, 2], &[0, 1, 2, 3], true);
        let d = g.above.or(g.below).unwrap();
        assert!(d.radius < 0.0);
        assert!((g.error() - 0.1).abs() < 1e-12, "{}", g.error());
    }
}
