//! `morpho graph POINTS --kind KIND [params] -o OUT`: geometric graphs and the γ-neighbourhood
//! graph (Veltkamp 1992, ch. 2–3; issue 4). Indices in the output refer to the input order.
//!
//! Outputs: `.json` (`{"kind", "dim", "points", "edges"}`; 3D hull, Delaunay, α and γ give
//! `"triangles"`; γ kinds add `"gamma": [[c0′, c1′]…]` aligned with the simplices), `.svg` (2D),
//! `.ply` (edges as a PLY `edge` element, triangles as faces).

use crate::report::Report;
use crate::Failure;
use morpho::graphs::{graph_2d, graph_3d, Kind};
use morpho::io::{self, Format};
use morpho::render;
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// Points (CSV with header, XYZ, PLY, JSON array).
    pub input: PathBuf,
    /// Read the points as 2D (x, y of 3D rows, e.g. `x y 1`) or require 3D points.
    #[arg(long, value_name = "2|3")]
    pub dims: Option<u8>,
    /// closest-pairs, nng, emst, strip, sig, rng, gabriel, hull, delaunay, alpha, beta-circle,
    /// beta-lune, gamma, gamma-range.
    #[arg(long)]
    pub kind: String,
    /// α-shape parameter a (radius 1/a; a < 0: empty discs; a = 0: hull).
    #[arg(long, allow_hyphen_values = true)]
    pub a: Option<f64>,
    /// β-skeleton parameter b ∈ [−1, 1].
    #[arg(long, allow_hyphen_values = true)]
    pub b: Option<f64>,
    /// γ(c0, c1): first parameter.
    #[arg(long, allow_hyphen_values = true)]
    pub c0: Option<f64>,
    /// γ(c0, c1): second parameter (|c0| ≤ |c1|).
    #[arg(long, allow_hyphen_values = true)]
    pub c1: Option<f64>,
    /// γ([c0,c1],[c2,c3]) as "c0,c1,c2,c3".
    #[arg(long, allow_hyphen_values = true)]
    pub range: Option<String>,
    /// Output file (.json, .svg, .ply).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Most candidate triples a 3D γ-graph with a parameter < 0 may test, and most points its
    /// search may add to their intervals (Θ(N³) triples on surface samples, Θ(N⁴) points on
    /// points of a sphere; default: MORPHO_TRIPLE_LIMIT, else 1e8, about 20–30 s of one core).
    #[arg(long, value_name = "N")]
    pub max_triples: Option<String>,
}

fn need(v: Option<f64>, name: &str, kind: &str) -> Result<f64, Failure> {
    v.ok_or_else(|| Failure::usage(format!("--kind {kind} needs --{name}")))
}

/// The graph kind from the command-line words.
pub fn parse_kind(a: &Args) -> Result<Kind, Failure> {
    let k = a.kind.as_str();
    Ok(match k {
        "closest-pairs" | "cp" => Kind::ClosestPairs,
        "nng" => Kind::Nng,
        "emst" => Kind::Emst,
        "strip" => Kind::Strip,
        "sig" => Kind::Sig,
        "rng" => Kind::Rng,
        "gabriel" | "gg" => Kind::Gabriel,
        "hull" => Kind::Hull,
        "delaunay" | "dt" => Kind::Delaunay,
        "alpha" => Kind::Alpha(need(a.a, "a", k)?),
        "beta-circle" => Kind::BetaCircle(need(a.b, "b", k)?),
        "beta-lune" => Kind::BetaLune(need(a.b, "b", k)?),
        "gamma" => Kind::Gamma(need(a.c0, "c0", k)?, need(a.c1, "c1", k)?),
        "gamma-range" => {
            let r = a
                .range
                .as_deref()
                .ok_or_else(|| Failure::usage("--kind gamma-range needs --range c0,c1,c2,c3"))?;
            let v: Vec<f64> = r
                .split(',')
                .map(|x| x.trim().parse::<f64>())
                .collect::<Result<_, _>>()
                .map_err(|_| {
                    Failure::usage(format!("--range '{r}': expected four numbers c0,c1,c2,c3"))
                })?;
            if v.len() != 4 {
                return Err(Failure::usage(format!(
                    "--range '{r}': expected four numbers c0,c1,c2,c3"
                )));
            }
            Kind::GammaRange([v[0], v[1], v[2], v[3]])
        }
        other => {
            return Err(Failure::usage(format!(
                "unknown --kind '{other}' (see 'morpho graph --help')"
            )))
        }
    })
}

pub fn run(args: Args, report: &mut Report) -> Result<u8, Failure> {
    let kind = parse_kind(&args)?;
    kind.validate().map_err(|e| Failure::usage(e.to_string()))?;
    if let Some(m) = &args.max_triples {
        let n = morpho::graphs::parse_count(m).ok_or_else(|| {
            Failure::usage(format!(
                "--max-triples must be a positive count such as 1e9, not '{m}'"
            ))
        })?;
        morpho::graphs::set_triple_limit(n);
    }
    let fmt = Format::of(&args.output)?;
    let pts = report.time("read", || super::read_points(&args.input, args.dims))?;
    report.set("kind", kind.name());
    report.set("dim", pts.dim);
    report.set("points", pts.len());
    let g = if pts.dim == 2 {
        let p = pts.to_points2();
        report.time("compute", || graph_2d(&p, kind))
    } else {
        let p = pts.to_points3();
        report.time("compute", || graph_3d(&p, kind))
    }
    .map_err(|e| morpho::Error::from(e).with_path(&args.input))?;
    report.set("edges", g.edges.len());
    report.set("triangles", g.triangles.len());
    let out = &args.output;
    report.time("write", || match fmt {
        Format::Json | Format::Ply => io::write_graph(out, kind, &pts, &g),
        Format::Svg if pts.dim == 2 => {
            io::write_text(out, &render::graph_svg(&pts.to_points2(), &g, None))
        }
        Format::Svg => Err(morpho::Error::unsupported(
            "SVG pictures are for 2D graphs; write .ply or .json",
        )
        .with_path(out)),
        _ => Err(morpho::Error::unsupported("graph writes .json, .svg or .ply").with_path(out)),
    })?;
    Ok(0)
}
