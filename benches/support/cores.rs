//! Each worker thread of a many-thread contender on a core of its own.
//!
//! Left to the scheduler, two worker threads woken after an idle spell
//! can share one core while the other stays idle. On the 2-core virtual
//! machine the benchmarks were measured on, `perf sched map` showed both
//! of `tiled`'s workers taking turns on one CPU for about 12 ms after the
//! one-thread contender before them had run, the other CPU idle. That
//! machine's kernel is booted with `sched_vcpu_pack`, a setting of that
//! virtual machine's kernel (not of Linux in general) that packs threads
//! onto few virtual CPUs. The bundled dragon's two-thread frame then took
//! as long as its one-thread frame (13.4 against 13.3 ms), its threads
//! counting the difference as waiting for a core (9.7 ms a frame); run
//! alone, frame after frame, it took 7.5 ms.
//!
//! So worker `i` of rasterlab's pools and llvmpipe's rasterizer thread
//! `llvmpipe-i` are each bound to the `i`-th CPU the process may run on;
//! the thread that calls them (the benchmark's main thread, llvmpipe's
//! drawing thread) is left free. What that measures:
//!
//! * a best case: each worker has a CPU of its own from the frame's
//!   first instruction. An application that does not bind its threads
//!   (`render --threads 2` does not) gets it only once the scheduler has
//!   spread them, which `render`'s frames, drawn one after another, do
//!   (its figures are in docs/benchmarks.md);
//! * on a CPU with simultaneous multithreading, the `i`-th CPU may be a
//!   sibling hardware thread of the `(i - 1)`-th, not a core of its own.
//!   The machine the figures of docs/benchmarks.md come from has none.
//!
//! Linux only (`sched_setaffinity`); elsewhere nothing is bound. The
//! printed context says whether every binding succeeded
//! ([`pool_binding`], [`LlvmpipeThreads::bind_new`]).

#[cfg(target_os = "linux")]
use std::collections::HashSet;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Whether the workers could be given a core each.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Binding {
    /// Worker `i` runs only on the `i`-th CPU the process may use.
    OneCoreEach,
    /// Fewer CPUs than workers, or no way to bind here: the scheduler
    /// places them.
    Unbound,
}

impl Binding {
    /// For the benchmark's printed context.
    pub fn describe(self) -> &'static str {
        match self {
            Binding::OneCoreEach => "bound to a core each",
            Binding::Unbound => {
                "left to the scheduler (fewer cores than threads, a binding refused, or not Linux; see benches/support/cores.rs)"
            }
        }
    }
}

/// The CPUs this process may run on, in order.
#[cfg(target_os = "linux")]
fn allowed_cpus() -> Vec<usize> {
    // SAFETY: `cpu_set_t` is plain bits, for which all zeros is the empty
    // set; `sched_getaffinity` writes at most `size_of::<cpu_set_t>()`
    // bytes into it.
    unsafe {
        let mut set: libc::cpu_set_t = std::mem::zeroed();
        if libc::sched_getaffinity(0, std::mem::size_of::<libc::cpu_set_t>(), &mut set) != 0 {
            return Vec::new();
        }
        (0..libc::CPU_SETSIZE as usize)
            .filter(|&cpu| libc::CPU_ISSET(cpu, &set))
            .collect()
    }
}

/// Binds thread `tid` (0: the calling thread) to `cpu` alone.
#[cfg(target_os = "linux")]
fn bind(tid: libc::pid_t, cpu: usize) -> bool {
    // SAFETY: as in `allowed_cpus`; `sched_setaffinity` only reads the set.
    unsafe {
        let mut set: libc::cpu_set_t = std::mem::zeroed();
        libc::CPU_SET(cpu, &mut set);
        libc::sched_setaffinity(tid, std::mem::size_of::<libc::cpu_set_t>(), &set) == 0
    }
}

/// The CPUs to bind `workers` threads to, the `i`-th worker to the
/// `i`-th: when there are more than one, and at least as many CPUs.
#[cfg(target_os = "linux")]
fn cpus_for(workers: usize) -> Option<Vec<usize>> {
    let cpus = allowed_cpus();
    (workers > 1 && cpus.len() >= workers).then_some(cpus)
}

/// Whether [`pool`] binds the workers of a pool of `threads`.
fn binds(threads: usize) -> bool {
    #[cfg(target_os = "linux")]
    return cpus_for(threads).is_some();
    #[cfg(not(target_os = "linux"))]
    {
        let _ = threads;
        false
    }
}

/// Workers of [`pool`]s that could not be bound, so far.
static UNBOUND_WORKERS: AtomicUsize = AtomicUsize::new(0);

/// How the workers of the pools of `threads` made so far were placed: a
/// core each if [`pool`] bound them and every binding succeeded.
pub fn pool_binding(threads: usize) -> Binding {
    if binds(threads) && UNBOUND_WORKERS.load(Ordering::Relaxed) == 0 {
        Binding::OneCoreEach
    } else {
        Binding::Unbound
    }
}

/// A rayon pool of `threads` workers, each bound to a CPU of its own when
/// there are more than one and at least as many CPUs.
pub fn pool(threads: usize) -> rayon::ThreadPool {
    let builder = rayon::ThreadPoolBuilder::new().num_threads(threads);
    #[cfg(target_os = "linux")]
    if let Some(cpus) = cpus_for(threads) {
        return builder
            .start_handler(move |i| {
                if !bind(0, cpus[i]) {
                    UNBOUND_WORKERS.fetch_add(1, Ordering::Relaxed);
                }
            })
            .build()
            .expect("a rayon pool");
    }
    builder.build().expect("a rayon pool")
}

/// The ids of this process's threads whose name is `llvmpipe-N`, with N.
#[cfg(target_os = "linux")]
fn llvmpipe_threads() -> Vec<(libc::pid_t, usize)> {
    let Ok(tasks) = std::fs::read_dir("/proc/self/task") else {
        return Vec::new();
    };
    tasks
        .flatten()
        .filter_map(|task| {
            let tid = task.file_name().to_str()?.parse().ok()?;
            let name = std::fs::read_to_string(task.path().join("comm")).ok()?;
            let n = name.trim_end().strip_prefix("llvmpipe-")?.parse().ok()?;
            Some((tid, n))
        })
        .collect()
}

/// llvmpipe's rasterizer threads started so far, to tell the next
/// context's from them.
#[derive(Default)]
pub struct LlvmpipeThreads {
    #[cfg(target_os = "linux")]
    seen: HashSet<libc::pid_t>,
}

impl LlvmpipeThreads {
    /// Notes the rasterizer threads running now.
    pub fn now() -> LlvmpipeThreads {
        #[cfg(target_os = "linux")]
        return LlvmpipeThreads {
            seen: llvmpipe_threads().into_iter().map(|(tid, _)| tid).collect(),
        };
        #[cfg(not(target_os = "linux"))]
        LlvmpipeThreads::default()
    }

    /// Binds the rasterizer threads started since `self` was taken (one
    /// context's, `llvmpipe-0` to `llvmpipe-{workers - 1}`), `llvmpipe-i`
    /// to the `i`-th CPU, when there are `workers` of them and at least as
    /// many CPUs; a single worker is left unbound, as rasterlab's is.
    pub fn bind_new(&self, workers: usize) -> Binding {
        #[cfg(target_os = "linux")]
        if let Some(cpus) = cpus_for(workers) {
            let new: Vec<_> = llvmpipe_threads()
                .into_iter()
                .filter(|(tid, _)| !self.seen.contains(tid))
                .collect();
            if new.len() == workers {
                let bound = new
                    .iter()
                    .all(|&(tid, n)| n < workers && bind(tid, cpus[n]));
                if bound {
                    return Binding::OneCoreEach;
                }
            }
        }
        let _ = workers;
        Binding::Unbound
    }
}
