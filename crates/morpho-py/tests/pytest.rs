//! Runs the Python tests (`tests/py`, pytest) of the `morpho` package from `cargo test`:
//!
//! 1. a virtual environment `target/pyenv` (created when missing: `python3 -m venv`, then
//!    `pip install maturin numpy pytest scikit-image trimesh dask distributed zarr`; `.ci/run`
//!    creates it beforehand; both use the marker `.morpho-ready-2`, renumbered whenever the list
//!    grows so that an existing venv gets the new packages),
//! 2. the `morpho` command (`cargo build --release -p morpho-cli`, which the tests compare with),
//! 3. the wheel (`maturin build --release`, into `target/wheels`) installed into the venv,
//! 4. `python -m pytest tests/py`; the test fails when pytest fails.
//!
//! `MORPHO_PYTHON` names the interpreter that creates the venv (default `python3`);
//! `MORPHO_SKIP_PYTHON=1` skips (for machines without Python). The staged data
//! (`../shared/data`) is passed as `MORPHO_DATA`; tests needing it skip without it.

use std::path::{Path, PathBuf};
use std::process::Command;

fn run(cmd: &mut Command, what: &str) {
    eprintln!("pytest.rs: {what}: {cmd:?}");
    let st = cmd
        .status()
        .unwrap_or_else(|e| panic!("{what}: cannot start {cmd:?}: {e}"));
    assert!(st.success(), "{what} failed ({st})");
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn target_dir() -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| root().join("target"))
}

/// The venv, created when missing.
fn venv() -> PathBuf {
    let venv = target_dir().join("pyenv");
    let py = venv.join("bin/python");
    let ready = venv.join(".morpho-ready-2");
    if !ready.exists() {
        let python = std::env::var("MORPHO_PYTHON").unwrap_or_else(|_| "python3".into());
        run(
            Command::new(&python).args(["-m", "venv"]).arg(&venv),
            "create the venv",
        );
        run(
            Command::new(&py).args([
                "-m",
                "pip",
                "install",
                "-q",
                "--disable-pip-version-check",
                "maturin",
                "numpy",
                "pytest",
                "scikit-image",
                "trimesh",
                "dask",
                "distributed",
                "zarr",
            ]),
            "pip install",
        );
        std::fs::write(&ready, "").expect("mark the venv ready");
    }
    venv
}

#[test]
fn pytest_suite() {
    if std::env::var_os("MORPHO_SKIP_PYTHON").is_some() {
        eprintln!("note: MORPHO_SKIP_PYTHON set; the Python tests are skipped");
        return;
    }
    let root = root();
    let venv = venv();
    let bin = venv.join("bin");
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    run(
        Command::new(&cargo)
            .args(["build", "--release", "-q", "-p", "morpho-cli"])
            .current_dir(&root),
        "build the morpho command",
    );
    let wheels = target_dir().join("wheels");
    let _ = std::fs::remove_dir_all(&wheels);
    run(
        Command::new(bin.join("maturin"))
            .args(["build", "--release", "-q", "-m"])
            .arg(root.join("crates/morpho-py/Cargo.toml"))
            .arg("-o")
            .arg(&wheels)
            .arg("-i")
            .arg(bin.join("python"))
            .env("PATH", &path)
            .env("VIRTUAL_ENV", &venv)
            .current_dir(&root),
        "maturin build",
    );
    let wheel = std::fs::read_dir(&wheels)
        .expect("target/wheels")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .find(|p| p.extension().is_some_and(|e| e == "whl"))
        .expect("maturin wrote a wheel");
    run(
        Command::new(bin.join("python"))
            .args([
                "-m",
                "pip",
                "install",
                "-q",
                "--disable-pip-version-check",
                "--no-deps",
                "--force-reinstall",
            ])
            .arg(&wheel),
        "install the wheel",
    );
    let mut pytest = Command::new(bin.join("python"));
    pytest
        .args(["-m", "pytest", "-q", "-p", "no:cacheprovider"])
        .arg(root.join("crates/morpho-py/tests/py"))
        .env("PATH", &path)
        .env("MORPHO_CLI", target_dir().join("release/morpho"))
        .current_dir(target_dir());
    let data = root.join("../shared/data");
    if std::env::var_os("MORPHO_DATA").is_none() && data.is_dir() {
        pytest.env("MORPHO_DATA", data);
    }
    run(&mut pytest, "pytest");
}
