//! What a benchmark's figures were measured on: the commit, the machine
//! (CPU model, cores) and how busy it was (the load average at the start
//! and at the end of the run), recorded with every set of figures.
//!
//! ```
//! use rasterlab::measure::Machine;
//! let machine = Machine::now();
//! assert!(machine.cores >= 1);
//! assert!(!machine.cpu.is_empty());
//! ```

use serde::Serialize;
use std::fmt;

/// The commit the code was built from: `git describe --always` when it
/// was built (by `build.rs`), `RASTERLAB_COMMIT` if set at build time, or
/// `unknown` (built outside a git checkout).
pub const COMMIT: &str = match option_env!("RASTERLAB_COMMIT") {
    Some(commit) => commit,
    None => "unknown",
};

/// The machine and its load at one moment.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Machine {
    /// CPU model (`/proc/cpuinfo`'s `model name`, or the architecture).
    pub cpu: String,
    /// Cores this process may use.
    pub cores: usize,
    /// Load average over 1, 5 and 15 minutes (`None` where the system does
    /// not tell): runnable threads of every process, to compare with
    /// `cores`.
    pub load_average: Option<[f64; 3]>,
}

impl Machine {
    /// The machine now.
    pub fn now() -> Machine {
        let cpu = std::fs::read_to_string("/proc/cpuinfo")
            .ok()
            .and_then(|info| {
                info.lines()
                    .find(|l| l.starts_with("model name"))
                    .and_then(|l| l.split_once(':'))
                    .map(|(_, name)| name.trim().to_string())
            })
            .unwrap_or_else(|| std::env::consts::ARCH.to_string());
        Machine {
            cpu,
            cores: std::thread::available_parallelism().map_or(1, usize::from),
            load_average: load_average(),
        }
    }
}

/// The load averages of `/proc/loadavg`.
pub fn load_average() -> Option<[f64; 3]> {
    let text = std::fs::read_to_string("/proc/loadavg").ok()?;
    let mut fields = text.split_whitespace().map(str::parse::<f64>);
    Some([
        fields.next()?.ok()?,
        fields.next()?.ok()?,
        fields.next()?.ok()?,
    ])
}

/// The context of one benchmark run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Context {
    /// The commit ([`COMMIT`]).
    pub commit: String,
    /// The machine when the run started.
    pub machine: Machine,
    /// The load average when the run ended.
    pub load_average_at_end: Option<[f64; 3]>,
    /// Threads rasterlab draws on (the rayon pool), unless a figure says
    /// otherwise.
    pub threads: usize,
    /// Timed runs per figure (after one warm-up run), or interleaved
    /// rounds.
    pub samples: usize,
    /// Target width in pixels.
    pub width: u32,
    /// Target height in pixels.
    pub height: u32,
}

impl Context {
    /// The context of a run starting now.
    pub fn start(threads: usize, samples: usize, width: u32, height: u32) -> Context {
        Context {
            commit: COMMIT.to_string(),
            machine: Machine::now(),
            load_average_at_end: None,
            threads,
            samples,
            width,
            height,
        }
    }

    /// Records the load average at the end of the run.
    pub fn finish(&mut self) {
        self.load_average_at_end = load_average();
    }
}

/// Load averages as `a b c`, or `unknown`.
fn loads(load: Option<[f64; 3]>) -> String {
    load.map_or_else(
        || "unknown".to_string(),
        |[a, b, c]| format!("{a:.2} {b:.2} {c:.2}"),
    )
}

impl fmt::Display for Context {
    /// Two lines: the commit, target, threads and samples; the machine and
    /// its load average at the start and end.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "commit {}, {}x{}, {} thread{}, {} timed runs per figure (median [min-max] ms)",
            self.commit,
            self.width,
            self.height,
            self.threads,
            if self.threads == 1 { "" } else { "s" },
            self.samples
        )?;
        writeln!(
            f,
            "machine: {}, {} cores; load average (1, 5, 15 min) {} at start, {} at end",
            self.machine.cpu,
            self.machine.cores,
            loads(self.machine.load_average),
            loads(self.load_average_at_end)
        )
    }
}
