//! Criterion benchmarks of `volume::isosurface` on a 96³ gyroid-like field (kept small so a run
//! stays short on a shared machine; the 256³ peer comparison is `examples/bench_isosurface.rs`).
use criterion::{black_box, criterion_group, criterion_main, Criterion};
use morpho::volume::Volume;
use morpho::volume::{isosurface, IsoMethod, IsoOptions, NormalMethod};

fn field(n: usize) -> Volume {
    let t = 4.0 * std::f64::consts::PI;
    Volume::from_fn([n; 3], [0.0; 3], [t; 3], |x, y, z| {
        x.sin() * y.cos() + y.sin() * z.cos() + z.sin() * x.cos()
    })
}

fn bench(c: &mut Criterion) {
    let v = field(96);
    let mut g = c.benchmark_group("isosurface 96^3 gyroid");
    g.sample_size(10);
    for (name, method, normals, topology) in [
        ("decider", IsoMethod::Decider, NormalMethod::None, false),
        (
            "decider+zucker+topology",
            IsoMethod::Decider,
            NormalMethod::ZuckerHummel,
            true,
        ),
        ("tetra", IsoMethod::Tetra, NormalMethod::None, false),
        ("lorensen", IsoMethod::Lorensen, NormalMethod::None, false),
    ] {
        for parallel in [false, true] {
            let opts = IsoOptions {
                level: 0.0,
                method,
                normals,
                flip: false,
                parallel,
                topology,
            };
            let label = format!("{name} {}", if parallel { "parallel" } else { "serial" });
            g.bench_function(label, |b| {
                b.iter(|| black_box(isosurface(&v, &opts).unwrap().mesh.triangles.len()))
            });
        }
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
