//! OBJ meshes. TODO(helper): implement.
use crate::mesh::TriMesh;
use crate::{Error, Result};
use std::io::Write;

/// Reads a mesh (polygons are fan-triangulated).
pub fn read(bytes: &[u8]) -> Result<TriMesh> {
    let _ = bytes;
    Err(Error::unsupported("not implemented yet"))
}
/// Writes a mesh.
pub fn write(w: &mut dyn Write, mesh: &TriMesh) -> Result<()> {
    let _ = (w, mesh);
    Err(Error::unsupported("not implemented yet"))
}
