//! The interactive browser viewer (issue 22, part 2): one self-contained HTML page (WebGL 2,
//! a small hand-written renderer in `viewer.js`, shaders `mesh.vert`/`mesh.frag`, all included
//! with `include_str!`) that loads from `file://` and works offline.
//!
//! Data are embedded compactly as base64 blobs: positions quantized to 16 bits per axis over
//! each layer's bounding box (error ≤ extent/131070), indices as plain little-endian `u32`,
//! vertex properties as `f32` (exact enough for picking). Per triangle that is ≈ 16 + 8·V/T
//! bytes of base64 against 13 + 12·V/T bytes of a binary PLY (float32 positions, int32
//! indices): for a closed surface (V ≈ T/2) the page is ≈ 1.05× the PLY.
//!
//! Layers: meshes (shaded, per-vertex colour maps from PLY properties such as `H`, `K`),
//! point sets (first columns as properties), 2D shapes (polygons and polylines as lines at
//! z = 0), volumes ([`Layer::volume`], [`VolumeLayer`]: three movable orthogonal slices with a
//! colour map of the sample values, drawn by `slices.js` with `slice.vert`/`slice.frag`; the
//! CLI adds the volume's contour surface as a mesh layer, hidden until ticked).
//! A mesh with more than [`Page::lod`] triangles also carries an interaction proxy of about that
//! many triangles ([`cluster_proxy`], vertex clustering, computed here at page-generation time,
//! indices as `u16` when they fit): the page draws the proxy, at half resolution, while the
//! camera moves, and the full mesh, progressively in chunks, when it rests.
//! The page has a test hook: `page.html#selftest=orbit,pick:123,bench:60` runs those steps
//! and writes a JSON result into `<pre id="morpho-selftest">` (see the browser tests); the
//! steps `fps:SECONDS` (a scripted orbit timed by `requestAnimationFrame`, drawing what an
//! interaction draws), `fpsfull:SECONDS` (the same with the full mesh) and `full` (wait for the
//! full-detail frame) are asynchronous: `window.morphoSelftest` is then a promise of the result
//! (`bench/viewer_fps.py` drives them over the DevTools protocol).
//!
//! ```
//! use morpho::viewer::{page_html, Layer, Page};
//! use morpho::mesh::TriMesh;
//! let m = TriMesh::new(
//!     vec![[0.0, 0.0, 0.0].into(), [1.0, 0.0, 0.0].into(), [0.0, 1.0, 0.0].into()],
//!     vec![[0, 1, 2]],
//! );
//! let page = Page {
//!     title: "t".into(),
//!     layers: vec![Layer::mesh("tri", &m)],
//!     figures: None,
//!     lod: morpho::viewer::DEFAULT_LOD,
//! };
//! let html = page_html(&page);
//! assert!(html.starts_with("<!DOCTYPE html>") && html.contains("morpho-selftest"));
//! ```

use crate::mesh::{PointSet, Shapes2, TriMesh};
use serde_json::{json, Value};

mod lod;
mod volume;
pub use lod::{cluster_proxy, Proxy};
pub use volume::{
    quantize_samples, Quantized, VolumeLayer, DEFAULT_MAX_SAMPLES, MAX_AXIS, NAN_CODE,
};

/// The default size of a mesh's interaction proxy (triangles). Measured with SwiftShader on two
/// cores at load average ≈ 8 (`bench/viewer_fps.py`, 1024×768, the proxy drawn at half
/// resolution while moving): 10 000 triangles orbit at 60 frames/s, 20 000 at 33, 60 000 at 17.
pub const DEFAULT_LOD: usize = 10_000;

/// One thing drawn in the page.
#[derive(Debug, Clone)]
pub struct Layer {
    /// Name shown in the panel.
    pub name: String,
    /// `mesh`, `points`, `lines` or `volume`.
    kind: &'static str,
    positions: Vec<[f64; 3]>,
    indices: Vec<u32>,
    props: Vec<(String, Vec<f64>)>,
    /// The samples of a `volume` layer.
    volume: Option<Box<VolumeLayer>>,
    /// Sentences shown under the layer's name in the panel.
    pub notes: Vec<String>,
    /// Drawn only once ticked in the panel.
    pub hidden: bool,
}

impl Layer {
    /// A triangle mesh with its vertex properties.
    pub fn mesh(name: &str, m: &TriMesh) -> Layer {
        Layer {
            name: name.into(),
            kind: "mesh",
            positions: m.positions.iter().map(|p| [p.x, p.y, p.z]).collect(),
            indices: m.triangles.iter().flatten().copied().collect(),
            props: m
                .vertex_props
                .iter()
                .map(|p| (p.name.clone(), p.values.clone()))
                .collect(),
            volume: None,
            notes: Vec::new(),
            hidden: false,
        }
    }
    /// A volume, drawn as three movable orthogonal slices (see [`VolumeLayer`]); its notes
    /// become the layer's.
    pub fn volume(name: &str, v: VolumeLayer) -> Layer {
        let mut positions = Vec::with_capacity(8);
        for k in 0..8 {
            let p: [f64; 3] = std::array::from_fn(|a| {
                let c = &v.coords[a];
                if k >> a & 1 == 1 {
                    c[c.len() - 1]
                } else {
                    c[0]
                }
            });
            positions.push(v.to_world(p));
        }
        Layer {
            name: name.into(),
            kind: "volume",
            positions,
            indices: Vec::new(),
            props: Vec::new(),
            notes: v.notes.clone(),
            volume: Some(Box::new(v)),
            hidden: false,
        }
    }
    /// A 2D or 3D point set with its columns.
    pub fn points(name: &str, p: &PointSet) -> Layer {
        let d = p.dim.max(1);
        let positions = p
            .coords
            .chunks(d)
            .map(|c| {
                [
                    c[0],
                    *c.get(1).unwrap_or(&0.0),
                    if d > 2 { c[2] } else { 0.0 },
                ]
            })
            .collect();
        Layer {
            name: name.into(),
            kind: "points",
            positions,
            indices: Vec::new(),
            props: p
                .columns
                .iter()
                .map(|c| (c.name.clone(), c.values.clone()))
                .collect(),
            volume: None,
            notes: Vec::new(),
            hidden: false,
        }
    }
    /// 2D polygons and polylines, as line segments at z = 0.
    pub fn shapes(name: &str, s: &Shapes2) -> Layer {
        let mut positions = Vec::new();
        let mut indices = Vec::new();
        let mut ring = |pts: &[crate::geom::Point2], closed: bool| {
            let b = positions.len() as u32;
            positions.extend(pts.iter().map(|p| [p.x, p.y, 0.0]));
            let n = pts.len() as u32;
            for i in 0..n.saturating_sub(1) {
                indices.extend([b + i, b + i + 1]);
            }
            if closed && n > 2 {
                indices.extend([b + n - 1, b]);
            }
        };
        for p in &s.polygons {
            for r in &p.rings {
                ring(r, true);
            }
        }
        for l in &s.polylines {
            ring(&l.points, l.closed);
        }
        Layer {
            name: name.into(),
            kind: "lines",
            positions,
            indices,
            props: Vec::new(),
            volume: None,
            notes: Vec::new(),
            hidden: false,
        }
    }
    /// True when the layer has nothing to draw.
    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }
}

/// A page: title, layers, and an optional figure panel (a `--report` JSON of an earlier run).
#[derive(Debug, Clone)]
pub struct Page {
    /// The page's title.
    pub title: String,
    /// What is drawn.
    pub layers: Vec<Layer>,
    /// Figures shown in the side panel (flattened key/value pairs of this JSON).
    pub figures: Option<Value>,
    /// Meshes with more triangles than this get an interaction proxy of about this many
    /// triangles (0: never). See [`DEFAULT_LOD`].
    pub lod: usize,
}

const B64: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

/// Standard base64 with padding.
fn base64(bytes: &[u8]) -> String {
    let mut s = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for c in bytes.chunks(3) {
        let n = (c[0] as u32) << 16
            | (*c.get(1).unwrap_or(&0) as u32) << 8
            | *c.get(2).unwrap_or(&0) as u32;
        for k in 0..4 {
            if k <= c.len() {
                s.push(B64[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

/// Flattens a JSON report into rows of (key, value).
fn figure_rows(v: &Value, prefix: &str, out: &mut Vec<(String, String)>) {
    match v {
        Value::Object(m) => {
            for (k, x) in m {
                let key = if prefix.is_empty() {
                    k.clone()
                } else {
                    format!("{prefix}.{k}")
                };
                figure_rows(x, &key, out);
            }
        }
        other => out.push((prefix.to_string(), other.to_string())),
    }
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Positions quantized to 16 bits per axis over the box `lo`..`lo+ext`, little-endian.
fn quantize(positions: &[[f64; 3]], lo: &[f64; 3], ext: &[f64]) -> Vec<u8> {
    let mut q = Vec::with_capacity(6 * positions.len());
    for p in positions {
        for k in 0..3 {
            let t = ((p[k] - lo[k]) / ext[k] * 65535.0).round();
            // NaN coordinates go to the box's corner (as casts do, but said out loud)
            let t = if t.is_finite() {
                t.clamp(0.0, 65535.0) as u16
            } else {
                0
            };
            q.extend(t.to_le_bytes());
        }
    }
    q
}

/// Vertex values as `f32` bytes, non-finite values as the sentinel −1e30 (drawn grey).
fn prop_bytes(v: &[f64]) -> Vec<u8> {
    v.iter()
        .flat_map(|&x| (if x.is_finite() { x as f32 } else { -1e30 }).to_le_bytes())
        .collect()
}

/// The layer's descriptor, its blobs appended to `blobs`.
fn encode(l: &Layer, lod: usize, blobs: &mut Vec<String>) -> Value {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in &l.positions {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let ext: Vec<f64> = (0..3)
        .map(|k| if hi[k] > lo[k] { hi[k] - lo[k] } else { 1.0 })
        .collect();
    for k in 0..3 {
        if !lo[k].is_finite() {
            lo[k] = 0.0;
        }
    }
    let mut push = |b: &[u8]| {
        blobs.push(base64(b));
        blobs.len() - 1
    };
    let pos = push(&quantize(&l.positions, &lo, &ext));
    let mut d = json!({"kind": l.kind, "name": l.name, "min": lo, "ext": ext, "pos": pos,
        "notes": l.notes, "hidden": l.hidden});
    if let Some(v) = &l.volume {
        let q = &v.quantized;
        d["volume"] = json!({"dims": v.dims, "coords": v.coords, "directions": v.directions,
            "pivot": v.pivot, "bits": q.bits, "lo": q.lo, "step": q.step,
            "range": [v.range.0, v.range.1], "stride": v.stride, "data": push(&q.bytes)});
    }
    if !l.indices.is_empty() {
        let b: Vec<u8> = l.indices.iter().flat_map(|i| i.to_le_bytes()).collect();
        d["idx"] = json!(push(&b));
    }
    let mut props = Vec::new();
    for (name, v) in &l.props {
        let fin = v.iter().copied().filter(|x| x.is_finite());
        let (mn, mx) = fin.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x), b.max(x))
        });
        let (mn, mx) = if mn <= mx { (mn, mx) } else { (0.0, 1.0) };
        props.push(json!({"name": name, "min": mn, "max": mx, "blob": push(&prop_bytes(v))}));
    }
    d["props"] = json!(props);
    if l.kind == "mesh" {
        let pv: Vec<&[f64]> = l.props.iter().map(|(_, v)| v.as_slice()).collect();
        if let Some(p) = cluster_proxy(&l.positions, &l.indices, &pv, lod) {
            let pos = push(&quantize(&p.positions, &lo, &ext));
            let wide = p.positions.len() > 65536;
            let idx: Vec<u8> = if wide {
                p.indices.iter().flat_map(|i| i.to_le_bytes()).collect()
            } else {
                p.indices
                    .iter()
                    .flat_map(|&i| (i as u16).to_le_bytes())
                    .collect()
            };
            let idx = push(&idx);
            let props: Vec<usize> = p.props.iter().map(|v| push(&prop_bytes(v))).collect();
            d["lod"] = json!({"pos": pos, "idx": idx, "wide": wide, "props": props,
                "triangles": p.indices.len() / 3});
        }
    }
    d
}

/// The self-contained HTML page.
pub fn page_html(page: &Page) -> String {
    let mut blobs = Vec::new();
    let layers: Vec<Value> = page
        .layers
        .iter()
        .map(|l| encode(l, page.lod, &mut blobs))
        .collect();
    let flat = page
        .layers
        .iter()
        .all(|l| l.positions.iter().all(|p| p[2] == 0.0));
    let cmaps: serde_json::Map<String, Value> = [
        crate::render::Colormap::Viridis,
        crate::render::Colormap::Greys,
        crate::render::Colormap::Coolwarm,
    ]
    .iter()
    .map(|m| {
        let lut: Vec<u8> = (0..256).flat_map(|i| m.color(i as f64 / 255.0)).collect();
        (m.name().to_string(), json!(lut))
    })
    .collect();
    let scene = json!({"layers": layers, "flat": flat, "cmaps": cmaps})
        .to_string()
        .replace("</", "<\\/");
    let shaders = json!({"vert": include_str!("mesh.vert"), "frag": include_str!("mesh.frag"),
        "svert": include_str!("slice.vert"), "sfrag": include_str!("slice.frag")});
    let mut rows = Vec::new();
    if let Some(f) = &page.figures {
        figure_rows(f, "", &mut rows);
    }
    let table: String = rows
        .iter()
        .map(|(k, v)| format!("<tr><td>{}</td><td>{}</td></tr>", esc(k), esc(v)))
        .collect();
    let mut h = String::with_capacity(blobs.iter().map(|b| b.len() + 64).sum::<usize>() + 40_000);
    h.push_str("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>");
    h.push_str(&esc(&page.title));
    h.push_str("</title><style>html,body{margin:0;height:100%;overflow:hidden;font:13px system-ui,sans-serif}\
#c{display:block;width:100vw;height:100vh}#panel{position:absolute;top:8px;right:8px;width:260px;max-height:95vh;overflow:auto;\
background:rgba(255,255,255,.85);padding:8px;border:1px solid #ccc}#legend{margin-top:8px}td{padding:1px 6px}\
#morpho-selftest{display:none}</style></head><body><canvas id=\"c\"></canvas><div id=\"panel\"><b>");
    h.push_str(&esc(&page.title));
    h.push_str("</b><div id=\"layers\"></div><div id=\"legend\"></div><div id=\"pick\">click a surface to pick a vertex</div>\
<div style=\"color:#666\">drag: orbit · shift-drag: pan · wheel: zoom</div><table>");
    h.push_str(&table);
    h.push_str("</table></div><pre id=\"morpho-selftest\"></pre>\n<script type=\"application/json\" id=\"morpho-scene\">");
    h.push_str(&scene);
    h.push_str("</script>\n");
    for (i, b) in blobs.iter().enumerate() {
        h.push_str(&format!(
            "<script type=\"application/octet-stream\" id=\"b{i}\">"
        ));
        h.push_str(b);
        h.push_str("</script>\n");
    }
    h.push_str("<script>const SHADERS = ");
    h.push_str(&shaders.to_string().replace("</", "<\\/"));
    h.push_str(";\n");
    h.push_str(include_str!("slices.js"));
    h.push_str(include_str!("viewer.js"));
    h.push_str("</script></body></html>\n");
    h
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn base64_matches_rfc4648_vectors() {
        assert_eq!(base64(b""), "");
        assert_eq!(base64(b"f"), "Zg==");
        assert_eq!(base64(b"fo"), "Zm8=");
        assert_eq!(base64(b"foo"), "Zm9v");
        assert_eq!(base64(b"foobar"), "Zm9vYmFy");
    }
}
