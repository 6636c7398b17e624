//! `morpho render IN -o IMAGE.{svg,png}`: pictures of any file morpho reads.
//!
//! - 2D points → SVG dots (coloured by a column with `--color-by`); 3D points → SVG of their
//!   orthographic projection from `--azimuth/--elevation`, nearer dots drawn last and darker
//!   farther ones;
//! - polygons/polylines → SVG;
//! - triangle meshes → PNG by the software rasterizer (`--flat|--smooth`, `--wireframe`,
//!   `--color-by` a vertex or face property or `x`/`y`/`z`; `--reflection-lines [N]`, the
//!   visual continuity check of Veltkamp 1992, §8.4, with `--beside MESH` drawn flat shaded to
//!   the left in the same view, e.g. a smooth surface beside its input mesh);
//! - volumes → PNG of the three orthogonal middle slices, or of one slice with `--slice z,10`.

use crate::report::Report;
use crate::Failure;
use morpho::io::{self, read_any, Data, Format};
use morpho::mesh::{PointSet, TriMesh};
use morpho::render::Colormap;
use morpho::render::{self, Axis, SliceOptions, Upsample};
use morpho::render::{point_set_svg, PointsView};
use morpho::render::{
    render_mesh_stats, Projection, ReflectionLines, RenderOptions, Scalars, Shading, UpAxis,
};
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// Input file (points, polygons, mesh or volume); omitted with --function.
    #[arg(required_unless_present = "function")]
    pub input: Option<PathBuf>,
    /// Output picture: .svg for points and polygons, .png for meshes and volumes.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Viewpoint rotation about the up axis, degrees.
    #[arg(long, default_value_t = 35.0, allow_hyphen_values = true)]
    pub azimuth: f64,
    /// Viewpoint height above the horizontal plane, degrees (−90…90).
    #[arg(long, default_value_t = 25.0, allow_hyphen_values = true)]
    pub elevation: f64,
    /// Which axis points up: y or z (default: y for meshes and points, z for volume views).
    #[arg(long, value_parser = ["y", "z"])]
    pub up: Option<String>,
    /// Flat shading (one normal per triangle).
    #[arg(long, conflicts_with = "smooth")]
    pub flat: bool,
    /// Smooth shading (vertex normals; the default).
    #[arg(long)]
    pub smooth: bool,
    /// Parallel instead of perspective projection.
    #[arg(long)]
    pub ortho: bool,
    /// Colour by a vertex/face property or point column, or by the coordinate x, y or z.
    /// (`--color` is the same; a signed property gets a symmetric range by default.)
    #[arg(long, alias = "color", value_name = "PROPERTY")]
    pub color_by: Option<String>,
    /// Colour map: viridis, coolwarm or grey.
    #[arg(long, default_value = "viridis")]
    pub colormap: String,
    /// Value range mapped to the colour map ends, `LO,HI` or `LO:HI` (default: the data's
    /// range).
    #[arg(long, value_name = "LO,HI", allow_hyphen_values = true)]
    pub range: Option<String>,
    /// Image width in pixels.
    #[arg(long, default_value_t = 800)]
    pub width: u32,
    /// Image height in pixels (meshes).
    #[arg(long, default_value_t = 600)]
    pub height: u32,
    /// One volume slice `AXIS,INDEX` (e.g. `z,10`; INDEX may be `mid`) instead of three.
    #[arg(long, value_name = "AXIS,INDEX")]
    pub slice: Option<String>,
    /// Volume view as Q×Q×Q sub-boxes with gaps, coloured by the values (Hamann §2.2).
    #[arg(long, value_name = "Q", conflicts_with_all = ["slice", "planes"])]
    pub boxes: Option<usize>,
    /// Volume view as translucent grid planes, every STRIDE-th plane per axis (Hamann §2.2).
    #[arg(long, value_name = "STRIDE", conflicts_with = "slice")]
    pub planes: Option<usize>,
    /// Transparency t of --planes (0 opaque … 1 invisible).
    #[arg(long, default_value_t = 0.75, allow_hyphen_values = true)]
    pub transparency: f64,
    /// Nearest-sample blocks instead of bilinear interpolation in volume slices.
    #[arg(long)]
    pub nearest: bool,
    /// Draw triangle edges (for small meshes).
    #[arg(long)]
    pub wireframe: bool,
    /// Reflection lines (Veltkamp 1992, §8.4): N parallel light lines per π of the reflected
    /// view ray's angle, drawn as dark stripes from the (vertex or facet) normals; continuous
    /// stripes show a G¹ surface.
    #[arg(long, value_name = "N", num_args = 0..=1, default_missing_value = "4")]
    pub reflection_lines: Option<u32>,
    /// A second mesh (e.g. the input of `morpho smooth`) drawn flat shaded to the left of the
    /// picture, in the same view and with the same reflection lines.
    #[arg(long, value_name = "MESH")]
    pub beside: Option<PathBuf>,
    /// No colour bar below meshes coloured with --color-by.
    #[arg(long)]
    pub no_legend: bool,
    /// Supersampling factor per axis for meshes (1 = no anti-aliasing).
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u32).range(1..=4))]
    pub supersample: u32,
    /// Hamann's volume views (`--view …`, `--function …`).
    #[command(flatten)]
    pub views: super::views::ViewArgs,
}

pub fn run(args: Args, report: &mut Report) -> Result<u8, Failure> {
    let out_fmt = Format::of(&args.output)?;
    if !matches!(out_fmt, Format::Svg | Format::Png) {
        return Err(Failure::usage(format!(
            "{}: render writes .svg or .png pictures",
            args.output.display()
        )));
    }
    if !(1..=8192).contains(&args.width) || !(1..=8192).contains(&args.height) {
        return Err(Failure::usage(
            "--width and --height must be between 1 and 8192",
        ));
    }
    if !args.azimuth.is_finite() || !args.elevation.is_finite() {
        return Err(Failure::usage(
            "--azimuth and --elevation must be finite numbers",
        ));
    }
    let colormap: Colormap = args
        .colormap
        .parse()
        .map_err(|e: morpho::render::RenderError| Failure::usage(e.to_string()))?;
    let range = match &args.range {
        None => None,
        Some(s) => Some(parse_range(s)?),
    };
    if args.views.function.is_some() {
        if args.input.is_some() {
            return Err(Failure::usage(
                "give an input file or --function NAME, not both",
            ));
        }
        if out_fmt != Format::Png {
            return Err(Failure::usage(
                "volume views are PNG: use an output ending in .png",
            ));
        }
        let camera = view_options(&args, UpAxis::Z);
        return super::views::run_function(&args, colormap, range, camera, report);
    }
    let Some(input) = args.input.as_deref() else {
        return Err(Failure::usage("give an input file or --function NAME"));
    };
    let data = report.time("read", || read_any(input))?;
    report.set("input", input.display().to_string());
    report.set("output", args.output.display().to_string());
    match (&data, out_fmt) {
        (Data::Points(p), Format::Svg) => points(&args, p, colormap, range, report)?,
        (Data::Points(_), _) => {
            return Err(Failure::usage(
                "points are drawn as SVG: use an output ending in .svg",
            ))
        }
        (Data::Shapes(s), Format::Svg) => {
            report.set("kind", "shapes");
            report.set("polygons", s.polygons.len());
            report.set("polylines", s.polylines.len());
            let text = report.time("compute", || render::polygon_svg(s));
            write_svg(&args, &text, report)?;
        }
        (Data::Shapes(_), _) => {
            return Err(Failure::usage(
                "polygons are drawn as SVG: use an output ending in .svg",
            ))
        }
        (Data::Mesh(m), Format::Png) => mesh(&args, m, colormap, range, report)?,
        (Data::Mesh(_), _) => {
            return Err(Failure::usage(
                "meshes are rendered as PNG: use an output ending in .png",
            ))
        }
        (Data::Volume(v), Format::Png) => {
            report.set("kind", "volume");
            let opts = SliceOptions {
                colormap,
                range,
                size: None,
                upsample: if args.nearest {
                    Upsample::Nearest
                } else {
                    Upsample::Bilinear
                },
                labels: true,
            };
            if args.views.view.is_some() && args.boxes.is_none() && args.planes.is_none() {
                let camera = view_options(&args, UpAxis::Z);
                return super::views::run_volume(&args, v, colormap, range, camera, report);
            }
            if args.boxes.is_some() || args.planes.is_some() {
                volume_view(&args, v, colormap, range, report)?;
                return Ok(0);
            }
            let img = match &args.slice {
                Some(s) => {
                    let (axis, index) = parse_slice(s, v)?;
                    report.set("slice", format!("{},{}", axis.name(), index));
                    let opts = SliceOptions {
                        size: Some(args.width),
                        ..opts
                    };
                    report.time("compute", || render::slice_image(v, axis, index, &opts))?
                }
                None => {
                    let mid = render::middle(v);
                    report.set("slice", serde_json::json!(mid));
                    report.time("compute", || render::orthogonal_slices(v, mid, &opts))?
                }
            };
            report.set("width", img.width);
            report.set("height", img.height);
            report.time("write", || img.save_png(&args.output))?;
        }
        (Data::Volume(_), _) => {
            return Err(Failure::usage(
                "volumes are drawn as PNG slices: use an output ending in .png",
            ))
        }
    }
    Ok(0)
}

fn parse_range(s: &str) -> Result<(f64, f64), Failure> {
    let bad = || Failure::usage(format!("--range {s:?}: expected LO,HI with LO < HI"));
    let (a, b) = s
        .split_once(',')
        .or_else(|| s.split_once(':'))
        .ok_or_else(bad)?;
    let lo: f64 = a.trim().parse().map_err(|_| bad())?;
    let hi: f64 = b.trim().parse().map_err(|_| bad())?;
    if lo.is_finite() && hi.is_finite() && lo < hi {
        Ok((lo, hi))
    } else {
        Err(bad())
    }
}

fn parse_slice(s: &str, v: &morpho::volume::Volume) -> Result<(Axis, usize), Failure> {
    let bad = |why: String| Failure::usage(format!("--slice {s:?}: {why}"));
    let (a, i) = s
        .split_once(',')
        .ok_or_else(|| bad("expected AXIS,INDEX such as z,10".into()))?;
    let axis: Axis = a
        .parse()
        .map_err(|e: morpho::render::RenderError| bad(e.to_string()))?;
    let n = v.dims[axis.index()];
    let index = if i.trim() == "mid" {
        n / 2
    } else {
        i.trim()
            .parse::<usize>()
            .map_err(|_| bad("INDEX must be a whole number or 'mid'".into()))?
    };
    if index >= n {
        return Err(bad(format!(
            "index {index} is out of range; the volume has {n} samples along {}",
            axis.name()
        )));
    }
    Ok((axis, index))
}

fn write_svg(args: &Args, text: &str, report: &mut Report) -> Result<(), Failure> {
    report.time("write", || io::write_text(&args.output, text))?;
    Ok(())
}

/// Values of `name` for each point: a column or a coordinate.
fn point_values(p: &PointSet, name: &str) -> Result<Vec<f64>, Failure> {
    if let Some(c) = p.column(name) {
        return Ok(c.values.clone());
    }
    let k = match name {
        "x" => 0,
        "y" => 1,
        "z" if p.dim == 3 => 2,
        _ => {
            let names: Vec<&str> = p.columns.iter().map(|c| c.name.as_str()).collect();
            return Err(Failure::usage(format!(
                "--color-by {name:?}: no such column (columns: {}; or x, y{})",
                if names.is_empty() {
                    "none".to_string()
                } else {
                    names.join(", ")
                },
                if p.dim == 3 { ", z" } else { "" }
            )));
        }
    };
    Ok((0..p.len()).map(|i| p.point(i)[k]).collect())
}

fn points(
    args: &Args,
    p: &PointSet,
    colormap: Colormap,
    range: Option<(f64, f64)>,
    report: &mut Report,
) -> Result<(), Failure> {
    report.set("kind", "points");
    report.set("points", p.len());
    let values = match &args.color_by {
        Some(name) => Some(point_values(p, name)?),
        None => None,
    };
    let view = PointsView {
        values: values.as_deref(),
        colormap,
        range,
        azimuth_deg: args.azimuth,
        elevation_deg: args.elevation,
        up: if args.up.as_deref() == Some("z") {
            UpAxis::Z
        } else {
            UpAxis::Y
        },
        width: args.width as f64,
    };
    let (text, skipped) = report.time("compute", || point_set_svg(p, &view));
    report.set("skipped", skipped);
    report.set("width", args.width);
    write_svg(args, &text, report)
}

/// Scalars for `--color-by NAME` on a mesh: vertex property, face property or coordinate.
fn mesh_scalars(
    m: &TriMesh,
    name: &str,
    colormap: Colormap,
    range: Option<(f64, f64)>,
) -> Result<Scalars, Failure> {
    let (values, per_face) = if let Some(p) = m.vertex_prop(name) {
        (p.values.clone(), false)
    } else if let Some(p) = m.face_prop(name) {
        (p.values.clone(), true)
    } else if let Some(k) = ["x", "y", "z"].iter().position(|c| *c == name) {
        (m.positions.iter().map(|p| p[k]).collect(), false)
    } else {
        let names: Vec<&str> = m
            .vertex_props
            .iter()
            .chain(&m.face_props)
            .map(|p| p.name.as_str())
            .collect();
        return Err(Failure::usage(format!(
            "--color-by {name:?}: no such property (properties: {}; or x, y, z)",
            if names.is_empty() {
                "none".to_string()
            } else {
                names.join(", ")
            }
        )));
    };
    // A signed property (both signs present, such as H or K) is centred on zero.
    let is_prop = m.vertex_prop(name).is_some() || m.face_prop(name).is_some();
    let range = range.or_else(|| match render::finite_range(values.iter().copied()) {
        Some((lo, hi)) if is_prop && lo < 0.0 && hi > 0.0 => {
            let a = lo.abs().max(hi);
            Some((-a, a))
        }
        _ => None,
    });
    Ok(Scalars {
        values,
        per_face,
        colormap,
        range,
    })
}

fn mesh(
    args: &Args,
    m: &TriMesh,
    colormap: Colormap,
    range: Option<(f64, f64)>,
    report: &mut Report,
) -> Result<(), Failure> {
    report.set("kind", "mesh");
    report.set("vertices", m.num_vertices());
    report.set("triangles", m.num_triangles());
    let scalars = match &args.color_by {
        Some(name) => Some(mesh_scalars(m, name, colormap, range)?),
        None => None,
    };
    let reflection_lines = match args.reflection_lines {
        None => None,
        Some(n) if (1..=1000).contains(&n) => Some(ReflectionLines {
            lines: n,
            ..Default::default()
        }),
        Some(n) => {
            return Err(Failure::usage(format!(
                "--reflection-lines {n}: give 1 to 1000 lines"
            )))
        }
    };
    let opts = RenderOptions {
        shading: if args.flat {
            Shading::Flat
        } else {
            Shading::Smooth
        },
        scalars,
        wireframe: args.wireframe,
        reflection_lines,
        ..view_options(args, UpAxis::Y)
    };
    let beside = match &args.beside {
        None => None,
        Some(p) => {
            let b = report.time("read", || morpho::io::read_mesh(p))?;
            report.set("beside", p.display().to_string());
            report.set("beside_triangles", b.num_triangles());
            Some(b)
        }
    };
    let (img, st) = report.time("compute", || {
        let (img, st) = render_mesh_stats(m, &opts);
        let img = match &beside {
            None => img,
            Some(b) => {
                let flat = RenderOptions {
                    shading: Shading::Flat,
                    scalars: None,
                    ..opts.clone()
                };
                super::reduce::hstack(&[render_mesh_stats(b, &flat).0, img])
            }
        };
        // A colour bar below the picture when a property is shown.
        match (st.range, &args.color_by) {
            (Some((lo, hi)), Some(name)) if !args.no_legend => (
                render::with_colorbar(&img, colormap, lo, hi, Some(name)),
                st,
            ),
            _ => (img, st),
        }
    });
    if let Some((lo, hi)) = st.range {
        report.set("range", serde_json::json!([lo, hi]));
    }
    report.set("width", img.width);
    report.set("height", img.height);
    report.set("drawn", st.drawn);
    report.set("skipped_invalid", st.invalid);
    report.set("degenerate", st.degenerate);
    report.time("write", || img.save_png(&args.output))?;
    Ok(())
}

/// `--boxes` and `--planes`: a volume drawn as a coloured mesh through the rasterizer.
fn volume_view(
    args: &Args,
    v: &morpho::volume::Volume,
    colormap: Colormap,
    range: Option<(f64, f64)>,
    report: &mut Report,
) -> Result<(), Failure> {
    use morpho::render::{domain_subdivision_mesh, grid_planes_mesh};
    if !(0.0..=1.0).contains(&args.transparency) {
        return Err(Failure::usage("--transparency must be between 0 and 1"));
    }
    let (m, view) = report.time("compute", || match (args.boxes, args.planes) {
        (Some(q), _) => {
            if !(1..=64).contains(&q) {
                return Err(Failure::usage("--boxes Q needs 1 <= Q <= 64"));
            }
            Ok((domain_subdivision_mesh(v, [q; 3], [1.0; 3], 4)?, "boxes"))
        }
        (None, Some(s)) => {
            if s == 0 {
                return Err(Failure::usage("--planes STRIDE needs STRIDE >= 1"));
            }
            Ok((grid_planes_mesh(v, [s; 3])?, "planes"))
        }
        _ => Err(Failure::usage("no volume view chosen")),
    })?;
    report.set("view", view);
    report.set("triangles", m.num_triangles());
    let values = m
        .vertex_prop("value")
        .map(|p| p.values.clone())
        .unwrap_or_default();
    let opts = RenderOptions {
        shading: Shading::Flat,
        scalars: Some(Scalars {
            values,
            per_face: false,
            colormap,
            range,
        }),
        transparency: (view == "planes").then_some(args.transparency),
        ..view_options(args, UpAxis::Z)
    };
    let img = report.time("compute", || {
        let (img, st) = render_mesh_stats(&m, &opts);
        match st.range {
            Some((lo, hi)) if !args.no_legend => {
                render::with_colorbar(&img, colormap, lo, hi, None)
            }
            _ => img,
        }
    });
    report.set("width", img.width);
    report.set("height", img.height);
    report.time("write", || img.save_png(&args.output))?;
    Ok(())
}

/// The camera and image settings shared by mesh and volume pictures; `--up` overrides
/// `default_up`.
fn view_options(args: &Args, default_up: UpAxis) -> RenderOptions {
    RenderOptions {
        width: args.width,
        height: args.height,
        azimuth_deg: args.azimuth,
        elevation_deg: args.elevation,
        up: match args.up.as_deref() {
            Some("z") => UpAxis::Z,
            Some("y") => UpAxis::Y,
            _ => default_up,
        },
        projection: if args.ortho {
            Projection::Orthographic
        } else {
            Projection::Perspective { fov_deg: 30.0 }
        },
        supersample: args.supersample,
        ..Default::default()
    }
}
