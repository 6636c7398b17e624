//! Exact geometric predicates (Shewchuk's adaptive-precision arithmetic, via the `robust` crate).
//!
//! The four predicates and the cheaper in-circle and in-sphere cascades of the Delaunay engines
//! ([`incircle_sign`], [`insphere_sign`]: their integer stages here, the in-circle's
//! stack-expansion stage on `geom::expansion::stack`, their stage counters).
//!
//! Every topological decision in morpho goes through these functions. The returned `f64` has the
//! exact sign of the determinant; its magnitude is only an approximation.
//!
//! Sign conventions (as Shewchuk's):
//! - `orient2d(a, b, c) > 0` when a, b, c are in counter-clockwise order;
//! - `orient3d(a, b, c, d) > 0` when d lies *below* the plane through a, b, c, "above" being the
//!   side from which a, b, c appear counter-clockwise; the value is (a−d)·((b−d)×(c−d));
//! - `incircle(a, b, c, d) > 0` when d lies inside the circle through a, b, c given counter-clockwise;
//! - `insphere(a, b, c, d, e) > 0` when e lies inside the sphere through a, b, c, d with
//!   `orient3d(a, b, c, d) > 0`.

use super::expansion::stack as xp;
use super::{Point2, Point3};
use robust::{Coord, Coord3D};

#[inline]
fn c2(p: &Point2) -> Coord<f64> {
    Coord { x: p.x, y: p.y }
}

#[inline]
fn c3(p: &Point3) -> Coord3D<f64> {
    Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

/// Twice the signed area of triangle (a, b, c), with exact sign; > 0 when counter-clockwise.
#[inline]
pub fn orient2d(a: &Point2, b: &Point2, c: &Point2) -> f64 {
    robust::orient2d(c2(a), c2(b), c2(c))
}

/// Six times the signed volume of (a, b, c, d) with exact sign: (a−d)·((b−d)×(c−d)).
///
/// ```
/// use morpho::geom::{orient3d, Point3};
/// let (a, b, c) = (Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0));
/// assert!(orient3d(&a, &b, &c, &Point3::new(0.0, 0.0, 1.0)) < 0.0); // above the ccw a, b, c
/// assert!(orient3d(&a, &b, &c, &Point3::new(0.0, 0.0, -1.0)) > 0.0);
/// assert_eq!(orient3d(&a, &b, &c, &Point3::new(3.0, 7.0, 0.0)), 0.0); // coplanar
/// ```
#[inline]
pub fn orient3d(a: &Point3, b: &Point3, c: &Point3, d: &Point3) -> f64 {
    robust::orient3d(c3(a), c3(b), c3(c), c3(d))
}

/// > 0 when d is strictly inside the circle through the counter-clockwise a, b, c; 0 when on it.
///
/// ```
/// use morpho::geom::{incircle, Point2};
/// let (a, b, c) = (Point2::new(0.0, 0.0), Point2::new(1.0, 0.0), Point2::new(0.0, 1.0));
/// assert!(incircle(&a, &b, &c, &Point2::new(0.5, 0.5)) > 0.0); // inside
/// assert!(incircle(&a, &b, &c, &Point2::new(2.0, 2.0)) < 0.0); // outside
/// assert_eq!(incircle(&a, &b, &c, &Point2::new(1.0, 1.0)), 0.0); // exactly on the circle
/// ```
#[inline]
pub fn incircle(a: &Point2, b: &Point2, c: &Point2, d: &Point2) -> f64 {
    robust::incircle(c2(a), c2(b), c2(c), c2(d))
}

/// > 0 when e is strictly inside the sphere through a, b, c, d (with `orient3d(a,b,c,d) > 0`).
#[inline]
pub fn insphere(a: &Point3, b: &Point3, c: &Point3, d: &Point3, e: &Point3) -> f64 {
    robust::insphere(c3(a), c3(b), c3(c), c3(d), c3(e))
}

/// Slice-based variants for flat coordinate arrays (`[x, y]`, `[x, y, z]`).
pub mod raw {
    use robust::{Coord, Coord3D};

    /// [`super::orient2d`] on `[x, y]` arrays.
    #[inline]
    pub fn orient2d(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
        robust::orient2d(
            Coord { x: a[0], y: a[1] },
            Coord { x: b[0], y: b[1] },
            Coord { x: c[0], y: c[1] },
        )
    }
    /// [`super::incircle`] on `[x, y]` arrays.
    #[inline]
    pub fn incircle(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> f64 {
        robust::incircle(
            Coord { x: a[0], y: a[1] },
            Coord { x: b[0], y: b[1] },
            Coord { x: c[0], y: c[1] },
            Coord { x: d[0], y: d[1] },
        )
    }
    #[inline]
    fn c3(p: [f64; 3]) -> Coord3D<f64> {
        Coord3D {
            x: p[0],
            y: p[1],
            z: p[2],
        }
    }
    /// [`super::orient3d`] on `[x, y, z]` arrays.
    #[inline]
    pub fn orient3d(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
        robust::orient3d(c3(a), c3(b), c3(c), c3(d))
    }
    /// [`super::insphere`] on `[x, y, z]` arrays.
    #[inline]
    pub fn insphere(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3], e: [f64; 3]) -> f64 {
        robust::insphere(c3(a), c3(b), c3(c), c3(d), c3(e))
    }
}

/// The in-circle sign through a cheaper adaptive stage (used by the Delaunay engines).
///
/// Returns the exact sign (+1, 0, −1) of [`incircle`]`(a, b, c, d)`: the same decision, reached
/// through a cascade whose middle stage is cheap on near-cocircular input (points along a curve,
/// where the float filter legitimately fails often):
///
/// 1. **Filter** (Shewchuk's stage A): the determinant of the differences `p − d` in floating
///    point with the semi-static bound `ε_A · permanent`, `ε_A = (10 + 96u)u`, u = 2⁻⁵³ (the
///    bound is computed from the same differences, so it adapts to the local scale — a single
///    static bound over the whole input would fail on every test between close points).
/// 2. **Exact, allocation-free** (only when stage 1 cannot decide): when the six differences
///    `adx = a.x − d.x, …` are exact (checked: `(a.x − adx) − d.x` is the rounding error of the
///    subtraction, by Knuth/Dekker's two-diff; all six zero), the determinant
///    `Σ_cyc (adx² + ady²)·(bdx·cdy − cdx·bdy)` is a polynomial in six doubles, evaluated
///    exactly as a Shewchuk expansion (error-free `two_prod`/`two_sum`, expansions grown by
///    exact scaling and exact sums, never rounded) of at most 96 components on the stack: its sign
///    is the sign of its largest component, so this stage is exact, not a filter. Differences
///    are exact by Sterbenz's lemma whenever the two coordinates are within a factor 2 of each
///    other, which is the common case for the near neighbours a Delaunay test compares; nothing
///    underflows in the range the engines accept (the 2D engine's module documentation gives it).
/// 3. Otherwise Shewchuk's full adaptive cascade ([`incircle`]), which handles inexact
///    differences.
///
/// Before stage 2, an exact **integer** evaluation after an exact power-of-two rescale decides
/// whenever the eight coordinates span at most 61 binary orders (most tests, including those
/// between far-apart points whose differences are inexact; the proof is at
/// `incircle_sign_int`); stages 2 and 3 serve the rest.
///
/// With the `predicate-stats` feature the calls decided at each stage are counted
/// ([`stats::snapshot`]).
#[inline]
pub fn incircle_sign(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> i32 {
    let adx = a[0] - d[0];
    let bdx = b[0] - d[0];
    let cdx = c[0] - d[0];
    let ady = a[1] - d[1];
    let bdy = b[1] - d[1];
    let cdy = c[1] - d[1];
    let bdxcdy = bdx * cdy;
    let cdxbdy = cdx * bdy;
    let alift = adx * adx + ady * ady;
    let cdxady = cdx * ady;
    let adxcdy = adx * cdy;
    let blift = bdx * bdx + bdy * bdy;
    let adxbdy = adx * bdy;
    let bdxady = bdx * ady;
    let clift = cdx * cdx + cdy * cdy;
    let det = alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
    let permanent = (bdxcdy.abs() + cdxbdy.abs()) * alift
        + (cdxady.abs() + adxcdy.abs()) * blift
        + (adxbdy.abs() + bdxady.abs()) * clift;
    let errbound = ICC_ERRBOUND_A * permanent;
    if det > errbound {
        stats::count(stats::INCIRCLE_FILTER);
        return 1;
    }
    if -det > errbound {
        stats::count(stats::INCIRCLE_FILTER);
        return -1;
    }
    incircle_sign_exact(a, b, c, d)
}

/// u = 2⁻⁵³, the unit roundoff.
const U: f64 = f64::EPSILON / 2.0;
/// Shewchuk's bound for the floating-point in-circle determinant (stage A).
const ICC_ERRBOUND_A: f64 = (10.0 + 96.0 * U) * U;

/// Stages 2–4 of [`incircle_sign`].
#[inline(never)]
fn incircle_sign_exact(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> i32 {
    if let Some(s) = incircle_sign_int([a, b, c, d]) {
        stats::count(stats::INCIRCLE_INT);
        return s;
    }
    let (adx, adxt) = xp::two_diff(a[0], d[0]);
    let (bdx, bdxt) = xp::two_diff(b[0], d[0]);
    let (cdx, cdxt) = xp::two_diff(c[0], d[0]);
    let (ady, adyt) = xp::two_diff(a[1], d[1]);
    let (bdy, bdyt) = xp::two_diff(b[1], d[1]);
    let (cdy, cdyt) = xp::two_diff(c[1], d[1]);
    if adxt != 0.0 || bdxt != 0.0 || cdxt != 0.0 || adyt != 0.0 || bdyt != 0.0 || cdyt != 0.0 {
        stats::count(stats::INCIRCLE_FULL);
        let s = raw::incircle(a, b, c, d);
        return (s > 0.0) as i32 - (s < 0.0) as i32;
    }
    stats::count(stats::INCIRCLE_EXACT);
    // Σ_cyc lift(a)·(b × c), each term an expansion of ≤ 32 components.
    let mut ta = [0.0; 32];
    let mut tb = [0.0; 32];
    let mut tc = [0.0; 32];
    let na = xp::lifted_cross(adx, ady, [bdx, bdy], [cdx, cdy], &mut ta);
    let nb = xp::lifted_cross(bdx, bdy, [cdx, cdy], [adx, ady], &mut tb);
    let nc = xp::lifted_cross(cdx, cdy, [adx, ady], [bdx, bdy], &mut tc);
    let mut ab = [0.0; 64];
    let nab = xp::sum(&ta[..na], &tb[..nb], &mut ab);
    let mut fin = [0.0; 96];
    let n = xp::sum(&ab[..nab], &tc[..nc], &mut fin);
    xp::sign(&fin[..n])
}

/// Stage 2 of [`incircle_sign`]: the determinant in integer arithmetic, or `None` when the
/// eight coordinates span more than 61 binary orders (or one is subnormal).
///
/// Why it is exact: every finite double is `±m·2^q` with an integer `m < 2^53`. Let `lo` be the
/// smallest exponent of a set bit over the eight coordinates and `2^hi` a bound on their
/// magnitudes. Multiplying every coordinate by `2^−lo` — an exact power-of-two rescale, done
/// here by shifting the mantissas, so no rounding and no overflow at any scale — gives integers
/// `X` with `|X| < 2^(hi−lo) ≤ 2^61`. The in-circle determinant is homogeneous of degree 4 in
/// the coordinates (it depends on differences only), so its sign is unchanged by the rescale.
/// Then the differences are < 2^62 (exact in `i64`), each product of two differences and each
/// 2×2 cross term or lift is < 2^125 (exact in `i128`), each product lift × cross is < 2^250
/// and the sum of the three is < 2^252, exact in the 256-bit two's-complement accumulator.
/// No step rounds, so the sign is the exact sign of the determinant.
#[inline]
fn incircle_sign_int(p: [[f64; 2]; 4]) -> Option<i32> {
    let lo = match int_scale(p.as_flattened(), 61)? {
        IntScale::Zero => return Some(0), // four copies of the origin
        IntScale::Shift(lo) => lo,
    };
    let [a, b, c, d] = p.map(|q| [to_int(q[0], lo), to_int(q[1], lo)]);
    let diff = |u: [i64; 2]| [(u[0] - d[0]) as i128, (u[1] - d[1]) as i128];
    let ([adx, ady], [bdx, bdy], [cdx, cdy]) = (diff(a), diff(b), diff(c));
    let term = |x: i128, y: i128, u: [i128; 2], v: [i128; 2]| {
        wide::mul(x * x + y * y, u[0] * v[1] - v[0] * u[1])
    };
    let det = wide::add(
        wide::add(
            term(adx, ady, [bdx, bdy], [cdx, cdy]),
            term(bdx, bdy, [cdx, cdy], [adx, ady]),
        ),
        term(cdx, cdy, [adx, ady], [bdx, bdy]),
    );
    Some(wide::sign(det))
}

/// The common power-of-two scale of the integer stages ([`int_scale`]).
enum IntScale {
    /// Every coordinate is zero.
    Zero,
    /// Multiplying by `2^−lo` makes every coordinate an integer (see [`to_int`]).
    Shift(i32),
}

/// The exponent `lo` of the smallest set bit over the coordinates `xs`, when every
/// `x·2^−lo` is an integer of magnitude below `2^max_span`; `None` when a coordinate is
/// subnormal or the coordinates span more than `max_span` binary orders.
#[inline]
fn int_scale(xs: &[f64], max_span: i32) -> Option<IntScale> {
    let mut lo = i32::MAX;
    let mut hi = i32::MIN;
    for &x in xs {
        if x == 0.0 {
            continue;
        }
        let bits = x.to_bits();
        let e = ((bits >> 52) & 0x7ff) as i32;
        if e == 0 {
            return None; // subnormal
        }
        let m = (bits & ((1u64 << 52) - 1)) | (1u64 << 52);
        // |x| = m·2^(e−1075) < 2^(e−1022)
        lo = lo.min(e - 1075 + m.trailing_zeros() as i32);
        hi = hi.max(e - 1022);
    }
    if hi == i32::MIN {
        return Some(IntScale::Zero);
    }
    if hi - lo > max_span {
        return None;
    }
    Some(IntScale::Shift(lo))
}

/// `x·2^−lo` as an integer, for an `lo` from [`int_scale`] over a set containing `x` (the
/// shift drops only zero bits, so it is exact).
#[inline]
fn to_int(x: f64, lo: i32) -> i64 {
    if x == 0.0 {
        return 0;
    }
    let bits = x.to_bits();
    let e = ((bits >> 52) & 0x7ff) as i32;
    let m = ((bits & ((1u64 << 52) - 1)) | (1u64 << 52)) as i64;
    // x·2^−lo = m·2^(e−1075−lo); a right shift drops only zero bits (lo ≤ e−1075+tz(m))
    let s = e - 1075 - lo;
    let v = if s >= 0 { m << s } else { m >> -s };
    if bits >> 63 == 1 {
        -v
    } else {
        v
    }
}

/// The in-sphere sign through a cheaper exact stage (used by the 3D Delaunay engine).
///
/// Returns the exact sign (+1, 0, −1) of [`insphere`]`(a, b, c, d, e)`, reached through:
///
/// 1. **Filter** (Shewchuk's stage A): the determinant of the differences `p − e` in floating
///    point, evaluated in Shewchuk's order, with his bound `ε = (16 + 224u)u · permanent`,
///    u = 2⁻⁵³ (the same decision `robust::insphere` takes first).
/// 2. **Exact integer evaluation** after an exact power-of-two rescale when the fifteen
///    coordinates span at most 61 binary orders (proof at `insphere_sign_int`). On points
///    sampled near a sphere, where the filter fails on a large share of the tests, this stage
///    replaces Shewchuk's expansion arithmetic (which took ≈ 90 % of the time of a
///    100k-point sphere, issue 23).
/// 3. Otherwise Shewchuk's adaptive cascade ([`insphere`]).
///
/// Valid where Shewchuk's predicates are (coordinates 0 or of magnitude in [2^−120, 2^120],
/// `geom::exact::safe_range`); outside it use `geom::exact::insphere_exact`.
/// With the `predicate-stats` feature the calls decided at each stage are counted.
#[inline]
pub fn insphere_sign(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3], e: [f64; 3]) -> i32 {
    if let Some(det) = insphere_stage_a(a, b, c, d, e) {
        stats::count(stats::INSPHERE_FILTER);
        return (det > 0.0) as i32 - (det < 0.0) as i32;
    }
    insphere_sign_exact(a, b, c, d, e)
}

/// Shewchuk's floating-point `insphere` stage A: the determinant of the differences `p − e`,
/// evaluated in his order, when its sign is certain (`|det| > (16 + 224u)u · permanent`).
/// Only in the safe range (`geom::exact::safe_range`: no product over- or underflows).
/// Also the first stage of `geom::near_sphere::NearSphere::insphere`.
#[inline]
pub(crate) fn insphere_stage_a(
    pa: [f64; 3],
    pb: [f64; 3],
    pc: [f64; 3],
    pd: [f64; 3],
    pe: [f64; 3],
) -> Option<f64> {
    let [aex, aey, aez] = [pa[0] - pe[0], pa[1] - pe[1], pa[2] - pe[2]];
    let [bex, bey, bez] = [pb[0] - pe[0], pb[1] - pe[1], pb[2] - pe[2]];
    let [cex, cey, cez] = [pc[0] - pe[0], pc[1] - pe[1], pc[2] - pe[2]];
    let [dex, dey, dez] = [pd[0] - pe[0], pd[1] - pe[1], pd[2] - pe[2]];
    let (aexbey, bexaey) = (aex * bey, bex * aey);
    let (bexcey, cexbey) = (bex * cey, cex * bey);
    let (cexdey, dexcey) = (cex * dey, dex * cey);
    let (dexaey, aexdey) = (dex * aey, aex * dey);
    let (aexcey, cexaey) = (aex * cey, cex * aey);
    let (bexdey, dexbey) = (bex * dey, dex * bey);
    let ab = aexbey - bexaey;
    let bc = bexcey - cexbey;
    let cd = cexdey - dexcey;
    let da = dexaey - aexdey;
    let ac = aexcey - cexaey;
    let bd = bexdey - dexbey;
    let abc = aez * bc - bez * ac + cez * ab;
    let bcd = bez * cd - cez * bd + dez * bc;
    let cda = cez * da + dez * ac + aez * cd;
    let dab = dez * ab + aez * bd + bez * da;
    let alift = aex * aex + aey * aey + aez * aez;
    let blift = bex * bex + bey * bey + bez * bez;
    let clift = cex * cex + cey * cey + cez * cez;
    let dlift = dex * dex + dey * dey + dez * dez;
    let det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);
    let (az, bz, cz, dz) = (aez.abs(), bez.abs(), cez.abs(), dez.abs());
    let permanent = ((cexdey.abs() + dexcey.abs()) * bz
        + (dexbey.abs() + bexdey.abs()) * cz
        + (bexcey.abs() + cexbey.abs()) * dz)
        * alift
        + ((dexaey.abs() + aexdey.abs()) * cz
            + (aexcey.abs() + cexaey.abs()) * dz
            + (cexdey.abs() + dexcey.abs()) * az)
            * blift
        + ((aexbey.abs() + bexaey.abs()) * dz
            + (bexdey.abs() + dexbey.abs()) * az
            + (dexaey.abs() + aexdey.abs()) * bz)
            * clift
        + ((bexcey.abs() + cexbey.abs()) * az
            + (cexaey.abs() + aexcey.abs()) * bz
            + (aexbey.abs() + bexaey.abs()) * cz)
            * dlift;
    let bound = ISP_ERRBOUND_A * permanent;
    (det > bound || -det > bound).then_some(det)
}

/// Shewchuk's bound for the floating-point in-sphere determinant (stage A).
const ISP_ERRBOUND_A: f64 = (16.0 + 224.0 * U) * U;

/// Stages 2–3 of [`insphere_sign`].
#[inline(never)]
fn insphere_sign_exact(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3], e: [f64; 3]) -> i32 {
    if let Some(s) = insphere_sign_int([a, b, c, d, e]) {
        stats::count(stats::INSPHERE_INT);
        return s;
    }
    stats::count(stats::INSPHERE_FULL);
    let s = raw::insphere(a, b, c, d, e);
    (s > 0.0) as i32 - (s < 0.0) as i32
}

/// Stage 2 of [`insphere_sign`]: the determinant in integer arithmetic, or `None` when the
/// fifteen coordinates span more than 61 binary orders (or one is subnormal).
///
/// Why it is exact (as at [`incircle_sign_int`]): after the exact rescale by `2^−lo` every
/// coordinate is an integer `X` with `|X| < 2^61`, and the sign of the determinant, homogeneous
/// of degree 5 in the differences, is unchanged. Then the differences `p − e` are < 2^62 (exact
/// in `i64`); the 2×2 minors of their x, y parts are < 2^125 (exact in `i128`); the 3×3 minors
/// `z·minor` summed three at a time are < 3·2^187 (exact in the 256-bit [`wide`] integers); the
/// lifts x² + y² + z² are < 3·2^124 (exact in `u128`); each lift × 3×3 minor is < 9·2^311 and
/// the sum of four < 2^317, exact in the 384-bit accumulator. Nothing rounds, so the sign is
/// exact. The expression is Shewchuk's, term for term, so the sign convention is his.
#[inline]
fn insphere_sign_int(p: [[f64; 3]; 5]) -> Option<i32> {
    let lo = match int_scale(p.as_flattened(), 61)? {
        IntScale::Zero => return Some(0), // five copies of the origin
        IntScale::Shift(lo) => lo,
    };
    let [a, b, c, d, e] = p.map(|q| q.map(|x| to_int(x, lo)));
    let diff = |u: [i64; 3]| [0, 1, 2].map(|k| (u[k] - e[k]) as i128);
    let ([aex, aey, aez], [bex, bey, bez], [cex, cey, cez], [dex, dey, dez]) =
        (diff(a), diff(b), diff(c), diff(d));
    let ab = aex * bey - bex * aey;
    let bc = bex * cey - cex * bey;
    let cd = cex * dey - dex * cey;
    let da = dex * aey - aex * dey;
    let ac = aex * cey - cex * aey;
    let bd = bex * dey - dex * bey;
    let m3 = |x: i128, p: i128, y: i128, q: i128, z: i128, r: i128| {
        wide::add(wide::add(wide::mul(x, p), wide::mul(y, q)), wide::mul(z, r))
    };
    let abc = m3(aez, bc, -bez, ac, cez, ab);
    let bcd = m3(bez, cd, -cez, bd, dez, bc);
    let cda = m3(cez, da, dez, ac, aez, cd);
    let dab = m3(dez, ab, aez, bd, bez, da);
    let lift = |x: i128, y: i128, z: i128| {
        let (x, y, z) = (x.unsigned_abs(), y.unsigned_abs(), z.unsigned_abs());
        x * x + y * y + z * z
    };
    let mut acc = [0u64; 6];
    wide::mul_add384(&mut acc, lift(dex, dey, dez), abc, false);
    wide::mul_add384(&mut acc, lift(cex, cey, cez), dab, true);
    wide::mul_add384(&mut acc, lift(bex, bey, bez), cda, false);
    wide::mul_add384(&mut acc, lift(aex, aey, aez), bcd, true);
    Some(wide::sign384(&acc))
}

/// 256-bit two's-complement integers `(high, low)` = high·2^128 + low, for
/// [`incircle_sign_int`] and [`insphere_sign_int`]: products of two `i128` below 2^126 in
/// magnitude and sums of a few; and the 384-bit accumulator of [`insphere_sign_int`].
mod wide {
    pub type W = (u128, u128);

    /// The exact product a·b (|a|, |b| < 2^126).
    #[inline]
    pub fn mul(a: i128, b: i128) -> W {
        let neg = (a < 0) != (b < 0);
        let (x, y) = (a.unsigned_abs(), b.unsigned_abs());
        let (x1, x0) = (x >> 64, x & u64::MAX as u128);
        let (y1, y0) = (y >> 64, y & u64::MAX as u128);
        let low = x0 * y0;
        let mid = x0 * y1 + x1 * y0; // < 2^127: no overflow
        let lo = low.wrapping_add(mid << 64);
        let carry = (lo < low) as u128;
        let hi = x1 * y1 + (mid >> 64) + carry;
        if neg {
            ((!hi).wrapping_add((lo == 0) as u128), (!lo).wrapping_add(1))
        } else {
            (hi, lo)
        }
    }

    /// a + b (no overflow for the magnitudes used).
    #[inline]
    pub fn add(a: W, b: W) -> W {
        let lo = a.1.wrapping_add(b.1);
        let carry = (lo < a.1) as u128;
        (a.0.wrapping_add(b.0).wrapping_add(carry), lo)
    }

    /// The sign of a (+1, 0, −1).
    #[inline]
    pub fn sign(a: W) -> i32 {
        if a.0 >> 127 == 1 {
            -1
        } else {
            (a.0 != 0 || a.1 != 0) as i32
        }
    }

    /// `acc ± l·m` in 384-bit two's complement (six little-endian `u64` limbs): `l < 2^128`,
    /// `|m| < 2^192`, `neg` subtracts. The caller keeps every partial sum below 2^383.
    #[inline]
    pub fn mul_add384(acc: &mut [u64; 6], l: u128, m: W, neg: bool) {
        // |m| and its sign
        let mneg = m.0 >> 127 == 1;
        let m = if mneg {
            let lo = (!m.1).wrapping_add(1);
            ((!m.0).wrapping_add((lo == 0) as u128), lo)
        } else {
            m
        };
        let x = [l as u64, (l >> 64) as u64];
        let y = [m.1 as u64, (m.1 >> 64) as u64, m.0 as u64];
        // schoolbook product, 2 × 3 limbs → 5 limbs
        let mut p = [0u64; 6];
        for (i, &xi) in x.iter().enumerate() {
            let mut carry = 0u128;
            for (j, &yj) in y.iter().enumerate() {
                let t = xi as u128 * yj as u128 + p[i + j] as u128 + carry;
                p[i + j] = t as u64;
                carry = t >> 64;
            }
            p[i + y.len()] = carry as u64;
        }
        if neg != mneg {
            // acc −= p
            let mut borrow = 0u64;
            for k in 0..6 {
                let (t, b1) = acc[k].overflowing_sub(p[k]);
                let (t, b2) = t.overflowing_sub(borrow);
                acc[k] = t;
                borrow = (b1 || b2) as u64;
            }
        } else {
            let mut carry = 0u64;
            for k in 0..6 {
                let (t, c1) = acc[k].overflowing_add(p[k]);
                let (t, c2) = t.overflowing_add(carry);
                acc[k] = t;
                carry = (c1 || c2) as u64;
            }
        }
    }

    /// The sign of a 384-bit two's-complement integer (+1, 0, −1).
    #[inline]
    pub fn sign384(a: &[u64; 6]) -> i32 {
        if a[5] >> 63 == 1 {
            -1
        } else {
            a.iter().any(|&x| x != 0) as i32
        }
    }
}

/// Counts of the stage at which each [`incircle_sign`] and [`insphere_sign`] call was decided (feature
/// `predicate-stats`; without it the counters stay 0 and cost nothing).
pub mod stats {
    #[cfg(feature = "predicate-stats")]
    use std::sync::atomic::{AtomicU64, Ordering};

    /// Decided by the floating-point filter.
    pub const INCIRCLE_FILTER: usize = 0;
    /// Decided by the exact integer evaluation after the power-of-two rescale.
    pub const INCIRCLE_INT: usize = 1;
    /// Decided by the exact expansion of exact differences.
    pub const INCIRCLE_EXACT: usize = 2;
    /// Passed to Shewchuk's full adaptive cascade (inexact differences).
    pub const INCIRCLE_FULL: usize = 3;
    /// Exactly zero in-circle determinant: decided by symbolic perturbation (counted by the
    /// Delaunay engine).
    pub const INCIRCLE_SOS: usize = 4;
    /// Visibility-walk steps (triangles visited) of the 2D engine.
    pub const WALK_STEPS: usize = 5;
    /// Lawson flips of the 2D engine.
    pub const FLIPS: usize = 6;
    /// [`super::insphere_sign`] decided by the floating-point filter.
    pub const INSPHERE_FILTER: usize = 7;
    /// [`super::insphere_sign`] decided by the exact integer evaluation.
    pub const INSPHERE_INT: usize = 8;
    /// [`super::insphere_sign`] passed to Shewchuk's adaptive cascade.
    pub const INSPHERE_FULL: usize = 9;
    /// Number of counters.
    pub const N: usize = 10;
    /// Names of the counters, in order.
    pub const NAMES: [&str; N] = [
        "incircle_filter",
        "incircle_int",
        "incircle_exact",
        "incircle_full",
        "incircle_sos",
        "walk_steps",
        "flips",
        "insphere_filter",
        "insphere_int",
        "insphere_full",
    ];

    #[cfg(feature = "predicate-stats")]
    static COUNTS: [AtomicU64; N] = [const { AtomicU64::new(0) }; N];

    /// Adds one to counter `k`.
    #[inline(always)]
    pub fn count(k: usize) {
        #[cfg(feature = "predicate-stats")]
        COUNTS[k].fetch_add(1, Ordering::Relaxed);
        #[cfg(not(feature = "predicate-stats"))]
        let _ = k;
    }

    /// The counters (all 0 without the feature).
    pub fn snapshot() -> [u64; N] {
        #[cfg(feature = "predicate-stats")]
        {
            std::array::from_fn(|k| COUNTS[k].load(Ordering::Relaxed))
        }
        #[cfg(not(feature = "predicate-stats"))]
        {
            [0; N]
        }
    }

    /// Sets every counter to 0.
    pub fn reset() {
        #[cfg(feature = "predicate-stats")]
        for c in &COUNTS {
            c.store(0, Ordering::Relaxed);
        }
    }
}

#[cfg(test)]
mod tests {
    //! The predicates must give the exact sign where naive floating-point evaluation does not.
    //! Oracles: closed-form signs of constructed near-degenerate inputs, and an exact i128
    //! evaluation of Shewchuk's determinant formulas on small-integer inputs.
    use super::raw;
    use proptest::prelude::*;

    fn sign(x: f64) -> i32 {
        (x > 0.0) as i32 - (x < 0.0) as i32
    }

    fn isign(x: i128) -> i32 {
        x.signum() as i32
    }

    // --- Exact i128 versions of Shewchuk's formulas (same expressions, integer arithmetic). ---

    fn i_orient2d(a: [i64; 2], b: [i64; 2], c: [i64; 2]) -> i128 {
        let [ax, ay, bx, by, cx, cy] = [a[0], a[1], b[0], b[1], c[0], c[1]].map(|v| v as i128);
        (ax - cx) * (by - cy) - (ay - cy) * (bx - cx)
    }

    fn i_incircle(a: [i64; 2], b: [i64; 2], c: [i64; 2], d: [i64; 2]) -> i128 {
        let f = |p: [i64; 2]| [(p[0] - d[0]) as i128, (p[1] - d[1]) as i128];
        let ([adx, ady], [bdx, bdy], [cdx, cdy]) = (f(a), f(b), f(c));
        let (al, bl, cl) = (
            adx * adx + ady * ady,
            bdx * bdx + bdy * bdy,
            cdx * cdx + cdy * cdy,
        );
        al * (bdx * cdy - cdx * bdy) + bl * (cdx * ady - adx * cdy) + cl * (adx * bdy - bdx * ady)
    }

    fn i_orient3d(a: [i64; 3], b: [i64; 3], c: [i64; 3], d: [i64; 3]) -> i128 {
        let f = |p: [i64; 3]| [0, 1, 2].map(|k| (p[k] - d[k]) as i128);
        let (a, b, c) = (f(a), f(b), f(c));
        a[0] * (b[1] * c[2] - b[2] * c[1])
            + b[0] * (c[1] * a[2] - c[2] * a[1])
            + c[0] * (a[1] * b[2] - a[2] * b[1])
    }

    fn i_insphere(a: [i64; 3], b: [i64; 3], c: [i64; 3], d: [i64; 3], e: [i64; 3]) -> i128 {
        let f = |p: [i64; 3]| [0, 1, 2].map(|k| (p[k] - e[k]) as i128);
        let ([aex, aey, aez], [bex, bey, bez], [cex, cey, cez], [dex, dey, dez]) =
            (f(a), f(b), f(c), f(d));
        let ab = aex * bey - bex * aey;
        let bc = bex * cey - cex * bey;
        let cd = cex * dey - dex * cey;
        let da = dex * aey - aex * dey;
        let ac = aex * cey - cex * aey;
        let bd = bex * dey - dex * bey;
        let abc = aez * bc - bez * ac + cez * ab;
        let bcd = bez * cd - cez * bd + dez * bc;
        let cda = cez * da + dez * ac + aez * cd;
        let dab = dez * ab + aez * bd + bez * da;
        let lift = |x: i128, y: i128, z: i128| x * x + y * y + z * z;
        let (al, bl, cl, dl) = (
            lift(aex, aey, aez),
            lift(bex, bey, bez),
            lift(cex, cey, cez),
            lift(dex, dey, dez),
        );
        (dl * abc - cl * dab) + (bl * cda - al * bcd)
    }

    fn f2(p: [i64; 2]) -> [f64; 2] {
        p.map(|v| v as f64)
    }
    fn f3(p: [i64; 3]) -> [f64; 3] {
        p.map(|v| v as f64)
    }

    /// Every stage of [`super::incircle_sign`] is reached and agrees: exact zeros with exact
    /// differences (stage 2), exact zeros with inexact differences (stage 3), near misses.
    #[test]
    fn incircle_sign_stages() {
        let u = 2f64.powi(-40);
        // cocircular integer points about a far centre: differences exact, determinant 0
        let o = 1024.0;
        let (a, b, c) = ([o + 5.0, o], [o + 3.0, o + 4.0], [o - 4.0, o + 3.0]);
        assert_eq!(super::incircle_sign(a, b, c, [o, o - 5.0]), 0);
        assert_eq!(super::incircle_sign(a, b, c, [o, o - 5.0 + 2.0 * u * o]), 1);
        assert_eq!(
            super::incircle_sign(a, b, c, [o, o - 5.0 - 2.0 * u * o]),
            -1
        );
        // a centre at the origin: differences across 0 are inexact for fractional coordinates
        let (a, b, c) = ([0.6, 0.8], [-0.8, 0.6], [0.0, -1.0]);
        for d in [[0.8, -0.6], [0.6, -0.8], [-0.6, -0.8], [1.0, 0.0]] {
            assert_eq!(
                super::incircle_sign(a, b, c, d),
                sign(raw::incircle(a, b, c, d)),
                "{d:?}"
            );
        }
    }

    /// Every stage of [`super::insphere_sign`] is reached and agrees with Shewchuk's sign:
    /// cospherical integer points (exact zeros, integer stage), points moved off the sphere by
    /// single ulps, coordinates spanning more than 61 binary orders (full cascade), and the
    /// integer stage at the largest magnitudes its proof allows (an overflow would flip signs).
    #[test]
    fn insphere_sign_stages() {
        let o = 2f64.powi(20);
        let u = 2f64.powi(-32);
        let (a, b, c, d) = (
            [o + 3.0, o + 4.0, o],
            [o - 4.0, o + 3.0, o],
            [o, o - 3.0, o + 4.0],
            [o, o, o - 5.0],
        );
        for k in -32i32..=32 {
            let e = [o, o, o + 5.0 - k as f64 * u];
            assert_eq!(
                super::insphere_sign(a, b, c, d, e),
                sign(raw::insphere(a, b, c, d, e)),
                "k={k}"
            );
            assert!(super::insphere_sign_int([a, b, c, d, e]).is_some());
        }
        assert_eq!(super::insphere_sign(a, b, c, d, [o, o, o + 5.0]), 0);
        // a tiny coordinate beside unit ones: more than 61 binary orders, the full cascade
        let t = 1e-30;
        let q = [
            [1.0, 0.0, t],
            [0.0, 1.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        assert!(super::insphere_sign_int([q[0], q[1], q[2], q[3], [0.0, -1.0, 0.0]]).is_none());
        for e in [
            [0.0, -1.0, 0.0],
            [0.0, -1.0, t],
            [0.0, -1.0, -t],
            [0.5, 0.5, 0.5],
        ] {
            assert_eq!(
                super::insphere_sign(q[0], q[1], q[2], q[3], e),
                sign(raw::insphere(q[0], q[1], q[2], q[3], e)),
                "{e:?}"
            );
        }
        // integer stage at full width: coordinates from 1 up to (2^53 − 1)·2^8 < 2^61
        let big = (2f64.powi(53) - 1.0) * 256.0;
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let m = (x >> 11) as f64 / 2f64.powi(53); // [0, 1)
            let v = if x & 1 == 0 { big } else { big * 0.5 };
            (v * m).round() * if x & 2 == 0 { 1.0 } else { -1.0 }
        };
        let mut decided = 0;
        for _ in 0..2000 {
            let mut p = [[0.0; 3]; 5];
            for q in p.iter_mut() {
                *q = [next(), next(), next()];
            }
            p[0][0] = big;
            p[1][1] = 1.0;
            let Some(s) = super::insphere_sign_int(p) else {
                continue;
            };
            decided += 1;
            assert_eq!(
                s,
                sign(raw::insphere(p[0], p[1], p[2], p[3], p[4])),
                "{p:?}"
            );
        }
        assert!(decided > 1900, "{decided}");
    }

    #[test]
    fn conventions() {
        assert!(raw::orient2d([0., 0.], [1., 0.], [0., 1.]) > 0.0);
        assert!(raw::incircle([1., 0.], [0., 1.], [-1., 0.], [0., 0.]) > 0.0);
        assert!(raw::incircle([1., 0.], [0., 1.], [-1., 0.], [2., 0.]) < 0.0);
        // d below the counter-clockwise (seen from +z) triangle ⇒ positive.
        let (a, b, c) = ([0., 0., 0.], [1., 0., 0.], [0., 1., 0.]);
        assert!(raw::orient3d(a, b, c, [0., 0., -1.]) > 0.0);
        let d = [0., 0., -1.];
        assert!(raw::insphere(a, b, c, d, [0.1, 0.1, -0.1]) > 0.0);
        assert!(raw::insphere(a, b, c, d, [5., 5., 5.]) < 0.0);
        // The i128 oracles agree on the conventions.
        assert!(i_orient3d([0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, -1]) > 0);
        assert!(i_insphere([0, 0, 0], [2, 0, 0], [0, 2, 0], [0, 0, -2], [1, 1, -1]) > 0);
        assert!(i_incircle([1, 0], [0, 1], [-1, 0], [0, 0]) > 0);
    }

    /// Kettner, Mehlhorn, Pion, Schirra, Yap, "Classroom examples of robustness problems in
    /// geometric computations" (2008): p = (0.5 + x·2⁻⁵³, 0.5 + y·2⁻⁵³), q = (12, 12),
    /// r = (24, 24). Exactly, orient2d(p, q, r) = 12·(p_y − p_x), so its sign is sign(y − x).
    #[test]
    fn orient2d_kettner_grid() {
        let u = 2f64.powi(-53);
        let (q, r) = ([12.0, 12.0], [24.0, 24.0]);
        let mut naive_wrong = 0;
        for x in 0..256i32 {
            for y in 0..256i32 {
                let p = [0.5 + x as f64 * u, 0.5 + y as f64 * u];
                let expect = (y - x).signum();
                assert_eq!(sign(raw::orient2d(p, q, r)), expect, "x={x} y={y}");
                assert_eq!(sign(raw::orient2d(q, r, p)), expect);
                assert_eq!(sign(raw::orient2d(r, p, q)), expect);
                let naive = (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
                naive_wrong += (sign(naive) != expect) as usize;
            }
        }
        // The example is hard: plain evaluation gets many of these signs wrong.
        assert!(naive_wrong > 1000, "naive wrong only {naive_wrong} times");
    }

    /// d on the vertical through the centre of the circle through a, b, c (radius R = 2^20), moved
    /// by k·2^-32: inside exactly when k > 0. The determinant is ~R³·k·2^-32 while its terms are
    /// ~R⁴, so plain evaluation loses the sign.
    #[test]
    fn incircle_nearly_cocircular() {
        let r = 2f64.powi(20);
        let u = 2f64.powi(-32);
        let mut naive_wrong = 0;
        for (ox, oy) in [(0.0, 0.0), (0.5, -0.25), (3.0 * r, r)] {
            let (a, b, c) = ([ox + r, oy], [ox, oy + r], [ox - r, oy]);
            for k in -64i32..=64 {
                let d = [ox, oy - r + k as f64 * u];
                assert_eq!(d[1] - (oy - r), k as f64 * u, "not representable");
                assert_eq!(sign(raw::incircle(a, b, c, d)), k.signum(), "k={k}");
                assert_eq!(sign(raw::incircle(b, c, a, d)), k.signum());
                assert_eq!(sign(raw::incircle(b, a, c, d)), -k.signum());
                let f = |p: [f64; 2]| [p[0] - d[0], p[1] - d[1]];
                let ([ax, ay], [bx, by], [cx, cy]) = (f(a), f(b), f(c));
                let naive = (ax * ax + ay * ay) * (bx * cy - cx * by)
                    + (bx * bx + by * by) * (cx * ay - ax * cy)
                    + (cx * cx + cy * cy) * (ax * by - bx * ay);
                naive_wrong += (sign(naive) != k.signum()) as usize;
            }
        }
        assert!(naive_wrong > 0, "the case is not hard for plain evaluation");
        eprintln!("incircle: naive evaluation wrong in {naive_wrong} of 387 cases");
    }

    /// d above/below the plane z = x + y − O through a, b, c by k ulps of z.
    #[test]
    fn orient3d_nearly_coplanar() {
        let o = 2f64.powi(20);
        let (a, b, c) = ([o, o, o], [o + 3.0, o, o + 3.0], [o, o + 5.0, o + 5.0]);
        // Normal (b−a)×(c−a) = (−15, −15, 15): a, b, c are counter-clockwise seen from +z.
        let mut naive_wrong = 0;
        for (x, y) in [(0.5, 0.25), (7.0, -3.0), (1e3 + 0.125, 2e3 + 0.375), (o, o)] {
            for k in -16i32..=16 {
                let z = o + x + y;
                let ulp = f64::from_bits(z.to_bits() + 1) - z;
                let d = [o + x, o + y, z + k as f64 * ulp];
                let expect = -k.signum();
                assert_eq!(sign(raw::orient3d(a, b, c, d)), expect, "x={x} y={y} k={k}");
                assert_eq!(sign(raw::orient3d(b, a, c, d)), -expect);
                let [ax, ay, az] = [a[0] - d[0], a[1] - d[1], a[2] - d[2]];
                let [bx, by, bz] = [b[0] - d[0], b[1] - d[1], b[2] - d[2]];
                let [cx, cy, cz] = [c[0] - d[0], c[1] - d[1], c[2] - d[2]];
                let naive =
                    ax * (by * cz - bz * cy) + bx * (cy * az - cz * ay) + cx * (ay * bz - az * by);
                naive_wrong += (sign(naive) != expect) as usize;
            }
        }
        assert!(naive_wrong > 0, "the case is not hard for plain evaluation");
        eprintln!("orient3d: naive evaluation wrong in {naive_wrong} of 132 cases");
    }

    /// e moved off a sphere through four integer points by k ulps.
    #[test]
    fn insphere_nearly_cospherical() {
        let o = 2f64.powi(20);
        let u = 2f64.powi(-32);
        // Sphere of radius 5 about (o, o, o): integer points (±3, ±4, 0) etc.
        let (a, b, c, d) = (
            [o + 3.0, o + 4.0, o],
            [o - 4.0, o + 3.0, o],
            [o, o - 3.0, o + 4.0],
            [o, o, o - 5.0],
        );
        let orient = sign(raw::orient3d(a, b, c, d));
        assert_ne!(orient, 0);
        for k in -32i32..=32 {
            let e = [o, o, o + 5.0 - k as f64 * u];
            // k > 0: e moves inside.
            assert_eq!(
                sign(raw::insphere(a, b, c, d, e)) * orient,
                k.signum(),
                "k={k}"
            );
        }
    }

    #[test]
    fn exact_zero_on_degenerate_integer_inputs() {
        // Collinear.
        for &(a, d, s, t) in &[
            ([3, -7], [2, 5], 3, -4),
            ([0, 0], [1, 1], 1, 2),
            ([100, 200], [-7, 13], 11, 5),
        ] {
            let p = |m: i64| [a[0] + m * d[0], a[1] + m * d[1]];
            assert_eq!(raw::orient2d(f2(a), f2(p(s)), f2(p(t))), 0.0);
        }
        // Cocircular: integer points on x² + y² = 25 about an integer centre.
        let circle = [
            [5, 0],
            [4, 3],
            [3, 4],
            [0, 5],
            [-3, 4],
            [-4, -3],
            [0, -5],
            [3, -4],
        ];
        for ctr in [[0, 0], [17, -9], [1 << 20, 1 << 21]] {
            let p =
                |i: usize| [circle[i][0] + ctr[0], circle[i][1] + ctr[1]].map(|v: i64| v as f64);
            for i in 0..circle.len() {
                for j in 0..circle.len() {
                    for k in 0..circle.len() {
                        for l in 0..circle.len() {
                            assert_eq!(raw::incircle(p(i), p(j), p(k), p(l)), 0.0);
                        }
                    }
                }
            }
        }
        // Coplanar: integer combinations a + s·u + t·v.
        let (a, u, v) = ([1i64, -2, 3], [2i64, 1, -1], [-3i64, 4, 5]);
        let q = |s: i64, t: i64| [0, 1, 2].map(|k| (a[k] + s * u[k] + t * v[k]) as f64);
        assert_eq!(raw::orient3d(q(0, 0), q(1, 0), q(0, 1), q(7, -3)), 0.0);
        assert_eq!(raw::orient3d(q(2, 5), q(-1, 3), q(4, 4), q(-6, 9)), 0.0);
        // Cospherical: integer points on x² + y² + z² = 25.
        let sphere = [
            [5, 0, 0],
            [0, 5, 0],
            [0, 0, -5],
            [3, 4, 0],
            [0, -3, 4],
            [4, 0, 3],
            [-3, 0, -4],
            [0, 4, -3],
        ];
        for ctr in [[0i64, 0, 0], [9, -2, 33], [1 << 25, 7, -(1 << 24)]] {
            let p = |i: usize| [0, 1, 2].map(|k| (sphere[i][k] + ctr[k]) as f64);
            for i in 0..4 {
                for e in 4..sphere.len() {
                    let (x, y, z, w) = (p(i), p((i + 1) % 4), p((i + 2) % 4), p((i + 3) % 4));
                    assert_eq!(raw::insphere(x, y, z, w, p(e)), 0.0);
                }
            }
        }
    }

    fn small() -> impl Strategy<Value = i64> {
        -(1i64 << 15)..(1i64 << 15)
    }
    fn tiny() -> impl Strategy<Value = i64> {
        -4i64..=4
    }
    fn coord() -> impl Strategy<Value = i64> {
        // Tiny values give many exactly degenerate configurations.
        prop_oneof![tiny(), small()]
    }
    fn p2() -> impl Strategy<Value = [i64; 2]> {
        [coord(), coord()]
    }
    fn p3() -> impl Strategy<Value = [i64; 3]> {
        [coord(), coord(), coord()]
    }
    /// Small integers (many exact degeneracies) or arbitrary floats in [−10, 10].
    fn fp3() -> impl Strategy<Value = [f64; 3]> {
        prop_oneof![
            [tiny(), tiny(), tiny()].prop_map(f3),
            [-10.0..10.0f64, -10.0..10.0, -10.0..10.0],
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        #[test]
        fn agree_with_i128_oracle(a in p2(), b in p2(), c in p2(), d in p2(),
                                  p in p3(), q in p3(), r in p3(), s in p3(), t in p3()) {
            prop_assert_eq!(sign(raw::orient2d(f2(a), f2(b), f2(c))), isign(i_orient2d(a, b, c)));
            prop_assert_eq!(sign(raw::incircle(f2(a), f2(b), f2(c), f2(d))), isign(i_incircle(a, b, c, d)));
            prop_assert_eq!(sign(raw::orient3d(f3(p), f3(q), f3(r), f3(s))), isign(i_orient3d(p, q, r, s)));
            prop_assert_eq!(
                sign(raw::insphere(f3(p), f3(q), f3(r), f3(s), f3(t))),
                isign(i_insphere(p, q, r, s, t))
            );
        }

        /// The cheaper cascade decides exactly as Shewchuk's: on integer points (exact zeros),
        /// on points nearly on a circle at several scales and offsets (the float filter fails,
        /// the differences are exact or not), and against the i128 oracle.
        #[test]
        fn incircle_sign_agrees(a in p2(), b in p2(), c in p2(), d in p2(),
                                t in proptest::array::uniform4(0.0..std::f64::consts::TAU),
                                k in proptest::array::uniform4(-64i32..=64),
                                sc in -40i32..40, off in prop_oneof![Just(0.0), -3.0..3.0f64]) {
            let s = super::incircle_sign(f2(a), f2(b), f2(c), f2(d));
            prop_assert_eq!(s, isign(i_incircle(a, b, c, d)));
            // four points on a circle of radius 2^sc about (off, off)·2^sc, moved by k ulps
            let r = 2f64.powi(sc);
            let q: Vec<[f64; 2]> = (0..4).map(|i| {
                let x = off * r + r * t[i].cos();
                let y = off * r + r * t[i].sin();
                let ux = f64::from_bits(x.abs().to_bits() + 1) - x.abs();
                [x + k[i] as f64 * ux, y]
            }).collect();
            prop_assert_eq!(
                super::incircle_sign(q[0], q[1], q[2], q[3]),
                sign(raw::incircle(q[0], q[1], q[2], q[3]))
            );
            // the same four points close together (exact differences by Sterbenz)
            let near: Vec<[f64; 2]> = q.iter().map(|p| [1.0 + p[0] * 1e-6, 1.5 + p[1] * 1e-6]).collect();
            prop_assert_eq!(
                super::incircle_sign(near[0], near[1], near[2], near[3]),
                sign(raw::incircle(near[0], near[1], near[2], near[3]))
            );
        }

        /// The in-sphere cascade decides exactly as Shewchuk's: on integer points (exact zeros)
        /// against the i128 oracle, and on points nearly on a sphere at several scales and
        /// offsets (the float filter fails; the differences are exact or not), moved by k ulps.
        #[test]
        fn insphere_sign_agrees(p in p3(), q in p3(), r in p3(), s in p3(), t in p3(),
                                th in proptest::array::uniform5(0.0..std::f64::consts::PI),
                                ph in proptest::array::uniform5(0.0..std::f64::consts::TAU),
                                k in proptest::array::uniform5(-64i32..=64),
                                sc in -40i32..40, off in prop_oneof![Just(0.0), -3.0..3.0f64]) {
            prop_assert_eq!(
                super::insphere_sign(f3(p), f3(q), f3(r), f3(s), f3(t)),
                isign(i_insphere(p, q, r, s, t))
            );
            let rad = 2f64.powi(sc);
            let v: Vec<[f64; 3]> = (0..5).map(|i| {
                let x = off * rad + rad * th[i].sin() * ph[i].cos();
                let y = off * rad + rad * th[i].sin() * ph[i].sin();
                let z = -off * rad + rad * th[i].cos();
                let ux = f64::from_bits(x.abs().to_bits() + 1) - x.abs();
                [x + k[i] as f64 * ux, y, z]
            }).collect();
            prop_assert_eq!(
                super::insphere_sign(v[0], v[1], v[2], v[3], v[4]),
                sign(raw::insphere(v[0], v[1], v[2], v[3], v[4]))
            );
            let near: Vec<[f64; 3]> =
                v.iter().map(|p| [1.0 + p[0] * 1e-6, 1.5 + p[1] * 1e-6, 0.75 + p[2] * 1e-6]).collect();
            prop_assert_eq!(
                super::insphere_sign(near[0], near[1], near[2], near[3], near[4]),
                sign(raw::insphere(near[0], near[1], near[2], near[3], near[4]))
            );
        }

        #[test]
        fn swapping_arguments_negates(a in fp3(), b in fp3(), c in fp3(), d in fp3(), e in fp3()) {
            let (a2, b2, c2, d2) = ([a[0], a[1]], [b[0], b[1]], [c[0], c[1]], [d[0], d[1]]);
            // The predicates are determinants: antisymmetric in every pair of arguments.
            let o2 = sign(raw::orient2d(a2, b2, c2));
            prop_assert_eq!(o2, -sign(raw::orient2d(b2, a2, c2)));
            prop_assert_eq!(o2, -sign(raw::orient2d(a2, c2, b2)));
            prop_assert_eq!(o2, sign(raw::orient2d(b2, c2, a2)));
            let ic = sign(raw::incircle(a2, b2, c2, d2));
            prop_assert_eq!(ic, -sign(raw::incircle(b2, a2, c2, d2)));
            prop_assert_eq!(ic, -sign(raw::incircle(a2, b2, d2, c2)));
            prop_assert_eq!(ic, sign(raw::incircle(c2, a2, b2, d2)));
            let o3 = sign(raw::orient3d(a, b, c, d));
            prop_assert_eq!(o3, -sign(raw::orient3d(b, a, c, d)));
            prop_assert_eq!(o3, -sign(raw::orient3d(a, b, d, c)));
            let is = sign(raw::insphere(a, b, c, d, e));
            prop_assert_eq!(is, -sign(raw::insphere(b, a, c, d, e)));
            prop_assert_eq!(is, -sign(raw::insphere(a, b, c, e, d)));
            prop_assert_eq!(is, -sign(raw::insphere(a, b, e, d, c)));
        }

        #[test]
        fn translation_invariant(a in p3(), b in p3(), c in p3(), d in p3(), e in p3(),
                                 t in [-(1i64 << 30)..(1i64 << 30), -(1i64 << 30)..(1i64 << 30), -(1i64 << 30)..(1i64 << 30)]) {
            let m = |p: [i64; 3]| [p[0] + t[0], p[1] + t[1], p[2] + t[2]];
            let two = |p: [i64; 3]| [p[0], p[1]];
            prop_assert_eq!(
                sign(raw::orient2d(f2(two(a)), f2(two(b)), f2(two(c)))),
                sign(raw::orient2d(f2(two(m(a))), f2(two(m(b))), f2(two(m(c)))))
            );
            prop_assert_eq!(
                sign(raw::incircle(f2(two(a)), f2(two(b)), f2(two(c)), f2(two(d)))),
                sign(raw::incircle(f2(two(m(a))), f2(two(m(b))), f2(two(m(c))), f2(two(m(d)))))
            );
            prop_assert_eq!(
                sign(raw::orient3d(f3(a), f3(b), f3(c), f3(d))),
                sign(raw::orient3d(f3(m(a)), f3(m(b)), f3(m(c)), f3(m(d))))
            );
            prop_assert_eq!(
                sign(raw::insphere(f3(a), f3(b), f3(c), f3(d), f3(e))),
                sign(raw::insphere(f3(m(a)), f3(m(b)), f3(m(c)), f3(m(d)), f3(m(e))))
            );
        }
    }
}
