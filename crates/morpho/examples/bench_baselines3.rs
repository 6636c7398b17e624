//! The 3D baselines against the 3D flintstone tree (issue 18 items 7 and "Numbers", the 3D
//! rows of the table): per mesh and method (flintstone, IEPF, prism) nodes, depth, fallback
//! nodes, build CPU (min of 3, methods taking turns), e1/e2/e5 at equal triangle counts, and
//! point-in-mesh on one thread (N random queries in the bounding box, seeded; flintstone walk
//! vs prism walk, same answers checked; CPU seconds and mean nodes visited).
//!
//! `RAYON_NUM_THREADS=1 cargo run --release -p morpho --example bench_baselines3 [queries]
//! [mesh file names…]` (default 100 000 queries; bunny_npm.obj spot.obj horse.obj.gz).

mod common;

use morpho::flint::{Containment, FlintTree3, PrismTree3, Target};

/// CPU seconds of this process (all threads).
fn cpu() -> f64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: a valid timespec pointer
    unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut ts) };
    ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9
}

fn main() -> morpho::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(100_000);
    let names: Vec<&str> = if args.len() > 2 {
        args[2..].iter().map(|s| s.as_str()).collect()
    } else {
        vec!["bunny_npm.obj", "spot.obj", "horse.obj.gz"]
    };
    let Some(dir) = common::data_dir() else {
        eprintln!("shared/data not found");
        return Ok(());
    };
    for name in names {
        let m = morpho::io::read_mesh(&dir.join("meshes").join(name))?;
        let mut best = [f64::INFINITY; 3];
        let mut trees = None;
        for _ in 0..3 {
            let c0 = cpu();
            let f = FlintTree3::from_mesh(&m)?;
            let c1 = cpu();
            let i = FlintTree3::iepf(&m)?;
            let c2 = cpu();
            let p = PrismTree3::new(&m)?;
            let c3 = cpu();
            for (b, d) in best.iter_mut().zip([c1 - c0, c2 - c1, c3 - c2]) {
                *b = b.min(d);
            }
            trees = Some((f, i, p));
        }
        let (f, i, p) = trees.expect("three runs");
        println!(
            "{name}: {} triangles; build CPU s (min of 3): flintstone {:.3}, iepf {:.3}, prism (iepf + prisms) {:.3}",
            m.triangles.len(),
            best[0],
            best[1],
            best[2]
        );
        for (label, t) in [("flintstone", &f), ("iepf", &i), ("prism", &p.tree)] {
            println!(
                "  {label}: {} nodes, depth {}, fallbacks {}",
                t.node_count(),
                t.depth(),
                t.fallbacks()
            );
        }
        println!("  prism nodes without a prism: {}", p.unfiltered());
        for count in [100, 500, 2000, 5000] {
            let show = |label: &str, a: morpho::flint::Approximation3| {
                println!(
                    "  count {count} {label}: {} triangles, e1 {:.5}, e2 {:.5}, e5 {}",
                    a.triangles.len(),
                    a.e1,
                    a.e2,
                    if a.e5.is_finite() {
                        format!("{:.5}", a.e5)
                    } else {
                        "∞".into()
                    }
                )
            };
            show("flintstone", f.approximate(Target::Count(count))?);
            show("iepf", i.approximate(Target::Count(count))?);
            show("prism", p.approximate(Target::Count(count))?);
        }
        let q = common::box_points3(&m.bbox(), n);
        let mut qbest = [f64::INFINITY; 3];
        let mut visits = [0usize; 3];
        let mut answers: [Vec<Containment>; 3] = Default::default();
        for _ in 0..3 {
            for k in 0..3 {
                let c0 = cpu();
                let mut v = 0;
                let mut ans = Vec::with_capacity(n);
                for x in &q {
                    let (c, w) = match k {
                        0 => f.locate_counted(*x)?,
                        1 => i.locate_counted(*x)?,
                        _ => p.locate_counted(*x)?,
                    };
                    v += w;
                    ans.push(c);
                }
                qbest[k] = qbest[k].min(cpu() - c0);
                visits[k] = v;
                answers[k] = ans;
            }
        }
        assert_eq!(answers[0], answers[1], "{name}: iepf walk differs");
        assert_eq!(answers[0], answers[2], "{name}: prism walk differs");
        let inside = answers[0]
            .iter()
            .filter(|&&c| c == Containment::Inside)
            .count();
        for (k, label) in ["flintstone", "iepf (flintstone filters)", "prism"]
            .iter()
            .enumerate()
        {
            println!(
                "  {n} queries ({inside} inside), one thread, {label}: {:.3} CPU s = {:.0} queries/s, mean nodes visited {:.1}",
                qbest[k],
                n as f64 / qbest[k],
                visits[k] as f64 / n as f64
            );
        }
    }
    Ok(())
}
