//! `morpho view FILE… -o page.html [--figures REPORT.json] [--level L] [--lod TRIANGLES]
//! [--volume-samples N]`: one self-contained interactive page (WebGL 2, offline, `file://`)
//! showing every input (issue 22, part 2; see `morpho::viewer`). Meshes with their vertex
//! properties as colour maps, point sets, 2D shapes; a volume as three movable orthogonal
//! slices (`morpho::viewer::VolumeLayer`, subsampled above `--volume-samples` with a note) and
//! its contour surface at `--level` (default: the midpoint of its range) as a second layer,
//! hidden until ticked (none, with a note, for a constant volume or one with a single sample
//! along an axis). A volume without a finite sample is `error:` (exit 2). Inputs are read
//! through `morpho::io`; the page is written with `io::write_text` (atomic, never over an
//! input).

use crate::report::Report;
use crate::Failure;
use morpho::io::{self, Data};
use morpho::viewer::{page_html, Layer, Page};
use std::path::PathBuf;

/// `morpho view` arguments.
#[derive(clap::Args)]
pub struct Args {
    /// Files to show: meshes, point sets, 2D shapes, volumes.
    #[arg(required = true)]
    pub inputs: Vec<PathBuf>,
    /// Output page (.html).
    #[arg(short, long)]
    pub output: PathBuf,
    /// A report JSON of an earlier run, shown as the figure panel.
    #[arg(long)]
    pub figures: Option<PathBuf>,
    /// Contour level for volumes (default: midpoint of the value range).
    #[arg(long)]
    pub level: Option<f64>,
    /// Meshes with more triangles get an interaction proxy of about this many triangles
    /// (vertex clustering), drawn while the camera moves; 0 turns it off.
    #[arg(long, default_value_t = morpho::viewer::DEFAULT_LOD)]
    pub lod: usize,
    /// Volumes with more samples are shown subsampled (one sample in s along each axis, the
    /// smallest s that fits), with a note.
    #[arg(long, default_value_t = morpho::viewer::DEFAULT_MAX_SAMPLES)]
    pub volume_samples: usize,
}

/// Runs `morpho view`.
pub fn run(args: Args, report: &mut Report) -> Result<u8, Failure> {
    if crate::cmd::extension(&args.output) != "html" {
        return Err(Failure::usage(format!(
            "{}: the viewer writes an .html page",
            args.output.display()
        )));
    }
    let mut layers = Vec::new();
    for p in &args.inputs {
        let name = p
            .file_name()
            .map(|n| n.to_string_lossy().to_string())
            .unwrap_or_default();
        let data = report.time("read", || io::read_any(p))?;
        let layer = match data {
            Data::Mesh(m) => Layer::mesh(&name, &m),
            Data::Points(ps) => Layer::points(&name, &ps),
            Data::Shapes(s) => Layer::shapes(&name, &s),
            Data::Volume(v) => {
                for l in volume_layers(p, &name, &v, &args)? {
                    for n in &l.notes {
                        eprintln!("note: {}: {n}", p.display());
                    }
                    layers.push(l);
                }
                continue;
            }
        };
        if layer.is_empty() {
            return Err(Failure::usage(format!("{}: nothing to show", p.display())));
        }
        layers.push(layer);
    }
    let figures = match &args.figures {
        Some(f) => {
            let b = io::read_bytes(f)?;
            Some(
                serde_json::from_slice(&b)
                    .map_err(|e| Failure::usage(format!("{}: bad JSON: {e}", f.display())))?,
            )
        }
        None => None,
    };
    let title = args
        .inputs
        .iter()
        .map(|p| p.display().to_string())
        .collect::<Vec<_>>()
        .join(", ");
    let html = report.time("compute", || {
        page_html(&Page {
            title,
            layers,
            figures,
            lod: args.lod,
        })
    });
    report.time("write", || io::write_text(&args.output, &html))?;
    report.set("bytes", html.len());
    eprintln!("wrote {} ({} bytes)", args.output.display(), html.len());
    Ok(0)
}

/// A volume's layers: its slices, then its contour surface (hidden until ticked), or a note on
/// the slices saying why there is none.
fn volume_layers(
    p: &std::path::Path,
    name: &str,
    v: &morpho::volume::Volume,
    args: &Args,
) -> Result<Vec<Layer>, Failure> {
    let vl = morpho::viewer::VolumeLayer::new(v, args.volume_samples)
        .map_err(|e| Failure::usage(format!("{}: {e}", p.display())))?;
    let (lo, hi) = v
        .value_range()
        .map_or((0.0, 0.0), |(a, b)| (a as f64, b as f64));
    let mut slices = Layer::volume(&format!("{name} (slices)"), vl);
    let mut out = Vec::new();
    if lo == hi || v.dims.iter().any(|&n| n < 2) {
        slices.notes.push(
            "no contour surface (the volume is constant or has one sample along an axis)".into(),
        );
    } else {
        let level = args.level.unwrap_or(0.5 * (lo + hi));
        let r = morpho::volume::isosurface(
            v,
            &morpho::volume::IsoOptions {
                level,
                ..Default::default()
            },
        )
        .map_err(|e| Failure::from(morpho::Error::from(e).with_path(p)))?;
        if r.mesh.triangles.is_empty() {
            slices
                .notes
                .push(format!("the contour surface at f = {level} is empty"));
        } else {
            let mut m = Layer::mesh(&format!("{name} (contour f = {level})"), &r.mesh);
            m.hidden = true;
            out.push(m);
        }
    }
    out.insert(0, slices);
    Ok(out)
}
