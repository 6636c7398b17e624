//! Volume views by slicing (Hamann 1991, §2.3): the domain of a trivariate function on a
//! rectilinear grid is cut by the planes `x = c₁`, `y = c₂`, `z = c₃` (normals n₁, n₂, n₃ =
//! the coordinate axes), the function restricted to each plane is sampled on a rectilinear grid
//! and shown
//! 1. as **coloured planes** ([`slice_image`], [`orthogonal_slices`]): each value is mapped
//!    linearly to a colour-map parameter (Hamann §2.2, `c = ((f_max − f)c_min + (f − f_min)c_max)
//!    / (f_max − f_min)`) and the rectangles between samples are filled by bilinear
//!    interpolation (Hamann uses Gouraud shading of the colour indices; here the values are
//!    interpolated and then mapped, which is the same for a linear map and better for a
//!    multi-colour one), or nearest-sample blocks;
//! 2. as **bivariate graphs** ([`slice_height_mesh`]): the points `(u_i, v_j, f_ij)` mapped into
//!    `[0, 1]³`, triangulated by Hamann's index sets I₁ = ((i,j),(i+1,j),(i+1,j+1)) and
//!    I₂ = ((i,j),(i+1,j+1),(i,j+1)), ready for [`super::raster::render_mesh`].
//!
//! Slice planes pass through grid planes (index along the slice normal), so no interpolation
//! across the normal is needed. Pixels keep the physical aspect: each sample owns the interval
//! between the midpoints to its neighbours, non-uniform axes included. In the images the
//! in-plane axes are: x-slice → (y right, z up), y-slice → (x right, z up), z-slice →
//! (x right, y up). NaN samples are drawn in the colour map's missing colour.
//!
//! Complexity: O(output pixels + n_u + n_v) per slice image; O(n_u n_v) for a height mesh.

use super::colormap::{finite_range, normalize, Colormap};
use super::font::{draw_text, text_height, text_width};
use super::legend::{label_num, with_colorbar};
use super::Image;
use super::RenderError;
use crate::geom::Point3;
use crate::mesh::{Property, ScalarKind, TriMesh};
use crate::volume::Volume;
use crate::Result;

/// The normal of a slice plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    /// Slice planes normal to x (the y–z plane).
    X,
    /// Slice planes normal to y (the x–z plane).
    Y,
    /// Slice planes normal to z (the x–y plane).
    Z,
}

impl Axis {
    /// Axis number 0, 1, 2.
    pub fn index(self) -> usize {
        match self {
            Axis::X => 0,
            Axis::Y => 1,
            Axis::Z => 2,
        }
    }
    /// Axis from its number (0, 1, 2).
    pub fn from_index(k: usize) -> Option<Axis> {
        [Axis::X, Axis::Y, Axis::Z].get(k).copied()
    }
    /// `"x"`, `"y"` or `"z"`.
    pub fn name(self) -> &'static str {
        ["x", "y", "z"][self.index()]
    }
    /// The in-plane axes (horizontal, vertical) of the slice image.
    pub fn in_plane(self) -> (usize, usize) {
        match self {
            Axis::X => (1, 2),
            Axis::Y => (0, 2),
            Axis::Z => (0, 1),
        }
    }
}

impl std::str::FromStr for Axis {
    type Err = RenderError;
    fn from_str(s: &str) -> Result<Axis, RenderError> {
        match s.trim().to_ascii_lowercase().as_str() {
            "x" | "0" => Ok(Axis::X),
            "y" | "1" => Ok(Axis::Y),
            "z" | "2" => Ok(Axis::Z),
            _ => Err(RenderError::UnknownAxis {
                name: s.to_string(),
            }),
        }
    }
}

/// How samples are spread over pixels.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Upsample {
    /// Each pixel shows the sample whose cell contains it (blocks).
    Nearest,
    /// Bilinear interpolation between the four surrounding samples (Hamann's Gouraud shading).
    #[default]
    Bilinear,
}

/// Options of the slice pictures.
#[derive(Debug, Clone, PartialEq)]
pub struct SliceOptions {
    /// The colour map.
    pub colormap: Colormap,
    /// Values mapped to the ends of the colour map; `None`: min..max of the volume's finite
    /// samples (shared by all slices of one volume).
    pub range: Option<(f64, f64)>,
    /// Longer side of one slice image in pixels (for [`orthogonal_slices`]: of the longest
    /// physical extent among the three axes). `None`: one pixel per (smallest mean) spacing.
    pub size: Option<u32>,
    /// How samples are interpolated between grid points.
    pub upsample: Upsample,
    /// Draw axis labels and a colour bar in [`orthogonal_slices`].
    pub labels: bool,
}

impl Default for SliceOptions {
    fn default() -> Self {
        SliceOptions {
            colormap: Colormap::Viridis,
            range: None,
            size: None,
            upsample: Upsample::Bilinear,
            labels: true,
        }
    }
}

const MAX_SIDE: f64 = 8192.0;

/// Sample positions and cell boundaries along one axis.
struct AxisGeom {
    centres: Vec<f64>,
    lo: f64,
    hi: f64,
    /// `bounds[i]..bounds[i+1]` is the cell of sample i.
    bounds: Vec<f64>,
}

fn axis_geom(vol: &Volume, k: usize) -> AxisGeom {
    let n = vol.dims[k];
    let centres: Vec<f64> = (0..n).map(|i| vol.coord(k, i)).collect();
    let mut bounds = Vec::with_capacity(n + 1);
    if n == 1 {
        let s = vol.spacing()[k];
        let s = if s.is_finite() && s > 0.0 { s } else { 1.0 };
        bounds.push(centres[0] - 0.5 * s);
        bounds.push(centres[0] + 0.5 * s);
    } else {
        bounds.push(centres[0] - 0.5 * (centres[1] - centres[0]));
        for i in 1..n {
            bounds.push(0.5 * (centres[i - 1] + centres[i]));
        }
        bounds.push(centres[n - 1] + 0.5 * (centres[n - 1] - centres[n - 2]));
    }
    AxisGeom {
        lo: bounds[0],
        hi: bounds[n],
        centres,
        bounds,
    }
}

/// Per-pixel lookup along one image axis: the nearest sample, or two samples and a weight.
#[derive(Clone, Copy)]
struct Tap {
    i0: usize,
    i1: usize,
    t: f64,
    nearest: usize,
}

fn taps(g: &AxisGeom, pixels: usize, flip: bool, mode: Upsample) -> Vec<Tap> {
    let n = g.centres.len();
    let len = g.hi - g.lo;
    (0..pixels)
        .map(|p| {
            let f = (p as f64 + 0.5) / pixels as f64;
            let u = if flip { g.hi - f * len } else { g.lo + f * len };
            // Cell containing u.
            let nearest = g.bounds[1..n].partition_point(|&b| b <= u).min(n - 1);
            let (i0, i1, t) = match mode {
                Upsample::Nearest => (nearest, nearest, 0.0),
                Upsample::Bilinear => {
                    let j = g.centres.partition_point(|&c| c <= u);
                    if j == 0 {
                        (0, 0, 0.0)
                    } else if j >= n {
                        (n - 1, n - 1, 0.0)
                    } else {
                        let (a, b) = (g.centres[j - 1], g.centres[j]);
                        (j - 1, j, ((u - a) / (b - a)).clamp(0.0, 1.0))
                    }
                }
            };
            Tap { i0, i1, t, nearest }
        })
        .collect()
}

fn check(vol: &Volume, axis: Axis, index: usize) -> Result<(), RenderError> {
    vol.validate()?;
    if vol.dims.contains(&0) {
        return Err(RenderError::EmptyVolume { dims: vol.dims });
    }
    let k = axis.index();
    if index >= vol.dims[k] {
        return Err(RenderError::SliceOutOfRange {
            index,
            axis: axis.name(),
            len: vol.dims[k],
        });
    }
    Ok(())
}

fn value_range(vol: &Volume, opts: &SliceOptions) -> (f64, f64) {
    opts.range
        .filter(|(a, b)| a.is_finite() && b.is_finite())
        .or_else(|| finite_range(vol.data.iter().map(|&v| v as f64)))
        .unwrap_or((0.0, 1.0))
}

/// Sample (u, v) of the slice `axis = index`.
fn sample(vol: &Volume, axis: Axis, index: usize, u: usize, v: usize) -> f64 {
    (match axis {
        Axis::X => vol.at(index, u, v),
        Axis::Y => vol.at(u, index, v),
        Axis::Z => vol.at(u, v, index),
    }) as f64
}

/// Pixel size in physical units for the given extents (longest → `size` px, or smallest mean
/// spacing → 1 px), limited so no side exceeds 8192 px.
fn pixel_size(extents: &[f64], counts: &[usize], size: Option<u32>) -> f64 {
    let longest = extents.iter().fold(0.0f64, |a, &b| a.max(b));
    let p = match size {
        Some(s) => longest / s.clamp(1, MAX_SIDE as u32) as f64,
        None => extents
            .iter()
            .zip(counts)
            .map(|(e, &c)| e / c.max(1) as f64)
            .fold(f64::INFINITY, f64::min),
    };
    p.max(longest / MAX_SIDE)
}

/// Draws slice `axis = index` into `img` at (`x0`, `y0`) with `w × h` pixels.
#[allow(clippy::too_many_arguments)]
fn paint(
    img: &mut Image,
    x0: u32,
    y0: u32,
    w: usize,
    h: usize,
    vol: &Volume,
    axis: Axis,
    index: usize,
    opts: &SliceOptions,
    range: (f64, f64),
) {
    let (ku, kv) = axis.in_plane();
    let (gu, gv) = (axis_geom(vol, ku), axis_geom(vol, kv));
    let tu = taps(&gu, w, false, opts.upsample);
    let tv = taps(&gv, h, true, opts.upsample);
    for (py, b) in tv.iter().enumerate() {
        for (px, a) in tu.iter().enumerate() {
            let s = |u: usize, v: usize| sample(vol, axis, index, u, v);
            let mut val = if a.i0 == a.i1 && b.i0 == b.i1 {
                s(a.i0, b.i0)
            } else {
                let top = (1.0 - a.t) * s(a.i0, b.i0) + a.t * s(a.i1, b.i0);
                let bot = (1.0 - a.t) * s(a.i0, b.i1) + a.t * s(a.i1, b.i1);
                (1.0 - b.t) * top + b.t * bot
            };
            if val.is_nan() {
                val = s(a.nearest, b.nearest);
            }
            let c = opts.colormap.color(normalize(val, range.0, range.1));
            img.put(x0 + px as u32, y0 + py as u32, [c[0], c[1], c[2], 255]);
        }
    }
}

fn slice_size(vol: &Volume, axis: Axis, p: f64) -> (usize, usize) {
    let (ku, kv) = axis.in_plane();
    let (gu, gv) = (axis_geom(vol, ku), axis_geom(vol, kv));
    let w = ((gu.hi - gu.lo) / p).round().clamp(1.0, MAX_SIDE) as usize;
    let h = ((gv.hi - gv.lo) / p).round().clamp(1.0, MAX_SIDE) as usize;
    (w, h)
}

/// The slice `axis = index` as an image (see the module documentation). With `size: None` and
/// equal spacing the image has one pixel per sample (`dims[u] × dims[v]`); anisotropic spacing
/// stretches the coarser axis so the picture keeps its physical aspect.
///
/// ```
/// use morpho::render::{slice_image, Axis, SliceOptions};
/// use morpho::volume::Volume;
/// let v = Volume::from_fn([8, 6, 4], [0.0; 3], [7.0, 5.0, 3.0], |x, _, _| x);
/// let img = slice_image(&v, Axis::Z, 2, &SliceOptions::default()).unwrap();
/// assert_eq!((img.width, img.height), (8, 6)); // one pixel per sample
/// let err = slice_image(&v, Axis::Z, 4, &SliceOptions::default()).unwrap_err();
/// assert_eq!(err.to_string(), "slice index 4 along z is out of range (0..4)");
/// ```
pub fn slice_image(
    vol: &Volume,
    axis: Axis,
    index: usize,
    opts: &SliceOptions,
) -> Result<Image, RenderError> {
    check(vol, axis, index)?;
    let (ku, kv) = axis.in_plane();
    let (gu, gv) = (axis_geom(vol, ku), axis_geom(vol, kv));
    let p = pixel_size(
        &[gu.hi - gu.lo, gv.hi - gv.lo],
        &[vol.dims[ku], vol.dims[kv]],
        opts.size,
    );
    let (w, h) = slice_size(vol, axis, p);
    let mut img = Image::new(w as u32, h as u32, [255; 4]);
    paint(
        &mut img,
        0,
        0,
        w,
        h,
        vol,
        axis,
        index,
        opts,
        value_range(vol, opts),
    );
    Ok(img)
}

/// The middle sample index along each axis.
pub fn middle(vol: &Volume) -> [usize; 3] {
    [vol.dims[0] / 2, vol.dims[1] / 2, vol.dims[2] / 2]
}

/// Three slices `x = c[ix]`, `y = c[iy]`, `z = c[iz]` side by side at one common scale, each
/// labelled with its axis, coordinate and index (`x = 1.5 [12]`), with a colour bar and the
/// value range below when `opts.labels`. Hamann 1991, §2.3, first possibility.
pub fn orthogonal_slices(
    vol: &Volume,
    index: [usize; 3],
    opts: &SliceOptions,
) -> Result<Image, RenderError> {
    for (k, &i) in index.iter().enumerate() {
        let axis = Axis::from_index(k).unwrap_or(Axis::Z);
        check(vol, axis, i)?;
    }
    let geoms: Vec<AxisGeom> = (0..3).map(|k| axis_geom(vol, k)).collect();
    let ext: Vec<f64> = geoms.iter().map(|g| g.hi - g.lo).collect();
    let mut p = pixel_size(&ext, &vol.dims, opts.size);
    if opts.size.is_none() {
        // Small volumes: enlarge (by an integer factor) until the longest side has ≥ 192 px.
        let longest = ext.iter().fold(0.0f64, |a, &b| a.max(b)) / p;
        if longest < 192.0 {
            p /= (192.0 / longest).ceil();
        }
    }
    let axes = [Axis::X, Axis::Y, Axis::Z];
    let sizes: Vec<(usize, usize)> = axes.iter().map(|&a| slice_size(vol, a, p)).collect();
    let scale = 2u32;
    let gap = 12usize;
    let label_h = if opts.labels {
        text_height(scale) as usize + 10
    } else {
        0
    };
    let mut width = gap + sizes.iter().map(|s| s.0 + gap).sum::<usize>();
    let range = value_range(vol, opts);
    let labels: Vec<String> = axes
        .iter()
        .zip(index)
        .map(|(a, i)| {
            format!(
                "{} = {} [{}]",
                a.name(),
                label_num(vol.coord(a.index(), i)),
                i
            )
        })
        .collect();
    if opts.labels {
        let need = gap
            + sizes
                .iter()
                .zip(&labels)
                .map(|(s, l)| s.0.max(text_width(l, scale) as usize) + gap)
                .sum::<usize>();
        width = width.max(need);
    }
    let height = gap + label_h + sizes.iter().map(|s| s.1).max().unwrap_or(1) + gap;
    let mut img = Image::new(width as u32, height as u32, [255; 4]);
    let black = [0, 0, 0, 255];
    let mut x = gap;
    for (k, &axis) in axes.iter().enumerate() {
        let (w, h) = sizes[k];
        let cell_w = if opts.labels {
            w.max(text_width(&labels[k], scale) as usize)
        } else {
            w
        };
        if opts.labels {
            draw_text(&mut img, x as i64, gap as i64, &labels[k], scale, black);
        }
        paint(
            &mut img,
            x as u32,
            (gap + label_h) as u32,
            w,
            h,
            vol,
            axis,
            index[k],
            opts,
            range,
        );
        x += cell_w + gap;
    }
    if opts.labels {
        img = with_colorbar(&img, opts.colormap, range.0, range.1, None);
    }
    Ok(img)
}

/// The graph of the slice `axis = index` as a triangle mesh (Hamann 1991, §2.3, second
/// possibility): vertex `(u_i, v_j, f_ij)` with the in-plane coordinates scaled by the larger
/// in-plane extent into `[0, 1]` (aspect kept) and the value mapped from `range` (or the slice's
/// finite range) to `[0, height]`; triangles from Hamann's index sets I₁ and I₂. Samples that
/// are NaN get height 0 and their triangles are left out. The vertex property `value` holds the
/// samples (for colouring). Vertical axis is z, so render with [`super::raster::UpAxis::Z`].
pub fn slice_height_mesh(
    vol: &Volume,
    axis: Axis,
    index: usize,
    range: Option<(f64, f64)>,
    height: f64,
) -> Result<TriMesh> {
    check(vol, axis, index)?;
    let (ku, kv) = axis.in_plane();
    let (nu, nv) = (vol.dims[ku], vol.dims[kv]);
    let (gu, gv) = (axis_geom(vol, ku), axis_geom(vol, kv));
    let eu = gu.centres[nu - 1] - gu.centres[0];
    let ev = gv.centres[nv - 1] - gv.centres[0];
    let e = eu.max(ev);
    let e = if e > 0.0 { e } else { 1.0 };
    let mut values = Vec::with_capacity(nu * nv);
    for j in 0..nv {
        for i in 0..nu {
            values.push(sample(vol, axis, index, i, j));
        }
    }
    let (lo, hi) = range
        .or_else(|| finite_range(values.iter().copied()))
        .unwrap_or((0.0, 1.0));
    let h = if height.is_finite() { height } else { 1.0 };
    let mut positions = Vec::with_capacity(nu * nv);
    for j in 0..nv {
        for i in 0..nu {
            let f = values[j * nu + i];
            let t = normalize(f, lo, hi);
            positions.push(Point3::new(
                (gu.centres[i] - gu.centres[0]) / e,
                (gv.centres[j] - gv.centres[0]) / e,
                if t.is_nan() { 0.0 } else { t * h },
            ));
        }
    }
    let id = |i: usize, j: usize| (j * nu + i) as u32;
    let mut triangles = Vec::with_capacity(2 * nu.saturating_sub(1) * nv.saturating_sub(1));
    for j in 0..nv.saturating_sub(1) {
        for i in 0..nu.saturating_sub(1) {
            for t in [
                [id(i, j), id(i + 1, j), id(i + 1, j + 1)],
                [id(i, j), id(i + 1, j + 1), id(i, j + 1)],
            ] {
                if t.iter().all(|&v| !values[v as usize].is_nan()) {
                    triangles.push(t);
                }
            }
        }
    }
    let mut m = TriMesh::new(positions, triangles);
    m.vertex_props.push(Property {
        name: "value".into(),
        kind: ScalarKind::F64,
        values,
    });
    Ok(m)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axis_parse() {
        assert_eq!("Y".parse::<Axis>().unwrap(), Axis::Y);
        assert!("w".parse::<Axis>().is_err());
        assert_eq!(Axis::X.in_plane(), (1, 2));
    }

    #[test]
    fn nonuniform_cells() {
        let v = Volume {
            dims: [3, 1, 1],
            axes: crate::volume::Axes::Coords([vec![0.0, 1.0, 3.0], vec![0.0], vec![0.0]]),
            data: vec![0.0, 1.0, 2.0],
            source_dtype: crate::volume::DType::F32,
            orientation: Default::default(),
        };
        let g = axis_geom(&v, 0);
        assert_eq!(g.bounds, vec![-0.5, 0.5, 2.0, 4.0]);
        let t = taps(&g, 9, false, Upsample::Nearest);
        // Pixels of width 0.5 from -0.5: centres -0.25, 0.25 → sample 0; 0.75..1.75 → 1; ≥2 → 2.
        let idx: Vec<usize> = t.iter().map(|t| t.nearest).collect();
        assert_eq!(idx, vec![0, 0, 1, 1, 1, 2, 2, 2, 2]);
    }
}
