//! End-to-end tests of `morpho triangulate --constraints` (constrained Delaunay triangulation):
//! outputs, the constrained edges, `error:` lines and exit codes on bad constraint files and
//! crossing segments.

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

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

/// Exit code 2 and exactly one `error:` line containing every `needle`.
fn assert_one_error(o: &Output, needles: &[&str]) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 1, "exactly one line expected: {err}");
    assert!(lines[0].starts_with("error: "), "{err}");
    for n in needles {
        assert!(lines[0].contains(n), "error should contain {n}: {err}");
    }
    assert!(!err.contains("panicked"), "{err}");
}

/// A 4 × 3 grid (x = 0..3, y = 0..2), index = y·4 + x, plus a duplicate of point 0.
const GRID: &[u8] = b"x,y\n0,0\n1,0\n2,0\n3,0\n0,1\n1,1\n2,1\n3,1\n0,2\n1,2\n2,2\n3,2\n0,0\n";

#[test]
fn constrained_json_svg_and_mesh() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let p = write(d, "p.csv", GRID);
    // the middle row end to end (through 5 and 6), a diagonal ending on it, a duplicate, a
    // comment
    let s = write(d, "s.csv", b"# segments\n4,7\n\n0 6\n7,4\n");
    let out = d.join("t.json");
    let rep = d.join("r.json");
    let o = morpho(&[
        "triangulate",
        p.to_str().unwrap(),
        "--constraints",
        s.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--report",
        rep.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    let tris = v["triangles"].as_array().unwrap();
    assert_eq!(tris.len(), 2 * 12 - 10 - 2, "Euler: 2n − h − 2");
    let mut cons: Vec<[u64; 2]> = v["constrained"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| {
            let a = e[0].as_u64().unwrap();
            let b = e[1].as_u64().unwrap();
            [a.min(b), a.max(b)]
        })
        .collect();
    cons.sort_unstable();
    // row 4-5-6-7 split at 5 and 6; 0-6 from (0,0) to (2,1) passes through no point
    assert_eq!(cons, vec![[0, 6], [4, 5], [5, 6], [6, 7]]);
    let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&rep).unwrap()).unwrap();
    let s = r.to_string();
    // 4,7 and its duplicate 7,4 are each split at 5 and 6
    assert_eq!(r["splits"], 4, "{s}");
    assert_eq!(r["constrained_edges"], 4, "{s}");

    let svg = d.join("t.svg");
    let o = morpho(&[
        "triangulate",
        p.to_str().unwrap(),
        "--constraints",
        d.join("s.csv").to_str().unwrap(),
        "-o",
        svg.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(
        text.contains("stroke-width=\"2.6\""),
        "constrained edges drawn bold"
    );

    let ply = d.join("t.ply");
    let o = morpho(&[
        "triangulate",
        p.to_str().unwrap(),
        "--constraints",
        d.join("s.csv").to_str().unwrap(),
        "-o",
        ply.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(std::fs::metadata(&ply).unwrap().len() > 0);
}

#[test]
fn bad_constraint_files_are_one_error_line() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let p = write(d, "p.csv", GRID);
    let out = d.join("t.json");
    let run = |s: &Path| {
        morpho(&[
            "triangulate",
            p.to_str().unwrap(),
            "--constraints",
            s.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ])
    };
    for (name, body, needle) in [
        ("three.csv", &b"0,1\n1,2,3\n"[..], "line 2"),
        ("word.csv", &b"0,1\n\nx,y\n"[..], "line 3"),
        ("neg.csv", &b"-1,2\n"[..], "line 1"),
        ("one.csv", &b"5\n"[..], "line 1"),
    ] {
        let s = write(d, name, body);
        let o = run(&s);
        assert_one_error(&o, &[name, needle]);
    }
    // crossing segments ((1,0)-(2,2) meets the row at x = 1.5): both named
    let s = write(d, "cross.csv", b"4,7\n1,10\n");
    let o = run(&s);
    assert_one_error(&o, &["cross", "0 (4, 7)", "1 (1, 10)"]);
    // index out of range
    let s = write(d, "range.csv", b"0,99\n");
    let o = run(&s);
    assert_one_error(&o, &["99"]);
    assert!(!out.exists(), "no output on errors");
    // 3D points with constraints: usage error
    let p3 = write(d, "p3.csv", b"x,y,z\n0,0,0\n1,0,0\n0,1,0\n0,0,1\n");
    let s = write(d, "ok.csv", b"0,1\n");
    let o = morpho(&[
        "triangulate",
        p3.to_str().unwrap(),
        "--constraints",
        s.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_one_error(&o, &["--constraints"]);
}
