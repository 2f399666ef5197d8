//! Fragments and the sink every back-end writes them into.
//!
//! A **fragment** is a candidate pixel (seed 002): a back-end decides only
//! *which* pixels a primitive covers, and hands each one to a
//! [`FragmentSink`]. Triangle fragments carry the exact integer edge values
//! at the pixel's sample point, so whatever receives them (the shared
//! [`FragmentStage`](crate::stage::FragmentStage), a test, a trace) computes
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
    /// The triangle's id ([`TriangleSetup::id`](crate::edge::TriangleSetup::id)).
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

/// Receives fragments from rasterizer back-ends.
pub trait FragmentSink {
    /// One covered pixel of a triangle.
    fn triangle_fragment(&mut self, fragment: &TriangleFragment);
    /// One pixel of a line.
    fn line_fragment(&mut self, fragment: &LineFragment);
}

/// Work a back-end did, for comparing algorithms.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub struct WorkCounters {
    /// Primitives that reached the back-end's set-up.
    pub primitives: u64,
    /// Samples (pixel centres) whose inside test was evaluated.
    pub samples_tested: u64,
    /// Fragments emitted.
    pub fragments: u64,
    /// Rows (scanline) or blocks (tiled) visited.
    pub spans: u64,
}

impl WorkCounters {
    /// Adds another set of counters to this one.
    pub fn add(&mut self, other: &WorkCounters) {
        self.primitives += other.primitives;
        self.samples_tested += other.samples_tested;
        self.fragments += other.fragments;
        self.spans += other.spans;
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
