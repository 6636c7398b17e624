//! HTML: the gallery page of `morpho demo` — one section per pipeline step, each with its
//! pictures, a table of its figures and links to its result files.
//!
//! Text is HTML-escaped (`& < > "`). The page is self-contained (inline style, images by
//! relative file name). Linear in the size of the sections.

use std::fmt::Write as _;
use std::path::Path;

/// One step of a pipeline as shown in the gallery.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Section {
    /// Heading.
    pub title: String,
    /// Paragraph under the heading.
    pub text: String,
    /// Pictures: (file name relative to the gallery, caption).
    pub images: Vec<(String, String)>,
    /// Figures: (name, value).
    pub figures: Vec<(String, String)>,
    /// Result files written (relative names).
    pub files: Vec<String>,
}

impl Section {
    /// A section without pictures, figures or files.
    pub fn new(title: &str, text: &str) -> Self {
        Section {
            title: title.into(),
            text: text.into(),
            ..Default::default()
        }
    }
    /// Adds a figure.
    pub fn fig(&mut self, name: &str, value: impl std::fmt::Display) {
        self.figures.push((name.into(), value.to_string()));
    }
    /// Adds a picture.
    pub fn img(&mut self, file: &str, caption: &str) {
        self.images.push((file.into(), caption.into()));
    }
}

/// A section of the gallery with the time it took, or the error that stopped it.
#[derive(Debug, Clone, PartialEq)]
pub struct Entry {
    /// The section (only its title is shown when it failed).
    pub section: Section,
    /// Seconds spent on it.
    pub seconds: f64,
    /// Why it failed, if it did.
    pub error: Option<String>,
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The gallery page; `data` is the folder of the real data used, if any.
///
/// ```
/// use morpho::io::html::{gallery_html, Entry, Section};
/// let mut s = Section::new("Points", "Some points.");
/// s.fig("points", 3);
/// let page = gallery_html(&[Entry { section: s, seconds: 0.5, error: None }], None);
/// assert!(page.contains("<tr><td>points</td><td>3</td></tr>"));
/// ```
pub fn gallery_html(entries: &[Entry], data: Option<&Path>) -> String {
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
        crate::VERSION
    );
    for e in entries {
        section_html(&mut h, e);
    }
    h.push_str("</body></html>\n");
    h
}

/// One `<section>` of the gallery.
fn section_html(h: &mut String, e: &Entry) {
    let s = &e.section;
    let _ = writeln!(h, "<section><h2>{}</h2>", esc(&s.title));
    if let Some(err) = &e.error {
        let _ = writeln!(h, "<p class=\"fail\">failed: {}</p></section>", esc(err));
        return;
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
    let _ = writeln!(h, "<tr><td>time</td><td>{:.3} s</td></tr>", e.seconds);
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

/// Writes the gallery page atomically.
pub fn write_gallery(path: &Path, entries: &[Entry], data: Option<&Path>) -> crate::Result<()> {
    super::write_text(path, &gallery_html(entries, data))
}
