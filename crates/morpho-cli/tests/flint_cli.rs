//! `morpho flint build|approx|contains|intersect`: outputs, the notes' numbers (A.6) through the CLI,
//! answers equal to brute-force crossing parity, and bad input refused with `error:`/exit 2.
#[path = "../../morpho/tests/common/mod.rs"]
mod common;
use common::data;
use std::path::Path;
use std::process::{Command, Output};

fn morpho(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_morpho"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("run morpho")
}

fn report(dir: &Path, name: &str) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(dir.join(name)).unwrap()).unwrap()
}

/// Exact-enough parity oracle on the test's own polygon (integer coordinates, queries at
/// half-integers: no ties, so float arithmetic is exact here).
fn parity(poly: &[[f64; 2]], q: [f64; 2]) -> bool {
    let mut inside = false;
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        if (a[1] > q[1]) != (b[1] > q[1]) {
            let x = a[0] + (q[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
            if q[0] < x {
                inside = !inside;
            }
        }
    }
    inside
}

#[test]
fn contains_equals_parity_and_marks_the_boundary() {
    let dir = tempfile::tempdir().unwrap();
    // a comb: a simple, non-convex polygon with integer vertices
    let mut poly = vec![[0.0, 0.0], [20.0, 0.0], [20.0, 10.0]];
    for k in (0..10).rev() {
        let x = 2.0 * k as f64;
        poly.push([x + 1.5, 10.0]);
        poly.push([x + 1.0, 3.0]);
        poly.push([x, 10.0]);
    }
    poly.dedup();
    let mut s = String::from("x,y\n");
    for p in &poly {
        s.push_str(&format!("{},{}\n", p[0], p[1]));
    }
    std::fs::write(dir.path().join("comb.csv"), s).unwrap();
    let mut q = String::from("x,y\n");
    let mut qs = Vec::new();
    for i in 0..44 {
        for j in 0..24 {
            let p = [i as f64 * 0.5 - 0.75, j as f64 * 0.5 - 0.75];
            qs.push(p);
            q.push_str(&format!("{},{}\n", p[0], p[1]));
        }
    }
    // two boundary points: a vertex and an edge midpoint
    q.push_str("20,10\n10,0\n");
    std::fs::write(dir.path().join("q.csv"), q).unwrap();
    let o = morpho(
        dir.path(),
        &[
            "flint", "contains", "comb.csv", "q.csv", "-o", "a.csv", "--report", "r.json",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(dir.path().join("a.csv")).unwrap();
    let rows: Vec<&str> = text.lines().skip(1).collect();
    assert_eq!(rows.len(), qs.len() + 2);
    let mut on_edge = 0;
    for (row, p) in rows.iter().zip(&qs) {
        let inside = row.rsplit(',').next().unwrap();
        // queries on a polygon edge line (x or y integer-aligned with an edge) are 2
        if inside == "2" {
            on_edge += 1;
            continue;
        }
        assert_eq!(inside == "1", parity(&poly, *p), "{row}");
    }
    assert!(
        rows[qs.len()].ends_with(",2") && rows[qs.len() + 1].ends_with(",2"),
        "{rows:?}"
    );
    let r = report(dir.path(), "r.json");
    assert_eq!(r["queries"], qs.len() + 2);
    assert_eq!(r["boundary"], on_edge + 2);
}

/// The tree JSON of `flint build` (written node by node): its keys, the root, and every node's
/// chord, split vertex, children and level consistent (`n` = vertices of the tree).
fn check_tree_json(t: &serde_json::Value, n: usize) {
    let keys: Vec<&str> = t.as_object().unwrap().keys().map(|k| k.as_str()).collect();
    for k in ["closed", "depth", "kinds", "nodes", "root", "vertices"] {
        assert!(keys.contains(&k), "{keys:?}");
    }
    assert_eq!(t["vertices"], n);
    let nodes = t["nodes"].as_array().unwrap();
    assert_eq!(nodes.len() + 2, n); // closed: N − 1 nodes with the root
    let mut depth = 0;
    for nd in nodes {
        let (lo, hi) = (
            nd["chord"][0].as_u64().unwrap(),
            nd["chord"][1].as_u64().unwrap(),
        );
        let v = nd["vertex"].as_u64().unwrap();
        assert!(lo < v && v < hi, "{nd}");
        depth = depth.max(nd["level"].as_u64().unwrap());
        for c in nd["children"].as_array().unwrap() {
            if let Some(c) = c.as_u64() {
                let ch = &nodes[c as usize];
                assert_eq!(
                    ch["level"].as_u64().unwrap(),
                    nd["level"].as_u64().unwrap() + 1
                );
                assert!(
                    ch["chord"][0].as_u64().unwrap() >= lo
                        && ch["chord"][1].as_u64().unwrap() <= hi
                );
            }
        }
        assert!(["cap", "intersection", "union", "segment", "unbounded"]
            .contains(&nd["kind"].as_str().unwrap()));
    }
    assert_eq!(t["depth"], depth);
    assert!(t["root"]["radius"].as_f64().unwrap() > 0.0);
}

#[test]
fn build_and_approx_reproduce_the_notes() {
    let Some(benelux) = data("polygons/benelux_mainland_ne50m.csv") else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let b = benelux.to_str().unwrap();
    let o = morpho(
        dir.path(),
        &["flint", "build", b, "-o", "t.json", "--report", "r.json"],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r = report(dir.path(), "r.json");
    assert_eq!(r["nodes"], 232);
    assert_eq!(r["depth"], 19);
    let t = report(dir.path(), "t.json");
    // the root (chord and disc) and 231 split nodes; the report's `nodes` counts both
    assert_eq!(t["nodes"].as_array().unwrap().len() + 1, 232);
    check_tree_json(&t, 233);
    for (args, edges) in [
        (&["--level", "3"][..], Some(13)),
        (&["--count", "60"][..], Some(60)),
        (&["--count", "60", "--method", "dp"][..], Some(60)),
        (&["--error", "0.05", "--method", "blg"][..], None),
    ] {
        let mut a = vec![
            "flint",
            "approx",
            b,
            "-o",
            "a.geojson",
            "--report",
            "ra.json",
        ];
        a.extend_from_slice(args);
        let o = morpho(dir.path(), &a);
        assert!(
            o.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let r = report(dir.path(), "ra.json");
        if let Some(e) = edges {
            assert_eq!(r["edges"], e, "{args:?}");
        }
        let e1 = r["e1"].as_f64().unwrap();
        let e5 = r["e5"].as_f64().unwrap();
        assert!(
            e1 <= e5 * (1.0 + 1e-12) + 1e-15,
            "{args:?}: e1 {e1} e5 {e5}"
        );
        if args.contains(&"--error") {
            assert!(e1 <= 0.05, "{args:?}: e1 {e1}");
        }
        let g = report(dir.path(), "a.geojson");
        assert!(g.to_string().contains("Polygon"), "{args:?}");
    }
}

/// The test's own all-pairs oracle on integer polygons (exact in i64): the meeting edge pairs
/// and whether each is a collinear overlap of positive length.
fn meetings(a: &[[i64; 2]], b: &[[i64; 2]]) -> Vec<(usize, usize, bool)> {
    let cr = |o: [i64; 2], p: [i64; 2], q: [i64; 2]| {
        ((p[0] - o[0]) * (q[1] - o[1]) - (p[1] - o[1]) * (q[0] - o[0])).signum()
    };
    let within = |p: [i64; 2], q: [i64; 2], x: [i64; 2]| {
        p[0].min(q[0]) <= x[0]
            && x[0] <= p[0].max(q[0])
            && p[1].min(q[1]) <= x[1]
            && x[1] <= p[1].max(q[1])
    };
    let mut out = Vec::new();
    for i in 0..a.len() {
        let (p, q) = (a[i], a[(i + 1) % a.len()]);
        for k in 0..b.len() {
            let (r, t) = (b[k], b[(k + 1) % b.len()]);
            let (d1, d2, d3, d4) = (cr(p, q, r), cr(p, q, t), cr(r, t, p), cr(r, t, q));
            let on = |u, v, x, d: i64| d == 0 && within(u, v, x);
            let meet = (d1 * d2 < 0 && d3 * d4 < 0)
                || on(p, q, r, d1)
                || on(p, q, t, d2)
                || on(r, t, p, d3)
                || on(r, t, q, d4);
            if meet {
                let mut ends: Vec<[i64; 2]> = Vec::new();
                for (x, ok) in [
                    (r, on(p, q, r, d1)),
                    (t, on(p, q, t, d2)),
                    (p, on(r, t, p, d3)),
                    (q, on(r, t, q, d4)),
                ] {
                    if ok && !ends.contains(&x) {
                        ends.push(x);
                    }
                }
                out.push((i, k, d1 == 0 && d2 == 0 && ends.len() >= 2));
            }
        }
    }
    out
}

#[test]
fn intersect_equals_all_pairs_and_reports_the_visits() {
    let dir = tempfile::tempdir().unwrap();
    // a comb and its copy moved by two units right: crossings, touchings, overlaps
    let mut comb: Vec<[i64; 2]> = vec![[0, 0], [20, 0], [20, 10]];
    for k in (0..5).rev() {
        comb.extend([[4 * k + 3, 10], [4 * k + 2, 3], [4 * k, 10]]);
    }
    comb.dedup();
    let moved: Vec<[i64; 2]> = comb.iter().map(|p| [p[0] + 2, p[1]]).collect();
    let write = |name: &str, p: &[[i64; 2]]| {
        let mut s = String::from("x,y\n");
        for q in p {
            s.push_str(&format!("{},{}\n", q[0], q[1]));
        }
        std::fs::write(dir.path().join(name), s).unwrap();
    };
    write("a.csv", &comb);
    write("b.csv", &moved);
    let mut want = meetings(&comb, &moved);
    want.sort();
    assert!(want.iter().any(|m| m.2) && want.len() > 10, "{want:?}");
    let o = morpho(
        dir.path(),
        &[
            "flint",
            "intersect",
            "a.csv",
            "b.csv",
            "-o",
            "m.csv",
            "--report",
            "r.json",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(dir.path().join("m.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("x,y,x2,y2,edge_a,edge_b,overlap"));
    let mut got: Vec<(usize, usize, bool)> = lines
        .map(|l| {
            let v: Vec<&str> = l.split(',').collect();
            (v[4].parse().unwrap(), v[5].parse().unwrap(), v[6] == "1")
        })
        .collect();
    got.sort();
    assert_eq!(got, want);
    let r = report(dir.path(), "r.json");
    assert_eq!(r["pairs"], want.len());
    assert_eq!(r["intersects"], true);
    assert_eq!(r["overlaps"], want.iter().filter(|m| m.2).count());
    assert_eq!(r["brute_pairs"], comb.len() * moved.len());
    assert!(
        r["visited"].as_u64().unwrap() > 0
            && r["leaf_tests"].as_u64().unwrap() >= want.len() as u64
    );
    // detection: one meeting at most, and one of the above
    let o = morpho(
        dir.path(),
        &[
            "flint",
            "intersect",
            "a.csv",
            "b.csv",
            "--first",
            "-o",
            "f.geojson",
            "--report",
            "rf.json",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r = report(dir.path(), "rf.json");
    assert_eq!(
        (r["pairs"].clone(), r["intersects"].clone()),
        (1.into(), true.into())
    );
    // disjoint: nothing, and only the root pair visited
    let far: Vec<[i64; 2]> = comb.iter().map(|p| [p[0] + 100, p[1]]).collect();
    write("far.csv", &far);
    let o = morpho(
        dir.path(),
        &[
            "flint",
            "intersect",
            "a.csv",
            "far.csv",
            "-o",
            "n.ply",
            "--report",
            "rn.json",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r = report(dir.path(), "rn.json");
    assert_eq!(
        (r["pairs"].clone(), r["visited"].clone()),
        (0.into(), 1.into())
    );
}

#[test]
fn bad_input_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("bow.csv"), "x,y\n0,0\n1,1\n1,0\n0,1\n").unwrap();
    std::fs::write(dir.path().join("two.csv"), "x,y\n0,0\n1,1\n").unwrap();
    std::fs::write(dir.path().join("sq.csv"), "x,y\n0,0\n1,0\n1,1\n0,1\n").unwrap();
    std::fs::write(dir.path().join("q.csv"), "x,y\n0.5,nan\n").unwrap();
    for args in [
        &["flint", "build", "bow.csv", "-o", "t.json"][..],
        &["flint", "build", "two.csv", "-o", "t.json"][..],
        &["flint", "build", "sq.csv", "-o", "t.csv"][..],
        &["flint", "approx", "sq.csv", "-o", "a.csv"][..],
        &[
            "flint", "approx", "sq.csv", "--level", "1", "--count", "2", "-o", "a.csv",
        ][..],
        &["flint", "approx", "sq.csv", "--error=-1", "-o", "a.csv"][..],
        &["flint", "approx", "sq.csv", "--count", "0", "-o", "a.csv"][..],
        &["flint", "contains", "sq.csv", "q.csv", "-o", "a.csv"][..],
        &["flint", "contains", "sq.csv", "sq.csv", "-o", "sq.csv"][..],
        &["flint", "intersect", "sq.csv", "bow.csv", "-o", "m.csv"][..],
        &["flint", "intersect", "two.csv", "sq.csv", "-o", "m.csv"][..],
        &["flint", "intersect", "sq.csv", "sq.csv", "-o", "m.png"][..],
        &["flint", "intersect", "sq.csv", "sq.csv", "-o", "sq.csv"][..],
    ] {
        let o = morpho(dir.path(), args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.starts_with("error: "), "{args:?}: {err}");
    }
    assert_eq!(
        std::fs::read_to_string(dir.path().join("sq.csv")).unwrap(),
        "x,y\n0,0\n1,0\n1,1\n0,1\n"
    );
}

/// `--repair`: the ne10m Australia ring (two zero-area spikes) is refused without it, with the
/// hint, and accepted with it (`spikes_removed`, input indices in `indices`); the Benelux ring
/// crosses itself and stays refused, its edges named by input vertices.
#[test]
fn repair_removes_spikes_and_refuses_crossings() {
    let (Some(au), Some(bx)) = (
        data("polygons/coast_australia_mainland_ne10m.csv"),
        data("polygons/benelux_mainland_ne10m.csv"),
    ) else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("q.csv"),
        "x,y\n136.21276212762126,-13.219\n134,-25\n0,0\n",
    )
    .unwrap();
    let (au, bx) = (au.to_str().unwrap(), bx.to_str().unwrap());
    let o = morpho(
        dir.path(),
        &["flint", "contains", au, "q.csv", "-o", "a.csv"],
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.starts_with("error: ") && err.contains("--repair"),
        "{err}"
    );
    let o = morpho(
        dir.path(),
        &[
            "flint", "contains", au, "q.csv", "-o", "a.csv", "--repair", "--report", "r.json",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r = report(dir.path(), "r.json");
    assert_eq!(r["spikes_removed"], 2);
    assert_eq!(r["removed_vertices"], serde_json::json!([5081, 7182]));
    // the streamed tree JSON with the repair's maps
    let o = morpho(
        dir.path(),
        &["flint", "build", au, "-o", "au.json", "--repair"],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let t = report(dir.path(), "au.json");
    assert_eq!(t["removed_vertices"], serde_json::json!([5081, 7182]));
    let kept = t["input_index"].as_array().unwrap();
    check_tree_json(&t, kept.len());
    assert!(kept.iter().all(|k| k != 5081 && k != 7182));
    let out = std::fs::read_to_string(dir.path().join("a.csv")).unwrap();
    let inside: Vec<&str> = out
        .lines()
        .skip(1)
        .map(|l| l.rsplit(',').next().unwrap())
        .collect();
    // on the removed spike (x of vertex 5081, between its ends): not boundary any more
    assert_ne!(inside[0], "2", "{out}");
    assert_eq!(&inside[1..], ["1", "0"], "{out}");
    let o = morpho(
        dir.path(),
        &[
            "flint", "approx", au, "--count", "50", "-o", "ap.csv", "--repair", "--report",
            "r2.json",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let idx = report(dir.path(), "r2.json")["indices"].clone();
    let idx: Vec<u64> = serde_json::from_value(idx).unwrap();
    assert!(idx.iter().all(|&i| i != 5081 && i != 7182 && i < 9454));
    assert_eq!(idx.len(), 50);
    let o = morpho(
        dir.path(),
        &["flint", "build", bx, "-o", "t.json", "--repair"],
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.starts_with("error: ") && err.contains("edge 584–585 meets edge 586–587"),
        "{err}"
    );
    assert!(!dir.path().join("t.json").exists());
}

/// A closed mesh written as OFF with its generator's integer coordinates.
fn write_off(path: &Path, m: &morpho::mesh::TriMesh) {
    let mut s = format!("OFF\n{} {} 0\n", m.positions.len(), m.triangles.len());
    for p in &m.positions {
        s.push_str(&format!("{} {} {}\n", p.x, p.y, p.z));
    }
    for t in &m.triangles {
        s.push_str(&format!("3 {} {} {}\n", t[0], t[1], t[2]));
    }
    std::fs::write(path, s).unwrap();
}

#[test]
fn mesh_contains_equals_brute_force() {
    let dir = tempfile::tempdir().unwrap();
    let m = morpho::mesh::generate::multi_torus(2); // genus 2, integer corners
    write_off(&dir.path().join("m.off"), &m);
    let b = m.bbox();
    let mut q = String::from("x,y,z\n");
    let mut qs = Vec::new();
    for i in 0..((b.max[0] - b.min[0]) * 4.0 + 5.0) as i32 {
        for j in 0..((b.max[1] - b.min[1]) * 4.0 + 5.0) as i32 {
            for k in 0..((b.max[2] - b.min[2]) * 4.0 + 5.0) as i32 {
                // quarter steps: on faces, edges and vertices, inside and outside
                let p = [
                    b.min[0] - 0.5 + 0.25 * f64::from(i),
                    b.min[1] - 0.5 + 0.25 * f64::from(j),
                    b.min[2] - 0.5 + 0.25 * f64::from(k),
                ];
                qs.push(p);
                q.push_str(&format!("{},{},{}\n", p[0], p[1], p[2]));
            }
        }
    }
    std::fs::write(dir.path().join("q.csv"), q).unwrap();
    // the flintstone walk and the prism tree's (the 3D baseline) give the same exact answers
    for method in ["flintstone", "prism"] {
        let o = morpho(
            dir.path(),
            &[
                "flint", "contains", "m.off", "q.csv", "-o", "a.csv", "--report", "r.json",
                "--method", method,
            ],
        );
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let pos: Vec<[f64; 3]> = m.positions.iter().map(|p| [p.x, p.y, p.z]).collect();
        let text = std::fs::read_to_string(dir.path().join("a.csv")).unwrap();
        let rows: Vec<&str> = text.lines().skip(1).collect();
        assert_eq!(rows.len(), qs.len());
        let mut counts = [0; 3];
        for (row, p) in rows.iter().zip(&qs) {
            let got: u8 = row.rsplit(',').next().unwrap().trim().parse().unwrap();
            let want = morpho::flint::contains_brute3(&pos, &m.triangles, *p) as u8;
            assert_eq!(got, want, "{p:?}");
            counts[want as usize] += 1;
        }
        assert!(counts.iter().all(|&c| c > 0), "{counts:?}");
        let r = report(dir.path(), "r.json");
        assert_eq!(r["queries"], qs.len());
        assert_eq!(r["boundary"], counts[2]);
        assert_eq!(r["method"], method);
    }
}

#[test]
fn mesh_baselines3_approx() {
    let dir = tempfile::tempdir().unwrap();
    let m = morpho::mesh::generate::icosphere(3);
    write_off(&dir.path().join("s.off"), &m);
    for method in ["iepf3", "prism"] {
        // the initial triangle both ways, then a 3-split of each half
        for (level, want) in [("0", 2), ("1", 6)] {
            let o = morpho(
                dir.path(),
                &[
                    "flint", "approx", "s.off", "--level", level, "--method", method, "-o",
                    "a.off", "--report", "a.json",
                ],
            );
            assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
            let r = report(dir.path(), "a.json");
            assert_eq!(r["triangles"], want, "{method} level {level}");
            assert_eq!(r["method"], method);
        }
        let mut last = 0;
        for eps in ["0.3", "0.1", "0.03", "0"] {
            let o = morpho(
                dir.path(),
                &[
                    "flint", "approx", "s.off", "--error", eps, "--method", method, "-o", "e.ply",
                    "--report", "e.json",
                ],
            );
            assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
            let r = report(dir.path(), "e.json");
            let n = r["triangles"].as_u64().unwrap() + r["dropped"].as_u64().unwrap();
            assert!(n >= last, "{method} ε {eps}: {n} < {last}");
            last = n;
            let (e1, e2) = (r["e1"].as_f64().unwrap(), r["e2"].as_f64().unwrap());
            assert!(e2 <= e1 * (1.0 + 1e-12), "{method}: e2 {e2} > e1 {e1}");
            if method == "iepf3" {
                // the 3D Douglas–Peucker: e1 within the bound
                assert!(e1 <= eps.parse::<f64>().unwrap(), "{eps}: e1 {e1}");
            }
            let out = morpho::io::read_mesh(&dir.path().join("e.ply")).unwrap();
            for p in &out.positions {
                assert!(m.positions.iter().any(|q| q == p));
            }
        }
        assert_eq!(last as usize, m.triangles.len());
        let o = morpho(
            dir.path(),
            &[
                "flint", "approx", "s.off", "--count", "100", "--method", method, "-o", "c.obj",
                "--report", "c.json",
            ],
        );
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert!(report(dir.path(), "c.json")["triangles"].as_u64().unwrap() >= 100);
    }
}

#[test]
fn mesh_build_and_approx() {
    let dir = tempfile::tempdir().unwrap();
    let m = morpho::mesh::generate::icosphere(3);
    morpho::io::write_mesh(
        &dir.path().join("s.ply"),
        &m,
        morpho::io::Encoding::BinaryLittleEndian,
    )
    .unwrap();
    let o = morpho(
        dir.path(),
        &[
            "flint", "build", "s.ply", "-o", "t.json", "--report", "r.json",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r = report(dir.path(), "r.json");
    assert_eq!(r["leaves"], m.triangles.len());
    assert_eq!(r["triangles"], m.triangles.len());
    let t = report(dir.path(), "t.json");
    let nodes = t["nodes"].as_array().unwrap();
    assert_eq!(nodes.len() + 1, r["nodes"].as_u64().unwrap() as usize);
    assert_eq!(
        nodes.iter().filter(|n| n.get("triangle").is_some()).count(),
        m.triangles.len()
    );
    // level 0 is the root triangle both ways; adaptive ε meets its bound
    let o = morpho(
        dir.path(),
        &[
            "flint", "approx", "s.ply", "--level", "0", "-o", "a.off", "--report", "a.json",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(report(dir.path(), "a.json")["triangles"], 2);
    let mut last = 0;
    for eps in ["0.3", "0.1", "0.03", "0"] {
        let o = morpho(
            dir.path(),
            &[
                "flint", "approx", "s.ply", "--error", eps, "-o", "e.obj", "--report", "e.json",
            ],
        );
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let r = report(dir.path(), "e.json");
        let n = r["triangles"].as_u64().unwrap() + r["dropped"].as_u64().unwrap();
        assert!(n >= last, "ε {eps}: {n} < {last}");
        last = n;
        assert!(r["e5"].as_f64().unwrap() <= eps.parse::<f64>().unwrap());
        let out = morpho::io::read_mesh(&dir.path().join("e.obj")).unwrap();
        assert_eq!(out.triangles.len() as u64, r["triangles"].as_u64().unwrap());
        // every output vertex is an input vertex
        for p in &out.positions {
            assert!(m.positions.iter().any(|q| q == p));
        }
    }
    assert_eq!(last as usize, m.triangles.len());
}

#[test]
fn bad_mesh_input_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let cube = morpho::mesh::generate::cube();
    write_off(&dir.path().join("cube.off"), &cube);
    let mut open = cube.clone();
    open.triangles.pop();
    write_off(&dir.path().join("open.off"), &open);
    let mut flip = cube.clone();
    flip.triangles[0].swap(1, 2);
    write_off(&dir.path().join("flip.off"), &flip);
    // a fin on edge 0–1 of triangle 0: three triangles at one edge
    let mut fin = cube.clone();
    let t0 = fin.triangles[0];
    fin.positions.push(morpho::geom::Point3::new(5.0, 5.0, 5.0));
    let v = fin.positions.len() as u32 - 1;
    fin.triangles.push([t0[1], t0[0], v]);
    fin.triangles.push([t0[0], t0[1], v]);
    write_off(&dir.path().join("fin.off"), &fin);
    std::fs::write(dir.path().join("tri.csv"), "x,y\n0,0\n1,0\n0,1\n").unwrap();
    std::fs::write(dir.path().join("q2.csv"), "x,y\n0.5,0.5\n").unwrap();
    std::fs::write(dir.path().join("qn.csv"), "x,y,z\n0.5,nan,0.5\n").unwrap();
    for args in [
        &["flint", "build", "open.off", "-o", "t.json"][..],
        &["flint", "build", "flip.off", "-o", "t.json"][..],
        &["flint", "approx", "cube.off", "--level", "1", "-o", "a.csv"][..],
        &[
            "flint", "approx", "cube.off", "--level", "1", "--method", "dp", "-o", "a.off",
        ][..],
        &["flint", "approx", "cube.off", "--error=-1", "-o", "a.off"][..],
        &[
            "flint", "approx", "open.off", "--level", "1", "--method", "iepf3", "-o", "a.off",
        ][..],
        &[
            "flint", "approx", "fin.off", "--level", "1", "--method", "prism", "-o", "a.off",
        ][..],
        &[
            "flint", "approx", "flip.off", "--level", "1", "--method", "iepf3", "-o", "a.off",
        ][..],
        &[
            "flint", "approx", "tri.csv", "--level", "1", "--method", "prism", "-o", "a.csv",
        ][..],
        &[
            "flint", "contains", "fin.off", "qn.csv", "--method", "prism", "-o", "a.csv",
        ][..],
        &[
            "flint", "contains", "tri.csv", "q2.csv", "--method", "prism", "-o", "a.csv",
        ][..],
        &["flint", "contains", "open.off", "qn.csv", "-o", "a.csv"][..],
        &["flint", "contains", "cube.off", "q2.csv", "-o", "a.csv"][..],
        &["flint", "contains", "cube.off", "qn.csv", "-o", "a.csv"][..],
    ] {
        let o = morpho(dir.path(), args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.starts_with("error: "), "{args:?}: {err}");
    }
}

#[test]
fn mesh_intersect_equals_brute_force_and_writes_segments() {
    use morpho::flint::intersect3_brute;
    let dir = tempfile::tempdir().unwrap();
    let m = morpho::mesh::generate::icosphere(2);
    let mut b = m.clone();
    for p in &mut b.positions {
        *p = morpho::geom::Point3::new(p.x + 0.6, p.y + 0.2, p.z);
    }
    let mut far = m.clone();
    for p in &mut far.positions {
        p.x += 5.0;
    }
    write_off(&dir.path().join("a.off"), &m);
    write_off(&dir.path().join("b.off"), &b);
    write_off(&dir.path().join("far.off"), &far);
    let flat = |m: &morpho::mesh::TriMesh| -> Vec<[f64; 3]> {
        m.positions.iter().map(|p| [p.x, p.y, p.z]).collect()
    };
    let want = intersect3_brute(&flat(&m), &m.triangles, &flat(&b), &b.triangles);
    assert!(want.len() > 20);
    let o = morpho(
        dir.path(),
        &[
            "flint",
            "intersect",
            "a.off",
            "b.off",
            "-o",
            "s.csv",
            "--report",
            "r.json",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r = report(dir.path(), "r.json");
    assert_eq!(r["intersects"], true);
    assert_eq!(r["pairs"], want.len());
    assert_eq!(
        r["segments"],
        want.len(),
        "no coplanar pairs here: one segment each"
    );
    assert_eq!(r["brute_pairs"], m.triangles.len() * b.triangles.len());
    assert!(r["leaf_tests"].as_u64().unwrap() < r["brute_pairs"].as_u64().unwrap() / 4);
    let csv = std::fs::read_to_string(dir.path().join("s.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next().unwrap(), "x,y,z,x2,y2,z2,tri_a,tri_b,coplanar");
    let got: Vec<[u32; 2]> = lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            [f[6].parse().unwrap(), f[7].parse().unwrap()]
        })
        .collect();
    assert_eq!(got, want);
    // the PLY holds the segments as edges
    let o = morpho(
        dir.path(),
        &["flint", "intersect", "a.off", "b.off", "-o", "s.ply"],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let ply = std::fs::read_to_string(dir.path().join("s.ply")).unwrap();
    assert!(
        ply.contains(&format!("element edge {}\n", want.len())),
        "{ply:.300}"
    );
    // detection, and disjoint meshes
    for (other, hit) in [("b.off", true), ("far.off", false)] {
        let o = morpho(
            dir.path(),
            &[
                "flint",
                "intersect",
                "a.off",
                other,
                "--first",
                "-o",
                "d.csv",
                "--report",
                "r.json",
            ],
        );
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert_eq!(report(dir.path(), "r.json")["intersects"], hit, "{other}");
    }
}

#[test]
fn bad_mesh_intersect_input_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let cube = morpho::mesh::generate::cube();
    write_off(&dir.path().join("cube.off"), &cube);
    let mut open = cube.clone();
    open.triangles.pop();
    write_off(&dir.path().join("open.off"), &open);
    let mut nm = cube.clone();
    let t0 = nm.triangles[0];
    // a third triangle on the edge t0[0]–t0[1]
    nm.positions.push(morpho::geom::Point3::new(0.3, 0.4, 2.0));
    nm.triangles
        .push([t0[0], t0[1], (nm.positions.len() - 1) as u32]);
    write_off(&dir.path().join("nonmanifold.off"), &nm);
    let mut nan = cube.clone();
    nan.positions[0].x = f64::NAN;
    write_off(&dir.path().join("nan.off"), &nan);
    let tet = morpho::mesh::generate::tetrahedron();
    let mut three = tet.clone();
    three.triangles.pop();
    write_off(&dir.path().join("three.off"), &three);
    for args in [
        &["flint", "intersect", "open.off", "cube.off", "-o", "s.csv"][..],
        &[
            "flint",
            "intersect",
            "cube.off",
            "nonmanifold.off",
            "-o",
            "s.csv",
        ][..],
        &["flint", "intersect", "nan.off", "cube.off", "-o", "s.csv"][..],
        &["flint", "intersect", "cube.off", "three.off", "-o", "s.csv"][..],
        &[
            "flint",
            "intersect",
            "cube.off",
            "cube.off",
            "-o",
            "s.geojson",
        ][..],
        &[
            "flint",
            "intersect",
            "cube.off",
            "cube.off",
            "--repair",
            "-o",
            "s.csv",
        ][..],
    ] {
        let o = morpho(dir.path(), args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.starts_with("error: "), "{args:?}: {err}");
    }
}
