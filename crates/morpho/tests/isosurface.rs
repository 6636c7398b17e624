//! Tests of `volume::isosurface` (Hamann 1991 §3.2–3.4): cell triangulations of all 256 sign
//! configurations against independent oracles, watertightness on random volumes, Euler
//! characteristics, level-set accuracy, H Fig. 3.5, Lorensen's holes, determinism of the
//! parallel run, rectilinear grids, NaN handling and normals.

mod common;
use morpho::geom::Point3;
use morpho::mesh::TriMesh;
use morpho::volume::{isosurface, IsoMethod, IsoOptions, IsoResult, NormalMethod};
use morpho::volume::{Axes, DType, Volume};
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::HashMap;

fn vol_from(dims: [usize; 3], data: Vec<f64>) -> Volume {
    Volume::new(
        dims,
        [0.0; 3],
        [1.0; 3],
        data.into_iter().map(|v| v as f32).collect(),
    )
    .unwrap()
}

fn run(v: &Volume, level: f64, method: IsoMethod) -> IsoResult {
    isosurface(
        v,
        &IsoOptions {
            level,
            method,
            ..Default::default()
        },
    )
    .unwrap()
}

/// Undirected edge -> list of (triangle, +1 if traversed a->b with a<b else -1).
fn edge_map(m: &TriMesh) -> HashMap<(u32, u32), Vec<(usize, i32)>> {
    let mut e: HashMap<(u32, u32), Vec<(usize, i32)>> = HashMap::new();
    for (t, tri) in m.triangles.iter().enumerate() {
        for i in 0..3 {
            let (a, b) = (tri[i], tri[(i + 1) % 3]);
            let k = (a.min(b), a.max(b));
            e.entry(k)
                .or_default()
                .push((t, if a < b { 1 } else { -1 }));
        }
    }
    e
}

/// True if both points lie on the same outer face of the box [0, hi].
fn on_outer_face(p: &Point3, q: &Point3, hi: [f64; 3]) -> bool {
    (0..3).any(|k| (p[k] == 0.0 && q[k] == 0.0) || (p[k] == hi[k] && q[k] == hi[k]))
}

/// Every edge not on the volume's outer faces is shared by exactly two triangles with opposite
/// directions; edges on outer faces by at most two (one, or two from a fold along the face).
fn check_watertight(m: &TriMesh, hi: [f64; 3]) -> Result<(), String> {
    for (&(a, b), uses) in &edge_map(m) {
        let (p, q) = (m.positions[a as usize], m.positions[b as usize]);
        let outer = on_outer_face(&p, &q, hi);
        if outer {
            if uses.len() != 1 {
                return Err(format!("outer edge {a}-{b} used {} times", uses.len()));
            }
        } else {
            if uses.len() != 2 {
                return Err(format!(
                    "interior edge {a}-{b} ({p:?} {q:?}) used {} times",
                    uses.len()
                ));
            }
            if uses[0].1 + uses[1].1 != 0 {
                return Err(format!("edge {a}-{b} not oppositely oriented"));
            }
        }
    }
    for t in &m.triangles {
        if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
            return Err(format!("degenerate index triple {t:?}"));
        }
    }
    Ok(())
}

fn euler(m: &TriMesh) -> i64 {
    let e = edge_map(m).len() as i64;
    let mut used = vec![false; m.positions.len()];
    for t in &m.triangles {
        for &v in t {
            used[v as usize] = true;
        }
    }
    used.iter().filter(|&&u| u).count() as i64 - e + m.triangles.len() as i64
}

/// Trilinear interpolant of `g = f - level` in the cell containing `p` (rectilinear axes).
fn trilinear(v: &Volume, level: f64, p: &Point3) -> (f64, f64) {
    let mut i = [0usize; 3];
    let mut u = [0.0; 3];
    for k in 0..3 {
        let c: Vec<f64> = (0..v.dims[k]).map(|j| v.coord(k, j)).collect();
        let mut j = c.partition_point(|&x| x <= p[k]).saturating_sub(1);
        j = j.min(v.dims[k] - 2);
        i[k] = j;
        u[k] = (p[k] - c[j]) / (c[j + 1] - c[j]);
    }
    let mut s = 0.0;
    let mut scale: f64 = 0.0;
    for c in 0..8usize {
        let b = |k: usize| c >> k & 1;
        let g = v.at(i[0] + b(0), i[1] + b(1), i[2] + b(2)) as f64 - level;
        scale = scale.max(g.abs());
        let w: f64 = (0..3)
            .map(|k| if b(k) == 1 { u[k] } else { 1.0 - u[k] })
            .product();
        s += w * g;
    }
    (s, scale)
}

fn cube_values(cfg: u8, rng: &mut ChaCha8Rng) -> Vec<f64> {
    (0..8)
        .map(|c| {
            let m = rng.gen_range(0.1..1.0);
            if cfg >> c & 1 == 1 {
                m
            } else {
                -m
            }
        })
        .collect()
}

/// Which cube edge (0..12 as in the module's tables: axis*4 + j) the point lies on, if any.
fn cube_edge_of(p: &Point3) -> Option<(usize, [u8; 3])> {
    let at = |x: f64| x == 0.0 || x == 1.0;
    let free: Vec<usize> = (0..3).filter(|&k| !at(p[k])).collect();
    if free.len() != 1 {
        return None;
    }
    let mut c = [0u8; 3];
    for k in 0..3 {
        c[k] = if k == free[0] { 2 } else { p[k] as u8 };
    }
    Some((free[0], c))
}

/// Oracle for a face's bilinear contour: are the two positive corners of an ambiguous face
/// connected within {f > 0}? Decided by flood fill on a 151x151 sampling of the bilinear patch.
fn positives_connected(h: [[f64; 2]; 2]) -> bool {
    let n = 151;
    let f = |i: usize, j: usize| {
        let (u, v) = (i as f64 / (n - 1) as f64, j as f64 / (n - 1) as f64);
        h[0][0] * (1.0 - u) * (1.0 - v)
            + h[1][0] * u * (1.0 - v)
            + h[0][1] * (1.0 - u) * v
            + h[1][1] * u * v
    };
    let start = if h[0][0] > 0.0 { (0, 0) } else { (n - 1, 0) };
    let goal = if h[0][0] > 0.0 {
        (n - 1, n - 1)
    } else {
        (0, n - 1)
    };
    let mut seen = vec![false; n * n];
    let mut stack = vec![start];
    seen[start.0 + n * start.1] = true;
    while let Some((i, j)) = stack.pop() {
        if (i, j) == goal {
            return true;
        }
        let nb = [
            (i.wrapping_sub(1), j),
            (i + 1, j),
            (i, j.wrapping_sub(1)),
            (i, j + 1),
        ];
        for (a, b) in nb {
            if a < n && b < n && !seen[a + n * b] && f(a, b) > 0.0 {
                seen[a + n * b] = true;
                stack.push((a, b));
            }
        }
    }
    false
}

#[test]
fn all_256_configurations_give_valid_cell_pieces() {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    for cfg in 0..=255u8 {
        for rep in 0..3 {
            let vals = cube_values(cfg, &mut rng);
            let v = vol_from([2, 2, 2], vals.clone());
            for method in [IsoMethod::Decider, IsoMethod::Tetra] {
                let r = run(&v, 0.0, method);
                let m = &r.mesh;
                if cfg == 0 || cfg == 255 {
                    assert!(m.triangles.is_empty());
                    continue;
                }
                // inside the cell: shared by exactly 2, opposite; on faces: exactly 1
                check_watertight(m, [1.0; 3])
                    .unwrap_or_else(|e| panic!("cfg {cfg} rep {rep} {method:?}: {e}"));
                assert_eq!(r.interior_holes, 0);
                assert_eq!(r.non_manifold_edges, 0);
                // face segments: compare with an oracle computed from the face values alone
                let em = edge_map(m);
                for axis in 0..3 {
                    for side in 0..2 {
                        let sval = side as f64;
                        let corner = |i: usize, j: usize| {
                            let (b, c) = ((axis + 1) % 3, (axis + 2) % 3);
                            let (b, c) = (b.min(c), b.max(c));
                            (side << axis) | (i << b) | (j << c)
                        };
                        let h = [
                            [vals[corner(0, 0)], vals[corner(0, 1)]],
                            [vals[corner(1, 0)], vals[corner(1, 1)]],
                        ];
                        let segs: Vec<(Point3, Point3)> = em
                            .keys()
                            .map(|&(a, b)| (m.positions[a as usize], m.positions[b as usize]))
                            .filter(|(p, q)| p[axis] == sval && q[axis] == sval)
                            .collect();
                        let pos: Vec<bool> = [h[0][0], h[1][0], h[1][1], h[0][1]]
                            .map(|x| x > 0.0)
                            .to_vec();
                        let cuts = (0..4).filter(|&k| pos[k] != pos[(k + 1) % 4]).count();
                        match method {
                            IsoMethod::Decider => {
                                assert_eq!(segs.len(), cuts / 2, "cfg {cfg} face {axis}/{side}");
                                if cuts == 4 {
                                    // each segment joins two edges around one corner; that
                                    // corner is positive iff the positives are separated
                                    let joined = positives_connected(h);
                                    for (p, q) in &segs {
                                        let (ep, eq) =
                                            (cube_edge_of(p).unwrap(), cube_edge_of(q).unwrap());
                                        // the common corner of the two edges
                                        let cc: [usize; 3] = std::array::from_fn(|k| {
                                            if ep.1[k] != 2 {
                                                ep.1[k] as usize
                                            } else {
                                                eq.1[k] as usize
                                            }
                                        });
                                        let ci = cc[0] | cc[1] << 1 | cc[2] << 2;
                                        let corner_pos = vals[ci] > 0.0;
                                        assert_eq!(
                                            corner_pos, !joined,
                                            "cfg {cfg} face {axis}/{side} {h:?}"
                                        );
                                    }
                                }
                            }
                            _ => {
                                // tetra: one segment per face triangle with mixed signs; the
                                // face diagonal joins the corners with the odd coordinate sum
                                // pattern used by H's split: (i,j) = (1,0) and (0,1)
                                let tris = [
                                    [h[0][0] > 0.0, h[1][0] > 0.0, h[0][1] > 0.0],
                                    [h[1][1] > 0.0, h[1][0] > 0.0, h[0][1] > 0.0],
                                ];
                                let mixed = tris
                                    .iter()
                                    .filter(|t| t.iter().any(|&x| x) && !t.iter().all(|&x| x))
                                    .count();
                                assert_eq!(segs.len(), mixed, "cfg {cfg} face {axis}/{side}");
                            }
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn fig_3_5_configuration() {
    // H Fig. 3.5: f = 2(1-x)(1-y)(1-z) + 1.6x(1-y)(1-z) + 1.4(1-x)y(1-z) + 1.4(1-x)(1-y)z
    //            + .4x(1-y)z + 2(1-x)yz + 2xyz, alpha = 1.5
    let f = |x: f64, y: f64, z: f64| {
        2.0 * (1.0 - x) * (1.0 - y) * (1.0 - z)
            + 1.6 * x * (1.0 - y) * (1.0 - z)
            + 1.4 * (1.0 - x) * y * (1.0 - z)
            + 1.4 * (1.0 - x) * (1.0 - y) * z
            + 0.4 * x * (1.0 - y) * z
            + 2.0 * (1.0 - x) * y * z
            + 2.0 * x * y * z
    };
    let v = Volume::from_fn([2, 2, 2], [0.0; 3], [1.0; 3], f);
    let r = run(&v, 1.5, IsoMethod::Decider);
    // one polygon of 8 contour points (two segments on each of the faces x=0 and x=1),
    // triangulated as a fan of 8 triangles around y_n on the line through the asymptotes'
    // intersection (0, 1/2, 1/2) of face x = 0 (Eqs. 3.10-3.11): t0 = (1.5-1.7)/(1.0-1.7) = 2/7
    assert_eq!(r.mesh.positions.len(), 9);
    assert_eq!(r.mesh.triangles.len(), 8);
    assert_eq!(r.fan_points, 1);
    assert_eq!(r.centroid_fallbacks, 0);
    assert_eq!(r.parts, 1);
    assert_eq!(r.boundary_edges, 8);
    let yn = r.mesh.positions[8];
    assert!(
        (yn - Point3::new(2.0 / 7.0, 0.5, 0.5)).norm() < 1e-6,
        "{yn:?}"
    );
    // every contour point on the trilinear contour f = 1.5 (f32 storage of 1.4 and 1.6)
    for p in &r.mesh.positions {
        let (g, _) = trilinear(&v, 1.5, p);
        assert!(g.abs() < 1e-6, "{p:?} {g}");
    }
    // edges on the cube faces are exactly the 8 polygon segments
    for (&(a, b), uses) in &edge_map(&r.mesh) {
        let on_face = a < 8 && b < 8;
        assert_eq!(uses.len(), if on_face { 1 } else { 2 });
    }
}

#[test]
fn lorensen_leaves_a_hole_where_decider_and_tetra_do_not() {
    // 3x2x2 samples, two cells sharing face x = 1 whose diagonal (y,z) = (0,0),(1,1) is positive.
    // Left cell has 2 positive corners, right cell 6: Lorensen's cell-local rule cuts off the
    // positives in one cell and the negatives in the other, so the segments on the shared face
    // differ (H Fig. 3.2).
    let mut data = vec![0.0; 12];
    let idx = |x: usize, y: usize, z: usize| x + 3 * (y + 2 * z);
    for z in 0..2 {
        for y in 0..2 {
            data[idx(0, y, z)] = -1.0;
            data[idx(2, y, z)] = 1.0;
        }
    }
    data[idx(1, 0, 0)] = 2.0;
    data[idx(1, 1, 1)] = 2.0;
    data[idx(1, 1, 0)] = -1.0;
    data[idx(1, 0, 1)] = -1.0;
    let v = vol_from([3, 2, 2], data);
    let l = run(&v, 0.0, IsoMethod::Lorensen);
    assert!(l.interior_holes > 0, "{l:?}");
    assert!(l.interior_boundary_edges > 0);
    assert!(check_watertight(&l.mesh, [2.0, 1.0, 1.0]).is_err());
    for m in [IsoMethod::Decider, IsoMethod::Tetra] {
        let r = run(&v, 0.0, m);
        assert_eq!(r.interior_holes, 0, "{m:?}");
        assert_eq!(r.interior_boundary_edges, 0, "{m:?}");
        check_watertight(&r.mesh, [2.0, 1.0, 1.0]).unwrap();
    }
}

fn random_volume(dims: [usize; 3], seed: u64, discrete: bool) -> Volume {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let n = dims[0] * dims[1] * dims[2];
    let data = (0..n)
        .map(|_| {
            if discrete {
                rng.gen_range(-2i32..=2) as f64
            } else {
                rng.gen_range(-1.0..1.0)
            }
        })
        .collect();
    vol_from(dims, data)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn random_volumes_are_watertight(
        nx in 2usize..9, ny in 2usize..9, nz in 2usize..9, seed in 0u64..1_000_000,
        discrete in any::<bool>()
    ) {
        let v = random_volume([nx, ny, nz], seed, discrete);
        let hi = [(nx - 1) as f64, (ny - 1) as f64, (nz - 1) as f64];
        for m in [IsoMethod::Decider, IsoMethod::Tetra] {
            let r = run(&v, 0.0, m);
            prop_assert!(check_watertight(&r.mesh, hi).is_ok(), "{m:?}: {:?}", check_watertight(&r.mesh, hi));
            prop_assert_eq!(r.interior_holes, 0);
            prop_assert_eq!(r.non_manifold_edges, 0);
            r.mesh.validate().unwrap();
        }
    }

    #[test]
    fn random_cells_points_on_trilinear_level_set(vals in proptest::collection::vec(-1.0f64..1.0, 8), level in -0.5f64..0.5) {
        let v = vol_from([2, 2, 2], vals);
        let r = run(&v, level, IsoMethod::Decider);
        let hi = [1.0; 3];
        prop_assert!(check_watertight(&r.mesh, hi).is_ok());
        let exact = r.mesh.positions.len() - r.centroid_fallbacks;
        for p in &r.mesh.positions[..exact] {
            let (g, s) = trilinear(&v, level, p);
            prop_assert!(g.abs() <= 1e-9 * s.max(1e-300), "{:?} {} {}", p, g, s);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Random volumes with NaN samples and values equal to the level: never a panic, a valid
    /// mesh, no interior holes for the consistent methods, identical parallel and serial output.
    #[test]
    fn random_volumes_with_nan(
        nx in 2usize..7, ny in 2usize..7, nz in 2usize..9, seed in 0u64..1_000_000,
        nan_rate in 0.0f64..0.15
    ) {
        let mut v = random_volume([nx, ny, nz], seed, true);
        let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x5eed);
        for s in v.data.iter_mut() {
            if rng.gen_bool(nan_rate) {
                *s = f32::NAN;
            }
        }
        for m in [IsoMethod::Decider, IsoMethod::Tetra, IsoMethod::Lorensen] {
            let o = |parallel| IsoOptions { level: 0.0, method: m, parallel, ..Default::default() };
            let r = isosurface(&v, &o(false)).unwrap();
            r.mesh.validate().unwrap();
            if m != IsoMethod::Lorensen {
                prop_assert_eq!(r.interior_holes, 0);
                prop_assert_eq!(r.non_manifold_edges, 0);
            }
            let p = isosurface(&v, &o(true)).unwrap();
            prop_assert!(r == p);
        }
    }
}

#[test]
fn large_random_volume_is_watertight() {
    for (seed, dims) in [(7u64, [16, 16, 16]), (8, [16, 5, 11]), (9, [3, 16, 2])] {
        for discrete in [false, true] {
            let v = random_volume(dims, seed, discrete);
            let hi = dims.map(|d| (d - 1) as f64);
            for m in [IsoMethod::Decider, IsoMethod::Tetra] {
                let r = run(&v, 0.0, m);
                check_watertight(&r.mesh, hi).unwrap();
                assert_eq!(r.interior_holes, 0);
            }
        }
    }
}

#[test]
fn level_set_accuracy_on_random_rectilinear_volume() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let dims = [9, 7, 8];
    let mut v = random_volume(dims, 11, false);
    let coords: [Vec<f64>; 3] = std::array::from_fn(|k| {
        let mut c = vec![0.0];
        for _ in 1..dims[k] {
            let last = *c.last().unwrap();
            c.push(last + rng.gen_range(0.1..3.0));
        }
        c
    });
    v.axes = Axes::Coords(coords);
    let r = run(&v, 0.1, IsoMethod::Decider);
    assert!(r.fan_points > 0 || r.mesh.positions.len() > 50);
    let exact = r.mesh.positions.len()
        - if r.centroid_fallbacks > 0 {
            r.fan_points
        } else {
            0
        };
    for p in &r.mesh.positions[..exact] {
        let (g, s) = trilinear(&v, 0.1, p);
        assert!(g.abs() <= 1e-9 * s, "{p:?} {g} {s}");
    }
}

fn sphere_field(c: [f64; 3], r: f64) -> impl Fn(f64, f64, f64) -> f64 {
    move |x, y, z| r * r - ((x - c[0]).powi(2) + (y - c[1]).powi(2) + (z - c[2]).powi(2))
}

#[test]
fn euler_characteristic_of_closed_objects() {
    let n = [24, 24, 24];
    let sphere = Volume::from_fn(n, [-1.2; 3], [1.2; 3], sphere_field([0.0; 3], 0.8));
    let torus = Volume::from_fn(n, [-1.2; 3], [1.2; 3], |x, y, z| {
        let q = ((x * x + y * y).sqrt() - 0.7).powi(2) + z * z;
        0.25f64.powi(2) - q
    });
    let two = Volume::from_fn(n, [-1.2; 3], [1.2; 3], |x, y, z| {
        let a = sphere_field([-0.5, 0.0, 0.0], 0.4)(x, y, z);
        let b = sphere_field([0.5, 0.1, 0.0], 0.35)(x, y, z);
        a.max(b)
    });
    for m in [IsoMethod::Decider, IsoMethod::Tetra, IsoMethod::Lorensen] {
        for (v, chi, parts) in [(&sphere, 2, 1), (&torus, 0, 1), (&two, 4, 2)] {
            let r = run(v, 0.0, m);
            assert_eq!(euler(&r.mesh), chi, "{m:?}");
            assert_eq!(r.parts, parts, "{m:?}");
            assert_eq!(r.boundary_edges, 0);
            check_watertight(&r.mesh, [1e9; 3]).unwrap();
            // outward orientation for "inside = above level": positive enclosed volume
            assert!(r.mesh.signed_volume() > 0.0);
            let fl = isosurface(
                v,
                &IsoOptions {
                    level: 0.0,
                    method: m,
                    flip: true,
                    ..Default::default()
                },
            )
            .unwrap();
            assert!((fl.mesh.signed_volume() + r.mesh.signed_volume()).abs() < 1e-9);
        }
    }
    // enclosed volume close to the sphere's
    let r = run(&sphere, 0.0, IsoMethod::Decider);
    let exact = 4.0 / 3.0 * std::f64::consts::PI * 0.8f64.powi(3);
    assert!((r.mesh.signed_volume() - exact).abs() / exact < 0.02);
}

#[test]
fn parallel_equals_serial() {
    let v = Volume::from_fn([15, 11, 29], [-1.0; 3], [1.0; 3], |x, y, z| {
        (3.0 * x).sin() * (2.0 * y).cos() + (4.0 * z).sin() * 0.7 + 0.1 * x * y
    });
    for m in [IsoMethod::Decider, IsoMethod::Tetra, IsoMethod::Lorensen] {
        for normals in [NormalMethod::ZuckerHummel, NormalMethod::Mesh] {
            if normals == NormalMethod::Mesh && m != IsoMethod::Decider {
                continue;
            }
            let o = |parallel| IsoOptions {
                level: 0.05,
                method: m,
                normals,
                parallel,
                ..Default::default()
            };
            let s = isosurface(&v, &o(false)).unwrap();
            let p = isosurface(&v, &o(true)).unwrap();
            assert!(s.mesh.triangles.len() > 100);
            assert_eq!(s, p, "{m:?}");
            let bits = |mm: &TriMesh| -> Vec<u64> {
                mm.positions
                    .iter()
                    .flat_map(|q| [q.x.to_bits(), q.y.to_bits(), q.z.to_bits()])
                    .collect()
            };
            assert_eq!(bits(&s.mesh), bits(&p.mesh));
            // without the topology pass: the same triangulation, no part labels
            let nt = isosurface(
                &v,
                &IsoOptions {
                    topology: false,
                    ..o(true)
                },
            )
            .unwrap();
            assert_eq!(nt.mesh.positions, s.mesh.positions);
            assert_eq!(nt.mesh.triangles, s.mesh.triangles);
            assert!(nt.mesh.face_props.is_empty() && nt.parts == 0);
        }
    }
}

#[test]
fn shared_vertices_no_duplicates() {
    let v = Volume::from_fn(
        [12, 12, 12],
        [-1.0; 3],
        [1.0; 3],
        sphere_field([0.1, 0.0, -0.1], 0.7),
    );
    for m in [IsoMethod::Decider, IsoMethod::Tetra, IsoMethod::Lorensen] {
        let r = run(&v, 0.0, m);
        let mut k: Vec<[u64; 3]> = r
            .mesh
            .positions
            .iter()
            .map(|p| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()])
            .collect();
        let n = k.len();
        k.sort_unstable();
        k.dedup();
        assert_eq!(k.len(), n, "{m:?}");
        let mut used = vec![false; n];
        for t in &r.mesh.triangles {
            for &i in t {
                used[i as usize] = true;
            }
        }
        assert!(used.iter().all(|&u| u));
    }
}

#[test]
fn non_uniform_grid_sphere() {
    // sphere r = 1 sampled on a rectilinear grid with growing spacing and on anisotropic voxels
    let axis = |n: usize| -> Vec<f64> {
        (0..n)
            .map(|i| {
                let t = i as f64 / (n - 1) as f64 * 2.0 - 1.0;
                1.5 * t * (0.6 + 0.4 * t.abs())
            })
            .collect()
    };
    let coords = [axis(31), axis(25), axis(37)];
    let dims = [31, 25, 37];
    let mut data = Vec::new();
    for z in 0..dims[2] {
        for y in 0..dims[1] {
            for x in 0..dims[0] {
                let (px, py, pz) = (coords[0][x], coords[1][y], coords[2][z]);
                data.push((1.0 - (px * px + py * py + pz * pz)) as f32);
            }
        }
    }
    let v = Volume {
        dims,
        axes: Axes::Coords(coords),
        data,
        source_dtype: DType::F32,
        orientation: Default::default(),
    };
    let aniso = Volume::from_fn([20, 40, 12], [-1.3; 3], [1.3; 3], |x, y, z| {
        1.0 - (x * x + y * y + z * z)
    });
    for vol in [&v, &aniso] {
        for m in [IsoMethod::Decider, IsoMethod::Tetra] {
            let r = run(vol, 0.0, m);
            assert_eq!(euler(&r.mesh), 2);
            for p in &r.mesh.positions {
                assert!((p.coords.norm() - 1.0).abs() < 0.02, "{m:?} {p:?}");
            }
            // normals point outward (inside = above the level) and match the radial direction
            let nr = r.mesh.normals.as_ref().unwrap();
            for (p, n) in r.mesh.positions.iter().zip(nr) {
                assert!(n.dot(&p.coords.normalize()) > 0.99, "{m:?} {p:?} {n:?}");
            }
        }
    }
}

#[test]
fn normal_methods_agree_on_a_sphere() {
    let v = Volume::from_fn(
        [26, 26, 26],
        [-1.25; 3],
        [1.25; 3],
        sphere_field([0.0; 3], 0.9),
    );
    for (nm, tol) in [
        (NormalMethod::ZuckerHummel, 0.995),
        (NormalMethod::Central, 0.995),
        (NormalMethod::Mesh, 0.98),
    ] {
        for flip in [false, true] {
            let r = isosurface(
                &v,
                &IsoOptions {
                    level: 0.0,
                    normals: nm,
                    flip,
                    ..Default::default()
                },
            )
            .unwrap();
            let nr = r.mesh.normals.as_ref().unwrap();
            let s = if flip { -1.0 } else { 1.0 };
            for (p, n) in r.mesh.positions.iter().zip(nr) {
                assert!((n.norm() - 1.0).abs() < 1e-9);
                assert!(s * n.dot(&p.coords.normalize()) > tol, "{nm:?} {p:?} {n:?}");
            }
        }
    }
    let r = isosurface(
        &v,
        &IsoOptions {
            normals: NormalMethod::None,
            ..Default::default()
        },
    )
    .unwrap();
    assert!(r.mesh.normals.is_none());
}

#[test]
fn nan_samples_are_skipped_without_holes() {
    let mut v = Volume::from_fn(
        [14, 14, 14],
        [-1.0; 3],
        [1.0; 3],
        sphere_field([0.0; 3], 0.7),
    );
    let i = v.index(7, 6, 10);
    v.data[i] = f32::NAN;
    let j = v.index(2, 2, 2);
    v.data[j] = f32::NAN;
    for m in [IsoMethod::Decider, IsoMethod::Tetra, IsoMethod::Lorensen] {
        let r = run(&v, 0.0, m);
        assert_eq!(r.skipped_cells, 16);
        assert!(r.note.as_deref().unwrap_or("").contains("NaN"));
        assert!(r.boundary_edges > 0, "{m:?}");
        assert_eq!(r.interior_holes, 0, "{m:?}");
        r.mesh.validate().unwrap();
        for n in r.mesh.normals.as_ref().unwrap() {
            assert!(n.iter().all(|c| c.is_finite()));
        }
    }
    // all NaN
    let w = Volume::new([2, 2, 2], [0.0; 3], [1.0; 3], vec![f32::NAN; 8]).unwrap();
    let r = run(&w, 0.0, IsoMethod::Decider);
    assert!(r.mesh.triangles.is_empty() && r.note.is_some());
}

#[test]
fn degenerate_volumes() {
    // flat volume: no cells
    let v = vol_from([5, 5, 1], vec![0.0; 25]);
    let r = run(&v, 0.0, IsoMethod::Decider);
    assert!(r.mesh.triangles.is_empty() && r.note.is_some());
    // constant volume equal to the level: perturbed above, no surface
    let v = vol_from([3, 3, 3], vec![1.0; 27]);
    let r = run(&v, 1.0, IsoMethod::Decider);
    assert!(r.mesh.triangles.is_empty());
    // level at the maximum: all samples >= level
    let v = random_volume([4, 4, 4], 5, true);
    let r = run(&v, 2.0, IsoMethod::Tetra);
    assert!(r.mesh.triangles.is_empty() || r.boundary_edges == 0 || r.interior_holes == 0);
}

#[test]
fn largest_part_extraction() {
    let v = Volume::from_fn([24, 24, 24], [-1.2; 3], [1.2; 3], |x, y, z| {
        let a = sphere_field([-0.5, 0.0, 0.0], 0.4)(x, y, z);
        let b = sphere_field([0.5, 0.1, 0.0], 0.3)(x, y, z);
        a.max(b)
    });
    let r = run(&v, 0.0, IsoMethod::Decider);
    assert_eq!(r.parts, 2);
    let l = morpho::volume::largest_part(&r.mesh).unwrap();
    let big = morpho::volume::extract_part(&r.mesh, l);
    big.validate().unwrap();
    assert_eq!(euler(&big), 2);
    assert!(big.bbox().center()[0] < 0.0);
    assert!(big.triangles.len() > r.mesh.triangles.len() / 2);
}

#[test]
fn regression_fan_point_on_outer_face() {
    // Eq. 3.11 gave t0 = 1 exactly (integer data): the interior point fell on the volume's face.
    let v = random_volume([5, 5, 2], 387585, true);
    let r = run(&v, 0.0, IsoMethod::Decider);
    check_watertight(&r.mesh, [4.0, 4.0, 1.0]).unwrap();
    assert!(r.centroid_fallbacks > 0);
}

#[test]
fn ct_head_bone_surface_has_no_interior_holes() {
    let Some(path) = common::data("volumes/cthead_8bit_256x256x99.raw.gz") else {
        return;
    };
    let bytes = morpho::io::read_bytes(&path).unwrap();
    assert_eq!(bytes.len(), 256 * 256 * 99);
    // a crop of the skull (x 80..144, y 40..104, z 24..48), spacing 1:1:2 as documented
    let (x0, y0, z0, n) = (80, 40, 24, [64usize, 64, 24]);
    let mut data = Vec::with_capacity(n[0] * n[1] * n[2]);
    for z in 0..n[2] {
        for y in 0..n[1] {
            for x in 0..n[0] {
                data.push(bytes[(x0 + x) + 256 * ((y0 + y) + 256 * (z0 + z))] as f32);
            }
        }
    }
    let v = Volume::new(n, [0.0; 3], [1.0, 1.0, 2.0], data).unwrap();
    let hi = [63.0, 63.0, 46.0];
    for m in [IsoMethod::Decider, IsoMethod::Tetra] {
        let r = run(&v, 120.0, m);
        assert!(r.mesh.triangles.len() > 2_000, "{}", r.mesh.triangles.len());
        assert_eq!(r.interior_holes, 0, "{m:?}");
        assert_eq!(r.non_manifold_edges, 0, "{m:?}");
        check_watertight(&r.mesh, hi).unwrap();
        assert!(r.parts >= 1);
    }
    // integer data hits the level exactly and has ambiguous faces: Lorensen shows holes
    let l = run(&v, 120.0, IsoMethod::Lorensen);
    assert!(l.interior_holes > 0);
    eprintln!(
        "CT crop: lorensen interior holes {}, boundary edges {}",
        l.interior_holes, l.boundary_edges
    );
}

#[test]
fn infinite_samples_give_finite_vertices() {
    let mut v = Volume::from_fn(
        [10, 10, 10],
        [-1.0; 3],
        [1.0; 3],
        sphere_field([0.0; 3], 0.6),
    );
    let i = v.index(5, 5, 5);
    v.data[i] = f32::INFINITY;
    let j = v.index(1, 1, 1);
    v.data[j] = f32::NEG_INFINITY;
    let k = v.index(5, 5, 2);
    v.data[k] = f32::INFINITY; // next to the surface
    for m in [IsoMethod::Decider, IsoMethod::Tetra, IsoMethod::Lorensen] {
        for nm in [NormalMethod::ZuckerHummel, NormalMethod::Mesh] {
            let r = isosurface(
                &v,
                &IsoOptions {
                    level: 0.0,
                    method: m,
                    normals: nm,
                    ..Default::default()
                },
            )
            .unwrap();
            r.mesh.validate().unwrap();
            assert!(r
                .mesh
                .normals
                .unwrap()
                .iter()
                .all(|n| n.iter().all(|c| c.is_finite())));
            if m != IsoMethod::Lorensen {
                assert_eq!(r.interior_holes, 0);
            }
        }
    }
}

/// The Zucker–Hummel normal of every edge vertex, recomputed from `gradient_at` at the edge's
/// two grid points and interpolated as H Eq. 3.19 says (the same arithmetic as the extraction),
/// on unit-spaced volumes: the extraction's per-slab gradient cache must hand out each grid
/// point's own gradient, whatever the plane, slab or thread. Returns the largest deviation.
fn zh_normal_deviation(v: &Volume, level: f64) -> f64 {
    use morpho::volume::{axis_coords, gradient_at, GradientOperator};
    let r = run(v, level, IsoMethod::Decider);
    let normals = r.mesh.normals.as_ref().expect("normals");
    let axes = axis_coords(v);
    let (lo, hi) = v
        .data
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &x| {
            (l.min(x as f64), h.max(x as f64))
        });
    let eps = (hi - lo) * 1e-9;
    let g = |p: [usize; 3]| {
        let d = v.at(p[0], p[1], p[2]) as f64 - level;
        if d == 0.0 {
            eps
        } else {
            d
        }
    };
    let mut worst = 0.0f64;
    let mut checked = 0;
    for (p, n) in r.mesh.positions.iter().zip(normals) {
        let c = [p.x, p.y, p.z];
        let frac: Vec<usize> = (0..3).filter(|&k| c[k].fract() != 0.0).collect();
        let [k] = frac[..] else { continue }; // an interior fan point
        let a = c.map(|x| x.floor() as usize);
        let mut b = a;
        b[k] += 1;
        let (ga, gb) = (g(a), g(b));
        let t = ga / (ga - gb);
        let (na, nb) = (
            gradient_at(v, &axes, a, GradientOperator::ZuckerHummel),
            gradient_at(v, &axes, b, GradientOperator::ZuckerHummel),
        );
        let m: [f64; 3] = std::array::from_fn(|i| na[i] * (1.0 - t) + nb[i] * t);
        let l2 = m[0] * m[0] + m[1] * m[1] + m[2] * m[2];
        if l2 == 0.0 {
            continue; // a flat spot: the normal comes from the mesh
        }
        let s = -1.0 / l2.sqrt();
        for i in 0..3 {
            worst = worst.max((m[i] * s - [n.x, n.y, n.z][i]).abs());
        }
        checked += 1;
    }
    assert!(checked > 0 || r.mesh.positions.is_empty());
    worst
}

#[test]
fn zucker_hummel_normals_are_the_grid_gradients_interpolated() {
    // smooth, several slabs in parallel, many layers sharing cached planes
    let v = Volume::from_fn([23, 19, 41], [0.0; 3], [22.0, 18.0, 40.0], |x, y, z| {
        (x * 0.4).sin() * (y * 0.3).cos() + (y * 0.3).sin() * (z * 0.25).cos() + (z * 0.2).sin()
    });
    assert_eq!(zh_normal_deviation(&v, 0.1), 0.0);
    // random samples, with samples exactly at the level (raised by ε)
    for seed in 0..40 {
        let dims = [
            3 + seed as usize % 7,
            2 + seed as usize % 5,
            2 + seed as usize % 9,
        ];
        for discrete in [false, true] {
            let v = random_volume(dims, seed, discrete);
            assert_eq!(zh_normal_deviation(&v, 0.0), 0.0, "seed {seed} {discrete}");
        }
    }
}

/// Brute-force parts of a triangulation: triangles sharing an edge are merged by repeated
/// flooding over the edge map; labels numbered in order of first triangle. Also the count of
/// edges with one triangle and with more than two.
fn brute_parts(m: &TriMesh) -> (Vec<usize>, usize, usize) {
    let em = edge_map(m);
    let mut nbrs = vec![Vec::new(); m.triangles.len()];
    for uses in em.values() {
        for &(a, _) in uses {
            for &(b, _) in uses {
                if a != b {
                    nbrs[a].push(b);
                }
            }
        }
    }
    let mut label = vec![usize::MAX; m.triangles.len()];
    let mut parts = 0;
    for t in 0..m.triangles.len() {
        if label[t] != usize::MAX {
            continue;
        }
        let mut stack = vec![t];
        label[t] = parts;
        while let Some(u) = stack.pop() {
            for &w in &nbrs[u] {
                if label[w] == usize::MAX {
                    label[w] = parts;
                    stack.push(w);
                }
            }
        }
        parts += 1;
    }
    let boundary = em.values().filter(|u| u.len() == 1).count();
    let nonmanifold = em.values().filter(|u| u.len() > 2).count();
    (label, boundary, nonmanifold)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// The topology pass's parts, labels, boundary and non-manifold edge counts equal a
    /// brute-force flood over the edge map, for every method, on random volumes with samples
    /// exactly at the level.
    #[test]
    fn topology_equals_brute_force(
        nx in 2usize..10, ny in 2usize..10, nz in 2usize..10, seed in 0u64..1_000_000,
        discrete in any::<bool>()
    ) {
        let v = random_volume([nx, ny, nz], seed, discrete);
        for m in [IsoMethod::Decider, IsoMethod::Tetra, IsoMethod::Lorensen] {
            let r = run(&v, 0.0, m);
            let (label, boundary, nonmanifold) = brute_parts(&r.mesh);
            let got: Vec<usize> = r.mesh.face_prop("part").map_or(Vec::new(), |p| {
                p.values.iter().map(|&x| x as usize).collect()
            });
            prop_assert_eq!(&got, &label, "{:?}", m);
            prop_assert_eq!(r.parts, label.iter().max().map_or(0, |&l| l + 1));
            prop_assert_eq!(r.boundary_edges, boundary);
            prop_assert_eq!(r.non_manifold_edges, nonmanifold);
        }
    }
}
