//! Drawing the pipeline's result through the shared fragment stage: on one
//! thread ([`draw`]), or band by band on every core ([`draw_binned`]), the
//! same image.
//!
//! The target is cut into horizontal **bands** of full rows, a few per
//! thread ([`band_rows`](super::bands::band_rows)). Each set-up triangle is **binned**: its index goes into
//! the list of every band its bounding box meets. The bands are then drawn in
//! parallel with `rayon`, each by its own [`FragmentStage`] writing only its
//! own rows, with the back-end's viewport narrowed to the band.
//!
//! A mesh rendered by [`MeshRenderer`](crate::geometry::render::MeshRenderer) on
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
//! as in [`draw`](fn@crate::geometry::pipeline::draw).
//!
//! With one thread there is nothing to share out, and the draw is
//! [`pipeline::draw`](fn@crate::geometry::pipeline::draw) itself. (The
//! mesh renderer on one thread goes further: it draws each batch of
//! triangles as soon as it is assembled, [`BatchDraw`].) That draw
//! goes band by band too when the triangles are few (at most 256), in
//! bands whose colour and depth fit a core's cache (64 rows at 1920
//! pixels wide), each band walking every triangle: large triangles over
//! one another are then drawn while the band is in the cache, instead of
//! each sweeping the whole buffers (docs/performance-log.md, "2026-12-02,
//! `37cc7c9` to `b275a82`", times `fill-4`'s four full-screen layers both
//! ways).
//!
//! The number of threads is rayon's: all cores by default,
//! `RAYON_NUM_THREADS` or a pool installed by the caller (`--threads N` on
//! the command line). Work counters are summed over bands, but for the
//! primitives: each triangle drawn counts once, however many bands it
//! meets, so the counts do not depend on the bands or the threads.

use super::bands::{Bands, Bins};
use super::geometry::{Geometry, Runs};
use super::Viewport;
use crate::raster::edge::TriangleSetup;
use crate::raster::fragment::WorkCounters;
use crate::raster::primitive::TriangleData;
use crate::raster::shader::FragmentShader;
use crate::raster::stage::{Blend, FragmentStage, Interpolation};
use crate::raster::target::{Clear, DepthState, RenderTarget, TargetRows};
use crate::raster::triangle::{TriangleRasterizer, TriangleSelection};
use rayon::prelude::*;

/// Rasterizes `geometry` with `backend` into `target` through the shared
/// fragment stage.
pub fn draw<S: FragmentShader + ?Sized>(
    geometry: &Geometry,
    backend: &dyn TriangleRasterizer,
    shader: &S,
    depth: DepthState,
    interpolation: Interpolation,
    target: &mut RenderTarget,
) -> WorkCounters {
    draw_clearing(
        geometry,
        backend,
        shader,
        depth,
        interpolation,
        Clear::NOTHING,
        target,
    )
}

/// [`draw`], with the target cleared by `clear` first: the same buffers as
/// a clear and then [`draw`], but each row is cleared just before the
/// first fragment written to it (see [`Clear`]), so the draw does not read
/// back a freshly cleared buffer from memory.
///
/// ```
/// use glam::Vec4;
/// use rasterlab::geometry::{draw, draw_clearing, setup_triangles, Geometry};
/// use rasterlab::raster::{Clear, DepthState, FillRule, FixedPoint, Flat, Interpolation, RenderTarget, ShadedVertex};
///
/// let p = |x, y| FixedPoint::snap(x, y).unwrap();
/// let triangle = [p(1.0, 1.0), p(7.0, 2.0), p(3.0, 6.0)];
/// let setups = setup_triangles(&[triangle], FillRule::TopLeft);
/// let red = ShadedVertex::flat(0.5, Vec4::new(1.0, 0.0, 0.0, 1.0));
/// let geometry = Geometry::of_screen_triangles(setups, &[[red; 3]]);
///
/// // A used target: a clear, then the draw ...
/// let mut used = RenderTarget::new(8, 8).unwrap();
/// used.color.fill([0, 0, 255, 255]);
/// used.depth.fill(0.25);
/// let mut eager = used.clone();
/// eager.clear();
/// let scanline = rasterlab::raster::triangle_backend("scanline").unwrap();
/// let (depth, lerp) = (DepthState::DEFAULT, Interpolation::PerspectiveCorrect);
/// draw(&geometry, scanline, &Flat, depth, lerp, &mut eager);
/// // ... or the clear folded into the draw: the same buffers.
/// let clear = Clear::all(RenderTarget::BLACK);
/// draw_clearing(&geometry, scanline, &Flat, depth, lerp, clear, &mut used);
/// assert_eq!(used, eager);
/// ```
pub fn draw_clearing<S: FragmentShader + ?Sized>(
    geometry: &Geometry,
    backend: &dyn TriangleRasterizer,
    shader: &S,
    depth: DepthState,
    interpolation: Interpolation,
    clear: Clear,
    target: &mut RenderTarget,
) -> WorkCounters {
    let runs = geometry.runs();
    let pass = Pass {
        shader,
        depth,
        interpolation,
        clear,
        blend: Blend::REPLACE,
    };
    draw_runs(&runs, backend, pass, target)
}

/// What a draw does besides rasterizing: shade, test depth, interpolate,
/// blend, and clear as it goes. The draw, and its stage, are compiled for the
/// shader's type `S` (see [`FragmentStage`]).
pub(crate) struct Pass<'a, S: ?Sized> {
    pub shader: &'a S,
    pub depth: DepthState,
    pub interpolation: Interpolation,
    pub clear: Clear,
    pub blend: Blend,
}

// Not derived: a derive would ask `S: Copy`, and a shader need not be.
impl<S: ?Sized> Clone for Pass<'_, S> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<S: ?Sized> Copy for Pass<'_, S> {}

impl<'a, S: FragmentShader + ?Sized> Pass<'a, S> {
    /// The stage of this pass, writing into `rows`, for triangles whose
    /// stage data is `shaded`.
    fn stage(self, rows: TargetRows<'a>, shaded: &'a TriangleData) -> FragmentStage<'a, S> {
        FragmentStage::on_rows(rows, self.shader)
            .with_triangles(shaded)
            .with_depth(self.depth)
            .with_blend(self.blend)
            .with_interpolation(self.interpolation)
    }
}

/// A draw on one thread of triangles that come batch by batch
/// ([`process_in_batches`](super::GeometryInParts::process_in_batches)):
/// each batch is rasterized through a stage of its own, which the
/// target's rows are lent to, so that the rows still waiting for their
/// clear are known from one batch to the next.
pub(crate) struct BatchDraw<'a, S: ?Sized> {
    rows: TargetRows<'a>,
    pass: Pass<'a, S>,
    backend: &'a dyn TriangleRasterizer,
    /// The work of the batches drawn so far.
    work: WorkCounters,
}

impl<'a, S: FragmentShader + ?Sized> BatchDraw<'a, S> {
    /// A draw of `pass` with `backend` into `target`, which it clears as
    /// it goes.
    pub(crate) fn new(
        target: &'a mut RenderTarget,
        backend: &'a dyn TriangleRasterizer,
        pass: Pass<'a, S>,
    ) -> Self {
        BatchDraw {
            rows: target.rows_clearing(pass.clear),
            pass,
            backend,
            work: WorkCounters::default(),
        }
    }

    /// Rasterizes one batch: `setups`, whose stage data is `shaded`.
    pub(crate) fn draw(&mut self, shaded: &TriangleData, setups: &[TriangleSetup]) {
        let viewport = self.rows.rect();
        let mut stage = self.pass.stage(self.rows.lend(), shaded);
        let work = self.backend.rasterize(setups, viewport, &mut stage);
        self.work.add(&work);
        let pending = stage.into_rows().into_pending();
        self.rows.resume(pending);
    }

    /// Ends the draw (clearing the rows no batch wrote); the work done.
    pub(crate) fn finish(mut self) -> WorkCounters {
        self.rows.finish();
        self.work
    }
}

/// Draws of at most this many triangles go band by band on one thread
/// too ([`cache_band_rows`]).
const BAND_BY_BAND_TRIANGLES: usize = 256;

/// Bytes of colour and depth in a band drawn band by band: well inside a
/// core's second-level cache.
const CACHE_BAND_BYTES: usize = 1 << 20;

/// Rows of the bands a draw of few triangles goes through on one thread:
/// as many as [`CACHE_BAND_BYTES`] hold for a target `width` pixels wide,
/// a multiple of 8 (the tiled back-end's block), at least 8.
///
/// Drawing triangle by triangle, each large triangle sweeps the whole
/// colour and depth buffers (16 MB at 1080p), and the next one finds them
/// back in memory, not in the cache. Drawing band by band, all the
/// triangles over a band are drawn while its rows are in the cache. Each
/// band walks every triangle, which costs nothing for a few and too much
/// for a mesh (those are binned on several threads, and walked in order
/// on one). Every pixel still meets its fragments in triangle order, so
/// the image is the same bits.
fn cache_band_rows(width: u32) -> u32 {
    let row_bytes = width as usize * (4 + 4);
    let rows = (CACHE_BAND_BYTES / row_bytes.max(1)) as u32;
    (rows / 8 * 8).max(8)
}

/// [`draw`] of triangles in runs: band by band when they are few
/// ([`cache_band_rows`]), else triangle by triangle over the target.
pub(crate) fn draw_runs<S: FragmentShader + ?Sized>(
    geometry: &Runs<'_>,
    backend: &dyn TriangleRasterizer,
    pass: Pass<'_, S>,
    target: &mut RenderTarget,
) -> WorkCounters {
    let triangles: usize = geometry.runs.iter().map(|r| r.setups.len()).sum();
    // A few triangles: every band walks all of them, and the pixels they
    // share are drawn while the band is in the cache. Otherwise one band,
    // the whole target.
    let rows = if triangles <= BAND_BY_BAND_TRIANGLES {
        cache_band_rows(target.width())
    } else {
        target.height()
    };
    let mut work = WorkCounters::default();
    for rows in target.bands_clearing(rows, pass.clear) {
        let viewport = rows.rect();
        let mut stage = pass.stage(rows, geometry.shaded);
        for run in &geometry.runs {
            stage.use_triangles(run.triangles);
            work.add(&backend.rasterize(run.setups, viewport, &mut stage));
        }
        stage.finish();
    }
    work.primitives = triangles as u64;
    work
}

/// Rasterizes `geometry` with `backend` into `target` through the shared
/// fragment stage, band by band in parallel; bit-identical to
/// [`pipeline::draw`](fn@crate::geometry::pipeline::draw).
pub fn draw_binned<S: FragmentShader + ?Sized>(
    geometry: &Geometry,
    backend: &dyn TriangleRasterizer,
    shader: &S,
    depth: DepthState,
    interpolation: Interpolation,
    target: &mut RenderTarget,
) -> WorkCounters {
    draw_binned_clearing(
        geometry,
        backend,
        shader,
        depth,
        interpolation,
        Clear::NOTHING,
        target,
    )
}

/// [`draw_binned`], with the target cleared by `clear` first, row by row
/// as the bands reach it ([`draw_clearing`]'s clear on rayon's threads):
/// the same bits as [`draw_clearing`].
pub fn draw_binned_clearing<S: FragmentShader + ?Sized>(
    geometry: &Geometry,
    backend: &dyn TriangleRasterizer,
    shader: &S,
    depth: DepthState,
    interpolation: Interpolation,
    clear: Clear,
    target: &mut RenderTarget,
) -> WorkCounters {
    let pass = Pass {
        shader,
        depth,
        interpolation,
        clear,
        blend: Blend::REPLACE,
    };
    draw_runs_binned(&geometry.runs(), backend, pass, target)
}

/// [`draw_binned`] of triangles in runs, with the bins of the pipeline's
/// parts when they are those of this draw.
pub(crate) fn draw_runs_binned<S: FragmentShader + ?Sized>(
    geometry: &Runs<'_>,
    backend: &dyn TriangleRasterizer,
    pass: Pass<'_, S>,
    target: &mut RenderTarget,
) -> WorkCounters {
    let threads = rayon::current_num_threads();
    if threads == 1 {
        return draw_runs(geometry, backend, pass, target);
    }
    let (width, height) = (target.width(), target.height());
    let runs = &geometry.runs;
    let bands = Bands::for_threads(height, threads);
    // Per chunk in id order: its run, and per band its triangles there.
    let computed: Bins;
    let chunks: Vec<(usize, &[Vec<u32>])> = match &geometry.bins {
        Some(b) if (b.bands, b.viewport) == (bands, Viewport { width, height }) => {
            b.per_run.iter().copied().enumerate().collect()
        }
        _ => {
            let setups: Vec<&[TriangleSetup]> = runs.iter().map(|r| r.setups).collect();
            computed = Bins::new(&setups, width, height, bands);
            computed.chunks.iter().map(|(r, b)| (*r, &b[..])).collect()
        }
    };
    // The bands in order of their triangle counts, most first, each
    // thread taking the next when it is done: the last band drawn is a
    // small one, so the threads end together; taken in row order, as
    // rayon splits a range, one thread was left drawing alone at the end
    // (docs/performance-log.md, "2026-12-03, `4dfac5a` to `1669cc6`"). A
    // band's pixels are its own, so the order changes no bit.
    let triangles_in =
        |b: usize| -> usize { chunks.iter().map(|(_, per_band)| per_band[b].len()).sum() };
    let mut largest_first: Vec<(usize, TargetRows<'_>)> = target
        .bands_clearing(bands.rows(), pass.clear)
        .into_iter()
        .enumerate()
        .collect();
    largest_first.sort_by_cached_key(|(b, _)| std::cmp::Reverse(triangles_in(*b)));
    let mut work = largest_first
        .into_iter()
        .par_bridge()
        .map(|(b, rows)| {
            let viewport = rows.rect();
            let mut stage = pass.stage(rows, geometry.shaded);
            let mut work = WorkCounters::default();
            for &(run, per_band) in &chunks {
                if !per_band[b].is_empty() {
                    let run = runs[run];
                    stage.use_triangles(run.triangles);
                    stage.use_selection(&per_band[b]);
                    let selection = TriangleSelection::indexed(run.setups, &per_band[b]);
                    work.add(&backend.rasterize_selection(selection, viewport, &mut stage));
                }
            }
            stage.finish();
            work
        })
        .reduce(WorkCounters::default, |mut a, b| {
            a.add(&b);
            a
        });
    work.primitives = runs.iter().map(|r| r.setups.len() as u64).sum();
    work
}
