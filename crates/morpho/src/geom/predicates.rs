//! Exact geometric predicates (Shewchuk's adaptive-precision arithmetic, via the `robust` crate).
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
