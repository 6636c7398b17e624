//! `morpho smooth IN -o OUT [--scheme curve|split3|split2|split6|side-vertex]
//! [--weights length|uniform|inverse] [--normals area|uniform|inverse|file] [--density N]
//! [--tension T]`: the G¹ curve through a polygon (Veltkamp 1992, §9.2; NOTES B.2), the cubic
//! three-split G¹ surface through a closed mesh (V §9.6; NOTES B.5), the cubic two-split
//! (V §9.7, experimental: pairs of triangles split at their common edge's midpoint where that
//! avoids thin micro triangles, the rest three-split; NOTES B.6; `morpho::smooth::two_split`;
//! report keys `pairs`, `rejected_pairs` and its parts `rejected_pairs_system`, `_move`,
//! `_check`), the cubic six-split
//! (V §9.8 rebuilt as a Powell–Sabin macro element with a prescribed normal field; NOTES B.7;
//! `morpho::smooth::six_split`) or Hamann's side-vertex surface of degree-elevated conics
//! (Hamann 1991, ch. 6; NOTES E); see `morpho::smooth`.
//!
//! - 2D input (`.csv`, `.geojson`: polygons with holes and polylines; every ring and polyline
//!   becomes one curve) → `.svg` (the true cubic path), `.json`
//!   `{"closed":true,"segments":[[[x,y]×4],…]}` (one curve) or `{"curves":[…]}` (several),
//!   `.geojson`/`.csv` (the curve sampled at `--density` points per segment, default 16).
//!   `--weights` is the tangent weighting (default `length`, the thesis's); a vertex where it
//!   fails G¹ is repaired with the uniform weighting and counted in `g1_failures`.
//! - Closed mesh (`.ply .obj .off .stl`) → the surface tessellated with `--density` steps per
//!   micro-patch edge (default 8; PLY carries the surface normals) or `.json`
//!   `{"degree":3,"patches":[{"macro":t,"control":[[x,y,z]×10]},…]}` (control points b300, b210,
//!   b201, b120, b111, b102, b030, b021, b012, b003). `--normals` as in `morpho curvature`.
//! - `--scheme side-vertex`: the rational side-vertex surface tessellated with `--density`
//!   steps per triangle edge (default 8, fewer on big meshes; PLY carries the surface normals);
//!   `--tension T` (default 1, the automatic weights of Thm 6.3) scales every conic weight;
//!   `--handle-floor K` (default 0.1, 0 = the text's conics) keeps conic handles from collapsing.
//!   No `.json` (the patches are not polynomial). Report: `max_normal_jump_rad` (20 samples per
//!   edge, finite-difference normals of both patches, `morpho::smooth::side_vertex_continuity`),
//!   `non_g1_edges`, `folds`, `fold_edges`, `inflected_edges` (generalized conics),
//!   `max_deviation` (surface vs flat mesh at the same parameter), `adjusted_normals`,
//!   `reversed_normals` (tessellation vertices whose surface normal points away from their
//!   triangles: folds inside a patch, see `morpho::smooth::side_vertex`).
//!
//! Report keys (3D): `max_normal_jump_rad` (every macro and micro edge, 20 samples per edge,
//! measured independently of the construction), `max_macro_jump_rad`, `max_micro_jump_rad`,
//! `non_g1_edges` (edges above 1e-9 rad), `folds` (samples with `n₁·n₂ ≤ 0`), `fold_edges`,
//! the non-G¹ edges by cause (`morpho::smooth::non_g1_causes`): `non_g1_micro`,
//! `non_g1_fold_invisible` (a fold at a vertex whose normal does not see its triangles),
//! `non_g1_fold`, `non_g1_inflected` (inflected or nearly flat macro edges), `non_g1_other`,
//! and `non_g1_unlisted` (non-G¹ macro edges the construction did not list as unresolved
//! or non-G¹), `non_g1_reported` (the macro edges the construction's own a-posteriori check
//! found not G¹: split3, split6 (both halves of a macro edge), split2 (split3's list less the
//! rebuilt edges)),
//! `singular_edges` (split6: edges built with the fallback normal field, inflected or flat),
//! `unresolved_edges` (split6: edges whose linear systems kept a residual: the only ones
//! that may be non-G¹), `sign_warnings`, `fold_guarded_edges` (split3 only),
//! `adjusted_normals` (with `--folds guard`, the default; see `morpho::smooth::visible_normals`
//! and `SplitOptions::fold_guard`), `max_displacement`,
//! `max_deviation` (surface vs flat mesh at the same parameter), `patches`, `triangles`;
//! (2D) `curves`, `segments`, `g1_failures`, `zero_handles`, `max_joint_sine`; timings.
//! Open, non-manifold or inconsistently oriented meshes, zero-area triangles, NaN, polygons
//! with repeated consecutive vertices or too few vertices: `error:` and exit 2.

use crate::report::Report;
use crate::Failure;
use morpho::geom::{Point2, Vector3};
use morpho::io::{self, Format};
use morpho::mesh::{NormalWeighting, Polygon, Polyline, Shapes2, TriMesh};
use morpho::smooth::{
    continuity, curve_joints, g1_curve, max_deviation, non_g1_causes, reversed_normals,
    side_vertex, side_vertex_continuity, six_split, tessellate, three_split_with, two_split,
    visible_normals, CurveWeighting, FailureKind, G1Curve, SideVertexOptions, SplitOptions,
};
use serde_json::json;
use std::path::{Path, PathBuf};

/// `morpho smooth` arguments.
#[derive(clap::Args)]
pub struct Args {
    /// Polygon or polyline (.csv .geojson) or closed triangle mesh (.ply .obj .off .stl).
    pub input: PathBuf,
    /// Output: .svg .json .geojson .csv for a curve; .ply .obj .off .stl .json for a surface.
    #[arg(short, long)]
    pub output: PathBuf,
    /// The construction (default: `curve` for 2D input, `split3` for a mesh; `side-vertex`:
    /// Hamann's conic surface; `split6`: the six-split, V §9.8 rebuilt, see
    /// `morpho::smooth::six_split`; `split2`: the two-split, V §9.7, experimental, see
    /// `morpho::smooth::two_split`).
    #[arg(long, value_parser = ["curve", "split3", "split2", "split6", "side-vertex"])]
    pub scheme: Option<String>,
    /// Side-vertex surface: scales every conic's automatic weight (1 = Thm 6.3; smaller
    /// values pull the surface towards the mesh).
    #[arg(long)]
    pub tension: Option<f64>,
    /// Side-vertex surface: the conics' handle floor κ in [0, 0.5] (default 0.1; 0 = the
    /// text's conics, whose handles can collapse; see `morpho::smooth::Conic`).
    #[arg(long)]
    pub handle_floor: Option<f64>,
    /// Tangent weighting of the curve (V §9.2).
    #[arg(long, default_value = "length", value_parser = ["length", "uniform", "inverse"])]
    pub weights: String,
    /// Vertex normals of the surface: estimated (V §9.4) or the file's.
    #[arg(long, default_value = "area", value_parser = ["area", "uniform", "inverse", "file"])]
    pub normals: String,
    /// Folds of the surface: `guard` (default) replaces vertex normals that do not see all
    /// their triangles and keeps a singular edge's cubic boundary where the quadratic one would
    /// fold a neighbour (reported as a crease); `keep` builds the text's construction as is.
    #[arg(long, default_value = "guard", value_parser = ["guard", "keep"])]
    pub folds: String,
    /// Samples per curve segment (2D sampled outputs, default 16) or steps per micro-patch
    /// edge of the tessellation (3D, default 8).
    #[arg(long)]
    pub density: Option<usize>,
}

/// A mesh file by its extension, gzipped too (`horse.obj.gz`).
fn is_mesh_input(p: &Path) -> bool {
    let mut e = crate::cmd::extension(p);
    if e == "gz" {
        e = p
            .file_stem()
            .map(|s| crate::cmd::extension(Path::new(s)))
            .unwrap_or_default();
    }
    matches!(e.as_str(), "ply" | "obj" | "off" | "stl")
}

/// Runs `morpho smooth`.
pub fn run(args: Args, report: &mut Report) -> Result<u8, Failure> {
    let mesh_in = is_mesh_input(&args.input);
    match (args.scheme.as_deref(), mesh_in) {
        (Some("curve"), true) => {
            return Err(Failure::usage(format!(
                "{}: --scheme curve smooths polygons (.csv .geojson); a mesh takes split3",
                args.input.display()
            )))
        }
        (Some(s @ ("split3" | "split2" | "split6" | "side-vertex")), false) => {
            return Err(Failure::usage(format!(
                "{}: --scheme {s} smooths closed meshes (.ply .obj .off .stl)",
                args.input.display()
            )))
        }
        _ => {}
    }
    let side = args.scheme.as_deref() == Some("side-vertex");
    if let Some(k) = args.handle_floor {
        if !side {
            return Err(Failure::usage(
                "--handle-floor applies to --scheme side-vertex only".to_string(),
            ));
        }
        if !(0.0..=0.5).contains(&k) {
            return Err(Failure::usage(format!(
                "--handle-floor must be in [0, 0.5], not {k}"
            )));
        }
    }
    if let Some(t) = args.tension {
        if !side {
            return Err(Failure::usage(
                "--tension applies to --scheme side-vertex only".to_string(),
            ));
        }
        if !(t > 0.0 && t <= 1e6) {
            return Err(Failure::usage(format!(
                "--tension must be in (0, 1e6], not {t}"
            )));
        }
    }
    if let Some(d) = args.density {
        let max = if mesh_in { 64 } else { 4096 };
        if d == 0 || d > max {
            return Err(Failure::usage(format!(
                "--density must be in 1..={max} here, not {d}"
            )));
        }
    }
    if side {
        run_side_vertex(&args, report)
    } else if mesh_in {
        run_surface(&args, report)
    } else {
        run_curve(&args, report)
    }
}

fn weighting(s: &str) -> CurveWeighting {
    match s {
        "uniform" => CurveWeighting::Uniform,
        "inverse" => CurveWeighting::InverseLength,
        _ => CurveWeighting::Length,
    }
}

fn curve_json(c: &G1Curve) -> serde_json::Value {
    json!({"closed": c.closed, "segments": c.segments})
}

/// The curve sampled at `n` points per segment (the segment's end is the next one's start;
/// an open curve adds its last vertex).
fn sampled(c: &G1Curve, n: usize) -> Vec<Point2> {
    let mut out = Vec::with_capacity(c.segments.len() * n + 1);
    for s in &c.segments {
        let b = morpho::smooth::BezierCurve {
            control: s.to_vec(),
        };
        for k in 0..n {
            let p = b.eval(k as f64 / n as f64);
            out.push(Point2::new(p[0], p[1]));
        }
    }
    if !c.closed {
        if let Some(s) = c.segments.last() {
            out.push(Point2::new(s[3][0], s[3][1]));
        }
    }
    out
}

fn run_curve(args: &Args, report: &mut Report) -> Result<u8, Failure> {
    let fmt = Format::of(&args.output)?;
    if !matches!(
        fmt,
        Format::Svg | Format::Json | Format::GeoJson | Format::Csv
    ) {
        return Err(Failure::usage(format!(
            "{}: a smooth curve is written as .svg, .json, .geojson or .csv",
            args.output.display()
        )));
    }
    let shapes = report.time("read", || io::read_shapes2(&args.input))?;
    let w = weighting(&args.weights);
    let fail = |e: morpho::smooth::SmoothError| {
        Failure::from(morpho::Error::from(e).with_path(&args.input))
    };
    // (curve, polygon index or None for a polyline)
    let mut curves: Vec<(G1Curve, Option<usize>)> = Vec::new();
    report.time("compute", || -> Result<(), Failure> {
        for (k, poly) in shapes.polygons.iter().enumerate() {
            for ring in &poly.rings {
                curves.push((g1_curve(ring, true, w).map_err(fail)?, Some(k)));
            }
        }
        for pl in &shapes.polylines {
            curves.push((g1_curve(&pl.points, pl.closed, w).map_err(fail)?, None));
        }
        Ok(())
    })?;
    if curves.is_empty() {
        return Err(Failure::usage(format!(
            "{}: no polygon or polyline to smooth",
            args.input.display()
        )));
    }
    let (mut fails, mut zero, mut segs, mut sine) = (0, 0, 0, 0.0f64);
    let mut cusps = 0;
    for (c, _) in &curves {
        fails += c.failures.len();
        zero += c
            .failures
            .iter()
            .filter(|f| f.kind == FailureKind::ZeroHandle)
            .count();
        segs += c.segments.len();
        for j in curve_joints(c) {
            sine = sine.max(j.sine);
            cusps += usize::from(j.dot <= 0.0);
        }
    }
    report.set("curves", curves.len());
    report.set("segments", segs);
    report.set("weights", args.weights.as_str());
    report.set("g1_failures", fails);
    report.set("zero_handles", zero);
    report.set("max_joint_sine", sine);
    report.set("cusps", cusps);
    let n = args.density.unwrap_or(16);
    let out = &args.output;
    report.time("write", || -> Result<(), Failure> {
        match fmt {
            Format::Svg => {
                let all: Vec<Point2> = curves
                    .iter()
                    .flat_map(|(c, _)| c.segments.iter().flatten())
                    .map(|p| Point2::new(p[0], p[1]))
                    .collect();
                let mut svg = morpho::render::Svg::fit(&all, 800.0);
                let stroke = morpho::render::Stroke::solid([40, 40, 40], 1.4);
                for (c, _) in &curves {
                    let s: Vec<[Point2; 4]> = c
                        .segments
                        .iter()
                        .map(|s| s.map(|p| Point2::new(p[0], p[1])))
                        .collect();
                    svg.cubics(&s, c.closed, &stroke);
                }
                io::write_text(out, &svg.finish())?;
            }
            Format::Json => {
                let v = if curves.len() == 1 {
                    curve_json(&curves[0].0)
                } else {
                    json!({"curves": curves.iter().map(|(c, _)| curve_json(c)).collect::<Vec<_>>()})
                };
                let mut text = serde_json::to_string(&v).map_err(|e| Failure {
                    code: 1,
                    msg: e.to_string(),
                })?;
                text.push('\n');
                io::write_text(out, &text)?;
            }
            _ => {
                let mut sh = Shapes2::default();
                for (c, poly) in &curves {
                    let pts = sampled(c, n);
                    match poly {
                        Some(k) => {
                            if sh.polygons.len() <= *k {
                                sh.polygons.resize(k + 1, Polygon::default());
                            }
                            sh.polygons[*k].rings.push(pts);
                        }
                        None => sh.polylines.push(Polyline {
                            points: pts,
                            closed: c.closed,
                        }),
                    }
                }
                io::write_shapes2(out, &sh)?;
            }
        }
        Ok(())
    })?;
    eprintln!(
        "wrote {} ({} curve{}, {} segments, {} G1 failure{} repaired)",
        out.display(),
        curves.len(),
        if curves.len() == 1 { "" } else { "s" },
        segs,
        fails,
        if fails == 1 { "" } else { "s" }
    );
    Ok(0)
}

/// The vertex normals `--normals` asks for.
fn normals(mesh: &TriMesh, which: &str, input: &Path) -> Result<Vec<Vector3>, Failure> {
    let w = match which {
        "file" => {
            return mesh.normals.clone().ok_or_else(|| {
                Failure::usage(format!(
                    "{}: --normals file, but the file has no vertex normals (nx, ny, nz)",
                    input.display()
                ))
            })
        }
        "uniform" => NormalWeighting::Uniform,
        "inverse" => NormalWeighting::InverseArea,
        _ => NormalWeighting::Area,
    };
    Ok(morpho::mesh::vertex_normals(mesh, w))
}

fn run_surface(args: &Args, report: &mut Report) -> Result<u8, Failure> {
    let fmt = Format::of(&args.output)?;
    if !io::is_mesh_format(fmt) && fmt != Format::Json {
        return Err(Failure::usage(format!(
            "{}: a smooth surface is written as .ply, .obj, .off, .stl (tessellated) or .json (patches)",
            args.output.display()
        )));
    }
    let mesh = report.time("read", || io::read_mesh(&args.input))?;
    let mut n = normals(&mesh, &args.normals, &args.input)?;
    let guard = args.folds == "guard";
    if guard {
        let a = report.time("normals", || visible_normals(&mesh, &n, 0.05));
        report.set("adjusted_normals", a.adjusted.len());
        report.set("adjusted_normals_infeasible", a.infeasible.len());
        report.set("max_normal_change_rad", a.max_change_rad);
        n = a.normals;
    }
    let opts = SplitOptions { fold_guard: guard };
    let scheme = args.scheme.as_deref().unwrap_or("split3");
    let mut pairs = None;
    let s = report.time("compute", || {
        match scheme {
            "split6" => six_split(&mesh, &n),
            "split2" => two_split(&mesh, &n, &opts).map(|t| {
                pairs = Some((t.pairs.len(), t.rejected.len(), t.rejected_by));
                t.surface
            }),
            _ => three_split_with(&mesh, &n, &opts),
        }
        .map_err(|e| Failure::from(morpho::Error::from(e).with_path(&args.input)))
    })?;
    if let Some((p, r, by)) = pairs {
        report.set("pairs", p);
        report.set("rejected_pairs", r);
        report.set("rejected_pairs_system", by.system);
        report.set("rejected_pairs_move", by.moved);
        report.set("rejected_pairs_check", by.check);
    }
    let c = report.time("check", || continuity(&s, 20));
    // default: 8 steps, fewer on big meshes (at most ~4M triangles); an explicit density is
    // refused beyond 32M triangles (no runaway allocation)
    let per = |d: usize| s.patches.len().saturating_mul(d * d);
    let density = match args.density {
        Some(d) if per(d) > 32_000_000 => {
            return Err(Failure::usage(format!(
                "--density {d} would give {} triangles over {} patches; choose a smaller density",
                per(d),
                s.patches.len()
            )))
        }
        Some(d) => d,
        None => (1..=8).rev().find(|&d| per(d) <= 4_000_000).unwrap_or(1),
    };
    let dev = report.time("deviation", || max_deviation(&s, &mesh, density.min(16)));
    report.set("scheme", scheme);
    report.set("normals", args.normals.as_str());
    report.set("vertices", mesh.positions.len());
    report.set("macro_triangles", mesh.triangles.len());
    report.set("patches", s.patches.len());
    report.set("max_normal_jump_rad", c.max_normal_jump_rad);
    report.set("max_macro_jump_rad", c.max_macro_jump_rad);
    report.set("max_micro_jump_rad", c.max_micro_jump_rad);
    report.set("max_position_gap", c.max_position_gap);
    report.set("non_g1_edges", c.non_g1_edges.len());
    let causes = non_g1_causes(&s, &mesh, &n, &c);
    report.set("non_g1_micro", causes.micro);
    report.set("non_g1_fold_invisible", causes.fold_invisible);
    report.set("non_g1_fold", causes.fold);
    report.set("non_g1_inflected", causes.inflected);
    report.set("non_g1_other", causes.other);
    report.set("non_g1_unlisted", causes.unlisted);
    report.set("non_g1_reported", s.non_g1_edges.len());
    report.set("non_g1_inner", s.non_g1_inner.len());
    report.set("split_edges", s.split_edges.len());
    report.set("edges_checked", c.edges);
    report.set("folds", c.folds);
    report.set("fold_edges", c.fold_edges);
    report.set("singular_edges", s.singular_edges.len());
    report.set("unresolved_edges", s.unresolved_edges.len());
    report.set("sign_warnings", s.sign_warnings.len());
    report.set("folds_mode", args.folds.as_str());
    report.set("fold_guarded_edges", s.fold_guarded.len());
    report.set("max_displacement", s.max_displacement);
    report.set("max_deviation", dev);
    let out = &args.output;
    if fmt == Format::Json {
        let patches: Vec<_> = s
            .patches
            .iter()
            .map(|p| json!({"macro": p.macro_tri, "control": p.control}))
            .collect();
        let mut text =
            serde_json::to_string(&json!({"degree": 3, "patches": patches})).map_err(|e| {
                Failure {
                    code: 1,
                    msg: e.to_string(),
                }
            })?;
        text.push('\n');
        report.time("write", || io::write_text(out, &text))?;
    } else {
        let t = report.time("tessellate", || {
            tessellate(&s, density)
                .map_err(|e| Failure::from(morpho::Error::from(e).with_path(&args.input)))
        })?;
        report.set("density", density);
        report.set("triangles", t.triangles.len());
        report.time("write", || {
            io::write_mesh(out, &t, io::Encoding::BinaryLittleEndian)
        })?;
    }
    eprintln!(
        "wrote {} ({} patches; max normal jump {:.1e} rad, {} non-G1 edges, {} fold edges, {} singular edges)",
        out.display(),
        s.patches.len(),
        c.max_normal_jump_rad,
        c.non_g1_edges.len(),
        c.fold_edges,
        s.singular_edges.len()
    );
    Ok(0)
}

/// `--scheme side-vertex`: Hamann's surface, tessellated (module doc).
fn run_side_vertex(args: &Args, report: &mut Report) -> Result<u8, Failure> {
    let fmt = Format::of(&args.output)?;
    if !io::is_mesh_format(fmt) {
        return Err(Failure::usage(format!(
            "{}: the side-vertex surface is written tessellated: .ply, .obj, .off or .stl",
            args.output.display()
        )));
    }
    let mesh = report.time("read", || io::read_mesh(&args.input))?;
    let mut n = normals(&mesh, &args.normals, &args.input)?;
    if args.folds == "guard" {
        let a = report.time("normals", || visible_normals(&mesh, &n, 0.05));
        report.set("adjusted_normals", a.adjusted.len());
        report.set("adjusted_normals_infeasible", a.infeasible.len());
        report.set("max_normal_change_rad", a.max_change_rad);
        n = a.normals;
    }
    let tension = args.tension.unwrap_or(1.0);
    let handle_floor = args.handle_floor.unwrap_or(0.1);
    let opts = SideVertexOptions {
        tension,
        handle_floor,
    };
    let s = report.time("compute", || {
        side_vertex(&mesh, &n, &opts)
            .map_err(|e| Failure::from(morpho::Error::from(e).with_path(&args.input)))
    })?;
    let c = report.time("check", || side_vertex_continuity(&s, 20, 1e-9));
    // default: 8 steps, fewer on big meshes (at most ~1M triangles: every point costs a few
    // dozen conic constructions); an explicit density is refused beyond 32M triangles
    let per = |d: usize| s.triangles.len().saturating_mul(d * d);
    let density = match args.density {
        Some(d) if per(d) > 32_000_000 => {
            return Err(Failure::usage(format!(
                "--density {d} would give {} triangles over {} patches; choose a smaller density",
                per(d),
                s.triangles.len()
            )))
        }
        Some(d) => d,
        None => (1..=8).rev().find(|&d| per(d) <= 1_000_000).unwrap_or(1),
    };
    let dev = report.time("deviation", || s.max_deviation(density.min(8)));
    let inflected = s.inflected_edges().len();
    report.set("scheme", "side-vertex");
    report.set("tension", tension);
    report.set("handle_floor", handle_floor);
    report.set("normals", args.normals.as_str());
    report.set("folds_mode", args.folds.as_str());
    report.set("vertices", mesh.positions.len());
    report.set("macro_triangles", mesh.triangles.len());
    report.set("patches", s.triangles.len());
    report.set("max_normal_jump_rad", c.max_normal_jump_rad);
    report.set("max_position_gap", c.max_position_gap);
    report.set("non_g1_edges", c.non_g1_edges.len());
    report.set("edges_checked", c.edges);
    report.set("folds", c.folds);
    report.set("fold_edges", c.fold_edges);
    report.set("inflected_edges", inflected);
    report.set("max_deviation", dev);
    let out = &args.output;
    let t = report.time("tessellate", || {
        s.tessellate(density)
            .map_err(|e| Failure::from(morpho::Error::from(e).with_path(&args.input)))
    })?;
    report.set("density", density);
    report.set("triangles", t.triangles.len());
    report.set("reversed_normals", reversed_normals(&t));
    report.time("write", || {
        io::write_mesh(out, &t, io::Encoding::BinaryLittleEndian)
    })?;
    eprintln!(
        "wrote {} (side-vertex, {} patches, {} triangles; max normal jump {:.1e} rad, {} inflected edges)",
        out.display(),
        s.triangles.len(),
        t.triangles.len(),
        c.max_normal_jump_rad,
        inflected
    );
    Ok(0)
}

/// The gallery sections of `morpho demo` (issue 19): the chalice's boundary polygon
/// (γ-constriction, Veltkamp 1992, §5.2) and a coarse subset of it with their G¹ cubic curves
/// (V §9.2), and a reduced scan (Hamann ch. 5) with its three-split (V §9.6) and side-vertex
/// (H ch. 6) surfaces, shaded and with reflection lines (V §8.4) beside the input mesh.
pub fn demo_section(ctx: &super::demo::Ctx) -> morpho::Result<Vec<morpho::io::html::Section>> {
    let mut out = vec![curve_demo(ctx)?];
    if let Some(path) = ctx.data_file("meshes/spot.obj") {
        out.push(surface_demo(ctx, &path)?);
    }
    Ok(out)
}

/// The chalice boundary and every fifth of its vertices, each with its G¹ curve (SVG).
fn curve_demo(ctx: &super::demo::Ctx) -> morpho::Result<morpho::io::html::Section> {
    use morpho::boundary::{boundary_2d, Options2};
    use morpho::io::html::Section;
    use morpho::render::{Stroke, Svg};
    let pts = morpho::samples::chalice_outline(240, 0.3, 1);
    let b = boundary_2d(&pts, &Options2::default())?;
    let full: Vec<Point2> = b.polygon.iter().map(|&i| pts[i as usize]).collect();
    let coarse: Vec<Point2> = full.iter().step_by(5).copied().collect();
    let mut s = Section::new(
        "Smooth curve: the G¹ cubic curve through the chalice boundary (Veltkamp §9.2)",
        "The closed boundary polygon of the chalice points (γ-constriction, §5.2), and every \
         fifth of its vertices, each with the cubic Bézier curve through every vertex: tangents \
         by length (the thesis default, T_i ∝ v_{i+1} − v_{i−1}), inner control points a third \
         of the way to the other end's projection onto the tangent line. A vertex where the \
         projections of its neighbours fall on one side (only tangent-line continuity, NOTES \
         B.2) is repaired with the uniform weighting and drawn red. Grey: the polygon; blue: \
         the curve (true cubic SVG path).",
    );
    for (poly, name, what) in [
        (&full, "smooth_chalice.svg", "boundary polygon"),
        (&coarse, "smooth_chalice_coarse.svg", "every fifth vertex"),
    ] {
        let t0 = std::time::Instant::now();
        let c = g1_curve(poly, true, CurveWeighting::Length)?;
        let dt = t0.elapsed().as_secs_f64();
        let joints = curve_joints(&c);
        let sine = joints.iter().fold(0.0f64, |m, j| m.max(j.sine));
        let cusps = joints.iter().filter(|j| j.dot <= 0.0).count();
        let mut svg = Svg::fit(poly, 640.0);
        svg.polyline(poly, true, &Stroke::solid([150, 150, 150], 1.0));
        let segs: Vec<[Point2; 4]> = c
            .segments
            .iter()
            .map(|s| s.map(|p| Point2::new(p[0], p[1])))
            .collect();
        svg.cubics(&segs, true, &Stroke::solid([25, 60, 170], 1.5));
        svg.points(poly, if poly.len() > 100 { 1.1 } else { 2.0 }, [60, 60, 60]);
        let failed: Vec<Point2> = c.failures.iter().map(|f| poly[f.vertex]).collect();
        svg.points(&failed, 3.5, [210, 30, 30]);
        morpho::io::write_text(&ctx.path(name), &svg.finish())?;
        s.img(
            name,
            &format!(
                "{what}: {} vertices, {} repaired",
                poly.len(),
                c.failures.len()
            ),
        );
        s.fig(
            &format!("{what}: vertices / repaired / cusps"),
            format!("{} / {} / {cusps}", poly.len(), c.failures.len()),
        );
        s.fig(
            &format!("{what}: max |P′(1)×Q′(0)| / (|P′(1)||Q′(0)|)"),
            format!("{sine:.1e} ({:.2} ms)", dt * 1e3),
        );
    }
    Ok(s)
}

/// The demo table's "max normal jump (rad) / non-G¹ edges of all / fold edges" of one surface.
fn jump_row(c: &morpho::smooth::Continuity) -> String {
    format!(
        "{:.1e} / {} of {} / {}",
        c.max_normal_jump_rad,
        c.non_g1_edges.len(),
        c.edges,
        c.fold_edges
    )
}

/// Spot reduced to 20 % (Hamann's Algorithm 5.1), its three-split, six-split and side-vertex
/// surfaces.
fn surface_demo(ctx: &super::demo::Ctx, path: &Path) -> morpho::Result<morpho::io::html::Section> {
    use morpho::io::html::Section;
    use morpho::reduce::{reduce, ReduceOptions, Stop};
    use morpho::render::{render_mesh, ReflectionLines, RenderOptions, Shading, UpAxis};
    let input = io::read_mesh(path)?;
    let r = reduce(
        &input,
        &ReduceOptions {
            stop: Stop::Keep(20.0),
            ..Default::default()
        },
    )
    .map_err(|e| morpho::Error::from(e).with_path(path))?;
    let m = r.mesh;
    io::write_mesh(&ctx.path("smooth_spot20.ply"), &m, io::Encoding::default())?;
    let mut s = Section::new(
        "Smooth surfaces: a reduced scan, three-split, two-split, six-split and side-vertex (Veltkamp §9.6–9.8, Hamann ch. 6)",
        "meshes/spot.obj reduced to 20 % of its triangles (Hamann's Algorithm 5.1), area-weighted \
         vertex normals (V §9.4; the few that do not see all their triangles adjusted), then the \
         cubic three-split (V §9.6: Farin's interior point, the Clough–Tocher split at the \
         centroid; per edge a degree-elevated quadratic boundary where one fits, else (9.4) where it \
         moves L1, R1 at most 3 edge lengths, else a bounded correction left creased and counted \
         as unresolved), the two-split (V §9.7, experimental: pairs of triangles across an edge \
         split at its midpoint where that avoids thin three-split micro triangles, chosen greedily \
         thinnest first with no two pairs adjacent, each pair C¹ over its unfolded quadrilateral, \
         its outer edges on a linear normal field shared with the three-split neighbour; a pair \
         whose system or local check fails stays three-split), the six-split (V §9.8 rebuilt: a C¹ piecewise-quadratic boundary, a \
         prescribed normal field per macro edge — linear where the edge is not inflected, through \
         the natural boundary with a free end scale where it is —, Powell–Sabin interior; a side \
         that would turn outward takes the nearest inward member of its exact solutions, and \
         where none exists, or the field has no positive solution, the edge falls back to a \
         reported crease) and Hamann's \
         side-vertex surface of degree-elevated conics (H ch. 6, automatic weights), each \
         tessellated with surface normals. Left to right: the input (flat), the three-split, the \
         two-split, the six-split, the side-vertex surface. Second row: reflection lines (V §8.4): parallel light lines far \
         away, reflected by the surface normals; they run continuously across a G¹ surface and \
         break at every edge of the flat mesh, and at the split surfaces' unresolved edges. (9.4) \
         alone gave the 'wild oscillation' of V Fig. 9.5 here: near-mirror-image triangles make \
         it nearly singular and pushed L1, R1 up to 1.4e14 edge lengths out; the continuity \
         figures are measured independently at 20 samples per macro and micro edge.",
    );
    s.fig(
        "input → reduced triangles",
        format!("{} → {}", input.triangles.len(), m.triangles.len()),
    );
    let n = morpho::mesh::vertex_normals(&m, NormalWeighting::Area);
    let adj = visible_normals(&m, &n, 0.05);
    s.fig("adjusted normals", adj.adjusted.len());
    let n = adj.normals;
    let t0 = std::time::Instant::now();
    let split = three_split_with(&m, &n, &SplitOptions { fold_guard: true })?;
    let t_split = t0.elapsed().as_secs_f64();
    let c3 = continuity(&split, 20);
    let dev3 = max_deviation(&split, &m, 8);
    let tess3 = tessellate(&split, 6)?;
    s.fig(
        "three-split: max normal jump (rad) / non-G¹ edges / fold edges",
        jump_row(&c3),
    );
    s.fig(
        "three-split: singular / unresolved edges, max displacement, max deviation",
        format!(
            "{} / {}, {:.1} edge lengths, {:.3}",
            split.singular_edges.len(),
            split.unresolved_edges.len(),
            split.max_displacement,
            dev3
        ),
    );
    s.fig(
        "three-split: construction time",
        format!("{:.1} ms", t_split * 1e3),
    );
    let t0 = std::time::Instant::now();
    let split2 = two_split(&m, &n, &SplitOptions { fold_guard: true })?;
    let t_split2 = t0.elapsed().as_secs_f64();
    let c2 = continuity(&split2.surface, 20);
    let tess2 = tessellate(&split2.surface, 6)?;
    s.fig(
        "two-split: max normal jump (rad) / non-G¹ edges / fold edges",
        jump_row(&c2),
    );
    s.fig(
        "two-split: pairs (rejected), unresolved edges, max deviation, construction time",
        format!(
            "{} ({}), {}, {:.3}, {:.1} ms",
            split2.pairs.len(),
            split2.rejected.len(),
            split2.surface.unresolved_edges.len(),
            max_deviation(&split2.surface, &m, 8),
            t_split2 * 1e3
        ),
    );
    let t0 = std::time::Instant::now();
    let split6 = six_split(&m, &n)?;
    let t_split6 = t0.elapsed().as_secs_f64();
    let c6 = continuity(&split6, 20);
    let tess6 = tessellate(&split6, 4)?;
    s.fig(
        "six-split: max normal jump (rad) / non-G¹ edges / fold edges",
        jump_row(&c6),
    );
    s.fig(
        "six-split: fallback / unresolved edges, max deviation, construction time",
        format!(
            "{} / {}, {:.3}, {:.1} ms",
            split6.singular_edges.len(),
            split6.unresolved_edges.len(),
            max_deviation(&split6, &m, 8),
            t_split6 * 1e3
        ),
    );
    let t0 = std::time::Instant::now();
    let sv = side_vertex(&m, &n, &SideVertexOptions::default())?;
    let t_sv = t0.elapsed().as_secs_f64();
    let csv = side_vertex_continuity(&sv, 20, 1e-9);
    let tess_sv = sv.tessellate(6)?;
    s.fig(
        "side-vertex: max normal jump (rad) / non-G¹ edges / fold edges",
        jump_row(&csv),
    );
    s.fig(
        "side-vertex: inflected edges, max deviation, construction time",
        format!(
            "{}, {:.3}, {:.1} ms",
            sv.inflected_edges().len(),
            sv.max_deviation(6),
            t_sv * 1e3
        ),
    );
    for (t, name) in [
        (&tess3, "smooth_spot_split3.ply"),
        (&tess2, "smooth_spot_split2.ply"),
        (&tess6, "smooth_spot_split6.ply"),
        (&tess_sv, "smooth_spot_side_vertex.ply"),
    ] {
        io::write_mesh(&ctx.path(name), t, io::Encoding::BinaryLittleEndian)?;
        s.files.push(name.into());
    }
    s.files.push("smooth_spot20.ply".into());
    let base = RenderOptions {
        width: 380,
        height: 380,
        up: UpAxis::Y,
        azimuth_deg: 150.0,
        elevation_deg: 20.0,
        ..Default::default()
    };
    let flat = RenderOptions {
        shading: Shading::Flat,
        ..base.clone()
    };
    let lines = |o: &RenderOptions| RenderOptions {
        reflection_lines: Some(ReflectionLines::default()),
        ..o.clone()
    };
    let shaded = [
        render_mesh(&m, &flat),
        render_mesh(&tess3, &base),
        render_mesh(&tess2, &base),
        render_mesh(&tess6, &base),
        render_mesh(&tess_sv, &base),
    ];
    let striped = [
        render_mesh(&m, &lines(&flat)),
        render_mesh(&tess3, &lines(&base)),
        render_mesh(&tess2, &lines(&base)),
        render_mesh(&tess6, &lines(&base)),
        render_mesh(&tess_sv, &lines(&base)),
    ];
    super::reduce::hstack(&shaded).save_png(&ctx.path("smooth_spot.png"))?;
    s.img(
        "smooth_spot.png",
        "input (flat) · three-split · two-split · six-split · side-vertex",
    );
    super::reduce::hstack(&striped).save_png(&ctx.path("smooth_spot_reflection.png"))?;
    s.img(
        "smooth_spot_reflection.png",
        "reflection lines: input (facet normals) · three-split · two-split · six-split · side-vertex",
    );
    Ok(s)
}
