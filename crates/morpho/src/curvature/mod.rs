//! Curvature of triangle meshes and of graphs of trivariate functions (Hamann 1991, ch. 4).
//!
//! * [`surface_curvature`]: κ₁ ≤ κ₂, principal directions, H, K and the absolute curvature
//!   per mesh vertex, by the osculating-paraboloid fit over the platelet (H §4.2), or, the
//!   default for estimated normals, by the curvature of a jet (degree 4) fitted over the 2-ring
//!   (`SurfaceFit::Jet`; `surface.rs` module doc); [`surface_curvature_scalars`] the same
//!   without the directions and normals.
//! * [`trivariate_curvature`] / [`volume_curvature`]: κ₁ ≤ κ₂ ≤ κ₃, H and K per grid point
//!   of the graph of a trivariate function, by the 6×6 fit in R⁴ over the 6-tetrahedra
//!   decomposition (H §4.3).
//! * [`tables`]: Tables 4.1 and 4.2 of the thesis, recomputed (benchmarks and tests).
//!
//! Undetermined fits are NaN, flagged and counted, never a silent number.

mod error;
mod fit;
mod surface;
pub mod tables;
mod trivariate;

pub use error::CurvatureError;
pub use surface::{
    surface_curvature, surface_curvature_scalars, NormalSource, SurfaceCurvature, SurfaceFit,
    SurfaceOptions, VertexStatus, SURFACE_MAX_COND,
};
pub use trivariate::{
    trivariate_curvature, volume_curvature, Gradients, VolumeCurvature, VOLUME_MAX_COND,
};
