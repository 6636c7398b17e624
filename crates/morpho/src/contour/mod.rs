//! Regions from rated samples: the linear-time *external contour* of a coloured triangulation
//! (Dorgerloh, Lüssem, Pilouk, Wirtgen, *Some Tools for Modeling and Analysis of Surfaces*, §3),
//! in 2D and, following §3.7, on tetrahedrizations in 3D.
//!
//! The three phases of the paper's introduction:
//! 1. *triangulation* — done by the caller (a Delaunay triangulation of the sample positions);
//!    every function here takes the triangulation as input;
//! 2. *rating* — [`rate_triangles`], [`classify`]: one number per triangle (mean, min, max, median or an area-weighted
//!    mean of the vertex values), black when it is above (or below) a threshold;
//! 3. *contour* — [`external_contour`]: the coloured dual graph (§3.1), `extend` (§3.2),
//!    `hollow_out` (§3.3), `remove_v_ext` and the black components (§3.4), and
//!    `contour_of_component` (§3.5 and the Appendix), all in O(n) time and memory.
//!
//! # What is computed
//!
//! Let S be the set of triangulation edges between a black triangle and a white triangle or the
//! exterior. The *external contour* is the set of cycles of S that are not enclosed by another
//! cycle of S. At a vertex where several cycles of S meet, S does not say by itself how its
//! edges form cycles; morpho follows the paper's construction, which fixes the rule:
//!
//! * a *black component* (§3.4) is a set of black triangles together with the white triangles
//!   they enclose (white triangles that cannot reach the exterior through white triangles sharing
//!   an edge), connected through shared edges;
//! * each black component has exactly one external cycle, its outer boundary, and that cycle is a
//!   simple polygon (counter-clockwise, black on the left). Two components that touch at a single
//!   vertex give two cycles that share that vertex (the "bow tie" is split at the vertex); a
//!   component whose two arms touch at a vertex around an enclosed white pocket gives one cycle
//!   that passes the vertex once, the pocket is a hole.
//!
//! Equivalently: follow the edges of S with black on the left, at each vertex turn into the next
//! edge of S around the *white* side, and cut each closed walk at vertices it visits twice; the
//! cycles so obtained that are not enclosed by another are exactly the output (this is the
//! brute-force oracle of the tests).
//!
//! Beyond the paper, [`boundary_regions`] gives the *complete* boundary: one polygon with holes
//! per set of black triangles connected through edges (outer ring counter-clockwise, holes
//! clockwise, each ring simple; rings of one polygon may touch at single vertices), and both
//! functions can drop regions smaller than an area.
//!
//! In 3D ([`external_surface`]) the same steps on tetrahedra give the closed boundary surfaces of the black
//! components that are not enclosed by another, as outward-oriented triangles.
//!
//! [`contour_triangulated_2d`] and [`contour_triangulated_3d`] run rating, colouring and contour on rated samples given their triangulation
//! (value column by name, samples without a value skipped, duplicates averaged);
//! [`contour_samples`] puts the Delaunay triangulation in front. The results are written by
//! [`crate::io::write_contour_2d`] (GeoJSON, a JSON list of cycles) and drawn by
//! [`crate::render::contour_svg`].
//!
//! ```
//! use morpho::contour::external_contour;
//! use morpho::geom::Point2;
//! // A square of four triangles around its centre (vertex 4); two opposite ones are black.
//! let p = [
//!     Point2::new(0.0, 0.0), Point2::new(2.0, 0.0), Point2::new(2.0, 2.0),
//!     Point2::new(0.0, 2.0), Point2::new(1.0, 1.0),
//! ];
//! let tri = [[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]];
//! let c = external_contour(&tri, &p, &[true, false, true, false]).unwrap();
//! // Two black triangles touching at the centre: two cycles, split at the shared vertex.
//! assert_eq!(c.cycles.len(), 2);
//! assert!(c.cycles.iter().all(|cy| cy.len() == 3 && cy.contains(&4)));
//! ```

mod cycles;
mod dual;
mod error;
mod pipeline;
mod rating;
mod samples;
mod tet;

pub use cycles::{boundary_regions, external_contour, external_contour_with};
pub use dual::simplex_neighbors;
pub use error::ContourError;
pub use pipeline::{
    contour_triangulated_2d, contour_triangulated_3d, select_samples, PlaneContour, SampleContour,
    SampleOptions, SampleTriangulation2, SampleTriangulation3, SelectedSamples, SpaceContour,
};
pub use rating::{classify, rate_tetrahedra, rate_triangles, Rating};
pub use samples::contour_samples;
pub use tet::{external_surface, external_surface_with, Surface3};

use crate::geom::Point2;
use crate::mesh::{Polygon, Shapes2};

/// Options of the 2D contour functions.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContourOptions {
    /// Regions whose area (outer ring minus holes) is below this are dropped (0 keeps all).
    pub min_area: f64,
}

/// A polygon of a [`Contour2`]: an outer ring and its holes, as indices into `Contour2::cycles`.
#[derive(Debug, Clone, PartialEq)]
pub struct Region2 {
    /// Index of the outer ring (counter-clockwise) in `cycles`.
    pub outer: u32,
    /// Indices of the holes (clockwise) in `cycles`.
    pub holes: Vec<u32>,
    /// Area of the region (outer ring minus holes).
    pub area: f64,
    /// True when the region is part of the external contour: it touches the white region that
    /// is connected to the exterior. (Always true for [`external_contour`].)
    pub external: bool,
}

/// The contour of a coloured triangulation.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Contour2 {
    /// Closed rings as vertex indices of the triangulation (not repeated at the end). Outer rings
    /// are counter-clockwise, holes clockwise; black is always on the left.
    pub cycles: Vec<Vec<u32>>,
    /// The polygons: for [`external_contour`] one per black component, without holes.
    pub regions: Vec<Region2>,
    /// Number of black components (kept regions).
    pub components: usize,
    /// Number of black triangles.
    pub black: usize,
    /// Number of triangles.
    pub triangles: usize,
    /// Regions dropped because their area was below `min_area`.
    pub dropped: usize,
}

impl Contour2 {
    /// The regions as polygons with coordinates (rings not closed explicitly; outer rings
    /// counter-clockwise, holes clockwise).
    pub fn to_shapes2(&self, points: &[Point2]) -> Shapes2 {
        let ring = |c: u32| -> Vec<Point2> {
            self.cycles[c as usize]
                .iter()
                .map(|&v| points[v as usize])
                .collect()
        };
        Shapes2 {
            polygons: self
                .regions
                .iter()
                .map(|r| Polygon {
                    rings: std::iter::once(r.outer)
                        .chain(r.holes.iter().copied())
                        .map(ring)
                        .collect(),
                })
                .collect(),
            polylines: vec![],
        }
    }
}

/// Signed area of a ring of vertex indices (shoelace; positive when counter-clockwise).
///
/// ```
/// use morpho::contour::ring_area;
/// use morpho::geom::Point2;
/// let p = [Point2::new(0.0, 0.0), Point2::new(1.0, 0.0), Point2::new(0.0, 1.0)];
/// assert_eq!(ring_area(&[0, 1, 2], &p), 0.5); // counter-clockwise
/// assert_eq!(ring_area(&[0, 2, 1], &p), -0.5);
/// ```
pub fn ring_area(ring: &[u32], points: &[Point2]) -> f64 {
    let n = ring.len();
    let mut s = 0.0;
    for i in 0..n {
        let a = points[ring[i] as usize];
        let b = points[ring[(i + 1) % n] as usize];
        s += (a.x - b.x) * (a.y + b.y);
    }
    0.5 * s
}
