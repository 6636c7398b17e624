//! Whitespace-separated coordinates, one point per line, no header. TODO(helper).
use crate::mesh::PointSet;
use crate::{Error, Result};
use std::io::Write;

/// Reads 2 or 3 numbers per line (the first line fixes the dimension).
pub fn read(bytes: &[u8]) -> Result<PointSet> {
    let _ = bytes;
    Err(Error::unsupported("not implemented yet"))
}
/// Writes one point per line.
pub fn write(w: &mut dyn Write, pts: &PointSet) -> Result<()> {
    let _ = (w, pts);
    Err(Error::unsupported("not implemented yet"))
}
