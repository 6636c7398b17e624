//! Throughput of `volume::isosurface` for peer comparison (bench/isosurface_peers.py).
//!
//! Usage: `cargo run --release -p morpho --example bench_isosurface -- [N] [RAW_OUT] [RAW_IN DIMS]`
//! * builds an N³ f32 gyroid-like field (default N = 256) on [0, 6π]³, level 0, or reads a raw
//!   little-endian f32 volume `RAW_IN` with dims "nx,ny,nz" and level from `LEVEL` (env);
//! * optionally writes the volume as raw little-endian f32 to `RAW_OUT` (x fastest);
//! * times single-thread and all-core runs of several option sets (one run each, no
//!   warm-up) and prints one JSON object per line: wall seconds, CPU seconds (thread CPU time
//!   for the single-thread run, process CPU time otherwise — use these on a loaded machine),
//!   triangles per wall second, and the process's peak RSS (VmHWM);
//!   `VARIANT=name` runs only that option set; `REPS=k` repeats each run and reports the
//!   minimum wall and CPU times.

use morpho::volume::Volume;
use morpho::volume::{isosurface, IsoMethod, IsoOptions, NormalMethod};
use std::io::Write;
use std::time::Instant;

fn peak_rss_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1))
                .and_then(|v| v.parse::<f64>().ok())
        })
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

/// CPU time of the calling thread in seconds (Linux /proc/thread-self/schedstat).
fn thread_cpu() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or(f64::NAN, |ns| ns * 1e-9)
}

/// CPU time of the process in seconds (user + system, 100 Hz ticks).
fn process_cpu() -> f64 {
    std::fs::read_to_string("/proc/self/stat")
        .ok()
        .and_then(|s| {
            let rest = &s[s.rfind(')')? + 2..];
            let f: Vec<&str> = rest.split_whitespace().collect();
            Some((f[11].parse::<f64>().ok()? + f[12].parse::<f64>().ok()?) / 100.0)
        })
        .unwrap_or(f64::NAN)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(256);
    let mut level = 0.0;
    let vol = if let (Some(path), Some(dims)) = (args.get(3), args.get(4)) {
        let d: Vec<usize> = dims.split(',').map(|s| s.parse().unwrap()).collect();
        let bytes = std::fs::read(path).unwrap();
        let data: Vec<f32> = bytes
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect();
        level = std::env::var("LEVEL")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(0.0);
        Volume::new([d[0], d[1], d[2]], [0.0; 3], [1.0; 3], data).unwrap()
    } else {
        let t = 6.0 * std::f64::consts::PI;
        Volume::from_fn([n; 3], [0.0; 3], [t; 3], |x, y, z| {
            x.sin() * y.cos() + y.sin() * z.cos() + z.sin() * x.cos()
        })
    };
    if let Some(out) = args.get(2).filter(|s| !s.is_empty() && *s != "-") {
        let mut f = std::io::BufWriter::new(std::fs::File::create(out).unwrap());
        for v in &vol.data {
            f.write_all(&v.to_le_bytes()).unwrap();
        }
    }
    let threads_all = rayon::current_num_threads();
    let variants = [
        (
            "decider_nonormals_notopo",
            IsoMethod::Decider,
            NormalMethod::None,
            false,
        ),
        (
            "decider_central_notopo",
            IsoMethod::Decider,
            NormalMethod::Central,
            false,
        ),
        (
            "decider_zucker_topo",
            IsoMethod::Decider,
            NormalMethod::ZuckerHummel,
            true,
        ),
        (
            "decider_zucker_notopo",
            IsoMethod::Decider,
            NormalMethod::ZuckerHummel,
            false,
        ),
        (
            "decider_nonormals_topo",
            IsoMethod::Decider,
            NormalMethod::None,
            true,
        ),
        (
            "tetra_nonormals_notopo",
            IsoMethod::Tetra,
            NormalMethod::None,
            false,
        ),
        (
            "lorensen_nonormals_notopo",
            IsoMethod::Lorensen,
            NormalMethod::None,
            false,
        ),
    ];
    let only = std::env::var("VARIANT").ok();
    let reps: usize = std::env::var("REPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1)
        .max(1);
    for (name, method, normals, topology) in variants {
        if only.as_deref().is_some_and(|o| o != name) {
            continue;
        }
        for threads in [1, threads_all] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let opts = IsoOptions {
                level,
                method,
                normals,
                flip: false,
                parallel: threads > 1,
                topology,
            };
            // (wall, cpu, vertices, triangles, parts, interior holes); results are not kept so
            // that the peak RSS reflects one run
            let mut best: Option<(f64, f64, usize, usize, usize, usize)> = None;
            for _ in 0..reps {
                let (secs, cpu, r) = if threads == 1 {
                    // on this thread: its CPU time is meaningful on a loaded machine
                    let (c0, t) = (thread_cpu(), Instant::now());
                    let r = isosurface(&vol, &opts).unwrap();
                    (t.elapsed().as_secs_f64(), thread_cpu() - c0, r)
                } else {
                    pool.install(|| {
                        let (c0, t) = (process_cpu(), Instant::now());
                        let r = isosurface(&vol, &opts).unwrap();
                        (t.elapsed().as_secs_f64(), process_cpu() - c0, r)
                    })
                };
                let (bs, bc) = best.map_or((f64::MAX, f64::MAX), |b| (b.0, b.1));
                best = Some((
                    secs.min(bs),
                    cpu.min(bc),
                    r.mesh.positions.len(),
                    r.mesh.triangles.len(),
                    r.parts,
                    r.interior_holes,
                ));
            }
            let Some((secs, cpu, nv, nt, parts, holes)) = best else {
                continue;
            };
            println!(
                "{{\"variant\":\"{name}\",\"threads\":{threads},\"dims\":{:?},\"seconds\":{secs:.4},\"cpu_seconds\":{cpu:.4},\"vertices\":{nv},\"triangles\":{nt},\"tri_per_s\":{:.0},\"parts\":{parts},\"interior_holes\":{holes},\"peak_rss_mb\":{:.1}}}",
                vol.dims,
                nt as f64 / secs,
                peak_rss_mb()
            );
        }
    }
}
