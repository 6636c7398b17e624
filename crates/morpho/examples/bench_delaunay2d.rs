//! Side-by-side timing of 2D Delaunay triangulations on the same inputs: morpho, the
//! `delaunator` and `spade` crates. Run in release, single thread:
//!
//! ```text
//! cargo run --release --example bench_delaunay2d -p morpho -- [N] [--write-points FILE] [--only morpho|delaunator|spade]
//!     [--dist uniform,grid,curve,curve0,circle] [--digest]
//! ```
//!
//! Inputs: N uniform random points in the unit square (seeded), a √N × √N integer grid, and N
//! points along a closed curve (`--dist` selects: `uniform`, `grid`, `curve`, `curve0`, `circle`; default
//! the first three):
//! - `curve`: the closed, non-convex "flower" r(t) = 1 + 0.3·sin(5t), x = r·cos t, y = r·sin t at
//!   t = 2πk/N (k = 0 … N−1, curve order), each coordinate moved by a uniform jitter in
//!   ±10⁻⁹ (sample spacing ≈ 8·10⁻⁶, so neighbouring points are nearly cocircular: every
//!   four consecutive samples lie within ~10⁻⁹ of their osculating circle);
//! - `curve0`: the same curve without jitter (coordinates only rounded to doubles);
//! - `circle`: N points on the unit circle at t = 2πk/N, rounded to doubles (no jitter).
//!
//! `--digest` prints, for morpho, a 64-bit FNV-1a hash of its triangle array as returned (`raw`)
//! and of the triangles as sorted input-index triples (`canon`: each triangle rotated to start at
//! its smallest input index, the list sorted), so two builds can be compared for identical output,
//! and counts the edges that fail the perturbed empty-circle test (Shewchuk's `incircle`).
//! Prints one line per (input, library) with wall-clock seconds and the ratio to delaunator, the
//! same for the process CPU time (fairer on a loaded machine), then the peak
//! resident memory (VmHWM) per point. `--write-points FILE` also writes the uniform points as
//! little-endian f64 pairs (for bench/run.sh to time scipy on the same points).

mod common;

use common::{flower_curve, grid_2d, vm_hwm_kib};
use morpho::delaunay::triangulate_2d;
use morpho::geom::Point2;
use rand::{Rng, SeedableRng};
use std::time::Instant;

/// CPU time (user + system) of this process in seconds, from /proc/self/stat (clock ticks of
/// 1/100 s); `None` where unavailable.
fn cpu_seconds() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/self/stat").ok()?;
    let rest = &s[s.rfind(')')? + 2..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    let utime: f64 = f.get(11)?.parse().ok()?;
    let stime: f64 = f.get(12)?.parse().ok()?;
    Some((utime + stime) / 100.0)
}

/// Runs `f`, returning (wall seconds, CPU seconds, result). On a loaded machine the CPU time is
/// the fairer measure; both are printed.
fn time<T>(f: impl FnOnce() -> T) -> (f64, f64, T) {
    let c0 = cpu_seconds();
    let t = Instant::now();
    let r = f();
    let wall = t.elapsed().as_secs_f64();
    let cpu = match (c0, cpu_seconds()) {
        (Some(a), Some(b)) => b - a,
        _ => f64::NAN,
    };
    (wall, cpu, r)
}

/// FNV-1a over u32 words.
fn fnv(words: impl Iterator<Item = u32>) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    for w in words {
        for b in w.to_le_bytes() {
            h = (h ^ b as u64).wrapping_mul(0x100_0000_01b3);
        }
    }
    h
}

fn digest(d: &morpho::delaunay::Delaunay2) -> (u64, u64) {
    let raw = fnv(d.triangles.iter().flatten().copied());
    let mut canon: Vec<[u32; 3]> = d
        .triangles
        .iter()
        .map(|t| {
            let t = t.map(|v| d.input_of_vertex[v as usize]);
            let k = (0..3).min_by_key(|&i| t[i]).unwrap();
            [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
        })
        .collect();
    canon.sort_unstable();
    (raw, fnv(canon.iter().flatten().copied()))
}

/// Edges that are not locally Delaunay under morpho's perturbation rule, tested with Shewchuk's
/// `incircle` (not morpho's in-circle cascade) and the tie-break only on exact zeros. Zero means
/// the result is the unique Delaunay triangulation of the perturbed points, i.e. the same
/// triangle set any correct build returns.
fn not_locally_delaunay(d: &morpho::delaunay::Delaunay2) -> usize {
    let mut bad = 0;
    for (t, tri) in d.triangles.iter().enumerate() {
        for i in 0..3 {
            let n = d.neighbors[t][i];
            if n == morpho::util::NONE || (n as usize) < t {
                continue;
            }
            let o = d.triangles[n as usize];
            let Some(&v) = o.iter().find(|v| !tri.contains(v)) else {
                bad += 1;
                continue;
            };
            let p = |k: u32| d.points[k as usize];
            let s = morpho::geom::incircle(&p(tri[0]), &p(tri[1]), &p(tri[2]), &p(v));
            if s > 0.0 || (s == 0.0 && d.incircle_sos(tri[0], tri[1], tri[2], v) > 0) {
                bad += 1;
            }
        }
    }
    bad
}

fn run(name: &str, pts: &[Point2], only: Option<&str>, dig: bool) {
    let want = |lib: &str| only.map_or(true, |o| o == lib);
    let mut base: Option<(f64, f64)> = None;
    let line = |lib: &str, s: f64, c: f64, tris: usize, base: Option<(f64, f64)>| {
        let (rw, rc) = base.map_or((f64::NAN, f64::NAN), |(bw, bc)| (s / bw, c / bc));
        println!(
            "{name:8} {lib:10} {s:8.3} s  ratio {rw:.3}  cpu {c:7.2} s  cpu-ratio {rc:.3}  triangles {tris}"
        );
    };
    // delaunator's sweep takes minutes on points along a curve (> 10 min for 10⁶ curve points
    // in one run): only with `--only delaunator` there
    let slow = matches!(name, "curve" | "curve0" | "circle") && only.is_none();
    if want("delaunator") && !slow {
        let dp: Vec<delaunator::Point> = pts
            .iter()
            .map(|p| delaunator::Point { x: p.x, y: p.y })
            .collect();
        let (s, c, t) = time(|| delaunator::triangulate(&dp));
        base = Some((s, c));
        line("delaunator", s, c, t.triangles.len() / 3, base);
    }
    if want("spade") {
        use spade::{DelaunayTriangulation, Point2 as SP, Triangulation};
        let sp: Vec<SP<f64>> = pts.iter().map(|p| SP::new(p.x, p.y)).collect();
        let (s, c, t) = time(|| DelaunayTriangulation::<SP<f64>>::bulk_load(sp).ok());
        let nt = t.map(|t| t.num_inner_faces()).unwrap_or(0);
        line("spade", s, c, nt, base);
    }
    if want("morpho") {
        use morpho::internals::predicate_stats as ps;
        ps::reset();
        let (s, c, d) = time(|| triangulate_2d(pts));
        let k = ps::snapshot();
        if k.iter().any(|&x| x > 0) {
            // built with --features morpho/predicate-stats
            let calls: u64 = k[..4].iter().sum();
            let share = |x: u64| 100.0 * x as f64 / calls.max(1) as f64;
            println!(
                "{name:8} morpho     incircle calls {calls}: filter {:.2} %, integer {:.3} %, expansion {:.3} %, full cascade {:.3} %, zero (perturbation) {:.3} %; walk steps/point {:.2}, flips/point {:.2}",
                share(k[0]), share(k[1]), share(k[2]), share(k[3]), share(k[4]),
                k[5] as f64 / pts.len() as f64, k[6] as f64 / pts.len() as f64
            );
        }
        let d = d.expect("triangulate");
        line("morpho", s, c, d.triangles.len(), base);
        if dig {
            let (r, c) = digest(&d);
            println!(
                "{name:8} morpho     digest raw {r:016x} canon {c:016x}, edges not locally Delaunay {}",
                not_locally_delaunay(&d)
            );
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut n = 1_000_000usize;
    let mut write = None;
    let mut only = None;
    let mut dists: Vec<String> = vec!["uniform".into(), "grid".into(), "curve".into()];
    let mut dig = false;
    let mut i = 0;
    while i < args.len() {
        match args[i].as_str() {
            "--write-points" => {
                write = args.get(i + 1).cloned();
                i += 1;
            }
            "--only" => {
                only = args.get(i + 1).cloned();
                i += 1;
            }
            "--no-grid" => dists.retain(|d| d != "grid"),
            "--digest" => dig = true,
            "--dist" => {
                dists = args[i + 1].split(',').map(String::from).collect();
                i += 1;
            }
            a => n = a.parse().expect("N must be an integer"),
        }
        i += 1;
    }
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(42);
    let uniform: Vec<Point2> = (0..n)
        .map(|_| Point2::new(rng.gen::<f64>(), rng.gen::<f64>()))
        .collect();
    if let Some(path) = write {
        let mut bytes = Vec::with_capacity(16 * n);
        for p in &uniform {
            bytes.extend_from_slice(&p.x.to_le_bytes());
            bytes.extend_from_slice(&p.y.to_le_bytes());
        }
        std::fs::write(&path, bytes).expect("write points");
    }
    println!("# 2D Delaunay, single thread, N = {n}");
    for dist in &dists {
        match dist.as_str() {
            "uniform" => run("uniform", &uniform, only.as_deref(), dig),
            "grid" => run("grid", &grid_2d(n), only.as_deref(), dig),
            "curve" => run("curve", &flower_curve(n), only.as_deref(), dig),
            "curve0" => {
                // the same curve without jitter (coordinates rounded to doubles only)
                let tau = std::f64::consts::TAU;
                let c: Vec<Point2> = (0..n)
                    .map(|k| {
                        let t = tau * k as f64 / n as f64;
                        let r = 1.0 + 0.3 * (5.0 * t).sin();
                        Point2::new(r * t.cos(), r * t.sin())
                    })
                    .collect();
                run("curve0", &c, only.as_deref(), dig);
            }
            "circle" => {
                let tau = std::f64::consts::TAU;
                let c: Vec<Point2> = (0..n)
                    .map(|k| {
                        let t = tau * k as f64 / n as f64;
                        Point2::new(t.cos(), t.sin())
                    })
                    .collect();
                run("circle", &c, only.as_deref(), dig);
            }
            d => panic!("unknown --dist {d}"),
        }
    }
    if let Some(kib) = vm_hwm_kib() {
        println!(
            "# peak memory (VmHWM) {:.1} MiB, {:.0} bytes per point (whole process, all runs)",
            kib as f64 / 1024.0,
            kib as f64 * 1024.0 / n as f64
        );
    }
}
