//! Smooth shapes (Veltkamp 1992, ch. 8–9; Hamann 1991, ch. 6; NOTES parts B and E): Bézier
//! curves and triangles, the closed G¹ cubic curve through a polygon, the cubic three-split G¹
//! surface and Hamann's side-vertex surface through a closed triangle mesh with its vertex
//! normals, with independent continuity checks and a tessellation.
//!
//! Deviations from the text (each documented in its file): the three-split's singular edges
//! (mirror-symmetric sides, where (9.4) has no solution) are detected and reported, and
//! built with a degree-elevated quadratic boundary and the ratio `e1/e0` that makes (9.3)
//! consistent, in closed form (see [`three_split`]); an edge the three-split still leaves non-G¹ (inflected edges above all) is bisected at a point of its first-pass boundary curve and the three-split re-run on the refined mesh (`edgesplit.rs`, up to two rounds; the patch list then has 3(k+1) patches for a macro triangle with k split edges); the 2D curve's failing vertices are
//! repaired with the uniform weighting (NOTES B.2), and its joint bound is relative to the
//! rounding of the stored control points ([`Joint::rounding`]). The side-vertex surface
//! ([`side_vertex`]) uses the corrections of NOTES E: squared blending weights
//! ([`side_vertex_weights`]), elevated conic weights `(1+2ω)/3` ([`Conic`]), the boundary normal
//! by an interpolated rotation angle ([`ConicEdge`]), and a stated recipe for the generalized
//! (inflected) conics the text leaves open.
//!
//! Reflection lines (V §8.4), the visual continuity check, are drawn by the rasterizer
//! ([`crate::render::ReflectionLines`]); the bench is `examples/bench_smooth.rs`. The six-split
//! (V §9.8, [`six_split`]) is rebuilt from its conditions (NOTES B.7): a C¹ piecewise-quadratic
//! boundary, a prescribed piecewise-linear normal field along every macro edge (linear along
//! the whole edge where the edge is not inflected, after Peters 1990), each side's cross
//! derivative solved independently against it, and the Powell–Sabin C¹ interior; see its
//! file. The two-split (V §9.7, [`two_split`], experimental as NOTES B.6 recommends) pairs
//! macro triangles across an edge where that avoids thin three-split micro triangles, builds
//! each pair C¹ over its unfolded domain and meets its three-split neighbours on a prescribed
//! linear normal field per outer edge (the text's Farin ratio construction is not given);
//! see its file. The CLI is `morpho smooth` (curve, three-split, two-split, six-split,
//! side-vertex).

mod bezier;
mod check;
mod conic;
mod curve;
mod dual;
mod edgesplit;
mod error;
mod normals;
mod side_vertex;
mod singular;
mod split2;
mod split3;
mod split6;
mod tessellate;
mod transversal;
mod triangle;

pub use bezier::{bernstein, joint, BezierCurve, Joint};
pub use check::{
    continuity, max_deviation, non_g1_causes, reversed_normals, side_vertex_continuity, Continuity,
    NonG1Causes,
};
pub use conic::{side_vertex_weights, Conic, ConicEdge};
pub use curve::{
    curve_joints, g1_curve, tangent, CurveFailure, CurveWeighting, FailureKind, G1Curve,
};
pub use error::SmoothError;
pub use normals::{visible_normals, AdjustedNormals};
pub use side_vertex::{side_vertex, SideVertexOptions, SideVertexSurface};
pub use split2::{two_split, Rejections, TwoSplit};
pub use split3::{three_split, three_split_with, MicroPatch, SplitOptions, SplitSurface};
pub use split6::six_split;
pub use tessellate::tessellate;
pub use triangle::{tri_index, BezierTriangle};
