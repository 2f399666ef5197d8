//! Wider vectors when the CPU has them, decided at run time.
//!
//! The build targets baseline x86-64, whose vectors (SSE2) hold four
//! `f32`. Most CPUs of the last decade also have AVX2, with eight. The
//! stage's span loops are written once, as plain loops the compiler turns
//! into vector code; [`run`] compiles such a loop a second time for AVX2
//! and picks that copy when the CPU reports AVX2.
//!
//! Both copies are the same Rust code, and Rust never fuses a multiply and
//! an add on its own, so they compute the very same bits: only how many
//! pixels go through at once differs. A test runs both on random spans and
//! compares the buffers bit for bit.
//!
//! This module is the crate's only unsafe code: calling a function compiled
//! for AVX2 is unsafe because running it on a CPU without AVX2 would fault.
//! [`run`] calls it only after the CPU said it has AVX2.
#![allow(unsafe_code)]

/// Which copy of a loop to run.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum Lanes {
    /// The widest vectors this CPU has (AVX2 when present).
    Widest,
    /// The baseline build's vectors (SSE2 on x86-64), whatever the CPU:
    /// what the tests compare the widest copy with.
    #[cfg(test)]
    Baseline,
}

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

/// Runs `kernel` compiled for `lanes`: with [`Lanes::Widest`] on a CPU
/// with AVX2, the copy compiled for AVX2; otherwise the one compiled as
/// the rest of the crate.
#[inline(always)]
pub(crate) fn run<K: Kernel>(lanes: Lanes, kernel: K) -> K::Output {
    #[cfg(target_arch = "x86_64")]
    if lanes == Lanes::Widest && has_avx2() {
        // SAFETY: the CPU has AVX2, checked just above; `avx2` only adds
        // that feature to the code `kernel` compiles to.
        return unsafe { avx2(kernel) };
    }
    let _ = lanes;
    kernel.run()
}

/// `kernel.run()`, compiled with AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn avx2<K: Kernel>(kernel: K) -> K::Output {
    kernel.run()
}
