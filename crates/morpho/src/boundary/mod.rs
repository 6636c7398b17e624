//! Boundary through all scattered points (Veltkamp 1992, ch. 4–5): the γ-graph constriction
//! and the two comparison methods, in 2D and 3D. One entry point per dimension, each with an
//! options type whose method variant carries its own parameters:
//!
//! [`boundary_2d`]`(points, &`[`Options2`]`)` returns a simple polygon through every input point
//! when it finds one, or the best simple polygon found together with the points it leaves out:
//! - [`Method2::Gamma`] — constriction of γ(\[-1,1\],\[0,1\]) by the γ-indicator (V §5.2,
//!   Algorithm 5.1), with the Hamiltonicity fallback of §5.4 (γ(\[-1,1\],\[c,1\]), c < 0, by
//!   adaptive augmentation; [`CParam`]) and constraints (§5.7);
//! - [`Method2::MinAreaChange`] — Boissonnat's minimal area change constriction of the
//!   Delaunay triangulation (V §4.3.3, Eq. 4.1);
//! - [`Method2::VoronoiSkeleton`] — O'Rourke et al.'s shortest Voronoi skeleton (V §4.3.4).
//!
//! [`boundary_3d`]`(points, &`[`Options3`]`)` constricts the 3D Delaunay tetrahedralization
//! (V §5.3) to a closed genus-0 triangle mesh through (ideally) every point; when that
//! constriction locks with points inside, a general engine continues with γ(\[-1,1\],\[c,1\])
//! triangles, c = −0.1 … −1, added where needed (V §5.4) — first on the live tetrahedra within
//! four neighbour steps of the vertices off the boundary (the rest of the object is locked for
//! the Delaunay constriction), on the whole object when that does not free every vertex; keep
//! triangles (V §5.7) that are not Delaunay faces are constricted by the general engine from
//! the hull ([`Method3::Gamma`], [`Method3::MinAreaChange`]). [`Method3::VoronoiSkeleton`]
//! grows the shortest Voronoi skeleton of Delaunay tetrahedra instead (V §4.3.4, §5.6). The
//! result is checked with [`crate::mesh::topology::analyze`] and the exact self-intersection
//! test ([`crate::mesh::validity::self_intersections_trusting`]: pairs of two Delaunay faces
//! are skipped, they meet only in common faces; every other pair is tested).
//!
//! The 2D result is checked, never assumed: [`check_polygon`] decides simplicity and coverage
//! with exact predicates. Duplicate input points map to one vertex (the first input index of
//! the group stands for it in the polygon; the others count as on the boundary).
//!
//! Layout (by the thesis's sections): `d2/` and `d3/` each hold the engine state of one run
//! (`Engine2`, `Engine3`, which own their steps and `finish`), the constriction (V §5.2,
//! §5.3), the adaptive augmentation (V §5.4) and the constraints (V §5.7); the γ-indicator
//! and the minimal-area-change key are in `indicator.rs`, the Voronoi skeletons (V §4.3.4) in
//! `voronoi_skeleton*.rs`.
//!
//! Preconditions: at least three distinct, not all collinear, finite points in 2D, four not
//! coplanar in 3D (otherwise no boundary exists and an error is returned).

pub(crate) mod d2;
pub(crate) mod d3;
mod error;
mod indicator;
pub(crate) mod voronoi_skeleton;
pub(crate) mod voronoi_skeleton3;

pub use crate::mesh::validity::{check_polygon, PolygonCheck};
pub use d2::{
    boundary_2d, constriction_steps_2d, triangulate_polygon, Boundary2, Method2, Options2,
};
pub use d3::{boundary_3d, Boundary3, Method3, Options3, Until};
pub use error::BoundaryError;
pub use indicator::Key;

/// The engine pieces that benches, examples and tests reach through [`crate::internals`] (no
/// stability promise).
pub(crate) mod internals {
    pub use super::d2::constrict::{constrict_dt, region_cycle, DtState};
    pub use super::d3::constrict::{
        constrict_3d, constrict_3d_keep, constrict_3d_with, min_area_change_3d, removal_key,
        Constriction3,
    };
    pub use super::d3::general::General3;
}

/// The γ-graph parameter c of γ(\[-1,1\],\[c,1\]) used for constriction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CParam {
    /// Start with the Delaunay graph (c = 0); when constriction locks, add the edges of
    /// c = −0.1, −0.2, …, −1 inside the current boundary one step at a time (V §5.4 adaptive
    /// augmentation) until every point is on the boundary.
    Auto,
    /// Constrict γ(\[-1,1\],\[c,1\]) from the convex hull (c ∈ [−1, 0]; c = 0 is the Delaunay
    /// graph, no fallback).
    Fixed(f64),
}
