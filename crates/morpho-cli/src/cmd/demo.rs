//! `morpho demo [--out DIR]`: runs every pipeline on generated sample data and on the bundled
//! real data (`../shared/data` next to the repository, when present) and writes a gallery:
//! `index.html` with one section per pipeline step, each picture beside its figures, plus the
//! result files. A section that fails is shown as failed and makes the command exit 1.
//!
//! Size (over 800 lines): one function per gallery section of the first pipelines; sections of
//! newer modules live in their own command files (`pub fn demo_section`).

use crate::report::Report;
use crate::Failure;
use morpho::io::html::{Entry, Section};
use morpho::render;
use morpho::Result;
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(clap::Args)]
pub struct Args {
    /// Folder for the gallery (created if missing).
    #[arg(long, default_value = "morpho-demo")]
    pub out: PathBuf,
    /// Folder with the real data (default: ../shared/data from the repository, if it exists).
    #[arg(long)]
    pub data: Option<PathBuf>,
    /// Build only the steps whose name contains this text (repeatable; the steps are
    /// "sample points", "delaunay", "gamma graphs", "boundary", "flintstones", "meshes",
    /// "volumes", "volume views", "contour surfaces", "triangle reduction", "smooth", "curvature", …).
    #[arg(long, value_name = "STEP")]
    pub only: Vec<String>,
}

/// Everything a section builder needs.
pub struct Ctx {
    pub out: PathBuf,
    pub data: Option<PathBuf>,
}

impl Ctx {
    /// Path of a gallery file.
    pub fn path(&self, name: &str) -> PathBuf {
        self.out.join(name)
    }
    /// A file of the real data set, if present.
    pub fn data_file(&self, rel: &str) -> Option<PathBuf> {
        let p = self.data.as_ref()?.join(rel);
        p.exists().then_some(p)
    }
}

type Builder = fn(&Ctx) -> Result<Vec<Section>>;

/// The CT head's contour surface for pictures: its slices run from the top of the skull
/// (z = 0) down, so z is mirrored and the head stands upright (every triangle reversed alike:
/// still consistently oriented); the normals, which the mirror would contradict, are dropped.
pub fn upright_head(mut m: morpho::mesh::TriMesh) -> morpho::mesh::TriMesh {
    for p in m.positions.iter_mut() {
        p.z = -p.z;
    }
    m.normals = None;
    m
}

/// The pipeline steps, in gallery order.
const SECTIONS: &[(&str, Builder)] = &[
    ("sample points", points_section),
    ("delaunay", delaunay_section),
    ("gamma graphs", gamma_section),
    ("boundary", boundary_section),
    ("non-Hamiltonian Delaunay", dillencourt_section),
    ("flintstones", crate::cmd::flint::demo_section),
    ("meshes", mesh_section),
    ("volumes", volume_section),
    ("volume views", crate::cmd::views::demo_section),
    ("contour surfaces", isosurface_section),
    ("triangle reduction", crate::cmd::reduce::demo_section),
    ("smooth", crate::cmd::smooth::demo_section),
    ("curvature", crate::cmd::curvature::demo_section),
    ("contours of rated samples", contour_section),
];

pub fn run(args: Args, report: &mut Report) -> Result<u8, Failure> {
    std::fs::create_dir_all(&args.out).map_err(|e| morpho::Error::io(&args.out, e))?;
    let data = args.data.clone().or_else(default_data_dir);
    let ctx = Ctx {
        out: args.out.clone(),
        data: data.clone(),
    };
    let mut done: Vec<Entry> = Vec::new();
    let mut failed = 0;
    let t0 = Instant::now();
    for (name, build) in SECTIONS {
        if !args.only.is_empty() && !args.only.iter().any(|o| name.contains(o.as_str())) {
            continue;
        }
        let t = Instant::now();
        match build(&ctx) {
            Ok(secs) => {
                let dt = t.elapsed().as_secs_f64() / secs.len().max(1) as f64;
                for mut section in secs {
                    if let Err(e) = add_views(&ctx, &mut section) {
                        eprintln!("error: demo step '{name}': interactive view: {e}");
                        failed += 1;
                    }
                    done.push(Entry {
                        section,
                        seconds: dt,
                        error: None,
                    });
                }
            }
            Err(e) => {
                failed += 1;
                eprintln!("error: demo step '{name}' failed: {e}");
                done.push(Entry {
                    section: Section::new(name, ""),
                    seconds: t.elapsed().as_secs_f64(),
                    error: Some(e.to_string()),
                });
            }
        }
    }
    report.add_time("compute", t0.elapsed().as_secs_f64());
    let index = args.out.join("index.html");
    report.time("write", || {
        morpho::io::html::write_gallery(&index, &done, data.as_deref())
    })?;
    report.set("sections", done.len());
    report.set("failed_sections", failed);
    report.set("index", index.display().to_string());
    println!(
        "wrote {} ({} sections, {} failed)",
        index.display(),
        done.len(),
        failed
    );
    Ok(if failed > 0 { 1 } else { 0 })
}

/// Issue 22: the interactive page (`morpho view`'s page) of a 3D result, written beside the
/// gallery as `NAME.view.html` and listed with the section's files, so the gallery links it.
pub fn view_page(ctx: &Ctx, s: &mut Section, name: &str, m: &morpho::mesh::TriMesh) -> Result<()> {
    write_view(ctx, s, name, vec![morpho::viewer::Layer::mesh(name, m)])
}

/// Writes the page of `layers` as `NAME.view.html` and lists it with the section's files.
fn write_view(
    ctx: &Ctx,
    s: &mut Section,
    name: &str,
    layers: Vec<morpho::viewer::Layer>,
) -> Result<()> {
    use morpho::viewer::{page_html, Page, DEFAULT_LOD};
    let page = Page {
        title: name.to_string(),
        layers,
        figures: None,
        lod: DEFAULT_LOD,
    };
    let file = format!("{name}.view.html");
    morpho::io::write_text(&ctx.path(&file), &page_html(&page))?;
    s.files.push(file);
    Ok(())
}

/// Issue 22: the interactive page of a volume (three movable slices, and the contour surface
/// at `level` as a hidden layer when given), written as `NAME.view.html` and listed with the
/// section's files.
pub fn volume_view_page(
    ctx: &Ctx,
    s: &mut Section,
    name: &str,
    v: &morpho::volume::Volume,
    level: Option<f64>,
) -> Result<()> {
    use morpho::viewer::{Layer, VolumeLayer, DEFAULT_MAX_SAMPLES};
    // the gallery's volumes are valid (finite samples): no page otherwise
    let Ok(vl) = VolumeLayer::new(v, DEFAULT_MAX_SAMPLES) else {
        return Ok(());
    };
    let mut layers = vec![Layer::volume(&format!("{name} (slices)"), vl)];
    if let Some(level) = level {
        let opts = morpho::volume::IsoOptions {
            level,
            ..Default::default()
        };
        let r = morpho::volume::isosurface(v, &opts)?;
        let mut m = Layer::mesh(&format!("{name} (contour f = {level})"), &r.mesh);
        m.hidden = true;
        layers.push(m);
    }
    write_view(ctx, s, name, layers)
}

/// Every mesh file of a section gets its interactive page ([`view_page`]).
fn add_views(ctx: &Ctx, s: &mut Section) -> Result<()> {
    let meshes: Vec<String> = s
        .files
        .iter()
        .filter(|f| {
            let e = crate::cmd::extension(Path::new(f.as_str()));
            matches!(e.as_str(), "ply" | "obj" | "off" | "stl")
                && !s.files.contains(&format!("{f}.view.html"))
        })
        .cloned()
        .collect();
    for f in meshes {
        let m = morpho::io::read_mesh(&ctx.path(&f))?;
        view_page(ctx, s, &f, &m)?;
    }
    Ok(())
}

/// `../shared/data` relative to the repository this binary was built from, or to the
/// current folder.
fn default_data_dir() -> Option<PathBuf> {
    let candidates = [
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data"),
        PathBuf::from("../shared/data"),
    ];
    candidates.into_iter().find(|p| p.is_dir())
}

fn write_svg(ctx: &Ctx, name: &str, svg: &str) -> Result<()> {
    morpho::io::write_text(&ctx.path(name), svg)
}

fn chalice() -> Vec<morpho::geom::Point2> {
    morpho::samples::chalice_outline(240, 0.3, 1)
}

fn points_section(ctx: &Ctx) -> Result<Vec<Section>> {
    let pts = chalice();
    let mut s = Section::new(
        "Points on a chalice outline",
        "Scattered points sampled from a closed chalice-like outline with a little noise: the \
         input of the boundary construction (Veltkamp 1992, ch. 5).",
    );
    let ps = morpho::mesh::PointSet::from_points2(&pts);
    morpho::io::write_points(&ctx.path("chalice.csv"), &ps)?;
    s.files.push("chalice.csv".into());
    write_svg(ctx, "chalice_points.svg", &morpho::render::points_svg(&pts))?;
    s.img("chalice_points.svg", "240 points (generated, seed 1)");
    let b = morpho::geom::bbox2(&pts);
    s.fig("points", pts.len());
    s.fig(
        "bbox",
        format!(
            "[{:.3}, {:.3}] .. [{:.3}, {:.3}]",
            b.min[0], b.min[1], b.max[0], b.max[1]
        ),
    );
    Ok(vec![s])
}

fn delaunay_section(ctx: &Ctx) -> Result<Vec<Section>> {
    use morpho::delaunay::{triangulate_2d, triangulate_3d};
    let pts = chalice();
    let t = Instant::now();
    let d = triangulate_2d(&pts)?;
    let dt = t.elapsed().as_secs_f64();
    let mut s = Section::new(
        "Delaunay triangulation and Voronoi diagram",
        "Exact predicates with symbolic perturbation (the result does not depend on the input \
         order); the Voronoi diagram is the dual (Veltkamp §2.2.9).",
    );
    write_svg(ctx, "chalice_delaunay.svg", &render::delaunay_svg(&d, true))?;
    s.img(
        "chalice_delaunay.svg",
        "Delaunay (blue) and Voronoi (red, dashed)",
    );
    s.fig("points", pts.len());
    s.fig("triangles", d.triangles.len());
    s.fig("hull vertices", d.hull.len());
    s.fig("triangulation time", format!("{:.2} ms", dt * 1e3));
    // a 3D example: 20 000 points on and in a sphere
    let p3 = morpho::samples::sphere_points(20_000, 1.0);
    let t = Instant::now();
    let d3 = triangulate_3d(&p3)?;
    s.fig("3D: points on a sphere", p3.len());
    s.fig("3D: tetrahedra", d3.tets.len());
    s.fig(
        "3D: time",
        format!("{:.1} ms", t.elapsed().as_secs_f64() * 1e3),
    );
    Ok(vec![s])
}

fn gamma_section(ctx: &Ctx) -> Result<Vec<Section>> {
    use morpho::graphs::{graph_2d, Kind};
    use rand_pts::points25;
    let p = points25();
    let mut out = Vec::new();
    /// (title, text, graphs with their labels)
    type Strip<'a> = (&'a str, &'a str, Vec<(Kind, String)>);
    let strips: [Strip; 3] = [
        (
            "γ([-1,1],[c,1]) for decreasing c (Veltkamp Fig. 3.3)",
            "From the convex hull (c = 1) through the Delaunay triangulation (c = 0) to graphs with crossing edges (c < 0).",
            [1.0, 0.6, 0.3, 0.0, -0.2, -0.5]
                .iter()
                .map(|&c| (Kind::GammaRange([-1.0, 1.0, c, 1.0]), format!("γ([-1,1],[{c},1])")))
                .collect(),
        ),
        (
            "β-skeletons as γ(c, c) (Veltkamp Fig. 3.4)",
            "N_γ(c, c) = N_βc(c); γ(0, 0) is the Gabriel graph.",
            [0.2, 0.1, 0.0, -0.2].iter().map(|&c| (Kind::Gamma(c, c), format!("γ({c},{c})"))).collect(),
        ),
        (
            "Intersection neighbourhoods (Veltkamp Fig. 3.5)",
            "γ([-1,1],[-1,0]) is the complement of the Delaunay triangulation; thinner neighbourhoods join points only when another point lies close to the edge.",
            vec![
                (Kind::GammaRange([-1.0, 1.0, -1.0, 0.0]), "γ([-1,1],[-1,0])".into()),
                (Kind::GammaRange([-0.25, 0.25, -0.25, 0.0]), "γ([-¼,¼],[-¼,0])".into()),
                (Kind::GammaRange([-1.0, 1.0, -1.0, -0.9]), "γ([-1,1],[-1,-0.9])".into()),
                (Kind::GammaRange([-1.0, 1.0, -1.0, -0.95]), "γ([-1,1],[-1,-0.95])".into()),
            ],
        ),
    ];
    for (si, (title, text, kinds)) in strips.into_iter().enumerate() {
        let mut s = Section::new(title, text);
        for (k, (kind, label)) in kinds.into_iter().enumerate() {
            let g = graph_2d(&p, kind)?;
            let name = format!("gamma_{si}_{k}.svg");
            write_svg(ctx, &name, &render::graph_svg(&p, &g, Some(&label)))?;
            s.img(&name, &format!("{label}: {} edges", g.edges.len()));
            s.fig(&label, format!("{} edges", g.edges.len()));
        }
        out.push(s);
    }
    Ok(out)
}

/// A fixed 25-point set for the γ-graph pictures.
mod rand_pts {
    use morpho::geom::Point2;
    pub fn points25() -> Vec<Point2> {
        // a low-discrepancy set (golden-ratio and √2 sequences) jittered by a fixed pattern
        (0..25)
            .map(|i| {
                let f = i as f64;
                let x = (f * 0.618_033_988_749_895).fract();
                let y = (f * 0.414_213_562_373_095 + 0.13 * ((f * 2.3).sin()))
                    .fract()
                    .abs();
                Point2::new(x, y)
            })
            .collect()
    }
}

fn mesh_figures(s: &mut Section, m: &morpho::mesh::TriMesh) {
    let t = morpho::mesh::analyze_topology(m);
    s.fig("vertices", m.num_vertices());
    s.fig("triangles", m.num_triangles());
    s.fig("parts", t.parts.len());
    s.fig("boundary loops", t.boundary_loops.len());
    s.fig("Euler characteristic", t.euler_characteristic);
    s.fig(
        "genus",
        t.genus()
            .map(|g| g.to_string())
            .unwrap_or_else(|| "undefined".into()),
    );
    s.fig("manifold", if t.manifold { "yes" } else { "no" });
}

fn mesh_section(ctx: &Ctx) -> Result<Vec<Section>> {
    use morpho::render::{render_mesh, RenderOptions};
    let mut out = Vec::new();
    let mut s = Section::new(
        "A generated mesh: the double torus",
        "Topology by Hamann §3.3 in linear time: parts, boundary loops, Euler characteristic and genus (Def. 5.14).",
    );
    let m = morpho::mesh::generate::multi_torus(2);
    let opts = RenderOptions {
        azimuth_deg: 25.0,
        elevation_deg: 50.0,
        shading: morpho::render::Shading::Flat,
        ..Default::default()
    };
    render_mesh(&m, &opts).save_png(&ctx.path("double_torus.png"))?;
    s.img("double_torus.png", "double torus (flat shading)");
    view_page(ctx, &mut s, "double_torus", &m)?;
    mesh_figures(&mut s, &m);
    out.push(s);
    for (file, title, az) in [
        (
            "meshes/stanford-bunny.obj.gz",
            "A real scan: the Stanford bunny",
            20.0,
        ),
        (
            "meshes/rocker-arm.obj",
            "A CAD part of genus 1: the rocker arm",
            35.0,
        ),
    ] {
        let Some(path) = ctx.data_file(file) else {
            continue;
        };
        let m = morpho::io::read_mesh(&path)?;
        let mut s = Section::new(
            title,
            &format!("Read from {file}; rendered by morpho's software rasterizer."),
        );
        let name = format!(
            "{}.png",
            Path::new(file)
                .file_name()
                .and_then(|n| n.to_str())
                .unwrap_or("mesh")
                .split('.')
                .next()
                .unwrap_or("mesh")
        );
        let opts = RenderOptions {
            azimuth_deg: az,
            ..Default::default()
        };
        render_mesh(&m, &opts).save_png(&ctx.path(&name))?;
        s.img(&name, file);
        mesh_figures(&mut s, &m);
        out.push(s);
    }
    Ok(out)
}

fn volume_section(ctx: &Ctx) -> Result<Vec<Section>> {
    use morpho::render::{middle, orthogonal_slices, SliceOptions};
    let mut out = Vec::new();
    let v = morpho::samples::shepp_logan_volume(96);
    let mut s = Section::new(
        "Volume: the 3D Shepp–Logan phantom",
        "Three orthogonal slices with a colour map (Hamann ch. 2).",
    );
    orthogonal_slices(&v, middle(&v), &SliceOptions::default())?
        .save_png(&ctx.path("phantom_slices.png"))?;
    s.img("phantom_slices.png", "x, y, z middle slices");
    s.fig("dims", format!("{:?}", v.dims));
    if let Some((lo, hi)) = v.value_range() {
        s.fig("value range", format!("{lo} .. {hi}"));
    }
    volume_view_page(ctx, &mut s, "phantom", &v, Some(0.1))?;
    out.push(s);
    if let Some(path) = ctx.data_file("volumes/cthead_8bit_256x256x99.json") {
        let v = morpho::io::read_volume(&path)?;
        let mut s = Section::new(
            "Volume: a CT head",
            "volumes/cthead_8bit_256x256x99 (u8, spacing 1:1:2), orthogonal slices.",
        );
        let opts = SliceOptions {
            colormap: morpho::render::Colormap::Greys,
            ..Default::default()
        };
        orthogonal_slices(&v, middle(&v), &opts)?.save_png(&ctx.path("cthead_slices.png"))?;
        s.img("cthead_slices.png", "CT head, middle slices");
        s.fig("dims", format!("{:?}", v.dims));
        s.fig("spacing", format!("{:?}", v.spacing()));
        if let Some((lo, hi)) = v.value_range() {
            s.fig("value range", format!("{lo} .. {hi}"));
        }
        volume_view_page(ctx, &mut s, "cthead", &v, None)?;
        out.push(s);
    }
    Ok(out)
}

fn contour_section(ctx: &Ctx) -> Result<Vec<Section>> {
    use morpho::contour::{contour_samples, SampleContour, SampleOptions};
    let mut out = Vec::new();
    let mut cases: Vec<(String, String, morpho::mesh::PointSet, SampleOptions, String)> = vec![(
        "Regions above a threshold: a synthetic borehole field".into(),
        "2000 generated boreholes with three deposits; triangles rated by the mean of their corners, black above 25; the external contour in linear time (Dorgerloh et al. §3).".into(),
        morpho::samples::borehole_field(2000, 7),
        SampleOptions {
            threshold: 25.0,
            ..Default::default()
        },
        "boreholes".into(),
    )];
    if let Some(path) = ctx.data_file("geostat/meuse.csv") {
        cases.push((
            "Real samples: zinc in the Meuse flood plain".into(),
            "geostat/meuse.csv (155 topsoil samples, zinc in ppm); black where the mean zinc of a triangle exceeds 500 ppm; regions with their holes.".into(),
            morpho::io::read_points(&path)?,
            SampleOptions {
                value: Some("zinc".into()),
                threshold: 500.0,
                holes: true,
                ..Default::default()
            },
            "meuse_zinc".into(),
        ));
    }
    for (title, text, samples, opts, name) in cases.drain(..) {
        let t = Instant::now();
        let r = contour_samples(&samples, &opts)?;
        let dt = t.elapsed().as_secs_f64();
        let SampleContour::Plane(pc) = r else {
            continue;
        };
        let mut s = Section::new(&title, &text);
        write_svg(ctx, &format!("{name}.svg"), &render::contour_svg(&pc))?;
        s.img(&format!("{name}.svg"), "black triangles and their contour");
        let gj = ctx.path(&format!("{name}.geojson"));
        morpho::io::write_contour_2d(&gj, &pc, opts.threshold, opts.below)?;
        s.files.push(format!("{name}.geojson"));
        s.fig("samples", samples.len());
        s.fig("triangles", pc.triangles.len());
        s.fig("black triangles", pc.black.iter().filter(|b| **b).count());
        s.fig("cycles", pc.contour.cycles.len());
        s.fig("threshold", opts.threshold);
        s.fig(
            "time (triangulation + rating + contour)",
            format!("{:.1} ms", dt * 1e3),
        );
        out.push(s);
    }
    Ok(out)
}

fn iso_figures(s: &mut Section, r: &morpho::volume::IsoResult, dt: f64) {
    s.fig("vertices", r.mesh.num_vertices());
    s.fig("triangles", r.mesh.num_triangles());
    s.fig("parts", r.parts);
    s.fig("boundary edges (on the volume's faces)", r.boundary_edges);
    s.fig("interior holes (Def. 3.10)", r.interior_holes);
    s.fig(
        "extraction + normals + topology",
        format!("{:.0} ms", dt * 1e3),
    );
}

fn isosurface_section(ctx: &Ctx) -> Result<Vec<Section>> {
    use morpho::render::{render_mesh, RenderOptions, UpAxis};
    use morpho::volume::{isosurface, IsoMethod, IsoOptions};
    let mut out = Vec::new();
    let v = morpho::samples::shepp_logan_volume(128);
    let t = Instant::now();
    let r = isosurface(
        &v,
        &IsoOptions {
            level: 0.1,
            ..Default::default()
        },
    )?;
    let dt = t.elapsed().as_secs_f64();
    let mut s = Section::new(
        "Contour surface of the Shepp–Logan phantom (f = 0.1)",
        "Marching cubes made consistent by the asymptotic decider and interior points (Hamann §3.2); \
         the head's outer surface and the inner surfaces around the ventricles are separate parts.",
    );
    let opts = RenderOptions {
        up: UpAxis::Z,
        azimuth_deg: 30.0,
        elevation_deg: 20.0,
        ..Default::default()
    };
    render_mesh(&r.mesh, &opts).save_png(&ctx.path("phantom_surface.png"))?;
    s.img("phantom_surface.png", "f = 0.1, Zucker–Hummel normals");
    iso_figures(&mut s, &r, dt);
    morpho::io::write_mesh(
        &ctx.path("phantom_surface.ply"),
        &r.mesh,
        morpho::io::Encoding::BinaryLittleEndian,
    )?;
    s.files.push("phantom_surface.ply".into());
    out.push(s);
    if let Some(path) = ctx.data_file("volumes/cthead_8bit_256x256x99.json") {
        let v = morpho::io::read_volume(&path)?;
        let mut s = Section::new(
            "Bone surface of a CT head (level 120)",
            "volumes/cthead_8bit_256x256x99 at the bone level; the consistent method leaves no interior \
             holes, the Lorensen–Cline table does (H Fig. 3.2).",
        );
        let t = Instant::now();
        let r = isosurface(
            &v,
            &IsoOptions {
                level: 120.0,
                ..Default::default()
            },
        )?;
        let dt = t.elapsed().as_secs_f64();
        let m = upright_head(r.mesh.clone());
        let opts = RenderOptions {
            up: UpAxis::Z,
            azimuth_deg: 25.0,
            elevation_deg: 5.0,
            ..Default::default()
        };
        render_mesh(&m, &opts).save_png(&ctx.path("cthead_bone.png"))?;
        s.img("cthead_bone.png", "decider method, level 120");
        view_page(ctx, &mut s, "cthead_bone", &m)?;
        iso_figures(&mut s, &r, dt);
        let lor = isosurface(
            &v,
            &IsoOptions {
                level: 120.0,
                method: IsoMethod::Lorensen,
                ..Default::default()
            },
        )?;
        s.fig("Lorensen–Cline: triangles", lor.mesh.num_triangles());
        s.fig("Lorensen–Cline: interior holes", lor.interior_holes);
        let tet = isosurface(
            &v,
            &IsoOptions {
                level: 120.0,
                method: IsoMethod::Tetra,
                ..Default::default()
            },
        )?;
        s.fig("6-tetrahedra method: triangles", tet.mesh.num_triangles());
        s.fig("6-tetrahedra method: interior holes", tet.interior_holes);
        out.push(s);
    }
    Ok(out)
}

fn boundary_section(ctx: &Ctx) -> Result<Vec<Section>> {
    let mut out = vec![chalice_constriction(ctx)?];
    if let Some(path) = ctx.data_file("curves2d/ohrhallinger_fitconnect/apple_2percent_noise.txt") {
        out.push(three_methods_2d(ctx, &path)?);
    }
    if let Some(path) = ctx.data_file("meshes/bunny_npm.obj") {
        out.push(bunny_boundary(ctx, &path)?);
    }
    Ok(out)
}

/// γ-constriction of the chalice, pictured at five steps.
fn chalice_constriction(ctx: &Ctx) -> Result<Section> {
    use morpho::boundary::{boundary_2d, constriction_steps_2d, Key, Options2};
    let p = chalice();
    let mut s = Section::new(
        "Boundary through all points: γ-constriction of the chalice (Veltkamp §5.2)",
        "Starting from the convex hull of the Delaunay triangulation, the removable boundary edge with the smallest \
         γ-indicator is deleted until every point is on the boundary (Algorithm 5.1, with a heap).",
    );
    let t = Instant::now();
    let b = boundary_2d(&p, &Options2::default())?;
    let dt = t.elapsed().as_secs_f64();
    let total = b.iterations.max(1);
    let steps: Vec<usize> = [0, total / 4, total / 2, 3 * total / 4, total].to_vec();
    let polys = constriction_steps_2d(&p, Key::Gamma, &steps)?;
    for (k, (cyc, step)) in polys.iter().zip(&steps).enumerate() {
        let name = format!("chalice_step{k}.svg");
        write_svg(
            ctx,
            &name,
            &render::cycle_svg(&p, cyc, &format!("after {step} deletions"), 260.0),
        )?;
        s.img(
            &name,
            &format!("{} of {} points on the boundary", cyc.len(), p.len()),
        );
    }
    s.fig("points", p.len());
    s.fig("deletions", b.iterations);
    s.fig("all points on the boundary", b.all_on_boundary);
    s.fig("area", format!("{:.4}", b.area));
    s.fig("time", format!("{:.1} ms", dt * 1e3));
    Ok(s)
}

/// The three 2D methods on a noisy outline with ground truth (the points in curve order).
fn three_methods_2d(ctx: &Ctx, path: &Path) -> Result<Section> {
    use morpho::boundary::{boundary_2d, Options2};
    let pts = morpho::io::read_points(path)?.to_points2();
    let mut s = Section::new(
        "Three methods on a noisy outline",
        "curves2d/ohrhallinger_fitconnect/apple_2percent_noise.txt: γ-indicator (V §5.2), minimal area change \
         (Boissonnat, V §4.3.3) and the shortest Voronoi skeleton (O'Rourke et al., V §4.3.4). The file lists the \
         points in curve order, so the fraction of its consecutive pairs that are polygon edges measures recovery.",
    );
    for (m, name) in [
        (Options2::gamma(), "gamma"),
        (Options2::min_area_change(), "min-area-change"),
        (Options2::voronoi_skeleton(200), "voronoi-skeleton"),
    ] {
        let t = Instant::now();
        let b = boundary_2d(&pts, &m)?;
        let dt = t.elapsed().as_secs_f64();
        let mut on: std::collections::HashSet<[u32; 2]> = std::collections::HashSet::new();
        for i in 0..b.polygon.len() {
            let (a, c) = (b.polygon[i], b.polygon[(i + 1) % b.polygon.len()]);
            on.insert([a.min(c), a.max(c)]);
        }
        let n = pts.len() as u32;
        let hit = (0..n)
            .filter(|&i| on.contains(&[i.min((i + 1) % n), i.max((i + 1) % n)]))
            .count();
        let file = format!("apple_{name}.svg");
        write_svg(
            ctx,
            &file,
            &render::cycle_svg(&pts, &b.polygon, name, 300.0),
        )?;
        s.img(&file, name);
        s.fig(
            &format!("{name}: ground-truth edges recovered"),
            format!("{:.3}", hit as f64 / n as f64),
        );
        s.fig(
            &format!("{name}: all points on the boundary / time"),
            format!("{} / {:.1} ms", b.all_on_boundary, dt * 1e3),
        );
    }
    Ok(s)
}

/// The 3D boundary through the vertices of the bunny scan, and the comparison methods.
fn bunny_boundary(ctx: &Ctx, path: &Path) -> Result<Section> {
    use morpho::boundary::{boundary_3d, Method3, Options3, Until};
    use morpho::render::{render_mesh, RenderOptions, Shading};
    let m = morpho::io::read_mesh(path)?;
    let t = Instant::now();
    let b = boundary_3d(&m.positions, &Options3::gamma(Until::All))?;
    let dt = t.elapsed().as_secs_f64();
    let mut s = Section::new(
        "A closed boundary through the vertices of a scan (Veltkamp §5.3)",
        "The 1839 vertices of meshes/bunny_npm.obj, without their triangles: the Delaunay tetrahedralization is \
         constricted (tetrahedra with one or two boundary triangles, the γ-indicator of Def. 5.2 and the sum rule) \
         until every point lies on the boundary. Below, the two comparison methods on the same points (V §5.6): \
         Boissonnat's minimal area change fills the body but bridges concavities with long thin triangles; \
         the shortest Voronoi skeleton twists through the body (V Figs 5.10–5.11) and gets stuck before \
         every point is reached.",
    );
    let mesh = morpho::mesh::TriMesh::new(m.positions.clone(), b.triangles.clone());
    let opts = RenderOptions {
        shading: Shading::Flat,
        azimuth_deg: 20.0,
        ..Default::default()
    };
    render_mesh(&mesh, &opts).save_png(&ctx.path("bunny_boundary.png"))?;
    view_page(ctx, &mut s, "bunny_boundary", &mesh)?;
    s.img(
        "bunny_boundary.png",
        "--until all: stop as soon as every point is on the boundary",
    );
    let bl = boundary_3d(&m.positions, &Options3::gamma(Until::Locked))?;
    let mesh_l = morpho::mesh::TriMesh::new(m.positions.clone(), bl.triangles.clone());
    render_mesh(&mesh_l, &opts).save_png(&ctx.path("bunny_boundary_locked.png"))?;
    s.img(
        "bunny_boundary_locked.png",
        "--until locked: continue while removals keep the boundary valid",
    );
    s.fig(
        "--until locked: triangles / closed / genus / volume",
        format!(
            "{} / {} / {} / {:.1}",
            bl.triangles.len(),
            bl.closed_manifold,
            bl.genus
                .map(|g| g.to_string())
                .unwrap_or_else(|| "undefined".into()),
            bl.volume
        ),
    );
    s.fig("points", m.positions.len());
    s.fig("boundary triangles", b.triangles.len());
    s.fig("all points on the boundary", b.all_on_boundary);
    s.fig("closed 2-manifold", b.closed_manifold);
    s.fig(
        "genus",
        b.genus
            .map(|g| g.to_string())
            .unwrap_or_else(|| "undefined".into()),
    );
    s.fig(
        "enclosed volume (original mesh: 194.3)",
        format!("{:.1}", b.volume),
    );
    s.fig("time", format!("{:.0} ms", dt * 1e3));
    // the comparison methods of V §4.3.3 and §4.3.4 on the same points (V §5.6)
    let sorted = |t: &[u32; 3]| {
        let mut t = *t;
        t.sort_unstable();
        t
    };
    let truth: std::collections::HashSet<[u32; 3]> = m.triangles.iter().map(sorted).collect();
    let recovered = |tris: &[[u32; 3]]| {
        let hit = tris.iter().filter(|t| truth.contains(&sorted(t))).count();
        100.0 * hit as f64 / truth.len().max(1) as f64
    };
    s.fig(
        "γ-indicator: original triangles recovered",
        format!("{:.1} %", recovered(&b.triangles)),
    );
    for (method, file, what) in [
        (
            Method3::MinAreaChange {
                c: morpho::boundary::CParam::Auto,
                until: Until::All,
                keep: Vec::new(),
            },
            "bunny_min_area.png",
            "minimal area change (Boissonnat, V §4.3.3)",
        ),
        (
            Method3::VoronoiSkeleton { max_seeds: 200 },
            "bunny_skeleton.png",
            "shortest Voronoi skeleton (O'Rourke et al., V §4.3.4)",
        ),
    ] {
        let o = Options3 { method };
        let t = Instant::now();
        let bm = boundary_3d(&m.positions, &o)?;
        let dt = t.elapsed().as_secs_f64();
        let mesh = morpho::mesh::TriMesh::new(m.positions.clone(), bm.triangles.clone());
        render_mesh(&mesh, &opts).save_png(&ctx.path(file))?;
        s.img(file, what);
        s.fig(
            &format!("{what}: left out / recovered / volume / time"),
            format!(
                "{} / {:.1} % / {:.1} / {:.0} ms",
                bm.left_out.len(),
                recovered(&bm.triangles),
                bm.volume,
                dt * 1e3
            ),
        );
    }
    Ok(s)
}

/// The picture of one γ-constriction through the Dillencourt set: the graph's edges thin, the
/// deleted ones dashed, the polygon fat, v highlighted, the key vertices labelled.
fn dillencourt_picture(
    p: &[morpho::geom::Point2],
    graph: &[[u32; 2]],
    deleted: &[[u32; 2]],
    polygon: &[u32],
    title: &str,
) -> String {
    let labels: Vec<render::PointLabel> = ["s0", "h1", "s1", "h2", "s2", "h3", "s3", "v", "w"]
        .iter()
        .enumerate()
        .map(|(index, text)| render::PointLabel {
            index,
            text,
            // v and h3 (far right) are labelled on their left
            dx: match index {
                7 => -13.0,
                5 => -18.0,
                _ => 3.0,
            },
        })
        .collect();
    render::constriction_svg(p, graph, deleted, polygon, title, Some(7), &labels)
}

fn dillencourt_section(ctx: &Ctx) -> Result<Vec<Section>> {
    use morpho::boundary::{boundary_2d, check_polygon, CParam, Options2};
    use morpho::graphs::{graph_2d, Kind};
    let p = morpho::samples::dillencourt_points();
    let mut s = Section::new(
        "A non-Hamiltonian Delaunay triangulation and the fallback (Veltkamp §5.4, Fig. 5.7)",
        "20 points whose Delaunay triangulation is non-degenerate and two-connected but has no Hamilton cycle \
         (after Dillencourt 1987; our own construction): the ears h1, h2, h3 have degree 2, so a Hamilton cycle \
         would use s1's edges to h1 and h2 and s2's edges to h2 and h3; v's only other neighbour is w. \
         Constriction of the Delaunay graph (c = 0) locks with v left out; constriction of γ([-1,1],[c,1]) for \
         c < 0 (the graph has crossing edges) finds a simple polygon through all points. Fat: the polygon; \
         dashed: the edges deleted during constriction.",
    );
    s.fig("points", p.len());
    let cases = [
        (CParam::Fixed(0.0), "γ([-1,1],[0,1]) = Delaunay: locked"),
        (CParam::Fixed(-0.1), "γ([-1,1],[-0.1,1])"),
        (CParam::Fixed(-0.2), "γ([-1,1],[-0.2,1])"),
        (CParam::Fixed(-0.3), "γ([-1,1],[-0.3,1])"),
        (CParam::Auto, "c = auto (adaptive augmentation)"),
    ];
    let dt = graph_2d(&p, Kind::Delaunay)?;
    write_svg(
        ctx,
        "dillencourt_dt.svg",
        &dillencourt_picture(&p, &dt.edges, &[], &[], "Delaunay triangulation"),
    )?;
    s.img(
        "dillencourt_dt.svg",
        &format!(
            "Delaunay triangulation: {} edges, no Hamilton cycle",
            dt.edges.len()
        ),
    );
    for (k, (c, label)) in cases.into_iter().enumerate() {
        let b = boundary_2d(
            &p,
            &Options2 {
                method: morpho::boundary::Method2::Gamma {
                    c,
                    keep: Vec::new(),
                },
            },
        )?;
        let chk = check_polygon(&p, &b.polygon);
        let g = graph_2d(&p, Kind::GammaRange([-1.0, 1.0, b.c_used, 1.0]))?;
        let name = format!("dillencourt_{k}.svg");
        write_svg(
            ctx,
            &name,
            &dillencourt_picture(&p, &g.edges, &b.deleted, &b.polygon, label),
        )?;
        s.img(
            &name,
            &format!(
                "{label}: {} of {} points on the polygon",
                b.polygon.len(),
                p.len()
            ),
        );
        s.fig(
            label,
            format!(
                "c_used {} · {} graph edges · {} deleted · boundary vertices {} · simple {}",
                b.c_used,
                g.edges.len(),
                b.deleted.len(),
                b.polygon.len(),
                chk.simple
            ),
        );
    }
    Ok(vec![s])
}
