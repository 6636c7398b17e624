//! [`TriGrid`]: the general engine's grids of triangle boxes (the live non-boundary triangles
//! and the boundary faces, [`super::general::General3`]; V §5.3 removability needs the
//! triangles near a tetrahedron). The same cells, levels and answers as the kernel's
//! [`BoxGrid`] (an id registered in every cell its box meets; boxes spanning more than
//! [`BoxGrid::MAX_SPAN`] cells on a coarser level, cells [`BoxGrid::COARSEN`]× wider, up to
//! [`BoxGrid::LEVELS`] levels, beyond that in a list every query returns), stored differently:
//! the boxes of the bulk construction ([`TriGrid::insert_many`], hundreds of thousands of
//! boundary faces at once) go into one flat array in a CSR layout over blocks of 8×8×8 cells
//! (built by a counting sort in O(entries), without a list per cell and without hashing), and
//! only the boxes inserted later one by one ([`TriGrid::insert`]) into a hash map of lists.
//!
//! The order in which ids come is unspecified ([`TriGrid::query`] sorts and deduplicates;
//! [`TriGrid::any_in_box`] is for predicates whose answer does not depend on it). The crossing
//! search and the boundary-hit test use [`super::crosstree::BoxIndex`] instead.

use crate::geom::grid::{BoxGrid, Cell};
use crate::util::{IdMap, NONE};

type P = [f64; 3];
type C = [i64; 3];
type G = BoxGrid<3>;

/// A grid's ids per `(level, cell)` (tests).
#[cfg(test)]
type Contents = std::collections::BTreeMap<(usize, C), Vec<u32>>;

/// Cells per block axis (as a shift) and per block.
const SHIFT: u32 = 3;
const MASK: i64 = (1 << SHIFT) - 1;
const BLOCK: usize = 1 << (3 * SHIFT);

/// The entries of a bulk construction: for every cell of the blocks that hold one, the ids of
/// its boxes (CSR); cells outside `[c0, c1]` or in an empty block hold none.
#[derive(Debug)]
struct Blocked {
    c0: C,
    c1: C,
    /// Blocks per axis.
    bdims: [usize; 3],
    /// Block → its slot in `start` (or `NONE`: no entry).
    dir: Vec<u32>,
    /// Slot · [`BLOCK`] + cell within the block → first entry (one more at the end).
    start: Vec<u32>,
    ids: Vec<u32>,
}

impl Blocked {
    /// The entry index of cell `c` (inside `[c0, c1]`) or `None` in an empty block.
    #[inline]
    fn index(&self, c: C) -> Option<usize> {
        let r: C = std::array::from_fn(|k| c[k] - self.c0[k]);
        let b = ((r[0] >> SHIFT) as usize * self.bdims[1] + (r[1] >> SHIFT) as usize)
            * self.bdims[2]
            + (r[2] >> SHIFT) as usize;
        let slot = self.dir[b];
        if slot == NONE {
            return None;
        }
        let local =
            (((r[0] & MASK) << (2 * SHIFT)) | ((r[1] & MASK) << SHIFT) | (r[2] & MASK)) as usize;
        Some(slot as usize * BLOCK + local)
    }

    /// The ids of cell `c` (inside `[c0, c1]`).
    #[inline]
    fn cell(&self, c: C) -> &[u32] {
        match self.index(c) {
            Some(i) => &self.ids[self.start[i] as usize..self.start[i + 1] as usize],
            None => &[],
        }
    }

    /// Calls `f` on the ids of every cell from `a` to `b` (clipped to the block range),
    /// skipping empty blocks whole, until it returns true.
    fn any(&self, a: C, b: C, f: &mut dyn FnMut(u32) -> bool) -> bool {
        let lo: C = std::array::from_fn(|k| a[k].max(self.c0[k]));
        let hi: C = std::array::from_fn(|k| b[k].min(self.c1[k]));
        if (0..3).any(|k| lo[k] > hi[k]) {
            return false;
        }
        let blo: C = std::array::from_fn(|k| (lo[k] - self.c0[k]) >> SHIFT);
        let bhi: C = std::array::from_fn(|k| (hi[k] - self.c0[k]) >> SHIFT);
        for bx in blo[0]..=bhi[0] {
            for by in blo[1]..=bhi[1] {
                for bz in blo[2]..=bhi[2] {
                    let bi =
                        (bx as usize * self.bdims[1] + by as usize) * self.bdims[2] + bz as usize;
                    if self.dir[bi] == NONE {
                        continue;
                    }
                    let bc = [bx, by, bz];
                    // the cells of this block inside [lo, hi]
                    let r: [(i64, i64); 3] = std::array::from_fn(|k| {
                        let s = self.c0[k] + (bc[k] << SHIFT);
                        (lo[k].max(s), hi[k].min(s + MASK))
                    });
                    for x in r[0].0..=r[0].1 {
                        for y in r[1].0..=r[1].1 {
                            for z in r[2].0..=r[2].1 {
                                if self.cell([x, y, z]).iter().any(|&i| f(i)) {
                                    return true;
                                }
                            }
                        }
                    }
                }
            }
        }
        false
    }
}

/// A uniform grid of triangle ids by bounding box (see the module documentation).
#[derive(Debug)]
pub(super) struct TriGrid {
    lo: P,
    cell: f64,
    bulk: Option<Blocked>,
    /// Boxes inserted one by one (and bulk constructions that fit no block layout).
    cells: IdMap<Cell<3>, Vec<u32>>,
    big: Vec<u32>,
    coarse: Option<Box<TriGrid>>,
    level: usize,
}

impl TriGrid {
    /// An empty grid with cells of size `cell` (1 when not positive and finite) from the
    /// origin `lo`, as [`BoxGrid::new`].
    pub(super) fn new(lo: P, cell: f64) -> Self {
        TriGrid {
            lo,
            cell: if cell > 0.0 && cell.is_finite() {
                cell
            } else {
                1.0
            },
            bulk: None,
            cells: IdMap::default(),
            big: Vec::new(),
            coarse: None,
            level: 0,
        }
    }

    /// The cell size of the finest level.
    #[cfg(test)]
    pub(super) fn cell(&self) -> f64 {
        self.cell
    }

    /// The cells of the box `[lo, hi]` on this level ([`BoxGrid::range`]).
    pub(super) fn range(&self, lo: P, hi: P) -> (C, C) {
        let c = |x: f64, k: usize| ((x - self.lo[k]) / self.cell).floor() as i64;
        (
            std::array::from_fn(|k| c(lo[k], k)),
            std::array::from_fn(|k| c(hi[k], k)),
        )
    }

    /// Registers `id` in every cell of this level meeting the box, or on a coarser level when
    /// the box spans more than [`BoxGrid::MAX_SPAN`] cells ([`BoxGrid::insert`]).
    pub(super) fn insert(&mut self, id: u32, lo: P, hi: P) {
        let (a, b) = self.range(lo, hi);
        if G::span(a, b) > G::MAX_SPAN {
            if self.level + 1 < G::LEVELS && (self.cell * G::COARSEN).is_finite() {
                let (origin, cell, level) = (self.lo, self.cell * G::COARSEN, self.level + 1);
                self.coarse
                    .get_or_insert_with(|| {
                        let mut g = TriGrid::new(origin, cell);
                        g.level = level;
                        Box::new(g)
                    })
                    .insert(id, lo, hi);
            } else {
                self.big.push(id);
            }
            return;
        }
        self.push_cells(id, a, b);
    }

    fn push_cells(&mut self, id: u32, a: C, b: C) {
        for x in a[0]..=b[0] {
            for y in a[1]..=b[1] {
                for z in a[2]..=b[2] {
                    self.cells.entry(Cell([x, y, z])).or_default().push(id);
                }
            }
        }
    }

    /// Inserts many boxes: the same cells as [`TriGrid::insert`] one by one. On an empty fine
    /// level the boxes go into the block layout (counting sort over the occupied 8×8×8
    /// blocks); when the blocks they span would be too many for their entries (boxes far
    /// apart), or the grid already holds boxes, one by one.
    pub(super) fn insert_many(&mut self, items: impl Iterator<Item = (u32, P, P)>) {
        let mut boxes: Vec<(u32, C, C)> = Vec::new();
        let mut total = 0usize;
        for (id, lo, hi) in items {
            let (a, b) = self.range(lo, hi);
            let span = G::span(a, b);
            if span > G::MAX_SPAN {
                self.insert(id, lo, hi);
                continue;
            }
            total += span as usize;
            boxes.push((id, a, b));
        }
        if self.bulk.is_some() || !self.cells.is_empty() || !self.build_blocked(&boxes, total) {
            for (id, a, b) in boxes {
                self.push_cells(id, a, b);
            }
        }
    }

    /// The block layout of `boxes` (each spanning at most [`BoxGrid::MAX_SPAN`] cells, `total`
    /// cells together); false (nothing built) when the blocks do not fit in memory
    /// proportional to the entries.
    fn build_blocked(&mut self, boxes: &[(u32, C, C)], total: usize) -> bool {
        if boxes.is_empty() || total >= u32::MAX as usize {
            return false;
        }
        let (mut c0, mut c1) = ([i64::MAX; 3], [i64::MIN; 3]);
        for (_, a, b) in boxes {
            for k in 0..3 {
                c0[k] = c0[k].min(a[k]);
                c1[k] = c1[k].max(b[k]);
            }
        }
        // blocks per axis, checked (cells may be anywhere in i64)
        let budget = 4 * boxes.len() + 4096;
        let mut bdims = [0usize; 3];
        let mut nb = 1usize;
        for k in 0..3 {
            let Some(n) = c1[k].checked_sub(c0[k]).and_then(|d| d.checked_add(1)) else {
                return false;
            };
            bdims[k] = ((n - 1) >> SHIFT) as usize + 1;
            match nb.checked_mul(bdims[k]) {
                Some(m) if m <= budget => nb = m,
                _ => return false,
            }
        }
        let bidx = |c: C| {
            let r: [usize; 3] = std::array::from_fn(|k| ((c[k] - c0[k]) >> SHIFT) as usize);
            (r[0] * bdims[1] + r[1]) * bdims[2] + r[2]
        };
        let mut dir = vec![NONE; nb];
        let mut slots = 0usize;
        for &(_, a, b) in boxes {
            let (ba, bb) = (bidx(a), bidx(b));
            if ba == bb {
                if dir[ba] == NONE {
                    dir[ba] = slots as u32;
                    slots += 1;
                }
                continue;
            }
            let r: [(i64, i64); 3] =
                std::array::from_fn(|k| ((a[k] - c0[k]) >> SHIFT, (b[k] - c0[k]) >> SHIFT));
            for x in r[0].0..=r[0].1 {
                for y in r[1].0..=r[1].1 {
                    for z in r[2].0..=r[2].1 {
                        let i = (x as usize * bdims[1] + y as usize) * bdims[2] + z as usize;
                        if dir[i] == NONE {
                            dir[i] = slots as u32;
                            slots += 1;
                        }
                    }
                }
            }
        }
        // the offsets: at most as many as a small multiple of the entries
        if slots.saturating_mul(BLOCK) > 8 * total + (1 << 16) {
            return false;
        }
        let mut g = Blocked {
            c0,
            c1,
            bdims,
            dir,
            start: vec![0u32; slots * BLOCK + 1],
            ids: Vec::new(),
        };
        let each = |g: &Blocked, a: C, b: C, f: &mut dyn FnMut(usize)| {
            for x in a[0]..=b[0] {
                for y in a[1]..=b[1] {
                    for z in a[2]..=b[2] {
                        // (every block of a box has a slot)
                        f(g.index([x, y, z]).unwrap_or(0));
                    }
                }
            }
        };
        let mut count = std::mem::take(&mut g.start);
        for &(_, a, b) in boxes {
            each(&g, a, b, &mut |i| count[i + 1] += 1);
        }
        for i in 1..count.len() {
            count[i] += count[i - 1];
        }
        let mut fill = count.clone();
        let mut ids = vec![0u32; total];
        for &(id, a, b) in boxes {
            each(&g, a, b, &mut |i| {
                ids[fill[i] as usize] = id;
                fill[i] += 1;
            });
        }
        g.start = count;
        g.ids = ids;
        self.bulk = Some(g);
        true
    }

    /// Calls `f` on the ids whose cells meet the box (an id may come more than once, in no
    /// particular order; every level and the list of wide boxes included) until it returns
    /// true; returns whether it did.
    #[cfg(test)]
    pub(super) fn any_in_box(&self, lo: P, hi: P, mut f: impl FnMut(u32) -> bool) -> bool {
        self.any_dyn(lo, hi, &mut f)
    }

    fn any_dyn(&self, lo: P, hi: P, f: &mut dyn FnMut(u32) -> bool) -> bool {
        if self.big.iter().any(|&i| f(i)) {
            return true;
        }
        if let Some(g) = &self.coarse {
            if g.any_dyn(lo, hi, f) {
                return true;
            }
        }
        let (a, b) = self.range(lo, hi);
        if let Some(bk) = &self.bulk {
            if bk.any(a, b, f) {
                return true;
            }
        }
        if self.cells.is_empty() {
            return false;
        }
        if G::span(a, b) as usize > self.cells.len() {
            self.cells.iter().any(|(key, ids)| {
                (0..3).all(|k| (a[k]..=b[k]).contains(&key.0[k])) && ids.iter().any(|&i| f(i))
            })
        } else {
            for x in a[0]..=b[0] {
                for y in a[1]..=b[1] {
                    for z in a[2]..=b[2] {
                        if let Some(ids) = self.cells.get(&Cell([x, y, z])) {
                            if ids.iter().any(|&i| f(i)) {
                                return true;
                            }
                        }
                    }
                }
            }
            false
        }
    }

    /// The ids whose cells meet the box, sorted, without repetitions.
    pub(super) fn query(&self, lo: P, hi: P, out: &mut Vec<u32>) {
        out.clear();
        self.any_dyn(lo, hi, &mut |i| {
            out.push(i);
            false
        });
        out.sort_unstable();
        out.dedup();
    }

    /// Every cell's ids (sorted), per level (`(level, cell)`), and the list of wide boxes
    /// (sorted) — what two grids must agree on to answer every query alike.
    #[cfg(test)]
    pub(super) fn contents(&self) -> (Contents, Vec<u32>) {
        let mut m = Contents::default();
        let mut big = self.big.clone();
        if let Some(bk) = &self.bulk {
            for x in bk.c0[0]..=bk.c1[0] {
                for y in bk.c0[1]..=bk.c1[1] {
                    for z in bk.c0[2]..=bk.c1[2] {
                        let ids = bk.cell([x, y, z]);
                        if !ids.is_empty() {
                            m.entry((self.level, [x, y, z]))
                                .or_default()
                                .extend_from_slice(ids);
                        }
                    }
                }
            }
        }
        for (c, ids) in &self.cells {
            m.entry((self.level, c.0))
                .or_default()
                .extend_from_slice(ids);
        }
        if let Some(g) = &self.coarse {
            let (mc, bc) = g.contents();
            m.extend(mc);
            big.extend(bc);
        }
        for v in m.values_mut() {
            v.sort_unstable();
        }
        big.sort_unstable();
        (m, big)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// The brute-force answer: the level of each box as [`BoxGrid::insert`] defines it (the
    /// first level, cells ×8 each, where it spans at most `MAX_SPAN` cells; none beyond the
    /// last), and the ids whose cell range on their level meets the query's, wide boxes always.
    fn brute(lo0: P, cell: f64, boxes: &[(u32, P, P)], q: (P, P)) -> Vec<u32> {
        let range = |cell: f64, lo: P, hi: P| -> (C, C) {
            let c = |x: f64, k: usize| ((x - lo0[k]) / cell).floor() as i64;
            (
                std::array::from_fn(|k| c(lo[k], k)),
                std::array::from_fn(|k| c(hi[k], k)),
            )
        };
        let mut out = Vec::new();
        for &(id, lo, hi) in boxes {
            let mut c = cell;
            let mut level = 0;
            let hit = loop {
                let (a, b) = range(c, lo, hi);
                if G::span(a, b) <= G::MAX_SPAN {
                    let (qa, qb) = range(c, q.0, q.1);
                    break (0..3).all(|k| a[k] <= qb[k] && qa[k] <= b[k]);
                }
                if level + 1 < G::LEVELS && (c * G::COARSEN).is_finite() {
                    c *= G::COARSEN;
                    level += 1;
                } else {
                    break true;
                }
            };
            if hit {
                out.push(id);
            }
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// Point sets: uniform in [0, 1]³; a cluster 1e-5 apart inside that spread; points on
    /// cell boundaries (multiples of the cell); two clusters 1e7 cells apart (no block layout).
    fn sets(rng: &mut impl Rng, cell: f64) -> Vec<Vec<P>> {
        let uni: Vec<P> = (0..3000)
            .map(|_| std::array::from_fn(|_| rng.gen_range(0.0..1.0)))
            .collect();
        let mut clus = uni[..1500].to_vec();
        let c0: P = [0.4321, 0.5678, 0.1234];
        clus.extend(
            (0..1500).map(|_| -> P {
                std::array::from_fn(|k| c0[k] + 1e-5 * rng.gen_range(0..8) as f64)
            }),
        );
        let on: Vec<P> = (0..3000)
            .map(|_| std::array::from_fn(|_| cell * rng.gen_range(0..40) as f64))
            .collect();
        let far: Vec<P> = (0..3000)
            .map(|i| {
                let off = if i < 1500 { 0.0 } else { 1e7 * cell };
                std::array::from_fn(|_| off + rng.gen_range(0.0..0.2))
            })
            .collect();
        vec![uni, clus, on, far]
    }

    /// Every query of the block layout (bulk) plus later insertions answers exactly the
    /// brute-force set and the kernel's [`BoxGrid`]'s, for zero-size boxes (points), triangle
    /// boxes of near points, wide boxes (coarse levels and the list beyond them), queries on
    /// cell boundaries, tiny, wide and far-away queries.
    #[test]
    fn queries_equal_brute_force_and_the_kernel_grid() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(17);
        let cell = 0.04;
        let lo0: P = [0.0, 0.0, 0.0];
        let mut blocked_sets = 0;
        for (si, pts) in sets(&mut rng, cell).into_iter().enumerate() {
            let n = pts.len();
            let mut boxes: Vec<(u32, P, P)> = Vec::new();
            for i in 0..n {
                let p = pts[i];
                let (lo, hi): (P, P) = match i % 5 {
                    // points
                    0 => (p, p),
                    // a far pair (a wide box)
                    4 if i % 100 == 4 => {
                        let q = pts[(i * 7919) % n];
                        (
                            std::array::from_fn(|k| p[k].min(q[k])),
                            std::array::from_fn(|k| p[k].max(q[k])),
                        )
                    }
                    // a triangle of near points: up to two cells, or 1e-5
                    _ => {
                        let r = if i % 3 == 0 { 2.0 * cell } else { 2e-5 };
                        let lo: P = std::array::from_fn(|k| p[k] - rng.gen_range(0.0..r));
                        let hi: P = std::array::from_fn(|k| p[k] + rng.gen_range(0.0..r));
                        (lo, hi)
                    }
                };
                boxes.push((i as u32, lo, hi));
            }
            // a few boxes too wide for every level
            boxes.push((n as u32, [-1e6; 3], [1e6; 3]));
            boxes.push((n as u32 + 1, [0.0; 3], [1e4, 1.0, 1.0]));
            let split = boxes.len() * 3 / 4;
            let mut g = TriGrid::new(lo0, cell);
            g.insert_many(boxes[..split].iter().copied());
            let mut k = BoxGrid::<3>::new(lo0, cell, true);
            k.insert_many(boxes[..split].iter().copied());
            for &(id, lo, hi) in &boxes[split..] {
                g.insert(id, lo, hi);
                k.insert(id, lo, hi);
            }
            blocked_sets += usize::from(g.bulk.is_some());
            assert_eq!(g.bulk.is_some(), si != 3, "set {si}");
            let mut queries: Vec<(P, P)> = Vec::new();
            for q in 0..400 {
                let c = pts[(q * 131) % n];
                let h = match q % 4 {
                    0 => 0.0,
                    1 => 1e-6,
                    2 => cell * rng.gen_range(0.5..3.0),
                    _ => rng.gen_range(0.05..0.7),
                };
                queries.push((c.map(|x| x - h), c.map(|x| x + h)));
                // exactly on cell boundaries
                let e: P = std::array::from_fn(|_| cell * rng.gen_range(0..40) as f64);
                queries.push((e, e.map(|x| x + cell * (q % 3) as f64)));
            }
            queries.push(([-1e9; 3], [1e9; 3]));
            queries.push(([5.0; 3], [6.0; 3]));
            let (mut got, mut old) = (Vec::new(), Vec::new());
            for (qi, &(lo, hi)) in queries.iter().enumerate() {
                g.query(lo, hi, &mut got);
                k.query(lo, hi, &mut old);
                let want = brute(lo0, cell, &boxes, (lo, hi));
                assert_eq!(got, want, "set {si} query {qi} {lo:?} {hi:?}");
                assert_eq!(old, want, "set {si} query {qi} (kernel grid)");
                // any_in_box: finds an id exactly when the set has one; visits all of them
                let mut seen = Vec::new();
                let any = g.any_in_box(lo, hi, |i| {
                    seen.push(i);
                    false
                });
                assert!(!any);
                seen.sort_unstable();
                seen.dedup();
                assert_eq!(seen, want);
                if let Some(&t) = want.get(want.len() / 2) {
                    assert!(g.any_in_box(lo, hi, |i| i == t));
                }
            }
        }
        assert_eq!(blocked_sets, 3);
    }
}
