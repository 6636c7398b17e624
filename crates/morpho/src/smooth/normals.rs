//! Vertex normals that "see" every incident triangle: the fold remedy of the three-split
//! (Veltkamp 1992, §9.6, the precondition after Step 5: where `f, g` have the wrong signs "the
//! normal at a vertex should be altered", with no rule given; NOTES B.1, B.5).
//!
//! Why (derived here, checked by the independent fold counter [`super::continuity`]). At the
//! end `M0` of a macro edge, `f0, g0` solve `(M1−M0) + f0(L0−M0) + g0(R0−M0) = 0` in the
//! tangent plane of `n`, where `L0−M0`, `R0−M0` are the bisectors of the two projected
//! triangles' angles at `M0` (Step 4: `W = (p300+p210+p201)/3`). The projection of a triangle
//! with face normal `n_f` onto the plane of `n` keeps its orientation iff `n·n_f > 0`. When both
//! triangles of the edge keep theirs, the two bisectors lie on either side of the projected
//! edge at angles below π/2 and the edge direction lies strictly inside their cone: `f0, g0 <
//! 0`, the orientation rule of B.1. A vertex normal with `n·n_f ≤ 0` for an incident face (a
//! sharp vertex: spot's horns, fandisk's corners; the area-weighted mean can fail there)
//! flips that projected triangle, and with it the signs: a fold.
//!
//! The remedy: at every vertex where `min_f n·n_f < margin` (default 0.05, a ~87° limit), the
//! normal is replaced by the direction that **maximises `min_f n·n_f`** over the incident unit
//! face normals (the centre of the smallest spherical cap holding them). The optimum is
//! fixed by one, two or three of them (the cap's boundary points), so the candidates are every
//! `n_f`, every normalised `n_i + n_j` and both unit vectors equidistant from three,
//! `±(n_j−n_i)×(n_k−n_i)`; the best feasible candidate wins. Such a direction with a positive
//! minimum exists iff the face normals lie in an open hemisphere; where they do not (a vertex
//! of a needle-thin fin), the best candidate still reduces the worst flip and the vertex is
//! counted in [`AdjustedNormals::infeasible`]. The surface then interpolates the adjusted
//! normals, which are reported ([`AdjustedNormals::adjusted`]). O(V · valence³) at adjusted
//! vertices (valence ≤ 24 is searched in full; above, the pairs only), O(T) otherwise.

use crate::geom::{vec, Vector3};
use crate::mesh::TriMesh;

type P3 = [f64; 3];

/// Vertex normals after the visibility adjustment.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct AdjustedNormals {
    /// Unit normals (the input's where no adjustment was needed).
    pub normals: Vec<Vector3>,
    /// Vertices whose normal was replaced.
    pub adjusted: Vec<u32>,
    /// Adjusted vertices whose best normal still has `min_f n·n_f ≤ 0` (no normal sees all
    /// their triangles).
    pub infeasible: Vec<u32>,
    /// Largest angle between an input normal and its replacement (radians).
    pub max_change_rad: f64,
}

fn unit(v: P3) -> Option<P3> {
    let l = vec::norm(v);
    (l > 0.0 && l.is_finite()).then(|| vec::scale(v, 1.0 / l))
}

fn min_dot(n: P3, faces: &[P3]) -> f64 {
    faces
        .iter()
        .map(|f| vec::dot(n, *f))
        .fold(f64::INFINITY, f64::min)
}

/// The unit direction maximising `min_f n·n_f` among the candidates of the module doc.
fn best_direction(faces: &[P3], start: P3) -> P3 {
    let mut best = (min_dot(start, faces), start);
    let mut consider = |c: P3| {
        if let Some(c) = unit(c) {
            let m = min_dot(c, faces);
            if m > best.0 {
                best = (m, c);
            }
        }
    };
    let k = faces.len();
    for i in 0..k {
        consider(faces[i]);
        for j in i + 1..k {
            consider(vec::add(faces[i], faces[j]));
            if k <= 24 {
                for l in j + 1..k {
                    let c = vec::cross(vec::sub(faces[j], faces[i]), vec::sub(faces[l], faces[i]));
                    consider(c);
                    consider(vec::scale(c, -1.0));
                }
            }
        }
    }
    best.1
}

/// `normals` adjusted so that each sees its incident triangles with `n·n_f ≥ margin` where
/// possible (module doc). `normals` must have one finite entry per vertex; zero ones and
/// degenerate triangles are left to the surface construction to refuse.
///
/// ```
/// use morpho::mesh::{generate, vertex_normals, NormalWeighting};
/// use morpho::smooth::visible_normals;
/// let m = generate::icosphere(1);
/// let n = vertex_normals(&m, NormalWeighting::Area);
/// let a = visible_normals(&m, &n, 0.05);
/// assert!(a.adjusted.is_empty()); // a convex mesh needs nothing
/// assert_eq!(a.normals, n);
/// ```
pub fn visible_normals(mesh: &TriMesh, normals: &[Vector3], margin: f64) -> AdjustedNormals {
    let nv = mesh.positions.len();
    let mut faces: Vec<Vec<P3>> = vec![Vec::new(); nv];
    for t in &mesh.triangles {
        if t.iter().any(|&v| v as usize >= nv) {
            continue;
        }
        let p = |k: usize| -> P3 { mesh.positions[t[k] as usize].into() };
        if let Some(f) = unit(vec::cross(vec::sub(p(1), p(0)), vec::sub(p(2), p(0)))) {
            for &v in t {
                faces[v as usize].push(f);
            }
        }
    }
    let mut out = AdjustedNormals {
        normals: normals.to_vec(),
        ..Default::default()
    };
    for (v, fs) in faces.iter().enumerate() {
        let Some(n) = normals.get(v).and_then(|n| unit([n.x, n.y, n.z])) else {
            continue;
        };
        if fs.is_empty() || min_dot(n, fs) >= margin {
            continue;
        }
        let b = best_direction(fs, n);
        if b == n {
            if min_dot(n, fs) <= 0.0 {
                out.infeasible.push(v as u32);
            }
            continue;
        }
        out.adjusted.push(v as u32);
        if min_dot(b, fs) <= 0.0 {
            out.infeasible.push(v as u32);
        }
        let ang = vec::norm(vec::cross(n, b)).atan2(vec::dot(n, b));
        out.max_change_rad = out.max_change_rad.max(ang);
        out.normals[v] = Vector3::new(b[0], b[1], b[2]);
    }
    out
}
