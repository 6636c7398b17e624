//! Exact decisions about distances and dot products, in any dimension D: the predicates behind
//! the distance-defined graphs (Veltkamp 1992 §2.2: nearest neighbours, EMST, RNG, Gabriel,
//! lune-based β-skeletons, sphere of influence, infinite strip).
//!
//! Each test is a polynomial in coordinate differences of degree 2 (4 for
//! [`sum_of_roots_exceeds`]). It is first evaluated in floating point with a forward error bound
//! (Shewchuk's filter idea, with generous constants); only when the value is within the bound
//! of zero is it recomputed exactly with expansions ([`super::expansion::Expansion`]). So ties
//! are ties and near-ties are decided correctly, at the cost of a few flops in the common case.
//!
//! Exact as long as no intermediate product over- or underflows (the same range as the
//! `robust` predicates).

use super::expansion::Expansion;
use super::vec::dist2;
use std::cmp::Ordering;

/// Relative filter constant: every float value below has relative error at most a few ε of the
/// sum of the magnitudes of its terms; 32ε leaves a wide margin.
const FILTER: f64 = 32.0 * f64::EPSILON;

/// Filtered value: `Some(sign)` when `value` is certainly away from zero given the magnitude
/// `mag` of its terms.
#[inline]
fn filtered(value: f64, mag: f64) -> Option<i32> {
    let bound = FILTER * mag;
    if value > bound {
        Some(1)
    } else if value < -bound {
        Some(-1)
    } else if mag == 0.0 {
        Some(0)
    } else {
        None
    }
}

/// Σ (a_k − c_k)(b_k − c_k) as an expansion.
fn xdot<const D: usize>(a: &[f64; D], b: &[f64; D], c: &[f64; D]) -> Expansion {
    let mut s = Expansion::zero();
    for k in 0..D {
        s = s.add(&Expansion::diff(a[k], c[k]).mul(&Expansion::diff(b[k], c[k])));
    }
    s
}

/// |a − b|² as an expansion.
fn xdist2<const D: usize>(a: &[f64; D], b: &[f64; D]) -> Expansion {
    xdot(a, a, b)
}

/// The exact sign (−1, 0, 1) of (a − c)·(b − c): positive when the angle at c is acute,
/// zero when right, negative when obtuse. Equivalently, −sign tells whether c lies strictly
/// inside (−1), on (0) or outside (+1) the ball with diameter ab.
pub fn dot_sign<const D: usize>(a: &[f64; D], b: &[f64; D], c: &[f64; D]) -> i32 {
    let mut v = 0.0;
    let mut mag = 0.0;
    for k in 0..D {
        let t = (a[k] - c[k]) * (b[k] - c[k]);
        v += t;
        mag += t.abs();
    }
    filtered(v, mag).unwrap_or_else(|| xdot(a, b, c).sign())
}

/// Exact comparison of |a − b|² with |c − d|².
pub fn cmp_dist2<const D: usize>(
    a: &[f64; D],
    b: &[f64; D],
    c: &[f64; D],
    d: &[f64; D],
) -> Ordering {
    if (a == c && b == d) || (a == d && b == c) {
        return Ordering::Equal; // the same pair: common when comparing with a nearest neighbour
    }
    let (x, y) = (dist2(*a, *b), dist2(*c, *d));
    match filtered(x - y, x + y) {
        Some(s) => s.cmp(&0),
        None => xdist2(a, b).sub(&xdist2(c, d)).sign().cmp(&0),
    }
}

/// True when q lies strictly inside the ball of the lune-based β-skeleton (Veltkamp Def. 2.16)
/// of the edge uv on u's far side: centre u + (v − u)/(2(1 − b)), radius |uv|/(2(1 − b)), for
/// b ∈ [0, 1). With k = 1/(2(1 − b)) the test |q − u − k(v − u)|² < k²|v − u|² is, after
/// multiplying by 1 − b > 0, (1 − b)|q − u|² − (q − u)·(v − u) < 0, which is evaluated exactly.
pub fn in_lune_ball<const D: usize>(q: &[f64; D], u: &[f64; D], v: &[f64; D], b: f64) -> bool {
    let (mut qq, mut qv, mut mag) = (0.0, 0.0, 0.0);
    for k in 0..D {
        let (e, f) = (q[k] - u[k], v[k] - u[k]);
        qq += e * e;
        qv += e * f;
        mag += (e * f).abs();
    }
    let val = qq - b * qq - qv;
    let mag = mag + qq * (1.0 + b.abs());
    let s = filtered(val, mag).unwrap_or_else(|| {
        let e2 = xdist2(q, u);
        e2.sub(&e2.scale(b)).sub(&xdot(q, v, u)).sign()
    });
    s < 0
}

/// True when √(|a − b|²) < √(|a − p|²) + √(|b − q|²) — the sphere-of-influence test of
/// Veltkamp Def. 2.7 with p, q the nearest neighbours of a, b. With d² = |a − b|² and
/// r², s² the two squared radii: d < r + s ⇔ d² − r² − s² < 0, or (d² − r² − s²)² < 4r²s².
pub fn sum_of_roots_exceeds<const D: usize>(
    a: &[f64; D],
    b: &[f64; D],
    p: &[f64; D],
    q: &[f64; D],
) -> bool {
    let (d2, r2, s2) = (dist2(*a, *b), dist2(*a, *p), dist2(*b, *q));
    let t = d2 - r2 - s2;
    let mag = d2 + r2 + s2;
    let lin = filtered(t, mag);
    if lin == Some(-1) {
        return true;
    }
    if lin.is_some() {
        // t ≥ 0 certainly (or all zero): compare t² with 4r²s²
        let val = t * t - 4.0 * r2 * s2;
        if let Some(s) = filtered(val, 4.0 * mag * mag) {
            return s < 0;
        }
    }
    let (xd, xr, xs) = (xdist2(a, b), xdist2(a, p), xdist2(b, q));
    let xt = xd.sub(&xr).sub(&xs);
    match xt.sign() {
        -1 => true,
        _ => xt.mul(&xt).sub(&xr.mul(&xs).scale(4.0)).sign() < 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Exact integer oracle for small integer coordinates.
    fn idot(a: [i64; 2], b: [i64; 2], c: [i64; 2]) -> i64 {
        (a[0] - c[0]) * (b[0] - c[0]) + (a[1] - c[1]) * (b[1] - c[1])
    }
    fn f(a: [i64; 2]) -> [f64; 2] {
        [a[0] as f64, a[1] as f64]
    }

    #[test]
    fn near_ties_are_exact() {
        // a right angle at c shifted far from the origin: the float dot product of the
        // differences is exact here, but the translated points make naive formulas fail
        let o = 1e15;
        let c = [o, o];
        let a = [o + 3.0, o];
        let b = [o, o + 5.0];
        assert_eq!(dot_sign(&a, &b, &c), 0);
        // tiny perturbations decide the sign
        let a2 = [o + 3.0, o + 0.125];
        assert_eq!(dot_sign(&a2, &b, &c), 1);
        let a3 = [o + 3.0, o - 0.125];
        assert_eq!(dot_sign(&a3, &b, &c), -1);
        // equal distances that differ in the last bits of the inputs
        let x = 0.1f64;
        let y = 0.3f64;
        assert_eq!(
            cmp_dist2(&[0.0, 0.0], &[x, y], &[0.0, 0.0], &[y, x]),
            Ordering::Equal
        );
        assert_eq!(
            cmp_dist2(
                &[0.0, 0.0],
                &[x, y],
                &[0.0, 0.0],
                &[y, f64::from_bits(x.to_bits() + 1)]
            ),
            Ordering::Less
        );
    }

    #[test]
    fn sum_of_roots_on_ties() {
        let a = [0.0, 0.0];
        let b = [0.0, 10.0];
        let p = [0.0, 6.0];
        assert!(
            !sum_of_roots_exceeds(&a, &b, &p, &[0.0, 6.0]),
            "10 < 6 + 4 is false"
        );
        assert!(sum_of_roots_exceeds(&a, &b, &p, &[0.0, 5.0]), "10 < 6 + 5");
        assert!(
            !sum_of_roots_exceeds(&a, &b, &p, &[0.0, 7.0]),
            "10 < 6 + 3 is false"
        );
        // d = 5, r = √8, s = √2: 3√2 ≈ 4.243 < 5
        assert!(!sum_of_roots_exceeds(
            &[0.0, 0.0],
            &[3.0, 4.0],
            &[2.0, 2.0],
            &[4.0, 5.0]
        ));
        // r = √18, s = √2: 4√2 ≈ 5.657 > 5
        assert!(sum_of_roots_exceeds(
            &[0.0, 0.0],
            &[3.0, 4.0],
            &[3.0, 3.0],
            &[4.0, 5.0]
        ));
        // a tie of irrational roots: √8 + √2 = √18 = d
        assert!(!sum_of_roots_exceeds(
            &[0.0, 0.0],
            &[3.0, 3.0],
            &[2.0, 2.0],
            &[4.0, 4.0]
        ));
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]
        #[test]
        fn dot_sign_matches_integers(a in prop::array::uniform2(-40i64..40), b in prop::array::uniform2(-40i64..40), c in prop::array::uniform2(-40i64..40), shift in -3i32..3) {
            // scaled by a power of two and shifted far away: still exact
            let s = 2f64.powi(shift * 20);
            let off = 1e12 * s;
            let g = |x: [i64; 2]| { let y = f(x); [y[0] * s + off, y[1] * s - off] };
            prop_assert_eq!(dot_sign(&g(a), &g(b), &g(c)), idot(a, b, c).signum() as i32);
            let da = idot(a, a, b);
            let dc = idot(c, c, [0, 0]);
            prop_assert_eq!(cmp_dist2(&g(a), &g(b), &g(c), &g([0, 0])), da.cmp(&dc));
        }

        #[test]
        fn lune_ball_matches_integers(q in prop::array::uniform2(-30i64..30), u in prop::array::uniform2(-30i64..30), v in prop::array::uniform2(-30i64..30), bi in 0i64..8) {
            // b = bi/8 is exact; (1 − b)|q − u|² − (q − u)·(v − u) < 0, times 8
            let b = bi as f64 / 8.0;
            let e = [q[0] - u[0], q[1] - u[1]];
            let ff = [v[0] - u[0], v[1] - u[1]];
            let val = (8 - bi) * (e[0] * e[0] + e[1] * e[1]) - 8 * (e[0] * ff[0] + e[1] * ff[1]);
            prop_assert_eq!(in_lune_ball(&f(q), &f(u), &f(v), b), val < 0);
        }

        #[test]
        fn sum_of_roots_matches_integers(a in prop::array::uniform2(-20i64..20), b in prop::array::uniform2(-20i64..20), p in prop::array::uniform2(-20i64..20), q in prop::array::uniform2(-20i64..20)) {
            // d < r + s with integer squares: decide by integer arithmetic
            let (d2, r2, s2) = (idot(a, a, b), idot(a, a, p), idot(b, b, q));
            let t = d2 - r2 - s2;
            let want = t < 0 || (t * t < 4 * r2 * s2);
            prop_assert_eq!(sum_of_roots_exceeds(&f(a), &f(b), &f(p), &f(q)), want);
        }
    }
}
