//! Cached classification for point-in-mesh batches on a 3D flintstone tree (issue 18's
//! throughput target; an extension of V §7.4, not in the text).
//!
//! A regular grid over the mesh's bounding box; each cell is labelled once:
//! - **near** (answered by the exact walk of `query3.rs`) if the bounding box of some input
//!   triangle meets the cell's *closed, slightly enlarged* box ([`CellCache3`] keeps, per axis,
//!   the interval `[lo_i, hi_i]` of cell `i`; consecutive intervals overlap by a margin);
//! - otherwise **empty**: no triangle meets the cell's box, so the box — convex and disjoint
//!   from the surface — lies in one component of ℝ³ minus the surface, where the crossing
//!   parity is constant; the cell's answer is [`Containment::Inside`] or
//!   [`Containment::Outside`], never the boundary.
//!
//! Empty cells that share a face have overlapping boxes, so their union is connected and
//! still misses the surface: the same answer. The labels of the empty cells therefore come
//! from a flood fill over face neighbours, with **one exact walk per component** (at the centre
//! of its first cell, checked to lie in the cell's box). A wrong "empty" label would give a
//! wrong answer to every query in that cell (the tests catch it: points on the surface would
//! not come out as [`Containment::Boundary`]).
//!
//! A query X outside the bounding box of the vertices is outside (the surface lies in the box).
//! Otherwise its cell index is computed in `f64` and then **verified exactly**: X must lie in
//! the cell's stored box by plain comparisons, else (rounding at a cell face) the walk answers.
//! So the cell index never has to be exact, and every answer equals the walk's. Queries in
//! near cells run the walk unchanged (exact at the leaves). No allocation per query; batches
//! are parallel (rayon), answers in input order.
//!
//! Cost: the build marks O(triangles × cells per triangle box) cells (binary search per axis
//! on the exact intervals), fills O(cells) and walks once per component; a query is O(1)
//! in empty cells and one walk in near cells.

use super::query::Containment;
use super::query3::contains_batch_by;
use super::tree3::FlintTree3;
use super::FlintError;
use crate::geom::Point3;

/// The default number of grid cells (about 2²², one byte each; the cells are about cubic).
pub const DEFAULT_CELLS: usize = 1 << 22;
/// At most this many cells (16 MiB of labels) whatever the caller asks.
pub const MAX_CELLS: usize = 1 << 24;

/// Cell labels.
const OUT: u8 = 0;
const IN: u8 = 1;
const NEAR: u8 = 2;
/// An empty cell not labelled yet (only during the build).
const UNSEEN: u8 = 3;

/// A grid of cached answers over a [`FlintTree3`] (see the module doc).
#[derive(Debug, Clone)]
pub struct CellCache3<'a> {
    tree: &'a FlintTree3,
    /// The bounding box of the mesh's vertices (exact).
    min: [f64; 3],
    max: [f64; 3],
    /// Cells per axis.
    n: [usize; 3],
    /// `n[k] / extent[k]` (the index estimate only; verified against `lo`/`hi`).
    inv: [f64; 3],
    /// Per axis, the closed interval of each cell (nondecreasing in the cell index; cell `i`'s
    /// interval overlaps cell `i + 1`'s).
    lo: [Vec<f64>; 3],
    hi: [Vec<f64>; 3],
    /// Per cell (x fastest): OUT, IN or NEAR.
    label: Vec<u8>,
    /// Connected components of empty cells (= exact walks of the build).
    components: usize,
}

impl FlintTree3 {
    /// The cached classification of [`CellCache3`] with about `cells` grid cells (at least 1,
    /// at most about [`MAX_CELLS`]).
    pub fn cell_cache(&self, cells: usize) -> CellCache3<'_> {
        CellCache3::new(self, cells)
    }
}

impl<'a> CellCache3<'a> {
    /// Builds the grid over `tree`'s bounding box (see the module doc).
    pub fn new(tree: &'a FlintTree3, cells: usize) -> CellCache3<'a> {
        let mut min = [f64::INFINITY; 3];
        let mut max = [f64::NEG_INFINITY; 3];
        for p in &tree.pos {
            for k in 0..3 {
                min[k] = min[k].min(p[k]);
                max[k] = max[k].max(p[k]);
            }
        }
        let ext: [f64; 3] = std::array::from_fn(|k| max[k] - min[k]);
        // cubic cells of side h with about `cells` of them; ≥ 1 and ≤ 2048 per axis
        let vol: f64 = ext.iter().map(|e| e.max(f64::MIN_POSITIVE)).product();
        let h = (vol / cells.clamp(1, MAX_CELLS) as f64).cbrt();
        let n: [usize; 3] = std::array::from_fn(|k| {
            let m = (ext[k] / h).ceil();
            if m.is_finite() {
                (m as usize).clamp(1, 2048)
            } else {
                1
            }
        });
        // rounding up per axis (or a flat box) may overshoot: halve the longest axis
        let mut n = n;
        while n[0] * n[1] * n[2] > 2 * MAX_CELLS {
            let k = (0..3).max_by_key(|&k| n[k]).unwrap_or(0);
            n[k] = n[k].div_ceil(2);
        }
        let inv: [f64; 3] = std::array::from_fn(|k| n[k] as f64 / ext[k]);
        let mut lo: [Vec<f64>; 3] = Default::default();
        let mut hi: [Vec<f64>; 3] = Default::default();
        for k in 0..3 {
            let step = ext[k] / n[k] as f64;
            // the margin only has to exceed the rounding of the index estimate; membership
            // is checked exactly, so its size trades fallbacks against near cells
            let margin = step * (1.0 / 1024.0);
            lo[k] = (0..n[k])
                .map(|i| min[k] + i as f64 * step - margin)
                .collect();
            hi[k] = (0..n[k])
                .map(|i| {
                    if i + 1 == n[k] {
                        max[k] + margin
                    } else {
                        min[k] + (i + 1) as f64 * step + margin
                    }
                })
                .collect();
        }
        let mut g = CellCache3 {
            tree,
            min,
            max,
            n,
            inv,
            lo,
            hi,
            label: vec![UNSEEN; n[0] * n[1] * n[2]],
            components: 0,
        };
        g.mark_near();
        g.fill();
        g
    }

    /// Marks every cell whose box meets the bounding box of a triangle (exact comparisons;
    /// the range per axis by binary search on the nondecreasing interval ends).
    fn mark_near(&mut self) {
        let [nx, ny, _] = self.n;
        for t in &self.tree.tris {
            let [a, b, c] = t.map(|v| self.tree.pos[v as usize]);
            let r: [(usize, usize); 3] = std::array::from_fn(|k| {
                let tmin = a[k].min(b[k]).min(c[k]);
                let tmax = a[k].max(b[k]).max(c[k]);
                // cells with hi ≥ tmin and lo ≤ tmax
                let s = self.hi[k].partition_point(|&h| h < tmin);
                let e = self.lo[k].partition_point(|&l| l <= tmax);
                (s, e)
            });
            for z in r[2].0..r[2].1 {
                for y in r[1].0..r[1].1 {
                    let row = (z * ny + y) * nx;
                    self.label[row + r[0].0..row + r[0].1].fill(NEAR);
                }
            }
        }
    }

    /// Labels the empty cells: flood fill over face neighbours, one exact walk per component.
    fn fill(&mut self) {
        let [nx, ny, nz] = self.n;
        let mut stack: Vec<usize> = Vec::new();
        for start in 0..self.label.len() {
            if self.label[start] != UNSEEN {
                continue;
            }
            let (x, y, z) = (start % nx, (start / nx) % ny, start / (nx * ny));
            let c = [x, y, z];
            let centre: [f64; 3] =
                std::array::from_fn(|k| 0.5 * (self.lo[k][c[k]] + self.hi[k][c[k]]));
            let inside_box =
                (0..3).all(|k| self.lo[k][c[k]] <= centre[k] && centre[k] <= self.hi[k][c[k]]);
            // the centre of an empty cell is never on the surface; should the walk say so
            // (or the centre round out of its box), the component is left to the walk
            let want = match (inside_box, self.tree.locate(centre).0) {
                (true, Containment::Inside) => IN,
                (true, Containment::Outside) => OUT,
                _ => NEAR,
            };
            self.components += 1;
            self.label[start] = want;
            stack.push(start);
            while let Some(i) = stack.pop() {
                let (x, y, z) = (i % nx, (i / nx) % ny, i / (nx * ny));
                let mut visit = |j: usize, label: &mut Vec<u8>| {
                    if label[j] == UNSEEN {
                        label[j] = want;
                        stack.push(j);
                    }
                };
                if x > 0 {
                    visit(i - 1, &mut self.label);
                }
                if x + 1 < nx {
                    visit(i + 1, &mut self.label);
                }
                if y > 0 {
                    visit(i - nx, &mut self.label);
                }
                if y + 1 < ny {
                    visit(i + nx, &mut self.label);
                }
                if z > 0 {
                    visit(i - nx * ny, &mut self.label);
                }
                if z + 1 < nz {
                    visit(i + nx * ny, &mut self.label);
                }
            }
        }
    }

    /// Where finite `x` is relative to the closed mesh: the cached answer of its cell, or the
    /// exact walk in a near cell or when `x` is not verified to lie in the estimated cell.
    #[inline]
    pub(crate) fn locate(&self, x: [f64; 3]) -> Containment {
        if (0..3).any(|k| x[k] < self.min[k] || x[k] > self.max[k]) {
            return Containment::Outside;
        }
        let mut cell = [0usize; 3];
        for k in 0..3 {
            // `as` saturates (NaN → 0), the min keeps the top face in the last cell
            let i = (((x[k] - self.min[k]) * self.inv[k]) as usize).min(self.n[k] - 1);
            if !(self.lo[k][i] <= x[k] && x[k] <= self.hi[k][i]) {
                return self.tree.locate(x).0;
            }
            cell[k] = i;
        }
        match self.label[(cell[2] * self.n[1] + cell[1]) * self.n[0] + cell[0]] {
            IN => Containment::Inside,
            OUT => Containment::Outside,
            _ => self.tree.locate(x).0,
        }
    }

    /// [`FlintTree3::contains`] through the cache (same answers; non-finite `x` refused).
    pub fn contains(&self, x: Point3) -> Result<Containment, FlintError> {
        if !(x.x.is_finite() && x.y.is_finite() && x.z.is_finite()) {
            return Err(FlintError::NonFiniteQuery);
        }
        Ok(self.locate([x.x, x.y, x.z]))
    }

    /// [`Self::contains`] for many points, in parallel (rayon), answers in input order.
    pub fn contains_batch(&self, xs: &[Point3]) -> Result<Vec<Containment>, FlintError> {
        contains_batch_by(xs, |x| self.locate(x))
    }

    /// Cells per axis.
    pub fn dims(&self) -> [usize; 3] {
        self.n
    }

    /// Cells labelled outside, inside and near (walk).
    pub fn label_counts(&self) -> [usize; 3] {
        let mut c = [0usize; 3];
        for &l in &self.label {
            c[l as usize] += 1;
        }
        c
    }

    /// Connected components of empty cells, i.e. exact walks run by the build.
    pub fn components(&self) -> usize {
        self.components
    }

    /// The cached label of cell `(i, j, k)`: `Some(answer)` for an empty cell, `None` for a
    /// near one; and the cell's closed box `[min, max]` (for tests).
    pub fn cell(&self, c: [usize; 3]) -> (Option<Containment>, [[f64; 3]; 2]) {
        let l = self.label[(c[2] * self.n[1] + c[1]) * self.n[0] + c[0]];
        let ans = match l {
            IN => Some(Containment::Inside),
            OUT => Some(Containment::Outside),
            _ => None,
        };
        (
            ans,
            [
                std::array::from_fn(|k| self.lo[k][c[k]]),
                std::array::from_fn(|k| self.hi[k][c[k]]),
            ],
        )
    }
}
