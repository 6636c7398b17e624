//! Times every geometric graph kind against the Delaunay triangulation it is built from, and the
//! γ-graph beyond the triangulation against the brute force of Veltkamp Thm 3.1.
//!
//! `cargo run --release -p morpho --example bench_graphs -- [N] [N_GAMMA] [N_BRUTE]`
//! (defaults 1000000, 100000, 2000). Prints one line per kind: seconds and the ratio to the
//! Delaunay time. `KIND=Emst` (a prefix of the kind's debug name) times only that kind.

use morpho::delaunay::triangulate_2d;
use morpho::geom::Point2;
use morpho::graphs::{graph_2d, Kind};
use morpho::internals::graphs::brute;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::time::Instant;

fn points(n: usize, seed: u64) -> Vec<Point2> {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    (0..n).map(|_| Point2::new(r.gen(), r.gen())).collect()
}

fn best_of<T>(k: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut out = None;
    for _ in 0..k {
        let t = Instant::now();
        let r = f();
        best = best.min(t.elapsed().as_secs_f64());
        out = Some(r);
    }
    (best, out.expect("k > 0"))
}

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let n = args.first().copied().unwrap_or(1_000_000);
    let ng = args.get(1).copied().unwrap_or(100_000);
    let nb = args.get(2).copied().unwrap_or(2000);
    let p = points(n, 1);
    let (tdt, d) = best_of(3, || triangulate_2d(&p).expect("triangulate"));
    println!(
        "{n} uniform points: Delaunay {tdt:.3} s ({} triangles)",
        d.triangles.len()
    );
    println!(
        "{:<40} {:>9} {:>9} {:>10}",
        "kind", "seconds", "ratio/DT", "edges"
    );
    for kind in [
        Kind::Delaunay,
        Kind::ClosestPairs,
        Kind::Nng,
        Kind::Emst,
        Kind::Rng,
        Kind::Gabriel,
        Kind::Hull,
        Kind::Alpha(-200.0),
        Kind::BetaCircle(0.2),
        Kind::BetaLune(0.3),
        Kind::Gamma(0.3, 0.5),
        Kind::GammaRange([-1.0, 1.0, 0.0, 1.0]),
        Kind::Sig,
    ] {
        if let Ok(only) = std::env::var("KIND") {
            if !format!("{kind:?}").starts_with(&only) {
                continue;
            }
        }
        let (t, g) = best_of(2, || graph_2d(&p, kind).expect("graph"));
        println!(
            "{:<40} {:>9.3} {:>9.2} {:>10}",
            format!("{kind:?}"),
            t,
            t / tdt,
            g.edges.len()
        );
    }
    let pg = points(ng, 2);
    let (tdg, _) = best_of(2, || triangulate_2d(&pg).expect("triangulate"));
    let (t, g) = best_of(1, || {
        graph_2d(&pg, Kind::GammaRange([-1.0, 1.0, -0.2, 1.0])).expect("graph")
    });
    println!(
        "γ([-1,1],[-0.2,1]) on {ng} points: {t:.3} s ({:.1}× its Delaunay time), {} edges",
        t / tdg,
        g.edges.len()
    );
    let pb = points(nb, 3);
    let arr: Vec<[f64; 2]> = pb.iter().map(|q| [q.x, q.y]).collect();
    let (tf, gf) = best_of(1, || {
        graph_2d(&pb, Kind::GammaRange([-1.0, 1.0, -0.2, 1.0])).expect("graph")
    });
    let (tb, vb) = best_of(1, || brute::gamma_values_2d(&arr));
    let nbrute = vb
        .iter()
        .filter(|(_, v)| morpho::graphs::in_gamma_range(*v, [-1.0, 1.0, -0.2, 1.0]))
        .count();
    println!(
        "γ([-1,1],[-0.2,1]) on {nb} points: fast {tf:.4} s, brute force (Thm 3.1) {tb:.2} s: speed-up {:.0}×; edges {} vs {}",
        tb / tf,
        gf.edges.len(),
        nbrute
    );
}
