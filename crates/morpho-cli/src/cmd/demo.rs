//! `morpho demo [--out DIR]`: runs every pipeline on generated sample data and on the bundled
//! real data (`../shared/data` next to the repository, when present) and writes a gallery:
//! `index.html` with one section per pipeline step, each picture beside its figures, plus the
//! result files. A section that fails is shown as failed and makes the command exit 1.

// Parts of the gallery API are used only by sections that land with later stages.
#![allow(dead_code)]

use crate::report::Report;
use crate::Failure;
use morpho::Result;
use std::fmt::Write as _;
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
}

/// One step of a pipeline as shown in the gallery.
pub struct Section {
    pub title: String,
    pub text: String,
    /// (file name relative to the gallery, caption)
    pub images: Vec<(String, String)>,
    /// (name, value)
    pub figures: Vec<(String, String)>,
    /// result files written (relative names)
    pub files: Vec<String>,
}

impl Section {
    fn new(title: &str, text: &str) -> Self {
        Section {
            title: title.into(),
            text: text.into(),
            images: vec![],
            figures: vec![],
            files: vec![],
        }
    }
    fn fig(&mut self, k: &str, v: impl std::fmt::Display) {
        self.figures.push((k.into(), v.to_string()));
    }
    fn img(&mut self, file: &str, caption: &str) {
        self.images.push((file.into(), caption.into()));
    }
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

/// The pipeline steps, in gallery order.
const SECTIONS: &[(&str, Builder)] = &[("sample points", points_section)];

pub fn run(args: Args, report: &mut Report) -> Result<u8, Failure> {
    std::fs::create_dir_all(&args.out).map_err(|e| morpho::Error::io(&args.out, e))?;
    let data = args.data.clone().or_else(default_data_dir);
    let ctx = Ctx {
        out: args.out.clone(),
        data: data.clone(),
    };
    let mut done: Vec<(Section, f64, Option<String>)> = Vec::new();
    let mut failed = 0;
    let t0 = Instant::now();
    for (name, build) in SECTIONS {
        let t = Instant::now();
        match build(&ctx) {
            Ok(secs) => {
                let dt = t.elapsed().as_secs_f64() / secs.len().max(1) as f64;
                for s in secs {
                    done.push((s, dt, None));
                }
            }
            Err(e) => {
                failed += 1;
                eprintln!("error: demo step '{name}' failed: {e}");
                done.push((
                    Section::new(name, ""),
                    t.elapsed().as_secs_f64(),
                    Some(e.to_string()),
                ));
            }
        }
    }
    report.add_time("compute", t0.elapsed().as_secs_f64());
    let html = gallery_html(&done, data.as_deref());
    let index = args.out.join("index.html");
    report.time("write", || {
        morpho::io::write_atomic(&index, |w| {
            w.write_all(html.as_bytes())
                .map_err(|e| morpho::Error::io(&index, e))
        })
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

/// `../shared/data` relative to the repository this binary was built from, or to the
/// current folder.
fn default_data_dir() -> Option<PathBuf> {
    let candidates = [
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data"),
        PathBuf::from("../shared/data"),
    ];
    candidates.into_iter().find(|p| p.is_dir())
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn gallery_html(sections: &[(Section, f64, Option<String>)], data: Option<&Path>) -> String {
    let mut h = String::new();
    h.push_str(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>morpho demo</title>\n<style>\n\
body{font-family:system-ui,sans-serif;margin:2em auto;max-width:1200px;color:#222}\n\
section{border-top:1px solid #ccc;padding:1em 0}\n.row{display:flex;flex-wrap:wrap;gap:1.5em;align-items:flex-start}\n\
figure{margin:0}figure img{max-width:540px;max-height:480px;border:1px solid #ddd;background:#fff}\n\
figcaption{font-size:90%;color:#555}\ntable{border-collapse:collapse;font-size:92%}td{padding:2px 10px;border-bottom:1px solid #eee}\n\
td:first-child{color:#555}.fail{color:#b00}\n</style></head><body>\n",
    );
    let _ = writeln!(
        h,
        "<h1>morpho demo</h1>\n<p>Every pipeline of morpho on generated sample data{}. morpho {}.</p>",
        match data {
            Some(d) => format!(" and the real data in <code>{}</code>", esc(&d.display().to_string())),
            None => " (real data folder not found)".into(),
        },
        morpho::VERSION
    );
    for (s, dt, err) in sections {
        let _ = writeln!(h, "<section><h2>{}</h2>", esc(&s.title));
        if let Some(e) = err {
            let _ = writeln!(h, "<p class=\"fail\">failed: {}</p></section>", esc(e));
            continue;
        }
        let _ = writeln!(h, "<p>{}</p><div class=\"row\">", esc(&s.text));
        for (img, cap) in &s.images {
            let _ = writeln!(
                h,
                "<figure><img src=\"{}\" alt=\"{}\"><figcaption>{}</figcaption></figure>",
                esc(img),
                esc(cap),
                esc(cap)
            );
        }
        h.push_str("<table>\n");
        for (k, v) in &s.figures {
            let _ = writeln!(h, "<tr><td>{}</td><td>{}</td></tr>", esc(k), esc(v));
        }
        let _ = writeln!(h, "<tr><td>time</td><td>{dt:.3} s</td></tr>");
        if !s.files.is_empty() {
            let links: Vec<String> = s
                .files
                .iter()
                .map(|f| format!("<a href=\"{0}\">{0}</a>", esc(f)))
                .collect();
            let _ = writeln!(h, "<tr><td>files</td><td>{}</td></tr>", links.join(" "));
        }
        h.push_str("</table></div></section>\n");
    }
    h.push_str("</body></html>\n");
    h
}

fn points_section(ctx: &Ctx) -> Result<Vec<Section>> {
    let pts = morpho::samples::chalice_outline(240, 0.3, 1);
    let mut s = Section::new(
        "Points on a chalice outline",
        "Scattered points sampled from a closed chalice-like outline with a little noise: the \
         input of the boundary construction (Veltkamp 1992, ch. 5).",
    );
    let ps = morpho::mesh::PointSet::from_points2(&pts);
    morpho::io::write_points(&ctx.path("chalice.csv"), &ps)?;
    s.files.push("chalice.csv".into());
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
