//! The render target: colour buffer, depth buffer and coverage-count buffer.
//!
//! The **colour buffer** holds one RGBA8 colour per pixel (the course chapter). The
//! **depth buffer** holds one `f32` per pixel and starts at `1.0`, the far
//! plane (the rasterization slides, the software-rasterizer article). The **coverage buffer** counts every
//! fragment that reached a pixel, before the depth test: it is how
//! rasterlab shows double-drawn pixels (count 2) and gaps (count 0) on
//! shared edges.

use crate::error::{Error, Result};
use crate::raster::edge::PixelRect;
use crate::raster::vector;
use rayon::prelude::*;
use std::path::Path;

/// The largest allowed width or height of a target, in pixels. Every pixel
/// centre then lies well inside the guard band.
pub const MAX_TARGET_SIDE: u32 = 16_384;

/// The comparison a fragment's depth must pass against the stored depth.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum DepthTest {
    /// Never passes.
    Never,
    /// `z < stored` (the default; the rasterization slides' test).
    #[default]
    Less,
    /// `z == stored`.
    Equal,
    /// `z <= stored`.
    LessEqual,
    /// `z > stored`.
    Greater,
    /// `z != stored`.
    NotEqual,
    /// `z >= stored`.
    GreaterEqual,
    /// Always passes (no depth test).
    Always,
}

impl DepthTest {
    /// Every comparison.
    pub const ALL: [DepthTest; 8] = [
        DepthTest::Never,
        DepthTest::Less,
        DepthTest::Equal,
        DepthTest::LessEqual,
        DepthTest::Greater,
        DepthTest::NotEqual,
        DepthTest::GreaterEqual,
        DepthTest::Always,
    ];

    /// Does a fragment at depth `z` pass against the `stored` depth?
    #[inline]
    pub fn passes(self, z: f32, stored: f32) -> bool {
        match self {
            DepthTest::Never => false,
            DepthTest::Less => z < stored,
            DepthTest::Equal => z == stored,
            DepthTest::LessEqual => z <= stored,
            DepthTest::Greater => z > stored,
            DepthTest::NotEqual => z != stored,
            DepthTest::GreaterEqual => z >= stored,
            DepthTest::Always => true,
        }
    }
}

crate::names::named_enum!(
    DepthTest,
    "depth test",
    Never = "never",
    Less = "less",
    Equal = "equal",
    LessEqual = "less-equal",
    Greater = "greater",
    NotEqual = "not-equal",
    GreaterEqual = "greater-equal",
    Always = "always"
);

/// Depth-buffer state: which comparison, and whether passing fragments
/// write their depth.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub struct DepthState {
    /// The comparison.
    pub test: DepthTest,
    /// Whether a passing fragment stores its depth.
    pub write: bool,
}

impl DepthState {
    /// `less` with writes on: the rasterization slides' depth buffer.
    pub const DEFAULT: DepthState = DepthState {
        test: DepthTest::Less,
        write: true,
    };

    /// No depth buffer: every fragment passes and nothing is written, so
    /// the stage neither evaluates depth for a span nor reads or writes
    /// the depth buffer (`--depth-test off`). The image is the one
    /// `always` without writes gives.
    pub const OFF: DepthState = DepthState {
        test: DepthTest::Always,
        write: false,
    };

    /// Whether the depth buffer is left alone ([`Self::OFF`]).
    pub fn is_off(self) -> bool {
        self == Self::OFF
    }

    /// The state `--depth-test NAME` asks for: `off` ([`Self::OFF`]), or
    /// a comparison with writes on.
    pub fn from_name(name: &str) -> Result<DepthState> {
        if name == "off" {
            return Ok(Self::OFF);
        }
        let test = name.parse::<DepthTest>().map_err(|e| match e {
            Error::UnknownName { what, name, known } => Error::UnknownName {
                what,
                name,
                known: format!("off, {known}"),
            },
            other => other,
        })?;
        Ok(DepthState { test, write: true })
    }
}

impl Default for DepthState {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Colour, depth and coverage buffers of one size.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderTarget {
    width: u32,
    height: u32,
    /// RGBA8 colours, row by row from the top.
    pub color: Vec<[u8; 4]>,
    /// Depths, starting at 1.0.
    pub depth: Vec<f32>,
    /// Fragments received per pixel (before the depth test), saturating;
    /// empty when the target does not count them
    /// ([`without_coverage`](Self::without_coverage)).
    pub coverage: Vec<u16>,
}

impl RenderTarget {
    /// Opaque black: the default clear colour.
    pub const BLACK: [u8; 4] = [0, 0, 0, 255];

    /// The depth a cleared depth buffer holds: the far plane.
    pub const FAR_DEPTH: f32 = 1.0;

    /// A cleared target: colour opaque black, depth 1.0, coverage 0.
    ///
    /// Errors on a zero side or a side over [`MAX_TARGET_SIDE`].
    pub fn new(width: u32, height: u32) -> Result<RenderTarget> {
        Self::cleared(width, height, true)
    }

    /// A cleared target that does not count coverage: colour and depth
    /// only, as an application's framebuffer. The count is a checking aid
    /// (the watertightness tests read it); without it each fragment reads
    /// and writes two bytes less, which is what the benchmarks measure
    /// against peers that do not count either. The image and depth are the
    /// same as with [`new`](Self::new).
    ///
    /// ```
    /// use rasterlab::raster::RenderTarget;
    ///
    /// let target = RenderTarget::without_coverage(4, 3).unwrap();
    /// assert!(!target.counts_coverage() && target.coverage.is_empty());
    /// assert_eq!(target.depth.len(), 12);
    /// ```
    pub fn without_coverage(width: u32, height: u32) -> Result<RenderTarget> {
        Self::cleared(width, height, false)
    }

    /// A cleared target, counting coverage or not. The buffers ask for
    /// 2 MiB pages ([`vector::advise_huge_pages`]); the zeroed count is
    /// left for the kernel to zero as it is first written.
    fn cleared(width: u32, height: u32, counts_coverage: bool) -> Result<RenderTarget> {
        Self::check_size(width, height)?;
        let n = width as usize * height as usize;
        Ok(RenderTarget {
            width,
            height,
            color: vector::filled_in_huge_pages(n, Self::BLACK),
            depth: vector::filled_in_huge_pages(n, Self::FAR_DEPTH),
            coverage: if counts_coverage {
                vector::zeroed_in_huge_pages(n)
            } else {
                Vec::new()
            },
        })
    }

    /// Whether fragments are counted in [`coverage`](Self::coverage).
    pub fn counts_coverage(&self) -> bool {
        !self.coverage.is_empty()
    }

    /// Errors unless both sides are between 1 and [`MAX_TARGET_SIDE`].
    pub fn check_size(width: u32, height: u32) -> Result<()> {
        if width == 0 || height == 0 || width > MAX_TARGET_SIDE || height > MAX_TARGET_SIDE {
            return Err(Error::InvalidTargetSize {
                width: width.into(),
                height: height.into(),
                max: MAX_TARGET_SIDE,
            });
        }
        Ok(())
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The buffer index of pixel `(x, y)`.
    #[inline]
    pub fn index(&self, x: u32, y: u32) -> usize {
        y as usize * self.width as usize + x as usize
    }

    /// Fills the colour buffer, on rayon's threads.
    pub fn clear_color(&mut self, color: [u8; 4]) {
        fill_in_parallel(&mut self.color, color);
    }

    /// Resets depth to 1.0 and coverage to 0 (colour is kept), on rayon's
    /// threads.
    pub fn clear_depth_and_coverage(&mut self) {
        fill_in_parallel(&mut self.depth, Self::FAR_DEPTH);
        fill_in_parallel(&mut self.coverage, 0);
    }

    /// Back to the state of a new target: colour black, depth 1.0,
    /// coverage 0.
    pub fn clear(&mut self) {
        self.clear_now(Clear::all(Self::BLACK));
    }

    /// Clears what `clear` says, at once, over the whole buffers: what a
    /// draw that folds `clear` into its writes
    /// ([`draw_clearing`](crate::geometry::pipeline::draw_clearing)) ends
    /// the same as.
    pub fn clear_now(&mut self, clear: Clear) {
        if let Some(color) = clear.color {
            self.clear_color(color);
        }
        if clear.depth_and_coverage {
            self.clear_depth_and_coverage();
        }
    }

    /// The colour buffer enlarged `scale` times: each pixel a `scale` x
    /// `scale` cell, with a one-pixel grey border from `scale >= 4` on, so
    /// that a small scene shows its pixels. `scale` 1 is [`Self::to_image`].
    pub fn to_image_scaled(&self, scale: u32) -> image::RgbaImage {
        if scale <= 1 {
            return self.to_image();
        }
        image::RgbaImage::from_fn(self.width * scale, self.height * scale, |x, y| {
            let border = scale >= 4 && (x % scale == 0 || y % scale == 0);
            if border {
                image::Rgba([96, 96, 96, 255])
            } else {
                image::Rgba(self.color[self.index(x / scale, y / scale)])
            }
        })
    }

    /// The colour buffer as an image.
    pub fn to_image(&self) -> image::RgbaImage {
        let bytes: Vec<u8> = self.color.iter().flatten().copied().collect();
        image::RgbaImage::from_raw(self.width, self.height, bytes)
            .expect("colour buffer holds width * height pixels")
    }

    /// Writes the colour buffer as a PNG file.
    pub fn save_png(&self, path: &Path) -> Result<()> {
        crate::output::write_png(path, &self.to_image())
    }

    /// All rows of the buffers, borrowed as one [`TargetRows`].
    pub fn rows_mut(&mut self) -> TargetRows<'_> {
        self.rows_clearing(Clear::NOTHING)
    }

    /// All rows, each cleared by `clear` just before its first write; the
    /// borrower calls [`TargetRows::finish`] when done, which clears the
    /// rows never written. The buffers then end as after `clear` and the
    /// draw, without a separate pass over them.
    pub(crate) fn rows_clearing(&mut self, clear: Clear) -> TargetRows<'_> {
        TargetRows::new(
            self.width,
            0,
            &mut self.color,
            &mut self.depth,
            &mut self.coverage,
            clear,
        )
    }

    /// The buffers cut into horizontal bands of `rows_per_band` rows (the
    /// last may be shorter), each borrowed separately so that bands can be
    /// drawn on different threads.
    pub fn bands_mut(&mut self, rows_per_band: u32) -> Vec<TargetRows<'_>> {
        self.bands_clearing(rows_per_band, Clear::NOTHING)
    }

    /// [`bands_mut`](Self::bands_mut), each band clearing its rows as
    /// [`rows_clearing`](Self::rows_clearing) does (each to be finished).
    pub(crate) fn bands_clearing(
        &mut self,
        rows_per_band: u32,
        clear: Clear,
    ) -> Vec<TargetRows<'_>> {
        let width = self.width;
        let rows_per_band = rows_per_band.max(1);
        let n = width as usize * rows_per_band as usize;
        // A target that does not count coverage lends every band an empty
        // count.
        let counts = self.counts_coverage();
        let mut coverage = self.coverage.chunks_mut(n);
        self.color
            .chunks_mut(n)
            .zip(self.depth.chunks_mut(n))
            .map(|bufs| (bufs, if counts { coverage.next() } else { None }))
            .enumerate()
            .map(|(i, ((color, depth), coverage))| {
                let first_row = i as u32 * rows_per_band;
                let coverage = coverage.unwrap_or_default();
                TargetRows::new(width, first_row, color, depth, coverage, clear)
            })
            .collect()
    }

    /// Pixels whose coverage count is exactly `n` (none when the target
    /// does not count).
    pub fn pixels_with_coverage(&self, n: u16) -> usize {
        self.coverage.iter().filter(|&&c| c == n).count()
    }
}

/// What a draw clears as it goes: a render pass's *load op*.
///
/// A separate clear writes the whole buffer, and the draw then reads it
/// back from memory. Folding the clear into the draw
/// ([`draw_clearing`](crate::geometry::pipeline::draw_clearing)) clears
/// each row just before the first write to it, while the row is about to
/// be in the cache anyway, and clears the rows no fragment reached when the
/// draw finishes. The buffers end exactly as after a clear and a draw.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Default)]
pub struct Clear {
    /// The colour to clear to, or `None` to keep the colour buffer.
    pub color: Option<[u8; 4]>,
    /// Whether depth goes back to 1.0 and the coverage count to 0
    /// ([`RenderTarget::clear_depth_and_coverage`]).
    pub depth_and_coverage: bool,
}

impl Clear {
    /// Clears nothing: the buffers are loaded as they are.
    pub const NOTHING: Clear = Clear {
        color: None,
        depth_and_coverage: false,
    };

    /// Depth to 1.0 and coverage to 0; colour kept.
    pub const DEPTH_AND_COVERAGE: Clear = Clear {
        color: None,
        depth_and_coverage: true,
    };

    /// Everything, colour to `color`: [`RenderTarget::clear`] with another
    /// colour.
    pub const fn all(color: [u8; 4]) -> Clear {
        Clear {
            color: Some(color),
            depth_and_coverage: true,
        }
    }

    /// Colour only, to `color`.
    pub const fn color(color: [u8; 4]) -> Clear {
        Clear {
            color: Some(color),
            depth_and_coverage: false,
        }
    }

    /// Whether nothing is cleared.
    pub fn is_nothing(self) -> bool {
        self == Self::NOTHING
    }
}

/// Consecutive full rows of a [`RenderTarget`]'s buffers, borrowed mutably:
/// the whole target ([`RenderTarget::rows_mut`]) or one band of it
/// ([`RenderTarget::bands_mut`]). Pixels are addressed in target
/// coordinates.
///
/// Rows a draw borrows with a [`Clear`] are cleared just before the first
/// fragment written to them, and those no fragment reached when the draw
/// finishes (see [`draw_clearing`](crate::geometry::pipeline::draw_clearing)).
#[derive(Debug)]
pub struct TargetRows<'a> {
    width: u32,
    first_row: u32,
    rows: u32,
    /// Colours of these rows.
    pub(crate) color: &'a mut [[u8; 4]],
    /// Depths of these rows.
    pub(crate) depth: &'a mut [f32],
    /// Coverage counts of these rows; empty when the target does not
    /// count coverage.
    pub(crate) coverage: &'a mut [u16],
    /// What the first load of a row clears.
    clear: Clear,
    /// Which rows still wait for that clear, and the cleared rows copied.
    pending: PendingClear,
}

/// The rows of a [`TargetRows`] still waiting for their clear, with the
/// cleared rows they are copied from: what rows lent for a batch of a
/// draw ([`TargetRows::lend`]) give back.
#[derive(Debug, Default)]
pub(crate) struct PendingClear {
    /// Per row held, whether it still waits for its clear; empty when
    /// nothing is cleared.
    unloaded: Vec<bool>,
    /// One row of the clear colour; empty when the colour is kept.
    clear_color_row: Vec<[u8; 4]>,
    /// One row of the far depth; empty when depth is kept.
    clear_depth_row: Vec<f32>,
}

impl<'a> TargetRows<'a> {
    /// Rows `first_row..first_row + rows` of the buffers, which hold just
    /// those rows, cleared on first load by `clear`.
    fn new(
        width: u32,
        first_row: u32,
        color: &'a mut [[u8; 4]],
        depth: &'a mut [f32],
        coverage: &'a mut [u16],
        clear: Clear,
    ) -> Self {
        let rows = (color.len() / width as usize) as u32;
        let unloaded = if clear.is_nothing() {
            Vec::new()
        } else {
            vec![true; rows as usize]
        };
        TargetRows {
            width,
            first_row,
            rows,
            color,
            depth,
            coverage,
            clear,
            pending: PendingClear {
                unloaded,
                clear_color_row: clear.color.map_or(Vec::new(), |c| vec![c; width as usize]),
                clear_depth_row: if clear.depth_and_coverage {
                    vec![RenderTarget::FAR_DEPTH; width as usize]
                } else {
                    Vec::new()
                },
            },
        }
    }

    /// Makes target row `y` ready for writing: clears it if it still waits
    /// for its clear. Every write to a row goes after this.
    #[inline(always)]
    pub(crate) fn load_row(&mut self, y: u32) {
        let row = y.wrapping_sub(self.first_row) as usize;
        if self.pending.unloaded.get(row) == Some(&true) {
            self.clear_row(row);
        }
    }

    /// Clears the rows no one loaded, so the buffers end as after an eager
    /// clear. A draw with rows borrowed by [`RenderTarget::rows_clearing`]
    /// or [`RenderTarget::bands_clearing`] calls this when it is done.
    pub(crate) fn finish(&mut self) {
        for row in 0..self.pending.unloaded.len() {
            self.clear_row(row);
        }
    }

    /// The same rows, lent for a shorter time: a draw that makes a stage
    /// for each batch of triangles (whose data lives no longer than the
    /// batch) lends the rows to each, and takes back with
    /// [`resume`](Self::resume) which rows are still to clear.
    pub(crate) fn lend(&mut self) -> TargetRows<'_> {
        TargetRows {
            width: self.width,
            first_row: self.first_row,
            rows: self.rows,
            color: self.color,
            depth: self.depth,
            coverage: self.coverage,
            clear: self.clear,
            pending: std::mem::take(&mut self.pending),
        }
    }

    /// What rows lent by [`lend`](Self::lend) still have to clear, for
    /// the rows they were lent from.
    pub(crate) fn into_pending(self) -> PendingClear {
        self.pending
    }

    /// Takes back what rows lent by [`lend`](Self::lend) left to clear.
    pub(crate) fn resume(&mut self, pending: PendingClear) {
        self.pending = pending;
    }

    /// Clears the `row`-th row held, if it still waits for its clear.
    ///
    /// Each buffer's row is copied from a cleared row, not filled value by
    /// value: a copy this long goes to the C library's `memcpy`, which with
    /// glibc on x86-64 is `rep movsb`, whose whole-line writes do not read
    /// the lines from memory first, where a loop of vector stores does
    /// (measured on the bundled dragon's frame: docs/performance-log.md).
    #[cold]
    fn clear_row(&mut self, row: usize) {
        if !std::mem::replace(&mut self.pending.unloaded[row], false) {
            return;
        }
        let width = self.width as usize;
        let pixels = row * width..(row + 1) * width;
        if self.clear.color.is_some() {
            self.color[pixels.clone()].copy_from_slice(&self.pending.clear_color_row);
        }
        if self.clear.depth_and_coverage {
            self.depth[pixels.clone()].copy_from_slice(&self.pending.clear_depth_row);
            if let Some(coverage) = self.coverage.get_mut(pixels) {
                coverage.fill(0);
            }
        }
    }
}

impl TargetRows<'_> {
    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// The target row of the first row held.
    pub fn first_row(&self) -> u32 {
        self.first_row
    }

    /// The number of rows held.
    pub fn rows(&self) -> u32 {
        self.rows
    }

    /// The pixels held, as a rectangle in target coordinates.
    pub fn rect(&self) -> PixelRect {
        PixelRect {
            x0: 0,
            y0: i64::from(self.first_row),
            x1: i64::from(self.width) - 1,
            y1: i64::from(self.first_row) + i64::from(self.rows) - 1,
        }
    }

    /// Whether fragments are counted in the coverage buffer.
    #[inline]
    pub fn counts_coverage(&self) -> bool {
        !self.coverage.is_empty()
    }

    /// The buffer index of target pixel `(x, y)` (`y` among the rows held).
    #[inline]
    pub fn index(&self, x: u32, y: u32) -> usize {
        (y - self.first_row) as usize * self.width as usize + x as usize
    }
}

/// Sets every element of `buffer` to `value`, in chunks of 256 KiB shared
/// between rayon's threads: one core alone does not reach the memory's
/// write bandwidth. Each chunk is copied from a filled head rather than
/// filled value by value, which measured a little faster
/// (docs/performance-log.md).
fn fill_in_parallel<T: Copy + Send + Sync>(buffer: &mut [T], value: T) {
    let size = std::mem::size_of::<T>().max(1);
    let (chunk, head) = ((256 * 1024 / size).max(1), (8 * 1024 / size).max(1));
    buffer.par_chunks_mut(chunk).for_each(|part| {
        // The chunk's first 8 KiB filled, and copied over the rest: as
        // `TargetRows::clear_row` copies a cleared row, for the same
        // reason (`rep movsb` does not read the lines it overwrites).
        let (first, rest) = part.split_at_mut(head.min(part.len()));
        first.fill(value);
        for copy in rest.chunks_mut(head) {
            copy.copy_from_slice(&first[..copy.len()]);
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every element is set, whatever the length: shorter than the filled
    /// head, a whole number of heads, and several chunks with a part of a
    /// head left over.
    #[test]
    fn filling_in_parallel_sets_every_element() {
        for len in [0, 1, 2047, 2048, 2049, 4096, 3 * 65_536 + 5] {
            let mut depth = vec![0.5f32; len];
            fill_in_parallel(&mut depth, 1.0);
            assert!(depth.iter().all(|&d| d == 1.0), "f32, {len}");
            let mut coverage = vec![7u16; len];
            fill_in_parallel(&mut coverage, 0);
            assert!(coverage.iter().all(|&c| c == 0), "u16, {len}");
        }
    }

    #[test]
    fn a_clear_folded_into_the_rows_ends_as_an_eager_clear() {
        for clear in [
            Clear::NOTHING,
            Clear::DEPTH_AND_COVERAGE,
            Clear::color([1, 2, 3, 4]),
            Clear::all([5, 6, 7, 8]),
        ] {
            for coverage in [true, false] {
                let mut dirty = RenderTarget::new(7, 5).unwrap();
                if !coverage {
                    dirty.coverage = Vec::new();
                }
                dirty.color.fill([9, 9, 9, 9]);
                dirty.depth.fill(0.25);
                dirty.coverage.fill(3);
                let mut eager = dirty.clone();
                eager.clear_now(clear);
                // Loading row 3 clears it at once; a write to it stays.
                let mut lazy = dirty.clone();
                let mut rows = lazy.rows_clearing(clear);
                rows.load_row(3);
                rows.depth[3 * 7 + 2] = 0.5;
                rows.finish();
                eager.depth[3 * 7 + 2] = 0.5;
                assert_eq!(lazy, eager, "{clear:?}");
                // Every band finishes its own rows.
                let mut banded = dirty.clone();
                for mut band in banded.bands_clearing(2, clear) {
                    band.finish();
                }
                eager.depth[3 * 7 + 2] = if clear.depth_and_coverage { 1.0 } else { 0.25 };
                assert_eq!(banded, eager, "{clear:?}");
            }
        }
    }

    #[test]
    fn zero_and_oversized_targets_are_errors() {
        assert!(matches!(
            RenderTarget::new(0, 10),
            Err(Error::InvalidTargetSize { .. })
        ));
        assert!(RenderTarget::new(10, 0).is_err());
        assert!(RenderTarget::new(MAX_TARGET_SIDE + 1, 1).is_err());
        let t = RenderTarget::new(3, 2).unwrap();
        assert_eq!(t.depth, vec![1.0; 6]);
        assert_eq!(t.to_image().dimensions(), (3, 2));
    }

    #[test]
    fn bands_cover_every_row_once() {
        let mut t = RenderTarget::new(3, 7).unwrap();
        let bands = t.bands_mut(3);
        let rows: Vec<(u32, u32)> = bands.iter().map(|b| (b.first_row(), b.rows())).collect();
        assert_eq!(rows, [(0, 3), (3, 3), (6, 1)]);
        assert_eq!(bands[1].index(2, 4), 5);
        assert!(bands
            .iter()
            .all(|b| b.counts_coverage() && b.coverage.len() == b.color.len()));
        assert_eq!(
            bands[2].rect(),
            PixelRect {
                x0: 0,
                y0: 6,
                x1: 2,
                y1: 6
            }
        );
    }

    #[test]
    fn a_target_without_coverage_lends_bands_empty_counts() {
        let mut t = RenderTarget::without_coverage(3, 7).unwrap();
        let bands = t.bands_mut(3);
        assert_eq!(bands.len(), 3);
        assert!(bands
            .iter()
            .all(|b| !b.counts_coverage() && b.color.len() == 3 * b.rows() as usize));
    }

    #[test]
    fn depth_tests_compare_as_named() {
        use DepthTest::*;
        let expect = [
            (Never, [false, false, false]),
            (Less, [true, false, false]),
            (Equal, [false, true, false]),
            (LessEqual, [true, true, false]),
            (Greater, [false, false, true]),
            (NotEqual, [true, false, true]),
            (GreaterEqual, [false, true, true]),
            (Always, [true, true, true]),
        ];
        for (test, results) in expect {
            assert_eq!(
                [0.25, 0.5, 0.75].map(|z| test.passes(z, 0.5)),
                results,
                "{test}"
            );
            assert_eq!(test.name().parse::<DepthTest>().unwrap(), test);
        }
    }
}
