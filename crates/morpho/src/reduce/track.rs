//! The error of the reduced surface against the original, kept up to date removal by removal
//! (Hamann 1991, Rem. 5.10, (5.41); notes D.3 "Stopping").
//!
//! Every original vertex (knot) is assigned to one current triangle. When a removal replaces a
//! platelet, the knots of its triangles are re-assigned among the new triangles:
//! - height fields: the new triangle whose xy projection contains the knot (exact
//!   `point_in_triangle`); the error is the vertical distance `|f − f̂|` of (5.41);
//! - surfaces: the nearest new triangle; the error is that Euclidean distance, an upper bound
//!   of the knot's distance to the reduced surface.
//!
//! The RMS is `sqrt(Σ err² / knots)`; the maximum is kept as a running maximum (an upper
//! bound, never decreasing). Flat arrays: per triangle slot the head of a linked list of knots.
//! O(knots in the platelet × new triangles) per removal.

use crate::geom::intersect::point_in_triangle;
use crate::geom::vec::{closest_on_triangle, dist};
use crate::util::NONE;

pub(crate) struct Tracker {
    knots: Vec<[f64; 3]>,
    vertical: bool,
    err: Vec<f64>,
    head: Vec<u32>,
    nxt: Vec<u32>,
    pub sse: f64,
    pub max: f64,
    /// Scratch of the last evaluation: (knot, local new triangle, error).
    pending: Vec<(u32, usize, f64)>,
    /// Scratch: the bounding ball of each new triangle.
    balls: Vec<([f64; 3], f64)>,
}

impl Tracker {
    pub fn new(knots: Vec<[f64; 3]>, tris: &[[u32; 3]], vertical: bool) -> Tracker {
        let n = knots.len();
        let mut t = Tracker {
            knots,
            vertical,
            err: vec![0.0; n],
            head: vec![NONE; tris.len()],
            nxt: vec![NONE; n],
            sse: 0.0,
            max: 0.0,
            pending: Vec::new(),
            balls: Vec::new(),
        };
        let mut done = vec![false; n];
        for (i, tr) in tris.iter().enumerate() {
            for &v in tr {
                if !done[v as usize] {
                    done[v as usize] = true;
                    t.nxt[v as usize] = t.head[i];
                    t.head[i] = v;
                }
            }
        }
        t
    }

    pub fn rms(&self) -> f64 {
        (self.sse / self.knots.len().max(1) as f64).sqrt()
    }

    fn error(&self, k: [f64; 3], t: [[f64; 3]; 3]) -> (bool, f64) {
        if self.vertical {
            let (a, b, c) = (t[0], t[1], t[2]);
            let inside = point_in_triangle([k[0], k[1]], [a[0], a[1]], [b[0], b[1]], [c[0], c[1]]);
            let det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
            let l1 = ((k[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (k[1] - a[1])) / det;
            let l2 = ((b[0] - a[0]) * (k[1] - a[1]) - (k[0] - a[0]) * (b[1] - a[1])) / det;
            let z = a[2] + l1 * (b[2] - a[2]) + l2 * (c[2] - a[2]);
            (inside, (k[2] - z).abs())
        } else {
            (true, dist(k, closest_on_triangle(k, t[0], t[1], t[2])))
        }
    }

    /// The (sse, max) after replacing the triangles `removed` by `new` (corner positions);
    /// remembers the assignment for [`Tracker::commit`].
    pub fn evaluate(&mut self, removed: &[u32], new: &[[[f64; 3]; 3]]) -> (f64, f64) {
        self.evaluate_within(removed, new, f64::INFINITY)
            .expect("an unbounded evaluation completes")
    }

    /// [`Tracker::evaluate`], abandoned (`None`, nothing to commit) as soon as one knot's error
    /// exceeds `bound`.
    pub fn evaluate_within(
        &mut self,
        removed: &[u32],
        new: &[[[f64; 3]; 3]],
        bound: f64,
    ) -> Option<(f64, f64)> {
        self.pending.clear();
        let (sse, max) = (self.sse, self.max);
        // surfaces: a triangle farther than |x − c| − r from a knot x (c its centroid, r its
        // farthest corner from c) cannot beat the best one found
        let mut balls = std::mem::take(&mut self.balls);
        balls.clear();
        if !self.vertical {
            balls.extend(new.iter().map(|t| {
                let c = std::array::from_fn(|i| (t[0][i] + t[1][i] + t[2][i]) / 3.0);
                (c, dist(c, t[0]).max(dist(c, t[1])).max(dist(c, t[2])))
            }));
        }
        let r = self.assign(removed, new, bound, &balls, sse, max);
        self.balls = balls;
        r
    }

    /// The knots of `removed` assigned among `new` (the loop of [`Tracker::evaluate_within`]).
    fn assign(
        &mut self,
        removed: &[u32],
        new: &[[[f64; 3]; 3]],
        bound: f64,
        balls: &[([f64; 3], f64)],
        mut sse: f64,
        mut max: f64,
    ) -> Option<(f64, f64)> {
        for &t in removed {
            let mut k = self.head.get(t as usize).copied().unwrap_or(NONE);
            while k != NONE {
                let x = self.knots[k as usize];
                let mut best = (false, f64::INFINITY, 0usize);
                for (j, nt) in new.iter().enumerate() {
                    if let Some(&(c, r)) = balls.get(j) {
                        if dist(x, c) - r > best.1 {
                            continue;
                        }
                    }
                    let (inside, e) = self.error(x, *nt);
                    // prefer containing triangles; among them (or none) the smallest error
                    if (inside && !best.0) || (inside == best.0 && e < best.1) {
                        best = (inside, e, j);
                    }
                }
                if best.1 > bound {
                    self.pending.clear();
                    return None;
                }
                let old = self.err[k as usize];
                sse += best.1 * best.1 - old * old;
                max = max.max(best.1);
                self.pending.push((k, best.2, best.1));
                k = self.nxt[k as usize];
            }
        }
        Some((sse.max(0.0), max))
    }

    /// The root of the summed squared errors of the knots re-assigned by the last
    /// evaluation (at least each one's error, so an evaluation abandoned at a bound `b` on
    /// the knots' errors has this measure above `b` too).
    pub fn last_local_l2(&self) -> f64 {
        self.pending.iter().map(|x| x.2 * x.2).sum::<f64>().sqrt()
    }

    /// Applies the last [`Tracker::evaluate`] with the slots of the new triangles.
    pub fn commit(&mut self, removed: &[u32], slots: &[u32], sse: f64, max: f64) {
        for &t in removed {
            if let Some(h) = self.head.get_mut(t as usize) {
                *h = NONE;
            }
        }
        let top = slots.iter().copied().max().unwrap_or(0) as usize;
        if self.head.len() <= top {
            self.head.resize(top + 1, NONE);
        }
        for &(k, j, e) in &self.pending {
            let s = slots[j] as usize;
            self.err[k as usize] = e;
            self.nxt[k as usize] = self.head[s];
            self.head[s] = k;
        }
        self.sse = sse;
        self.max = max;
    }
}
