//! `morpho info FILE`: what a file holds — counts, bounding box, and topology for meshes
//! (parts, boundary loops, Euler characteristic, genus, manifold, orientable).

use crate::report::Report;
use crate::Failure;
use morpho::io::{read_any, Data};
use morpho::mesh::analyze_topology;
use serde_json::json;
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// Any file morpho reads (points, polygons, mesh, volume).
    pub input: PathBuf,
    /// Validity checks by exact predicates: polygons are simple (no two non-adjacent edges
    /// meet); meshes are closed 2-manifolds without self-intersections (genus reported).
    /// Exit code 1 when a check fails.
    #[arg(long)]
    pub check: bool,
}

pub fn run(args: Args, report: &mut Report) -> Result<u8, Failure> {
    let data = report.time("read", || read_any(&args.input))?;
    report.set("file", args.input.display().to_string());
    let t = std::time::Instant::now();
    let lines = describe(&data, report);
    report.add_time("compute", t.elapsed().as_secs_f64());
    for l in lines {
        println!("{l}");
    }
    if args.check {
        let t = std::time::Instant::now();
        let (valid, lines) = check(&data, report);
        report.add_time("compute", t.elapsed().as_secs_f64());
        for l in lines {
            println!("{l}");
        }
        report.set("valid", valid);
        return Ok(if valid { 0 } else { 1 });
    }
    Ok(0)
}

/// The `--check` validity tests; returns whether everything passed and the lines to print.
fn check(data: &Data, report: &mut Report) -> (bool, Vec<String>) {
    use morpho::mesh::validity;
    let mut out = Vec::new();
    let mut valid = true;
    match data {
        Data::Shapes(s) => {
            let mut bad = Vec::new();
            for (pi, poly) in s.polygons.iter().enumerate() {
                for (ri, ring) in poly.rings.iter().enumerate() {
                    let cycle: Vec<u32> = (0..ring.len() as u32).collect();
                    let c = validity::check_polygon(ring, &cycle);
                    if !c.simple {
                        valid = false;
                        let what = match c.conflict {
                            Some((a, b)) if ring[a] == ring[b] => {
                                format!("vertices {a} and {b} coincide")
                            }
                            Some((a, b)) => format!("edges {a} and {b} meet"),
                            None => "fewer than 3 distinct vertices".into(),
                        };
                        out.push(format!(
                            "check: polygon {pi} ring {ri} is not simple: {what}"
                        ));
                        bad.push(json!({"polygon": pi, "ring": ri, "conflict": c.conflict}));
                    }
                }
            }
            if valid {
                out.push("check: every ring is a simple polygon".into());
            }
            report.set("not_simple", bad);
        }
        Data::Mesh(m) => {
            let t = analyze_topology(m);
            let closed = t.manifold && t.boundary_loops.is_empty() && !m.triangles.is_empty();
            let pos: Vec<[f64; 3]> = m.positions.iter().map(|p| [p.x, p.y, p.z]).collect();
            let hits = validity::self_intersections(&pos, &m.triangles, 10);
            valid = closed && hits.is_empty();
            out.push(format!("check: closed 2-manifold: {}", yes(closed)));
            out.push(format!(
                "check: self-intersections: {}",
                if hits.is_empty() {
                    "none".to_string()
                } else {
                    format!(
                        "{} or more, e.g. triangles {} and {}",
                        hits.len(),
                        hits[0].0,
                        hits[0].1
                    )
                }
            ));
            report.set("closed_manifold", closed);
            report.set("self_intersections", json!(hits));
        }
        _ => {
            out.push("check: nothing to check for points and volumes".into());
        }
    }
    (valid, out)
}

fn fmt_bbox(min: &[f64], max: &[f64]) -> String {
    let f = |v: &[f64]| {
        v.iter()
            .map(|x| format!("{x:.6}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    format!("[{}] .. [{}]", f(min), f(max))
}

/// Fills the report and returns the human-readable lines.
fn describe(data: &Data, report: &mut Report) -> Vec<String> {
    let mut out = Vec::new();
    match data {
        Data::Points(p) => {
            report.set("kind", "points");
            report.set("points", p.len());
            report.set("dim", p.dim);
            let mut min = vec![f64::INFINITY; p.dim];
            let mut max = vec![f64::NEG_INFINITY; p.dim];
            for i in 0..p.len() {
                for (k, &c) in p.point(i).iter().enumerate() {
                    min[k] = min[k].min(c);
                    max[k] = max[k].max(c);
                }
            }
            report.set("bbox", json!([min, max]));
            out.push(format!("kind: points ({}D)", p.dim));
            out.push(format!("points: {}", p.len()));
            out.push(format!("bbox: {}", fmt_bbox(&min, &max)));
            if !p.columns.is_empty() {
                let names: Vec<&str> = p.columns.iter().map(|c| c.name.as_str()).collect();
                out.push(format!("columns: {}", names.join(", ")));
                report.set("columns", names);
            }
        }
        Data::Shapes(s) => {
            report.set("kind", "polygons");
            let rings: usize = s.polygons.iter().map(|p| p.rings.len()).sum();
            let verts: usize = s
                .polygons
                .iter()
                .flat_map(|p| &p.rings)
                .map(Vec::len)
                .sum::<usize>()
                + s.polylines.iter().map(|l| l.points.len()).sum::<usize>();
            report.set("polygons", s.polygons.len());
            report.set("rings", rings);
            report.set("polylines", s.polylines.len());
            report.set("vertices", verts);
            let mut b = morpho::geom::Aabb2::empty();
            for p in s
                .polygons
                .iter()
                .flat_map(|p| &p.rings)
                .flatten()
                .chain(s.polylines.iter().flat_map(|l| &l.points))
            {
                b.add(p.coords.as_slice());
            }
            report.set("bbox", json!([b.min, b.max]));
            out.push("kind: polygons".into());
            out.push(format!("polygons: {} ({} rings)", s.polygons.len(), rings));
            out.push(format!("polylines: {}", s.polylines.len()));
            out.push(format!("vertices: {verts}"));
            out.push(format!("bbox: {}", fmt_bbox(&b.min, &b.max)));
        }
        Data::Mesh(m) => {
            let t = analyze_topology(m);
            let b = m.bbox();
            report.set("kind", "mesh");
            report.set("vertices", m.num_vertices());
            report.set("used_vertices", t.num_used_vertices);
            report.set("triangles", m.num_triangles());
            report.set("edges", t.num_edges);
            report.set("parts", t.parts.len());
            report.set("boundary_loops", t.boundary_loops.len());
            report.set("euler_characteristic", t.euler_characteristic);
            report.set("genus", json!(t.genus()));
            report.set("manifold", t.manifold);
            report.set("orientable", t.orientable);
            report.set("consistently_oriented", t.consistently_oriented);
            report.set("non_manifold_edges", t.non_manifold_edges.len());
            report.set("non_manifold_vertices", t.non_manifold_vertices.len());
            report.set("bbox", json!([b.min, b.max]));
            report.set("area", m.area());
            report.set("signed_volume", m.signed_volume());
            out.push("kind: triangle mesh".into());
            out.push(format!(
                "vertices: {} ({} used)",
                m.num_vertices(),
                t.num_used_vertices
            ));
            out.push(format!("triangles: {}", m.num_triangles()));
            out.push(format!("edges: {}", t.num_edges));
            out.push(format!("bbox: {}", fmt_bbox(&b.min, &b.max)));
            out.push(format!("parts: {}", t.parts.len()));
            out.push(format!("boundary loops: {}", t.boundary_loops.len()));
            out.push(format!("euler characteristic: {}", t.euler_characteristic));
            out.push(match t.genus() {
                Some(g) => format!("genus: {g}"),
                None => "genus: undefined (not an orientable manifold)".into(),
            });
            out.push(format!(
                "manifold: {}{}",
                yes(t.manifold),
                if t.manifold {
                    String::new()
                } else {
                    format!(
                        " ({} non-manifold edges, {} non-manifold vertices)",
                        t.non_manifold_edges.len(),
                        t.non_manifold_vertices.len()
                    )
                }
            ));
            out.push(format!("orientable: {}", yes(t.orientable)));
            out.push(format!(
                "consistently oriented: {}",
                yes(t.consistently_oriented)
            ));
            out.push(format!("area: {:.6}", m.area()));
            out.push(format!("signed volume: {:.6}", m.signed_volume()));
            if m.normals.is_some() {
                out.push("vertex normals: yes".into());
            }
            for p in &m.vertex_props {
                out.push(format!("vertex property: {}", p.name));
            }
            for p in &m.face_props {
                out.push(format!("face property: {}", p.name));
            }
        }
        Data::Volume(v) => {
            report.set("kind", "volume");
            report.set("dims", json!(v.dims));
            report.set("spacing", json!(v.spacing()));
            report.set("dtype", json!(v.source_dtype));
            let (lo, hi) = v
                .value_range()
                .map(|(a, b)| (a as f64, b as f64))
                .unwrap_or((f64::NAN, f64::NAN));
            report.set("min", json!(lo.is_finite().then_some(lo)));
            report.set("max", json!(hi.is_finite().then_some(hi)));
            let nonfinite = v.data.iter().filter(|x| !x.is_finite()).count();
            report.set("nonfinite_samples", nonfinite);
            // the world-space box of the grid's 8 corners (through the axis directions)
            let lo3: [f64; 3] = std::array::from_fn(|k| v.coord(k, 0));
            let hi3: [f64; 3] = std::array::from_fn(|k| v.coord(k, v.dims[k].saturating_sub(1)));
            let (mut bmin, mut bmax) = (vec![f64::INFINITY; 3], vec![f64::NEG_INFINITY; 3]);
            for c in 0..8 {
                let corner = std::array::from_fn(|k| if c >> k & 1 == 0 { lo3[k] } else { hi3[k] });
                let w = v.orientation.to_world(lo3, corner);
                for k in 0..3 {
                    bmin[k] = bmin[k].min(w[k]);
                    bmax[k] = bmax[k].max(w[k]);
                }
            }
            report.set("bbox", json!([bmin, bmax]));
            report.set("space", json!(v.orientation.space));
            report.set("directions", json!(v.orientation.directions));
            out.push("kind: volume".into());
            out.push(format!(
                "dims: {} x {} x {}",
                v.dims[0], v.dims[1], v.dims[2]
            ));
            out.push(format!(
                "samples: {} ({:?} in the file)",
                v.len(),
                v.source_dtype
            ));
            let s = v.spacing();
            out.push(format!("spacing: {} x {} x {}", s[0], s[1], s[2]));
            if let Some(space) = &v.orientation.space {
                out.push(format!("space: {space}"));
            }
            if let Some(d) = v.orientation.directions {
                out.push(format!("axis directions: {d:?}"));
            }
            out.push(format!("bbox: {}", fmt_bbox(&bmin, &bmax)));
            out.push(format!("value range: {lo} .. {hi}"));
            if nonfinite > 0 {
                out.push(format!("non-finite samples: {nonfinite}"));
            }
        }
    }
    out
}

fn yes(b: bool) -> &'static str {
    if b {
        "yes"
    } else {
        "no"
    }
}
