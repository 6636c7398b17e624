//! Triangles that can never meet the open tetrahedron of a removal, for the crossing search of
//! the general 3D engine ([`super::general::General3`]; V §5.4: removing a tetrahedron Q
//! deletes every live triangle meeting the open Q): the triangles lying in a **supporting
//! plane** of the point set (every point on one closed side), proven so by exact `orient3d`.
//!
//! Why they never meet it: the corners of every Q are points of the set, so Q lies in the closed
//! side of such a plane H, and its open interior strictly inside; a triangle in H is then
//! separated from the open Q by H itself. The engine's conservative test
//! ([`super::removal::may_meet_open_tet`]) finds exactly that separation for a non-degenerate
//! triangle t in H (and a Q that is not flat, which a removal never is): sharing a vertex a
//! with Q, its first plane is the one through a and t's two other corners, which is H, with
//! t on it and Q's corners on one side; sharing none, the triangle's own plane H has all of
//! Q's corners on one side. So leaving these triangles out of the search changes no answer.
//!
//! Where they come from: the candidates of the constriction from the hull include every empty
//! triangle of each coplanar hull facet (`graphs::fast::GroupTriples::All`), Θ(g³) long
//! triangles for a facet of g points — most of all triangles on CAD models such as the fandisk,
//! where they made every removal test a fixed fraction of all triangles (issue 17 item 8).
//!
//! The planes are proposed by faces of the initial boundary surface — all of them from the
//! hull; on the local path only those whose corners are corners of the live triangles
//! (`general::support_faces`: fewer planes only means more triangles left to the exact
//! crossing test) —: coplanar edge-connected groups of those faces with at least four vertices, each verified against every point (largest groups
//! first, within a budget of O(n) orientation tests: an unverified group only costs time).
//! A triangle is in a verified plane when its three corners are vertices of that group and it
//! is not collinear (one `orient3d` against a point off the plane). O(B α(B) + budget) to
//! build for B boundary faces; O(1) expected per triangle.

use super::general::{dk, P};
use crate::geom::predicates::raw::{orient2d, orient3d};
use crate::util::IdMap;

/// Verified supporting planes of the point set and the vertices of the boundary groups lying
/// in them.
#[derive(Debug, Default)]
pub(super) struct Support {
    /// Per plane: three non-collinear vertices in it and one vertex off it.
    planes: Vec<[u32; 4]>,
    /// Vertex → the planes whose group it is a vertex of.
    of_vertex: IdMap<u32, smallvec::SmallVec<[u32; 2]>>,
}

/// Exact: are the three points collinear (all three coordinate projections are)?
fn collinear(a: P, b: P, c: P) -> bool {
    (0..3).all(|k| {
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        orient2d([a[i], a[j]], [b[i], b[j]], [c[i], c[j]]) == 0.0
    })
}

fn find(parent: &mut [u32], mut x: u32) -> u32 {
    while parent[x as usize] != x {
        let up = parent[parent[x as usize] as usize];
        parent[x as usize] = up;
        x = up;
    }
    x
}

impl Support {
    /// The supporting planes proposed by the faces of `boundary` (a closed surface, oriented
    /// faces) and verified against every point of `p`.
    pub(super) fn new(p: &[P], boundary: &[[u32; 3]]) -> Self {
        let mut s = Support::default();
        if boundary.len() < 2 || p.len() < 4 {
            return s;
        }
        let pt = |v: u32| p[v as usize];
        let valid = |f: &[u32; 3]| f.iter().all(|&v| (v as usize) < p.len());
        // directed edge → face; two faces across an edge join when coplanar
        let mut by_edge: IdMap<u64, u32> = IdMap::default();
        by_edge.reserve(3 * boundary.len());
        for (i, f) in boundary.iter().enumerate() {
            if valid(f) {
                for k in 0..3 {
                    by_edge.insert(dk(f[k], f[(k + 1) % 3]), i as u32);
                }
            }
        }
        // whether a face is not collinear, decided only for faces about to join (a collinear
        // face is coplanar with every neighbour and must join none): 0 unknown, 1 yes, 2 no
        let mut ok = vec![0u8; boundary.len()];
        let mut is_ok = |i: usize| {
            if ok[i] == 0 {
                let f = boundary[i];
                ok[i] = if collinear(pt(f[0]), pt(f[1]), pt(f[2])) {
                    2
                } else {
                    1
                };
            }
            ok[i] == 1
        };
        let mut parent: Vec<u32> = (0..boundary.len() as u32).collect();
        // faces that joined another: the only ones that can form a group of ≥ 4 vertices
        let mut joined = vec![false; boundary.len()];
        for (i, f) in boundary.iter().enumerate() {
            if !valid(f) {
                continue;
            }
            for k in 0..3 {
                let (a, b) = (f[k], f[(k + 1) % 3]);
                let Some(&j) = by_edge.get(&dk(b, a)) else {
                    continue;
                };
                if j as usize <= i {
                    continue;
                }
                let g = boundary[j as usize];
                let d = g.into_iter().find(|&v| v != a && v != b).unwrap_or(a);
                if orient3d(pt(f[0]), pt(f[1]), pt(f[2]), pt(d)) == 0.0
                    && is_ok(i)
                    && is_ok(j as usize)
                {
                    let (x, y) = (find(&mut parent, i as u32), find(&mut parent, j));
                    if x != y {
                        parent[x.max(y) as usize] = x.min(y);
                    }
                    joined[i] = true;
                    joined[j as usize] = true;
                }
            }
        }
        // groups: root → (first face, vertices)
        let mut groups: IdMap<u32, (u32, Vec<u32>)> = IdMap::default();
        for (i, f) in boundary.iter().enumerate() {
            if !joined[i] {
                continue;
            }
            let r = find(&mut parent, i as u32);
            let e = groups.entry(r).or_insert_with(|| (i as u32, Vec::new()));
            e.0 = e.0.min(i as u32);
            e.1.extend_from_slice(f);
        }
        let mut groups: Vec<(u32, Vec<u32>)> = groups
            .into_values()
            .map(|(f, mut vs)| {
                vs.sort_unstable();
                vs.dedup();
                (f, vs)
            })
            .filter(|(_, vs)| vs.len() >= 4)
            .collect();
        groups.sort_by(|a, b| b.1.len().cmp(&a.1.len()).then(a.0.cmp(&b.0)));
        // verification budget: O(n) orientation tests in all
        let mut budget = 16 * p.len() + (1 << 22);
        for (f, vs) in groups {
            if budget < p.len() {
                break;
            }
            budget -= p.len();
            let [a, b, c] = boundary[f as usize];
            let (pa, pb, pc) = (pt(a), pt(b), pt(c));
            let (mut pos, mut neg, mut far) = (false, false, None);
            for (v, &x) in p.iter().enumerate() {
                let o = orient3d(pa, pb, pc, x);
                if o > 0.0 {
                    pos = true;
                } else if o < 0.0 {
                    neg = true;
                } else {
                    continue;
                }
                if pos && neg {
                    break;
                }
                far.get_or_insert(v as u32);
            }
            let Some(far) = far else { continue };
            if pos && neg {
                continue;
            }
            let id = s.planes.len() as u32;
            s.planes.push([a, b, c, far]);
            for v in vs {
                s.of_vertex.entry(v).or_default().push(id);
            }
        }
        s
    }

    /// Number of verified planes (tests).
    #[cfg(test)]
    pub(super) fn len(&self) -> usize {
        self.planes.len()
    }

    /// Triangle `t` lies in a verified supporting plane and is not collinear: it never meets
    /// the open tetrahedron of a removal (see the module documentation).
    pub(super) fn holds(&self, p: &[P], t: [u32; 3]) -> bool {
        if self.planes.is_empty() {
            return false;
        }
        let (Some(la), Some(lb), Some(lc)) = (
            self.of_vertex.get(&t[0]),
            self.of_vertex.get(&t[1]),
            self.of_vertex.get(&t[2]),
        ) else {
            return false;
        };
        la.iter()
            .find(|id| lb.contains(id) && lc.contains(id))
            .is_some_and(|&id| {
                let far = self.planes[id as usize][3];
                let q = t.map(|v| p[v as usize]);
                orient3d(q[0], q[1], q[2], p[far as usize]) != 0.0
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// On the hull of points with coplanar facets (a lattice box and a cube with points on
    /// its faces): a triangle is held exactly when every point is on one closed side of its
    /// plane and it is not collinear (brute force over every point), for random triangles of
    /// facet vertices and of any vertices; every box face is found.
    #[test]
    fn holds_exactly_the_triangles_in_supporting_planes() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let mut cube = super::super::test_sets::cube(&mut rng, 300);
        for p in cube.iter_mut().step_by(2) {
            let k = rng.gen_range(0..3);
            p[k] = if rng.gen_bool(0.5) { 1.0 } else { -1.0 };
        }
        for (pts, planes) in [(super::super::test_sets::lattice(6, 5, 4), 6), (cube, 6)] {
            let d = crate::delaunay::d3::triangulate(&pts).unwrap();
            let pos: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
            let s = Support::new(&pos, &d.hull);
            assert_eq!(s.len(), planes);
            let hull_v: Vec<u32> = {
                let mut v: Vec<u32> = d.hull.iter().flatten().copied().collect();
                v.sort_unstable();
                v.dedup();
                v
            };
            let n = pos.len() as u32;
            let (mut held, mut not) = (0, 0);
            for k in 0..20000 {
                let t: [u32; 3] = if k % 2 == 0 {
                    std::array::from_fn(|_| hull_v[rng.gen_range(0..hull_v.len())])
                } else {
                    std::array::from_fn(|_| rng.gen_range(0..n))
                };
                let q = t.map(|v| pos[v as usize]);
                let sides: Vec<f64> = pos.iter().map(|&x| orient3d(q[0], q[1], q[2], x)).collect();
                let expect = !collinear(q[0], q[1], q[2])
                    && (sides.iter().all(|&o| o >= 0.0) || sides.iter().all(|&o| o <= 0.0));
                assert_eq!(s.holds(&pos, t), expect, "{t:?}");
                if expect {
                    held += 1;
                } else {
                    not += 1;
                }
            }
            assert!(held > 200 && not > 1000, "{held} {not}");
        }
        // no coplanar faces on points in general position, and a non-convex surface's
        // coplanar group is refused when points lie on both sides of its plane
        let pts = super::super::test_sets::cube(&mut rng, 200);
        let d = crate::delaunay::d3::triangulate(&pts).unwrap();
        let pos: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
        assert_eq!(Support::new(&pos, &d.hull).len(), 0);
        let lat = super::super::test_sets::lattice(4, 4, 2);
        let d = crate::delaunay::d3::triangulate(&lat).unwrap();
        let mut lp: Vec<P> = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
        assert_eq!(Support::new(&lp, &d.hull).len(), 6);
        lp.push([1.5, 1.5, 7.0]); // above the top facet: it no longer supports
        assert_eq!(Support::new(&lp, &d.hull).len(), 5);
    }
}
