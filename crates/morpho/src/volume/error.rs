//! The refusals of the volume family ([`crate::volume::Volume::validate`],
//! [`crate::volume::isosurface()`]).

/// Why a volume or an isosurface request was refused. Each variant carries the offending input;
/// the `Display` text is the one-line message the CLI prints after `error: `.
///
/// ```
/// use morpho::volume::{Volume, VolumeError};
/// let err = Volume::new([2, 2, 2], [0.0; 3], [1.0; 3], vec![0.0; 7]).unwrap_err();
/// assert!(matches!(err, VolumeError::SampleCount { found: 7, needed: 8, .. }));
/// assert_eq!(err.to_string(), "volume has 7 samples but dims [2, 2, 2] need 8");
/// ```
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum VolumeError {
    /// The product of the dimensions does not fit in `usize`.
    #[error("volume dimensions overflow")]
    DimsOverflow {
        /// The dimensions (samples along x, y, z).
        dims: [usize; 3],
    },
    /// The number of samples differs from the product of the dimensions.
    #[error("volume has {found} samples but dims {dims:?} need {needed}")]
    SampleCount {
        /// Samples present.
        found: usize,
        /// The dimensions.
        dims: [usize; 3],
        /// Their product.
        needed: usize,
    },
    /// Uniform axes with a non-finite origin or a spacing that is not finite and positive.
    #[error("spacing must be finite and positive, origin finite")]
    BadSpacing {
        /// The origin given.
        origin: [f64; 3],
        /// The spacing given.
        spacing: [f64; 3],
    },
    /// Per-index coordinates of an axis whose count differs from the dimension.
    #[error("axis {axis} has {found} coordinates, dims say {needed}")]
    AxisLength {
        /// The axis (0 = x, 1 = y, 2 = z).
        axis: usize,
        /// Coordinates given.
        found: usize,
        /// The dimension along that axis.
        needed: usize,
    },
    /// Per-index coordinates of an axis that are not finite and strictly increasing.
    #[error("axis {axis} coordinates must be finite and strictly increasing")]
    AxisNotIncreasing {
        /// The axis (0 = x, 1 = y, 2 = z).
        axis: usize,
    },
    /// The contour level is NaN or infinite.
    #[error("contour level must be finite")]
    NonFiniteLevel {
        /// The level given.
        level: f64,
    },
    /// An axis has more than 2²⁰ samples (the vertex keys of the extraction hold 20 bits per
    /// axis).
    #[error("volume axes longer than 2^20 samples")]
    AxisTooLong {
        /// The dimensions of the volume.
        dims: [usize; 3],
    },
    /// A block given to [`crate::volume::isosurface_block`] that does not fit its grid (outside
    /// it, missing the samples its cells or their gradients need, too large a grid).
    #[error("block: {reason}")]
    BadBlock {
        /// What is wrong with the block.
        reason: String,
    },
    /// Blocks given to [`crate::volume::stitch_blocks`] that disagree: two blocks own the same
    /// cell, or give different positions or normals to the contour point of one grid entity
    /// (blocks of different volumes, levels or options).
    #[error("blocks disagree: {reason}")]
    BlocksDisagree {
        /// Where they disagree.
        reason: String,
    },
    /// The contour surface would have more than 2³¹ − 1 vertices.
    #[error("contour has {vertices} vertices, more than 2^31 - 1")]
    TooManyVertices {
        /// Vertices counted when the extraction stopped.
        vertices: usize,
    },
}
