//! `contour_samples`: the three phases of Dorgerloh et al. §1 on a point set with values —
//! Delaunay triangulation (2D, or 3D for x, y, z samples, §3.7), rating and colouring, contour.
//!
//! integration: this file is not declared in `contour/mod.rs` yet because it uses
//! `delaunay::d2::triangulate` and `delaunay::d3::triangulate`, which were stubs in the contour
//! worktree. After merging the Delaunay branches, add `pub mod samples;` and
//! `pub use samples::contour_samples;` to `contour/mod.rs`, and replace the body of
//! `contour_samples` in `morpho-cli/src/cmd/contour.rs` by a call to this function.

use super::pipeline::{
    finish_plane, finish_space, select_samples, SampleContour, SampleOptions, Triangulation2,
    Triangulation3,
};
use crate::delaunay::{d2, d3};
use crate::geom::{Point2, Point3};
use crate::mesh::PointSet;
use crate::Result;

/// Triangulates the samples (2D or 3D by `samples.dim`) and computes their contour. Samples
/// without a value are skipped; samples at the same position share a vertex whose value is
/// their mean. O(n log n) for the triangulation, O(n) after it.
pub fn contour_samples(samples: &PointSet, opts: &SampleOptions) -> Result<SampleContour> {
    let sel = select_samples(samples, opts.value.as_deref())?;
    if samples.dim == 2 {
        let pts: Vec<Point2> = sel
            .input
            .iter()
            .map(|&i| {
                let p = samples.point(i as usize);
                Point2::new(p[0], p[1])
            })
            .collect();
        let d = d2::triangulate(&pts)?;
        let tri = Triangulation2 {
            points: &d.points,
            vertex_of_input: &d.vertex_of_input,
            input_of_vertex: &d.input_of_vertex,
            triangles: &d.triangles,
            neighbors: Some(&d.neighbors),
        };
        Ok(SampleContour::Plane(finish_plane(sel, tri, opts)?))
    } else {
        let pts: Vec<Point3> = sel
            .input
            .iter()
            .map(|&i| {
                let p = samples.point(i as usize);
                Point3::new(p[0], p[1], p[2])
            })
            .collect();
        let d = d3::triangulate(&pts)?;
        let tri = Triangulation3 {
            points: &d.points,
            vertex_of_input: &d.vertex_of_input,
            input_of_vertex: &d.input_of_vertex,
            tets: &d.tets,
            neighbors: Some(&d.neighbors),
        };
        Ok(SampleContour::Space(finish_space(sel, tri, opts)?))
    }
}
