//! One file per subcommand. Each has `Args` (clap) and `run(args, report) -> Result<exit code>`:
//! it checks the arguments, calls the library, writes its results through `morpho::io` (data)
//! or `morpho::render` (pictures) and fills the report. The handling of output paths shared by
//! all commands (never over an input, formats by extension) is here.

pub mod boundary;
pub mod contour;
pub mod convert;
pub mod curvature;
pub mod demo;
pub mod flint;
pub mod flint3;
pub mod graph;
pub mod info;
pub mod isostream;
pub mod isosurface;
pub mod reduce;
pub mod render;
pub mod smooth;
pub mod triangulate;
pub mod view;
pub mod views;

use crate::Failure;
use std::path::Path;

/// The extension of an output path, lower case (`""` without one): the formats a command
/// accepts are checked on it before anything is computed.
pub fn extension(p: &Path) -> String {
    p.extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase()
}

/// The files a command names on its command line: what it reads and what it writes
/// (`--report` included; the data file beside an `.mhd` output too).
#[derive(Default)]
pub struct Paths<'a> {
    pub inputs: Vec<&'a Path>,
    pub outputs: Vec<std::borrow::Cow<'a, Path>>,
}

impl<'a> Paths<'a> {
    /// Adds an output (and the data file its format writes beside it).
    pub fn output(&mut self, p: &'a Path) {
        if extension(p) == "mhd" {
            self.outputs
                .extend(morpho::io::mhd::data_file(p).map(Into::into));
        }
        self.outputs.push(p.into());
    }

    /// Checks, before anything is read or computed, that no output is an input, that no two
    /// outputs are the same file, and that every output is a path morpho may write
    /// ([`morpho::io::guard::output_target`]: a new path, a regular file, a FIFO or a
    /// character device). Files that headers name (detached volume data) are only known
    /// once read: the writers check them ([`morpho::io::guard`]).
    pub fn check(&self) -> Result<(), Failure> {
        use morpho::io::guard::same_file;
        for o in &self.outputs {
            if let Some(i) = self.inputs.iter().find(|i| same_file(o, i)) {
                return Err(Failure::usage(format!(
                    "{}: output would overwrite the input {}; choose another output",
                    o.display(),
                    i.display()
                )));
            }
        }
        Ok(morpho::io::guard::check_outputs(&self.outputs)?)
    }
}

/// Reads the points of a geometric command (`triangulate`, `boundary`, `graph`). `dims`
/// (`--dims`) forces the dimension: `Some(2)` keeps x and y of 3D points; `Some(3)` refuses
/// 2D points. Without it, 3D points with a constant coordinate — `x y 1` rows, a 2D set saved
/// with a third column — stay 3D (they are coplanar: no tetrahedra, no closed surface) and a
/// `note:` says which coordinate is constant and how to read them as 2D (issue 17 item 10).
pub(crate) fn read_points(
    path: &std::path::Path,
    dims: Option<u8>,
) -> Result<morpho::mesh::PointSet, Failure> {
    let mut ps = morpho::io::read_points(path)?;
    match dims {
        None if ps.dim == 3 && ps.len() > 1 => {
            if let Some(axis) = constant_axis(&ps) {
                let name = ["x", "y", "z"][axis];
                let value = ps.coords[axis];
                let hint = if axis == 2 {
                    "pass --dims 2 to read them as 2D points"
                } else {
                    "drop that column to read them as 2D points"
                };
                eprintln!(
                    "note: {}: every point has {name} = {value}: the points are coplanar; {hint}",
                    path.display()
                );
            }
        }
        None => {}
        Some(2) if ps.dim == 3 => {
            ps.coords = ps
                .coords
                .chunks_exact(3)
                .flat_map(|p| [p[0], p[1]])
                .collect();
            ps.dim = 2;
        }
        Some(3) if ps.dim == 2 => {
            return Err(Failure::usage(format!(
                "{}: --dims 3 given, but the points are 2D",
                path.display()
            )))
        }
        Some(2 | 3) => {}
        Some(d) => return Err(Failure::usage(format!("--dims must be 2 or 3, not {d}"))),
    }
    Ok(ps)
}

/// The first axis on which every point has the same coordinate (bitwise equal values).
fn constant_axis(ps: &morpho::mesh::PointSet) -> Option<usize> {
    (0..ps.dim).find(|&k| {
        let first = ps.coords[k];
        ps.coords
            .iter()
            .skip(k)
            .step_by(ps.dim)
            .all(|&v| v == first)
    })
}

/// Rows of `K` point indices (keep edges/triangles, constraint segments): one row per line,
/// fields separated by commas, semicolons, tabs or spaces; blank lines and `#` comments are
/// skipped; a first line with letters (`i,j`) is a header. Anything else is an error naming
/// the line. `what` names the file in messages.
pub(crate) fn read_index_rows<const K: usize>(
    path: &std::path::Path,
    what: &str,
) -> morpho::Result<Vec<[u32; K]>> {
    let bytes = morpho::io::read_bytes(path)?;
    // CR, LF and CRLF line ends alike
    let bytes = morpho::io::unify_line_ends(&bytes);
    let text = std::str::from_utf8(&bytes)
        .map_err(|_| morpho::Error::format(format!("{what} file is not UTF-8")).with_path(path))?;
    let mut out = Vec::new();
    let mut first = true;
    for (ln, line) in text.lines().enumerate() {
        let l = line.trim();
        if l.is_empty() || l.starts_with('#') {
            continue;
        }
        let f: Vec<&str> = l
            .split([',', ';', '\t', ' '])
            .filter(|s| !s.is_empty())
            .collect();
        let parsed: Option<[u32; K]> = if f.len() == K {
            let v: Vec<u32> = f.iter().filter_map(|x| x.parse::<u32>().ok()).collect();
            v.try_into().ok()
        } else {
            None
        };
        match parsed {
            Some(e) => out.push(e),
            None if first && l.chars().any(char::is_alphabetic) => {}
            None => {
                return Err(morpho::Error::at_line(
                    ln as u64 + 1,
                    format!("expected {K} point indices per line, found `{l}`"),
                )
                .with_path(path))
            }
        }
        first = false;
    }
    Ok(out)
}
