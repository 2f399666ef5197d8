//! Wider vectors when the CPU has them, decided at run time.
//!
//! The build targets baseline x86-64, whose vectors (SSE2) hold four
//! `f32`, in the legacy two-operand encoding. Most CPUs of the last decade
//! also have AVX2: eight `f32` per vector, three-operand instructions. The
//! hot loops (the stage's span loop, the vertex shading loop, triangle
//! assembly and set-up) are written once, as plain Rust; [`run`] compiles
//! such a loop (a [`Kernel`]) a second time for AVX2 and picks that copy
//! when the CPU reports AVX2.
//!
//! Both copies are the same Rust code, and Rust never fuses a multiply and
//! an add on its own, so they compute the very same bits: only how the
//! work is laid out on the vectors differs. Tests run both copies and
//! compare the results bit for bit (`on_baseline` forces the baseline
//! copy).
//!
//! This module is the crate's only unsafe code: calling a function compiled
//! for AVX2 is unsafe because running it on a CPU without AVX2 would fault.
//! [`run`] calls it only after the CPU said it has AVX2.
#![allow(unsafe_code)]

/// Whether this CPU runs AVX2 code (checked once, then cached by `std`).
#[inline(always)]
pub(crate) fn has_avx2() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx2")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// A loop to compile twice. Its [`run`](Kernel::run) must be
/// `#[inline(always)]`, as must everything it calls, so that all of it is
/// compiled into each copy.
pub(crate) trait Kernel {
    /// What the loop gives back.
    type Output;
    /// The loop.
    fn run(self) -> Self::Output;
}

/// Runs `kernel`: the copy compiled for AVX2 on a CPU with AVX2, the one
/// compiled as the rest of the crate otherwise.
#[inline(always)]
pub(crate) fn run<K: Kernel>(kernel: K) -> K::Output {
    #[cfg(target_arch = "x86_64")]
    if has_avx2() && !baseline_only() {
        // SAFETY: the CPU has AVX2, checked just above; `avx2` only adds
        // that feature to the code `kernel` compiles to.
        return unsafe { avx2(kernel) };
    }
    kernel.run()
}

/// `kernel.run()`, compiled with AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn avx2<K: Kernel>(kernel: K) -> K::Output {
    kernel.run()
}

/// Whether the tests asked for the baseline copies only.
#[cfg(not(test))]
#[inline(always)]
fn baseline_only() -> bool {
    false
}

#[cfg(test)]
static BASELINE_ONLY: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Whether the tests asked for the baseline copies only.
#[cfg(test)]
fn baseline_only() -> bool {
    BASELINE_ONLY.load(std::sync::atomic::Ordering::Relaxed)
}

/// Runs `f` with every kernel on its baseline copy, on every thread, then
/// restores the choice (tests running meanwhile are slowed, never changed:
/// both copies give the same bits).
#[cfg(test)]
pub(crate) fn on_baseline<R>(f: impl FnOnce() -> R) -> R {
    static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());
    let _guard = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    BASELINE_ONLY.store(true, std::sync::atomic::Ordering::Relaxed);
    let result = f();
    BASELINE_ONLY.store(false, std::sync::atomic::Ordering::Relaxed);
    result
}
