//! Table 5.1 of Hamann 1991 (p. 122; notes D.4): the 9 functions of Table 4.1 on the 51×51
//! grid of `[-1, 1]²` (diagonal `(i,j)–(i+1,j+1)`, N0 = 5000 triangles), reduced with the
//! bivariate new point and exact normals to 50 %, 20 % and 10 % of the triangles, and the RMS
//! (5.41) of the piecewise-linear reduced surface at the 2601 knots.

use super::engine::{reduce, Domain, NewTriangles, Order, ReduceOptions, Reduced, Stop};
use super::error::ReduceError;
use crate::curvature::NormalSource;
use crate::geom::{Point3, Vector3};
use crate::mesh::TriMesh;

/// The functions with their gradients: (name, f, ∇f).
#[allow(clippy::type_complexity)]
pub fn functions() -> Vec<(&'static str, fn(f64, f64) -> f64, fn(f64, f64) -> [f64; 2])> {
    use std::f64::consts::PI;
    vec![
        ("plane", |x, y| 0.2 * (x + y), |_, _| [0.2, 0.2]),
        (
            "cylinder",
            |x, _| (2.0 - x * x).sqrt(),
            |x, _| [-x / (2.0 - x * x).sqrt(), 0.0],
        ),
        (
            "sphere",
            |x, y| (4.0 - x * x - y * y).sqrt(),
            |x, y| {
                let r = (4.0 - x * x - y * y).sqrt();
                [-x / r, -y / r]
            },
        ),
        (
            "paraboloid",
            |x, y| 0.4 * (x * x + y * y),
            |x, y| [0.8 * x, 0.8 * y],
        ),
        (
            "hyperboloid",
            |x, y| 0.4 * (x * x - y * y),
            |x, y| [0.8 * x, -0.8 * y],
        ),
        (
            "monkey saddle",
            |x, y| 0.2 * (x * x * x - 3.0 * x * y * y),
            |x, y| [0.2 * (3.0 * x * x - 3.0 * y * y), -1.2 * x * y],
        ),
        (
            "cubic",
            |x, y| 0.15 * (x * x * x + 2.0 * x * x * y - x * y + 2.0 * y * y),
            |x, y| {
                [
                    0.15 * (3.0 * x * x + 4.0 * x * y - y),
                    0.15 * (2.0 * x * x - x + 4.0 * y),
                ]
            },
        ),
        (
            "exponential",
            |x, y| (-0.5 * (x * x + y * y)).exp(),
            |x, y| {
                let e = (-0.5 * (x * x + y * y)).exp();
                [-x * e, -y * e]
            },
        ),
        (
            "trigonometric",
            |x, y| 0.1 * ((PI * x).cos() + (PI * y).cos()),
            |x, y| [-0.1 * PI * (PI * x).sin(), -0.1 * PI * (PI * y).sin()],
        ),
    ]
}

/// The thesis's values: rows in [`functions`] order, columns 50 %, 80 %, 90 % removed.
pub const THESIS: [[f64; 3]; 9] = [
    [0.0, 0.0, 0.0],
    [0.000485, 0.000999, 0.002105],
    [0.000445, 0.001234, 0.002288],
    [0.000610, 0.001591, 0.003619],
    [0.000248, 0.000794, 0.002009],
    [0.000355, 0.000843, 0.001853],
    [0.000381, 0.001029, 0.002160],
    [0.000336, 0.000916, 0.002075],
    [0.000359, 0.001088, 0.002054],
];

/// The 51×51 grid mesh of `f` and its exact unit normals.
pub fn grid_mesh(f: fn(f64, f64) -> f64, g: fn(f64, f64) -> [f64; 2]) -> (TriMesh, Vec<Vector3>) {
    let n = 51;
    let mut pos = Vec::with_capacity(n * n);
    let mut nor = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (-1.0 + i as f64 / 25.0, -1.0 + j as f64 / 25.0);
            pos.push(Point3::new(x, y, f(x, y)));
            let [fx, fy] = g(x, y);
            nor.push(Vector3::new(-fx, -fy, 1.0).normalize());
        }
    }
    let id = |i: usize, j: usize| (j * n + i) as u32;
    let mut tris = Vec::with_capacity(2 * (n - 1) * (n - 1));
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            tris.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            tris.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    (TriMesh::new(pos, tris), nor)
}

/// The reduction of function `k` (index into [`functions`]) to `keep` percent by the Table 5.1
/// protocol: height-field domain (the square stays covered, fold-free), bivariate new point,
/// exact normals for the H ch. 4 curvature of the input's vertices.
pub fn reduce_function(k: usize, keep: f64) -> Result<Reduced, ReduceError> {
    reduce_function_with(k, keep, NewTriangles::default())
}

/// [`reduce_function`] with a chosen reading of Rem. 5.9.
pub fn reduce_function_with(
    k: usize,
    keep: f64,
    new_triangles: NewTriangles,
) -> Result<Reduced, ReduceError> {
    reduce_function_ordered(k, keep, new_triangles, Order::Hamann)
}

/// [`reduce_function_with`] in a chosen [`Order`] (the thesis: [`Order::Hamann`]).
pub fn reduce_function_ordered(
    k: usize,
    keep: f64,
    new_triangles: NewTriangles,
    order: Order,
) -> Result<Reduced, ReduceError> {
    let (_, f, g) = functions()[k];
    let (mesh, nor) = grid_mesh(f, g);
    let opts = ReduceOptions {
        stop: Stop::Keep(keep),
        domain: Domain::HeightField,
        normals: NormalSource::Given(nor),
        check_intersections: false,
        new_triangles,
        order,
        ..Default::default()
    };
    reduce(&mesh, &opts)
}

/// The RMS (5.41) of function `k` (index into [`functions`]) reduced to `keep` percent, and
/// the number of triangles left.
pub fn rms(k: usize, keep: f64) -> Result<(f64, usize), ReduceError> {
    let r = reduce_function(k, keep)?;
    Ok((r.rms.unwrap_or(f64::NAN), r.mesh.triangles.len()))
}

/// (5.41) measured from scratch on a reduced mesh, independent of the incremental tracker:
/// `sqrt(Σ (f − f̂)² / 51²)` over the 2601 knots, `f̂` the piecewise-linear interpolant of the
/// triangle whose xy projection contains the knot (closed triangles, barycentric
/// coordinates ≥ −1e-12). Returns (rms, max |f − f̂|, knots in no triangle); uncovered knots
/// are left out of the sum (they cannot occur when the domain is kept).
pub fn knot_rms(mesh: &TriMesh, f: fn(f64, f64) -> f64) -> (f64, f64, usize) {
    let pos: Vec<[f64; 3]> = mesh.positions.iter().map(|p| p.coords.into()).collect();
    let (mut sse, mut max, mut miss) = (0.0, 0.0f64, 0);
    for j in 0..51 {
        for i in 0..51 {
            let (x, y) = (-1.0 + i as f64 / 25.0, -1.0 + j as f64 / 25.0);
            let z = mesh.triangles.iter().find_map(|t| {
                let [a, b, c] = t.map(|v| pos[v as usize]);
                let det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
                let l1 = ((x - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (y - a[1])) / det;
                let l2 = ((b[0] - a[0]) * (y - a[1]) - (x - a[0]) * (b[1] - a[1])) / det;
                (l1 >= -1e-12 && l2 >= -1e-12 && l1 + l2 <= 1.0 + 1e-12)
                    .then(|| a[2] + l1 * (b[2] - a[2]) + l2 * (c[2] - a[2]))
            });
            match z {
                Some(z) => {
                    let e = f(x, y) - z;
                    sse += e * e;
                    max = max.max(e.abs());
                }
                None => miss += 1,
            }
        }
    }
    ((sse / 2601.0).sqrt(), max, miss)
}
