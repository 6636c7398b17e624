//! `morpho contour SAMPLES --threshold T [--value COL] [--rating mean|min|max|median|area-mean]
//! [--below] [--holes] [--min-area A] -o OUT`: regions where the rating of the samples is above
//! (below) a threshold — Delaunay triangulation, rating, and the external contour of
//! Dorgerloh et al. (2D), or the external boundary surfaces of rated tetrahedra (3D samples).
//!
//! 2D outputs: `.geojson` (FeatureCollection of Polygons, closed rings, outer rings
//! counter-clockwise, holes clockwise, property `threshold`), `.json` (`{"cycles": [[sample
//! indices…]…]}`), `.svg` (coloured triangles with the contour). 3D outputs: `.ply` (or another
//! mesh format: `.obj .off .stl .vtu .vtk`) with a face property `component`.
//! Report keys: `samples`, `triangles` or `tetrahedra`, `black`, `components`, `cycles`
//! (2D) or `surface_triangles` (3D), `skipped`, `value`.

use crate::report::Report;
use crate::Failure;
use morpho::contour::{Rating, SampleContour, SampleOptions};
use morpho::io::{self, Encoding, Format};
use morpho::mesh::PointSet;
use morpho::render;
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// Samples with values: CSV with header `x,y,value…` (2D) or `x,y,z,value…` (3D), XYZ, PLY.
    pub input: PathBuf,
    /// Output: .geojson, .json or .svg for 2D samples; .ply (.obj .off .stl .vtu .vtk) for 3D
    /// samples.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Threshold of the rating: triangles rated above it are black (the regions).
    #[arg(long, allow_hyphen_values = true)]
    pub threshold: f64,
    /// The value column (default: `value`, or the only column).
    #[arg(long)]
    pub value: Option<String>,
    /// How a triangle is rated from its corner values.
    #[arg(long, default_value = "mean", value_parser = ["mean", "min", "max", "median", "area-mean"])]
    pub rating: String,
    /// Regions where the rating is below the threshold instead of above.
    #[arg(long)]
    pub below: bool,
    /// 2D: the complete boundary — polygons with their holes — instead of the external contour.
    #[arg(long)]
    pub holes: bool,
    /// 2D: drop regions with a smaller area.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub min_area: f64,
}

/// Triangulates the samples (2D or 3D by their dimension), rates and contours them.
fn contour_samples(samples: &PointSet, opts: &SampleOptions) -> morpho::Result<SampleContour> {
    morpho::contour::contour_samples(samples, opts).map_err(morpho::Error::from)
}

pub fn run(args: Args, report: &mut Report) -> Result<u8, Failure> {
    let fmt = Format::of(&args.output)?;
    let plane_out = matches!(fmt, Format::GeoJson | Format::Json | Format::Svg);
    let mesh_out = io::is_mesh_format(fmt);
    if !plane_out && !mesh_out {
        return Err(Failure::usage(format!(
            "{}: contour writes .geojson, .json or .svg (2D) or .ply/.obj/.off/.stl/.vtu/.vtk (3D)",
            args.output.display()
        )));
    }
    if !args.threshold.is_finite() || !args.min_area.is_finite() {
        return Err(Failure::usage(
            "--threshold and --min-area must be finite numbers",
        ));
    }
    let rating: Rating = args.rating.parse()?;
    let opts = SampleOptions {
        value: args.value.clone(),
        threshold: args.threshold,
        rating,
        below: args.below,
        holes: args.holes,
        min_area: args.min_area,
    };
    let samples = report.time("read", || io::read_points(&args.input))?;
    if samples.dim == 3 && plane_out {
        return Err(Failure::usage(format!(
            "{}: the samples are 3D (x, y, z); write the surface as .ply, .obj, .off, .stl, .vtu or .vtk",
            args.input.display()
        )));
    }
    if samples.dim == 3 && (args.holes || args.min_area > 0.0) {
        return Err(Failure::usage(
            "--holes and --min-area apply to 2D samples; 3D gives the external surfaces",
        ));
    }
    if samples.dim == 2 && mesh_out {
        return Err(Failure::usage(format!(
            "{}: the samples are 2D; write the contour as .geojson, .json or .svg",
            args.input.display()
        )));
    }
    let result = report
        .time("compute", || contour_samples(&samples, &opts))
        .map_err(|e| Failure::from(e.with_path(&args.input)))?;
    report.set("samples", samples.len());
    report.set("threshold", args.threshold);
    let out = &args.output;
    match &result {
        SampleContour::Plane(r) => {
            report.set("value", r.selected.column.clone());
            report.set("skipped", r.selected.skipped);
            report.set("triangles", r.triangles.len());
            report.set("black", r.contour.black);
            report.set("components", r.contour.components);
            report.set("cycles", r.contour.cycles.len());
            report.set("dropped", r.contour.dropped);
            report.time("write", || match fmt {
                Format::Svg => io::write_text(out, &render::contour_svg(r)),
                _ => io::write_contour_2d(out, r, args.threshold, args.below),
            })?;
        }
        SampleContour::Space(r) => {
            report.set("value", r.selected.column.clone());
            report.set("skipped", r.selected.skipped);
            report.set("tetrahedra", r.tets.len());
            report.set("black", r.surface.black);
            report.set("components", r.surface.components);
            report.set("surface_triangles", r.surface.triangles.len());
            let mesh = r.surface.to_trimesh(&r.points);
            report.time("write", || {
                io::write_mesh(out, &mesh, Encoding::BinaryLittleEndian)
            })?;
        }
    }
    report.set("output", out.display().to_string());
    Ok(0)
}
