//! Point sets shared by the unit tests of the 3D boundary (test-only): the same draws from the
//! caller's generator as the copies they replace, so every test keeps its exact input; and the
//! faces of a constriction's live tetrahedra, the general engine's starting triangles.

use super::constrict::{constrict_3d, Constriction3, Until};
use crate::delaunay::d3::Delaunay3;
use crate::geom::Point3;
use crate::util::sorted3;
use rand::Rng;

/// `n` points uniform in the cube [−1, 1)³.
pub(super) fn cube(rng: &mut impl Rng, n: usize) -> Vec<Point3> {
    (0..n)
        .map(|_| {
            let v: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
            Point3::new(v[0], v[1], v[2])
        })
        .collect()
}

/// `n` cube points ([`cube`], drawn from `rng`), their Delaunay tetrahedralization, the points
/// as `[f64; 3]`, and every triangle of the tetrahedralization (the general engine's input in
/// the tests of its primitives).
pub(super) fn cube_candidates(
    rng: &mut impl Rng,
    n: usize,
) -> (Delaunay3, Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let d = crate::delaunay::d3::triangulate(&cube(rng, n)).unwrap();
    let pos = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
    let all = crate::graphs::fast::candidates_3d(&d).triangles;
    (d, pos, all)
}

/// The clustered cube points on which the Delaunay constriction locks (for seeds 1647 and
/// 1755; the integration test `locked_delaunay_constriction_falls_back_and_stays_valid`): a
/// ChaCha8 generator from `seed` draws n ∈ [40, 600), then n cube points whose coordinates are
/// cubed (dense towards the centre and the coordinate planes).
pub(super) fn clustered_cube(seed: u64) -> Vec<Point3> {
    use rand::SeedableRng;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let n = rng.gen_range(40..600);
    cube(&mut rng, n)
        .into_iter()
        .map(|q| Point3::new(q.x.powi(3), q.y.powi(3), q.z.powi(3)))
        .collect()
}

/// The clustered cube of `seed` ([`clustered_cube`]), its Delaunay tetrahedralization, its
/// points as `[f64; 3]` and its Delaunay constriction run until no removal is left — when that
/// constriction locks (leaves a point off the boundary); `None` when every point ends on it.
pub(super) fn locked_clustered_cube(
    seed: u64,
) -> Option<(Delaunay3, Vec<[f64; 3]>, Constriction3)> {
    let d = crate::delaunay::d3::triangulate(&clustered_cube(seed)).unwrap();
    let pos: Vec<[f64; 3]> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
    let st = constrict_3d(&d, Until::All);
    (st.boundary_vertices < pos.len()).then_some((d, pos, st))
}

/// `n` points of a bumpy ellipsoid (radius 1 + 0.2·sin(4x)·cos(3z) in the directions of
/// uniform cube points, z stretched by 1.4), every fifth at radius 0.7 inside it.
pub(super) fn bumpy_sphere(rng: &mut impl Rng, n: usize) -> Vec<Point3> {
    (0..n)
        .map(|i| {
            let v: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
            let r = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-3);
            let s = if i % 5 == 0 {
                0.7
            } else {
                1.0 + 0.2 * (4.0 * v[0] / r).sin() * (3.0 * v[2] / r).cos()
            };
            Point3::new(v[0] / r * s, v[1] / r * s, 1.4 * v[2] / r * s)
        })
        .collect()
}

/// The integer lattice {0..nx} × {0..ny} × {0..nz}, x fastest.
pub(super) fn lattice(nx: usize, ny: usize, nz: usize) -> Vec<Point3> {
    (0..nx * ny * nz)
        .map(|i| {
            Point3::new(
                (i % nx) as f64,
                (i / nx % ny) as f64,
                (i / (nx * ny)) as f64,
            )
        })
        .collect()
}

/// Every face of the tetrahedra of `d` marked in `alive`, once, as sorted vertex triples in
/// sorted order.
pub(super) fn live_faces(d: &Delaunay3, alive: &[bool]) -> Vec<[u32; 3]> {
    let mut live: Vec<[u32; 3]> = Vec::new();
    for (t, tet) in d.tets.iter().enumerate() {
        if alive[t] {
            for (a, b, c) in [(0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)] {
                live.push(sorted3([tet[a], tet[b], tet[c]]));
            }
        }
    }
    live.sort_unstable();
    live.dedup();
    live
}

/// The integer points on the surface of the L-shaped prism
/// ([0, 2k] × [0, k] ∪ [0, k] × [0, 2k]) × [0, k]: a fandisk-like sample, large coplanar
/// facets on a regular lattice (a point is on the surface when one of the eight half-step
/// diagonal offsets around it is outside the prism).
pub(super) fn l_prism(k: i64) -> Vec<Point3> {
    let inside = |x: f64, y: f64, z: f64| {
        let kf = k as f64;
        (0.0..=kf).contains(&z)
            && ((0.0..=2.0 * kf).contains(&x) && (0.0..=kf).contains(&y)
                || (0.0..=kf).contains(&x) && (0.0..=2.0 * kf).contains(&y))
    };
    let mut out = Vec::new();
    for i in 0..=2 * k {
        for j in 0..=2 * k {
            for l in 0..=k {
                let (x, y, z) = (i as f64, j as f64, l as f64);
                if !inside(x, y, z) {
                    continue;
                }
                let surface = (0..8).any(|m| {
                    let o = |b: i32| if m >> b & 1 == 1 { 0.5 } else { -0.5 };
                    !inside(x + o(0), y + o(1), z + o(2))
                });
                if surface {
                    out.push(Point3::new(x, y, z));
                }
            }
        }
    }
    out
}
