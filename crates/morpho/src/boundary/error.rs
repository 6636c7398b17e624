//! [`BoundaryError`]: why [`super::boundary_2d`] or [`super::boundary_3d`] refused its input.

/// A refusal of the boundary constructions, naming the offending input. The `Display` text is
/// the one-line message the CLI prints after `error: `.
///
/// ```rust
/// use morpho::boundary::{boundary_2d, BoundaryError, CParam, Method2, Options2};
/// use morpho::geom::Point2;
/// let p = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)].map(|(x, y)| Point2::new(x, y));
/// let o = Options2 { method: Method2::Gamma { c: CParam::Fixed(0.5), keep: vec![] } };
/// let e = boundary_2d(&p, &o).unwrap_err();
/// assert!(matches!(e, BoundaryError::COutOfRange { c } if c == 0.5));
/// assert_eq!(e.to_string(), "boundary: c = 0.5 is not in [-1, 0]");
/// // wrapped in the crate's error (which adds the file path when known)
/// assert_eq!(morpho::Error::from(e).to_string(), "boundary: c = 0.5 is not in [-1, 0]");
/// ```
#[non_exhaustive]
#[derive(Debug, thiserror::Error)]
pub enum BoundaryError {
    /// A 2D point with a NaN or infinite coordinate (`index`: the first such input point).
    #[error("boundary: non-finite coordinate")]
    NonFinite {
        /// Input index of the point.
        index: usize,
    },
    /// Fewer than three distinct 2D points, or all collinear: no simple polygon exists.
    #[error("boundary: fewer than 3 distinct points or all collinear: no simple polygon exists")]
    NoPolygon,
    /// The 3D Delaunay tetrahedralization has no tetrahedron (fewer than four points, or all
    /// coplanar): no closed surface exists.
    #[error("boundary: no closed surface exists ({reason})")]
    NoSurface {
        /// Why the tetrahedralization is empty (from the Delaunay engine).
        reason: String,
    },
    /// [`super::CParam::Fixed`]`(c)` with c outside [−1, 0].
    #[error("boundary: c = {c} is not in [-1, 0]")]
    COutOfRange {
        /// The value given.
        c: f64,
    },
    /// A keep edge names a point that does not exist.
    #[error("boundary: keep edge ({}, {}) refers to a point that does not exist ({points} points)", edge[0], edge[1])]
    KeepEdgeOutOfRange {
        /// Position of the edge in the keep list.
        index: usize,
        /// The edge (input indices).
        edge: [u32; 2],
        /// Number of input points.
        points: usize,
    },
    /// A keep edge joins two copies of one point.
    #[error("boundary: keep edge ({}, {}) joins two copies of one point", edge[0], edge[1])]
    KeepEdgeDuplicate {
        /// Position of the edge in the keep list.
        index: usize,
        /// The edge (input indices).
        edge: [u32; 2],
    },
    /// A keep edge passes through a point that is not one of its ends (exact test).
    #[error("boundary: keep edge {index} passes through another point")]
    KeepEdgeThroughPoint {
        /// Position of the edge in the keep list.
        index: usize,
    },
    /// Two keep edges cross (exact test).
    #[error("boundary: keep edges cross each other")]
    KeepEdgesCross {
        /// Positions of the two edges in the keep list.
        edges: [usize; 2],
    },
    /// A keep triangle names a point that does not exist.
    #[error("boundary: keep triangle {triangle:?} refers to a point that does not exist")]
    KeepTriangleOutOfRange {
        /// Position of the triangle in the keep list.
        index: usize,
        /// The triangle (input indices).
        triangle: [u32; 3],
        /// Number of input points.
        points: usize,
    },
    /// A keep triangle has two copies of one point among its corners.
    #[error("boundary: keep triangle {triangle:?} has two copies of one point")]
    KeepTriangleDuplicate {
        /// Position of the triangle in the keep list.
        index: usize,
        /// The triangle (input indices).
        triangle: [u32; 3],
    },
    /// A keep triangle is degenerate (its corners collinear; exact test).
    #[error("boundary: keep triangle {vertices:?} is degenerate")]
    KeepTriangleDegenerate {
        /// Position of the triangle in the keep list.
        index: usize,
        /// Its corners as vertices of the tetrahedralization (duplicates merged; the message
        /// has always printed these).
        vertices: [u32; 3],
    },
    /// Two keep triangles meet beyond a shared vertex or edge (exact test).
    #[error("boundary: keep triangles intersect each other")]
    KeepTrianglesIntersect {
        /// Positions of the two triangles in the keep list.
        triangles: [usize; 2],
    },
    /// Keep edges or triangles (`what`) with the Voronoi skeleton method, which takes none
    /// (raised by callers that read a method name and a keep list separately, like the CLI).
    #[error("boundary: keep {what} are supported by the gamma and min-area-change methods")]
    KeepUnsupported {
        /// `"edges"` or `"triangles"`.
        what: &'static str,
    },
    /// The Delaunay triangulation of the points refused them.
    #[error(transparent)]
    Delaunay(#[from] crate::delaunay::DelaunayError),
    /// An error of another lower family.
    #[error(transparent)]
    Lower(#[from] Box<crate::Error>),
}

impl From<crate::Error> for BoundaryError {
    fn from(e: crate::Error) -> Self {
        BoundaryError::Lower(Box::new(e))
    }
}

impl BoundaryError {
    /// Whether the input (not the machine) is at fault; all refusals are, except a lower
    /// family's error that says otherwise.
    pub fn is_input_error(&self) -> bool {
        match self {
            BoundaryError::Lower(e) => e.is_input_error(),
            BoundaryError::Delaunay(e) => e.is_input_error(),
            _ => true,
        }
    }
}
