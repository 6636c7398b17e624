//! Rectilinear volumes f(x, y, z) sampled on a grid (Hamann 1991, ch. 2–3).

mod error;
mod gradient;
mod isosurface;

pub use error::VolumeError;
pub use gradient::{axis_coords, gradient_at, mesh_normals, GradientOperator};
pub use isosurface::{
    extract_part, isosurface, largest_part, IsoMethod, IsoOptions, IsoResult, NormalMethod,
};

/// Data type of the samples as stored in a file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum DType {
    /// Unsigned 8-bit integer.
    U8,
    /// Signed 16-bit integer.
    I16,
    /// Unsigned 16-bit integer.
    U16,
    /// Signed 32-bit integer.
    I32,
    /// 32-bit float.
    F32,
    /// 64-bit float.
    F64,
}

impl DType {
    /// Bytes per sample.
    pub fn size(self) -> usize {
        match self {
            DType::U8 => 1,
            DType::I16 | DType::U16 => 2,
            DType::I32 | DType::F32 => 4,
            DType::F64 => 8,
        }
    }
}

/// Positions of the grid planes along the three axes.
#[derive(Debug, Clone, PartialEq)]
pub enum Axes {
    /// Uniform spacing: coordinate of index i on axis k is `origin[k] + i * spacing[k]`.
    Uniform {
        /// Position of the sample (0, 0, 0).
        origin: [f64; 3],
        /// Distance between neighbouring samples along each axis (positive).
        spacing: [f64; 3],
    },
    /// Per-index coordinates, strictly increasing, `coords[k].len() == dims[k]`.
    Coords([Vec<f64>; 3]),
}

/// A scalar volume on a rectilinear grid. Samples are stored as `f32`, x varying fastest,
/// then y, then z (`data[x + nx * (y + ny * z)]`).
#[derive(Debug, Clone, PartialEq)]
pub struct Volume {
    /// Number of samples along x, y and z.
    pub dims: [usize; 3],
    /// Positions of the grid planes.
    pub axes: Axes,
    /// Samples, x fastest: `data[x + nx * (y + ny * z)]`.
    pub data: Vec<f32>,
    /// Type of the samples in the file they came from.
    pub source_dtype: DType,
}

impl Volume {
    /// A volume with uniform axes. Fails when `data.len()` differs from the product of `dims`.
    pub fn new(
        dims: [usize; 3],
        origin: [f64; 3],
        spacing: [f64; 3],
        data: Vec<f32>,
    ) -> Result<Self, VolumeError> {
        let v = Volume {
            dims,
            axes: Axes::Uniform { origin, spacing },
            data,
            source_dtype: DType::F32,
        };
        v.validate()?;
        Ok(v)
    }
    /// Samples a function on a uniform grid over the box `[lo, hi]`.
    ///
    /// ```
    /// use morpho::volume::Volume;
    /// let v = Volume::from_fn([3, 2, 2], [0.0; 3], [2.0, 1.0, 1.0], |x, y, _| x + 10.0 * y);
    /// assert_eq!(v.len(), 12);
    /// assert_eq!(v.at(2, 1, 0), 12.0); // x = 2, y = 1
    /// assert_eq!(v.coord(0, 1), 1.0); // spacing 1 along x
    /// ```
    pub fn from_fn(
        dims: [usize; 3],
        lo: [f64; 3],
        hi: [f64; 3],
        f: impl Fn(f64, f64, f64) -> f64,
    ) -> Self {
        let sp = |k: usize| {
            if dims[k] > 1 {
                (hi[k] - lo[k]) / (dims[k] - 1) as f64
            } else {
                1.0
            }
        };
        let spacing = [sp(0), sp(1), sp(2)];
        let mut data = Vec::with_capacity(dims[0] * dims[1] * dims[2]);
        for z in 0..dims[2] {
            for y in 0..dims[1] {
                for x in 0..dims[0] {
                    data.push(f(
                        lo[0] + x as f64 * spacing[0],
                        lo[1] + y as f64 * spacing[1],
                        lo[2] + z as f64 * spacing[2],
                    ) as f32);
                }
            }
        }
        Volume {
            dims,
            axes: Axes::Uniform {
                origin: lo,
                spacing,
            },
            data,
            source_dtype: DType::F32,
        }
    }
    /// Number of samples.
    pub fn len(&self) -> usize {
        self.dims[0] * self.dims[1] * self.dims[2]
    }
    /// True for a volume without samples.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Linear index of sample (x, y, z).
    #[inline]
    pub fn index(&self, x: usize, y: usize, z: usize) -> usize {
        x + self.dims[0] * (y + self.dims[1] * z)
    }
    /// Sample at (x, y, z).
    #[inline]
    pub fn at(&self, x: usize, y: usize, z: usize) -> f32 {
        self.data[self.index(x, y, z)]
    }
    /// Coordinate of grid plane `i` along axis `k`.
    #[inline]
    pub fn coord(&self, k: usize, i: usize) -> f64 {
        match &self.axes {
            Axes::Uniform { origin, spacing } => origin[k] + i as f64 * spacing[k],
            Axes::Coords(c) => c[k][i],
        }
    }
    /// Spacing along each axis (mean spacing for per-index coordinates).
    pub fn spacing(&self) -> [f64; 3] {
        match &self.axes {
            Axes::Uniform { spacing, .. } => *spacing,
            Axes::Coords(c) => {
                let mut s = [1.0; 3];
                for k in 0..3 {
                    if c[k].len() > 1 {
                        s[k] = (c[k][c[k].len() - 1] - c[k][0]) / (c[k].len() - 1) as f64;
                    }
                }
                s
            }
        }
    }
    /// Smallest and largest finite sample (`None` when there is none).
    pub fn value_range(&self) -> Option<(f32, f32)> {
        let mut r: Option<(f32, f32)> = None;
        for &v in &self.data {
            if v.is_finite() {
                r = Some(match r {
                    None => (v, v),
                    Some((a, b)) => (a.min(v), b.max(v)),
                });
            }
        }
        r
    }
    /// Checks sizes, axes and spacing.
    pub fn validate(&self) -> Result<(), VolumeError> {
        let n = self.dims[0]
            .checked_mul(self.dims[1])
            .and_then(|v| v.checked_mul(self.dims[2]))
            .ok_or(VolumeError::DimsOverflow { dims: self.dims })?;
        if n != self.data.len() {
            return Err(VolumeError::SampleCount {
                found: self.data.len(),
                dims: self.dims,
                needed: n,
            });
        }
        match &self.axes {
            Axes::Uniform { origin, spacing } => {
                if origin.iter().chain(spacing).any(|v| !v.is_finite())
                    || spacing.iter().any(|&s| s <= 0.0)
                {
                    return Err(VolumeError::BadSpacing {
                        origin: *origin,
                        spacing: *spacing,
                    });
                }
            }
            Axes::Coords(c) => {
                for k in 0..3 {
                    if c[k].len() != self.dims[k] {
                        return Err(VolumeError::AxisLength {
                            axis: k,
                            found: c[k].len(),
                            needed: self.dims[k],
                        });
                    }
                    if c[k]
                        .windows(2)
                        .any(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater))
                        || c[k].iter().any(|v| !v.is_finite())
                    {
                        return Err(VolumeError::AxisNotIncreasing { axis: k });
                    }
                }
            }
        }
        Ok(())
    }
}
