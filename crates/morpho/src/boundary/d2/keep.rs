//!KEEP2_DOC

use super::constrict::{ekey, General};
use crate::boundary::BoundaryError;
use crate::delaunay::d2::Delaunay2;
use crate::geom::intersect::segments_cross_properly;

impl General<'_> {
    /// V §5.7 rewiring: keep edge `kab` from i or j crosses the triangle i j k of boundary edge
    /// i→j; delete other–k and insert other–l (l the keep edge's other end, other the end of
    /// i→j it does not start from) so that i j l becomes a boundary triangle. Returns false
    /// (nothing done) when the keep edge starts at neither i nor j.
    pub(super) fn rewire(&mut self, i: u32, j: u32, k: u32, kab: [u32; 2]) -> bool {
        let [a, b] = kab;
        let (shared, l) = if a == j || b == j {
            (j, if a == j { b } else { a })
        } else if a == i || b == i {
            (i, if a == i { b } else { a })
        } else {
            return false;
        };
        let other = if shared == j { i } else { j };
        if let Some(&e) = self.id.get(&ekey(other, k)) {
            if !self.keep.contains(&ekey(other, k)) {
                self.kill(e);
            }
        }
        if !self.has(other, l) && self.inside(other, l) {
            self.add_edge(other, l);
        }
        true
    }

    /// Segment ab properly crosses a live keep edge.
    pub(super) fn crosses_keep(&self, a: u32, b: u32) -> bool {
        let (pa, pb) = (self.p[a as usize], self.p[b as usize]);
        let mut hit = false;
        self.egrid.for_each(
            [pa[0].min(pb[0]), pa[1].min(pb[1])],
            [pa[0].max(pb[0]), pa[1].max(pb[1])],
            |e| {
                let [u, w] = self.edges[e as usize];
                if !hit
                    && self.live[e as usize]
                    && self.keep.contains(&ekey(u, w))
                    && segments_cross_properly(pa, pb, self.p[u as usize], self.p[w as usize])
                {
                    hit = true;
                }
            },
        );
        hit
    }
}

/// The keep edges (input indices) in vertex indices of `d`, checked: both ends name points,
/// they are two different points, and [`check_keep`] holds.
pub(super) fn keep_vertices(
    d: &Delaunay2,
    p: &[[f64; 2]],
    keep_in: &[[u32; 2]],
) -> Result<Vec<[u32; 2]>, BoundaryError> {
    let n_in = d.vertex_of_input.len();
    let mut keep = Vec::with_capacity(keep_in.len());
    for (index, &[a, b]) in keep_in.iter().enumerate() {
        if a as usize >= n_in || b as usize >= n_in {
            return Err(BoundaryError::KeepEdgeOutOfRange {
                index,
                edge: [a, b],
                points: n_in,
            });
        }
        let (u, v) = (d.vertex_of_input[a as usize], d.vertex_of_input[b as usize]);
        if u == v {
            return Err(BoundaryError::KeepEdgeDuplicate {
                index,
                edge: [a, b],
            });
        }
        keep.push([u, v]);
    }
    check_keep(p, &keep)?;
    Ok(keep)
}

/// Keep edges must not pass through another point or cross each other.
fn check_keep(p: &[[f64; 2]], keep: &[[u32; 2]]) -> Result<(), BoundaryError> {
    use crate::geom::predicates::raw::orient2d;
    if keep.is_empty() {
        return Ok(());
    }
    for (k, &[a, b]) in keep.iter().enumerate() {
        let (pa, pb) = (p[a as usize], p[b as usize]);
        for (v, &q) in p.iter().enumerate() {
            if v as u32 != a
                && v as u32 != b
                && orient2d(pa, pb, q) == 0.0
                && crate::geom::intersect::on_segment(pa, pb, q)
            {
                return Err(BoundaryError::KeepEdgeThroughPoint { index: k });
            }
        }
        for (j, &[c, e]) in keep.iter().enumerate().skip(k + 1) {
            if crate::geom::intersect::segments_cross_properly(pa, pb, p[c as usize], p[e as usize])
            {
                return Err(BoundaryError::KeepEdgesCross { edges: [k, j] });
            }
        }
    }
    Ok(())
}

/// The keep edges (vertex indices) that are not edges of the cycle `cyc`.
pub(super) fn keep_missing(cyc: &[u32], keep: &[[u32; 2]]) -> Vec<[u32; 2]> {
    if keep.is_empty() {
        return Vec::new();
    }
    let m = cyc.len();
    let mut bedges = std::collections::HashSet::new();
    for k in 0..m {
        let (a, b) = (cyc[k], cyc[(k + 1) % m]);
        bedges.insert((a.min(b), a.max(b)));
    }
    keep.iter()
        .filter(|e| !bedges.contains(&(e[0].min(e[1]), e[0].max(e[1]))))
        .copied()
        .collect()
}
