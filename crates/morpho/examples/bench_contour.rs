//! The contour command's work (`contour::contour_samples`: Delaunay triangulation, rating,
//! external contour) against the Delaunay triangulation alone, on the same synthetic boreholes.
//!
//! ```text
//! cargo run --release -p morpho --example bench_contour -- [N] [--3d] [--reps R]
//! ```
//! N uniform random sample positions in the unit square (cube with `--3d`), ChaCha8 seed 7, a
//! smooth value field thresholded at 0.2. Each round times `triangulate_2d` (`_3d`) and then
//! `contour_samples` on the same points; prints each wall and CPU time (all threads), the minima
//! over the rounds and the ratio of the minima (the issue-23 target is ≤ 1.15). Single-threaded unless
//! `RAYON_NUM_THREADS` says otherwise.

use morpho::contour::{contour_samples, SampleContour, SampleOptions};
use morpho::delaunay::{triangulate_2d, triangulate_3d};
use morpho::geom::{Point2, Point3};
use morpho::mesh::{Column, PointSet};
use rand::{Rng, SeedableRng};
use std::time::Instant;

/// CPU nanoseconds of all threads of this process (sum of `/proc/self/task/*/schedstat`).
fn cpu_secs() -> f64 {
    let Ok(dir) = std::fs::read_dir("/proc/self/task") else {
        return f64::NAN;
    };
    let mut ns = 0u64;
    for e in dir.flatten() {
        if let Ok(s) = std::fs::read_to_string(e.path().join("schedstat")) {
            ns += s
                .split_whitespace()
                .next()
                .and_then(|x| x.parse::<u64>().ok())
                .unwrap_or(0);
        }
    }
    ns as f64 * 1e-9
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut n = 1_000_000usize;
    let mut three = false;
    let mut reps = 3usize;
    let mut i = 0;
    while i < args.len() {
        match args[i].as_str() {
            "--3d" => three = true,
            "--reps" => {
                i += 1;
                reps = args[i].parse().expect("reps");
            }
            s => n = s.parse().expect("N"),
        }
        i += 1;
    }
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    let field = |x: f64, y: f64, z: f64| {
        (7.0 * x).sin() * (5.0 * y).cos() + 0.5 * (11.0 * (x + y + z)).sin()
    };
    let (samples, tri2, tri3): (PointSet, Vec<Point2>, Vec<Point3>);
    let values: Vec<f64>;
    if three {
        tri3 = (0..n)
            .map(|_| Point3::new(rng.gen(), rng.gen(), rng.gen()))
            .collect();
        tri2 = vec![];
        values = tri3.iter().map(|p| field(p.x, p.y, p.z)).collect();
        samples = PointSet::from_points3(&tri3);
    } else {
        tri2 = (0..n).map(|_| Point2::new(rng.gen(), rng.gen())).collect();
        tri3 = vec![];
        values = tri2.iter().map(|p| field(p.x, p.y, 0.0)).collect();
        samples = PointSet::from_points2(&tri2);
    }
    let mut samples = samples;
    samples.columns.push(Column {
        name: "value".into(),
        values,
    });
    let opts = SampleOptions {
        threshold: 0.2,
        ..Default::default()
    };
    let (mut best_d, mut best_c) = (f64::INFINITY, f64::INFINITY);
    let (mut cpu_d, mut cpu_c) = (f64::INFINITY, f64::INFINITY);
    for r in 0..reps {
        let c0 = cpu_secs();
        let t = Instant::now();
        let simplices = if three {
            triangulate_3d(&tri3).expect("delaunay").tets.len()
        } else {
            triangulate_2d(&tri2).expect("delaunay").triangles.len()
        };
        let d = t.elapsed().as_secs_f64();
        let c1 = cpu_secs();
        let t = Instant::now();
        let c = contour_samples(&samples, &opts).expect("contour");
        let ct = t.elapsed().as_secs_f64();
        let c2 = cpu_secs();
        cpu_d = cpu_d.min(c1 - c0);
        cpu_c = cpu_c.min(c2 - c1);
        let what = match &c {
            SampleContour::Plane(p) => format!("{} cycles", p.contour.cycles.len()),
            SampleContour::Space(s) => format!("{} triangles", s.surface.triangles.len()),
        };
        println!(
            "round {r}: delaunay {d:.3} s (CPU {:.3}, {simplices} simplices), contour {ct:.3} s (CPU {:.3}, {what}), ratio {:.3}",
            c1 - c0,
            c2 - c1,
            ct / d
        );
        best_d = best_d.min(d);
        best_c = best_c.min(ct);
    }
    println!(
        "{} N={n}: min delaunay {best_d:.3} s (CPU {cpu_d:.3}), min contour {best_c:.3} s (CPU {cpu_c:.3}), ratio {:.3} (CPU {:.3})",
        if three { "3d" } else { "2d" },
        best_c / best_d,
        cpu_c / cpu_d
    );
}
