//! `morpho`: the command-line tool over the morpho library.
//!
//! A thin layer: parse arguments (clap), call the library, write outputs atomically, print the
//! one-line `error: …` on failure. Exit codes: 0 success, 2 bad usage or bad input, 1 anything else.

mod cmd;
mod report;

use clap::{Parser, Subcommand};
use report::Report;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "morpho",
    version,
    about = "Computational morphology: shapes from points, samples and volumes"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Write machine-readable figures (counts, validity, timings) to this JSON file.
    #[arg(long, global = true, value_name = "FILE.json")]
    report: Option<PathBuf>,
    /// Let volume headers name data files outside their own folder (absolute paths, `..`).
    #[arg(long, global = true)]
    allow_outside_data: bool,
}

#[derive(Subcommand)]
enum Command {
    /// Run every pipeline on generated sample data and write a gallery (index.html + images).
    Demo(cmd::demo::Args),
    /// Show what a file holds: counts, bounding box, topology.
    Info(cmd::info::Args),
    /// Convert between file formats (by extension; meshes and tetrahedral PLY also to .vtu/.vtk).
    Convert(cmd::convert::Args),
    /// Draw points, polygons, graphs (SVG) or meshes and volume slices (PNG).
    Render(cmd::render::Args),
    /// Delaunay triangulation of 2D or 3D points.
    Triangulate(cmd::triangulate::Args),
    /// A boundary through all points: simple polygon (2D) or closed mesh (3D) by γ-graph constriction.
    Boundary(cmd::boundary::Args),
    /// Geometric graphs (NNG, EMST, RNG, Gabriel, α-shape, β-skeletons, γ-graph, …).
    Graph(cmd::graph::Args),
    /// Contour surface f = level of a volume (consistent marching cubes).
    Isosurface(cmd::isosurface::Args),
    /// External contour of thresholded samples (regions where a rating exceeds a threshold).
    Contour(cmd::contour::Args),
}

/// What a command returns on failure: the error and the exit code it deserves.
pub struct Failure {
    pub code: u8,
    pub msg: String,
}

impl From<morpho::Error> for Failure {
    fn from(e: morpho::Error) -> Self {
        Failure {
            code: if e.is_input_error() { 2 } else { 1 },
            msg: e.to_string(),
        }
    }
}

// f-rest families: their errors reach the CLI through `morpho::Error` (same message, same code)
impl From<morpho::volume::VolumeError> for Failure {
    fn from(e: morpho::volume::VolumeError) -> Self {
        morpho::Error::from(e).into()
    }
}
impl From<morpho::mesh::MeshError> for Failure {
    fn from(e: morpho::mesh::MeshError) -> Self {
        morpho::Error::from(e).into()
    }
}
impl From<morpho::render::RenderError> for Failure {
    fn from(e: morpho::render::RenderError) -> Self {
        morpho::Error::from(e).into()
    }
}
impl From<morpho::contour::ContourError> for Failure {
    fn from(e: morpho::contour::ContourError) -> Self {
        morpho::Error::from(e).into()
    }
}

impl Failure {
    /// A usage error (exit 2).
    pub fn usage(msg: impl Into<String>) -> Self {
        Failure {
            code: 2,
            msg: msg.into(),
        }
    }
}

fn main() -> ExitCode {
    // A closed pipe ends the program quietly, as it does every Unix filter (Rust ignores
    // SIGPIPE, so `println!` would panic on `morpho info X | head -1`). Outputs named by `-o`
    // are written atomically and are not affected.
    #[cfg(unix)]
    // SAFETY: called first in main, before any thread exists; SIG_DFL is a valid handler.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
                let _ = e.print();
                return ExitCode::SUCCESS;
            }
            let msg = e.to_string();
            let first = msg
                .lines()
                .next()
                .unwrap_or("bad usage")
                .trim_start_matches("error: ");
            eprintln!("error: {first}");
            eprintln!("(see 'morpho --help')");
            return ExitCode::from(2);
        }
    };
    let name = match &cli.command {
        Command::Demo(_) => "demo",
        Command::Info(_) => "info",
        Command::Convert(_) => "convert",
        Command::Render(_) => "render",
        Command::Triangulate(_) => "triangulate",
        Command::Isosurface(_) => "isosurface",
        Command::Graph(_) => "graph",
        Command::Boundary(_) => "boundary",
        Command::Contour(_) => "contour",
    };
    // every path named on the command line, checked before anything is read or written
    let mut paths = cmd::Paths::default();
    match &cli.command {
        Command::Demo(_) => {}
        Command::Info(a) => paths.inputs.push(&a.input),
        Command::Convert(a) => {
            paths.inputs.push(&a.input);
            paths.output(&a.output);
        }
        Command::Render(a) => {
            paths.inputs.push(&a.input);
            paths.output(&a.output);
        }
        Command::Triangulate(a) => {
            paths.inputs.push(&a.input);
            paths.inputs.extend(a.constraints.as_deref());
            paths.output(&a.output);
        }
        Command::Isosurface(a) => {
            paths.inputs.push(&a.input);
            paths.output(&a.output);
        }
        Command::Graph(a) => {
            paths.inputs.push(&a.input);
            paths.output(&a.output);
        }
        Command::Boundary(a) => {
            paths.inputs.push(&a.input);
            paths.inputs.extend(a.keep.as_deref());
            paths.output(&a.output);
            if let Some(i) = &a.interior {
                paths.output(i);
            }
        }
        Command::Contour(a) => {
            paths.inputs.push(&a.input);
            paths.output(&a.output);
        }
    }
    if let Some(r) = &cli.report {
        paths.output(r);
    }
    if let Err(f) = paths.check() {
        // nothing is written, not even the report: its own path may be the problem
        eprintln!("error: {}", f.msg);
        return ExitCode::from(f.code);
    }
    drop(paths);
    // from here no output may replace a file that was read (data files named by headers
    // included) or a file this run already wrote
    morpho::io::guard::protect_inputs();
    morpho::io::guard::allow_data_outside_header_folder(cli.allow_outside_data);
    let mut report = Report::new(name);
    let result = match cli.command {
        Command::Demo(a) => cmd::demo::run(a, &mut report),
        Command::Info(a) => cmd::info::run(a, &mut report),
        Command::Convert(a) => cmd::convert::run(a, &mut report),
        Command::Render(a) => cmd::render::run(a, &mut report),
        Command::Triangulate(a) => cmd::triangulate::run(a, &mut report),
        Command::Isosurface(a) => cmd::isosurface::run(a, &mut report),
        Command::Graph(a) => cmd::graph::run(a, &mut report),
        Command::Boundary(a) => cmd::boundary::run(a, &mut report),
        Command::Contour(a) => cmd::contour::run(a, &mut report),
    };
    let code = match result {
        Ok(code) => code,
        Err(f) => {
            eprintln!("error: {}", f.msg);
            report.set("error", f.msg.clone());
            f.code
        }
    };
    if let Some(path) = &cli.report {
        if let Err(e) = report.save(path) {
            eprintln!("error: {e}");
            return ExitCode::from(if code == 0 { 1 } else { code });
        }
    }
    ExitCode::from(code)
}
