//! The empty triangles of a coplanar point set: the hull triangles of a coplanar hull facet
//! (Veltkamp 1992, Def. 2.10: every triangle of the facet whose closed triangle holds no other
//! point), which are also the triangles of γ(\[-1,1\],\[0,1\]) on the facet that only the outer
//! half-space leaves empty (γ-values (−1, 1), V §3.3).
//!
//! # Algorithm
//! Dobkin, Edelsbrunner & Overmars (1990, "Searching for empty convex polygons", §3): for each
//! point p, the points after it in lexicographic order sorted by angle around p (all lie in a
//! half-plane, so the angular order is a total order; of the points on one ray from p only the
//! nearest can be a corner, the farther ones lie beyond it) form a star-shaped polygon, and the
//! triangle p, r_i, r_j is empty iff r_i sees r_j inside it. The visibility graph is built in
//! time proportional to its size with one queue per vertex: r_k sees r_j (k < i < j) iff r_k sees
//! r_i, r_i sees r_j and r_k, r_i, r_j turn left (r_i strictly beyond the chord). Every empty
//! triangle is reported once, from its lexicographically smallest corner.
//!
//! # Complexity
//! O(g² log g) for the angular sorts plus O(1) per empty triangle, against O(g⁴) for testing
//! all g³/6 triples against all g points (1597 coplanar points on the top facet of the fandisk
//! model ran for hours in `graph --kind gamma` and `--kind hull`; issue 17, item 8). A set of g
//! points has at least Ω(g²) empty triangles, so this is output-sensitive up to the logarithm.
//!
//! # Exactness
//! Only orientation signs and lexicographic comparisons of coordinates. 3D points are
//! projected along a coordinate axis the plane is not parallel to ([`project_plane`]): that
//! projection maps the plane one-to-one onto the coordinate plane, so every orientation sign
//! is the same up to one global sign and the empty triangles are the same.

use crate::geom::predicates::raw;
use std::cmp::Ordering;
use std::collections::VecDeque;

/// The coplanar 3D points `p` projected to 2D along an axis their plane is not parallel to
/// (exact: a coordinate is dropped), or `None` when they are collinear (or fewer than 3).
pub fn project_plane(p: &[[f64; 3]]) -> Option<Vec<[f64; 2]>> {
    for k in (0..3).rev() {
        let q: Vec<[f64; 2]> = p
            .iter()
            .map(|x| match k {
                0 => [x[1], x[2]],
                1 => [x[2], x[0]],
                _ => [x[0], x[1]],
            })
            .collect();
        // a non-collinear projection: the plane is not parallel to axis k
        let Some(b) = q.iter().position(|x| *x != q[0]) else {
            continue;
        };
        if q.iter().any(|x| raw::orient2d(q[0], q[b], *x) != 0.0) {
            return Some(q);
        }
    }
    None
}

#[cfg(test)]
thread_local! {
    /// Orientation tests made by [`empty_triangles_2d`] on this thread (tests only).
    pub(super) static EMPTY_WORK: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

#[inline(always)]
fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    #[cfg(test)]
    EMPTY_WORK.with(|w| w.set(w.get() + 1));
    raw::orient2d(a, b, c)
}

/// Lexicographic order of 2D points (x, then y).
fn lex(a: &[f64; 2], b: &[f64; 2]) -> Ordering {
    a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1]))
}

/// Calls `f(i, j, k)` (indices into `p`, the first one the lexicographically smallest corner)
/// once for every non-degenerate triangle of points of `p` whose closed triangle contains no
/// other point of `p`. The points must be distinct. O(g² log g + K) for K such triangles.
pub fn empty_triangles_2d(p: &[[f64; 2]], mut f: impl FnMut(u32, u32, u32)) {
    let mut ord: Vec<u32> = (0..p.len() as u32).collect();
    ord.sort_by(|&a, &b| lex(&p[a as usize], &p[b as usize]));
    let mut rays: Vec<u32> = Vec::new();
    let mut queues: Vec<VecDeque<u32>> = Vec::new();
    let mut stack: Vec<u32> = Vec::new();
    for (r, &a) in ord.iter().enumerate() {
        let pa = p[a as usize];
        // the later points by angle around a (counter-clockwise), nearer first on a ray
        rays.clear();
        rays.extend_from_slice(&ord[r + 1..]);
        rays.sort_by(|&u, &v| {
            let (pu, pv) = (p[u as usize], p[v as usize]);
            let o = orient(pa, pu, pv);
            if o > 0.0 {
                Ordering::Less
            } else if o < 0.0 {
                Ordering::Greater
            } else {
                // on one ray from a: lexicographic order is the order of distance
                lex(&pu, &pv)
            }
        });
        // only the nearest point of each ray
        rays.dedup_by(|v, u| orient(pa, p[*u as usize], p[*v as usize]) == 0.0);
        let m = rays.len();
        if m < 2 {
            continue;
        }
        let q = |i: u32| p[rays[i as usize] as usize];
        queues.iter_mut().for_each(VecDeque::clear);
        if queues.len() < m {
            queues.resize_with(m, VecDeque::new);
        }
        for i in 0..m as u32 - 1 {
            // PROCEED(i, i + 1) of DEO'90, without recursion: PROCEED(i, j) first runs
            // PROCEED(k, j) for the front k of queue i while k, i, j turn left (dequeuing k
            // after it), then reports (i, j) and enqueues i on queue j
            let j = i + 1;
            stack.clear();
            stack.push(i);
            while let Some(&x) = stack.last() {
                match queues[x as usize].front() {
                    Some(&k) if orient(q(k), q(x), q(j)) > 0.0 => stack.push(k),
                    _ => {
                        f(a, rays[x as usize], rays[j as usize]);
                        queues[j as usize].push_back(x);
                        stack.pop();
                        if let Some(&parent) = stack.last() {
                            queues[parent as usize].pop_front();
                        }
                    }
                }
            }
        }
    }
}

/// [`empty_triangles_2d`] for coplanar 3D points (projected by [`project_plane`]); nothing when
/// they are collinear.
pub fn empty_triangles_3d(p: &[[f64; 3]], f: impl FnMut(u32, u32, u32)) {
    if let Some(q) = project_plane(p) {
        empty_triangles_2d(&q, f);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// Every empty triangle by the definition: O(g⁴).
    fn brute(p: &[[f64; 2]]) -> Vec<[u32; 3]> {
        let n = p.len();
        let mut out = Vec::new();
        for i in 0..n {
            for j in i + 1..n {
                for k in j + 1..n {
                    let s = raw::orient2d(p[i], p[j], p[k]);
                    if s == 0.0 {
                        continue;
                    }
                    let inside = (0..n).any(|x| {
                        x != i
                            && x != j
                            && x != k
                            && raw::orient2d(p[i], p[j], p[x]) * s >= 0.0
                            && raw::orient2d(p[j], p[k], p[x]) * s >= 0.0
                            && raw::orient2d(p[k], p[i], p[x]) * s >= 0.0
                    });
                    if !inside {
                        out.push([i as u32, j as u32, k as u32]);
                    }
                }
            }
        }
        out
    }

    fn fast(p: &[[f64; 2]]) -> Vec<[u32; 3]> {
        let mut out = Vec::new();
        empty_triangles_2d(p, |a, b, c| {
            let mut t = [a, b, c];
            t.sort_unstable();
            out.push(t);
        });
        let n = out.len();
        out.sort_unstable();
        out.dedup();
        assert_eq!(out.len(), n, "a triangle reported twice");
        out
    }

    fn sets() -> Vec<(String, Vec<[f64; 2]>)> {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(17);
        let mut v: Vec<(String, Vec<[f64; 2]>)> = Vec::new();
        for n in [3, 4, 5, 8, 13, 30, 60] {
            let p = (0..n)
                .map(|_| [rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0)])
                .collect();
            v.push((format!("random {n}"), p));
            // small integer coordinates: many collinear triples and shared rays
            let mut p: Vec<[f64; 2]> = (0..n)
                .map(|_| [rng.gen_range(0..5) as f64, rng.gen_range(0..5) as f64])
                .collect();
            p.sort_by(lex);
            p.dedup();
            v.push((format!("small integers {n}"), p));
        }
        for (w, h) in [(1, 5), (2, 2), (3, 3), (4, 7), (6, 6)] {
            let p = (0..w * h)
                .map(|i| [(i % w) as f64, (i / w) as f64])
                .collect();
            v.push((format!("grid {w}×{h}"), p));
        }
        // convex position (every triple empty) and points on a circle
        v.push((
            "regular 17-gon".into(),
            (0..17)
                .map(|i| {
                    let t = i as f64 * std::f64::consts::TAU / 17.0;
                    [t.cos(), t.sin()]
                })
                .collect(),
        ));
        v.push((
            "cocircular 5²".into(),
            crate::graphs::tests::CIRCLE5
                .iter()
                .copied()
                .chain([[0., 0.]])
                .collect(),
        ));
        v
    }

    #[test]
    fn empty_triangles_equal_the_definition() {
        for (name, p) in sets() {
            assert_eq!(fast(&p), brute(&p), "{name}");
        }
    }

    /// In 3D, on planes not parallel to any axis and parallel to each, the same triangles.
    #[test]
    fn coplanar_3d_points_give_the_triangles_of_their_plane() {
        for (name, p) in sets() {
            let want = brute(&p);
            // axis-parallel planes, and a slanted one (exact on integers only)
            let integers = !name.starts_with("random") && !name.starts_with("regular");
            for (m, map) in [
                |x: [f64; 2]| [x[0], x[1], 7.0],
                |x: [f64; 2]| [x[0], 3.0, x[1]],
                |x: [f64; 2]| [-2.0, x[1], x[0]],
                |x: [f64; 2]| [x[0] + x[1], 2.0 * x[0] - x[1], 3.0 * x[1] - x[0]],
            ]
            .into_iter()
            .enumerate()
            {
                if m == 3 && !integers {
                    continue;
                }
                let q: Vec<[f64; 3]> = p.iter().map(|&x| map(x)).collect();
                let mut got = Vec::new();
                empty_triangles_3d(&q, |a, b, c| {
                    let mut t = [a, b, c];
                    t.sort_unstable();
                    got.push(t);
                });
                got.sort_unstable();
                assert_eq!(got, want, "{name}");
            }
        }
    }

    /// O(1) orientation tests per empty triangle after the sorts: on a 30×30 grid (900 points,
    /// 489,900 empty triangles) against 900³/6 ≈ 1.2·10⁸ triples for the definition.
    #[test]
    fn work_is_proportional_to_the_output() {
        let g = 30;
        let p: Vec<[f64; 2]> = (0..g * g)
            .map(|i| [(i % g) as f64, (i / g) as f64])
            .collect();
        EMPTY_WORK.with(|w| w.set(0));
        let mut k = 0u64;
        empty_triangles_2d(&p, |_, _, _| k += 1);
        let work = EMPTY_WORK.with(|w| w.get());
        let n = p.len() as u64;
        let sorts = n * n * (64 - n.leading_zeros() as u64);
        assert!(k > n * n / 2, "{k} empty triangles");
        assert!(
            work <= 3 * k + sorts,
            "{work} orientation tests for {k} triangles (bound {})",
            3 * k + sorts
        );
    }
}
