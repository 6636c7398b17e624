//! `morpho curvature`: PLY/CSV columns k1,k2,H,K,A, a plane's zero curvature, a volume's five
//! NRRD fields on the input grid, and bad input refused with `error:` and exit 2.
use std::path::Path;
use std::process::{Command, Output};

fn morpho(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_morpho"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("run morpho")
}

/// An n×n grid of the plane z = 0.3x − 0.2y + 1 (tilted, so no coordinate is special).
fn plane(dir: &Path, n: usize) {
    let mut s = String::new();
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (i as f64 * 0.1, j as f64 * 0.1 + 0.013 * (i % 3) as f64);
            s.push_str(&format!("v {x} {y} {}\n", 0.3 * x - 0.2 * y + 1.0));
        }
    }
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let a = j * n + i + 1;
            s.push_str(&format!(
                "f {} {} {}\nf {} {} {}\n",
                a,
                a + 1,
                a + n + 1,
                a,
                a + n + 1,
                a + n
            ));
        }
    }
    std::fs::write(dir.join("plane.obj"), s).unwrap();
}

#[test]
fn a_plane_has_zero_curvature_in_every_column() {
    let dir = tempfile::tempdir().unwrap();
    plane(dir.path(), 12);
    for ring in ["1", "2"] {
        let o = morpho(
            dir.path(),
            &[
                "curvature",
                "plane.obj",
                "-o",
                "c.csv",
                "--ring",
                ring,
                "--report",
                "r.json",
            ],
        );
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let text = std::fs::read_to_string(dir.path().join("c.csv")).unwrap();
        let mut lines = text.lines();
        assert_eq!(lines.next().unwrap(), "x,y,z,index,k1,k2,H,K,A");
        let mut determined = 0;
        for l in lines {
            for v in l.split(',').skip(4) {
                if v.is_empty() {
                    continue; // undetermined (NaN is an empty CSV cell)
                }
                let v: f64 = v.parse().unwrap();
                if v.is_finite() {
                    assert!(v.abs() < 1e-9, "ring {ring}: {l}");
                    determined += 1;
                }
            }
        }
        assert!(determined >= 5 * 100, "ring {ring}: {determined}");
        let r: serde_json::Value =
            serde_json::from_slice(&std::fs::read(dir.path().join("r.json")).unwrap()).unwrap();
        assert_eq!(r["vertices"], 144);
    }
    let o = morpho(dir.path(), &["curvature", "plane.obj", "-o", "c.ply"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let ply = std::fs::read(dir.path().join("c.ply")).unwrap();
    let head = String::from_utf8_lossy(&ply[..600.min(ply.len())]).into_owned();
    for p in ["k1", "k2", "H", "K", "A"] {
        assert!(head.contains(&format!(" {p}\n")), "{p}: {head}");
    }
}

#[test]
fn a_volume_gives_five_fields_on_its_grid() {
    let dir = tempfile::tempdir().unwrap();
    // f = x² + 2y² + 3z² on a 6×5×4 grid (raw + JSON sidecar)
    let (nx, ny, nz) = (6usize, 5usize, 4usize);
    let mut raw = Vec::new();
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                let (x, y, z) = (i as f32 * 0.5, j as f32 * 0.5, k as f32 * 0.5);
                raw.extend_from_slice(&(x * x + 2.0 * y * y + 3.0 * z * z).to_le_bytes());
            }
        }
    }
    std::fs::write(dir.path().join("f.raw"), raw).unwrap();
    std::fs::write(
        dir.path().join("f.json"),
        r#"{"data":"f.raw","dims":[6,5,4],"dtype":"float32","spacing":[0.5,0.5,0.5]}"#,
    )
    .unwrap();
    let o = morpho(dir.path(), &["curvature", "f.json", "-o", "out"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for f in ["k1", "k2", "k3", "H", "K"] {
        let o = morpho(dir.path(), &["info", &format!("out/{f}.nrrd")]);
        let text = String::from_utf8_lossy(&o.stdout).into_owned();
        assert!(text.contains("dims: 6 x 5 x 4"), "{f}: {text}");
        assert!(text.contains("spacing: 0.5 x 0.5 x 0.5"), "{f}: {text}");
    }
    // a volume with one sample along an axis is refused
    std::fs::write(dir.path().join("flat.raw"), vec![0u8; 6 * 5 * 4]).unwrap();
    std::fs::write(
        dir.path().join("flat.json"),
        r#"{"data":"flat.raw","dims":[6,5,1],"dtype":"float32"}"#,
    )
    .unwrap();
    let o = morpho(dir.path(), &["curvature", "flat.json", "-o", "out2"]);
    assert_eq!(
        o.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

#[test]
fn bad_input_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    plane(dir.path(), 4);
    std::fs::write(
        dir.path().join("nan.obj"),
        "v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n",
    )
    .unwrap();
    for args in [
        &["curvature", "plane.obj", "-o", "c.stl"][..],
        &["curvature", "plane.obj", "-o", "c.ply", "--ring", "0"][..],
        &["curvature", "plane.obj", "-o", "c.ply", "--normals", "file"][..],
        &["curvature", "nan.obj", "-o", "c.ply"][..],
        &["curvature", "plane.obj", "-o", "plane.obj"][..],
    ] {
        let o = morpho(dir.path(), args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.starts_with("error: "), "{args:?}: {err}");
    }
}

fn report(dir: &Path, name: &str) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(dir.join(name)).unwrap()).unwrap()
}

/// The default (the jet's curvature over the 2-ring), the previous default (jet normals +
/// 1-ring paraboloid) and the thesis's method by flag, named in the report; `--fit quadric`
/// and `--fit jet` default to the 2-ring (the jet needs at least 2).
#[test]
fn default_thesis_and_quadric_are_reported() {
    let dir = tempfile::tempdir().unwrap();
    plane(dir.path(), 8);
    for (args, normals, fit, ring) in [
        (&[][..], "jet", "jet", 2),
        (&["--ring", "1"][..], "jet", "jet", 2),
        (&["--fit", "paraboloid"][..], "jet", "paraboloid", 1),
        (&["--normals", "area"][..], "area", "paraboloid", 1),
        (&["--normals", "area", "--fit", "jet"][..], "area", "jet", 2),
        (&["--fit", "quadric"][..], "jet", "quadric", 2),
        (
            &["--fit", "quadric", "--ring", "3"][..],
            "jet",
            "quadric",
            3,
        ),
    ] {
        let mut a = vec![
            "curvature",
            "plane.obj",
            "-o",
            "c.csv",
            "--report",
            "r.json",
        ];
        a.extend_from_slice(args);
        let o = morpho(dir.path(), &a);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let r = report(dir.path(), "r.json");
        assert_eq!(r["normals"], normals, "{args:?}");
        assert_eq!(r["fit"], fit, "{args:?}");
        assert_eq!(r["ring"], ring, "{args:?}");
        assert_eq!(
            r.get("jet_fallbacks").is_some(),
            normals == "jet" || fit == "jet"
        );
        // a plane: every determined value is 0
        for q in ["k1", "k2", "H", "K"] {
            for k in ["min", "max"] {
                assert!(r[q][k].as_f64().unwrap().abs() < 1e-9, "{args:?} {q} {k}");
            }
        }
    }
}

/// Non-manifold vertices, isolated vertices and zero-area triangles are a documented result
/// (exit 0, undetermined vertices counted and NaN/empty), not an error.
#[test]
fn non_manifold_isolated_and_zero_area_are_counted() {
    let dir = tempfile::tempdir().unwrap();
    let mut s = String::from("v 0 0 0\n");
    for fan in 0..2 {
        for i in 0..8 {
            let t = i as f64 * std::f64::consts::TAU / 8.0;
            s.push_str(&format!(
                "v {} {} {}\n",
                t.cos(),
                t.sin(),
                0.2 * fan as f64 - 0.1
            ));
        }
    }
    s.push_str("v 5 5 5\nv 7 0 0\nv 8 0 0\nv 9 0 0\n");
    for fan in 0..2 {
        for i in 0..8 {
            let b = 2 + 8 * fan;
            s.push_str(&format!("f 1 {} {}\n", b + i, b + (i + 1) % 8));
        }
    }
    s.push_str("f 19 20 21\n");
    std::fs::write(dir.path().join("bad.obj"), s).unwrap();
    for normals in ["jet", "area"] {
        let o = morpho(
            dir.path(),
            &[
                "curvature",
                "bad.obj",
                "-o",
                "c.csv",
                "--normals",
                normals,
                "--report",
                "r.json",
            ],
        );
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let r = report(dir.path(), "r.json");
        assert_eq!(r["vertices"], 21);
        // the isolated vertex and the three of the zero-area triangle at least
        assert!(r["undetermined"].as_u64().unwrap() >= 4, "{r}");
        let csv = std::fs::read_to_string(dir.path().join("c.csv")).unwrap();
        let empty = csv
            .lines()
            .skip(1)
            .filter(|l| l.split(',').nth(6) == Some(""))
            .count() as u64;
        assert_eq!(empty, r["undetermined"].as_u64().unwrap(), "{csv}");
    }
}

/// An open cylinder of radius 2 around the z axis (24 × 13 vertices, height 3).
fn cylinder(dir: &Path) {
    let (n, m) = (24usize, 13usize);
    let mut s = String::new();
    for j in 0..m {
        for i in 0..n {
            let t = i as f64 * std::f64::consts::TAU / n as f64;
            s.push_str(&format!(
                "v {} {} {}\n",
                2.0 * t.cos(),
                2.0 * t.sin(),
                j as f64 * 0.25
            ));
        }
    }
    for j in 0..m - 1 {
        for i in 0..n {
            let a = j * n + i + 1;
            let b = j * n + (i + 1) % n + 1;
            s.push_str(&format!("f {a} {b} {}\nf {a} {} {}\n", b + n, b + n, a + n));
        }
    }
    std::fs::write(dir.join("cyl.obj"), s).unwrap();
}

/// `--directions`: six more columns; on a cylinder the direction of the curvature nearer 0 runs
/// along the axis and the other around it, both unit and orthogonal (at the vertices two rings
/// away from the open ends); NaN where undetermined; refused for volumes.
#[test]
fn directions_follow_the_cylinder() {
    let dir = tempfile::tempdir().unwrap();
    cylinder(dir.path());
    for normals in ["jet", "area"] {
        let o = morpho(
            dir.path(),
            &[
                "curvature",
                "cyl.obj",
                "-o",
                "c.csv",
                "--directions",
                "--normals",
                normals,
            ],
        );
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let text = std::fs::read_to_string(dir.path().join("c.csv")).unwrap();
        let mut lines = text.lines();
        assert_eq!(
            lines.next().unwrap(),
            "x,y,z,index,k1,k2,H,K,A,d1x,d1y,d1z,d2x,d2y,d2z"
        );
        let mut checked = 0;
        for l in lines {
            let v: Vec<f64> = l
                .split(',')
                .map(|x| x.parse().unwrap_or(f64::NAN))
                .collect();
            let (z, k1, k2) = (v[2], v[4], v[5]);
            let (d1, d2) = ([v[9], v[10], v[11]], [v[12], v[13], v[14]]);
            if k1.is_nan() {
                assert!(d1.iter().chain(&d2).all(|x| x.is_nan()), "{l}");
                continue;
            }
            if !(0.4..=2.6).contains(&z) {
                continue;
            }
            let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
            assert!(
                (dot(d1, d1) - 1.0).abs() < 1e-9 && (dot(d2, d2) - 1.0).abs() < 1e-9,
                "{l}"
            );
            assert!(dot(d1, d2).abs() < 1e-9, "{l}");
            let (axis, around) = if k1.abs() < k2.abs() {
                (d1, d2)
            } else {
                (d2, d1)
            };
            assert!(axis[2].abs() > 0.99, "{normals}: {l}");
            assert!(around[2].abs() < 0.1, "{normals}: {l}");
            // around the axis: orthogonal to the radius (x, y)
            assert!(
                (around[0] * v[0] + around[1] * v[1]).abs() < 0.1 * 2.0,
                "{normals}: {l}"
            );
            checked += 1;
        }
        assert!(checked >= 24 * 8, "{normals}: {checked}");
    }
    let o = morpho(
        dir.path(),
        &["curvature", "cyl.obj", "-o", "c.ply", "--directions"],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let ply = std::fs::read(dir.path().join("c.ply")).unwrap();
    let head = String::from_utf8_lossy(&ply[..800.min(ply.len())]).into_owned();
    for p in ["k1", "A", "d1x", "d1y", "d1z", "d2x", "d2y", "d2z"] {
        assert!(head.contains(&format!(" {p}\n")), "{p}: {head}");
    }
    let o = morpho(dir.path(), &["curvature", "cyl.obj", "-o", "plain.ply"]);
    assert!(o.status.success());
    let plain = std::fs::read(dir.path().join("plain.ply")).unwrap();
    assert!(!String::from_utf8_lossy(&plain[..600.min(plain.len())]).contains("d1x"));
    let o = morpho(
        dir.path(),
        &["curvature", "v.nrrd", "-o", "out", "--directions"],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--directions"));
}
