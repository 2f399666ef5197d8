//! Generators and helpers shared by the integration tests: proptest
//! strategies, the command-line runner, and the note a test gives when a
//! part it needs (a browser, a Python package, Mesa) is not installed.
#![allow(dead_code)]

use std::process::{Command, Output};

/// Runs the `rasterlab` binary with `args` and returns what it did.
pub fn rasterlab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rasterlab"))
        .args(args)
        .output()
        .expect("the binary runs")
}

/// Reports that `test` did not run because `part` is missing. The note
/// goes straight to standard error, past the test harness's capture, so
/// it shows in every run; when the environment variable `required` is set
/// (as `.ci/run` sets it after installing the part) a missing part fails
/// the test instead.
pub fn part_missing(test: &str, part: &str, required: &str) {
    use std::io::Write;
    assert!(
        std::env::var_os(required).is_none(),
        "{required} is set but {part} was not found: {test} cannot run"
    );
    let note = format!(
        "\nNOT RUN: {test}: {part} was not found (set {required}=1 to make this a failure)\n"
    );
    let _ = std::io::stderr().lock().write_all(note.as_bytes());
}

use proptest::prelude::*;
use rasterlab::geometry::{setup_triangles, Polygon};
use rasterlab::raster::triangle::naive::Naive;
use rasterlab::raster::triangle::TriangleRasterizer;
use rasterlab::raster::{
    triangle_backends, FillRule, FixedPoint, FragmentList, PixelRect, TriangleSetup,
};

/// Side of the square target used by the property tests.
pub const SIZE: u32 = 40;

/// Grid a coordinate is rounded to: whole pixels and half pixels (pixel
/// centres) make ties with sample points common, 1/256 is the snapping grid
/// itself, and `None` leaves arbitrary floats that snapping rounds.
pub fn quantum() -> impl Strategy<Value = Option<f32>> {
    prop_oneof![
        Just(Some(1.0)),
        Just(Some(0.5)),
        Just(Some(1.0 / 256.0)),
        Just(None),
    ]
}

pub fn quantize(v: f32, q: Option<f32>) -> f32 {
    match q {
        Some(q) => (v / q).round() * q,
        None => v,
    }
}

pub fn snap(x: f32, y: f32) -> FixedPoint {
    FixedPoint::snap(x, y).expect("test coordinates lie inside the guard band")
}

/// A point in `[lo, hi)^2`, rounded to `q`.
pub fn point(lo: f32, hi: f32, q: Option<f32>) -> impl Strategy<Value = FixedPoint> + Clone {
    (lo..hi, lo..hi).prop_map(move |(x, y)| snap(quantize(x, q), quantize(y, q)))
}

/// A triangle soup of 1 to `max` triangles around (and partly outside) the target.
pub fn triangle_soup(max: usize) -> impl Strategy<Value = Vec<[FixedPoint; 3]>> {
    quantum().prop_flat_map(move |q| {
        let p = point(-8.0, SIZE as f32 + 8.0, q);
        proptest::collection::vec([p.clone(), p.clone(), p], 1..=max)
    })
}

/// A star-shaped ring around `c`: `n` vertices at jittered, increasing angles.
fn star_ring(
    c: (f32, f32),
    n: usize,
    radii: (f32, f32),
    q: Option<f32>,
) -> impl Strategy<Value = Vec<FixedPoint>> {
    proptest::collection::vec((0.0f32..0.8, radii.0..radii.1), n).prop_map(move |v| {
        v.iter()
            .enumerate()
            .map(|(i, &(jitter, r))| {
                let a = (i as f32 + jitter) / n as f32 * std::f32::consts::TAU;
                snap(
                    quantize(c.0 + r * a.cos(), q),
                    quantize(c.1 + r * a.sin(), q),
                )
            })
            .collect()
    })
}

/// A random simple polygon, star-shaped, with or without a hole, partly
/// outside the target at times, with vertices on or off the subpixel grid.
pub fn polygon() -> impl Strategy<Value = Polygon> {
    (
        quantum(),
        (4.0f32..36.0, 4.0f32..36.0),
        3usize..=11,
        proptest::option::of(3usize..=6),
    )
        .prop_flat_map(|(q, c, n, hole)| {
            let outer = star_ring(c, n, (9.0, 24.0), q);
            let hole = match hole {
                Some(m) => star_ring(c, m, (2.0, 7.0), q).prop_map(Some).boxed(),
                None => Just(None).boxed(),
            };
            (outer, hole)
        })
        .prop_filter_map("snapping made the polygon non-simple", |(outer, hole)| {
            Polygon::new(outer, hole.into_iter().collect()).ok()
        })
}

/// The triangles of a polygon's constrained Delaunay triangulation.
pub fn triangulation(poly: &Polygon) -> Vec<[FixedPoint; 3]> {
    poly.triangulate()
        .expect("a validated simple polygon triangulates")
}

pub fn viewport() -> PixelRect {
    PixelRect::of_target(SIZE, SIZE)
}

/// Every fragment of a back-end, in emission order.
pub fn fragments(
    backend: &dyn TriangleRasterizer,
    triangles: &[[FixedPoint; 3]],
    rule: FillRule,
) -> FragmentList {
    let setups: Vec<TriangleSetup> = setup_triangles(triangles, rule);
    let mut list = FragmentList::default();
    backend.rasterize(&setups, viewport(), &mut list);
    list
}

/// Asserts every back-end's fragments equal `naive`'s, as sorted lists,
/// and that each back-end emits each pixel's fragments in ascending
/// triangle order (what makes the shared stage's output identical).
pub fn assert_all_match_naive(triangles: &[[FixedPoint; 3]]) {
    for rule in FillRule::ALL {
        let reference = fragments(&Naive, triangles, rule).sorted_triangle_fragments();
        for backend in triangle_backends() {
            let list = fragments(*backend, triangles, rule);
            assert_eq!(
                list.sorted_triangle_fragments(),
                reference,
                "{} differs from naive under {rule} on {triangles:?}",
                backend.name()
            );
            let mut last = std::collections::HashMap::new();
            for f in &list.triangles {
                if let Some(prev) = last.insert((f.x, f.y), f.triangle) {
                    assert!(prev < f.triangle, "{}: pixel order", backend.name());
                }
            }
        }
    }
}

/// How many fragments each pixel received.
pub fn coverage_counts(list: &FragmentList) -> Vec<u32> {
    let mut counts = vec![0u32; (SIZE * SIZE) as usize];
    for f in &list.triangles {
        counts[(f.y * SIZE + f.x) as usize] += 1;
    }
    counts
}

/// Headless Chromium for the browser tests: `$RASTERLAB_CHROMIUM`, or
/// `chromium` or `chromium-browser` on the `PATH`.
pub fn chromium() -> Option<std::path::PathBuf> {
    if let Some(path) = std::env::var_os("RASTERLAB_CHROMIUM") {
        return Some(std::path::PathBuf::from(path));
    }
    ["chromium", "chromium-browser"].iter().find_map(|name| {
        std::env::var_os("PATH").and_then(|paths| {
            std::env::split_paths(&paths)
                .map(|dir| dir.join(name))
                .find(|p| p.is_file())
        })
    })
}

/// The flags every headless Chromium run of the tests starts with: no
/// sandbox (root), no GPU, and no background connections, which this
/// machine's closed network would refuse.
pub const HEADLESS: [&str; 8] = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
];

/// A proptest configuration of `cases` cases that keeps the failures it
/// finds in `file` (under `tests/proptest-regressions/`, beside the named
/// regression tests of `tests/regressions.rs`), where every later run
/// tries them first.
pub fn proptest_config(cases: u32, file: &'static str) -> proptest::test_runner::Config {
    proptest::test_runner::Config {
        failure_persistence: Some(Box::new(
            proptest::test_runner::FileFailurePersistence::Direct(file),
        )),
        ..proptest::test_runner::Config::with_cases(cases)
    }
}
