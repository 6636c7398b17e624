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
