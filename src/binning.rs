//! Binning and parallel drawing: the same image, drawn band by band on
//! every core.
//!
//! The target is cut into horizontal **bands** of full rows, a few per
//! thread ([`band_rows`]). Each set-up triangle is **binned**: its index goes into
//! the list of every band its bounding box meets. The bands are then drawn in
//! parallel with `rayon`, each by its own [`FragmentStage`] writing only its
//! own rows, with the back-end's viewport narrowed to the band.
//!
//! A mesh rendered by [`MeshRenderer`](crate::render::MeshRenderer) on
//! several threads comes binned already: the pipeline's tasks bin the
//! triangles they keep as they set them up, and leave them in their own
//! chunks (runs), which the bands read in order, without a copy into one
//! array. Other geometry is binned here, in parallel chunks.
//!
//! Why the image is bit-identical to a single-threaded draw: a pixel lies in
//! exactly one band, and that band receives its triangles in ascending id
//! order (binning keeps the order: triangles are binned in chunks, and each
//! band walks its chunk lists in chunk order). Every back-end emits a
//! pixel's fragments in triangle order, and the stage is a pure function of
//! the fragment, so each pixel sees exactly the same sequence of fragments
//! as in [`draw`](crate::pipeline::draw).
//!
//! With one thread there is nothing to share out, and the draw is
//! [`pipeline::draw`](crate::pipeline::draw) itself. The number of threads
//! is rayon's: all cores by default,
//! `RAYON_NUM_THREADS` or a pool installed by the caller (`--threads N` on
//! the command line). Work counters are summed over bands, so a triangle
//! met by three bands counts three primitives.

use crate::edge::{PixelRect, TriangleSetup};
use crate::fragment::WorkCounters;
use crate::pipeline::{Geometry, TriangleRun, Viewport};
use crate::stage::{FragmentShader, FragmentStage, Interpolation};
use crate::target::{DepthState, RenderTarget};
use crate::triangle::{TriangleRasterizer, TriangleSelection};
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
/// frame is bound by. On the full dragon at 1920x1080 with two threads,
/// rasterization took 11.2 ms in 16 bands of 72 rows and 10.2 ms in 8
/// bands of 136 rows (and 24 ms in 16-row bands, when bins were walked
/// over the whole triangle list).
pub fn band_rows(height: u32, threads: usize) -> u32 {
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

/// Adds triangle `id`, whose pixels lie in `bounds` (not empty, inside the
/// target), to the bins of the bands of `band_rows` rows that it meets.
#[inline]
pub(crate) fn bin(bins: &mut [Vec<u32>], band_rows: u32, bounds: PixelRect, id: u32) {
    let rows = i64::from(band_rows);
    for band in &mut bins[(bounds.y0 / rows) as usize..=(bounds.y1 / rows) as usize] {
        band.push(id);
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
    /// Bins the triangles of `runs` into bands of `band_rows` rows of a
    /// `width` x `height` target, in parallel.
    pub fn new(runs: &[TriangleRun<'_>], width: u32, height: u32, band_rows: u32) -> Bins {
        let band_rows = band_rows.max(1);
        let bands = height.div_ceil(band_rows) as usize;
        let viewport = PixelRect::of_target(width, height);
        let total = runs.iter().map(|r| r.setups.len()).sum();
        let chunk = chunk_len(total, 4, MIN_CHUNK);
        // (run, first index in the run, the chunk's set-ups)
        let work: Vec<(usize, usize, &[TriangleSetup])> = runs
            .iter()
            .enumerate()
            .flat_map(|(r, run)| {
                run.setups
                    .chunks(chunk)
                    .enumerate()
                    .map(move |(c, setups)| (r, c * chunk, setups))
            })
            .collect();
        let chunks = work
            .into_par_iter()
            .map(|(run, first, triangles)| {
                let mut per_band: Vec<Vec<u32>> = vec![Vec::new(); bands];
                for (i, t) in triangles.iter().enumerate() {
                    let r = t.bounds_within(viewport);
                    if !r.is_empty() {
                        bin(&mut per_band, band_rows, r, (first + i) as u32);
                    }
                }
                (run, per_band)
            })
            .collect();
        Bins { chunks }
    }
}

/// Rasterizes `geometry` with `backend` into `target` through the shared
/// fragment stage, band by band in parallel; bit-identical to
/// [`pipeline::draw`](crate::pipeline::draw).
pub fn draw_binned(
    geometry: &Geometry,
    backend: &dyn TriangleRasterizer,
    shader: &dyn FragmentShader,
    depth: DepthState,
    interpolation: Interpolation,
    target: &mut RenderTarget,
) -> WorkCounters {
    let threads = rayon::current_num_threads();
    if threads == 1 {
        return crate::pipeline::draw(geometry, backend, shader, depth, interpolation, target);
    }
    let (width, height) = (target.width(), target.height());
    let runs = geometry.runs();
    let band_rows = band_rows(height, threads);
    // Per chunk in id order: its run, and per band its triangles there.
    let computed: Bins;
    let chunks: Vec<(usize, &[Vec<u32>])> =
        match geometry.bins_of_parts(band_rows, Viewport { width, height }) {
            Some(parts) => parts.into_iter().enumerate().collect(),
            None => {
                computed = Bins::new(&runs, width, height, band_rows);
                computed.chunks.iter().map(|(r, b)| (*r, &b[..])).collect()
            }
        };
    target
        .bands_mut(band_rows)
        .into_par_iter()
        .enumerate()
        .map(|(b, rows)| {
            let viewport = rows.rect();
            let mut stage = FragmentStage::on_rows(rows, shader)
                .with_triangles(&geometry.shaded)
                .with_depth(depth)
                .with_interpolation(interpolation);
            let mut work = WorkCounters::default();
            for &(run, per_band) in &chunks {
                if !per_band[b].is_empty() {
                    let run = runs[run];
                    stage.use_triangles(run.triangles);
                    let selection = TriangleSelection::indexed(run.setups, &per_band[b]);
                    work.add(&backend.rasterize_selection(selection, viewport, &mut stage));
                }
            }
            work
        })
        .reduce(WorkCounters::default, |mut a, b| {
            a.add(&b);
            a
        })
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
