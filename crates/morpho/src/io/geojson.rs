//! GeoJSON Polygon, MultiPolygon, LineString (also inside Feature/FeatureCollection). TODO(helper).
use crate::mesh::Shapes2;
use crate::{Error, Result};
use std::io::Write;

/// Reads all polygons and line strings.
pub fn read(bytes: &[u8]) -> Result<Shapes2> {
    let _ = bytes;
    Err(Error::unsupported("not implemented yet"))
}
/// Writes a FeatureCollection.
pub fn write(w: &mut dyn Write, shapes: &Shapes2) -> Result<()> {
    let _ = (w, shapes);
    Err(Error::unsupported("not implemented yet"))
}
