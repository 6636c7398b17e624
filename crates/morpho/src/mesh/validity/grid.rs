//! The broad phase of [`super::self_intersections`] on triangles in a spatially coherent order,
//! in six steps: the uniform grid ([`CellGrid::new`]: cell twice the median edge length,
//! coarsened to at most 8n + 64 cells), each triangle's cell range ([`CellGrid::ranges`];
//! triangles over more than 512 cells are "big"), the cells an untrusted triangle reaches
//! ([`hot_cells`]), the counting sort of (cell, triangle) entries with their low-cell masks
//! ([`fill_cells`]), the pairs sharing a cell, each tested once in the cell of the low corner
//! of the boxes' intersection ([`cell_pairs`]), and the big triangles, tested against each other
//! by boxes and against the cells their plane passes ([`big_pairs`]). Cells and big triangles
//! are processed in parallel (rayon); the result does not depend on the thread count.

use super::mesh::tri_boxes;
use super::pair::{pair_meets_filtered, TriRec};
use crate::geom::vec::{cross, dist, sub};
use rayon::prelude::*;

type P = [f64; 3];

/// Cell range (low and high cell per axis) of a box.
type Range = ([u64; 3], [u64; 3]);

/// [`super::self_intersections`] on triangles in the given order, every pair (sorted, no
/// repeats); pairs of two trusted triangles are skipped when flags are given.
pub(super) fn self_intersections_ordered(
    pos: &[P],
    tris: &[[u32; 3]],
    trusted: Option<&[bool]>,
) -> Vec<(u32, u32)> {
    let boxes = tri_boxes(pos, tris);
    // 1. the grid; 2. the cell range of every box
    let grid = CellGrid::new(pos, tris, &boxes);
    let ranges = grid.ranges(&boxes);
    let trusted_at = |i: u32| trusted.is_some_and(|t| t[i as usize]);
    // 3. the cells that matter; 4. their entries
    let hot = hot_cells(&grid, &ranges, trusted);
    let cells = fill_cells(&grid, &ranges, hot.as_deref());
    drop(ranges);
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
    // 5. the pairs sharing a cell; 6. the big triangles
    let mut bad_pairs = cell_pairs(&cells, &overlap, &bad);
    let big_bad = big_pairs(&grid, &cells, pos, tris, &boxes, &recs, &overlap, &bad);
    bad_pairs.extend(big_bad);
    bad_pairs.sort_unstable();
    bad_pairs.dedup();
    bad_pairs
}

/// The uniform grid over the triangles' boxes.
struct CellGrid {
    lo: P,
    hi: P,
    /// The extent of the boxes.
    ext: P,
    cell: f64,
    dims: [u64; 3],
}

impl CellGrid {
    /// Step 1: the bounding box of the boxes; the cell twice the median edge length (the mean
    /// is dominated by a few long edges), any positive size when every edge has length 0 (or
    /// overflows), coarsened by 1.5 until the grid has at most 8n + 64 cells.
    fn new(pos: &[P], tris: &[[u32; 3]], boxes: &[(P, P)]) -> Self {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for (bl, bh) in boxes {
            for k in 0..3 {
                lo[k] = lo[k].min(bl[k]);
                hi[k] = hi[k].max(bh[k]);
            }
        }
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
        CellGrid {
            lo,
            hi,
            ext,
            cell,
            dims,
        }
    }

    /// The cell of coordinate `x` on axis `k`, clamped to the grid (monotone in `x`).
    #[inline]
    fn cidx(&self, x: f64, k: usize) -> u64 {
        let c = ((x - self.lo[k]) / self.cell).floor();
        if c.is_finite() && c > 0.0 {
            (c as u64).min(self.dims[k] - 1)
        } else {
            0
        }
    }

    #[inline]
    fn key(&self, c: [u64; 3]) -> u64 {
        c[0] + self.dims[0] * (c[1] + self.dims[1] * c[2])
    }

    fn ncells(&self) -> usize {
        (self.dims[0] * self.dims[1] * self.dims[2]) as usize
    }

    /// The cell range of a box.
    fn range(&self, (bl, bh): &(P, P)) -> Range {
        (
            std::array::from_fn(|k| self.cidx(bl[k], k)),
            std::array::from_fn(|k| self.cidx(bh[k], k)),
        )
    }

    /// Step 2: the cell range of every box; `None` for a big triangle (over 512 cells).
    fn ranges(&self, boxes: &[(P, P)]) -> Vec<Option<Range>> {
        boxes
            .par_iter()
            .map(|b| {
                let (mn, mx) = self.range(b);
                let span: u64 = (0..3).map(|k| mx[k] - mn[k] + 1).product();
                (span <= 512).then_some((mn, mx))
            })
            .collect()
    }
}

/// Calls `f` with every cell of a range.
#[inline]
fn for_cells(grid: &CellGrid, (mn, mx): &Range, mut f: impl FnMut(u64, [u64; 3])) {
    for z in mn[2]..=mx[2] {
        for y in mn[1]..=mx[1] {
            for x in mn[0]..=mx[0] {
                f(grid.key([x, y, z]), [x, y, z]);
            }
        }
    }
}

/// Step 3: with trust flags, only the cells an untrusted triangle reaches hold entries (a pair
/// with an untrusted member is tested in a cell of both boxes, so one of those cells); `None`
/// (every cell kept) without flags or when an untrusted big triangle walks the whole grid.
fn hot_cells(
    grid: &CellGrid,
    ranges: &[Option<Range>],
    trusted: Option<&[bool]>,
) -> Option<Vec<bool>> {
    let trusted = trusted?;
    if (0..ranges.len()).any(|i| !trusted[i] && ranges[i].is_none()) {
        return None;
    }
    let mut hot = vec![false; grid.ncells()];
    for (i, r) in ranges.iter().enumerate() {
        if let (false, Some(r)) = (trusted[i], r) {
            for_cells(grid, r, |c, _| hot[c as usize] = true);
        }
    }
    Some(hot)
}

/// The (cell, triangle) entries, counting-sorted by cell.
struct Cells {
    /// Entries of cell c: `start[c]..start[c + 1]`.
    start: Vec<usize>,
    ids: Vec<u32>,
    /// Per entry, which coordinates of the cell equal those of the triangle's low cell (bit k
    /// for axis k): a pair sharing the cell owns it iff the two masks cover all three axes.
    masks: Vec<u8>,
    /// The big triangles (no entries).
    big: Vec<u32>,
}

impl Cells {
    fn of(&self, k: u64) -> &[u32] {
        let k = k as usize;
        &self.ids[self.start[k]..self.start[k + 1]]
    }
}

/// Step 4: the counting sort of the entries in the kept cells (all cells when `hot` is
/// `None`), with their masks.
fn fill_cells(grid: &CellGrid, ranges: &[Option<Range>], hot: Option<&[bool]>) -> Cells {
    let ncells = grid.ncells();
    let kept = |c: u64| hot.map_or(true, |h| h[c as usize]);
    let mut start = vec![0usize; ncells + 1];
    let mut big: Vec<u32> = Vec::new();
    for (i, r) in ranges.iter().enumerate() {
        match r {
            None => big.push(i as u32),
            Some(r) => for_cells(grid, r, |c, _| {
                if kept(c) {
                    start[c as usize + 1] += 1;
                }
            }),
        }
    }
    for c in 0..ncells {
        start[c + 1] += start[c];
    }
    let mut ids = vec![0u32; start[ncells]];
    let mut masks = vec![0u8; start[ncells]];
    let mut fill = start.clone();
    for (i, r) in ranges.iter().enumerate() {
        if let Some(r @ (mn, _)) = r {
            for_cells(grid, r, |c, [x, y, z]| {
                let c = c as usize;
                if !kept(c as u64) {
                    return;
                }
                ids[fill[c]] = i as u32;
                masks[fill[c]] =
                    (x == mn[0]) as u8 | ((y == mn[1]) as u8) << 1 | ((z == mn[2]) as u8) << 2;
                fill[c] += 1;
            });
        }
    }
    Cells {
        start,
        ids,
        masks,
        big,
    }
}

/// Step 5: each pair of triangles sharing a cell is tested in the cell of the low corner of
/// the boxes' intersection, i.e. (`cidx` is monotone) the larger of the two low cells axis by
/// axis: the cell where, on every axis, one of the two starts. Grouping a cell's entries by
/// their masks enumerates exactly those pairs (masks ma | mb == 0b111).
fn cell_pairs(
    cells: &Cells,
    overlap: &(impl Fn(u32, u32) -> bool + Sync),
    bad: &(impl Fn(u32, u32) -> bool + Sync),
) -> Vec<(u32, u32)> {
    let (start, ids, masks) = (&cells.start, &cells.ids, &cells.masks);
    let busy: Vec<u64> = (0..start.len() as u64 - 1)
        .filter(|&c| start[c as usize + 1] - start[c as usize] >= 2)
        .collect();
    busy.par_iter()
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
        .collect()
}

/// Step 6: big triangles, against each other by boxes, against the grid through the cells
/// their plane passes (floating-point culling with a generous margin; the exact test decides;
/// a triangle spanning several cells of the walk is taken once: `seen[b] == a + 1`).
#[allow(clippy::too_many_arguments)]
fn big_pairs(
    grid: &CellGrid,
    cells: &Cells,
    pos: &[P],
    tris: &[[u32; 3]],
    boxes: &[(P, P)],
    recs: &[TriRec],
    overlap: &(impl Fn(u32, u32) -> bool + Sync),
    bad: &(impl Fn(u32, u32) -> bool + Sync),
) -> Vec<(u32, u32)> {
    let big = &cells.big;
    let (lo, hi, ext, cell) = (grid.lo, grid.hi, grid.ext, grid.cell);
    big.par_iter()
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
            let (mn, mx) = grid.range(&boxes[a as usize]);
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
                            grid.cidx((wc - half).max(bl[w]), w).max(mn[w]),
                            grid.cidx((wc + half).min(bh[w]), w).min(mx[w]),
                        )
                    } else {
                        (mn[w], mx[w])
                    };
                    for cw in wlo..=whi {
                        let mut c = [0u64; 3];
                        c[u] = cu;
                        c[v] = cv;
                        c[w] = cw;
                        for &b in cells.of(grid.key(c)) {
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
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::intersect::triangles_intersect;

    use super::super::mesh::tests::{soup, sphere};
    use super::super::mesh::{self_intersections, self_intersections_brute};

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
