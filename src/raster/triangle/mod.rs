//! Triangle rasterizer back-ends.
//!
//! Each back-end is a unit struct named after its algorithm that states
//! its facts once ([`TriangleAlgorithm::DESCRIPTOR`]) and draws one
//! triangle ([`TriangleAlgorithm::draw_triangle`]); the loop over a draw's
//! triangles is written once, and makes every algorithm an object-safe
//! [`TriangleRasterizer`], so tools and tests loop over
//! [`crate::raster::triangle_backends`] by name. A back-end only decides
//! *which* pixels each triangle covers; every one of them applies the same
//! exact inside test ([`TriangleSetup::inside`](crate::raster::edge::TriangleSetup::inside)) to the same sample points,
//! so they all emit the same fragments, and differ only in how many samples
//! they test and in what order they visit them.
//!
//! | back-end | idea | tests per pixel |
//! |---|---|---|
//! | [`naive`] | the course pseudocode: every pixel, every triangle | `triangles` |
//! | [`bbox`] | only pixels in the triangle's bounding box, edge functions evaluated directly | 1 inside the box |
//! | [`scanline`] | per row, solve exactly where the row enters and leaves the triangle | 0 |
//! | [`incremental`] | bounding box, edge functions stepped by additions (Pineda) | 1 inside the box |
//! | [`tiled`] | 8x8 blocks, trivial reject / accept from the corners, per-pixel tests only on edges | 1 in straddling blocks, 0 elsewhere |
//!
//! Every back-end emits, for each pixel, that pixel's fragments in
//! ascending triangle order, so the shared stage's depth test resolves ties
//! the same way whichever back-end ran.

pub mod bbox;
pub mod incremental;
pub mod naive;
pub mod scanline;
pub mod tiled;

use crate::raster::descriptor::Descriptor;
use crate::raster::edge::{PixelRect, TriangleSetup};
use crate::raster::fragment::{FragmentSink, TriangleFragment, TriangleSpan, WorkCounters};

/// A triangle back-end's facts ([`Descriptor`] of a [`TriangleWalk`]).
pub type TriangleDescriptor = Descriptor<TriangleWalk>;

/// How a triangle back-end walks the pixels: what its step-by-step trace
/// ([`crate::teaching::trace_triangle`]) is headed with.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum TriangleWalk {
    /// Every pixel of the target, each tested on its own (the course's
    /// per-pixel loop).
    EveryPixel,
    /// Every pixel of the triangle's bounding box, each tested on its own.
    BoundingBox,
    /// Row by row, between the edges active on the row.
    Scanline,
    /// Pixel by pixel, the edge values stepped by adding constants.
    IncrementalEdges,
    /// Blocks classified as a whole, partial blocks pixel by pixel.
    Blocks,
    /// A walk of its own, said in a few words.
    Own(&'static str),
}

/// What the corner test says about a block of pixels (a hierarchical
/// walk's step).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum BlockClass {
    /// No sample of the block is inside.
    Outside,
    /// Every sample of the block is inside.
    Inside,
    /// The block straddles an edge: test each sample.
    Partial,
}

/// What one edge says about a row's span, solved without testing a pixel
/// (a scanline walk's step).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum Bound {
    /// A left edge: the span starts at this column.
    First(i64),
    /// A right edge: the span ends at this column.
    Last(i64),
    /// A horizontal edge the row's samples pass: every column.
    All,
    /// A horizontal edge the row's samples fail: no column.
    None,
}

/// The steps of a walk, as a back-end reports them while it draws: what
/// a trace records. Every method does nothing by default; the step for
/// one triangle is generic over its observer, so with [`Unobserved`] (how
/// every draw runs) the calls compile to nothing.
pub trait WalkObserver {
    /// Pixel `(x, y)`'s sample was tested: its edge values and whether it
    /// is inside.
    #[inline(always)]
    fn sample(&mut self, x: i64, y: i64, edges: [i64; 3], inside: bool) {
        let _ = (x, y, edges, inside);
    }
    /// Row `y`'s walk stops after pixel `x` (the row's span is behind it).
    #[inline(always)]
    fn row_stops(&mut self, y: i64, x: i64) {
        let _ = (y, x);
    }
    /// Edge `edge` bounds row `y`'s span so.
    #[inline(always)]
    fn crossing(&mut self, y: i64, edge: usize, bound: Bound) {
        let _ = (y, edge, bound);
    }
    /// Row `y`'s span is `first..=last` (empty when `last < first`).
    #[inline(always)]
    fn span(&mut self, y: i64, first: i64, last: i64) {
        let _ = (y, first, last);
    }
    /// The pixels of `rect` were classified as a whole.
    #[inline(always)]
    fn block(&mut self, rect: PixelRect, class: BlockClass) {
        let _ = (rect, class);
    }
}

/// The observer of an untraced draw: it keeps nothing.
#[derive(Copy, Clone, Debug, Default)]
pub struct Unobserved;

impl WalkObserver for Unobserved {}

/// One step of a walk, as recorded ([`WalkObserver`]'s calls as data).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum WalkStep {
    /// [`WalkObserver::sample`].
    Sample {
        /// Column.
        x: i64,
        /// Row.
        y: i64,
        /// Edge values at the sample.
        edges: [i64; 3],
        /// The verdict.
        inside: bool,
    },
    /// [`WalkObserver::row_stops`].
    RowStops {
        /// Row.
        y: i64,
        /// Last column tested.
        x: i64,
    },
    /// [`WalkObserver::crossing`].
    Crossing {
        /// Row.
        y: i64,
        /// The edge (opposite vertex `edge`).
        edge: usize,
        /// What it says of the span.
        bound: Bound,
    },
    /// [`WalkObserver::span`].
    Span {
        /// Row.
        y: i64,
        /// First column.
        first: i64,
        /// Last column (empty span when below `first`).
        last: i64,
    },
    /// [`WalkObserver::block`].
    Block {
        /// The pixels classified.
        rect: PixelRect,
        /// Their class.
        class: BlockClass,
    },
}

/// A recording: every step, in the order the walk made them.
impl WalkObserver for Vec<WalkStep> {
    fn sample(&mut self, x: i64, y: i64, edges: [i64; 3], inside: bool) {
        self.push(WalkStep::Sample {
            x,
            y,
            edges,
            inside,
        });
    }
    fn row_stops(&mut self, y: i64, x: i64) {
        self.push(WalkStep::RowStops { y, x });
    }
    fn crossing(&mut self, y: i64, edge: usize, bound: Bound) {
        self.push(WalkStep::Crossing { y, edge, bound });
    }
    fn span(&mut self, y: i64, first: i64, last: i64) {
        self.push(WalkStep::Span { y, first, last });
    }
    fn block(&mut self, rect: PixelRect, class: BlockClass) {
        self.push(WalkStep::Block { rect, class });
    }
}

/// One triangle's walk in progress: what a back-end reports to as it
/// draws. It holds the triangle, the sink its fragments go to, the work
/// counters and the observer, so that a back-end says each thing once:
/// [`test`](Self::test) a sample (counted, and recorded by a trace),
/// emit a [`fragment`](Self::fragment) or a [`span`](Self::span) (counted,
/// and handed to the sink), and report a row's
/// [`crossing`](Self::crossing) or a [`block`](Self::block) it classified.
///
/// The observer is a type parameter: with [`Unobserved`], how every draw
/// runs, the reports compile to nothing but the counters.
pub struct Walk<'a, O: WalkObserver = Unobserved> {
    triangle: &'a TriangleSetup,
    sink: &'a mut dyn FragmentSink,
    work: &'a mut WorkCounters,
    observer: &'a mut O,
}

impl<'a, O: WalkObserver> Walk<'a, O> {
    /// The walk of `triangle` into `sink`, counted in `work` and reported
    /// to `observer`; it counts the triangle as one primitive.
    #[inline]
    pub fn new(
        triangle: &'a TriangleSetup,
        sink: &'a mut dyn FragmentSink,
        work: &'a mut WorkCounters,
        observer: &'a mut O,
    ) -> Self {
        work.primitives += 1;
        Walk {
            triangle,
            sink,
            work,
            observer,
        }
    }

    /// The triangle walked.
    #[inline(always)]
    pub fn triangle(&self) -> &'a TriangleSetup {
        self.triangle
    }

    /// The inside test of pixel `(x, y)`'s sample, whose edge values are
    /// `edges` (the fill rule's tie-breaking included): counted as one
    /// sample tested, and reported to the observer.
    #[inline(always)]
    pub fn test(&mut self, x: i64, y: i64, edges: [i64; 3]) -> bool {
        self.work.samples_tested += 1;
        let inside = self.triangle.inside(edges);
        self.observer.sample(x, y, edges, inside);
        inside
    }

    /// Emits pixel `(x, y)` (inside the viewport) as a fragment, with the
    /// edge values `edges` there.
    #[inline(always)]
    pub fn fragment(&mut self, x: i64, y: i64, edges: [i64; 3]) {
        self.work.fragments += 1;
        emit(self.sink, self.triangle, x, y, edges);
    }

    /// Emits pixels `first..=last` of row `y` (inside the viewport,
    /// `first <= last`) as one span, given the edge values `edges` at
    /// `first`; a single pixel (most rows of a small triangle) as a plain
    /// fragment, which costs the stage less.
    #[inline(always)]
    pub fn span(&mut self, y: i64, first: i64, last: i64, edges: [i64; 3]) {
        self.work.fragments += (last - first + 1) as u64;
        if first == last {
            emit(self.sink, self.triangle, first, y, edges);
            return;
        }
        self.sink.triangle_span(&TriangleSpan {
            y: y as u32,
            x0: first as u32,
            x1: last as u32,
            triangle: self.triangle.id,
            edges,
            step: self.triangle.pixel_steps().0,
        });
    }

    /// One row (a scanline walk) or one block or stretch of blocks (a
    /// hierarchical walk) visited: the counters' `spans`.
    #[inline(always)]
    pub fn visit(&mut self) {
        self.work.spans += 1;
    }

    /// Row `y`'s test stops after pixel `x`: the row's run of inside
    /// pixels is behind it.
    #[inline(always)]
    pub fn row_stops(&mut self, y: i64, x: i64) {
        self.observer.row_stops(y, x);
    }

    /// Edge `edge` bounds row `y`'s span so (solved, not tested).
    #[inline(always)]
    pub fn crossing(&mut self, y: i64, edge: usize, bound: Bound) {
        self.observer.crossing(y, edge, bound);
    }

    /// Row `y`'s span, as its crossings solved it, is `first..=last`
    /// (empty when `last < first`).
    #[inline(always)]
    pub fn row_span(&mut self, y: i64, first: i64, last: i64) {
        self.observer.span(y, first, last);
    }

    /// The pixels of `rect` were classified as a whole.
    #[inline(always)]
    pub fn block(&mut self, rect: PixelRect, class: BlockClass) {
        self.observer.block(rect, class);
    }
}

/// A triangle rasterization algorithm, as its file writes it: its facts
/// and its walk over one triangle's pixels. Counting, recording and
/// emitting are the [`Walk`]'s, and the loop over the triangles a draw
/// selects is provided once, by the [`TriangleRasterizer`] every
/// algorithm is: a new back-end is its walk and one descriptor.
///
/// ```
/// use rasterlab::raster::{CostClass, PixelRect, Role, TriangleSetup};
/// use rasterlab::raster::triangle::{TriangleAlgorithm, TriangleDescriptor, TriangleRasterizer, TriangleWalk, Walk, WalkObserver};
///
/// /// The bounding box, walked bottom row first.
/// struct BottomUp;
///
/// impl TriangleAlgorithm for BottomUp {
///     const DESCRIPTOR: TriangleDescriptor = TriangleDescriptor {
///         name: "bottom-up",
///         description: "the bounding box, bottom row first",
///         walk: TriangleWalk::Own("bounding box, bottom row first"),
///         role: Role::Alternative,
///         cost: CostClass::FollowsSize,
///     };
///     fn draw_triangle<O: WalkObserver>(&self, t: &TriangleSetup, viewport: PixelRect, walk: &mut Walk<O>) {
///         let r = t.bounds_within(viewport);
///         for y in (r.y0..=r.y1).rev() {
///             for x in r.x0..=r.x1 {
///                 let e = t.edge_values_at_pixel(x, y);
///                 if walk.test(x, y, e) {
///                     walk.fragment(x, y, e);
///                 }
///             }
///         }
///     }
/// }
/// assert_eq!(BottomUp.name(), "bottom-up");
/// // Its trace is the recording of its walk: the bottom row first.
/// let t = TriangleSetup::new(0, [(0.5, 0.5), (4.5, 0.5), (0.5, 3.5)]
///     .map(|(x, y)| rasterlab::raster::FixedPoint::snap_f64(x, y).unwrap()),
///     rasterlab::raster::FillRule::TopLeft).unwrap();
/// let (steps, work) = BottomUp.record(&t, PixelRect::of_target(6, 4), &mut rasterlab::raster::FragmentList::default());
/// assert!(matches!(steps[0], rasterlab::raster::triangle::WalkStep::Sample { y: 3, .. }));
/// // Every sample the walk tested was counted once.
/// assert_eq!(work.samples_tested, 20);
/// ```
pub trait TriangleAlgorithm: Send + Sync {
    /// The back-end's name, description, walk, role and cost class.
    const DESCRIPTOR: TriangleDescriptor;

    /// Walks triangle `t` (the walk's own) over the pixels of `viewport`:
    /// tests samples, emits every fragment whose pixel lies in `viewport`
    /// (for each pixel once: one call per triangle keeps each pixel's
    /// fragments in triangle order), and reports its rows and blocks, all
    /// through `walk`.
    fn draw_triangle<O: WalkObserver>(
        &self,
        t: &TriangleSetup,
        viewport: PixelRect,
        walk: &mut Walk<O>,
    );
}

/// A triangle back-end, as tools hold it (`&dyn TriangleRasterizer`):
/// every [`TriangleAlgorithm`] is one.
pub trait TriangleRasterizer: Send + Sync {
    /// The back-end's facts.
    fn descriptor(&self) -> TriangleDescriptor;

    /// Short name used on the command line (the descriptor's).
    fn name(&self) -> &'static str {
        self.descriptor().name
    }

    /// One-line description (the descriptor's).
    fn description(&self) -> &'static str {
        self.descriptor().description
    }

    /// Emits every fragment of the selected triangles whose pixel lies in
    /// `viewport`, and returns the work done.
    fn rasterize_selection(
        &self,
        triangles: TriangleSelection<'_>,
        viewport: PixelRect,
        sink: &mut dyn FragmentSink,
    ) -> WorkCounters;

    /// Draws triangle `t` into `sink` as [`Self::rasterize`] does,
    /// recording every step of the walk: what its trace shows.
    fn record(
        &self,
        t: &TriangleSetup,
        viewport: PixelRect,
        sink: &mut dyn FragmentSink,
    ) -> (Vec<WalkStep>, WorkCounters);

    /// Emits every fragment of `triangles` whose pixel lies in `viewport`,
    /// and returns the work done.
    fn rasterize(
        &self,
        triangles: &[TriangleSetup],
        viewport: PixelRect,
        sink: &mut dyn FragmentSink,
    ) -> WorkCounters {
        self.rasterize_selection(TriangleSelection::all(triangles), viewport, sink)
    }
}

impl<A: TriangleAlgorithm> TriangleRasterizer for A {
    fn descriptor(&self) -> TriangleDescriptor {
        A::DESCRIPTOR
    }

    /// The loop every back-end shares: each selected triangle, in order,
    /// through the algorithm's step.
    fn rasterize_selection(
        &self,
        triangles: TriangleSelection<'_>,
        viewport: PixelRect,
        sink: &mut dyn FragmentSink,
    ) -> WorkCounters {
        let mut work = WorkCounters::default();
        for t in triangles.iter() {
            self.draw_triangle(
                t,
                viewport,
                &mut Walk::new(t, sink, &mut work, &mut Unobserved),
            );
        }
        work
    }

    fn record(
        &self,
        t: &TriangleSetup,
        viewport: PixelRect,
        sink: &mut dyn FragmentSink,
    ) -> (Vec<WalkStep>, WorkCounters) {
        let (mut steps, mut work) = (Vec::new(), WorkCounters::default());
        self.draw_triangle(t, viewport, &mut Walk::new(t, sink, &mut work, &mut steps));
        (steps, work)
    }
}

/// The triangles a back-end is asked to draw: all of a slice, or those at
/// some indices of it (a bin), in the order given.
#[derive(Copy, Clone, Debug)]
pub struct TriangleSelection<'a> {
    setups: &'a [TriangleSetup],
    indices: Option<&'a [u32]>,
}

/// How many triangles ahead an indexed selection asks for the set-up of.
const SETUP_PREFETCH_AHEAD: usize = 4;

impl<'a> TriangleSelection<'a> {
    /// Every triangle of `setups`.
    pub fn all(setups: &'a [TriangleSetup]) -> Self {
        TriangleSelection {
            setups,
            indices: None,
        }
    }

    /// The triangles of `setups` at `indices`, in that order.
    pub fn indexed(setups: &'a [TriangleSetup], indices: &'a [u32]) -> Self {
        TriangleSelection {
            setups,
            indices: Some(indices),
        }
    }

    /// The number of triangles selected.
    pub fn len(&self) -> usize {
        self.indices.map_or(self.setups.len(), <[u32]>::len)
    }

    /// True when nothing is selected.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The selected triangles, in order.
    pub fn iter(&self) -> impl Iterator<Item = &'a TriangleSetup> + 'a {
        let (setups, indices) = (self.setups, self.indices);
        let all = indices.is_none().then(|| setups.iter());
        // Indexed, the set-ups are read with gaps the hardware's stride
        // prefetcher does not follow: each is asked for a few ahead.
        let some = indices.map(|indices| {
            indices.iter().enumerate().map(move |(j, &i)| {
                let ahead = indices.get(j + SETUP_PREFETCH_AHEAD);
                if let Some(setup) = ahead.and_then(|&a| setups.get(a as usize)) {
                    crate::raster::vector::prefetch_all(setup);
                }
                &setups[i as usize]
            })
        });
        all.into_iter().flatten().chain(some.into_iter().flatten())
    }
}

/// Hands one fragment of `triangle` at pixel `(x, y)` (inside the
/// viewport) with the edge values `edges` there to `sink`.
#[inline(always)]
fn emit(sink: &mut dyn FragmentSink, triangle: &TriangleSetup, x: i64, y: i64, edges: [i64; 3]) {
    sink.triangle_fragment(&TriangleFragment {
        x: x as u32,
        y: y as u32,
        triangle: triangle.id,
        edges,
    });
}
