//! The external contour of a coloured tetrahedrization (Dorgerloh et al., §3.7): the closed
//! boundary surfaces of the black components that are not enclosed by another, as triangles.
//!
//! The steps are those of the planar algorithm with tetrahedra for triangles: the dual graph
//! joins tetrahedra that share a face (at most four neighbours), `extend` joins `v_ext` to the
//! tetrahedra with a face on the hull, `hollow_out` deletes the white tetrahedra reachable from
//! the exterior through shared faces and marks the black ones it reaches, and the black
//! components are the connected parts of what remains (black tetrahedra and the white ones they
//! enclose). The external surface of a component is the set of faces of its marked tetrahedra
//! whose other side is the exterior or a deleted white tetrahedron (the 3D form of
//! `contour_of_component`). Each face is oriented outwards (counter-clockwise seen from the white
//! side), so each component's faces form a closed oriented surface: every directed edge a→b is
//! matched by b→a. The surface may be non-manifold where a component touches itself along an
//! edge or at a vertex. O(n) time and memory for n tetrahedra.
//!
//! Preconditions: the tetrahedra form a tetrahedrization (no overlaps; each face shared by at most
//! two); either orientation is accepted, zero-volume tetrahedra are refused.

use super::dual::{check_indices, check_neighbors, facet, simplex_neighbors, Dual, Valid};
use super::ContourError;
use crate::geom::{orient3d, Point3};
use crate::mesh::{Property, ScalarKind, TriMesh};
use crate::util::NONE;
use crate::Result;
use std::borrow::Cow;

/// The external boundary surfaces of the black components of a coloured tetrahedrization.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Surface3 {
    /// Outward-oriented boundary triangles (vertex indices of the tetrahedrization).
    pub triangles: Vec<[u32; 3]>,
    /// Black component of each triangle (0-based, consecutive).
    pub component: Vec<u32>,
    /// Number of black components.
    pub components: usize,
    /// Number of black tetrahedra.
    pub black: usize,
    /// Number of tetrahedra.
    pub tetrahedra: usize,
}

impl Surface3 {
    /// The surface as a triangle mesh over the vertices it uses, with a face property
    /// `component`.
    pub fn to_trimesh(&self, points: &[Point3]) -> TriMesh {
        let mut map = vec![NONE; points.len()];
        let mut positions = Vec::new();
        let triangles = self
            .triangles
            .iter()
            .map(|t| {
                t.map(|v| {
                    if map[v as usize] == NONE {
                        map[v as usize] = positions.len() as u32;
                        positions.push(points[v as usize]);
                    }
                    map[v as usize]
                })
            })
            .collect();
        let mut m = TriMesh::new(positions, triangles);
        m.face_props.push(Property {
            name: "component".into(),
            kind: ScalarKind::U32,
            values: self.component.iter().map(|&c| c as f64).collect(),
        });
        m
    }
}

/// The external surface of a coloured tetrahedrization; `black[t]` is the colour of tetrahedron t.
///
/// ```
/// use morpho::contour::external_surface;
/// use morpho::geom::Point3;
/// let p = [
///     Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0),
///     Point3::new(0.0, 1.0, 0.0), Point3::new(0.0, 0.0, 1.0),
/// ];
/// let s = external_surface(&[[0, 1, 2, 3]], &p, &[true]).unwrap();
/// assert_eq!((s.triangles.len(), s.components), (4, 1));
/// // outward oriented: the enclosed volume is positive
/// assert!((s.to_trimesh(&p).signed_volume() - 1.0 / 6.0).abs() < 1e-12);
/// ```
pub fn external_surface(
    tets: &[[u32; 4]],
    points: &[Point3],
    black: &[bool],
) -> Result<Surface3, ContourError> {
    external_surface_with(tets, None, points, black)
}

/// [`external_surface`] with a given neighbour array (`neighbors[t][i]` across the face opposite
/// corner i, [`NONE`] on the hull; computed in O(n) when `None`).
pub fn external_surface_with(
    tets: &[[u32; 4]],
    neighbors: Option<&[[u32; 4]]>,
    points: &[Point3],
    black: &[bool],
) -> Result<Surface3, ContourError> {
    external_surface_impl(tets, neighbors, points, black, None)
}

/// [`external_surface_with`] on a tetrahedrization `valid` vouches for (no re-validation).
pub(crate) fn external_surface_valid(
    tets: &[[u32; 4]],
    neighbors: &[[u32; 4]],
    points: &[Point3],
    black: &[bool],
    valid: Valid,
) -> Result<Surface3, ContourError> {
    external_surface_impl(tets, Some(neighbors), points, black, Some(valid))
}

fn external_surface_impl(
    tets: &[[u32; 4]],
    neighbors: Option<&[[u32; 4]]>,
    points: &[Point3],
    black: &[bool],
    valid: Option<Valid>,
) -> Result<Surface3, ContourError> {
    if black.len() != tets.len() {
        return Err(ContourError::ColourCount {
            colours: black.len(),
            simplices: tets.len(),
            kind: "tetrahedra",
        });
    }
    if let (Some(_), Some(nb)) = (valid, neighbors) {
        return Ok(surface_of(tets, nb, black));
    }
    check_indices(tets, points.len())?;
    if let Some(i) = points
        .iter()
        .position(|p| !(p.x.is_finite() && p.y.is_finite() && p.z.is_finite()))
    {
        return Err(ContourError::NonFinitePoint { index: i });
    }
    let mut flip = Vec::new();
    for (t, &[a, b, c, d]) in tets.iter().enumerate() {
        let p = |v: u32| &points[v as usize];
        let o = orient3d(p(a), p(b), p(c), p(d));
        if o == 0.0 {
            return Err(ContourError::ZeroVolume { tetrahedron: t });
        }
        if o < 0.0 {
            flip.push(t);
        }
    }
    let tets: Cow<[[u32; 4]]> = if flip.is_empty() {
        Cow::Borrowed(tets)
    } else {
        let mut v = tets.to_vec();
        for &t in &flip {
            v[t].swap(2, 3);
        }
        Cow::Owned(v)
    };
    let nb: Cow<[[u32; 4]]> = match neighbors {
        Some(n) => {
            let mut n: Cow<[[u32; 4]]> = Cow::Borrowed(n);
            if !flip.is_empty() && n.len() == tets.len() {
                let v = n.to_mut();
                for &t in &flip {
                    v[t].swap(2, 3);
                }
            }
            check_neighbors(&tets, &n)?;
            n
        }
        None => Cow::Owned(simplex_neighbors(&tets, points.len())?),
    };
    Ok(surface_of(&tets, &nb, black))
}

/// §3.1–§3.4 and the faces of the marked tetrahedra on positively oriented tetrahedra with
/// their neighbours.
fn surface_of(tets: &[[u32; 4]], nb: &[[u32; 4]], black: &[bool]) -> Surface3 {
    let mut g = Dual::<4>::run(nb, black);
    let comps = g.marked_components();
    // The component of each marked tetrahedron (the only ones read below); the others keep the
    // zero of a fresh allocation, whose pages are not touched.
    let mut comp = vec![0u32; tets.len()];
    for c in 0..comps.len() {
        for &u in comps.group(c) {
            comp[u as usize] = c as u32;
        }
    }
    let mut out = Surface3 {
        black: black.iter().filter(|&&b| b).count(),
        tetrahedra: tets.len(),
        components: comps.len(),
        ..Default::default()
    };
    for (u, t) in tets.iter().enumerate() {
        if !g.marked(u) {
            continue;
        }
        for k in 0..4 {
            if g.is_contour_facet(u, k) {
                out.triangles.push(facet(t, k));
                out.component.push(comp[u]);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn facets_are_outward() {
        let p = [
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(0.0, 1.0, 0.0),
            Point3::new(0.0, 0.0, 1.0),
        ];
        let t = [0u32, 1, 2, 3];
        let t = if orient3d(&p[0], &p[1], &p[2], &p[3]) > 0.0 {
            t
        } else {
            [0, 1, 3, 2]
        };
        for k in 0..4 {
            let f = facet(&t, k);
            let o = orient3d(
                &p[f[0] as usize],
                &p[f[1] as usize],
                &p[f[2] as usize],
                &p[t[k] as usize],
            );
            assert!(o > 0.0, "facet {k} not outward");
        }
        let s = external_surface(&[[0, 1, 2, 3]], &p, &[true]).unwrap();
        assert_eq!(s.triangles.len(), 4);
        assert_eq!(s.components, 1);
        let m = s.to_trimesh(&p);
        assert!(m.signed_volume() > 0.0);
        let w = external_surface(&[[0, 1, 2, 3]], &p, &[false]).unwrap();
        assert!(w.triangles.is_empty());
        assert!(external_surface(&[[0, 1, 2, 3]], &p, &[]).is_err());
    }
}
