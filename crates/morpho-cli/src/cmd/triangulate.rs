//! `morpho triangulate POINTS -o OUT`: Delaunay triangulation of 2D or 3D points (issue 3).
//!
//! The dimension comes from the input. Outputs: `.json` (`{"points", "triangles"}` in 2D,
//! `{"points", "tetrahedra"}` in 3D, indices into the input order — a merged duplicate is
//! represented by its first occurrence), a mesh format (`.ply/.obj/.off/.stl/.vtu/.vtk`: the
//! triangles in 2D with z = 0, the hull surface in 3D), with `--tets` (3D) the tetrahedra as VTK
//! (`.vtu` XML or `.vtk` legacy unstructured grid, cell type 10: ParaView, meshio) or as a PLY
//! with a `tetra` element, or `.svg` (2D, optionally with the Voronoi diagram).
//!
//! `--constraints SEGMENTS.csv` (2D): one `i,j` pair of input indices per line (blank lines and
//! `#` comments skipped; anything else is an error naming the line, exit 2); the result is the
//! constrained Delaunay triangulation ([`morpho::delaunay::cdt`]). Crossing segments are an
//! error naming both. The JSON output gains `"constrained": [[i, j], …]` (the constrained edges,
//! segments split at the points they pass through), the SVG draws them bold, and the report
//! has `constrained_edges`, `segments`, `splits`.

use crate::report::Report;
use crate::Failure;
use morpho::delaunay::{self, triangulate_2d, triangulate_3d};
use morpho::io::json::{Triangulation2, Triangulation3};
use morpho::io::{self, Format};
use morpho::render;
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// Points (CSV with header, XYZ, PLY, JSON array of [x, y(, z)]).
    pub input: PathBuf,
    /// Read the points as 2D (x, y of 3D rows, e.g. `x y 1`) or require 3D points.
    #[arg(long, value_name = "2|3")]
    pub dims: Option<u8>,
    /// Output: .json, .ply/.obj/.off/.stl/.vtu/.vtk, or .svg (2D).
    #[arg(short, long)]
    pub output: PathBuf,
    /// 3D: write the tetrahedra instead of the hull surface: .vtu/.vtk (VTK unstructured grid,
    /// for ParaView and meshio) or .ply (a `tetra` element).
    #[arg(long)]
    pub tets: bool,
    /// 2D SVG: draw the Voronoi diagram too.
    #[arg(long)]
    pub voronoi: bool,
    /// 2D: constraint segments, one `i,j` pair of input indices per line: the result is the
    /// constrained Delaunay triangulation.
    #[arg(long)]
    pub constraints: Option<PathBuf>,
}

/// The mesh formats a triangulation is written in (besides `.json` and, in 2D, `.svg`).
fn is_mesh(fmt: Format) -> bool {
    io::is_mesh_format(fmt)
}

pub fn run(args: Args, report: &mut Report) -> Result<u8, Failure> {
    let fmt = Format::of(&args.output)?;
    let pts = report.time("read", || super::read_points(&args.input, args.dims))?;
    if pts.dim == 2 {
        if let Some(c) = &args.constraints {
            if args.voronoi {
                return Err(Failure::usage(
                    "--voronoi and --constraints cannot be combined (the Voronoi diagram is the \
                     dual of the unconstrained triangulation)",
                ));
            }
            let segs = report.time("read", || super::read_index_rows::<2>(c, "constraints"))?;
            return run_constrained(&args, &pts.to_points2(), &segs, fmt, report);
        }
    } else if args.constraints.is_some() {
        return Err(Failure::usage(
            "--constraints is for 2D points (constrained Delaunay triangulation)",
        ));
    }
    report.set("dim", pts.dim);
    report.set("points", pts.len());
    if pts.dim == 2 {
        run_2d(&args, &pts.to_points2(), fmt, report)
    } else {
        run_3d(&args, &pts.to_points3(), fmt, report)
    }
}

/// The 2D Delaunay triangulation.
fn run_2d(
    args: &Args,
    p2: &[morpho::geom::Point2],
    fmt: Format,
    report: &mut Report,
) -> Result<u8, Failure> {
    let d = report
        .time("compute", || triangulate_2d(p2))
        .map_err(|e| morpho::Error::from(e).with_path(&args.input))?;
    let unique = d.points.len();
    if unique < 3 {
        return Err(Failure::usage(format!(
            "{}: a 2D triangulation needs at least 3 distinct points, the file has {unique}",
            args.input.display()
        )));
    }
    report.set("unique_points", unique);
    report.set("duplicates", d.duplicates);
    report.set("triangles", d.triangles.len());
    report.set("hull_size", d.hull.len());
    if d.collinear {
        let note = "all points are collinear: no triangles, the hull is the line of points";
        report.set("note", note);
        eprintln!("note: {note}");
    }
    let tris = d.to_input_indices();
    let hull: Vec<u32> = d
        .hull
        .iter()
        .map(|&v| d.input_of_vertex[v as usize])
        .collect();
    let t = Triangulation2 {
        points: p2,
        triangles: &tris,
        hull: &hull,
        constrained: None,
    };
    let path = &args.output;
    report.time("write", || match fmt {
        Format::Svg => io::write_text(path, &render::delaunay_svg(&d, args.voronoi)),
        f if f == Format::Json || is_mesh(f) => io::write_triangulation_2d(path, &t),
        _ => Err(morpho::Error::unsupported(
            "triangulate writes .json, .svg, .ply, .obj, .off, .stl, .vtu or .vtk",
        )
        .with_path(path)),
    })?;
    Ok(0)
}

/// The 3D Delaunay tetrahedralization.
fn run_3d(
    args: &Args,
    p3: &[morpho::geom::Point3],
    fmt: Format,
    report: &mut Report,
) -> Result<u8, Failure> {
    let d = report
        .time("compute", || triangulate_3d(p3))
        .map_err(|e| morpho::Error::from(e).with_path(&args.input))?;
    let unique = d.points.len();
    if unique < 4 {
        return Err(Failure::usage(format!(
            "{}: a 3D triangulation needs at least 4 distinct points, the file has {unique}",
            args.input.display()
        )));
    }
    report.set("unique_points", unique);
    report.set("duplicates", d.duplicates);
    report.set("tetrahedra", d.tets.len());
    report.set("hull_size", d.hull.len());
    if let Some(why) = &d.degenerate {
        report.set("note", why.as_str());
        eprintln!("note: {why}: no tetrahedra");
    }
    let tets = d.to_input_indices();
    let hull: Vec<[u32; 3]> = d
        .hull
        .iter()
        .map(|t| t.map(|v| d.input_of_vertex[v as usize]))
        .collect();
    let t = Triangulation3 {
        points: p3,
        tets: &tets,
        hull: &hull,
    };
    let path = &args.output;
    report.time("write", || match fmt {
        f if f == Format::Json || is_mesh(f) => io::write_triangulation_3d(path, &t, args.tets),
        Format::Svg => Err(morpho::Error::unsupported(
            "SVG pictures are for 2D points; render the hull with `morpho render`",
        )
        .with_path(path)),
        _ => Err(morpho::Error::unsupported(
            "triangulate writes .json, .ply, .obj, .off, .stl, .vtu or .vtk",
        )
        .with_path(path)),
    })?;
    Ok(0)
}

/// The 2D constrained Delaunay triangulation (see the module documentation).
fn run_constrained(
    args: &Args,
    p2: &[morpho::geom::Point2],
    segs: &[[u32; 2]],
    fmt: Format,
    report: &mut Report,
) -> Result<u8, Failure> {
    let c = report
        .time("compute", || delaunay::triangulate_constrained_2d(p2, segs))
        .map_err(|e| {
            morpho::Error::from(e).with_path(args.constraints.as_deref().unwrap_or(&args.input))
        })?;
    let unique = c.points().len();
    if unique < 3 || c.collinear() {
        return Err(Failure::usage(format!(
            "{}: a constrained triangulation needs at least 3 distinct points not all on one line",
            args.input.display()
        )));
    }
    let inp = |v: u32| c.input_of_vertex()[v as usize];
    let cons: Vec<[u32; 2]> = c
        .constrained_edges()
        .iter()
        .map(|e| [inp(e[0]), inp(e[1])])
        .collect();
    report.set("unique_points", unique);
    report.set("duplicates", c.duplicates());
    report.set("triangles", c.triangles.len());
    report.set("hull_size", c.hull().len());
    report.set("segments", segs.len());
    report.set("constrained_edges", cons.len());
    report.set("splits", c.splits);
    let tris = c.to_input_indices();
    let hull: Vec<u32> = c.hull().iter().map(|&v| inp(v)).collect();
    let t = Triangulation2 {
        points: p2,
        triangles: &tris,
        hull: &hull,
        constrained: Some(&cons),
    };
    let path = &args.output;
    report.time("write", || match fmt {
        Format::Svg => io::write_text(path, &render::cdt_svg(&c)),
        f if f == Format::Json || is_mesh(f) => io::write_triangulation_2d(path, &t),
        _ => Err(morpho::Error::unsupported(
            "triangulate writes .json, .svg, .ply, .obj, .off, .stl, .vtu or .vtk",
        )
        .with_path(path)),
    })?;
    Ok(0)
}
