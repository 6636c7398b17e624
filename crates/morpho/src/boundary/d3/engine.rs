//! The 3D boundary engine state [`Engine3`]: the Delaunay tetrahedralization of the (scaled)
//! points and the keep triangles, the constriction steps of [`super::boundary_3d`] (Veltkamp
//! 1992, §5.3 Delaunay constriction, §5.4 fallback, §5.7 constraints, §4.3.4 skeleton) and the
//! step that turns a constricted surface into a checked [`Boundary3`] ([`Engine3::finish`]).
//!
//! The steps, in the order [`super::boundary_3d`] calls them:
//! 1. [`Engine3::new`]: the tetrahedralization (refused when it has no tetrahedron);
//! 2. [`Engine3::set_keep`]: keep triangles checked and mapped to vertices ([`super::keep`]);
//! 3. one constriction: [`Engine3::skeleton`], [`Engine3::gamma_from_hull`] (c < 0),
//!    [`Engine3::keep_from_hull`] (keep triangles that are not Delaunay faces) or
//!    [`Engine3::delaunay_constriction`] (continued by adaptive augmentation when it locks,
//!    [`Engine3::augment_after_lock`] in [`super::augment`]);
//! 4. [`Engine3::finish`]: topology, exact self-intersections, points left out, interior,
//!    missing keep triangles, volume — all in input indices.

use super::augment::{augment_until_done_3d, BEYOND_ALL_MAX};

/// The most points the whole γ-graph of [`Engine3::gamma_from_hull`] (inputs up to
/// [`BEYOND_ALL_MAX`] points) may add to its triples' intervals before the local path takes
/// over: 10⁷, about 2 s of one core on nearly cospherical points, where every triple scans
/// every point (issue 17 item 8; generic inputs of that size stay far below it).
pub(super) const WHOLE_BUDGET: u64 = 10_000_000;
use super::constrict::{constrict_3d_with, Until};
use super::general::General3;
use super::keep::{has_non_delaunay_keep, keep_missing_v, keep_vertices};
use super::Boundary3;
use crate::boundary::indicator::Key;
use crate::boundary::voronoi_skeleton3;
use crate::boundary::BoundaryError;
use crate::delaunay::d3::{Delaunay3, FACE_OF};
use crate::geom::Point3;
use crate::mesh::validity;
use crate::util::NONE;

type Result<T> = std::result::Result<T, BoundaryError>;

/// What a constriction step produced, before the checks of [`Engine3::finish`] (vertex
/// indices).
#[derive(Clone)]
pub(super) struct Outcome3 {
    /// The boundary triangles, oriented outward.
    pub(super) triangles: Vec<[u32; 3]>,
    /// For each triangle, whether the engine knows it to be a face of the Delaunay
    /// tetrahedralization (`None`: not known, [`Engine3::finish`] looks it up).
    pub(super) delaunay_faces: Option<Vec<bool>>,
    /// The live tetrahedra when the result is a set of Delaunay tetrahedra (`None` after the
    /// general engine, whose tetrahedra are implicit).
    pub(super) alive: Option<Vec<bool>>,
    pub(super) c_used: f64,
    pub(super) iterations: usize,
    pub(super) added: usize,
    pub(super) skeleton_length: Option<f64>,
}

impl Outcome3 {
    /// The outcome of the general engine `g` after it ran with c down to `c_used`, after
    /// `before` removals of an earlier constriction.
    pub(super) fn general(g: &General3<'_>, c_used: f64, before: usize) -> Self {
        let (triangles, delaunay_faces) = g.boundary_with_delaunay_flags();
        Outcome3 {
            triangles,
            delaunay_faces,
            alive: None,
            c_used,
            iterations: before + g.iterations,
            added: g.added,
            skeleton_length: None,
        }
    }
}

/// The state of one [`super::boundary_3d`] run (see the module documentation).
pub(super) struct Engine3 {
    pub(super) d: Delaunay3,
    /// The vertices' coordinates.
    pub(super) pos: Vec<[f64; 3]>,
    /// The keep triangles as given (input indices).
    pub(super) keep: Vec<[u32; 3]>,
    /// The keep triangles in vertex indices.
    pub(super) keep_v: Vec<[u32; 3]>,
}

impl Engine3 {
    /// Step 1: the Delaunay tetrahedralization; an error when it has no tetrahedron (fewer
    /// than four points, or all coplanar).
    pub(super) fn new(points: &[Point3]) -> Result<Self> {
        let d = crate::delaunay::d3::triangulate(points).map_err(BoundaryError::from)?;
        if d.tets.is_empty() {
            return Err(BoundaryError::NoSurface {
                reason: d
                    .degenerate
                    .as_deref()
                    .unwrap_or("degenerate input")
                    .to_string(),
            });
        }
        let pos = d.points.iter().map(|q| [q.x, q.y, q.z]).collect();
        Ok(Engine3 {
            d,
            pos,
            keep: Vec::new(),
            keep_v: Vec::new(),
        })
    }

    /// Step 2: the keep triangles (input indices), checked ([`keep_vertices`]).
    pub(super) fn set_keep(&mut self, keep: &[[u32; 3]]) -> Result<()> {
        self.keep_v = keep_vertices(&self.d, &self.pos, keep)?;
        self.keep = keep.to_vec();
        Ok(())
    }

    /// Step 3, shortest Voronoi skeleton (V §4.3.4, [`voronoi_skeleton3`]).
    pub(super) fn skeleton(&self, max_seeds: usize) -> Outcome3 {
        let sk = voronoi_skeleton3::shortest_skeleton_3d(&self.d, max_seeds);
        Outcome3 {
            triangles: sk.triangles,
            delaunay_faces: None,
            alive: Some(sk.alive),
            c_used: 0.0,
            iterations: sk.iterations,
            added: 0,
            skeleton_length: Some(sk.length),
        }
    }

    /// Step 3, γ(\[-1,1\],\[c,1\]) with c < 0 constricted from the convex hull: the whole graph up
    /// to [`BEYOND_ALL_MAX`] vertices, the Delaunay triangles plus the local γ-triangles above
    /// (without the empty triangles of the coplanar hull facets, which change no removal:
    /// [`super::removal::FROM_HULL_TRIPLES`]).
    pub(super) fn gamma_from_hull(&self, c: f64) -> Outcome3 {
        let d = &self.d;
        let small = d.points.len() <= BEYOND_ALL_MAX;
        // (the whole γ needs every candidate; the local path leaves out the facet triangles,
        // which never take part in a removal: `removal::FROM_HULL_TRIPLES`)
        let which = if small {
            crate::graphs::fast::GroupTriples::All
        } else {
            super::removal::FROM_HULL_TRIPLES
        };
        let cand = crate::graphs::fast::candidates_3d_with(d, which).0;
        let mut all = cand.triangles.clone();
        // at most C(BEYOND_ALL_MAX, 3) ≈ 1.06·10⁷ candidate triples, but on (nearly)
        // cospherical points each is decided by a scan of every point (minutes at 300 points):
        // past `WHOLE_BUDGET` points added (`GraphError::TooMuchWork`) the local path below
        // takes over, as for larger inputs
        let whole = small
            .then(|| {
                let limit = crate::graphs::triple_limit().min(WHOLE_BUDGET);
                crate::graphs::beyond3::beyond_dt_3d(d, &cand, c, limit).ok()
            })
            .flatten();
        let local = whole.is_none();
        if let Some(beyond) = whole {
            all.extend(beyond.0);
        }
        let mut g = General3::new(&self.pos, &d.hull, &all, &self.keep_v);
        if local {
            let extra = g.local_gamma(c, 16);
            g.augment(&extra);
        }
        g.run();
        Outcome3::general(&g, c, 0)
    }

    /// Step 3 with keep triangles that are not all Delaunay faces (V §5.7): they are added to
    /// the Delaunay triangles and the general engine constricts from the hull (with adaptive
    /// augmentation unless `fixed_c`).
    pub(super) fn keep_from_hull(&self, fixed_c: Option<f64>) -> Outcome3 {
        let all = crate::graphs::fast::candidates_3d(&self.d).triangles;
        let mut g = General3::new(&self.pos, &self.d.hull, &all, &self.keep_v);
        let c = match fixed_c {
            Some(c) => {
                g.run();
                c
            }
            None => augment_until_done_3d(&mut g, 0.0),
        };
        Outcome3::general(&g, c, 0)
    }

    /// Step 3, the Delaunay constriction (V §5.3) with `key`; when it locks with points (or
    /// keep triangles) off the boundary and `augment`, continued by adaptive augmentation
    /// ([`Engine3::augment_after_lock`]).
    pub(super) fn delaunay_constriction(&self, key: Key, until: Until, augment: bool) -> Outcome3 {
        let st = constrict_3d_with(&self.d, until, &self.keep_v, key);
        let done = st.boundary_vertices >= self.d.points.len()
            && keep_missing_v(&st.triangles, &self.keep_v).is_empty();
        if done || !augment {
            return Outcome3 {
                triangles: st.triangles,
                delaunay_faces: None,
                alive: Some(st.alive),
                c_used: 0.0,
                iterations: st.iterations,
                added: 0,
                skeleton_length: None,
            };
        }
        self.augment_after_lock(&st)
    }

    /// Every face of the live tetrahedra: each interior face once (from the smaller
    /// tetrahedron), the faces on dead or absent neighbours always; sorted vertex triples.
    pub(super) fn faces_of(&self, alive: &[bool]) -> Vec<[u32; 3]> {
        let d = &self.d;
        let mut out = Vec::new();
        for (t, tet) in d.tets.iter().enumerate() {
            if alive[t] {
                for (fi, f) in FACE_OF.iter().enumerate() {
                    let n = d.neighbors[t][fi];
                    let mut s = [tet[f[0]], tet[f[1]], tet[f[2]]];
                    s.sort_unstable();
                    if n == NONE || !alive[n as usize] || (t as u32) < n {
                        out.push(s);
                    }
                }
            }
        }
        out
    }

    /// Step 4: the checked result in input indices. The surface is checked with
    /// [`crate::mesh::topology::analyze`] and the exact self-intersection test
    /// ([`crate::mesh::validity::self_intersections_trusting`]): faces of the Delaunay tetrahedralization
    /// meet only in common faces (a simplicial complex), so only pairs with a triangle that is
    /// not one of its faces can intersect.
    pub(super) fn finish(&self, o: Outcome3) -> Boundary3 {
        let d = &self.d;
        let tris = o.triangles;
        let mesh = crate::mesh::TriMesh::new(d.points.clone(), tris.clone());
        let topo = crate::mesh::topology::analyze(&mesh);
        // the Delaunay faces among the triangles: as the engine knows them, or looked up (the
        // check then skips only pairs of them, which meet properly in any case)
        let delaunay_face = match o.delaunay_faces {
            Some(f) if f.len() == tris.len() => f,
            _ => validity::faces_of_tetrahedra(&d.tets, &tris),
        };
        let intersections =
            validity::self_intersections_trusting(&self.pos, &tris, &delaunay_face, 10);
        let mut on = vec![false; d.points.len()];
        for t in &tris {
            for &v in t {
                on[v as usize] = true;
            }
        }
        let inp = |v: u32| d.input_of_vertex[v as usize];
        let left_out: Vec<u32> = (0..d.vertex_of_input.len())
            .filter(|&i| !on[d.vertex_of_input[i] as usize])
            .map(|i| i as u32)
            .collect();
        let mut interior = Vec::new();
        if let Some(alive) = &o.alive {
            for (t, tet) in d.tets.iter().enumerate() {
                if alive[t] {
                    interior.push(tet.map(inp));
                }
            }
        }
        let missing = keep_missing_v(&tris, &self.keep_v);
        Boundary3 {
            triangles: tris.iter().map(|t| t.map(inp)).collect(),
            all_on_boundary: left_out.is_empty(),
            left_out,
            iterations: o.iterations,
            c_used: o.c_used,
            added_triangles: o.added,
            closed_manifold: topo.is_closed() && topo.manifold && topo.parts.len() == 1,
            genus: topo.genus(),
            intersections,
            keep_missing: self
                .keep
                .iter()
                .zip(&self.keep_v)
                .filter(|(_, v)| missing.contains(v))
                .map(|(k, _)| *k)
                .collect(),
            interior,
            volume: mesh.signed_volume(),
            skeleton_length: o.skeleton_length,
        }
    }

    /// Some keep triangle is not a face of the Delaunay tetrahedralization.
    pub(super) fn non_delaunay_keep(&self) -> bool {
        has_non_delaunay_keep(&self.d, &self.keep_v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::boundary::d3::test_sets;
    use rand::SeedableRng;

    /// The Delaunay-face flags the general engine hands to the final check after a locked
    /// Delaunay constriction are true (each flagged triangle is a face of a Delaunay
    /// tetrahedron, by the lookup the check made before), and the checked result is the same
    /// as with the lookup.
    #[test]
    fn engine_delaunay_face_flags_are_true_and_check_alike() {
        let mut locked = 0;
        // clustered cube points on which the Delaunay constriction locks (the seeds of the
        // integration test `locked_delaunay_constriction_falls_back_and_stays_valid`, and of
        // `general::tests::sweeps_that_skip_unchanged_faces_constrict_identically`)
        for seed in [1647u64, 1755, 1, 2, 3, 4] {
            let pts = super::super::test_sets::clustered_cube(seed);
            let e = Engine3::new(&pts).unwrap();
            let o = e.delaunay_constriction(Key::Gamma, Until::All, true);
            let Some(flags) = o.delaunay_faces.clone() else {
                continue;
            };
            locked += 1;
            let oracle = validity::faces_of_tetrahedra(&e.d.tets, &o.triangles);
            assert_eq!(flags.len(), oracle.len());
            assert!(
                flags.iter().zip(&oracle).all(|(&f, &t)| !f || t),
                "seed {seed}"
            );
            // (the triangles the engine added are the only ones not flagged)
            assert!(flags.iter().filter(|&&f| f).count() + o.added >= oracle.len());
            let mut looked_up = o.clone();
            looked_up.delaunay_faces = None;
            let (a, b) = (e.finish(o), e.finish(looked_up));
            assert!(
                a.closed_manifold && a.intersections.is_empty(),
                "seed {seed}"
            );
            assert_eq!(a.genus, Some(0));
            assert_eq!(a.triangles, b.triangles);
            assert_eq!(a.left_out, b.left_out);
            assert_eq!(a.intersections, b.intersections);
            assert_eq!(a.volume.to_bits(), b.volume.to_bits());
        }
        assert!(locked >= 2, "{locked} sets locked");
    }

    /// A corrupted general-engine result is rejected by the final check with the engine's
    /// flags: a boundary face listed in both orientations (the copy is not trusted: the pair
    /// intersects, the surface is not a 2-manifold), and a face missing (not closed).
    #[test]
    fn corrupted_engine_results_are_rejected() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        let pts = test_sets::cube(&mut rng, 200);
        let e = Engine3::new(&pts).unwrap();
        let hull = e.d.hull.clone();
        // sound: the hull itself (every point is not on it, but it is a closed genus-0 surface)
        let mut g = General3::new(&e.pos, &hull, &[], &[]);
        g.trust_initial_as_delaunay();
        let ok = e.finish(Outcome3::general(&g, 0.0, 0));
        assert!(ok.closed_manifold && ok.intersections.is_empty(), "hull");
        assert!(!ok.all_on_boundary && !ok.left_out.is_empty());
        // a face in both orientations
        let f = hull[3];
        g.set_boundary([f[0], f[2], f[1]], true);
        let o = Outcome3::general(&g, 0.0, 0);
        let flags = o.delaunay_faces.clone().unwrap();
        assert_eq!(
            flags.iter().filter(|&&x| !x).count(),
            1,
            "one copy untrusted"
        );
        let bad = e.finish(o);
        assert!(!bad.closed_manifold, "doubled face");
        assert!(
            !bad.intersections.is_empty(),
            "doubled face: the copies meet"
        );
        // a face missing
        let mut g = General3::new(&e.pos, &hull, &[], &[]);
        g.trust_initial_as_delaunay();
        g.set_boundary(hull[7], false);
        let bad = e.finish(Outcome3::general(&g, 0.0, 0));
        assert!(!bad.closed_manifold, "missing face");
    }
}
