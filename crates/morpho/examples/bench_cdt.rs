//! Timing of the 2D constrained Delaunay triangulation (`delaunay::cdt`) against the plain
//! Delaunay triangulation and against the `spade` crate on the same inputs. Run in release:
//!
//! ```text
//! cargo run --release --example bench_cdt -p morpho -- [N] [M]
//! ```
//!
//! Inputs (seeded): N uniform random points in the unit square (default 1 000 000) and M
//! (default 100 000) non-crossing segments: the edges of the star-shaped polygon through the
//! first M points sorted by angle around the centre (edges between consecutive angles never
//! cross; they are long, each crosses many Delaunay triangles). Second input: the interior of
//! the star-shaped polygon through all N points ([`triangulate_polygon_2d`]).
//! Prints wall-clock seconds per step (on a shared machine, compare ratios of one run).

use morpho::delaunay::triangulate_2d;
use morpho::delaunay::{triangulate_polygon_2d, Cdt2};
use morpho::geom::Point2;
use rand::{Rng, SeedableRng};
use spade::{ConstrainedDelaunayTriangulation, DelaunayTriangulation, Triangulation};
use std::time::Instant;

fn time<T>(f: impl FnOnce() -> T) -> (f64, T) {
    let t = Instant::now();
    let r = f();
    (t.elapsed().as_secs_f64(), r)
}

/// Indices `0..m` sorted by angle around (0.5, 0.5): a star-shaped simple polygon.
fn star_cycle(p: &[Point2], m: usize) -> Vec<u32> {
    let mut idx: Vec<u32> = (0..m as u32).collect();
    let ang = |i: u32| {
        let q = p[i as usize];
        (q.y - 0.5).atan2(q.x - 0.5)
    };
    idx.sort_by(|&a, &b| ang(a).total_cmp(&ang(b)));
    idx
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args
        .get(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(1_000_000);
    let m: usize = args
        .get(2)
        .and_then(|s| s.parse().ok())
        .unwrap_or(100_000)
        .min(n);
    let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(2026);
    let p: Vec<Point2> = (0..n)
        .map(|_| Point2::new(r.gen::<f64>(), r.gen::<f64>()))
        .collect();
    let cyc = star_cycle(&p, m);
    let segs: Vec<[u32; 2]> = (0..m).map(|k| [cyc[k], cyc[(k + 1) % m]]).collect();
    println!("input: {n} random points, {m} segments (star polygon through {m} of them)");

    let (t_dt, d) = time(|| triangulate_2d(&p).expect("delaunay"));
    println!(
        "morpho Delaunay              {t_dt:8.3} s  triangles {}",
        d.triangles.len()
    );
    let (t_ins, c) = time(|| {
        let mut c = Cdt2::new(d);
        c.insert_input_segments(&segs).expect("cdt");
        c
    });
    println!(
        "morpho CDT segment insertion {t_ins:8.3} s  triangles {}  constrained edges {}  splits {}  re-triangulated {} ({:.1} per segment)",
        c.triangles.len(),
        c.constrained_edges().len(),
        c.splits,
        c.retriangulated,
        c.retriangulated as f64 / m.max(1) as f64
    );
    println!(
        "morpho CDT total             {:8.3} s  ratio to Delaunay {:.2}",
        t_dt + t_ins,
        (t_dt + t_ins) / t_dt
    );
    drop(c);

    let sp: Vec<spade::Point2<f64>> = p.iter().map(|q| spade::Point2::new(q.x, q.y)).collect();
    let (t_sdt, sdt) = time(|| DelaunayTriangulation::<spade::Point2<f64>>::bulk_load(sp.clone()));
    let sdt = sdt.expect("spade delaunay");
    println!(
        "spade Delaunay (bulk_load)   {t_sdt:8.3} s  triangles {}",
        sdt.num_inner_faces()
    );
    drop(sdt);
    let (t_scdt, scdt) = time(|| {
        let mut c = ConstrainedDelaunayTriangulation::<spade::Point2<f64>>::bulk_load_cdt(
            sp.clone(),
            vec![],
        )
        .expect("spade");
        for s in &segs {
            c.add_constraint(
                spade::handles::FixedVertexHandle::from_index(s[0] as usize),
                spade::handles::FixedVertexHandle::from_index(s[1] as usize),
            );
        }
        c
    });
    println!(
        "spade CDT (bulk_load_cdt without edges + add_constraint) {t_scdt:8.3} s  triangles {}  constraints {}",
        scdt.num_inner_faces(),
        scdt.num_constraints()
    );
    drop(scdt);
    let edges: Vec<[usize; 2]> = segs
        .iter()
        .map(|s| [s[0] as usize, s[1] as usize])
        .collect();
    let (t_sbulk, sb) = time(|| {
        ConstrainedDelaunayTriangulation::<spade::Point2<f64>>::bulk_load_cdt(sp.clone(), edges)
    });
    let sb = sb.expect("spade bulk cdt");
    println!(
        "spade CDT (bulk_load_cdt)    {t_sbulk:8.3} s  triangles {}",
        sb.num_inner_faces()
    );
    drop(sb);
    println!(
        "ratio morpho CDT / spade CDT: {:.2} (incremental), {:.2} (spade bulk_load_cdt)",
        (t_dt + t_ins) / t_scdt,
        (t_dt + t_ins) / t_sbulk
    );

    // interior of a star polygon through all n points
    let cyc = star_cycle(&p, n);
    let (t_poly, tris) = time(|| triangulate_polygon_2d(&p, &cyc).expect("interior"));
    println!(
        "morpho polygon interior ({n} vertices) {t_poly:8.3} s  triangles {} (n − 2 = {})  ratio to Delaunay {:.2}",
        tris.len(),
        n - 2,
        t_poly / t_dt
    );
    drop(tris);
    let edges: Vec<[usize; 2]> = (0..n)
        .map(|k| [cyc[k] as usize, cyc[(k + 1) % n] as usize])
        .collect();
    let (t_spoly, sb) = time(|| {
        ConstrainedDelaunayTriangulation::<spade::Point2<f64>>::bulk_load_cdt(sp.clone(), edges)
    });
    let sb = sb.expect("spade bulk cdt");
    println!(
        "spade CDT of the same polygon (bulk_load_cdt, no inside selection) {t_spoly:8.3} s  triangles {}  ratio morpho/spade {:.2}",
        sb.num_inner_faces(),
        t_poly / t_spoly
    );
}
