//! `morpho`: the command-line tool over the morpho library.
//!
//! A thin layer: parse arguments (clap), call the library, write outputs atomically, print the
//! one-line `error: …` on failure. Exit codes: 0 success, 2 bad usage or bad input, 1 anything else.

mod cmd;
mod report;
mod stream;

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
    /// Most memory a reader may allocate, e.g. `4G`, `512M` (default: MORPHO_MEMORY_LIMIT, else
    /// three quarters of the machine's memory).
    #[arg(long, global = true, value_name = "BYTES")]
    memory_limit: Option<String>,
    /// Coordinate reference system named in GeoJSON outputs, e.g. `EPSG:28992` (GeoJSON
    /// readers otherwise assume WGS84 longitude/latitude).
    #[arg(long, global = true, value_name = "NAME")]
    crs: Option<String>,
    /// Format (a file extension: ply, obj, csv, geojson, nrrd, mha, …) of an output named `-`,
    /// which goes to standard output.
    #[arg(long, global = true, value_name = "EXT")]
    format: Option<String>,
    /// Format of an input named `-` (standard input); without it the format is recognised
    /// from the first bytes.
    #[arg(long, global = true, value_name = "EXT")]
    input_format: Option<String>,
}

#[derive(Subcommand)]
// Parsed once per process; boxing the large argument structs would buy nothing.
#[allow(clippy::large_enum_variant)]
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
    /// Flintstone trees of polygons and polylines: build, approximate, point-in-polygon,
    /// intersection.
    Flint(cmd::flint::Args),
    /// Curvature of a triangle mesh (k1, k2, H, K, A per vertex) or of a volume's function.
    Curvature(cmd::curvature::Args),
    /// G¹ smooth curve through a polygon or G¹ surface through a closed mesh (cubic Bézier).
    Smooth(cmd::smooth::Args),
    /// Fewer triangles, same shape and genus: curvature-driven triangle reduction.
    Reduce(cmd::reduce::Args),
    /// An interactive page (WebGL 2, offline) showing meshes, points, shapes and volumes.
    View(cmd::view::Args),
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

/// SIGTERM, SIGHUP and SIGINT end the program as they would by default (exit status 128 +
/// signal), but first remove the temporary files of unfinished atomic writes
/// (`io::guard::remove_temporaries`). The signals are blocked in every thread and taken by one
/// thread with `sigwait`, so the cleanup runs as ordinary code, not in a signal handler.
/// Must be called before any other thread is started (threads inherit the blocked set).
#[cfg(unix)]
fn remove_temporaries_on_signals() {
    // SAFETY: plain libc calls on a local, zero-initialised signal set; no other thread exists
    // yet, so the mask applies to every thread started later.
    let set = unsafe {
        let mut set: libc::sigset_t = std::mem::zeroed();
        libc::sigemptyset(&mut set);
        for sig in [libc::SIGTERM, libc::SIGHUP, libc::SIGINT] {
            libc::sigaddset(&mut set, sig);
        }
        if libc::pthread_sigmask(libc::SIG_BLOCK, &set, std::ptr::null_mut()) != 0 {
            return;
        }
        set
    };
    let spawned = std::thread::Builder::new()
        .name("signals".into())
        .spawn(move || {
            let mut sig: libc::c_int = 0;
            // SAFETY: `set` is a valid signal set and `sig` a valid out-pointer.
            if unsafe { libc::sigwait(&set, &mut sig) } != 0 {
                return;
            }
            morpho::io::guard::remove_temporaries();
            stream::remove_staging();
            // SAFETY: ends the process at once, as the default action of the signal would.
            unsafe { libc::_exit(128 + sig) }
        });
    if spawned.is_err() {
        // no thread, no cleanup: give the signals back their default action
        // SAFETY: as above.
        unsafe {
            libc::pthread_sigmask(libc::SIG_UNBLOCK, &set, std::ptr::null_mut());
        }
    }
}

const SUBCOMMANDS: [&str; 14] = [
    "demo",
    "info",
    "convert",
    "render",
    "triangulate",
    "boundary",
    "graph",
    "isosurface",
    "contour",
    "flint",
    "curvature",
    "smooth",
    "reduce",
    "view",
];

/// clap's usage error on one line: its first paragraph (without the `error: ` clap adds), the
/// indented lines of that paragraph — the names of the missing arguments — joined to it, the
/// usage synopsis and tips left out (`--help` shows them). Control characters are escaped.
fn usage_line(rendered: &str) -> String {
    let mut lines = rendered
        .lines()
        .take_while(|l| !l.trim().is_empty() && !l.starts_with("Usage:"));
    let first = lines.next().unwrap_or("bad usage");
    let mut out = first.trim_start_matches("error: ").trim_end().to_string();
    let rest: Vec<&str> = lines.map(str::trim).collect();
    if !rest.is_empty() {
        out.push(' ');
        out.push_str(&rest.join(", "));
    }
    printable(&out)
}

/// `msg` with every control character (an escape sequence, a carriage return, a NUL from a
/// hostile file name or header) written as `\u{…}`, so an `error:` line is one line and cannot
/// drive the terminal.
pub fn printable(msg: &str) -> String {
    if !msg.chars().any(char::is_control) {
        return msg.to_string();
    }
    msg.chars()
        .map(|c| {
            if c.is_control() {
                c.escape_unicode().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
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
    #[cfg(unix)]
    remove_temporaries_on_signals();
    // `-` (standard input/output) is staged through a temporary folder (see stream.rs)
    let staged = match stream::stage(std::env::args_os().collect()) {
        Ok(s) => s,
        Err(msg) => {
            eprintln!("error: {}", printable(&msg));
            return ExitCode::from(2);
        }
    };
    let cli = match Cli::try_parse_from(&staged.args) {
        Ok(c) => c,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
                let _ = e.print();
                return ExitCode::SUCCESS;
            }
            eprintln!("error: {}", usage_line(&e.render().to_string()));
            let sub = std::env::args()
                .nth(1)
                .filter(|a| SUBCOMMANDS.contains(&a.as_str()));
            match sub {
                Some(sub) => eprintln!("(see 'morpho {sub} --help')"),
                None => eprintln!("(see 'morpho --help')"),
            }
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
        Command::Flint(_) => "flint",
        Command::Curvature(_) => "curvature",
        Command::Smooth(_) => "smooth",
        Command::Reduce(_) => "reduce",
        Command::View(_) => "view",
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
            paths.inputs.extend(a.input.as_deref());
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
        Command::Curvature(a) => {
            paths.inputs.push(&a.input);
            if !a.output.is_dir() {
                paths.output(&a.output);
            }
        }
        Command::Smooth(a) => {
            paths.inputs.push(&a.input);
            paths.output(&a.output);
        }
        Command::Reduce(a) => {
            paths.inputs.push(&a.input);
            paths.output(&a.output);
        }
        Command::View(a) => {
            paths.inputs.extend(a.inputs.iter().map(|p| p.as_path()));
            paths.inputs.extend(a.figures.as_deref());
            paths.output(&a.output);
        }
        Command::Flint(a) => {
            let (ins, out) = a.paths();
            paths.inputs.extend(ins);
            paths.output(out);
        }
    }
    if let Some(r) = &cli.report {
        paths.output(r);
    }
    if let Err(f) = paths.check() {
        // nothing is written, not even the report: its own path may be the problem
        eprintln!("error: {}", printable(&staged.unmap(&f.msg)));
        return ExitCode::from(f.code);
    }
    drop(paths);
    // from here no output may replace a file that was read (data files named by headers
    // included) or a file this run already wrote
    morpho::io::guard::protect_inputs();
    morpho::io::guard::allow_data_outside_header_folder(cli.allow_outside_data);
    if let Some(m) = &cli.memory_limit {
        match morpho::io::memory::parse_size(m).filter(|&b| b > 0) {
            Some(b) => morpho::io::memory::set_limit(b),
            None => {
                eprintln!(
                    "error: --memory-limit must be a size such as 4G or 512M, not '{}'",
                    printable(m)
                );
                return ExitCode::from(2);
            }
        }
    }
    morpho::io::geojson::carry_input_crs(true);
    if let Err(e) = morpho::io::geojson::set_crs(cli.crs.as_deref()) {
        eprintln!("error: {}", printable(&e.to_string()));
        return ExitCode::from(2);
    }
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
        Command::Flint(a) => cmd::flint::run(a, &mut report),
        Command::Curvature(a) => cmd::curvature::run(a, &mut report),
        Command::Smooth(a) => cmd::smooth::run(a, &mut report),
        Command::Reduce(a) => cmd::reduce::run(a, &mut report),
        Command::View(a) => cmd::view::run(a, &mut report),
    };
    let code = match result {
        Ok(code) => code,
        Err(f) => {
            let msg = staged.unmap(&f.msg);
            eprintln!("error: {}", printable(&msg));
            report.set("error", msg);
            f.code
        }
    };
    if let Some((r, w)) = morpho::io::guard::traffic() {
        report.set_io(r, w);
    }
    if let Some(path) = &cli.report {
        if let Err(e) = report.save(path) {
            eprintln!("error: {}", printable(&staged.unmap(&e.to_string())));
            return ExitCode::from(if code == 0 { 1 } else { code });
        }
    }
    if code == 0 {
        if let Err(msg) = staged.finish() {
            eprintln!("error: {}", printable(&msg));
            return ExitCode::from(1);
        }
    }
    ExitCode::from(code)
}
