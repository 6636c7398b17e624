//! `morpho contour`. TODO(helper).
use crate::report::Report;
use crate::Failure;
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// Input file.
    pub input: PathBuf,
    /// Output file.
    #[arg(short, long)]
    pub output: PathBuf,
}

pub fn run(args: Args, report: &mut Report) -> Result<u8, Failure> {
    let _ = (args, report);
    Err(Failure {
        code: 1,
        msg: "contour: not implemented yet".into(),
    })
}
