//! Validity of a 2D boundary (Veltkamp 1992, §4.2 "Boundary construction 2D": a simple polygon
//! through all vertices).
//!
//! [`check_polygon`] decides, with exact predicates only, whether a vertex cycle is a simple
//! polygon (no two non-adjacent edges meet, adjacent edges share only their common vertex, no
//! repeated vertex) and which input points it misses. Segment pairs are found through a sparse
//! grid of cells about the edges' size (`first_crossing`, in parallel): expected O(n log n) for
//! boundaries with edges of similar length, worst case O(n²). The segment tests are
//! those of [`crate::geom::intersect`].

use crate::geom::intersect::{on_segment, segments_intersect};
use crate::geom::predicates::raw::orient2d;
use crate::geom::Point2;
use rayon::prelude::*;

/// The result of [`check_polygon`].
#[derive(Debug, Clone, PartialEq)]
pub struct PolygonCheck {
    /// The cycle is a simple polygon (≥ 3 distinct vertices, no self-intersection).
    pub simple: bool,
    /// A pair of edges (by the index of their first vertex in the cycle) that meet although
    /// they must not, or a repeated vertex (both positions), when not simple.
    pub conflict: Option<(usize, usize)>,
    /// Input points whose coordinates are not a vertex of the polygon.
    pub missing: Vec<u32>,
    /// Twice the signed area (> 0: counter-clockwise).
    pub area2: f64,
}

/// Checks that `cycle` (indices into `points`) is a simple polygon and lists the points of
/// `points` not on it (a point is on it when a cycle vertex has the same coordinates, so
/// duplicated input points count as covered). Exact; expected O(n log n) for well-spread
/// polygons (parallel). Of edges that meet, the lexicographically smallest pair is reported.
///
/// ```rust
/// use morpho::geom::Point2;
/// use morpho::mesh::validity::check_polygon;
/// let p = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(|(x, y)| Point2::new(x, y));
/// let square = check_polygon(&p, &[0, 1, 2, 3]);
/// assert!(square.simple && square.missing.is_empty() && square.area2 == 2.0);
/// let bowtie = check_polygon(&p, &[0, 2, 1, 3]);
/// assert!(!bowtie.simple && bowtie.conflict.is_some());
/// assert_eq!(check_polygon(&p, &[0, 1, 2]).missing, vec![3]);
/// ```
pub fn check_polygon(points: &[Point2], cycle: &[u32]) -> PolygonCheck {
    let n = cycle.len();
    let mut out = PolygonCheck {
        simple: false,
        conflict: None,
        missing: Vec::new(),
        area2: 0.0,
    };
    let valid_idx = cycle.iter().all(|&i| (i as usize) < points.len());
    if !valid_idx {
        out.missing = (0..points.len() as u32).collect();
        return out;
    }
    // vertices by coordinates (−0 as +0): sorted (key, position) pairs give the repeats and,
    // by binary search, the points not on the cycle
    let key = |p: &Point2| ((p.x + 0.0).to_bits(), (p.y + 0.0).to_bits());
    let mut ck: Vec<((u64, u64), u32)> = cycle
        .par_iter()
        .enumerate()
        .map(|(pos, &i)| (key(&points[i as usize]), pos as u32))
        .collect();
    ck.par_sort_unstable();
    // the first repeat met walking the cycle: the smallest second occurrence of any key, with
    // the first occurrence of that key
    let repeated = ck
        .chunk_by(|a, b| a.0 == b.0)
        .filter(|run| run.len() > 1)
        .map(|run| (run[0].1 as usize, run[1].1 as usize))
        .min_by_key(|r| r.1);
    ck.dedup_by_key(|e| e.0);
    // a point of the cycle is on it; any other only through a cycle vertex of its coordinates
    let mut on = vec![false; points.len()];
    for &i in cycle {
        on[i as usize] = true;
    }
    out.missing = (0..points.len() as u32)
        .into_par_iter()
        .filter(|&i| {
            if on[i as usize] {
                return false;
            }
            let k = key(&points[i as usize]);
            ck.binary_search_by(|e| e.0.cmp(&k)).is_err()
        })
        .collect();
    drop(ck);
    // exact power-of-two scaling so that no predicate over- or underflows at extreme scales
    let m = cycle.iter().fold(0.0f64, |m, &i| {
        let p = points[i as usize];
        m.max(p.x.abs()).max(p.y.abs())
    });
    let s = crate::geom::exact::power_of_two_scale(m);
    let pt = |k: usize| {
        let p = points[cycle[k % n] as usize];
        [p.x * s, p.y * s]
    };
    for k in 0..n {
        let (a, b) = (pt(k), pt(k + 1));
        out.area2 += a[0] * b[1] - a[1] * b[0];
    }
    out.area2 = out.area2 / s / s;
    if n < 3 {
        return out;
    }
    if let Some(r) = repeated {
        out.conflict = Some(r);
        return out;
    }
    // adjacent edges: only a fold-back (collinear overlap) is a conflict
    let fold = (0..n).into_par_iter().find_first(|&k| {
        let (u, v, w) = (pt(k), pt(k + 1), pt(k + 2));
        orient2d(u, v, w) == 0.0 && (on_segment(v, w, u) || on_segment(u, v, w))
    });
    if let Some(k) = fold {
        out.conflict = Some((k, (k + 1) % n));
        return out;
    }
    if let Some(c) = first_crossing(n, &pt) {
        out.conflict = Some(c);
        return out;
    }
    out.simple = true;
    out
}

/// The lexicographically smallest pair (k, m), k < m, of non-adjacent edges of the closed
/// polyline `pt(0), …, pt(n − 1)` (edge k from `pt(k)` to `pt(k + 1)`; `pt` wraps) that meet
/// (exact [`segments_intersect`]).
///
/// Broad phase: a sparse grid with cells of twice the median edge extent (the larger side of
/// an edge's bounding box), as a sorted list of (cell, edge) entries — a polygon fills a thin
/// band of its bounding box, so a dense grid bounded by the number of edges would need cells
/// far larger than the edges. Edges whose box
/// spans more than [`BIG_SPAN`] cells are kept out of the grid and tested against every edge by
/// boxes; the cell is doubled while there are more than a few of them. Pairs are tested in
/// parallel (rayon), each edge against the later edges of its cells.
fn first_crossing(n: usize, pt: &(impl Fn(usize) -> [f64; 2] + Sync)) -> Option<(usize, usize)> {
    let boxes: Vec<([f64; 2], [f64; 2])> = (0..n)
        .into_par_iter()
        .map(|k| {
            let (a, b) = (pt(k), pt(k + 1));
            (
                [a[0].min(b[0]), a[1].min(b[1])],
                [a[0].max(b[0]), a[1].max(b[1])],
            )
        })
        .collect();
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for (l, h) in &boxes {
        for d in 0..2 {
            lo[d] = lo[d].min(l[d]);
            hi[d] = hi[d].max(h[d]);
        }
    }
    let ext = [hi[0] - lo[0], hi[1] - lo[1]];
    let mut lens: Vec<f64> = boxes
        .par_iter()
        .map(|(l, h)| (h[0] - l[0]).max(h[1] - l[1]))
        .collect();
    let mid = lens.len() / 2;
    let mut cell = 2.0 * *lens.select_nth_unstable_by(mid, f64::total_cmp).1;
    drop(lens);
    if !(cell > 0.0 && cell.is_finite()) {
        cell = ext[0].max(ext[1]);
    }
    if !(cell > 0.0 && cell.is_finite()) {
        cell = 1.0;
    }
    // cell ranges (monotone in the coordinates: overlapping boxes share a cell)
    let (dims, big) = loop {
        let dims = [(ext[0] / cell).floor() + 1.0, (ext[1] / cell).floor() + 1.0];
        let dims = if dims[0] * dims[1] < 2f64.powi(62) {
            [dims[0] as u64, dims[1] as u64]
        } else if (2.0 * cell).is_finite() && ext.iter().all(|e| e.is_finite()) {
            cell *= 2.0;
            continue;
        } else {
            [1, 1] // (coordinates that are not finite: one cell)
        };
        let big: Vec<usize> = (0..n)
            .into_par_iter()
            .filter(|&k| cells_spanned(&boxes[k], lo, cell, dims) > BIG_SPAN)
            .collect();
        if big.len() <= 16 + n / 4096 || !(2.0 * cell).is_finite() {
            break (dims, big);
        }
        cell *= 2.0;
    };
    let range = |b: &([f64; 2], [f64; 2])| cell_range(b, lo, cell, dims);
    let mut is_big = vec![false; n];
    for &k in &big {
        is_big[k] = true;
    }
    // (cell key, edge) entries, sorted: by cell, each cell's edges in cycle order
    let mut entries: Vec<(u64, u32)> = (0..n)
        .into_par_iter()
        .filter(|&k| !is_big[k])
        .flat_map_iter(|k| {
            let r = range(&boxes[k]);
            (r[1][0]..=r[1][1])
                .flat_map(move |y| (r[0][0]..=r[0][1]).map(move |x| (y * dims[0] + x, k as u32)))
        })
        .collect();
    entries.par_sort_unstable();
    let adjacent = |k: usize, m: usize| m == k + 1 || (k == 0 && m == n - 1);
    let meet = |k: usize, m: usize| segments_intersect(pt(k), pt(k + 1), pt(m), pt(m + 1));
    let overlap = |k: usize, m: usize| {
        let (a, b) = (&boxes[k], &boxes[m]);
        (0..2).all(|d| a.0[d] <= b.1[d] && b.0[d] <= a.1[d])
    };
    // pairs of two grid edges: for the smallest k with a conflict, its smallest partner
    let in_grid = (0..n).into_par_iter().find_map_first(|k| {
        if is_big[k] {
            return None;
        }
        let r = range(&boxes[k]);
        let mut best: Option<usize> = None;
        for y in r[1][0]..=r[1][1] {
            for x in r[0][0]..=r[0][1] {
                let c = y * dims[0] + x;
                let s = entries.partition_point(|e| e.0 < c);
                for &(ec, m) in &entries[s..] {
                    if ec != c {
                        break;
                    }
                    let m = m as usize;
                    if m > k
                        && best.map_or(true, |b| m < b)
                        && !adjacent(k, m)
                        && overlap(k, m)
                        && meet(k, m)
                    {
                        best = Some(m);
                    }
                }
            }
        }
        best.map(|m| (k, m))
    });
    // pairs with a big edge: each big edge against every edge
    let with_big = big
        .par_iter()
        .filter_map(|&b| {
            (0..n)
                .filter(|&m| m != b)
                .map(|m| (b.min(m), b.max(m)))
                .filter(|&(k, m)| !adjacent(k, m) && overlap(k, m) && meet(k, m))
                .min()
        })
        .min();
    match (in_grid, with_big) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// Edges whose box spans more cells than this are tested by boxes against every edge
/// ([`first_crossing`]).
const BIG_SPAN: u64 = 1024;

/// The cell range of a box (clamped to the grid of `dims` cells from `lo`).
fn cell_range(b: &([f64; 2], [f64; 2]), lo: [f64; 2], cell: f64, dims: [u64; 2]) -> [[u64; 2]; 2] {
    let f = |v: f64, d: usize| -> u64 {
        let c = ((v - lo[d]) / cell).floor();
        if c.is_nan() || c < 0.0 {
            0
        } else {
            (c as u64).min(dims[d] - 1)
        }
    };
    [[f(b.0[0], 0), f(b.1[0], 0)], [f(b.0[1], 1), f(b.1[1], 1)]]
}

/// The number of cells a box spans.
fn cells_spanned(b: &([f64; 2], [f64; 2]), lo: [f64; 2], cell: f64, dims: [u64; 2]) -> u64 {
    let r = cell_range(b, lo, cell, dims);
    (r[0][1] - r[0][0] + 1) * (r[1][1] - r[1][0] + 1)
}

/// The O(n²) reference check of simplicity (every pair of edges), for tests: the oracle of
/// [`check_polygon`]`(…).simple`.
///
/// ```rust
/// use morpho::geom::Point2;
/// use morpho::mesh::validity::is_simple_brute;
/// let p = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].map(|(x, y)| Point2::new(x, y));
/// assert!(is_simple_brute(&p, &[0, 1, 2, 3]));
/// assert!(!is_simple_brute(&p, &[0, 2, 1, 3]));
/// ```
pub fn is_simple_brute(points: &[Point2], cycle: &[u32]) -> bool {
    let n = cycle.len();
    if n < 3 {
        return false;
    }
    let pt = |k: usize| {
        let p = points[cycle[k % n] as usize];
        [p.x, p.y]
    };
    for i in 0..n {
        for j in i + 1..n {
            if pt(i) == pt(j) {
                return false;
            }
        }
    }
    for i in 0..n {
        for j in i + 1..n {
            let adjacent = j == i + 1 || (i == 0 && j == n - 1);
            if adjacent {
                // share exactly one vertex: overlap iff collinear fold-back
                let (s, v, t) = if j == i + 1 {
                    (pt(i), pt(i + 1), pt(i + 2))
                } else {
                    (pt(n - 1), pt(0), pt(1))
                };
                if orient2d(s, v, t) == 0.0 && (on_segment(v, t, s) || on_segment(s, v, t)) {
                    return false;
                }
            } else if segments_intersect(pt(i), pt(i + 1), pt(j), pt(j + 1)) {
                return false;
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(v: &[[f64; 2]]) -> Vec<Point2> {
        v.iter().map(|a| Point2::new(a[0], a[1])).collect()
    }

    #[test]
    fn square_and_bowtie() {
        let pts = p(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
        let c = check_polygon(&pts, &[0, 1, 2, 3]);
        assert!(c.simple && c.missing.is_empty() && c.area2 > 0.0);
        let c = check_polygon(&pts, &[0, 2, 1, 3]);
        assert!(!c.simple);
        assert!(!is_simple_brute(&pts, &[0, 2, 1, 3]));
        let c = check_polygon(&pts, &[0, 1, 2]);
        assert!(c.simple && c.missing == vec![3]);
    }

    #[test]
    fn touching_vertex_and_foldback() {
        // vertex 4 touches edge 0-1 from above
        let pts = p(&[
            [0.0, 0.0],
            [2.0, 0.0],
            [2.0, 2.0],
            [1.0, 1.0],
            [1.0, 0.0],
            [0.0, 2.0],
        ]);
        let c = check_polygon(&pts, &[0, 1, 2, 4, 5]);
        assert!(!c.simple);
        assert!(!is_simple_brute(&pts, &[0, 1, 2, 4, 5]));
        // collinear fold-back 0 -> 1 -> 4
        let c = check_polygon(&pts, &[0, 1, 4, 3]);
        assert!(!c.simple);
        assert!(!is_simple_brute(&pts, &[0, 1, 4, 3]));
        // collinear but straight: fine
        let c = check_polygon(&pts, &[0, 4, 1, 2, 5]);
        assert!(c.simple && is_simple_brute(&pts, &[0, 4, 1, 2, 5]));
    }

    #[test]
    fn verdicts_do_not_depend_on_the_absolute_scale() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        for _ in 0..200 {
            let n = rng.gen_range(3..8);
            let pts: Vec<Point2> = (0..n)
                .map(|_| Point2::new(rng.gen_range(0..4) as f64, rng.gen_range(0..4) as f64))
                .collect();
            let cycle: Vec<u32> = (0..n as u32).collect();
            let want = check_polygon(&pts, &cycle);
            // powers of two keep the configuration exactly; the products of the predicates
            // under- or overflow at these scales unless the check rescales
            for scale in [
                2f64.powi(-1000),
                2f64.powi(-520),
                2f64.powi(520),
                2f64.powi(1000),
            ] {
                let q: Vec<Point2> = pts.iter().map(|p| p * scale).collect();
                let got = check_polygon(&q, &cycle);
                assert_eq!(got.simple, want.simple, "{pts:?} at scale {scale:e}");
                assert_eq!(got.conflict, want.conflict);
                // (the area itself, in input units, underflows to 0 at 2^-1000)
                if got.area2 != 0.0 {
                    assert_eq!(got.area2 > 0.0, want.area2 > 0.0);
                }
            }
        }
    }

    /// The broad phase finds the lexicographically smallest pair of non-adjacent edges that
    /// meet, as all pairs do: on star-shaped polygons (simple) with a few or many long spikes
    /// (edges kept out of the grid; many of them coarsen the grid), on integer coordinates
    /// (touching and collinear cases), and after swapping vertices (crossings).
    #[test]
    fn first_crossing_is_the_smallest_pair_of_all_pairs() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(23);
        let (mut simple, mut crossing) = (0, 0);
        for case in 0..60 {
            let n = rng.gen_range(20..400);
            let spikes = [0, 5, 40][case % 3];
            let integer = case % 2 == 1;
            let mut ang: Vec<f64> = (0..n)
                .map(|_| rng.gen_range(0.0..std::f64::consts::TAU))
                .collect();
            ang.sort_by(f64::total_cmp);
            let mut pts: Vec<[f64; 2]> = ang
                .iter()
                .enumerate()
                .map(|(i, a)| {
                    let r = if i % (n / spikes.max(1)).max(1) == 0 && spikes > 0 {
                        50.0
                    } else {
                        rng.gen_range(0.5..1.0)
                    };
                    let q = [r * a.cos(), r * a.sin()];
                    if integer {
                        q.map(|x| (x * 20.0).round())
                    } else {
                        q
                    }
                })
                .collect();
            for _ in 0..case % 4 {
                let (i, j) = (rng.gen_range(0..n), rng.gen_range(0..n));
                pts.swap(i, j);
            }
            let pt = |k: usize| pts[k % n];
            let adjacent = |k: usize, m: usize| m == k + 1 || (k == 0 && m == n - 1);
            let mut want = None;
            'outer: for k in 0..n {
                for m in k + 1..n {
                    if !adjacent(k, m) && segments_intersect(pt(k), pt(k + 1), pt(m), pt(m + 1)) {
                        want = Some((k, m));
                        break 'outer;
                    }
                }
            }
            assert_eq!(first_crossing(n, &pt), want, "case {case}");
            if want.is_some() {
                crossing += 1;
            } else {
                simple += 1;
            }
        }
        assert!(simple > 10 && crossing > 10, "{simple} {crossing}");
    }

    #[test]
    fn grid_agrees_with_brute_on_random_cycles() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        for _ in 0..300 {
            let n = rng.gen_range(3..9);
            let pts: Vec<Point2> = (0..n)
                .map(|_| Point2::new(rng.gen_range(0..4) as f64, rng.gen_range(0..4) as f64))
                .collect();
            let cycle: Vec<u32> = (0..n as u32).collect();
            assert_eq!(
                check_polygon(&pts, &cycle).simple,
                is_simple_brute(&pts, &cycle)
            );
        }
    }
}
