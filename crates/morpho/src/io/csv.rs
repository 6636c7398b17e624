//! CSV points (header `x,y[,z][,more columns]`) and polygons (ordered vertices). TODO(helper).
use crate::mesh::{PointSet, Shapes2};
use crate::{Error, Result};
use std::io::Write;

/// Points with header; columns other than x, y, z become named value columns.
pub fn read_points(bytes: &[u8]) -> Result<PointSet> {
    let _ = bytes;
    Err(Error::unsupported("not implemented yet"))
}
/// Writes points with a header.
pub fn write_points(w: &mut dyn Write, pts: &PointSet) -> Result<()> {
    let _ = (w, pts);
    Err(Error::unsupported("not implemented yet"))
}
/// A polygon as ordered vertices (a repeated first vertex at the end closes the ring).
pub fn read_polygon(bytes: &[u8]) -> Result<Shapes2> {
    let _ = bytes;
    Err(Error::unsupported("not implemented yet"))
}
/// Writes the rings/polylines as ordered vertices.
pub fn write_polygon(w: &mut dyn Write, shapes: &Shapes2) -> Result<()> {
    let _ = (w, shapes);
    Err(Error::unsupported("not implemented yet"))
}
