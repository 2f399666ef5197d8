//! Wider vectors when the CPU has them, decided at run time.
//!
//! The build targets baseline x86-64, whose vectors (SSE2) hold four
//! `f32`, in the legacy two-operand encoding. Most CPUs of the last decade
//! also have AVX2 (eight `f32` per vector, three-operand instructions).
//! The hot loops use them in two ways:
//!
//! * **Compiled twice.** The stage's span loop, the vertex shading loop
//!   and the triangle assembly loop are plain Rust; [`run`] has such a
//!   loop (a [`Kernel`]) compiled once per [`Width`] and runs the widest
//!   copy the CPU reports it can run. Every copy is the same Rust code,
//!   and Rust never fuses a multiply and an add on its own, so they
//!   compute the very same bits: only how the work is laid out on the
//!   vectors differs. Tests run every copy the CPU has and compare the
//!   results bit for bit (`limited_to` caps the copy). AVX-512 (sixteen
//!   `f32`) measured no faster on the fills as a third copy, so there is
//!   none.
//! * **Written lane by lane.** Two steps that the compiler does not turn
//!   into vector code on its own are written with AVX2 intrinsics, one
//!   vertex or triangle per lane: [`transform`], the vertex shader,
//!   divide and snap of eight mesh vertices (read as rows of floats and
//!   transposed into lanes in registers), and [`triangles`], the area,
//!   culling, bounds and small-triangle tests of eight triangles. The
//!   vertex loop and the assembly loop call them, and do the lanes they
//!   leave (and everything, on a CPU without AVX2) one at a time.
//!
//! It also has [`prefetch`], the hint that brings a cache line in ahead of
//! its use ([`prefetch_all`] for every line of a larger value);
//! [`truncate_to_bytes`], a colour's conversion to bytes; and
//! [`ratios_to_f32`] and [`divide_each`], a fragment's divisions two and
//! four lanes at a time.
//!
//! This module is the crate's only unsafe code. Calling a function
//! compiled for AVX2 is unsafe because running it on a CPU without AVX2
//! would fault: [`run`], [`transform::shade`] and [`triangles::classify`]
//! each call their AVX2 code only after the CPU said it has the feature.
//! The intrinsics of [`truncate_to_bytes`], [`ratios_to_f32`] and
//! [`divide_each`] need only SSE2, which every x86-64 CPU has; the last
//! two load and store through pointers to local arrays of four lanes. The
//! prefetch intrinsic is unsafe as every `std::arch` call taking a pointer
//! is, though it reads nothing and cannot fault: [`prefetch`] takes a
//! reference, and [`prefetch_all`] the lines that reference's value spans.
#![allow(unsafe_code)]

pub(crate) mod transform;
pub(crate) mod triangles;

/// The vector widths a loop is compiled for, narrowest first.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Width {
    /// As the rest of the crate: SSE2 on x86-64.
    Baseline,
    /// AVX2: eight `f32` per vector.
    Avx2,
}

/// The widest copy this CPU runs (checked once, then cached by `std`).
#[inline(always)]
pub(crate) fn widest() -> Width {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx2") {
            return Width::Avx2;
        }
    }
    Width::Baseline
}

/// A loop to compile once per [`Width`]. Its [`run`](Kernel::run) must be
/// `#[inline(always)]`, as must everything it calls, so that all of it is
/// compiled into each copy.
pub(crate) trait Kernel {
    /// What the loop gives back.
    type Output;
    /// The loop.
    fn run(self) -> Self::Output;
}

/// Runs `kernel`: the widest copy this CPU runs.
#[inline(always)]
pub(crate) fn run<K: Kernel>(kernel: K) -> K::Output {
    let copy = widest().min(allowed());
    // SAFETY: `copy` is at most the widest copy the CPU runs, checked by
    // `widest`; `avx2` only adds that feature to the code `kernel`
    // compiles to.
    #[cfg(target_arch = "x86_64")]
    if copy == Width::Avx2 {
        return unsafe { avx2(kernel) };
    }
    let _ = copy;
    kernel.run()
}

/// `kernel.run()`, compiled with AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn avx2<K: Kernel>(kernel: K) -> K::Output {
    kernel.run()
}

/// Asks the CPU to bring the cache line holding `value` into the cache,
/// so that a load of it soon after does not wait for memory. Only a hint:
/// it reads nothing and changes nothing the program can see.
#[inline(always)]
pub(crate) fn prefetch<T>(value: &T) {
    prefetch_line((value as *const T).cast());
}

/// [`prefetch`] of every cache line `value` spans, for a value larger
/// than one line (64 bytes) or not aligned to one.
#[inline(always)]
pub(crate) fn prefetch_all<T>(value: &T) {
    let start = (value as *const T).cast::<u8>();
    let lines = (start as usize % 64 + std::mem::size_of::<T>()).div_ceil(64);
    for line in 0..lines {
        // `value`'s first byte plus whole lines: an address in one of the
        // lines `value` spans (the last may be past its end, not past its
        // line), computed with `wrapping_add`, which claims nothing of it.
        prefetch_line(start.wrapping_add(line * 64));
    }
}

/// The prefetch hint for the cache line holding `address`, whatever the
/// address: a prefetch reads nothing and cannot fault.
#[inline(always)]
fn prefetch_line(address: *const u8) {
    // SAFETY: SSE, which `_mm_prefetch` needs, is part of baseline x86-64;
    // a prefetch does not access memory as far as the program can tell,
    // and does not fault on any address.
    #[cfg(target_arch = "x86_64")]
    unsafe {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        _mm_prefetch::<_MM_HINT_T0>(address.cast::<i8>());
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = address;
}

/// The four lanes of `v`, each in `[0, 256)`, truncated to bytes: on
/// x86-64 one SSE2 conversion and two packs. (`as i32` on each lane
/// compiles to a conversion and the checks that saturate it, for a value
/// out of range or NaN, lane by lane.) Out of that range the bytes are
/// unspecified.
#[inline(always)]
pub(crate) fn truncate_to_bytes(v: glam::Vec4) -> [u8; 4] {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: SSE2, which these intrinsics need, is part of baseline
    // x86-64; they take and return values, no pointer.
    unsafe {
        use std::arch::x86_64::{
            __m128, _mm_cvtsi128_si32, _mm_cvttps_epi32, _mm_packs_epi32, _mm_packus_epi16,
        };
        let truncated = _mm_cvttps_epi32(__m128::from(v));
        let words = _mm_packs_epi32(truncated, truncated);
        _mm_cvtsi128_si32(_mm_packus_epi16(words, words)).to_ne_bytes()
    }
    #[cfg(not(target_arch = "x86_64"))]
    v.as_ivec4().to_array().map(|v| v as u8)
}

/// `(n as f64 / d) as f32` for each numerator, two at a time: on x86-64
/// SSE2 divides and converts two lanes per instruction, so three
/// barycentrics take two divisions instead of three. Each lane's
/// conversion, division and rounding to `f32` are those of the scalar
/// expression, so the bits are the same.
#[inline(always)]
pub(crate) fn ratios_to_f32<const N: usize>(n: [i64; N], d: f64) -> [f32; N] {
    const { assert!(N <= 4, "four lanes at most") };
    #[cfg(target_arch = "x86_64")]
    // SAFETY: SSE2, which these intrinsics need, is part of baseline
    // x86-64; the store writes the four lanes to a local array of four.
    unsafe {
        use std::arch::x86_64::{
            _mm_cvtpd_ps, _mm_div_pd, _mm_movelh_ps, _mm_set1_pd, _mm_set_pd, _mm_storeu_ps,
        };
        let lane = |i: usize| n.get(i).map_or(0.0, |&v| v as f64);
        let d = _mm_set1_pd(d);
        let low = _mm_cvtpd_ps(_mm_div_pd(_mm_set_pd(lane(1), lane(0)), d));
        let high = if N > 2 {
            _mm_cvtpd_ps(_mm_div_pd(_mm_set_pd(lane(3), lane(2)), d))
        } else {
            low
        };
        let mut lanes = [0.0f32; 4];
        _mm_storeu_ps(lanes.as_mut_ptr(), _mm_movelh_ps(low, high));
        std::array::from_fn(|i| lanes[i])
    }
    #[cfg(not(target_arch = "x86_64"))]
    n.map(|v| (v as f64 / d) as f32)
}

/// `v / d` for each lane of `v`, in one SSE2 division on x86-64 (the same
/// bits as dividing each: a vector division rounds each lane as a scalar
/// one does).
#[inline(always)]
pub(crate) fn divide_each<const N: usize>(v: [f32; N], d: f32) -> [f32; N] {
    const { assert!(N <= 4, "four lanes at most") };
    #[cfg(target_arch = "x86_64")]
    // SAFETY: SSE2, which these intrinsics need, is part of baseline
    // x86-64; the load and store read and write local arrays of four.
    unsafe {
        use std::arch::x86_64::{_mm_div_ps, _mm_loadu_ps, _mm_set1_ps, _mm_storeu_ps};
        let mut lanes = [1.0f32; 4];
        lanes[..N].copy_from_slice(&v);
        let quotient = _mm_div_ps(_mm_loadu_ps(lanes.as_ptr()), _mm_set1_ps(d));
        _mm_storeu_ps(lanes.as_mut_ptr(), quotient);
        std::array::from_fn(|i| lanes[i])
    }
    #[cfg(not(target_arch = "x86_64"))]
    v.map(|x| x / d)
}

/// The widest copy the tests allow.
#[cfg(not(test))]
#[inline(always)]
fn allowed() -> Width {
    Width::Avx2
}

#[cfg(test)]
static ALLOWED: std::sync::atomic::AtomicU8 = std::sync::atomic::AtomicU8::new(Width::Avx2 as u8);

/// The widest copy the tests allow.
#[cfg(test)]
fn allowed() -> Width {
    match ALLOWED.load(std::sync::atomic::Ordering::Relaxed) {
        0 => Width::Baseline,
        _ => Width::Avx2,
    }
}

/// The copies this CPU runs, narrowest first.
#[cfg(test)]
pub(crate) fn copies() -> Vec<Width> {
    [Width::Baseline, Width::Avx2]
        .into_iter()
        .filter(|&c| c <= widest())
        .collect()
}

/// Runs `f` with every kernel on `copy` at most, on every thread, then
/// lifts the limit (tests running meanwhile are slowed, never changed:
/// every copy gives the same bits).
#[cfg(test)]
pub(crate) fn limited_to<R>(copy: Width, f: impl FnOnce() -> R) -> R {
    static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());
    let _guard = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    ALLOWED.store(copy as u8, std::sync::atomic::Ordering::Relaxed);
    let result = f();
    ALLOWED.store(Width::Avx2 as u8, std::sync::atomic::Ordering::Relaxed);
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The lane-wise divisions give, lane for lane, the bits of the scalar
    /// expressions they stand for, for one to four lanes, over numerators
    /// and divisors of every size (ties, zeros and negative values
    /// included).
    #[test]
    fn the_divisions_in_lanes_give_the_scalar_bits() {
        let mut rng = fastrand::Rng::with_seed(3921);
        for _ in 0..50_000 {
            let bits = rng.u32(0..63);
            let mut int = || rng.i64(..) >> bits;
            let n = [int(), int(), int(), int()];
            let d = (rng.i64(1..i64::MAX) >> rng.u32(0..63)) as f64;
            let scalar = |n: i64| (n as f64 / d) as f32;
            let same = |a: &[f32], b: &[f32]| {
                assert_eq!(
                    a.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                    b.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                    "{n:?} / {d}"
                )
            };
            same(&ratios_to_f32([n[0]], d), &[scalar(n[0])]);
            same(
                &ratios_to_f32([n[0], n[1]], d),
                &n[..2].iter().map(|&v| scalar(v)).collect::<Vec<_>>(),
            );
            same(
                &ratios_to_f32([n[0], n[1], n[2]], d),
                &n[..3].iter().map(|&v| scalar(v)).collect::<Vec<_>>(),
            );
            same(&ratios_to_f32(n, d), &n.map(scalar));

            let v =
                n.map(|n| f32::from_bits(n as u32 & 0x7f7f_ffff) * if n < 0 { -1.0 } else { 1.0 });
            let s = f32::from_bits(rng.u32(0x0080_0000..0x7f7f_ffff));
            same(&divide_each([v[0]], s), &[v[0] / s]);
            same(&divide_each([v[0], v[1]], s), &[v[0] / s, v[1] / s]);
            same(
                &divide_each([v[0], v[1], v[2]], s),
                &[v[0] / s, v[1] / s, v[2] / s],
            );
            same(&divide_each(v, s), &v.map(|x| x / s));
        }
    }
}
