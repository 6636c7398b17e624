//! `morpho render IN -o IMAGE.{svg,png}`. TODO: wire to morpho::render once it exists.
use crate::report::Report;
use crate::Failure;
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// Input file.
    pub input: PathBuf,
    /// Output picture (.svg for 2D, .png for meshes and volumes).
    #[arg(short, long)]
    pub output: PathBuf,
}

pub fn run(args: Args, report: &mut Report) -> Result<u8, Failure> {
    let _ = (args, report);
    Err(Failure {
        code: 1,
        msg: "render: not implemented yet".into(),
    })
}
