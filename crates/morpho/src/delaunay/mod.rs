//! Delaunay triangulations in 2D ([`d2`]), 3D ([`d3`]) and d dimensions ([`dd`]), convex hulls
//! and Voronoi duals ([`voronoi`]) (Veltkamp 1992 §2.2.8–2.2.9; Dorgerloh et al. §2).

pub mod cdt;
pub mod d2;
pub mod d3;
pub mod dd;
pub mod voronoi;
