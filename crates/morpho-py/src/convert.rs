//! The boundary between Python and the library: numpy arrays in and out, errors to exceptions,
//! computations with the GIL released and panics caught.
//!
//! Contracts (the Python layer in `python/morpho/__init__.py` converts before calling):
//! - coordinates arrive as C-contiguous `float64` arrays of shape `(n, d)`; the slice is
//!   reinterpreted as `&[Point2]`/`&[Point3]` without a copy (nalgebra points are `repr(C)`
//!   arrays of `f64`);
//! - index arrays leave as `uint32` arrays that own the library's `Vec` (no copy).

use morpho::geom::{Point2, Point3};
use numpy::ndarray::Array2;
use numpy::{PyArray1, PyArray2, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;

/// A library error as a Python exception: bad input → `ValueError`, a file that cannot be read
/// or written → `OSError`, anything else → `RuntimeError`; the message is the library's.
pub fn py_err(e: impl Into<morpho::Error>) -> PyErr {
    let e: morpho::Error = e.into();
    match &e {
        morpho::Error::Io { .. } => PyOSError::new_err(e.to_string()),
        _ if e.is_input_error() => PyValueError::new_err(e.to_string()),
        _ => PyRuntimeError::new_err(e.to_string()),
    }
}

/// A `ValueError` with this message.
pub fn bad(msg: impl Into<String>) -> PyErr {
    PyValueError::new_err(msg.into())
}

/// Runs `f` with the GIL released; a panic becomes a `RuntimeError` instead of unwinding into
/// Python (which would abort the interpreter).
pub fn compute<T: Send>(py: Python<'_>, f: impl FnOnce() -> T + Send) -> PyResult<T> {
    py.allow_threads(|| std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)))
        .map_err(|p| {
            let msg = p
                .downcast_ref::<String>()
                .map(String::as_str)
                .or_else(|| p.downcast_ref::<&str>().copied())
                .unwrap_or("unknown panic");
            PyRuntimeError::new_err(format!("morpho: internal error (panic): {msg}"))
        })
}

/// The coordinates of `(n, d)` points, borrowed without a copy. Fails unless the array is
/// C-contiguous with `d` in `dims` and every coordinate finite.
pub fn coords<'a>(
    a: &'a PyReadonlyArray2<'_, f64>,
    what: &str,
    dims: &[usize],
) -> PyResult<(&'a [f64], usize)> {
    let shape = a.shape();
    let d = shape[1];
    if !dims.contains(&d) {
        return Err(bad(format!(
            "{what}: expected an array of shape (n, {}), got {:?}",
            dims.iter()
                .map(|d| d.to_string())
                .collect::<Vec<_>>()
                .join(" or "),
            shape
        )));
    }
    if !a.is_c_contiguous() {
        return Err(bad(format!("{what}: the array must be C-contiguous")));
    }
    let s = a.as_slice().map_err(|e| bad(format!("{what}: {e}")))?;
    if let Some(i) = s.iter().position(|v| !v.is_finite()) {
        return Err(bad(format!(
            "{what}: point {} has a non-finite coordinate ({})",
            i / d,
            s[i]
        )));
    }
    Ok((s, d))
}

/// `n × 2` coordinates as points (no copy).
pub fn as_points2(s: &[f64]) -> &[Point2] {
    debug_assert_eq!(s.len() % 2, 0);
    // SAFETY: nalgebra's Point2<f64> is repr(C) over [f64; 2] (size 16, align 8), so a
    // contiguous run of 2n f64 is n points.
    unsafe { std::slice::from_raw_parts(s.as_ptr() as *const Point2, s.len() / 2) }
}

/// `n × 3` coordinates as points (no copy).
pub fn as_points3(s: &[f64]) -> &[Point3] {
    debug_assert_eq!(s.len() % 3, 0);
    // SAFETY: nalgebra's Point3<f64> is repr(C) over [f64; 3] (size 24, align 8).
    unsafe { std::slice::from_raw_parts(s.as_ptr() as *const Point3, s.len() / 3) }
}

/// `Vec<[T; K]>` as `Vec<T>` on the same buffer (no copy).
pub fn flatten<T: Copy, const K: usize>(v: Vec<[T; K]>) -> Vec<T> {
    let mut v = std::mem::ManuallyDrop::new(v);
    let (ptr, len, cap) = (v.as_mut_ptr(), v.len(), v.capacity());
    // SAFETY: [T; K] has the alignment of T and K times its size, so the allocation of `cap`
    // rows is exactly that of `cap * K` elements; `v` is not dropped.
    unsafe { Vec::from_raw_parts(ptr as *mut T, len * K, cap * K) }
}

const _: () = assert!(
    std::mem::size_of::<Point3>() == 24 && std::mem::align_of::<Point3>() == 8,
    "Point3 is [f64; 3]"
);
const _: () = assert!(
    std::mem::size_of::<morpho::geom::Vector3>() == 24
        && std::mem::align_of::<morpho::geom::Vector3>() == 8,
    "Vector3 is [f64; 3]"
);

/// `Vec<Point3>` as `Vec<[f64; 3]>` on the same buffer (no copy).
pub fn point_rows(v: Vec<Point3>) -> Vec<[f64; 3]> {
    let mut v = std::mem::ManuallyDrop::new(v);
    let (ptr, len, cap) = (v.as_mut_ptr(), v.len(), v.capacity());
    // SAFETY: Point3<f64> is repr(C) over [f64; 3] (checked above: same size and alignment).
    unsafe { Vec::from_raw_parts(ptr as *mut [f64; 3], len, cap) }
}

/// `Vec<Vector3>` as `Vec<[f64; 3]>` on the same buffer (no copy).
pub fn vector_rows(v: Vec<morpho::geom::Vector3>) -> Vec<[f64; 3]> {
    let mut v = std::mem::ManuallyDrop::new(v);
    let (ptr, len, cap) = (v.as_mut_ptr(), v.len(), v.capacity());
    // SAFETY: Vector3<f64> is a repr(C) matrix over [[f64; 3]; 1] (same size and alignment).
    unsafe { Vec::from_raw_parts(ptr as *mut [f64; 3], len, cap) }
}

/// A `Vec` of index rows as an `(m, K)` array that owns the vector's buffer (no copy).
pub fn rows<'py, const K: usize>(py: Python<'py>, v: Vec<[u32; K]>) -> Bound<'py, PyArray2<u32>> {
    let m = v.len();
    let flat = flatten(v);
    let a = Array2::from_shape_vec((m, K), flat).expect("shape matches");
    PyArray2::from_owned_array(py, a)
}

/// Float rows (e.g. positions) as an `(m, K)` array owning the flattened vector.
pub fn frows<'py, const K: usize>(py: Python<'py>, v: Vec<[f64; K]>) -> Bound<'py, PyArray2<f64>> {
    let m = v.len();
    let flat = flatten(v);
    let a = Array2::from_shape_vec((m, K), flat).expect("shape matches");
    PyArray2::from_owned_array(py, a)
}

/// A `Vec<u32>` as a one-dimensional array (no copy).
pub fn indices<'py>(py: Python<'py>, v: Vec<u32>) -> Bound<'py, PyArray1<u32>> {
    PyArray1::from_vec(py, v)
}

/// Index rows `(m, K)` from a C-contiguous `uint32`/`int64` array checked against `n` points.
pub fn index_rows<const K: usize>(
    a: &Bound<'_, PyAny>,
    what: &str,
    n: usize,
) -> PyResult<Vec<[u32; K]>> {
    let arr: PyReadonlyArray2<'_, i64> = a
        .extract()
        .map_err(|_| bad(format!("{what}: expected an int64 array of shape (m, {K})")))?;
    let shape = arr.shape();
    if shape[1] != K {
        return Err(bad(format!(
            "{what}: expected an array of shape (m, {K}), got {shape:?}"
        )));
    }
    let view = arr.as_array();
    let mut out = Vec::with_capacity(shape[0]);
    for (r, row) in view.rows().into_iter().enumerate() {
        let mut t = [0u32; K];
        for (k, &v) in row.iter().enumerate() {
            if v < 0 || v as u64 >= n as u64 {
                return Err(bad(format!(
                    "{what}: row {r} refers to vertex {v}, there are {n} vertices"
                )));
            }
            t[k] = v as u32;
        }
        out.push(t);
    }
    Ok(out)
}
