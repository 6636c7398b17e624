//! Geometry kernel: points, vectors, bounding boxes, exact predicates, intersection tests,
//! enclosing balls.
//!
//! Following CGAL's kernel idea, *decisions* (which side, inside which circle) are made by the
//! exact adaptive predicates of [`predicates`] (and the crate's exact distance comparisons),
//! whose exact fallbacks (expansions, big integers, power-of-two rescaling) live in crate-private
//! modules; *constructions* (circumcentres, interpolated points) are ordinary `f64` arithmetic.
//! The public surface is the point types, [`Aabb`], the predicates (also re-exported here:
//! [`orient2d`], [`orient3d`], [`incircle`], [`insphere`]), the intersection tests of
//! [`intersect`] and the smallest enclosing disc and ball.
//!
//! ```
//! use morpho::geom::{orient2d, Point2};
//! let (a, b) = (Point2::new(0.0, 0.0), Point2::new(1.0, 0.0));
//! assert!(orient2d(&a, &b, &Point2::new(0.5, 1.0)) > 0.0); // left of a→b
//! assert!(orient2d(&a, &b, &Point2::new(0.5, -1.0)) < 0.0); // right
//! assert_eq!(orient2d(&a, &b, &Point2::new(7.0, 0.0)), 0.0); // exactly collinear
//! ```

pub(crate) mod bounded;
pub(crate) mod distance;
mod enclosing;
pub(crate) mod exact;
pub(crate) mod expansion;
pub(crate) mod grid;
pub(crate) mod near_sphere;
// Exact intersection tests of segments and triangles (2D and 3D): a namespace of its own because
// its names (`segments_intersect`, `triangles_intersect`, …) only make sense next to each other.
pub mod intersect;
// The exact adaptive predicates, on [`Point2`]/[`Point3`] and (in [`predicates::raw`]) on flat
// `[f64; D]` coordinates: a namespace so that both flavours keep the classic names.
pub mod predicates;
pub(crate) mod vec;

pub use enclosing::{
    smallest_enclosing_ball, smallest_enclosing_disc, EnclosingBall, EnclosingDisc,
};
pub use predicates::{incircle, insphere, orient2d, orient3d};

/// A point in the plane.
pub type Point2 = nalgebra::Point2<f64>;
/// A point in space.
pub type Point3 = nalgebra::Point3<f64>;
/// A vector in the plane.
pub type Vector2 = nalgebra::Vector2<f64>;
/// A vector in space.
pub type Vector3 = nalgebra::Vector3<f64>;

/// Axis-aligned bounding box in `D` dimensions. An empty box has `min > max`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb<const D: usize> {
    /// Smallest coordinate on each axis.
    pub min: [f64; D],
    /// Largest coordinate on each axis.
    pub max: [f64; D],
}

impl<const D: usize> Default for Aabb<D> {
    fn default() -> Self {
        Self::empty()
    }
}

impl<const D: usize> Aabb<D> {
    /// The empty box (contains nothing; `is_empty()` is true).
    pub fn empty() -> Self {
        Aabb {
            min: [f64::INFINITY; D],
            max: [f64::NEG_INFINITY; D],
        }
    }
    /// True when no point was added.
    pub fn is_empty(&self) -> bool {
        (0..D).any(|k| self.min[k] > self.max[k])
    }
    /// Grows the box to contain `p`.
    pub fn add(&mut self, p: &[f64]) {
        for k in 0..D {
            self.min[k] = self.min[k].min(p[k]);
            self.max[k] = self.max[k].max(p[k]);
        }
    }
    /// The box of a set of points.
    pub fn of<'a>(points: impl IntoIterator<Item = &'a [f64]>) -> Self {
        let mut b = Self::empty();
        for p in points {
            b.add(p);
        }
        b
    }
    /// Edge lengths (0 for an empty box).
    pub fn extent(&self) -> [f64; D] {
        let mut e = [0.0; D];
        if !self.is_empty() {
            for (k, ek) in e.iter_mut().enumerate() {
                *ek = self.max[k] - self.min[k];
            }
        }
        e
    }
    /// Length of the diagonal.
    pub fn diagonal(&self) -> f64 {
        self.extent().iter().map(|e| e * e).sum::<f64>().sqrt()
    }
    /// Centre of the box.
    pub fn center(&self) -> [f64; D] {
        let mut c = [0.0; D];
        for (k, ck) in c.iter_mut().enumerate() {
            *ck = 0.5 * (self.min[k] + self.max[k]);
        }
        c
    }
}

/// 2D bounding box.
pub type Aabb2 = Aabb<2>;
/// 3D bounding box.
pub type Aabb3 = Aabb<3>;

/// Bounding box of 3D points.
pub fn bbox3(points: &[Point3]) -> Aabb3 {
    let mut b = Aabb3::empty();
    for p in points {
        b.add(p.coords.as_slice());
    }
    b
}

/// Bounding box of 2D points.
///
/// ```
/// use morpho::geom::{bbox2, Point2};
/// let b = bbox2(&[Point2::new(1.0, 2.0), Point2::new(-1.0, 0.0)]);
/// assert_eq!((b.min, b.max), ([-1.0, 0.0], [1.0, 2.0]));
/// assert_eq!((b.center(), b.extent()), ([0.0, 1.0], [2.0, 2.0]));
/// ```
pub fn bbox2(points: &[Point2]) -> Aabb2 {
    let mut b = Aabb2::empty();
    for p in points {
        b.add(p.coords.as_slice());
    }
    b
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bbox_of_points() {
        let b = bbox3(&[Point3::new(1.0, -2.0, 3.0), Point3::new(-1.0, 5.0, 0.0)]);
        assert_eq!(b.min, [-1.0, -2.0, 0.0]);
        assert_eq!(b.max, [1.0, 5.0, 3.0]);
        assert_eq!(b.center(), [0.0, 1.5, 1.5]);
        assert!(Aabb2::empty().is_empty());
        assert_eq!(Aabb2::empty().extent(), [0.0, 0.0]);
    }
}
