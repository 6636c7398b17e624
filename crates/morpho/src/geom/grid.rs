//! The spatial grid of the library: uniform bucket grids for range queries.
//!
//! Two storages, one cell sizing:
//! - [`PointGrid`]: points bucketed once into a dense grid in a CSR layout (one sorted index
//!   array and cell offsets); O(N) to build, a query visits the cells meeting its box. For the
//!   static point sets of the graph constructions.
//! - [`BoxGrid`]: a sparse hash grid of ids by bounding box, each id registered in every cell
//!   its box meets; boxes spanning more than [`BoxGrid::MAX_SPAN`] cells go to a coarser level
//!   (cells [`BoxGrid::COARSEN`]× wider), up to [`BoxGrid::LEVELS`] levels, beyond that to a
//!   list every query returns. Dynamic (insertions at any time, bulk insertion by counting
//!   sort); for the boundary engines' triangles, segments and vertices.
//!
//! Both size their cells through [`fit_cells`], which terminates for any input and keeps the
//! number of cells bounded: a point set 1e-300 wide, 1e300 wide, with zero-extent axes, or with
//! an extent that overflows (coordinates near ±f64::MAX) gets a positive finite cell and at
//! most the allowed number of cells (in the last case a single cell).

use crate::util::IdMap;
use std::hash::{Hash, Hasher};

/// The cell size and the number of cells per axis of a uniform grid over a box of extent
/// `ext`: the cell starts at `cell` (when that is not positive and finite, at the size that
/// spreads `max_cells` cells over the axes of positive extent) and grows by 1.5× until there
/// are at most `max_cells` cells. Always terminates (at the
/// latest when the cell overflows to infinity, which leaves one cell per axis) and always
/// returns at least one cell per axis; negative or NaN extents count as 0.
pub fn fit_cells<const D: usize>(ext: [f64; D], cell: f64, max_cells: usize) -> (f64, [usize; D]) {
    let ext = ext.map(|e| if e > 0.0 { e } else { 0.0 });
    let mut cell = if cell.is_finite() && cell > 0.0 {
        cell
    } else {
        // no usable cell (a caller's estimate that under- or overflowed): the budget of cells
        // spread over the axes with a finite positive extent
        let finite = ext.iter().copied().filter(|e| e.is_finite() && *e > 0.0);
        let (m, d) = finite.fold((0.0f64, 0), |(m, d), e| (m.max(e), d + 1));
        let c = m / (max_cells.max(1) as f64).powf(1.0 / d.max(1) as f64);
        if c.is_finite() && c > 0.0 {
            c
        } else {
            1.0
        }
    };
    loop {
        let mut dims = [1usize; D];
        let mut total = 1usize;
        for k in 0..D {
            // (a NaN quotient, inf / inf, casts to 0)
            dims[k] = ((ext[k] / cell).floor() as usize).saturating_add(1);
            total = total.saturating_mul(dims[k]);
        }
        if total <= max_cells || !cell.is_finite() {
            return (cell, dims);
        }
        cell *= 1.5;
    }
}

/// Points bucketed into a uniform grid of about `N / per_cell` cells, in a CSR layout.
pub struct PointGrid<'a, const D: usize> {
    pts: &'a [[f64; D]],
    min: [f64; D],
    cell: f64,
    dims: [usize; D],
    start: Vec<u32>,
    items: Vec<u32>,
}

impl<'a, const D: usize> PointGrid<'a, D> {
    /// A grid with about `per_cell` points per occupied cell for uniformly spread points (at
    /// most about 4N cells). O(N).
    pub fn new(pts: &'a [[f64; D]], per_cell: f64) -> Self {
        let mut min = [f64::INFINITY; D];
        let mut max = [f64::NEG_INFINITY; D];
        for p in pts {
            for k in 0..D {
                min[k] = min[k].min(p[k]);
                max[k] = max[k].max(p[k]);
            }
        }
        let n = pts.len().max(1) as f64;
        let mut vol = 1.0;
        let mut ext = [0.0; D];
        for k in 0..D {
            ext[k] = (max[k] - min[k]).max(0.0);
        }
        let maxext = ext
            .iter()
            .cloned()
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE);
        for k in 0..D {
            vol *= ext[k].max(maxext * 1e-3);
        }
        let mut cell = (vol * per_cell / n).powf(1.0 / D as f64);
        if !(cell.is_finite() && cell > 0.0) {
            // the volume under- or overflowed (a set 1e-300 or 1e300 wide): the same cell
            // computed relative to the largest extent
            let mut rel = 1.0;
            for k in 0..D {
                rel *= (ext[k] / maxext).max(1e-3);
            }
            cell = maxext * (rel * per_cell / n).powf(1.0 / D as f64);
        }
        if !(cell.is_finite() && cell > 0.0) {
            cell = maxext.max(1.0);
        }
        let (cell, dims) = fit_cells(ext, cell, 4 * pts.len() + 16);
        let mut g = PointGrid {
            pts,
            min,
            cell,
            dims,
            start: vec![],
            items: vec![],
        };
        let ncell: usize = dims.iter().product();
        let mut count = vec![0u32; ncell + 1];
        let ids: Vec<usize> = pts.iter().map(|p| g.cell_of(p)).collect();
        for &c in &ids {
            count[c + 1] += 1;
        }
        for c in 0..ncell {
            count[c + 1] += count[c];
        }
        let mut fill = count.clone();
        let mut items = vec![0u32; pts.len()];
        for (i, &c) in ids.iter().enumerate() {
            items[fill[c] as usize] = i as u32;
            fill[c] += 1;
        }
        g.start = count;
        g.items = items;
        g
    }

    fn coord(&self, x: f64, k: usize) -> usize {
        let c = ((x - self.min[k]) / self.cell).floor();
        if c <= 0.0 {
            0
        } else {
            (c as usize).min(self.dims[k] - 1)
        }
    }

    fn cell_of(&self, p: &[f64; D]) -> usize {
        let mut idx = 0;
        for k in (0..D).rev() {
            idx = idx * self.dims[k] + self.coord(p[k], k);
        }
        idx
    }

    /// The cell size.
    #[allow(dead_code)] // kernel API without a caller yet
    pub fn cell(&self) -> f64 {
        self.cell
    }

    /// The number of cells.
    #[allow(dead_code)] // kernel API without a caller yet
    pub fn cell_count(&self) -> usize {
        self.start.len() - 1
    }

    /// The points of cell `cell`.
    #[allow(dead_code)] // kernel API without a caller yet
    pub fn cell_items(&self, cell: usize) -> &[u32] {
        &self.items[self.start[cell] as usize..self.start[cell + 1] as usize]
    }

    /// Calls `f(cell, d2)` for every cell meeting the box of half-width `r` around `c`, with
    /// `d2` the squared distance from `c` to the cell (0 inside); stops early when `f` returns
    /// false.
    #[allow(dead_code)] // kernel API without a caller yet
    pub fn for_each_cell_near(&self, c: [f64; D], r: f64, mut f: impl FnMut(usize, f64) -> bool) {
        let mut a = [0usize; D];
        let mut b = [0usize; D];
        for k in 0..D {
            if c[k] + r < self.min[k] {
                return;
            }
            a[k] = self.coord(c[k] - r, k);
            b[k] = self.coord(c[k] + r, k);
        }
        let mut cur = a;
        loop {
            let mut idx = 0;
            let mut d2 = 0.0;
            for k in (0..D).rev() {
                idx = idx * self.dims[k] + cur[k];
                let lo = self.min[k] + cur[k] as f64 * self.cell;
                let hi = lo + self.cell;
                let d = (lo - c[k]).max(c[k] - hi).max(0.0);
                d2 += d * d;
            }
            if !f(idx, d2) {
                return;
            }
            let mut k = 0;
            loop {
                if k == D {
                    return;
                }
                if cur[k] < b[k] {
                    cur[k] += 1;
                    break;
                }
                cur[k] = a[k];
                k += 1;
            }
        }
    }

    /// The points in cell order (cells in index order, the first axis fastest): slot `s` holds
    /// point `items()[s]`. Data laid out in this order is read contiguously by
    /// [`PointGrid::for_each_run`].
    pub fn items(&self) -> &[u32] {
        &self.items
    }

    /// Calls `f(slots)` for every run of slots (positions in [`PointGrid::items`]) whose cells
    /// meet the box `[lo, hi]`: one run per row of cells along the first axis (a superset of the
    /// points in the box). `f` returns false to stop early; the function then returns false.
    pub fn for_each_run(
        &self,
        lo: [f64; D],
        hi: [f64; D],
        mut f: impl FnMut(std::ops::Range<usize>) -> bool,
    ) -> bool {
        let mut a = [0usize; D];
        let mut b = [0usize; D];
        for k in 0..D {
            if hi[k] < self.min[k] {
                return true;
            }
            a[k] = self.coord(lo[k], k);
            b[k] = self.coord(hi[k], k);
        }
        let mut cur = a;
        loop {
            let mut idx = 0;
            for k in (1..D).rev() {
                idx = idx * self.dims[k] + cur[k];
            }
            let row = idx * self.dims[0];
            let run = self.start[row + a[0]] as usize..self.start[row + b[0] + 1] as usize;
            if !run.is_empty() && !f(run) {
                return false;
            }
            // next row
            let mut k = 1;
            loop {
                if k >= D {
                    return true;
                }
                if cur[k] < b[k] {
                    cur[k] += 1;
                    break;
                }
                cur[k] = a[k];
                k += 1;
            }
        }
    }

    /// Calls `f(i)` for every point whose cell meets the box `[lo, hi]` (a superset of the
    /// points in the box). `f` returns false to stop early; the function then returns false.
    pub fn for_each_in_box(
        &self,
        lo: [f64; D],
        hi: [f64; D],
        mut f: impl FnMut(u32) -> bool,
    ) -> bool {
        // the cells of one row along the first axis are contiguous in `items`
        self.for_each_run(lo, hi, |run| self.items[run].iter().all(|&i| f(i)))
    }

    /// Calls `f(i)` for every point strictly within distance `r` of `c`; stops early (returning
    /// false) when `f` returns false.
    pub fn for_each_within(&self, c: [f64; D], r: f64, mut f: impl FnMut(u32) -> bool) -> bool {
        let mut lo = c;
        let mut hi = c;
        for k in 0..D {
            lo[k] -= r;
            hi[k] += r;
        }
        let r2 = r * r;
        self.for_each_in_box(lo, hi, |i| {
            let p = &self.pts[i as usize];
            let d2: f64 = (0..D).map(|k| (p[k] - c[k]) * (p[k] - c[k])).sum();
            if d2 < r2 {
                f(i)
            } else {
                true
            }
        })
    }
}

/// The integer coordinates of a [`BoxGrid`] cell. Hashes like the tuple of its coordinates
/// (one `write_i64` each, no length prefix).
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Debug)]
pub struct Cell<const D: usize>(pub [i64; D]);

impl<const D: usize> Hash for Cell<D> {
    #[inline]
    fn hash<H: Hasher>(&self, state: &mut H) {
        for &c in &self.0 {
            state.write_i64(c);
        }
    }
}

/// The cells from `a` to `b` (inclusive), the first axis outermost (as nested loops would
/// visit them), until `f` returns true; returns whether it did. `D` is 2 or 3.
#[inline(always)]
fn any_cell<const D: usize>(a: [i64; D], b: [i64; D], mut f: impl FnMut([i64; D]) -> bool) -> bool {
    const { assert!(D == 2 || D == 3, "BoxGrid is for 2 or 3 dimensions") };
    let r = |k: usize| if k < D { (a[k], b[k]) } else { (0, 0) };
    let ((x0, x1), (y0, y1), (z0, z1)) = (r(0), r(1), r(2));
    for x in x0..=x1 {
        for y in y0..=y1 {
            for z in z0..=z1 {
                let xyz = [x, y, z];
                if f(std::array::from_fn(|k| xyz[k])) {
                    return true;
                }
            }
        }
    }
    false
}

/// [`any_cell`] visiting every cell.
#[inline(always)]
fn each_cell<const D: usize>(a: [i64; D], b: [i64; D], mut f: impl FnMut([i64; D])) {
    any_cell(a, b, |c| {
        f(c);
        false
    });
}

/// The cells from `a` to `b` as an iterator (the order of [`any_cell`]).
#[inline]
fn cell_iter<const D: usize>(a: [i64; D], b: [i64; D]) -> impl Iterator<Item = [i64; D]> {
    let r = move |k: usize| if k < D { (a[k], b[k]) } else { (0, 0) };
    let ((x0, x1), (y0, y1), (z0, z1)) = (r(0), r(1), r(2));
    (x0..=x1).flat_map(move |x| {
        (y0..=y1).flat_map(move |y| {
            (z0..=z1).map(move |z| {
                let xyz = [x, y, z];
                std::array::from_fn(|k| xyz[k])
            })
        })
    })
}

/// A uniform hash grid of ids by bounding box in 2 or 3 dimensions (see the module
/// documentation): an id whose box spans more than [`BoxGrid::MAX_SPAN`] cells goes to a
/// coarser grid (cell × [`BoxGrid::COARSEN`]), up to [`BoxGrid::LEVELS`] levels; beyond that
/// to a list returned by every query. Cells are unbounded (any `i64` coordinates), so the grid
/// needs no extent; [`BoxGrid::fitted`] sizes the cell for a known extent.
#[derive(PartialEq, Debug)]
pub struct BoxGrid<const D: usize> {
    lo: [f64; D],
    cell: f64,
    cells: IdMap<Cell<D>, Vec<u32>>,
    big: Vec<u32>,
    coarse: Option<Box<BoxGrid<D>>>,
    level: usize,
    /// Ids may sit in several cells (boxes, not points): queries deduplicate.
    multi: bool,
}

/// A box's cells on one level: the low and high cell (inclusive).
type CellRange<const D: usize> = ([i64; D], [i64; D]);

impl<const D: usize> BoxGrid<D> {
    /// Boxes spanning more cells than this go to the next coarser level.
    pub const MAX_SPAN: i64 = 512;
    /// How much wider the cells of each coarser level are.
    pub const COARSEN: f64 = 8.0;
    /// The number of levels (the finest included); boxes too wide for the coarsest go to a
    /// list that every query returns.
    pub const LEVELS: usize = 3;
    /// [`BoxGrid::insert_many`] sorts at most this many (cell, id) entries at once.
    const BULK_MAX: usize = 1 << 23;

    /// An empty grid with cells of size `cell` (1 when not positive and finite) from the
    /// origin `lo`. With `multi`, [`BoxGrid::query`] sorts and deduplicates (ids of boxes sit
    /// in several cells); without, it returns ids as found (for points, each in one cell).
    pub fn new(lo: [f64; D], cell: f64, multi: bool) -> Self {
        BoxGrid {
            lo,
            cell: if cell > 0.0 && cell.is_finite() {
                cell
            } else {
                1.0
            },
            cells: IdMap::default(),
            big: Vec::new(),
            coarse: None,
            level: 0,
            multi,
        }
    }

    /// An empty grid over the box `[lo, hi]` with cells of about `cell` (made positive and
    /// enlarged until the box holds at most `max_cells` cells, by [`fit_cells`]; at least 16).
    pub fn fitted(lo: [f64; D], hi: [f64; D], cell: f64, max_cells: usize, multi: bool) -> Self {
        let ext: [f64; D] = std::array::from_fn(|k| hi[k] - lo[k]);
        let (cell, _) = fit_cells(ext, cell, max_cells.max(16));
        Self::new(lo, cell, multi)
    }

    /// The cell size of the finest level.
    pub fn cell(&self) -> f64 {
        self.cell
    }

    /// The origin of the cells.
    pub fn origin(&self) -> [f64; D] {
        self.lo
    }

    /// True when every id sits on the finest level (no coarser level, no list of boxes too
    /// wide for every level).
    pub fn is_single_level(&self) -> bool {
        self.coarse.is_none() && self.big.is_empty()
    }

    /// The cells of the box `[lo, hi]` on this level (coordinates beyond `i64` saturate, NaN
    /// gives cell 0).
    pub fn range(&self, lo: [f64; D], hi: [f64; D]) -> CellRange<D> {
        let c = |x: f64, k: usize| ((x - self.lo[k]) / self.cell).floor() as i64;
        (
            std::array::from_fn(|k| c(lo[k], k)),
            std::array::from_fn(|k| c(hi[k], k)),
        )
    }

    /// The number of cells from `a` to `b` (saturating at `i64::MAX`).
    pub fn span(a: [i64; D], b: [i64; D]) -> i64 {
        (0..D).fold(1i64, |s, k| {
            s.saturating_mul(b[k].saturating_sub(a[k]).saturating_add(1))
        })
    }

    /// Registers `id` in every cell of this level meeting the box `[lo, hi]`, or on a coarser
    /// level when the box spans more than [`BoxGrid::MAX_SPAN`] cells.
    pub fn insert(&mut self, id: u32, lo: [f64; D], hi: [f64; D]) {
        let (a, b) = self.range(lo, hi);
        if Self::span(a, b) > Self::MAX_SPAN {
            if self.level + 1 < Self::LEVELS && (self.cell * Self::COARSEN).is_finite() {
                let (origin, cell, multi, level) = (
                    self.lo,
                    self.cell * Self::COARSEN,
                    self.multi,
                    self.level + 1,
                );
                self.coarse
                    .get_or_insert_with(|| {
                        let mut g = BoxGrid::new(origin, cell, multi);
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

    /// Appends `id` to every cell from `a` to `b` (inclusive).
    fn push_cells(&mut self, id: u32, a: [i64; D], b: [i64; D]) {
        let cells = &mut self.cells;
        each_cell(a, b, |c| cells.entry(Cell(c)).or_default().push(id));
    }

    /// Inserts many boxes at once, in the given order; the same grid as [`BoxGrid::insert`]
    /// one by one (every cell lists its ids in insertion order, as long as the ids increase
    /// along `items`), with each cell's list allocated once. The (cell, id) entries are grouped
    /// by a counting sort when the boxes span a compact block of cells, otherwise by a
    /// parallel sort.
    pub fn insert_many(&mut self, items: impl Iterator<Item = (u32, [f64; D], [f64; D])>) {
        self.insert_many_capped(items, Self::BULK_MAX);
    }

    /// [`BoxGrid::insert_many`] sorting at most `cap` entries (beyond: one box after the other).
    pub fn insert_many_capped(
        &mut self,
        items: impl Iterator<Item = (u32, [f64; D], [f64; D])>,
        cap: usize,
    ) {
        use rayon::prelude::*;
        // entries: the cell's coordinates (21 bits each, when they fit) above the id, so that
        // one parallel integer sort orders them by cell and then by id
        const BITS: u32 = 21;
        let fits = |c: i64| (0..1 << BITS).contains(&c);
        let mut boxes: Vec<(u32, [i64; D], [i64; D])> = Vec::new();
        let mut all_fit = true;
        let mut total = 0usize;
        for (id, lo, hi) in items {
            let (a, b) = self.range(lo, hi);
            let span = Self::span(a, b);
            if span > Self::MAX_SPAN {
                self.insert(id, lo, hi);
                continue;
            }
            all_fit &= a.iter().chain(&b).all(|&c| fits(c));
            total += span as usize;
            boxes.push((id, a, b));
        }
        if total > cap {
            // too many entries to hold at once (16–32 bytes each against 4 in the cells)
            for (id, a, b) in boxes {
                self.push_cells(id, a, b);
            }
            return;
        }
        let cells_of =
            |&(id, a, b): &(u32, [i64; D], [i64; D])| cell_iter(a, b).map(move |c| (Cell(c), id));
        let mut add_run = |cell: Cell<D>, ids: &mut dyn Iterator<Item = u32>, n: usize| {
            let v = self.cells.entry(cell).or_default();
            v.reserve_exact(n);
            v.extend(ids);
        };
        if let Some((c0, dims)) = Self::dense_block(&boxes, total) {
            // counting sort over the block of cells the boxes span (boxes in order, so every
            // cell's ids stay in insertion order); cells numbered with the last axis fastest
            let idx =
                |c: [i64; D]| (0..D).fold(0usize, |i, k| i * dims[k] + (c[k] - c0[k]) as usize);
            let ncell: usize = dims.iter().product();
            let mut start = vec![0u32; ncell + 1];
            for &(_, a, b) in &boxes {
                each_cell(a, b, |c| start[idx(c) + 1] += 1);
            }
            for c in 1..start.len() {
                start[c] += start[c - 1];
            }
            let mut ids = vec![0u32; total];
            let mut fill = start.clone();
            for &(id, a, b) in &boxes {
                each_cell(a, b, |c| {
                    let c = idx(c);
                    ids[fill[c] as usize] = id;
                    fill[c] += 1;
                });
            }
            drop(fill);
            for c in 0..ncell {
                let (s, e) = (start[c] as usize, start[c + 1] as usize);
                if e > s {
                    let mut cell = [0i64; D];
                    let mut rest = c;
                    for k in (0..D).rev() {
                        cell[k] = (rest % dims[k]) as i64 + c0[k];
                        rest /= dims[k];
                    }
                    add_run(Cell(cell), &mut ids[s..e].iter().copied(), e - s);
                }
            }
        } else if all_fit {
            let mut e: Vec<u128> = boxes
                .par_iter()
                .flat_map_iter(cells_of)
                .map(|(c, id)| {
                    let cell = (0..D).fold(0u128, |v, k| v << BITS | c.0[k] as u128);
                    cell << 32 | id as u128
                })
                .collect();
            e.par_sort_unstable();
            let mask = (1u128 << BITS) - 1;
            for run in e.chunk_by(|a, b| a >> 32 == b >> 32) {
                let cell = run[0] >> 32;
                let c: [i64; D] =
                    std::array::from_fn(|k| (cell >> ((D - 1 - k) as u32 * BITS) & mask) as i64);
                add_run(Cell(c), &mut run.iter().map(|&x| x as u32), run.len());
            }
        } else {
            let mut e: Vec<(Cell<D>, u32)> = boxes.par_iter().flat_map_iter(cells_of).collect();
            e.par_sort_unstable();
            for run in e.chunk_by(|a, b| a.0 == b.0) {
                add_run(run[0].0, &mut run.iter().map(|x| x.1), run.len());
            }
        }
    }

    /// The block of cells spanned by `boxes` (its low cell and size per axis) when it has at
    /// most about twice as many cells as the boxes have (cell, id) entries (`total`): then
    /// [`BoxGrid::insert_many`] counting-sorts over it instead of sorting the entries.
    fn dense_block(
        boxes: &[(u32, [i64; D], [i64; D])],
        total: usize,
    ) -> Option<([i64; D], [usize; D])> {
        let (mut lo, mut hi) = ([i64::MAX; D], [i64::MIN; D]);
        for (_, a, b) in boxes {
            for k in 0..D {
                lo[k] = lo[k].min(a[k]);
                hi[k] = hi[k].max(b[k]);
            }
        }
        if boxes.is_empty() || total >= u32::MAX as usize {
            return None;
        }
        let mut n: usize = 1;
        let mut dims = [0usize; D];
        for k in 0..D {
            dims[k] = usize::try_from(hi[k].checked_sub(lo[k])?.checked_add(1)?).ok()?;
            n = n.checked_mul(dims[k])?;
        }
        (n <= 2 * total + (1 << 16)).then_some((lo, dims))
    }

    /// Calls `f` on the ids whose cells meet the box (an id may come more than once; every
    /// level and the list of wide boxes included) until it returns true; returns whether it
    /// did.
    // (no caller outside the tests since the 3D engine's triangle grids became
    // `boundary::d3::trigrid::TriGrid`; kept as the grid's early-exit query)
    #[cfg_attr(not(test), allow(dead_code))]
    pub fn any_in_box(&self, lo: [f64; D], hi: [f64; D], mut f: impl FnMut(u32) -> bool) -> bool {
        self.any_in_box_dyn(lo, hi, &mut f)
    }

    fn any_in_box_dyn(&self, lo: [f64; D], hi: [f64; D], f: &mut dyn FnMut(u32) -> bool) -> bool {
        if self.big.iter().any(|&i| f(i)) {
            return true;
        }
        if let Some(g) = &self.coarse {
            if g.any_in_box_dyn(lo, hi, f) {
                return true;
            }
        }
        let (a, b) = self.range(lo, hi);
        if Self::span(a, b) as usize > self.cells.len() {
            for (key, ids) in &self.cells {
                if (0..D).all(|k| (a[k]..=b[k]).contains(&key.0[k])) && ids.iter().any(|&i| f(i)) {
                    return true;
                }
            }
            false
        } else {
            any_cell(a, b, |c| {
                self.cells
                    .get(&Cell(c))
                    .is_some_and(|ids| ids.iter().any(|&i| f(i)))
            })
        }
    }

    /// Calls `f` on every id whose cells meet the box, with repetitions (an id in several of
    /// the cells comes once per cell).
    pub fn for_each(&self, lo: [f64; D], hi: [f64; D], mut f: impl FnMut(u32)) {
        self.any_in_box_dyn(lo, hi, &mut |i| {
            f(i);
            false
        });
    }

    /// Ids whose cells meet the box (sorted without repetitions for a `multi` grid).
    pub fn query(&self, lo: [f64; D], hi: [f64; D], out: &mut Vec<u32>) {
        out.clear();
        self.collect(lo, hi, out);
        if self.multi {
            out.sort_unstable();
            out.dedup();
        }
    }

    /// Appends the ids whose cells (on every level) meet the box, with repetitions.
    fn collect(&self, lo: [f64; D], hi: [f64; D], out: &mut Vec<u32>) {
        out.extend_from_slice(&self.big);
        if let Some(g) = &self.coarse {
            g.collect(lo, hi, out);
        }
        self.for_cells(lo, hi, |_, ids| out.extend_from_slice(ids));
    }

    /// Calls `f` on every non-empty cell of this level (not the coarser ones, not the list of
    /// wide boxes) that meets the box, with its coordinates and ids.
    pub fn for_cells<'a>(
        &'a self,
        lo: [f64; D],
        hi: [f64; D],
        mut f: impl FnMut([i64; D], &'a [u32]),
    ) {
        let (a, b) = self.range(lo, hi);
        if Self::span(a, b) as usize > self.cells.len() {
            for (key, ids) in &self.cells {
                if (0..D).all(|k| (a[k]..=b[k]).contains(&key.0[k])) {
                    f(key.0, ids);
                }
            }
        } else {
            each_cell(a, b, |c| {
                if let Some(ids) = self.cells.get(&Cell(c)) {
                    f(c, ids);
                }
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    type P = [f64; 3];

    fn boxes_meet<const D: usize>(a: ([f64; D], [f64; D]), b: ([f64; D], [f64; D])) -> bool {
        (0..D).all(|k| a.0[k] <= b.1[k] && b.0[k] <= a.1[k])
    }

    /// The sizing terminates with a bounded, positive number of cells at every scale, for
    /// zero-extent axes and for extents that overflow; and the point grid built on such sets
    /// answers queries like the brute force.
    #[test]
    fn sizing_is_sane_at_every_scale() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
        for scale in [1e-300, 1e-200, 1e-12, 1.0, 1e12, 1e200, 1e300, 1e307] {
            for flat in [false, true] {
                let pts: Vec<[f64; 3]> = (0..500)
                    .map(|_| {
                        let z = if flat {
                            0.0
                        } else {
                            rng.gen_range(-1.0..1.0) * scale
                        };
                        [
                            rng.gen_range(-1.0..1.0) * scale,
                            rng.gen_range(-1.0..1.0) * scale,
                            z,
                        ]
                    })
                    .collect();
                let g = PointGrid::new(&pts, 2.0);
                assert!(g.cell() > 0.0 && g.cell().is_finite(), "{scale:e}");
                assert!(g.cell_count() <= 4 * 500 + 16);
                // not degenerate into one cell: about 250 cells for 500 spread points
                assert!(g.cell_count() > 20, "{scale:e} {flat}: {}", g.cell_count());
                let c = pts[0];
                let r = 0.3 * scale;
                let mut got = Vec::new();
                g.for_each_within(c, r, |i| {
                    got.push(i);
                    true
                });
                got.sort_unstable();
                let want: Vec<u32> = (0..pts.len() as u32)
                    .filter(|&i| {
                        let p = pts[i as usize];
                        (0..3).map(|k| (p[k] - c[k]) * (p[k] - c[k])).sum::<f64>() < r * r
                    })
                    .collect();
                assert_eq!(got, want, "{scale:e} {flat}");
            }
        }
        // all points equal; an extent that overflows; a single point
        let same = vec![[1e-300, -2.0]; 50];
        assert_eq!(PointGrid::new(&same, 2.0).cell_count(), 1);
        let wide = [[-f64::MAX, 0.0], [f64::MAX, 1.0], [0.0, 0.5]];
        let g = PointGrid::new(&wide, 2.0);
        assert!(g.cell_count() <= 4 * 3 + 16);
        let mut all = 0;
        g.for_each_in_box([-f64::MAX, 0.0], [f64::MAX, 1.0], |_| {
            all += 1;
            true
        });
        assert_eq!(all, 3);
        assert_eq!(PointGrid::new(&[[3.0, 4.0]], 1.0).cell_count(), 1);
        for (ext, cell) in [
            ([0.0, 0.0], 0.0),
            ([f64::NAN, 1.0], f64::NAN),
            ([1e300; 2], 1e-300),
        ] {
            let (c, dims) = fit_cells(ext, cell, 64);
            assert!(
                c > 0.0 && dims.iter().product::<usize>() <= 64,
                "{ext:?} {cell}"
            );
        }
    }

    #[test]
    fn box_grids_at_extreme_scales_answer_like_the_brute_force() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(2);
        for scale in [1e-300, 1.0, 1e300] {
            let boxes: Vec<([f64; 2], [f64; 2])> = (0..300)
                .map(|_| {
                    let lo = [
                        rng.gen_range(-1.0..1.0) * scale,
                        rng.gen_range(-1.0..1.0) * scale,
                    ];
                    let w = rng.gen_range(0.0..0.1) * scale;
                    (lo, [lo[0] + w, lo[1] + w / 2.0])
                })
                .collect();
            // the cell a caller might compute from the area per box, underflowing or not
            let cell = (4.0 * scale * scale / 300.0).sqrt();
            let lo = [-scale, -scale];
            let hi = [1.1 * scale, 1.1 * scale];
            let mut g = BoxGrid::fitted(lo, hi, cell, 2 * 300 + 16, true);
            for (i, b) in boxes.iter().enumerate() {
                g.insert(i as u32, b.0, b.1);
            }
            for _ in 0..100 {
                let q0 = [
                    rng.gen_range(-1.0..1.0) * scale,
                    rng.gen_range(-1.0..1.0) * scale,
                ];
                let q = (q0, [q0[0] + 0.2 * scale, q0[1] + 0.1 * scale]);
                let mut got = Vec::new();
                g.query(q.0, q.1, &mut got);
                for (i, b) in boxes.iter().enumerate() {
                    if boxes_meet(*b, q) {
                        assert!(got.binary_search(&(i as u32)).is_ok(), "{scale:e} {i}");
                    }
                }
                let mut each = Vec::new();
                g.for_each(q.0, q.1, |i| each.push(i));
                each.sort_unstable();
                each.dedup();
                assert_eq!(each, got);
            }
        }
    }

    /// The bulk insertion builds exactly the grid of inserting one by one (same cells, same
    /// lists in the same order, coarse levels included), on every path: counting sort over a
    /// dense block, the packed integer sort, the tuple sort (cells beyond 21 bits), and the
    /// one-by-one fallback beyond the cap.
    #[test]
    fn bulk_grid_insertion_equals_one_by_one_on_every_path() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        // (origin, cap, extent, dense): the sort of packed cells, the sort of cell tuples
        // (cells beyond 21 bits), one box after the other (capped), the counting sort
        for (origin, cap, extent, dense) in [
            (0.0, usize::MAX, 100.0, false),
            (-1e9, usize::MAX, 100.0, false),
            (0.0, 100, 100.0, false),
            (-1e9, usize::MAX, 12.0, true),
        ] {
            let items: Vec<(u32, P, P)> = (0..3000u32)
                .map(|id| {
                    let lo: P = std::array::from_fn(|_| rng.gen_range(0.0..extent));
                    let w = match id % 50 {
                        _ if id % 500 == 0 => 1e5,
                        0 => 90.0,
                        1..=3 => 20.0,
                        _ => rng.gen_range(0.0..3.0),
                    };
                    let hi: P = std::array::from_fn(|k| lo[k] + w * (0.5 + (k as f64) / 4.0));
                    (id, lo, hi)
                })
                .collect();
            let mut bulk = BoxGrid::new([origin; 3], 1.0, true);
            let fine: Vec<(u32, [i64; 3], [i64; 3])> = items
                .iter()
                .map(|&(id, lo, hi)| {
                    let (a, b) = bulk.range(lo, hi);
                    (id, a, b)
                })
                .filter(|(_, a, b)| BoxGrid::span(*a, *b) <= BoxGrid::<3>::MAX_SPAN)
                .collect();
            let total: i64 = fine.iter().map(|(_, a, b)| BoxGrid::span(*a, *b)).sum();
            assert_eq!(BoxGrid::dense_block(&fine, total as usize).is_some(), dense);
            bulk.insert_many_capped(items.iter().copied(), cap);
            let mut one = BoxGrid::new([origin; 3], 1.0, true);
            for &(id, lo, hi) in &items {
                one.insert(id, lo, hi);
            }
            let coarse = bulk.coarse.as_ref().and_then(|g| g.coarse.as_ref());
            assert!(coarse.is_some_and(|g| !g.big.is_empty()) && !bulk.cells.is_empty());
            assert_eq!(bulk, one, "origin {origin}, cap {cap}");
            // and in 2D
            let items2: Vec<(u32, [f64; 2], [f64; 2])> = items
                .iter()
                .map(|&(id, lo, hi)| (id, [lo[0], lo[1]], [hi[0], hi[1]]))
                .collect();
            let mut bulk2 = BoxGrid::new([origin; 2], 1.0, true);
            bulk2.insert_many_capped(items2.iter().copied(), cap);
            let mut one2 = BoxGrid::new([origin; 2], 1.0, true);
            for &(id, lo, hi) in &items2 {
                one2.insert(id, lo, hi);
            }
            assert_eq!(bulk2, one2, "2D: origin {origin}, cap {cap}");
        }
    }

    /// Every id whose box meets the query box is reported by `query` and seen by
    /// `any_in_box`, on all levels (boxes from a tenth of a cell to thousands of cells wide).
    #[test]
    fn grid_reports_every_meeting_box_on_every_level() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let mut g = BoxGrid::new([0.0; 3], 1.0, true);
        let mut boxes = Vec::new();
        for id in 0..600u32 {
            let size = [0.1, 3.0, 30.0, 300.0, 3000.0][id as usize % 5];
            let lo: P = std::array::from_fn(|_| rng.gen_range(-100.0..100.0));
            let hi: P = std::array::from_fn(|k| lo[k] + rng.gen_range(0.0..size));
            g.insert(id, lo, hi);
            boxes.push((lo, hi));
        }
        let top = g.coarse.as_ref().and_then(|c| c.coarse.as_ref());
        assert!(top.is_some_and(|t| !t.big.is_empty() && !t.cells.is_empty()));
        let mut out = Vec::new();
        for _ in 0..300 {
            let lo: P = std::array::from_fn(|_| rng.gen_range(-120.0..120.0));
            let hi: P = std::array::from_fn(|k| lo[k] + rng.gen_range(0.0..20.0));
            g.query(lo, hi, &mut out);
            assert!(out.windows(2).all(|w| w[0] < w[1]));
            for (id, b) in boxes.iter().enumerate() {
                if boxes_meet(*b, (lo, hi)) {
                    assert!(out.binary_search(&(id as u32)).is_ok(), "{id}");
                    assert!(g.any_in_box(lo, hi, |i| i == id as u32), "{id}");
                }
            }
        }
        // a box so wide that its cell count overflows i64 goes to the list of wide boxes
        g.insert(9999, [-1e300; 3], [1e300; 3]);
        assert!(g.any_in_box([5.0; 3], [5.0; 3], |i| i == 9999));
    }

    /// The cell key hashes like the tuple it replaced (the hash map's layout, and so the order
    /// in which a wide query visits the cells, is that of the tuple-keyed grid).
    #[test]
    fn cell_keys_hash_like_tuples() {
        use std::hash::BuildHasher;
        let s = std::hash::BuildHasherDefault::<crate::util::IdHasher>::default();
        for c in [[0i64, 0, 0], [1, -2, 3], [i64::MIN, 7, i64::MAX]] {
            assert_eq!(s.hash_one(Cell(c)), s.hash_one((c[0], c[1], c[2])));
        }
    }
}

/// The examples of this crate-private module (run as unit tests, since doc-tests only see
/// the public API).
#[cfg(test)]
mod examples {
    #[test]
    fn example_1() {
        use crate::geom::grid::{BoxGrid, PointGrid};
        let pts = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [5.0, 5.0]];
        let g = PointGrid::new(&pts, 1.0);
        let mut near = Vec::new();
        g.for_each_within([0.0, 0.0], 1.5, |i| {
            near.push(i);
            true
        });
        near.sort();
        assert_eq!(near, [0, 1, 2]);

        let mut b = BoxGrid::new([0.0; 3], 1.0, true);
        b.insert(7, [0.5, 0.5, 0.5], [2.5, 0.6, 0.7]);
        let mut out = Vec::new();
        b.query([2.0, 0.0, 0.0], [3.0, 1.0, 1.0], &mut out);
        assert_eq!(out, [7]);
    }
    #[test]
    fn example_2() {
        use crate::geom::grid::fit_cells;
        let (cell, dims) = fit_cells([10.0, 0.0], 1.0, 100);
        assert_eq!((cell, dims), (1.0, [11, 1]));
        let (cell, dims) = fit_cells([1e300, 1e300], 1e-300, 1000);
        assert!(cell.is_finite() && dims[0] * dims[1] <= 1000);
        let (_, dims) = fit_cells([f64::INFINITY, 1.0], 1.0, 1000);
        assert_eq!(dims[0], 1);
    }
}
