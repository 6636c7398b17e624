//! Python bindings of morpho: the native module `morpho._morpho`, wrapped by the pure-Python
//! package `morpho` (`python/morpho/__init__.py`, which converts and checks arguments, and
//! `__init__.pyi`, the type stubs). Built by maturin (`pyproject.toml`, distribution
//! `morpho-geom`); the `extension-module` feature is enabled only there, so that
//! `cargo build/test/clippy --workspace` compile this crate as a plain cdylib.
//!
//! Every function releases the GIL while the library computes, catches panics (a
//! `RuntimeError`, never an abort) and turns library errors into `ValueError` (bad input),
//! `OSError` (files) or `RuntimeError`, with the library's message.

mod blocks;
mod convert;
mod flint;
mod io;
mod mesh;
mod points;
mod reduce;
mod volume;

use pyo3::prelude::*;

/// Panics inside a computation (for the tests: it must be a `RuntimeError`, not an abort).
#[pyfunction]
fn _panic_for_tests(py: Python<'_>) -> PyResult<()> {
    convert::compute(py, || -> () { panic!("deliberate test panic") })
}

/// The native part of the `morpho` package (use `import morpho`).
#[pymodule]
fn _morpho(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", morpho::VERSION)?;
    m.add_function(wrap_pyfunction!(points::triangulate, m)?)?;
    m.add_function(wrap_pyfunction!(points::graph, m)?)?;
    m.add_function(wrap_pyfunction!(points::boundary, m)?)?;
    m.add_function(wrap_pyfunction!(points::contour, m)?)?;
    m.add_function(wrap_pyfunction!(volume::isosurface, m)?)?;
    m.add_function(wrap_pyfunction!(blocks::_block_range, m)?)?;
    m.add_function(wrap_pyfunction!(blocks::_isosurface_block, m)?)?;
    m.add_function(wrap_pyfunction!(blocks::_stitch_blocks, m)?)?;
    m.add_function(wrap_pyfunction!(mesh::info, m)?)?;
    m.add_function(wrap_pyfunction!(mesh::curvature, m)?)?;
    m.add_function(wrap_pyfunction!(reduce::reduce, m)?)?;
    m.add_function(wrap_pyfunction!(reduce::smooth, m)?)?;
    m.add_function(wrap_pyfunction!(io::read, m)?)?;
    m.add_function(wrap_pyfunction!(io::write, m)?)?;
    m.add_class::<flint::FlintTree>()?;
    m.add_function(wrap_pyfunction!(_panic_for_tests, m)?)?;
    Ok(())
}
