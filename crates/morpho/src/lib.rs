//! # morpho — computational morphology
//!
//! Turns scattered points, samples with values and scalar volumes into valid shapes (boundary
//! polygons, closed meshes, contour surfaces, region contours), then approximates, localizes,
//! smooths and analyses them. The methods are those of Veltkamp (1992), Hamann (1991) and
//! Dorgerloh et al.; each module cites the section it implements.
//!
//! The library never prints and never exits; every fallible function returns [`Result`].
//!
//! | module | what |
//! |---|---|
//! | [`geom`] | points, exact predicates, bounding boxes, smallest enclosing disc/ball |
//! | [`mesh`] | polygons, triangle/tetrahedral meshes, point sets, topology |
//! | [`contour`] | external contours of coloured triangulations (Dorgerloh et al.) |
//! | [`delaunay`] | Delaunay triangulations, hulls, Voronoi |
//! | [`volume`] | rectilinear volumes |
//! | [`graphs`] | geometric graphs and the γ-neighbourhood graph (Veltkamp ch. 2–3) |
//! | [`boundary`] | boundaries through scattered points: γ-constriction in 2D and 3D (Veltkamp ch. 4–5) |
//! | [`io`] | file formats |
//! | [`render`] | SVG and PNG pictures |
//! | [`samples`] | generated sample data (chalice outline, Shepp–Logan phantom, borehole field) |
//! | [`util`] | sentinels, the id hasher and maps, seeded generators, Hilbert keys |

#![warn(missing_docs)]
#![deny(rustdoc::broken_intra_doc_links)]
// Geometry code indexes coordinates by axis on purpose.
#![allow(clippy::needless_range_loop)]

pub mod boundary;
pub mod contour;
pub mod curvature;
pub mod delaunay;
pub mod error;
pub mod flint;
pub mod geom;
pub mod graphs;
pub mod io;
pub mod mesh;
pub mod reduce;
pub mod render;
pub mod samples;
pub mod smooth;
pub mod util;
pub mod viewer;
pub mod volume;

pub use error::{Error, Location, Result};

/// Engine pieces for benches, examples and tests of internal invariants. **No stability
/// promise**: anything here may change or disappear in any release.
#[doc(hidden)]
pub mod internals {
    // --- delaunay, graphs (f-tri) ---
    /// Delaunay engine pieces: the symbolically perturbed predicates, the insertion-order test.
    pub mod delaunay {
        pub use crate::delaunay::d2::{
            incircle_sos, lex_cmp, triangulate_split, triangulate_with_insertion_seed, Split,
        };
        /// The 3D engines: the sequential one, and the split-and-merge one with its counters.
        pub use crate::delaunay::d3::triangulate as triangulate_3d_sequential;
        pub use crate::delaunay::dd::perturbed_insphere;
        pub use crate::delaunay::par3::{
            predicted_seam_share, triangulate_split as triangulate_3d_split,
            triangulate_split_stats as triangulate_3d_split_stats, SplitStats, PAR_MIN,
        };
    }
    /// Graph engine pieces: the brute-force oracles and the γ-interval of one simplex.
    pub mod graphs {
        pub use crate::graphs::beyond3::beyond_dt_3d;
        pub use crate::graphs::fast::coords2;
        pub use crate::graphs::gamma::{
            center_interval_2d, center_interval_3d, def_contains_2d, def_contains_3d,
            CenterInterval,
        };
        /// Every graph straight from its definition (the oracles of the tests).
        pub mod brute {
            pub use crate::graphs::brute::*;
        }
    }
    // --- end delaunay, graphs ---
    // --- geom (f-rest): the exact fallbacks, checked against the adaptive predicates ---
    pub use crate::geom::exact::{insphere_exact, insphere_sign, orient3d_exact, orient_sign};
    /// Stage counters of the in-circle cascade (feature `predicate-stats`).
    pub use crate::geom::predicates::stats as predicate_stats;
    // --- end f-rest ---
    // --- boundary (f-bnd): engines of boundary_2d / boundary_3d ---
    pub use crate::boundary::internals::*;
}

/// The library version.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");
