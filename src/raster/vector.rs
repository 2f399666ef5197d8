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
//!   leave (and everything, on a CPU without AVX2) one at a time. A third,
//!   [`weights`], gives the interpolation weights of eight pixels of a
//!   span: the compiler vectorised the span loop's plain Rust for them,
//!   but passed the values through memory. The loop's copy for AVX2
//!   calls it; the baseline copy keeps the plain Rust.
//!
//! It also has [`prefetch`], the hint that brings a cache line in ahead of
//! its use ([`prefetch_all`] for every line of a larger value);
//! [`advise_huge_pages`], the hint that asks Linux for 2 MiB pages under a
//! large buffer;
//! [`truncate_to_bytes`], a colour's conversion to bytes; and
//! [`ratios_to_f32`] and [`divide_each`], a fragment's divisions two and
//! four lanes at a time.
//!
//! This module is the crate's only unsafe code. Calling a function
//! compiled for AVX2 is unsafe because running it on a CPU without AVX2
//! would fault: [`run`], [`transform::shade`], [`triangles::classify`]
//! and [`weights::weights`] each call their AVX2 code only after the CPU
//! said it has the feature.
//! The intrinsics of [`truncate_to_bytes`], [`ratios_to_f32`] and
//! [`divide_each`] need only SSE2, which every x86-64 CPU has; the last
//! two load and store through pointers to local arrays of four lanes. The
//! prefetch intrinsic is unsafe as every `std::arch` call taking a pointer
//! is, though it reads nothing and cannot fault: [`prefetch`] takes a
//! reference, and [`prefetch_all`] the lines that reference's value spans.
//! `madvise` is a system call, unsafe as every foreign function is; the
//! advice it is given changes no byte of the range, which lies inside a
//! live allocation.
#![allow(unsafe_code)]

pub(crate) mod transform;
pub(crate) mod triangles;
pub(crate) mod weights;

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

/// The size of the large pages Linux backs a region with when asked
/// (transparent huge pages, 2 MiB on x86-64).
const HUGE_PAGE: usize = 2 << 20;

/// Asks the kernel to back the memory of `buffer`'s allocation (its
/// capacity, not only its length) with 2 MiB pages, wherever whole such
/// pages lie in it. Only a hint: it changes no byte, and the kernel may
/// ignore it (transparent huge pages off, or no 2 MiB page free).
///
/// The frame's large buffers (the target, the shaded vertices, the
/// set-ups) are read and written all over: a fragment's depth and colour,
/// a triangle's three corners. In 4 KiB pages their 100 MB are 25,000
/// pages, far more than the TLB holds, and each miss walks the page
/// tables; in 2 MiB pages they are 50. Linux's default (`madvise`) gives
/// the large pages only to memory that asks for them, and the system
/// allocator does not ask (mimalloc, the `rasterlab` program's allocator,
/// does). Memory not yet written then faults in in 2 MiB pages; memory
/// already written (an allocation the allocator reused) is collapsed into
/// them at once (`MADV_COLLAPSE`, Linux 6.1 and later; an older kernel
/// refuses it and the pages stay as they were).
///
/// With the system allocator, the hint makes a frame of the full dragon
/// markedly faster (docs/performance-log.md).
pub(crate) fn advise_huge_pages<T>(buffer: &Vec<T>) {
    let start = buffer.as_ptr() as usize;
    let end = start + buffer.capacity() * std::mem::size_of::<T>();
    let (first, last) = (
        start.next_multiple_of(HUGE_PAGE),
        end / HUGE_PAGE * HUGE_PAGE,
    );
    if last <= first {
        return;
    }
    #[cfg(target_os = "linux")]
    // SAFETY: `madvise` with `MADV_HUGEPAGE` changes no content, mapping or
    // protection, only how the kernel backs the range; the range is
    // page-aligned and lies within `buffer`'s live allocation. Its result
    // is ignored: a refused hint leaves the memory as it was.
    unsafe {
        const MADV_COLLAPSE: libc::c_int = 25;
        let range = (first as *mut libc::c_void, last - first);
        libc::madvise(range.0, range.1, libc::MADV_HUGEPAGE);
        libc::madvise(range.0, range.1, MADV_COLLAPSE);
    }
}

/// A vector of `n` copies of `value`, in memory asked for in 2 MiB pages
/// before its first write ([`advise_huge_pages`]).
pub(crate) fn filled_in_huge_pages<T: Clone>(n: usize, value: T) -> Vec<T> {
    let mut buffer = Vec::with_capacity(n);
    advise_huge_pages(&buffer);
    buffer.resize(n, value);
    buffer
}

/// A vector of `n` zeroes, in memory asked for in 2 MiB pages. The
/// allocator hands fresh memory out zeroed without writing it, so the
/// first write of each page is its user's; memory it reused, which it
/// zeroed, is collapsed into 2 MiB pages ([`advise_huge_pages`]).
pub(crate) fn zeroed_in_huge_pages<T: bytemuck::Zeroable>(n: usize) -> Vec<T> {
    let buffer = bytemuck::zeroed_vec(n);
    advise_huge_pages(&buffer);
    buffer
}

/// Reserves room for `additional` more elements in `buffer`, and when that
/// takes a new allocation, asks for it in 2 MiB pages
/// ([`advise_huge_pages`]).
pub(crate) fn reserve_in_huge_pages<T>(buffer: &mut Vec<T>, additional: usize) {
    let before = buffer.capacity();
    buffer.reserve(additional);
    if buffer.capacity() != before {
        advise_huge_pages(buffer);
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

    /// The huge-page hint changes no value: a filled buffer holds its
    /// values, a reserved one keeps those it had, and an empty or small one
    /// (no whole 2 MiB page in it) is left alone.
    #[test]
    fn buffers_asked_for_in_huge_pages_keep_their_values() {
        let filled = filled_in_huge_pages(3 << 20, 7u32);
        assert_eq!(filled.len(), 3 << 20);
        assert!(filled.iter().all(|&v| v == 7));
        let mut kept: Vec<u64> = (0..1000).collect();
        reserve_in_huge_pages(&mut kept, 1 << 20);
        assert!(kept.capacity() >= 1000 + (1 << 20));
        assert!(kept.iter().copied().eq(0..1000));
        assert!(filled_in_huge_pages(0, 1u8).is_empty());
        assert_eq!(filled_in_huge_pages(3, 1u8), [1, 1, 1]);
    }

    /// Where Linux gives huge pages to memory that asks for them, a buffer
    /// filled after the hint lies, in part at least, in 2 MiB pages (the
    /// mapping's `AnonHugePages` in `/proc/self/smaps`). Without the hint,
    /// under the default `madvise` setting, it has none.
    #[cfg(target_os = "linux")]
    #[test]
    fn the_kernel_backs_a_buffer_filled_after_the_hint_with_huge_pages() {
        let setting = "/sys/kernel/mm/transparent_hugepage/enabled";
        let enabled = std::fs::read_to_string(setting).unwrap_or_default();
        if !enabled.contains("[madvise]") && !enabled.contains("[always]") {
            eprintln!("NOT CHECKED: transparent huge pages are off here ({setting}: {enabled:?})");
            return;
        }
        let buffer = filled_in_huge_pages(8 << 20, 1u32);
        let start = buffer.as_ptr() as usize;
        let end = start + buffer.len() * 4;
        // The hint splits the buffer's mapping where its 2 MiB pages begin
        // and end: every mapping it overlaps counts.
        let smaps = std::fs::read_to_string("/proc/self/smaps").unwrap();
        let mut overlaps = false;
        let mut huge_kb = 0;
        for line in smaps.lines() {
            let range = line.split_whitespace().next().unwrap_or("");
            if let Some((low, high)) = range.split_once('-') {
                let parse = |hex| usize::from_str_radix(hex, 16);
                if let (Ok(low), Ok(high)) = (parse(low), parse(high)) {
                    overlaps = low < end && start < high;
                    continue;
                }
            }
            if let Some(kb) = line.strip_prefix("AnonHugePages:").filter(|_| overlaps) {
                huge_kb += kb
                    .trim()
                    .trim_end_matches("kB")
                    .trim()
                    .parse::<u64>()
                    .unwrap();
            }
        }
        assert!(
            huge_kb >= 2048,
            "a 32 MiB buffer asked for in huge pages has {huge_kb} kB of them"
        );
    }
}
