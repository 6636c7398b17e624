//! The refusals of the mesh family: meshes and point sets that break their invariants, and
//! surfaces that cannot be oriented.

/// Why a mesh or point set was refused. Each variant carries the offending input; the `Display`
/// text is the one-line message the CLI prints after `error: `.
///
/// ```
/// use morpho::geom::Point3;
/// use morpho::mesh::{MeshError, TriMesh};
/// let m = TriMesh::new(vec![Point3::origin(); 3], vec![[0, 1, 3]]);
/// let err = m.validate().unwrap_err();
/// assert!(matches!(err, MeshError::VertexOutOfRange { triangle: 0, vertex: 3, vertices: 3 }));
/// assert_eq!(err.to_string(), "triangle 0 refers to vertex 3, but there are only 3 vertices");
/// ```
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MeshError {
    /// More vertices than `u32` indices can address.
    #[error("more than 2^32-1 vertices")]
    TooManyVertices {
        /// Vertices given.
        vertices: usize,
    },
    /// A vertex with a NaN or infinite coordinate.
    #[error("vertex {vertex} has a non-finite coordinate")]
    NonFiniteVertex {
        /// Index of the vertex.
        vertex: usize,
    },
    /// A triangle that refers to a vertex that does not exist.
    #[error(
        "triangle {triangle} refers to vertex {vertex}, but there are only {vertices} vertices"
    )]
    VertexOutOfRange {
        /// Index of the triangle.
        triangle: usize,
        /// The vertex it names.
        vertex: u32,
        /// Number of vertices.
        vertices: usize,
    },
    /// Vertex normals present but not one per vertex.
    #[error("normal count differs from vertex count")]
    NormalCount {
        /// Normals given.
        normals: usize,
        /// Vertices.
        vertices: usize,
    },
    /// A per-vertex or per-face property whose length is not the vertex or triangle count.
    #[error("{per} property {name} has the wrong length")]
    PropertyLength {
        /// `"vertex"` or `"face"`.
        per: &'static str,
        /// The property's name.
        name: String,
    },
    /// A point set that is neither 2D nor 3D.
    #[error("points must be 2D or 3D, not {dim}D")]
    Dimension {
        /// The dimension given.
        dim: usize,
    },
    /// A flat coordinate array whose length is not a multiple of the dimension.
    #[error("coordinate count is not a multiple of dim")]
    CoordinateCount {
        /// Coordinates given.
        coords: usize,
        /// The dimension.
        dim: usize,
    },
    /// A point with a NaN or infinite coordinate.
    #[error("point {point} has a non-finite coordinate")]
    NonFinitePoint {
        /// Index of the point.
        point: usize,
    },
    /// A value column whose length is not the number of points.
    #[error("column {name} has the wrong length")]
    ColumnLength {
        /// The column's name.
        name: String,
    },
    /// [`crate::mesh::orient_consistently`]: an index out of range.
    #[error("triangle refers to vertex {vertex}, but there are only {vertices} vertices")]
    IndexOutOfRange {
        /// The vertex named.
        vertex: u32,
        /// Number of vertices.
        vertices: usize,
    },
    /// [`crate::mesh::orient_consistently`]: a connected surface that is not orientable.
    #[error("the surface containing triangle {triangle} is not orientable (e.g. a Möbius strip)")]
    NotOrientable {
        /// A triangle of that surface.
        triangle: usize,
    },
}
