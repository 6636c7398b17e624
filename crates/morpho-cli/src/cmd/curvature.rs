//! `morpho curvature MESH|VOLUME -o OUT`: curvature of a triangle mesh (Hamann 1991, §4.2, the
//! osculating-paraboloid fit over the k-ring platelet) or of the graph of a trivariate function
//! (H §4.3, the 6-tetrahedra platelet); see `morpho::curvature`.
//!
//! - Meshes → `.ply` (the mesh with vertex properties `k1,k2,H,K,A`, κ₁ ≤ κ₂, NaN where the fit
//!   is undetermined) or `.csv` (`x,y,z,index,k1,k2,H,K,A` per vertex; an undetermined value is
//!   an empty cell). Normals: `--normals jet` (default) estimates them by area weighting and
//!   corrects each by a cubic fit over its 2-ring; `area` (= `mesh`), `uniform`, `inverse` are
//!   the weightings of V §9.4 alone; `file` uses the file's (PLY `nx,ny,nz`; refused when
//!   absent). `--fit paraboloid` (default) is the thesis's osculating paraboloid (H §4.2) over
//!   the `--ring K` platelet (default 1); `--fit quadric` adds linear terms (default ring 2).
//!   **The thesis's method** is `--normals area --fit paraboloid --ring 1` (or `--normals file`
//!   with exact normals, as in H Table 4.1). The default's jet normals are an extension: with
//!   area normals alone the 1-ring paraboloid loses to libigl and VTK on irregular meshes
//!   (`bench/curvature_peers.py`, `bench/README.md`). Curvature is measured along the normal:
//!   an outward-oriented sphere of radius R has H = −1/R.
//! - Volumes → `-o DIR`: `DIR/k1.nrrd k2.nrrd k3.nrrd H.nrrd K.nrrd` on the input grid (same
//!   dims, spacing, origin, orientation), f32, NaN where undetermined; gradients by central
//!   differences.
//!
//! Report keys: `vertices` (or `samples`), `undetermined`, and `min`/`max`/`median` of each
//! quantity over the determined vertices; timings.

use crate::report::Report;
use crate::Failure;
use morpho::curvature::{
    surface_curvature, volume_curvature, Gradients, NormalSource, SurfaceFit, SurfaceOptions,
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
    /// Vertex normals: `jet` = area-weighted, corrected by a cubic fit over the 2-ring
    /// (default; not in the thesis); `area` (= `mesh`), `uniform`, `inverse` = that weighting
    /// alone (V §9.4); `file` = the file's. The thesis's method: `--normals area` (or `file`)
    /// with the default fit and ring.
    #[arg(long, default_value = "jet", value_parser = ["jet", "mesh", "area", "uniform", "inverse", "file"])]
    pub normals: String,
    /// The fitted surface: `paraboloid` (the thesis's, H §4.2) or `quadric` (with linear
    /// terms: corrects a tilted normal, needs ≥ 5 points).
    #[arg(long, default_value = "paraboloid", value_parser = ["paraboloid", "quadric"])]
    pub fit: String,
    /// Fit over the K-ring of each vertex (default: 1 for the paraboloid = the thesis's
    /// platelet, 2 for the quadric).
    #[arg(long)]
    pub ring: Option<usize>,
}

/// min, max, median of the finite values (None when there are none).
fn summary(v: &[f64]) -> serde_json::Value {
    let mut f: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
    if f.is_empty() {
        return json!(null);
    }
    f.sort_by(f64::total_cmp);
    json!({"min": f[0], "max": f[f.len() - 1], "median": f[f.len() / 2]})
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
    let mut mesh = report.time("read", || io::read_mesh(&args.input))?;
    let normals = match args.normals.as_str() {
        "file" => NormalSource::File,
        "uniform" => NormalSource::Estimated(NormalWeighting::Uniform),
        "inverse" => NormalSource::Estimated(NormalWeighting::InverseArea),
        _ => NormalSource::Estimated(NormalWeighting::Area),
    };
    let fit = match args.fit.as_str() {
        "quadric" => SurfaceFit::Quadric,
        _ => SurfaceFit::Paraboloid,
    };
    let jet_normals = args.normals == "jet";
    let ring = args.ring.unwrap_or(match fit {
        SurfaceFit::Quadric => 2,
        _ => 1,
    });
    let opts = SurfaceOptions {
        normals,
        ring,
        fit,
        jet_normals,
    };
    let c = report.time("compute", || {
        surface_curvature(&mesh, &opts)
            .map_err(|e| Failure::from(morpho::Error::from(e).with_path(&args.input)))
    })?;
    report.set("vertices", mesh.positions.len());
    report.set("undetermined", c.undetermined);
    if jet_normals {
        report.set("jet_fallbacks", c.jet_fallbacks);
    }
    report.set("ring", ring);
    report.set(
        "fit",
        match fit {
            SurfaceFit::Quadric => "quadric",
            _ => "paraboloid",
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
    if out_ext == "ply" {
        mesh.vertex_props
            .retain(|p| !["k1", "k2", "H", "K", "A"].contains(&p.name.as_str()));
        for (name, v) in columns {
            mesh.vertex_props.push(Property {
                name: name.into(),
                kind: ScalarKind::F64,
                values: v.clone(),
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
                cols
            },
        };
        report.time("write", || io::write_points(&args.output, &pts))?;
    }
    eprintln!(
        "wrote {} ({} vertices, {} undetermined)",
        args.output.display(),
        mesh.positions.len(),
        c.undetermined
    );
    Ok(0)
}

fn run_volume(args: &Args, report: &mut Report) -> Result<u8, Failure> {
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
