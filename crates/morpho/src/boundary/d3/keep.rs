//! Constrained constriction in 3D (Veltkamp 1992, §5.7): the checks of the keep triangles, V's
//! 3D rewiring in the general engine, and the keep triangles missing from a result.
//!
//! Keep triangles are live from the start (added to the graph like V's F) and never deleted: a
//! keep boundary face is never removable, and a tetrahedron whose interior a keep triangle
//! meets is not removed. V's 3D rewiring: when keep triangle x y m blocks a tetrahedron on
//! boundary face x y z, the triangles z x m and z y m are inserted (where they can be certified
//! inside, as for augmentation), so that x y z m becomes a boundary tetrahedron whose removal
//! brings x y m to the boundary. The constriction may still lock with a keep triangle off the
//! boundary (V: "a constrained constriction may get locked"); the caller reports it.

use super::general::*;
use crate::boundary::BoundaryError;
use crate::delaunay::d3::Delaunay3;
use crate::geom::intersect::degenerate_triangle;
use crate::mesh::validity;
use crate::util::sorted3;

impl General3<'_> {
    /// V §5.7 (3D, Fig. 5.12 right): keep triangle `kt` = x y m crosses a tetrahedron on
    /// boundary face f = x y z: insert z x m and z y m (where they lie inside, see
    /// [`General3::augment`]) so that f + m becomes a tetrahedron whose removal brings `kt` to
    /// the boundary. Returns whether a triangle was inserted.
    pub(super) fn rewire(&mut self, f: [u32; 3], kt: [u32; 3]) -> bool {
        let common: Vec<u32> = f.iter().copied().filter(|v| kt.contains(v)).collect();
        if common.len() != 2 {
            return false;
        }
        let (Some(&z), Some(&m)) = (
            f.iter().find(|v| !common.contains(v)),
            kt.iter().find(|v| !common.contains(v)),
        ) else {
            return false;
        };
        let mut any = false;
        for &x in &common {
            any |= self.try_insert([z, x, m]);
        }
        any
    }
}

/// The keep triangles (input indices) in vertex indices of `d`, checked: every index names a
/// point, the three corners are distinct points, the triangle is not degenerate, and no two
/// keep triangles intersect (exact, [`validity::self_intersections`]).
pub(super) fn keep_vertices(
    d: &Delaunay3,
    pos: &[[f64; 3]],
    keep: &[[u32; 3]],
) -> Result<Vec<[u32; 3]>, BoundaryError> {
    let mut keep_v = Vec::with_capacity(keep.len());
    let points = d.vertex_of_input.len();
    for (index, &triangle) in keep.iter().enumerate() {
        if triangle.iter().any(|&i| i as usize >= points) {
            return Err(BoundaryError::KeepTriangleOutOfRange {
                index,
                triangle,
                points,
            });
        }
        let v = triangle.map(|i| d.vertex_of_input[i as usize]);
        if v[0] == v[1] || v[1] == v[2] || v[0] == v[2] {
            return Err(BoundaryError::KeepTriangleDuplicate { index, triangle });
        }
        keep_v.push(v);
    }
    for (index, &vertices) in keep_v.iter().enumerate() {
        let q = vertices.map(|v| pos[v as usize]);
        if degenerate_triangle(q[0], q[1], q[2]) {
            return Err(BoundaryError::KeepTriangleDegenerate { index, vertices });
        }
    }
    if let Some(&(a, b)) = validity::self_intersections(pos, &keep_v, 1).first() {
        return Err(BoundaryError::KeepTrianglesIntersect {
            triangles: [a as usize, b as usize],
        });
    }
    Ok(keep_v)
}

/// Some keep triangle (vertex indices) is not a face of the Delaunay tetrahedralization `d`:
/// then the general engine constricts from the hull (the Delaunay constriction keeps only
/// Delaunay faces).
pub(super) fn has_non_delaunay_keep(d: &Delaunay3, keep_v: &[[u32; 3]]) -> bool {
    if keep_v.is_empty() {
        return false;
    }
    let faces: std::collections::HashSet<[u32; 3]> =
        d.triangles().iter().map(|f| sorted3(f.v)).collect();
    keep_v.iter().any(|k| !faces.contains(&sorted3(*k)))
}

/// The keep triangles (vertex indices) that are not among `tris`.
pub(super) fn keep_missing_v(tris: &[[u32; 3]], keep: &[[u32; 3]]) -> Vec<[u32; 3]> {
    if keep.is_empty() {
        return Vec::new();
    }
    let on: std::collections::HashSet<[u32; 3]> = tris.iter().map(|t| sorted3(*t)).collect();
    keep.iter()
        .filter(|v| !on.contains(&sorted3(**v)))
        .copied()
        .collect()
}
