//! `morpho render VOLUME -o OUT.png --view subdivision|transparency|slices|heights` and
//! `morpho render --function NAME -o OUT.png --view …`: Hamann's volume views (1991, ch. 2)
//! through [`morpho::render::render_view`], with the camera of `render` (`--azimuth`,
//! `--elevation`, `--ortho`, `--width`, `--height`), `--colormap`, `--range` and a colour bar.
//! Also the gallery section of the views (`demo_section`).

use super::render::Args;
use crate::report::Report;
use crate::Failure;
use morpho::render::{
    render_view, Colormap, Formula, HeightStyle, RenderOptions, Source, UpAxis, View, ViewOptions,
};
use morpho::volume::Volume;

/// The view options of `morpho render` (flattened into its arguments).
#[derive(clap::Args, Debug, Clone, Default)]
pub struct ViewArgs {
    /// Volume view (Hamann ch. 2): subdivision, transparency, slices or heights.
    #[arg(long, value_parser = ["subdivision", "transparency", "slices", "heights"])]
    pub view: Option<String>,
    /// Draw a function given by formula instead of an input file: hamann-exp (Figs 2.2, 2.3,
    /// 2.9) or hamann-cos (Fig. 2.4, partial unit ball).
    #[arg(long, value_name = "NAME")]
    pub function: Option<String>,
    /// Cells per axis where a --function is sampled (transparency, slices).
    #[arg(long, value_name = "N", default_value_t = 32)]
    pub grid: usize,
    /// Sub-boxes per axis of --view subdivision: Q or QX,QY,QZ.
    #[arg(long, value_name = "Q", default_value = "5")]
    pub q: String,
    /// Gap ratios of --view subdivision (gap / box edge): A or AX,AY,AZ.
    #[arg(long, value_name = "A", default_value = "1")]
    pub alpha: String,
    /// Refinement: samples per box edge minus one (subdivision, default 4) or grid cells per
    /// slice side (heights, default 30).
    #[arg(long, value_name = "K")]
    pub k: Option<usize>,
    /// Links between the centroids of neighbouring sub-boxes (subdivision).
    #[arg(long)]
    pub links: bool,
    /// Resample the transparency view on (N+1)³ points (default: the volume's grid).
    #[arg(long, value_name = "N")]
    pub n: Option<usize>,
    /// Height surfaces as curve networks instead of shaded surfaces.
    #[arg(long)]
    pub network: bool,
}

/// One value or three, comma-separated.
fn triple<T: std::str::FromStr + Copy>(s: &str, flag: &str) -> Result<[T; 3], Failure> {
    let bad = || {
        Failure::usage(format!(
            "--{flag} {s:?}: expected one number or three (X,Y,Z)"
        ))
    };
    let v: Vec<T> = s
        .split(',')
        .map(|x| x.trim().parse::<T>().map_err(|_| bad()))
        .collect::<Result<_, _>>()?;
    match v.as_slice() {
        [a] => Ok([*a; 3]),
        [a, b, c] => Ok([*a, *b, *c]),
        _ => Err(bad()),
    }
}

/// The view chosen by the arguments.
fn view_of(args: &Args) -> Result<View, Failure> {
    let v = &args.views;
    Ok(match v.view.as_deref().unwrap_or("subdivision") {
        "subdivision" => {
            let q: [usize; 3] = triple(&v.q, "q")?;
            if q.iter().any(|&x| !(1..=64).contains(&x)) {
                return Err(Failure::usage("--q needs 1 <= Q <= 64 per axis"));
            }
            let alpha: [f64; 3] = triple(&v.alpha, "alpha")?;
            if alpha.iter().any(|a| !(a.is_finite() && *a >= 0.0)) {
                return Err(Failure::usage("--alpha must be finite and >= 0"));
            }
            let k = v.k.unwrap_or(4);
            if !(1..=64).contains(&k) {
                return Err(Failure::usage("--k needs 1 <= K <= 64 for subdivision"));
            }
            View::Subdivision {
                q,
                alpha,
                k,
                links: v.links,
            }
        }
        "transparency" => {
            if !(0.0..=1.0).contains(&args.transparency) {
                return Err(Failure::usage("--transparency must be between 0 and 1"));
            }
            if let Some(n) = v.n {
                if !(1..=512).contains(&n) {
                    return Err(Failure::usage("--n needs 1 <= N <= 512"));
                }
            }
            View::Transparency {
                n: v.n,
                t: args.transparency,
            }
        }
        "slices" => View::Slices,
        _ => {
            let k = v.k.unwrap_or(30);
            if !(1..=1024).contains(&k) {
                return Err(Failure::usage("--k needs 1 <= K <= 1024 for heights"));
            }
            View::Heights {
                k,
                style: if v.network {
                    HeightStyle::Network
                } else {
                    HeightStyle::Surface
                },
            }
        }
    })
}

/// Draws the chosen view of `src` to `args.output`.
fn draw(
    args: &Args,
    src: &Source,
    colormap: Colormap,
    range: Option<(f64, f64)>,
    camera: RenderOptions,
    report: &mut Report,
) -> Result<u8, Failure> {
    let view = view_of(args)?;
    let opts = ViewOptions {
        render: camera,
        colormap,
        range,
        legend: !args.no_legend,
    };
    report.set("view", args.views.view.as_deref().unwrap_or("subdivision"));
    let pic = report.time("compute", || render_view(src, &view, &opts))?;
    report.set("primitives", pic.primitives);
    report.set("triangles", pic.triangles);
    report.set("range", serde_json::json!([pic.range.0, pic.range.1]));
    report.set("notes", serde_json::json!(pic.notes));
    report.set("width", pic.image.width);
    report.set("height", pic.image.height);
    report.time("write", || pic.image.save_png(&args.output))?;
    Ok(0)
}

/// `--view` on a volume read from a file.
pub fn run_volume(
    args: &Args,
    v: &Volume,
    colormap: Colormap,
    range: Option<(f64, f64)>,
    camera: RenderOptions,
    report: &mut Report,
) -> Result<u8, Failure> {
    report.set("kind", "volume");
    draw(args, &Source::Volume(v), colormap, range, camera, report)
}

/// `--function NAME`: the view of a formula.
pub fn run_function(
    args: &Args,
    colormap: Colormap,
    range: Option<(f64, f64)>,
    camera: RenderOptions,
    report: &mut Report,
) -> Result<u8, Failure> {
    let name = args.views.function.as_deref().unwrap_or_default();
    let formula: Formula = name
        .parse()
        .map_err(|e: morpho::render::RenderError| Failure::usage(e.to_string()))?;
    if !(1..=256).contains(&args.views.grid) {
        return Err(Failure::usage("--grid needs 1 <= N <= 256"));
    }
    report.set("kind", "function");
    report.set("function", formula.name());
    report.set("output", args.output.display().to_string());
    let src = Source::Formula {
        formula,
        grid: args.views.grid,
    };
    draw(args, &src, colormap, range, camera, report)
}

/// Gallery: the four views of a real volume and of Hamann's exponential function, Fig. 2.4,
/// and a curvature-coloured mesh.
pub fn demo_section(ctx: &super::demo::Ctx) -> morpho::Result<Vec<morpho::io::html::Section>> {
    use morpho::io::html::Section;
    let camera = RenderOptions {
        width: 480,
        height: 360,
        up: UpAxis::Z,
        ..Default::default()
    };
    let views: [(&str, View); 4] = [
        (
            "subdivision",
            View::Subdivision {
                q: [5; 3],
                alpha: [1.0; 3],
                k: 4,
                links: true,
            },
        ),
        ("transparency", View::Transparency { n: Some(8), t: 0.5 }),
        ("slices", View::Slices),
        (
            "heights",
            View::Heights {
                k: 30,
                style: HeightStyle::Surface,
            },
        ),
    ];
    let mut out = Vec::new();
    let exp = Source::Formula {
        formula: Formula::HamannExp,
        grid: 32,
    };
    let mut cases: Vec<(String, String, Source, Colormap)> = vec![(
        "Hamann's exponential function (H Figs 2.2, 2.5, 2.9)".into(),
        "hamann_exp".into(),
        exp,
        Colormap::Viridis,
    )];
    let real = match ctx.data_file("volumes/dipy_aniso_vox_58x58x24_i16.json") {
        Some(p) => Some(morpho::io::read_volume(&p)?),
        None => None,
    };
    if let Some(v) = &real {
        cases.push((
            "A real MRI volume (dipy_aniso_vox, 58×58×24, 4×4×5 mm)".into(),
            "dipy".into(),
            Source::Volume(v),
            Colormap::Greys,
        ));
    }
    for (title, stem, src, cmap) in &cases {
        let mut s = Section::new(
            &format!("Volume views: {title}"),
            "Hamann ch. 2: sub-boxes with gaps (q = 5, α = 1, centroid links), transparency \
             (n = 8, t = 0.5), three orthogonal slices, height surfaces of the middle slices \
             (k = l = 30, I1/I2 triangles).",
        );
        for (name, view) in &views {
            let opts = ViewOptions {
                render: camera.clone(),
                colormap: *cmap,
                range: None,
                legend: true,
            };
            let pic = render_view(src, view, &opts)?;
            let file = format!("views_{stem}_{name}.png");
            pic.image.save_png(&ctx.path(&file))?;
            s.img(&file, name);
            s.fig(&format!("{name}: primitives"), pic.primitives.to_string());
        }
        out.push(s);
    }
    // Fig. 2.4: the partial unit ball.
    let mut s = Section::new(
        "Volume views: cos(2|x|) over a partial unit ball (H Fig. 2.4)",
        "Sub-boxes laid out in uvw-space (q = 5, α = 2) and mapped to the ball.",
    );
    let ball = Source::Formula {
        formula: Formula::HamannCos,
        grid: 32,
    };
    let view = View::Subdivision {
        q: [5; 3],
        alpha: [2.0; 3],
        k: 4,
        links: false,
    };
    let opts = ViewOptions {
        render: camera.clone(),
        ..Default::default()
    };
    render_view(&ball, &view, &opts)?
        .image
        .save_png(&ctx.path("views_ball_subdivision.png"))?;
    s.img("views_ball_subdivision.png", "Fig. 2.4 parameters");
    out.push(s);
    // A curvature-coloured mesh (mean curvature H of a real mesh).
    if let Some(p) = ctx.data_file("meshes/spot.obj") {
        use morpho::curvature::{surface_curvature, SurfaceOptions};
        let m = morpho::io::read_mesh(&p)?;
        let h = surface_curvature(&m, &SurfaceOptions::default())?.h;
        let h_values = h.clone();
        let r = morpho::render::finite_range(h.iter().copied()).unwrap_or((-1.0, 1.0));
        let a = r.0.abs().max(r.1.abs()).min(20.0);
        let ro = RenderOptions {
            scalars: Some(morpho::render::Scalars {
                values: h,
                per_face: false,
                colormap: Colormap::Coolwarm,
                range: Some((-a, a)),
            }),
            ..camera.clone()
        };
        let img = morpho::render::render_mesh(
            &m,
            &RenderOptions {
                up: UpAxis::Y,
                ..ro
            },
        );
        morpho::render::with_colorbar(&img, Colormap::Coolwarm, -a, a, Some("H"))
            .save_png(&ctx.path("views_spot_H.png"))?;
        let mut s = Section::new(
            "Mesh coloured by mean curvature H (spot.obj)",
            "morpho render MESH.ply --color H: H from the osculating-paraboloid fit (H §4.2).",
        );
        s.img("views_spot_H.png", "mean curvature H, symmetric range");
        let mut mh = m.clone();
        mh.vertex_props.push(morpho::mesh::Property {
            name: "H".into(),
            kind: morpho::mesh::ScalarKind::F64,
            values: h_values,
        });
        super::demo::view_page(ctx, &mut s, "spot_H", &mh)?;
        out.push(s);
    }
    Ok(out)
}
