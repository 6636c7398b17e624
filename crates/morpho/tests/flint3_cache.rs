//! The cached point-in-mesh classification (`flint/locate3.rs`): answers equal the exact walk
//! and brute force (random points, vertices, edge midpoints, face centroids, points on grid
//! planes, rays through vertices) on generated meshes (genus 0 to 3) and the bunny, spot, the
//! rocker arm (genus 1) and the horse; every empty cell is free of the surface; bad queries.
mod common;
use common::{real_mesh as real, XorShift as Rng};
use morpho::flint::{contains_brute3, CellCache3, Containment, FlintError, FlintTree3};
use morpho::geom::Point3;
use morpho::mesh::{generate, TriMesh};

fn pos(m: &TriMesh) -> Vec<[f64; 3]> {
    m.positions.iter().map(|p| [p.x, p.y, p.z]).collect()
}

/// Brute force on many points: `contains_brute3` (ray along +z) over the triangles whose
/// closed xy box holds the point — the others neither hold it nor meet its +z ray, so the
/// answer is the full brute force's. Buckets over xy with a slack of one bucket, the exact
/// box test per candidate.
struct Brute {
    pos: Vec<[f64; 3]>,
    tris: Vec<[u32; 3]>,
    min: [f64; 2],
    step: [f64; 2],
    n: usize,
    buckets: Vec<Vec<u32>>,
}

impl Brute {
    fn new(m: &TriMesh) -> Brute {
        let pos = pos(m);
        let b = m.bbox();
        let n = ((m.triangles.len() as f64).sqrt() as usize).clamp(1, 512);
        let min = [b.min[0], b.min[1]];
        let step = [
            (b.max[0] - b.min[0]) / n as f64,
            (b.max[1] - b.min[1]) / n as f64,
        ];
        let mut buckets = vec![Vec::new(); n * n];
        let cell =
            |v: f64, k: usize| ((v - min[k]) / step[k]).floor().clamp(0.0, (n - 1) as f64) as usize;
        for (t, tri) in m.triangles.iter().enumerate() {
            let [a, bb, c] = tri.map(|v| pos[v as usize]);
            let lo = [0, 1].map(|k| cell(a[k].min(bb[k]).min(c[k]), k).saturating_sub(1));
            let hi = [0, 1].map(|k| (cell(a[k].max(bb[k]).max(c[k]), k) + 1).min(n - 1));
            for y in lo[1]..=hi[1] {
                for x in lo[0]..=hi[0] {
                    buckets[y * n + x].push(t as u32);
                }
            }
        }
        Brute {
            pos,
            tris: m.triangles.clone(),
            min,
            step,
            n,
            buckets,
        }
    }

    fn contains(&self, x: [f64; 3]) -> Containment {
        let b = [0, 1].map(|k| {
            ((x[k] - self.min[k]) / self.step[k])
                .floor()
                .clamp(0.0, (self.n - 1) as f64) as usize
        });
        let cand: Vec<[u32; 3]> = self.buckets[b[1] * self.n + b[0]]
            .iter()
            .map(|&t| self.tris[t as usize])
            .filter(|t| {
                let [a, bb, c] = t.map(|v| self.pos[v as usize]);
                (0..2)
                    .all(|k| a[k].min(bb[k]).min(c[k]) <= x[k] && x[k] <= a[k].max(bb[k]).max(c[k]))
            })
            .collect();
        contains_brute3(&self.pos, &cand, x)
    }
}

/// Random points in the enlarged box, every k-th vertex, edge midpoints, centroids, points on
/// the grid's cell planes, and points whose +x ray (the walk's) or +z ray (brute force's)
/// passes through a vertex.
fn queries(m: &TriMesh, g: &CellCache3, n_random: usize, rng: &mut Rng) -> Vec<[f64; 3]> {
    let b = m.bbox();
    let e = b.extent();
    let mut q = Vec::new();
    for _ in 0..n_random {
        q.push(std::array::from_fn(|k| {
            b.min[k] - 0.05 * e[k] + 1.1 * e[k] * rng.unit()
        }));
    }
    let p = |v: u32| {
        let x = m.positions[v as usize];
        [x.x, x.y, x.z]
    };
    let (nv, nt) = (m.positions.len(), m.triangles.len());
    let dims = g.dims();
    for _ in 0..n_random / 10 {
        let v = p(rng.below(nv) as u32);
        q.push(v);
        let [a, bb, c] = m.triangles[rng.below(nt)].map(p);
        q.push(std::array::from_fn(|k| 0.5 * (a[k] + bb[k])));
        q.push(std::array::from_fn(|k| (a[k] + bb[k] + c[k]) / 3.0));
        let s = b.min[0] - 0.1 * e[0] + 1.2 * e[0] * rng.unit();
        q.push([s, v[1], v[2]]);
        let s = b.min[2] - 0.1 * e[2] + 1.2 * e[2] * rng.unit();
        q.push([v[0], v[1], s]);
        // a corner of a random cell's box and the nominal grid plane through it
        let c3: [usize; 3] = std::array::from_fn(|k| rng.below(dims[k]));
        let (_, bx) = g.cell(c3);
        q.push(std::array::from_fn(|k| bx[rng.below(2)][k]));
        let k = rng.below(3);
        let mut w: [f64; 3] = std::array::from_fn(|k| b.min[k] + e[k] * rng.unit());
        w[k] = b.min[k] + e[k] * (c3[k] as f64 / dims[k] as f64);
        q.push(w);
    }
    q
}

/// Cached answers against the walk on every query and against brute force on every
/// `stride`-th; returns the brute-force counts outside/inside/boundary.
fn compare(name: &str, m: &TriMesh, cells: usize, n_random: usize, stride: usize) -> [usize; 3] {
    let t = FlintTree3::from_mesh(m).unwrap_or_else(|e| panic!("{name}: {e}"));
    let g = t.cell_cache(cells);
    let [o, i, near] = g.label_counts();
    // the cache is used: cells inside (and, but for the cube filling its box, outside)
    assert!(
        near > 0 && (cells < 100 || (i > 0 && (o > 0 || name == "cube"))),
        "{name}: {:?}",
        g.label_counts()
    );
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15 ^ cells as u64);
    let q = queries(m, &g, n_random, &mut rng);
    let pts: Vec<Point3> = q.iter().map(|x| Point3::new(x[0], x[1], x[2])).collect();
    let got = g.contains_batch(&pts).unwrap();
    let walk = t.contains_batch(&pts).unwrap();
    let brute = Brute::new(m);
    let mut counts = [0usize; 3];
    let mut cached_hits = 0;
    for (j, x) in q.iter().enumerate() {
        assert_eq!(
            got[j], walk[j],
            "{name} ({cells} cells): query {j} {x:?} vs walk"
        );
        if j % stride == 0 {
            let want = brute.contains(*x);
            assert_eq!(got[j], want, "{name} ({cells} cells): query {j} {x:?}");
            counts[want as usize] += 1;
        }
        cached_hits += usize::from(got[j] != Containment::Boundary);
    }
    eprintln!(
        "{name}: {cells} cells {:?}, labels out/in/near {:?}, {} queries, brute-force counts {counts:?}",
        g.dims(),
        g.label_counts(),
        q.len()
    );
    assert!(cached_hits > 0);
    counts
}

#[test]
fn cached_answers_equal_walk_and_brute_force_on_generated_meshes() {
    let meshes = [
        ("cube", generate::cube()),
        ("icosphere3", generate::icosphere(3)),
        ("torus", generate::torus(2.0, 0.6, 32, 14)),
        ("multi_torus3", generate::multi_torus(3)),
    ];
    let mut total = 0;
    for (name, m) in &meshes {
        for cells in [1, 512, 40_000] {
            let c = compare(name, m, cells, 12_000, 1);
            assert!(c[0] > 0 && c[2] > 0, "{name}: {c:?}");
            if *name != "cube" || cells > 1 {
                total += c.iter().sum::<usize>();
            }
        }
    }
    assert!(total >= 100_000, "{total}");
}

#[test]
fn cached_answers_on_real_meshes() {
    for (name, n_random, stride) in [
        ("bunny_npm.obj", 100_000, 1),
        ("spot.obj", 100_000, 1),
        ("rocker-arm.obj", 100_000, 1),
        ("horse.obj.gz", 100_000, 1),
    ] {
        let Some(m) = real(name) else {
            eprintln!("skipping {name}: not found");
            continue;
        };
        let c = compare(name, &m, 1 << 18, n_random, stride);
        assert!(c.iter().all(|&k| k > 0), "{name}: {c:?}");
    }
}

/// Every empty cell's box meets no triangle's bounding box (all pairs), holds no vertex,
/// edge midpoint or centroid of the mesh, and its label is the brute-force answer at its
/// centre and corners.
#[test]
fn empty_cells_are_free_of_the_surface() {
    for (name, m) in [
        ("icosphere2", generate::icosphere(2)),
        ("torus", generate::torus(2.0, 0.6, 16, 8)),
    ] {
        let t = FlintTree3::from_mesh(&m).unwrap();
        let g = t.cell_cache(6_000);
        let p = pos(&m);
        let mut probes: Vec<[f64; 3]> = p.clone();
        for tri in &m.triangles {
            let [a, b, c] = tri.map(|v| p[v as usize]);
            probes.push(std::array::from_fn(|k| 0.5 * (a[k] + b[k])));
            probes.push(std::array::from_fn(|k| (a[k] + b[k] + c[k]) / 3.0));
        }
        let [nx, ny, nz] = g.dims();
        let mut empty = 0;
        for z in 0..nz {
            for y in 0..ny {
                for x in 0..nx {
                    let (label, [lo, hi]) = g.cell([x, y, z]);
                    let Some(label) = label else { continue };
                    empty += 1;
                    for tri in &m.triangles {
                        let [a, b, c] = tri.map(|v| p[v as usize]);
                        let meets = (0..3).all(|k| {
                            a[k].min(b[k]).min(c[k]) <= hi[k] && lo[k] <= a[k].max(b[k]).max(c[k])
                        });
                        assert!(!meets, "{name}: empty cell {:?} meets {tri:?}", [x, y, z]);
                    }
                    assert!(
                        !probes
                            .iter()
                            .any(|v| (0..3).all(|k| lo[k] <= v[k] && v[k] <= hi[k])),
                        "{name}: empty cell {:?} holds a point of the surface",
                        [x, y, z]
                    );
                    let centre: [f64; 3] = std::array::from_fn(|k| 0.5 * (lo[k] + hi[k]));
                    assert_eq!(contains_brute3(&p, &m.triangles, centre), label);
                    for corner in 0..8 {
                        let c: [f64; 3] =
                            std::array::from_fn(
                                |k| if corner >> k & 1 == 0 { lo[k] } else { hi[k] },
                            );
                        assert_eq!(contains_brute3(&p, &m.triangles, c), label, "{name}");
                    }
                }
            }
        }
        assert!(empty > 0);
    }
}

#[test]
fn bad_and_far_queries() {
    let m = generate::icosphere(2);
    let t = FlintTree3::from_mesh(&m).unwrap();
    let g = t.cell_cache(1000);
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let x = Point3::new(0.0, bad, 0.0);
        assert!(matches!(g.contains(x), Err(FlintError::NonFiniteQuery)));
        assert!(matches!(
            g.contains_batch(&[Point3::new(0.0, 0.0, 0.0), x]),
            Err(FlintError::NonFiniteQuery)
        ));
    }
    for far in [1e300, -1e300, 5.0, f64::MAX, f64::MIN_POSITIVE] {
        let x = Point3::new(far, 0.0, 0.0);
        assert_eq!(g.contains(x).unwrap(), t.contains(x).unwrap());
    }
    assert_eq!(
        g.contains(Point3::new(0.0, 0.0, 0.0)).unwrap(),
        Containment::Inside
    );
    // one cell, and more cells than the axis cap
    for cells in [0, 1, usize::MAX] {
        let g = t.cell_cache(cells);
        assert_eq!(
            g.contains(Point3::new(0.0, 0.0, 0.0)).unwrap(),
            Containment::Inside
        );
        assert!(g.dims().iter().all(|&d| (1..=2048).contains(&d)));
    }
}
