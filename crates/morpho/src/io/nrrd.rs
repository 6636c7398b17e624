//! Volume format nrrd. TODO(helper).
use crate::volume::Volume;
use crate::{Error, Result};
use std::path::Path;

/// Reads a volume (detached data is found relative to `path`).
pub fn read(path: &Path) -> Result<Volume> {
    let _ = path;
    Err(Error::unsupported("not implemented yet"))
}
/// Writes a volume (with its data file beside it where the format has one), atomically.
pub fn write(path: &Path, v: &Volume) -> Result<()> {
    let _ = (path, v);
    Err(Error::unsupported("not implemented yet"))
}
