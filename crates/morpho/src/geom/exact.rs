//! Exact arithmetic behind the predicates: every exact fallback of the library in one place.
//!
//! - **Big integers.** Every `f64` is an integer times a power of two ([`float_parts`]), so after
//!   a common power-of-two scaling a set of coordinates is a set of integers ([`to_big_ints`],
//!   [`to_big_rows`]) and any polynomial sign can be evaluated exactly. Used for the dD
//!   determinants ([`orient_sign`], [`insphere_sign`]: a floating-point filter [`det_filter`],
//!   then Bareiss' fraction-free elimination [`bareiss_sign`]), affine independence, and the
//!   diametral-sphere side of the 3D γ-indicator ([`diametral_side_exact`]).
//! - **Any-range predicates.** Shewchuk's adaptive predicates are exact only while no
//!   intermediate value over- or underflows; [`orient3d_exact`], [`insphere_exact`] and
//!   [`orient2d_exact`] use them inside [`safe_range`] and the big-integer determinants outside
//!   it (coordinates such as 1e-300 or 1e300).
//! - **Small integers.** Lattice inputs hit exact ties constantly; [`insphere_small_int`],
//!   [`orient2d_i64`] and [`incircle_i128`] evaluate the predicates in machine integers.
//! - **Power-of-two rescaling.** [`power_of_two_scale`] brings the largest magnitude near 1 by an
//!   exact multiplication, which keeps the adaptive predicates valid at any absolute scale.
//!
//! Expansion arithmetic (Shewchuk's nonoverlapping sums) is in [`super::expansion`]. Symbolic
//! perturbation stays with the triangulations whose vertex order defines it
//! (`delaunay::d2::incircle_sos`, `delaunay::d3`, `delaunay::dd::perturbed_insphere`); their
//! exact arithmetic comes from here.

use super::predicates::raw::{insphere, orient2d, orient3d};
use num_bigint::{BigInt, Sign};

/// Largest dimension of the dD determinants ([`orient_sign`] takes at most `MAX_DIM + 1`
/// points, [`insphere_sign`] `MAX_DIM + 2`).
pub const MAX_DIM: usize = 7;

/// The unit roundoff.
const U: f64 = f64::EPSILON * 0.5;

/// Determinant of the `n`×`n` row-major matrix `m` by cofactor expansion over column subsets,
/// with a rigorous rounding-error bound from the permanent of `|m|`; `Some(det)` when the sign is
/// certain. `lift_err`: a column whose entries carry a relative error of up to `lift_err·u` (the
/// lifted column `|q|²` of an in-sphere matrix). `n ≤ MAX_DIM + 2`.
pub fn det_filter(m: &[f64], n: usize, lift_err: f64) -> Option<f64> {
    let full = (1usize << n) - 1;
    let mut d = [0.0f64; 1 << (MAX_DIM + 2)];
    let mut p = [0.0f64; 1 << (MAX_DIM + 2)];
    for s in 1..=full {
        let k = s.count_ones() as usize;
        let r = n - k;
        let row = &m[r * n..r * n + n];
        if k == 1 {
            let j = s.trailing_zeros() as usize;
            d[s] = row[j];
            p[s] = row[j].abs();
            continue;
        }
        let (mut acc, mut pacc) = (0.0, 0.0);
        let mut pos = 0;
        for j in 0..n {
            if s & (1 << j) != 0 {
                let sub = s & !(1 << j);
                let t = row[j] * d[sub];
                if pos & 1 == 0 {
                    acc += t;
                } else {
                    acc -= t;
                }
                pacc += row[j].abs() * p[sub];
                pos += 1;
            }
        }
        d[s] = acc;
        p[s] = pacc;
    }
    let (det, perm) = (d[full], p[full]);
    if !perm.is_finite() || !det.is_finite() {
        return None;
    }
    if perm < 1e-250 {
        return None;
    }
    let nf = n as f64;
    let bound = 2.0 * (nf * nf + 2.0 * nf + 8.0 + lift_err) * U * perm + 1e-290;
    if det.abs() > bound {
        Some(det)
    } else {
        None
    }
}

/// `x = m · 2^e` exactly (the mantissa with its sign, and the exponent; subnormals included).
pub fn float_parts(x: f64) -> (i64, i32) {
    let bits = x.to_bits();
    let neg = bits >> 63 != 0;
    let eb = ((bits >> 52) & 0x7ff) as i32;
    let frac = (bits & ((1u64 << 52) - 1)) as i64;
    let (m, e) = if eb == 0 {
        (frac, -1074)
    } else {
        (frac | (1i64 << 52), eb - 1075)
    };
    (if neg { -m } else { m }, e)
}

/// Exact sign of the determinant of the `n`×`n` row-major big-integer matrix `m` (Bareiss'
/// fraction-free elimination).
pub fn bareiss_sign(mut m: Vec<BigInt>, n: usize) -> i32 {
    let mut sign = 1;
    let mut prev = BigInt::from(1);
    for k in 0..n.saturating_sub(1) {
        if m[k * n + k].sign() == Sign::NoSign {
            let Some(r) = (k + 1..n).find(|&r| m[r * n + k].sign() != Sign::NoSign) else {
                return 0;
            };
            for j in 0..n {
                m.swap(k * n + j, r * n + j);
            }
            sign = -sign;
        }
        for i in k + 1..n {
            for j in k + 1..n {
                let v = (&m[i * n + j] * &m[k * n + k] - &m[i * n + k] * &m[k * n + j]) / &prev;
                m[i * n + j] = v;
            }
        }
        prev = m[k * n + k].clone();
    }
    match m[n * n - 1].sign() {
        Sign::Plus => sign,
        Sign::Minus => -sign,
        Sign::NoSign => 0,
    }
}

/// The coordinates of `q` as integers after a common power-of-two scaling (every `f64` is an
/// integer times a power of two): exact, and the sign of any homogeneous polynomial in them is
/// the sign of the same polynomial in the original coordinates.
pub fn to_big_rows(q: &[&[f64]]) -> Vec<Vec<BigInt>> {
    let emin = q
        .iter()
        .flat_map(|r| r.iter())
        .filter(|x| **x != 0.0)
        .map(|&x| float_parts(x).1)
        .min()
        .unwrap_or(0);
    q.iter()
        .map(|r| {
            r.iter()
                .map(|&x| {
                    let (m, e) = float_parts(x);
                    BigInt::from(m) << ((e - emin) as usize)
                })
                .collect()
        })
        .collect()
}

/// Exact sign (−1, 0, 1) of `orient(q_0 … q_d)` = det of rows `[q_i, 1]`; `q.len() == d + 1`,
/// d ≤ `MAX_DIM`. For d = 2, 3 the sign of Shewchuk's `orient2d`/`orient3d`.
pub fn orient_sign(q: &[&[f64]]) -> i32 {
    let n = q.len();
    let d = n - 1;
    let mut m = [0.0f64; (MAX_DIM + 1) * (MAX_DIM + 1)];
    for (i, r) in q.iter().enumerate() {
        m[i * n..i * n + d].copy_from_slice(&r[..d]);
        m[i * n + d] = 1.0;
    }
    if let Some(v) = det_filter(&m[..n * n], n, 0.0) {
        return if v > 0.0 {
            1
        } else if v < 0.0 {
            -1
        } else {
            0
        };
    }
    let ints = to_big_rows(q);
    let mut mb = Vec::with_capacity(n * n);
    for r in ints {
        mb.extend(r);
        mb.push(BigInt::from(1));
    }
    bareiss_sign(mb, n)
}

/// Exact sign of `insphere(q_0 … q_{d+1})` = det of rows `[q_i, |q_i|², 1]`; positive when
/// `q_{d+1}` is inside the sphere through the positively oriented `q_0 … q_d`; d ≤ `MAX_DIM`.
pub fn insphere_sign(q: &[&[f64]]) -> i32 {
    let n = q.len();
    let d = n - 2;
    let mut m = [0.0f64; (MAX_DIM + 2) * (MAX_DIM + 2)];
    for (i, r) in q.iter().enumerate() {
        m[i * n..i * n + d].copy_from_slice(&r[..d]);
        m[i * n + d] = r[..d].iter().map(|x| x * x).sum();
        m[i * n + d + 1] = 1.0;
    }
    if let Some(v) = det_filter(&m[..n * n], n, (d + 2) as f64) {
        return if v > 0.0 {
            1
        } else if v < 0.0 {
            -1
        } else {
            0
        };
    }
    let ints = to_big_rows(q);
    let mut mb = Vec::with_capacity(n * n);
    for r in ints {
        let s: BigInt = r.iter().map(|x| x * x).sum();
        mb.extend(r);
        mb.push(s);
        mb.push(BigInt::from(1));
    }
    bareiss_sign(mb, n)
}

/// Exact test that the points are affinely independent (the d-dimensional points `q` span a
/// simplex of dimension `q.len() − 1`).
pub fn affinely_independent(q: &[&[f64]]) -> bool {
    if q.len() <= 1 {
        return true;
    }
    let ints = to_big_rows(q);
    let d = q[0].len();
    let rows = q.len() - 1;
    let mut m: Vec<Vec<BigInt>> = (1..q.len())
        .map(|i| (0..d).map(|k| &ints[i][k] - &ints[0][k]).collect())
        .collect();
    // fraction-free row echelon; rank == rows?
    let mut rank = 0;
    for col in 0..d {
        if rank == rows {
            break;
        }
        let Some(r) = (rank..rows).find(|&r| m[r][col].sign() != Sign::NoSign) else {
            continue;
        };
        m.swap(rank, r);
        for i in rank + 1..rows {
            if m[i][col].sign() == Sign::NoSign {
                continue;
            }
            let (a, b) = (m[rank][col].clone(), m[i][col].clone());
            for k in 0..d {
                let v = &m[i][k] * &a - &m[rank][k] * &b;
                m[i][k] = v;
            }
        }
        rank += 1;
    }
    rank == rows
}

/// Exact `insphere` (same sign as Shewchuk's) for integer coordinates of magnitude ≤ 2^20:
/// differences ≤ 2^21, 2×2 minors ≤ 2^43 (i64), the determinant ≤ 2^112 (i128). Lattice inputs
/// hit exact zeros constantly; this avoids the expansion arithmetic of the adaptive predicate.
#[inline]
pub fn insphere_small_int(q: &[[f64; 3]; 5]) -> f64 {
    let e = q[4];
    let d = |p: [f64; 3]| {
        [
            (p[0] - e[0]) as i64,
            (p[1] - e[1]) as i64,
            (p[2] - e[2]) as i64,
        ]
    };
    let (a, b, c, dd) = (d(q[0]), d(q[1]), d(q[2]), d(q[3]));
    let ab = a[0] * b[1] - b[0] * a[1];
    let bc = b[0] * c[1] - c[0] * b[1];
    let cd = c[0] * dd[1] - dd[0] * c[1];
    let da = dd[0] * a[1] - a[0] * dd[1];
    let ac = a[0] * c[1] - c[0] * a[1];
    let bd = b[0] * dd[1] - dd[0] * b[1];
    let w = |x: i64| x as i128;
    let abc = w(a[2]) * w(bc) - w(b[2]) * w(ac) + w(c[2]) * w(ab);
    let bcd = w(b[2]) * w(cd) - w(c[2]) * w(bd) + w(dd[2]) * w(bc);
    let cda = w(c[2]) * w(da) + w(dd[2]) * w(ac) + w(a[2]) * w(cd);
    let dab = w(dd[2]) * w(ab) + w(a[2]) * w(bd) + w(b[2]) * w(da);
    let lift = |p: [i64; 3]| w(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    let det = (lift(dd) * abc - lift(c) * dab) + (lift(b) * cda - lift(a) * bcd);
    det.signum() as f64
}

/// True when every coordinate is 0 or has a magnitude in [2^-120, 2^120], the range in which
/// Shewchuk's adaptive predicates (degree ≤ 5) can neither overflow nor underflow.
#[inline]
pub fn safe_range(q: &[[f64; 3]]) -> bool {
    q.iter().all(|p| {
        p.iter().all(|x| {
            let e = ((x.to_bits() >> 52) & 0x7ff) as i32;
            *x == 0.0 || (1023 - 120..=1023 + 120).contains(&e)
        })
    })
}

/// Exact `orient3d` (sign exact, magnitude approximate) for any finite coordinates: Shewchuk's
/// adaptive predicate in its safe range, big-integer arithmetic ([`orient_sign`])
/// outside it (tiny or huge coordinates such as 1e-300 or 1e300).
#[inline]
pub fn orient3d_exact(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
    if safe_range(&[a, b, c, d]) {
        orient3d(a, b, c, d)
    } else {
        orient_sign(&[&a, &b, &c, &d]) as f64
    }
}

/// Exact `insphere` for any finite coordinates (see [`orient3d_exact`]).
#[inline]
pub fn insphere_exact(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3], e: [f64; 3]) -> f64 {
    if safe_range(&[a, b, c, d, e]) {
        insphere(a, b, c, d, e)
    } else {
        insphere_sign(&[&a, &b, &c, &d, &e]) as f64
    }
}

/// Exact `orient2d` for any finite coordinates (see [`orient3d_exact`]).
#[inline]
pub fn orient2d_exact(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    let z = |p: [f64; 2]| [p[0], p[1], 0.0];
    if safe_range(&[z(a), z(b), z(c)]) {
        orient2d(a, b, c)
    } else {
        orient_sign(&[&a, &b, &c]) as f64
    }
}

/// The coordinates `xs` as integers after a common power-of-two scaling (flat; see
/// [`to_big_rows`]).
pub fn to_big_ints(xs: &[f64]) -> Vec<BigInt> {
    to_big_rows(&[xs]).pop().unwrap_or_default()
}

/// The sign of a big integer as −1, 0, 1.
#[inline]
pub fn big_sign(x: &BigInt) -> i32 {
    match x.sign() {
        Sign::Plus => 1,
        Sign::Minus => -1,
        Sign::NoSign => 0,
    }
}

/// Exact sign of q·|n|² for triangle ijk and point l (n = (j − i) × (k − i), q = |l − m|² − r²
/// with m, r the triangle's circumcentre and circumradius): +1 when l lies outside the
/// diametral sphere of the triangle (the centre of the sphere through i, j, k, l is on l's
/// side of the triangle's plane), −1 inside, 0 on it. The big-integer evaluation of
/// `boundary`'s 3D γ-indicator sign (Veltkamp 1992, Eq. 5.2), for when its float filter is
/// not certain; the polynomial is |d|²|n|² − d · (|c|² n × b + |b|² c × n) with
/// b = j − i, c = k − i, d = l − i.
pub fn diametral_side_exact(i: [f64; 3], j: [f64; 3], k: [f64; 3], l: [f64; 3]) -> i32 {
    let v = to_big_ints(&[
        i[0], i[1], i[2], j[0], j[1], j[2], k[0], k[1], k[2], l[0], l[1], l[2],
    ]);
    let (b, c, d) = (big_sub(&v, 1, 0), big_sub(&v, 2, 0), big_sub(&v, 3, 0));
    let n = big_cross(&b, &c);
    let (bb, cc, dd, nn) = (
        big_dot(&b, &b),
        big_dot(&c, &c),
        big_dot(&d, &d),
        big_dot(&n, &n),
    );
    let nb = big_cross(&n, &b);
    let cn = big_cross(&c, &n);
    let w = [
        &cc * &nb[0] + &bb * &cn[0],
        &cc * &nb[1] + &bb * &cn[1],
        &cc * &nb[2] + &bb * &cn[2],
    ];
    big_sign(&(dd * nn - big_dot(&d, &w)))
}

/// |c| = C / S exactly, for 0 ≤ |c| < 1 (S a power of two).
fn ratio_of(c_abs: f64) -> (BigInt, BigInt) {
    if c_abs == 0.0 {
        return (BigInt::from(0), BigInt::from(1));
    }
    let (m, e) = float_parts(c_abs);
    // c_abs < 1, so e < 0
    (BigInt::from(m), BigInt::from(1) << ((-e) as usize))
}

/// Exact sign of τ(x)² (1 − |c|)² − ρ₀² |c| (2 − |c|) for the triangle (a, b, c) and a point x
/// off its plane: whether the ball through a, b, c and x (centre m + τ n, n = (b − a) × (c − a))
/// is beyond (+1), on (0) or within (−1) the balls of parameter ±|c| (offset ρ₀ √(k² − 1),
/// k = 1/(1 − |c|), ρ₀ = r/|n|), 0 ≤ |c| < 1. With u = b − a, v = c − a, w = x − a:
/// τ = N / (2|n|² h), N = |w|²|n|² + |u|² n·(v × w) + |v|² n·(w × u), h = w·n, and
/// ρ₀² = |u|²|v|²|u − v|² / (4|n|⁴); with |c| = C/S the sign is that of
/// N² (S − C)² − h² |u|²|v|²|u − v|² C (2S − C) (homogeneous: any common scaling of the
/// coordinates keeps it). The big-integer fallback of `graphs::gamma`'s exact γ-value decision.
pub fn offset_reach_sign_3d(t: [[f64; 3]; 3], x: [f64; 3], c_abs: f64) -> i32 {
    let [a, b, c] = t;
    let v = to_big_ints(&[
        a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2], x[0], x[1], x[2],
    ]);
    let (u, vv_, w) = (big_sub(&v, 1, 0), big_sub(&v, 2, 0), big_sub(&v, 3, 0));
    let n = big_cross(&u, &vv_);
    let (uu, vv, ww, nn) = (
        big_dot(&u, &u),
        big_dot(&vv_, &vv_),
        big_dot(&w, &w),
        big_dot(&n, &n),
    );
    let num =
        &ww * &nn + &uu * big_dot(&n, &big_cross(&vv_, &w)) + &vv * big_dot(&n, &big_cross(&w, &u));
    let h = big_dot(&w, &n);
    let uv: [BigInt; 3] = [0, 1, 2].map(|k| &u[k] - &vv_[k]);
    let (cn, cs) = ratio_of(c_abs);
    let k1 = &cs - &cn;
    let kk = &cn * (BigInt::from(2) * &cs - &cn);
    let lhs = &num * &num * &k1 * &k1;
    let rhs = &h * &h * uu * vv * big_dot(&uv, &uv) * kk;
    big_sign(&(lhs - rhs))
}

/// The 2D analogue of [`offset_reach_sign_3d`] for the edge (a, b) and a point x off its line:
/// τ = q / 2h with q = (x − a)·(x − b), h = orient2d(a, b, x), ρ₀ = 1/2, so the sign is that
/// of q² (S − C)² − h² C (2S − C) for |c| = C/S.
pub fn offset_reach_sign_2d(a: [f64; 2], b: [f64; 2], x: [f64; 2], c_abs: f64) -> i32 {
    let v = to_big_ints(&[a[0], a[1], b[0], b[1], x[0], x[1]]);
    let (xa0, xa1) = (&v[4] - &v[0], &v[5] - &v[1]);
    let (xb0, xb1) = (&v[4] - &v[2], &v[5] - &v[3]);
    let (ba0, ba1) = (&v[2] - &v[0], &v[3] - &v[1]);
    let q = &xa0 * &xb0 + &xa1 * &xb1;
    let h = &ba0 * &xa1 - &ba1 * &xa0;
    let (cn, cs) = ratio_of(c_abs);
    let k1 = &cs - &cn;
    let kk = &cn * (BigInt::from(2) * &cs - &cn);
    big_sign(&(&q * &q * &k1 * &k1 - &h * &h * kk))
}

/// Point `a` minus point `o` of a flat array of 3D points (`[x₀, y₀, z₀, x₁, …]`), exactly.
fn big_sub(v: &[BigInt], a: usize, o: usize) -> [BigInt; 3] {
    [0, 1, 2].map(|k| &v[3 * a + k] - &v[3 * o + k])
}

/// a · b of big-integer 3-vectors.
pub fn big_dot(a: &[BigInt; 3], b: &[BigInt; 3]) -> BigInt {
    &a[0] * &b[0] + &a[1] * &b[1] + &a[2] * &b[2]
}

/// a × b of big-integer 3-vectors.
pub fn big_cross(a: &[BigInt; 3], b: &[BigInt; 3]) -> [BigInt; 3] {
    [
        &a[1] * &b[2] - &a[2] * &b[1],
        &a[2] * &b[0] - &a[0] * &b[2],
        &a[0] * &b[1] - &a[1] * &b[0],
    ]
}

/// orient2d of integer points in `i64`: exact while |coordinates| < 2^30 (differences < 2^31,
/// products < 2^62). Positive when a, b, c are counter-clockwise.
#[inline]
pub fn orient2d_i64(a: [i64; 2], b: [i64; 2], c: [i64; 2]) -> i64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// The in-circle determinant of integer points in `i128` (positive when d is inside the circle
/// through the counter-clockwise a, b, c): exact while |coordinates| < 2^28 (differences < 2^29,
/// lifts < 2^59, products < 2^118).
#[inline]
pub fn incircle_i128(a: [i64; 2], b: [i64; 2], c: [i64; 2], d: [i64; 2]) -> i128 {
    let (adx, ady) = (a[0] - d[0], a[1] - d[1]);
    let (bdx, bdy) = (b[0] - d[0], b[1] - d[1]);
    let (cdx, cdy) = (c[0] - d[0], c[1] - d[1]);
    let al = (adx * adx + ady * ady) as i128;
    let bl = (bdx * bdx + bdy * bdy) as i128;
    let cl = (cdx * cdx + cdy * cdy) as i128;
    al * (bdx * cdy - cdx * bdy) as i128
        + bl * (cdx * ady - adx * cdy) as i128
        + cl * (adx * bdy - bdx * ady) as i128
}

/// The power of two that brings the largest coordinate magnitude `m` near 1 (1 for 0 or a
/// non-finite `m`). Multiplying coordinates by it is exact (barring underflow of coordinates
/// below 2⁻¹⁰²²·m), and it keeps Shewchuk's predicates — exact only while no intermediate
/// result over- or underflows — valid at any absolute scale (1e-300 … 1e300).
pub fn power_of_two_scale(m: f64) -> f64 {
    if m == 0.0 || !m.is_finite() {
        return 1.0;
    }
    let e = m.log2().round() as i32;
    // 2^-e computed in two steps so that neither factor over- or underflows.
    let half = -e / 2;
    2f64.powi(half) * 2f64.powi(-e - half)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    #[test]
    fn predicates_match_shewchuk() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        for _ in 0..500 {
            let q: Vec<[f64; 3]> = (0..5)
                .map(|_| {
                    [
                        rng.gen_range(-4..4) as f64,
                        rng.gen_range(-4..4) as f64,
                        rng.gen::<f64>(),
                    ]
                })
                .collect();
            let r: Vec<&[f64]> = q.iter().map(|x| &x[..]).collect();
            let o = orient3d(q[0], q[1], q[2], q[3]);
            assert_eq!(orient_sign(&r[..4]), o.partial_cmp(&0.0).unwrap() as i32);
            let s = insphere(q[0], q[1], q[2], q[3], q[4]);
            assert_eq!(insphere_sign(&r), s.partial_cmp(&0.0).unwrap() as i32);
            let q2: Vec<&[f64]> = q.iter().map(|x| &x[..2]).collect();
            let o2 = orient2d([q[0][0], q[0][1]], [q[1][0], q[1][1]], [q[2][0], q[2][1]]);
            assert_eq!(orient_sign(&q2[..3]), o2.partial_cmp(&0.0).unwrap() as i32);
        }
    }

    #[test]
    fn exact_on_extreme_scales() {
        // collinear after scaling by 1e-300 and 1e300
        for s in [1e-300, 1e300, 1e-310] {
            let a = [0.0, 0.0];
            let b = [s, s];
            let c = [2.0 * s, 2.0 * s];
            assert_eq!(orient_sign(&[&a, &b, &c]), 0);
            let c2 = [2.0 * s, 3.0 * s];
            assert_eq!(orient_sign(&[&a, &b, &c2]), 1);
        }
        // cocircular unit square scaled by 1e200 (the lifted column overflows)
        let s = 1e200;
        let q = [[0.0, 0.0], [s, 0.0], [s, s], [0.0, s]];
        let r: Vec<&[f64]> = q.iter().map(|x| &x[..]).collect();
        assert_eq!(insphere_sign(&r), 0);
    }

    #[test]
    fn small_int_insphere_matches_shewchuk() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(9);
        for r in [2i32, 5, 1 << 20] {
            for _ in 0..3000 {
                let q: [[f64; 3]; 5] =
                    std::array::from_fn(|_| std::array::from_fn(|_| rng.gen_range(-r..=r) as f64));
                let want = insphere(q[0], q[1], q[2], q[3], q[4]);
                assert_eq!(
                    insphere_small_int(&q),
                    want.signum() * (want != 0.0) as i32 as f64
                );
            }
        }
    }

    /// The any-range predicates agree with the adaptive ones on scaled copies: a power-of-two
    /// scaling keeps every sign, and 2^±1000 takes the coordinates out of the safe range.
    #[test]
    fn any_range_predicates_keep_their_signs_at_extreme_scales() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        let mut zeros = 0;
        for _ in 0..2000 {
            let q: [[f64; 3]; 5] =
                std::array::from_fn(|_| std::array::from_fn(|_| rng.gen_range(-3..=3) as f64));
            let o = orient3d(q[0], q[1], q[2], q[3]);
            let s = insphere(q[0], q[1], q[2], q[3], q[4]);
            let o2 = orient2d([q[0][0], q[0][1]], [q[1][0], q[1][1]], [q[2][0], q[2][1]]);
            zeros += (s == 0.0) as usize;
            for e in [-1000, 1000] {
                let f = 2f64.powi(e);
                let w = q.map(|p| p.map(|x| x * f));
                assert!(!safe_range(&w[..]) || q.iter().flatten().all(|&x| x == 0.0));
                let sign = |x: f64| if x == 0.0 { 0.0 } else { x.signum() };
                assert_eq!(sign(orient3d_exact(w[0], w[1], w[2], w[3])), sign(o));
                assert_eq!(sign(insphere_exact(w[0], w[1], w[2], w[3], w[4])), sign(s));
                let p2 = |p: [f64; 3]| [p[0], p[1]];
                assert_eq!(sign(orient2d_exact(p2(w[0]), p2(w[1]), p2(w[2]))), sign(o2));
            }
        }
        assert!(zeros > 50, "{zeros}");
    }

    /// The big-integer determinants against the adaptive predicates in 2D and 3D, and the
    /// i64/i128 kernels against the adaptive ones on small integers.
    #[test]
    fn determinants_agree_with_the_adaptive_predicates() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        for _ in 0..2000 {
            let q: [[f64; 3]; 5] =
                std::array::from_fn(|_| std::array::from_fn(|_| rng.gen_range(-4..4) as f64));
            let r: Vec<&[f64]> = q.iter().map(|p| &p[..]).collect();
            let sgn = |x: f64| (x > 0.0) as i32 - (x < 0.0) as i32;
            assert_eq!(orient_sign(&r[..4]), sgn(orient3d(q[0], q[1], q[2], q[3])));
            assert_eq!(
                insphere_sign(&r),
                sgn(insphere(q[0], q[1], q[2], q[3], q[4]))
            );
            // the float filter alone, when it decides, decides right
            let mut m = [0.0; 16];
            for (i, p) in q[..4].iter().enumerate() {
                m[4 * i..4 * i + 3].copy_from_slice(p);
                m[4 * i + 3] = 1.0;
            }
            if let Some(v) = det_filter(&m, 4, 0.0) {
                assert_eq!(sgn(v), orient_sign(&r[..4]));
            }
            let p2: Vec<[f64; 2]> = q.iter().map(|p| [p[0], p[1]]).collect();
            let i2: Vec<[i64; 2]> = p2.iter().map(|p| [p[0] as i64, p[1] as i64]).collect();
            let r2: Vec<&[f64]> = p2.iter().map(|p| &p[..]).collect();
            let o = orient2d(p2[0], p2[1], p2[2]);
            assert_eq!(orient_sign(&r2[..3]), sgn(o));
            assert_eq!(orient2d_i64(i2[0], i2[1], i2[2]).signum() as i32, sgn(o));
            let ic = crate::geom::predicates::raw::incircle(p2[0], p2[1], p2[2], p2[3]);
            assert_eq!(
                incircle_i128(i2[0], i2[1], i2[2], i2[3]).signum() as i32,
                sgn(ic)
            );
        }
        // collinear points are affinely dependent, a triangle is not
        let (a, b, c) = ([0.0, 0.0, 0.0], [1.0, 1.0, 1.0], [2.0, 2.0, 2.0]);
        assert!(!affinely_independent(&[&a, &b, &c]));
        assert!(affinely_independent(&[&a, &b, &[2.0, 2.0, 2.5]]));
    }

    /// The diametral side against its definition in exact rationals on small integers: the
    /// circumcentre m of ijk and |l − m|² − r², all scaled by 2|n|² so that they are integers.
    #[test]
    fn diametral_side_matches_its_definition() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(8);
        let (mut inside, mut on) = (0, 0);
        for _ in 0..3000 {
            let p: [[i64; 3]; 4] =
                std::array::from_fn(|_| std::array::from_fn(|_| rng.gen_range(-3..=3)));
            let s = |x: [i64; 3], y: [i64; 3]| [x[0] - y[0], x[1] - y[1], x[2] - y[2]];
            let dt = |x: [i64; 3], y: [i64; 3]| x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
            let cr = |x: [i64; 3], y: [i64; 3]| {
                [
                    x[1] * y[2] - x[2] * y[1],
                    x[2] * y[0] - x[0] * y[2],
                    x[0] * y[1] - x[1] * y[0],
                ]
            };
            let (b, c, d) = (s(p[1], p[0]), s(p[2], p[0]), s(p[3], p[0]));
            let n = cr(b, c);
            let nn = dt(n, n) as i128;
            if nn == 0 {
                continue;
            }
            // 2|n|²(m − i) = |b|² (c × n) + |c|² (n × b)
            let (bc, cn) = (cr(c, n), cr(n, b));
            let m2: [i128; 3] = std::array::from_fn(|k| {
                dt(b, b) as i128 * bc[k] as i128 + dt(c, c) as i128 * cn[k] as i128
            });
            // (2|n|²)²(|d − (m − i)|² − |m − i|²) = (2|n|²)²|d|² − 2·2|n|² d·(2|n|²(m − i))
            let dd = dt(d, d) as i128;
            let dm: i128 = (0..3).map(|k| d[k] as i128 * m2[k]).sum();
            let want = (4 * nn * nn * dd - 4 * nn * dm).signum() as i32;
            let f = |x: [i64; 3]| x.map(|v| v as f64);
            assert_eq!(
                diametral_side_exact(f(p[0]), f(p[1]), f(p[2]), f(p[3])),
                want
            );
            inside += (want < 0) as usize;
            on += (want == 0) as usize;
        }
        assert!(inside > 100 && on > 20, "{inside} {on}");
    }

    #[test]
    fn float_parts_and_scaling_are_exact() {
        for x in [1.0, -3.5, 1e-310, f64::MAX, f64::MIN_POSITIVE, 0.1] {
            let (m, e) = float_parts(x);
            assert_eq!((m as f64) * 2f64.powi(e / 2) * 2f64.powi(e - e / 2), x);
        }
        for m in [1e-300, 1e300, 3.0, 0.7, f64::MAX] {
            let s = power_of_two_scale(m);
            assert!((0.5..2.0).contains(&(m * s)), "{m}");
        }
        let big = to_big_ints(&[1e-310, 1.0]);
        assert!(big[0] > BigInt::from(0) && big[1] > big[0]);
    }
}

/// The examples of this crate-private module (run as unit tests, since doc-tests only see
/// the public API).
#[cfg(test)]
mod examples {
    #[test]
    fn example_1() {
        use crate::geom::exact::{insphere_exact, orient3d_exact};
        // a tetrahedron at 1e-300, far below the range of the adaptive predicates' products
        let s = 1e-300;
        let (a, b, c, d) = ([0.0, 0.0, 0.0], [s, 0.0, 0.0], [0.0, s, 0.0], [0.0, 0.0, s]);
        assert!(orient3d_exact(a, b, c, d) < 0.0); // d above the counter-clockwise abc
        assert!(orient3d_exact(a, c, b, d) > 0.0);
        // the centroid is inside the circumsphere of the positive (a, c, b, d)
        let g = [s / 4.0, s / 4.0, s / 4.0];
        assert!(insphere_exact(a, c, b, d, g) > 0.0);
    }
    #[test]
    fn example_2() {
        use crate::geom::exact::float_parts;
        assert_eq!(float_parts(3.0), (3 << 51, -51));
        assert_eq!(float_parts(-0.5), (-(1 << 52), -53));
    }
    #[test]
    fn example_3() {
        use crate::geom::exact::orient_sign;
        let (a, b, c) = ([0.0, 0.0], [1.0, 0.0], [0.0, 1.0]);
        assert_eq!(orient_sign(&[&a, &b, &c]), 1); // counter-clockwise
        assert_eq!(orient_sign(&[&a, &c, &b]), -1);
        assert_eq!(orient_sign(&[&a, &b, &[2.0, 0.0]]), 0);
    }
    #[test]
    fn example_4() {
        use crate::geom::exact::to_big_ints;
        let v = to_big_ints(&[0.5, -1.5, 0.0]);
        assert_eq!(v[1], -3 * &v[0]); // the same common factor for all
        assert_eq!(v[2], 0.into());
    }
    #[test]
    fn example_5() {
        use crate::geom::exact::diametral_side_exact;
        let (i, j, k) = ([0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]);
        // the diametral sphere has centre (1, 1, 0) and radius √2
        assert_eq!(diametral_side_exact(i, j, k, [1.0, 1.0, 1.0]), -1);
        assert_eq!(diametral_side_exact(i, j, k, [1.0, 1.0, 2.0]), 1);
        assert_eq!(diametral_side_exact(i, j, k, [2.0, 2.0, 0.0]), 0);
    }
    #[test]
    fn example_6() {
        use crate::geom::exact::power_of_two_scale;
        let s = power_of_two_scale(3e300);
        assert!((0.5..2.0).contains(&(3e300 * s)));
        assert_eq!(s.log2().fract(), 0.0); // a power of two: the scaling is exact
        assert_eq!(power_of_two_scale(0.0), 1.0);
    }
}
