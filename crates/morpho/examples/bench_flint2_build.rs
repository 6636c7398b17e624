//! The 2D flintstone tree build in process (issue 18: "tree build on 1M vertices within 2× of
//! Douglas–Peucker"): for each polygon CSV given, the CPU seconds of the exact simplicity check
//! (`check_polygon`), the smallest enclosing disc (Welzl) and `FlintTree2::new` (which does both
//! and then the tree and the query layout), so "tree + layout" = new − check − Welzl. One
//! thread; minimum of `ROUNDS` (default 3) rounds.
//!
//! `cargo run --release -p morpho --example bench_flint2_build -- POLY.csv [POLY.csv …]`

mod common;

use morpho::flint::FlintTree2;
use morpho::geom::{smallest_enclosing_disc, Point2};

fn cpu<T>(f: impl FnOnce() -> T) -> (T, f64) {
    let c = common::cpu_seconds();
    let r = f();
    (r, common::cpu_seconds() - c)
}

fn main() -> morpho::Result<()> {
    let rounds: usize = std::env::var("ROUNDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(3);
    for path in std::env::args().skip(1) {
        let s = morpho::io::read_shapes2(std::path::Path::new(&path))?;
        let ring: Vec<Point2> = s.polygons[0].rings[0].clone();
        let cycle: Vec<u32> = (0..ring.len() as u32).collect();
        let (mut ck, mut wz, mut all) = (f64::MAX, f64::MAX, f64::MAX);
        let mut nodes = 0;
        for _ in 0..rounds {
            let (c, t) = cpu(|| morpho::mesh::validity::check_polygon(&ring, &cycle));
            assert!(c.simple);
            ck = ck.min(t);
            let (_, t) = cpu(|| smallest_enclosing_disc(&ring));
            wz = wz.min(t);
            let (tree, t) = cpu(|| FlintTree2::new(&ring, true).expect("simple"));
            all = all.min(t);
            nodes = tree.node_count();
        }
        println!(
            "{path}: {} vertices, {nodes} nodes; cpu check {ck:.3} s, welzl {wz:.3} s, new {all:.3} s, tree+layout {:.3} s",
            ring.len(),
            all - ck - wz
        );
    }
    Ok(())
}
