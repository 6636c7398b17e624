//! Re-triangulation of the platelet after a removal (Hamann 1991, §5.2, (5.40), Def. 5.15,
//! Fig. 5.6; notes D.3 step 6): the fan from the new point `p` to the ordered boundary vertex
//! set, improved by a Lawson-like loop that swaps the diagonal of two neighbouring new
//! triangles when
//! - their quadrilateral projected onto the removed triangle's plane is strictly convex
//!   (Def. 5.15, exact `orient2d` on the projected coordinates; for height fields also over
//!   the xy plane, so the projection stays fold-free),
//! - the new diagonal is not already an edge of the mesh (it would become non-manifold), and
//! - the smaller angle weight of the pair increases (so the minimum over the new triangles never
//!   decreases; each swap raises the sorted weight vector lexicographically, so the loop ends).
//!
//! Local indices: 0 is `p`, `1 + j` is ring vertex `j`. O(k²) per pass for k new triangles.

use super::weight::angle_weight;
use crate::geom::predicates::raw::orient2d;

/// The fan (5.40): `(p, y_j, y_{j+1})`, closing when `closed`.
pub(crate) fn fan(m: usize, closed: bool, out: &mut Vec<[usize; 3]>) {
    out.clear();
    let k = if closed { m } else { m - 1 };
    for j in 0..k {
        out.push([0, 1 + j, 1 + (j + 1) % m]);
    }
}

/// The corner of `t` after `x` and the one after that, if `t` contains `x`.
fn rotate_to(t: [usize; 3], x: usize) -> Option<[usize; 3]> {
    let i = t.iter().position(|&v| v == x)?;
    Some([t[i], t[(i + 1) % 3], t[(i + 2) % 3]])
}

/// Max-min angle weight swaps on `tris` (local indices into `p3` / `p2` / `xy`).
/// `p2`: coordinates in the removed triangle's plane; `xy`: the xy coordinates when the
/// projection over xy must stay fold-free; `edge_exists(a, b)` for two ring vertices.
pub(crate) fn improve(
    tris: &mut [[usize; 3]],
    p3: &[[f64; 3]],
    p2: &[[f64; 2]],
    xy: Option<&[[f64; 2]]>,
    mut edge_exists: impl FnMut(usize, usize) -> bool,
) -> usize {
    let sigma = |t: [usize; 3]| angle_weight(p3[t[0]], p3[t[1]], p3[t[2]]);
    let convex = |q: [usize; 4], c: &[[f64; 2]]| {
        (0..4).all(|i| orient2d(c[q[i]], c[q[(i + 1) % 4]], c[q[(i + 2) % 4]]) > 0.0)
    };
    let mut w: Vec<f64> = tris.iter().map(|&t| sigma(t)).collect();
    let mut swaps = 0;
    for _pass in 0..64 {
        let mut changed = false;
        for i in 0..tris.len() {
            for j in 0..tris.len() {
                if i == j {
                    continue;
                }
                // an edge x→y of tris[i] used as y→x by tris[j]
                for e in 0..3 {
                    let (x, y) = (tris[i][e], tris[i][(e + 1) % 3]);
                    let Some(tj) = rotate_to(tris[j], y) else {
                        continue;
                    };
                    if tj[1] != x {
                        continue;
                    }
                    let a = tris[i][(e + 2) % 3];
                    let b = tj[2];
                    let quad = [x, b, y, a];
                    if !convex(quad, p2) || xy.is_some_and(|c| !convex(quad, c)) {
                        continue;
                    }
                    let (n1, n2) = ([a, x, b], [b, y, a]);
                    let old = w[i].min(w[j]);
                    let (w1, w2) = (sigma(n1), sigma(n2));
                    let new = w1.min(w2);
                    if new.partial_cmp(&(old + 1e-12)) != Some(std::cmp::Ordering::Greater) {
                        continue;
                    }
                    if a != 0 && b != 0 && edge_exists(a, b) {
                        continue;
                    }
                    tris[i] = n1;
                    tris[j] = n2;
                    (w[i], w[j]) = (w1, w2);
                    swaps += 1;
                    changed = true;
                    break;
                }
            }
        }
        if !changed {
            break;
        }
    }
    swaps
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn swaps_never_lower_the_minimum_angle_weight() {
        // p near one side of a hexagon: the fan has skinny triangles
        let m = 6;
        let mut p3 = vec![[0.8, 0.0, 0.0]];
        for j in 0..m {
            let a = std::f64::consts::TAU * j as f64 / m as f64;
            p3.push([a.cos(), a.sin(), 0.0]);
        }
        let p2: Vec<[f64; 2]> = p3.iter().map(|p| [p[0], p[1]]).collect();
        let mut t = Vec::new();
        fan(m, true, &mut t);
        let min = |t: &[[usize; 3]]| {
            t.iter()
                .map(|t| angle_weight(p3[t[0]], p3[t[1]], p3[t[2]]))
                .fold(1.0f64, f64::min)
        };
        let before = min(&t);
        improve(&mut t, &p3, &p2, None, |_, _| false);
        assert!(min(&t) >= before);
        // still a triangulation of the hexagon: areas add up, all counter-clockwise
        let area: f64 = t
            .iter()
            .map(|t| orient2d(p2[t[0]], p2[t[1]], p2[t[2]]))
            .inspect(|&a| assert!(a > 0.0))
            .sum();
        assert!((area / 2.0 - 1.5 * 3f64.sqrt()).abs() < 1e-12);
    }
}
