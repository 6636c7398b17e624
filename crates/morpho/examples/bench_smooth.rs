//! Smooth surfaces on a ~100k-triangle closed mesh (issue 19, "Numbers": split surfaces in well
//! under a second per scheme on all cores, tessellation throughput in triangles/s): for the
//! three-split (Veltkamp 1992, §9.6), the six-split (V §9.8 rebuilt) and the side-vertex
//! surface (Hamann 1991, ch. 6), the
//! time of the normals, the construction, the independent continuity check (20 samples per
//! edge) and the tessellation at `density`, each on one thread and on all threads (rayon),
//! best of `REPS` (default 3) runs.
//!
//! `cargo run --release -p morpho --example bench_smooth [mesh file name] [density]`
//! (default: horse.obj.gz from shared/data/meshes, density 4).
//!
//! The two-split (V §9.7, experimental, `morpho::smooth::two_split`) is measured after the
//! three-split (it builds on it).

mod common;

use morpho::mesh::{vertex_normals, NormalWeighting, TriMesh};
use morpho::smooth::{
    continuity, side_vertex, side_vertex_continuity, six_split, tessellate, three_split_with,
    two_split, visible_normals, SideVertexOptions, SplitOptions,
};
use std::time::Instant;

/// Best wall time of `reps` runs of `f` (with the CPU seconds of that run), and its last
/// result. Under load the CPU time is the steadier figure.
fn best<T>(reps: usize, mut f: impl FnMut() -> T) -> ((f64, f64), T) {
    let mut t_best = (f64::INFINITY, 0.0);
    let mut out = None;
    for _ in 0..reps.max(1) {
        let (t0, c0) = (Instant::now(), common::cpu_seconds());
        let r = f();
        let t = t0.elapsed().as_secs_f64();
        if t < t_best.0 {
            t_best = (t, common::cpu_seconds() - c0);
        }
        out = Some(r);
    }
    (t_best, out.expect("at least one run"))
}

/// `wall s (cpu s)`.
fn fmt((wall, cpu): (f64, f64)) -> String {
    format!("{wall:7.3} s (cpu {cpu:6.2} s)")
}

fn run(m: &TriMesh, density: usize, reps: usize) -> morpho::Result<()> {
    let (t_n, n) = best(reps, || {
        let n = vertex_normals(m, NormalWeighting::Area);
        visible_normals(m, &n, 0.05).normals
    });
    println!("  normals (area, visibility repair) {}", fmt(t_n));
    let opts = SplitOptions { fold_guard: true };
    let (t_s, s) = best(reps, || three_split_with(m, &n, &opts));
    let s = s?;
    let check = std::env::var("CHECK").is_ok_and(|v| v == "1");
    let jump = |j: f64, e: usize, t: f64| {
        if check {
            format!("check {t:7.3} s (max jump {j:.1e} rad, {e} non-G1 edges)")
        } else {
            "check skipped".to_string()
        }
    };
    let (t_c, c) = if check {
        let t0 = Instant::now();
        let c = continuity(&s, 20);
        (t0.elapsed().as_secs_f64(), c)
    } else {
        (0.0, Default::default())
    };
    let (t_t, t) = best(reps, || tessellate(&s, density));
    let t = t?;
    println!(
        "  split3      build {} ({} patches)  {}  tessellate {} = {:.2e} triangles/s ({} triangles)",
        fmt(t_s),
        s.patches.len(),
        jump(c.max_normal_jump_rad, c.non_g1_edges.len(), t_c),
        fmt(t_t),
        t.triangles.len() as f64 / t_t.0,
        t.triangles.len()
    );
    let (t_2, s2) = best(reps, || two_split(m, &n, &opts));
    let s2 = s2?;
    let (t_c2, c2) = if check {
        let t0 = Instant::now();
        let c = continuity(&s2.surface, 20);
        (t0.elapsed().as_secs_f64(), c)
    } else {
        (0.0, Default::default())
    };
    println!(
        "  split2      build {} ({} patches, {} pairs, {} rejected: {:?})  {}",
        fmt(t_2),
        s2.surface.patches.len(),
        s2.pairs.len(),
        s2.rejected.len(),
        s2.rejected_by,
        jump(c2.max_normal_jump_rad, c2.non_g1_edges.len(), t_c2),
    );
    let (t_6, s6) = best(reps, || six_split(m, &n));
    let s6 = s6?;
    let (t_c6, c6) = if check {
        let t0 = Instant::now();
        let c = continuity(&s6, 20);
        (t0.elapsed().as_secs_f64(), c)
    } else {
        (0.0, Default::default())
    };
    let (t_t6, t6) = best(reps, || tessellate(&s6, density));
    let t6 = t6?;
    println!(
        "  split6      build {} ({} patches, {} unresolved edges)  {}  tessellate {} = {:.2e} triangles/s ({} triangles)",
        fmt(t_6),
        s6.patches.len(),
        s6.unresolved_edges.len(),
        jump(c6.max_normal_jump_rad, c6.non_g1_edges.len(), t_c6),
        fmt(t_t6),
        t6.triangles.len() as f64 / t_t6.0,
        t6.triangles.len()
    );
    let (t_v, v) = best(reps, || side_vertex(m, &n, &SideVertexOptions::default()));
    let v = v?;
    let (t_vc, vc) = if check {
        let t0 = Instant::now();
        let c = side_vertex_continuity(&v, 20, 1e-9);
        (t0.elapsed().as_secs_f64(), c)
    } else {
        (0.0, Default::default())
    };
    let (t_vt, vt) = best(reps, || v.tessellate(density));
    let vt = vt?;
    println!(
        "  side-vertex build {} ({} patches)  {}  tessellate {} = {:.2e} triangles/s ({} triangles)",
        fmt(t_v),
        v.triangles.len(),
        jump(vc.max_normal_jump_rad, vc.non_g1_edges.len(), t_vc),
        fmt(t_vt),
        vt.triangles.len() as f64 / t_vt.0,
        vt.triangles.len()
    );
    Ok(())
}

fn main() -> morpho::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let name = args.get(1).map_or("horse.obj.gz", |s| s.as_str());
    let density: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(4);
    let reps: usize = std::env::var("REPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(3);
    let Some(dir) = common::data_dir() else {
        eprintln!("shared/data not found");
        return Ok(());
    };
    let m = morpho::io::read_mesh(&dir.join("meshes").join(name))?;
    let all = rayon::current_num_threads();
    println!(
        "{name}: {} triangles, {} vertices, density {density}, best of {reps}",
        m.triangles.len(),
        m.positions.len()
    );
    for threads in [1, all] {
        println!("{threads} thread(s):");
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a rayon thread pool");
        pool.install(|| run(&m, density, reps))?;
    }
    Ok(())
}
