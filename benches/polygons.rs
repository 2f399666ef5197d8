//! Polygons filled directly, beside triangulation, beside tiny-skia's
//! aliased `fill_path`: the same polygons, colour only, at 1024x1024, in
//! interleaved rounds (`rasterlab::measure::rounds`).
//!
//! * `polygon-bundled`: `assets/polygon.txt` (a pentagon with a
//!   triangular hole) scaled 32 times, to fill most of the target;
//! * `polygons-random`: 1,024 random star-shaped polygons of 6 to 40
//!   vertices, one in each 32 px cell of the target, every other one with
//!   a quadrilateral hole: simple, so spade triangulates them and both
//!   winding rules fill the same pixels;
//! * `polygons-crossing`: 1,024 rings of 5 to 12 random points, one in
//!   each cell, crossing themselves: the winding rules differ, and spade
//!   takes none of them;
//! * `outline-10k`: one ring of 10,000 vertices, a flower of 50 petals
//!   (radius `350 + 100 sin(50 a)` px about the centre).
//!
//! Contenders, one thread each: `edge-table` and `crossings` under each
//! rule, through the shared fragment stage in one constant colour with
//! the depth test off (the target's colour cleared first); `scanline` on
//! spade's triangles, triangulated once outside the timing, drawn the same
//! way (the clear folded into the draw); `spade+scanline`, the
//! triangulation timed too; tiny-skia's `fill_path` with anti-aliasing
//! off under each rule (`EvenOdd`, `Winding`), into a pixmap filled black
//! first. The ratio table sets each peer against rasterlab's best.
//!
//! Before the rounds, each rule's pixels are compared with tiny-skia's
//! (a pixel is tiny-skia's when its alpha is not 0), twice: as drawn; and
//! against rasterlab filling the same polygons as tiny-skia samples them,
//! its vertices truncated to its 1/64 px grid (`(x * 64) as i32`) and
//! its ties the other way round (a centre on a right or bottom edge
//! inside, on a left or top one outside: tiny-skia counts an edge's rows
//! from `round(y0)` to `round(y1) - 1` and a span from `round(xl)` to
//! `round(xr) - 1`), which is rasterlab's top-left convention on the
//! polygons turned by 180 degrees, its pixels turned back. What is left
//! then is tiny-skia's crossings, stepped by a slope rounded to 16.16
//! fixed point.
//!
//! ```text
//! cargo bench --bench polygons                        # everything, 10 rounds
//! cargo bench --bench polygons -- --rounds 5 random   # workloads named *random*
//! ```

use glam::Vec4;
use rasterlab::geometry::{Outline, Polygon};
use rasterlab::measure::{ratio_header, Contender, Context, Side, TriangleWorkload, Workload};
use rasterlab::raster::polygon::crossings::Crossings;
use rasterlab::raster::polygon::edge_table::EdgeTable;
use rasterlab::raster::polygon::{PolygonRasterizer, PolygonSetup, WindingRule};
use rasterlab::raster::{
    triangle_backend, Constant, DepthState, FixedPoint, FragmentList, FragmentStage, PixelRect,
    RenderTarget, ShadedVertex, TriangleData,
};
use std::cell::RefCell;
use std::path::PathBuf;

const SIDE: u32 = 1024;
const COLOUR: Vec4 = Vec4::new(0.2, 0.5, 0.9, 1.0);

/// One workload's polygons: their outlines, and spade's triangles when
/// they are simple.
struct Polygons {
    name: &'static str,
    outlines: Vec<Outline>,
    simple: Option<Vec<Polygon>>,
}

fn p(x: f64, y: f64) -> FixedPoint {
    FixedPoint::snap_f64(x, y).expect("inside the guard band")
}

fn bundled() -> Polygons {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/polygon.txt");
    let file = rasterlab::geometry::read_polygons(&path, None).unwrap();
    let scale = |ring: &Vec<FixedPoint>| -> Vec<FixedPoint> {
        ring.iter()
            .map(|q| FixedPoint::from_raw(q.x.raw() * 32, q.y.raw() * 32).unwrap())
            .collect()
    };
    let outline = &file.outlines[0];
    let outer = scale(&outline.rings[0]);
    let holes: Vec<_> = outline.rings[1..].iter().map(scale).collect();
    let polygon = Polygon::new(outer.clone(), holes.clone()).unwrap();
    Polygons {
        name: "polygon-bundled",
        outlines: vec![Outline::with_holes(outer, holes).unwrap()],
        simple: Some(vec![polygon]),
    }
}

/// A star-shaped ring about `(cx, cy)`: `n` vertices at angles evenly
/// spaced and jittered by under a third of a step, radii in `r`.
fn star(rng: &mut fastrand::Rng, cx: f64, cy: f64, n: usize, r: (f64, f64)) -> Vec<FixedPoint> {
    let step = std::f64::consts::TAU / n as f64;
    (0..n)
        .map(|k| {
            let a = (k as f64 + rng.f64() * 0.3) * step;
            let radius = r.0 + rng.f64() * (r.1 - r.0);
            p(cx + radius * a.cos(), cy + radius * a.sin())
        })
        .collect()
}

fn random_simple() -> Polygons {
    let mut rng = fastrand::Rng::with_seed(63);
    let mut outlines = Vec::new();
    let mut simple = Vec::new();
    for cell in 0..(SIDE / 32) * (SIDE / 32) {
        let (cx, cy) = (
            f64::from(cell % 32) * 32.0 + 16.0,
            f64::from(cell / 32) * 32.0 + 16.0,
        );
        let n = rng.usize(6..=40);
        let outer = star(&mut rng, cx, cy, n, (9.0, 15.5));
        // Neighbouring vertices are at most 1.3 steps apart, so every
        // edge of the outer ring passes at least 9 cos(0.65 pi / 3), about
        // 7 px, from the centre: a hole of radius under 4.5 lies inside.
        let holes = if cell % 2 == 0 {
            vec![star(&mut rng, cx, cy, 4, (2.0, 4.5))]
        } else {
            Vec::new()
        };
        simple.push(Polygon::new(outer.clone(), holes.clone()).unwrap());
        outlines.push(Outline::with_holes(outer, holes).unwrap());
    }
    Polygons {
        name: "polygons-random",
        outlines,
        simple: Some(simple),
    }
}

fn random_crossing() -> Polygons {
    let mut rng = fastrand::Rng::with_seed(64);
    let outlines = (0..(SIDE / 32) * (SIDE / 32))
        .map(|cell| {
            let (x0, y0) = (f64::from(cell % 32) * 32.0, f64::from(cell / 32) * 32.0);
            let ring = (0..rng.usize(5..=12))
                .map(|_| p(x0 + 1.0 + rng.f64() * 30.0, y0 + 1.0 + rng.f64() * 30.0))
                .collect();
            Outline::new(vec![ring]).unwrap()
        })
        .collect();
    Polygons {
        name: "polygons-crossing",
        outlines,
        simple: None,
    }
}

fn flower() -> Polygons {
    let n = 10_000;
    let ring: Vec<FixedPoint> = (0..n)
        .map(|k| {
            let a = k as f64 / n as f64 * std::f64::consts::TAU;
            let r = 350.0 + 100.0 * (50.0 * a).sin();
            p(512.0 + r * a.cos(), 512.0 + r * a.sin())
        })
        .collect();
    let polygon = Polygon::new(ring.clone(), Vec::new()).unwrap();
    Polygons {
        name: "outline-10k",
        outlines: vec![Outline::new(vec![ring]).unwrap()],
        simple: Some(vec![polygon]),
    }
}

/// spade's triangles of every polygon.
fn triangulate(polygons: &[Polygon]) -> Vec<[FixedPoint; 3]> {
    polygons
        .iter()
        .flat_map(|p| p.triangulate().unwrap())
        .collect()
}

/// The outlines as one tiny-skia path each (vertices as `f32`, exact:
/// they lie on the 1/256 px grid).
fn skia_paths(outlines: &[Outline]) -> Vec<tiny_skia::Path> {
    outlines
        .iter()
        .filter_map(|o| {
            let mut path = tiny_skia::PathBuilder::new();
            for ring in &o.rings {
                let (x, y) = ring[0].to_f64();
                path.move_to(x as f32, y as f32);
                for q in &ring[1..] {
                    let (x, y) = q.to_f64();
                    path.line_to(x as f32, y as f32);
                }
                path.close();
            }
            path.finish()
        })
        .collect()
}

fn skia_rule(rule: WindingRule) -> tiny_skia::FillRule {
    match rule {
        WindingRule::EvenOdd => tiny_skia::FillRule::EvenOdd,
        WindingRule::Nonzero => tiny_skia::FillRule::Winding,
    }
}

fn skia_fill(paths: &[tiny_skia::Path], rule: WindingRule, pixmap: &mut tiny_skia::Pixmap) {
    let mut paint = tiny_skia::Paint::default();
    paint.set_color_rgba8(51, 128, 230, 255);
    paint.anti_alias = false;
    pixmap.fill(tiny_skia::Color::BLACK);
    for path in paths {
        pixmap.fill_path(
            path,
            &paint,
            skia_rule(rule),
            tiny_skia::Transform::identity(),
            None,
        );
    }
}

/// The pixels `paths` fill, by tiny-skia.
fn skia_mask(paths: &[tiny_skia::Path], rule: WindingRule) -> Vec<bool> {
    let mut pixmap = tiny_skia::Pixmap::new(SIDE, SIDE).unwrap();
    let mut paint = tiny_skia::Paint::default();
    paint.set_color_rgba8(255, 255, 255, 255);
    paint.anti_alias = false;
    for path in paths {
        pixmap.fill_path(
            path,
            &paint,
            skia_rule(rule),
            tiny_skia::Transform::identity(),
            None,
        );
    }
    pixmap.pixels().iter().map(|c| c.alpha() != 0).collect()
}

/// The pixels `setups` fill, by the edge table.
fn edge_table_mask(setups: &[PolygonSetup], rule: WindingRule) -> Vec<bool> {
    let mut list = FragmentList::default();
    EdgeTable.rasterize(setups, rule, PixelRect::of_target(SIDE, SIDE), &mut list);
    let mut mask = vec![false; (SIDE * SIDE) as usize];
    for f in &list.triangles {
        mask[(f.y * SIDE + f.x) as usize] = true;
    }
    mask
}

/// The outlines as tiny-skia samples them, for the edge table: vertices
/// truncated to 1/64 px, then turned by 180 degrees about the target's
/// centre so that the top-left convention decides ties as tiny-skia does.
fn as_skia_samples_turned(outlines: &[Outline]) -> Vec<PolygonSetup> {
    let side = i64::from(SIDE) * 256;
    outlines
        .iter()
        .enumerate()
        .map(|(i, o)| {
            let rings: Vec<Vec<FixedPoint>> = o
                .rings
                .iter()
                .map(|ring| {
                    ring.iter()
                        .map(|q| {
                            let (x, y) = (q.x.raw(), q.y.raw());
                            let (x, y) = (x - x.rem_euclid(4), y - y.rem_euclid(4));
                            FixedPoint::from_raw(side - x, side - y).unwrap()
                        })
                        .collect()
                })
                .collect();
            PolygonSetup::new(i as u32, &rings)
        })
        .collect()
}

/// The horizontal distance, in pixels, from the centre of pixel `(x, y)`
/// to the nearest crossing of its row's sample line by an edge of
/// `setups` (turned back by 180 degrees).
fn distance_to_edge(turned: &[PolygonSetup], x: u32, y: u32) -> f64 {
    // The pixel's centre in the turned polygons' frame.
    let side = f64::from(SIDE);
    let (cx, cy) = (side - (f64::from(x) + 0.5), side - (f64::from(y) + 0.5));
    let mut best = f64::INFINITY;
    for s in turned {
        for e in &s.edges {
            let (tx, ty) = e.top.to_f64();
            let (bx, by) = e.bottom.to_f64();
            if ty <= cy && cy <= by {
                let crossing = tx + (cy - ty) * (bx - tx) / (by - ty);
                best = best.min((crossing - cx).abs());
            }
        }
    }
    best
}

/// Prints how many pixels tiny-skia fills otherwise than the edge table,
/// as drawn and as tiny-skia samples.
fn agreement(polygons: &Polygons, setups: &[PolygonSetup], paths: &[tiny_skia::Path]) {
    let turned = as_skia_samples_turned(&polygons.outlines);
    for rule in WindingRule::ALL {
        let skia = skia_mask(paths, rule);
        let ours = edge_table_mask(setups, rule);
        let mut theirs_turned = edge_table_mask(&turned, rule);
        theirs_turned.reverse();
        let differ = |a: &[bool], b: &[bool]| a.iter().zip(b).filter(|(a, b)| a != b).count();
        let filled = |m: &[bool]| m.iter().filter(|&&b| b).count();
        let (ours_only, skia_only) = ours.iter().zip(&skia).fold((0, 0), |(o, s), (a, b)| {
            (o + usize::from(*a && !*b), s + usize::from(*b && !*a))
        });
        // Where the two still differ, how close the pixel centre lies
        // to an edge (as tiny-skia's vertices have it).
        let left: Vec<f64> = (0..SIDE * SIDE)
            .filter(|&i| theirs_turned[i as usize] != skia[i as usize])
            .map(|i| distance_to_edge(&turned, i % SIDE, i / SIDE))
            .collect();
        let farthest = left.iter().copied().fold(0.0, f64::max);
        println!(
            "{} {rule}: edge-table fills {} pixels, tiny-skia {}; {} differ ({:.3}%: {ours_only} edge-table's only, {skia_only} tiny-skia's only); \
             with tiny-skia's 1/64 px vertices and its ties (right and bottom edges inside): {} differ, every centre of them within {farthest:.5} px of an edge",
            polygons.name,
            filled(&ours),
            filled(&skia),
            differ(&ours, &skia),
            100.0 * differ(&ours, &skia) as f64 / filled(&skia).max(1) as f64,
            left.len(),
        );
    }
}

fn main() {
    let mut rounds = 10;
    let mut filters = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--rounds" => {
                rounds = args
                    .next()
                    .and_then(|n| n.parse().ok())
                    .filter(|n| *n >= 1)
                    .expect("--rounds takes a whole number of at least 1")
            }
            a if a.starts_with("--") => {}
            a => filters.push(a.to_string()),
        }
    }
    let wants = |name: &str| filters.is_empty() || filters.iter().any(|f| name.contains(f));
    let mut context = Context::start(1, rounds, SIDE, SIDE);
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let target = RefCell::new(RenderTarget::without_coverage(SIDE, SIDE).unwrap());
    let pixmap = RefCell::new(tiny_skia::Pixmap::new(SIDE, SIDE).unwrap());
    let scanline = triangle_backend("scanline").unwrap();
    let mut results = Vec::new();
    for make in [bundled, random_simple, random_crossing, flower] {
        let polygons = make();
        if !wants(polygons.name) {
            continue;
        }
        let setups: Vec<PolygonSetup> = polygons
            .outlines
            .iter()
            .enumerate()
            .map(|(i, o)| o.setup(i as u32))
            .collect();
        let look = [ShadedVertex::flat(0.5, COLOUR); 3];
        let data = TriangleData::of_triangles(&[], &vec![look; setups.len()]);
        let paths = skia_paths(&polygons.outlines);
        agreement(&polygons, &setups, &paths);
        let triangles = polygons.simple.as_deref().map(|s| {
            let t = triangulate(s);
            TriangleWorkload::new(polygons.name.to_string(), &t, |_| 0.5)
        });
        let vertices: usize = polygons
            .outlines
            .iter()
            .flat_map(|o| &o.rings)
            .map(Vec::len)
            .sum();
        println!(
            "{}: {} polygons, {} vertices, {}",
            polygons.name,
            polygons.outlines.len(),
            vertices,
            triangles
                .as_ref()
                .map_or("not simple: no triangulation".into(), |t| {
                    format!("{} triangles by spade", t.triangles())
                })
        );
        let mut work = Workload::new(polygons.name);
        let (setups, data, one, target) = (&setups, &data, &one, &target);
        for rule in WindingRule::ALL {
            let backends: [&dyn PolygonRasterizer; 2] = [&EdgeTable, &Crossings];
            for b in backends {
                work.add(Contender::new(
                    &format!("{}-{rule}", b.name()),
                    Side::Rasterlab,
                    1,
                    move || {
                        let target = &mut *target.borrow_mut();
                        // The clear too on the one thread (it may split
                        // its rows among the pool's).
                        one.install(|| {
                            target.clear_color(RenderTarget::BLACK);
                            let shader = Constant(COLOUR);
                            let mut stage = FragmentStage::new(target, &shader)
                                .with_triangles(data)
                                .with_depth(DepthState::OFF);
                            b.rasterize(setups, rule, PixelRect::of_target(SIDE, SIDE), &mut stage)
                                .work
                                .fragments
                        })
                    },
                ));
            }
        }
        if let (Some(t), Some(simple)) = (&triangles, &polygons.simple) {
            work.add(Contender::new("scanline", Side::Rasterlab, 1, move || {
                let target = &mut *target.borrow_mut();
                one.install(|| t.run_colour_only(scanline, target))
            }));
            work.add(Contender::new(
                "spade+scanline",
                Side::Rasterlab,
                1,
                move || {
                    let t = TriangleWorkload::new(String::new(), &triangulate(simple), |_| 0.5);
                    let target = &mut *target.borrow_mut();
                    one.install(|| t.run_colour_only(scanline, target))
                },
            ));
        }
        for rule in WindingRule::ALL {
            let (paths, pixmap) = (&paths, &pixmap);
            work.add(Contender::new(
                &format!("peer-tiny-skia-{rule}"),
                Side::Peer,
                1,
                move || {
                    let pixmap = &mut pixmap.borrow_mut();
                    skia_fill(paths, rule, pixmap);
                    pixmap.data()[0]
                },
            ));
        }
        let result = work.run(rounds);
        print!("{}", result.figure_table());
        results.push(result);
    }
    context.finish();
    let mut ratios = ratio_header();
    for result in &results {
        result.ratio_rows(&mut ratios);
    }
    println!();
    println!(
        "cargo bench --bench polygons -- --rounds {rounds}{}",
        filters.iter().map(|f| format!(" {f}")).collect::<String>()
    );
    print!("{context}");
    println!("every contender on one thread, colour only; peer / best: tiny-skia's time over rasterlab's best, median of the per-round ratios [min-max]; above 1, rasterlab is faster");
    print!("{ratios}");
}
