//! Side-by-side timing of 2D Delaunay triangulations on the same inputs: morpho, the
//! `delaunator` and `spade` crates. Run in release, single thread:
//!
//! ```text
//! cargo run --release --example bench_delaunay2d -p morpho -- [N] [--write-points FILE] [--only morpho|delaunator|spade]
//! ```
//!
//! Inputs: N uniform random points in the unit square (seeded), and a √N × √N integer grid.
//! Prints one line per (input, library) with wall-clock seconds and the ratio to delaunator, the
//! same for the process CPU time (fairer on a loaded machine), then the peak
//! resident memory (VmHWM) per point. `--write-points FILE` also writes the uniform points as
//! little-endian f64 pairs (for bench/run.sh to time scipy on the same points).

use morpho::delaunay::triangulate_2d;
use morpho::geom::Point2;
use rand::{Rng, SeedableRng};
use std::time::Instant;

fn vm_hwm_kib() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

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

fn run(name: &str, pts: &[Point2], only: Option<&str>) {
    let want = |lib: &str| only.map_or(true, |o| o == lib);
    let mut base: Option<(f64, f64)> = None;
    let line = |lib: &str, s: f64, c: f64, tris: usize, base: Option<(f64, f64)>| {
        let (rw, rc) = base.map_or((f64::NAN, f64::NAN), |(bw, bc)| (s / bw, c / bc));
        println!(
            "{name:8} {lib:10} {s:8.3} s  ratio {rw:.3}  cpu {c:7.2} s  cpu-ratio {rc:.3}  triangles {tris}"
        );
    };
    if want("delaunator") {
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
        let (s, c, d) = time(|| triangulate_2d(pts));
        let d = d.expect("triangulate");
        line("morpho", s, c, d.triangles.len(), base);
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut n = 1_000_000usize;
    let mut write = None;
    let mut only = None;
    let mut grid = true;
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
            "--no-grid" => grid = false,
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
    run("uniform", &uniform, only.as_deref());
    if grid {
        let side = (n as f64).sqrt().round() as usize;
        let g: Vec<Point2> = (0..side * side)
            .map(|k| Point2::new((k % side) as f64, (k / side) as f64))
            .collect();
        run("grid", &g, only.as_deref());
    }
    if let Some(kib) = vm_hwm_kib() {
        println!(
            "# peak memory (VmHWM) {:.1} MiB, {:.0} bytes per point (whole process, all runs)",
            kib as f64 / 1024.0,
            kib as f64 * 1024.0 / n as f64
        );
    }
}
