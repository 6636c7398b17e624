//! Vertex normals of a triangle mesh with the three weightings of Veltkamp 1992, §9.4 (NOTES
//! B.3): with `c_t = (x1−x0)×(x2−x0)` per incident triangle (`|c_t|` = twice its area),
//! by area `n ∝ Σ c_t` (the thesis default), uniform `n ∝ Σ c_t/|c_t|`, by inverse area
//! `n ∝ Σ (c_t/|c_t|)/area_t`; normalised. O(triangles). The mesh should be consistently
//! oriented (counter-clockwise seen from outside gives outward normals). Triangles of zero
//! area add nothing; a vertex whose sum vanishes (or that no triangle uses) gets the zero
//! vector, which callers needing unit normals must refuse.

use super::TriMesh;
use crate::geom::{vec, Vector3};

/// The weighting of the incident triangles' normals (§9.4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum NormalWeighting {
    /// By triangle area (the thesis default; Sloan 1991 reports it most accurate).
    #[default]
    Area,
    /// Every incident triangle counts the same.
    Uniform,
    /// By inverse triangle area.
    InverseArea,
}

/// Unit vertex normals (zero where undefined, see the module doc).
///
/// ```
/// use morpho::mesh::{generate, vertex_normals, NormalWeighting};
/// let m = generate::tetrahedron();
/// let n = vertex_normals(&m, NormalWeighting::Area);
/// let p = m.positions[0].coords;
/// // outward: the normal points away from the centroid (the origin here)
/// assert!(n[0].dot(&p) > 0.0);
/// ```
pub fn vertex_normals(mesh: &TriMesh, weighting: NormalWeighting) -> Vec<Vector3> {
    let mut acc = vec![[0.0f64; 3]; mesh.positions.len()];
    let p = |i: u32| -> [f64; 3] { mesh.positions[i as usize].into() };
    for t in &mesh.triangles {
        if t.iter().any(|&i| i as usize >= acc.len()) {
            continue;
        }
        let c = vec::cross(vec::sub(p(t[1]), p(t[0])), vec::sub(p(t[2]), p(t[0])));
        let l = vec::norm(c);
        if !(l > 0.0 && l.is_finite()) {
            continue;
        }
        let w = match weighting {
            NormalWeighting::Area => 1.0,
            NormalWeighting::Uniform => 1.0 / l,
            NormalWeighting::InverseArea => 2.0 / (l * l),
        };
        for &i in t {
            acc[i as usize] = vec::add_scaled(acc[i as usize], w, c);
        }
    }
    acc.into_iter()
        .map(|a| {
            let l = vec::norm(a);
            if l > 0.0 && l.is_finite() {
                Vector3::new(a[0] / l, a[1] / l, a[2] / l)
            } else {
                Vector3::zeros()
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weightings_differ_only_by_the_weights() {
        // a vertex with two incident faces of different size: the weightings differ
        let m = crate::mesh::generate::cube();
        for w in [
            NormalWeighting::Area,
            NormalWeighting::Uniform,
            NormalWeighting::InverseArea,
        ] {
            let n = vertex_normals(&m, w);
            for (v, nv) in n.iter().enumerate() {
                assert!((nv.norm() - 1.0).abs() < 1e-12);
                // outward on the cube centred where its bbox centre is
                let c = m.bbox().center();
                let d = m.positions[v].coords - Vector3::new(c[0], c[1], c[2]);
                assert!(nv.dot(&d) > 0.0);
            }
        }
    }
}
