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
#[inline]
pub fn orient3d(a: &Point3, b: &Point3, c: &Point3, d: &Point3) -> f64 {
    robust::orient3d(c3(a), c3(b), c3(c), c3(d))
}

/// > 0 when d is strictly inside the circle through the counter-clockwise a, b, c; 0 when on it.
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
