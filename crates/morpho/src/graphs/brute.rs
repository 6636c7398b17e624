//! Geometric graphs straight from their definitions (Veltkamp 1992, §2.2 Defs. 2.3–2.16 and
//! §3.2–3.3 Defs. 3.1–3.3), by brute force: O(N²) per edge set and O(N^{k+1}) for the
//! neighbourhood graphs (Thm 3.1). They are the oracles the fast constructions are tested
//! against, and the fallback for tiny inputs.
//!
//! Conventions: points are distinct; edges are `[i, j]` with i < j, triangles sorted, and
//! every list is sorted. Neighbourhoods are open, as in V §2.2 (points on a boundary circle do
//! not block), with the special rule for half-space neighbourhoods (the closed simplex belongs
//! to them). Where a graph is not unique (NNG and EMST under ties) the oracle returns the
//! union of all choices (NNG) or one tree (EMST; compare lengths).

use super::gamma::{
    center_interval_2d, center_interval_3d, def_contains_2d, def_contains_3d, CenterInterval,
    TriFrame,
};
use crate::geom::distance::{cmp_dist2, dot_sign, in_lune_ball, sum_of_roots_exceeds};
use crate::geom::predicates::raw;
use crate::geom::vec::{cross, dist, dot, sub};
use std::cmp::Ordering;

fn pairs(n: usize) -> impl Iterator<Item = (usize, usize)> {
    (0..n).flat_map(move |i| (i + 1..n).map(move |j| (i, j)))
}

/// Closest pairs (Def. 2.3): all pairs at the minimum distance (exact comparisons).
pub fn closest_pairs<const D: usize>(p: &[[f64; D]]) -> Vec<[u32; 2]> {
    let mut best: Option<(usize, usize)> = None;
    for (i, j) in pairs(p.len()) {
        match best {
            Some((a, b)) if cmp_dist2(&p[i], &p[j], &p[a], &p[b]) != Ordering::Less => {}
            _ => best = Some((i, j)),
        }
    }
    let Some((a, b)) = best else { return vec![] };
    pairs(p.len())
        .filter(|&(i, j)| cmp_dist2(&p[i], &p[j], &p[a], &p[b]) == Ordering::Equal)
        .map(|(i, j)| [i as u32, j as u32])
        .collect()
}

/// A nearest neighbour of every point (the first one in index order; exact comparisons).
pub fn nearest<const D: usize>(p: &[[f64; D]]) -> Vec<usize> {
    (0..p.len())
        .map(|i| {
            let mut best = usize::MAX;
            for j in (0..p.len()).filter(|&j| j != i) {
                if best == usize::MAX || cmp_dist2(&p[i], &p[j], &p[i], &p[best]) == Ordering::Less
                {
                    best = j;
                }
            }
            best
        })
        .collect()
}

/// Nearest neighbours graph (Def. 2.4), with every tie: (i, j) whenever j is a nearest
/// neighbour of i or i of j.
pub fn nng<const D: usize>(p: &[[f64; D]]) -> Vec<[u32; 2]> {
    let nn = nearest(p);
    let is_nn = |i: usize, j: usize| cmp_dist2(&p[i], &p[j], &p[i], &p[nn[i]]) == Ordering::Equal;
    pairs(p.len())
        .filter(|&(i, j)| is_nn(i, j) || is_nn(j, i))
        .map(|(i, j)| [i as u32, j as u32])
        .collect()
}

/// Euclidean minimum spanning tree (Def. 2.5) by Prim's algorithm with exact comparisons: one
/// tree (under ties several exist; compare lengths).
pub fn emst<const D: usize>(p: &[[f64; D]]) -> Vec<[u32; 2]> {
    let n = p.len();
    if n < 2 {
        return vec![];
    }
    // best[j]: the tree vertex closest to j
    let mut best = vec![0usize; n];
    let mut done = vec![false; n];
    done[0] = true;
    let mut out = Vec::with_capacity(n - 1);
    for _ in 1..n {
        let mut k = usize::MAX;
        for j in 0..n {
            if !done[j]
                && (k == usize::MAX
                    || cmp_dist2(&p[j], &p[best[j]], &p[k], &p[best[k]]) == Ordering::Less)
            {
                k = j;
            }
        }
        done[k] = true;
        let (a, b) = (best[k].min(k), best[k].max(k));
        out.push([a as u32, b as u32]);
        for j in 0..n {
            if !done[j] && cmp_dist2(&p[k], &p[j], &p[best[j]], &p[j]) == Ordering::Less {
                best[j] = k;
            }
        }
    }
    out.sort_unstable();
    out
}

/// Total length of a set of edges.
pub fn length<const D: usize>(p: &[[f64; D]], edges: &[[u32; 2]]) -> f64 {
    edges
        .iter()
        .map(|e| dist(p[e[0] as usize], p[e[1] as usize]))
        .sum()
}

/// Infinite strip graph (Def. 2.6): no point strictly between the two planes through i and j
/// perpendicular to ij, i.e. with (x − i)·(j − i) > 0 and (x − j)·(i − j) > 0 (exact signs).
pub fn strip<const D: usize>(p: &[[f64; D]]) -> Vec<[u32; 2]> {
    pairs(p.len())
        .filter(|&(i, j)| !(0..p.len()).any(|x| x != i && x != j && in_slab(&p[i], &p[j], &p[x])))
        .map(|(i, j)| [i as u32, j as u32])
        .collect()
}

/// x strictly between the planes through a and b perpendicular to ab.
pub fn in_slab<const D: usize>(a: &[f64; D], b: &[f64; D], x: &[f64; D]) -> bool {
    // signs of (x − a)·(b − a) and (x − b)·(a − b)
    dot_sign(x, b, a) > 0 && dot_sign(x, a, b) > 0
}

/// Sphere of influence graph (Def. 2.7): the balls of nearest-neighbour radius around i and j
/// overlap in more than one point, d(i, j) < r_i + r_j (decided exactly).
pub fn sig<const D: usize>(p: &[[f64; D]]) -> Vec<[u32; 2]> {
    let nn = nearest(p);
    pairs(p.len())
        .filter(|&(i, j)| sum_of_roots_exceeds(&p[i], &p[j], &p[nn[i]], &p[nn[j]]))
        .map(|(i, j)| [i as u32, j as u32])
        .collect()
}

/// Relative neighbourhood graph (Def. 2.8): no x with max(d(x,i), d(x,j)) < d(i,j).
pub fn rng<const D: usize>(p: &[[f64; D]]) -> Vec<[u32; 2]> {
    pairs(p.len())
        .filter(|&(i, j)| {
            !(0..p.len()).any(|x| {
                x != i
                    && x != j
                    && cmp_dist2(&p[x], &p[i], &p[i], &p[j]) == Ordering::Less
                    && cmp_dist2(&p[x], &p[j], &p[i], &p[j]) == Ordering::Less
            })
        })
        .map(|(i, j)| [i as u32, j as u32])
        .collect()
}

/// Gabriel graph (Def. 2.9): no x strictly inside the ball with diameter ij,
/// i.e. (i − x)·(j − x) < 0 (exact sign).
pub fn gabriel<const D: usize>(p: &[[f64; D]]) -> Vec<[u32; 2]> {
    pairs(p.len())
        .filter(|&(i, j)| {
            !(0..p.len()).any(|x| x != i && x != j && dot_sign(&p[i], &p[j], &p[x]) < 0)
        })
        .map(|(i, j)| [i as u32, j as u32])
        .collect()
}

/// 2D convex hull edges (Def. 2.10): no point in the open half-plane on one side of the line
/// through i and j, nor on the closed segment ij (other than i, j).
pub fn hull_2d(p: &[[f64; 2]]) -> Vec<[u32; 2]> {
    pairs(p.len())
        .filter(|&(i, j)| {
            let mut left = false;
            let mut right = false;
            for x in 0..p.len() {
                if x == i || x == j {
                    continue;
                }
                let o = raw::orient2d(p[i], p[j], p[x]);
                if o > 0.0 {
                    left = true;
                } else if o < 0.0 {
                    right = true;
                } else {
                    // on the closed segment: (x − i)·(j − i) ≥ 0 and (x − j)·(i − j) ≥ 0
                    if dot_sign(&p[x], &p[j], &p[i]) >= 0 && dot_sign(&p[x], &p[i], &p[j]) >= 0 {
                        return false;
                    }
                }
            }
            !(left && right)
        })
        .map(|(i, j)| [i as u32, j as u32])
        .collect()
}

fn triples(n: usize) -> impl Iterator<Item = (usize, usize, usize)> {
    (0..n).flat_map(move |i| (i + 1..n).flat_map(move |j| (j + 1..n).map(move |k| (i, j, k))))
}

/// 3D convex hull triangles (Def. 2.10): all points on one closed side of the plane, none
/// (other than the corners) in the closed triangle. Coplanar hull facets therefore give every
/// triangle among their points that contains no other point.
pub fn hull_3d(p: &[[f64; 3]]) -> Vec<[u32; 3]> {
    triples(p.len())
        .filter(|&(i, j, k)| {
            let n = cross(sub(p[j], p[i]), sub(p[k], p[i]));
            if dot(n, n) == 0.0 {
                return false;
            }
            let (mut above, mut below) = (false, false);
            for x in 0..p.len() {
                if x == i || x == j || x == k {
                    continue;
                }
                let o = raw::orient3d(p[i], p[j], p[k], p[x]);
                if o > 0.0 {
                    below = true;
                } else if o < 0.0 {
                    above = true;
                } else if super::gamma::in_closed_triangle_3d(p[i], p[j], p[k], p[x], n) {
                    return false;
                }
            }
            !(above && below)
        })
        .map(|(i, j, k)| [i as u32, j as u32, k as u32])
        .collect()
}

/// α(a)-shape edges in 2D (Defs. 2.12–2.14, following Edelsbrunner et al. 1983): (i, j) is an
/// edge when some generalized disc of radius 1/a has i and j on its boundary and contains all
/// points: for a > 0 a disc of radius 1/a, for a < 0 the complement of an (open) disc of radius
/// 1/|a| — i.e. an empty disc —, for a = 0 a half-plane (the convex hull).
pub fn alpha_2d(p: &[[f64; 2]], a: f64) -> Vec<[u32; 2]> {
    if a == 0.0 {
        return hull_2d(p);
    }
    let rad = 1.0 / a.abs();
    pairs(p.len())
        .filter(|&(i, j)| {
            // disc through i and j with centre m + t·N (N the unnormalised left normal):
            // |x − c|² − R² = q − 2t·h with q = |x − m|² − r², h = (x − m)·N (no square roots
            // in the comparison, so points exactly on the circle stay on it)
            let (pi, pj) = (p[i], p[j]);
            let dd = [pj[0] - pi[0], pj[1] - pi[1]];
            let l2 = dd[0] * dd[0] + dd[1] * dd[1];
            let h2 = rad * rad - l2 / 4.0;
            if h2 < 0.0 {
                return false;
            }
            let t = (h2 / l2).sqrt();
            let m = [0.5 * (pi[0] + pj[0]), 0.5 * (pi[1] + pj[1])];
            let nrm = [-dd[1], dd[0]];
            [1.0, -1.0].iter().any(|&sd| {
                (0..p.len()).filter(|&x| x != i && x != j).all(|x| {
                    let xm = [p[x][0] - m[0], p[x][1] - m[1]];
                    let q = xm[0] * xm[0] + xm[1] * xm[1] - l2 / 4.0;
                    let h = xm[0] * nrm[0] + xm[1] * nrm[1];
                    let v = q - 2.0 * sd * t * h; // |x − c|² − R²
                    if a > 0.0 {
                        v <= 0.0
                    } else {
                        v >= 0.0
                    }
                })
            })
        })
        .map(|(i, j)| [i as u32, j as u32])
        .collect()
}

/// Circle-based β-skeleton (Def. 2.15) in 2D: N_βc(b) = N_γ(b, b).
pub fn beta_circle_2d(p: &[[f64; 2]], b: f64) -> Vec<[u32; 2]> {
    gamma_2d_def(p, b, b)
}

/// Lune-based β-skeleton (Def. 2.16) for b ∈ [0, 1] in 2D or 3D: the open intersection of the
/// balls of radius d/(2(1−b)) centred at i + (j−i)/(2(1−b)) and j + (i−j)/(2(1−b)), plus the
/// open segment (b = 1: the infinite strip). For b < 0 the lune-based skeleton is the
/// circle-based one ([`beta_circle_2d`]).
pub fn beta_lune<const D: usize>(p: &[[f64; D]], b: f64) -> Vec<[u32; 2]> {
    if b >= 1.0 {
        return strip(p);
    }
    pairs(p.len())
        .filter(|&(i, j)| {
            !(0..p.len()).any(|x| {
                x != i
                    && x != j
                    && (in_lune_ball(&p[x], &p[i], &p[j], b)
                        && in_lune_ball(&p[x], &p[j], &p[i], b)
                        || on_open_segment(&p[i], &p[j], &p[x]))
            })
        })
        .map(|(i, j)| [i as u32, j as u32])
        .collect()
}

/// x on the open segment ij (exactly collinear, strictly between).
fn on_open_segment<const D: usize>(a: &[f64; D], b: &[f64; D], x: &[f64; D]) -> bool {
    // collinear: x − a parallel to b − a (exact for the cases that matter: uses orient2d in
    // each coordinate plane)
    for u in 0..D {
        for v in u + 1..D {
            if raw::orient2d([a[u], a[v]], [b[u], b[v]], [x[u], x[v]]) != 0.0 {
                return false;
            }
        }
    }
    in_slab(a, b, x)
}

/// γ(c₀, c₁) in 2D straight from Defs. 3.1–3.2: an edge is in the graph when one of its two
/// mirror-symmetric neighbourhoods contains no other point. O(N³).
pub fn gamma_2d_def(p: &[[f64; 2]], c0: f64, c1: f64) -> Vec<[u32; 2]> {
    pairs(p.len())
        .filter(|&(i, j)| {
            [1.0, -1.0].iter().any(|&side| {
                !(0..p.len())
                    .any(|x| x != i && x != j && def_contains_2d(p[i], p[j], c0, c1, side, p[x]))
            })
        })
        .map(|(i, j)| [i as u32, j as u32])
        .collect()
}

/// γ(c₀, c₁) in 3D straight from Defs. 3.1–3.2. O(N⁴).
pub fn gamma_3d_def(p: &[[f64; 3]], c0: f64, c1: f64) -> Vec<[u32; 3]> {
    triples(p.len())
        .filter(|&(i, j, k)| {
            let t = [p[i], p[j], p[k]];
            let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
            if dot(n, n) == 0.0 {
                return false;
            }
            [1.0, -1.0].iter().any(|&side| {
                !(0..p.len())
                    .any(|x| x != i && x != j && x != k && def_contains_3d(t, c0, c1, side, p[x]))
            })
        })
        .map(|(i, j, k)| [i as u32, j as u32, k as u32])
        .collect()
}

/// The γ-values of every pair in 2D (brute force, Thm 3.1): `(edge, (c₀′, c₁′))` for the
/// pairs that have any empty neighbourhood.
pub fn gamma_values_2d(p: &[[f64; 2]]) -> Vec<([u32; 2], (f64, f64))> {
    pairs(p.len())
        .filter_map(|(i, j)| {
            center_interval_2d(p, i, j)
                .gamma_values()
                .map(|v| ([i as u32, j as u32], v))
        })
        .collect()
}

/// The γ-values of every triple in 3D (brute force, Thm 3.1).
pub fn gamma_values_3d(p: &[[f64; 3]]) -> Vec<([u32; 3], (f64, f64))> {
    triples(p.len())
        .filter_map(|(i, j, k)| {
            center_interval_3d(p, i, j, k)?
                .gamma_values()
                .map(|v| ([i as u32, j as u32, k as u32], v))
        })
        .collect()
}

/// The triples of `p` with γ-values that `keep` accepts, decided on each triangle's frame and
/// interval (brute force, Thm 3.1; e.g. [`TriFrame::in_gamma`], exact), with their γ-values.
pub fn gamma_filter_3d(
    p: &[[f64; 3]],
    keep: impl Fn(&TriFrame, &CenterInterval) -> bool,
) -> Vec<([u32; 3], (f64, f64))> {
    triples(p.len())
        .filter_map(|(i, j, k)| {
            let f = TriFrame::new(p[i], p[j], p[k])?;
            let iv = center_interval_3d(p, i, j, k)?;
            let v = iv.gamma_values()?;
            keep(&f, &iv).then_some(([i as u32, j as u32, k as u32], v))
        })
        .collect()
}

/// α(a)-shape triangles in 3D from the definition (Defs. 2.12–2.14): a generalized ball of
/// radius 1/a through the three corners that contains all points (a > 0: a ball; a < 0: the
/// complement of an open ball, i.e. an empty ball; a = 0: the hull).
pub fn alpha_3d(p: &[[f64; 3]], a: f64) -> Vec<[u32; 3]> {
    if a == 0.0 {
        return hull_3d(p);
    }
    let rad = 1.0 / a.abs();
    triples(p.len())
        .filter(|&(i, j, k)| {
            let Some((m, r2, n)) = super::gamma::triangle_circle(p[i], p[j], p[k]) else {
                return false;
            };
            let h2 = rad * rad - r2;
            if h2 < 0.0 {
                return false;
            }
            let t = (h2 / dot(n, n)).sqrt();
            [1.0, -1.0].iter().any(|&sd| {
                (0..p.len())
                    .filter(|&x| x != i && x != j && x != k)
                    .all(|x| {
                        let xm = sub(p[x], m);
                        let v = dot(xm, xm) - r2 - 2.0 * sd * t * dot(xm, n); // |x − c|² − R²
                        if a > 0.0 {
                            v <= 0.0
                        } else {
                            v >= 0.0
                        }
                    })
            })
        })
        .map(|(i, j, k)| [i as u32, j as u32, k as u32])
        .collect()
}
