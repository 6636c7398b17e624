//! `morpho isosurface VOLUME --level A -o MESH`: the contour surface f = A of a volume
//! (Hamann 1991 §3.2–3.4; see `morpho::volume::isosurface`). Report keys: `vertices`,
//! `triangles`, `parts`, `boundary_edges`, `interior_holes`, `method`, `normals`, `level`,
//! `fan_points`, `centroid_fallbacks`, `skipped_cells`, `note` (when the result is empty or
//! NaN cells were skipped), and the global `elapsed_s`. A level outside the data range writes an
//! empty mesh, sets `note` and exits 0.

use crate::report::Report;
use crate::Failure;
use morpho::io::{self, Encoding};
use morpho::mesh::TriMesh;
use morpho::volume::Volume;
use morpho::volume::{extract_part, isosurface, largest_part, IsoMethod, IsoOptions, NormalMethod};
use std::path::PathBuf;

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum MethodArg {
    /// Marching cubes with the asymptotic decider and interior points (consistent).
    Decider,
    /// Six tetrahedra per cell (consistent).
    Tetra,
    /// Lorensen–Cline cell-local table (baseline; may leave holes).
    Lorensen,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum NormalsArg {
    /// Zucker–Hummel 3x3x3 gradient operator, interpolated to contour points.
    Zucker,
    /// Central differences, interpolated to contour points.
    Central,
    /// From the triangulation alone (fitted quadric).
    Mesh,
    /// No normals.
    None,
}

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Input volume.
    pub input: PathBuf,
    /// Output mesh (.ply keeps normals and the `part` face property).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Contour level α.
    #[arg(long, allow_hyphen_values = true)]
    pub level: f64,
    /// Contouring method.
    #[arg(long, value_enum, default_value_t = MethodArg::Decider)]
    pub method: MethodArg,
    /// Vertex normals.
    #[arg(long, value_enum, default_value_t = NormalsArg::Zucker)]
    pub normals: NormalsArg,
    /// Keep only the part with the most triangles.
    #[arg(long)]
    pub largest_part: bool,
    /// Orient triangles and normals along +grad f (inside = below the level).
    #[arg(long)]
    pub flip: bool,
    /// Run on one thread (the output is identical).
    #[arg(long)]
    pub serial: bool,
    /// Write PLY as ASCII.
    #[arg(long)]
    pub ascii: bool,
    /// Read the volume slab by slab and write the mesh as it is made, for volumes larger than
    /// memory (raw, gzip or zlib data; PLY output; the same file as without).
    #[arg(long)]
    pub stream: bool,
    /// With --stream: memory for the samples of one slab, in MiB (at least one z-slice is
    /// read whatever the value).
    #[arg(long, default_value_t = 64.0, value_name = "MIB", requires = "stream")]
    pub slab_mib: f64,
}

/// Refuses a volume whose sample coordinates overflow (a header's spacing of 1e308 over a few
/// samples): the surface's vertices would be infinite. The input is blamed, not the output
/// (issue 17 item 12).
pub fn finite_extent(
    axes: &morpho::volume::Axes,
    dims: [usize; 3],
    input: &std::path::Path,
) -> Result<(), Failure> {
    let ends: Vec<f64> = match axes {
        morpho::volume::Axes::Uniform { origin, spacing } => (0..3)
            .flat_map(|k| {
                let last = dims[k].saturating_sub(1) as f64;
                [origin[k], origin[k] + last * spacing[k]]
            })
            .collect(),
        morpho::volume::Axes::Coords(c) => c.iter().flatten().copied().collect(),
    };
    if ends.iter().all(|v| v.is_finite()) {
        return Ok(());
    }
    Err(Failure::usage(format!(
        "{}: the volume's extent is not a finite number (origin + spacing × (size − 1) \
         overflows): its sample coordinates cannot be represented",
        input.display()
    )))
}

pub fn run(args: Args, report: &mut Report) -> Result<u8, Failure> {
    io::Format::of(&args.output)?;
    if args.stream {
        return super::isostream::run(&args, report);
    }
    let vol = report
        .time("read", || io::read_volume(&args.input))
        .map_err(|e| {
            let mut f = Failure::from(e);
            if f.msg.contains("memory limit") {
                f.msg.push_str("; --stream reads the volume slab by slab");
            }
            f
        })?;
    finite_extent(&vol.axes, vol.dims, &args.input)?;
    let t = std::time::Instant::now();
    let mesh = process(&vol, &args, report)?;
    report.add_time("compute", t.elapsed().as_secs_f64());
    let enc = if args.ascii {
        Encoding::Ascii
    } else {
        Encoding::BinaryLittleEndian
    };
    report.time("write", || io::write_mesh(&args.output, &mesh, enc))?;
    report.set("input", args.input.display().to_string());
    report.set("output", args.output.display().to_string());
    Ok(0)
}

/// IsoOptions from the arguments.
pub fn options(args: &Args) -> IsoOptions {
    IsoOptions {
        level: args.level,
        method: match args.method {
            MethodArg::Decider => IsoMethod::Decider,
            MethodArg::Tetra => IsoMethod::Tetra,
            MethodArg::Lorensen => IsoMethod::Lorensen,
        },
        normals: match args.normals {
            NormalsArg::Zucker => NormalMethod::ZuckerHummel,
            NormalsArg::Central => NormalMethod::Central,
            NormalsArg::Mesh => NormalMethod::Mesh,
            NormalsArg::None => NormalMethod::None,
        },
        flip: args.flip,
        parallel: !args.serial,
        topology: true,
    }
}

/// The report's names of the method and the normals.
fn names(args: &Args) -> (&'static str, &'static str) {
    let method = match args.method {
        MethodArg::Decider => "decider",
        MethodArg::Tetra => "tetra",
        MethodArg::Lorensen => "lorensen",
    };
    let normals = match args.normals {
        NormalsArg::Zucker => "zucker",
        NormalsArg::Central => "central",
        NormalsArg::Mesh => "mesh",
        NormalsArg::None => "none",
    };
    (method, normals)
}

/// The report's method, normals, level and the result's figures (not its counts).
pub fn report_figures(report: &mut Report, args: &Args, r: &morpho::volume::IsoResult) {
    let (method, normals) = names(args);
    report.set("method", method);
    report.set("normals", normals);
    report.set("level", args.level);
    report.set("parts", r.parts);
    report.set("boundary_edges", r.boundary_edges);
    report.set("interior_holes", r.interior_holes);
    report.set("interior_boundary_edges", r.interior_boundary_edges);
    report.set("non_manifold_edges", r.non_manifold_edges);
    report.set("fan_points", r.fan_points);
    report.set("centroid_fallbacks", r.centroid_fallbacks);
    report.set("skipped_cells", r.skipped_cells);
    if let Some(n) = &r.note {
        report.set("note", n.clone());
    }
}

/// Extracts the surface, fills the report, applies `--largest-part`.
pub fn process(vol: &Volume, args: &Args, report: &mut Report) -> Result<TriMesh, Failure> {
    let r = isosurface(vol, &options(args))?;
    report_figures(report, args, &r);
    let mut mesh = r.mesh;
    if args.largest_part {
        if let Some(p) = largest_part(&mesh) {
            mesh = extract_part(&mesh, p);
        }
        report.set("largest_part_triangles", mesh.triangles.len());
    }
    report.set("vertices", mesh.positions.len());
    report.set("triangles", mesh.triangles.len());
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(level: f64, method: MethodArg, largest: bool) -> Args {
        Args {
            input: "in.vol".into(),
            output: "out.ply".into(),
            level,
            method,
            normals: NormalsArg::Zucker,
            largest_part: largest,
            flip: false,
            serial: false,
            ascii: false,
            stream: false,
            slab_mib: 256.0,
        }
    }

    fn two_blobs() -> Volume {
        Volume::from_fn([20, 20, 20], [-1.0; 3], [1.0; 3], |x, y, z| {
            let a = 0.16 - ((x + 0.5).powi(2) + y * y + z * z);
            let b = 0.09 - ((x - 0.5).powi(2) + y * y + z * z);
            a.max(b)
        })
    }

    #[test]
    fn report_keys_and_largest_part() {
        let v = two_blobs();
        let mut rep = Report::new("isosurface");
        let m = process(&v, &args(0.0, MethodArg::Decider, false), &mut rep)
            .unwrap_or_else(|f| panic!("{}", f.msg));
        let j = rep.to_json();
        assert_eq!(j["parts"], 2);
        assert_eq!(j["interior_holes"], 0);
        assert_eq!(j["boundary_edges"], 0);
        assert_eq!(j["method"], "decider");
        assert_eq!(j["triangles"], m.triangles.len());
        assert_eq!(j["vertices"], m.positions.len());
        let mut rep2 = Report::new("isosurface");
        let big = process(&v, &args(0.0, MethodArg::Tetra, true), &mut rep2)
            .unwrap_or_else(|f| panic!("{}", f.msg));
        big.validate().unwrap();
        assert!(big.positions.iter().all(|p| p.x < 0.0));
    }

    #[test]
    fn level_outside_range_is_empty_with_note() {
        let v = two_blobs();
        let mut rep = Report::new("isosurface");
        let m = process(&v, &args(50.0, MethodArg::Lorensen, true), &mut rep)
            .unwrap_or_else(|f| panic!("{}", f.msg));
        assert!(m.triangles.is_empty());
        assert!(rep.to_json()["note"].as_str().unwrap().contains("outside"));
    }
}
