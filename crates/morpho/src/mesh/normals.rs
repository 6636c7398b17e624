//! Vertex normals of a triangle mesh with the three weightings of Veltkamp 1992, §9.4
//! (notes B.3): for the incident triangles' cross products `c_t = (x1−x0)×(x2−x0)`
//! (`|c_t|` = twice the area),
//! 1. by area: `n ∝ Σ c_t` (the thesis's default),
//! 2. uniform: `n ∝ Σ c_t/|c_t|`,
//! 3. inverse area: `n ∝ Σ (c_t/|c_t|)/area_t`,
//!
//! normalised. The normals are oriented like the triangles (outward for a counter-clockwise,
//! outward-oriented mesh). O(V + T).
//!
//! A vertex in no triangle, or whose triangles all have zero area, or whose weighted sum
//! cancels, gets the zero vector (callers treat it as "no normal"). Zero-area triangles add
//! nothing under any weighting (their direction is undefined).

use super::TriMesh;
use crate::geom::{vec, Vector3};

/// How the incident triangles' normals are weighted in a vertex normal (V §9.4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum NormalWeighting {
    /// Weighted by triangle area (V §9.4 weighting 1; the default).
    #[default]
    Area,
    /// Every incident triangle counts once (V §9.4 weighting 2).
    Uniform,
    /// Weighted by the inverse of the triangle area (V §9.4 weighting 3).
    InverseArea,
}

/// Unit vertex normals of `mesh` under `weighting`; the zero vector where none is defined.
///
/// ```
/// use morpho::mesh::{generate, vertex_normals, NormalWeighting};
/// let m = generate::icosphere(2);
/// let n = vertex_normals(&m, NormalWeighting::Area);
/// let p = m.positions[0].coords.normalize();
/// assert!((n[0] - p).norm() < 1e-12); // outward on a regular icosphere
/// ```
pub fn vertex_normals(mesh: &TriMesh, weighting: NormalWeighting) -> Vec<Vector3> {
    let mut acc = vec![[0.0f64; 3]; mesh.positions.len()];
    for t in &mesh.triangles {
        let Some((w, ct)) = weighted_cross(mesh, t, weighting) else {
            continue;
        };
        for v in *t {
            let s = &mut acc[v as usize];
            *s = vec::add_scaled(*s, w, ct);
        }
    }
    acc.into_iter().map(unit_or_zero).collect()
}

/// Every triangle's weighted cross product `w_t c_t`, in parallel: what
/// [`vertex_normal_from`] sums. A zero-area or non-finite triangle (which [`vertex_normals`]
/// skips) gets `(−0, −0, −0)`: `x + (−0) = x` for every `x` (−0 included) in IEEE
/// round-to-nearest, so adding it is adding nothing, bit for bit, and the sums need no test
/// per triangle (a flat 24-byte row instead of a 32-byte `Option`: the normals read 25 % fewer
/// bytes). The products are rounded exactly as [`vertex_normals`] rounds them (`s + w·c` is
/// `s + (w·c)`: no fused multiply-add), so the sums are the same bits; each triangle's cross
/// product and length are computed once instead of once per corner.
/// The array asks for transparent huge pages before it is written
/// ([`crate::util::advise_huge_pages`]: 12 MB on the 257k-vertex skull, 6 page faults instead
/// of 3 000).
pub(crate) fn weighted_crosses(mesh: &TriMesh, weighting: NormalWeighting) -> Vec<[f64; 3]> {
    use rayon::prelude::*;
    let mut out = Vec::with_capacity(mesh.triangles.len());
    crate::util::advise_huge_pages(&mut out);
    out.par_extend(
        mesh.triangles
            .par_iter()
            .map(|t| match weighted_cross(mesh, t, weighting) {
                Some((w, ct)) => vec::scale(ct, w),
                None => [-0.0; 3],
            }),
    );
    out
}

/// The unit normal of one vertex from its incident triangles `tris` (indices into
/// `crosses`, from [`weighted_crosses`]): the same sums in the same order as
/// [`vertex_normals`] when `tris` is ascending, so the same bits (a skipped triangle's `−0`
/// changes no sum); for callers that need the normals one vertex at a time (in parallel,
/// without the whole array).
pub(crate) fn vertex_normal_from(crosses: &[[f64; 3]], tris: &[u32]) -> Vector3 {
    let mut s = [0.0f64; 3];
    for &t in tris {
        s = vec::add(s, crosses[t as usize]);
    }
    unit_or_zero(s)
}

/// The weight and cross product `c_t = (x1−x0)×(x2−x0)` of one triangle, `None` for a
/// zero-area (or non-finite) one.
#[inline]
fn weighted_cross(
    mesh: &TriMesh,
    &[a, b, c]: &[u32; 3],
    weighting: NormalWeighting,
) -> Option<(f64, [f64; 3])> {
    let p = |i: u32| -> [f64; 3] { mesh.positions[i as usize].into() };
    let (pa, pb, pc) = (p(a), p(b), p(c));
    let ct = vec::cross(vec::sub(pb, pa), vec::sub(pc, pa));
    // the test on |c|² decides as the test on |c| = √|c|² would (|c|² is NaN, +0, +∞ or
    // positive, and √ keeps each of these), without the square root the area weighting never
    // uses
    let len2 = vec::norm2(ct);
    if len2.is_nan() || len2 <= 0.0 || len2.is_infinite() {
        return None;
    }
    let w = match weighting {
        NormalWeighting::Area => 1.0,
        NormalWeighting::Uniform => 1.0 / len2.sqrt(),
        // (c/|c|)/area = 2c/|c|²
        NormalWeighting::InverseArea => {
            let len = len2.sqrt();
            2.0 / (len * len)
        }
    };
    Some((w, ct))
}

/// `s/|s|`, or the zero vector when `s` has no direction.
#[inline]
fn unit_or_zero(s: [f64; 3]) -> Vector3 {
    let l = vec::norm(s);
    if l > 0.0 && l.is_finite() {
        Vector3::from(vec::scale(s, 1.0 / l))
    } else {
        Vector3::zeros()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Point3;

    #[test]
    fn weightings_differ_and_orient_like_triangles() {
        // a fan around the origin with one large and one small triangle, tilted differently
        let pos = vec![
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(4.0, 0.0, 0.0),
            Point3::new(0.0, 4.0, 1.0),
            Point3::new(-0.1, 0.0, 0.1),
        ];
        let m = TriMesh::new(pos, vec![[0, 1, 2], [0, 2, 3]]);
        let a = vertex_normals(&m, NormalWeighting::Area)[0];
        let u = vertex_normals(&m, NormalWeighting::Uniform)[0];
        let i = vertex_normals(&m, NormalWeighting::InverseArea)[0];
        for n in [a, u, i] {
            assert!((n.norm() - 1.0).abs() < 1e-12);
            assert!(n.z > 0.0);
        }
        assert!((a - u).norm() > 1e-3 && (u - i).norm() > 1e-3);
        let mut f = m.clone();
        f.triangles.iter_mut().for_each(|t| t.swap(1, 2));
        assert!((vertex_normals(&f, NormalWeighting::Area)[0] + a).norm() < 1e-15);
    }

    #[test]
    fn isolated_and_degenerate_get_zero() {
        let pos = vec![
            Point3::origin(),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(2.0, 0.0, 0.0),
            Point3::new(5.0, 5.0, 5.0),
        ];
        let m = TriMesh::new(pos, vec![[0, 1, 2]]);
        for w in [
            NormalWeighting::Area,
            NormalWeighting::Uniform,
            NormalWeighting::InverseArea,
        ] {
            assert!(vertex_normals(&m, w).iter().all(|n| n.norm() == 0.0));
        }
    }
}
