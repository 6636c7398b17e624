//! Validity of polygons and triangle meshes (Veltkamp 1992, §4.2: a boundary is a simple
//! polygon, or a closed polyhedron whose triangles meet only in shared vertices and edges),
//! decided with exact predicates only.
//!
//! - [`check_polygon`]: is a vertex cycle a simple polygon, and which points does it miss
//!   ([`PolygonCheck`]); [`is_simple_brute`] is its all-pairs oracle;
//! - [`self_intersections`]: the pairs of triangles of a mesh that meet although they must not;
//!   [`self_intersections_trusting`] skips pairs of two triangles known to be faces of one
//!   tetrahedralization ([`faces_of_tetrahedra`] finds them); [`self_intersections_brute`] is
//!   the all-pairs oracle;
//! - [`remove_spikes`]: the repair of zero-area spikes (collinear back-tracks) and repeated
//!   consecutive vertices of a ring, area unchanged exactly ([`SpikeRepair`]).
//!
//! The checks are used by the boundary engines on their results and by `morpho info --check`
//! on any mesh or polygon.

mod grid;
mod mesh;
mod pair;
mod polygon;
mod spikes;

pub use mesh::{
    faces_of_tetrahedra, self_intersections, self_intersections_brute, self_intersections_trusting,
};
pub use polygon::{check_polygon, is_simple_brute, PolygonCheck};
pub use spikes::{remove_spikes, SpikeRepair};
