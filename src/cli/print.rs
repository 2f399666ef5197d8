//! What every subcommand shares to print: standard output that reports a
//! closed pipe as an error instead of panicking, and a progress bar.

use rasterlab::{Error, Result};
use std::fmt::Display;
use std::io::Write;

/// Prints `value` on standard output, as it displays itself; a closed or
/// full output is an [`Error::Write`], not a panic.
pub fn out(value: impl Display) -> Result<()> {
    let mut stdout = std::io::BufWriter::new(std::io::stdout().lock());
    write!(stdout, "{value}")
        .and_then(|()| stdout.flush())
        .map_err(stdout_error)
}

/// A failed write to standard output, as the error the command reports.
pub fn stdout_error(e: std::io::Error) -> Error {
    Error::write("<stdout>", &e)
}

/// Prints `value` and a newline on standard output (see [`out`]).
pub fn line(value: impl Display) -> Result<()> {
    out(format_args!("{value}\n"))
}

/// A progress bar on standard error for `total` steps; hidden when the run
/// is short or standard error is not a terminal (indicatif's own check).
pub fn progress_bar(total: u64, what: &str) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(total);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} {msg} ({eta} left)")
            .expect("a valid progress template"),
    );
    bar.set_message(what.to_string());
    bar
}
