//! The empty-lune test of the lune-based β-skeleton (Veltkamp Def. 2.16, b ∈ (0, 1); the RNG of
//! Def. 2.8 is b = ½) for the Gabriel edges of a 2D point set.
//!
//! The lune of uv is the open intersection of the balls D₁ (centre u + k(v − u)) and D₂ (centre
//! v + k(u − v)) of radius k|uv|, k = 1/(2(1 − b)). An edge is tested in two steps:
//! 1. the apexes of its two Delaunay triangles (the likeliest blockers, already at hand);
//! 2. a grid query over the lune's own bounding box — not the box of the disc around the
//!    midpoint that contains the lune, which is up to twice as large. Its coordinates are kept
//!    in the grid's cell order ([`LuneGrid`]), so a query reads a few contiguous runs.
//!
//! The box is the extent of the lune's boundary: the two arcs' extreme points in each axis
//! direction that lie in the other ball, and the two corners where the circles cross; it is
//! widened by a margin far above the rounding error. A point is rejected in floating point only
//! when it is certainly outside a ball (margin again); every other one is decided by the exact
//! [`in_lune_ball`]. Neither the apexes nor the Delaunay neighbours of u and v alone decide the
//! lune (the test `one_ring_is_not_enough` has a counterexample), hence step 2.

use crate::geom::distance::in_lune_ball;
use crate::geom::grid::PointGrid as Grid;
use rayon::prelude::*;

/// Relative margin of the float filters (their rounding error is a few ε of the magnitudes
/// involved).
const MARGIN: f64 = 1e-9;

/// The lune of an edge in coordinates relative to its end u.
struct Lune {
    pu: [f64; 2],
    pv: [f64; 2],
    b: f64,
    k: f64,
    c1: [f64; 2],
    c2: [f64; 2],
    r2: f64,
}

impl Lune {
    fn new(pu: [f64; 2], pv: [f64; 2], b: f64) -> Self {
        let a = [pv[0] - pu[0], pv[1] - pu[1]];
        let k = 0.5 / (1.0 - b);
        Lune {
            pu,
            pv,
            b,
            k,
            c1: [k * a[0], k * a[1]],
            c2: [(1.0 - k) * a[0], (1.0 - k) * a[1]],
            r2: k * k * (a[0] * a[0] + a[1] * a[1]),
        }
    }

    /// False when q is certainly outside one of the balls (float filter).
    #[inline]
    fn may_contain(&self, q: [f64; 2]) -> bool {
        let x = [q[0] - self.pu[0], q[1] - self.pu[1]];
        let m = MARGIN * (x[0] * x[0] + x[1] * x[1] + self.r2);
        let d1 = (x[0] - self.c1[0]).powi(2) + (x[1] - self.c1[1]).powi(2) - self.r2;
        let d2 = (x[0] - self.c2[0]).powi(2) + (x[1] - self.c2[1]).powi(2) - self.r2;
        !(d1 > m || d2 > m)
    }

    /// Exactly: q lies in the open lune.
    fn contains(&self, q: &[f64; 2]) -> bool {
        self.may_contain(*q)
            && in_lune_ball(q, &self.pu, &self.pv, self.b)
            && in_lune_ball(q, &self.pv, &self.pu, self.b)
    }

    /// A box containing the lune, or with `side` = ±1 its part on that side of u → v (left: +1)
    /// (absolute coordinates; NaN widened to everything).
    fn bbox(&self, side: Option<f64>) -> ([f64; 2], [f64; 2]) {
        let a = [self.pv[0] - self.pu[0], self.pv[1] - self.pu[1]];
        let aa = a[0] * a[0] + a[1] * a[1];
        // the circles cross at the midpoint ± √(k − ¼)·n, n = (−a₁, a₀) the left normal
        let s = (self.k - 0.25).max(0.0).sqrt();
        let (m, n) = ([0.5 * a[0], 0.5 * a[1]], [-s * a[1], s * a[0]]);
        let (mut lo, mut hi) = ([0.0f64, 0.0], [0.0f64, 0.0]);
        let mut add = |x: [f64; 2]| {
            for i in 0..2 {
                lo[i] = lo[i].min(x[i]);
                hi[i] = hi[i].max(x[i]);
            }
        };
        // u (the origin), v and the corners on the side(s) asked for
        add(a);
        for sg in [1.0, -1.0] {
            if side.map_or(true, |t| t == sg) {
                add([m[0] + sg * n[0], m[1] + sg * n[1]]);
            }
        }
        // the extreme points of each arc that lie in the other ball (and on the side)
        let r = self.r2.sqrt();
        let near = self.r2 * (1.0 + MARGIN);
        for (c, other) in [(self.c1, self.c2), (self.c2, self.c1)] {
            for i in 0..2 {
                for sg in [-1.0, 1.0] {
                    let mut x = c;
                    x[i] += sg * r;
                    let d = (x[0] - other[0]).powi(2) + (x[1] - other[1]).powi(2);
                    let h = a[0] * x[1] - a[1] * x[0];
                    let on_side = side.map_or(true, |t| {
                        let lim = -MARGIN * (aa + x[0] * x[0] + x[1] * x[1]);
                        t * h >= lim || (t * h).is_nan() || lim.is_nan()
                    });
                    if (d <= near || d.is_nan() || near.is_nan()) && on_side {
                        add(x);
                    }
                }
            }
        }
        let scale = self.pu[0].abs() + self.pu[1].abs() + self.pv[0].abs() + self.pv[1].abs();
        let delta = MARGIN * r + 1e-14 * scale;
        let mut out = ([0.0; 2], [0.0; 2]);
        for i in 0..2 {
            let (l, h) = (self.pu[i] + lo[i] - delta, self.pu[i] + hi[i] + delta);
            out.0[i] = if l.is_nan() { f64::NEG_INFINITY } else { l };
            out.1[i] = if h.is_nan() { f64::INFINITY } else { h };
        }
        out
    }

    /// True when the open half of the lune on the side of `w` (`side` = +1: left of u → v,
    /// −1: right; w a Delaunay neighbour of u and v there, forming a Delaunay triangle with them)
    /// certainly lies in the open circumdisc of u v w, which is empty. Float filter with a margin:
    /// false when unsure.
    ///
    /// With m the midpoint, n the left normal of u → v (|n| = |uv|), the circle through u, v, w
    /// has its centre at m + σn, σ = q / 2h with h = side·(w − m)·n > 0 and q = |w − m|² − |uv|²/4;
    /// the lune's corner on that side is m + side·√(k − ¼)·n, inside the circle iff
    /// σ > θ = (k − ½) / (2√(k − ¼)), i.e. q − 2θh > 0. Then the arcs from u and from v to the
    /// corner lie in the closed disc too (each arc starts inside it at u or v, as σ > 0, and
    /// ends inside it; two circles meet twice at most), hence the closed half-lune, whose
    /// interior is the open half-lune, lies in the closed disc.
    fn half_covered(&self, w: [f64; 2], side: f64) -> bool {
        let a = [self.pv[0] - self.pu[0], self.pv[1] - self.pu[1]];
        // w − m from differences of nearby points (their rounding error is relative to the
        // edge's scale, not to the coordinates' magnitude)
        let x = [
            (w[0] - self.pu[0]) - 0.5 * a[0],
            (w[1] - self.pu[1]) - 0.5 * a[1],
        ];
        let aa = a[0] * a[0] + a[1] * a[1];
        let xx = x[0] * x[0] + x[1] * x[1];
        let h = side * (a[0] * x[1] - a[1] * x[0]);
        let q = xx - 0.25 * aa;
        let theta = (self.k - 0.5) / (2.0 * (self.k - 0.25).sqrt());
        h > 0.0 && q - 2.0 * theta * h > MARGIN * (1.0 + theta) * (xx + aa)
    }
}

/// A grid over 2D points with their coordinates in the grid's cell order, for lune queries. It
/// needs only the coordinates (any point set containing the graph's points; repeats are
/// harmless: the ends of an edge are never strictly inside its lune), so it can be built from
/// the input points while the triangulation is being built.
pub struct LuneGrid<'a> {
    grid: Grid<'a, 2>,
    slots: Vec<[f64; 2]>,
}

impl<'a> LuneGrid<'a> {
    /// O(N).
    pub fn new(p: &'a [[f64; 2]]) -> Self {
        let grid = Grid::new(p, 2.0);
        let slots = grid.items().par_iter().map(|&v| p[v as usize]).collect();
        LuneGrid { grid, slots }
    }

    /// True when no point of the grid lies in the open lune of the pair (pu, pv) for
    /// b ∈ (0, 1) (V Def. 2.16). `apexes` = [left, right]: for a Delaunay edge the apexes of its
    /// triangles left and right of u → v, tried first and used to skip the halves of the lune
    /// that their empty circumdiscs cover. Exact.
    pub fn lune_empty(
        &self,
        pu: [f64; 2],
        pv: [f64; 2],
        apexes: [Option<[f64; 2]>; 2],
        b: f64,
    ) -> bool {
        let lune = Lune::new(pu, pv, b);
        if apexes.iter().flatten().any(|w| lune.contains(w)) {
            return false;
        }
        // the halves covered by the empty circumdiscs of the edge's triangles need no query
        let covered = |k: usize, side: f64| apexes[k].is_some_and(|w| lune.half_covered(w, side));
        let side = match (covered(0, 1.0), covered(1, -1.0)) {
            (true, true) => return true,
            (true, false) => Some(-1.0),
            (false, true) => Some(1.0),
            (false, false) => None,
        };
        let (lo, hi) = lune.bbox(side);
        self.grid.for_each_run(lo, hi, |run| {
            // (u and v themselves lie on the lune's boundary: `contains` rejects them)
            !self.slots[run].iter().any(|q| lune.contains(q))
        })
    }
}
