//! Anti-aliasing compared: each way of estimating a pixel's coverage, its
//! error against the exact area and its cost, on the same triangles, with
//! tiny-skia's anti-aliased fill beside them.
//!
//! ```text
//! cargo bench --bench antialias                 # 5 rounds
//! cargo bench --bench antialias -- --rounds 9
//! ```
//!
//! Two meshes (triangles that share edges and never overlap), drawn on a
//! 320 x 240 target under the top-left rule by the default back-end:
//!
//! * `delaunay`: the Delaunay triangulation (by spade) of 1,500 random
//!   points of the target and its corners: 3,000 triangles of about 26 px²,
//!   most pixels crossed by an edge;
//! * `star`: a star of 40 points, 220 px across, triangulated by spade:
//!   long thin triangles meeting at the centre.
//!
//! Each method of `rasterlab::measure::METHODS` estimates every pixel's
//! coverage by every triangle; its error against the exact area is given
//! per triangle (root mean square and worst over the (pixel, triangle)
//! pairs either covers) and in the picture (each pixel's triangles
//! summed). tiny-skia fills each triangle anti-aliased (a path, winding
//! fill, anti-alias on) over the others, as a 2D library draws a mesh:
//! its per-triangle coverage is read from each triangle filled alone, and
//! its picture is the filled pixmap's alpha, which blends shared edges
//! (conflation). The cost is each method's median time over the rounds
//! (interleaved, one thread) per (pixel, triangle) pair of the exact
//! area; tiny-skia's is its fill of the whole mesh.

use rasterlab::measure::{coverage_error, coverage_of, Coverage, Method, Table, METHODS};
use rasterlab::raster::{default_triangle_backend, FillRule, FixedPoint, PixelRect};
use spade::{DelaunayTriangulation, Point2, Triangulation};
use std::collections::BTreeMap;
use std::time::Instant;

const W: u32 = 320;
const H: u32 = 240;

fn snap(x: f64, y: f64) -> FixedPoint {
    FixedPoint::snap_f64(x, y).expect("inside the guard band")
}

/// The Delaunay triangulation of `n` random points and the corners.
fn delaunay(n: usize) -> Vec<[FixedPoint; 3]> {
    let mut rng = fastrand::Rng::with_seed(1);
    let mut t: DelaunayTriangulation<Point2<f64>> = DelaunayTriangulation::new();
    let corners = [
        (0.0, 0.0),
        (W as f64, 0.0),
        (W as f64, H as f64),
        (0.0, H as f64),
    ];
    for (x, y) in corners {
        t.insert(Point2::new(x, y)).expect("a corner inserts");
    }
    for _ in 0..n {
        // Points on the snapping grid, so that the mesh is the same once
        // snapped.
        let x = (rng.f64() * W as f64 * 256.0).round() / 256.0;
        let y = (rng.f64() * H as f64 * 256.0).round() / 256.0;
        t.insert(Point2::new(x, y)).expect("a point inserts");
    }
    t.inner_faces()
        .map(|f| f.positions().map(|p| snap(p.x, p.y)))
        .collect()
}

/// A star of 40 points around the target's centre, triangulated by spade.
fn star() -> Vec<[FixedPoint; 3]> {
    let ring: Vec<FixedPoint> = (0..40)
        .map(|i| {
            let a = i as f64 / 40.0 * std::f64::consts::TAU;
            let r = if i % 2 == 0 { 110.0 } else { 45.3 };
            snap(160.0 + r * a.cos(), 120.0 + r * a.sin())
        })
        .collect();
    rasterlab::geometry::Polygon::new(ring, Vec::new())
        .expect("the star is simple")
        .triangulate()
        .expect("the star triangulates")
}

/// tiny-skia's anti-aliased fill of `triangles` into `pixmap`, each over
/// the others.
fn tiny_skia_fill(triangles: &[[FixedPoint; 3]], pixmap: &mut tiny_skia::Pixmap) {
    pixmap.fill(tiny_skia::Color::TRANSPARENT);
    let mut paint = tiny_skia::Paint::default();
    paint.set_color_rgba8(255, 255, 255, 255);
    paint.anti_alias = true;
    for t in triangles {
        let mut path = tiny_skia::PathBuilder::new();
        let p = t.map(|v| v.to_f64());
        path.move_to(p[0].0 as f32, p[0].1 as f32);
        path.line_to(p[1].0 as f32, p[1].1 as f32);
        path.line_to(p[2].0 as f32, p[2].1 as f32);
        path.close();
        if let Some(path) = path.finish() {
            pixmap.fill_path(
                &path,
                &paint,
                tiny_skia::FillRule::Winding,
                tiny_skia::Transform::identity(),
                None,
            );
        }
    }
}

/// tiny-skia's coverage of each pixel by each triangle (each filled
/// alone), and its picture (the mesh filled, each triangle over the
/// others).
fn tiny_skia_coverage(triangles: &[[FixedPoint; 3]]) -> (Vec<Coverage>, BTreeMap<(i64, i64), f64>) {
    let mut pixmap = tiny_skia::Pixmap::new(W, H).expect("a pixmap");
    let alpha = |pixmap: &tiny_skia::Pixmap, x: u32, y: u32| {
        f64::from(pixmap.pixel(x, y).expect("inside").alpha()) / 255.0
    };
    let mut per_triangle = Vec::new();
    for (id, t) in triangles.iter().enumerate() {
        tiny_skia_fill(std::slice::from_ref(t), &mut pixmap);
        let (lo, hi) = t.iter().fold(
            ((f64::MAX, f64::MAX), (f64::MIN, f64::MIN)),
            |(lo, hi), v| {
                let (x, y) = v.to_f64();
                ((lo.0.min(x), lo.1.min(y)), (hi.0.max(x), hi.1.max(y)))
            },
        );
        let xs = (lo.0.floor().max(0.0) as u32)..=((hi.0.ceil() as u32).min(W - 1));
        for y in (lo.1.floor().max(0.0) as u32)..=((hi.1.ceil() as u32).min(H - 1)) {
            for x in xs.clone() {
                let value = alpha(&pixmap, x, y);
                if value > 0.0 {
                    per_triangle.push(Coverage {
                        x: i64::from(x),
                        y: i64::from(y),
                        triangle: id as u32,
                        value,
                    });
                }
            }
        }
    }
    tiny_skia_fill(triangles, &mut pixmap);
    let mut picture = BTreeMap::new();
    for y in 0..H {
        for x in 0..W {
            let value = alpha(&pixmap, x, y);
            if value > 0.0 {
                picture.insert((i64::from(y), i64::from(x)), value);
            }
        }
    }
    (per_triangle, picture)
}

fn median(samples: &mut [f64]) -> f64 {
    samples.sort_by(f64::total_cmp);
    samples[samples.len() / 2]
}

fn main() {
    let mut rounds = 5usize;
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        if arg == "--rounds" {
            rounds = args
                .next()
                .and_then(|r| r.parse().ok())
                .filter(|&r| r > 0)
                .expect("--rounds takes a number above 0");
        }
    }
    let rect = PixelRect::of_target(W, H);
    let backend = default_triangle_backend();
    let rule = FillRule::TopLeft;
    let mut table = Table::with_text_columns(
        2,
        &[
            "mesh",
            "method",
            "samples",
            "RMS per triangle",
            "worst per triangle",
            "RMS in the picture",
            "worst in the picture",
            "ns per pair",
        ],
    );
    for (name, triangles) in [("delaunay", delaunay(1500)), ("star", star())] {
        let exact = coverage_of(Method::Area, backend, &triangles, rect, rule).expect("areas");
        let pairs = exact.len() as f64;
        let mut times = vec![Vec::new(); METHODS.len() + 1];
        let mut pixmap = tiny_skia::Pixmap::new(W, H).expect("a pixmap");
        for _ in 0..rounds {
            for (i, &method) in METHODS.iter().enumerate() {
                let start = Instant::now();
                let c = coverage_of(method, backend, &triangles, rect, rule).expect("coverage");
                times[i].push(start.elapsed().as_secs_f64() * 1e9 / pairs);
                std::hint::black_box(c);
            }
            let start = Instant::now();
            tiny_skia_fill(&triangles, &mut pixmap);
            times[METHODS.len()].push(start.elapsed().as_secs_f64() * 1e9 / pairs);
        }
        for (i, &method) in METHODS.iter().enumerate() {
            let estimate = coverage_of(method, backend, &triangles, rect, rule).expect("coverage");
            let (per_triangle, picture) = coverage_error(&estimate, &exact, None);
            table.row(vec![
                name.to_string(),
                method.to_string(),
                method.samples().to_string(),
                format!("{:.4}", per_triangle.rms),
                format!("{:.3}", per_triangle.worst),
                format!("{:.4}", picture.rms),
                format!("{:.3}", picture.worst),
                format!("{:.0}", median(&mut times[i])),
            ]);
        }
        let (per, picture_of) = tiny_skia_coverage(&triangles);
        let (per_triangle, picture) = coverage_error(&per, &exact, Some(&picture_of));
        table.row(vec![
            name.to_string(),
            "tiny-skia, anti-aliased".into(),
            "-".into(),
            format!("{:.4}", per_triangle.rms),
            format!("{:.3}", per_triangle.worst),
            format!("{:.4}", picture.rms),
            format!("{:.3}", picture.worst),
            format!("{:.0}", median(&mut times[METHODS.len()])),
        ]);
        println!(
            "{name}: {} triangles, {} (pixel, triangle) pairs of the exact area",
            triangles.len(),
            exact.len()
        );
    }
    println!(
        "Coverage against the exact area, {W}x{H}, top-left rule, {} back-end, {rounds} interleaved rounds (median)",
        backend.name()
    );
    print!("{table}");
}
