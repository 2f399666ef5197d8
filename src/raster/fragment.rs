//! Fragments and the sink every back-end writes them into.
//!
//! A **fragment** is a candidate pixel (the rasterization slides): a back-end decides only
//! *which* pixels a primitive covers, and hands each one to a
//! [`FragmentSink`]. Triangle fragments carry the exact integer edge values
//! at the pixel's sample point, so whatever receives them (the shared
//! [`FragmentStage`](crate::raster::stage::FragmentStage), a test, a trace) computes
//! barycentrics, depth and colour the same way whichever back-end produced
//! them. Two back-ends that emit the same fragments therefore produce
//! bit-identical images.

/// A pixel covered by a triangle.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct TriangleFragment {
    /// Pixel column, inside the target.
    pub x: u32,
    /// Pixel row, inside the target.
    pub y: u32,
    /// The triangle's id ([`TriangleSetup::id`](crate::raster::edge::TriangleSetup::id)).
    pub triangle: u32,
    /// The three edge values at the pixel's sample point (inside-positive,
    /// edge `i` opposite vertex `i`).
    pub edges: [i64; 3],
}

/// A pixel drawn by a line back-end.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct LineFragment {
    /// Pixel column, inside the target.
    pub x: u32,
    /// Pixel row, inside the target.
    pub y: u32,
    /// The segment's index in the draw.
    pub line: u32,
    /// How much of the pixel the line covers, in `[0, 1]`: `1.0` for
    /// aliased back-ends, Xiaolin Wu's intensity for `wu`.
    pub coverage: f32,
}

/// A run of covered pixels of one triangle on one row: pixels `x0..=x1` of
/// row `y`. Triangles are convex, so the covered pixels of a row are always
/// one run; back-ends that know the run hand it over whole.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct TriangleSpan {
    /// Pixel row.
    pub y: u32,
    /// First pixel column.
    pub x0: u32,
    /// Last pixel column (inclusive, `>= x0`).
    pub x1: u32,
    /// The triangle's id.
    pub triangle: u32,
    /// The edge values at pixel `x0`'s sample point.
    pub edges: [i64; 3],
    /// What the edge values gain per pixel to the right.
    pub step: [i64; 3],
}

impl TriangleSpan {
    /// The span's fragments, left to right.
    pub fn fragments(&self) -> impl Iterator<Item = TriangleFragment> + '_ {
        (self.x0..=self.x1).scan(self.edges, |e, x| {
            let f = TriangleFragment {
                x,
                y: self.y,
                triangle: self.triangle,
                edges: *e,
            };
            *e = [0, 1, 2].map(|k| e[k] + self.step[k]);
            Some(f)
        })
    }
}

/// Receives fragments from rasterizer back-ends.
pub trait FragmentSink {
    /// One covered pixel of a triangle.
    fn triangle_fragment(&mut self, fragment: &TriangleFragment);
    /// A run of covered pixels of a triangle on one row: the same as each
    /// of [`TriangleSpan::fragments`] in turn, which is what the default
    /// does; sinks override it to do per-span work once.
    fn triangle_span(&mut self, span: &TriangleSpan) {
        for f in span.fragments() {
            self.triangle_fragment(&f);
        }
    }
    /// One pixel of a line.
    fn line_fragment(&mut self, fragment: &LineFragment);
    /// Pixels of lines, in the order they were drawn: the same as each of
    /// them to [`line_fragment`](Self::line_fragment) in turn, which is
    /// what the default does. Line back-ends hand over a segment's pixels
    /// this way, and the stage writes them in one loop instead of one
    /// call each.
    fn line_fragments(&mut self, fragments: &[LineFragment]) {
        for f in fragments {
            self.line_fragment(f);
        }
    }
}

/// Work a back-end did, for comparing algorithms.
///
/// A draw on several threads cuts the target into bands of rows and gives
/// each band the triangles that reach it; the counters of the bands are
/// added. `samples_tested` and `fragments` are the algorithm's and the
/// same for any number of threads; `primitives` and `spans` also count the
/// binning's extra work: a triangle reaching two bands is set up twice,
/// and a row of blocks cut by a band's edge is classified in both bands.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct WorkCounters {
    /// Primitives that reached the back-end's set-up (once per band they
    /// reach, on several threads).
    pub primitives: u64,
    /// Samples (pixel centres) whose inside test was evaluated; the same
    /// for any number of threads.
    pub samples_tested: u64,
    /// Fragments emitted.
    pub fragments: u64,
    /// Rows (scanline) or blocks (tiled) visited (on several threads, a
    /// block row cut by a band's edge once per band).
    pub spans: u64,
    /// Helper pixels: where a texture's derivatives are taken in 2x2 quads
    /// ([`Derivatives::Quad`](crate::raster::Derivatives)), the pixels of
    /// the quads each triangle's fragments touch that the triangle does
    /// not cover, shaded only to take differences (quad overshading; see
    /// [`quad_helpers`](crate::raster::quad_helpers)). 0 otherwise.
    pub helpers: u64,
}

impl WorkCounters {
    /// Adds another set of counters to this one.
    pub fn add(&mut self, other: &WorkCounters) {
        self.primitives += other.primitives;
        self.samples_tested += other.samples_tested;
        self.fragments += other.fragments;
        self.spans += other.spans;
        self.helpers += other.helpers;
    }

    /// The share of the shaded pixels (fragments and helpers) that are
    /// helpers: 0 without quads, 3/4 for triangles of one pixel each.
    pub fn helper_share(&self) -> f64 {
        let shaded = self.fragments + self.helpers;
        if shaded == 0 {
            0.0
        } else {
            self.helpers as f64 / shaded as f64
        }
    }

    /// Samples tested per fragment emitted (0 when nothing was emitted).
    pub fn tests_per_fragment(&self) -> f64 {
        if self.fragments == 0 {
            0.0
        } else {
            self.samples_tested as f64 / self.fragments as f64
        }
    }
}

/// A sink that keeps every fragment, in emission order.
#[derive(Clone, Debug, Default)]
pub struct FragmentList {
    /// Triangle fragments, in emission order.
    pub triangles: Vec<TriangleFragment>,
    /// Line fragments, in emission order.
    pub lines: Vec<LineFragment>,
}

impl FragmentSink for FragmentList {
    fn triangle_fragment(&mut self, fragment: &TriangleFragment) {
        self.triangles.push(*fragment);
    }
    fn line_fragment(&mut self, fragment: &LineFragment) {
        self.lines.push(*fragment);
    }
}

impl FragmentList {
    /// The triangle fragments sorted by (triangle, row, column): the
    /// canonical order for comparing back-ends that visit pixels in
    /// different orders.
    pub fn sorted_triangle_fragments(&self) -> Vec<TriangleFragment> {
        let mut v = self.triangles.clone();
        v.sort_unstable_by_key(|f| (f.triangle, f.y, f.x));
        v
    }
}
