//! The three 2D boundary methods on the real point sets with a ground truth (issue 5: "Run all
//! three methods on the 2D point sets with ground truth in ../shared/data … per data set and
//! method, whether the result is valid, the fraction of ground-truth edges recovered, and the
//! time").
//!
//! Sets (`../shared/data`, see its README):
//! - `curves2d/svg_groundtruth/*_samples*.csv` with a single closed component (`order` column =
//!   the truth polygon);
//! - `curves2d/ohrhallinger_fitconnect/*_2percent_noise.txt` (file order = the outline);
//! - the everyday-object outlines of fitconnect (`Cup0` …): no stated order, so only validity
//!   and time are reported;
//! - `polygons/*.csv` rings (the ring order is the truth; a closing repeat of the first vertex
//!   is dropped): the Meuse outline, the Benelux mainland (Veltkamp's "flintstone" outline, his
//!   Fig. 5.3), and four coastlines.
//!
//! The points are shuffled (seed 17) so that no method can profit from the file order. Methods:
//! γ-indicator with `--c auto` (V §5.2, §5.4), minimal area change (V §4.3.3, also with the
//! fallback) and the shortest Voronoi skeleton (V §4.3.4, the CLI's default 200 seeds). "valid"
//! = the exact simple-polygon check of `boundary::check_polygon` passes (counter-clockwise,
//! no two edges meeting except neighbours at their shared vertex); "left out" = points not on it; "recovered" = the fraction of ground-truth edges that are polygon edges.
//!
//! `cargo run --release -p morpho --example bench_boundary2d [FILTER]` prints a Markdown table
//! (rows whose set name contains FILTER only).

mod common;

use morpho::boundary::{boundary_2d, check_polygon, Options2};
use morpho::geom::Point2;
use rand::seq::SliceRandom;
use rand::SeedableRng;
use std::collections::HashSet;
use std::time::Instant;

/// A point set in truth order (`truth` = whether that order is a ground-truth polygon).
struct Set {
    name: String,
    points: Vec<Point2>,
    truth: bool,
}

fn load(dir: &std::path::Path) -> Vec<Set> {
    let mut sets = Vec::new();
    let mut add = |rel: &str, truth: bool| {
        let path = dir.join(rel);
        let Ok(ps) = morpho::io::read_points(&path) else {
            eprintln!("{rel}: missing or unreadable, skipped");
            return;
        };
        let mut pts = ps.to_points2();
        if let Some(order) = ps.column("order") {
            let mut idx: Vec<usize> = (0..pts.len()).collect();
            idx.sort_by(|&a, &b| order.values[a].total_cmp(&order.values[b]));
            pts = idx.iter().map(|&i| pts[i]).collect();
        }
        if pts.len() > 1 && pts.first() == pts.last() {
            pts.pop();
        }
        let name = rel.rsplit('/').next().unwrap_or(rel).to_string();
        sets.push(Set {
            name,
            points: pts,
            truth,
        });
    };
    for f in ["simple", "blob2", "spiral"] {
        add(&format!("curves2d/svg_groundtruth/{f}_samples.csv"), true);
        add(
            &format!("curves2d/svg_groundtruth/{f}_samples_sparse.csv"),
            true,
        );
    }
    for f in ["apple", "butterfly", "crab", "dolphin"] {
        add(
            &format!("curves2d/ohrhallinger_fitconnect/{f}_2percent_noise.txt"),
            true,
        );
    }
    for f in ["Cup0", "Mouse0", "Keyboard0", "Monitor0"] {
        add(&format!("curves2d/ohrhallinger_fitconnect/{f}.txt"), false);
    }
    for f in [
        "meuse_riv",
        "benelux_mainland_ne50m",
        "benelux_mainland_ne10m",
        "coast_ireland_ne10m",
        "coast_iceland_ne10m",
        "coast_great_britain_ne10m",
        "coast_australia_mainland_ne10m",
    ] {
        add(&format!("polygons/{f}.csv"), true);
    }
    sets
}

fn edge_set(c: &[u32]) -> HashSet<(u32, u32)> {
    let n = c.len();
    (0..n)
        .map(|k| {
            let (a, b) = (c[k], c[(k + 1) % n]);
            (a.min(b), a.max(b))
        })
        .collect()
}

fn main() {
    let filter = std::env::args().nth(1).unwrap_or_default();
    let Some(dir) = common::data_dir() else {
        eprintln!("../shared/data not found");
        return;
    };
    println!("| set | points | method | valid | left out | recovered | c used | time |");
    println!("|---|---|---|---|---|---|---|---|");
    for set in load(&dir) {
        if !set.name.contains(&filter) {
            continue;
        }
        let n = set.points.len();
        let mut idx: Vec<u32> = (0..n as u32).collect();
        idx.shuffle(&mut rand_chacha::ChaCha8Rng::seed_from_u64(17));
        let pts: Vec<Point2> = idx.iter().map(|&i| set.points[i as usize]).collect();
        // truth polygon in shuffled indices: the original k-th point now sits at pos[k]
        let mut pos = vec![0u32; n];
        for (new, &old) in idx.iter().enumerate() {
            pos[old as usize] = new as u32;
        }
        let truth = edge_set(&pos);
        for opts in [
            Options2::gamma(),
            Options2::min_area_change(),
            Options2::voronoi_skeleton(200),
        ] {
            let m = &opts.method;
            let t = Instant::now();
            let r = boundary_2d(&pts, &opts);
            let el = t.elapsed().as_secs_f64();
            match r {
                Err(e) => println!("| {} | {n} | {} | error: {e} | | | | |", set.name, m.name()),
                Ok(b) => {
                    let chk = check_polygon(&pts, &b.polygon);
                    let valid = chk.simple && chk.area2 > 0.0;
                    let rec = if set.truth {
                        let got = edge_set(&b.polygon);
                        let k = truth.intersection(&got).count();
                        format!("{:.1} %", 100.0 * k as f64 / truth.len() as f64)
                    } else {
                        "—".to_string()
                    };
                    println!(
                        "| {} | {n} | {} | {} | {} | {rec} | {} | {:.1} ms |",
                        set.name,
                        m.name(),
                        if valid { "yes" } else { "no" },
                        b.left_out.len(),
                        b.c_used,
                        el * 1e3
                    );
                }
            }
        }
    }
}
