//! The completion of the three-split's singular edges (a deviation from Veltkamp 1992, §9.6;
//! NOTES B.5): where (9.4) is singular — mirror-symmetric edge sides, `f0 g1 = g0 f1` — the
//! text's pair has no solution, and even the exact tangent-plane condition
//! `det[K−M, L−M, R−M](t) ≡ 0` (8.7) cannot be met by moving the interior points `L1, R1`
//! alone (checked: the Gauss–Newton iterates run off to infinity on the octahedron). So the
//! unknowns are widened, in the spirit of the constrained least-squares completion the notes
//! recommend (B.7): per singular edge, `L1`, `R1` **and its two edge points `M1, M2`**, each
//! kept in its vertex's tangent plane (2 parameters), so interpolation of positions and
//! normals is untouched; the points `W = (V + E + E′)/3` next to the vertices follow the edge
//! points, so the interior stays C¹ (Step 6 is run afterwards). The residuals are the det
//! condition at 9 interior samples of every singular edge (its end coefficients vanish by
//! construction); they are driven to zero by Gauss–Newton with minimum-norm (SVD) steps from
//! the Step-4 values, i.e. the smallest move to first order, with step halving. Dense: used
//! for up to [`MAX_GLOBAL`] singular edges at once; beyond that only `L1, R1` move.
//! Nonsingular edges are then solved by (9.4) with the moved edge points.

use crate::geom::vec;
use std::collections::HashMap;

type P3 = [f64; 3];

/// Most singular edges solved together (dense SVD of a 9S × 10S Jacobian).
pub const MAX_GLOBAL: usize = 150;

const SAMPLES: usize = 9;

/// What the completion needs of the mesh.
pub(crate) struct Ctx<'a> {
    pub tris: &'a [[u32; 3]],
    pub half: &'a HashMap<(u32, u32), usize>,
    pub pos: &'a [P3],
    pub nrm: &'a [P3],
}

fn third(ctx: &Ctx, a: u32, b: u32) -> u32 {
    let h = ctx.half[&(a, b)];
    ctx.tris[h / 3][(h % 3 + 2) % 3]
}

fn tangent_basis(n: P3) -> (P3, P3) {
    let pick = if n[0].abs() < 0.6 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let u = vec::cross(n, pick);
    let u = vec::scale(u, 1.0 / vec::norm(u));
    (u, vec::cross(n, u))
}

/// `det[K−M, L−M, R−M](t)` of an edge (`m` the 4 edge points, `l`, `r` the first rows).
pub(crate) fn edge_det(m: &[P3; 4], l: &[P3; 3], r: &[P3; 3], t: f64) -> f64 {
    let u = 1.0 - t;
    let q = |p: [P3; 3]| {
        vec::add(
            vec::add(vec::scale(p[0], t * t), vec::scale(p[1], 2.0 * t * u)),
            vec::scale(p[2], u * u),
        )
    };
    let mm = q([m[0], m[1], m[2]]);
    let k = q([m[1], m[2], m[3]]);
    let (a, b, c) = (vec::sub(k, mm), vec::sub(q(*l), mm), vec::sub(q(*r), mm));
    vec::dot(vec::cross(a, b), c)
}

/// Completes the singular `edges` (a < b). `start[k]` holds edge k's Step-4 `(L1, R1)`.
/// Moves the edge points of these edges in `handles` and returns the new `(L1, R1)` and,
/// per edge, whether its residual vanished (≤ 1e-13 relative).
pub(crate) fn complete(
    ctx: &Ctx,
    handles: &mut HashMap<(u32, u32), P3>,
    edges: &[[u32; 2]],
    start: &[(P3, P3)],
) -> (Vec<(P3, P3)>, Vec<bool>) {
    let s = edges.len();
    if s > MAX_GLOBAL {
        // too many for the dense solve: left as they are and reported unresolved
        return (start.to_vec(), vec![false; s]);
    }
    let free_handles = s <= MAX_GLOBAL;
    let per = if free_handles { 10 } else { 6 };
    let base = handles.clone();
    let slot: HashMap<(u32, u32), usize> = edges
        .iter()
        .enumerate()
        .flat_map(|(k, &[a, b])| [((a, b), per * k + 6), ((b, a), per * k + 8)])
        .collect();
    let len: Vec<f64> = edges
        .iter()
        .map(|&[a, b]| vec::dist(ctx.pos[a as usize], ctx.pos[b as usize]))
        .collect();
    let basis: Vec<(P3, P3)> = ctx.nrm.iter().map(|&n| tangent_basis(n)).collect();
    let handle = |x: &[f64], a: u32, b: u32| -> P3 {
        let h = base[&(a, b)];
        match slot.get(&(a, b)) {
            Some(&o) if free_handles => {
                let (u, v) = basis[a as usize];
                let l = len[(o - 6) / per];
                vec::add(
                    h,
                    vec::add(vec::scale(u, l * x[o]), vec::scale(v, l * x[o + 1])),
                )
            }
            _ => h,
        }
    };
    let interior = |x: &[f64], k: usize| -> (P3, P3) {
        let (l1, r1) = start[k];
        let o = per * k;
        let sh = |p: P3, d: usize| {
            vec::add(
                p,
                vec::scale([x[o + d], x[o + d + 1], x[o + d + 2]], len[k]),
            )
        };
        (sh(l1, 0), sh(r1, 3))
    };
    let residuals = |x: &[f64], out: &mut Vec<f64>| {
        out.clear();
        for (k, &[a, b]) in edges.iter().enumerate() {
            let (c, d) = (third(ctx, a, b), third(ctx, b, a));
            let (pa, pb) = (ctx.pos[a as usize], ctx.pos[b as usize]);
            let w = |v: P3, i: u32, j: u32, o: u32| {
                vec::scale(
                    vec::add(vec::add(v, handle(x, i, j)), handle(x, i, o)),
                    1.0 / 3.0,
                )
            };
            let m = [pa, handle(x, a, b), handle(x, b, a), pb];
            let (l1, r1) = interior(x, k);
            let l = [w(pa, a, b, c), l1, w(pb, b, a, c)];
            let r = [w(pa, a, b, d), r1, w(pb, b, a, d)];
            let n3 = len[k].powi(3);
            for i in 1..=SAMPLES {
                out.push(edge_det(&m, &l, &r, i as f64 / (SAMPLES + 1) as f64) / n3);
            }
        }
    };
    let n = per * s;
    let mut x = vec![0.0; n];
    let mut r = Vec::new();
    residuals(&x, &mut r);
    let amax = |r: &[f64]| r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut tmp = Vec::new();
    for _ in 0..40 {
        if amax(&r) <= 1e-15 {
            break;
        }
        let h = 1e-5;
        let mut j = nalgebra::DMatrix::zeros(r.len(), n);
        for c in 0..n {
            let keep = x[c];
            x[c] = keep + h;
            residuals(&x, &mut tmp);
            let plus = tmp.clone();
            x[c] = keep - h;
            residuals(&x, &mut tmp);
            x[c] = keep;
            for (row, (p, m)) in plus.iter().zip(&tmp).enumerate() {
                j[(row, c)] = (p - m) / (2.0 * h);
            }
        }
        let svd = j.svd(true, true);
        let rv = nalgebra::DVector::from_column_slice(&r);
        let Ok(step) = svd.solve(&rv, 1e-10 * svd.singular_values.max()) else {
            break;
        };
        let mut t = 1.0;
        let before = r.iter().map(|v| v * v).sum::<f64>();
        let mut improved = false;
        for _ in 0..12 {
            let trial: Vec<f64> = x.iter().zip(step.iter()).map(|(a, d)| a - t * d).collect();
            residuals(&trial, &mut tmp);
            if tmp.iter().map(|v| v * v).sum::<f64>() < before {
                x = trial;
                std::mem::swap(&mut r, &mut tmp);
                improved = true;
                break;
            }
            t *= 0.5;
        }
        if !improved {
            break;
        }
    }
    if free_handles {
        for (&(a, b), _) in slot.iter() {
            let p = handle(&x, a, b);
            handles.insert((a, b), p);
        }
    }
    let sol = (0..s).map(|k| interior(&x, k)).collect();
    let ok = (0..s)
        .map(|k| amax(&r[k * SAMPLES..(k + 1) * SAMPLES]) <= 1e-13)
        .collect();
    (sol, ok)
}
