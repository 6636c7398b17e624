//! 3D boundary timing against the 3D Delaunay tetrahedralization (issue 5: "3D, 100k points of
//! a scan: total time within 5× of the 3D Delaunay time; report memory").
//!
//! Sets: the horse's 48 485 vertices, 100 000 points sampled uniformly on the horse's surface
//! (area-weighted triangles, uniform barycentric coordinates, seed 1), and the Stanford bunny's
//! 34 834 used vertices. For each: Delaunay time, the boundary_3d phases (Delaunay inside it,
//! constriction, fallback, checks), the ratio boundary/Delaunay, the result's validity and the
//! peak resident memory (VmHWM, process-wide, so printed after each set in order).
//!
//! `cargo run --release -p morpho --example bench_boundary3d [horse|horse100k|bunny ...]`
//!
//! Each set runs the Delaunay tetrahedralization and `boundary_3d` alternately three times and
//! reports the ratio of the minima. Latest (2026-11-23 21:14 UTC, current main, shared machine
//! at load 1.6): bunny 0.57 s = 3.09× its Delaunay time (282 triangles added), horse 0.75 s =
//! 3.25× (888 added), horse 100k 2.56 s = 4.11× (8823 added); all 0 left out, closed, genus 0,
//! no intersections. (The numbers before 18:00 came from γ decisions that stopped too early;
//! see `bench/README.md`.)
//! The history of these numbers (82× in the morning) and the phase breakdown are in
//! `bench/README.md` ("3D (`bench_boundary3d`)").
//!
//! `... --example bench_boundary3d file PATH [phases]` runs (or phases) the points of a file, e.g.
//! those of `bench/dragon_points.py`.
//!
//! `... --example bench_boundary3d phases [bunny|horse|horse100k]` prints the time of every
//! step of the general engine (as `boundary_3d_with` runs it); `... check [horse100k]` times
//! the exact self-intersection check of every pair alone (three runs); `... constrict
//! [horse100k]` the Delaunay constriction alone (five runs).
//!
//! The check alone on horse 100k (199 556 triangles; `check horse100k`, the process's CPU time
//! alongside), measured 2026-11-23 16:35 UTC, machine loaded by other jobs (`uptime` load
//! 3.1–3.3 on 2 cores, so wall ≈ CPU): before the check3 changes best 1.63 s wall / 1.62 s CPU,
//! after them best 0.68 s / 0.67 s (2.4×); on a quieter machine (load 1.2–1.7) 0.82 s wall /
//! 1.57 s CPU before, ≈ 0.53 s / 1.0 s after the broad-phase changes alone. Of the pair work:
//! 81.6 M cell-pair candidates became the 13.9 M owned pairs, the big-triangle walk's 18.8 M
//! duplicate candidates are stamped away, and 490 k exact triangle–triangle tests became
//! 2-predicate Guigue–Devillers decisions (a few hundred exact tests remain).
//!
//! `... --example bench_boundary3d keys` (only when asked): the γ-indicator against Boissonnat's
//! minimal area change (V §4.3.3, Eq. 4.1) on bunny_npm.obj and spot.obj (every mesh vertex is
//! a point, same index), each with the Delaunay constriction alone (`CParam::Fixed(0.0)`) and
//! with the fallback (`CParam::Auto`): points left out, closed/genus/self-intersections, the
//! fraction of the mesh's triangles (sorted vertex triples) on the result, time.
//!
//! Measured 2026-11-23 (release): neither key locks on these meshes, so Fixed(0) and Auto are
//! identical; every point on a closed genus-0 mesh without self-intersections in all runs.
//!
//! | mesh (V, T) | key | left out | recovered triangles | time |
//! |---|---|---|---|---|
//! | bunny_npm (1839, 3674) | γ-indicator | 0 | 2325 = 63.3 % | 0.02 s |
//! | bunny_npm | min area change | 0 | 951 = 25.9 % | 0.02 s |
//! | spot (2930, 5856) | γ-indicator | 0 | 4030 = 68.8 % | 0.05 s |
//! | spot | min area change | 0 | 1557 = 26.6 % | 0.05 s |

mod common;

use morpho::boundary::Until;
use morpho::boundary::{boundary_3d, CParam, Method3, Options3};
use morpho::geom::Point3;
use morpho::internals::constrict_3d;
use morpho::mesh::validity;
use rand::{Rng, SeedableRng};
use std::time::Instant;

fn vm_hwm_mb() -> f64 {
    let s = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    s.lines()
        .find(|l| l.starts_with("VmHWM:"))
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|k| k.parse::<f64>().ok())
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

/// CPU time (user + system) of the whole process so far, all threads (`/proc/self/stat`,
/// clock ticks of 1/100 s); NaN where unavailable.
fn cpu_seconds() -> f64 {
    let s = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    // fields after the command name (which is in parentheses): state is field 3, utime 14
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

fn used_vertices(m: &morpho::mesh::TriMesh) -> Vec<Point3> {
    let mut used = vec![false; m.positions.len()];
    for t in &m.triangles {
        for &v in t {
            used[v as usize] = true;
        }
    }
    m.positions
        .iter()
        .zip(&used)
        .filter(|(_, &u)| u)
        .map(|(p, _)| *p)
        .collect()
}

/// The horse's vertices, or 100 000 points sampled on its surface (`hundred_k`).
fn horse_points(dir: &std::path::Path, hundred_k: bool) -> Vec<Point3> {
    let horse = morpho::io::read_mesh(&dir.join("meshes/horse.obj.gz")).expect("horse");
    if hundred_k {
        sample_surface(&horse, 100_000, 1)
    } else {
        used_vertices(&horse)
    }
}

/// `n` points uniformly distributed on the mesh surface (deterministic).
fn sample_surface(m: &morpho::mesh::TriMesh, n: usize, seed: u64) -> Vec<Point3> {
    let mut cum = Vec::with_capacity(m.triangles.len());
    let mut total = 0.0;
    for t in &m.triangles {
        let [a, b, c] = t.map(|v| m.positions[v as usize]);
        total += 0.5 * (b - a).cross(&(c - a)).norm();
        cum.push(total);
    }
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| {
            let x = rng.gen_range(0.0..total);
            let k = cum.partition_point(|&c| c < x).min(cum.len() - 1);
            let [a, b, c] = m.triangles[k].map(|v| m.positions[v as usize]);
            let (mut u, mut v): (f64, f64) = (rng.gen_range(0.0..1.0), rng.gen_range(0.0..1.0));
            if u + v > 1.0 {
                (u, v) = (1.0 - u, 1.0 - v);
            }
            a + (b - a) * u + (c - a) * v
        })
        .collect()
}

fn run(name: &str, pts: &[Point3]) {
    // Delaunay and boundary_3d alternately, three times each: the ratio of the minima (the
    // machine's load moves single runs by ±20 %)
    let mut dts = Vec::new();
    let mut alls = Vec::new();
    let mut mem_dt = f64::NAN;
    let mut b = None;
    for _ in 0..RUNS {
        let t = Instant::now();
        let d = morpho::delaunay::triangulate_3d(pts).expect("triangulate");
        dts.push(t.elapsed().as_secs_f64());
        if mem_dt.is_nan() {
            mem_dt = vm_hwm_mb();
        }
        drop(d);
        let t = Instant::now();
        b = Some(boundary_3d(pts, &Options3::gamma(Until::All)).expect("boundary"));
        alls.push(t.elapsed().as_secs_f64());
    }
    let b = b.expect("runs");
    let min = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
    let (t_dt, t_all) = (min(&dts), min(&alls));
    let each = |v: &[f64]| {
        v.iter()
            .map(|x| format!("{x:.2}"))
            .collect::<Vec<_>>()
            .join("/")
    };
    let d = morpho::delaunay::triangulate_3d(pts).expect("triangulate");
    let t = Instant::now();
    let c = constrict_3d(&d, Until::All);
    let t_con = t.elapsed().as_secs_f64();
    let pos: Vec<[f64; 3]> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
    let t = Instant::now();
    let _ = validity::self_intersections(&pos, &c.triangles, 10);
    let t_si = t.elapsed().as_secs_f64();
    drop(d);
    println!(
        "{name}: {} points | delaunay {t_dt:.2} s (min of {RUNS}: {}) | phases: constriction {t_con:.2} s ({} removals, {} left by Delaunay constriction), full self-intersection check (every pair, as `morpho info --check`) {t_si:.2} s | boundary_3d total {t_all:.2} s (min of {RUNS}: {}) = {:.2}× delaunay | left out {}, c_used {}, added {}, closed {}, genus {:?}, intersections {} | VmHWM after delaunay {mem_dt:.0} MB, after boundary {:.0} MB",
        pts.len(),
        each(&dts),
        c.iterations,
        pts.len() - c.boundary_vertices.min(pts.len()),
        each(&alls),
        t_all / t_dt,
        b.left_out.len(),
        b.c_used,
        b.added_triangles,
        b.closed_manifold,
        b.genus,
        b.intersections.len(),
        vm_hwm_mb()
    );
}

/// The key comparison on one mesh (see the module documentation).
fn compare_keys(name: &str, m: &morpho::mesh::TriMesh) {
    let sorted = |t: &[u32; 3]| {
        let mut s = *t;
        s.sort_unstable();
        s
    };
    let orig: std::collections::HashSet<[u32; 3]> = m.triangles.iter().map(sorted).collect();
    println!(
        "{name}: {} vertices ({} used), {} triangles",
        m.positions.len(),
        used_vertices(m).len(),
        m.triangles.len()
    );
    for mac in [false, true] {
        for (cname, c) in [("Fixed(0)", CParam::Fixed(0.0)), ("Auto", CParam::Auto)] {
            let (until, keep) = (Until::All, Vec::new());
            let method = if mac {
                Method3::MinAreaChange { c, until, keep }
            } else {
                Method3::Gamma { c, until, keep }
            };
            let opts = Options3 { method };
            let mname = if mac { "MinAreaChange" } else { "Gamma" };
            let t = Instant::now();
            let b = boundary_3d(&m.positions, &opts).expect("boundary");
            let secs = t.elapsed().as_secs_f64();
            let hit = b
                .triangles
                .iter()
                .filter(|t| orig.contains(&sorted(t)))
                .count();
            println!(
                "  {mname} {cname}: left out {}, closed {}, genus {:?}, intersections {}, c_used {}, added {}, triangles {}, recovered {hit}/{} = {:.1} %, {secs:.2} s",
                b.left_out.len(),
                b.closed_manifold,
                b.genus,
                b.intersections.len(),
                b.c_used,
                b.added_triangles,
                b.triangles.len(),
                orig.len(),
                100.0 * hit as f64 / orig.len() as f64
            );
        }
    }
}

/// Runs of the Delaunay tetrahedralization and of boundary_3d per set in [`run`].
const RUNS: usize = 3;

/// A wall-clock and CPU stopwatch for [`phases`].
struct Watch(Instant, f64);

impl Watch {
    fn start() -> Self {
        Watch(Instant::now(), cpu_seconds())
    }
    /// "wall s (cpu s)"
    fn show(&self) -> String {
        format!(
            "{:.3} s (cpu {:.2})",
            self.0.elapsed().as_secs_f64(),
            cpu_seconds() - self.1
        )
    }
}

/// Phase timing of the fallback path (`phases` argument): constriction, engine construction,
/// each run / local_gamma / augment step, final checks.
fn phases(name: &str, pts: &[Point3]) {
    use morpho::internals::General3;
    let t = Watch::start();
    let d = morpho::delaunay::triangulate_3d(pts).expect("triangulate");
    let t_dt = t.show();
    let t = Watch::start();
    let st = constrict_3d(&d, Until::All);
    println!("{name}: delaunay {t_dt}, constriction {}", t.show());
    let pos: Vec<[f64; 3]> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
    let t = Watch::start();
    // the region of boundary_3d_with (near_locked, depth 4)
    let mut on = vec![false; d.points.len()];
    for t in &st.triangles {
        for &v in t {
            on[v as usize] = true;
        }
    }
    let mut region = vec![false; d.tets.len()];
    let mut front: Vec<u32> = Vec::new();
    for (t, tet) in d.tets.iter().enumerate() {
        if st.alive[t] && tet.iter().any(|&v| !on[v as usize]) {
            region[t] = true;
            front.push(t as u32);
        }
    }
    for _ in 0..4 {
        let mut next = Vec::new();
        for &t in &front {
            for &n in &d.neighbors[t as usize] {
                if n != morpho::util::NONE && st.alive[n as usize] && !region[n as usize] {
                    region[n as usize] = true;
                    next.push(n);
                }
            }
        }
        front = next;
    }
    let mut live = Vec::new();
    for (ti, tet) in d.tets.iter().enumerate() {
        if region[ti] {
            for (fi, f) in morpho::delaunay::FACE_OF.iter().enumerate() {
                let n = d.neighbors[ti][fi];
                let mut s = [tet[f[0]], tet[f[1]], tet[f[2]]];
                s.sort_unstable();
                if n == morpho::util::NONE || !region[n as usize] || (ti as u32) < n {
                    live.push(s);
                }
            }
        }
    }
    let mut g = General3::new(&pos, &st.triangles, &live, &[]);
    println!("  new: {} ({} live)", t.show(), live.len());
    let t = Watch::start();
    g.run();
    println!(
        "  run0: {}, bv {}/{}",
        t.show(),
        g.boundary_vertices,
        pos.len()
    );
    let mut step = 1;
    while !g.done() && step <= 10 {
        let c = -(step as f64) / 10.0;
        let t = Watch::start();
        let extra = g.local_gamma(c, 16);
        let t_lg = t.show();
        let t = Watch::start();
        let a = g.augment(&extra);
        let t_au = t.show();
        let t = Watch::start();
        if a > 0 {
            g.run();
        }
        println!(
            "  c {c}: local_gamma {t_lg} ({} tris), augment {t_au} ({a} added), run {}, bv {}/{}",
            extra.len(),
            t.show(),
            g.boundary_vertices,
            pos.len()
        );
        step += 1;
    }
    if !g.done() {
        let t = Watch::start();
        let n = g.insert_left_out();
        if n > 0 {
            g.run();
        }
        println!(
            "  insert_left_out: {} ({n} put on the boundary), bv {}/{}",
            t.show(),
            g.boundary_vertices,
            pos.len()
        );
    }
    let t = Watch::start();
    let b = g.boundary();
    let delaunay_face = validity::faces_of_tetrahedra(&d.tets, &b);
    let si = validity::self_intersections_trusting(&pos, &b, &delaunay_face, 10);
    println!(
        "  final check {} ({} intersections), iterations {}",
        t.show(),
        si.len(),
        g.iterations
    );
}

fn main() {
    let Some(dir) = common::data_dir() else {
        eprintln!("shared data not found");
        return;
    };
    let args: Vec<String> = std::env::args().skip(1).collect();
    let want = |s: &str| args.is_empty() || args.iter().any(|a| a == s);
    if let Some(i) = args.iter().position(|a| a == "file") {
        // `file PATH [phases]`: a point file (e.g. of bench/dragon_points.py)
        let path = std::path::Path::new(args.get(i + 1).expect("file PATH"));
        let ps = morpho::io::read_points(path).expect("points");
        assert_eq!(ps.dim, 3, "3D points");
        let pts: Vec<Point3> = ps
            .coords
            .chunks_exact(3)
            .map(|c| Point3::new(c[0], c[1], c[2]))
            .collect();
        let name = path.display().to_string();
        if want("phases") {
            phases(&name, &pts);
        } else {
            run(&name, &pts);
        }
        return;
    }
    if args.iter().any(|a| a == "keys") {
        for f in ["bunny_npm.obj", "spot.obj"] {
            let m = morpho::io::read_mesh(&dir.join("meshes").join(f)).expect("mesh");
            compare_keys(f, &m);
        }
        if args.len() == 1 {
            return;
        }
    }
    if args.iter().any(|a| a == "check") {
        let pts = horse_points(&dir, want("horse100k"));
        let d = morpho::delaunay::triangulate_3d(&pts).expect("triangulate");
        let c = constrict_3d(&d, Until::All);
        let pos: Vec<[f64; 3]> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
        for _ in 0..3 {
            let (t, cpu) = (Instant::now(), cpu_seconds());
            let n = validity::self_intersections(&pos, &c.triangles, 10).len();
            println!(
                "check {} triangles: {:.3} s wall, {:.2} s CPU ({n})",
                c.triangles.len(),
                t.elapsed().as_secs_f64(),
                cpu_seconds() - cpu
            );
        }
        return;
    }
    if args.iter().any(|a| a == "constrict") {
        let pts = horse_points(&dir, want("horse100k"));
        let d = morpho::delaunay::triangulate_3d(&pts).expect("triangulate");
        for _ in 0..5 {
            let (t, cpu) = (Instant::now(), cpu_seconds());
            let c = constrict_3d(&d, Until::All);
            println!(
                "constriction of {} tetrahedra: {:.3} s wall, {:.2} s CPU ({} removals)",
                d.tets.len(),
                t.elapsed().as_secs_f64(),
                cpu_seconds() - cpu,
                c.iterations
            );
        }
        return;
    }
    if args.iter().any(|a| a == "phases") {
        let horse = morpho::io::read_mesh(&dir.join("meshes/horse.obj.gz")).expect("horse");
        let bunny =
            morpho::io::read_mesh(&dir.join("meshes/stanford-bunny.obj.gz")).expect("bunny");
        if want("bunny") {
            phases("bunny", &used_vertices(&bunny));
        }
        if want("horse") {
            phases("horse", &used_vertices(&horse));
        }
        if want("horse100k") {
            phases("horse100k", &sample_surface(&horse, 100_000, 1));
        }
        return;
    }
    let horse = morpho::io::read_mesh(&dir.join("meshes/horse.obj.gz")).expect("horse");
    if want("horse") {
        run("horse vertices", &used_vertices(&horse));
    }
    if want("horse100k") {
        run(
            "horse 100k surface samples",
            &sample_surface(&horse, 100_000, 1),
        );
    }
    if want("bunny") {
        let m = morpho::io::read_mesh(&dir.join("meshes/stanford-bunny.obj.gz")).expect("bunny");
        run("stanford bunny vertices", &used_vertices(&m));
    }
}
