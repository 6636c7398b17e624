//! End-to-end tests of the `morpho` binary: exit codes, `error:` lines, atomic outputs,
//! reports, and behaviour on bad input (issue 2 item 8).

#[path = "../../morpho/tests/common/mod.rs"]
mod common;
use common::data_dir;
use std::path::{Path, PathBuf};
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

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Asserts exit code 2 and exactly one `error: FILE: …` line naming the file.
fn assert_input_error(o: &Output, file: &Path) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 1, "exactly one line expected: {err}");
    assert!(lines[0].starts_with("error: "), "{err}");
    let name = file.display().to_string();
    assert!(lines[0].contains(&name), "error should name {name}: {err}");
    assert!(!err.contains("panicked"), "{err}");
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

/// No file but the given ones is left in `dir` (no temporary or partial output).
fn assert_only(dir: &Path, names: &[&str]) {
    let mut found: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    found.sort();
    let mut want: Vec<String> = names.iter().map(|s| s.to_string()).collect();
    want.sort();
    assert_eq!(found, want);
}

const CUBE_OBJ: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";

#[test]
fn info_on_a_closed_cube() {
    let dir = tempfile::tempdir().unwrap();
    let f = write(dir.path(), "cube.obj", CUBE_OBJ.as_bytes());
    let rep = dir.path().join("r.json");
    let o = morpho(&[
        "info",
        f.to_str().unwrap(),
        "--report",
        rep.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("vertices: 8"), "{out}");
    assert!(out.contains("triangles: 12"), "{out}");
    let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&rep).unwrap()).unwrap();
    assert_eq!(r["command"], "info");
    assert_eq!(r["kind"], "mesh");
    assert_eq!(r["vertices"], 8);
    assert_eq!(r["triangles"], 12);
    assert_eq!(r["parts"], 1);
    assert_eq!(r["boundary_loops"], 0);
    assert_eq!(r["euler_characteristic"], 2);
    assert_eq!(r["genus"], 0);
    assert_eq!(r["manifold"], true);
    assert_eq!(r["orientable"], true);
    assert!(r["elapsed_s"].as_f64().unwrap() >= 0.0);
    // the input's bytes; nothing written but the report (saved after the figures)
    assert_eq!(r["io"]["read_bytes"], CUBE_OBJ.len());
    assert_eq!(r["io"]["write_bytes"], 0);
    for k in ["read", "compute", "write"] {
        assert!(r["timings"][k].as_f64().is_some(), "timings.{k}");
    }
    assert_eq!(
        r["bbox"],
        serde_json::json!([[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]])
    );
}

#[test]
fn bad_inputs_give_one_error_line_and_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut cases: Vec<PathBuf> = vec![
        write(d, "empty.ply", b""),
        write(d, "empty.obj", b""),
        write(d, "empty.csv", b""),
        write(d, "empty.stl", b""),
        write(d, "huge.ply", b"ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n\0\0\0\0"),
        write(d, "huge.off", b"OFF\n1000000000000 1 0\n0 0 0\n"),
        write(d, "range.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"),
        write(d, "nan.obj", b"v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"),
        write(d, "inf.xyz", b"0 0 0\n1 inf 0\n"),
        write(d, "nan.csv", b"x,y\n0,0\nNaN,1\n"),
        write(d, "bytes.obj", b"v 0 0 0\nv \xff\xfe 0 0\n"),
        write(d, "unknown.xyzzy", b"hello"),
        write(d, "noext", b"hello"),
    ];
    // a binary PLY whose data stops in the middle of the faces
    let mut trunc = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n".to_vec();
    for v in [[0f32, 0., 0.], [1., 0., 0.], [0., 1., 0.]] {
        for c in v {
            trunc.extend_from_slice(&c.to_le_bytes());
        }
    }
    trunc.extend_from_slice(&[3, 0, 0, 0, 0, 1]);
    cases.push(write(d, "trunc.ply", &trunc));
    // binary STL claiming 10 triangles but holding one
    let mut stl = vec![0u8; 80];
    stl.extend_from_slice(&10u32.to_le_bytes());
    stl.extend_from_slice(&[0u8; 50]);
    cases.push(write(d, "trunc.stl", &stl));
    for f in &cases {
        let o = morpho(&["info", f.to_str().unwrap()]);
        assert_input_error(&o, f);
    }
    // convert of a bad input leaves no output file behind
    let out = d.join("out.ply");
    for f in &cases {
        let o = morpho(&["convert", f.to_str().unwrap(), "-o", out.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(2), "{}: {}", f.display(), stderr(&o));
        assert!(!out.exists(), "partial output left for {}", f.display());
    }
    let names: Vec<String> = cases
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    let refs: Vec<&str> = names.iter().map(String::as_str).collect();
    assert_only(d, &refs);
}

#[test]
fn missing_file_and_bad_usage_exit_2() {
    let o = morpho(&["info", "/nonexistent/file.obj"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).starts_with("error: /nonexistent/file.obj"),
        "{}",
        stderr(&o)
    );
    let o = morpho(&["info"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).starts_with("error: "));
    let o = morpho(&["frobnicate"]);
    assert_eq!(o.status.code(), Some(2));
    let o = morpho(&["--help"]);
    assert_eq!(o.status.code(), Some(0));
}

#[test]
fn output_never_overwrites_input() {
    let dir = tempfile::tempdir().unwrap();
    let f = write(dir.path(), "cube.obj", CUBE_OBJ.as_bytes());
    let o = morpho(&["convert", f.to_str().unwrap(), "-o", f.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(&f).unwrap(), CUBE_OBJ);
    // the same file under another spelling of its path
    let alias = dir.path().join(".").join("cube.obj");
    let o = morpho(&[
        "convert",
        f.to_str().unwrap(),
        "-o",
        alias.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(std::fs::read_to_string(&f).unwrap(), CUBE_OBJ);
}

#[test]
fn convert_round_trips_a_mesh_through_every_format() {
    let dir = tempfile::tempdir().unwrap();
    let f = write(dir.path(), "cube.obj", CUBE_OBJ.as_bytes());
    let mut prev = f.clone();
    for ext in ["ply", "off", "stl", "obj"] {
        let out = dir.path().join(format!("c.{ext}"));
        let o = morpho(&[
            "convert",
            prev.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(0), "{ext}: {}", stderr(&o));
        let rep = dir.path().join(format!("{ext}.json"));
        let o = morpho(&[
            "info",
            out.to_str().unwrap(),
            "--report",
            rep.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&rep).unwrap()).unwrap();
        assert_eq!(r["vertices"], 8, "{ext}");
        assert_eq!(r["triangles"], 12, "{ext}");
        assert_eq!(r["genus"], 0, "{ext}");
        prev = out;
    }
}

#[test]
fn non_manifold_mesh_is_reported_not_rejected() {
    // three triangles sharing the edge (0,1)
    let dir = tempfile::tempdir().unwrap();
    let f = write(
        dir.path(),
        "fin.obj",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n",
    );
    let rep = dir.path().join("r.json");
    let o = morpho(&[
        "info",
        f.to_str().unwrap(),
        "--report",
        rep.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&rep).unwrap()).unwrap();
    assert_eq!(r["manifold"], false);
    assert_eq!(r["non_manifold_edges"], 1);
    assert!(stdout(&o).contains("manifold: no"));
}

#[test]
fn info_on_real_meshes_matches_the_data_readme() {
    let Some(data) = data_dir() else { return };
    // (file, vertices, triangles, parts, boundary loops, genus or None, manifold)
    type Case<'a> = (&'a str, u64, u64, u64, Option<u64>, Option<i64>, bool);
    let cases: [Case; 4] = [
        (
            "meshes/bunny_npm.obj",
            1839,
            3674,
            1,
            Some(0),
            Some(0),
            true,
        ),
        (
            "meshes/rocker-arm.obj",
            10044,
            20088,
            1,
            Some(0),
            Some(1),
            true,
        ),
        ("meshes/fandisk.obj", 6475, 12946, 1, Some(0), Some(0), true),
        (
            "meshes/dragon_vrip_res4.obj",
            5205,
            11102,
            1,
            None,
            None,
            false,
        ),
    ];
    let dir = tempfile::tempdir().unwrap();
    for (name, v, t, parts, loops, genus, manifold) in cases {
        let f = data.join(name);
        let rep = dir.path().join("r.json");
        let o = morpho(&[
            "info",
            f.to_str().unwrap(),
            "--report",
            rep.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(0), "{name}: {}", stderr(&o));
        let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&rep).unwrap()).unwrap();
        assert_eq!(r["vertices"], v, "{name}");
        assert_eq!(r["triangles"], t, "{name}");
        assert_eq!(r["manifold"], manifold, "{name}");
        if manifold {
            assert_eq!(r["parts"], parts, "{name}");
        }
        if let Some(l) = loops {
            assert_eq!(r["boundary_loops"], l, "{name}");
        }
        assert_eq!(r["genus"], serde_json::json!(genus), "{name}");
    }
}

#[test]
fn triangulate_2d_and_3d() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // unit square corners, its centre and a duplicate of corner 1
    let f = write(d, "p.csv", b"x,y\n0,0\n1,0\n1,1\n0,1\n0.5,0.5\n1,0\n");
    let out = d.join("t.json");
    let rep = d.join("r.json");
    let o = morpho(&[
        "triangulate",
        f.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--report",
        rep.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    let tris = v["triangles"].as_array().unwrap();
    assert_eq!(tris.len(), 4, "2n − 2 − h = 10 − 2 − 4");
    for t in tris {
        for i in t.as_array().unwrap() {
            assert_ne!(
                i.as_u64().unwrap(),
                5,
                "the duplicate is represented by its first occurrence"
            );
        }
    }
    let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&rep).unwrap()).unwrap();
    assert_eq!(r["points"], 6);
    assert_eq!(r["unique_points"], 5);
    assert_eq!(r["hull_size"], 4);
    // SVG and mesh outputs
    for ext in ["svg", "ply", "off"] {
        let out = d.join(format!("t.{ext}"));
        let o = morpho(&[
            "triangulate",
            f.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--voronoi",
        ]);
        assert_eq!(o.status.code(), Some(0), "{ext}: {}", stderr(&o));
        assert!(std::fs::metadata(&out).unwrap().len() > 0);
    }
    // collinear: no triangles, a note, exit 0
    let f = write(d, "line.xyz", b"0 0\n1 1\n3 3\n2 2\n");
    let o = morpho(&[
        "triangulate",
        f.to_str().unwrap(),
        "-o",
        d.join("l.json").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stderr(&o).contains("collinear"));
    // too few distinct points, NaN, empty: exit 2
    for (name, bytes) in [
        ("two.xyz", &b"0 0\n1 1\n0 0\n"[..]),
        ("nan.xyz", b"0 0\n1 nan\n2 0\n"),
        ("empty.csv", b""),
    ] {
        let f = write(d, name, bytes);
        let o = morpho(&[
            "triangulate",
            f.to_str().unwrap(),
            "-o",
            d.join("bad.json").to_str().unwrap(),
        ]);
        assert_input_error(&o, &f);
        assert!(!d.join("bad.json").exists());
    }
    // 3D: the cube corners and centre
    let f = write(
        d,
        "c.xyz",
        b"0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n1 1 1\n0.5 0.5 0.5\n",
    );
    let out = d.join("c.json");
    let o = morpho(&[
        "triangulate",
        f.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    // the centre sees all 6 faces, each split into 2 triangles: 12 tetrahedra
    assert_eq!(v["tetrahedra"].as_array().unwrap().len(), 12);
    let o = morpho(&[
        "triangulate",
        f.to_str().unwrap(),
        "-o",
        d.join("c.ply").to_str().unwrap(),
        "--tets",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}

#[test]
fn graph_command() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let f = write(d, "p.csv", b"x,y\n0,0\n4,0\n4,3\n0,3\n2,1.4\n1,2\n3,2.2\n");
    let out = d.join("g.json");
    let o = morpho(&[
        "graph",
        f.to_str().unwrap(),
        "--kind",
        "gamma",
        "--c0",
        "-0.2",
        "--c1",
        "0.4",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    assert_eq!(v["kind"], "gamma");
    assert_eq!(
        v["edges"].as_array().unwrap().len(),
        v["gamma"].as_array().unwrap().len()
    );
    // the hull of a rectangle with interior points: 4 edges
    let o = morpho(&[
        "graph",
        f.to_str().unwrap(),
        "--kind",
        "hull",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0));
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    assert_eq!(
        v["edges"],
        serde_json::json!([[0, 1], [0, 3], [1, 2], [2, 3]])
    );
    for args in [
        vec!["--kind", "nonsense"],
        vec!["--kind", "gamma", "--c0", "0.5", "--c1", "0.1"],
        vec!["--kind", "alpha"],
        vec!["--kind", "gamma-range", "--range", "1,2"],
    ] {
        let mut a = vec!["graph", f.to_str().unwrap()];
        a.extend(args.iter().copied());
        let x = d.join("x.json");
        a.extend(["-o", x.to_str().unwrap()]);
        let o = morpho(&a);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).starts_with("error: "));
    }
    for ext in ["svg", "ply"] {
        let out = d.join(format!("g.{ext}"));
        let o = morpho(&[
            "graph",
            f.to_str().unwrap(),
            "--kind",
            "gabriel",
            "-o",
            out.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    }
}

/// Issue 17 item 8: a 3D γ-graph with a parameter < 0 tests Θ(N³) candidate triples on
/// samples of a surface; above `--max-triples` (or MORPHO_TRIPLE_LIMIT, default 1e8) it is
/// refused at once with one `error:` line naming the limit, and nothing is written. The whole
/// fandisk (6 475 points, about 4.5·10¹⁰ triples, hours of work) is refused by default.
#[test]
fn gamma_below_zero_in_3d_is_refused_above_the_triple_limit() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // 64 points on the faces of a cube (every vertex open at c < 0)
    let mut txt = String::new();
    let mut r: u64 = 12345;
    for i in 0..64 {
        let mut q = [0.0f64; 3];
        for x in &mut q {
            r = r
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            *x = (r >> 11) as f64 / (1u64 << 53) as f64;
        }
        q[i % 3] = (i / 3 % 2) as f64;
        txt.push_str(&format!("{} {} {}\n", q[0], q[1], q[2]));
    }
    let f = write(d, "cube.xyz", txt.as_bytes());
    let out = d.join("g.json");
    let args = |extra: &[&str]| -> Vec<String> {
        let mut a: Vec<String> = ["graph", f.to_str().unwrap(), "--kind", "gamma"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        a.extend(["--c0=0", "--c1=-0.5", "-o", out.to_str().unwrap()].map(String::from));
        a.extend(extra.iter().map(|s| s.to_string()));
        a
    };
    let run = |a: Vec<String>, env: Option<&str>| {
        let mut c = Command::new(env!("CARGO_BIN_EXE_morpho"));
        c.args(&a).env_remove("MORPHO_TRIPLE_LIMIT");
        if let Some(v) = env {
            c.env("MORPHO_TRIPLE_LIMIT", v);
        }
        c.output().expect("run morpho")
    };
    let o = run(args(&[]), None);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    std::fs::remove_file(&out).unwrap();
    for (extra, env) in [
        (&["--max-triples", "100"][..], None),
        (&[][..], Some("100")),
        (&["--max-triples", "1e2"][..], Some("1e12")),
    ] {
        let o = run(args(extra), env);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{extra:?} {env:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(
            err.starts_with("error: ")
                && err.contains("limit of 100")
                && err.contains("--max-triples"),
            "{err}"
        );
        assert!(
            !out.exists(),
            "nothing is written when the graph is refused"
        );
    }
    let o = run(args(&["--max-triples", "lots"]), None);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).starts_with("error: ") && stderr(&o).contains("--max-triples"));
    // the whole fandisk: refused by default, before its triple loop
    let Some(data) = data_dir() else { return };
    let fan = data.join("meshes/fandisk.obj");
    let o = run(
        vec![
            "graph".into(),
            fan.to_str().unwrap().into(),
            "--kind".into(),
            "gamma".into(),
            "--c0=0".into(),
            "--c1=-0.5".into(),
            "-o".into(),
            out.to_str().unwrap().into(),
        ],
        None,
    );
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("candidate triples") && err.contains("limit of 100000000"),
        "{err}"
    );
    assert!(!out.exists());
}

/// A raw f32 volume of a sphere function with its JSON sidecar.
fn sphere_volume(dir: &Path, n: usize, dims_claimed: usize) -> PathBuf {
    let mut raw = Vec::new();
    let c = (n as f32 - 1.0) / 2.0;
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                let d = ((x as f32 - c).powi(2) + (y as f32 - c).powi(2) + (z as f32 - c).powi(2))
                    .sqrt();
                raw.extend_from_slice(&(c - d).to_le_bytes());
            }
        }
    }
    std::fs::write(dir.join("s.raw"), raw).unwrap();
    let side = format!(
        r#"{{"data":"s.raw","dims":[{d},{d},{d}],"spacing":[1,1,1],"origin":[0,0,0],"dtype":"f32","endian":"little"}}"#,
        d = dims_claimed
    );
    write(dir, &format!("s{dims_claimed}.json"), side.as_bytes())
}

#[test]
fn isosurface_command() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let vol = sphere_volume(d, 16, 16);
    let out = d.join("s.ply");
    let rep = d.join("r.json");
    let o = morpho(&[
        "isosurface",
        vol.to_str().unwrap(),
        "--level",
        "5",
        "-o",
        out.to_str().unwrap(),
        "--report",
        rep.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&rep).unwrap()).unwrap();
    assert_eq!(r["parts"], 1);
    assert_eq!(r["interior_holes"], 0);
    assert_eq!(
        r["boundary_edges"], 0,
        "a sphere inside the volume is closed"
    );
    assert!(r["triangles"].as_u64().unwrap() > 100);
    // io: the sidecar and its raw data file were read, the PLY written
    let len = |p: &Path| std::fs::metadata(p).unwrap().len();
    assert_eq!(r["io"]["read_bytes"], len(&vol) + len(&d.join("s.raw")));
    assert_eq!(r["io"]["write_bytes"], len(&out));
    assert!(r["io"]["write_mb_s"].as_f64().unwrap() > 0.0);
    // the written mesh is a closed genus-0 surface
    let rep2 = d.join("i.json");
    let o = morpho(&[
        "info",
        out.to_str().unwrap(),
        "--report",
        rep2.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let i: serde_json::Value = serde_json::from_slice(&std::fs::read(&rep2).unwrap()).unwrap();
    assert_eq!(i["genus"], 0);
    assert_eq!(i["boundary_loops"], 0);
    assert_eq!(i["euler_characteristic"], 2);
    // a level outside the data: empty mesh, a note, exit 0
    let o = morpho(&[
        "isosurface",
        vol.to_str().unwrap(),
        "--level",
        "1000",
        "-o",
        d.join("e.ply").to_str().unwrap(),
        "--report",
        rep.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&rep).unwrap()).unwrap();
    assert_eq!(r["triangles"], 0);
    assert!(r["note"].is_string());
    // dims that disagree with the data size: exit 2, no output
    let bad = sphere_volume(d, 16, 17);
    let o = morpho(&[
        "isosurface",
        bad.to_str().unwrap(),
        "--level",
        "5",
        "-o",
        d.join("b.ply").to_str().unwrap(),
    ]);
    // the error names the data file the sidecar points to, whose size is wrong
    assert_input_error(&o, &d.join("s.raw"));
    assert!(!d.join("b.ply").exists());
}

#[test]
fn contour_command() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // a 6 × 6 grid of samples with a high block in the middle
    let mut csv = String::from("x,y,zinc\n");
    for j in 0..6 {
        for i in 0..6 {
            let v = if (2..4).contains(&i) && (2..4).contains(&j) {
                900.0
            } else {
                100.0
            };
            csv.push_str(&format!(
                "{},{},{}\n",
                i as f64 + 0.01 * j as f64,
                j as f64 + 0.013 * i as f64,
                v
            ));
        }
    }
    let f = write(d, "s.csv", csv.as_bytes());
    let out = d.join("c.geojson");
    let rep = d.join("r.json");
    let o = morpho(&[
        "contour",
        f.to_str().unwrap(),
        "--value",
        "zinc",
        "--threshold",
        "500",
        "-o",
        out.to_str().unwrap(),
        "--report",
        rep.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&rep).unwrap()).unwrap();
    assert_eq!(r["samples"], 36);
    assert_eq!(r["components"], 1);
    assert_eq!(r["cycles"], 1);
    let g: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    assert_eq!(g["type"], "FeatureCollection");
    assert_eq!(g["features"][0]["geometry"]["type"], "Polygon");
    // the JSON cycles use input sample indices of the high block's neighbourhood
    let out = d.join("c.json");
    let o = morpho(&[
        "contour",
        f.to_str().unwrap(),
        "--value",
        "zinc",
        "--threshold",
        "500",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let c: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    assert!(!c["cycles"][0].as_array().unwrap().is_empty());
    // an unknown column: exit 2
    let o = morpho(&[
        "contour",
        f.to_str().unwrap(),
        "--value",
        "lead",
        "--threshold",
        "500",
        "-o",
        d.join("x.geojson").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).starts_with("error: "));
}

#[test]
fn info_check_reports_simplicity_and_closedness() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // a bow-tie ring (edges 0 and 2 cross) and a square
    let bow = write(
        d,
        "bow.geojson",
        br#"{"type":"Polygon","coordinates":[[[0,0],[2,2],[2,0],[0,2],[0,0]]]}"#,
    );
    let o = morpho(&["info", bow.to_str().unwrap(), "--check"]);
    assert_eq!(o.status.code(), Some(1), "{}", stdout(&o));
    assert!(stdout(&o).contains("edges 0 and 2 meet"), "{}", stdout(&o));
    let sq = write(
        d,
        "sq.geojson",
        br#"{"type":"Polygon","coordinates":[[[0,0],[2,0],[2,2],[0,2],[0,0]]]}"#,
    );
    let o = morpho(&["info", sq.to_str().unwrap(), "--check"]);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
    // a closed cube passes; the same cube with one face missing fails
    let cube = write(d, "cube.obj", CUBE_OBJ.as_bytes());
    let rep = d.join("r.json");
    let o = morpho(&[
        "info",
        cube.to_str().unwrap(),
        "--check",
        "--report",
        rep.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
    let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&rep).unwrap()).unwrap();
    assert_eq!(r["valid"], true);
    assert_eq!(r["closed_manifold"], true);
    let open: String = CUBE_OBJ
        .lines()
        .filter(|l| *l != "f 1 3 2")
        .map(|l| format!("{l}\n"))
        .collect();
    let open = write(d, "open.obj", open.as_bytes());
    let o = morpho(&["info", open.to_str().unwrap(), "--check"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stdout(&o).contains("closed 2-manifold: no"));
    // two cubes passing through each other: closed but self-intersecting
    let mut two = String::from(CUBE_OBJ);
    for l in CUBE_OBJ.lines().filter(|l| l.starts_with("v ")) {
        let c: Vec<f64> = l[2..]
            .split(' ')
            .map(|x| x.parse::<f64>().unwrap() + 0.5)
            .collect();
        two.push_str(&format!("v {} {} {}\n", c[0], c[1], c[2]));
    }
    for l in CUBE_OBJ.lines().filter(|l| l.starts_with("f ")) {
        let f: Vec<u32> = l[2..]
            .split(' ')
            .map(|x| x.parse::<u32>().unwrap() + 8)
            .collect();
        two.push_str(&format!("f {} {} {}\n", f[0], f[1], f[2]));
    }
    let two = write(d, "two.obj", two.as_bytes());
    let o = morpho(&["info", two.to_str().unwrap(), "--check"]);
    assert_eq!(o.status.code(), Some(1), "{}", stdout(&o));
    assert!(
        !stdout(&o).contains("self-intersections: none"),
        "{}",
        stdout(&o)
    );
}

#[test]
fn tetrahedra_as_vtk() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let f = write(
        d,
        "c.xyz",
        b"0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n1 1 1\n0.5 0.5 0.5\n",
    );
    let path = |n: &str| d.join(n).to_str().unwrap().to_string();
    for out in ["t.vtu", "t.vtk", "t.ply"] {
        let o = morpho(&[
            "triangulate",
            f.to_str().unwrap(),
            "--tets",
            "-o",
            &path(out),
        ]);
        assert_eq!(o.status.code(), Some(0), "{out}: {}", stderr(&o));
    }
    let has = |file: &str, what: &[u8]| {
        std::fs::read(d.join(file))
            .unwrap()
            .windows(what.len())
            .any(|w| w == what)
    };
    assert!(has("t.vtu", b"<VTKFile type=\"UnstructuredGrid\""));
    assert!(has(
        "t.vtu",
        b"<Piece NumberOfPoints=\"9\" NumberOfCells=\"12\">"
    ));
    assert!(has("t.vtu", b"<AppendedData encoding=\"raw\">"));
    assert!(has("t.vtk", b"# vtk DataFile Version 3.0\n"));
    assert!(has("t.vtk", b"\nBINARY\n"));
    assert!(has("t.vtk", b"\nCELLS 12 60\n"));
    // the hull surface without --tets: 12 triangles (cell type 5)
    let o = morpho(&["triangulate", f.to_str().unwrap(), "-o", &path("h.vtk")]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(has("h.vtk", b"\nCELLS 12 48\n"));
    // convert: the tetrahedral PLY to VTK, ASCII
    let o = morpho(&["convert", &path("t.ply"), "-o", &path("c.vtk"), "--ascii"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let c = std::fs::read_to_string(d.join("c.vtk")).unwrap();
    assert!(c.contains("\nASCII\n") && c.contains("\nCELLS 12 60\n4 "));
    assert_eq!(c.matches("\n10").count(), 12, "12 cells of type 10");
    // a triangle mesh converts to VTK too
    let o = morpho(&["convert", &path("h.vtk"), "-o", &path("x.vtu")]);
    assert_eq!(o.status.code(), Some(2), "VTK is written, not read");
}

/// Issue 17 item 5: `info --check` on a mesh with a face that repeats a vertex (`f 1 1 2`
/// added to a closed OBJ, or a binary STL with a sliver facet whose two corners coincide)
/// panicked with an index out of bounds in the pair test; now it reports the mesh as not a
/// closed 2-manifold, the degenerate face as meeting its neighbours, and exits 1.
#[test]
fn info_check_on_a_face_with_a_repeated_vertex_reports_instead_of_panicking() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let obj = write(d, "deg.obj", format!("{CUBE_OBJ}f 1 1 2\n").as_bytes());
    // the cube as a binary STL, plus one facet with two equal corners
    let (mut vs, mut fs) = (Vec::new(), Vec::new());
    for l in CUBE_OBJ.lines() {
        let w: Vec<&str> = l.split(' ').collect();
        match w[0] {
            "v" => vs.push([1, 2, 3].map(|k| w[k].parse::<f32>().unwrap())),
            "f" => fs.push([1, 2, 3].map(|k| w[k].parse::<usize>().unwrap() - 1)),
            _ => {}
        }
    }
    fs.push([0, 0, 1]);
    let mut stl = vec![0u8; 80];
    stl.extend((fs.len() as u32).to_le_bytes());
    for f in &fs {
        stl.extend([0u8; 12]); // normal
        for &v in f {
            for x in vs[v] {
                stl.extend(x.to_le_bytes());
            }
        }
        stl.extend([0u8; 2]);
    }
    let stl = write(d, "deg.stl", &stl);
    for f in [obj, stl] {
        let rep = d.join("r.json");
        let o = morpho(&[
            "info",
            f.to_str().unwrap(),
            "--check",
            "--report",
            rep.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(1), "{}{}", stdout(&o), stderr(&o));
        assert!(!stderr(&o).contains("panicked"), "{}", stderr(&o));
        assert!(
            stdout(&o).contains("closed 2-manifold: no"),
            "{}",
            stdout(&o)
        );
        let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&rep).unwrap()).unwrap();
        assert_eq!(r["valid"], false);
        // the face 1 1 2 is the cube's edge 1–2 doubled: it folds onto the two faces there
        let hits = r["self_intersections"].as_array().unwrap();
        assert_eq!(hits.len(), 2, "{hits:?}");
        assert!(hits.iter().all(|h| h[1] == 12), "{hits:?}");
    }
}

/// Points convert to and from GeoJSON (one `Point` feature per point, columns as numeric
/// properties) and keep their values; `--polygon` reads a CSV as a polygon instead; `--ascii`
/// applies to point PLY files too (it used to be ignored: points were always binary).
#[test]
fn points_and_polygons_convert_through_geojson_and_ascii_ply() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let csv = write(d, "s.csv", b"x,y,value\n0,0,1.5\n1,0,-2\n1,1,3\n0,1,4\n");
    let gj = d.join("s.geojson");
    let o = morpho(&["convert", csv.to_str().unwrap(), "-o", gj.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&gj).unwrap()).unwrap();
    let f = v["features"].as_array().unwrap();
    assert_eq!(f.len(), 4);
    assert_eq!(f[1]["geometry"]["type"], "Point");
    assert_eq!(f[1]["properties"]["value"], -2.0);
    let back = d.join("back.csv");
    let o = morpho(&[
        "convert",
        gj.to_str().unwrap(),
        "-o",
        back.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = std::fs::read_to_string(&back).unwrap();
    assert_eq!(text.lines().next(), Some("x,y,value"));
    assert_eq!(text.lines().count(), 5);
    assert!(text.contains("1,0,-2"), "{text}");

    let poly = d.join("p.geojson");
    let o = morpho(&[
        "convert",
        csv.to_str().unwrap(),
        "-o",
        poly.to_str().unwrap(),
        "--polygon",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&poly).unwrap()).unwrap();
    assert_eq!(v["features"][0]["geometry"]["type"], "Polygon");
    assert_eq!(
        v["features"][0]["geometry"]["coordinates"][0]
            .as_array()
            .unwrap()
            .len(),
        5
    );
    let o = morpho(&[
        "convert",
        gj.to_str().unwrap(),
        "-o",
        d.join("q.geojson").to_str().unwrap(),
        "--polygon",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).starts_with("error: "), "{}", stderr(&o));

    let ply = d.join("a.ply");
    let o = morpho(&[
        "convert",
        csv.to_str().unwrap(),
        "-o",
        ply.to_str().unwrap(),
        "--ascii",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let head = std::fs::read(&ply).unwrap();
    assert!(head.starts_with(b"ply\nformat ascii 1.0\n"));
}

// ---- morpho reduce (issue 21) ----

fn json(p: &Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(p).unwrap()).unwrap()
}

/// An n×n grid over [-1, 1]² as an ASCII PLY height field z = f(x, y), with vertex
/// properties `red green blue` (uchar, from the grid index) and `quality` (float, = z).
fn grid_ply(n: usize, f: impl Fn(f64, f64) -> f64) -> String {
    let mut s = format!(
        "ply\nformat ascii 1.0\nelement vertex {}\nproperty double x\nproperty double y\nproperty double z\n\
property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float quality\n\
element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        n * n,
        2 * (n - 1) * (n - 1)
    );
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (
                -1.0 + 2.0 * i as f64 / (n - 1) as f64,
                -1.0 + 2.0 * j as f64 / (n - 1) as f64,
            );
            let z = f(x, y);
            s += &format!(
                "{x} {y} {z} {} {} {} {z}\n",
                i % 256,
                j % 256,
                (i + j) % 256
            );
        }
    }
    let id = |i: usize, j: usize| j * n + i;
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            s += &format!("3 {} {} {}\n", id(i, j), id(i + 1, j), id(i + 1, j + 1));
            s += &format!("3 {} {} {}\n", id(i, j), id(i + 1, j + 1), id(i, j + 1));
        }
    }
    s
}

#[test]
fn reduce_real_scan_keeps_topology_and_reports() {
    let Some(data) = data_dir() else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    for (name, chi, loops) in [("bunny_npm.obj", 2, 0), ("stanford-bunny.obj.gz", -3, 5)] {
        let input = data.join("meshes").join(name);
        let out = dir.path().join("out.ply");
        let rep = dir.path().join("r.json");
        let o = morpho(&[
            "reduce",
            input.to_str().unwrap(),
            "--keep",
            "25",
            "-o",
            out.to_str().unwrap(),
            "--check",
            "--report",
            rep.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(0), "{name}: {}", stderr(&o));
        let r = json(&rep);
        let tin = r["triangles_in"].as_u64().unwrap();
        let tout = r["triangles_out"].as_u64().unwrap();
        assert!(tout <= tin / 4 && tout > tin / 5, "{name}: {tin} → {tout}");
        assert_eq!(r["euler_characteristic"], chi, "{name}");
        assert_eq!(r["boundary_loops"], loops, "{name}");
        assert_eq!(r["parts"], 1, "{name}");
        assert_eq!(r["manifold"], true, "{name}");
        assert_eq!(r["consistently_oriented"], true, "{name}");
        assert_eq!(r["self_intersections"], 0, "{name}");
        assert_eq!(r["no_removable_left"], false, "{name}");
        assert_eq!(r["stop"], "target", "{name}");
        let (rms, h) = (r["rms"].as_f64().unwrap(), r["hausdorff"].as_f64().unwrap());
        assert!(rms > 0.0 && rms <= h, "{name}: rms {rms} hausdorff {h}");
        for k in ["read", "compute", "measure", "write"] {
            assert!(r["timings"][k].as_f64().is_some(), "{name}: timing {k}");
        }
        assert!(r["triangles_per_second"].as_f64().unwrap() > 0.0);
        // the written mesh is what the report says
        let m = morpho::io::read_mesh(&out).unwrap();
        assert_eq!(m.triangles.len() as u64, tout);
        let t = morpho::mesh::analyze_topology(&m);
        assert_eq!(t.euler_characteristic, chi);
        if chi == 2 {
            assert_eq!(t.genus(), Some(0));
            assert_eq!(r["genus"], 0);
        }
    }
}

#[test]
fn reduce_keeps_ply_vertex_properties_of_surviving_vertices() {
    let dir = tempfile::tempdir().unwrap();
    // a plane: new points stay on it, so the interpolated `quality` (= z) stays exact
    let f = write(
        dir.path(),
        "plane.ply",
        grid_ply(21, |x, y| 0.2 * x + 0.3 * y).as_bytes(),
    );
    let out = dir.path().join("out.ply");
    let rep = dir.path().join("r.json");
    let o = morpho(&[
        "reduce",
        f.to_str().unwrap(),
        "--keep",
        "30",
        "--height-field",
        "-o",
        out.to_str().unwrap(),
        "--report",
        rep.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let input = morpho::io::read_mesh(&f).unwrap();
    let m = morpho::io::read_mesh(&out).unwrap();
    assert!(m.triangles.len() <= 240);
    let names: Vec<&str> = m.vertex_props.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["red", "green", "blue", "quality"]);
    let prop = |mesh: &morpho::mesh::TriMesh, name: &str| {
        mesh.vertex_props
            .iter()
            .find(|p| p.name == name)
            .unwrap()
            .values
            .clone()
    };
    let (q, red, green) = (prop(&m, "quality"), prop(&m, "red"), prop(&m, "green"));
    let (red_in, green_in) = (prop(&input, "red"), prop(&input, "green"));
    let mut kept = 0;
    for (i, p) in m.positions.iter().enumerate() {
        assert!((q[i] - p.z).abs() < 1e-6, "quality {} at z {}", q[i], p.z);
        assert!((p.z - (0.2 * p.x + 0.3 * p.y)).abs() < 1e-12);
        assert_eq!(red[i].fract(), 0.0);
        if let Some(s) = input.positions.iter().position(|x| x == p) {
            assert_eq!((red[i], green[i]), (red_in[s], green_in[s]), "vertex {i}");
            kept += 1;
        }
    }
    let r = json(&rep);
    assert!(kept > 0);
    // a new point may land on an input vertex (a domain corner of the plane): it is
    // interpolated there, to the same values
    let interpolated = r["vertices_interpolated"].as_u64().unwrap() as usize;
    assert!(interpolated >= m.positions.len() - kept && interpolated < m.positions.len());
    assert!(r["rms"].as_f64().unwrap() < 1e-12);
}

#[test]
fn reduce_tolerance_and_open_boundaries() {
    let dir = tempfile::tempdir().unwrap();
    let f = write(
        dir.path(),
        "bowl.ply",
        grid_ply(31, |x, y| 0.4 * (x * x + y * y)).as_bytes(),
    );
    let out = dir.path().join("out.ply");
    let rep = dir.path().join("r.json");
    let run = |extra: &[&str]| {
        let mut a = vec!["reduce", f.to_str().unwrap(), "-o", out.to_str().unwrap()];
        a.extend_from_slice(extra);
        a.extend_from_slice(&["--report", rep.to_str().unwrap()]);
        let o = morpho(&a);
        assert_eq!(o.status.code(), Some(0), "{extra:?}: {}", stderr(&o));
        json(&rep)
    };
    // (5.41)-style vertical RMS tolerance on the height field
    let r = run(&["--rms", "0.002", "--height-field"]);
    assert_eq!(r["stop"], "tolerance");
    assert!(r["rms"].as_f64().unwrap() <= 0.002);
    assert!(r["triangles_out"].as_u64().unwrap() < 1800);
    // the same tolerance as a surface (distance to the reduced surface)
    let r = run(&["--tolerance", "0.002"]);
    assert_eq!(r["stop"], "tolerance");
    assert!(r["rms"].as_f64().unwrap() <= 0.002);
    assert_eq!(r["boundary_loops"], 1);
    assert_eq!(r["euler_characteristic"], 1);
    // frozen boundary: all 120 boundary vertices stay where they were
    let r = run(&["--triangles", "400", "--freeze-boundary"]);
    assert_eq!(r["boundary_loops"], 1);
    let m = morpho::io::read_mesh(&out).unwrap();
    let t = morpho::mesh::analyze_topology(&m);
    assert_eq!(t.boundary_loops[0].len(), 120);
    for &v in &t.boundary_loops[0] {
        let p = m.positions[v as usize];
        assert!(
            p.x.abs() == 1.0 || p.y.abs() == 1.0,
            "{p:?} left the boundary"
        );
    }
}

#[test]
fn reduce_stops_early_when_nothing_is_removable() {
    let dir = tempfile::tempdir().unwrap();
    let tet = write(
        dir.path(),
        "tet.obj",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n",
    );
    let out = dir.path().join("out.obj");
    let rep = dir.path().join("r.json");
    let o = morpho(&[
        "reduce",
        tet.to_str().unwrap(),
        "--triangles",
        "2",
        "-o",
        out.to_str().unwrap(),
        "--report",
        rep.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stderr(&o).contains("note: no removable triangle left"));
    let r = json(&rep);
    assert_eq!(r["no_removable_left"], true);
    assert_eq!(r["stop"], "no_removable_left");
    assert_eq!(r["triangles_out"], 4);
}

#[test]
fn reduce_bad_input_exits_2() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let out = d.join("out.ply");
    let o_ = out.to_str().unwrap();
    let cube = write(d, "cube.obj", CUBE_OBJ.as_bytes());
    let fin = write(
        d,
        "fin.obj",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n",
    );
    let flip = write(
        d,
        "flip.obj",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nf 1 2 3\nf 1 2 4\n",
    );
    let nan = write(d, "nan.obj", b"v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n");
    let empty = write(d, "empty.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    for (file, extra) in [
        (&fin, vec!["--keep", "50"]),
        (&flip, vec!["--keep", "50"]),
        (&nan, vec!["--keep", "50"]),
        (&empty, vec!["--keep", "50"]),
        (&cube, vec!["--keep", "0"]),
        (&cube, vec!["--keep", "100.5"]),
        (&cube, vec!["--keep", "-5"]),
        (&cube, vec!["--triangles", "13"]),
        (&cube, vec!["--rms", "-1"]),
        (&cube, vec!["--keep", "50", "--height-field"]),
    ] {
        let mut a = vec!["reduce", file.to_str().unwrap(), "-o", o_];
        a.extend(extra.iter().copied());
        let o = morpho(&a);
        assert_input_error(&o, file);
        assert!(!out.exists(), "{extra:?}: output written");
    }
    // usage: no stop, two stops, an output that is not a mesh
    for extra in [
        vec![],
        vec!["--keep", "50", "--triangles", "4"],
        vec!["--keep", "50", "-o", "x.csv"],
    ] {
        let mut a = vec!["reduce", cube.to_str().unwrap()];
        if !extra.contains(&"-o") {
            a.extend(["-o", o_]);
        }
        a.extend(extra.iter().copied());
        let o = morpho(&a);
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {}", stderr(&o));
        assert!(stderr(&o).starts_with("error: "), "{}", stderr(&o));
        assert!(!stderr(&o).contains("panicked"));
    }
    assert_only(
        d,
        &["cube.obj", "fin.obj", "flip.obj", "nan.obj", "empty.obj"],
    );
}
