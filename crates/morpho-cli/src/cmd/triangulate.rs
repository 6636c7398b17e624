//! `morpho triangulate` (issue 3). TODO(helper).
use crate::report::Report;
use crate::Failure;
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// Points (CSV with header, XYZ, PLY, JSON array).
    pub input: PathBuf,
    /// Output: .json, .ply/.obj/.off, or .svg (2D).
    #[arg(short, long)]
    pub output: PathBuf,
}

pub fn run(args: Args, report: &mut Report) -> Result<u8, Failure> {
    let _ = (args, report);
    Err(Failure {
        code: 1,
        msg: "triangulate: not implemented yet".into(),
    })
}
