//! Error type of the library: every fallible function returns [`Result`].
//!
//! Errors name the input they concern. Parsers that work on bytes leave `path` empty and the
//! caller fills it in with [`Error::with_path`]; the CLI prints `error: {err}`.

use std::fmt;

/// Where in an input file a problem was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Location {
    /// 1-based line number of a text file.
    Line(u64),
    /// 0-based byte offset of a binary file.
    Byte(u64),
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Location::Line(l) => write!(f, "line {l}"),
            Location::Byte(b) => write!(f, "byte {b}"),
        }
    }
}

/// Everything that can go wrong in morpho.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The operating system refused to read or write a file.
    #[error("{}{source}", prefix(path))]
    Io {
        /// The file, empty when the data did not come from a file.
        path: String,
        #[source]
        /// What the operating system said.
        source: std::io::Error,
    },
    /// An input file is malformed (bad header, truncated, out-of-range index, NaN, …).
    #[error("{}{}{msg}", prefix(path), loc(location))]
    Format {
        /// The file, empty when the data did not come from a file.
        path: String,
        /// Line (and column, where known) of the fault.
        location: Option<Location>,
        /// What is wrong, in words.
        msg: String,
    },
    /// The input is well-formed but cannot be processed (too few points, wrong dimension, …).
    #[error("{}{msg}", prefix(path))]
    Invalid {
        /// The input file, empty for in-memory data.
        path: String,
        /// What is wrong, in words.
        msg: String,
    },
    /// The file type or feature is not supported.
    #[error("{}{msg}", prefix(path))]
    Unsupported {
        /// The input or output file, empty for in-memory data.
        path: String,
        /// The missing feature, in words.
        msg: String,
    },
    // --- delaunay, graphs (f-tri) ---
    /// A triangulation refused its input ([`crate::delaunay`]); `path` names the file the
    /// points came from, when known.
    #[error("{}{source}", prefix(path))]
    Delaunay {
        /// The input file, or empty.
        path: String,
        /// What was refused.
        #[source]
        source: crate::delaunay::DelaunayError,
    },
    /// A graph construction refused its input ([`crate::graphs`]).
    #[error("{}{source}", prefix(path))]
    Graph {
        /// The input file, or empty.
        path: String,
        /// What was refused.
        #[source]
        source: crate::graphs::GraphError,
    },
    // --- end delaunay, graphs ---
    // --- families of f-rest (volume, contour, mesh, render) ---
    /// A volume or an isosurface request was refused ([`crate::volume`]).
    #[error("{}{source}", prefix(path))]
    Volume {
        /// The file the volume came from (empty when none).
        path: String,
        /// What was refused.
        #[source]
        source: crate::volume::VolumeError,
    },
    /// A contour computation was refused ([`crate::contour`]).
    #[error("{}{source}", prefix(path))]
    Contour {
        /// The file the samples came from (empty when none).
        path: String,
        /// What was refused.
        #[source]
        source: crate::contour::ContourError,
    },
    /// A mesh or point set was refused ([`crate::mesh`]).
    #[error("{}{source}", prefix(path))]
    Mesh {
        /// The file the mesh came from (empty when none).
        path: String,
        /// What was refused.
        #[source]
        source: crate::mesh::MeshError,
    },
    /// A picture was refused ([`crate::render`]).
    #[error("{}{source}", prefix(path))]
    Render {
        /// The file concerned (empty when none).
        path: String,
        /// What was refused.
        #[source]
        source: crate::render::RenderError,
    },
    // --- end f-rest ---
    // --- boundary family (f-bnd) ---
    /// A refusal of [`crate::boundary`] (`path`: the input file when known).
    #[error("{}{source}", prefix(path))]
    Boundary {
        /// The input file, empty when unknown.
        path: String,
        /// The refusal.
        #[source]
        source: crate::boundary::BoundaryError,
    },
    /// A refusal of [`crate::flint`] (`path`: the input file when known).
    #[error("{}{source}", prefix(path))]
    Flint {
        /// The input file, empty when unknown.
        path: String,
        /// The refusal.
        #[source]
        source: crate::flint::FlintError,
    },
    /// A refusal of [`crate::curvature`] (`path`: the input file when known).
    #[error("{}{source}", prefix(path))]
    Curvature {
        /// The input file, empty when unknown.
        path: String,
        /// The refusal.
        #[source]
        source: crate::curvature::CurvatureError,
    },
    /// A refusal of [`crate::smooth`] (`path`: the input file when known).
    #[error("{}{source}", prefix(path))]
    Smooth {
        /// The input file, empty when unknown.
        path: String,
        /// The refusal.
        #[source]
        source: crate::smooth::SmoothError,
    },
    /// A refusal of [`crate::reduce`] (`path`: the input file when known).
    #[error("{}{source}", prefix(path))]
    Reduce {
        /// The input file, empty when unknown.
        path: String,
        /// The refusal.
        #[source]
        source: crate::reduce::ReduceError,
    },
}

/// `From<FamilyError> for Error`: the family's variant with an empty path (filled by
/// [`Error::with_path`]).
macro_rules! from_family {
    ($($family:ty => $variant:ident),* $(,)?) => {$(
        impl From<$family> for Error {
            fn from(source: $family) -> Self {
                Error::$variant {
                    path: String::new(),
                    source,
                }
            }
        }
    )*};
}

from_family! {
    crate::delaunay::DelaunayError => Delaunay,
    crate::graphs::GraphError => Graph,
    crate::volume::VolumeError => Volume,
    crate::mesh::MeshError => Mesh,
    crate::render::RenderError => Render,
    crate::boundary::BoundaryError => Boundary,
    crate::flint::FlintError => Flint,
    crate::curvature::CurvatureError => Curvature,
    crate::smooth::SmoothError => Smooth,
    crate::reduce::ReduceError => Reduce,
}

impl From<crate::contour::ContourError> for Error {
    fn from(source: crate::contour::ContourError) -> Self {
        match source {
            // a lower family's error keeps its own variant
            crate::contour::ContourError::Lower(e) => *e,
            source => Error::Contour {
                path: String::new(),
                source,
            },
        }
    }
}

fn prefix(path: &str) -> String {
    if path.is_empty() {
        String::new()
    } else {
        format!("{path}: ")
    }
}

fn loc(l: &Option<Location>) -> String {
    match l {
        Some(l) => format!("{l}: "),
        None => String::new(),
    }
}

impl Error {
    /// A malformed-input error without file name (filled in later by [`Error::with_path`]).
    pub fn format(msg: impl Into<String>) -> Self {
        Error::Format {
            path: String::new(),
            location: None,
            msg: msg.into(),
        }
    }
    /// A malformed-input error at a 1-based line.
    pub fn at_line(line: u64, msg: impl Into<String>) -> Self {
        Error::Format {
            path: String::new(),
            location: Some(Location::Line(line)),
            msg: msg.into(),
        }
    }
    /// A malformed-input error at a 0-based byte offset.
    pub fn at_byte(byte: u64, msg: impl Into<String>) -> Self {
        Error::Format {
            path: String::new(),
            location: Some(Location::Byte(byte)),
            msg: msg.into(),
        }
    }
    /// Input that is well-formed but unusable.
    pub fn invalid(msg: impl Into<String>) -> Self {
        Error::Invalid {
            path: String::new(),
            msg: msg.into(),
        }
    }
    /// Unsupported format or feature.
    pub fn unsupported(msg: impl Into<String>) -> Self {
        Error::Unsupported {
            path: String::new(),
            msg: msg.into(),
        }
    }
    /// An I/O error on `path`.
    pub fn io(path: impl AsRef<std::path::Path>, source: std::io::Error) -> Self {
        Error::Io {
            path: path.as_ref().display().to_string(),
            source,
        }
    }
    /// Sets the file name if none is set yet.
    pub fn with_path(mut self, p: impl AsRef<std::path::Path>) -> Self {
        let name = p.as_ref().display().to_string();
        match &mut self {
            Error::Io { path, .. }
            | Error::Format { path, .. }
            | Error::Invalid { path, .. }
            | Error::Unsupported { path, .. }
            // delaunay, graphs (f-tri)
            | Error::Delaunay { path, .. }
            | Error::Graph { path, .. }
            // f-rest families
            | Error::Volume { path, .. }
            | Error::Contour { path, .. }
            | Error::Mesh { path, .. }
            | Error::Render { path, .. }
            | Error::Boundary { path, .. }
            | Error::Flint { path, .. }
            | Error::Curvature { path, .. }
            | Error::Smooth { path, .. }
            | Error::Reduce { path, .. } => {
                if path.is_empty() {
                    *path = name;
                }
            }
        }
        self
    }
    /// True for errors caused by the user's input or arguments (CLI exit code 2).
    pub fn is_input_error(&self) -> bool {
        // delaunay, graphs (f-tri): a broken invariant is a bug, not bad input
        match self {
            Error::Delaunay { source, .. } => return source.is_input_error(),
            Error::Graph { source, .. } => return source.is_input_error(),
            Error::Boundary { source, .. } => return source.is_input_error(),
            _ => {}
        }
        !matches!(self, Error::Io { source, .. } if source.kind() != std::io::ErrorKind::NotFound
            && source.kind() != std::io::ErrorKind::PermissionDenied
            && source.kind() != std::io::ErrorKind::InvalidData
            && source.kind() != std::io::ErrorKind::UnexpectedEof)
    }
}

/// Result with morpho's [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_file_and_location() {
        let e = Error::at_line(7, "expected 3 coordinates").with_path("a.xyz");
        assert_eq!(e.to_string(), "a.xyz: line 7: expected 3 coordinates");
        let e = Error::at_byte(84, "truncated")
            .with_path("m.stl")
            .with_path("other");
        assert_eq!(e.to_string(), "m.stl: byte 84: truncated");
        assert!(e.is_input_error());
        assert_eq!(Error::invalid("too few").to_string(), "too few");
    }
}
