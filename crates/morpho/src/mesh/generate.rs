//! Meshes of known shape and topology, for tests, benchmarks and the demo.
//!
//! | generator | surface | χ | genus | boundary loops |
//! |---|---|---|---|---|
//! | [`uv_sphere`], [`icosphere`], [`tetrahedron`], [`cube`] | sphere | 2 | 0 | 0 |
//! | [`torus`] | torus | 0 | 1 | 0 |
//! | [`multi_torus`]`(g)` | closed surface of genus g | 2 − 2g | g | 0 |
//! | [`disk`] | disc | 1 | 0 | 1 |
//! | [`annulus`] | disc with a hole | 0 | 0 | 2 |
//! | [`mobius`] | Möbius strip (non-orientable) | 0 | — | 1 |
//!
//! All meshes are free of duplicate vertices; closed ones are oriented outward (positive signed
//! volume), the disc and annulus lie in the plane z = 0 facing +z. Sizes are clamped to the
//! smallest values that give a valid surface (e.g. `n_lon ≥ 3`). Each generator is O(output).
//! Convex generators choose each face's orientation with the exact [`crate::geom::orient3d`].

use super::TriMesh;
use crate::geom::{orient3d, Point3};
use std::collections::HashMap;
use std::f64::consts::{PI, TAU};

/// Makes every face of a mesh that is star-shaped about `center` face away from it.
fn orient_away_from(m: &mut TriMesh, center: Point3) {
    for t in m.triangles.iter_mut() {
        let [a, b, c] = t.map(|v| m.positions[v as usize]);
        if orient3d(&a, &b, &c, &center) < 0.0 {
            t.swap(1, 2);
        }
    }
}

/// A UV sphere of radius `r > 0`: `n_lat ≥ 2` latitude bands between two poles, `n_lon ≥ 3`
/// meridians.
/// Vertices: 2 + (n_lat − 1)·n_lon; triangles: 2·(n_lat − 1)·n_lon.
pub fn uv_sphere(center: Point3, r: f64, n_lat: usize, n_lon: usize) -> TriMesh {
    let (n_lat, n_lon) = (n_lat.max(2), n_lon.max(3));
    let mut pos = vec![center + nalgebra::Vector3::new(0.0, 0.0, r)];
    for i in 1..n_lat {
        let th = PI * i as f64 / n_lat as f64;
        for j in 0..n_lon {
            let ph = TAU * j as f64 / n_lon as f64;
            pos.push(
                center
                    + r * nalgebra::Vector3::new(
                        th.sin() * ph.cos(),
                        th.sin() * ph.sin(),
                        th.cos(),
                    ),
            );
        }
    }
    pos.push(center - nalgebra::Vector3::new(0.0, 0.0, r));
    let south = (pos.len() - 1) as u32;
    let ring = |i: usize, j: usize| (1 + (i - 1) * n_lon + j % n_lon) as u32;
    let mut tris = Vec::new();
    for j in 0..n_lon {
        tris.push([0, ring(1, j), ring(1, j + 1)]);
        tris.push([ring(n_lat - 1, j), south, ring(n_lat - 1, j + 1)]);
    }
    for i in 1..n_lat - 1 {
        for j in 0..n_lon {
            tris.push([ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)]);
            tris.push([ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)]);
        }
    }
    TriMesh::new(pos, tris)
}

/// A unit icosphere about the origin: the icosahedron with each triangle split into four
/// `subdiv` times, new vertices pushed to the sphere. 10·4^s + 2 vertices, 20·4^s triangles.
pub fn icosphere(subdiv: u32) -> TriMesh {
    let g = (1.0 + 5f64.sqrt()) / 2.0;
    let mut pos: Vec<Point3> = [
        (-1.0, g, 0.0),
        (1.0, g, 0.0),
        (-1.0, -g, 0.0),
        (1.0, -g, 0.0),
        (0.0, -1.0, g),
        (0.0, 1.0, g),
        (0.0, -1.0, -g),
        (0.0, 1.0, -g),
        (g, 0.0, -1.0),
        (g, 0.0, 1.0),
        (-g, 0.0, -1.0),
        (-g, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| Point3::from(nalgebra::Vector3::new(x, y, z).normalize()))
    .collect();
    let mut tris: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    let mut m = TriMesh::new(pos.clone(), tris.clone());
    orient_away_from(&mut m, Point3::origin());
    tris = m.triangles;
    for _ in 0..subdiv.min(10) {
        let mut mid: HashMap<(u32, u32), u32> = HashMap::new();
        let mut next = Vec::with_capacity(tris.len() * 4);
        let mut midpoint = |a: u32, b: u32, pos: &mut Vec<Point3>| -> u32 {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                let p = nalgebra::center(&pos[a as usize], &pos[b as usize]);
                pos.push(Point3::from(p.coords.normalize()));
                (pos.len() - 1) as u32
            })
        };
        for &[a, b, c] in &tris {
            let ab = midpoint(a, b, &mut pos);
            let bc = midpoint(b, c, &mut pos);
            let ca = midpoint(c, a, &mut pos);
            next.extend_from_slice(&[[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        tris = next;
    }
    TriMesh::new(pos, tris)
}

/// A torus about the z axis: major radius `big_r`, tube radius `r` (< `big_r`), `n_major ≥ 3`
/// segments around the axis and `n_minor ≥ 3` around the tube. χ = 0, genus 1.
pub fn torus(big_r: f64, r: f64, n_major: usize, n_minor: usize) -> TriMesh {
    let (nu, nv) = (n_major.max(3), n_minor.max(3));
    let mut pos = Vec::with_capacity(nu * nv);
    for i in 0..nu {
        let u = TAU * i as f64 / nu as f64;
        for j in 0..nv {
            let v = TAU * j as f64 / nv as f64;
            let w = big_r + r * v.cos();
            pos.push(Point3::new(w * u.cos(), w * u.sin(), r * v.sin()));
        }
    }
    let id = |i: usize, j: usize| ((i % nu) * nv + j % nv) as u32;
    let mut tris = Vec::with_capacity(2 * nu * nv);
    for i in 0..nu {
        for j in 0..nv {
            tris.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            tris.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    TriMesh::new(pos, tris)
}

/// The boundary surface of a set of unit voxels `[i, i+1] × [j, j+1] × [k, k+1]` of an
/// `nx × ny × nz` grid, outward oriented, lattice vertices shared. Manifold as long as no two
/// solid voxels touch only along an edge or at a corner.
fn voxel_surface(dims: [usize; 3], solid: impl Fn(usize, usize, usize) -> bool) -> TriMesh {
    let is = |p: [i64; 3]| {
        (0..3).all(|a| p[a] >= 0 && (p[a] as usize) < dims[a])
            && solid(p[0] as usize, p[1] as usize, p[2] as usize)
    };
    let mut index: HashMap<[i64; 3], u32> = HashMap::new();
    let mut pos = Vec::new();
    let mut vid = |p: [i64; 3], pos: &mut Vec<Point3>| -> u32 {
        *index.entry(p).or_insert_with(|| {
            pos.push(Point3::new(p[0] as f64, p[1] as f64, p[2] as f64));
            (pos.len() - 1) as u32
        })
    };
    let mut tris = Vec::new();
    for k in 0..dims[2] as i64 {
        for j in 0..dims[1] as i64 {
            for i in 0..dims[0] as i64 {
                let c = [i, j, k];
                if !is(c) {
                    continue;
                }
                for a in 0..3 {
                    let (b, d) = ((a + 1) % 3, (a + 2) % 3);
                    for s in [-1i64, 1] {
                        let mut n = c;
                        n[a] += s;
                        if is(n) {
                            continue;
                        }
                        // Face at x_a = c[a] + (s > 0); e_b × e_d = e_a.
                        let mut p = c;
                        p[a] += (s > 0) as i64;
                        let mut q = [p, p, p, p];
                        q[1][b] += 1;
                        q[2][b] += 1;
                        q[2][d] += 1;
                        q[3][d] += 1;
                        let v = q.map(|x| vid(x, &mut pos));
                        if s > 0 {
                            tris.push([v[0], v[1], v[2]]);
                            tris.push([v[0], v[2], v[3]]);
                        } else {
                            tris.push([v[0], v[2], v[1]]);
                            tris.push([v[0], v[3], v[2]]);
                        }
                    }
                }
            }
        }
    }
    TriMesh::new(pos, tris)
}

/// A closed orientable surface of genus `genus`: the boundary of a 1-voxel-thick plate of
/// (2g + 1) × 3 unit voxels with g square holes (voxels (2i + 1, 1) removed). Coordinates are
/// integers in [0, 2g + 1] × [0, 3] × [0, 1]. χ = 2 − 2g.
pub fn multi_torus(genus: usize) -> TriMesh {
    voxel_surface([2 * genus + 1, 3, 1], |i, j, _| !(j == 1 && i % 2 == 1))
}

/// The unit disc in the plane z = 0, facing +z: a centre vertex and `n_rings ≥ 1` rings of
/// `n_sectors ≥ 3` vertices. χ = 1, one boundary loop.
pub fn disk(n_rings: usize, n_sectors: usize) -> TriMesh {
    let (nr, ns) = (n_rings.max(1), n_sectors.max(3));
    let mut pos = vec![Point3::origin()];
    rings(&mut pos, 1, nr, ns, |k| k as f64 / nr as f64);
    let id = |k: usize, j: usize| (1 + (k - 1) * ns + j % ns) as u32;
    let mut tris = Vec::new();
    for j in 0..ns {
        tris.push([0, id(1, j), id(1, j + 1)]);
    }
    for k in 1..nr {
        for j in 0..ns {
            tris.push([id(k, j), id(k + 1, j), id(k + 1, j + 1)]);
            tris.push([id(k, j), id(k + 1, j + 1), id(k, j + 1)]);
        }
    }
    TriMesh::new(pos, tris)
}

fn rings(
    pos: &mut Vec<Point3>,
    first: usize,
    last: usize,
    ns: usize,
    radius: impl Fn(usize) -> f64,
) {
    for k in first..=last {
        let r = radius(k);
        for j in 0..ns {
            let a = TAU * j as f64 / ns as f64;
            pos.push(Point3::new(r * a.cos(), r * a.sin(), 0.0));
        }
    }
}

/// The annulus `r_inner ≤ |x| ≤ r_outer` in the plane z = 0, facing +z: `n_rings + 1 ≥ 2`
/// circles of `n_sectors ≥ 3` vertices. χ = 0, two boundary loops, genus 0. Needs
/// `0 < r_inner < r_outer` for distinct vertex positions (the connectivity does not depend on it).
pub fn annulus(r_inner: f64, r_outer: f64, n_rings: usize, n_sectors: usize) -> TriMesh {
    let (nr, ns) = (n_rings.max(1), n_sectors.max(3));
    let mut pos = Vec::new();
    rings(&mut pos, 0, nr, ns, |k| {
        r_inner + (r_outer - r_inner) * k as f64 / nr as f64
    });
    let id = |k: usize, j: usize| (k * ns + j % ns) as u32;
    let mut tris = Vec::new();
    for k in 0..nr {
        for j in 0..ns {
            tris.push([id(k, j), id(k + 1, j), id(k + 1, j + 1)]);
            tris.push([id(k, j), id(k + 1, j + 1), id(k, j + 1)]);
        }
    }
    TriMesh::new(pos, tris)
}

/// A Möbius strip about the unit circle: `n_len ≥ 3` segments along, `n_width ≥ 1` across.
/// Non-orientable, χ = 0, one boundary loop of 2·n_len edges.
///
/// ```
/// use morpho::mesh::{analyze_topology, generate};
/// let t = analyze_topology(&generate::mobius(12, 2));
/// assert!(!t.orientable);
/// assert_eq!(t.boundary_loops.len(), 1); // one boundary curve
/// ```
pub fn mobius(n_len: usize, n_width: usize) -> TriMesh {
    let (nu, nw) = (n_len.max(3), n_width.max(1));
    let mut pos = Vec::new();
    for i in 0..nu {
        let u = TAU * i as f64 / nu as f64;
        for j in 0..=nw {
            let w = -0.5 + j as f64 / nw as f64;
            let rr = 1.0 + 0.5 * w * (u / 2.0).cos();
            pos.push(Point3::new(
                rr * u.cos(),
                rr * u.sin(),
                0.5 * w * (u / 2.0).sin(),
            ));
        }
    }
    // Going once around flips the strip: (nu, j) is (0, nw − j).
    let id = |i: usize, j: usize| {
        if i == nu {
            (nw - j) as u32
        } else {
            (i * (nw + 1) + j) as u32
        }
    };
    let mut tris = Vec::new();
    for i in 0..nu {
        for j in 0..nw {
            tris.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            tris.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    TriMesh::new(pos, tris)
}

/// A regular tetrahedron inscribed in the cube [−1, 1]³, outward oriented.
pub fn tetrahedron() -> TriMesh {
    let pos = vec![
        Point3::new(1.0, 1.0, 1.0),
        Point3::new(1.0, -1.0, -1.0),
        Point3::new(-1.0, 1.0, -1.0),
        Point3::new(-1.0, -1.0, 1.0),
    ];
    let mut m = TriMesh::new(pos, vec![[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]]);
    orient_away_from(&mut m, Point3::origin());
    m
}

/// The unit cube [0, 1]³: 8 vertices, 12 triangles, outward oriented.
///
/// ```
/// use morpho::mesh::{analyze_topology, generate};
/// let c = generate::cube();
/// let t = analyze_topology(&c);
/// assert!(t.is_closed() && t.consistently_oriented);
/// assert_eq!((t.euler_characteristic, t.genus()), (2, Some(0)));
/// assert!(c.signed_volume() > 0.0); // outward
/// ```
pub fn cube() -> TriMesh {
    voxel_surface([1, 1, 1], |_, _, _| true)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::analyze_topology;

    /// (χ, genus, boundary loops, parts) and the shared sanity checks.
    fn check(m: &TriMesh, chi: i64, genus: Option<i64>, loops: usize) {
        m.validate().unwrap();
        let t = analyze_topology(m);
        assert_eq!(t.euler_characteristic, chi, "χ");
        assert_eq!(t.genus(), genus, "genus");
        assert_eq!(t.boundary_loops.len(), loops, "loops");
        assert_eq!(t.parts.len(), 1);
        assert_eq!(t.num_used_vertices, m.num_vertices(), "unused vertices");
        assert!(t.manifold && t.degenerate_triangles.is_empty());
        // No two vertices at the same place.
        let mut p: Vec<[u64; 3]> = m
            .positions
            .iter()
            .map(|p| [p.x, p.y, p.z].map(|c| (c + 0.0).to_bits()))
            .collect();
        p.sort_unstable();
        p.dedup();
        assert_eq!(p.len(), m.num_vertices(), "duplicate vertices");
        if genus.is_some() {
            assert!(t.consistently_oriented);
            if loops == 0 {
                assert!(m.signed_volume() > 0.0, "not outward");
            }
        }
    }

    #[test]
    fn spheres() {
        for (a, b) in [(2, 3), (3, 4), (10, 17)] {
            check(
                &uv_sphere(Point3::new(1.0, 2.0, 3.0), 2.0, a, b),
                2,
                Some(0),
                0,
            );
        }
        for s in 0..4 {
            let m = icosphere(s);
            assert_eq!(m.num_triangles(), 20 * 4usize.pow(s));
            check(&m, 2, Some(0), 0);
        }
        let m = uv_sphere(Point3::origin(), 1.0, 64, 128);
        assert!((m.signed_volume() - 4.0 / 3.0 * PI).abs() < 0.01);
        check(&tetrahedron(), 2, Some(0), 0);
        check(&cube(), 2, Some(0), 0);
        assert!((cube().signed_volume() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn tori() {
        check(&torus(2.0, 0.5, 3, 3), 0, Some(1), 0);
        check(&torus(2.0, 0.5, 20, 9), 0, Some(1), 0);
        for g in 0..5 {
            let m = multi_torus(g);
            check(&m, 2 - 2 * g as i64, Some(g as i64), 0);
            assert!((m.signed_volume() - (3 * (2 * g + 1) - g) as f64).abs() < 1e-9);
        }
    }

    #[test]
    fn flat() {
        let m = disk(1, 3);
        assert_eq!(m.num_triangles(), 3);
        check(&m, 1, Some(0), 1);
        check(&disk(5, 12), 1, Some(0), 1);
        let t = analyze_topology(&disk(5, 12));
        assert_eq!(t.boundary_loops[0].len(), 12);
        check(&annulus(0.5, 1.0, 1, 3), 0, Some(0), 2);
        check(&annulus(0.5, 2.0, 4, 16), 0, Some(0), 2);
        // All face +z.
        for m in [disk(3, 7), annulus(1.0, 2.0, 2, 9)] {
            for t in &m.triangles {
                let [a, b, c] = t.map(|v| m.positions[v as usize]);
                assert!((b - a).cross(&(c - a)).z > 0.0);
            }
        }
    }

    #[test]
    fn mobius_strip() {
        for (n, w) in [(3, 1), (12, 3)] {
            let m = mobius(n, w);
            let t = analyze_topology(&m);
            assert_eq!(t.euler_characteristic, 0);
            assert_eq!(t.boundary_loops.len(), 1);
            assert_eq!(t.boundary_loops[0].len(), 2 * n);
            assert!(!t.orientable && t.genus().is_none() && t.manifold);
        }
    }
}
