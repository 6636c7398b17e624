//! The last step of the 3D fallback (Veltkamp 1992, §5.4 at c = −1): vertices still off the
//! boundary after the adaptive augmentation are put on it one by one, each by the removal of a
//! tetrahedron spanned by a boundary face and the vertex ([`General3::insert_left_out`]).
//!
//! At c = −1 every triangle whose closed triangle holds no other point is in γ(\[-1,1\],\[-1,1\]),
//! so the tetrahedron (f, v) of a boundary face f and a vertex v off the boundary is removable in
//! the sense of V §5.3 whenever it is empty and its three new faces meet no boundary triangle —
//! the general engine's own test ([`General3::check`]). The engine proposes such tetrahedra only
//! on the faces near v that [`General3::local_gamma`] looks at (the edges of the 16 boundary
//! faces nearest to v, pairs of its 16 nearest vertices); where the surface folds close to v —
//! thin parts, tight clusters of points (the full Stanford dragon scan: four points ≈ 1e-5
//! apart against a spacing of 2.2e-4) — those faces are all blocked, and the whole-object
//! engine run that followed neither freed v nor stayed near the Delaunay time (25× on the
//! dragon). This step widens the search instead: boundary faces by distance of their centroid
//! to v, in boxes of doubling half-width, each tested exactly (`orient3d` side, empty closed
//! tetrahedron, the three new faces against the boundary by exact triangle–triangle tests).
//!
//! Why the result is still a closed embedded genus-0 surface through the region: the removed
//! tetrahedron lies on the inner side of f, holds no point and meets no boundary triangle
//! except f and in common vertices/edges, so it lies in the closed region; removing it replaces
//! f by three faces around the new boundary vertex v (V + 1, E + 3, F + 2: χ unchanged); the
//! live triangles meeting it are deleted as by every removal (`remove`).
//!
//! A vertex that no boundary face within [`MAX_FACES`] faces sees that way stays off the
//! boundary and is reported in [`super::Boundary3::left_out`]. Cost: O(L·F·m) for L vertices,
//! F ≤ [`MAX_FACES`] faces tried each and m boundary triangles near a tetrahedron.

use super::general::*;
use crate::geom::predicates::raw::orient3d;
use crate::util::{sorted3, IdSet};

/// Boundary faces tried per vertex (nearest first).
pub(super) const MAX_FACES: usize = 1024;

/// Box doublings of the face search around a vertex.
const MAX_ROUNDS: usize = 8;

impl General3<'_> {
    /// Puts every vertex off the boundary on it where a boundary face sees it (see the module
    /// documentation), repeating while that frees vertices (a vertex freed changes the faces
    /// the others see); returns how many were put on the boundary.
    pub fn insert_left_out(&mut self) -> usize {
        let mut count = 0;
        loop {
            let left: Vec<u32> = (0..self.p.len() as u32)
                .filter(|&v| !self.on_boundary(v))
                .collect();
            let before = count;
            for v in left {
                if !self.on_boundary(v) && self.insert_vertex(v) {
                    count += 1;
                }
            }
            if count == before || self.done() {
                return count;
            }
        }
    }

    /// Puts vertex `v` (off the boundary) on it through the nearest boundary face that sees it.
    fn insert_vertex(&mut self, v: u32) -> bool {
        let pv = self.pt(v);
        let mut rad = 2.0 * self.vgrid.cell();
        let mut tried: IdSet<[u32; 3]> = Default::default();
        let mut buf = Vec::new();
        for _ in 0..MAX_ROUNDS {
            self.bgrid.query(
                std::array::from_fn(|i| pv[i] - rad),
                std::array::from_fn(|i| pv[i] + rad),
                &mut buf,
            );
            // the live boundary faces (oriented outward), nearest centroid first (an order of
            // trial only: every decision below is exact)
            let mut faces: Vec<(f64, [u32; 3])> = buf
                .iter()
                .filter(|&&i| self.live[i as usize] && self.bflag[i as usize])
                .map(|&i| {
                    let s = self.tris[i as usize];
                    let f = if self.is_bface(s) {
                        s
                    } else {
                        [s[0], s[2], s[1]]
                    };
                    let q = f.map(|x| self.pt(x));
                    let d2 = (0..3)
                        .map(|k| ((q[0][k] + q[1][k] + q[2][k]) / 3.0 - pv[k]).powi(2))
                        .sum::<f64>();
                    (d2, f)
                })
                .filter(|(_, f)| !tried.contains(&sorted3(*f)))
                .collect();
            faces.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            for (_, f) in faces {
                if tried.len() >= MAX_FACES {
                    return false;
                }
                tried.insert(sorted3(f));
                if self.pierce(f, v) {
                    return true;
                }
            }
            rad *= 2.0;
        }
        false
    }

    /// Removes the tetrahedron (boundary face f, vertex v off the boundary) when the engine's
    /// check ([`General3::check`]) allows it with its three other faces live; true when done.
    /// Cheap exact rejections first (side of f, emptiness, new faces against the boundary), so
    /// that the triangles are added only for a tetrahedron that will be removed.
    fn pierce(&mut self, f: [u32; 3], v: u32) -> bool {
        let [a, b, c] = f;
        if f.contains(&v) || self.on_boundary(v) || !self.is_bface(f) {
            return false;
        }
        if !self.keep.is_empty() && self.keep.contains(&sorted3(f)) {
            return false;
        }
        if orient3d(self.pt(a), self.pt(b), self.pt(c), self.pt(v)) <= 0.0 {
            return false; // v not on the inner side of f
        }
        if !self.empty([a, b, c, v]) {
            return false;
        }
        // the new faces (inward faces of the tetrahedron, outward faces of the object after)
        let nf = [[b, v, a], [c, v, b], [a, v, c]];
        if nf.iter().any(|&t| self.hits_boundary(t, &[f])) {
            return false;
        }
        let added: Vec<[u32; 3]> = nf.iter().copied().filter(|&t| self.add_tri(t)).collect();
        match self.check(f, v) {
            Some((_, bf, nf)) => {
                self.added += added.len();
                self.remove(f, v, &bf, &nf);
                true
            }
            None => {
                for t in added {
                    if let Some(i) = self.id_of(sorted3(t)) {
                        self.kill(i);
                    }
                }
                false
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// A closed surface sample (sphere, spacing ≈ 2e-4) with tight clusters of points
    /// (≈ 1e-5 apart) just inside it, and an engine whose only live triangles are the hull's:
    /// nothing is removable, so the engine alone leaves every cluster point off the boundary
    /// (the old behaviour after a lock); `insert_left_out` puts all of them on a closed
    /// genus-0 surface without self-intersections.
    #[test]
    fn clusters_inside_a_locked_surface_are_put_on_it() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(17);
        let r = 2e-4 * (3000.0f64 / (4.0 * std::f64::consts::PI)).sqrt();
        let dir = |rng: &mut rand_chacha::ChaCha8Rng| {
            let v: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
            let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-3);
            v.map(|x| x / n)
        };
        let mut pts: Vec<crate::geom::Point3> = (0..3000)
            .map(|_| {
                let u = dir(&mut rng);
                crate::geom::Point3::new(r * u[0], r * u[1], r * u[2])
            })
            .collect();
        for _ in 0..6 {
            let u = dir(&mut rng);
            for _ in 0..5 {
                let q: [f64; 3] =
                    std::array::from_fn(|i| (r - 3e-5) * u[i] + rng.gen_range(-1e-5..1e-5));
                pts.push(crate::geom::Point3::new(q[0], q[1], q[2]));
            }
        }
        let d = crate::delaunay::d3::triangulate(&pts).unwrap();
        let pos: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
        let mut g = General3::new(&pos, &d.hull, &[], &[]);
        g.run();
        let off = pos.len() - g.boundary_vertices;
        assert!(off >= 30, "{off} off the boundary");
        assert_eq!(g.insert_left_out(), off);
        assert!(g.done());
        let b = g.boundary();
        let mesh = crate::mesh::TriMesh::new(d.points.clone(), b.clone());
        let topo = crate::mesh::topology::analyze(&mesh);
        assert!(topo.is_closed() && topo.manifold && topo.parts.len() == 1);
        assert_eq!(topo.genus(), Some(0));
        assert!(crate::mesh::validity::self_intersections(&pos, &b, 1).is_empty());
        let mut on = vec![false; pos.len()];
        for t in &b {
            for &v in t {
                on[v as usize] = true;
            }
        }
        assert!(on.iter().all(|&x| x));
    }
}
