//! `morpho demo [--out DIR]`: every pipeline on generated and bundled data, as a gallery.
use crate::report::Report;
use crate::Failure;
use std::path::PathBuf;

#[derive(clap::Args)]
pub struct Args {
    /// Folder for the gallery.
    #[arg(long, default_value = "morpho-demo")]
    pub out: PathBuf,
}

pub fn run(args: Args, report: &mut Report) -> Result<u8, Failure> {
    let _ = (args, report);
    Err(Failure {
        code: 1,
        msg: "demo: not implemented yet".into(),
    })
}
