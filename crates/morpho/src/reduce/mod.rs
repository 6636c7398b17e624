//! Curvature-driven triangle reduction (Hamann 1991, ch. 5; notes D): the least significant
//! triangle (flat and well-shaped first, ω = σρ) is replaced by one point fitted to the
//! surface, repeatedly, keeping the genus.
//!
//! * [`reduce`] with [`ReduceOptions`]: Algorithm 5.1 with the stops of [`Stop`] (a
//!   percentage kept, a triangle count, an RMS or maximum tolerance), the new point of
//!   [`NewPoint`] (bivariate or implicit quadric fit), frozen boundaries (Rem. 5.8) and the
//!   height-field mode of Table 5.1 ([`Domain::HeightField`]). Every output keeps the parts,
//!   boundary loops and Euler characteristic, is manifold and consistently oriented, and has
//!   no new self-intersection (exact tests, see `engine` docs).
//! * The pieces of the method: [`classify_corona`] (Defs 5.3–5.5), [`half_plane_test`]
//!   ((5.18)), [`angle_weight`] / [`triangle_weight`] (Defs 5.11–5.13),
//!   [`graph_quadratic_curvature`] (Thm 5.5, corrected) and [`quadric_curvature`] (Thm 5.6,
//!   corrected), [`line_intersection`] ((5.33)).
//! * [`mesh_distance`] (RMS at the input's vertices, sampled symmetric Hausdorff) and
//!   [`carry_vertex_data`] for reports and outputs.
//! * [`table51`]: the Table 5.1 protocol (9 functions on the 51×51 grid).

mod corona;
mod distance;
mod engine;
mod error;
mod heap;
mod point;
mod qem;
mod retri;
mod state;
pub mod table51;
mod track;
mod weight;

pub use corona::{classify_corona, half_plane_test, CoronaClass};
pub use distance::{carry_vertex_data, mesh_distance, MeshDistance, SurfaceIndex};
pub use engine::{reduce, Domain, NewTriangles, Order, ReduceOptions, Reduced, Stop, StopReason};
pub use error::ReduceError;
pub use point::{
    graph_quadratic_curvature, line_intersection, quadric_curvature, NewPoint, Quadric,
};
pub use weight::{angle_weight, triangle_weight};
