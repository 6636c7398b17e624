//! Geometric graphs on point sets (Veltkamp 1992, ch. 2) and the γ-neighbourhood graph (ch. 3).
//!
//! # Entry points
//! One function per dimension, `graph_<dimension>`: [`graph_2d`] and [`graph_3d`] build the
//! graph of any [`Kind`]; each kind that has a parameter carries it (`Kind::BetaLune(b)`,
//! `Kind::Gamma(c0, c1)`, …), validated by [`Kind::validate`]. The result is a [`Graph`]:
//! edges in 2D, edges or triangles in 3D, with the γ-values of every simplex for the γ kinds
//! (test them against other parameters with [`in_gamma`] / [`in_gamma_range`] without
//! rebuilding). Refusals are [`GraphError`]s.
//!
//! # Complexity
//! Every kind is built from the Delaunay triangulation ([`crate::delaunay`], O(N log N)
//! expected). After it: closest pairs, NNG, hull, Delaunay, Gabriel, α (a ≤ 0), circle-based β
//! and γ with parameters ≥ 0: O(N); EMST (Borůvka on the Delaunay edges): O(N log N) worst case;
//! RNG and lune-based β (b > 0): O(N·k) with k the points in the box of a lune; SIG: O(N·k) with
//! k the points near an edge; ∞-SG: O(N) filter plus O(N) per surviving edge; α (a > 0): O(h³)
//! over the h hull vertices; γ beyond the Delaunay triangulation (a parameter < 0):
//! (2D) the partner searches of `fast::beyond_dt_2d`; in 3D Θ(N³) cheap tests where vertices are "open" (near the hull, samples
//! of a surface: `beyond3`'s module documentation), refused above [`triple_limit`] candidate
//! triples (10⁸ by default, overridable). In 3D, γ with a parameter −1 (nearly every triple of points, the brute force of
//! V Thm 3.1) and degenerate (coplanar) input are limited to [`BRUTE_LIMIT_3D`] points, α with
//! a > 0 to [`ALPHA_HULL_LIMIT_3D`] hull vertices (O(h⁴) worst case). Degenerate groups are
//! output-sensitive: the Θ(g³) triples of g cospherical or cocircular points cost O(1) each
//! (`fast::SphereGroup`, `fast::CircleGroup`), and a hull facet of g coplanar points costs
//! O(g² log g) plus O(1) per empty triangle ([`facets`]) for the hull and the γ kinds with a
//! parameter −1, nothing more for the other kinds (it cost O(g⁴) for every triangle kind).
//!
//! Every decision is exact (`geom::predicates`, `geom::distance`); point sets at extreme scales
//! are first multiplied by an exact power of two.
//!
//! ```rust
//! use morpho::graphs::{graph_2d, Kind};
//! use morpho::geom::Point2;
//! // the corners of a unit square: EMST has n − 1 edges, the hull 4, the Delaunay graph 5
//! let p = [[0., 0.], [1., 0.], [1., 1.], [0., 1.]].map(|[x, y]| Point2::new(x, y));
//! assert_eq!(graph_2d(&p, Kind::Emst)?.edges.len(), 3);
//! assert_eq!(graph_2d(&p, Kind::Hull)?.edges.len(), 4);
//! assert_eq!(graph_2d(&p, Kind::Delaunay)?.edges.len(), 5);
//! # Ok::<(), morpho::graphs::GraphError>(())
//! ```

// Other families use these files by path (`crate::graphs::fast::candidates_3d`, …).
pub(crate) mod beyond3;
pub(crate) mod brute;
mod build;
mod build3;
mod distance;
mod error;
pub(crate) mod facets;
pub(crate) mod fast;
pub(crate) mod gamma;
mod lens_tree;
mod limit;
mod lune;

pub use build::{graph_2d, Graph, Kind, ALPHA_HULL_LIMIT_3D, BRUTE_LIMIT_3D};
pub use build3::graph_3d;
pub use error::GraphError;
pub use gamma::{in_gamma, in_gamma_range};
pub use limit::{parse_count, set_triple_limit, triple_limit, DEFAULT_TRIPLE_LIMIT};

#[cfg(test)]
mod tests;
