//! Validity of a 3D boundary (Veltkamp 1992, §4.2 "Boundary construction 3D": a simple closed
//! polyhedron through all vertices): no two triangles may meet except in their shared
//! vertices/edge.
//!
//! [`self_intersections`] tests, with exact `orient3d`/`orient2d` only, every pair of triangles
//! whose bounding boxes share a cell of a uniform grid:
//! - pairs with no common vertex: full closed triangle–triangle test (non-coplanar: some edge of
//!   one meets the other closed triangle — the intersection of two triangles in different planes
//!   is a segment whose ends lie on edges; coplanar: 2D test in an exact non-degenerate axis
//!   projection);
//! - pairs with one common vertex v: the edge opposite v of each must not meet the other
//!   triangle, and for coplanar pairs the projected triangles must not overlap beyond v;
//! - pairs with a common edge ab (triangles abc, abd): they meet beyond the edge iff they are
//!   coplanar (`orient3d(a, b, c, d) == 0`) and c, d lie on the same side of line ab in that
//!   plane (exact `orient2d` in a non-degenerate axis projection) — a fold onto itself — or one
//!   of them is degenerate (c or d on line ab);
//! - the same triangle twice (three common vertices) always counts as an intersection.
//!
//! Expected O(n) for meshes of evenly sized triangles, O(n²) worst case.

use super::grid::self_intersections_ordered;
use super::pair::pair_meets;
use crate::geom::vec::dist;

type P = [f64; 3];

/// Pairs of triangles (indices into `tris`) that intersect although they must not (see the
/// module documentation); at most `limit` are returned (the smallest pairs).
///
/// Broad phase: a uniform grid (cell: twice the median edge length, coarsened until it has at
/// most 8 cells per triangle), as a counting-sorted list of (cell, triangle) entries; each pair whose
/// bounding boxes overlap is tested exactly once, in the cell of the low corner of the boxes'
/// intersection (a cell's entries are grouped by which axes of the cell their low cell shares,
/// so only those pairs are visited). Triangles spanning more than 512 cells are tested against
/// each other by boxes and against the triangles of the cells their plane passes. Cells and
/// big triangles are processed in parallel (rayon); the result does not depend on the thread
/// count. Each pair goes through a floating-point plane filter with a proven bound first
/// (`PlaneFilter`); pairs without a common vertex whose filtered signs all are certain and
/// straddle are decided by two exact predicates (Guigue–Devillers), every other undecided pair
/// by the exact test of its class.
///
/// The triangles are first put in a spatially coherent order (by the cell of their centroid in
/// a grid of about one cell per triangle, rows in z, y, x order), so that the triangles of one
/// cell sit close together in memory; the pairs are mapped back to the input indices.
///
/// Coordinates are first multiplied by the power of two that brings the largest magnitude
/// near 1 (exact), so that no predicate over- or
/// underflows at extreme absolute scales (1e-300 … 1e300).
///
/// The surface of a tetrahedron is clean; a triangle piercing it is found:
/// ```rust
/// use morpho::mesh::validity::self_intersections;
/// let mut pos = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
/// let mut tris = vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];
/// assert!(self_intersections(&pos, &tris, 10).is_empty());
/// pos.extend([[0.2, 0.2, -1.0], [0.3, 0.2, 2.0], [0.2, 0.3, 2.0]]);
/// tris.push([4, 5, 6]);
/// let hits = self_intersections(&pos, &tris, 10);
/// assert!(!hits.is_empty() && hits.iter().all(|&(_, b)| b == 4));
/// ```
pub fn self_intersections(pos: &[P], tris: &[[u32; 3]], limit: usize) -> Vec<(u32, u32)> {
    self_intersections_masked(pos, tris, None, limit)
}

/// [`self_intersections`] without testing the pairs of two *trusted* triangles
/// (`trusted[i]` for `tris[i]`): faces of one tetrahedralization, for instance, meet only in
/// common vertices and edges (a simplicial complex), so among them only pairs with at least
/// one other triangle can intersect. The result is the pairs of [`self_intersections`] with
/// an untrusted member. Only the grid cells that an untrusted triangle's box reaches are
/// filled and visited, so the cost follows the untrusted triangles and their neighbours
/// (nothing is tested when every triangle is trusted).
///
/// # Panics
/// When `trusted` and `tris` differ in length.
///
/// ```rust
/// use morpho::mesh::validity::{faces_of_tetrahedra, self_intersections_trusting};
/// let pos = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
/// let tris = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2], [0, 2, 1]];
/// // the last triangle repeats the first: only a pair with an untrusted member is tested
/// let mut trusted = faces_of_tetrahedra(&[[0, 1, 2, 3]], &tris);
/// assert!(trusted[..4].iter().all(|&t| t));
/// trusted[4] = true;
/// assert!(self_intersections_trusting(&pos, &tris, &trusted, 10).is_empty());
/// trusted[4] = false;
/// assert_eq!(self_intersections_trusting(&pos, &tris, &trusted, 10), vec![(0, 4)]);
/// ```
pub fn self_intersections_trusting(
    pos: &[P],
    tris: &[[u32; 3]],
    trusted: &[bool],
    limit: usize,
) -> Vec<(u32, u32)> {
    assert_eq!(trusted.len(), tris.len(), "one trust flag per triangle");
    self_intersections_masked(pos, tris, Some(trusted), limit)
}

/// For every triangle of `tris`, whether it is a face of one of the tetrahedra `tets` (vertex
/// indices in any order): the flags for [`self_intersections_trusting`] when the tetrahedra
/// form a tetrahedralization.
///
/// ```rust
/// use morpho::mesh::validity::faces_of_tetrahedra;
/// let f = faces_of_tetrahedra(&[[0, 1, 2, 3]], &[[2, 1, 0], [0, 1, 4]]);
/// assert_eq!(f, vec![true, false]);
/// ```
pub fn faces_of_tetrahedra(tets: &[[u32; 4]], tris: &[[u32; 3]]) -> Vec<bool> {
    use crate::util::sorted3 as sort3;
    use rayon::prelude::*;
    let mut index: crate::util::IdMap<[u32; 3], u32> = Default::default();
    index.reserve(tris.len());
    for (i, &t) in tris.iter().enumerate() {
        index.entry(sort3(t)).or_insert(i as u32);
    }
    let found: Vec<u32> = tets
        .par_iter()
        .flat_map_iter(|t| {
            let index = &index;
            (0..4).filter_map(move |k| {
                let f = [t[(k + 1) % 4], t[(k + 2) % 4], t[(k + 3) % 4]];
                index.get(&sort3(f)).copied()
            })
        })
        .collect();
    // (a triangle listed twice is trusted once, its first copy: the pair of copies is still
    // tested)
    let mut out = vec![false; tris.len()];
    for i in found {
        out[i as usize] = true;
    }
    out
}

/// The bounding box of every triangle (in parallel).
pub(super) fn tri_boxes(pos: &[P], tris: &[[u32; 3]]) -> Vec<(P, P)> {
    use rayon::prelude::*;
    tris.par_iter()
        .map(|t| {
            let q = t.map(|v| pos[v as usize]);
            (
                std::array::from_fn(|k| q[0][k].min(q[1][k]).min(q[2][k])),
                std::array::from_fn(|k| q[0][k].max(q[1][k]).max(q[2][k])),
            )
        })
        .collect()
}

/// The triangles that may meet an untrusted one: the untrusted triangles and every triangle
/// whose bounding box reaches a grid cell that an untrusted triangle's box reaches (cells of
/// twice the median edge length of the untrusted triangles; cell indices are monotone in the
/// coordinates, so overlapping boxes share a cell). Indices in increasing order; `None` when
/// the untrusted triangles are not finite or too spread out for a small grid (then the whole
/// set is checked).
fn near_untrusted(pos: &[P], tris: &[[u32; 3]], trusted: &[bool]) -> Option<Vec<u32>> {
    use rayon::prelude::*;
    let boxes = tri_boxes(pos, tris);
    let untrusted: Vec<u32> = (0..tris.len() as u32)
        .filter(|&i| !trusted[i as usize])
        .collect();
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    let mut lens = Vec::with_capacity(3 * untrusted.len());
    for &i in &untrusted {
        let (bl, bh) = boxes[i as usize];
        if !bl.iter().chain(&bh).all(|x| x.is_finite()) {
            return None;
        }
        for k in 0..3 {
            lo[k] = lo[k].min(bl[k]);
            hi[k] = hi[k].max(bh[k]);
        }
        let q = tris[i as usize].map(|v| pos[v as usize]);
        for k in 0..3 {
            let (a, b) = (q[k], q[(k + 1) % 3]);
            lens.push(dist(a, b));
        }
    }
    let mid = lens.len() / 2;
    let cell = 2.0 * *lens.select_nth_unstable_by(mid, f64::total_cmp).1;
    let dims: Vec<f64> = (0..3)
        .map(|k| ((hi[k] - lo[k]) / cell).floor() + 1.0)
        .collect();
    if !(cell > 0.0 && cell.is_finite())
        || dims.iter().any(|&d| d.is_nan() || d >= (1u64 << 21) as f64)
    {
        return None;
    }
    let dims: [u64; 3] = std::array::from_fn(|k| dims[k] as u64);
    // cell range of a box, clamped to the grid; None when outside it
    let range = |(bl, bh): (P, P)| -> Option<([u64; 3], [u64; 3])> {
        let mut mn = [0u64; 3];
        let mut mx = [0u64; 3];
        for k in 0..3 {
            let (a, b) = (
                ((bl[k] - lo[k]) / cell).floor(),
                ((bh[k] - lo[k]) / cell).floor(),
            );
            if b < 0.0 || a > (dims[k] - 1) as f64 {
                return None;
            }
            mn[k] = a.max(0.0) as u64;
            mx[k] = b.min((dims[k] - 1) as f64) as u64;
        }
        Some((mn, mx))
    };
    let key = |x: u64, y: u64, z: u64| x | y << 21 | z << 42;
    let mut hot: crate::util::IdSet<u64> = Default::default();
    for &i in &untrusted {
        let (mn, mx) = range(boxes[i as usize])?;
        if (0..3).map(|k| mx[k] - mn[k] + 1).product::<u64>() > 4096 {
            return None;
        }
        for z in mn[2]..=mx[2] {
            for y in mn[1]..=mx[1] {
                for x in mn[0]..=mx[0] {
                    hot.insert(key(x, y, z));
                }
            }
        }
    }
    // a trusted box over more cells than this is kept without looking
    const LOOK: u64 = 64;
    Some(
        (0..tris.len() as u32)
            .into_par_iter()
            .filter(|&i| {
                let b = boxes[i as usize];
                if !trusted[i as usize] || !b.0.iter().chain(&b.1).all(|x| x.is_finite()) {
                    return true;
                }
                let Some((mn, mx)) = range(b) else {
                    return false;
                };
                if (0..3).map(|k| mx[k] - mn[k] + 1).product::<u64>() > LOOK {
                    return true;
                }
                (mn[2]..=mx[2]).any(|z| {
                    (mn[1]..=mx[1]).any(|y| (mn[0]..=mx[0]).any(|x| hot.contains(&key(x, y, z))))
                })
            })
            .collect(),
    )
}

/// [`self_intersections`], skipping pairs of two trusted triangles when flags are given.
fn self_intersections_masked(
    pos: &[P],
    tris: &[[u32; 3]],
    trusted: Option<&[bool]>,
    limit: usize,
) -> Vec<(u32, u32)> {
    use rayon::prelude::*;
    if tris.is_empty() || trusted.is_some_and(|t| t.iter().all(|&x| x)) {
        return Vec::new();
    }
    let m = tris
        .par_iter()
        .map(|t| {
            t.iter()
                .flat_map(|&v| pos[v as usize])
                .filter(|x| x.is_finite())
                .fold(0.0f64, |m, x| m.max(x.abs()))
        })
        .reduce(|| 0.0, f64::max);
    let s = crate::geom::exact::power_of_two_scale(m);
    let scaled: Vec<P>;
    let pos = if s != 1.0 {
        scaled = pos.par_iter().map(|q| q.map(|x| x * s)).collect();
        &scaled[..]
    } else {
        pos
    };
    // few untrusted triangles: only they and the triangles near them
    if let Some(t) = trusted {
        let untrusted = t.iter().filter(|&&x| !x).count();
        if untrusted * 8 < tris.len() {
            if let Some(sub) = near_untrusted(pos, tris, t) {
                let sub_tris: Vec<[u32; 3]> = sub.iter().map(|&i| tris[i as usize]).collect();
                let sub_trust: Vec<bool> = sub.iter().map(|&i| t[i as usize]).collect();
                let mut pairs: Vec<(u32, u32)> =
                    self_intersections_grid(pos, &sub_tris, Some(&sub_trust), usize::MAX)
                        .into_iter()
                        .map(|(a, b)| (sub[a as usize], sub[b as usize]))
                        .collect();
                // (sub is increasing, so the pairs stay ordered)
                pairs.truncate(limit);
                return pairs;
            }
        }
    }
    self_intersections_grid(pos, tris, trusted, limit)
}

/// [`self_intersections_masked`] by the grid over all triangles (see [`self_intersections`]),
/// on coordinates already scaled near 1.
fn self_intersections_grid(
    pos: &[P],
    tris: &[[u32; 3]],
    trusted: Option<&[bool]>,
    limit: usize,
) -> Vec<(u32, u32)> {
    use rayon::prelude::*;
    let cen: Vec<P> = tris
        .par_iter()
        .map(|t| std::array::from_fn(|k| t.iter().map(|&v| pos[v as usize][k] / 3.0).sum()))
        .collect();
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for c in cen.iter().filter(|c| c.iter().all(|x| x.is_finite())) {
        for k in 0..3 {
            lo[k] = lo[k].min(c[k]);
            hi[k] = hi[k].max(c[k]);
        }
    }
    let side = (tris.len() as f64).cbrt().ceil().max(1.0);
    let cell_of = |x: f64, k: usize| -> u64 {
        let c = ((x - lo[k]) / (hi[k] - lo[k]) * side).floor();
        if c.is_finite() && c > 0.0 {
            (c as u64).min(side as u64 - 1)
        } else {
            0
        }
    };
    let s = side as u64;
    let mut order: Vec<(u64, u32)> = cen
        .par_iter()
        .enumerate()
        .map(|(i, c)| {
            let g: [u64; 3] = std::array::from_fn(|k| cell_of(c[k], k));
            (g[0] + s * (g[1] + s * g[2]), i as u32)
        })
        .collect();
    drop(cen);
    order.par_sort_unstable();
    let sorted: Vec<[u32; 3]> = order.par_iter().map(|&(_, i)| tris[i as usize]).collect();
    let sorted_trust: Option<Vec<bool>> =
        trusted.map(|t| order.par_iter().map(|&(_, i)| t[i as usize]).collect());
    let mut pairs: Vec<(u32, u32)> =
        self_intersections_ordered(pos, &sorted, sorted_trust.as_deref())
            .into_iter()
            .map(|(a, b)| {
                let (a, b) = (order[a as usize].1, order[b as usize].1);
                (a.min(b), a.max(b))
            })
            .collect();
    pairs.sort_unstable();
    pairs.dedup();
    pairs.truncate(limit);
    pairs
}

/// Every pair of triangles that intersect although they must not, by testing all pairs
/// (O(n²); the oracle of [`self_intersections`] in tests).
///
/// ```rust
/// use morpho::mesh::validity::self_intersections_brute;
/// // two triangles crossing like the blades of a cross
/// let pos = [[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0],
///            [0.0, -1.0, 0.5], [0.0, 1.0, 0.5], [0.0, 0.0, -1.0]];
/// assert_eq!(self_intersections_brute(&pos, &[[0, 1, 2], [3, 4, 5]]), vec![(0, 1)]);
/// ```
pub fn self_intersections_brute(pos: &[P], tris: &[[u32; 3]]) -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    for a in 0..tris.len() {
        for b in a + 1..tris.len() {
            if pair_meets(pos, tris[a], tris[b]) {
                out.push((a as u32, b as u32));
            }
        }
    }
    out
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    #[test]
    fn closed_tetrahedron_surface_is_clean_and_a_pierced_one_is_not() {
        let pos = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        let tris = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];
        assert!(self_intersections(&pos, &tris, 10).is_empty());
        let mut pos2 = pos.to_vec();
        pos2.extend([[0.2, 0.2, -0.5], [0.2, 0.2, 0.5], [0.3, 0.25, 2.0]]);
        let mut tris2 = tris.to_vec();
        tris2.push([4, 5, 6]);
        assert!(!self_intersections(&pos2, &tris2, 10).is_empty());
        // shared vertex, coplanar overlapping wedges
        let pos3 = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 2.0, 0.0],
            [2.0, 1.0, 0.0],
            [1.0, 2.0, 0.0],
        ];
        assert!(!self_intersections(&pos3, &[[0, 1, 2], [0, 3, 4]], 10).is_empty());
    }

    /// Issue 17 item 5: a face repeating a vertex (`f 1 1 2` added to a closed mesh) made the
    /// pair test index past its corners (a panic in `morpho info --check`). It is the segment
    /// it covers: here the edge 0–1, folded onto the two faces on that edge.
    #[test]
    fn faces_with_a_repeated_vertex_are_checked_as_segments() {
        let pos = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        let mut tris = vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];
        tris.push([0, 0, 1]);
        assert_eq!(self_intersections(&pos, &tris, 10), vec![(0, 4), (1, 4)]);
        assert_eq!(self_intersections_brute(&pos, &tris), vec![(0, 4), (1, 4)]);
        // a point face at a vertex meets nothing beyond it; every other repeat form is checked
        for extra in [[3, 3, 3], [2, 2, 0], [1, 3, 1], [3, 2, 2]] {
            let mut t = tris[..4].to_vec();
            t.push(extra);
            assert_eq!(
                self_intersections(&pos, &t, 10),
                self_intersections_brute(&pos, &t),
                "{extra:?}"
            );
        }
        let trusted = [true, true, true, true, false];
        assert_eq!(
            self_intersections_trusting(&pos, &tris, &trusted, 10),
            vec![(0, 4), (1, 4)]
        );
    }

    /// A closed tetrahedron surface plus a folded flap, and a repeated triangle.
    #[test]
    fn folds_and_repeats_are_found() {
        let pos = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.3, 0.3, 0.0],
        ];
        let tris = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];
        assert!(self_intersections(&pos, &tris, 10).is_empty());
        let mut t2 = tris.to_vec();
        t2.push([0, 1, 4]); // lies inside face 0 2 1, common edge 0 1
        assert_eq!(self_intersections(&pos, &t2, 10), vec![(0, 4)]);
        // the same triangle twice
        let mut t3 = tris.to_vec();
        t3.push([1, 2, 3]);
        assert_eq!(self_intersections(&pos, &t3, 10), vec![(2, 4)]);
    }

    /// A closed UV sphere (`m` × `m` quads, poles fanned), every vertex perturbed by up to
    /// `noise` (deterministic).
    pub(in crate::mesh::validity) fn sphere(
        m: usize,
        noise: f64,
        seed: u64,
    ) -> (Vec<P>, Vec<[u32; 3]>) {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let mut pos: Vec<P> = vec![[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]];
        for i in 1..m {
            let th = std::f64::consts::PI * i as f64 / m as f64;
            for j in 0..m {
                let ph = 2.0 * std::f64::consts::PI * j as f64 / m as f64;
                let mut q = [th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()];
                for x in &mut q {
                    *x += rng.gen_range(-noise..=noise);
                }
                pos.push(q);
            }
        }
        let id = |i: usize, j: usize| (2 + (i - 1) * m + j % m) as u32;
        let mut tris = Vec::new();
        for j in 0..m {
            tris.push([0, id(1, j), id(1, j + 1)]);
            tris.push([1, id(m - 1, j + 1), id(m - 1, j)]);
            for i in 1..m - 1 {
                tris.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                tris.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        (pos, tris)
    }

    /// 250 random triangles over 200 points, mostly small (corners drawn near the first), every
    /// 40th big; integer coordinates (coplanar and touching cases) or not; corners shared by
    /// drawing them from the pool; the fourth triangle repeated at the end.
    pub(in crate::mesh::validity) fn soup(
        rng: &mut rand_chacha::ChaCha8Rng,
        integer: bool,
    ) -> (Vec<P>, Vec<[u32; 3]>) {
        use rand::Rng;
        let n_pts = 200;
        let pos: Vec<P> = (0..n_pts)
            .map(|_| {
                std::array::from_fn(|_| {
                    if integer {
                        rng.gen_range(0..12) as f64
                    } else {
                        rng.gen_range(0.0..10.0)
                    }
                })
            })
            .collect();
        let mut tris = Vec::new();
        for k in 0..250 {
            let a = rng.gen_range(0..n_pts);
            let mut near = || -> usize {
                if k % 40 == 0 {
                    rng.gen_range(0..n_pts) // big
                } else {
                    // a close point: the nearest of a few random ones
                    (0..8)
                        .map(|_| rng.gen_range(0..n_pts))
                        .min_by(|&x, &y| {
                            let d = |v: usize| {
                                (0..3).map(|i| (pos[v][i] - pos[a][i]).powi(2)).sum::<f64>()
                            };
                            d(x).total_cmp(&d(y))
                        })
                        .unwrap_or(0)
                }
            };
            let (b, c) = (near(), near());
            if a != b && b != c && a != c {
                tris.push([a as u32, b as u32, c as u32]);
            }
        }
        tris.push(tris[3]);
        (pos, tris)
    }

    /// The trusting check returns exactly the all-pairs result restricted to pairs with an
    /// untrusted member, whether few triangles are untrusted (the near-untrusted subset), many
    /// (the whole grid), none or all; on random soups and on a closed mesh with crossings.
    #[test]
    fn trusting_check_keeps_exactly_the_pairs_with_an_untrusted_member() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(17);
        let mut cases: Vec<(Vec<P>, Vec<[u32; 3]>)> =
            (0..6).map(|r| soup(&mut rng, r % 2 == 0)).collect();
        // a bumpy closed mesh with a few small triangles poking through it
        let (mut pos, mut tris) = sphere(24, 0.02, 8);
        for k in 0..6 {
            let t = tris[k * 97];
            let q = t.map(|v| pos[v as usize]);
            let c: P = std::array::from_fn(|i| (q[0][i] + q[1][i] + q[2][i]) / 3.0);
            let base = pos.len() as u32;
            pos.push(c.map(|x| x * 1.05));
            pos.push(c.map(|x| x * 0.95));
            pos.push(std::array::from_fn(|i| {
                c[i] * 0.95 + 0.01 * (q[0][i] - c[i])
            }));
            tris.push([base, base + 1, base + 2]);
        }
        cases.push((pos, tris));
        let mut checked_subset = 0;
        for (ci, (pos, tris)) in cases.iter().enumerate() {
            let all = self_intersections_brute(pos, tris);
            assert!(!all.is_empty(), "case {ci}");
            let n = tris.len();
            for frac in [0.0, 0.03, 0.1, 0.5, 1.0] {
                let mut trusted: Vec<bool> = (0..n).map(|_| !rng.gen_bool(frac)).collect();
                if ci == cases.len() - 1 && frac > 0.0 {
                    // the poking triangles are the untrusted ones (plus random others)
                    for t in trusted[n - 6..].iter_mut() {
                        *t = false;
                    }
                }
                let untrusted = trusted.iter().filter(|&&t| !t).count();
                if untrusted > 0 && untrusted * 8 < n {
                    checked_subset += 1;
                }
                let expect: Vec<(u32, u32)> = all
                    .iter()
                    .copied()
                    .filter(|&(a, b)| !(trusted[a as usize] && trusted[b as usize]))
                    .collect();
                let found = self_intersections_trusting(pos, tris, &trusted, usize::MAX);
                assert_eq!(found, expect, "case {ci}, untrusted {untrusted} of {n}");
                if ci == cases.len() - 1 {
                    // the same at extreme scales (powers of two keep the configuration)
                    for sc in [2f64.powi(-1000), 2f64.powi(1000)] {
                        let q: Vec<P> = pos.iter().map(|p| p.map(|x| x * sc)).collect();
                        let got = self_intersections_trusting(&q, tris, &trusted, usize::MAX);
                        assert_eq!(got, expect, "scale {sc:e}");
                    }
                }
                if expect.len() > 2 {
                    assert_eq!(
                        self_intersections_trusting(pos, tris, &trusted, 2),
                        expect[..2].to_vec()
                    );
                }
            }
        }
        assert!(checked_subset >= 6, "{checked_subset}");
    }

    /// Face membership against a hash set of every tetrahedron's faces, on a Delaunay
    /// tetrahedralization with its faces, non-faces and a repeated face (trusted once).
    #[test]
    fn faces_of_tetrahedra_is_membership_in_the_faces_of_the_tetrahedra() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let pts: Vec<crate::geom::Point3> = (0..300)
            .map(|_| {
                crate::geom::Point3::new(
                    rng.gen_range(0.0..1.0),
                    rng.gen_range(0.0..1.0),
                    rng.gen_range(0.0..1.0),
                )
            })
            .collect();
        let d = crate::delaunay::d3::triangulate(&pts).unwrap();
        let mut faces = std::collections::HashSet::new();
        for t in &d.tets {
            for k in 0..4 {
                let mut f = [t[(k + 1) % 4], t[(k + 2) % 4], t[(k + 3) % 4]];
                f.sort_unstable();
                faces.insert(f);
            }
        }
        let mut tris: Vec<[u32; 3]> = Vec::new();
        for _ in 0..3000 {
            let t = d.tets[rng.gen_range(0..d.tets.len())];
            let k = rng.gen_range(0..4);
            // a face in some rotation, or a random triple (almost never a face)
            if rng.gen_bool(0.5) {
                tris.push([t[(k + 2) % 4], t[(k + 1) % 4], t[(k + 3) % 4]]);
            } else {
                let mut v = || rng.gen_range(0..300u32);
                let f = [v(), v(), v()];
                if f[0] != f[1] && f[1] != f[2] && f[0] != f[2] {
                    tris.push(f);
                }
            }
        }
        let first_face = tris.iter().position(|t| {
            let mut s = *t;
            s.sort_unstable();
            faces.contains(&s)
        });
        let first_face = first_face.unwrap();
        tris.push(tris[first_face]);
        let got = faces_of_tetrahedra(&d.tets, &tris);
        let mut seen = std::collections::HashSet::new();
        let mut non_faces = 0;
        for (i, t) in tris.iter().enumerate() {
            let mut s = *t;
            s.sort_unstable();
            let is_face = faces.contains(&s);
            non_faces += !is_face as usize;
            // a repeated triangle: only its first copy is trusted
            assert_eq!(got[i], is_face && seen.insert(s), "{i}: {t:?}");
        }
        assert!(
            non_faces > 100 && non_faces < tris.len() - 100,
            "{non_faces}"
        );
        assert!(!got[tris.len() - 1]);
    }

    /// Verdicts do not depend on the absolute scale: a clean closed mesh and one with injected
    /// crossings, multiplied by powers of two (exact) where the predicates' products would under-
    /// or overflow without the rescaling.
    #[test]
    fn verdicts_do_not_depend_on_the_absolute_scale() {
        let (mut pos, mut tris) = sphere(10, 0.05, 4);
        assert!(self_intersections(&pos, &tris, usize::MAX).is_empty());
        let scaled =
            |pos: &[P], s: f64| -> Vec<P> { pos.iter().map(|q| q.map(|x| x * s)).collect() };
        for s in [
            2f64.powi(-1000),
            2f64.powi(-520),
            2f64.powi(480),
            2f64.powi(1000),
        ] {
            assert!(
                self_intersections(&scaled(&pos, s), &tris, usize::MAX).is_empty(),
                "{s:e}"
            );
        }
        let n0 = pos.len() as u32;
        pos.extend([[0.05, 0.02, -2.0], [0.03, 0.06, 2.0], [0.5, 0.5, 0.1]]);
        tris.push([n0, n0 + 1, n0 + 2]);
        let want = self_intersections(&pos, &tris, usize::MAX);
        assert!(want.len() >= 2, "{want:?}");
        for s in [
            2f64.powi(-1000),
            2f64.powi(-520),
            2f64.powi(480),
            2f64.powi(1000),
        ] {
            assert_eq!(
                self_intersections(&scaled(&pos, s), &tris, usize::MAX),
                want,
                "{s:e}"
            );
        }
    }
}
