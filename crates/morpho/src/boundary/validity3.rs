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

use crate::geom::intersect::triangles_meet_beyond_shared;
use crate::geom::predicates::raw::orient3d;
use crate::geom::vec::{cross, dist, dot, sub};

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
/// near 1 ([`crate::geom::exact::power_of_two_scale`]; exact), so that no predicate over- or
/// underflows at extreme absolute scales (1e-300 … 1e300).
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
fn tri_boxes(pos: &[P], tris: &[[u32; 3]]) -> Vec<(P, P)> {
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

/// [`self_intersections`] on triangles in the given order, every pair (sorted, no repeats);
/// pairs of two trusted triangles are skipped when flags are given.
fn self_intersections_ordered(
    pos: &[P],
    tris: &[[u32; 3]],
    trusted: Option<&[bool]>,
) -> Vec<(u32, u32)> {
    use rayon::prelude::*;
    let boxes = tri_boxes(pos, tris);
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for (bl, bh) in &boxes {
        for k in 0..3 {
            lo[k] = lo[k].min(bl[k]);
            hi[k] = hi[k].max(bh[k]);
        }
    }
    // cell: twice the median edge length (the mean is dominated by a few long edges)
    let mut lens: Vec<f64> = tris
        .par_iter()
        .flat_map_iter(|t| {
            let q = t.map(|v| pos[v as usize]);
            (0..3).map(move |k| {
                let (a, b) = (q[k], q[(k + 1) % 3]);
                dist(a, b)
            })
        })
        .collect();
    let mid = lens.len() / 2;
    let mut cell = 2.0 * *lens.select_nth_unstable_by(mid, f64::total_cmp).1;
    drop(lens);
    let ext = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
    if !(cell > 0.0 && cell.is_finite()) {
        // all edges of length 0 (or overflowing): any positive cell will do
        cell = ext
            .iter()
            .copied()
            .filter(|e| e.is_finite())
            .fold(0.0, f64::max);
        if !(cell > 0.0 && cell.is_finite()) {
            cell = 1.0;
        }
    }
    let cells_of = |cell: f64| {
        ext.iter()
            .map(|e| (e / cell).floor() + 1.0)
            .product::<f64>()
    };
    while cells_of(cell) > 8.0 * tris.len() as f64 + 64.0 && (2.0 * cell).is_finite() {
        cell *= 1.5;
    }
    let dims: [u64; 3] = std::array::from_fn(|k| {
        let n = (ext[k] / cell).floor();
        if (0.0..1e15).contains(&n) {
            n as u64 + 1
        } else {
            1
        }
    });
    let cidx = |x: f64, k: usize| -> u64 {
        let c = ((x - lo[k]) / cell).floor();
        if c.is_finite() && c > 0.0 {
            (c as u64).min(dims[k] - 1)
        } else {
            0
        }
    };
    let key = |c: [u64; 3]| c[0] + dims[0] * (c[1] + dims[1] * c[2]);
    // counting sort of (cell, triangle) entries (at most 8n + 64 cells); big triangles apart
    let ncells = (dims[0] * dims[1] * dims[2]) as usize;
    let ranges: Vec<Option<([u64; 3], [u64; 3])>> = boxes
        .par_iter()
        .map(|(bl, bh)| {
            let mn: [u64; 3] = std::array::from_fn(|k| cidx(bl[k], k));
            let mx: [u64; 3] = std::array::from_fn(|k| cidx(bh[k], k));
            let span: u64 = (0..3).map(|k| mx[k] - mn[k] + 1).product();
            (span <= 512).then_some((mn, mx))
        })
        .collect();
    let trusted_at = |i: u32| trusted.is_some_and(|t| t[i as usize]);
    // with trust flags, only the cells an untrusted triangle reaches hold entries: a pair with
    // an untrusted member is tested in a cell of both boxes (below), so one of those cells;
    // an untrusted big triangle walks the whole grid, so then every cell is kept
    let hot: Option<Vec<bool>> = trusted
        .filter(|_| !(0..tris.len() as u32).any(|i| !trusted_at(i) && ranges[i as usize].is_none()))
        .map(|_| {
            let mut hot = vec![false; ncells];
            for (i, r) in ranges.iter().enumerate() {
                if let (false, Some((mn, mx))) = (trusted_at(i as u32), r) {
                    for z in mn[2]..=mx[2] {
                        for y in mn[1]..=mx[1] {
                            for x in mn[0]..=mx[0] {
                                hot[key([x, y, z]) as usize] = true;
                            }
                        }
                    }
                }
            }
            hot
        });
    let kept = |c: u64| hot.as_ref().map_or(true, |h| h[c as usize]);
    let mut start = vec![0usize; ncells + 1];
    let mut big: Vec<u32> = Vec::new();
    for (i, r) in ranges.iter().enumerate() {
        match r {
            None => big.push(i as u32),
            Some((mn, mx)) => {
                for z in mn[2]..=mx[2] {
                    for y in mn[1]..=mx[1] {
                        for x in mn[0]..=mx[0] {
                            let c = key([x, y, z]);
                            if kept(c) {
                                start[c as usize + 1] += 1;
                            }
                        }
                    }
                }
            }
        }
    }
    for c in 0..ncells {
        start[c + 1] += start[c];
    }
    // per entry, which coordinates of the cell equal those of the triangle's low cell (bit k
    // for axis k): a pair sharing the cell owns it iff the two masks cover all three axes
    let mut ids = vec![0u32; start[ncells]];
    let mut masks = vec![0u8; start[ncells]];
    {
        let mut fill = start.clone();
        for (i, r) in ranges.iter().enumerate() {
            if let Some((mn, mx)) = r {
                for z in mn[2]..=mx[2] {
                    for y in mn[1]..=mx[1] {
                        for x in mn[0]..=mx[0] {
                            let c = key([x, y, z]) as usize;
                            if !kept(c as u64) {
                                continue;
                            }
                            ids[fill[c]] = i as u32;
                            masks[fill[c]] = (x == mn[0]) as u8
                                | ((y == mn[1]) as u8) << 1
                                | ((z == mn[2]) as u8) << 2;
                            fill[c] += 1;
                        }
                    }
                }
            }
        }
    }
    drop(ranges);
    let cell_ids = |k: u64| -> &[u32] {
        let k = k as usize;
        &ids[start[k]..start[k + 1]]
    };
    let overlap = |a: u32, b: u32| {
        let ((al, ah), (bl, bh)) = (boxes[a as usize], boxes[b as usize]);
        (0..3).all(|k| al[k] <= bh[k] && bl[k] <= ah[k])
    };
    // corners, vertex ids and plane filter of every triangle side by side, in the spatially
    // coherent order (the pair test then reads two records instead of five scattered ones)
    let recs: Vec<TriRec> = tris
        .par_iter()
        .map(|&t| TriRec::new(t, t.map(|v| pos[v as usize])))
        .collect();
    let bad = |a: u32, b: u32| {
        !(trusted_at(a) && trusted_at(b))
            && pair_meets_filtered(&recs[a as usize], &recs[b as usize])
    };
    let busy: Vec<u64> = (0..ncells as u64)
        .filter(|&c| start[c as usize + 1] - start[c as usize] >= 2)
        .collect();
    // Each pair of triangles sharing a cell is tested in the cell of the low corner of the
    // boxes' intersection, i.e. (cidx is monotone) the larger of the two low cells axis by
    // axis: the cell where, on every axis, one of the two starts. Grouping a cell's entries
    // by their masks enumerates exactly those pairs (masks ma | mb == 0b111).
    let mut bad_pairs: Vec<(u32, u32)> = busy
        .par_iter()
        .with_min_len(64)
        .map_init(Vec::new, |buf: &mut Vec<u32>, &cell_key| {
            let (s, e) = (start[cell_key as usize], start[cell_key as usize + 1]);
            let mut at = [0usize; 9];
            for &m in &masks[s..e] {
                at[m as usize + 1] += 1;
            }
            for m in 0..8 {
                at[m + 1] += at[m];
            }
            buf.clear();
            buf.resize(e - s, 0);
            let mut fill = at;
            for (&id, &m) in ids[s..e].iter().zip(&masks[s..e]) {
                buf[fill[m as usize]] = id;
                fill[m as usize] += 1;
            }
            let group = |m: usize| &buf[at[m]..at[m + 1]];
            let mut found = Vec::new();
            let mut test = |a: u32, b: u32| {
                if overlap(a, b) && bad(a, b) {
                    found.push((a.min(b), a.max(b)));
                }
            };
            let full = group(7);
            for (i, &a) in full.iter().enumerate() {
                for &b in &full[i + 1..] {
                    test(a, b);
                }
            }
            for ma in 0..7 {
                for mb in ma + 1..8 {
                    if ma | mb == 7 {
                        for &a in group(ma) {
                            for &b in group(mb) {
                                test(a, b);
                            }
                        }
                    }
                }
            }
            found
        })
        .flat_map_iter(|f| f)
        .collect();
    // big triangles: against each other by boxes, against the grid through the cells their
    // plane passes (floating-point culling with a generous margin; the exact test decides)
    // (a triangle spanning several cells of the walk is taken once: `seen[b] == a + 1`)
    let big_bad: Vec<(u32, u32)> = big
        .par_iter()
        .enumerate()
        .with_min_len(64)
        .map_init(Vec::new, |seen: &mut Vec<u32>, (i, &a)| {
            if seen.is_empty() {
                seen.resize(tris.len(), 0);
            }
            let mut cand: Vec<u32> = big[i + 1..]
                .iter()
                .copied()
                .filter(|&b| overlap(a, b))
                .collect();
            let q = tris[a as usize].map(|v| pos[v as usize]);
            let n = cross(sub(q[1], q[0]), sub(q[2], q[0]));
            // dominant axis w: the plane is a function of the two other coordinates
            let w = (0..3)
                .max_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
                .unwrap_or(2);
            let (u, v) = ((w + 1) % 3, (w + 2) % 3);
            let (bl, bh) = boxes[a as usize];
            let mn: [u64; 3] = std::array::from_fn(|k| cidx(bl[k], k));
            let mx: [u64; 3] = std::array::from_fn(|k| cidx(bh[k], k));
            let nw = n[w];
            // Each rounded n_k is within 4ε·perm_k of the exact normal N_k (PlaneFilter). With
            // |n_w| ≥ 2⁻¹⁰·Σ perm, the ratios n_u/n_w, n_v/n_w are within ≈ 2¹³ε ≈ 2e-12 of
            // N_u/N_w, N_v/N_w, so the plane's w over the box is off by far less than the
            // margin, which also covers the rounding of the cell coordinates (relative to the
            // coordinates' magnitude, not just the extent: a mesh far from the origin). A
            // thinner triangle (a needle: its rounded normal may be mostly noise) walks the
            // whole w-range of its box.
            let perm = recs[a as usize].f.perm;
            let slope = if nw.abs() >= (perm[0] + perm[1] + perm[2]) * 2f64.powi(-10) {
                (n[u].abs() + n[v].abs()) / nw.abs()
            } else {
                f64::INFINITY
            };
            let mag: f64 = (0..3).map(|k| lo[k].abs().max(hi[k].abs())).sum();
            let margin =
                1e-9 * (0..3).map(|k| ext[k].abs()).sum::<f64>() + 1e-12 * mag + cell * 1e-6;
            let mut grid_cand: Vec<u32> = Vec::new();
            for cu in mn[u]..=mx[u] {
                for cv in mn[v]..=mx[v] {
                    // w-range of the plane over this column (cell centre ± half extent · slope)
                    let (wlo, whi) = if slope.is_finite() {
                        let xu = lo[u] + (cu as f64 + 0.5) * cell;
                        let xv = lo[v] + (cv as f64 + 0.5) * cell;
                        let wc = q[0][w] - (n[u] * (xu - q[0][u]) + n[v] * (xv - q[0][v])) / nw;
                        let half = 0.5 * cell * slope + margin;
                        (
                            cidx((wc - half).max(bl[w]), w).max(mn[w]),
                            cidx((wc + half).min(bh[w]), w).min(mx[w]),
                        )
                    } else {
                        (mn[w], mx[w])
                    };
                    for cw in wlo..=whi {
                        let mut c = [0u64; 3];
                        c[u] = cu;
                        c[v] = cv;
                        c[w] = cw;
                        for &b in cell_ids(key(c)) {
                            if seen[b as usize] != a + 1 {
                                seen[b as usize] = a + 1;
                                if overlap(a, b) {
                                    grid_cand.push(b);
                                }
                            }
                        }
                    }
                }
            }
            cand.extend(grid_cand);
            cand.retain(|&b| bad(a, b));
            cand.iter()
                .map(|&b| (a.min(b), a.max(b)))
                .collect::<Vec<_>>()
        })
        .flat_map_iter(|c| c)
        .collect();
    bad_pairs.extend(big_bad);
    bad_pairs.sort_unstable();
    bad_pairs.dedup();
    bad_pairs
}

/// Every pair of triangles that intersect although they must not, by testing all pairs
/// (O(n²); the oracle of [`self_intersections`] in tests).
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

/// A triangle's floating-point plane for the sign filter of [`pair_meets_filtered`]: a corner
/// `a`, the rounded normal n = (b − a) × (c − a), and per axis the permanent
/// |u_j v_k| + |u_k v_j| of that cross product (u = b − a, v = c − a).
#[derive(Clone, Copy)]
pub(crate) struct PlaneFilter {
    a: P,
    n: P,
    perm: P,
}

impl PlaneFilter {
    pub(crate) fn new(t: [P; 3]) -> Self {
        let (u, v) = (sub(t[1], t[0]), sub(t[2], t[0]));
        let n = cross(u, v);
        let perm = [
            (u[1] * v[2]).abs() + (u[2] * v[1]).abs(),
            (u[2] * v[0]).abs() + (u[0] * v[2]).abs(),
            (u[0] * v[1]).abs() + (u[1] * v[0]).abs(),
        ];
        PlaneFilter { a: t[0], n, perm }
    }

    /// The sign of n · (x − a), i.e. of −orient3d(a, b, c, x) in robust's convention, when its
    /// float evaluation certifies it, else 0 (unknown). Error analysis: each difference, product and sum rounds once (relative ε);
    /// the rounded n_i is within 4ε·perm_i of the exact cross product and the computed sum
    /// within 8ε·Σ perm_i |x_i − a_i| (+ O(ε²)) of the exact determinant. The filter uses
    /// 16ε times that bound, and gives up (0) below 2⁻⁹⁰⁰ (gradual underflow breaks the
    /// relative-error model) and on non-finite values; the exact predicate decides then.
    #[inline]
    pub(crate) fn side(&self, x: P) -> i8 {
        let w = sub(x, self.a);
        let s = dot(self.n, w);
        let b = self.perm[0] * w[0].abs() + self.perm[1] * w[1].abs() + self.perm[2] * w[2].abs();
        let bound = 16.0 * f64::EPSILON * b;
        if !(bound.is_finite() && s.is_finite()) || b < 1e-270 {
            return 0;
        }
        if s > bound {
            1
        } else if s < -bound {
            -1
        } else {
            0
        }
    }

    /// Every given point is certainly strictly on one side (the same for all) of the plane.
    #[inline]
    fn all_one_side(&self, xs: &[P]) -> bool {
        let s0 = self.side(xs[0]);
        s0 != 0 && xs[1..].iter().all(|&x| self.side(x) == s0)
    }
}

/// One triangle for [`pair_meets_filtered`]: its vertex ids, its other two corners and the
/// plane filter (which holds the first corner).
#[derive(Clone, Copy)]
pub(crate) struct TriRec {
    f: PlaneFilter,
    bc: [P; 2],
    v: [u32; 3],
}

impl TriRec {
    pub(crate) fn new(v: [u32; 3], p: [P; 3]) -> Self {
        TriRec {
            f: PlaneFilter::new(p),
            bc: [p[1], p[2]],
            v,
        }
    }

    #[inline]
    fn corner(&self, k: usize) -> P {
        if k == 0 {
            self.f.a
        } else {
            self.bc[k - 1]
        }
    }

    #[inline]
    fn corners(&self) -> [P; 3] {
        [self.f.a, self.bc[0], self.bc[1]]
    }
}

/// [`pair_meets`] behind a floating-point filter: the pair is cleared without exact arithmetic
/// when the other triangle's corners that are not shared lie certainly strictly on one side of
/// one triangle's plane (then the two meet at most in their shared vertices or edge; for a
/// common edge abc/abd, d strictly off plane abc rules out a fold). Undecided pairs go to the
/// exact test, so the verdict always equals [`pair_meets`].
fn pair_meets_filtered(ta: &TriRec, tb: &TriRec) -> bool {
    let mut pts_b = [[0.0; 3]; 3];
    let mut nb = 0;
    for k in 0..3 {
        if !ta.v.contains(&tb.v[k]) {
            pts_b[nb] = tb.corner(k);
            nb += 1;
        }
    }
    if nb == 0 {
        // every id of tb is one of ta's: the same triangle, or a face repeating an id (a
        // segment or point of ta's), which the exact test decides
        return pair_meets_at(ta.v, tb.v, ta.corners(), tb.corners());
    }
    if nb == 3 {
        // no common vertex: certified signs of each triangle's corners against the other's plane
        let (pa, pb) = (ta.corners(), tb.corners());
        let (u0, u1, u2) = (ta.f.side(pb[0]), ta.f.side(pb[1]), ta.f.side(pb[2]));
        if u0 != 0 && u0 == u1 && u1 == u2 {
            return false;
        }
        let (t0, t1, t2) = (tb.f.side(pa[0]), tb.f.side(pa[1]), tb.f.side(pa[2]));
        if t0 != 0 && t0 == t1 && t1 == t2 {
            return false;
        }
        if u0 != 0 && u1 != 0 && u2 != 0 && t0 != 0 && t1 != 0 && t2 != 0 {
            return crossing_triangles_meet(pa, [t0, t1, t2], pb, [u0, u1, u2]);
        }
        return pair_meets_at(ta.v, tb.v, pa, pb);
    }
    if ta.f.all_one_side(&pts_b[..nb]) {
        return false;
    }
    if nb < 3 {
        // a common vertex: the other direction; a common edge: d on the plane or undecided
        if nb == 2 {
            let mut pts_a = [[0.0; 3]; 2];
            let mut na = 0;
            for k in 0..3 {
                if !tb.v.contains(&ta.v[k]) && na < 2 {
                    pts_a[na] = ta.corner(k);
                    na += 1;
                }
            }
            if na == 2 && tb.f.all_one_side(&pts_a) {
                return false;
            }
        }
    } else if tb.f.all_one_side(&ta.corners()) {
        return false;
    }
    pair_meets_at(ta.v, tb.v, ta.corners(), tb.corners())
}

/// Triangles t and u, each with its corners strictly on both sides of the other's plane
/// (`st`: the signs of t's corners against u's plane, `su`: of u's against t's, all nonzero
/// and not all equal, as [`PlaneFilter::side`] certifies them), intersect (exact).
///
/// Guigue & Devillers 2003 ("Fast and robust triangle–triangle overlap test using orientation
/// predicates", §3): both triangles meet the line L of the two planes in a segment; t's runs
/// between its two edges from the corner p₁ alone on its side of u's plane, u's between the
/// edges from p₂. With p₁ on the positive side of u and p₂ on the positive side of t in the
/// sense of [`PlaneFilter::side`] (n · (x − a) > 0; swap the other two corners, i.e. reverse
/// the orientation, when not), the two segments overlap iff orient3d(p₁, q₁, p₂, q₂) ≥ 0 and
/// orient3d(p₁, r₁, r₂, p₂) ≥ 0 (the paper's ≤ 0 with its opposite orientation convention):
/// two exact predicates in place of the up to thirty of [`triangles_intersect`] (= 0 is a
/// touching, which counts).
fn crossing_triangles_meet(t: [P; 3], st: [i8; 3], u: [P; 3], su: [i8; 3]) -> bool {
    // the corner whose sign differs from the two others'
    let alone = |s: [i8; 3]| {
        if s[0] == s[1] {
            2
        } else if s[0] == s[2] {
            1
        } else {
            0
        }
    };
    let (i, j) = (alone(st), alone(su));
    let (p1, mut q1, mut r1) = (t[i], t[(i + 1) % 3], t[(i + 2) % 3]);
    let (p2, mut q2, mut r2) = (u[j], u[(j + 1) % 3], u[(j + 2) % 3]);
    if st[i] < 0 {
        std::mem::swap(&mut q2, &mut r2);
    }
    if su[j] < 0 {
        std::mem::swap(&mut q1, &mut r1);
    }
    orient3d(p1, q1, p2, q2) >= 0.0 && orient3d(p1, r1, r2, p2) >= 0.0
}

/// The exact test of one pair by its number of common vertices (see the module documentation).
fn pair_meets(pos: &[P], ta: [u32; 3], tb: [u32; 3]) -> bool {
    pair_meets_at(
        ta,
        tb,
        ta.map(|v| pos[v as usize]),
        tb.map(|v| pos[v as usize]),
    )
}

/// [`pair_meets`] with the corners given (`pa`, `pb`: the positions of `ta`, `tb`).
fn pair_meets_at(ta: [u32; 3], tb: [u32; 3], pa: [P; 3], pb: [P; 3]) -> bool {
    triangles_meet_beyond_shared(ta, pa, tb, pb)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::intersect::triangles_intersect;

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

    /// An m × m grid of the unit square mapped by `f`, two triangles per square.
    fn grid_sheet(m: usize, f: impl Fn(f64, f64) -> P) -> (Vec<P>, Vec<[u32; 3]>) {
        let mut pos = Vec::new();
        for j in 0..=m {
            for i in 0..=m {
                pos.push(f(i as f64 / m as f64, j as f64 / m as f64));
            }
        }
        let id = |i: usize, j: usize| (j * (m + 1) + i) as u32;
        let mut tris = Vec::new();
        for j in 0..m {
            for i in 0..m {
                tris.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                tris.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        (pos, tris)
    }

    /// Big needles (a corner within 1e-5 … 1e-15 of the opposite edge, so that the rounded
    /// normal is mostly noise) and big triangles far from the origin relative to their size are
    /// found through the grid walk like any other: compared with all pairs by brute force.
    #[test]
    fn big_needles_and_offset_meshes_are_walked_conservatively() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(9);
        let m = 40;
        for (round, off) in [0.0, 0.0, 0.0, 1e3, 1e6].into_iter().enumerate() {
            // a wavy sheet (not planar: the needle's bad plane must not line up with it)
            let (mut pos, mut tris) = grid_sheet(m, |x, y| {
                [
                    x + off,
                    y + off,
                    0.05 * (7.0 * x).sin() * (5.0 * y).cos() + off,
                ]
            });
            for _ in 0..6 {
                let a: P = [rng.gen_range(0.0..0.3), rng.gen_range(0.0..1.0), -0.7];
                let b: P = [rng.gen_range(0.7..1.0), rng.gen_range(0.0..1.0), 0.6];
                let eps = 10f64.powi(-rng.gen_range(5..=15));
                let dir: P = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
                let t = rng.gen_range(0.2..0.8);
                let c: P = std::array::from_fn(|k| a[k] + t * (b[k] - a[k]) + eps * dir[k]);
                let n0 = pos.len() as u32;
                pos.extend([a, b, c].map(|q| q.map(|x| x + off)));
                tris.push([n0, n0 + 1, n0 + 2]);
            }
            let found = self_intersections(&pos, &tris, usize::MAX);
            let expect = self_intersections_brute(&pos, &tris);
            assert!(expect.len() >= 6, "round {round}: {}", expect.len());
            assert_eq!(found, expect, "round {round}");
        }
    }

    #[test]
    fn big_triangles_are_tested_through_the_cells_of_their_plane() {
        // a fine flat grid mesh on z = 0 and big triangles spanning it
        let m = 60;
        let (mut pos, mut tris) = grid_sheet(m, |x, y| [x, y, 0.0]);
        let n0 = pos.len() as u32;
        // vertical, slanted big triangle piercing the sheet along a segment
        pos.extend([[0.013, 0.021, -1.0], [0.977, 0.963, -1.0], [0.5, 0.4, 1.0]]);
        // a big one parallel above it, and a big one crossing the first
        pos.extend([[0.0, 0.0, 0.5], [1.0, 0.0, 0.5], [0.0, 1.0, 0.5]]);
        let nt = tris.len() as u32;
        tris.push([n0, n0 + 1, n0 + 2]);
        tris.push([n0 + 3, n0 + 4, n0 + 5]);
        let found = self_intersections(&pos, &tris, usize::MAX);
        // brute force over every pair involving the two big triangles
        let mut expect = Vec::new();
        for big in [nt, nt + 1] {
            let pb = tris[big as usize].map(|v| pos[v as usize]);
            for (k, t) in tris.iter().enumerate() {
                let k = k as u32;
                if k == big || (k > nt + 1) || (k == nt && big == nt + 1) {
                    continue;
                }
                if triangles_intersect(t.map(|v| pos[v as usize]), pb) {
                    expect.push((k.min(big), k.max(big)));
                }
            }
        }
        expect.sort_unstable();
        expect.dedup();
        assert!(expect.len() >= 40, "{}", expect.len());
        assert_eq!(found, expect);
    }

    /// A closed UV sphere (`m` × `m` quads, poles fanned), every vertex perturbed by up to
    /// `noise` (deterministic).
    fn sphere(m: usize, noise: f64, seed: u64) -> (Vec<P>, Vec<[u32; 3]>) {
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

    #[test]
    fn grid_check_agrees_with_all_pairs_on_random_triangle_soups() {
        use rand::SeedableRng;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        for round in 0..6 {
            let (pos, tris) = soup(&mut rng, round % 2 == 0);
            let found = self_intersections(&pos, &tris, usize::MAX);
            let expect = self_intersections_brute(&pos, &tris);
            assert!(expect.len() > 5, "round {round}: {}", expect.len());
            let missing: Vec<_> = expect.iter().filter(|x| !found.contains(x)).collect();
            let extra: Vec<_> = found.iter().filter(|x| !expect.contains(x)).collect();
            for &&(a, b) in &missing {
                eprintln!(
                    "{:?} {:?}",
                    tris[a as usize].map(|v| pos[v as usize]),
                    tris[b as usize].map(|v| pos[v as usize])
                );
            }
            assert!(
                missing.is_empty() && extra.is_empty(),
                "round {round}: missing {missing:?} extra {extra:?}"
            );
            // the limit keeps the smallest pairs
            assert_eq!(self_intersections(&pos, &tris, 3), expect[..3].to_vec());
        }
    }

    /// 250 random triangles over 200 points, mostly small (corners drawn near the first), every
    /// 40th big; integer coordinates (coplanar and touching cases) or not; corners shared by
    /// drawing them from the pool; the fourth triangle repeated at the end.
    fn soup(rng: &mut rand_chacha::ChaCha8Rng, integer: bool) -> (Vec<P>, Vec<[u32; 3]>) {
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

    /// The two-predicate test of crossing triangles ([`crossing_triangles_meet`], reached from
    /// [`pair_meets_filtered`] when no corner is shared and all six filtered signs are certain)
    /// agrees with the exact [`triangles_intersect`]: random pairs of nearby triangles, integer
    /// grids (touching configurations: the two final predicates are 0), the same nudged by a few
    /// ulps, corners rounded onto the other's plane (near-coplanar: the filter's bound is what
    /// keeps float signs from being trusted; with ε/4 instead of 16ε this test fails), at scales
    /// 2^-400 … 2^400. Counts make sure the shortcut itself decided many pairs,
    /// both ways.
    #[test]
    fn crossing_pair_shortcut_agrees_with_the_exact_test() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(77);
        let (mut short_hit, mut short_miss) = (0, 0);
        for round in 0..12 {
            let scale = 2f64.powi([0, -400, 400, 7][round % 4]);
            for _ in 0..20_000 {
                let pt = |rng: &mut rand_chacha::ChaCha8Rng| -> P {
                    std::array::from_fn(|_| match round / 4 {
                        0 => rng.gen_range(0..4) as f64,
                        _ => {
                            let x = rng.gen_range(0..4) as f64 + 0.5;
                            let k = rng.gen_range(-3i64..=3);
                            if rng.gen_bool(0.5) {
                                f64::from_bits((x.to_bits() as i64 + k) as u64)
                            } else {
                                rng.gen_range(0.0..4.0)
                            }
                        }
                    })
                };
                let t: [P; 3] = std::array::from_fn(|_| pt(&mut rng).map(|x| x * scale));
                let mut u: [P; 3] = std::array::from_fn(|_| pt(&mut rng).map(|x| x * scale));
                if round / 4 == 2 {
                    // near-coplanar: u's corners are rounded points of t's plane (the float
                    // signs are noise of the order of the filter's bound)
                    for q in u.iter_mut().take(rng.gen_range(1..=3)) {
                        let (al, be): (f64, f64) =
                            (rng.gen_range(-0.5..1.5), rng.gen_range(-0.5..1.5));
                        *q = std::array::from_fn(|k| {
                            t[0][k] + al * (t[1][k] - t[0][k]) + be * (t[2][k] - t[0][k])
                        });
                    }
                }
                let (ra, rb) = (TriRec::new([0, 1, 2], t), TriRec::new([3, 4, 5], u));
                let exact = triangles_intersect(t, u);
                assert_eq!(pair_meets_filtered(&ra, &rb), exact, "{t:?} {u:?}");
                assert_eq!(pair_meets_filtered(&rb, &ra), exact, "{t:?} {u:?}");
                let su = u.map(|x| ra.f.side(x));
                let st = t.map(|x| rb.f.side(x));
                let straddle =
                    |s: [i8; 3]| s.iter().all(|&x| x != 0) && s.iter().any(|&x| x != s[0]);
                if straddle(su) && straddle(st) {
                    assert_eq!(crossing_triangles_meet(t, st, u, su), exact);
                    assert_eq!(crossing_triangles_meet(u, su, t, st), exact);
                    if exact {
                        short_hit += 1;
                    } else {
                        short_miss += 1;
                    }
                }
            }
        }
        assert!(
            short_hit > 5000 && short_miss > 5000,
            "{short_hit} {short_miss}"
        );
    }

    /// The exact pair test is symmetric, and the floating-point plane filter never changes its
    /// verdict: integer points (coplanar, collinear, duplicate positions), and the same points
    /// nudged by a few ulps (near-coplanar: float signs of n·(x − a) go wrong without the bound).
    #[test]
    fn pair_test_is_symmetric_and_the_filter_agrees_with_it() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(21);
        for nudge in [false, true] {
            let mut pos: Vec<P> = (0..24)
                .map(|_| std::array::from_fn(|_| rng.gen_range(0..4) as f64 * 1e3 + 0.5))
                .collect();
            // duplicate positions under other indices
            for i in 0..6 {
                pos.push(pos[i]);
            }
            if nudge {
                for q in pos.iter_mut().skip(3) {
                    for x in q.iter_mut() {
                        let k = rng.gen_range(-3i64..=3);
                        *x = f64::from_bits((x.to_bits() as i64 + k) as u64);
                    }
                }
            }
            let n = pos.len() as u32;
            let (mut meets, mut clear) = (0, 0);
            for _ in 0..20_000 {
                let ta: [u32; 3] = std::array::from_fn(|_| rng.gen_range(0..n));
                let mut tb: [u32; 3] = std::array::from_fn(|_| rng.gen_range(0..n));
                // share 0, 1 or 2 vertices (by index) often
                for k in 0..rng.gen_range(0..3) {
                    tb[k] = ta[(k + 1) % 3];
                }
                // (repeated ids, faces without area, are kept: issue 17 item 5)
                let ab = pair_meets(&pos, ta, tb);
                assert_eq!(ab, pair_meets(&pos, tb, ta), "{ta:?} {tb:?}");
                let (fa, fb) = (
                    TriRec::new(ta, ta.map(|v| pos[v as usize])),
                    TriRec::new(tb, tb.map(|v| pos[v as usize])),
                );
                assert_eq!(ab, pair_meets_filtered(&fa, &fb), "{ta:?} {tb:?}");
                if ab {
                    meets += 1;
                } else {
                    clear += 1;
                }
            }
            assert!(meets > 1000 && clear > 1000, "{meets} {clear}");
        }
    }

    #[test]
    fn grid_check_agrees_with_all_pairs_on_perturbed_closed_meshes() {
        for (seed, noise) in [(1u64, 0.0), (2, 0.01), (3, 0.2)] {
            let (mut pos, mut tris) = sphere(14, noise, seed);
            let clean = self_intersections_brute(&pos, &tris);
            assert_eq!(self_intersections(&pos, &tris, usize::MAX), clean);
            if noise == 0.0 {
                assert!(clean.is_empty());
            }
            // injected: a spike through the surface, a flap folded onto a face, a triangle
            // through a vertex, a big triangle cutting the sphere
            let n0 = pos.len() as u32;
            pos.extend([
                [0.05, 0.02, -2.0],
                [0.03, 0.06, 2.0],
                [0.5, 0.5, 0.1],
                [0.0, 0.0, 0.0],
                [-3.0, -3.0, 0.05],
                [3.0, -3.0, 0.05],
                [0.0, 3.0, 0.05],
            ]);
            tris.push([n0, n0 + 1, n0 + 2]);
            let f = tris[40];
            let (a, b, c) = (pos[f[0] as usize], pos[f[1] as usize], pos[f[2] as usize]);
            pos.push(std::array::from_fn(|k| (a[k] + b[k] + 2.0 * c[k]) / 4.0));
            let flap = pos.len() as u32 - 1;
            tris.push([f[0], f[1], flap]);
            tris.push([n0 + 3, f[0], n0 + 2]);
            tris.push([n0 + 4, n0 + 5, n0 + 6]);
            let found = self_intersections(&pos, &tris, usize::MAX);
            let expect = self_intersections_brute(&pos, &tris);
            assert!(
                expect.len() >= clean.len() + 20,
                "{} {}",
                expect.len(),
                clean.len()
            );
            assert_eq!(found, expect, "seed {seed}");
        }
    }
}
