//! End-to-end tests of `morpho smooth` (issue 19 item 7): the G¹ curve of a real polygon in
//! every output format, checked from the written control points; the three-split surface of
//! a closed mesh, checked from the written patches and the tessellation; the report's figures
//! against their invariants on a real mesh; bad input → one `error:` line, exit 2.

#[path = "../../morpho/tests/common/mod.rs"]
mod common;
use common::data;
use morpho::smooth::{continuity, MicroPatch, SplitSurface};
use serde_json::Value;
use std::path::Path;
use std::process::{Command, Output};

fn morpho(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_morpho"))
        .args(args)
        .output()
        .expect("run morpho")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn ok(o: &Output) {
    assert_eq!(o.status.code(), Some(0), "stderr: {}", stderr(o));
}

/// Exit code 2 and exactly one `error:` line, naming `file` when given.
fn assert_input_error(o: &Output, file: Option<&Path>) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    let first = err.lines().next().unwrap_or("");
    assert!(first.starts_with("error: "), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert_eq!(
        err.lines().filter(|l| l.starts_with("error:")).count(),
        1,
        "{err}"
    );
    if let Some(f) = file {
        assert!(first.contains(&f.display().to_string()), "{err}");
    }
}

/// A surface scheme refuses an open mesh (the error names it) and 2D points, with exit 2.
fn refuses_open_mesh_and_points(
    dir: &Path,
    scheme: &str,
    open: &Path,
    mesh_out: &Path,
    json_out: &Path,
) {
    let run = |input: &Path, out: &Path| {
        morpho(&[
            "smooth",
            input.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--scheme",
            scheme,
        ])
    };
    assert_input_error(&run(open, mesh_out), Some(open));
    let csv = dir.join("p.csv");
    std::fs::write(&csv, "x,y\n0,0\n1,0\n0,1\n").unwrap();
    assert_input_error(&run(&csv, json_out), None);
}

fn json(p: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap()
}

fn pt(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// The `patches` of a written patch `.json` (`{"macro": t, "control": [[x, y, z] × 10]}`).
fn micro_patches(v: &Value) -> Vec<MicroPatch> {
    v["patches"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            let c: Vec<Vec<f64>> = p["control"].as_array().unwrap().iter().map(pt).collect();
            let mut control = [[0.0; 3]; 10];
            for (k, x) in c.iter().enumerate() {
                control[k] = [x[0], x[1], x[2]];
            }
            MicroPatch {
                macro_tri: p["macro"].as_u64().unwrap() as u32,
                control,
            }
        })
        .collect()
}

fn sub(a: &[f64], b: &[f64]) -> Vec<f64> {
    a.iter().zip(b).map(|(x, y)| x - y).collect()
}

#[test]
fn smooth_curve_of_a_real_polygon_in_every_format() {
    let Some(input) = data("polygons/benelux_mainland_ne50m.csv") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("c.json");
    let rep = dir.path().join("r.json");
    ok(&morpho(&[
        "smooth",
        input.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--report",
        rep.to_str().unwrap(),
    ]));
    // the input vertices, read independently (lon,lat rows; the closing repeat dropped)
    let text = std::fs::read_to_string(&input).unwrap();
    let mut verts: Vec<[f64; 2]> = text
        .lines()
        .skip(1)
        .map(|l| {
            let f: Vec<f64> = l.split(',').map(|s| s.trim().parse().unwrap()).collect();
            [f[0], f[1]]
        })
        .collect();
    if verts.first() == verts.last() {
        verts.pop();
    }
    let c = json(&out);
    assert_eq!(c["closed"], Value::Bool(true));
    let segs = c["segments"].as_array().unwrap();
    assert_eq!(segs.len(), verts.len());
    let mut worst: f64 = 0.0;
    for (k, s) in segs.iter().enumerate() {
        let s: Vec<Vec<f64>> = s.as_array().unwrap().iter().map(pt).collect();
        assert_eq!(s.len(), 4);
        assert_eq!(s[0], verts[k].to_vec(), "segment {k} starts at vertex {k}");
        let next: Vec<Vec<f64>> = segs[(k + 1) % segs.len()]
            .as_array()
            .unwrap()
            .iter()
            .map(pt)
            .collect();
        assert_eq!(s[3], next[0], "C0 at joint {k}");
        // G¹ at the joint, from the written control points: P'(1) ∥ Q'(0), same direction
        let (a, b) = (sub(&s[3], &s[2]), sub(&next[1], &next[0]));
        let cross = a[0] * b[1] - a[1] * b[0];
        let dot = a[0] * b[0] + a[1] * b[1];
        let na = a[0].hypot(a[1]);
        let nb = b[0].hypot(b[1]);
        assert!(dot > 0.0, "cusp at joint {k}");
        worst = worst.max(cross.abs() / (na * nb));
    }
    assert!(worst <= 1e-9, "{worst}");
    let r = json(&rep);
    assert_eq!(r["segments"].as_u64(), Some(verts.len() as u64));
    assert_eq!(r["cusps"].as_u64(), Some(0));
    assert!(r["g1_failures"].as_u64().is_some());
    assert!(r["max_joint_sine"].as_f64().unwrap() <= 1e-9);

    // SVG: one true cubic path, one C per segment
    let svg = dir.path().join("c.svg");
    ok(&morpho(&[
        "smooth",
        input.to_str().unwrap(),
        "-o",
        svg.to_str().unwrap(),
    ]));
    let s = std::fs::read_to_string(&svg).unwrap();
    assert_eq!(s.matches("<path").count(), 1);
    assert_eq!(s.matches('C').count(), verts.len());
    // sampled GeoJSON: `--density` points per segment on one ring
    let geo = dir.path().join("c.geojson");
    ok(&morpho(&[
        "smooth",
        input.to_str().unwrap(),
        "-o",
        geo.to_str().unwrap(),
        "--density",
        "5",
    ]));
    let g = json(&geo);
    let ring = &g["features"][0]["geometry"]["coordinates"][0];
    // GeoJSON repeats the first position at the end
    assert_eq!(ring.as_array().unwrap().len(), 5 * verts.len() + 1);
    // exactly one sample in five is a polygon vertex (the writer may reverse the ring)
    let ring = ring.as_array().unwrap();
    let on_vertex = ring[1..]
        .iter()
        .filter(|q| {
            let p = pt(q);
            verts.iter().any(|v| v[..] == p[..])
        })
        .count();
    assert_eq!(on_vertex, verts.len());
}

/// An irregular closed octahedron (no mirror-symmetric edge) as OBJ text.
fn octahedron_obj() -> String {
    let v = [
        [1.2, 0.0, 0.1],
        [-0.8, 0.1, 0.0],
        [0.1, 1.1, 0.1],
        [0.1, -0.9, 0.05],
        [0.0, 0.1, 1.3],
        [0.05, 0.0, -0.7],
    ];
    let f = [
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    let mut s = String::new();
    for p in v {
        s += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    for t in f {
        s += &format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
    }
    s
}

#[test]
fn smooth_surface_of_a_closed_mesh_is_g1_and_interpolates() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("oct.obj");
    std::fs::write(&input, octahedron_obj()).unwrap();
    let m = morpho::io::read_mesh(&input).unwrap();
    // patches as JSON, checked independently of the construction
    let pj = dir.path().join("p.json");
    let rep = dir.path().join("r.json");
    ok(&morpho(&[
        "smooth",
        input.to_str().unwrap(),
        "-o",
        pj.to_str().unwrap(),
        "--report",
        rep.to_str().unwrap(),
    ]));
    let v = json(&pj);
    assert_eq!(v["degree"].as_u64(), Some(3));
    let patches = micro_patches(&v);
    assert_eq!(patches.len(), 3 * m.triangles.len());
    // b300 of patch 3t+i is corner i of macro triangle t, b030 corner i+1
    for (k, p) in patches.iter().enumerate() {
        let t = m.triangles[k / 3];
        let a: [f64; 3] = m.positions[t[k % 3] as usize].into();
        let b: [f64; 3] = m.positions[t[(k + 1) % 3] as usize].into();
        assert_eq!(p.control[0], a);
        assert_eq!(p.control[6], b);
    }
    let s = SplitSurface {
        patches,
        ..Default::default()
    };
    let c = continuity(&s, 25);
    assert_eq!(c.open_edges, 0);
    assert_eq!(c.folds, 0);
    assert!(c.max_normal_jump_rad <= 1e-9, "{c:?}");
    let r = json(&rep);
    assert!(r["max_normal_jump_rad"].as_f64().unwrap() <= 1e-9);
    assert_eq!(r["non_g1_edges"].as_u64(), Some(0));
    assert_eq!(r["folds"].as_u64(), Some(0));
    assert_eq!(r["patches"].as_u64(), Some(24));
    assert!(r["max_deviation"].as_f64().unwrap() > 0.0);

    // tessellated PLY: closed, surface normals, every input vertex on it
    let ply = dir.path().join("t.ply");
    ok(&morpho(&[
        "smooth",
        input.to_str().unwrap(),
        "-o",
        ply.to_str().unwrap(),
        "--density",
        "4",
    ]));
    let t = morpho::io::read_mesh(&ply).unwrap();
    assert_eq!(t.triangles.len(), 24 * 16);
    assert!(morpho::mesh::analyze_topology(&t).is_closed());
    assert!(t.normals.is_some());
    for p in &m.positions {
        assert!(t.positions.iter().any(|q| (q - p).norm() <= 1e-12));
    }
}

#[test]
fn smooth_report_on_a_real_mesh_is_consistent() {
    let Some(input) = data("meshes/spot.obj") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("s.ply");
    let rep = dir.path().join("r.json");
    ok(&morpho(&[
        "smooth",
        input.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--density",
        "2",
        "--report",
        rep.to_str().unwrap(),
    ]));
    let r = json(&rep);
    let u = |k: &str| r[k].as_u64().unwrap_or_else(|| panic!("{k}: {r}"));
    let f = |k: &str| r[k].as_f64().unwrap_or_else(|| panic!("{k}: {r}"));
    eprintln!("spot: {r}");
    // three per macro triangle, more where the edge split bisected one (split3.rs, edgesplit.rs)
    assert!(u("patches") >= 3 * u("macro_triangles") + 6 * u("split_edges"));
    assert_eq!(u("triangles"), 4 * u("patches"));
    // a folded edge has a normal angle ≥ π/2: it is among the non-G¹ edges
    assert!(u("fold_edges") <= u("non_g1_edges"));
    assert!(u("fold_edges") <= u("folds"));
    assert_eq!(u("non_g1_edges") == 0, f("max_normal_jump_rad") <= 1e-9);
    assert!(u("unresolved_edges") <= u("singular_edges"));
    assert!(f("max_position_gap") <= 1e-9);
    // the fold guard (default) removes spot's 277 fold samples (26 edges) of `--folds keep`
    assert_eq!(u("folds"), 0);
    // a fold-guarded edge keeps its cubic boundary and is then solved like any other edge;
    // what stays creased is reported: every non-G¹ edge is an unresolved one
    assert!(u("non_g1_edges") <= u("unresolved_edges"));
    let rep2 = dir.path().join("r2.json");
    ok(&morpho(&[
        "smooth",
        input.to_str().unwrap(),
        "-o",
        out.with_extension("obj").to_str().unwrap(),
        "--density",
        "1",
        "--folds",
        "keep",
        "--report",
        rep2.to_str().unwrap(),
    ]));
    let r2 = json(&rep2);
    eprintln!("spot --folds keep: {r2}");
    assert!(r2["folds"].as_u64().unwrap() > 0);
    assert_eq!(r2["fold_guarded_edges"].as_u64(), Some(0));
}

#[test]
fn smooth_refuses_bad_input_with_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let out = d.join("o.ply");
    let run = |input: &Path, out: &Path, extra: &[&str]| {
        let mut a = vec![
            "smooth",
            input.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ];
        a.extend_from_slice(extra);
        morpho(&a)
    };
    // open mesh: the octahedron without its last face
    let oct = octahedron_obj();
    let open = d.join("open.obj");
    std::fs::write(&open, oct.lines().take(13).collect::<Vec<_>>().join("\n")).unwrap();
    assert_input_error(&run(&open, &out, &[]), Some(&open));
    // inconsistently oriented: one face flipped
    let flipped = d.join("flip.obj");
    std::fs::write(&flipped, oct.replace("f 1 3 5", "f 3 1 5")).unwrap();
    assert_input_error(&run(&flipped, &out, &[]), Some(&flipped));
    // non-manifold: a face used twice
    let twice = d.join("twice.obj");
    std::fs::write(&twice, format!("{oct}f 1 3 5\n")).unwrap();
    assert_input_error(&run(&twice, &out, &[]), Some(&twice));
    // polygon with a repeated consecutive vertex; with a NaN; too few vertices
    let csv = |name: &str, body: &str| {
        let p = d.join(name);
        std::fs::write(&p, format!("x,y\n{body}")).unwrap();
        p
    };
    let rep = csv("rep.csv", "0,0\n1,0\n1,0\n0,1\n");
    assert_input_error(&run(&rep, &d.join("o.json"), &[]), Some(&rep));
    let nan = csv("nan.csv", "0,0\n1,0\nnan,1\n0,1\n");
    assert_input_error(&run(&nan, &d.join("o.json"), &[]), Some(&nan));
    let two = csv("two.csv", "0,0\n1,0\n");
    assert_input_error(&run(&two, &d.join("o.json"), &[]), Some(&two));
    // wrong output kind, scheme for the other kind, density 0, output over the input
    let good = d.join("oct.obj");
    std::fs::write(&good, &oct).unwrap();
    assert_input_error(&run(&good, &d.join("o.svg"), &[]), None);
    assert_input_error(&run(&good, &out, &["--scheme", "curve"]), None);
    assert_input_error(&run(&good, &out, &["--density", "0"]), None);
    assert_input_error(&run(&good, &good, &[]), None);
    assert_eq!(std::fs::read_to_string(&good).unwrap(), oct);
    assert!(!out.exists());
}

/// The regular tetrahedron inscribed in the unit sphere, with the sphere's normals, as PLY.
fn unit_tetrahedron_ply() -> String {
    let s = 1.0 / 3f64.sqrt();
    let v = [[s, s, s], [s, -s, -s], [-s, s, -s], [-s, -s, s]];
    let f = [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]];
    let mut out = String::from(
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\n\
         property double z\nproperty double nx\nproperty double ny\nproperty double nz\n\
         element face 4\nproperty list uchar int vertex_indices\nend_header\n",
    );
    for p in v {
        out += &format!("{} {} {} {} {} {}\n", p[0], p[1], p[2], p[0], p[1], p[2]);
    }
    for t in f {
        out += &format!("3 {} {} {}\n", t[0], t[1], t[2]);
    }
    out
}

#[test]
fn side_vertex_surface_of_the_tetrahedron_and_a_real_mesh() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let tet = d.join("tet.ply");
    std::fs::write(&tet, unit_tetrahedron_ply()).unwrap();
    let (out, rep) = (d.join("s.ply"), d.join("r.json"));
    let run = |extra: &[&str]| {
        let mut a = vec![
            "smooth",
            tet.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--scheme",
            "side-vertex",
            "--normals",
            "file",
            "--report",
            rep.to_str().unwrap(),
        ];
        a.extend_from_slice(extra);
        morpho(&a)
    };
    ok(&run(&["--density", "48"]));
    let r = json(&rep);
    assert_eq!(r["scheme"], "side-vertex");
    assert_eq!(r["patches"], 4);
    assert_eq!(r["triangles"], 4 * 48 * 48);
    assert_eq!(
        (r["non_g1_edges"].as_u64(), r["folds"].as_u64()),
        (Some(0), Some(0))
    );
    assert!(r["max_normal_jump_rad"].as_f64().unwrap() <= 1e-9, "{r}");
    assert_eq!(r["inflected_edges"], 0);
    // Hamann's sphere test from the written mesh: 0.03422 at the face centroids
    let m = morpho::io::read_mesh(&out).unwrap();
    let dev = m
        .positions
        .iter()
        .map(|p| (p.coords.norm() - 1.0).abs())
        .fold(0.0, f64::max);
    assert!((0.03420..=0.03424).contains(&dev), "{dev}");
    let normals = m.normals.as_ref().expect("PLY with surface normals");
    for (p, n) in m.positions.iter().zip(normals) {
        assert!((n.norm() - 1.0).abs() < 1e-6 && n.dot(&p.coords.normalize()) > 0.99);
    }
    let topo = morpho::mesh::analyze_topology(&m);
    assert!(topo.is_closed() && topo.consistently_oriented);
    // a lower tension pulls the surface towards the tetrahedron
    let flat_dev = r["max_deviation"].as_f64().unwrap();
    ok(&run(&["--density", "12", "--tension", "0.5"]));
    let r2 = json(&rep);
    assert_eq!(r2["tension"], 0.5);
    assert!(r2["max_deviation"].as_f64().unwrap() < flat_dev);
    // refused: tension 0, tension with split3, JSON output, 2D input
    assert_input_error(&run(&["--tension", "0"]), None);
    let o = morpho(&[
        "smooth",
        tet.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--tension",
        "0.5",
    ]);
    assert_input_error(&o, None);
    let o = morpho(&[
        "smooth",
        tet.to_str().unwrap(),
        "-o",
        d.join("s.json").to_str().unwrap(),
        "--scheme",
        "side-vertex",
    ]);
    assert_input_error(&o, None);
    let csv = d.join("p.csv");
    std::fs::write(&csv, "x,y\n0,0\n1,0\n0,1\n").unwrap();
    let o = morpho(&[
        "smooth",
        csv.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--scheme",
        "side-vertex",
    ]);
    assert_input_error(&o, None);
    // an open mesh names the file
    let open = d.join("open.obj");
    let oct = octahedron_obj();
    std::fs::write(&open, oct.lines().take(13).collect::<Vec<_>>().join("\n")).unwrap();
    let o = morpho(&[
        "smooth",
        open.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--scheme",
        "side-vertex",
    ]);
    assert_input_error(&o, Some(&open));
    // a real mesh (default handle floor 0.1): no fold at the edges, C⁰, jumps ≤ 1e-7
    let Some(spot) = data("meshes/spot.obj") else {
        return;
    };
    let o = morpho(&[
        "smooth",
        spot.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--scheme",
        "side-vertex",
        "--density",
        "2",
        "--report",
        rep.to_str().unwrap(),
    ]);
    ok(&o);
    let r = json(&rep);
    assert_eq!(r["folds"], 0);
    assert!(r["max_position_gap"].as_f64().unwrap() <= 1e-14);
    assert!(r["max_normal_jump_rad"].as_f64().unwrap() <= 1e-7, "{r}");
    assert!(r["inflected_edges"].as_u64().unwrap() > 0);
    assert_eq!(r["edges_checked"], 8784);
    let m = morpho::io::read_mesh(&out).unwrap();
    assert_eq!(m.triangles.len(), 5856 * 4);
    assert!(morpho::mesh::analyze_topology(&m).is_closed());
}

#[test]
fn reflection_lines_beside_the_input_mesh() {
    // the octahedron's side-vertex surface, rendered with reflection lines beside the octahedron
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("oct.obj");
    std::fs::write(&input, octahedron_obj()).unwrap();
    let surf = dir.path().join("s.ply");
    ok(&morpho(&[
        "smooth",
        input.to_str().unwrap(),
        "-o",
        surf.to_str().unwrap(),
        "--scheme",
        "side-vertex",
    ]));
    let png = dir.path().join("r.png");
    let rep = dir.path().join("r.json");
    ok(&morpho(&[
        "render",
        surf.to_str().unwrap(),
        "-o",
        png.to_str().unwrap(),
        "--reflection-lines",
        "--beside",
        input.to_str().unwrap(),
        "--width",
        "120",
        "--height",
        "100",
        "--report",
        rep.to_str().unwrap(),
    ]));
    let r = json(&rep);
    // two pictures side by side with an 8-pixel gap
    assert_eq!(r["width"].as_u64(), Some(248));
    assert_eq!(r["beside_triangles"].as_u64(), Some(8));
    // bad line count: exit 2
    let o = morpho(&[
        "render",
        surf.to_str().unwrap(),
        "-o",
        png.to_str().unwrap(),
        "--reflection-lines",
        "0",
    ]);
    assert_input_error(&o, None);
}

/// `--scheme split6`: the `.json` patches (six per macro triangle, the vertices at their
/// corners), checked independently of the construction; the report keys of split3; bad
/// input refused with exit 2.
#[test]
fn six_split_surface_from_the_cli() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("oct.obj");
    std::fs::write(&input, octahedron_obj()).unwrap();
    let m = morpho::io::read_mesh(&input).unwrap();
    let pj = dir.path().join("p.json");
    let rep = dir.path().join("r.json");
    ok(&morpho(&[
        "smooth",
        input.to_str().unwrap(),
        "-o",
        pj.to_str().unwrap(),
        "--scheme",
        "split6",
        "--report",
        rep.to_str().unwrap(),
    ]));
    let v = json(&pj);
    assert_eq!(v["degree"].as_u64(), Some(3));
    let patches = micro_patches(&v);
    assert_eq!(patches.len(), 6 * m.triangles.len());
    // patch 6t+2i starts at corner i, patch 6t+2i+1 ends at corner i+1
    for (k, p) in patches.iter().enumerate() {
        let t = m.triangles[k / 6];
        let i = (k % 6) / 2;
        assert_eq!(p.macro_tri as usize, k / 6);
        if k % 2 == 0 {
            let a: [f64; 3] = m.positions[t[i] as usize].into();
            assert_eq!(p.control[0], a);
        } else {
            let b: [f64; 3] = m.positions[t[(i + 1) % 3] as usize].into();
            assert_eq!(p.control[6], b);
        }
    }
    let s = SplitSurface {
        patches,
        ..Default::default()
    };
    let c = continuity(&s, 25);
    assert_eq!(c.open_edges, 0);
    assert_eq!(c.folds, 0);
    assert!(c.max_normal_jump_rad <= 1e-9, "{c:?}");
    let r = json(&rep);
    assert_eq!(r["scheme"], "split6");
    for k in [
        "max_normal_jump_rad",
        "non_g1_edges",
        "max_deviation",
        "unresolved_edges",
        "folds",
    ] {
        assert!(r.get(k).is_some(), "{k}: {r}");
    }
    assert!(r["max_normal_jump_rad"].as_f64().unwrap() <= 1e-9);
    assert_eq!(r["non_g1_edges"].as_u64(), Some(0));
    assert_eq!(r["patches"].as_u64(), Some(48));
    assert!(r["max_deviation"].as_f64().unwrap() > 0.0);
    // tessellated: closed, every input vertex on it
    let ply = dir.path().join("t.ply");
    ok(&morpho(&[
        "smooth",
        input.to_str().unwrap(),
        "-o",
        ply.to_str().unwrap(),
        "--scheme",
        "split6",
        "--density",
        "3",
    ]));
    let t = morpho::io::read_mesh(&ply).unwrap();
    assert_eq!(t.triangles.len(), 48 * 9);
    assert!(morpho::mesh::analyze_topology(&t).is_closed());
    for p in &m.positions {
        assert!(t.positions.iter().any(|q| (q - p).norm() <= 1e-12));
    }
    // bad input: open mesh, 2D input with split6
    let open = dir.path().join("open.obj");
    std::fs::write(
        &open,
        octahedron_obj()
            .lines()
            .take(13)
            .collect::<Vec<_>>()
            .join("\n"),
    )
    .unwrap();
    refuses_open_mesh_and_points(dir.path(), "split6", &open, &ply, &pj);
}

/// `--scheme split2` (the two-split, V §9.7, experimental): on the icosphere every triangle
/// qualifies for a pair; the `.json` patches (2 per paired, 3 per three-split triangle, the
/// count given by the report's `pairs`) are checked independently of the construction, the
/// report keys are those of the other schemes; bad input refused with exit 2.
#[test]
fn two_split_surface_from_the_cli() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("ico.ply");
    let m = morpho::mesh::generate::icosphere(1);
    morpho::io::write_mesh(&input, &m, morpho::io::Encoding::default()).unwrap();
    let pj = dir.path().join("p.json");
    let rep = dir.path().join("r.json");
    ok(&morpho(&[
        "smooth",
        input.to_str().unwrap(),
        "-o",
        pj.to_str().unwrap(),
        "--scheme",
        "split2",
        "--report",
        rep.to_str().unwrap(),
    ]));
    let r = json(&rep);
    assert_eq!(r["scheme"], "split2");
    for k in [
        "max_normal_jump_rad",
        "non_g1_edges",
        "max_deviation",
        "unresolved_edges",
        "folds",
        "pairs",
        "rejected_pairs",
    ] {
        assert!(r.get(k).is_some(), "{k}: {r}");
    }
    let pairs = r["pairs"].as_u64().unwrap() as usize;
    assert!(pairs >= 10, "{r}");
    let v = json(&pj);
    assert_eq!(v["degree"].as_u64(), Some(3));
    let patches = micro_patches(&v);
    assert_eq!(patches.len(), 3 * m.triangles.len() - 2 * pairs);
    assert_eq!(r["patches"].as_u64(), Some(patches.len() as u64));
    // every patch has two macro vertices among its corners (b300, b030, b003)
    for p in &patches {
        let t = m.triangles[p.macro_tri as usize];
        let at_vertex = [0, 6, 9]
            .iter()
            .filter(|&&i| {
                t.iter().any(|&v| {
                    let x: [f64; 3] = m.positions[v as usize].into();
                    p.control[i] == x
                })
            })
            .count();
        assert_eq!(at_vertex, 2, "{p:?}");
    }
    let s = SplitSurface {
        patches,
        ..Default::default()
    };
    let c = continuity(&s, 25);
    assert_eq!(c.open_edges, 0);
    assert_eq!(c.folds, 0);
    assert!(c.max_normal_jump_rad <= 1e-9, "{c:?}");
    assert!(r["max_normal_jump_rad"].as_f64().unwrap() <= 1e-9);
    assert_eq!(r["non_g1_edges"].as_u64(), Some(0));
    let dev = r["max_deviation"].as_f64().unwrap();
    assert!(dev > 0.0 && dev < 0.2, "{dev}");
    // bad input: open mesh, 2D input with split2
    let mut open = m.clone();
    open.triangles.pop();
    let op = dir.path().join("open.ply");
    morpho::io::write_mesh(&op, &open, morpho::io::Encoding::default()).unwrap();
    let ply = dir.path().join("t.ply");
    refuses_open_mesh_and_points(dir.path(), "split2", &op, &ply, &pj);
}
