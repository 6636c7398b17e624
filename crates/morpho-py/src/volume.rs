//! `isosurface`: the contour surface of a volume given as a 3D numpy array (Hamann 1991
//! §3.2–3.4 through `morpho::volume::isosurface`), with the conventions of
//! `skimage.measure.marching_cubes`: `volume[i, j, k]` is the sample at index `(i, j, k)`,
//! vertices are `origin + (i, j, k) * spacing` in that column order.
//!
//! Layout: the library's volume is x-fastest (`data[x + nx (y + ny z)]`). A Fortran-ordered
//! array already is (x = axis 0); a C-ordered or strided one is read in its logical order with
//! x = axis 2, and the result's columns are reversed (and the winding flipped, since reversing
//! the axes mirrors space) so that the output is in axis order either way. The samples are
//! converted to `float32` (the library's sample type) in one pass, without the GIL.

use crate::convert::{bad, compute, frows, py_err, rows};
use morpho::volume::{isosurface as iso, IsoMethod, IsoOptions, IsoResult, NormalMethod, Volume};
use numpy::ndarray::ArrayView3;
use numpy::{Element, PyReadonlyArray3, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};
use rayon::prelude::*;

/// Samples of a typed array as the library's `f32` samples, x fastest; `true` when x is the
/// array's axis 2 (C order).
fn samples<T: Element + Copy + Sync>(
    a: ArrayView3<'_, T>,
    f_order: bool,
    transpose: bool,
    cast: fn(T) -> f32,
) -> Vec<f32> {
    let contiguous = if f_order {
        a.as_slice_memory_order()
    } else {
        a.as_slice()
    };
    if transpose {
        a.reversed_axes().iter().map(|&v| cast(v)).collect()
    } else if let Some(s) = contiguous {
        // the one copy the library's owned volume needs, on every core
        s.par_iter()
            .with_min_len(1 << 16)
            .map(|&v| cast(v))
            .collect()
    } else {
        a.iter().map(|&v| cast(v)).collect()
    }
}

/// Expands `$m!(type, cast to f32)` for every dtype a volume may have, in the order tried.
macro_rules! each_volume_dtype {
    ($m:ident) => {
        $m!(f32, |v| v);
        $m!(f64, |v| v as f32);
        $m!(u8, |v| v as f32);
        $m!(i8, |v| v as f32);
        $m!(u16, |v| v as f32);
        $m!(i16, |v| v as f32);
        $m!(u32, |v| v as f32);
        $m!(i32, |v| v as f32);
        $m!(i64, |v| v as f32);
        $m!(u64, |v| v as f32);
    };
}

/// Reads the array (any of the supported dtypes) into a [`Volume`]; the flag tells whether the
/// volume's x is the array's axis 2 (C order, read without reordering). With `keep_axes`, x is
/// always axis 0 (a C-ordered array is then transposed while it is converted).
pub fn to_volume(
    py: Python<'_>,
    a: &Bound<'_, PyAny>,
    spacing: [f64; 3],
    origin: [f64; 3],
    keep_axes: bool,
) -> PyResult<(Volume, bool)> {
    macro_rules! try_dtype {
        ($t:ty, $cast:expr) => {
            if let Ok(arr) = a.extract::<PyReadonlyArray3<'_, $t>>() {
                let shape = arr.shape().to_vec();
                let f_order = arr.is_fortran_contiguous() && !arr.is_c_contiguous();
                let transpose = keep_axes && !f_order;
                let view = arr.as_array();
                let data = compute(py, || samples(view, f_order, transpose, $cast))?;
                let (dims, sp, or) = if f_order || transpose {
                    ([shape[0], shape[1], shape[2]], spacing, origin)
                } else {
                    let r = |v: [f64; 3]| [v[2], v[1], v[0]];
                    ([shape[2], shape[1], shape[0]], r(spacing), r(origin))
                };
                let v = Volume::new(dims, or, sp, data).map_err(py_err)?;
                return Ok((v, !(f_order || transpose)));
            }
        };
    }
    each_volume_dtype!(try_dtype);
    Err(unsupported(a))
}

/// The samples of a 3D array of any supported dtype in its logical order (the last axis
/// fastest: the library's x is the array's axis 2), as `f32`, with the array's shape; one pass
/// without the GIL, whatever the layout.
pub fn c_samples(py: Python<'_>, a: &Bound<'_, PyAny>) -> PyResult<(Vec<f32>, [usize; 3])> {
    macro_rules! try_dtype {
        ($t:ty, $cast:expr) => {
            if let Ok(arr) = a.extract::<PyReadonlyArray3<'_, $t>>() {
                let s = arr.shape();
                let shape = [s[0], s[1], s[2]];
                let view = arr.as_array();
                let data = compute(py, || samples(view, false, false, $cast))?;
                return Ok((data, shape));
            }
        };
    }
    each_volume_dtype!(try_dtype);
    Err(unsupported(a))
}

fn unsupported(a: &Bound<'_, PyAny>) -> PyErr {
    let desc = match (a.getattr("dtype"), a.getattr("ndim")) {
        (Ok(d), Ok(n)) => format!("an array of dtype {d} and ndim {n}"),
        _ => match a.get_type().name() {
            Ok(n) => format!("a {n}"),
            Err(_) => "an object".to_string(),
        },
    };
    bad(format!(
        "volume: expected a 3D array of integers or floats, got {desc}"
    ))
}

/// The contour surface `f = level`: `(vertices (n, 3) float64, faces (m, 3) uint32,
/// normals (n, 3) float64 or None)`, and with `return_report` a fourth item, a dict of figures.
#[pyfunction]
#[pyo3(signature = (volume, level, spacing=(1.0, 1.0, 1.0), origin=(0.0, 0.0, 0.0), method="decider", normals="zucker", flip=false, return_report=false))]
#[allow(clippy::too_many_arguments)]
pub fn isosurface<'py>(
    py: Python<'py>,
    volume: &Bound<'py, PyAny>,
    level: f64,
    spacing: (f64, f64, f64),
    origin: (f64, f64, f64),
    method: &str,
    normals: &str,
    flip: bool,
    return_report: bool,
) -> PyResult<Bound<'py, PyTuple>> {
    let opts = iso_options(level, method, normals, flip, return_report)?;
    let (sp, or) = grid_frame(spacing, origin)?;
    let (vol, reversed) = to_volume(py, volume, sp, or, false)?;
    let r = compute(py, || iso(&vol, &opts))?.map_err(py_err)?;
    drop(vol);
    result(py, r, reversed, return_report)
}

/// The options of `isosurface` (and of the chunked contour of `blocks`) from the Python names.
pub fn iso_options(
    level: f64,
    method: &str,
    normals: &str,
    flip: bool,
    topology: bool,
) -> PyResult<IsoOptions> {
    let method = match method {
        "decider" => IsoMethod::Decider,
        "tetra" => IsoMethod::Tetra,
        "lorensen" => IsoMethod::Lorensen,
        m => {
            return Err(bad(format!(
                "unknown isosurface method '{m}': use decider, tetra or lorensen"
            )))
        }
    };
    let normal_method = match normals {
        "zucker" => NormalMethod::ZuckerHummel,
        "central" => NormalMethod::Central,
        "mesh" => NormalMethod::Mesh,
        "none" => NormalMethod::None,
        n => {
            return Err(bad(format!(
                "unknown normals '{n}': use zucker, central, mesh or none"
            )))
        }
    };
    if !level.is_finite() {
        return Err(bad(format!("level must be a finite number, got {level}")));
    }
    Ok(IsoOptions {
        level,
        method,
        normals: normal_method,
        flip,
        parallel: true,
        topology,
    })
}

/// Spacing and origin as arrays, checked (positive finite spacing, finite origin).
pub fn grid_frame(
    spacing: (f64, f64, f64),
    origin: (f64, f64, f64),
) -> PyResult<([f64; 3], [f64; 3])> {
    let sp = [spacing.0, spacing.1, spacing.2];
    let or = [origin.0, origin.1, origin.2];
    if sp.iter().any(|s| !(s.is_finite() && *s > 0.0)) || or.iter().any(|o| !o.is_finite()) {
        return Err(bad(format!(
            "spacing must be three positive finite numbers and origin three finite numbers, \
             got spacing {sp:?}, origin {or:?}"
        )));
    }
    Ok((sp, or))
}

/// A library result as `isosurface`'s tuple; `reversed`: the library's x is the array's axis
/// 2, so the columns are put back in axis order and the windings flipped.
pub fn result<'py>(
    py: Python<'py>,
    r: IsoResult,
    reversed: bool,
    return_report: bool,
) -> PyResult<Bound<'py, PyTuple>> {
    let m = r.mesh;
    // In place and without a copy: points and vectors are `[f64; 3]` (see `convert`).
    let (pos, tri, nor) = compute(py, || {
        let mut pos = crate::convert::point_rows(m.positions);
        let mut tri = m.triangles;
        let mut nor = m.normals.map(crate::convert::vector_rows);
        if reversed {
            pos.par_iter_mut().for_each(|p| p.swap(0, 2));
            tri.par_iter_mut().for_each(|t| t.swap(1, 2));
            if let Some(n) = nor.as_mut() {
                n.par_iter_mut().for_each(|v| v.swap(0, 2));
            }
        }
        (pos, tri, nor)
    })?;
    let verts = frows(py, pos).into_any();
    let faces = rows(py, tri).into_any();
    let nor = match nor {
        Some(n) => frows(py, n).into_any(),
        None => py.None().into_bound(py),
    };
    if !return_report {
        return PyTuple::new(py, [verts, faces, nor]);
    }
    let d = PyDict::new(py);
    d.set_item("parts", r.parts)?;
    d.set_item("boundary_edges", r.boundary_edges)?;
    d.set_item("interior_boundary_edges", r.interior_boundary_edges)?;
    d.set_item("interior_holes", r.interior_holes)?;
    d.set_item("non_manifold_edges", r.non_manifold_edges)?;
    d.set_item("fan_points", r.fan_points)?;
    d.set_item("centroid_fallbacks", r.centroid_fallbacks)?;
    d.set_item("skipped_cells", r.skipped_cells)?;
    d.set_item("note", r.note)?;
    PyTuple::new(py, [verts, faces, nor, d.into_any()])
}
