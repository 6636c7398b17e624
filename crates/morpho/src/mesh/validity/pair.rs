//! The exact pair test of [`super::self_intersections`]: do two triangles meet beyond their
//! shared vertices/edge? A floating-point plane filter with a proven error bound
//! ([`PlaneFilter`]) decides most pairs; pairs without a common vertex whose filtered signs all
//! are certain and straddle are decided by two exact predicates (Guigue–Devillers); every
//! other pair by the exact test of its class ([`crate::geom::intersect::triangles_meet_beyond_shared`]).

use crate::geom::intersect::triangles_meet_beyond_shared;
use crate::geom::predicates::raw::orient3d;
use crate::geom::vec::{cross, dot, sub};

type P = [f64; 3];

/// A triangle's floating-point plane for the sign filter of [`pair_meets_filtered`]: a corner
/// `a`, the rounded normal n = (b − a) × (c − a), and per axis the permanent
/// |u_j v_k| + |u_k v_j| of that cross product (u = b − a, v = c − a).
#[derive(Clone, Copy)]
pub(crate) struct PlaneFilter {
    pub(super) a: P,
    pub(super) n: P,
    pub(super) perm: P,
}

impl PlaneFilter {
    pub(crate) fn new(t: [P; 3]) -> Self {
        let (u, v) = (sub(t[1], t[0]), sub(t[2], t[0]));
        let n = cross(u, v);
        let perm = [
            (u[1] * v[2]).abs() + (u[2] * v[1]).abs(),
            (u[2] * v[0]).abs() + (u[0] * v[2]).abs(),
            (u[0] * v[1]).abs() + (u[1] * v[0]).abs(),
        ];
        PlaneFilter { a: t[0], n, perm }
    }

    /// The sign of n · (x − a), i.e. of −orient3d(a, b, c, x) in robust's convention, when its
    /// float evaluation certifies it, else 0 (unknown). Error analysis: each difference, product and sum rounds once (relative ε);
    /// the rounded n_i is within 4ε·perm_i of the exact cross product and the computed sum
    /// within 8ε·Σ perm_i |x_i − a_i| (+ O(ε²)) of the exact determinant. The filter uses
    /// 16ε times that bound, and gives up (0) below 2⁻⁹⁰⁰ (gradual underflow breaks the
    /// relative-error model) and on non-finite values; the exact predicate decides then.
    #[inline]
    pub(crate) fn side(&self, x: P) -> i8 {
        let w = sub(x, self.a);
        let s = dot(self.n, w);
        let b = self.perm[0] * w[0].abs() + self.perm[1] * w[1].abs() + self.perm[2] * w[2].abs();
        let bound = 16.0 * f64::EPSILON * b;
        if !(bound.is_finite() && s.is_finite()) || b < 1e-270 {
            return 0;
        }
        if s > bound {
            1
        } else if s < -bound {
            -1
        } else {
            0
        }
    }

    /// Every given point is certainly strictly on one side (the same for all) of the plane.
    #[inline]
    fn all_one_side(&self, xs: &[P]) -> bool {
        let s0 = self.side(xs[0]);
        s0 != 0 && xs[1..].iter().all(|&x| self.side(x) == s0)
    }
}

/// One triangle for [`pair_meets_filtered`]: its vertex ids, its other two corners and the
/// plane filter (which holds the first corner).
#[derive(Clone, Copy)]
pub(crate) struct TriRec {
    pub(super) f: PlaneFilter,
    pub(super) bc: [P; 2],
    pub(super) v: [u32; 3],
}

impl TriRec {
    pub(crate) fn new(v: [u32; 3], p: [P; 3]) -> Self {
        TriRec {
            f: PlaneFilter::new(p),
            bc: [p[1], p[2]],
            v,
        }
    }

    #[inline]
    fn corner(&self, k: usize) -> P {
        if k == 0 {
            self.f.a
        } else {
            self.bc[k - 1]
        }
    }

    #[inline]
    fn corners(&self) -> [P; 3] {
        [self.f.a, self.bc[0], self.bc[1]]
    }
}

/// [`pair_meets`] behind a floating-point filter: the pair is cleared without exact arithmetic
/// when the other triangle's corners that are not shared lie certainly strictly on one side of
/// one triangle's plane (then the two meet at most in their shared vertices or edge; for a
/// common edge abc/abd, d strictly off plane abc rules out a fold). Undecided pairs go to the
/// exact test, so the verdict always equals [`pair_meets`].
pub(super) fn pair_meets_filtered(ta: &TriRec, tb: &TriRec) -> bool {
    let mut pts_b = [[0.0; 3]; 3];
    let mut nb = 0;
    for k in 0..3 {
        if !ta.v.contains(&tb.v[k]) {
            pts_b[nb] = tb.corner(k);
            nb += 1;
        }
    }
    if nb == 0 {
        // every id of tb is one of ta's: the same triangle, or a face repeating an id (a
        // segment or point of ta's), which the exact test decides
        return pair_meets_at(ta.v, tb.v, ta.corners(), tb.corners());
    }
    if nb == 3 {
        // no common vertex: certified signs of each triangle's corners against the other's plane
        let (pa, pb) = (ta.corners(), tb.corners());
        let (u0, u1, u2) = (ta.f.side(pb[0]), ta.f.side(pb[1]), ta.f.side(pb[2]));
        if u0 != 0 && u0 == u1 && u1 == u2 {
            return false;
        }
        let (t0, t1, t2) = (tb.f.side(pa[0]), tb.f.side(pa[1]), tb.f.side(pa[2]));
        if t0 != 0 && t0 == t1 && t1 == t2 {
            return false;
        }
        if u0 != 0 && u1 != 0 && u2 != 0 && t0 != 0 && t1 != 0 && t2 != 0 {
            return crossing_triangles_meet(pa, [t0, t1, t2], pb, [u0, u1, u2]);
        }
        return pair_meets_at(ta.v, tb.v, pa, pb);
    }
    if ta.f.all_one_side(&pts_b[..nb]) {
        return false;
    }
    if nb < 3 {
        // a common vertex: the other direction; a common edge: d on the plane or undecided
        if nb == 2 {
            let mut pts_a = [[0.0; 3]; 2];
            let mut na = 0;
            for k in 0..3 {
                if !tb.v.contains(&ta.v[k]) && na < 2 {
                    pts_a[na] = ta.corner(k);
                    na += 1;
                }
            }
            if na == 2 && tb.f.all_one_side(&pts_a) {
                return false;
            }
        }
    } else if tb.f.all_one_side(&ta.corners()) {
        return false;
    }
    pair_meets_at(ta.v, tb.v, ta.corners(), tb.corners())
}

/// Triangles t and u, each with its corners strictly on both sides of the other's plane
/// (`st`: the signs of t's corners against u's plane, `su`: of u's against t's, all nonzero
/// and not all equal, as [`PlaneFilter::side`] certifies them), intersect (exact).
///
/// Guigue & Devillers 2003 ("Fast and robust triangle–triangle overlap test using orientation
/// predicates", §3): both triangles meet the line L of the two planes in a segment; t's runs
/// between its two edges from the corner p₁ alone on its side of u's plane, u's between the
/// edges from p₂. With p₁ on the positive side of u and p₂ on the positive side of t in the
/// sense of [`PlaneFilter::side`] (n · (x − a) > 0; swap the other two corners, i.e. reverse
/// the orientation, when not), the two segments overlap iff orient3d(p₁, q₁, p₂, q₂) ≥ 0 and
/// orient3d(p₁, r₁, r₂, p₂) ≥ 0 (the paper's ≤ 0 with its opposite orientation convention):
/// two exact predicates in place of the up to thirty of [`crate::geom::intersect::triangles_intersect`] (= 0 is a
/// touching, which counts).
pub(super) fn crossing_triangles_meet(t: [P; 3], st: [i8; 3], u: [P; 3], su: [i8; 3]) -> bool {
    // the corner whose sign differs from the two others'
    let alone = |s: [i8; 3]| {
        if s[0] == s[1] {
            2
        } else if s[0] == s[2] {
            1
        } else {
            0
        }
    };
    let (i, j) = (alone(st), alone(su));
    let (p1, mut q1, mut r1) = (t[i], t[(i + 1) % 3], t[(i + 2) % 3]);
    let (p2, mut q2, mut r2) = (u[j], u[(j + 1) % 3], u[(j + 2) % 3]);
    if st[i] < 0 {
        std::mem::swap(&mut q2, &mut r2);
    }
    if su[j] < 0 {
        std::mem::swap(&mut q1, &mut r1);
    }
    orient3d(p1, q1, p2, q2) >= 0.0 && orient3d(p1, r1, r2, p2) >= 0.0
}

/// The exact test of one pair by its number of common vertices (see the module documentation).
pub(super) fn pair_meets(pos: &[P], ta: [u32; 3], tb: [u32; 3]) -> bool {
    pair_meets_at(
        ta,
        tb,
        ta.map(|v| pos[v as usize]),
        tb.map(|v| pos[v as usize]),
    )
}

/// [`pair_meets`] with the corners given (`pa`, `pb`: the positions of `ta`, `tb`).
pub(super) fn pair_meets_at(ta: [u32; 3], tb: [u32; 3], pa: [P; 3], pb: [P; 3]) -> bool {
    triangles_meet_beyond_shared(ta, pa, tb, pb)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::intersect::triangles_intersect;

    /// The two-predicate test of crossing triangles ([`crossing_triangles_meet`], reached from
    /// [`pair_meets_filtered`] when no corner is shared and all six filtered signs are certain)
    /// agrees with the exact [`triangles_intersect`]: random pairs of nearby triangles, integer
    /// grids (touching configurations: the two final predicates are 0), the same nudged by a few
    /// ulps, corners rounded onto the other's plane (near-coplanar: the filter's bound is what
    /// keeps float signs from being trusted; with ε/4 instead of 16ε this test fails), at scales
    /// 2^-400 … 2^400. Counts make sure the shortcut itself decided many pairs,
    /// both ways.
    #[test]
    fn crossing_pair_shortcut_agrees_with_the_exact_test() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(77);
        let (mut short_hit, mut short_miss) = (0, 0);
        for round in 0..12 {
            let scale = 2f64.powi([0, -400, 400, 7][round % 4]);
            for _ in 0..20_000 {
                let pt = |rng: &mut rand_chacha::ChaCha8Rng| -> P {
                    std::array::from_fn(|_| match round / 4 {
                        0 => rng.gen_range(0..4) as f64,
                        _ => {
                            let x = rng.gen_range(0..4) as f64 + 0.5;
                            let k = rng.gen_range(-3i64..=3);
                            if rng.gen_bool(0.5) {
                                f64::from_bits((x.to_bits() as i64 + k) as u64)
                            } else {
                                rng.gen_range(0.0..4.0)
                            }
                        }
                    })
                };
                let t: [P; 3] = std::array::from_fn(|_| pt(&mut rng).map(|x| x * scale));
                let mut u: [P; 3] = std::array::from_fn(|_| pt(&mut rng).map(|x| x * scale));
                if round / 4 == 2 {
                    // near-coplanar: u's corners are rounded points of t's plane (the float
                    // signs are noise of the order of the filter's bound)
                    for q in u.iter_mut().take(rng.gen_range(1..=3)) {
                        let (al, be): (f64, f64) =
                            (rng.gen_range(-0.5..1.5), rng.gen_range(-0.5..1.5));
                        *q = std::array::from_fn(|k| {
                            t[0][k] + al * (t[1][k] - t[0][k]) + be * (t[2][k] - t[0][k])
                        });
                    }
                }
                let (ra, rb) = (TriRec::new([0, 1, 2], t), TriRec::new([3, 4, 5], u));
                let exact = triangles_intersect(t, u);
                assert_eq!(pair_meets_filtered(&ra, &rb), exact, "{t:?} {u:?}");
                assert_eq!(pair_meets_filtered(&rb, &ra), exact, "{t:?} {u:?}");
                let su = u.map(|x| ra.f.side(x));
                let st = t.map(|x| rb.f.side(x));
                let straddle =
                    |s: [i8; 3]| s.iter().all(|&x| x != 0) && s.iter().any(|&x| x != s[0]);
                if straddle(su) && straddle(st) {
                    assert_eq!(crossing_triangles_meet(t, st, u, su), exact);
                    assert_eq!(crossing_triangles_meet(u, su, t, st), exact);
                    if exact {
                        short_hit += 1;
                    } else {
                        short_miss += 1;
                    }
                }
            }
        }
        assert!(
            short_hit > 5000 && short_miss > 5000,
            "{short_hit} {short_miss}"
        );
    }

    /// The exact pair test is symmetric, and the floating-point plane filter never changes its
    /// verdict: integer points (coplanar, collinear, duplicate positions), and the same points
    /// nudged by a few ulps (near-coplanar: float signs of n·(x − a) go wrong without the bound).
    #[test]
    fn pair_test_is_symmetric_and_the_filter_agrees_with_it() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(21);
        for nudge in [false, true] {
            let mut pos: Vec<P> = (0..24)
                .map(|_| std::array::from_fn(|_| rng.gen_range(0..4) as f64 * 1e3 + 0.5))
                .collect();
            // duplicate positions under other indices
            for i in 0..6 {
                pos.push(pos[i]);
            }
            if nudge {
                for q in pos.iter_mut().skip(3) {
                    for x in q.iter_mut() {
                        let k = rng.gen_range(-3i64..=3);
                        *x = f64::from_bits((x.to_bits() as i64 + k) as u64);
                    }
                }
            }
            let n = pos.len() as u32;
            let (mut meets, mut clear) = (0, 0);
            for _ in 0..20_000 {
                let ta: [u32; 3] = std::array::from_fn(|_| rng.gen_range(0..n));
                let mut tb: [u32; 3] = std::array::from_fn(|_| rng.gen_range(0..n));
                // share 0, 1 or 2 vertices (by index) often
                for k in 0..rng.gen_range(0..3) {
                    tb[k] = ta[(k + 1) % 3];
                }
                // (repeated ids, faces without area, are kept: issue 17 item 5)
                let ab = pair_meets(&pos, ta, tb);
                assert_eq!(ab, pair_meets(&pos, tb, ta), "{ta:?} {tb:?}");
                let (fa, fb) = (
                    TriRec::new(ta, ta.map(|v| pos[v as usize])),
                    TriRec::new(tb, tb.map(|v| pos[v as usize])),
                );
                assert_eq!(ab, pair_meets_filtered(&fa, &fb), "{ta:?} {tb:?}");
                if ab {
                    meets += 1;
                } else {
                    clear += 1;
                }
            }
            assert!(meets > 1000 && clear > 1000, "{meets} {clear}");
        }
    }
}
