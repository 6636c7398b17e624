//! [`SmoothError`]: why a smooth curve or surface construction refused its input.

/// A refusal of the `smooth` family, naming the offending input. The `Display` text is the
/// one-line message the CLI prints after `error: `.
///
/// ```
/// use morpho::geom::Point2;
/// use morpho::smooth::{g1_curve, CurveWeighting, SmoothError};
/// let p = [(0.0, 0.0), (1.0, 0.0), (1.0, 0.0), (0.0, 1.0)].map(|(x, y)| Point2::new(x, y));
/// let e = g1_curve(&p, true, CurveWeighting::Length).unwrap_err();
/// assert!(matches!(e, SmoothError::RepeatedVertex { index: 2 }));
/// ```
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SmoothError {
    /// A point with a NaN or infinite coordinate.
    #[error("smooth: vertex {index} has a non-finite coordinate")]
    NonFinite {
        /// Index of the vertex.
        index: usize,
    },
    /// Fewer vertices than the construction needs (2 for an open polyline, 3 for a closed
    /// polygon, 4 for a closed mesh).
    #[error("smooth: {got} vertices, at least {need} needed")]
    TooFew {
        /// Vertices given.
        got: usize,
        /// Vertices needed.
        need: usize,
    },
    /// Two consecutive polygon vertices coincide (no tangent can be estimated there).
    #[error("smooth: vertex {index} repeats the vertex before it")]
    RepeatedVertex {
        /// Index of the second of the two equal vertices.
        index: usize,
    },
    /// The polygon doubles back exactly at a vertex (angle 0): no weighting gives G¹ there.
    #[error("smooth: the polygon doubles back on itself at vertex {index}")]
    DoublesBack {
        /// Index of the vertex.
        index: usize,
    },
    /// A mesh edge has no opposite half-edge: the mesh is not closed.
    #[error("smooth: the mesh is not closed (edge {a}-{b} has one side only)")]
    NotClosed {
        /// First vertex of the edge.
        a: u32,
        /// Second vertex of the edge.
        b: u32,
    },
    /// A directed edge used twice: non-manifold or inconsistently oriented.
    #[error("smooth: edge {a}-{b} is non-manifold or its triangles are inconsistently oriented")]
    NonManifold {
        /// First vertex of the edge.
        a: u32,
        /// Second vertex of the edge.
        b: u32,
    },
    /// A triangle with a repeated vertex or zero area.
    #[error("smooth: triangle {triangle} has zero area")]
    ZeroArea {
        /// Index of the triangle.
        triangle: usize,
    },
    /// A triangle refers to a vertex that does not exist.
    #[error("smooth: triangle {triangle} refers to a missing vertex")]
    BadIndex {
        /// Index of the triangle.
        triangle: usize,
    },
    /// Vertex normals of the wrong count, non-unit, non-finite or zero.
    #[error("smooth: vertex {vertex} has no usable normal")]
    BadNormal {
        /// Index of the vertex.
        vertex: usize,
    },
    /// A parameter out of range (density 0, …).
    #[error("smooth: {what}")]
    Parameter {
        /// What is wrong, in words.
        what: String,
    },
}
