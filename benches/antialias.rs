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
//!
//! Then the cost of multisampling a mesh through the stage: the full
//! Stanford dragon (871,414 triangles, from the data folder; the bundled
//! small dragon when it is not there) rendered as `rasterlab render`
//! draws it (640 x 480, diffuse, back faces culled, `scanline`), on one
//! thread, with one sample through the one-sample stage and with 1, 2, 4,
//! 8 and 16 samples through the multisampled stage, in interleaved
//! rounds: each frame's median and its ratio to the one-sample frame (the
//! median of the per-round ratios).
//!
//! cairo's anti-aliased fill is compared as tiny-skia's is, through
//! pycairo (`examples/adapters/cairo_antialias.py`, its time measured in
//! the script around the fills); without Python or pycairo its rows say
//! why they are missing. Each mesh's error against cost is charted in
//! `bench-output/antialias-MESH.svg`.

use rasterlab::geometry::{CullMode, Mesh, MeshRenderer, RenderSettings};
use rasterlab::measure::{
    coverage_error, coverage_of, find, Contender, Coverage, ErrorSummary, Method, Side, Table,
    Workload, FULL_DRAGON, METHODS,
};
use rasterlab::raster::{
    default_triangle_backend, FillRule, FixedPoint, MultisampleTarget, PixelRect, RenderTarget,
    SamplePattern, SAMPLE_COUNTS,
};
use rasterlab::teaching::{antialias_chart_svg, ChartPoint};
use spade::{DelaunayTriangulation, Point2, Triangulation};
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Mutex;
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

/// A peer's picture: each pixel's alpha in `[0, 1]` by (row, column).
type Picture = BTreeMap<(i64, i64), f64>;

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
fn tiny_skia_coverage(triangles: &[[FixedPoint; 3]]) -> (Vec<Coverage>, Picture) {
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

/// cairo's anti-aliased fill of `triangles` (`examples/adapters/cairo_antialias.py`,
/// through pycairo): its coverage of each pixel by each triangle filled
/// alone, its picture, and its median time to fill the mesh over
/// `rounds`, in nanoseconds; or why it could not run.
fn cairo_coverage(
    triangles: &[[FixedPoint; 3]],
    rounds: usize,
) -> Result<(Vec<Coverage>, Picture, f64), String> {
    use std::io::Write;
    use std::process::{Command, Stdio};
    let script =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/adapters/cairo_antialias.py");
    let mut child = Command::new("python3")
        .arg(&script)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("python3 did not start: {e}"))?;
    let mut input = format!("{W} {H} {rounds}\n");
    for t in triangles {
        let p = t.map(|v| v.to_f64());
        input.push_str(&format!(
            "{} {} {} {} {} {}\n",
            p[0].0, p[0].1, p[1].0, p[1].1, p[2].0, p[2].1
        ));
    }
    child
        .stdin
        .take()
        .expect("piped")
        .write_all(input.as_bytes())
        .map_err(|e| format!("writing to the cairo script: {e}"))?;
    let output = child.wait_with_output().map_err(|e| e.to_string())?;
    if !output.status.success() {
        let err = String::from_utf8_lossy(&output.stderr);
        return Err(err
            .lines()
            .last()
            .unwrap_or("the cairo script failed")
            .to_string());
    }
    let (mut per_triangle, mut picture, mut ns) = (Vec::new(), BTreeMap::new(), f64::NAN);
    for line in String::from_utf8_lossy(&output.stdout).lines() {
        let f: Vec<&str> = line.split(' ').collect();
        let num = |i: usize| f[i].parse::<f64>().expect("a number from the cairo script");
        match f[0] {
            "time" => ns = num(1),
            "t" => per_triangle.push(Coverage {
                triangle: num(1) as u32,
                x: num(2) as i64,
                y: num(3) as i64,
                value: num(4) / 255.0,
            }),
            "p" => {
                picture.insert((num(2) as i64, num(1) as i64), num(3) / 255.0);
            }
            other => return Err(format!("the cairo script wrote {other:?}")),
        }
    }
    Ok((per_triangle, picture, ns))
}

fn median(samples: &mut [f64]) -> f64 {
    samples.sort_by(f64::total_cmp);
    samples[samples.len() / 2]
}

/// The cost of multisampling the dragon, frame by frame, on one thread.
fn multisampled_dragon(rounds: usize) {
    let (name, path) = match find(FULL_DRAGON) {
        Ok(path) => ("full dragon", path),
        Err(why) => {
            println!("{why}; the bundled small dragon instead");
            let bundled = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
            (
                "dragon_res4",
                bundled.join("assets/dragon_vrip_res4.ply.gz"),
            )
        }
    };
    let mesh = Mesh::load(&path).expect("the dragon loads");
    let mut settings = RenderSettings::default();
    settings.pipeline.cull = CullMode::Back;
    let renderer = MeshRenderer::new(&mesh, settings).expect("a renderer");
    let backend = default_triangle_backend();
    let (w, h) = (settings.width, settings.height);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a thread pool");
    let pixels = Mutex::new(Vec::new());
    let mut work = Workload::new(name);
    let mut one = RenderTarget::without_coverage(w, h).expect("a target");
    renderer.prepare().expect("the buffers");
    work.add(Contender::new(
        "one sample, one-sample stage",
        Side::Rasterlab,
        1,
        move || pool.install(|| renderer_frame(&renderer, backend, &mut one)),
    ));
    for count in SAMPLE_COUNTS {
        let pattern = SamplePattern::standard(count).expect("a standard count");
        let mut target = MultisampleTarget::new(w, h, pattern).expect("a target");
        let renderer = MeshRenderer::new(&mesh, settings).expect("a renderer");
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .expect("a thread pool");
        let pixels = &pixels;
        work.add(Contender::new(
            &format!("MSAA {count}"),
            Side::Rasterlab,
            1,
            move || {
                pool.install(|| {
                    let stats = renderer
                        .render_multisampled_into(backend, &mut target)
                        .expect("a frame");
                    pixels
                        .lock()
                        .expect("not poisoned")
                        .push((count, stats.work.fragments));
                })
            },
        ));
    }
    let result = work.run(rounds);
    let base = &result.figures[0].rounds_ms;
    let mut table = Table::with_text_columns(
        1,
        &[
            "frame",
            "median ms",
            "x one sample",
            "(pixel, triangle) masks",
        ],
    );
    for figure in &result.figures {
        let mut ratios: Vec<f64> = figure
            .rounds_ms
            .iter()
            .zip(base)
            .map(|(m, b)| m / b)
            .collect();
        let count: u32 = figure
            .name
            .strip_prefix("MSAA ")
            .map_or(0, |c| c.parse().unwrap_or(0));
        let masked = pixels
            .lock()
            .expect("not poisoned")
            .iter()
            .find(|(c, _)| *c == count)
            .map_or("-".to_string(), |(_, p)| p.to_string());
        table.row(vec![
            figure.name.clone(),
            format!("{:.1}", figure.spread.median_ms),
            format!("{:.2}", median(&mut ratios)),
            masked,
        ]);
    }
    println!(
        "{name} ({} triangles), {w}x{h}, diffuse, back faces culled, {}, one thread, {rounds} interleaved rounds (median)",
        mesh.triangles.len(),
        backend.name()
    );
    print!("{table}");
}

/// One frame of `renderer` into `target`, the one-sample stage.
fn renderer_frame(
    renderer: &MeshRenderer,
    backend: &dyn rasterlab::raster::triangle::TriangleRasterizer,
    target: &mut RenderTarget,
) {
    renderer.render_into(backend, target).expect("a frame");
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
        let mut points = Vec::new();
        let mut add = |method: String,
                       samples: String,
                       errors: (ErrorSummary, ErrorSummary),
                       ns: f64,
                       peer: bool| {
            let (per_triangle, picture) = errors;
            table.row(vec![
                name.to_string(),
                method.clone(),
                samples,
                format!("{:.4}", per_triangle.rms),
                format!("{:.3}", per_triangle.worst),
                format!("{:.4}", picture.rms),
                format!("{:.3}", picture.worst),
                format!("{ns:.0}"),
            ]);
            points.push(ChartPoint {
                name: method,
                ns_per_pair: ns,
                rms: per_triangle.rms,
                peer,
            });
        };
        for (i, &method) in METHODS.iter().enumerate() {
            let estimate = coverage_of(method, backend, &triangles, rect, rule).expect("coverage");
            let samples = match method.samples() {
                0 => "-".to_string(),
                n => n.to_string(),
            };
            let errors = coverage_error(&estimate, &exact, None);
            add(
                method.to_string(),
                samples,
                errors,
                median(&mut times[i]),
                false,
            );
        }
        let (per, picture_of) = tiny_skia_coverage(&triangles);
        let errors = coverage_error(&per, &exact, Some(&picture_of));
        let ns = median(&mut times[METHODS.len()]);
        add(
            "tiny-skia, anti-aliased".into(),
            "-".into(),
            errors,
            ns,
            true,
        );
        match cairo_coverage(&triangles, rounds) {
            Ok((per, picture_of, ns)) => {
                let errors = coverage_error(&per, &exact, Some(&picture_of));
                add(
                    "cairo, anti-aliased".into(),
                    "-".into(),
                    errors,
                    ns / pairs,
                    true,
                );
            }
            Err(why) => println!("cairo not compared on {name}: {why}"),
        }
        let chart = antialias_chart_svg(&format!("{name}, {W} x {H}, {rounds} rounds"), &points);
        let out = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("bench-output");
        let file = out.join(format!("antialias-{name}.svg"));
        match std::fs::create_dir_all(&out).and_then(|()| std::fs::write(&file, chart)) {
            Ok(()) => println!("{name}: chart written to {}", file.display()),
            Err(e) => println!("{name}: chart not written to {}: {e}", file.display()),
        }
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
    multisampled_dragon(rounds);
}
