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
    /// Start the --exec program once and give it input after input on its
    /// standard input, as `rasterlab check --persistent` does ({rule} is
    /// replaced once, at the start).
    #[arg(long, requires = "exec")]
    persistent: bool,
}

pub fn run(args: &LabArgs) -> Result<()> {
    let program = match args.exec.as_deref() {
        None => None,
        Some(command) if args.persistent => Some(Program::persistent(command, "top-left")?),
        Some(command) if !command.contains("{input}") => {
            return Err(Error::InvalidArgument(
                "the --exec command has no {input}, so the program would not be given the \
                 input: a program that reads its input on its standard input runs with \
                 --persistent; one that reads a file takes {input}"
                    .into(),
            ))
        }
        Some(command) => Some(Program::new(command, "top-left")),
    };
    let server = LabServer::bind(args.port)?;
    let stop = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&stop);
    ctrlc::set_handler(move || flag.store(true, Ordering::Relaxed))
        .map_err(|e| Error::InvalidArgument(format!("cannot catch Ctrl-C: {e}")))?;
    super::print::line(format_args!(
        "rasterlab lab: http://127.0.0.1:{}/ (Ctrl-C stops it)",
        server.port()
    ))?;
    server.serve(program, &stop);
    eprintln!("rasterlab lab: stopped");
    Ok(())
}
