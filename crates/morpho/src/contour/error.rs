//! The refusals of the contour family: bad colourings, broken triangulations, bad values.

/// Why a contour computation was refused. Each variant carries the offending input; the
/// `Display` text is the one-line message the CLI prints after `error: `.
///
/// ```
/// use morpho::contour::{external_contour, ContourError};
/// use morpho::geom::Point2;
/// let p = [Point2::new(0.0, 0.0), Point2::new(1.0, 0.0), Point2::new(0.0, 1.0)];
/// // one triangle, but two colours
/// let err = external_contour(&[[0, 1, 2]], &p, &[true, false]).unwrap_err();
/// assert!(matches!(err, ContourError::ColourCount { colours: 2, simplices: 1, .. }));
/// assert_eq!(err.to_string(), "2 colours for 1 triangles");
/// ```
#[non_exhaustive]
#[derive(Debug, thiserror::Error)]
pub enum ContourError {
    /// The colouring does not have one entry per simplex.
    #[error("{colours} colours for {simplices} {kind}")]
    ColourCount {
        /// Colours given.
        colours: usize,
        /// Simplices of the triangulation.
        simplices: usize,
        /// `"triangles"` or `"tetrahedra"`.
        kind: &'static str,
    },
    /// A point has a NaN or infinite coordinate.
    #[error("point {index} has a non-finite coordinate")]
    NonFinitePoint {
        /// Index of the point.
        index: usize,
    },
    /// A triangle whose corners are collinear.
    #[error("triangle {triangle} has zero area")]
    ZeroArea {
        /// Index of the triangle.
        triangle: usize,
    },
    /// A tetrahedron whose corners are coplanar.
    #[error("tetrahedron {tetrahedron} has zero volume")]
    ZeroVolume {
        /// Index of the tetrahedron.
        tetrahedron: usize,
    },
    /// More simplices than `u32` indices can address.
    #[error("too many simplices")]
    TooManySimplices {
        /// Simplices given.
        count: usize,
    },
    /// A simplex refers to a vertex that does not exist.
    #[error("simplex {simplex} refers to vertex {vertex}, but there are only {vertices} vertices")]
    VertexOutOfRange {
        /// Index of the simplex.
        simplex: usize,
        /// The vertex it names.
        vertex: u32,
        /// Number of vertices.
        vertices: usize,
    },
    /// A simplex names one vertex twice.
    #[error("simplex {simplex} repeats vertex {vertex}")]
    RepeatedVertex {
        /// Index of the simplex.
        simplex: usize,
        /// The repeated vertex.
        vertex: u32,
    },
    /// Two simplices lie on the same side of their common facet.
    #[error(
        "simplices {first} and {second} lie on the same side of their common facet \
         (overlapping or inconsistently oriented)"
    )]
    SameSide {
        /// Index of one simplex.
        first: usize,
        /// Index of the other.
        second: usize,
    },
    /// A facet shared by more than two simplices.
    #[error("a facet of simplex {simplex} is shared by {count} simplices (not a manifold)")]
    NonManifoldFacet {
        /// Index of one simplex with that facet.
        simplex: usize,
        /// How many simplices share it.
        count: usize,
    },
    /// The neighbour array given does not have one row per simplex.
    #[error("neighbour array and simplices differ in length")]
    NeighbourCount {
        /// Rows of the neighbour array.
        neighbours: usize,
        /// Simplices.
        simplices: usize,
    },
    /// A neighbour given does not share the facet it stands for.
    #[error("neighbour {facet} of simplex {simplex} is inconsistent with the simplices")]
    BadNeighbour {
        /// Index of the simplex.
        simplex: usize,
        /// The facet (the vertex opposite it).
        facet: usize,
    },
    /// Tracing the contour found that the input is not a valid planar triangulation (the reason
    /// says which step failed).
    #[error("{reason}")]
    InvalidTriangulation {
        /// What was found, e.g. `"boundary does not close (invalid triangulation)"`.
        reason: &'static str,
    },
    /// The value column asked for does not exist.
    #[error("no column '{name}' (columns: {columns})")]
    NoSuchColumn {
        /// The name asked for.
        name: String,
        /// The columns there are, comma separated.
        columns: String,
    },
    /// The samples have no value column at all.
    #[error("the samples have no value column (CSV header x,y,value or x,y,z,value)")]
    NoValueColumn,
    /// Several value columns and none chosen.
    #[error("several value columns; choose one with --value (columns: {columns})")]
    SeveralValueColumns {
        /// The columns there are, comma separated.
        columns: String,
    },
    /// A value column with another length than the point set.
    #[error("column {name} has the wrong length")]
    ColumnLength {
        /// The column's name.
        name: String,
    },
    /// The map from samples to triangulation vertices is inconsistent with the values or the
    /// triangulation.
    #[error("{reason}")]
    BadVertexMap {
        /// What was found, e.g. `"vertex map refers to a missing vertex"`.
        reason: &'static str,
    },
    /// A rating name that is not one of mean, min, max, median, area-mean.
    #[error("unknown rating '{name}' (use mean, min, max, median or area-mean)")]
    UnknownRating {
        /// The name given.
        name: String,
    },
    /// Not one value per vertex.
    #[error("{values} values for {vertices} vertices")]
    ValueCount {
        /// Values given.
        values: usize,
        /// Vertices.
        vertices: usize,
    },
    /// A value that is NaN or infinite.
    #[error("value of sample {index} is not finite")]
    NonFiniteValue {
        /// Index of the sample.
        index: usize,
    },
    /// The triangulation of the samples failed (a lower family's error).
    #[error(transparent)]
    Lower(#[from] Box<crate::Error>),
}
