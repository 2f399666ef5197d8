//! Whether the cores were free: the CPU time each of the process's
//! threads got, and the time they were ready to run but waited for a
//! core, beside a measurement's wall time.
//!
//! A figure measured on a shared machine says little on its own: two
//! threads on a CPU for all of their wall time had their cores; the same
//! wall time with half of it on a CPU and the other half waiting did
//! not. On Linux the kernel keeps both times per thread
//! (`/proc/self/task/*/schedstat`: time on a CPU, time waiting on a run
//! queue, in nanoseconds); elsewhere [`ThreadTimes::now`] is `None` and the
//! figures are printed as unknown.

use serde::Serialize;
use std::time::Duration;

/// The run and wait times of every thread of the process at one moment.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ThreadTimes {
    /// `(thread id, nanoseconds on a CPU, nanoseconds waiting for one)`.
    threads: Vec<(u32, u64, u64)>,
}

impl ThreadTimes {
    /// The times now, or `None` where the kernel does not give them.
    ///
    /// The kernel adds a running thread's time when it leaves the CPU or
    /// at a clock tick, so the calling thread first sleeps for a
    /// millisecond: its own time is then up to date, and so is that of
    /// worker threads that have just gone idle.
    pub fn now() -> Option<ThreadTimes> {
        std::thread::sleep(Duration::from_millis(1));
        let mut threads = Vec::new();
        for entry in std::fs::read_dir("/proc/self/task").ok()? {
            let entry = entry.ok()?;
            let Some(id) = entry.file_name().to_str().and_then(|s| s.parse().ok()) else {
                continue;
            };
            // A thread may end between the listing and the read.
            let Ok(text) = std::fs::read_to_string(entry.path().join("schedstat")) else {
                continue;
            };
            let mut fields = text.split_whitespace().map(str::parse::<u64>);
            if let (Some(Ok(run)), Some(Ok(wait))) = (fields.next(), fields.next()) {
                threads.push((id, run, wait));
            }
        }
        (!threads.is_empty()).then_some(ThreadTimes { threads })
    }

    /// Adds the times each thread got between `before` and `after` (a
    /// thread is known by its id), to sum the CPU use of runs apart.
    pub fn accumulate(&mut self, before: &ThreadTimes, after: &ThreadTimes) {
        for &(id, run, wait) in &after.threads {
            let (run0, wait0) = before
                .threads
                .iter()
                .find(|t| t.0 == id)
                .map_or((0, 0), |t| (t.1, t.2));
            let (run, wait) = (run.saturating_sub(run0), wait.saturating_sub(wait0));
            match self.threads.iter_mut().find(|t| t.0 == id) {
                Some(t) => (t.1, t.2) = (t.1 + run, t.2 + wait),
                None => self.threads.push((id, run, wait)),
            }
        }
    }

    /// The CPU use between `self` and `later`, divided by `runs`.
    pub fn until(&self, later: &ThreadTimes, runs: usize) -> CpuUse {
        let runs = runs.max(1) as f64;
        let mut per_thread_ms = Vec::new();
        let mut waiting_ns = 0u64;
        for &(id, run, wait) in &later.threads {
            let (run0, wait0) = self
                .threads
                .iter()
                .find(|t| t.0 == id)
                .map_or((0, 0), |t| (t.1, t.2));
            let ran = run.saturating_sub(run0);
            waiting_ns += wait.saturating_sub(wait0);
            // Threads that got less than 1% of a millisecond per run did
            // no part of the work (idle pool threads, the progress bar).
            if ran as f64 / runs > 10_000.0 {
                per_thread_ms.push(ran as f64 / runs / 1e6);
            }
        }
        per_thread_ms.sort_by(|a, b| b.total_cmp(a));
        CpuUse {
            per_thread_ms,
            waiting_ms: waiting_ns as f64 / runs / 1e6,
        }
    }
}

/// CPU time per run of a measurement, beside its wall time.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct CpuUse {
    /// CPU time per run of each thread that worked, busiest first, in
    /// milliseconds.
    pub per_thread_ms: Vec<f64>,
    /// Time per run the process's threads were ready to run but waited for
    /// a core (taken by another process), summed over threads, in
    /// milliseconds.
    pub waiting_ms: f64,
}

impl CpuUse {
    /// The CPU time of all threads, per run, in milliseconds.
    pub fn total_ms(&self) -> f64 {
        self.per_thread_ms.iter().sum()
    }

    /// Short text: the CPU milliseconds of each working thread and the
    /// milliseconds spent waiting for a core, e.g. `cpu 12.1+11.8 wait 0.3`.
    pub fn summary(&self) -> String {
        let threads: Vec<String> = self
            .per_thread_ms
            .iter()
            .map(|ms| crate::measure::table::significant(*ms))
            .collect();
        format!(
            "cpu {} wait {}",
            if threads.is_empty() {
                "0".to_string()
            } else {
                threads.join("+")
            },
            crate::measure::table::significant(self.waiting_ms)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn busy_threads_show_their_cpu_time() {
        let Some(before) = ThreadTimes::now() else {
            eprintln!("skipped: no per-thread times on this system");
            return;
        };
        let spin = |ms: u64| {
            let start = std::time::Instant::now();
            let mut x = 0u64;
            while start.elapsed() < Duration::from_millis(ms) {
                x = std::hint::black_box(x.wrapping_add(1));
            }
        };
        // The worker stays alive until its times are read: an ended
        // thread leaves the list.
        let (done, wait_for_done) = std::sync::mpsc::channel::<()>();
        let worker = std::thread::spawn(move || {
            spin(60);
            wait_for_done.recv().ok();
        });
        spin(30);
        std::thread::sleep(Duration::from_millis(40));
        let after = ThreadTimes::now().unwrap();
        done.send(()).unwrap();
        worker.join().unwrap();
        let used = before.until(&after, 2);
        // Two threads spun, one twice as long as the other: on a CPU or
        // waiting for one, their mean per "run" is above the bound (other
        // tests of this process add their own).
        assert!(used.total_ms() + used.waiting_ms >= 40.0, "{used:?}");
        assert!(used.per_thread_ms.len() >= 2, "{used:?}");
        assert!(used.summary().starts_with("cpu "));
    }
}
