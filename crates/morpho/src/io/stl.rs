//! STL meshes, ASCII and binary. TODO(helper): implement.
use super::Encoding;
use crate::mesh::TriMesh;
use crate::{Error, Result};
use std::io::Write;

/// Reads ASCII or binary STL; coincident corner positions are merged into shared vertices.
pub fn read(bytes: &[u8]) -> Result<TriMesh> {
    let _ = bytes;
    Err(Error::unsupported("not implemented yet"))
}
/// Writes binary STL (`Ascii` encoding: ASCII STL; big endian is not an STL variant → error).
pub fn write(w: &mut dyn Write, mesh: &TriMesh, enc: Encoding) -> Result<()> {
    let _ = (w, mesh, enc);
    Err(Error::unsupported("not implemented yet"))
}
