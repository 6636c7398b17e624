//! Curvature of the graph `(x, y, z, f(x, y, z))` of a trivariate function in R⁴, Hamann 1991,
//! §4.3 (notes C.1, C.3).
//!
//! The grid is split into 6 tetrahedra per cell (H §3.2; corners as offsets of the cell's
//! lowest corner: `000 100 010 001`, `100 010 001 011`, `100 101 001 011`, `100 110 010 011`,
//! `100 110 101 011`, `110 101 011 111`; every face uses the anti-diagonal, so neighbouring
//! cells match). The platelet of a grid point (H Def. 4.12) is every tetrahedron containing it:
//! 14 neighbours inside the grid, fewer on its faces. At each point `y₀ = (x, f)` with unit
//! normal `n = (−∇f, 1)/√(1+|∇f|²)`:
//! 1. a tangent basis `b₁, b₂, b₃` by Gram–Schmidt of the first three axes against `n`,
//! 2. heights `d_j = n·(y_j − y₀)` and tangent coordinates `(u, v, w)_j`,
//! 3. least squares `½(c200 u² + 2c110 uv + 2c101 uw + c020 v² + 2c011 vw + c002 w²) = d_j`
//!    with rows `(u²/2, uv, uw, v²/2, vw, w²/2)` (the text prints the rows without the ½ and
//!    its literal solution has to be doubled, notes C.3; these rows give `c` directly),
//! 4. κ₁ ≤ κ₂ ≤ κ₃ are the eigenvalues of `[[c200,c110,c101],[c110,c020,c011],[c101,c011,c002]]`
//!    (H (4.50)) — computed with nalgebra's symmetric eigen-solver instead of the text's Newton
//!    iteration with deflation — and `H = (κ₁+κ₂+κ₃)/3`, `K = κ₁κ₂κ₃` (H (4.38)).
//!
//! Signs follow the graph convention (H (4.36)): the upward normal, so `f = ½xᵀAx` has the
//! eigenvalues of A at the origin.
//!
//! **Undetermined points** (NaN, `determined[i] == false`, counted): fewer than 6 platelet
//! points, or `cond(UᵀU) > 1e4` (scale-free; notes C.3). On the 26³ grid of Table 4.2 this
//! excludes 102 face points, where `UᵀU` is singular for a linear function and so
//! ill-conditioned for curved ones that the solution is garbage (K RMS up to 420).
//!
//! The normal comes from exact gradients ([`Gradients::Given`]; the thesis's tables use
//! them) or from central differences on the grid, one-sided on its faces
//! ([`Gradients::Differences`]). Cost: O(samples), in parallel (rayon).

use super::error::CurvatureError;
use super::fit::Normal;
use crate::geom::vec;
use crate::volume::Volume;
use rayon::prelude::*;

/// The 6 tetrahedra of a cell (H §3.2) as corner offsets `(dx, dy, dz)`.
const TETS: [[[usize; 3]; 4]; 6] = [
    [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]],
    [[1, 0, 0], [0, 1, 0], [0, 0, 1], [0, 1, 1]],
    [[1, 0, 0], [1, 0, 1], [0, 0, 1], [0, 1, 1]],
    [[1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 1, 1]],
    [[1, 0, 0], [1, 1, 0], [1, 0, 1], [0, 1, 1]],
    [[1, 1, 0], [1, 0, 1], [0, 1, 1], [1, 1, 1]],
];

/// Condition-number bound of the 6×6 normal matrix (notes C.3).
pub const VOLUME_MAX_COND: f64 = 1e4;

/// Where the gradients that define the normals come from.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Gradients {
    /// Central differences on the grid (one-sided on its faces).
    #[default]
    Differences,
    /// One gradient per sample, x fastest (for example the exact one of an analytic function).
    Given(Vec<[f64; 3]>),
}

/// Per-sample curvatures of a trivariate graph, x fastest like [`Volume::data`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct VolumeCurvature {
    /// Samples along x, y, z.
    pub dims: [usize; 3],
    /// Smallest principal curvature κ₁.
    pub k1: Vec<f64>,
    /// Middle principal curvature κ₂.
    pub k2: Vec<f64>,
    /// Largest principal curvature κ₃.
    pub k3: Vec<f64>,
    /// Mean curvature (κ₁+κ₂+κ₃)/3.
    pub h: Vec<f64>,
    /// Gaussian curvature κ₁κ₂κ₃.
    pub k: Vec<f64>,
    /// False where the fit is undetermined (all values NaN there).
    pub determined: Vec<bool>,
    /// Number of undetermined samples.
    pub undetermined: usize,
}

/// Curvatures of a volume's graph, on the volume's grid (its axis coordinates; samples taken
/// as f64). Refuses an axis with one sample and non-finite samples.
///
/// ```
/// use morpho::curvature::{volume_curvature, Gradients};
/// use morpho::volume::Volume;
/// // f = ½(x² + 2y² + 3z²) on a small grid: at the centre κ = 1, 2, 3 up to O(h²)
/// let v = Volume::from_fn([5, 5, 5], [-0.1; 3], [0.1; 3], |x, y, z| 0.5 * (x * x + 2.0 * y * y + 3.0 * z * z));
/// let c = volume_curvature(&v, &Gradients::Differences).unwrap();
/// let i = v.index(2, 2, 2);
/// assert!((c.k1[i] - 1.0).abs() < 1e-3 && (c.k3[i] - 3.0).abs() < 1e-3);
/// ```
pub fn volume_curvature(
    vol: &Volume,
    gradients: &Gradients,
) -> Result<VolumeCurvature, CurvatureError> {
    let coords: [Vec<f64>; 3] =
        std::array::from_fn(|k| (0..vol.dims[k]).map(|i| vol.coord(k, i)).collect());
    let values: Vec<f64> = vol.data.iter().map(|&x| x as f64).collect();
    trivariate_curvature(vol.dims, &coords, &values, gradients)
}

/// Curvatures of the graph of the samples `values` (x fastest) on the rectilinear grid with
/// plane coordinates `coords` (H §4.3; the module doc gives the steps and conventions).
pub fn trivariate_curvature(
    dims: [usize; 3],
    coords: &[Vec<f64>; 3],
    values: &[f64],
    gradients: &Gradients,
) -> Result<VolumeCurvature, CurvatureError> {
    check(dims, coords, values)?;
    let n = values.len();
    let grads: Vec<[f64; 3]> = match gradients {
        Gradients::Given(g) if g.len() != n => {
            return Err(CurvatureError::NormalCount {
                given: g.len(),
                vertices: n,
            })
        }
        Gradients::Given(g) => g.clone(),
        Gradients::Differences => (0..n)
            .map(|i| differences(dims, coords, values, i))
            .collect(),
    };
    let per: Vec<Option<[f64; 3]>> = (0..n)
        .into_par_iter()
        .map(|i| fit_point(dims, coords, values, i, grads[i]))
        .collect();
    let mut out = VolumeCurvature {
        dims,
        ..Default::default()
    };
    for r in per {
        let k = r.unwrap_or([f64::NAN; 3]);
        out.undetermined += usize::from(r.is_none());
        out.determined.push(r.is_some());
        out.k1.push(k[0]);
        out.k2.push(k[1]);
        out.k3.push(k[2]);
        out.h.push((k[0] + k[1] + k[2]) / 3.0);
        out.k.push(k[0] * k[1] * k[2]);
    }
    Ok(out)
}

fn check(dims: [usize; 3], coords: &[Vec<f64>; 3], values: &[f64]) -> Result<(), CurvatureError> {
    for axis in 0..3 {
        if dims[axis] < 2 {
            return Err(CurvatureError::FlatAxis {
                dims,
                axis,
                samples: dims[axis],
            });
        }
        let c = &coords[axis];
        if c.len() != dims[axis] {
            return Err(CurvatureError::BadCoordinates { axis });
        }
        if let Some(i) = c.iter().position(|x| !x.is_finite()) {
            return Err(CurvatureError::NonFiniteSample { index: i });
        }
        if c.windows(2).any(|w| w[1] <= w[0]) {
            return Err(CurvatureError::BadCoordinates { axis });
        }
    }
    let need = dims[0]
        .checked_mul(dims[1])
        .and_then(|x| x.checked_mul(dims[2]));
    if need != Some(values.len()) {
        return Err(CurvatureError::SampleCount {
            found: values.len(),
            dims,
        });
    }
    if let Some(index) = values.iter().position(|x| !x.is_finite()) {
        return Err(CurvatureError::NonFiniteSample { index });
    }
    Ok(())
}

fn unravel(dims: [usize; 3], i: usize) -> [usize; 3] {
    [
        i % dims[0],
        (i / dims[0]) % dims[1],
        i / (dims[0] * dims[1]),
    ]
}

fn ravel(dims: [usize; 3], p: [usize; 3]) -> usize {
    p[0] + dims[0] * (p[1] + dims[1] * p[2])
}

/// Central differences at sample `i` (one-sided on the grid's faces).
fn differences(dims: [usize; 3], coords: &[Vec<f64>; 3], values: &[f64], i: usize) -> [f64; 3] {
    let p = unravel(dims, i);
    std::array::from_fn(|k| {
        let lo = p[k].saturating_sub(1);
        let hi = (p[k] + 1).min(dims[k] - 1);
        let (mut a, mut b) = (p, p);
        a[k] = lo;
        b[k] = hi;
        (values[ravel(dims, b)] - values[ravel(dims, a)]) / (coords[k][hi] - coords[k][lo])
    })
}

/// The platelet neighbours of grid point `p` (at most 14), from the tetrahedra containing it.
fn platelet(dims: [usize; 3], p: [usize; 3], out: &mut Vec<[usize; 3]>) {
    out.clear();
    for corner in 0..8usize {
        let c = [corner & 1, (corner >> 1) & 1, corner >> 2];
        // the cell whose corner c is p
        if (0..3).any(|k| p[k] < c[k] || p[k] - c[k] + 1 >= dims[k]) {
            continue;
        }
        let origin: [usize; 3] = std::array::from_fn(|k| p[k] - c[k]);
        for tet in &TETS {
            if !tet.contains(&c) {
                continue;
            }
            for q in tet.iter().filter(|q| **q != c) {
                let g: [usize; 3] = std::array::from_fn(|k| origin[k] + q[k]);
                if !out.contains(&g) {
                    out.push(g);
                }
            }
        }
    }
}

/// The 6×6 fit at sample `i` with gradient `g`; κ₁ ≤ κ₂ ≤ κ₃ or `None` when undetermined.
fn fit_point(
    dims: [usize; 3],
    coords: &[Vec<f64>; 3],
    values: &[f64],
    i: usize,
    g: [f64; 3],
) -> Option<[f64; 3]> {
    if !g.iter().all(|x| x.is_finite()) {
        return None;
    }
    let p = unravel(dims, i);
    let mut nbrs = Vec::with_capacity(14);
    platelet(dims, p, &mut nbrs);
    let l = (1.0 + vec::norm2(g)).sqrt();
    let n = [-g[0] / l, -g[1] / l, -g[2] / l, 1.0 / l];
    // Gram–Schmidt of e₁, e₂, e₃ against n
    let mut basis: Vec<[f64; 4]> = Vec::with_capacity(3);
    for k in 0..3 {
        let mut a = [0.0; 4];
        a[k] = 1.0;
        for b in std::iter::once(&n).chain(basis.iter()) {
            a = vec::add_scaled(a, -vec::dot(a, *b), *b);
        }
        let len = vec::norm(a);
        basis.push(vec::scale(a, 1.0 / len));
    }
    let at = |q: [usize; 3]| -> [f64; 4] {
        [
            coords[0][q[0]],
            coords[1][q[1]],
            coords[2][q[2]],
            values[ravel(dims, q)],
        ]
    };
    let y0 = at(p);
    let mut ne = Normal::<6>::new();
    for &q in &nbrs {
        let w = vec::sub(at(q), y0);
        let d = vec::dot(n, w);
        let (u, v, t) = (
            vec::dot(w, basis[0]),
            vec::dot(w, basis[1]),
            vec::dot(w, basis[2]),
        );
        ne.add(
            [0.5 * u * u, u * v, u * t, 0.5 * v * v, v * t, 0.5 * t * t],
            d,
        );
    }
    let c = ne.solve(VOLUME_MAX_COND)?;
    let m = nalgebra::Matrix3::new(c[0], c[1], c[2], c[1], c[3], c[4], c[2], c[4], c[5]);
    let e = m.symmetric_eigenvalues();
    let mut k = [e[0], e[1], e[2]];
    k.sort_by(f64::total_cmp);
    Some(k)
}
