//! Time of Hamann's transparency view (H §2.2, issue 22: a 64³ volume in under 1 s on one
//! core), in process, the picture of
//! `morpho render --function hamann-exp --view transparency --grid 64 --transparency 0.5 -o t.png`
//! (800×600, supersample 2, azimuth 35°, elevation 25°, z up, colour bar) without the PNG write.
//!
//! Usage: `cargo run --release -p morpho --example bench_transparency -- [GRID] [T] [SS]`
//! (defaults 64, 0.5, 2). Runs the view in a 1-thread and a 2-thread rayon pool, `REPS` times
//! each (default 3), and prints one JSON object per pool: the minimum wall and process CPU
//! (user + system, `getrusage`) seconds, the load average before the runs, the rectangles
//! drawn, and a checksum of the picture (equal for both pools: the output does not depend on
//! the thread count).

use morpho::render::{render_view, Formula, RenderOptions, Source, UpAxis, View, ViewOptions};
use std::time::Instant;

/// User + system CPU seconds of the whole process.
fn process_cpu() -> f64 {
    // SAFETY: getrusage writes the struct it is given; zeroed is a valid rusage.
    let mut ru: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: a valid pointer to a rusage for the calling process.
    if unsafe { libc::getrusage(libc::RUSAGE_SELF, &mut ru) } != 0 {
        return f64::NAN;
    }
    let s = |t: libc::timeval| t.tv_sec as f64 + t.tv_usec as f64 * 1e-6;
    s(ru.ru_utime) + s(ru.ru_stime)
}

fn loadavg() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_default()
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let grid: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(64);
    let t: f64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(0.5);
    let ss: u32 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(2);
    let reps: usize = std::env::var("REPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(3);
    let src = Source::Formula {
        formula: Formula::HamannExp,
        grid,
    };
    let view = View::Transparency { n: None, t };
    let opts = ViewOptions {
        render: RenderOptions {
            up: UpAxis::Z,
            supersample: ss,
            ..Default::default()
        },
        ..Default::default()
    };
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("thread pool");
        let load = loadavg();
        let (mut wall, mut cpu) = (f64::INFINITY, f64::INFINITY);
        let mut sum = 0u64;
        let mut rects = 0;
        for _ in 0..reps {
            let (c0, w0) = (process_cpu(), Instant::now());
            let pic = pool
                .install(|| render_view(&src, &view, &opts))
                .expect("the view renders");
            wall = wall.min(w0.elapsed().as_secs_f64());
            cpu = cpu.min(process_cpu() - c0);
            rects = pic.primitives;
            sum = pic.image.rgba.iter().fold(0u64, |h, &b| {
                (h ^ u64::from(b)).wrapping_mul(0x100_0000_01b3)
            });
        }
        println!(
            "{{\"grid\": {grid}, \"t\": {t}, \"supersample\": {ss}, \"threads\": {threads}, \
             \"rectangles\": {rects}, \"wall_s\": {wall:.3}, \"cpu_s\": {cpu:.3}, \
             \"load_before\": \"{load}\", \"reps\": {reps}, \"checksum\": \"{sum:016x}\"}}"
        );
    }
}
