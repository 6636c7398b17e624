//! The refusals of the reduction family ([`super::reduce`]): meshes the method cannot take
//! (Hamann 1991, §5.1 assumes a manifold, consistently oriented triangulation) and stopping
//! rules that make no sense.

use crate::mesh::MeshError;

/// Why a reduction was refused. Each variant names the offending input; the `Display` text is
/// the one-line message the CLI prints after `error: `.
///
/// ```
/// use morpho::reduce::{reduce, ReduceError, ReduceOptions, Stop};
/// use morpho::mesh::generate;
/// let opts = ReduceOptions { stop: Stop::Keep(0.0), ..Default::default() };
/// let err = reduce(&generate::icosphere(2), &opts).unwrap_err();
/// assert!(matches!(err, ReduceError::BadPercentage { .. }));
/// ```
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ReduceError {
    /// The mesh breaks its invariants (non-finite coordinate, index out of range, …).
    #[error("{0}")]
    Mesh(#[from] MeshError),
    /// The curvature fit refused the mesh or its normals.
    #[error("{0}")]
    Curvature(#[from] crate::curvature::CurvatureError),
    /// A mesh without triangles.
    #[error("the mesh has no triangles")]
    Empty,
    /// A triangle with a repeated vertex index or collinear corners.
    #[error("triangle {triangle} is degenerate (repeated vertex or zero area)")]
    DegenerateTriangle {
        /// Index of the triangle.
        triangle: usize,
    },
    /// An edge shared by more than two triangles.
    #[error("edge {a}-{b} is shared by more than two triangles (non-manifold)")]
    NonManifoldEdge {
        /// One end.
        a: u32,
        /// The other end.
        b: u32,
    },
    /// Two triangles traverse their common edge in the same direction.
    #[error("edge {a}-{b} is used twice in the same direction (inconsistent orientation)")]
    InconsistentOrientation {
        /// One end.
        a: u32,
        /// The other end.
        b: u32,
    },
    /// A vertex whose triangles do not form one fan (two cones touching at a point).
    #[error("vertex {vertex} is non-manifold (its triangles form more than one fan)")]
    NonManifoldVertex {
        /// Index of the vertex.
        vertex: u32,
    },
    /// `Stop::Keep` outside (0, 100] (or not finite).
    #[error("percentage to keep must be in (0, 100], got {percent}")]
    BadPercentage {
        /// The percentage given.
        percent: f64,
    },
    /// `Stop::Triangles` above the input's triangle count.
    #[error("target of {target} triangles is above the input's {input}")]
    CountAboveInput {
        /// The target.
        target: usize,
        /// Triangles of the input.
        input: usize,
    },
    /// A tolerance that is negative or not finite, or no tolerance at all.
    #[error("tolerance must be finite and >= 0, got {tolerance}")]
    BadTolerance {
        /// The tolerance given.
        tolerance: f64,
    },
    /// `Domain::HeightField` on a mesh that is not the graph of a function over xy: some
    /// triangle is not counter-clockwise in the xy projection.
    #[error("triangle {triangle} is not counter-clockwise over the xy plane: not a height field")]
    NotAHeightField {
        /// Index of the triangle.
        triangle: usize,
    },
    /// Curvature normals given with the wrong count.
    #[error("{given} normals given for {vertices} vertices")]
    NormalCount {
        /// Normals given.
        given: usize,
        /// Vertices of the mesh.
        vertices: usize,
    },
}
