//! Why a triangulation refused its input: [`DelaunayError`].

/// A refusal of the Delaunay family, naming the offending input.
///
/// `Display` is the one-line message the CLI prints after `error:`; the crate error
/// [`crate::Error::Delaunay`] adds the file name.
///
/// ```rust
/// use morpho::delaunay::{triangulate_2d, DelaunayError};
/// use morpho::geom::Point2;
/// let e = triangulate_2d(&[Point2::new(0.0, f64::NAN)]).unwrap_err();
/// assert!(matches!(e, DelaunayError::NonFinite { index: 0, .. }));
/// assert_eq!(e.to_string(), "point 0 has a non-finite coordinate (0, NaN)");
/// ```
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DelaunayError {
    /// No input points (`dim`: 2, 3 or the dimension of [`crate::delaunay::triangulate_nd`]).
    #[error("{}", if *dim == 2 { "Delaunay triangulation of an empty point set" } else { "no points" })]
    NoPoints {
        /// Dimension of the triangulation asked for.
        dim: usize,
    },
    /// More points than the vertex indices (`u32`, with room for the construction) can hold.
    #[error("{}", if *dim == 2 { "too many points for a 2D Delaunay triangulation" } else { "too many points" })]
    TooManyPoints {
        /// Number of input points.
        found: usize,
        /// Dimension of the triangulation asked for.
        dim: usize,
    },
    /// Input point `index` (0-based) has a NaN or infinite coordinate.
    #[error("{}", non_finite(*index, coords))]
    NonFinite {
        /// 0-based index of the point in the input.
        index: usize,
        /// Its coordinates (2D only; empty otherwise).
        coords: Vec<f64>,
    },
    /// A 2D coordinate too small relative to the largest for the exact floating-point
    /// predicates (below 2⁻¹⁸⁰ times the largest magnitude).
    #[error(
        "2D Delaunay: coordinate ({}, {}) is non-zero but below 2^-180 times the largest \
         coordinate magnitude; exact predicates cannot be guaranteed",
        point[0],
        point[1]
    )]
    CoordinateTooSmall {
        /// The offending point.
        point: [f64; 2],
    },
    /// The 2D predicates contradicted each other (coordinates outside the exact range).
    #[error("2D Delaunay: inconsistent predicates (coordinates outside the exact range)")]
    InconsistentPredicates,
    /// The construction reached its simplex limit (3D: 2³⁰ tetrahedra, dD: 2²⁸ simplices).
    #[error("{}", too_many_simplices(*dim, *limit))]
    TooManySimplices {
        /// Dimension of the triangulation.
        dim: usize,
        /// The limit that was reached.
        limit: usize,
    },
    /// [`crate::delaunay::triangulate_nd`] in a dimension outside 2 ..= `max`.
    #[error("dimension {dim} (supported: 2 to {max})")]
    UnsupportedDimension {
        /// The dimension asked for.
        dim: usize,
        /// The largest supported dimension ([`crate::delaunay::MAX_DIM`]).
        max: usize,
    },
    /// The flat coordinate array of [`crate::delaunay::triangulate_nd`] is not a multiple of
    /// the dimension.
    #[error("{coords} coordinates are not a multiple of dimension {dim}")]
    DimensionMismatch {
        /// Length of the coordinate array.
        coords: usize,
        /// The dimension given.
        dim: usize,
    },
    /// Constraint segment number `segment` names an input point that does not exist.
    #[error(
        "constraint segment {segment} ({}, {}) refers to a point that does not exist ({points} points)",
        ends[0],
        ends[1]
    )]
    SegmentOutOfRange {
        /// Position of the segment in the list given.
        segment: usize,
        /// Its two input indices.
        ends: [u32; 2],
        /// Number of input points.
        points: usize,
    },
    /// A constraint segment given by vertex indices names a vertex that does not exist.
    #[error(
        "constraint segment ({}, {}) refers to a vertex that does not exist ({vertices} vertices)",
        ends[0],
        ends[1]
    )]
    VertexOutOfRange {
        /// The two vertex indices.
        ends: [u32; 2],
        /// Number of vertices.
        vertices: usize,
    },
    /// Two constraint segments cross (no Steiner points are invented).
    #[error(
        "constraint segments {first} ({}, {}) and {second} ({}, {}) cross",
        first_ends[0],
        first_ends[1],
        second_ends[0],
        second_ends[1]
    )]
    CrossingSegments {
        /// Number of the earlier segment.
        first: u32,
        /// Its two ends (as given).
        first_ends: [u32; 2],
        /// Number of the segment being inserted.
        second: u32,
        /// Its two ends (as given).
        second_ends: [u32; 2],
    },
    /// A constraint segment crosses an earlier constraint that can no longer be named.
    #[error(
        "constraint segment {segment} ({}, {}) crosses an earlier constraint",
        ends[0],
        ends[1]
    )]
    CrossesConstraint {
        /// Number of the segment being inserted.
        segment: u32,
        /// Its two ends (as given).
        ends: [u32; 2],
    },
    /// A polygon with fewer than `needed` vertices.
    #[error("polygon interior: {found} vertices, a polygon needs at least {needed}")]
    PolygonTooFewVertices {
        /// Number of vertices given.
        found: usize,
        /// The minimum (3).
        needed: usize,
    },
    /// Polygon vertex `vertex` is point `point`, which does not exist.
    #[error(
        "polygon interior: vertex {vertex} is point {point}, which does not exist ({points} points)"
    )]
    PolygonVertexOutOfRange {
        /// Position in the cycle.
        vertex: usize,
        /// The point index given.
        point: u32,
        /// Number of points.
        points: usize,
    },
    /// Polygon vertex `vertex` repeats an earlier vertex (same index or same coordinates).
    #[error(
        "polygon interior: not a simple polygon, vertex {vertex} (point {point}) repeats an earlier vertex"
    )]
    PolygonRepeatedVertex {
        /// Position in the cycle.
        vertex: usize,
        /// Its point index.
        point: u32,
    },
    /// All polygon vertices lie on one line.
    #[error("polygon interior: all vertices are collinear (zero area)")]
    PolygonCollinear,
    /// Two polygon edges cross (the source names them).
    #[error("polygon interior: not a simple polygon: {0}")]
    PolygonEdgesCross(Box<DelaunayError>),
    /// Polygon edge `edge` passes through another polygon vertex.
    #[error(
        "polygon interior: not a simple polygon, edge {edge} ({}, {}) passes through another vertex",
        ends[0],
        ends[1]
    )]
    PolygonEdgeThroughVertex {
        /// Position of the edge (from vertex `edge` to `edge + 1`).
        edge: usize,
        /// Its two point indices.
        ends: [u32; 2],
    },
    /// The polygon's inside does not have `n − 2` triangles (it is not simple).
    #[error(
        "polygon interior: not a simple polygon ({found} interior triangles, expected {expected})"
    )]
    PolygonNotSimple {
        /// Interior triangles found.
        found: usize,
        /// `n − 2`.
        expected: usize,
    },
    /// A broken invariant of the construction: a bug, not bad input (CLI exit code 1).
    #[error("{what}")]
    Internal {
        /// What broke.
        what: &'static str,
    },
}

fn non_finite(index: usize, coords: &[f64]) -> String {
    // 2D names the point 0-based with its coordinates; 3D and dD count from 1 (as before)
    if let [x, y] = coords {
        format!("point {index} has a non-finite coordinate ({x}, {y})")
    } else {
        format!("point {} has a non-finite coordinate", index + 1)
    }
}

fn too_many_simplices(dim: usize, limit: usize) -> String {
    if dim == 3 {
        format!("more than {limit} tetrahedra (input too large or too degenerate)")
    } else {
        "more than 2^28 simplices".to_string()
    }
}

impl DelaunayError {
    /// True for refusals of the input (everything but [`DelaunayError::Internal`]).
    pub fn is_input_error(&self) -> bool {
        !matches!(self, DelaunayError::Internal { .. })
    }
}
