//! Times the 3D γ-graph γ([-1,1],[c,1]) beyond the Delaunay tetrahedralization
//! (`graphs::beyond3::beyond_dt_3d` through `graph_3d`) against the brute force of Veltkamp
//! Thm 3.1 (`brute::gamma_values_3d`, O(N⁴)).
//!
//! `cargo run --release -p morpho --example bench_graphs3d -- [C] [N ...]`
//! (defaults: c = −0.2, N = 2000). Uniform random points in the unit cube. For each N prints the
//! tetrahedralization time, the γ-graph time, the triangle count (and how many lie outside
//! γ([-1,1],[0,1])); the brute force is timed on N/10 points and extrapolated by (N/n)⁴.

use morpho::delaunay::triangulate_3d;
use morpho::geom::Point3;
use morpho::graphs::{graph_3d, Kind};
use morpho::internals::graphs::brute;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::time::Instant;

fn points(n: usize, seed: u64) -> Vec<Point3> {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    (0..n)
        .map(|_| Point3::new(r.gen(), r.gen(), r.gen()))
        .collect()
}

fn main() {
    let mut args = std::env::args().skip(1);
    let c: f64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(-0.2);
    let mut ns: Vec<usize> = args.filter_map(|a| a.parse().ok()).collect();
    if ns.is_empty() {
        ns.push(2000);
    }
    for n in ns {
        let p = points(n, 1);
        let t = Instant::now();
        let d = triangulate_3d(&p).expect("triangulation");
        let t_dt = t.elapsed().as_secs_f64();
        drop(d);
        let t = Instant::now();
        let dt = graph_3d(&p, Kind::GammaRange([-1.0, 1.0, 0.0, 1.0])).expect("γ");
        let t_dt_graph = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let g = graph_3d(&p, Kind::GammaRange([-1.0, 1.0, c, 1.0])).expect("γ");
        let t_g = t.elapsed().as_secs_f64();
        println!(
            "N = {n}: tetrahedralization {t_dt:.3} s; γ([-1,1],[0,1]) {t_dt_graph:.3} s, {} triangles; \
             γ([-1,1],[{c},1]) {t_g:.3} s, {} triangles ({} beyond the tetrahedralization)",
            dt.triangles.len(),
            g.triangles.len(),
            g.triangles.len() - dt.triangles.len()
        );
        let nb = (n / 10).clamp(20, 200);
        let pb: Vec<[f64; 3]> = points(nb, 2).iter().map(|q| [q.x, q.y, q.z]).collect();
        let t = Instant::now();
        let v = brute::gamma_values_3d(&pb);
        let k = v.iter().filter(|x| x.1 .1 >= c).count();
        let t_b = t.elapsed().as_secs_f64();
        let est = t_b * (n as f64 / nb as f64).powi(4);
        println!(
            "  brute force (Thm 3.1) on {nb} points: {t_b:.3} s ({k} triangles with c1' >= {c}); \
             extrapolated to {n}: {est:.0} s"
        );
    }
}
