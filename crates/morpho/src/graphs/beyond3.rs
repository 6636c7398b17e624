//! 3D γ-graphs beyond the Delaunay tetrahedralization (Veltkamp 1992, Defs. 3.1–3.3, Thm 3.1,
//! §3.3–3.6): the triangles outside γ([-1,1],[0,1]) whose largest intersection parameter c₁′
//! is ≥ c for a given c < 0.
//!
//! (First version: candidate triples restricted by a necessary condition, decided exactly by
//! [`TriFrame`] on the points that can bind.)

use super::fast::{coords3, Candidates3};
use super::gamma::{triangle_circle, CenterInterval, TriFrame};
use super::grid::Grid;
use crate::delaunay::d3::Delaunay3;
use rayon::prelude::*;
use std::collections::HashSet;

/// The triangles outside γ([-1,1],[0,1]) (i.e. not in `cand.triangles`) whose largest
/// intersection parameter c₁′ is ≥ `c` (c < 0), with their intervals (normal of the sorted
/// corners (b − a) × (c − a)). Sorted by triangle.
pub fn beyond_dt_3d(
    d: &Delaunay3,
    cand: &Candidates3,
    c: f64,
) -> (Vec<[u32; 3]>, Vec<CenterInterval>) {
    let p = coords3(d);
    let n = p.len();
    if n < 4 || c >= 0.0 {
        return (vec![], vec![]);
    }
    let existing: HashSet<[u32; 3]> = cand.triangles.iter().copied().collect();
    let grid = Grid::new(&p, 2.0);
    let cabs = c.abs().min(1.0);
    let k = if cabs >= 1.0 {
        f64::INFINITY
    } else {
        1.0 / (1.0 - cabs)
    };
    // radius of the ball around the circumcentre inside the lens, over r
    let mu = if k.is_finite() {
        k - (k * k - 1.0).sqrt()
    } else {
        0.0
    };
    let reach_over_r = k + (k * k - 1.0).sqrt();
    let per_vertex: Vec<Vec<([u32; 3], CenterInterval)>> = (0..n)
        .into_par_iter()
        .map(|a| {
            let mut found = Vec::new();
            for b in a + 1..n {
                for cc in b + 1..n {
                    let t = [a as u32, b as u32, cc as u32];
                    if existing.contains(&t) {
                        continue;
                    }
                    if let Some(iv) = decide(&p, &grid, t, c, mu, reach_over_r) {
                        found.push((t, iv));
                    }
                }
            }
            found
        })
        .collect();
    per_vertex.into_iter().flatten().unzip()
}

/// Decides one triangle outside γ([-1,1],[0,1]): its exact interval when c₁′ ≥ c.
fn decide(
    p: &[[f64; 3]],
    grid: &Grid<'_, 3>,
    t: [u32; 3],
    c: f64,
    mu: f64,
    reach_over_r: f64,
) -> Option<CenterInterval> {
    let [pa, pb, pc] = t.map(|v| p[v as usize]);
    let f = TriFrame::new(pa, pb, pc)?;
    let (m, r2, _) = triangle_circle(pa, pb, pc)?;
    let r = r2.sqrt();
    // necessary: the open ball of radius μ·r around the circumcentre lies in the lens
    let w = mu * r * (1.0 - 1e-9);
    if w > 0.0 && !grid.for_each_within(m, w, |x| t.contains(&x)) {
        return None;
    }
    let mut iv = f.start();
    let mut add = |x: u32| {
        if !t.contains(&x) {
            f.add(&mut iv, p[x as usize]);
        }
        true
    };
    let reach = r * reach_over_r * (1.0 + 1e-9);
    if reach.is_finite() {
        grid.for_each_within(m, reach, &mut add);
    } else {
        (0..p.len() as u32).for_each(|x| {
            add(x);
        });
    }
    // only a gap can be trusted (see `super::fast::beyond_dt_2d`)
    if iv.lo <= iv.hi {
        return None;
    }
    let (_, c1) = iv.gamma_values()?;
    (c1 >= c).then_some(iv)
}
