//! The interaction proxy of a large mesh: vertex clustering on a uniform grid (Rossignac and
//! Borrel 1993, "Multi-resolution 3D approximations for rendering complex scenes"). The viewer
//! draws it while the camera moves and the full mesh when the camera rests (issue 22: a
//! 1M-triangle contour surface must orbit at ≥ 30 frames/s with software GL).
//!
//! Every vertex falls into a cubic cell of a grid over the bounding box; the cell's vertices
//! merge into one at their mean (vertex properties: the mean of their finite values, NaN when
//! none); a triangle survives when its three vertices lie in three different cells, once per
//! unordered triple (the first one's orientation is kept). The cell size is searched so that
//! the proxy has between 90 % and 100 % of `target` triangles when it can: a few passes, each
//! scaling the cells by √(count/target) (a surface's triangle count grows with the square of
//! the resolution), bisecting once the target is bracketed.
//!
//! The proxy is a picture aid, not a reduction: it may change the topology (holes close,
//! thin parts vanish). `morpho reduce` keeps topology and bounds the error.
//!
//! Complexity: O((V + T) · passes) time (at most nine passes), O(V + T) memory.
//! Preconditions: none (non-finite coordinates fall into the first cell).

use crate::util::{sorted3, IdMap, IdSet};

/// A clustered mesh: positions, triangle indices (three per triangle), one value array per
/// vertex property of the input (same order).
#[derive(Debug, Clone, PartialEq)]
pub struct Proxy {
    /// Cluster positions (the mean of their vertices).
    pub positions: Vec<[f64; 3]>,
    /// Triangles, three indices each.
    pub indices: Vec<u32>,
    /// Per property, the mean of the cluster's finite values (NaN when none).
    pub props: Vec<Vec<f64>>,
}

/// One clustering pass with `g` cells along the longest side of the box `lo`..`lo+ext`.
fn cluster_pass(
    positions: &[[f64; 3]],
    indices: &[u32],
    props: &[&[f64]],
    lo: [f64; 3],
    ext: f64,
    g: u32,
) -> Proxy {
    let h = ext / g as f64;
    // cells per axis (the longest side's far face falls into cell g)
    let n = g as u64 + 1;
    let cell_of = |p: &[f64; 3]| -> u64 {
        let mut key = 0u64;
        for k in (0..3).rev() {
            let c = ((p[k] - lo[k]) / h).floor();
            let c = if c.is_finite() {
                c.clamp(0.0, (n - 1) as f64) as u64
            } else {
                0
            };
            key = key * n + c;
        }
        key
    };
    let mut id_of: IdMap<u64, u32> = IdMap::default();
    let mut cluster = Vec::with_capacity(positions.len());
    let mut sum: Vec<[f64; 4]> = Vec::new();
    for p in positions {
        let next = sum.len() as u32;
        let c = *id_of.entry(cell_of(p)).or_insert(next);
        if c == next {
            sum.push([0.0; 4]);
        }
        if p.iter().all(|x| x.is_finite()) {
            let s = &mut sum[c as usize];
            s[0] += p[0];
            s[1] += p[1];
            s[2] += p[2];
            s[3] += 1.0;
        }
        cluster.push(c);
    }
    // the surviving triangles, and the clusters they use renumbered in order of first use
    let mut seen: IdSet<[u32; 3]> = IdSet::default();
    let mut new_id = vec![u32::MAX; sum.len()];
    let mut order = Vec::new();
    let mut out = Vec::new();
    for t in indices.chunks_exact(3) {
        let c = [
            cluster[t[0] as usize],
            cluster[t[1] as usize],
            cluster[t[2] as usize],
        ];
        if c[0] == c[1] || c[1] == c[2] || c[0] == c[2] || !seen.insert(sorted3(c)) {
            continue;
        }
        for x in c {
            if new_id[x as usize] == u32::MAX {
                new_id[x as usize] = order.len() as u32;
                order.push(x);
            }
            out.push(new_id[x as usize]);
        }
    }
    let positions_out = order
        .iter()
        .map(|&c| {
            let s = sum[c as usize];
            if s[3] > 0.0 {
                [s[0] / s[3], s[1] / s[3], s[2] / s[3]]
            } else {
                lo
            }
        })
        .collect();
    let props_out = props
        .iter()
        .map(|v| {
            let mut acc = vec![(0.0f64, 0u32); sum.len()];
            for (i, &x) in v.iter().enumerate() {
                if x.is_finite() {
                    let a = &mut acc[cluster[i] as usize];
                    a.0 += x;
                    a.1 += 1;
                }
            }
            order
                .iter()
                .map(|&c| {
                    let (s, k) = acc[c as usize];
                    if k > 0 {
                        s / k as f64
                    } else {
                        f64::NAN
                    }
                })
                .collect()
        })
        .collect();
    Proxy {
        positions: positions_out,
        indices: out,
        props: props_out,
    }
}

/// The proxy of a triangle mesh (flat indices, three per triangle) with about `target`
/// triangles, or `None` when the mesh has no more than `target` triangles already.
///
/// ```
/// use morpho::viewer::cluster_proxy;
/// // a 100×100 grid of squares in the plane, 20 000 triangles
/// let n = 101u32;
/// let pos: Vec<[f64; 3]> = (0..n * n).map(|i| [(i % n) as f64, (i / n) as f64, 0.0]).collect();
/// let mut idx = Vec::new();
/// for j in 0..n - 1 {
///     for i in 0..n - 1 {
///         let a = j * n + i;
///         idx.extend([a, a + 1, a + n + 1, a, a + n + 1, a + n]);
///     }
/// }
/// let p = cluster_proxy(&pos, &idx, &[], 2000).unwrap();
/// let t = p.indices.len() / 3;
/// assert!(t > 1000 && t < 3000, "{t}");
/// ```
pub fn cluster_proxy(
    positions: &[[f64; 3]],
    indices: &[u32],
    props: &[&[f64]],
    target: usize,
) -> Option<Proxy> {
    let tris = indices.len() / 3;
    if tris <= target || target == 0 || positions.is_empty() {
        return None;
    }
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in positions.iter().filter(|p| p.iter().all(|x| x.is_finite())) {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let ext = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    if !(ext > 0.0 && ext.is_finite()) {
        return None;
    }
    // a surface with T triangles sampled by a g-grid: about T ∝ g², start from the input's own
    // resolution (V ≈ T/2 vertices ≈ cells at the finest useful grid)
    let mut g = ((tris as f64).sqrt() * (target as f64 / tris as f64).sqrt()).max(2.0);
    // the finest grid found with at most `target` triangles, and the coarsest with more
    let mut under: Option<(f64, Proxy)> = None;
    let mut over: Option<(f64, Proxy)> = None;
    for _ in 0..8 {
        let gi = g.round().clamp(2.0, 4096.0);
        let p = cluster_pass(positions, indices, props, lo, ext, gi as u32);
        let got = p.indices.len() / 3;
        if got <= target {
            if 10 * got >= 9 * target {
                return Some(p);
            }
            if under.as_ref().map_or(true, |(ug, _)| gi > *ug) {
                under = Some((gi, p));
            }
        } else if over.as_ref().map_or(true, |(og, _)| gi < *og) {
            over = Some((gi, p));
        }
        let lo_g = under.as_ref().map_or(1.0, |(ug, _)| *ug);
        let hi_g = over.as_ref().map_or(f64::INFINITY, |(og, _)| *og);
        let mut next = (gi * (target as f64 / got.max(1) as f64).sqrt()).round();
        if next == gi {
            // the estimate rounds to this grid: one cell more or less
            next = if got > target { gi - 1.0 } else { gi + 1.0 };
        }
        if !(next > lo_g && next < hi_g) {
            next = if hi_g.is_finite() {
                (0.5 * (lo_g + hi_g)).floor()
            } else {
                2.0 * gi
            };
        }
        if next <= lo_g || next >= hi_g || gi >= 4096.0 || next < 2.0 {
            break;
        }
        g = next;
    }
    // at most the target when such a grid was found, else the smallest proxy above it
    under.or(over).map(|(_, p)| p)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A UV sphere: (positions, flat indices).
    fn sphere(n: usize) -> (Vec<[f64; 3]>, Vec<u32>) {
        let mut p = vec![[0.0, 0.0, 1.0]];
        for i in 1..n {
            let th = std::f64::consts::PI * i as f64 / n as f64;
            for j in 0..2 * n {
                let ph = std::f64::consts::PI * j as f64 / n as f64;
                p.push([th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos()]);
            }
        }
        p.push([0.0, 0.0, -1.0]);
        let m = 2 * n;
        let id = |i: usize, j: usize| (1 + (i - 1) * m + j % m) as u32;
        let last = p.len() as u32 - 1;
        let mut t = Vec::new();
        for j in 0..m {
            t.extend([0, id(1, j), id(1, j + 1)]);
            t.extend([last, id(n - 1, j + 1), id(n - 1, j)]);
        }
        for i in 1..n - 1 {
            for j in 0..m {
                t.extend([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                t.extend([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        (p, t)
    }

    #[test]
    fn proxy_of_a_sphere_is_near_the_target_and_on_the_sphere() {
        let (p, t) = sphere(200); // 159 600 triangles
        let vals: Vec<f64> = p.iter().map(|q| q[2]).collect();
        let q = cluster_proxy(&p, &t, &[&vals], 5000).unwrap();
        let n = q.indices.len() / 3;
        assert!((2500..=5000).contains(&n), "{n} triangles");
        assert!(q.indices.iter().all(|&i| (i as usize) < q.positions.len()));
        // cluster means lie inside the unit ball, close to the sphere
        for x in &q.positions {
            let r = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
            assert!(r <= 1.0 + 1e-12 && r > 0.9, "{r}");
        }
        // the property is the mean of the merged vertices' values: near z
        for (x, v) in q.positions.iter().zip(&q.props[0]) {
            assert!((x[2] - v).abs() < 1e-9);
        }
        // no degenerate or repeated triangle
        let mut seen = IdSet::default();
        for c in q.indices.chunks_exact(3) {
            assert!(c[0] != c[1] && c[1] != c[2] && c[0] != c[2]);
            assert!(seen.insert(sorted3([c[0], c[1], c[2]])));
        }
    }

    /// The search ends near the target for many targets (a regression: an estimate that
    /// rounded to the grid just tried once stopped the search and fell back to a 2-cell grid).
    #[test]
    fn proxy_size_tracks_the_target() {
        let (p, t) = sphere(150);
        for target in [500, 1000, 2000, 3000, 7000, 10_000, 20_000] {
            let q = cluster_proxy(&p, &t, &[], target).unwrap();
            let n = q.indices.len() / 3;
            assert!(
                n <= target && 2 * n >= target,
                "target {target}: {n} triangles"
            );
        }
    }

    #[test]
    fn small_or_degenerate_meshes_get_no_proxy() {
        let (p, t) = sphere(10);
        assert!(cluster_proxy(&p, &t, &[], 1_000_000).is_none());
        let flat = vec![[1.0, 1.0, 1.0]; 4];
        assert!(cluster_proxy(&flat, &[0, 1, 2, 1, 2, 3], &[], 1).is_none());
        let nan = vec![
            [f64::NAN; 3],
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        // must not panic; whatever survives indexes valid positions
        if let Some(q) = cluster_proxy(&nan, &[0, 1, 2, 1, 2, 3, 0, 2, 3], &[], 1) {
            assert!(q.indices.iter().all(|&i| (i as usize) < q.positions.len()));
        }
    }
}
