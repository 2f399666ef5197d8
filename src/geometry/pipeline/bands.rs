//! The band arithmetic of drawing on several threads: the target cut into
//! horizontal bands of full rows, a few per thread ([`band_rows`]), each
//! set-up triangle binned into the bands its bounding box meets, and the
//! chunks a list is cut into to share it between threads.

use crate::raster::edge::{PixelRect, TriangleSetup};
use rayon::prelude::*;

/// Bands per thread: enough for rayon to balance a mesh that covers only
/// part of the screen.
const BANDS_PER_THREAD: u32 = 4;
/// Triangles binned per task, at least.
const MIN_CHUNK: usize = 4096;

/// Rows per band for a target `height` rows high drawn by `threads`
/// threads: four bands per thread, rounded up to a multiple
/// of 8 rows (the tiled back-end's block).
///
/// Bands are kept few and tall on purpose. Each band walks its bins of
/// every chunk of triangles in order; the fewer the bands, the fewer
/// triangles are met by two bands and the more of each walk is a
/// sequential stream through the set-up data, which is what a dragon
/// frame is bound by: on the full dragon with two threads, twice as many
/// bands, or much shorter ones, rasterized more slowly
/// (docs/performance-log.md, "2026-12-06, `6745bfd` to `f1ae308`", for
/// eight bands a thread).
pub(crate) fn band_rows(height: u32, threads: usize) -> u32 {
    let bands = (threads as u32).saturating_mul(BANDS_PER_THREAD).max(1);
    height.div_ceil(bands).div_ceil(8).max(1) * 8
}

/// The length of the chunks a list of `len` items is cut into to share it
/// between rayon's threads: `per_thread` chunks per thread to balance the
/// load, of at least `min` items; with one thread, one chunk (nothing to
/// balance, and no partial results to join).
pub(crate) fn chunk_len(len: usize, per_thread: usize, min: usize) -> usize {
    let threads = rayon::current_num_threads();
    if threads == 1 {
        len.max(1)
    } else {
        len.div_ceil(per_thread * threads).max(min)
    }
}

/// The target's horizontal bands: how many rows each has (the last may
/// have fewer) and how many there are. The one place their arithmetic is
/// done: the pipeline's parts bin into them, [`Bins`] bins into them, and a
/// binned draw cuts the target into them.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) struct Bands {
    rows: u32,
    count: usize,
}

impl Bands {
    /// The bands of a target `height` rows high drawn by `threads`
    /// threads ([`band_rows`]).
    pub fn for_threads(height: u32, threads: usize) -> Bands {
        let rows = band_rows(height, threads);
        Bands {
            rows,
            count: height.div_ceil(rows) as usize,
        }
    }

    /// Rows per band.
    pub fn rows(self) -> u32 {
        self.rows
    }

    /// The number of bands.
    pub fn count(self) -> usize {
        self.count
    }

    /// Adds triangle `id`, whose pixels lie in `bounds` (not empty, inside
    /// the target), to the bins (one per band) of the bands it meets.
    #[inline]
    pub fn bin(self, bins: &mut [Vec<u32>], bounds: PixelRect, id: u32) {
        let rows = i64::from(self.rows);
        for band in &mut bins[(bounds.y0 / rows) as usize..=(bounds.y1 / rows) as usize] {
            band.push(id);
        }
    }
}

/// Triangles binned by band, chunk by chunk of the draw's runs.
#[derive(Clone, Debug, Default)]
pub(crate) struct Bins {
    /// In id order: a chunk of one run (the run's index), and per band the
    /// indices in that run of the chunk's triangles meeting the band.
    pub chunks: Vec<(usize, Vec<Vec<u32>>)>,
}

impl Bins {
    /// Bins the triangles of `runs` (the set-ups of each run, in id order)
    /// into the `bands` of a `width` x `height` target, in parallel.
    pub fn new(runs: &[&[TriangleSetup]], width: u32, height: u32, bands: Bands) -> Bins {
        let viewport = PixelRect::of_target(width, height);
        let total = runs.iter().map(|r| r.len()).sum();
        let chunk = chunk_len(total, 4, MIN_CHUNK);
        // (run, first index in the run, the chunk's set-ups)
        let work: Vec<(usize, usize, &[TriangleSetup])> = runs
            .iter()
            .enumerate()
            .flat_map(|(r, run)| {
                run.chunks(chunk)
                    .enumerate()
                    .map(move |(c, setups)| (r, c * chunk, setups))
            })
            .collect();
        let chunks = work
            .into_par_iter()
            .map(|(run, first, triangles)| {
                let mut per_band: Vec<Vec<u32>> = vec![Vec::new(); bands.count()];
                for (i, t) in triangles.iter().enumerate() {
                    let r = t.bounds_within(viewport);
                    if !r.is_empty() {
                        bands.bin(&mut per_band, r, (first + i) as u32);
                    }
                }
                (run, per_band)
            })
            .collect();
        Bins { chunks }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bands_are_a_few_per_thread_and_align_to_blocks() {
        assert_eq!(band_rows(1080, 2), 136);
        assert_eq!(band_rows(1080, 1), 272);
        assert_eq!(band_rows(1, 64), 8);
        assert!((1..3000).all(|h| band_rows(h, 3).is_multiple_of(8)));
        assert!((1..3000u32).all(|h| h.div_ceil(band_rows(h, 2)) <= 8));
    }
}
