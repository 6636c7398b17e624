//! PLY (Stanford polygon file format): ASCII, binary little and big endian.
//! TODO(helper): implement.
use super::Encoding;
use crate::mesh::{PointSet, TriMesh};
use crate::{Error, Result};
use std::io::Write;

/// Reads vertices and faces (polygons are fan-triangulated); extra properties are kept.
pub fn read_mesh(bytes: &[u8]) -> Result<TriMesh> {
    let _ = bytes;
    Err(Error::unsupported("PLY: not implemented yet"))
}
/// Reads the vertices only, as points (3D; extra vertex properties become columns).
pub fn read_points(bytes: &[u8]) -> Result<PointSet> {
    let _ = bytes;
    Err(Error::unsupported("PLY: not implemented yet"))
}
/// Writes a mesh with its normals and extra properties.
pub fn write_mesh(w: &mut dyn Write, mesh: &TriMesh, enc: Encoding) -> Result<()> {
    let _ = (w, mesh, enc);
    Err(Error::unsupported("PLY: not implemented yet"))
}
/// Writes points (with their columns as vertex properties).
pub fn write_points(w: &mut dyn Write, pts: &PointSet, enc: Encoding) -> Result<()> {
    let _ = (w, pts, enc);
    Err(Error::unsupported("PLY: not implemented yet"))
}
