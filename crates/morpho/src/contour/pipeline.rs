//! The whole pipeline of Dorgerloh et al. §1 on rated samples, without the triangulation call
//! itself: choose the value column, drop samples without a value, give each triangulation
//! vertex a value (the mean over samples at the same position), rate the simplices, colour them
//! and compute the contour. The thin `contour_samples` (file `samples.rs`) adds the Delaunay
//! triangulation in front, through `contour_delaunay_2d/3d`, which trust the triangulation they
//! are handed (see `dual::Valid`) instead of re-validating it as the public entry points do for
//! a triangulation from a caller or a file. O(n) after the triangulation.

use super::cycles::{boundary_regions_valid, external_contour_valid};
use super::dual::Valid;
use super::rating::{rate_tetrahedra_valid, rate_triangles_valid};
use super::tet::external_surface_valid;
use super::ContourError;
use super::{
    boundary_regions, classify, external_contour_with, external_surface_with, rate_tetrahedra,
    rate_triangles, Contour2, ContourOptions, Rating, Surface3,
};
use crate::delaunay::{Delaunay2, Delaunay3};
use crate::geom::{Point2, Point3};
use crate::mesh::{Column, PointSet};
use crate::Result;

/// What to compute from rated samples.
#[derive(Debug, Clone, PartialEq)]
pub struct SampleOptions {
    /// The value column by name; `None` takes the column `value` or the only column there is.
    pub value: Option<String>,
    /// Threshold of the rating.
    pub threshold: f64,
    /// How a simplex is rated from its corner values.
    pub rating: Rating,
    /// Black where the rating is below the threshold (instead of above).
    pub below: bool,
    /// 2D: the complete boundary (polygons with holes) instead of the external contour.
    pub holes: bool,
    /// 2D: regions with a smaller area are dropped.
    pub min_area: f64,
}

impl Default for SampleOptions {
    fn default() -> Self {
        SampleOptions {
            value: None,
            threshold: 0.0,
            rating: Rating::Mean,
            below: false,
            holes: false,
            min_area: 0.0,
        }
    }
}

/// The samples that enter the triangulation.
#[derive(Debug, Clone, PartialEq)]
pub struct SelectedSamples {
    /// Name of the value column used.
    pub column: String,
    /// Input index of each kept sample.
    pub input: Vec<u32>,
    /// Value of each kept sample.
    pub values: Vec<f64>,
    /// Samples dropped because their value is missing (NaN) or not finite.
    pub skipped: usize,
}

/// The value column: by name, else `value`, else the only column.
pub fn value_column<'a>(
    samples: &'a PointSet,
    name: Option<&str>,
) -> Result<&'a Column, ContourError> {
    let names = || {
        samples
            .columns
            .iter()
            .map(|c| c.name.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    };
    match name {
        Some(n) => samples.column(n).ok_or_else(|| ContourError::NoSuchColumn {
            name: n.to_string(),
            columns: names(),
        }),
        None => {
            if let Some(c) = samples.column("value") {
                Ok(c)
            } else if samples.columns.len() == 1 {
                Ok(&samples.columns[0])
            } else if samples.columns.is_empty() {
                Err(ContourError::NoValueColumn)
            } else {
                Err(ContourError::SeveralValueColumns { columns: names() })
            }
        }
    }
}

/// Chooses the value column and keeps the samples whose value is finite.
pub fn select_samples(
    samples: &PointSet,
    name: Option<&str>,
) -> Result<SelectedSamples, ContourError> {
    let col = value_column(samples, name)?;
    if col.values.len() != samples.len() {
        return Err(ContourError::ColumnLength {
            name: col.name.clone(),
        });
    }
    let mut input = Vec::with_capacity(samples.len());
    let mut values = Vec::with_capacity(samples.len());
    for (i, &v) in col.values.iter().enumerate() {
        if v.is_finite() {
            input.push(i as u32);
            values.push(v);
        }
    }
    Ok(SelectedSamples {
        column: col.name.clone(),
        skipped: samples.len() - input.len(),
        input,
        values,
    })
}

/// The value of each vertex: the mean of the values of the samples merged into it.
pub fn vertex_values(
    nverts: usize,
    vertex_of_input: &[u32],
    values: &[f64],
) -> Result<Vec<f64>, ContourError> {
    if vertex_of_input.len() != values.len() {
        return Err(ContourError::BadVertexMap {
            reason: "vertex map and values differ in length",
        });
    }
    let mut sum = vec![0.0; nverts];
    let mut cnt = vec![0u32; nverts];
    for (&v, &x) in vertex_of_input.iter().zip(values) {
        let v = v as usize;
        if v >= nverts {
            return Err(ContourError::BadVertexMap {
                reason: "vertex map refers to a missing vertex",
            });
        }
        sum[v] += x;
        cnt[v] += 1;
    }
    Ok(sum
        .iter()
        .zip(&cnt)
        .map(|(&s, &c)| if c > 0 { s / c as f64 } else { 0.0 })
        .collect())
}

/// [`vertex_values`] of a Delaunay triangulation: without merged duplicates every vertex holds
/// exactly one sample, so its mean is that sample's value (`0.0 + x`, as the sum computes it,
/// which keeps the bits, −0 included) and one gather replaces the two summing passes.
fn delaunay_vertex_values(
    duplicates: usize,
    vertex_of_input: &[u32],
    input_of_vertex: &[u32],
    values: &[f64],
) -> Result<Vec<f64>, ContourError> {
    if duplicates != 0 || vertex_of_input.len() != input_of_vertex.len() {
        return vertex_values(input_of_vertex.len(), vertex_of_input, values);
    }
    // One range check, then a gather of known length: collecting `Result`s would grow the
    // vector by doubling (its size hint is 0), copying and faulting in pages several times.
    if input_of_vertex.iter().any(|&i| i as usize >= values.len()) {
        return Err(ContourError::BadVertexMap {
            reason: "vertex refers to a missing sample",
        });
    }
    Ok(input_of_vertex
        .iter()
        .map(|&i| 0.0 + values[i as usize])
        .collect())
}

/// A triangulation of the kept samples, as produced by a Delaunay triangulator.
#[derive(Debug, Clone, Copy)]
pub struct SampleTriangulation2<'a> {
    /// Vertices of the triangulation (the kept samples, duplicates merged).
    pub points: &'a [Point2],
    /// Triangulation vertex of each kept sample (index into `points`).
    pub vertex_of_input: &'a [u32],
    /// Kept-sample index of each triangulation vertex (the first of a merged group).
    pub input_of_vertex: &'a [u32],
    /// Triangles, counter-clockwise, as indices into `points`.
    pub triangles: &'a [[u32; 3]],
    /// `neighbors[t][i]`: the triangle across edge (v_i, v_{i+1}) of triangle t, or `NONE`; computed when `None`.
    pub neighbors: Option<&'a [[u32; 3]]>,
}

/// A tetrahedrization of the kept samples.
#[derive(Debug, Clone, Copy)]
pub struct SampleTriangulation3<'a> {
    /// Vertices of the tetrahedrization (the kept samples, duplicates merged).
    pub points: &'a [Point3],
    /// Tetrahedrization vertex of each kept sample (index into `points`).
    pub vertex_of_input: &'a [u32],
    /// Kept-sample index of each tetrahedrization vertex (the first of a merged group).
    pub input_of_vertex: &'a [u32],
    /// Positively oriented tetrahedra, as indices into `points`.
    pub tets: &'a [[u32; 4]],
    /// `neighbors[t][i]`: the tetrahedron opposite vertex i of tetrahedron t, or `NONE`; computed when `None`.
    pub neighbors: Option<&'a [[u32; 4]]>,
}

/// The result in the plane.
#[derive(Debug, Clone, PartialEq)]
pub struct PlaneContour {
    /// The samples that took part (finite values) and their values.
    pub selected: SelectedSamples,
    /// Triangulation vertices.
    pub points: Vec<Point2>,
    /// Input sample index of each vertex.
    pub sample_of_vertex: Vec<u32>,
    /// Triangles of the triangulation, counter-clockwise, as indices into `points`.
    pub triangles: Vec<[u32; 3]>,
    /// Value of each vertex.
    pub values: Vec<f64>,
    /// Rating of each triangle.
    pub ratings: Vec<f64>,
    /// Colour of each triangle.
    pub black: Vec<bool>,
    /// The contour (vertex indices of `points`).
    pub contour: Contour2,
}

impl PlaneContour {
    /// The contour cycles as input sample indices.
    pub fn cycles_as_samples(&self) -> Vec<Vec<u32>> {
        self.contour
            .cycles
            .iter()
            .map(|c| {
                c.iter()
                    .map(|&v| self.sample_of_vertex[v as usize])
                    .collect()
            })
            .collect()
    }
}

/// The result in space.
#[derive(Debug, Clone, PartialEq)]
pub struct SpaceContour {
    /// The samples that took part (finite values) and their values.
    pub selected: SelectedSamples,
    /// Tetrahedrization vertices.
    pub points: Vec<Point3>,
    /// Input sample index of each vertex.
    pub sample_of_vertex: Vec<u32>,
    /// Positively oriented tetrahedra, as indices into `points`.
    pub tets: Vec<[u32; 4]>,
    /// Value of each vertex.
    pub values: Vec<f64>,
    /// Rating of each tetrahedron.
    pub ratings: Vec<f64>,
    /// Colour of each tetrahedron.
    pub black: Vec<bool>,
    /// The contour surface (triangles between black and white tetrahedra).
    pub surface: Surface3,
}

/// Either result.
#[derive(Debug, Clone, PartialEq)]
pub enum SampleContour {
    /// Samples in the plane (two coordinates).
    Plane(PlaneContour),
    /// Samples in space (three coordinates).
    Space(SpaceContour),
}

/// Rating, colouring and contour phases on a triangulation of the selected samples.
pub fn contour_triangulated_2d(
    selected: SelectedSamples,
    tri: SampleTriangulation2<'_>,
    opts: &SampleOptions,
) -> Result<PlaneContour, ContourError> {
    let values = vertex_values(tri.points.len(), tri.vertex_of_input, &selected.values)?;
    let r = plane_phases(tri, values, opts, None)?;
    let sample_of_vertex = map_vertices(tri.input_of_vertex, &selected.input)?;
    Ok(r.into_contour(
        selected,
        sample_of_vertex,
        tri.points.to_vec(),
        tri.triangles.to_vec(),
    ))
}

/// [`contour_triangulated_2d`] on the Delaunay triangulation of the selected samples that
/// `delaunay::triangulate_2d` has just returned: the triangulation is not re-validated, and its
/// points and triangles move into the result instead of being copied.
pub(crate) fn contour_delaunay_2d(
    selected: SelectedSamples,
    d: Delaunay2,
    opts: &SampleOptions,
) -> Result<PlaneContour, ContourError> {
    let valid = Valid::delaunay2(&d);
    let tri = SampleTriangulation2 {
        points: &d.points,
        vertex_of_input: &d.vertex_of_input,
        input_of_vertex: &d.input_of_vertex,
        triangles: &d.triangles,
        neighbors: Some(&d.neighbors),
    };
    let values = delaunay_vertex_values(
        d.duplicates,
        &d.vertex_of_input,
        &d.input_of_vertex,
        &selected.values,
    )?;
    let r = plane_phases(tri, values, opts, Some(valid))?;
    let sample_of_vertex = map_vertices_owned(d.input_of_vertex, &selected.input)?;
    Ok(r.into_contour(selected, sample_of_vertex, d.points, d.triangles))
}

/// What the plane pipeline computes besides the triangulation itself.
struct PlanePhases {
    values: Vec<f64>,
    ratings: Vec<f64>,
    black: Vec<bool>,
    contour: Contour2,
}

impl PlanePhases {
    fn into_contour(
        self,
        selected: SelectedSamples,
        sample_of_vertex: Vec<u32>,
        points: Vec<Point2>,
        triangles: Vec<[u32; 3]>,
    ) -> PlaneContour {
        PlaneContour {
            selected,
            points,
            sample_of_vertex,
            triangles,
            values: self.values,
            ratings: self.ratings,
            black: self.black,
            contour: self.contour,
        }
    }
}

/// Rating, colouring and contour; the triangulation is checked unless `valid` vouches for it
/// (then `tri.neighbors` is `Some`).
fn plane_phases(
    tri: SampleTriangulation2<'_>,
    values: Vec<f64>,
    opts: &SampleOptions,
    valid: Option<Valid>,
) -> Result<PlanePhases, ContourError> {
    let ratings = match valid {
        Some(v) => rate_triangles_valid(tri.triangles, tri.points, &values, opts.rating, v)?,
        None => rate_triangles(tri.triangles, tri.points, &values, opts.rating)?,
    };
    let black = classify(&ratings, opts.threshold, opts.below);
    let copts = ContourOptions {
        min_area: opts.min_area,
    };
    let contour = match (valid, tri.neighbors) {
        (Some(v), Some(nb)) if opts.holes => {
            boundary_regions_valid(tri.triangles, nb, tri.points, &black, &copts, v)?
        }
        (Some(v), Some(nb)) => {
            external_contour_valid(tri.triangles, nb, tri.points, &black, &copts, v)?
        }
        _ if opts.holes => {
            boundary_regions(tri.triangles, tri.neighbors, tri.points, &black, &copts)?
        }
        _ => external_contour_with(tri.triangles, tri.neighbors, tri.points, &black, &copts)?,
    };
    Ok(PlanePhases {
        values,
        ratings,
        black,
        contour,
    })
}

/// Rating, colouring and contour phases on a tetrahedrization of the selected samples.
pub fn contour_triangulated_3d(
    selected: SelectedSamples,
    tri: SampleTriangulation3<'_>,
    opts: &SampleOptions,
) -> Result<SpaceContour, ContourError> {
    let values = vertex_values(tri.points.len(), tri.vertex_of_input, &selected.values)?;
    let r = space_phases(tri, values, opts, None)?;
    let sample_of_vertex = map_vertices(tri.input_of_vertex, &selected.input)?;
    Ok(r.into_contour(
        selected,
        sample_of_vertex,
        tri.points.to_vec(),
        tri.tets.to_vec(),
    ))
}

/// [`contour_triangulated_3d`] on the Delaunay tetrahedrization of the selected samples that
/// `delaunay::triangulate_3d` has just returned: not re-validated, points and tetrahedra moved
/// into the result.
pub(crate) fn contour_delaunay_3d(
    selected: SelectedSamples,
    d: Delaunay3,
    opts: &SampleOptions,
) -> Result<SpaceContour, ContourError> {
    let valid = Valid::delaunay3(&d);
    let tri = SampleTriangulation3 {
        points: &d.points,
        vertex_of_input: &d.vertex_of_input,
        input_of_vertex: &d.input_of_vertex,
        tets: &d.tets,
        neighbors: Some(&d.neighbors),
    };
    let values = delaunay_vertex_values(
        d.duplicates,
        &d.vertex_of_input,
        &d.input_of_vertex,
        &selected.values,
    )?;
    let r = space_phases(tri, values, opts, Some(valid))?;
    let sample_of_vertex = map_vertices_owned(d.input_of_vertex, &selected.input)?;
    Ok(r.into_contour(selected, sample_of_vertex, d.points, d.tets))
}

/// What the space pipeline computes besides the tetrahedrization itself.
struct SpacePhases {
    values: Vec<f64>,
    ratings: Vec<f64>,
    black: Vec<bool>,
    surface: Surface3,
}

impl SpacePhases {
    fn into_contour(
        self,
        selected: SelectedSamples,
        sample_of_vertex: Vec<u32>,
        points: Vec<Point3>,
        tets: Vec<[u32; 4]>,
    ) -> SpaceContour {
        SpaceContour {
            selected,
            points,
            sample_of_vertex,
            tets,
            values: self.values,
            ratings: self.ratings,
            black: self.black,
            surface: self.surface,
        }
    }
}

/// Rating, colouring and the external surface; checked unless `valid` vouches for the
/// tetrahedrization.
fn space_phases(
    tri: SampleTriangulation3<'_>,
    values: Vec<f64>,
    opts: &SampleOptions,
    valid: Option<Valid>,
) -> Result<SpacePhases, ContourError> {
    let ratings = match valid {
        Some(v) => rate_tetrahedra_valid(tri.tets, tri.points, &values, opts.rating, v)?,
        None => rate_tetrahedra(tri.tets, tri.points, &values, opts.rating)?,
    };
    let black = classify(&ratings, opts.threshold, opts.below);
    let surface = match (valid, tri.neighbors) {
        (Some(v), Some(nb)) => external_surface_valid(tri.tets, nb, tri.points, &black, v)?,
        _ => external_surface_with(tri.tets, tri.neighbors, tri.points, &black)?,
    };
    Ok(SpacePhases {
        values,
        ratings,
        black,
        surface,
    })
}

/// [`map_vertices`] taking the vertex map by value: when nothing was skipped (`input` is the
/// identity) and the map is in range, the sample of each vertex is its kept-sample index, and
/// the map itself is the result (moved, not copied).
fn map_vertices_owned(input_of_vertex: Vec<u32>, input: &[u32]) -> Result<Vec<u32>, ContourError> {
    let identity = input.iter().enumerate().all(|(i, &k)| k as usize == i);
    if identity && input_of_vertex.iter().all(|&i| (i as usize) < input.len()) {
        return Ok(input_of_vertex);
    }
    map_vertices(&input_of_vertex, input)
}

/// The input sample of each vertex: `input[input_of_vertex[v]]`.
fn map_vertices(input_of_vertex: &[u32], input: &[u32]) -> Result<Vec<u32>, ContourError> {
    // Nothing skipped (the usual case): `input` is the identity and one sequential copy replaces
    // a gather in vertex order.
    let identity = input.iter().enumerate().all(|(i, &k)| k as usize == i);
    if identity && input_of_vertex.iter().all(|&i| (i as usize) < input.len()) {
        return Ok(input_of_vertex.to_vec());
    }
    input_of_vertex
        .iter()
        .map(|&i| {
            input
                .get(i as usize)
                .copied()
                .ok_or(ContourError::BadVertexMap {
                    reason: "vertex refers to a missing sample",
                })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn samples() -> PointSet {
        let mut p = PointSet::from_points2(&[
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 0.0),
            Point2::new(0.0, 1.0),
            Point2::new(1.0, 1.0),
            Point2::new(1.0, 1.0),
        ]);
        p.columns.push(Column {
            name: "zinc".into(),
            values: vec![1.0, f64::NAN, 3.0, 4.0, 6.0],
        });
        p
    }

    #[test]
    fn columns_and_selection() {
        let mut p = samples();
        assert_eq!(value_column(&p, None).unwrap().name, "zinc");
        assert!(value_column(&p, Some("lead")).is_err());
        let s = select_samples(&p, Some("zinc")).unwrap();
        assert_eq!(s.input, [0, 2, 3, 4]);
        assert_eq!(s.skipped, 1);
        p.columns.push(Column {
            name: "lead".into(),
            values: vec![0.0; 5],
        });
        assert!(value_column(&p, None).is_err());
        p.columns[1].name = "value".into();
        assert_eq!(value_column(&p, None).unwrap().name, "value");
        // Duplicates share a vertex whose value is their mean.
        assert_eq!(
            vertex_values(3, &[0, 1, 2, 2], &s.values).unwrap(),
            [1.0, 3.0, 5.0]
        );
    }

    #[test]
    fn plane_pipeline_on_a_given_triangulation() {
        let p = samples();
        let sel = select_samples(&p, None).unwrap();
        let pts = [
            Point2::new(0.0, 0.0),
            Point2::new(0.0, 1.0),
            Point2::new(1.0, 1.0),
        ];
        let tri = SampleTriangulation2 {
            points: &pts,
            vertex_of_input: &[0, 1, 2, 2],
            input_of_vertex: &[0, 1, 2],
            triangles: &[[0, 2, 1]],
            neighbors: None,
        };
        let opts = SampleOptions {
            threshold: 2.0,
            ..Default::default()
        };
        let r = contour_triangulated_2d(sel, tri, &opts).unwrap();
        assert_eq!(r.ratings, [3.0]);
        assert_eq!(r.contour.cycles.len(), 1);
        // Cycles in input indices: vertex 2 is sample 3 (the first of the duplicates).
        let mut c = r.cycles_as_samples()[0].clone();
        c.sort();
        assert_eq!(c, [0, 2, 3]);
    }
}
