//! `morpho flint build|approx|contains` on a closed triangle mesh (.ply/.obj/.off/.stl, also
//! gzipped): the 3D flintstone tree (Veltkamp 1992, §7.3, Alg. 7.2; see `morpho::flint`).
//!
//! - `build MESH -o TREE.json`: root (ball, level-0 triangle, children) and per node its
//!   corners, kind, the two side balls (vertex, centre, signed radius, width), error,
//!   children, level, and for leaves the input triangle; report keys `triangles`, `nodes`,
//!   `leaves`, `depth`, `kinds`, `fallbacks` (nodes divided into disc patches).
//! - `approx MESH (--level L | --error E | --count N) [--method flintstone|iepf3|prism]
//!   -o OUT.(ply|obj|off|stl)`: the approximation's triangles on the used input vertices, in
//!   input order; report keys `method`, `nodes`, `triangles`, `dropped` (triangles with
//!   coalescing corners), `e1`, `e2`, `e5` (e3 and e4 are 2D criteria, notes A.1), `fallbacks`.
//!   `iepf3` is the 3D iterative extreme-point fit (refined by e1), `prism` the prism tree on it
//!   (same triangles at a level; refined by the prisms' half heights); `morpho::flint`'s
//!   `baselines3.rs`, `prism.rs`.
//! - `contains MESH QUERIES [--method flintstone|prism] -o OUT.csv`: the query rows (`x,y,z`)
//!   plus `inside` (1 inside, 0 outside, 2 on the boundary; exact with either hierarchy). The
//!   flintstone method answers through a grid of cached answers (`morpho::flint::CellCache3`,
//!   about 4 cells per query up to 2²²; report keys `cells`, `near_cells`, timing `index`).
//! - `intersect A B -o OUT.(csv|ply)`: the pairs of intersecting (closed) triangles by
//!   descending both trees (exact at the leaves, `morpho::flint::intersect3`) and their
//!   intersection segments — a CSV row `x,y,z,x2,y2,z2,tri_a,tri_b,coplanar` per segment (a
//!   coplanar overlap gives its polygon's edges, a touching point a zero-length segment), or a
//!   PLY of the segments as edges; `--first` only answers whether they meet. Report keys
//!   `intersects`, `pairs`, `segments`, `coplanar_pairs`, `triangles_a`, `triangles_b`,
//!   `visited` (node pairs filtered), `passed`, `leaf_tests` against `brute_pairs`, timings
//!   `build`, `intersect`, `segments`.

use crate::report::Report;
use crate::Failure;
use morpho::flint::{Containment, FlintTree3, PrismTree3, SideBall, Target, DEFAULT_CELLS};
use morpho::geom::Point3;
use morpho::io;
use morpho::mesh::{Column, PointSet, TriMesh};
use morpho::util::NONE;
use rayon::prelude::*;
use serde_json::json;
use std::path::Path;

/// True when `path` names a mesh file (the 3D tree), by extension (a `.gz` is looked through).
pub fn is_mesh(path: &Path) -> bool {
    let mut ext = crate::cmd::extension(path);
    if ext == "gz" {
        ext = path
            .file_stem()
            .map(Path::new)
            .map(crate::cmd::extension)
            .unwrap_or_default();
    }
    matches!(ext.as_str(), "ply" | "obj" | "off" | "stl")
}

fn read(path: &Path, report: &mut Report) -> Result<TriMesh, Failure> {
    Ok(report.time("read", || io::read_mesh(path))?)
}

fn tree(path: &Path, m: &TriMesh, report: &mut Report) -> Result<FlintTree3, Failure> {
    report.time("build", || {
        FlintTree3::from_mesh(m).map_err(|e| morpho::Error::from(e).with_path(path).into())
    })
}

fn iepf(path: &Path, m: &TriMesh, report: &mut Report) -> Result<FlintTree3, Failure> {
    report.time("build", || {
        FlintTree3::iepf(m).map_err(|e| morpho::Error::from(e).with_path(path).into())
    })
}

fn prism_tree(path: &Path, m: &TriMesh, report: &mut Report) -> Result<PrismTree3, Failure> {
    report.time("build", || {
        PrismTree3::new(m).map_err(|e| morpho::Error::from(e).with_path(path).into())
    })
}

/// `flint build` on a mesh.
pub fn build(input: &Path, output: &Path, report: &mut Report) -> Result<u8, Failure> {
    let m = read(input, report)?;
    let t = tree(input, &m, report)?;
    let k = t.kind_counts();
    let kinds =
        json!({"cap": k[0], "intersection": k[1], "flat": k[2], "union": k[3], "unbounded": k[4]});
    report.set("vertices", m.positions.len());
    report.set("triangles", m.triangles.len());
    report.set("nodes", t.node_count());
    report.set("leaves", t.leaf_count());
    report.set("depth", t.depth());
    report.set("kinds", kinds.clone());
    report.set("fallbacks", t.fallbacks());
    let ball = |d: &Option<SideBall>| {
        d.as_ref().map(
            |d| json!({"vertex": d.vertex, "center": d.center, "radius": d.radius, "width": d.width}),
        )
    };
    let nodes: Vec<_> = t
        .nodes
        .iter()
        .map(|n| match &n.stone {
            None => json!({"corners": n.corners, "triangle": n.triangle, "level": n.level}),
            Some(s) => json!({
                "corners": n.corners,
                "kind": if s.kind == morpho::flint::StoneKind::Segment { "flat" } else { s.kind.name() },
                "below": ball(&s.below),
                "above": ball(&s.above),
                "error": s.error().is_finite().then_some(s.error()),
                "children": n.children,
                "level": n.level,
                "patched": n.patched,
            }),
        })
        .collect();
    let r = &t.root;
    let doc = json!({
        "triangles": m.triangles.len(),
        "root": {"center": r.center, "radius": r.radius,
                 "corners": (r.corners[0] != NONE).then_some(r.corners),
                 "children": r.children, "patched": r.patched},
        "depth": t.depth(),
        "kinds": kinds,
        "nodes": nodes,
    });
    report.time("write", || {
        io::write_atomic(output, |w| io::json::write_value(w, &doc))
    })?;
    eprintln!(
        "wrote {} ({} nodes for {} triangles, depth {})",
        output.display(),
        t.node_count(),
        m.triangles.len(),
        t.depth()
    );
    Ok(0)
}

/// `flint approx` on a mesh.
pub fn approx(
    input: &Path,
    output: &Path,
    target: Target,
    method: &str,
    report: &mut Report,
) -> Result<u8, Failure> {
    if !matches!(method, "flintstone" | "iepf3" | "prism") {
        return Err(Failure::usage(format!(
            "--method {method} is a 2D baseline; a mesh takes --method flintstone, iepf3 or prism"
        )));
    }
    if !is_mesh(output) {
        return Err(Failure::usage(format!(
            "{}: a mesh approximation is written as .ply, .obj, .off or .stl",
            output.display()
        )));
    }
    let m = read(input, report)?;
    let (t, prisms) = match method {
        "flintstone" => (tree(input, &m, report)?, None),
        "iepf3" => (iepf(input, &m, report)?, None),
        _ => {
            let p = prism_tree(input, &m, report)?;
            (p.tree.clone(), Some(p))
        }
    };
    let a = report.time("approximate", || {
        match &prisms {
            Some(p) => p.approximate(target),
            None => t.approximate(target),
        }
        .map_err(|e| Failure::from(morpho::Error::from(e).with_path(input)))
    })?;
    let (mesh, map) = a.to_mesh(&t);
    report.set("method", method);
    report.set("nodes", t.node_count());
    report.set("fallbacks", t.fallbacks());
    report.set("triangles_in", m.triangles.len());
    report.set("triangles", a.triangles.len());
    report.set("vertices", map.len());
    report.set("dropped", a.dropped);
    for (k, v) in [("e1", a.e1), ("e2", a.e2), ("e5", a.e5)] {
        report.set(k, json!(v.is_finite().then_some(v)));
    }
    report.time("write", || {
        io::write_mesh(output, &mesh, io::Encoding::BinaryLittleEndian)
    })?;
    eprintln!(
        "wrote {} ({} triangles of {}, e5 {:.6})",
        output.display(),
        a.triangles.len(),
        m.triangles.len(),
        a.e5
    );
    Ok(0)
}

/// `flint contains` on a mesh.
pub fn contains(
    input: &Path,
    queries: &Path,
    output: &Path,
    method: &str,
    report: &mut Report,
) -> Result<u8, Failure> {
    let m = read(input, report)?;
    let mut q = report.time("read", || crate::cmd::read_points(queries, Some(3)))?;
    if q.dim != 3 {
        return Err(Failure::usage(format!(
            "{}: point-in-mesh needs x,y,z queries",
            queries.display()
        )));
    }
    let xs: Vec<Point3> = q
        .coords
        .chunks_exact(3)
        .map(|c| Point3::new(c[0], c[1], c[2]))
        .collect();
    let refused = |e| Failure::from(morpho::Error::from(e).with_path(queries));
    let ans = if method == "prism" {
        let p = prism_tree(input, &m, report)?;
        report.time("query", || p.contains_batch(&xs).map_err(refused))?
    } else {
        let t = tree(input, &m, report)?;
        // the cached classification (morpho::flint::CellCache3): about 4 cells per query
        let g = report.time("index", || {
            t.cell_cache(xs.len().saturating_mul(4).min(DEFAULT_CELLS))
        });
        report.set("cells", g.dims().to_vec());
        report.set("near_cells", g.label_counts()[2]);
        report.time("query", || g.contains_batch(&xs).map_err(refused))?
    };
    report.set("method", method);
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
    report.time("write", || io::write_points(output, &q))?;
    eprintln!(
        "wrote {} ({} queries: {} inside, {} on the boundary)",
        output.display(),
        xs.len(),
        count(Containment::Inside),
        count(Containment::Boundary)
    );
    Ok(0)
}

/// One output segment: its ends, the triangle pair, coplanar.
type Seg = ([[f64; 3]; 2], [u32; 2], bool);

/// `flint intersect` on two meshes.
pub fn intersect(
    a: &Path,
    b: &Path,
    output: &Path,
    first: bool,
    report: &mut Report,
) -> Result<u8, Failure> {
    let ext = crate::cmd::extension(output);
    if !matches!(ext.as_str(), "csv" | "ply") {
        return Err(Failure::usage(format!(
            "{}: the intersection of two meshes is written as .csv or .ply",
            output.display()
        )));
    }
    for p in [a, b] {
        if !is_mesh(p) {
            return Err(Failure::usage(format!(
                "{}: both inputs of a mesh intersection must be meshes (.ply/.obj/.off/.stl)",
                p.display()
            )));
        }
    }
    let ma = read(a, report)?;
    let mb = read(b, report)?;
    let (ta, tb) = report.time("build", || -> Result<_, Failure> {
        let ta = FlintTree3::from_mesh(&ma).map_err(|e| morpho::Error::from(e).with_path(a))?;
        let tb = FlintTree3::from_mesh(&mb).map_err(|e| morpho::Error::from(e).with_path(b))?;
        Ok((ta, tb))
    })?;
    report.set("triangles_a", ma.triangles.len());
    report.set("triangles_b", mb.triangles.len());
    report.set("first_only", first);
    let (pairs, st) = if first {
        let (hit, st) = report.time("intersect", || morpho::flint::intersects3(&ta, &tb));
        report.set("intersects", hit);
        report.set("visited", st.visited);
        report.set("passed", st.passed);
        report.set("leaf_tests", st.leaf_tests);
        report.set("brute_pairs", st.brute_pairs);
        eprintln!(
            "{} and {} {} ({} node pairs visited)",
            a.display(),
            b.display(),
            if hit { "intersect" } else { "do not intersect" },
            st.visited
        );
        // detection only: the output holds no segments
        (Vec::new(), st)
    } else {
        report.time("intersect", || morpho::flint::intersect3(&ta, &tb))
    };
    let (pa, pb) = (ta.positions(), tb.positions());
    let (tra, trb) = (ta.triangles(), tb.triangles());
    let meets: Vec<morpho::flint::TriangleMeet> = report.time("segments", || {
        pairs
            .par_iter()
            .map(|&[i, j]| {
                let ca = tra[i as usize].map(|v| pa[v as usize]);
                let cb = trb[j as usize].map(|v| pb[v as usize]);
                morpho::flint::triangle_meet(ca, cb).expect("the pair was found intersecting")
            })
            .collect()
    });
    let mut segs: Vec<Seg> = Vec::new();
    for (m, &p) in meets.iter().zip(&pairs) {
        for s in m.segments() {
            segs.push((s, p, m.coplanar));
        }
    }
    let coplanar = meets.iter().filter(|m| m.coplanar).count();
    if !first {
        report.set("intersects", !pairs.is_empty());
        report.set("pairs", pairs.len());
        report.set("segments", segs.len());
        report.set("coplanar_pairs", coplanar);
        report.set("visited", st.visited);
        report.set("passed", st.passed);
        report.set("leaf_tests", st.leaf_tests);
        report.set("brute_pairs", st.brute_pairs);
    }
    if ext == "ply" {
        let pts: Vec<Point3> = segs
            .iter()
            .flat_map(|(s, _, _)| s.map(|p| Point3::new(p[0], p[1], p[2])))
            .collect();
        let g = morpho::graphs::Graph {
            dim: 3,
            edges: (0..segs.len() as u32).map(|k| [2 * k, 2 * k + 1]).collect(),
            triangles: Vec::new(),
            gamma: Vec::new(),
        };
        report.time("write", || {
            io::write_atomic(output, |w| io::ply::write_graph(w, &pts, &g))
        })?;
    } else {
        let mut coords = Vec::with_capacity(3 * segs.len());
        for (s, _, _) in &segs {
            coords.extend_from_slice(&s[0]);
        }
        let col = |name: &str, f: &dyn Fn(&Seg) -> f64| Column {
            name: name.into(),
            values: segs.iter().map(f).collect(),
        };
        let columns = vec![
            col("x2", &|s| s.0[1][0]),
            col("y2", &|s| s.0[1][1]),
            col("z2", &|s| s.0[1][2]),
            col("tri_a", &|s| f64::from(s.1[0])),
            col("tri_b", &|s| f64::from(s.1[1])),
            col("coplanar", &|s| f64::from(u8::from(s.2))),
        ];
        let out = PointSet {
            dim: 3,
            coords,
            columns,
        };
        report.time("write", || io::write_points(output, &out))?;
    }
    if !first {
        eprintln!(
            "wrote {} ({} intersecting triangle pairs, {} coplanar, {} segments; {} node pairs visited, {} leaf tests of {} brute force)",
            output.display(),
            pairs.len(),
            coplanar,
            segs.len(),
            st.visited,
            st.leaf_tests,
            st.brute_pairs
        );
    }
    Ok(0)
}
