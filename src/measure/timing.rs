//! Timing one piece of work: a warm-up run, then timed runs, kept as
//! their minimum, median and maximum (the spread shows how far one figure
//! can be trusted on a shared machine), with the CPU time the threads got
//! meanwhile ([`crate::measure::cpu`]).
//!
//! ```
//! use rasterlab::measure::{significant, time_runs};
//! let (timing, answer) = time_runs(5, || (1..=100u64).sum::<u64>());
//! assert_eq!(answer, 5050);
//! assert_eq!(timing.spread.runs, 5);
//! assert!(timing.spread.min_ms <= timing.spread.median_ms);
//! assert!(timing.spread.median_ms <= timing.spread.max_ms);
//! assert_eq!(significant(0.001234), "0.00123");
//! assert_eq!(significant(1234.6), "1235");
//! ```

use crate::measure::cpu::{CpuUse, ThreadTimes};
use crate::measure::table::significant;
use serde::Serialize;
use std::time::{Duration, Instant};

/// The minimum, median and maximum of a measurement's timed runs.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Spread {
    /// Timed runs.
    pub runs: usize,
    /// Fastest run, in milliseconds.
    pub min_ms: f64,
    /// Median run, in milliseconds.
    pub median_ms: f64,
    /// Slowest run, in milliseconds.
    pub max_ms: f64,
}

impl Spread {
    /// The spread of `values` (in milliseconds; at least one).
    pub fn of_ms(values: &[f64]) -> Spread {
        let mut sorted = values.to_vec();
        sorted.sort_by(f64::total_cmp);
        let n = sorted.len();
        let median = match n {
            0 => 0.0,
            _ if n % 2 == 1 => sorted[n / 2],
            _ => (sorted[n / 2 - 1] + sorted[n / 2]) / 2.0,
        };
        Spread {
            runs: n,
            min_ms: sorted.first().copied().unwrap_or(0.0),
            median_ms: median,
            max_ms: sorted.last().copied().unwrap_or(0.0),
        }
    }

    /// The spread of `times`.
    pub fn of(times: &[Duration]) -> Spread {
        let ms: Vec<f64> = times.iter().map(|t| t.as_secs_f64() * 1e3).collect();
        Spread::of_ms(&ms)
    }

    /// `median [min-max]`, three significant digits each, e.g.
    /// `1.23 [1.20-1.31]`.
    pub fn summary(&self) -> String {
        format!(
            "{} [{}-{}]",
            significant(self.median_ms),
            significant(self.min_ms),
            significant(self.max_ms)
        )
    }
}

/// A measurement: the spread of its wall times and, where the system
/// tells, the CPU time its threads got per run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Timing {
    /// Wall time of the timed runs.
    pub spread: Spread,
    /// CPU time per run (`None` where the system does not tell).
    pub cpu: Option<CpuUse>,
}

/// Runs `run` once to warm up, then `samples` (at least one) timed runs;
/// returns their timing and the warm-up run's result.
pub fn time_runs<T>(samples: usize, mut run: impl FnMut() -> T) -> (Timing, T) {
    let first = run();
    let samples = samples.max(1);
    let before = ThreadTimes::now();
    let times: Vec<Duration> = (0..samples)
        .map(|_| {
            let start = Instant::now();
            std::hint::black_box(run());
            start.elapsed()
        })
        .collect();
    let cpu = before
        .zip(ThreadTimes::now())
        .map(|(a, b)| a.until(&b, samples));
    let timing = Timing {
        spread: Spread::of(&times),
        cpu,
    };
    (timing, first)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_spread_is_the_minimum_median_and_maximum() {
        let s = Spread::of_ms(&[3.0, 1.0, 2.0, 10.0]);
        assert_eq!(
            (s.runs, s.min_ms, s.median_ms, s.max_ms),
            (4, 1.0, 2.5, 10.0)
        );
        assert_eq!(s.summary(), "2.50 [1.00-10.0]");
        let s = Spread::of_ms(&[7.0]);
        assert_eq!((s.min_ms, s.median_ms, s.max_ms), (7.0, 7.0, 7.0));
        assert_eq!(significant(0.0), "0");
        assert_eq!(significant(99.96), "100");
        assert_eq!(significant(0.09996), "0.100");
        assert_eq!(significant(0.5), "0.500");
    }
}
