//! Smooth shapes (Veltkamp 1992, ch. 8–9; NOTES part B): Bézier curves and triangles, the
//! closed G¹ cubic curve through a polygon, and the cubic three-split G¹ surface through a
//! closed triangle mesh with its vertex normals, with an independent continuity check and a
//! tessellation.
//!
//! Deviations from the text (each documented in its file): the three-split's singular edges
//! (mirror-symmetric sides, where (9.4) has no solution) are detected and reported, and
//! built with a degree-elevated quadratic boundary and the ratio `e1/e0` that makes (9.3)
//! consistent, in closed form (see [`three_split`]); the 2D curve's failing vertices are
//! repaired with the uniform weighting (NOTES B.2), and its joint bound is relative to the
//! rounding of the stored control points ([`Joint::rounding`]).
//!
//! Not yet built (issue 19): the two- and six-split, the side-vertex surface (H ch. 6),
//! reflection lines and benches. The CLI is `morpho smooth` (curve and three-split).

mod bezier;
mod check;
mod curve;
mod error;
mod normals;
mod singular;
mod split3;
mod tessellate;
mod triangle;

pub use bezier::{bernstein, joint, BezierCurve, Joint};
pub use check::{continuity, max_deviation, Continuity};
pub use curve::{
    curve_joints, g1_curve, tangent, CurveFailure, CurveWeighting, FailureKind, G1Curve,
};
pub use error::SmoothError;
pub use normals::{visible_normals, AdjustedNormals};
pub use split3::{three_split, three_split_with, MicroPatch, SplitOptions, SplitSurface};
pub use tessellate::tessellate;
pub use triangle::{tri_index, BezierTriangle};
