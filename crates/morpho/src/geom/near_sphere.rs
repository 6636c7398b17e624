//! Exact `insphere` signs for points that lie close to a known sphere (a certified filter in
//! front of Shewchuk's adaptive predicate).
//!
//! # Why
//! Shewchuk's `insphere` is fast when its floating-point stage decides, and needs expansion
//! arithmetic (≈ µs per call) when the five points are nearly cospherical. Sets whose points all
//! lie within rounding of one sphere (cospherical integer points after a non-power-of-two
//! scaling, say) make *every* in-sphere test nearly degenerate, and the graphs that compare
//! in-sphere offsets of all points against all triangles (3D γ at c = −1) then spend all their
//! time in the exact stages (issue 17 item B).
//!
//! # How
//! For any reference sphere S (centre o, squared radius R², both floats) let
//! w(p) = |p − o|² − R² (the power of p with respect to S). With q = p − e the determinant of
//! `insphere(a, b, c, d, e)` is det\[q_i, |q_i|²\] (i = a, b, c, d), and
//! |q_i|² = (w(p_i) − w(e)) − 2 q_i·(e − o): the last part is a combination of the first three
//! columns and does not change the determinant. Expanding along the lift column,
//!
//! ```text
//! insphere(a,b,c,d,e) = W_d·O(a,b,c,e) − W_c·O(d,a,b,e) + W_b·O(c,d,a,e) − W_a·O(b,c,d,e)
//! ```
//!
//! with W_i = w(p_i) − w(e) and O = `orient3d` (Shewchuk's determinant). When the points lie
//! near S the W are tiny, but they are computed *accurately* (exact expansion of
//! |p − o|² − R², then rounded with a certified bound), and the orientations are well
//! conditioned: the sum has a small relative error and its sign is certified by a bound on
//! every rounding. When the bound does not separate the sum from zero (exact ties, or a poor
//! reference sphere), [`NearSphere::insphere`] falls back to the adaptive predicate, so the
//! sign returned is always the exact one.
//!
//! Underflow: the filter is used only when every coordinate is 0 or within 2^±120 (the range of
//! [`super::exact::safe_range`]) and the sum and its bound are normal numbers; otherwise the
//! adaptive predicate decides.

use super::exact::safe_range;
use super::expansion::{two_prod, two_sum};
use super::predicates::{insphere_stage_a, raw};

/// Shewchuk's ε (half an ulp of 1).
const EPS: f64 = f64::EPSILON * 0.5;
/// Error bound factor of the floating-point `orient3d` (Shewchuk's o3derrboundA).
const O3D_A: f64 = (7.0 + 56.0 * EPS) * EPS;
/// Smallest magnitude the filter's sums and bounds may have (far above the subnormals).
const TINY: f64 = 1e-280;

/// A reference sphere for [`NearSphere::insphere`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NearSphere {
    o: [f64; 3],
    r2: f64,
}

/// The power w(p) of a point with respect to a [`NearSphere`] and a bound on its error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lift {
    pub w: f64,
    pub err: f64,
}

impl NearSphere {
    /// The sphere through four points (floating-point circumsphere); `None` when they are
    /// (nearly) coplanar or the construction is not finite or not in the safe range.
    pub fn through(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> Option<Self> {
        let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        let t = [d[0] - a[0], d[1] - a[1], d[2] - a[2]];
        let dot = |x: [f64; 3], y: [f64; 3]| x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
        let cross = |x: [f64; 3], y: [f64; 3]| {
            [
                x[1] * y[2] - x[2] * y[1],
                x[2] * y[0] - x[0] * y[2],
                x[0] * y[1] - x[1] * y[0],
            ]
        };
        let det = dot(u, cross(v, t));
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let (uu, vv, tt) = (dot(u, u), dot(v, v), dot(t, t));
        let (vt, tu, uv) = (cross(v, t), cross(t, u), cross(u, v));
        let off: [f64; 3] =
            std::array::from_fn(|k| (uu * vt[k] + vv * tu[k] + tt * uv[k]) / (2.0 * det));
        let o = [a[0] + off[0], a[1] + off[1], a[2] + off[2]];
        let r2 = dot(off, off);
        let s = NearSphere { o, r2 };
        (o.iter().all(|x| x.is_finite())
            && r2.is_finite()
            && safe_range(&[o])
            && safe_range(&[[r2, 0.0, 0.0]]))
        .then_some(s)
    }

    /// w(x) = |x − o|² − R² with a bound on the error of the returned float: the 19 exact
    /// parts (x − o = s + t exactly per axis; s², 2st, t² as exact products; −R²) summed by
    /// Ogita–Rump–Oishi's Sum2 (cascaded TWO-SUM), whose error is at most
    /// ε·|w| + γ₁₈²·Σ|parts| (γ_k = kε/(1 − kε)); the bound returned is twice that.
    pub fn lift(&self, x: [f64; 3]) -> Lift {
        let (mut sum, mut tail, mut abs) = (-self.r2, 0.0, self.r2.abs());
        let mut add = |v: f64| {
            let (s2, q) = two_sum(sum, v);
            sum = s2;
            tail += q;
            abs += v.abs();
        };
        for k in 0..3 {
            let (s, t) = two_sum(x[k], -self.o[k]);
            let (p, pe) = two_prod(s, s);
            let (m, me) = two_prod(2.0 * s, t);
            let (q, qe) = two_prod(t, t);
            for v in [p, pe, m, me, q, qe] {
                add(v);
            }
        }
        let w = sum + tail;
        let g = 18.0 * EPS / (1.0 - 18.0 * EPS);
        Lift {
            w,
            err: 2.0 * (EPS * w.abs() + g * g * abs) * (1.0 + 4.0 * EPS),
        }
    }

    /// The exact sign of `insphere(a, b, c, d, e)` (as [`raw::insphere`]: > 0 when e lies inside
    /// the sphere through a, b, c, d with `orient3d(a, b, c, d) > 0`), with the lifts of the
    /// five points (`lifts[i]` of the i-th argument) when they are known: the floating-point
    /// stage, then the near-sphere filter, then the adaptive predicate.
    pub fn insphere(&self, q: [[f64; 3]; 5], lifts: [Option<Lift>; 5]) -> f64 {
        let [a, b, c, d, e] = q;
        if !safe_range(&q) {
            return raw::insphere(a, b, c, d, e);
        }
        if let Some(s) = insphere_stage_a(a, b, c, d, e) {
            return s;
        }
        let l: [Lift; 5] = std::array::from_fn(|i| lifts[i].unwrap_or_else(|| self.lift(q[i])));
        lifted_sign(q, l).unwrap_or_else(|| raw::insphere(a, b, c, d, e))
    }
}

/// Floating-point `orient3d(a, b, c, d)` (Shewchuk's formula) and a bound on its error.
fn orient3d_bounded(pa: [f64; 3], pb: [f64; 3], pc: [f64; 3], pd: [f64; 3]) -> (f64, f64) {
    let [adx, ady, adz] = [pa[0] - pd[0], pa[1] - pd[1], pa[2] - pd[2]];
    let [bdx, bdy, bdz] = [pb[0] - pd[0], pb[1] - pd[1], pb[2] - pd[2]];
    let [cdx, cdy, cdz] = [pc[0] - pd[0], pc[1] - pd[1], pc[2] - pd[2]];
    let (bdxcdy, cdxbdy) = (bdx * cdy, cdx * bdy);
    let (cdxady, adxcdy) = (cdx * ady, adx * cdy);
    let (adxbdy, bdxady) = (adx * bdy, bdx * ady);
    let det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
    let permanent = (bdxcdy.abs() + cdxbdy.abs()) * adz.abs()
        + (cdxady.abs() + adxcdy.abs()) * bdz.abs()
        + (adxbdy.abs() + bdxady.abs()) * cdz.abs();
    (det, O3D_A * permanent * (1.0 + 4.0 * EPS))
}

/// The near-sphere filter: the sign of W_d·O(a,b,c,e) − W_c·O(d,a,b,e) + W_b·O(c,d,a,e) −
/// W_a·O(b,c,d,e) when a bound on every rounding separates it from zero.
fn lifted_sign(q: [[f64; 3]; 5], l: [Lift; 5]) -> Option<f64> {
    let [a, b, c, d, e] = q;
    let we = l[4];
    // W_i = w_i − w_e and its error bound
    let big_w = |li: Lift| {
        let v = li.w - we.w;
        (v, li.err + we.err + EPS * v.abs())
    };
    let terms = [
        (1.0, big_w(l[3]), orient3d_bounded(a, b, c, e)),
        (-1.0, big_w(l[2]), orient3d_bounded(d, a, b, e)),
        (1.0, big_w(l[1]), orient3d_bounded(c, d, a, e)),
        (-1.0, big_w(l[0]), orient3d_bounded(b, c, d, e)),
    ];
    let (mut sum, mut bound, mut mag) = (0.0, 0.0, 0.0);
    for (s, (w, dw), (o, d_o)) in terms {
        let p = w * o;
        if !p.is_finite() || !dw.is_finite() || !d_o.is_finite() {
            return None;
        }
        sum += s * p;
        mag += p.abs();
        bound += w.abs() * d_o + o.abs() * dw + dw * d_o;
    }
    // the products and the three additions: ≤ 4ε·Σ|W·O| (with room to spare), all rounded up
    let bound = (bound + 4.0 * EPS * mag) * (1.0 + 16.0 * EPS) * 2.0;
    (bound.is_finite() && sum.abs() > bound && sum.abs() >= TINY).then_some(sum)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    fn sgn(x: f64) -> i32 {
        (x > 0.0) as i32 - (x < 0.0) as i32
    }

    /// Points of an integer sphere scaled by a factor that is not a power of two: rounding moves
    /// them off the sphere by ~1e-16 relative, so every in-sphere test is nearly degenerate
    /// (some stay exactly degenerate: points with the same coordinate magnitudes).
    fn rounded_sphere(scale: f64) -> Vec<[f64; 3]> {
        let mut v = Vec::new();
        for x in -7i32..=7 {
            for y in -7i32..=7 {
                for z in -7i32..=7 {
                    if x * x + y * y + z * z == 50 {
                        v.push([x as f64 * scale, y as f64 * scale, z as f64 * scale]);
                    }
                }
            }
        }
        v
    }

    /// The filter returns the sign of the adaptive predicate on every 5-tuple it is asked about:
    /// nearly cospherical (rounded), exactly cospherical, random, and with a poor reference.
    #[test]
    fn near_sphere_insphere_matches_the_adaptive_predicate() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(17);
        let mut decided_by_filter = 0;
        for (scale, sets) in [(0.1f64, 0), (1.0, 1), (3.7e-3, 2), (1.0 / 3.0, 3)] {
            let p = rounded_sphere(scale);
            let n = p.len();
            let refs = [
                NearSphere::through(p[0], p[5], p[17], p[40]),
                Some(NearSphere {
                    o: [0.3, -0.2, 0.1],
                    r2: 0.7,
                }),
            ];
            for _ in 0..4000 {
                let q: [[f64; 3]; 5] = std::array::from_fn(|_| p[rng.gen_range(0..n)]);
                let want = sgn(raw::insphere(q[0], q[1], q[2], q[3], q[4]));
                for r in refs.iter().flatten() {
                    let l: [Option<Lift>; 5] =
                        std::array::from_fn(|i| (i % 2 == 0).then(|| r.lift(q[i])));
                    assert_eq!(sgn(r.insphere(q, l)), want, "set {sets}, {q:?}");
                    let lifts = q.map(|x| r.lift(x));
                    if insphere_stage_a(q[0], q[1], q[2], q[3], q[4]).is_none()
                        && lifted_sign(q, lifts).is_some()
                    {
                        decided_by_filter += 1;
                    }
                }
            }
        }
        // random points: the floating-point stage or the fallback, same signs
        for _ in 0..2000 {
            let q: [[f64; 3]; 5] =
                std::array::from_fn(|_| std::array::from_fn(|_| rng.gen_range(-1.0..1.0)));
            let r = NearSphere::through(q[0], q[1], q[2], q[3]).unwrap();
            let want = sgn(raw::insphere(q[0], q[1], q[2], q[3], q[4]));
            assert_eq!(sgn(r.insphere(q, [None; 5])), want);
        }
        assert!(decided_by_filter > 1000, "{decided_by_filter}");
    }
}
