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
//! The loop visits the pairs in a fixed order (passes over `i`, and for each `i` its
//! neighbours `j` in increasing order, the first improving swap taken) until a pass swaps
//! nothing. Two things make it cheap without changing a single decision:
//! - the neighbours of a triangle come from a table of directed edges (local vertex pair →
//!   triangle) instead of a scan over all triangles, while every directed edge has one owner
//!   (always for a fan; should a swap ever create a second owner, the loop falls back to the
//!   scan for the rest of the call);
//! - a pair found not to swap is remembered with the versions of its two triangles, and is
//!   not evaluated again until one of them changes (the decision depends on the two
//!   triangles alone, and is the same from either side): the last, swap-free pass and the
//!   second visit of every edge cost one comparison each.
//!
//! `tests::improve_equals_the_plain_loop` checks that the result equals the plain
//! all-pairs loop, triangle for triangle, on random fans (star-shaped, folded, open).
//!
//! Local indices: 0 is `p`, `1 + j` is ring vertex `j`. O(k) per pass and neighbour visit for
//! k new triangles (O(k²) per pass in the fallback).

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

/// Local vertex counts up to this use the directed-edge table (its size is the square).
const TABLE_MAX: usize = 128;
const FREE: u16 = u16::MAX;

/// Reusable buffers of [`improve`] (no allocation per call once grown).
#[derive(Default)]
pub(crate) struct Flips {
    w: Vec<f64>,
    /// Version of each triangle (changes with every swap it takes part in).
    ver: Vec<u32>,
    /// Per pair `(i, j)`, `i < j`: the versions at which it was last found not to swap.
    idle: Vec<(u32, u32)>,
    /// Directed edge `x → y` (index `x · nv + y`) → the triangle holding it; all [`FREE`]
    /// between calls.
    owner: Vec<u16>,
}

impl Flips {
    /// The angle weights of the triangles [`improve`] returned, in their order.
    pub fn weights(&self) -> &[f64] {
        &self.w
    }
}

/// Max-min angle weight swaps on `tris` (local indices into `p3` / `p2` / `xy`).
/// `p2`: coordinates in the removed triangle's plane; `xy`: the xy coordinates when the
/// projection over xy must stay fold-free; `edge_exists(a, b)` for two ring vertices.
/// Returns the number of swaps.
pub(crate) fn improve(
    tris: &mut [[usize; 3]],
    p3: &[[f64; 3]],
    p2: &[[f64; 2]],
    xy: Option<&[[f64; 2]]>,
    mut edge_exists: impl FnMut(usize, usize) -> bool,
    sc: &mut Flips,
) -> usize {
    let sigma = |t: [usize; 3]| angle_weight(p3[t[0]], p3[t[1]], p3[t[2]]);
    let convex = |q: [usize; 4], c: &[[f64; 2]]| {
        (0..4).all(|i| orient2d(c[q[i]], c[q[(i + 1) % 4]], c[q[(i + 2) % 4]]) > 0.0)
    };
    let n = tris.len();
    let nv = p3.len();
    sc.w.clear();
    sc.w.extend(tris.iter().map(|&t| sigma(t)));
    sc.ver.clear();
    sc.ver.resize(n, 0);
    sc.idle.clear();
    sc.idle.resize(n * n, (u32::MAX, u32::MAX));
    let mut clock = 0u32;
    // the directed-edge table, while every directed edge has one owner
    let mut table = nv <= TABLE_MAX && n < FREE as usize;
    if table {
        if sc.owner.len() < nv * nv {
            sc.owner.resize(nv * nv, FREE);
        }
        'fill: for (i, t) in tris.iter().enumerate() {
            for e in 0..3 {
                let k = t[e] * nv + t[(e + 1) % 3];
                if sc.owner[k] != FREE {
                    table = false;
                    break 'fill;
                }
                sc.owner[k] = i as u16;
            }
        }
        if !table {
            clear_table(&mut sc.owner, tris, nv);
        }
    }
    let mut swaps = 0;
    for _pass in 0..64 {
        let mut changed = false;
        for i in 0..n {
            let mut j_min = 0;
            loop {
                // the next neighbour j ≥ j_min of tris[i] (across an edge y → x of it)
                let next = if table {
                    let t = tris[i];
                    (0..3)
                        .map(|e| sc.owner[t[(e + 1) % 3] * nv + t[e]] as usize)
                        .filter(|&j| j != FREE as usize && j >= j_min && j != i)
                        .min()
                } else {
                    (j_min..n).find(|&j| {
                        j != i
                            && (0..3).any(|e| {
                                let (x, y) = (tris[i][e], tris[i][(e + 1) % 3]);
                                rotate_to(tris[j], y).is_some_and(|tj| tj[1] == x)
                            })
                    })
                };
                let Some(j) = next else {
                    break;
                };
                j_min = j + 1;
                let (lo, hi) = (i.min(j), i.max(j));
                let vers = (sc.ver[lo], sc.ver[hi]);
                if sc.idle[lo * n + hi] == vers {
                    continue;
                }
                // every edge x→y of tris[i] used as y→x by tris[j], in order (one for a
                // triangulation); the first improving swap is taken
                let mut swapped = None;
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
                    let old = sc.w[i].min(sc.w[j]);
                    let (w1, w2) = (sigma(n1), sigma(n2));
                    let new = w1.min(w2);
                    if new.partial_cmp(&(old + 1e-12)) != Some(std::cmp::Ordering::Greater) {
                        continue;
                    }
                    if a != 0 && b != 0 && edge_exists(a, b) {
                        continue;
                    }
                    swapped = Some((x, y, a, b, n1, n2, w1, w2));
                    break;
                }
                let Some((x, y, a, b, n1, n2, w1, w2)) = swapped else {
                    sc.idle[lo * n + hi] = vers;
                    continue;
                };
                if table {
                    if sc.owner[a * nv + b] != FREE || sc.owner[b * nv + a] != FREE {
                        // a second owner of a directed edge: scan from here on
                        clear_table(&mut sc.owner, tris, nv);
                        table = false;
                    } else {
                        sc.owner[x * nv + y] = FREE;
                        sc.owner[y * nv + x] = FREE;
                        for e in 0..3 {
                            sc.owner[n1[e] * nv + n1[(e + 1) % 3]] = i as u16;
                            sc.owner[n2[e] * nv + n2[(e + 1) % 3]] = j as u16;
                        }
                    }
                }
                tris[i] = n1;
                tris[j] = n2;
                (sc.w[i], sc.w[j]) = (w1, w2);
                clock += 1;
                sc.ver[i] = clock;
                clock += 1;
                sc.ver[j] = clock;
                swaps += 1;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    if table {
        clear_table(&mut sc.owner, tris, nv);
    }
    swaps
}

/// Resets the table entries of the directed edges of `tris` (all of them [`FREE`] after).
fn clear_table(owner: &mut [u16], tris: &[[usize; 3]], nv: usize) {
    for t in tris {
        for e in 0..3 {
            owner[t[e] * nv + t[(e + 1) % 3]] = FREE;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::util::Rng;

    /// The plain loop [`improve`] must equal: every pair `(i, j)` of every pass, in order.
    fn improve_plain(
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

    #[test]
    fn improve_equals_the_plain_loop() {
        // random fans: star-shaped rings with the new point inside, rings with two vertices
        // exchanged (folded), points outside, open fans, height-field projections; one
        // scratch for all (stale buffers must not leak from one call into the next)
        let mut rng = Rng::new(21);
        let mut unit = || rng.unit();
        let mut sc = Flips::default();
        let (mut total, mut cases_with_swaps) = (0, 0);
        for case in 0..3000 {
            let m = 3 + (unit() * 18.0) as usize;
            let closed = case % 5 != 0;
            let mut p3 = vec![[
                (unit() - 0.5) * if case % 7 == 0 { 3.0 } else { 1.2 },
                (unit() - 0.5) * 1.2,
                (unit() - 0.5) * 0.3,
            ]];
            let span = if closed { std::f64::consts::TAU } else { 2.5 };
            for j in 0..m {
                let ang = span * (j as f64 + 0.8 * unit()) / m as f64;
                let r = 1.0 + 0.6 * (unit() - 0.5);
                p3.push([r * ang.cos(), r * ang.sin(), (unit() - 0.5) * 0.4]);
            }
            if case % 3 == 0 && m > 3 {
                let k = 1 + (unit() * (m - 1) as f64) as usize;
                p3.swap(k, k % m + 1);
            }
            let p2: Vec<[f64; 2]> = p3.iter().map(|p| [p[0], p[1]]).collect();
            let xy: Option<Vec<[f64; 2]>> =
                (case % 4 == 1).then(|| p3.iter().map(|p| [p[0] + 0.3 * p[2], p[1]]).collect());
            let exists = |a: usize, b: usize| (a * b + a + b) % 11 == 0;
            let mut t1 = Vec::new();
            fan(m, closed, &mut t1);
            let mut t2 = t1.clone();
            let s1 = improve_plain(&mut t1, &p3, &p2, xy.as_deref(), exists);
            let s2 = improve(&mut t2, &p3, &p2, xy.as_deref(), exists, &mut sc);
            assert_eq!((s1, &t1), (s2, &t2), "case {case}");
            let w: Vec<f64> = t2
                .iter()
                .map(|t| angle_weight(p3[t[0]], p3[t[1]], p3[t[2]]))
                .collect();
            assert_eq!(sc.weights(), &w[..], "case {case}: weights");
            total += s1;
            cases_with_swaps += usize::from(s1 > 1);
        }
        assert!(
            total > 3000 && cases_with_swaps > 500,
            "{total} {cases_with_swaps}"
        );
        assert!(sc.owner.iter().all(|&o| o == FREE));
    }

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
        improve(&mut t, &p3, &p2, None, |_, _| false, &mut Flips::default());
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
