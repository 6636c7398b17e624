//! The refusals of the curvature family ([`super::surface_curvature`],
//! [`super::volume_curvature`], [`super::trivariate_curvature`]).

use crate::mesh::MeshError;

/// Why a curvature computation was refused. Each variant names the offending input; the
/// `Display` text is the one-line message the CLI prints after `error: `.
///
/// ```
/// use morpho::curvature::{surface_curvature, CurvatureError, NormalSource, SurfaceOptions};
/// use morpho::mesh::generate;
/// let opts = SurfaceOptions { normals: NormalSource::File, ..Default::default() };
/// let err = surface_curvature(&generate::cube(), &opts).unwrap_err();
/// assert!(matches!(err, CurvatureError::NoFileNormals));
/// ```
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CurvatureError {
    /// The mesh breaks its invariants (non-finite coordinate, index out of range, …).
    #[error("{0}")]
    Mesh(#[from] MeshError),
    /// Normals from the file were asked for, but the mesh has none.
    #[error("the mesh has no per-vertex normals (nx, ny, nz); use estimated normals")]
    NoFileNormals,
    /// Given normals (or gradients) whose count differs from the number of vertices (samples).
    #[error("{given} normals given for {vertices} vertices")]
    NormalCount {
        /// Normals given.
        given: usize,
        /// Vertices (or samples) of the input.
        vertices: usize,
    },
    /// A neighbourhood of zero rings.
    #[error("the ring size must be at least 1 (got 0)")]
    ZeroRing,
    /// A volume with fewer than two samples along an axis has no trivariate platelets.
    #[error("volume has {samples} sample(s) along axis {axis} (dims {dims:?}); curvature needs at least 2")]
    FlatAxis {
        /// The dimensions.
        dims: [usize; 3],
        /// The axis (0 = x, 1 = y, 2 = z).
        axis: usize,
        /// Samples along it.
        samples: usize,
    },
    /// Sample values whose count differs from the product of the dimensions.
    #[error("{found} samples for dims {dims:?}")]
    SampleCount {
        /// Samples given.
        found: usize,
        /// The dimensions.
        dims: [usize; 3],
    },
    /// A NaN or infinite sample (or grid coordinate) in a volume.
    #[error("volume sample {index} is not finite")]
    NonFiniteSample {
        /// Linear index (x fastest) of the sample, or of the coordinate for grid planes.
        index: usize,
    },
    /// Grid coordinates that are not strictly increasing along an axis.
    #[error("grid coordinates along axis {axis} are not strictly increasing")]
    BadCoordinates {
        /// The axis.
        axis: usize,
    },
}
