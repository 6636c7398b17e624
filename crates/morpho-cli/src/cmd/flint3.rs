//! `morpho flint build|approx|contains` on a closed triangle mesh (.ply/.obj/.off/.stl, also
//! gzipped): the 3D flintstone tree (Veltkamp 1992, §7.3, Alg. 7.2; see `morpho::flint`).
//!
//! - `build MESH -o TREE.json`: root (ball, level-0 triangle, children) and per node its
//!   corners, kind, the two side balls (vertex, centre, signed radius, width), error,
//!   children, level, and for leaves the input triangle; report keys `triangles`, `nodes`,
//!   `leaves`, `depth`, `kinds`, `fallbacks` (nodes divided into disc patches).
//! - `approx MESH (--level L | --error E | --count N) -o OUT.(ply|obj|off|stl)`: the
//!   approximation's triangles on the used input vertices, in input order; report keys
//!   `triangles`, `dropped` (triangles with coalescing corners), `e1`, `e2`, `e5`.
//! - `contains MESH QUERIES -o OUT.csv`: the query rows (`x,y,z`) plus `inside` (1 inside,
//!   0 outside, 2 on the boundary; exact).

use crate::report::Report;
use crate::Failure;
use morpho::flint::{Containment, FlintTree3, SideBall, Target};
use morpho::geom::Point3;
use morpho::io;
use morpho::mesh::{Column, PointSet, TriMesh};
use morpho::util::NONE;
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
    if method != "flintstone" {
        return Err(Failure::usage(format!(
            "--method {method}: the 3D baselines are not built yet; a mesh takes --method flintstone"
        )));
    }
    if !is_mesh(output) {
        return Err(Failure::usage(format!(
            "{}: a mesh approximation is written as .ply, .obj, .off or .stl",
            output.display()
        )));
    }
    let m = read(input, report)?;
    let t = tree(input, &m, report)?;
    let a = report.time("approximate", || {
        t.approximate(target)
            .map_err(|e| Failure::from(morpho::Error::from(e).with_path(input)))
    })?;
    let (mesh, map) = a.to_mesh(&t);
    report.set("method", "flintstone");
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
    let t = tree(input, &m, report)?;
    let xs: Vec<Point3> = q
        .coords
        .chunks_exact(3)
        .map(|c| Point3::new(c[0], c[1], c[2]))
        .collect();
    let ans = report.time("query", || {
        t.contains_batch(&xs)
            .map_err(|e| Failure::from(morpho::Error::from(e).with_path(queries)))
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
