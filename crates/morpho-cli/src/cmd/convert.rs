//! `morpho convert IN -o OUT`: format conversion by extension. Meshes, points, polygons and
//! volumes convert between the formats of their kind; a tetrahedral PLY (a `tetra` element, as
//! `morpho triangulate --tets` writes it) converts to VTK (`.vtu`, `.vtk`), and so does a
//! triangle mesh. A CSV or XYZ file is a point set (to `.geojson`: one `Point` feature per
//! point, columns as properties); `--polygon` reads a CSV as the ordered vertices of a polygon
//! instead (to `.geojson`: a `Polygon`).

use crate::report::Report;
use crate::Failure;
use morpho::io::{self, read_any, Data, Encoding, Format};
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// Input file.
    pub input: PathBuf,
    /// Output file; its extension chooses the format.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Write PLY/STL/VTK as ASCII instead of binary.
    #[arg(long)]
    pub ascii: bool,
    /// Write binary PLY (and .vtu) big endian.
    #[arg(long, conflicts_with = "ascii")]
    pub big_endian: bool,
    /// Read a CSV input as the ordered vertices of a polygon (a repeated first vertex closes
    /// it), not as a point set.
    #[arg(long)]
    pub polygon: bool,
}

pub fn run(args: Args, report: &mut Report) -> Result<u8, Failure> {
    Format::of(&args.output)?;
    let enc = if args.ascii {
        Encoding::Ascii
    } else if args.big_endian {
        Encoding::BinaryBigEndian
    } else {
        Encoding::BinaryLittleEndian
    };
    let out = &args.output;
    if matches!(Format::of(out)?, Format::Vtu | Format::Vtk) {
        if let Some(t) = report.time("read", || io::read_tets_if_present(&args.input))? {
            report.time("write", || io::write_tets(out, &t, enc))?;
            report.set("input", args.input.display().to_string());
            report.set("output", out.display().to_string());
            report.set("tetrahedra", t.tets.len());
            return Ok(0);
        }
    }
    let data = if args.polygon {
        if Format::of(&args.input)? != Format::Csv {
            return Err(Failure::usage("--polygon reads a .csv input"));
        }
        report.time("read", || io::read_shapes2(&args.input).map(Data::Shapes))?
    } else {
        report.time("read", || read_any(&args.input))?
    };
    report.time("write", || match &data {
        Data::Mesh(m) => io::write_mesh(out, m, enc),
        Data::Points(p) => io::write_points_as(out, p, enc),
        Data::Shapes(s) => io::write_shapes2(out, s),
        Data::Volume(v) => io::write_volume(out, v),
    })?;
    report.set("input", args.input.display().to_string());
    report.set("output", out.display().to_string());
    Ok(0)
}
