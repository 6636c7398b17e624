//! Rectilinear volumes f(x, y, z) sampled on a grid (Hamann 1991, ch. 2–3).

mod error;
mod gradient;
mod isosurface;

pub use error::VolumeError;
// `Orientation` is defined below, beside `Volume`.
pub use gradient::{axis_coords, gradient_at, mesh_normals, GradientOperator};
pub use isosurface::{
    extract_part, isosurface, isosurface_block, largest_part, stitch_blocks, IsoBlock, IsoMethod,
    IsoOptions, IsoResult, IsoStream, NormalMethod, StreamPiece, StreamSummary, VolumeGrid,
    INTERIOR_REF,
};

/// Smallest and largest finite value of `data`, widening `start` (`None`: no finite value
/// yet) — so ranges of consecutive pieces of a volume combine into the whole volume's.
pub fn finite_range(data: &[f32], start: Option<(f32, f32)>) -> Option<(f32, f32)> {
    let mut r = start;
    for &v in data {
        if v.is_finite() {
            r = Some(match r {
                None => (v, v),
                Some((a, b)) => (a.min(v), b.max(v)),
            });
        }
    }
    r
}

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
    /// Where the grid sits in the scanner's or patient's space (NRRD `space`, `space
    /// directions`; MHD `TransformMatrix`, `AnatomicalOrientation`). Default: axis-aligned,
    /// no named space.
    pub orientation: Orientation,
}

/// The orientation of a uniform grid in its world space (issue 17 item 11).
///
/// Convention (that of NRRD, ITK and 3D Slicer): the world position of sample (i, j, k) is
/// `origin + i·spacing[0]·d[0] + j·spacing[1]·d[1] + k·spacing[2]·d[2]`, where `d[a]` is the
/// unit direction of grid axis a ([`Orientation::directions`]) and `origin`, `spacing` are
/// those of [`Axes::Uniform`]. The world axes are those of [`Orientation::space`]: NRRD names
/// them (`left-posterior-superior` = LPS: +x towards the patient's left, +y posterior, +z
/// superior; `right-anterior-superior` = RAS), MetaImage files are LPS (ITK's convention), and
/// morpho writes what it read. Contour surfaces ([`isosurface()`]) are returned in world
/// coordinates. Per-index coordinates ([`Axes::Coords`]) carry no directions.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Orientation {
    /// The world space by its NRRD name (`left-posterior-superior`, `right-anterior-superior`,
    /// `left-anterior-superior`, `scanner-xyz`, `3D-right-handed`, …), as in the file; `None`
    /// when the file names none.
    pub space: Option<String>,
    /// MetaImage's `AnatomicalOrientation` code (e.g. `RAI`), as in the file.
    pub anatomical: Option<String>,
    /// Unit direction of each grid axis in world coordinates (`directions[a]` for axis a);
    /// `None`: the identity (axis a along world axis a).
    pub directions: Option<[[f64; 3]; 3]>,
}

impl Orientation {
    /// True when the grid axes are the world axes (no directions, or the identity).
    pub fn is_axis_aligned(&self) -> bool {
        match self.directions {
            None => true,
            Some(d) => (0..3).all(|a| (0..3).all(|b| d[a][b] == if a == b { 1.0 } else { 0.0 })),
        }
    }

    /// The world position of a point given in the axis-aligned frame (`origin + Σ offset_a e_a`):
    /// `origin + Σ offset_a d[a]`.
    pub fn to_world(&self, origin: [f64; 3], p: [f64; 3]) -> [f64; 3] {
        match self.directions {
            None => p,
            Some(d) => {
                let o = [p[0] - origin[0], p[1] - origin[1], p[2] - origin[2]];
                std::array::from_fn(|b| {
                    origin[b] + o[0] * d[0][b] + o[1] * d[1][b] + o[2] * d[2][b]
                })
            }
        }
    }

    /// The determinant of the direction matrix (1 for axis-aligned grids; negative when the
    /// directions mirror, so that triangle windings must flip to keep their orientation).
    pub fn determinant(&self) -> f64 {
        match self.directions {
            None => 1.0,
            Some(d) => {
                d[0][0] * (d[1][1] * d[2][2] - d[1][2] * d[2][1])
                    - d[0][1] * (d[1][0] * d[2][2] - d[1][2] * d[2][0])
                    + d[0][2] * (d[1][0] * d[2][1] - d[1][1] * d[2][0])
            }
        }
    }

    /// Directions from a file: each axis vector (any length, as NRRD `space directions` or a
    /// MetaImage `TransformMatrix` row) normalized; `None` for the identity. Fails when a vector
    /// is zero or not finite, or the three are linearly dependent.
    pub fn unit_directions(v: [[f64; 3]; 3]) -> Result<Option<[[f64; 3]; 3]>, String> {
        let mut d = [[0.0; 3]; 3];
        for a in 0..3 {
            let len = v[a].iter().map(|x| x * x).sum::<f64>().sqrt();
            if !(len.is_finite() && len > 0.0) {
                return Err(format!("the direction of axis {a} is {:?}", v[a]));
            }
            d[a] = v[a].map(|x| x / len);
        }
        let o = Orientation {
            directions: Some(d),
            ..Default::default()
        };
        if o.determinant().abs() < 1e-12 {
            return Err("the axis directions are linearly dependent".into());
        }
        Ok((!o.is_axis_aligned()).then_some(d))
    }

    /// Origin and directions in LPS (MetaImage's world space) when [`Orientation::space`] is
    /// LPS, RAS or LAS (or unnamed: taken as LPS); `None` for any other named space.
    pub fn to_lps(&self, origin: [f64; 3]) -> Option<([f64; 3], [[f64; 3]; 3])> {
        let d = self
            .directions
            .unwrap_or([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
        let flip: [f64; 3] = match self
            .space
            .as_deref()
            .map(str::to_ascii_lowercase)
            .as_deref()
        {
            None | Some("left-posterior-superior") | Some("lps") => [1.0, 1.0, 1.0],
            Some("right-anterior-superior") | Some("ras") => [-1.0, -1.0, 1.0],
            Some("left-anterior-superior") | Some("las") => [1.0, -1.0, 1.0],
            _ => return None,
        };
        // `+ 0.0` turns −0 into 0, so that files do not show "-0.0"
        let o = std::array::from_fn(|b| origin[b] * flip[b] + 0.0);
        let dd = d.map(|row| std::array::from_fn(|b| row[b] * flip[b] + 0.0));
        Some((o, dd))
    }

    /// A vector normal to a surface in the axis-aligned frame, mapped to the world frame (by the
    /// inverse transpose of the direction matrix, then normalized).
    pub fn normal_to_world(&self, n: [f64; 3]) -> [f64; 3] {
        let Some(d) = self.directions else { return n };
        // M maps e_a to d[a]; M^{-T} = cof(M) / det, and cof(M)[b][a] is the cofactor of d[a][b]
        let c = |a: usize, b: usize| {
            let (a1, a2) = ((a + 1) % 3, (a + 2) % 3);
            let (b1, b2) = ((b + 1) % 3, (b + 2) % 3);
            d[a1][b1] * d[a2][b2] - d[a1][b2] * d[a2][b1]
        };
        let det = self.determinant();
        let w: [f64; 3] =
            std::array::from_fn(|b| (0..3).map(|a| c(a, b) * n[a]).sum::<f64>() / det);
        let len = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
        if len > 0.0 && len.is_finite() {
            w.map(|x| x / len)
        } else {
            n
        }
    }
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
            orientation: Orientation::default(),
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
            orientation: Orientation::default(),
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
        finite_range(&self.data, None)
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
        validate_axes(&self.axes, self.dims)?;
        Ok(())
    }
}

/// The check of [`Volume::validate`] on the axes of a grid of `dims` samples: finite origin and
/// positive finite spacing, or per-axis coordinates of the right length, finite and strictly
/// increasing.
pub(crate) fn validate_axes(axes: &Axes, dims: [usize; 3]) -> Result<(), VolumeError> {
    match axes {
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
                if c[k].len() != dims[k] {
                    return Err(VolumeError::AxisLength {
                        axis: k,
                        found: c[k].len(),
                        needed: dims[k],
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
