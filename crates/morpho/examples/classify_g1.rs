//! The non-G¹ edges of the three- and six-split on closed meshes by cause (issue 19;
//! `morpho::smooth::non_g1_causes`), area normals with the visibility repair and the
//! three-split's fold guard (the CLI defaults).
//!
//! `cargo run --release -p morpho --example classify_g1 [--split6] mesh...` (file names in
//! shared/data/meshes).

mod common;

use morpho::mesh::{vertex_normals, NormalWeighting};
use morpho::smooth::{
    continuity, non_g1_causes, six_split, three_split_with, visible_normals, SplitOptions,
};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let six = args.iter().any(|a| a == "--split6");
    let Some(data) = common::data_dir() else {
        eprintln!("no shared data directory");
        return;
    };
    for name in args.iter().filter(|a| !a.starts_with("--")) {
        let m = morpho::io::read_mesh(&data.join("meshes").join(name)).expect("readable mesh");
        let n0 = vertex_normals(&m, NormalWeighting::Area);
        let a = visible_normals(&m, &n0, 0.05);
        let s = if six {
            six_split(&m, &a.normals)
        } else {
            three_split_with(&m, &a.normals, &SplitOptions { fold_guard: true })
        }
        .expect("a closed mesh");
        let c = continuity(&s, 20);
        let k = non_g1_causes(&s, &m, &a.normals, &c);
        println!(
            "{name} {}: non-G1 {} of {}, unresolved {}, fold edges {}, adjusted normals {} (infeasible {}); {k:?}",
            if six { "split6" } else { "split3" },
            c.non_g1_edges.len(),
            c.edges,
            s.unresolved_edges.len(),
            c.fold_edges,
            a.adjusted.len(),
            a.infeasible.len(),
        );
    }
}
