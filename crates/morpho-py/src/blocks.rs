//! Chunked contour surfaces (issue 24 part 3): the bindings `morpho.dask` builds on —
//! `_block_range` (the finite sample range of a chunk), `_isosurface_block` (the contour of one
//! chunk's cells, `morpho::volume::isosurface_block`) and `_stitch_blocks`
//! (`morpho::volume::stitch_blocks`, the surface `isosurface` gives for the whole array).
//!
//! Everything is in the array's axis order, as `isosurface`: grid shape, offsets and cells are
//! `(i, j, k)`, vertex columns too, and triangles wind as `isosurface`'s do. Inside, the
//! library's x is the array's axis 2 (a chunk is read in its logical order, whatever its
//! layout), so a stitched result equals `isosurface` of the whole C-ordered array bit for bit.
//!
//! A block crosses process boundaries as a plain tuple (picklable):
//! `(ids (n,) uint64, vertices (n, 3) float64, normals (n, 3) float64 | None,
//!   faces (m, 3) uint32, face_cells (m,) uint64, nan_cells (k,) uint64,
//!   fan_points, centroid_fallbacks, zero_normals)`.
//! Vertex ids and cell numbers are the library's global ones (`volume::isosurface` module
//! doc); a cell's number is the C-order linear index of its first sample in the array.

use crate::convert::{bad, compute, frows, py_err, rows};
use crate::volume::{c_samples, grid_frame, iso_options, result};
use morpho::geom::{Point3, Vector3};
use morpho::volume::{isosurface_block, stitch_blocks, IsoBlock, VolumeGrid};
use numpy::{PyArray1, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyList, PyTuple};

type Triple = (usize, usize, usize);

/// `(i, j, k)` as the library's `[x, y, z]` (x = axis 2).
fn rev<T: Copy>(t: (T, T, T)) -> [T; 3] {
    [t.2, t.1, t.0]
}

/// The smallest and largest finite sample of a chunk (as `float32`, the library's samples),
/// `None` when it has none. The range of the whole array (min of the minima, max of the
/// maxima) sets the perturbation ε every block must share.
#[pyfunction]
pub fn _block_range(py: Python<'_>, block: &Bound<'_, PyAny>) -> PyResult<Option<(f32, f32)>> {
    let (s, _) = c_samples(py, block)?;
    compute(py, || {
        let mut r: Option<(f32, f32)> = None;
        for &v in s.iter().filter(|v| v.is_finite()) {
            r = Some(match r {
                None => (v, v),
                Some((a, b)) => (a.min(v), b.max(v)),
            });
        }
        r
    })
}

/// The contour of the cells `cells` (`((i0, i1), (j0, j1), (k0, k1))`, half-open, cell i spans
/// samples i and i + 1) of an array of shape `shape`, given the chunk `block` whose first
/// sample is the array's sample `offset` and which holds the cells' samples plus the
/// one-sample halo where the array continues. `value_range`: the whole array's finite range.
#[pyfunction]
#[pyo3(signature = (block, shape, offset, cells, value_range, level, spacing, origin, method, normals, flip))]
#[allow(clippy::too_many_arguments)]
pub fn _isosurface_block<'py>(
    py: Python<'py>,
    block: &Bound<'py, PyAny>,
    shape: Triple,
    offset: Triple,
    cells: ((usize, usize), (usize, usize), (usize, usize)),
    value_range: Option<(f32, f32)>,
    level: f64,
    spacing: (f64, f64, f64),
    origin: (f64, f64, f64),
    method: &str,
    normals: &str,
    flip: bool,
) -> PyResult<Bound<'py, PyTuple>> {
    let opts = iso_options(level, method, normals, flip, false)?;
    let (sp, or) = grid_frame(spacing, origin)?;
    let grid = VolumeGrid::uniform(rev(shape), [or[2], or[1], or[0]], [sp[2], sp[1], sp[0]]);
    let (samples, bshape) = c_samples(py, block)?;
    let dims = [bshape[2], bshape[1], bshape[0]];
    let cells = rev(cells).map(|c| [c.0, c.1]);
    let b = compute(py, || {
        isosurface_block(
            &grid,
            &samples,
            dims,
            rev(offset),
            cells,
            value_range,
            &opts,
        )
    })?
    .map_err(py_err)?;
    drop(samples);
    block_tuple(py, b)
}

/// A library block as the tuple of the module doc, in axis order.
fn block_tuple(py: Python<'_>, b: IsoBlock) -> PyResult<Bound<'_, PyTuple>> {
    let pos: Vec<[f64; 3]> = b.positions.iter().map(|p| [p.z, p.y, p.x]).collect();
    let nor = b
        .normals
        .map(|n| n.iter().map(|v| [v.z, v.y, v.x]).collect::<Vec<[f64; 3]>>());
    let tri: Vec<[u32; 3]> = b.triangles.iter().map(|t| [t[0], t[2], t[1]]).collect();
    let items: Vec<Bound<'_, PyAny>> = vec![
        PyArray1::from_vec(py, b.ids).into_any(),
        frows(py, pos).into_any(),
        match nor {
            Some(n) => frows(py, n).into_any(),
            None => py.None().into_bound(py),
        },
        rows(py, tri).into_any(),
        PyArray1::from_vec(py, b.triangle_cells).into_any(),
        PyArray1::from_vec(py, b.nan_cells).into_any(),
        b.fan_points.into_pyobject(py)?.into_any(),
        b.centroid_fallbacks.into_pyobject(py)?.into_any(),
        pyo3::types::PyBool::new(py, b.zero_normals)
            .to_owned()
            .into_any(),
    ];
    PyTuple::new(py, items)
}

fn u64s(a: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<u64>> {
    let arr: PyReadonlyArray1<'_, u64> = a.extract().map_err(|_| {
        bad(format!(
            "block {what}: expected a uint64 array of shape (n,)"
        ))
    })?;
    Ok(arr.as_array().to_vec())
}

/// `(n, 3)` float64 rows as `[z, y, x]` triples (back to the library's order).
fn xyz(a: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<[f64; 3]>> {
    let arr: PyReadonlyArray2<'_, f64> = a.extract().map_err(|_| {
        bad(format!(
            "block {what}: expected a float64 array of shape (n, 3)"
        ))
    })?;
    if arr.shape()[1] != 3 {
        return Err(bad(format!(
            "block {what}: expected shape (n, 3), got {:?}",
            arr.shape()
        )));
    }
    Ok(arr
        .as_array()
        .rows()
        .into_iter()
        .map(|r| [r[2], r[1], r[0]])
        .collect())
}

/// A block tuple back as the library's block.
fn iso_block(t: &Bound<'_, PyAny>) -> PyResult<IsoBlock> {
    let t = t
        .downcast::<PyTuple>()
        .map_err(|_| bad("a block is the 9-tuple _isosurface_block returns"))?;
    if t.len() != 9 {
        return Err(bad("a block is the 9-tuple _isosurface_block returns"));
    }
    let positions = xyz(&t.get_item(1)?, "vertices")?
        .into_iter()
        .map(Point3::from)
        .collect();
    let n = t.get_item(2)?;
    let normals = if n.is_none() {
        None
    } else {
        Some(xyz(&n, "normals")?.into_iter().map(Vector3::from).collect())
    };
    let f: PyReadonlyArray2<'_, u32> = t
        .get_item(3)?
        .extract()
        .map_err(|_| bad("block faces: expected a uint32 array of shape (m, 3)"))?;
    if f.shape()[1] != 3 {
        return Err(bad("block faces: expected shape (m, 3)"));
    }
    let triangles = f
        .as_array()
        .rows()
        .into_iter()
        .map(|r| [r[0], r[2], r[1]])
        .collect();
    Ok(IsoBlock {
        ids: u64s(&t.get_item(0)?, "ids")?,
        positions,
        normals,
        triangles,
        triangle_cells: u64s(&t.get_item(4)?, "face cells")?,
        nan_cells: u64s(&t.get_item(5)?, "NaN cells")?,
        fan_points: t.get_item(6)?.extract()?,
        centroid_fallbacks: t.get_item(7)?.extract()?,
        zero_normals: t.get_item(8)?.extract()?,
    })
}

/// Stitches the blocks (a list of block tuples, any order, each cell in at most one block) of
/// an array of shape `shape` into `isosurface`'s result for the whole array (same arguments).
#[pyfunction]
#[pyo3(signature = (shape, blocks, value_range, level, spacing, origin, method, normals, flip, return_report=false))]
#[allow(clippy::too_many_arguments)]
pub fn _stitch_blocks<'py>(
    py: Python<'py>,
    shape: Triple,
    blocks: &Bound<'py, PyList>,
    value_range: Option<(f32, f32)>,
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
    let grid = VolumeGrid::uniform(rev(shape), [or[2], or[1], or[0]], [sp[2], sp[1], sp[0]]);
    let mut bs = Vec::with_capacity(blocks.len());
    for b in blocks.iter() {
        bs.push(iso_block(&b)?);
    }
    let r = compute(py, || stitch_blocks(&grid, bs, value_range, &opts))?.map_err(py_err)?;
    result(py, r, true, return_report)
}
