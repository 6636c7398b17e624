//! The refusals of the render family: unknown names, slices out of range, pictures too large.

/// Why a picture was refused. Each variant carries the offending input; the `Display` text is
/// the one-line message the CLI prints after `error: `. Write failures are not here: saving
/// goes through [`crate::io`] and fails with [`crate::Error::Io`].
///
/// ```
/// use morpho::render::{Colormap, RenderError};
/// let err = "rainbow".parse::<Colormap>().unwrap_err();
/// assert!(matches!(&err, RenderError::UnknownColormap { name } if name == "rainbow"));
/// assert_eq!(err.to_string(), r#"unknown colour map "rainbow" (use viridis, coolwarm or grey)"#);
/// ```
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RenderError {
    /// A colour map name that is not viridis, coolwarm or grey.
    #[error("unknown colour map {name:?} (use viridis, coolwarm or grey)")]
    UnknownColormap {
        /// The name given.
        name: String,
    },
    /// An axis name that is not x, y, z (or 0, 1, 2).
    #[error("unknown axis {name:?} (use x, y or z)")]
    UnknownAxis {
        /// The name given.
        name: String,
    },
    /// A volume with a zero dimension.
    #[error("volume has no samples")]
    EmptyVolume {
        /// The dimensions of the volume.
        dims: [usize; 3],
    },
    /// A slice index beyond the volume.
    #[error("slice index {index} along {axis} is out of range (0..{len})")]
    SliceOutOfRange {
        /// The index given.
        index: usize,
        /// The axis name (`x`, `y` or `z`).
        axis: &'static str,
        /// Samples along that axis.
        len: usize,
    },
    /// A domain subdivision with no sub-box along some axis, or k = 0.
    #[error("need at least one sub-box per axis and k >= 1")]
    SubBoxes {
        /// Sub-boxes per axis.
        boxes: [usize; 3],
        /// Subdivisions per sub-box edge.
        k: usize,
    },
    /// Gap ratios that are negative or not finite.
    #[error("gap ratios must be finite and >= 0")]
    GapRatios {
        /// The ratios given (per axis).
        ratios: [f64; 3],
    },
    /// A domain subdivision that would have more than `max` triangles.
    #[error("too many triangles (more than {max}); use fewer sub-boxes or a smaller k")]
    TooManyBoxTriangles {
        /// The largest number of triangles allowed.
        max: usize,
    },
    /// Grid planes that would have more triangles than allowed.
    #[error("too many triangles ({triangles}); use a larger plane stride")]
    TooManyPlaneTriangles {
        /// Triangles the planes would have.
        triangles: usize,
    },
    /// A function name that is not one of [`crate::render::Formula::ALL`].
    #[error("unknown function {name:?} (use hamann-exp or hamann-cos)")]
    UnknownFunction {
        /// The name given.
        name: String,
    },
    /// A sampling grid with no cell or too many (1 ≤ n ≤ 1024 cells per axis).
    #[error("grid of {n} cells per axis: need 1 to 1024")]
    GridSize {
        /// Cells per axis asked for.
        n: usize,
    },
    /// A volume whose samples are all NaN or infinite.
    #[error("volume has no finite value ({samples} samples)")]
    NoFiniteValues {
        /// Number of samples.
        samples: usize,
    },
    /// A 3D view of a volume with a single sample (or no extent) along an axis.
    #[error("volume has one sample (no extent) along {axis}: a 3D view needs at least two; use --view slices")]
    FlatVolume {
        /// The axis name.
        axis: &'static str,
    },
    /// A view parameter out of its range.
    #[error("{what}")]
    ViewParameter {
        /// What is wrong, naming the parameter.
        what: String,
    },
    /// The PNG encoder refused the image (not a write failure).
    #[error("PNG: {reason}")]
    Png {
        /// The encoder's message.
        reason: String,
    },
    /// The volume itself was refused.
    #[error(transparent)]
    Volume(#[from] crate::volume::VolumeError),
}
