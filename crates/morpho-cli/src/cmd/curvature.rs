//! `morpho curvature MESH|VOLUME -o OUT`: curvature of a triangle mesh (Hamann 1991, §4.2, the
//! osculating-paraboloid fit over the k-ring platelet) or of the graph of a trivariate function
//! (H §4.3, the 6-tetrahedra platelet); see `morpho::curvature`.
//!
//! - Meshes → `.ply` (the mesh with vertex properties `k1,k2,H,K,A`, κ₁ ≤ κ₂, NaN where the fit
//!   is undetermined) or `.csv` (`x,y,z,index,k1,k2,H,K,A` per vertex; an undetermined value is
//!   an empty cell). `--directions` adds the unit principal directions `d1x,d1y,d1z` (of κ₁)
//!   and `d2x,d2y,d2z` (of κ₂ = normal × d1), NaN (empty in CSV) where undetermined; they are
//!   opt-in because most users want the scalars (the full pass keeps 19 MB more on the skull
//!   and the PLY grows by half). **Default** (`--normals jet`, `--fit jet`): a jet (degree 4, else 3)
//!   fitted over each vertex's 2-ring in the frame of the area-weighted normal, and the
//!   curvature of the fitted graph at the vertex (on a boundary vertex, where that fit is
//!   one-sided, the quadric with linear terms over the 2-ring instead). Not in the thesis: it
//!   beats libigl and VTK on the meshes of `bench/curvature_peers.py` (`bench/README.md`).
//!   `--normals jet --fit paraboloid` is the previous default (the jet's normal, then the
//!   thesis's 1-ring paraboloid). `--normals area` (= `mesh`), `uniform`, `inverse` are the
//!   weightings of V §9.4 alone; `file` uses the file's (PLY `nx,ny,nz`; refused when absent);
//!   with these the default fit is `--fit paraboloid`, the thesis's osculating paraboloid
//!   (H §4.2) over the `--ring K` platelet (default 1); `--fit quadric` adds linear terms
//!   (default ring 2); `--fit jet` is the jet in their normals' frame (default ring 2).
//!   **The thesis's method** is `--normals area` (= `--normals area --fit paraboloid --ring 1`;
//!   or `--normals file` with exact normals, as in H Table 4.1). Curvature is measured along
//!   the normal: an outward-oriented sphere of radius R has H = −1/R.
//! - Volumes → `-o DIR`: `DIR/k1.nrrd k2.nrrd k3.nrrd H.nrrd K.nrrd` on the input grid (same
//!   dims, spacing, origin, orientation), f32, NaN where undetermined; gradients by central
//!   differences.
//!
//! Report keys: `vertices` (or `samples`), `undetermined`, and `min`/`max`/`median` of each
//! quantity over the determined vertices; timings.

use crate::report::Report;
use crate::Failure;
use morpho::curvature::{
    surface_curvature, surface_curvature_scalars, volume_curvature, Gradients, NormalSource,
    SurfaceFit, SurfaceOptions,
};
use morpho::io;
use morpho::mesh::{NormalWeighting, Property, ScalarKind};
use serde_json::json;
use std::path::PathBuf;

/// `morpho curvature` arguments.
#[derive(clap::Args)]
pub struct Args {
    /// Triangle mesh (.ply .obj .off .stl) or volume (.nrrd .nhdr .mhd .json).
    pub input: PathBuf,
    /// Output: .ply or .csv for a mesh; a folder for a volume.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Vertex normals: `jet` = area-weighted, with the jet fit's own normal and curvature
    /// (default; not in the thesis; boundary vertices get the quadric over the 2-ring instead);
    /// `area` (= `mesh`), `uniform`, `inverse` = that weighting
    /// alone (V §9.4); `file` = the file's. The thesis's method: `--normals area` (or `file`)
    /// with the default fit and ring.
    #[arg(long, default_value = "jet", value_parser = ["jet", "mesh", "area", "uniform", "inverse", "file"])]
    pub normals: String,
    /// The fitted surface: `jet` (a polynomial of degree 4, else 3, over the 2-ring: the
    /// curvature of the fitted graph at the vertex; default with `--normals jet`; not in the
    /// thesis), `paraboloid` (the thesis's, H §4.2;
    /// default with any other `--normals`) or `quadric` (with linear terms: corrects a tilted
    /// normal, needs ≥ 5 points). `--normals jet --fit paraboloid` is the jet-corrected normal
    /// followed by the thesis's paraboloid.
    #[arg(long, value_parser = ["jet", "paraboloid", "quadric"])]
    pub fit: Option<String>,
    /// Fit over the K-ring of each vertex (default: 1 for the paraboloid = the thesis's
    /// platelet, 2 for the quadric and the jet; the jet uses at least 2).
    #[arg(long)]
    pub ring: Option<usize>,
    /// Also write the unit principal directions: `d1x,d1y,d1z` (of κ₁) and `d2x,d2y,d2z` (of
    /// κ₂), NaN where the vertex is undetermined.
    #[arg(long)]
    pub directions: bool,
}

/// min, max, median of the finite values (None when there are none).
fn summary(v: &[f64]) -> serde_json::Value {
    let mut f: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
    if f.is_empty() {
        return json!(null);
    }
    // the values a full sort would put first, in the middle and last (selection: O(V), where
    // five sorts of the skull's columns took as long as the curvature itself)
    let (min, max) = f.iter().fold((f[0], f[0]), |(lo, hi), &x| {
        (
            if x.total_cmp(&lo).is_lt() { x } else { lo },
            if x.total_cmp(&hi).is_gt() { x } else { hi },
        )
    });
    let mid = f.len() / 2;
    let median = *f.select_nth_unstable_by(mid, f64::total_cmp).1;
    json!({"min": min, "max": max, "median": median})
}

/// Lets the allocator hand the mesh command's large freed blocks to its later allocations
/// instead of returning them to the kernel and asking for fresh pages (glibc: blocks up to
/// 32 MiB, the ceiling of glibc's own adaptive threshold, come from the heap,
/// `mallopt(M_MMAP_THRESHOLD)`, and the heap's top is never trimmed, `M_TRIM_THRESHOLD`). The
/// read stage frees the file's bytes (21 MB on the 257k-vertex skull) just before the
/// curvature allocates its adjacency and cross products. On the benchmark's virtual machine a
/// fresh page's first touch costs 0.6 ms/MB (4 KiB pages) and, for huge pages, 0.08 or
/// 1.2–2 ms/MB depending on whether the host still backs the block (free page reporting):
/// that made the skull's one-thread time bimodal; a reused heap page costs a `memset` at most
/// (0.05 ms/MB). Measured in `bench/README.md` (branch `jet10`). The outputs are the same
/// bytes (only where the memory comes from changes). Elsewhere a no-op.
fn reuse_freed_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: `mallopt` only sets two of glibc's allocation thresholds (taking the arena's
    // lock itself); no memory is touched and no pointer is passed
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 32 << 20);
        libc::mallopt(libc::M_TRIM_THRESHOLD, i32::MAX);
    }
}

fn is_volume(ext: &str) -> bool {
    matches!(ext, "nrrd" | "nhdr" | "mhd" | "mha" | "json")
}

/// Runs `morpho curvature`.
pub fn run(args: Args, report: &mut Report) -> Result<u8, Failure> {
    if args.ring == Some(0) {
        return Err(Failure::usage("--ring must be at least 1"));
    }
    let ext = crate::cmd::extension(&args.input);
    if is_volume(&ext) {
        return run_volume(&args, report);
    }
    let out_ext = crate::cmd::extension(&args.output);
    if !matches!(out_ext.as_str(), "ply" | "csv") {
        return Err(Failure::usage(format!(
            "{}: mesh curvature is written as .ply or .csv",
            args.output.display()
        )));
    }
    reuse_freed_memory();
    let mut mesh = report.time("read", || io::read_mesh(&args.input))?;
    let normals = match args.normals.as_str() {
        "file" => NormalSource::File,
        "uniform" => NormalSource::Estimated(NormalWeighting::Uniform),
        "inverse" => NormalSource::Estimated(NormalWeighting::InverseArea),
        _ => NormalSource::Estimated(NormalWeighting::Area),
    };
    let jet = args.normals == "jet";
    let fit = match (args.fit.as_deref(), jet) {
        (Some("quadric"), _) => SurfaceFit::Quadric,
        (Some("jet"), _) | (None, true) => SurfaceFit::Jet,
        _ => SurfaceFit::Paraboloid,
    };
    // `--normals jet` corrects the normal before a paraboloid or quadric; the jet fit needs no
    // correction (it is the same cubic)
    let jet_normals = jet && fit != SurfaceFit::Jet;
    let ring = args.ring.unwrap_or(match fit {
        SurfaceFit::Paraboloid => 1,
        _ => 2,
    });
    // the jet needs at least the 2-ring (the report names the ring used)
    let ring = if fit == SurfaceFit::Jet {
        ring.max(2)
    } else {
        ring
    };
    let opts = SurfaceOptions {
        normals,
        ring,
        fit,
        jet_normals,
    };
    // without --directions the PLY and the CSV hold k1, k2, H, K, A only: no principal
    // directions and normals kept in memory (the same values, `surface_curvature_scalars`)
    let c = report.time("compute", || {
        if args.directions {
            surface_curvature(&mesh, &opts)
        } else {
            surface_curvature_scalars(&mesh, &opts)
        }
        .map_err(|e| Failure::from(morpho::Error::from(e).with_path(&args.input)))
    })?;
    let directions = if args.directions {
        direction_columns(&c)
    } else {
        Vec::new()
    };
    report.set("directions", args.directions);
    report.set("vertices", mesh.positions.len());
    report.set("undetermined", c.undetermined);
    if jet_normals || fit == SurfaceFit::Jet {
        report.set("jet_fallbacks", c.jet_fallbacks);
    }
    report.set("ring", ring);
    report.set(
        "fit",
        match fit {
            SurfaceFit::Quadric => "quadric",
            SurfaceFit::Jet => "jet",
            SurfaceFit::Paraboloid => "paraboloid",
        },
    );
    report.set("normals", args.normals.as_str());
    let columns = [
        ("k1", &c.k1),
        ("k2", &c.k2),
        ("H", &c.h),
        ("K", &c.k),
        ("A", &c.a),
    ];
    for (name, v) in columns {
        report.set(name, summary(v));
    }
    let undetermined = c.undetermined;
    if out_ext == "ply" {
        mesh.vertex_props
            .retain(|p| !["k1", "k2", "H", "K", "A"].contains(&p.name.as_str()));
        // the columns move into the mesh (no copy)
        let mut c = c;
        for (name, v) in [
            ("k1", &mut c.k1),
            ("k2", &mut c.k2),
            ("H", &mut c.h),
            ("K", &mut c.k),
            ("A", &mut c.a),
        ] {
            mesh.vertex_props.push(Property {
                name: name.into(),
                kind: ScalarKind::F64,
                values: std::mem::take(v),
            });
        }
        for (name, values) in directions {
            mesh.vertex_props.retain(|p| p.name != name);
            mesh.vertex_props.push(Property {
                name: name.into(),
                kind: ScalarKind::F64,
                values,
            });
        }
        report.time("write", || {
            io::write_mesh(&args.output, &mesh, io::Encoding::BinaryLittleEndian)
        })?;
    } else {
        let mut cols = vec![morpho::mesh::Column {
            name: "index".into(),
            values: (0..mesh.positions.len()).map(|i| i as f64).collect(),
        }];
        // x, y, z as the point set's coordinates; the index and curvatures as columns
        let pts = morpho::mesh::PointSet {
            dim: 3,
            coords: mesh
                .positions
                .iter()
                .flat_map(|p| [p.x, p.y, p.z])
                .collect(),
            columns: {
                cols.extend(columns.iter().map(|(n, v)| morpho::mesh::Column {
                    name: (*n).into(),
                    values: (*v).clone(),
                }));
                cols.extend(
                    directions
                        .into_iter()
                        .map(|(n, values)| morpho::mesh::Column {
                            name: n.into(),
                            values,
                        }),
                );
                cols
            },
        };
        report.time("write", || io::write_points(&args.output, &pts))?;
    }
    eprintln!(
        "wrote {} ({} vertices, {} undetermined)",
        args.output.display(),
        mesh.positions.len(),
        undetermined
    );
    Ok(0)
}

/// The principal directions as six columns `d1x … d2z`, NaN at the undetermined vertices
/// (whose k1 is NaN).
fn direction_columns(c: &morpho::curvature::SurfaceCurvature) -> Vec<(&'static str, Vec<f64>)> {
    let names = [["d1x", "d1y", "d1z"], ["d2x", "d2y", "d2z"]];
    let mut out = Vec::with_capacity(6);
    for (d, names) in [&c.dir1, &c.dir2].into_iter().zip(names) {
        for (axis, name) in names.into_iter().enumerate() {
            let values = d
                .iter()
                .zip(&c.k1)
                .map(|(v, k1)| if k1.is_nan() { f64::NAN } else { v[axis] })
                .collect();
            out.push((name, values));
        }
    }
    out
}

fn run_volume(args: &Args, report: &mut Report) -> Result<u8, Failure> {
    if args.directions {
        return Err(Failure::usage(
            "--directions is for meshes: volume curvature writes k1 … K only",
        ));
    }
    if args.output.exists() && !args.output.is_dir() {
        return Err(Failure::usage(format!(
            "{}: volume curvature is written into a folder (k1.nrrd … K.nrrd); this is a file",
            args.output.display()
        )));
    }
    let vol = report.time("read", || io::read_volume(&args.input))?;
    let c = report.time("compute", || {
        volume_curvature(&vol, &Gradients::Differences)
            .map_err(|e| Failure::from(morpho::Error::from(e).with_path(&args.input)))
    })?;
    report.set("samples", vol.data.len());
    report.set("undetermined", c.undetermined);
    let fields = [
        ("k1", &c.k1),
        ("k2", &c.k2),
        ("k3", &c.k3),
        ("H", &c.h),
        ("K", &c.k),
    ];
    for (name, v) in fields {
        report.set(name, summary(v));
    }
    std::fs::create_dir_all(&args.output)
        .map_err(|e| Failure::from(morpho::Error::io(&args.output, e)))?;
    report.time("write", || -> Result<(), Failure> {
        for (name, v) in fields {
            let mut out = vol.clone();
            out.data = v.iter().map(|&x| x as f32).collect();
            out.source_dtype = morpho::volume::DType::F32;
            io::write_volume(&args.output.join(format!("{name}.nrrd")), &out)?;
        }
        Ok(())
    })?;
    eprintln!(
        "wrote {}/{{k1,k2,k3,H,K}}.nrrd ({} samples, {} undetermined)",
        args.output.display(),
        vol.data.len(),
        c.undetermined
    );
    Ok(0)
}

/// The median of the finite values (NaN when there are none).
fn summary_median(v: &[f64]) -> f64 {
    let mut f: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
    if f.is_empty() {
        return f64::NAN;
    }
    f.sort_by(f64::total_cmp);
    f[f.len() / 2]
}

/// A symmetric colour range `±a` for signed curvature: `a` is the `pct`-th percentile of `|x|`
/// over the finite values (curvature of scans is heavy-tailed: the maximum would wash
/// everything else out to grey).
fn symmetric_range(v: &[f64], pct: usize) -> f64 {
    let mut a: Vec<f64> = v
        .iter()
        .filter(|x| x.is_finite())
        .map(|x| x.abs())
        .collect();
    if a.is_empty() {
        return 1.0;
    }
    a.sort_by(f64::total_cmp);
    let q = a[(a.len() * pct / 100).min(a.len() - 1)];
    if q > 0.0 {
        q
    } else {
        1.0
    }
}

/// A mesh coloured by its mean curvature over `±a` (diverging map centred on 0) with a
/// colour bar.
fn h_picture(
    m: &morpho::mesh::TriMesh,
    h: &[f64],
    a: f64,
    view: &morpho::render::RenderOptions,
) -> morpho::render::Image {
    use morpho::render::{render_mesh, with_colorbar, Colormap, Scalars};
    let img = render_mesh(
        m,
        &morpho::render::RenderOptions {
            scalars: Some(Scalars {
                values: h.to_vec(),
                per_face: false,
                colormap: Colormap::Coolwarm,
                range: Some((-a, a)),
            }),
            ..view.clone()
        },
    );
    with_colorbar(&img, Colormap::Coolwarm, -a, a, Some("H"))
}

/// `morpho demo` section "curvature" (issue 20): the CT skull and the Stanford bunny coloured
/// by mean curvature (the default for estimated normals), and the Table 4.2 slices of
/// H Figs 4.9–4.12 (exact beside approximated H).
pub fn demo_section(ctx: &super::demo::Ctx) -> morpho::Result<Vec<morpho::io::html::Section>> {
    use morpho::curvature::tables::{table_4_2_fields, table_4_2_name};
    use morpho::io::html::Section;
    use morpho::render::{orthogonal_slices, Colormap, RenderOptions, SliceOptions, UpAxis};
    use std::time::Instant;
    let mut out = Vec::new();
    let opts = SurfaceOptions::estimated_normals();
    let mut s = Section::new(
        "Mean curvature of a contour surface and of a scan",
        "Hamann ch. 4: H per vertex by a local surface fit (H §4.2): morpho's default for \
         estimated normals fits a jet of degree 4 (else 3) with linear terms over the 2-ring in \
         the frame of the area-weighted normal and takes the fitted graph's curvature at the \
         vertex (`--normals area` is the thesis's method, the osculating paraboloid over the \
         1-ring). Diverging colour map \
         centred on H = 0: blue H < 0 (bending away from the outward normal: convex), red \
         H > 0 (concave), grey flat or saddle-balanced. The skull's contour surface carries \
         voxel-scale steps (slices 2 voxels apart), so it is fitted over the 3-ring \
         (`--ring 3`) and shown over ±1.5 × the median of |H| (the vault, radius ≈ 75 voxels, is \
         blue); the bunny over the 2-ring, range ±(95th percentile of |H|).",
    );
    if let Some(path) = ctx.data_file("volumes/cthead_8bit_256x256x99.json") {
        use morpho::volume::{isosurface, IsoOptions};
        let v = morpho::io::read_volume(&path)?;
        let r = isosurface(
            &v,
            &IsoOptions {
                level: 120.0,
                ..Default::default()
            },
        )?;
        let t = Instant::now();
        let c = surface_curvature(
            &r.mesh,
            &SurfaceOptions {
                ring: 3,
                ..opts.clone()
            },
        )?;
        let dt = t.elapsed().as_secs_f64();
        let a = 1.5 * symmetric_range(&c.h, 50);
        // curvature on the surface as extracted (outward normals), pictures upright
        let m = super::demo::upright_head(r.mesh);
        let view = RenderOptions {
            up: UpAxis::Z,
            azimuth_deg: 25.0,
            elevation_deg: 5.0,
            ..Default::default()
        };
        h_picture(&m, &c.h, a, &view).save_png(&ctx.path("curvature_skull_H.png"))?;
        s.img(
            "curvature_skull_H.png",
            "CT head bone surface (level 120), mean curvature over the 3-ring",
        );
        s.fig(
            "skull: vertices / undetermined",
            format!("{} / {}", m.positions.len(), c.undetermined),
        );
        s.fig("skull: seconds (3-ring)", format!("{dt:.2}"));
        s.fig("skull: median H", format!("{:.4}", summary_median(&c.h)));
    }
    if let Some(path) = ctx.data_file("meshes/stanford-bunny.obj.gz") {
        let m = morpho::io::read_mesh(&path)?;
        let t = Instant::now();
        let c = surface_curvature(&m, &opts)?;
        let dt = t.elapsed().as_secs_f64();
        let view = RenderOptions {
            up: UpAxis::Y,
            azimuth_deg: 20.0,
            elevation_deg: 20.0,
            ..Default::default()
        };
        h_picture(&m, &c.h, symmetric_range(&c.h, 95), &view)
            .save_png(&ctx.path("curvature_bunny_H.png"))?;
        s.img(
            "curvature_bunny_H.png",
            "Stanford bunny (range scan), mean curvature",
        );
        s.fig(
            "bunny: vertices / undetermined",
            format!("{} / {}", m.positions.len(), c.undetermined),
        );
        s.fig("bunny: seconds", format!("{dt:.2}"));
    }
    out.push(s);
    let mut s = Section::new(
        "Curvature of trivariate graphs: Table 4.2 slices (H Figs 4.9–4.12)",
        "Hamann §4.3: mean curvature H of the graph (x, y, z, f) in R⁴ on the 26³ grid over \
         [-1,1]³, fitted over the 6-tetrahedra platelet with exact gradients. Each row: the \
         exact H (top) and the approximated H (below) on the three middle slices x = 0, y = 0, \
         z = 0, one symmetric colour range per function; grey: undetermined face points (102 \
         on this grid).",
    );
    let m = 26;
    for (row, fig) in [(2, "4.9"), (3, "4.10"), (4, "4.11"), (6, "4.12")] {
        let (Some([hx, ha, _, _]), Some(name)) = (table_4_2_fields(row, m), table_4_2_name(row))
        else {
            continue;
        };
        let a = hx
            .iter()
            .chain(&ha)
            .filter(|x| x.is_finite())
            .fold(0.0f64, |a, x| a.max(x.abs()));
        let a = if a > 0.0 { a } else { 1.0 };
        let so = SliceOptions {
            colormap: Colormap::Coolwarm,
            range: Some((-a, a)),
            size: Some(200),
            ..Default::default()
        };
        for (field, which) in [(&hx, "exact"), (&ha, "approx")] {
            let vol = morpho::volume::Volume::from_fn([m; 3], [-1.0; 3], [1.0; 3], |x, y, z| {
                let q = |c: f64| ((c + 1.0) * 0.5 * (m - 1) as f64).round() as usize;
                field[q(x) + m * q(y) + m * m * q(z)]
            });
            let img = orthogonal_slices(&vol, [m / 2; 3], &so)?;
            let file = format!("curvature_t42_{row}_{which}.png");
            img.save_png(&ctx.path(&file))?;
            s.img(
                &file,
                &format!("Fig. {fig}: {name}, {which} H (middle slices)"),
            );
        }
    }
    for r in morpho::curvature::tables::table_4_2(m) {
        s.fig(
            &format!("Table 4.2 row {}: RMS H / K (thesis)", r.row),
            format!(
                "{:.6} / {:.6} ({:.6} / {:.6}); interior {:.6} / {:.6}",
                r.rms[0], r.rms[1], r.thesis[0], r.thesis[1], r.rms_interior[0], r.rms_interior[1]
            ),
        );
    }
    out.push(s);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// After `reuse_freed_memory` a block of 24 MB (the skull's file is 21 MB) is carved from
    /// the heap, not mapped on its own: glibc's count of directly mapped bytes does not grow
    /// by it (a lower threshold, or no call, maps it and fails this).
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    #[test]
    fn large_blocks_come_from_the_heap_after_reuse_freed_memory() {
        reuse_freed_memory();
        // SAFETY: `mallinfo2` only reads the allocator's statistics
        let mapped = || unsafe { libc::mallinfo2() }.hblkhd;
        let before = mapped();
        let v: Vec<u8> = Vec::with_capacity(24 << 20);
        std::hint::black_box(v.as_ptr());
        let during = mapped();
        drop(v);
        assert!(
            during < before + (24 << 20),
            "the 24 MB block was mapped on its own: {before} → {during} bytes mapped"
        );
    }
}
