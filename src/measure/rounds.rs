//! Interleaved rounds: rasterlab and its peers timed turn by turn, so a
//! change in the machine's load falls on all of them alike, and the ratio
//! table read off those rounds.
//!
//! On a shared machine, timing one program for a while and then another
//! moves their ratio by as much as the load moves in between
//! (docs/benchmarks.md says by how much). In each round every contender
//! runs once, the order turning by one each round; a contender's figure
//! is the median of its rounds, and a ratio is the median of the
//! per-round ratios (each taken within one round), with their minimum and
//! maximum beside it.
//!
//! Interleaved, each run finds the caches as the other contenders left
//! them: **cold**. An application redraws its own frame after frame, its
//! buffers still in the caches: **warm**. A workload asked to
//! ([`Workload::also_warm`]) times that too, after the rounds: each
//! contender once unmeasured, then `rounds` runs back to back; the warm
//! ratio is the peer's warm median over the best's.
//!
//! ```
//! use rasterlab::measure::{Contender, Side, Workload};
//! let mut work = Workload::new("sum");
//! work.add(Contender::new("fast", Side::Rasterlab, 1, || (1..=10u64).sum::<u64>()));
//! work.add(Contender::new("slow", Side::Peer, 1, || (1..=1000u64).sum::<u64>()));
//! let result = work.run(5);
//! assert_eq!(result.figures.len(), 2);
//! assert!(result.ratio_table().to_string().contains("slow"));
//! ```

use crate::measure::cpu::{CpuUse, ThreadTimes};
use crate::measure::data::Skipped;
use crate::measure::table::significant;
use crate::measure::table::Table;
use crate::measure::timing::{time_runs, Spread};
use serde::Serialize;
use std::time::Instant;

/// Whose code a contender runs.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Side {
    /// One of rasterlab's back-ends.
    Rasterlab,
    /// A published rasterizer doing the same work.
    Peer,
}

/// One contender of a workload: a name and the work, run once per round.
pub struct Contender<'a> {
    name: String,
    side: Side,
    threads: usize,
    run: Box<dyn FnMut() + 'a>,
}

impl<'a> Contender<'a> {
    /// `run` as `name`, on `threads` threads.
    pub fn new<T>(name: &str, side: Side, threads: usize, mut run: impl FnMut() -> T + 'a) -> Self {
        Contender {
            name: name.to_string(),
            side,
            threads,
            run: Box::new(move || {
                std::hint::black_box(run());
            }),
        }
    }
}

/// A workload's contenders, and the ones that could not run.
pub struct Workload<'a> {
    name: String,
    contenders: Vec<Contender<'a>>,
    skipped: Vec<(String, Skipped)>,
    warm: bool,
}

/// One contender's figure.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Figure {
    /// Contender name.
    pub name: String,
    /// Rasterlab or a peer.
    pub side: Side,
    /// Threads it draws on.
    pub threads: usize,
    /// Wall time over the rounds.
    pub spread: Spread,
    /// CPU time per run (`None` where the system does not tell).
    pub cpu: Option<CpuUse>,
    /// Wall time of each round, in milliseconds, in round order.
    pub rounds_ms: Vec<f64>,
    /// Wall time run after run, back to back (`None` unless the workload
    /// was asked to time it, [`Workload::also_warm`]).
    pub warm: Option<Spread>,
}

/// A workload's figures, in the order the contenders were added.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WorkloadResult {
    /// Workload name.
    pub workload: String,
    /// Every contender that ran.
    pub figures: Vec<Figure>,
    /// Contenders that could not run, with the reason.
    pub skipped: Vec<(String, String)>,
}

impl<'a> Workload<'a> {
    /// A workload without contenders.
    pub fn new(name: &str) -> Self {
        Workload {
            name: name.to_string(),
            contenders: Vec::new(),
            skipped: Vec::new(),
            warm: false,
        }
    }

    /// After the interleaved rounds, also times each contender run after
    /// run, as an application redraws: one run unmeasured, then as many
    /// back to back as there are rounds ([`Figure::warm`]).
    pub fn also_warm(&mut self) {
        self.warm = true;
    }

    /// Adds a contender.
    pub fn add(&mut self, contender: Contender<'a>) {
        self.contenders.push(contender);
    }

    /// Records a contender that cannot run, with the reason.
    pub fn skip(&mut self, name: &str, why: Skipped) {
        self.skipped.push((name.to_string(), why));
    }

    /// One warm-up run of each contender, then `rounds` rounds (and the
    /// warm runs, if asked for).
    pub fn run(mut self, rounds: usize) -> WorkloadResult {
        let rounds = rounds.max(1);
        let n = self.contenders.len();
        for c in &mut self.contenders {
            (c.run)();
        }
        let mut times = vec![Vec::with_capacity(rounds); n];
        let mut cpu: Vec<Option<ThreadTimes>> = vec![Some(ThreadTimes::default()); n];
        for round in 0..rounds {
            for k in 0..n {
                let i = (k + round) % n;
                let before = ThreadTimes::now();
                let start = Instant::now();
                (self.contenders[i].run)();
                times[i].push(start.elapsed().as_secs_f64() * 1e3);
                cpu[i] = match (cpu[i].take(), before, ThreadTimes::now()) {
                    (Some(mut sum), Some(before), Some(after)) => {
                        sum.accumulate(&before, &after);
                        Some(sum)
                    }
                    _ => None,
                };
            }
        }
        let warm: Vec<Option<Spread>> = self
            .contenders
            .iter_mut()
            .map(|c| self.warm.then(|| time_runs(rounds, &mut c.run).0.spread))
            .collect();
        WorkloadResult {
            workload: self.name,
            figures: self
                .contenders
                .into_iter()
                .zip(times)
                .zip(cpu)
                .zip(warm)
                .map(|(((c, rounds_ms), cpu), warm)| Figure {
                    name: c.name,
                    side: c.side,
                    threads: c.threads,
                    spread: Spread::of_ms(&rounds_ms),
                    cpu: cpu.map(|sum| ThreadTimes::default().until(&sum, rounds)),
                    rounds_ms,
                    warm,
                })
                .collect(),
            skipped: self
                .skipped
                .into_iter()
                .map(|(name, why)| (name, why.to_string()))
                .collect(),
        }
    }

    /// The workload, all of it skipped for `why`.
    pub fn skipped(name: &str, why: &Skipped) -> WorkloadResult {
        WorkloadResult {
            workload: name.to_string(),
            figures: Vec::new(),
            skipped: vec![(String::new(), why.to_string())],
        }
    }
}

/// A peer against rasterlab's best on one workload.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Ratio {
    /// The peer.
    pub peer: String,
    /// rasterlab's fastest contender with the peer's thread count (or,
    /// when none has it, the fastest of all).
    pub best: String,
    /// The peer's time over the best's, round by round.
    pub ratio: Spread,
    /// The peer's CPU time per run (all its threads) over the best's:
    /// steadier than the wall times when the cores were busy (`None`
    /// where the system does not tell).
    pub cpu_ratio: Option<f64>,
    /// The peer's warm median over that of rasterlab's fastest warm
    /// contender on as many threads (`None` unless both were timed warm).
    pub warm_ratio: Option<WarmRatio>,
}

/// A peer's warm median over rasterlab's fastest warm one.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WarmRatio {
    /// The ratio; above 1, rasterlab is faster.
    pub ratio: f64,
    /// rasterlab's contender with the fastest warm median.
    pub best: String,
}

impl WorkloadResult {
    /// Each peer against rasterlab's best: the contender of rasterlab with
    /// the smallest median among those on the peer's thread count (all of
    /// rasterlab's when none is), the ratio taken round by round. Above 1,
    /// rasterlab is faster.
    pub fn ratios(&self) -> Vec<Ratio> {
        // rasterlab's figure with the smallest `time` on `threads` threads
        // (on any number when none ran on that many), and that time.
        let fastest = |threads: usize, time: fn(&Figure) -> Option<f64>| {
            let on = |t: Option<usize>| {
                self.figures
                    .iter()
                    .filter(|f| f.side == Side::Rasterlab && t.is_none_or(|t| f.threads == t))
                    .filter_map(|f| Some((f, time(f)?)))
                    .min_by(|a, b| a.1.total_cmp(&b.1))
            };
            on(Some(threads)).or_else(|| on(None))
        };
        let cold: fn(&Figure) -> Option<f64> = |f| Some(f.spread.median_ms);
        let warm: fn(&Figure) -> Option<f64> = |f| f.warm.as_ref().map(|w| w.median_ms);
        self.figures
            .iter()
            .filter(|f| f.side == Side::Peer)
            .filter_map(|peer| {
                let (best, _) = fastest(peer.threads, cold)?;
                let per_round: Vec<f64> = peer
                    .rounds_ms
                    .iter()
                    .zip(&best.rounds_ms)
                    .map(|(p, b)| p / b.max(1e-9))
                    .collect();
                let cpu = |f: &Figure| f.cpu.as_ref().map(CpuUse::total_ms);
                Some(Ratio {
                    peer: peer.name.clone(),
                    best: best.name.clone(),
                    ratio: Spread::of_ms(&per_round),
                    cpu_ratio: cpu(peer).zip(cpu(best)).map(|(p, b)| p / b.max(1e-9)),
                    warm_ratio: warm(peer).zip(fastest(peer.threads, warm)).map(
                        |(p, (fastest_warm, b))| WarmRatio {
                            ratio: p / b.max(1e-9),
                            best: fastest_warm.name.clone(),
                        },
                    ),
                })
            })
            .collect()
    }

    /// Every figure: median [min-max] wall time, CPU per working thread
    /// and time spent waiting for a core, and the warm median [min-max]
    /// where it was timed; then the skipped contenders.
    pub fn figure_table(&self) -> Table {
        let warm = self.figures.iter().any(|f| f.warm.is_some());
        let mut header = vec![
            self.workload.as_str(),
            "threads",
            "ms median [min-max]",
            "cpu ms per thread, waited",
        ];
        if warm {
            header.push("warm ms median [min-max]");
        }
        let mut table = Table::new(&header);
        for f in &self.figures {
            let mut row = vec![
                f.name.clone(),
                f.threads.to_string(),
                f.spread.summary(),
                f.cpu
                    .as_ref()
                    .map_or_else(|| "unknown".to_string(), CpuUse::summary),
            ];
            if warm {
                row.push(f.warm.as_ref().map_or_else(String::new, Spread::summary));
            }
            table.row(row);
        }
        for (name, why) in &self.skipped {
            table.row(vec![name.clone(), why.clone()]);
        }
        table
    }

    /// The ratio rows of this workload (see [`ratios`](Self::ratios)),
    /// or its skipped rows.
    pub fn ratio_table(&self) -> Table {
        let mut table = ratio_header();
        self.ratio_rows(&mut table);
        table
    }

    /// Adds this workload's ratio rows to `table` (made by
    /// [`ratio_header`]).
    pub fn ratio_rows(&self, table: &mut Table) {
        let figure = |name: &str| self.figures.iter().find(|f| f.name == name);
        for r in self.ratios() {
            let (Some(peer), Some(best)) = (figure(&r.peer), figure(&r.best)) else {
                continue;
            };
            table.row(vec![
                self.workload.clone(),
                r.peer.clone(),
                peer.spread.summary(),
                r.best.clone(),
                best.spread.summary(),
                format!(
                    "{}x [{}-{}]",
                    significant(r.ratio.median_ms),
                    significant(r.ratio.min_ms),
                    significant(r.ratio.max_ms)
                ),
                r.cpu_ratio
                    .map_or_else(|| "unknown".to_string(), |c| format!("{}x", significant(c))),
                r.warm_ratio.as_ref().map_or_else(String::new, |w| {
                    format!("{}x ({})", significant(w.ratio), w.best)
                }),
            ]);
        }
        for (name, why) in &self.skipped {
            let what = if name.is_empty() {
                String::new()
            } else {
                format!("{name}: ")
            };
            table.row(vec![self.workload.clone(), format!("{what}{why}")]);
        }
    }
}

/// The header of a ratio table: workload, peer and its time, rasterlab's
/// best and its time, the ratio of the two (median of the per-round
/// ratios, [min-max]), the ratio of their CPU times, and the ratio of
/// their warm medians where they were timed warm.
pub fn ratio_header() -> Table {
    Table::with_text_columns(
        2,
        &[
            "workload",
            "peer",
            "peer ms",
            "rasterlab best",
            "best ms",
            "peer / best",
            "cpu peer / best",
            "warm peer / best",
        ],
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn rounds_interleave_and_ratios_compare_with_the_best_on_as_many_threads() {
        let order = std::cell::RefCell::new(Vec::new());
        let mut work = Workload::new("w");
        let sleeper = |name: &'static str, ms: u64| {
            let order = &order;
            move || {
                order.borrow_mut().push(name);
                std::thread::sleep(Duration::from_millis(ms));
            }
        };
        work.add(Contender::new("a", Side::Rasterlab, 1, sleeper("a", 4)));
        work.add(Contender::new("a2", Side::Rasterlab, 2, sleeper("a2", 2)));
        work.add(Contender::new("b", Side::Rasterlab, 1, sleeper("b", 20)));
        work.add(Contender::new("peer", Side::Peer, 1, sleeper("peer", 8)));
        work.skip(
            "gl",
            Skipped {
                reason: "no GL".into(),
            },
        );
        let result = work.run(3);
        // A warm-up of each, then three rounds, each turned by one.
        let order = order.into_inner();
        assert_eq!(&order[4..8], ["a", "a2", "b", "peer"]);
        assert_eq!(&order[8..12], ["a2", "b", "peer", "a"]);
        assert_eq!(&order[12..16], ["b", "peer", "a", "a2"]);
        assert!(result.figures.iter().all(|f| f.rounds_ms.len() == 3));
        let ratios = result.ratios();
        assert_eq!(ratios.len(), 1);
        // The best on one thread is `a`, not the faster two-thread `a2`.
        assert_eq!(ratios[0].best, "a");
        assert!(ratios[0].ratio.median_ms > 1.0);
        // Sleeping takes no CPU time: the CPU ratio is whatever it is, but
        // it is there wherever the system tells.
        assert_eq!(
            ratios[0].cpu_ratio.is_some(),
            result.figures[0].cpu.is_some()
        );
        let text = result.ratio_table().to_string();
        assert!(text.contains("w         peer"), "{text}");
        assert!(
            text.lines().last().unwrap().ends_with("gl: skipped: no GL"),
            "{text}"
        );
        let figures = result.figure_table().to_string();
        assert_eq!(figures.lines().count(), 6, "{figures}");
    }

    /// Warm runs come after the rounds, each contender's back to back
    /// after one unmeasured run, and give a warm ratio; without
    /// `also_warm` there are none, and no warm column.
    #[test]
    fn warm_runs_come_back_to_back_after_the_rounds() {
        type Order = std::cell::RefCell<Vec<&'static str>>;
        fn contenders<'a>(work: &mut Workload<'a>, order: &'a Order) {
            for (name, side, ms) in [("a", Side::Rasterlab, 2), ("peer", Side::Peer, 6)] {
                work.add(Contender::new(name, side, 1, move || {
                    order.borrow_mut().push(name);
                    std::thread::sleep(Duration::from_millis(ms));
                }));
            }
        }
        let order = Order::default();
        let mut work = Workload::new("w");
        contenders(&mut work, &order);
        work.also_warm();
        let result = work.run(3);
        let ran = order.take();
        // Warm-up, three rounds of two, then 1 + 3 of each back to back.
        assert_eq!(ran.len(), 2 + 6 + 8);
        assert_eq!(
            &ran[8..],
            ["a", "a", "a", "a", "peer", "peer", "peer", "peer"]
        );
        let warm = result.figures[1].warm.as_ref().expect("timed warm");
        assert!(warm.median_ms >= 6.0, "{warm:?}");
        let ratio = result.ratios()[0].warm_ratio.clone().expect("a warm ratio");
        assert!(ratio.ratio > 1.0, "{ratio:?}");
        assert_eq!(ratio.best, "a");
        assert!(result.figure_table().to_string().contains("warm ms"));

        let mut cold = Workload::new("w");
        contenders(&mut cold, &order);
        let result = cold.run(1);
        assert!(result.figures.iter().all(|f| f.warm.is_none()));
        assert_eq!(result.ratios()[0].warm_ratio, None);
        assert!(!result.figure_table().to_string().contains("warm ms"));
    }
}
