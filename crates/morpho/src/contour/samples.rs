//! `contour_samples`: the three phases of Dorgerloh et al. §1 on a point set with values —
//! Delaunay triangulation (2D, or 3D for x, y, z samples, §3.7), rating and colouring, contour.

use super::pipeline::{
    contour_delaunay_2d, contour_delaunay_3d, select_samples, SampleContour, SampleOptions,
};
use super::ContourError;
use crate::delaunay::{d2, d3};
use crate::geom::{Point2, Point3};
use crate::mesh::PointSet;
use crate::Result;

/// A refusal of the Delaunay triangulation, kept whole inside the contour error.
fn lower(e: impl Into<crate::Error>) -> ContourError {
    ContourError::Lower(Box::new(e.into()))
}

/// Triangulates the samples (2D or 3D by `samples.dim`) and computes their contour. Samples
/// without a value are skipped; samples at the same position share a vertex whose value is
/// their mean. O(n log n) for the triangulation, O(n) after it; the triangulation, made here,
/// is not re-validated by the contour phase (a given one is: [`super::contour_triangulated_2d`]).
///
/// ```
/// use morpho::contour::{contour_samples, SampleContour, SampleOptions};
/// use morpho::geom::Point2;
/// use morpho::mesh::{Column, PointSet};
/// // a 4 × 4 grid of samples, value 10 on the inner 2 × 2, 0 elsewhere
/// let pts: Vec<Point2> = (0..16).map(|i| Point2::new((i % 4) as f64, (i / 4) as f64)).collect();
/// let values = (0..16)
///     .map(|i| if (1..3).contains(&(i % 4)) && (1..3).contains(&(i / 4)) { 10.0 } else { 0.0 })
///     .collect();
/// let mut samples = PointSet::from_points2(&pts);
/// samples.columns.push(Column { name: "value".into(), values });
/// let opts = SampleOptions { threshold: 5.0, ..Default::default() };
/// let SampleContour::Plane(c) = contour_samples(&samples, &opts).unwrap() else { panic!() };
/// assert_eq!(c.contour.cycles.len(), 1); // one black component, one external cycle
/// assert_eq!(c.selected.skipped, 0);
/// ```
pub fn contour_samples(
    samples: &PointSet,
    opts: &SampleOptions,
) -> Result<SampleContour, ContourError> {
    let sel = select_samples(samples, opts.value.as_deref())?;
    if samples.dim == 2 {
        // Nothing skipped (the usual case): the kept samples are all samples in order, and one
        // sequential pass over the coordinates replaces the gather.
        let pts: Vec<Point2> = if sel.input.len() == samples.len() {
            samples
                .coords
                .chunks_exact(2)
                .map(|p| Point2::new(p[0], p[1]))
                .collect()
        } else {
            sel.input
                .iter()
                .map(|&i| {
                    let p = samples.point(i as usize);
                    Point2::new(p[0], p[1])
                })
                .collect()
        };
        let d = d2::triangulate(&pts).map_err(lower)?;
        drop(pts);
        Ok(SampleContour::Plane(contour_delaunay_2d(sel, d, opts)?))
    } else {
        let pts: Vec<Point3> = if sel.input.len() == samples.len() && samples.dim >= 3 {
            samples
                .coords
                .chunks_exact(samples.dim)
                .map(|p| Point3::new(p[0], p[1], p[2]))
                .collect()
        } else {
            sel.input
                .iter()
                .map(|&i| {
                    let p = samples.point(i as usize);
                    Point3::new(p[0], p[1], p[2])
                })
                .collect()
        };
        let d = d3::triangulate(&pts).map_err(lower)?;
        drop(pts);
        Ok(SampleContour::Space(contour_delaunay_3d(sel, d, opts)?))
    }
}
