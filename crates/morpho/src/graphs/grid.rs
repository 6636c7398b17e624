//! A uniform bucket grid over points in D dimensions (CSR layout: one sorted index array and
//! cell offsets), for range queries in the graph constructions. Building is O(N); a query
//! visits the cells overlapping the query box.

/// Points bucketed into a uniform grid of about `N / per_cell` cells.
pub struct Grid<'a, const D: usize> {
    pts: &'a [[f64; D]],
    min: [f64; D],
    cell: f64,
    dims: [usize; D],
    start: Vec<u32>,
    items: Vec<u32>,
}

impl<'a, const D: usize> Grid<'a, D> {
    /// A grid with about `per_cell` points per occupied cell for uniformly spread points.
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
            cell = maxext.max(1.0);
        }
        // cap the number of cells at ~4N
        let mut dims = [1usize; D];
        loop {
            let mut total = 1usize;
            for k in 0..D {
                dims[k] = ((ext[k] / cell).floor() as usize + 1).max(1);
                total = total.saturating_mul(dims[k]);
            }
            if total <= 4 * pts.len() + 16 {
                break;
            }
            cell *= 1.5;
        }
        let mut g = Grid {
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

    /// The number of cells.
    pub fn cell_count(&self) -> usize {
        self.start.len() - 1
    }

    /// The points of cell `cell`.
    pub fn cell_items(&self, cell: usize) -> &[u32] {
        &self.items[self.start[cell] as usize..self.start[cell + 1] as usize]
    }

    /// Calls `f(cell, d2)` for every cell meeting the box of half-width `r` around `c`, with
    /// `d2` the squared distance from `c` to the cell (0 inside); stops early when `f` returns
    /// false.
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
    /// [`Grid::for_each_run`].
    pub fn items(&self) -> &[u32] {
        &self.items
    }

    /// Calls `f(slots)` for every run of slots (positions in [`Grid::items`]) whose cells meet the
    /// box `[lo, hi]`: one run per row of cells along the first axis (a superset of the points in
    /// the box). `f` returns false to stop early; the function then returns false.
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
