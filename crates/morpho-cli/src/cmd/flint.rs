//! `morpho flint build|approx|contains|intersect`: the 2D flintstone tree of a polygon or polyline
//! (Veltkamp 1992, ch. 6–7; see `morpho::flint`).
//!
//! IN is a polygon or polyline: a CSV in order (`x,y`) or a GeoJSON Polygon/LineString (the
//! first one; a polygon's outer ring). A CSV is a closed polygon unless `--open`.
//! - `build IN -o TREE.json`: the tree — root chord and disc, and per node its split vertex,
//!   kind (`cap`, `intersection`, `union`, `segment`, `unbounded`), the two side discs (centre,
//!   signed radius, width), children and level; report keys `nodes`, `depth`, `kinds`.
//! - `approx IN (--level L | --error E | --count N) [--method flintstone|dp|strip|blg|arc] -o OUT`:
//!   the approximation by input vertices, in input order, as `.csv`/`.geojson`; report keys
//!   `edges`, `e1`…`e5`, `simple` (early levels need not be simple: reported, not hidden).
//! - `contains IN QUERIES -o OUT.csv`: the query rows (`x,y`) plus an `inside` column: 1 inside,
//!   0 outside, 2 on the boundary (exact); report keys `queries`, `inside`, `outside`,
//!   `boundary`, timings.
//!
//! - `intersect A B -o OUT`: every meeting of the two boundaries, one row per meeting edge
//!   pair (`x,y`, `x2,y2` = other end of a collinear overlap, `edge_a`, `edge_b`, `overlap`) as
//!   `.csv`/`.geojson`/`.ply`/`.xyz`; `--first` stops at the first (detection); report keys
//!   `intersects`, `pairs`, `overlaps`, `visited` (piece pairs the descent filtered) against
//!   `brute_pairs` (edge pairs of brute force), timings.
//!
//! Not built yet: the 3D tree.

use crate::report::Report;
use crate::Failure;
use morpho::flint::{baseline, Baseline, Containment, FlintTree2, Target};
use morpho::geom::Point2;
use morpho::io;
use morpho::mesh::{Column, PointSet, Polygon, Polyline, Shapes2};
use serde_json::json;
use std::path::{Path, PathBuf};

/// `morpho flint` and its subcommands.
#[derive(clap::Args)]
pub struct Args {
    /// What to do with the tree.
    #[command(subcommand)]
    pub command: Sub,
}

/// The subcommands of `morpho flint`.
#[derive(clap::Subcommand)]
pub enum Sub {
    /// Build the flintstone tree and write it as JSON.
    Build {
        /// Polygon or polyline (.csv in order, .geojson).
        input: PathBuf,
        /// Output tree (.json).
        #[arg(short, long)]
        output: PathBuf,
        /// Read a CSV as an open polyline (a GeoJSON says what it is).
        #[arg(long)]
        open: bool,
    },
    /// Approximate the polygon by a level, an error bound or an edge count.
    Approx {
        /// Polygon or polyline (.csv in order, .geojson).
        input: PathBuf,
        /// Output polygon/polyline (.csv, .geojson).
        #[arg(short, long)]
        output: PathBuf,
        /// All vertices of tree levels 0..=L.
        #[arg(long, group = "target")]
        level: Option<u32>,
        /// Refine every edge whose error exceeds E.
        #[arg(long, group = "target")]
        error: Option<f64>,
        /// Refine the worst edge first until N edges.
        #[arg(long, group = "target")]
        count: Option<usize>,
        /// The hierarchy: flintstone (V ch. 7) or a baseline of V §6.3.
        #[arg(long, default_value = "flintstone", value_parser = ["flintstone", "dp", "strip", "blg", "arc"])]
        method: String,
        /// Read a CSV as an open polyline.
        #[arg(long)]
        open: bool,
    },
    /// Point-in-polygon for every row of QUERIES (x,y): adds an `inside` column.
    Contains {
        /// Closed polygon (.csv in order, .geojson).
        input: PathBuf,
        /// Query points (.csv or .xyz with x, y).
        queries: PathBuf,
        /// Output (.csv): the queries plus `inside` (1 inside, 0 outside, 2 on the boundary).
        #[arg(short, long)]
        output: PathBuf,
    },
    /// Where the boundaries of A and B meet: one row per meeting edge pair.
    Intersect {
        /// First polygon or polyline (.csv in order, .geojson).
        a: PathBuf,
        /// Second polygon or polyline.
        b: PathBuf,
        /// Output (.csv, .geojson, .ply, .xyz): `x,y` and `x2,y2` (the other end of a collinear
        /// overlap, else the same point), `edge_a`, `edge_b`, `overlap` (1 for an overlap).
        #[arg(short, long)]
        output: PathBuf,
        /// Detection only: stop at the first meeting found.
        #[arg(long)]
        first: bool,
        /// Read CSV inputs as open polylines.
        #[arg(long)]
        open: bool,
    },
}

impl Args {
    /// The files read and written (for the checks before anything runs).
    pub fn paths(&self) -> (Vec<&Path>, &Path) {
        match &self.command {
            Sub::Build { input, output, .. } | Sub::Approx { input, output, .. } => {
                (vec![input.as_path()], output.as_path())
            }
            Sub::Contains {
                input,
                queries,
                output,
            } => (vec![input.as_path(), queries.as_path()], output.as_path()),
            Sub::Intersect { a, b, output, .. } => {
                (vec![a.as_path(), b.as_path()], output.as_path())
            }
        }
    }
}

/// The first polygon (outer ring, closed) or polyline of `path`.
fn read_curve(path: &Path, open: bool) -> Result<(Vec<Point2>, bool), Failure> {
    let s = io::read_shapes2(path)?;
    let (pts, closed) = if let Some(p) = s.polygons.first() {
        (p.rings.first().cloned().unwrap_or_default(), !open)
    } else if let Some(l) = s.polylines.first() {
        (l.points.clone(), l.closed && !open)
    } else {
        return Err(Failure::usage(format!(
            "{}: no polygon or polyline in the file",
            path.display()
        )));
    };
    if s.polygons.len() + s.polylines.len() > 1 {
        eprintln!(
            "note: {}: {} shapes in the file; the first is used",
            path.display(),
            s.polygons.len() + s.polylines.len()
        );
    }
    Ok((pts, closed))
}

fn tree(path: &Path, pts: &[Point2], closed: bool) -> Result<FlintTree2, Failure> {
    FlintTree2::new(pts, closed).map_err(|e| morpho::Error::from(e).with_path(path).into())
}

/// Runs `morpho flint`.
pub fn run(args: Args, report: &mut Report) -> Result<u8, Failure> {
    match args.command {
        Sub::Build {
            input,
            output,
            open,
        } => {
            if crate::cmd::extension(&output) != "json" {
                return Err(Failure::usage(format!(
                    "{}: the tree is written as .json",
                    output.display()
                )));
            }
            let (pts, closed) = report.time("read", || read_curve(&input, open))?;
            let t = report.time("build", || tree(&input, &pts, closed))?;
            let k = t.kind_counts();
            report.set("vertices", pts.len());
            report.set("closed", closed);
            report.set("nodes", t.node_count());
            report.set("depth", t.depth());
            let kinds = json!({"cap": k[0], "intersection": k[1], "union": k[2], "segment": k[3], "unbounded": k[4]});
            report.set("kinds", kinds.clone());
            let side = |d: &Option<morpho::flint::SideDisc>| {
                d.as_ref().map(|d| {
                    json!({"vertex": d.pos, "center": d.center, "radius": d.radius, "width": d.width})
                })
            };
            let nodes: Vec<_> = t
                .nodes
                .iter()
                .map(|n| {
                    json!({
                        "vertex": n.vertex,
                        "kind": n.stone.kind.name(),
                        "chord": [n.stone.lo, n.stone.hi],
                        "left": side(&n.stone.left),
                        "right": side(&n.stone.right),
                        "error": n.stone.error(),
                        "children": n.children.map(|c| (c != morpho::util::NONE).then_some(c)),
                        "level": n.level,
                    })
                })
                .collect();
            let doc = json!({
                "closed": closed,
                "vertices": pts.len(),
                "root": {"chord": t.root.chord, "center": t.root.center, "radius": t.root.radius,
                         "children": t.root.children.map(|c| (c != morpho::util::NONE).then_some(c))},
                "depth": t.depth(),
                "kinds": kinds,
                "nodes": nodes,
            });
            report.time("write", || {
                io::write_atomic(&output, |w| io::json::write_value(w, &doc))
            })?;
            eprintln!(
                "wrote {} ({} nodes, depth {})",
                output.display(),
                t.node_count(),
                t.depth()
            );
            Ok(0)
        }
        Sub::Approx {
            input,
            output,
            level,
            error,
            count,
            method,
            open,
        } => {
            let target = match (level, error, count) {
                (Some(l), None, None) => Target::Level(l),
                (None, Some(e), None) => Target::Error(e),
                (None, None, Some(n)) => Target::Count(n),
                _ => {
                    return Err(Failure::usage(
                        "flint approx needs one of --level L, --error E, --count N",
                    ))
                }
            };
            let ext = crate::cmd::extension(&output);
            if !matches!(ext.as_str(), "csv" | "geojson" | "json") {
                return Err(Failure::usage(format!(
                    "{}: the approximation is written as .csv or .geojson",
                    output.display()
                )));
            }
            let (pts, closed) = report.time("read", || read_curve(&input, open))?;
            let a = report.time("approximate", || -> Result<_, Failure> {
                let r = match method.as_str() {
                    "flintstone" => tree(&input, &pts, closed)?.approximate(target),
                    m => {
                        let b = match m {
                            "dp" => Baseline::DouglasPeucker,
                            "strip" => Baseline::Strip,
                            "blg" => Baseline::Blg,
                            _ => Baseline::Arc,
                        };
                        baseline(&pts, closed, b, target)
                    }
                };
                r.map_err(|e| morpho::Error::from(e).with_path(&input).into())
            })?;
            report.set("method", method.as_str());
            report.set("vertices", pts.len());
            report.set("edges", a.edges());
            for (k, v) in [
                ("e1", a.errors.e1),
                ("e2", a.errors.e2),
                ("e3", a.errors.e3),
                ("e4", a.errors.e4),
                ("e5", a.errors.e5),
            ] {
                report.set(k, json!(v.is_finite().then_some(v)));
            }
            report.set("simple", json!(a.simple));
            report.set("indices", json!(a.vertices));
            let kept: Vec<Point2> = a.vertices.iter().map(|&i| pts[i]).collect();
            let shapes = if a.closed {
                Shapes2 {
                    polygons: vec![Polygon { rings: vec![kept] }],
                    ..Default::default()
                }
            } else {
                Shapes2 {
                    polylines: vec![Polyline {
                        points: kept,
                        closed: false,
                    }],
                    ..Default::default()
                }
            };
            report.time("write", || io::write_shapes2(&output, &shapes))?;
            if a.simple == Some(false) {
                eprintln!("note: the approximation is not simple (coarse levels need not be)");
            }
            eprintln!(
                "wrote {} ({} edges of {}, e5 {:.6})",
                output.display(),
                a.edges(),
                pts.len() - usize::from(!closed),
                a.errors.e5
            );
            Ok(0)
        }
        Sub::Contains {
            input,
            queries,
            output,
        } => {
            if crate::cmd::extension(&output) != "csv" {
                return Err(Failure::usage(format!(
                    "{}: the answers are written as .csv",
                    output.display()
                )));
            }
            let (pts, closed) = report.time("read", || read_curve(&input, false))?;
            if !closed {
                return Err(Failure::usage(format!(
                    "{}: point-in-polygon needs a closed polygon, the file holds an open polyline",
                    input.display()
                )));
            }
            let mut q = report.time("read", || crate::cmd::read_points(&queries, Some(2)))?;
            let t = report.time("build", || tree(&input, &pts, true))?;
            let xs: Vec<Point2> = q
                .coords
                .chunks_exact(2)
                .map(|c| Point2::new(c[0], c[1]))
                .collect();
            let ans = report.time("query", || {
                t.contains_batch(&xs)
                    .map_err(|e| Failure::from(morpho::Error::from(e).with_path(&queries)))
            })?;
            let count = |c: Containment| ans.iter().filter(|&&a| a == c).count();
            report.set("queries", xs.len());
            report.set("inside", count(Containment::Inside));
            report.set("outside", count(Containment::Outside));
            report.set("boundary", count(Containment::Boundary));
            q.columns.push(Column {
                name: "inside".into(),
                values: ans.iter().map(|&a| a as u8 as f64).collect(),
            });
            let q: PointSet = q;
            report.time("write", || io::write_points(&output, &q))?;
            eprintln!(
                "wrote {} ({} queries: {} inside, {} on the boundary)",
                output.display(),
                xs.len(),
                count(Containment::Inside),
                count(Containment::Boundary)
            );
            Ok(0)
        }
        Sub::Intersect {
            a,
            b,
            output,
            first,
            open,
        } => {
            let ext = crate::cmd::extension(&output);
            if !matches!(ext.as_str(), "csv" | "geojson" | "json" | "ply" | "xyz") {
                return Err(Failure::usage(format!(
                    "{}: the meetings are written as .csv, .geojson, .ply or .xyz",
                    output.display()
                )));
            }
            let (pa, ca) = report.time("read", || read_curve(&a, open))?;
            let (pb, cb) = report.time("read", || read_curve(&b, open))?;
            let (ta, tb) = report.time("build", || -> Result<_, Failure> {
                Ok((tree(&a, &pa, ca)?, tree(&b, &pb, cb)?))
            })?;
            let (m, st) = report.time("intersect", || {
                morpho::flint::intersect_counted(&ta, &tb, first)
            });
            let overlaps = m.iter().filter(|c| c.overlap.is_some()).count();
            report.set("intersects", !m.is_empty());
            report.set("pairs", m.len());
            report.set("overlaps", overlaps);
            report.set("edges_a", ta.len() - usize::from(!ca));
            report.set("edges_b", tb.len() - usize::from(!cb));
            report.set("visited", st.pairs_visited);
            report.set("passed", st.pairs_passed);
            report.set("leaf_tests", st.leaf_tests);
            report.set("brute_pairs", st.brute_pairs);
            report.set("first_only", first);
            let mut coords = Vec::with_capacity(2 * m.len());
            let col = |name: &str, f: &dyn Fn(&morpho::flint::Crossing) -> f64| Column {
                name: name.into(),
                values: m.iter().map(f).collect(),
            };
            let columns = vec![
                col("x2", &|c| c.overlap.unwrap_or(c.point)[0]),
                col("y2", &|c| c.overlap.unwrap_or(c.point)[1]),
                col("edge_a", &|c| c.a as f64),
                col("edge_b", &|c| c.b as f64),
                col("overlap", &|c| f64::from(u8::from(c.overlap.is_some()))),
            ];
            for c in &m {
                coords.extend_from_slice(&c.point);
            }
            let out = PointSet {
                dim: 2,
                coords,
                columns,
            };
            report.time("write", || io::write_points(&output, &out))?;
            eprintln!(
                "wrote {} ({} meeting edge pairs, {} overlaps; {} pairs visited, brute force {})",
                output.display(),
                m.len(),
                overlaps,
                st.pairs_visited,
                st.brute_pairs
            );
            Ok(0)
        }
    }
}
