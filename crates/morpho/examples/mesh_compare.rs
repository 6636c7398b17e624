//! The measuring stick of `bench/reduce_peers.py` (issue 21): one JSON line comparing a
//! simplified mesh with its input, the same code for morpho's output and every peer's.
//!
//! `cargo run --release --example mesh_compare -p morpho -- INPUT OUTPUT`
//!
//! Prints the output's triangle and vertex counts, its topology (Euler characteristic, genus,
//! parts, boundary loops, non-manifold edges and vertices, orientation conflicts, degenerate
//! triangles — `morpho::mesh::analyze_topology`), and the distances of
//! `morpho::reduce::mesh_distance`: RMS of the input's vertices to the output surface, and the
//! sampled symmetric Hausdorff distance (input vertices → output, and output vertices plus a
//! barycentric lattice on every output triangle → input), all relative to the input's bounding
//! box diagonal as well as absolute.
use morpho::mesh::analyze_topology;
use morpho::reduce::mesh_distance;
use std::path::PathBuf;

fn main() {
    let args: Vec<PathBuf> = std::env::args_os().skip(1).map(PathBuf::from).collect();
    if args.len() != 2 {
        eprintln!("usage: mesh_compare INPUT OUTPUT");
        std::process::exit(2);
    }
    let read = |p: &PathBuf| match morpho::io::read_mesh(p) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
    };
    let input = read(&args[0]);
    let output = read(&args[1]);
    let diag = input.bbox().diagonal();
    let t = analyze_topology(&output);
    let d = mesh_distance(&input, &output);
    let genus = t.genus().map_or("null".to_string(), |g| g.to_string());
    println!(
        "{{\"triangles\":{},\"vertices\":{},\"euler_characteristic\":{},\"genus\":{},\"parts\":{},\
         \"boundary_loops\":{},\"non_manifold_edges\":{},\"non_manifold_vertices\":{},\
         \"orientation_conflicts\":{},\"degenerate_triangles\":{},\"manifold\":{},\
         \"consistently_oriented\":{},\"rms\":{:e},\"hausdorff\":{:e},\"rms_rel\":{:e},\
         \"hausdorff_rel\":{:e},\"diagonal\":{:e}}}",
        output.triangles.len(),
        t.num_used_vertices,
        t.euler_characteristic,
        genus,
        t.parts.len(),
        t.boundary_loops.len(),
        t.non_manifold_edges.len(),
        t.non_manifold_vertices.len(),
        t.num_directed_edge_conflicts,
        t.degenerate_triangles.len(),
        t.manifold,
        t.consistently_oriented,
        d.rms,
        d.hausdorff,
        d.rms / diag,
        d.hausdorff / diag,
        diag
    );
}
