//! Tables 4.1 and 4.2 of Hamann 1991 (H p. 74 and p. 88; notes C.4, C.5), recomputed.
//!
//! * Table 4.1: 9 bivariate functions sampled on the 51×51 grid over `[-1,1]²` (h = 0.04),
//!   every quad split along `(i,j)–(i+1,j+1)`, the 1-ring fit of [`super::surface_curvature`]
//!   with the **exact** normals `(−∇f, 1)/l` (the notes show the table used them), RMS (H (4.32))
//!   of κ₁, κ₂, H, K (κ₁ ≤ κ₂) over the determined vertices (all but the 2 corners in one
//!   triangle) and over the interior vertices (49² = 2401).
//! * Table 4.2: 6 trivariate functions on the 26³ grid over `[-1,1]³` (h = 0.08), the fit of
//!   [`super::trivariate_curvature`] with exact gradients, RMS of H and K over the determined
//!   points (all but 102) and over the interior points (24³ = 13824).
//!
//! The exact values: for a graph, `K = (f_uu f_vv − f_uv²)/l⁴`,
//! `H = ((1+f_v²)f_uu − 2f_u f_v f_uv + (1+f_u²)f_vv)/(2l³)` and `κ = H ∓ √(H²−K)` (H (4.15));
//! in R⁴ the eigenvalues of `(1/l) Hess f (I + ∇f∇fᵀ)⁻¹` (H (4.36)), computed from the similar
//! symmetric matrix `(1/l) S Hess f S` with `S = (I + ∇f∇fᵀ)^{-1/2}`.

use super::{surface_curvature, trivariate_curvature, Gradients, NormalSource, SurfaceOptions};
use crate::geom::{Point3, Vector3};
use crate::mesh::TriMesh;
use std::f64::consts::PI;

/// One row of a recomputed table.
#[derive(Debug, Clone, PartialEq)]
pub struct TableRow {
    /// Row number in the thesis (1-based).
    pub row: usize,
    /// The function's name and formula as in the thesis.
    pub name: &'static str,
    /// The thesis's values (Table 4.1: κ₁, κ₂, H, K; Table 4.2: H, K).
    pub thesis: Vec<f64>,
    /// RMS over the determined vertices, same columns.
    pub rms: Vec<f64>,
    /// RMS over the interior vertices, same columns.
    pub rms_interior: Vec<f64>,
    /// Number of undetermined vertices (excluded from both RMS).
    pub undetermined: usize,
}

/// A bivariate function with its derivatives: `(f, f_x, f_y, f_xx, f_xy, f_yy)`.
type F2 = fn(f64, f64) -> [f64; 6];

const T41: [(&str, [f64; 4], F2); 9] = [
    ("Plane: .2(x+y)", [0.0; 4], |x, y| {
        [0.2 * (x + y), 0.2, 0.2, 0.0, 0.0, 0.0]
    }),
    (
        "Cylinder: sqrt(2-x^2)",
        [0.000291, 0.000035, 0.000132, 0.000025],
        |x, _| {
            let s = (2.0 - x * x).sqrt();
            [s, -x / s, 0.0, -2.0 / (s * s * s), 0.0, 0.0]
        },
    ),
    (
        "Sphere: sqrt(4-(x^2+y^2))",
        [0.000159, 0.000046, 0.000080, 0.000080],
        |x, y| {
            let s = (4.0 - x * x - y * y).sqrt();
            let s3 = s * s * s;
            [
                s,
                -x / s,
                -y / s,
                -(4.0 - y * y) / s3,
                -x * y / s3,
                -(4.0 - x * x) / s3,
            ]
        },
    ),
    (
        "Paraboloid: .4(x^2+y^2)",
        [0.003073, 0.001342, 0.001358, 0.001684],
        |x, y| [0.4 * (x * x + y * y), 0.8 * x, 0.8 * y, 0.8, 0.0, 0.8],
    ),
    (
        "Hyperboloid: .4(x^2-y^2)",
        [0.002058, 0.002058, 0.001057, 0.001767],
        |x, y| [0.4 * (x * x - y * y), 0.8 * x, -0.8 * y, 0.8, 0.0, -0.8],
    ),
    (
        "Monkey saddle: .2(x^3-3xy^2)",
        [0.004483, 0.004483, 0.001591, 0.007247],
        |x, y| {
            [
                0.2 * (x * x * x - 3.0 * x * y * y),
                0.6 * (x * x - y * y),
                -1.2 * x * y,
                1.2 * x,
                -1.2 * y,
                -1.2 * x,
            ]
        },
    ),
    (
        "Cubic: .15(x^3+2x^2y-xy+2y^2)",
        [0.002258, 0.003598, 0.001665, 0.002242],
        |x, y| {
            [
                0.15 * (x * x * x + 2.0 * x * x * y - x * y + 2.0 * y * y),
                0.15 * (3.0 * x * x + 4.0 * x * y - y),
                0.15 * (2.0 * x * x - x + 4.0 * y),
                0.15 * (6.0 * x + 4.0 * y),
                0.15 * (4.0 * x - 1.0),
                0.6,
            ]
        },
    ),
    (
        "Exponential: exp(-(x^2+y^2)/2)",
        [0.001757, 0.005546, 0.002722, 0.002602],
        |x, y| {
            let e = (-0.5 * (x * x + y * y)).exp();
            [
                e,
                -x * e,
                -y * e,
                (x * x - 1.0) * e,
                x * y * e,
                (y * y - 1.0) * e,
            ]
        },
    ),
    (
        "Trigonometric: .1(cos(pi x)+cos(pi y))",
        [0.002998, 0.002821, 0.001013, 0.003541],
        |x, y| {
            let (cx, cy) = ((PI * x).cos(), (PI * y).cos());
            [
                0.1 * (cx + cy),
                -0.1 * PI * (PI * x).sin(),
                -0.1 * PI * (PI * y).sin(),
                -0.1 * PI * PI * cx,
                0.0,
                -0.1 * PI * PI * cy,
            ]
        },
    ),
];

/// The exact κ₁ ≤ κ₂, H, K of a graph from its derivatives (H (4.15)).
pub fn graph_curvatures(d: [f64; 6]) -> [f64; 4] {
    let [_, fu, fv, fuu, fuv, fvv] = d;
    let l2 = 1.0 + fu * fu + fv * fv;
    let l = l2.sqrt();
    let k = (fuu * fvv - fuv * fuv) / (l2 * l2);
    let h = ((1.0 + fv * fv) * fuu - 2.0 * fu * fv * fuv + (1.0 + fu * fu) * fvv) / (2.0 * l2 * l);
    let r = (h * h - k).max(0.0).sqrt();
    [h - r, h + r, h, k]
}

/// The graph of `f` sampled on the `m×m` grid over `[-1,1]²`, quads split along
/// `(i,j)–(i+1,j+1)`, counter-clockwise seen from above, with the exact upward normals.
pub fn grid_mesh(m: usize, f: impl Fn(f64, f64) -> [f64; 6]) -> TriMesh {
    let h = 2.0 / (m - 1) as f64;
    let mut pos = Vec::with_capacity(m * m);
    let mut nrm = Vec::with_capacity(m * m);
    for j in 0..m {
        for i in 0..m {
            let (x, y) = (-1.0 + i as f64 * h, -1.0 + j as f64 * h);
            let d = f(x, y);
            pos.push(Point3::new(x, y, d[0]));
            nrm.push(Vector3::new(-d[1], -d[2], 1.0).normalize());
        }
    }
    let id = |i: usize, j: usize| (i + m * j) as u32;
    let mut tri = Vec::with_capacity(2 * (m - 1) * (m - 1));
    for j in 0..m - 1 {
        for i in 0..m - 1 {
            tri.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            tri.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    let mut mesh = TriMesh::new(pos, tri);
    mesh.normals = Some(nrm);
    mesh
}

fn rms(sum: &[f64], n: usize) -> Vec<f64> {
    sum.iter().map(|s| (s / n as f64).sqrt()).collect()
}

/// Table 4.1 (H p. 74) on an `m×m` grid (the thesis: m = 51), exact normals, 1-ring.
pub fn table_4_1(m: usize) -> Vec<TableRow> {
    T41.iter()
        .enumerate()
        .map(|(r, &(name, thesis, f))| {
            let mesh = grid_mesh(m, f);
            let opts = SurfaceOptions {
                normals: NormalSource::File,
                ring: 1,
                ..Default::default()
            };
            let c = surface_curvature(&mesh, &opts).expect("a valid grid mesh");
            let (mut all, mut inner) = ([0.0; 4], [0.0; 4]);
            let (mut na, mut ni) = (0, 0);
            for (v, p) in mesh.positions.iter().enumerate() {
                if c.k1[v].is_nan() {
                    continue;
                }
                let ex = graph_curvatures(f(p.x, p.y));
                let ap = [c.k1[v], c.k2[v], c.h[v], c.k[v]];
                let (i, j) = (v % m, v / m);
                let interior = i > 0 && j > 0 && i + 1 < m && j + 1 < m;
                na += 1;
                ni += usize::from(interior);
                for q in 0..4 {
                    let e2 = (ex[q] - ap[q]).powi(2);
                    all[q] += e2;
                    if interior {
                        inner[q] += e2;
                    }
                }
            }
            TableRow {
                row: r + 1,
                name,
                thesis: thesis.to_vec(),
                rms: rms(&all, na),
                rms_interior: rms(&inner, ni),
                undetermined: c.undetermined,
            }
        })
        .collect()
}

/// A trivariate function with gradient and Hessian.
type F3 = fn([f64; 3]) -> (f64, [f64; 3], [[f64; 3]; 3]);

const T42: [(&str, [f64; 2], F3); 6] = [
    ("Linear: .2(x+y+z)", [0.0; 2], |p| {
        (0.2 * (p[0] + p[1] + p[2]), [0.2; 3], [[0.0; 3]; 3])
    }),
    ("Quadratic q1: .4(x^2+y^2+z^2)", [0.002950, 0.002597], |p| {
        let f = 0.4 * (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        (f, p.map(|x| 0.8 * x), diag([0.8; 3]))
    }),
    ("Quadratic q2: .4(x^2-y^2-z^2)", [0.001115, 0.002216], |p| {
        let f = 0.4 * (p[0] * p[0] - p[1] * p[1] - p[2] * p[2]);
        (
            f,
            [0.8 * p[0], -0.8 * p[1], -0.8 * p[2]],
            diag([0.8, -0.8, -0.8]),
        )
    }),
    (
        "Cubic: .15(x^3+2x^2y-xz^2+2y^2)",
        [0.002545, 0.001207],
        |p| {
            let [x, y, z] = p;
            let f = 0.15 * (x * x * x + 2.0 * x * x * y - x * z * z + 2.0 * y * y);
            let g = [
                0.15 * (3.0 * x * x + 4.0 * x * y - z * z),
                0.15 * (2.0 * x * x + 4.0 * y),
                -0.3 * x * z,
            ];
            let (xx, xy, xz) = (0.15 * (6.0 * x + 4.0 * y), 0.6 * x, -0.3 * z);
            (f, g, [[xx, xy, xz], [xy, 0.6, 0.0], [xz, 0.0, -0.3 * x]])
        },
    ),
    (
        "Exponential: exp(-(x^2+y^2+z^2)/2)",
        [0.006349, 0.002802],
        |p| {
            let e = (-0.5 * (p[0] * p[0] + p[1] * p[1] + p[2] * p[2])).exp();
            let h = std::array::from_fn(|i| {
                std::array::from_fn(|j| (p[i] * p[j] - f64::from(u8::from(i == j))) * e)
            });
            (e, p.map(|x| -x * e), h)
        },
    ),
    (
        "Trigonometric: .1(cos(pi x)+cos(pi y)+cos(pi z))",
        [0.003269, 0.009065],
        |p| {
            let f = 0.1 * p.iter().map(|x| (PI * x).cos()).sum::<f64>();
            (
                f,
                p.map(|x| -0.1 * PI * (PI * x).sin()),
                diag(p.map(|x| -0.1 * PI * PI * (PI * x).cos())),
            )
        },
    ),
];

fn diag(d: [f64; 3]) -> [[f64; 3]; 3] {
    [[d[0], 0.0, 0.0], [0.0, d[1], 0.0], [0.0, 0.0, d[2]]]
}

/// The exact κ₁ ≤ κ₂ ≤ κ₃ of the graph of a trivariate function (H (4.36)).
pub fn trivariate_exact(g: [f64; 3], hess: [[f64; 3]; 3]) -> [f64; 3] {
    let g = nalgebra::Vector3::from(g);
    let hm = nalgebra::Matrix3::from_fn(|i, j| hess[i][j]);
    let g2 = g.norm_squared();
    let l = (1.0 + g2).sqrt();
    // (I + g gᵀ)^{-1/2} = I + (1/l − 1) ĝ ĝᵀ
    let s = if g2 > 0.0 {
        nalgebra::Matrix3::identity() + (g * g.transpose()) * ((1.0 / l - 1.0) / g2)
    } else {
        nalgebra::Matrix3::identity()
    };
    let e = (s * hm * s / l).symmetric_eigenvalues();
    let mut k = [e[0], e[1], e[2]];
    k.sort_by(f64::total_cmp);
    k
}

/// Exact and approximated H and K of one Table 4.2 function on the `m³` grid over `[-1,1]³`.
struct Fields42 {
    exact: Vec<[f64; 2]>,
    approx: Vec<[f64; 2]>,
    determined: Vec<bool>,
    undetermined: usize,
}

fn fields_4_2(m: usize, f: F3) -> Fields42 {
    let h = 2.0 / (m - 1) as f64;
    let axis: Vec<f64> = (0..m).map(|i| -1.0 + i as f64 * h).collect();
    let coords = [axis.clone(), axis.clone(), axis];
    let vals: Vec<_> = (0..m * m * m)
        .map(|i| f([i % m, (i / m) % m, i / (m * m)].map(|q| -1.0 + q as f64 * h)))
        .collect();
    let values: Vec<f64> = vals.iter().map(|v| v.0).collect();
    let grads = Gradients::Given(vals.iter().map(|v| v.1).collect());
    let c = trivariate_curvature([m; 3], &coords, &values, &grads).expect("a valid grid");
    let exact = vals
        .iter()
        .map(|v| {
            let k = trivariate_exact(v.1, v.2);
            [(k[0] + k[1] + k[2]) / 3.0, k[0] * k[1] * k[2]]
        })
        .collect();
    let approx = c.h.iter().zip(&c.k).map(|(&h, &k)| [h, k]).collect();
    Fields42 {
        exact,
        approx,
        determined: c.determined,
        undetermined: c.undetermined,
    }
}

/// The H Table 4.2 function of row `row` (1-based, 1..=6) on the `m³` grid over `[-1,1]³`
/// (exact gradients): `[exact H, approximated H, exact K, approximated K]`, x fastest, NaN
/// where the fit is undetermined — the fields of H Figs 4.9–4.12. `None` for another row or
/// `m < 2`.
pub fn table_4_2_fields(row: usize, m: usize) -> Option<[Vec<f64>; 4]> {
    if m < 2 || row == 0 || row > T42.len() {
        return None;
    }
    let fl = fields_4_2(m, T42[row - 1].2);
    let col = |v: &[[f64; 2]], i: usize| v.iter().map(|x| x[i]).collect::<Vec<f64>>();
    Some([
        col(&fl.exact, 0),
        col(&fl.approx, 0),
        col(&fl.exact, 1),
        col(&fl.approx, 1),
    ])
}

/// The name of Table 4.2's row `row` (1-based), as in the thesis.
pub fn table_4_2_name(row: usize) -> Option<&'static str> {
    T42.get(row.checked_sub(1)?).map(|r| r.0)
}

/// Table 4.2 (H p. 88) on an `m³` grid (the thesis: m = 26), exact gradients.
pub fn table_4_2(m: usize) -> Vec<TableRow> {
    T42.iter()
        .enumerate()
        .map(|(r, &(name, thesis, f))| {
            let fl = fields_4_2(m, f);
            let (mut all, mut inner) = ([0.0; 2], [0.0; 2]);
            let (mut na, mut ni) = (0, 0);
            for (i, (ex, ap)) in fl.exact.iter().zip(&fl.approx).enumerate() {
                if !fl.determined[i] {
                    continue;
                }
                let q = [i % m, (i / m) % m, i / (m * m)];
                let interior = q.iter().all(|&x| x > 0 && x + 1 < m);
                na += 1;
                ni += usize::from(interior);
                for t in 0..2 {
                    let e2 = (ex[t] - ap[t]).powi(2);
                    all[t] += e2;
                    if interior {
                        inner[t] += e2;
                    }
                }
            }
            TableRow {
                row: r + 1,
                name,
                thesis: thesis.to_vec(),
                rms: rms(&all, na),
                rms_interior: rms(&inner, ni),
                undetermined: fl.undetermined,
            }
        })
        .collect()
}
