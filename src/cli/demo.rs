//! `rasterlab demo`: every back-end on the bundled scenes, checked identical.

use clap::Args;
use rasterlab::teaching::{bundled_assets, run_demo};
use rasterlab::{Error, Result};
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct DemoArgs {
    /// Directory the pictures are written to.
    #[arg(long, default_value = "demo-output")]
    out: PathBuf,
}

pub fn run(args: &DemoArgs) -> Result<()> {
    let report = run_demo(&args.out, &bundled_assets())?;
    super::print::out(&report)?;
    if report.all_identical() {
        Ok(())
    } else {
        Err(Error::Mismatch("back-ends disagree".into()))
    }
}
