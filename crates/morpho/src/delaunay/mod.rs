//! Delaunay triangulations in 2D, 3D and d dimensions, constrained triangulations, convex hulls
//! and Voronoi duals (Veltkamp 1992 §2.2.8–2.2.9; Dorgerloh et al. §2).
//!
//! # Entry points
//! One naming convention: `<what>_<dimension>` with the dimension as `2d`, `3d` or `nd`.
//!
//! | capability | function | result |
//! |---|---|---|
//! | Delaunay triangulation of points in the plane | [`triangulate_2d`] | [`Delaunay2`] |
//! | Delaunay tetrahedralization of points in space | [`triangulate_3d`] | [`Delaunay3`] |
//! | Delaunay triangulation in d = 2 … [`MAX_DIM`] dimensions | [`triangulate_nd`] | [`DelaunayD`] |
//! | constrained Delaunay triangulation (segments) | [`triangulate_constrained_2d`] | [`Cdt2`] |
//! | triangles of a simple polygon's interior | [`triangulate_polygon_2d`] | `Vec<[u32; 3]>` |
//! | Voronoi diagram (dual of a [`Delaunay2`]) | [`voronoi_2d`] | [`Voronoi2`] |
//!
//! The convex hull comes with every triangulation: [`Delaunay2::hull`] (vertex cycle),
//! [`Delaunay3::hull`] (outward triangles), [`DelaunayD::hull`] (facets), [`Cdt2::hull`]; the
//! hull as a graph is [`crate::graphs::Kind::Hull`].
//!
//! [`triangulate_3d`] uses both cores on large inputs: with more than one rayon thread and at
//! least `par3::PAR_MIN` points it splits the sorted points in two, triangulates the halves in
//! parallel and merges them with an exact certificate (`par3.rs`); the tetrahedron set is the
//! same, their order differs from the one-thread order (each order is deterministic).
//! [`triangulate_2d`] stays on one thread: its two-thread split (`par2.rs`, the same design)
//! gave only 1.10–1.16× on two idle cores for 1.5× the CPU and is reached through
//! `morpho::internals::delaunay::triangulate_split` (bench `examples/bench_delaunay2d_par.rs`).
//!
//! All decisions use exact predicates (symbolic perturbation breaks co-circular and
//! co-spherical ties), so the result is a function of the point *set*: independent of the input
//! order and of the absolute scale. Every function refuses bad input with a
//! [`DelaunayError`] naming it (no panics on user data).
//!
//! ```rust
//! use morpho::delaunay::triangulate_2d;
//! use morpho::geom::Point2;
//! // a square with its centre: 4 triangles, Euler's relation V − E + F = 1 (no outer face)
//! let p = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0], [1.0, 1.0]].map(|[x, y]| Point2::new(x, y));
//! let d = triangulate_2d(&p)?;
//! assert_eq!(d.triangles.len(), 4);
//! assert_eq!(d.points.len() as i64 - d.edges().len() as i64 + d.triangles.len() as i64, 1);
//! # Ok::<(), morpho::delaunay::DelaunayError>(())
//! ```

// Other families use these files by path (`crate::delaunay::d3::FACE_OF`, …): crate-visible.
pub(crate) mod cdt;
pub(crate) mod d2;
pub(crate) mod d3;
pub(crate) mod dd;
mod error;
mod merge2;
pub(crate) mod par2;
pub(crate) mod par3;
#[cfg(test)]
mod test_sets;
pub(crate) mod voronoi;

pub use cdt::{
    triangulate_constrained_2d, triangulate_polygon_interior as triangulate_polygon_2d, Cdt2,
};
pub use d2::{triangulate as triangulate_2d, Delaunay2, Location, TrianglesAround};
pub use d3::{Delaunay3, Face3, FACE_OF};
pub use dd::{triangulate_d as triangulate_nd, DelaunayD, MAX_DIM};
pub use error::DelaunayError;
pub use par3::triangulate_auto as triangulate_3d;
pub use voronoi::{voronoi as voronoi_2d, Voronoi2, VoronoiCell, VoronoiEdge};
