//! The independent continuity check of a split surface (Veltkamp 1992, Thm 8.1; NOTES B.9
//! checks 2–3): every pair of patches sharing an edge (found by its corner positions, not by
//! the construction's bookkeeping) is sampled at `samples` interior points of the edge; at
//! each, both patches' unit normals (8.4) are evaluated from their own control points and
//! compared, `angle = atan2(|n1×n2|, n1·n2)` (a fold, `n1·n2 ≤ 0`, gives an angle ≥ π/2),
//! and the positions are compared (C⁰). O(patches · samples). The side-vertex surface (H ch. 6)
//! has no control points: [`side_vertex_continuity`] compares finite-difference normals.

use super::{SideVertexSurface, SplitSurface};
use crate::geom::vec;
use std::collections::HashMap;

/// What [`continuity`] measured.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Continuity {
    /// Largest normal angle over every macro and micro edge (radians).
    pub max_normal_jump_rad: f64,
    /// Largest normal angle over edges between different macro triangles.
    pub max_macro_jump_rad: f64,
    /// Largest normal angle over edges inside one macro triangle.
    pub max_micro_jump_rad: f64,
    /// Largest distance between the two patches' points along an edge (C⁰ gap).
    pub max_position_gap: f64,
    /// Samples where the normals point into opposite half-spaces (`n1·n2 ≤ 0`).
    pub folds: usize,
    /// Shared edges with at least one fold sample.
    pub fold_edges: usize,
    /// Shared edges whose normal angle exceeds 1e-9 rad, as `(patch, patch)`.
    pub non_g1_edges: Vec<(usize, usize)>,
    /// Patch edges with no partner (0 on a closed surface).
    pub open_edges: usize,
    /// Shared edges examined.
    pub edges: usize,
}

fn key(p: [f64; 3]) -> [u64; 3] {
    p.map(|c| (c + 0.0).to_bits())
}

/// The continuity figures of `s` at `samples` (≥ 1) interior points per edge.
pub fn continuity(s: &SplitSurface, samples: usize) -> Continuity {
    let tris: Vec<_> = s.patches.iter().map(|p| p.triangle()).collect();
    let unit = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let mut map: HashMap<([u64; 3], [u64; 3]), (usize, usize)> = HashMap::new();
    for (p, t) in tris.iter().enumerate() {
        let c = t.corners();
        for i in 0..3 {
            map.insert((key(c[i]), key(c[(i + 1) % 3])), (p, i));
        }
    }
    let mut out = Continuity::default();
    for (&(ka, kb), &(p, i)) in &map {
        let Some(&(q, j)) = map.get(&(kb, ka)) else {
            out.open_edges += 1;
            continue;
        };
        if p > q {
            continue;
        }
        out.edges += 1;
        let mut worst: f64 = 0.0;
        let mut folded = false;
        for k in 1..=samples.max(1) {
            let t = k as f64 / (samples.max(1) + 1) as f64;
            // p runs corner i → i+1; q runs j → j+1 the other way
            let bp = vec::lerp(unit[i], unit[(i + 1) % 3], t);
            let bq = vec::lerp(unit[j], unit[(j + 1) % 3], 1.0 - t);
            let (x1, x2) = (tris[p].eval(bp), tris[q].eval(bq));
            out.max_position_gap = out.max_position_gap.max(vec::dist(x1, x2));
            let (n1, n2) = (tris[p].normal(bp), tris[q].normal(bq));
            let d = vec::dot(n1, n2);
            if d <= 0.0 {
                out.folds += 1;
                folded = true;
            }
            worst = worst.max(vec::norm(vec::cross(n1, n2)).atan2(d));
        }
        out.fold_edges += usize::from(folded);
        if s.patches[p].macro_tri == s.patches[q].macro_tri {
            out.max_micro_jump_rad = out.max_micro_jump_rad.max(worst);
        } else {
            out.max_macro_jump_rad = out.max_macro_jump_rad.max(worst);
        }
        if worst > 1e-9 {
            out.non_g1_edges.push((p, q));
        }
    }
    out.non_g1_edges.sort_unstable();
    out.max_normal_jump_rad = out.max_macro_jump_rad.max(out.max_micro_jump_rad);
    out
}

/// The largest distance between the split surface `s` of `mesh` and the flat mesh, measured
/// at the same parameter: for the three-split, micro patch `3t+i` (corners `V_i, V_{i+1}, Z`
/// of macro triangle t) at barycentric `(a, b, c)` against `a V_i + b V_{i+1} + c·centroid`;
/// for the six-split (`6·T` patches), patch `6t+2i` against the flat `(V_i, M_i, Z)` and
/// `6t+2i+1` against `(M_i, V_{i+1}, Z)`, `M_i` the edge midpoint; where the surface gives
/// each patch's corners in its macro triangle ([`SplitSurface::domain`], the two-split),
/// against the flat triangle of those corners; on the grid with
/// `samples` (≥ 1) steps per micro edge. An upper bound of the distance from the surface to
/// the input mesh. O(patches · samples²).
pub fn max_deviation(s: &SplitSurface, mesh: &crate::mesh::TriMesh, samples: usize) -> f64 {
    let n = samples.max(1);
    let six = s.patches.len() == 6 * mesh.triangles.len();
    let mut worst: f64 = 0.0;
    for (k, patch) in s.patches.iter().enumerate() {
        let Some(t) = mesh.triangles.get(patch.macro_tri as usize) else {
            continue;
        };
        let v = t.map(|i| -> [f64; 3] { mesh.positions[i as usize].into() });
        let z = vec::scale(vec::add(vec::add(v[0], v[1]), v[2]), 1.0 / 3.0);
        let at = |w: [f64; 3]| {
            vec::add(
                vec::add(vec::scale(v[0], w[0]), vec::scale(v[1], w[1])),
                vec::scale(v[2], w[2]),
            )
        };
        let (a, b, z) = if let Some(d) = s
            .domain
            .get(k)
            .filter(|_| s.domain.len() == s.patches.len())
        {
            (at(d[0]), at(d[1]), at(d[2]))
        } else if six {
            let i = (k % 6) / 2;
            let m = vec::midpoint(v[i], v[(i + 1) % 3]);
            if k % 2 == 0 {
                (v[i], m, z)
            } else {
                (m, v[(i + 1) % 3], z)
            }
        } else {
            (v[k % 3], v[(k + 1) % 3], z)
        };
        let tri = patch.triangle();
        for i in 0..=n {
            for j in 0..=n - i {
                let w = [
                    (n - i - j) as f64 / n as f64,
                    j as f64 / n as f64,
                    i as f64 / n as f64,
                ];
                let flat = vec::add(
                    vec::add(vec::scale(a, w[0]), vec::scale(b, w[1])),
                    vec::scale(z, w[2]),
                );
                worst = worst.max(vec::dist(tri.eval(w), flat));
            }
        }
    }
    worst
}

/// The continuity figures of the side-vertex surface `s` at `samples` (≥ 1) interior points
/// per mesh edge, independent of its construction: both patches of an edge (paired by their
/// corner indices) are evaluated at the edge points with [`SideVertexSurface::eval`], and each
/// patch's normal there is the cross product of its own one-sided finite-difference
/// derivatives from inside its triangle ([`SideVertexSurface::difference_normal`]), never the
/// boundary normal the construction prescribes. The jump at a sample is the smallest angle
/// between the two patches' normals over the steps `h = 1e-3, 1e-4, 1e-5, 1e-6`: a crease shows at
/// every step, while the difference error is step-dependent (O(h⁴) truncation, large where a
/// radial conic's end handle nearly collapses and the normal turns within a short distance of
/// the edge; rounding about 1e-13/h; a sample resolved to 1e-10 at a larger step stops
/// there). Edges are checked in parallel. Every edge is a macro edge (`max_micro_jump_rad` = 0);
/// `non_g1_edges` holds triangle pairs above `tol` rad. O(edges · samples) evaluations.
pub fn side_vertex_continuity(s: &SideVertexSurface, samples: usize, tol: f64) -> Continuity {
    use rayon::prelude::*;
    let mut map: HashMap<(u32, u32), (usize, usize)> = HashMap::new();
    for (t, tri) in s.triangles.iter().enumerate() {
        for i in 0..3 {
            // side i runs from corner i+1 to corner i+2
            map.insert((tri[(i + 1) % 3], tri[(i + 2) % 3]), (t, i));
        }
    }
    let mut out = Continuity::default();
    let mut pairs = Vec::with_capacity(map.len() / 2);
    for (&(a, b), &(p, i)) in &map {
        match map.get(&(b, a)) {
            None => out.open_edges += 1,
            Some(&(q, j)) if a < b => pairs.push((p, i, q, j)),
            Some(_) => {}
        }
    }
    pairs.sort_unstable();
    let n = samples.max(1);
    // per edge: (largest jump, largest gap, fold samples)
    let per: Vec<(f64, f64, usize)> = pairs
        .par_iter()
        .map(|&(p, i, q, j)| {
            let (mut worst, mut gap, mut folds) = (0.0f64, 0.0f64, 0);
            for k in 1..=n {
                let t = k as f64 / (n + 1) as f64;
                let mut up = [0.0; 3];
                up[(i + 1) % 3] = 1.0 - t;
                up[(i + 2) % 3] = t;
                let mut uq = [0.0; 3];
                uq[(j + 1) % 3] = t;
                uq[(j + 2) % 3] = 1.0 - t;
                gap = gap.max(vec::dist(s.eval(p, up), s.eval(q, uq)));
                let (mut jump, mut dot) = (f64::INFINITY, -1.0f64);
                for h in [1e-3, 1e-4, 1e-5, 1e-6] {
                    let (n1, n2) = (s.difference_normal(p, up, h), s.difference_normal(q, uq, h));
                    let d = vec::dot(n1, n2);
                    jump = jump.min(vec::norm(vec::cross(n1, n2)).atan2(d));
                    dot = dot.max(d);
                    if jump <= 1e-10 {
                        break; // resolved: smaller steps only add rounding
                    }
                }
                folds += usize::from(dot <= 0.0);
                worst = worst.max(jump);
            }
            (worst, gap, folds)
        })
        .collect();
    for (&(p, _, q, _), &(worst, gap, folds)) in pairs.iter().zip(&per) {
        out.edges += 1;
        out.max_position_gap = out.max_position_gap.max(gap);
        out.folds += folds;
        out.fold_edges += usize::from(folds > 0);
        out.max_macro_jump_rad = out.max_macro_jump_rad.max(worst);
        if worst > tol {
            out.non_g1_edges.push((p.min(q), p.max(q)));
        }
    }
    out.non_g1_edges.sort_unstable();
    out.max_normal_jump_rad = out.max_macro_jump_rad;
    out
}

/// Vertices of a tessellated surface whose stored normal points away from the mean of its
/// triangles (area-weighted facet normal · surface normal ≤ 0): where the surface folds
/// inside a patch (see the side-vertex module doc, case (a)). 0 without stored normals. O(V + T).
pub fn reversed_normals(mesh: &crate::mesh::TriMesh) -> usize {
    let Some(stored) = mesh.normals.as_ref() else {
        return 0;
    };
    let facet = crate::mesh::vertex_normals(mesh, crate::mesh::NormalWeighting::Area);
    facet
        .iter()
        .zip(stored)
        .filter(|(f, s)| f.norm() > 0.0 && f.dot(s) <= 0.0)
        .count()
}

/// The non-G¹ edges of a split surface by cause (issue 19; see [`non_g1_causes`]). Every edge
/// of [`Continuity::non_g1_edges`] is counted in exactly one of the first five fields.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct NonG1Causes {
    /// Edges inside one macro triangle.
    pub micro: usize,
    /// Macro edges with a fold sample (`n₁·n₂ ≤ 0`) and an end vertex whose normal does not
    /// see every incident triangle (`min_f n·n_f ≤ 0`): a fold is then unavoidable for a
    /// surface interpolating that normal ([`super::visible_normals`]).
    pub fold_invisible: usize,
    /// Other macro edges with a fold sample.
    pub fold: usize,
    /// Macro edges `a b` without a fold whose tangent planes lie on one side of the chord
    /// `d = b − a`, `(n_a·d)(n_b·d) ≥ 0`, or are nearly parallel, `|n_a × n_b| < 1e-3`:
    /// inflected or nearly flat edges, where no degree-elevated quadratic boundary near the
    /// Step-2 one exists and (9.4) is ill-conditioned (three-split module doc).
    pub inflected: usize,
    /// The remaining macro edges.
    pub other: usize,
    /// Non-G¹ macro edges (any cause) that the construction did not list in
    /// [`SplitSurface::unresolved_edges`]: claimed G¹, measured not.
    pub unlisted: usize,
}

/// Classifies the non-G¹ edges `c.non_g1_edges` of `s` (a split surface of `mesh` built with
/// the unit-able vertex `normals`) by cause, as [`NonG1Causes`] says. The macro edge of a
/// pair of patches of different macro triangles is the pair of vertices those triangles
/// share; its fold test re-samples the pair at the 20 interior points of [`continuity`]. Only
/// the listed edges are examined: O(T + V + |non_g1_edges|).
pub fn non_g1_causes(
    s: &SplitSurface,
    mesh: &crate::mesh::TriMesh,
    normals: &[crate::geom::Vector3],
    c: &Continuity,
) -> NonG1Causes {
    let pos: Vec<[f64; 3]> = mesh.positions.iter().map(|p| (*p).into()).collect();
    let nrm: Vec<[f64; 3]> = normals
        .iter()
        .map(|n| {
            let l = n.norm();
            [n.x / l, n.y / l, n.z / l]
        })
        .collect();
    // min over the incident faces of n·n_f, per vertex
    let mut sees = vec![f64::INFINITY; pos.len()];
    for t in &mesh.triangles {
        let p = |k: usize| pos[t[k] as usize];
        let f = vec::cross(vec::sub(p(1), p(0)), vec::sub(p(2), p(0)));
        let l = vec::norm(f);
        for &v in t {
            if let (Some(s), Some(n)) = (sees.get_mut(v as usize), nrm.get(v as usize)) {
                *s = s.min(vec::dot(f, *n) / l);
            }
        }
    }
    let unresolved: std::collections::HashSet<[u32; 2]> =
        s.unresolved_edges.iter().copied().collect();
    let mut out = NonG1Causes::default();
    for &(p, q) in &c.non_g1_edges {
        let (tp, tq) = (s.patches[p].macro_tri, s.patches[q].macro_tri);
        let (Some(ta), Some(tb)) = (
            mesh.triangles.get(tp as usize),
            mesh.triangles.get(tq as usize),
        ) else {
            out.other += 1;
            continue;
        };
        if tp == tq {
            out.micro += 1;
            continue;
        }
        let shared: Vec<u32> = ta.iter().copied().filter(|v| tb.contains(v)).collect();
        if shared.len() != 2 {
            out.other += 1;
            continue;
        }
        let (a, b) = (shared[0].min(shared[1]), shared[0].max(shared[1]));
        let (ia, ib) = (a as usize, b as usize);
        out.unlisted += usize::from(!unresolved.contains(&[a, b]));
        let fold = pair_folds(s, p, q);
        let d = vec::sub(pos[ib], pos[ia]);
        let inflected = vec::dot(nrm[ia], d) * vec::dot(nrm[ib], d) >= 0.0
            || vec::norm(vec::cross(nrm[ia], nrm[ib])) < 1e-3;
        if fold && (sees[ia] <= 0.0 || sees[ib] <= 0.0) {
            out.fold_invisible += 1;
        } else if fold {
            out.fold += 1;
        } else if inflected {
            out.inflected += 1;
        } else {
            out.other += 1;
        }
    }
    out
}

/// Whether patches `p` and `q` of `s` have a fold sample (`n₁·n₂ ≤ 0`) on their shared edge,
/// at the sample points of [`continuity`] (20 per edge).
fn pair_folds(s: &SplitSurface, p: usize, q: usize) -> bool {
    let (tp, tq) = (s.patches[p].triangle(), s.patches[q].triangle());
    let (cp, cq) = (tp.corners(), tq.corners());
    let unit = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for i in 0..3 {
        for j in 0..3 {
            if key(cp[i]) == key(cq[(j + 1) % 3]) && key(cp[(i + 1) % 3]) == key(cq[j]) {
                return (1..=20).any(|k| {
                    let t = k as f64 / 21.0;
                    let n1 = tp.normal(vec::lerp(unit[i], unit[(i + 1) % 3], t));
                    let n2 = tq.normal(vec::lerp(unit[j], unit[(j + 1) % 3], 1.0 - t));
                    vec::dot(n1, n2) <= 0.0
                });
            }
        }
    }
    false
}
