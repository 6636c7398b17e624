//! The three 3D boundary methods of issue 5 on the vertex sets of the meshes in shared/data
//! (every mesh vertex is a point, same index, as in `bench_boundary3d keys`): the γ-indicator
//! constriction with the fallback (`CParam::Auto`), Boissonnat's minimal area change
//! (Delaunay constriction alone, `CParam::Fixed(0)`), and the shortest Voronoi skeleton
//! (O'Rourke et al., V §4.3.4, `max_seeds` 200 and, for small sets, every tetrahedron as a
//! seed). For each: points left out, closed / genus / exact self-intersections, the fraction of
//! the mesh's triangles (sorted vertex triples) on the result, the skeleton length, time.
//!
//! `cargo run --release -p morpho --example bench_voronoi_skeleton3 [mesh file names …]`
//! (default: bunny_npm.obj spot.obj fandisk.obj dragon_vrip_res4.obj rocker-arm.obj).
//!
//! Measured 2026-11-23 (release, 2 cores with load ≈ 7–9 from other jobs, so times ±50 %);
//! every result closed, genus 0, no exact self-intersection; recovered = mesh triangles on the
//! result:
//!
//! | mesh (points, triangles) | method | left out | recovered | time |
//! |---|---|---|---|---|
//! | bunny_npm (1839, 3674) | γ Auto | 0 | 63.3 % | 0.09 s |
//! | | min-area-change Fixed(0) | 0 | 25.9 % | 0.06 s |
//! | | skeleton 200 seeds | 87 | 23.8 % | 0.23 s |
//! | | skeleton all 11 346 seeds | 75 | 24.5 % | 10 s |
//! | spot (2930, 5856) | γ Auto | 0 | 68.8 % | 0.19 s |
//! | | min-area-change | 0 | 26.6 % | 0.19 s |
//! | | skeleton 200 seeds | 155 | 21.2 % | 0.45 s |
//! | | skeleton all 19 157 seeds | 130 | 21.2 % | 30 s |
//! | fandisk (6475, 12946) | γ Auto | 0 | 38.9 % | 0.36 s |
//! | | min-area-change | 4 | 28.5 % | 0.39 s |
//! | | skeleton 200 seeds | 339 | 28.2 % | 1.1 s |
//! | dragon_vrip_res4 (5205, 11102) | γ Auto | 0 | 18.6 % | 0.41 s |
//! | | min-area-change | 0 | 18.2 % | 0.16 s |
//! | | skeleton 200 seeds | 300 | 16.1 % | 0.67 s |
//! | rocker-arm (10044, 20088) | γ Auto | 0 | 27.3 % | 0.89 s |
//! | | min-area-change | 0 | 31.5 % | 0.32 s |
//! | | skeleton 200 seeds | 424 | 26.2 % | 1.6 s |
//! | stanford-bunny (35947, 69451) | γ Auto | 0 | 23.3 % | 7.2 s |
//! | | min-area-change | 2 | 20.6 % | 1.9 s |
//! | | skeleton 200 seeds | 2624 | 19.0 % | 12 s |
//! | horse (48485, 96966) | γ Auto | 0 | 27.0 % | 31 s |
//! | | min-area-change | 26 | 26.7 % | 3.7 s |
//! | | skeleton 200 seeds | 3622 | 19.6 % | 17 s |
//!
//! The skeleton's enclosed volume is about 10–25 % of the γ result's (bunny_npm 44.9 vs 223.9,
//! spot 0.15 vs 0.82): V §5.6's "the body of the object is not filled properly".

mod common;

use morpho::boundary::{boundary_3d, CParam, Method3, Options3, Until};
use std::collections::HashSet;
use std::time::Instant;

fn sorted(t: &[u32; 3]) -> [u32; 3] {
    let mut s = *t;
    s.sort_unstable();
    s
}

fn compare(name: &str, m: &morpho::mesh::TriMesh) {
    let orig: HashSet<[u32; 3]> = m.triangles.iter().map(sorted).collect();
    println!(
        "{name}: {} points, {} triangles",
        m.positions.len(),
        m.triangles.len()
    );
    let t = Instant::now();
    let d = morpho::delaunay::triangulate_3d(&m.positions).expect("triangulate");
    println!(
        "  Delaunay: {} tetrahedra, {:.2} s",
        d.tets.len(),
        t.elapsed().as_secs_f64()
    );
    let mut runs: Vec<(String, Options3)> = vec![
        ("gamma (Auto)".into(), Options3::gamma(Until::All)),
        (
            "min-area-change (Fixed(0))".into(),
            Options3 {
                method: Method3::MinAreaChange {
                    c: CParam::Fixed(0.0),
                    until: Until::All,
                    keep: Vec::new(),
                },
            },
        ),
        (
            "voronoi-skeleton (200 seeds)".into(),
            Options3::voronoi_skeleton(200),
        ),
    ];
    if d.tets.len() <= 25_000 {
        runs.push((
            format!("voronoi-skeleton (all {} seeds)", d.tets.len()),
            Options3::voronoi_skeleton(usize::MAX),
        ));
    }
    for (label, opts) in runs {
        let t = Instant::now();
        let b = boundary_3d(&m.positions, &opts).expect("boundary");
        let secs = t.elapsed().as_secs_f64();
        let hit = b
            .triangles
            .iter()
            .filter(|t| orig.contains(&sorted(t)))
            .count();
        println!(
            "  {label}: left out {}, closed {}, genus {:?}, intersections {}, triangles {}, recovered {hit}/{} = {:.1} %, volume {:.4}, skeleton {:?}, {secs:.2} s",
            b.left_out.len(),
            b.closed_manifold,
            b.genus,
            b.intersections.len(),
            b.triangles.len(),
            orig.len(),
            100.0 * hit as f64 / orig.len() as f64,
            b.volume,
            b.skeleton_length,
        );
    }
}

fn main() {
    let Some(dir) = common::data_dir() else {
        eprintln!("shared data not found");
        return;
    };
    let mut names: Vec<String> = std::env::args().skip(1).collect();
    if names.is_empty() {
        names = [
            "bunny_npm.obj",
            "spot.obj",
            "fandisk.obj",
            "dragon_vrip_res4.obj",
            "rocker-arm.obj",
        ]
        .map(String::from)
        .to_vec();
    }
    for f in names {
        let m = morpho::io::read_mesh(&dir.join("meshes").join(&f)).expect("mesh");
        compare(&f, &m);
    }
}
