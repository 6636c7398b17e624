//! `morpho boundary POINTS -o OUT`: a simple polygon through all scattered 2D points, or a
//! closed genus-0 mesh through 3D points (issue 5; Veltkamp 1992 ch. 4–5), by γ-graph
//! constriction or (2D) one of the two comparison methods.
//!
//! 3D: `-o` `.ply/.obj/.off/.vtu/.vtk` (every input point is a vertex, in input order) or `.json`
//! (`{"triangles":[[i,j,k],…]}`); `--until all|locked`; `--keep` triangles; report keys `closed_manifold`, `genus`,
//! `volume`, `c_used`, `added_triangles`; `--c auto|C` as in 2D (auto: Delaunay constriction, then
//! the general engine with γ([-1,1],[c,1]) triangles, c = −0.1 … −1, when it locks);
//! `--interior FILE.json` writes `{"tetrahedra":[…],"volume":V}` (empty, with a `"note"` and a
//! warning on stderr, when the general engine ran); `.ply` (a `tetra` element), `.vtu`, `.vtk`
//! write the same tetrahedra as a tetrahedral mesh; other extensions are refused before anything
//! is computed.
//! 3D methods: gamma and min-area-change (the key of the Delaunay constriction; the general
//! engine after a lock always uses the γ-indicator) and voronoi-skeleton (the shortest tree of
//! Delaunay tetrahedra grown from up to `--seeds` seeds, `--interior` = its tetrahedra, report
//! key `skeleton_length`; `--until`, `--c` and `--keep` do not apply).
//!
//! 2D outputs by extension: `.csv` (`index,x,y` in boundary order), `.geojson` (one Polygon
//! feature), `.json` (`{"polygon":[input indices]}`), `.svg` (points, Delaunay graph faint,
//! boundary bold, deleted edges dashed). `--interior FILE` writes the interior triangulation
//! (`.json` `{"triangles":[[i,j,k],…]}` or a mesh format with z = 0). Exit code 1 when not every
//! point is on the boundary (or a keep edge is not on it): the best valid polygon is still
//! written and the report lists the points left out.

use crate::report::Report;
use crate::Failure;
use morpho::boundary::{
    boundary_2d, boundary_3d, check_polygon, BoundaryError, CParam, Method2, Method3, Options2,
    Options3, Until,
};
use morpho::io;
use morpho::render;
use morpho::Error;
use serde_json::json;
use std::path::{Path, PathBuf};

#[derive(clap::Args)]
pub struct Args {
    /// Points (CSV with header, XYZ, PLY, JSON array); 2D.
    pub input: PathBuf,
    /// Read the points as 2D (x, y of 3D rows, e.g. `x y 1`) or require 3D points.
    #[arg(long, value_name = "2|3")]
    pub dims: Option<u8>,
    /// Output: .csv, .geojson, .json or .svg.
    #[arg(short, long)]
    pub output: PathBuf,
    /// gamma (V §5.2), min-area-change (Boissonnat, V §4.3.3) or voronoi-skeleton (O'Rourke et
    /// al., V §4.3.4). 3D min-area-change: the key of the Delaunay constriction; with
    /// `--c auto` a lock continues in the γ general engine.
    #[arg(long, default_value = "gamma")]
    pub method: String,
    /// γ([-1,1],[c,1]) parameter: `auto` (Delaunay first, adaptive augmentation down to −1 when
    /// constriction locks; gamma method only) or a number in [−1, 0]. A fixed c < 0 constricts
    /// the whole γ([-1,1],[c,1]) from the hull; for points sampled on a closed curve that graph
    /// has Θ(N²) chords across the empty interior, so a fixed c is slow beyond a few thousand
    /// points (2000 curve points: ≈ 10 s at c = −0.1); `auto` adds those edges only where needed.
    #[arg(long, default_value = "auto", allow_hyphen_values = true)]
    pub c: String,
    /// Edges (2D: `i,j`) or triangles (3D: `i,j,k`) that must be on the boundary, input
    /// indices, one per line.
    #[arg(long)]
    pub keep: Option<PathBuf>,
    /// Write the interior triangulation here (.json, .ply, .obj, .off).
    #[arg(long)]
    pub interior: Option<PathBuf>,
    /// 3D: stop when every point is on the boundary (`all`) or continue while tetrahedra are
    /// removable (`locked`).
    #[arg(long, default_value = "all")]
    pub until: String,
    /// Seeds tried by the Voronoi skeleton method.
    #[arg(long, default_value_t = 200)]
    pub seeds: usize,
}

pub fn run(args: Args, report: &mut Report) -> Result<u8, Failure> {
    let method = args.method.as_str();
    match method {
        "gamma" | "min-area-change" | "voronoi-skeleton" => {}
        m => {
            return Err(Failure::usage(format!(
                "unknown --method {m}: use gamma, min-area-change or voronoi-skeleton"
            )))
        }
    }
    let c = if args.c == "auto" {
        CParam::Auto
    } else {
        match args.c.parse::<f64>() {
            Ok(v) if (-1.0..=0.0).contains(&v) => CParam::Fixed(v),
            _ => return Err(Failure::usage("--c must be `auto` or a number in [-1, 0]")),
        }
    };
    let until = match args.until.as_str() {
        "all" => Until::All,
        "locked" => Until::Locked,
        _ => return Err(Failure::usage("--until must be `all` or `locked`")),
    };
    let ext = super::extension(&args.output);
    let ps = report.time("read", || super::read_points(&args.input, args.dims))?;
    if ps.dim == 3 {
        let keep = match &args.keep {
            Some(k) => report.time("read", || super::read_index_rows::<3>(k, "keep"))?,
            None => Vec::new(),
        };
        let method = match method {
            "gamma" => Method3::Gamma { c, until, keep },
            "min-area-change" => Method3::MinAreaChange { c, until, keep },
            _ => {
                no_keep(&keep, "triangles")?;
                Method3::VoronoiSkeleton {
                    max_seeds: args.seeds.max(1),
                }
            }
        };
        return run_3d(&args, ps.to_points3(), &Options3 { method }, &ext, report);
    }
    if !matches!(ext.as_str(), "csv" | "geojson" | "json" | "svg") {
        return Err(Failure::usage(format!(
            "{}: output must be .csv, .geojson, .json or .svg",
            args.output.display()
        )));
    }
    let (pts, keep) = report.time("read", || -> morpho::Result<_> {
        if ps.dim != 2 {
            return Err(
                Error::unsupported("boundary: points must be 2D or 3D").with_path(&args.input)
            );
        }
        let keep = match &args.keep {
            Some(k) => super::read_index_rows::<2>(k, "keep")?,
            None => Vec::new(),
        };
        Ok((ps.to_points2(), keep))
    })?;
    let with_keep = !keep.is_empty();
    let method = match method {
        "gamma" => Method2::Gamma { c, keep },
        "min-area-change" => Method2::MinAreaChange { c, keep },
        _ => {
            no_keep(&keep, "edges")?;
            Method2::VoronoiSkeleton {
                max_seeds: args.seeds.max(1),
            }
        }
    };
    let opts = Options2 { method };
    let b = report.time("compute", || boundary_2d(&pts, &opts).map_err(Error::from))?;
    let check = report.time("compute", || check_polygon(&pts, &b.polygon));
    report.set("method", opts.method.name());
    report.set("points", pts.len());
    report.set("boundary_vertices", b.polygon.len());
    report.set("duplicates_merged", duplicates(&pts));
    report.set("all_on_boundary", b.all_on_boundary);
    report.set("c_used", b.c_used);
    report.set("iterations", b.iterations);
    report.set("simple", check.simple);
    report.set("area", b.area);
    report.set("left_out", json!(b.left_out));
    if with_keep {
        report.set("keep_missing", json!(b.keep_missing));
    }
    if let Some(l) = b.skeleton_length {
        report.set("skeleton_length", l);
    }
    let out = &args.output;
    report.time("write", || -> morpho::Result<()> {
        if ext == "svg" {
            io::write_text(out, &render::boundary_svg(&pts, &b))?;
        } else {
            io::write_boundary_2d(out, &pts, &b)?;
        }
        if let Some(i) = &args.interior {
            io::write_interior_2d(i, &pts, &b)?;
        }
        Ok(())
    })?;
    if !check.simple {
        return Err(Failure {
            code: 1,
            msg: "boundary: internal error, the result is not a simple polygon".into(),
        });
    }
    if !b.all_on_boundary || !b.keep_missing.is_empty() {
        eprintln!(
            "error: boundary: no simple polygon through all points found: {} point(s) left out, {} keep edge(s) missing; the best polygon was written",
            b.left_out.len(),
            b.keep_missing.len()
        );
        return Ok(1);
    }
    Ok(0)
}

/// How many points repeat an earlier one (same coordinates; −0 equals 0): the boundary goes
/// through each location once, so these are merged into their first copy.
fn duplicates(pts: &[morpho::geom::Point2]) -> usize {
    let key = |v: f64| if v == 0.0 { 0u64 } else { v.to_bits() };
    let distinct: std::collections::HashSet<(u64, u64)> =
        pts.iter().map(|p| (key(p.x), key(p.y))).collect();
    pts.len() - distinct.len()
}

fn run_3d(
    args: &Args,
    pts: Vec<morpho::geom::Point3>,
    opts: &Options3,
    ext: &str,
    report: &mut Report,
) -> Result<u8, Failure> {
    if !matches!(ext, "ply" | "obj" | "off" | "vtu" | "vtk" | "json") {
        return Err(Failure::usage(format!(
            "{}: 3D output must be .ply, .obj, .off, .vtu, .vtk or .json",
            args.output.display()
        )));
    }
    let interior_ext = args.interior.as_deref().map(crate::cmd::extension);
    if let Some(e) = &interior_ext {
        if !matches!(e.as_str(), "json" | "ply" | "vtu" | "vtk") {
            return Err(Failure::usage(format!(
                "{}: the 3D interior is tetrahedra: write it as .json, .ply (tetra element), .vtu or .vtk",
                args.interior.as_deref().unwrap_or(Path::new("")).display()
            )));
        }
    }
    let b = report.time("compute", || boundary_3d(&pts, opts).map_err(Error::from))?;
    let vertices: std::collections::HashSet<u32> = b.triangles.iter().flatten().copied().collect();
    report.set("method", opts.method.name());
    report.set("points", pts.len());
    report.set("boundary_vertices", vertices.len());
    report.set("all_on_boundary", b.all_on_boundary);
    report.set("c_used", b.c_used);
    report.set("added_triangles", b.added_triangles);
    report.set("iterations", b.iterations);
    report.set("closed_manifold", b.closed_manifold);
    report.set("genus", json!(b.genus));
    report.set("self_intersections", b.intersections.len());
    report.set("triangles", b.triangles.len());
    report.set("volume", b.volume);
    report.set("left_out", json!(b.left_out));
    let with_keep = match &opts.method {
        Method3::Gamma { keep, .. } | Method3::MinAreaChange { keep, .. } => !keep.is_empty(),
        Method3::VoronoiSkeleton { .. } => false,
    };
    if with_keep {
        report.set("keep_missing", json!(b.keep_missing));
    }
    if let Some(l) = b.skeleton_length {
        report.set("skeleton_length", l);
    }
    report.time("write", || -> morpho::Result<()> {
        io::write_boundary_3d(&args.output, &pts, &b)?;
        if let Some(i) = &args.interior {
            if let Some(note) = io::json::interior_3d_note(&b) {
                eprintln!("warning: boundary: {note}");
            }
            if interior_ext.as_deref() == Some("json") {
                // `{"tetrahedra", "volume"}`, see the module docs
                io::write_atomic(i, |w| io::json::write_interior_3d(w, &b))?;
            } else {
                let tets = morpho::mesh::TetMesh {
                    positions: pts.clone(),
                    tets: b.interior.clone(),
                };
                io::write_tets(i, &tets, io::Encoding::BinaryLittleEndian)?;
            }
        }
        Ok(())
    })?;
    if !b.closed_manifold || b.genus != Some(0) || !b.intersections.is_empty() {
        return Err(Failure {
            code: 1,
            msg: "boundary: internal error, the result is not a closed genus-0 manifold without self-intersections".into(),
        });
    }
    if !b.all_on_boundary || !b.keep_missing.is_empty() {
        eprintln!(
            "error: boundary: {} point(s) are not on the boundary, {} keep triangle(s) missing; the best closed mesh was written",
            b.left_out.len(),
            b.keep_missing.len()
        );
        return Ok(1);
    }
    Ok(0)
}

/// The Voronoi skeleton method takes no keep edges or triangles (`what`).
fn no_keep<T>(keep: &[T], what: &'static str) -> morpho::Result<()> {
    if keep.is_empty() {
        return Ok(());
    }
    Err(BoundaryError::KeepUnsupported { what }.into())
}
