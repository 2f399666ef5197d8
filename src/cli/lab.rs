//! `rasterlab lab`: the interactive lab, served on 127.0.0.1 until Ctrl-C.

use clap::Args;
use rasterlab::check::Program;
use rasterlab::lab::LabServer;
use rasterlab::{Error, Result};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

#[derive(Args, Debug)]
pub struct LabArgs {
    /// Port on 127.0.0.1 (0: any free port).
    #[arg(long, default_value_t = 7878)]
    port: u16,
    /// A rasterizer of your own to overlay, with the `rasterlab check`
    /// protocol ({input}, {width}, {height}, {rule}; prints `x y t`).
    #[arg(long)]
    exec: Option<String>,
}

pub fn run(args: &LabArgs) -> Result<()> {
    let server = LabServer::bind(args.port)?;
    let stop = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&stop);
    ctrlc::set_handler(move || flag.store(true, Ordering::Relaxed))
        .map_err(|e| Error::InvalidArgument(format!("cannot catch Ctrl-C: {e}")))?;
    super::print::line(format_args!(
        "rasterlab lab: http://127.0.0.1:{}/ (Ctrl-C stops it)",
        server.port()
    ))?;
    let program = args
        .exec
        .as_deref()
        .map(|command| Program::new(command, "top-left"));
    server.serve(program, &stop);
    eprintln!("rasterlab lab: stopped");
    Ok(())
}
