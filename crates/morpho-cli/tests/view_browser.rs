//! Issue 22 part 3: `morpho view` pages opened in headless Chromium (SwiftShader). The page's
//! `#selftest=` hook runs a scripted orbit and a pick and writes JSON into the DOM, which
//! `--dump-dom` returns. Chromium missing: installed with apt-get when root, else the test fails.

use std::path::Path;
use std::process::Command;

fn chromium() -> &'static str {
    if Command::new("chromium").arg("--version").output().is_err() {
        let root = Command::new("id")
            .arg("-u")
            .output()
            .map(|o| o.stdout == b"0\n")
            .unwrap_or(false);
        assert!(root, "chromium is not installed (apt-get install -y chromium as root); the browser tests cannot run");
        let ok = Command::new("apt-get")
            .args(["install", "-y", "chromium"])
            .status()
            .map(|s| s.success())
            .unwrap_or(false);
        assert!(ok, "installing chromium with apt-get failed");
    }
    "chromium"
}

/// A UV sphere of radius 1 as OBJ text.
fn sphere_obj(n: usize) -> String {
    let mut s = String::from("v 0 0 1\n");
    for i in 1..n {
        let th = std::f64::consts::PI * i as f64 / n as f64;
        for j in 0..2 * n {
            let ph = std::f64::consts::PI * j as f64 / n as f64;
            s += &format!(
                "v {} {} {}\n",
                th.sin() * ph.cos(),
                th.sin() * ph.sin(),
                th.cos()
            );
        }
    }
    s += "v 0 0 -1\n";
    let m = 2 * n;
    let id = |i: usize, j: usize| 2 + (i - 1) * m + j % m; // 1-based
    for j in 0..m {
        s += &format!("f 1 {} {}\n", id(1, j), id(1, j + 1));
        let last = 2 + (n - 1) * m;
        s += &format!("f {} {} {}\n", last, id(n - 1, j + 1), id(n - 1, j));
    }
    for i in 1..n - 1 {
        for j in 0..m {
            s += &format!("f {} {} {}\n", id(i, j), id(i + 1, j), id(i + 1, j + 1));
            s += &format!("f {} {} {}\n", id(i, j), id(i + 1, j + 1), id(i, j + 1));
        }
    }
    s
}

fn selftest(page: &Path, steps: &str, profile: &Path) -> serde_json::Value {
    let url = format!("file://{}#selftest={steps}", page.display());
    let out = Command::new(chromium())
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--use-angle=swiftshader",
            "--enable-unsafe-swiftshader",
            "--window-size=1024,768",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .args(["--dump-dom", &url])
        .output()
        .expect("chromium runs");
    let dom = String::from_utf8_lossy(&out.stdout);
    let tag = "<pre id=\"morpho-selftest\">";
    let start = dom.find(tag).expect("selftest element") + tag.len();
    let end = start + dom[start..].find('<').unwrap();
    let text = dom[start..end]
        .replace("&quot;", "\"")
        .replace("&amp;", "&");
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("selftest output {text:?}: {e}"))
}

#[test]
fn mesh_page_renders_orbits_and_picks_in_chromium() {
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("s.obj");
    std::fs::write(&obj, sphere_obj(24)).unwrap();
    let ply = dir.path().join("s.ply");
    let page = dir.path().join("s.html");
    let bin = env!("CARGO_BIN_EXE_morpho");
    let st = Command::new(bin)
        .arg("curvature")
        .arg(&obj)
        .arg("-o")
        .arg(&ply)
        .status()
        .unwrap();
    assert!(st.success());
    let st = Command::new(bin)
        .arg("view")
        .arg(&ply)
        .arg("-o")
        .arg(&page)
        .status()
        .unwrap();
    assert!(st.success());
    let r = selftest(&page, "orbit,pick:300", &dir.path().join("profile"));
    assert_eq!(r["errors"], serde_json::json!([]), "console errors: {r}");
    assert!(
        r["before"]["foreground"].as_f64().unwrap() > 0.02,
        "blank canvas: {r}"
    );
    assert!(
        r["changed"].as_f64().unwrap() > 0.001,
        "orbit changed nothing: {r}"
    );
    assert_eq!(r["pick"]["vertex"], 300, "{r}");
    // the unit sphere (outward) has H = -1 and K = 1 by morpho's convention
    let h = r["pick"]["values"]["H"].as_f64().unwrap();
    let k = r["pick"]["values"]["K"].as_f64().unwrap();
    assert!(
        (h + 1.0).abs() < 0.05 && (k - 1.0).abs() < 0.1,
        "picked H {h}, K {k}"
    );
}

/// A float32 volume as a detached NRRD header (spacing and origin given) and raw data.
fn nrrd(
    dir: &Path,
    name: &str,
    dims: [usize; 3],
    spacing: [f64; 3],
    origin: [f64; 3],
    f: impl Fn([f64; 3]) -> f32,
) -> std::path::PathBuf {
    let mut raw = Vec::new();
    for k in 0..dims[2] {
        for j in 0..dims[1] {
            for i in 0..dims[0] {
                let p = [
                    origin[0] + i as f64 * spacing[0],
                    origin[1] + j as f64 * spacing[1],
                    origin[2] + k as f64 * spacing[2],
                ];
                raw.extend(f(p).to_le_bytes());
            }
        }
    }
    std::fs::write(dir.join(format!("{name}.raw")), raw).unwrap();
    let h = dir.join(format!("{name}.nhdr"));
    std::fs::write(
        &h,
        format!(
            "NRRD0004\ntype: float\ndimension: 3\nsizes: {} {} {}\nspacings: {} {} {}\n\
             axis mins: {} {} {}\nendian: little\nencoding: raw\ndata file: {name}.raw\n",
            dims[0],
            dims[1],
            dims[2],
            spacing[0],
            spacing[1],
            spacing[2],
            origin[0],
            origin[1],
            origin[2]
        ),
    )
    .unwrap();
    h
}

fn view(args: &[&Path]) -> std::process::Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_morpho"));
    c.arg("view");
    for a in args {
        c.arg(a);
    }
    c.output().unwrap()
}

/// f(x, y, z) = 2x − 0.5y + 0.25z: bilinear interpolation on a slice is exact, so a picked
/// slice pixel must report f at the picked world point to within half a quantization step.
fn linear(p: [f64; 3]) -> f64 {
    2.0 * p[0] - 0.5 * p[1] + 0.25 * p[2]
}

#[test]
fn volume_page_shows_three_movable_slices_and_picks_sample_values_in_chromium() {
    let dir = tempfile::tempdir().unwrap();
    let (dims, spacing, origin) = ([40, 30, 20], [0.5, 1.0, 2.0], [-3.0, 1.0, 5.0]);
    let h = nrrd(dir.path(), "lin", dims, spacing, origin, |p| {
        linear(p) as f32
    });
    let page = dir.path().join("lin.html");
    let o = view(&[&h, Path::new("-o"), &page]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r = selftest(
        &page,
        "orbit,slice:0:3,slice:2:17,vpick:0.5:0.5,vpick:0.45:0.6,vpick:0.55:0.42,vpick:0.4:0.35",
        &dir.path().join("profile"),
    );
    assert_eq!(r["errors"], serde_json::json!([]), "console errors: {r}");
    // the slices are drawn, through the colour map (many colours, not one grey)
    assert!(r["before"]["foreground"].as_f64().unwrap() > 0.05, "{r}");
    assert!(r["before"]["colours"].as_u64().unwrap() >= 8, "{r}");
    assert!(r["changed"].as_f64().unwrap() > 0.01, "orbit: {r}");
    // moving a slice moves it in world coordinates (origin + index·spacing) and changes the picture
    for (s, (axis, index)) in r["slices"]
        .as_array()
        .unwrap()
        .iter()
        .zip([(0, 3), (2, 17)])
    {
        assert_eq!(s["index"], index, "{s}");
        let want = origin[axis] + index as f64 * spacing[axis];
        assert!(
            (s["position"].as_f64().unwrap() - want).abs() < 1e-12,
            "{s}"
        );
        assert!(s["changed"].as_f64().unwrap() > 0.005, "slice move: {s}");
    }
    // picks: on a slice plane, inside the box, the value f(point)
    let (lo, hi) = (linear([-3.0, 30.0, 5.0]), linear([16.5, 1.0, 43.0]));
    let step = (hi - lo) / 65534.0;
    let mut hits = 0;
    for p in r["vpick"].as_array().unwrap() {
        if p.is_null() {
            continue;
        }
        hits += 1;
        let x: Vec<f64> = (0..3).map(|k| p["point"][k].as_f64().unwrap()).collect();
        let axis = p["slice"].as_u64().unwrap() as usize;
        let idx = p["index"].as_f64().unwrap();
        assert!(
            (x[axis] - (origin[axis] + idx * spacing[axis])).abs() < 1e-9,
            "not on the slice: {p}"
        );
        for k in 0..3 {
            let end = origin[k] + (dims[k] - 1) as f64 * spacing[k];
            assert!(
                x[k] >= origin[k] - 1e-9 && x[k] <= end + 1e-9,
                "outside: {p}"
            );
        }
        let v = p["value"].as_f64().unwrap();
        let want = linear([x[0], x[1], x[2]]);
        // half a step of quantization, the f32 samples' rounding
        assert!(
            (v - want).abs() <= 0.5 * step + 1e-5 * want.abs().max(1.0),
            "picked {v}, f = {want}: {p}"
        );
    }
    assert!(hits >= 3, "too few picks hit a slice: {r}");
}

#[test]
fn degenerate_volumes_give_a_page_with_a_note_or_error_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let out = |name: &str| d.join(format!("{name}.html"));
    // one sample along z: the z slice is the picture
    let flat = nrrd(d, "flat", [30, 20, 1], [1.0; 3], [0.0; 3], |p| {
        (p[0] * p[1]) as f32
    });
    let o = view(&[&flat, Path::new("-o"), &out("flat")]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        o.status.success() && err.contains("note:") && err.contains("one sample along z"),
        "{err}"
    );
    let r = selftest(&out("flat"), "orbit", &d.join("profile"));
    assert_eq!(r["errors"], serde_json::json!([]), "console errors: {r}");
    assert!(r["before"]["foreground"].as_f64().unwrap() > 0.05, "{r}");
    // constant: one colour, no contour surface, said so
    let c = nrrd(d, "const", [5, 5, 5], [1.0; 3], [0.0; 3], |_| 3.0);
    let o = view(&[&c, Path::new("-o"), &out("const")]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success() && err.contains("constant"), "{err}");
    let html = std::fs::read_to_string(out("const")).unwrap();
    assert!(html.contains("no contour surface"));
    // one sample along two axes: a page, only the box
    let line = nrrd(d, "line", [1, 1, 7], [1.0; 3], [0.0; 3], |p| p[2] as f32);
    let o = view(&[&line, Path::new("-o"), &out("line")]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // no finite sample: error, exit 2, no page
    let nan = nrrd(d, "nan", [4, 4, 4], [1.0; 3], [0.0; 3], |_| f32::NAN);
    let o = view(&[&nan, Path::new("-o"), &out("nan")]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.starts_with("error:") && err.contains("no finite sample"),
        "{err}"
    );
    assert!(!out("nan").exists());
}
