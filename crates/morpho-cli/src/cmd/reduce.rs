//! `morpho reduce MESH -o OUT (--keep PCT | --triangles N | --rms TOL | --max-error E)`:
//! curvature-driven triangle reduction (Hamann 1991, ch. 5; `morpho::reduce`). The least
//! significant triangle (flat and well-shaped first) is replaced by one point fitted to the
//! surface, repeatedly; parts, boundary loops and the Euler characteristic (genus) stay, the
//! output is manifold, consistently oriented and gains no self-intersection.
//!
//! - Stops (exactly one): `--keep PCT` of the triangles kept, in (0, 100]; `--triangles N` at
//!   most N left (N ≤ the input's count); `--rms TOL` (alias `--tolerance`) the RMS error at
//!   the input's vertices stays ≤ TOL (Rem. 5.10; the removal that would exceed it is not
//!   made); `--max-error E` the largest such error stays ≤ E. For surfaces the tracked error
//!   is the distance of each input vertex to the reduced triangle it is assigned to (an upper
//!   bound of its distance to the reduced surface); with `--height-field` the vertical error
//!   of (5.41).
//! - `--point bivariate|implicit` (H (5.29) / (5.33)); `--freeze-boundary` never removes a
//!   triangle touching the boundary (Rem. 5.8); `--height-field` reduces the graph of a
//!   function over xy keeping the domain covered, fold-free (Table 5.1); `--normals` of the
//!   H ch. 4 curvature fit (`area` default, `uniform`, `inverse`, `file`);
//!   `--new-triangles generations|last-step` (Rem. 5.9, see `morpho::reduce::NewTriangles`).
//! - `--order levels|hamann`: `levels` (default) removes in Hamann's weight order within
//!   doubling error levels, placing the new point at the fit or at a corner, whichever moves
//!   the input less (`morpho::reduce::Order::ErrorLevels`, an extension: 1.8–5.6× smaller RMS
//!   on the scans at 50–90 %, 2.4–5.8× slower); `hamann` is Algorithm 5.1's order alone.
//! - `--check`: the output is tested for self-intersections with the exact triangle–triangle
//!   test (the reduction itself checks every re-triangulation locally); a new intersection
//!   is a bug (exit 1).
//! - Open meshes are accepted: their boundary loops stay (boundary vertices may move along the
//!   surface; `--freeze-boundary` keeps them). Refused with exit 2: no triangles, a
//!   non-manifold edge or vertex, inconsistent orientation, a degenerate triangle, NaN or
//!   infinite coordinates, a stop value out of range, `--height-field` on a mesh that is not
//!   counter-clockwise over xy.
//! - Vertex data: normals and PLY vertex properties of vertices that keep their position are
//!   copied; new points take the values at the closest point of the input (floats and normals
//!   interpolated, integers from the nearest corner). Face properties are dropped (every
//!   triangle around a removal is new); the report says so.
//!
//! Report keys: `triangles_in`, `triangles_out`, `vertices_in`, `vertices_out`, `removals`,
//! `stop` (`target`, `tolerance`, `no_removable_left`), `no_removable_left` (true when it
//! stopped before the target: nothing removable, Rem. 5.11; exit 0 with a `note:`),
//! `euler_characteristic`, `genus`, `parts`, `boundary_loops`, `manifold`,
//! `consistently_oriented`, `rms` (input vertices to the output surface; vertical (5.41) with
//! `--height-field`), `max_error`, `hausdorff` (symmetric, sampled), `hausdorff_samples`,
//! `rms_tracked` / `max_tracked` (the stop's own measure, when tracked), `point`,
//! `vertices_interpolated`, `face_properties_dropped`, `self_intersections` (with `--check`),
//! `triangles_per_second`, and `timings` (`read`, `compute`, `measure`, `check`, `write`).

use crate::report::Report;
use crate::Failure;
use morpho::curvature::NormalSource;
use morpho::io;
use morpho::mesh::{analyze_topology, NormalWeighting};
use morpho::reduce::{
    carry_vertex_data, mesh_distance, reduce, Domain, NewPoint, NewTriangles, Order, ReduceOptions,
    Stop, StopReason,
};
use std::path::PathBuf;

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum PointArg {
    /// Bivariate quadratic over the removed triangle's plane (H (5.29); the thesis's choice).
    Bivariate,
    /// Implicit quadric intersected with the normal line (H (5.33)).
    Implicit,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum OrderArg {
    /// Weight order within doubling error levels (default; see morpho::reduce::Order).
    Levels,
    /// Weight order alone, Algorithm 5.1 as written.
    Hamann,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum NewArg {
    /// New triangles wait until no old triangle is removable (default).
    Generations,
    /// Only the last step's triangles wait.
    LastStep,
}

/// `morpho reduce` arguments.
#[derive(clap::Args, Debug)]
#[command(group(clap::ArgGroup::new("stop").required(true).multiple(false)
    .args(["keep", "triangles", "rms", "max_error"])))]
pub struct Args {
    /// Input triangle mesh (.ply .obj .off .stl).
    pub input: PathBuf,
    /// Output mesh (.ply keeps normals and vertex properties).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Percentage of the triangles to keep, in (0, 100].
    #[arg(long, value_name = "PCT", allow_hyphen_values = true)]
    pub keep: Option<f64>,
    /// Stop at this many triangles or fewer.
    #[arg(long, value_name = "N")]
    pub triangles: Option<usize>,
    /// Stop before the RMS error at the input's vertices would exceed TOL.
    #[arg(
        long,
        alias = "tolerance",
        value_name = "TOL",
        allow_hyphen_values = true
    )]
    pub rms: Option<f64>,
    /// Stop before the largest error at the input's vertices would exceed E.
    #[arg(long, value_name = "E", allow_hyphen_values = true)]
    pub max_error: Option<f64>,
    /// How the new point is computed.
    #[arg(long, value_enum, default_value_t = PointArg::Bivariate)]
    pub point: PointArg,
    /// Never remove a triangle with a corner on the boundary (Rem. 5.8).
    #[arg(long)]
    pub freeze_boundary: bool,
    /// The mesh is the graph of a function over xy: keep the domain covered, fold-free, and
    /// measure vertical errors (Table 5.1).
    #[arg(long)]
    pub height_field: bool,
    /// Normals of the curvature fit at the input's vertices.
    #[arg(long, default_value = "area", value_parser = ["area", "uniform", "inverse", "file"])]
    pub normals: String,
    /// Removal order: Hamann's weight alone, or within doubling error levels.
    #[arg(long, value_enum, default_value_t = OrderArg::Levels)]
    pub order: OrderArg,
    /// Which triangles count as "new" (Rem. 5.9).
    #[arg(long, value_enum, default_value_t = NewArg::Generations)]
    pub new_triangles: NewArg,
    /// Test the output for self-intersections (exact).
    #[arg(long)]
    pub check: bool,
}

/// Runs `morpho reduce`.
pub fn run(args: Args, report: &mut Report) -> Result<u8, Failure> {
    let out_ext = crate::cmd::extension(&args.output);
    if !matches!(out_ext.as_str(), "ply" | "obj" | "off" | "stl") {
        return Err(Failure::usage(format!(
            "{}: a reduced mesh is written as .ply, .obj, .off or .stl",
            args.output.display()
        )));
    }
    let stop = match (args.keep, args.triangles, args.rms, args.max_error) {
        (Some(p), ..) => Stop::Keep(p),
        (_, Some(n), ..) => Stop::Triangles(n),
        (_, _, Some(e), _) => Stop::Rms(e),
        (.., Some(e)) => Stop::MaxError(e),
        _ => {
            return Err(Failure::usage(
                "give one of --keep, --triangles, --rms, --max-error",
            ))
        }
    };
    let mesh = report.time("read", || io::read_mesh(&args.input))?;
    let with_path = |e: morpho::reduce::ReduceError| {
        Failure::from(morpho::Error::from(e).with_path(&args.input))
    };
    let opts = ReduceOptions {
        stop,
        point: match args.point {
            PointArg::Bivariate => NewPoint::Bivariate,
            PointArg::Implicit => NewPoint::Implicit,
        },
        freeze_boundary: args.freeze_boundary,
        domain: if args.height_field {
            Domain::HeightField
        } else {
            Domain::Surface
        },
        normals: match args.normals.as_str() {
            "file" => NormalSource::File,
            "uniform" => NormalSource::Estimated(NormalWeighting::Uniform),
            "inverse" => NormalSource::Estimated(NormalWeighting::InverseArea),
            _ => NormalSource::Estimated(NormalWeighting::Area),
        },
        check_intersections: !args.height_field,
        new_triangles: match args.new_triangles {
            NewArg::Generations => NewTriangles::Generations,
            NewArg::LastStep => NewTriangles::LastStep,
        },
        order: match args.order {
            OrderArg::Levels => Order::ErrorLevels,
            OrderArg::Hamann => Order::Hamann,
        },
    };
    if opts.normals == NormalSource::File && mesh.normals.is_none() {
        return Err(Failure::usage(format!(
            "{}: --normals file, but the mesh has no vertex normals",
            args.input.display()
        )));
    }
    let t0 = std::time::Instant::now();
    let r = report.time("compute", || reduce(&mesh, &opts).map_err(with_path))?;
    let secs = t0.elapsed().as_secs_f64();
    let mut out = r.mesh.clone();
    let interpolated = carry_vertex_data(&mesh, &mut out, &r.source);
    let topo = analyze_topology(&out);
    let d = report.time("measure", || mesh_distance(&mesh, &out));
    let (rms, max_error) = if args.height_field {
        (r.rms.unwrap_or(f64::NAN), r.max_error.unwrap_or(f64::NAN))
    } else {
        (d.rms, d.max_input_to_output)
    };
    report.set("triangles_in", r.triangles_in);
    report.set("triangles_out", out.triangles.len());
    report.set("vertices_in", mesh.positions.len());
    report.set("vertices_out", out.positions.len());
    report.set("removals", r.removals);
    let early = r.stop == StopReason::NoRemovable;
    report.set(
        "stop",
        match r.stop {
            StopReason::Target => "target",
            StopReason::Tolerance => "tolerance",
            StopReason::NoRemovable => "no_removable_left",
        },
    );
    report.set("no_removable_left", early);
    report.set("euler_characteristic", topo.euler_characteristic);
    report.set("genus", topo.genus());
    report.set("parts", topo.parts.len());
    report.set("boundary_loops", topo.boundary_loops.len());
    report.set("manifold", topo.manifold);
    report.set("consistently_oriented", topo.consistently_oriented);
    report.set("rms", rms);
    report.set("max_error", max_error);
    report.set(
        "error_measure",
        if args.height_field {
            "vertical at the input's vertices (5.41)"
        } else {
            "distance of the input's vertices to the output surface"
        },
    );
    report.set("hausdorff", d.hausdorff);
    report.set("hausdorff_samples", d.output_samples + mesh.positions.len());
    if let Some(x) = r.rms {
        report.set("rms_tracked", x);
    }
    if let Some(x) = r.max_error {
        report.set("max_tracked", x);
    }
    if let Stop::Rms(e) | Stop::MaxError(e) = stop {
        report.set("tolerance", e);
    }
    report.set(
        "point",
        match args.point {
            PointArg::Bivariate => "bivariate",
            PointArg::Implicit => "implicit",
        },
    );
    report.set("vertices_interpolated", interpolated);
    report.set("face_properties_dropped", mesh.face_props.len());
    report.set(
        "triangles_per_second",
        if secs > 0.0 {
            (r.triangles_in - out.triangles.len()) as f64 / secs
        } else {
            0.0
        },
    );
    let mut code = 0;
    if args.check {
        let pos: Vec<[f64; 3]> = out.positions.iter().map(|p| p.coords.into()).collect();
        let hits = report.time("check", || {
            morpho::mesh::validity::self_intersections(&pos, &out.triangles, 1000)
        });
        report.set("self_intersections", hits.len());
        if !hits.is_empty() {
            let pin: Vec<[f64; 3]> = mesh.positions.iter().map(|p| p.coords.into()).collect();
            let before = morpho::mesh::validity::self_intersections(&pin, &mesh.triangles, 1);
            if before.is_empty() {
                eprintln!(
                    "error: {}: the reduction created {} self-intersecting triangle pair(s) (a bug; please report)",
                    args.input.display(),
                    hits.len()
                );
                code = 1;
            } else {
                eprintln!(
                    "note: {}: the input already intersects itself; the output has {} intersecting pair(s)",
                    args.input.display(),
                    hits.len()
                );
            }
        }
    }
    report.time("write", || {
        io::write_mesh(&args.output, &out, io::Encoding::BinaryLittleEndian)
    })?;
    if early {
        eprintln!(
            "note: no removable triangle left (Rem. 5.11): stopped at {} triangles",
            out.triangles.len()
        );
    }
    eprintln!(
        "wrote {} ({} → {} triangles, rms {:.3e}, hausdorff {:.3e})",
        args.output.display(),
        r.triangles_in,
        out.triangles.len(),
        rms,
        d.hausdorff
    );
    Ok(code)
}

/// Images side by side (top-aligned, white gaps of 8 px).
pub(crate) fn hstack(images: &[morpho::render::Image]) -> morpho::render::Image {
    let gap = 8;
    let w = images.iter().map(|i| i.width).sum::<u32>() + gap * (images.len() as u32 - 1);
    let h = images.iter().map(|i| i.height).max().unwrap_or(1);
    let mut out = morpho::render::Image::new(w, h, [255, 255, 255, 255]);
    let mut x0 = 0;
    for im in images {
        for y in 0..im.height {
            for x in 0..im.width {
                out.put(x0 + x, y, im.get(x, y));
            }
        }
        x0 += im.width + gap;
    }
    out
}

/// The demo's two views of a mesh, 420 px square: flat shaded (as in H Fig. 5.11) and the same
/// with its edges drawn.
fn flat_and_wire(
    up: morpho::render::UpAxis,
    azimuth_deg: f64,
    elevation_deg: f64,
) -> (morpho::render::RenderOptions, morpho::render::RenderOptions) {
    let shaded = morpho::render::RenderOptions {
        width: 420,
        height: 420,
        up,
        azimuth_deg,
        elevation_deg,
        shading: morpho::render::Shading::Flat,
        ..Default::default()
    };
    let wire = morpho::render::RenderOptions {
        wireframe: true,
        wire_color: [40, 50, 70],
        ..shaded.clone()
    };
    (shaded, wire)
}

/// The gallery sections of `morpho demo`: a real scan reduced to 25 % and 10 % beside the
/// original (flat shaded, H Fig. 5.11 style), and Table 5.1 with the pictures of Figs
/// 5.7–5.9 (original, 50/80/90 % removed).
pub fn demo_section(ctx: &super::demo::Ctx) -> morpho::Result<Vec<morpho::io::html::Section>> {
    use morpho::io::html::Section;
    use morpho::render::{render_mesh, RenderOptions, Shading, UpAxis};
    let mut out = Vec::new();
    for (file, stem, title, az, el) in [
        (
            "meshes/stanford-bunny.obj.gz",
            "reduce_bunny",
            "the Stanford bunny (range scan, open: 5 holes in the base)",
            20.0,
            20.0,
        ),
        (
            "meshes/horse.obj.gz",
            "reduce_horse",
            "the Cyberware horse (closed scan)",
            60.0,
            15.0,
        ),
    ] {
        let Some(path) = ctx.data_file(file) else {
            continue;
        };
        let m = morpho::io::read_mesh(&path)?;
        let mut s = Section::new(
            &format!("Triangle reduction: {title}"),
            &format!(
                "Hamann ch. 5 (Algorithm 5.1): the triangle of least weight ω = σρ (angle weight \
                 × absolute curvature) whose corona is continuous, acyclic and passes the \
                 half-plane test is replaced by one point of the bivariate quadratic fit; new \
                 triangles wait until no old one is removable (Rem. 5.9). Left to right: {file} \
                 as read, 25 % and 10 % of its triangles kept; flat shaded, as in H Fig. 5.11. \
                 The second row shows the edges of the two reductions: flat regions are emptied \
                 first, curved ones keep their triangles."
            ),
        );
        let (shaded, wire) = flat_and_wire(UpAxis::Y, az, el);
        let mut row = vec![render_mesh(&m, &shaded)];
        let mut edges = Vec::new();
        let t = morpho::mesh::analyze_topology(&m);
        s.fig("input triangles", m.triangles.len());
        s.fig(
            "input χ / genus / loops",
            format!(
                "{} / {} / {}",
                t.euler_characteristic,
                t.genus().map_or("-".into(), |g| g.to_string()),
                t.boundary_loops.len()
            ),
        );
        for keep in [25.0, 10.0] {
            let opts = ReduceOptions {
                stop: Stop::Keep(keep),
                ..Default::default()
            };
            let t0 = std::time::Instant::now();
            let r = reduce(&m, &opts).map_err(|e| morpho::Error::from(e).with_path(&path))?;
            let secs = t0.elapsed().as_secs_f64();
            let d = mesh_distance(&m, &r.mesh);
            let to = morpho::mesh::analyze_topology(&r.mesh);
            row.push(render_mesh(&r.mesh, &shaded));
            edges.push(render_mesh(&r.mesh, &wire));
            let name = format!("{stem}_{keep}.ply");
            morpho::io::write_mesh(&ctx.path(&name), &r.mesh, morpho::io::Encoding::default())?;
            s.files.push(name);
            s.fig(
                &format!("{keep} %: triangles"),
                format!(
                    "{} ({:.2} s, {:.0} removed/s)",
                    r.mesh.triangles.len(),
                    secs,
                    (m.triangles.len() - r.mesh.triangles.len()) as f64 / secs.max(1e-9)
                ),
            );
            s.fig(
                &format!("{keep} %: χ / genus / loops / manifold"),
                format!(
                    "{} / {} / {} / {}",
                    to.euler_characteristic,
                    to.genus().map_or("-".into(), |g| g.to_string()),
                    to.boundary_loops.len(),
                    if to.manifold && to.consistently_oriented {
                        "yes"
                    } else {
                        "no"
                    }
                ),
            );
            s.fig(
                &format!("{keep} %: rms / Hausdorff"),
                format!("{:.2e} / {:.2e}", d.rms, d.hausdorff),
            );
        }
        hstack(&row).save_png(&ctx.path(&format!("{stem}.png")))?;
        s.img(&format!("{stem}.png"), "original · 25 % kept · 10 % kept");
        hstack(&edges).save_png(&ctx.path(&format!("{stem}_edges.png")))?;
        s.img(&format!("{stem}_edges.png"), "edges: 25 % kept · 10 % kept");
        out.push(s);
    }
    if let Some(path) = ctx.data_file("volumes/cthead_8bit_256x256x99.json") {
        out.push(skull_section(ctx, &path)?);
    }
    // Table 5.1 and Figs 5.7–5.9
    use morpho::reduce::table51;
    let mut s = Section::new(
        "Triangle reduction: Table 5.1 of Hamann's thesis",
        "The 9 functions on the 51×51 grid of [-1, 1]² (5000 triangles), reduced by 50, 80 and \
         90 % as height fields (the domain stays covered), RMS (5.41) of the piecewise-linear \
         result at the 2601 knots beside the thesis's values. Pictures: the paraboloid (H Fig. \
         5.7), the cubic (5.8) and the trigonometric function (5.9), original and 50/80/90 % \
         removed, seen from above the graph.",
    );
    for (k, (name, f, g)) in table51::functions().iter().enumerate() {
        let mut cells = Vec::new();
        let mut pics = Vec::new();
        let show = [3usize, 6, 8].contains(&k);
        let wire = RenderOptions {
            width: 300,
            height: 300,
            up: UpAxis::Z,
            azimuth_deg: 20.0,
            elevation_deg: 40.0,
            shading: Shading::Flat,
            wireframe: true,
            wire_color: [40, 50, 70],
            ..Default::default()
        };
        if show {
            pics.push(render_mesh(&table51::grid_mesh(*f, *g).0, &wire));
        }
        for (c, keep) in [50.0, 20.0, 10.0].into_iter().enumerate() {
            let r = table51::reduce_function(k, keep)
                .map_err(|e| morpho::Error::from(e).with_path(name))?;
            let (rms, _, _) = table51::knot_rms(&r.mesh, *f);
            let th = table51::THESIS[k][c];
            cells.push(if th > 0.0 {
                format!("{rms:.6} ({th:.6}, {:.2}×)", rms / th)
            } else {
                format!("{rms:.1e} (0)")
            });
            if show {
                pics.push(render_mesh(&r.mesh, &wire));
            }
        }
        s.fig(
            &format!("{}. {name}: 50 / 80 / 90 % removed (thesis, ratio)", k + 1),
            cells.join(" · "),
        );
        if show {
            let file = format!("reduce_table51_{}.png", name.replace(' ', "_"));
            hstack(&pics).save_png(&ctx.path(&file))?;
            s.img(
                &file,
                &format!("{name}: original · 50 % · 80 % · 90 % removed"),
            );
        }
    }
    out.push(s);
    Ok(out)
}

/// H Fig. 5.11: the bone surface of the CT head (`morpho isosurface --level 120`) with 90 % of
/// its triangles removed by Algorithm 5.1 (the thesis's order), flat shaded beside the input.
fn skull_section(
    ctx: &super::demo::Ctx,
    path: &std::path::Path,
) -> morpho::Result<morpho::io::html::Section> {
    use morpho::io::html::Section;
    use morpho::render::{render_mesh, UpAxis};
    use morpho::volume::{isosurface, IsoOptions};
    let v = morpho::io::read_volume(path)?;
    let iso = isosurface(
        &v,
        &IsoOptions {
            level: 120.0,
            ..Default::default()
        },
    )?;
    let m = super::demo::upright_head(iso.mesh);
    let mut s = Section::new(
        "Triangle reduction: the CT head's bone surface, 90 % removed (H Fig. 5.11)",
        "The contour surface of volumes/cthead_8bit_256x256x99 at level 120 (as `morpho \
         isosurface` makes it), reduced to 10 % of its triangles by Algorithm 5.1 in the \
         thesis's order (library default; the command's default `--order levels` is slower \
         and closer to the input, see bench/README.md). Left: input; middle: reduced, flat \
         shaded; right: the reduced triangles. Parts, boundary loops and χ are kept.",
    );
    let t0 = std::time::Instant::now();
    let r = reduce(
        &m,
        &ReduceOptions {
            stop: Stop::Keep(10.0),
            ..Default::default()
        },
    )
    .map_err(|e| morpho::Error::from(e).with_path(path))?;
    let secs = t0.elapsed().as_secs_f64();
    let d = mesh_distance(&m, &r.mesh);
    let (a, b) = (analyze_topology(&m), analyze_topology(&r.mesh));
    let (shaded, wire) = flat_and_wire(UpAxis::Z, 25.0, 5.0);
    hstack(&[
        render_mesh(&m, &shaded),
        render_mesh(&r.mesh, &shaded),
        render_mesh(&r.mesh, &wire),
    ])
    .save_png(&ctx.path("reduce_skull.png"))?;
    s.img(
        "reduce_skull.png",
        "input · 10 % of the triangles kept · its edges",
    );
    super::demo::view_page(ctx, &mut s, "reduce_skull_10", &r.mesh)?;
    let topo = |t: &morpho::mesh::Topology| {
        format!(
            "{} / {} / {}",
            t.parts.len(),
            t.boundary_loops.len(),
            t.euler_characteristic
        )
    };
    s.fig(
        "triangles",
        format!("{} → {}", m.triangles.len(), r.mesh.triangles.len()),
    );
    s.fig("parts / loops / χ, input", topo(&a));
    s.fig("parts / loops / χ, reduced", topo(&b));
    s.fig("manifold, oriented", b.manifold && b.consistently_oriented);
    s.fig("reduction time", format!("{secs:.2} s"));
    s.fig(
        "rms / Hausdorff (sampled, symmetric)",
        format!("{:.3} / {:.3} (volume units)", d.rms, d.hausdorff),
    );
    Ok(s)
}
