//! One file per subcommand. Each has `Args` (clap) and `run(args, report) -> Result<exit code>`.

pub mod boundary;
pub mod contour;
pub mod convert;
pub mod demo;
pub mod graph;
pub mod info;
pub mod isosurface;
pub mod render;
pub mod triangulate;

use crate::Failure;
use std::path::Path;

/// Refuses to write an output over an input file (same path after resolving links).
pub fn check_not_input(output: &Path, inputs: &[&Path]) -> Result<(), Failure> {
    let out = std::fs::canonicalize(output).ok();
    for i in inputs {
        let same = match (&out, std::fs::canonicalize(i).ok()) {
            (Some(a), Some(b)) => *a == b,
            _ => output == *i,
        };
        if same {
            return Err(Failure::usage(format!(
                "{}: output would overwrite the input; choose another -o",
                output.display()
            )));
        }
    }
    Ok(())
}
