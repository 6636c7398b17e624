//! Geometry fuzzing of the algorithm entry points (issue 17, "a fuzzing campaign in the test
//! suite"): small degenerate configurations — lattices, duplicates, exactly cocircular and
//! cospherical integer points, collinear and coplanar sets — at scales from 1e-300 to 1e300 and
//! far from the origin, through every entry point. Each case asserts:
//! - **no panic** (`catch_unwind`; the failure names the entry point and the configuration);
//! - **a time bound** of [`CASE_SECONDS`] (release build, ≤ 48 points per case);
//! - **bounded allocation**: a counting global allocator (all threads: rayon's too) records the
//!   peak of live bytes; a case fails above [`CASE_BYTES`];
//! - **correct when it answers**: a 2D boundary that claims every point is a simple polygon
//!   through all of them (exact check), a 2D Delaunay triangulation has empty circumcircles
//!   (exact `incircle`), a 3D boundary that claims every point is a closed manifold.
//!
//! An error (`Err`) is a valid answer for degenerate input; a panic, a hang, a runaway
//! allocation or a wrong answer is not.
use morpho::boundary::{boundary_2d, boundary_3d, check_polygon, Options2, Options3};
use morpho::delaunay::{triangulate_2d, triangulate_3d, voronoi_2d};
use morpho::geom::{incircle, Point2, Point3};
use morpho::graphs::{graph_2d, graph_3d, Kind};
use morpho::mesh::{analyze_topology, generate, validity, TriMesh};
use morpho::volume::{isosurface, IsoOptions, Volume};
use std::alloc::{GlobalAlloc, Layout, System};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicIsize, Ordering::Relaxed};
use std::time::Instant;

/// The definition of a hang (issue 17, "Done when": > 20 s on inputs under 1 MB).
/// The slowest case measured was 3D `gamma-range` with c = −1 on 40 near-cospherical points at
/// 1e±150/1e-300 (O(n⁴) exact `insphere` in the brute force of `beyond_dt_3d`): 2.9–3.7 s
/// alone, 5.5–6.4 s on a loaded machine — a 5 s bound made CI depend on the load. With the
/// near-sphere in-sphere filter it takes 0.25–0.35 s CPU (see
/// [`gamma_range_on_rounded_cospherical_points_is_fast`]).
const CASE_SECONDS: f64 = 20.0;
const CASE_BYTES: isize = 256 << 20;

struct Counting;
static LIVE: AtomicIsize = AtomicIsize::new(0);
static PEAK: AtomicIsize = AtomicIsize::new(0);

fn note(d: isize) {
    let v = LIVE.fetch_add(d, Relaxed) + d;
    PEAK.fetch_max(v, Relaxed);
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        let p = System.alloc(l);
        if !p.is_null() {
            note(l.size() as isize);
        }
        p
    }
    unsafe fn alloc_zeroed(&self, l: Layout) -> *mut u8 {
        let p = System.alloc_zeroed(l);
        if !p.is_null() {
            note(l.size() as isize);
        }
        p
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        System.dealloc(p, l);
        note(-(l.size() as isize));
    }
    unsafe fn realloc(&self, p: *mut u8, l: Layout, n: usize) -> *mut u8 {
        let q = System.realloc(p, l, n);
        if !q.is_null() {
            note(n as isize - l.size() as isize);
        }
        q
    }
}

#[global_allocator]
static ALLOC: Counting = Counting;

/// The peak counter is global: the tests of this file run one at a time.
static SERIAL: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// Runs one case: no panic, within time and memory; `Err(description)` otherwise.
fn case(what: &str, config: &str, f: impl FnOnce() -> Result<(), String>) -> Result<(), String> {
    let base = LIVE.load(Relaxed);
    PEAK.store(base, Relaxed);
    let start = Instant::now();
    let r = catch_unwind(AssertUnwindSafe(f));
    let secs = start.elapsed().as_secs_f64();
    let peak = PEAK.load(Relaxed) - base;
    let id = format!("{what} on {config}");
    match r {
        Err(_) => return Err(format!("{id}: panicked")),
        Ok(Err(wrong)) => return Err(format!("{id}: wrong answer: {wrong}")),
        Ok(Ok(())) => {}
    }
    if secs > CASE_SECONDS {
        return Err(format!("{id}: {secs:.1} s"));
    }
    if peak > CASE_BYTES {
        return Err(format!("{id}: {} MB live", peak >> 20));
    }
    Ok(())
}

/// Integer points exactly on the circle x² + y² = r².
fn cocircular(r: i64) -> Vec<[f64; 2]> {
    let mut v = Vec::new();
    for x in -r..=r {
        let y2 = r * r - x * x;
        let y = (y2 as f64).sqrt().round() as i64;
        if y * y == y2 {
            v.push([x as f64, y as f64]);
            if y != 0 {
                v.push([x as f64, -y as f64]);
            }
        }
    }
    v
}

/// Integer points exactly on the sphere x² + y² + z² = r2.
fn cospherical(r2: i64, max: usize) -> Vec<[f64; 3]> {
    let r = (r2 as f64).sqrt() as i64 + 1;
    let mut v = Vec::new();
    for x in -r..=r {
        for y in -r..=r {
            let z2 = r2 - x * x - y * y;
            if z2 < 0 {
                continue;
            }
            let z = (z2 as f64).sqrt().round() as i64;
            if z * z == z2 {
                v.push([x as f64, y as f64, z as f64]);
                if z != 0 {
                    v.push([x as f64, y as f64, -z as f64]);
                }
            }
        }
    }
    v.truncate(max);
    v
}

/// Degenerate plane configurations (name, unit-scale points).
fn configs2() -> Vec<(String, Vec<[f64; 2]>)> {
    let mut c: Vec<(String, Vec<[f64; 2]>)> = Vec::new();
    for k in [2usize, 3, 4, 6] {
        let g = (0..k * k)
            .map(|i| [(i % k) as f64, (i / k) as f64])
            .collect::<Vec<_>>();
        c.push((format!("{k}x{k} lattice"), g.clone()));
        let mut d = g.clone();
        d.extend(g.iter().step_by(2));
        c.push((format!("{k}x{k} lattice with duplicates"), d));
    }
    for r in [5, 25, 65] {
        c.push((format!("cocircular r={r}"), cocircular(r)));
        let mut v = cocircular(r);
        v.push([0.0, 0.0]);
        c.push((format!("cocircular r={r} and centre"), v));
    }
    c.push((
        "collinear".into(),
        (0..10).map(|i| [i as f64, 2.0 * i as f64]).collect(),
    ));
    c.push(("one point ten times".into(), vec![[1.0, 1.0]; 10]));
    c.push(("two points".into(), vec![[0.0, 0.0], [1.0, 0.0]]));
    c.push((
        "three points".into(),
        vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]],
    ));
    c.push(("empty".into(), vec![]));
    let mut s = 12345u64;
    let mut next = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    c.push((
        "random 40".into(),
        (0..40).map(|_| [next(), next()]).collect(),
    ));
    c
}

fn configs3() -> Vec<(String, Vec<[f64; 3]>)> {
    let mut c: Vec<(String, Vec<[f64; 3]>)> = Vec::new();
    for k in [2usize, 3] {
        let g = (0..k * k * k)
            .map(|i| [(i % k) as f64, ((i / k) % k) as f64, (i / (k * k)) as f64])
            .collect::<Vec<_>>();
        c.push((format!("{k}^3 lattice"), g.clone()));
        let mut d = g.clone();
        d.extend(g.iter().step_by(3));
        c.push((format!("{k}^3 lattice with duplicates"), d));
    }
    for r2 in [9, 25, 50] {
        c.push((format!("cospherical r2={r2}"), cospherical(r2, 40)));
    }
    c.push((
        "coplanar".into(),
        (0..16)
            .map(|i| [(i % 4) as f64, (i / 4) as f64, 1.0])
            .collect(),
    ));
    c.push((
        "collinear".into(),
        (0..8).map(|i| [i as f64, i as f64, i as f64]).collect(),
    ));
    c.push((
        "four points".into(),
        vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
    ));
    c.push(("one point".into(), vec![[0.5; 3]; 6]));
    c
}

/// The placements each configuration is tried at: (name, scale, offset).
const PLACES: &[(&str, f64, f64)] = &[
    ("unit", 1.0, 0.0),
    ("1e-300", 1e-300, 0.0),
    ("1e-150", 1e-150, 0.0),
    ("1e150", 1e150, 0.0),
    ("1e300", 1e300, 0.0),
    ("offset 1e9", 1.0, 1e9),
    ("1e-12 at 1", 1e-12, 1.0),
];

fn kinds() -> Vec<Kind> {
    vec![
        Kind::ClosestPairs,
        Kind::Nng,
        Kind::Emst,
        Kind::Strip,
        Kind::Sig,
        Kind::Rng,
        Kind::Gabriel,
        Kind::Hull,
        Kind::Delaunay,
        Kind::Alpha(1.5),
        Kind::BetaCircle(0.5),
        Kind::BetaLune(-0.5),
        Kind::BetaLune(1.0),
        Kind::Gamma(-0.5, 0.5),
        Kind::GammaRange([-1.0, 1.0, -0.5, 1.0]),
    ]
}

/// Multiplies by the power of two that brings the largest magnitude near 1 (exact unless the
/// coordinates are subnormal), so that the oracle's `incircle` neither over- nor underflows.
fn normalized(p: &[Point2]) -> Vec<Point2> {
    let m = p
        .iter()
        .flat_map(|q| [q.x.abs(), q.y.abs()])
        .fold(0.0, f64::max);
    if m == 0.0 {
        return p.to_vec();
    }
    let k = -(m.log2().floor() as i32);
    let (h1, h2) = (2f64.powi(k / 2), 2f64.powi(k - k / 2));
    p.iter()
        .map(|q| Point2::new(q.x * h1 * h2, q.y * h1 * h2))
        .collect()
}

fn delaunay_2d_empty_circles(p: &[Point2]) -> Result<(), String> {
    if let Ok(d) = triangulate_2d(p) {
        let v = normalized(&d.points);
        for t in &d.triangles {
            let [a, b, c] = t.map(|i| v[i as usize]);
            for (i, q) in v.iter().enumerate() {
                if !t.contains(&(i as u32)) && incircle(&a, &b, &c, q) > 0.0 {
                    return Err(format!("vertex {i} inside the circumcircle of {t:?}"));
                }
            }
        }
        let _ = voronoi_2d(&d);
    }
    Ok(())
}

fn boundary_2d_checked(p: &[Point2], opts: &Options2) -> Result<(), String> {
    if let Ok(b) = boundary_2d(p, opts) {
        let chk = check_polygon(p, &b.polygon);
        if !chk.simple {
            return Err(format!("{} polygon is not simple", opts.method.name()));
        }
        if b.all_on_boundary && !b.left_out.is_empty() {
            return Err("all_on_boundary with points left out".into());
        }
    }
    Ok(())
}

#[test]
fn plane_entry_points_on_degenerate_input() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let mut failures = Vec::new();
    let mut n = 0;
    for (name, pts) in configs2() {
        for &(place, s, o) in PLACES {
            let p: Vec<Point2> = pts
                .iter()
                .map(|q| Point2::new(q[0] * s + o, q[1] * s + o))
                .collect();
            let cfg = format!("{name} ({} points, {place})", p.len());
            let mut run = |what: &str, f: &dyn Fn() -> Result<(), String>| {
                n += 1;
                if let Err(e) = case(what, &cfg, f) {
                    failures.push(e);
                }
            };
            run("triangulate_2d", &|| delaunay_2d_empty_circles(&p));
            for k in kinds() {
                run(&format!("graph_2d {}", k.name()), &|| {
                    let _ = graph_2d(&p, k);
                    Ok(())
                });
            }
            for o in [
                Options2::gamma(),
                Options2::min_area_change(),
                Options2::voronoi_skeleton(8),
            ] {
                run(&format!("boundary_2d {}", o.method.name()), &|| {
                    boundary_2d_checked(&p, &o)
                });
            }
        }
    }
    eprintln!("{n} plane cases");
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn space_entry_points_on_degenerate_input() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let mut failures = Vec::new();
    let mut n = 0;
    for (name, pts) in configs3() {
        for &(place, s, o) in PLACES {
            let p: Vec<Point3> = pts
                .iter()
                .map(|q| Point3::new(q[0] * s + o, q[1] * s + o, q[2] * s + o))
                .collect();
            let cfg = format!("{name} ({} points, {place})", p.len());
            let mut run = |what: &str, f: &dyn Fn() -> Result<(), String>| {
                n += 1;
                if let Err(e) = case(what, &cfg, f) {
                    failures.push(e);
                }
            };
            run("triangulate_3d", &|| {
                let _ = triangulate_3d(&p);
                Ok(())
            });
            for k in kinds() {
                run(&format!("graph_3d {}", k.name()), &|| {
                    let _ = graph_3d(&p, k);
                    Ok(())
                });
            }
            run("boundary_3d", &|| {
                if let Ok(b) = boundary_3d(&p, &Options3::default()) {
                    if b.all_on_boundary {
                        let m = TriMesh {
                            positions: p.clone(),
                            triangles: b.triangles.clone(),
                            ..Default::default()
                        };
                        let t = analyze_topology(&m);
                        if !(t.is_closed() && t.manifold) {
                            return Err("boundary_3d claims a surface that is not closed".into());
                        }
                    }
                }
                Ok(())
            });
        }
    }
    eprintln!("{n} space cases");
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// CPU seconds of this process (user + system, all threads) from `/proc/self/stat`; NaN where
/// that file does not exist.
fn cpu_seconds() -> f64 {
    let s = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    // the fields after the command name (in parentheses): utime is the 12th, stime the 13th
    let rest = s.rsplit_once(')').map_or("", |(_, r)| r);
    let f: Vec<f64> = rest
        .split_whitespace()
        .skip(11)
        .take(2)
        .filter_map(|x| x.parse().ok())
        .collect();
    if f.len() == 2 {
        (f[0] + f[1]) / 100.0
    } else {
        f64::NAN
    }
}

/// Issue 17 (B): 3D `gamma-range` at c = −1 (the brute force over every triple) and c = −0.5 on
/// 40 nearly cospherical points — integer points of the sphere x² + y² + z² = 50 scaled by
/// 1e-300 or 1e150, which rounding moves off the sphere, so that every in-sphere test is nearly
/// degenerate — took 1.3 s CPU per case (3–7 s wall on the loaded CI machine) in Shewchuk's
/// expansion stages; with the near-sphere filter of `beyond_dt_3d` 0.25–0.35 s CPU. Bounds:
/// 5 s wall (generous for CI load) and 0.9 s CPU per case (all tests of this file hold
/// `SERIAL`, so the process's CPU time is this case's; skipped where `/proc` is missing).
#[test]
fn gamma_range_on_rounded_cospherical_points_is_fast() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let pts = cospherical(50, 40);
    assert_eq!(pts.len(), 40);
    for scale in [1e-300, 1e150] {
        let p: Vec<Point3> = pts
            .iter()
            .map(|q| Point3::new(q[0] * scale, q[1] * scale, q[2] * scale))
            .collect();
        for range in [[-1.0, 1.0, -1.0, 1.0], [-1.0, 1.0, -0.5, 1.0]] {
            let (start, cpu) = (Instant::now(), cpu_seconds());
            let g = graph_3d(&p, Kind::GammaRange(range)).expect("graph");
            let (secs, cpu) = (start.elapsed().as_secs_f64(), cpu_seconds() - cpu);
            let what = format!("40 points x{scale:e}, range {range:?}");
            eprintln!(
                "{what}: {} triangles, {secs:.2} s, cpu {cpu:.2} s",
                g.triangles.len()
            );
            assert!(secs < 5.0, "{what}: {secs:.1} s");
            assert!(cpu.is_nan() || cpu < 0.9, "{what}: {cpu:.2} s CPU");
        }
    }
}

/// An edit of a mesh.
type Edit = Box<dyn Fn(&mut TriMesh)>;

/// Meshes with degenerate triangles (repeated vertex, zero area, duplicate, flipped, NaN-free
/// but huge coordinates) through topology and the exact self-intersection test (the reproducer
/// of issue 17 item 5: `f 1 1 2` added to a closed mesh panicked in `info --check`).
#[test]
fn mesh_checks_on_degenerate_triangles() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let mut failures = Vec::new();
    let mut n = 0;
    let bases = [
        ("tetrahedron", generate::tetrahedron()),
        ("cube", generate::cube()),
        ("torus", generate::torus(1.0, 0.4, 8, 5)),
    ];
    for (name, base) in bases {
        let edits: Vec<(&str, Edit)> = vec![
            ("as is", Box::new(|_| {})),
            ("f 1 1 2", Box::new(|m| m.triangles.push([0, 0, 1]))),
            ("f 1 1 1", Box::new(|m| m.triangles.push([0, 0, 0]))),
            (
                "collinear sliver",
                Box::new(|m| {
                    let a = m.positions[0];
                    let b = m.positions[1];
                    m.positions.push((a + b.coords) * 0.5);
                    let k = m.positions.len() as u32 - 1;
                    m.triangles.push([0, 1, k]);
                }),
            ),
            (
                "duplicate triangle",
                Box::new(|m| {
                    let t = m.triangles[0];
                    m.triangles.push(t);
                }),
            ),
            (
                "flipped triangle",
                Box::new(|m| {
                    let t = m.triangles[0];
                    m.triangles[0] = [t[0], t[2], t[1]];
                }),
            ),
            (
                "scaled 1e300",
                Box::new(|m| m.positions.iter_mut().for_each(|p| *p *= 1e300)),
            ),
            (
                "scaled 1e-300",
                Box::new(|m| m.positions.iter_mut().for_each(|p| *p *= 1e-300)),
            ),
        ];
        for (edit, f) in &edits {
            let mut m = base.clone();
            f(&mut m);
            let cfg = format!("{name}, {edit}");
            n += 1;
            let r = case("topology + self-intersections", &cfg, || {
                let _ = analyze_topology(&m);
                let pos: Vec<[f64; 3]> = m.positions.iter().map(|p| [p.x, p.y, p.z]).collect();
                let _ = validity::self_intersections(&pos, &m.triangles, 100);
                Ok(())
            });
            if let Err(e) = r {
                failures.push(e);
            }
        }
    }
    eprintln!("{n} mesh cases");
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// Tiny volumes whose samples equal the level, are constant, or alternate, at extreme spacings.
#[test]
fn isosurface_on_degenerate_volumes() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let mut failures = Vec::new();
    let mut n = 0;
    for dims in [[2usize, 2, 2], [3, 2, 2], [4, 4, 4]] {
        let len = dims[0] * dims[1] * dims[2];
        let fields: Vec<(&str, Vec<f32>)> = vec![
            ("constant 0", vec![0.0; len]),
            ("alternating", (0..len).map(|i| (i % 2) as f32).collect()),
            ("ramp", (0..len).map(|i| i as f32).collect()),
            (
                "saddle",
                (0..len)
                    .map(|i| if i % 3 == 0 { 1.0 } else { -1.0 })
                    .collect(),
            ),
        ];
        for (fname, data) in fields {
            for spacing in [1.0, 1e-300, 1e300] {
                for level in [0.0, 0.5, 1.0, -1.0] {
                    let cfg = format!("{dims:?} {fname}, spacing {spacing:e}, level {level}");
                    n += 1;
                    let r = case("isosurface", &cfg, || {
                        if let Ok(v) = Volume::new(dims, [0.0; 3], [spacing; 3], data.clone()) {
                            let _ = isosurface(
                                &v,
                                &IsoOptions {
                                    level,
                                    ..Default::default()
                                },
                            );
                        }
                        Ok(())
                    });
                    if let Err(e) = r {
                        failures.push(e);
                    }
                }
            }
        }
    }
    eprintln!("{n} volume cases");
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
