//! `rasterlab bench`: every back-end on the same workloads, timed in one
//! run, with a table, JSON and a bar chart.
//!
//! Each (workload, back-end) pair is run `samples` times after one warm-up
//! run, and the **median** time is kept (the machine is shared and noisy;
//! the median ignores the odd slow run). From it: millions of primitives
//! per second, billions of pixels per second, and the ratio to the slowest
//! back-end on that workload. For published crates side by side, and
//! confidence intervals, `cargo bench --bench side_by_side` runs the same
//! workloads under criterion.

use crate::error::Result;
use crate::geometry::mesh::Mesh;
use crate::geometry::pipeline::CullMode;
use crate::geometry::render::{MeshRenderer, RenderSettings};
use crate::measure::workload::{self, LineWorkload};
use crate::raster::backend::{line_backends, triangle_backends};
use crate::raster::target::RenderTarget;
use serde::Serialize;
use std::path::Path;
use std::time::{Duration, Instant};

/// One measured (workload, back-end) pair.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Measurement {
    /// Workload name.
    pub workload: String,
    /// Back-end name.
    pub backend: String,
    /// Primitives (triangles or lines) per run.
    pub primitives: u64,
    /// Pixels written per run.
    pub pixels: u64,
    /// Median time of one run, in milliseconds.
    pub median_ms: f64,
    /// Millions of primitives per second.
    pub mprims_per_s: f64,
    /// Billions of pixels per second.
    pub gpixels_per_s: f64,
    /// How many times faster than the slowest back-end on this workload.
    pub vs_slowest: f64,
}

/// Which workloads to run.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum WorkloadSet {
    /// A few seconds: fill, three sizes, slivers, 100k short and 1k long
    /// lines, the bundled dragon.
    #[default]
    Quick,
    /// The `cargo bench` sizes: 1M short and 10k long lines, six triangle
    /// sizes, two fill depths.
    Full,
}

crate::names::named_enum!(WorkloadSet, "workload set", Quick = "quick", Full = "full");

/// What to run.
#[derive(Clone, Debug)]
pub struct BenchOptions {
    /// Which workloads.
    pub set: WorkloadSet,
    /// Target width.
    pub width: u32,
    /// Target height.
    pub height: u32,
    /// Timed runs per pair (after one warm-up run).
    pub samples: usize,
    /// Meshes to render (with every back-end but `naive`).
    pub meshes: Vec<std::path::PathBuf>,
}

/// The median of `samples` timed runs of `run`, after one warm-up run.
pub(crate) fn median_time<T>(samples: usize, mut run: impl FnMut() -> T) -> (Duration, T) {
    let first = run();
    let mut times: Vec<Duration> = (0..samples.max(1))
        .map(|_| {
            let start = Instant::now();
            std::hint::black_box(run());
            start.elapsed()
        })
        .collect();
    times.sort_unstable();
    (times[times.len() / 2], first)
}

/// What [`run`] reports before timing each (workload, back-end) pair.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Progress<'a> {
    /// Pairs timed so far.
    pub done: usize,
    /// Pairs in all.
    pub total: usize,
    /// The pair about to be timed, `workload / back-end`.
    pub pair: &'a str,
}

/// Runs the benchmark; `progress` is called before each pair is timed.
pub fn run(options: &BenchOptions, progress: &mut dyn FnMut(Progress)) -> Result<Vec<Measurement>> {
    RenderTarget::check_size(options.width, options.height)?;
    let (w, h) = (options.width, options.height);
    let mut results = Vec::new();
    // Colour and depth, as the peers draw: the coverage count is a
    // checking aid that a renderer does not need.
    let mut target = RenderTarget::without_coverage(w, h)?;
    let mut measure = |workload: &str, backend: &str, prims: u64, time: Duration, pixels: u64| {
        let s = time.as_secs_f64().max(1e-9);
        results.push(Measurement {
            workload: workload.to_string(),
            backend: backend.to_string(),
            primitives: prims,
            pixels,
            median_ms: s * 1e3,
            mprims_per_s: prims as f64 / s / 1e6,
            gpixels_per_s: pixels as f64 / s / 1e9,
            vs_slowest: 1.0,
        });
    };

    let mut triangle_workloads = vec![workload::fill(w, h, 1)];
    let (sizes, lines): (&[f32], (usize, usize)) = match options.set {
        WorkloadSet::Quick => (&[4.0, 32.0, 250.0], (100_000, 1_000)),
        WorkloadSet::Full => {
            triangle_workloads.push(workload::fill(w, h, 4));
            (&[1.0, 4.0, 16.0, 64.0, 250.0, 500.0], (1_000_000, 10_000))
        }
    };
    for &size in sizes {
        triangle_workloads.push(workload::sized(w, h, size));
    }
    for angle in [0.0, 45.0, 90.0] {
        triangle_workloads.push(workload::slivers(w, h, angle));
    }
    let line_workloads = [
        LineWorkload::new("lines-short", workload::short_lines(w, h, lines.0)),
        LineWorkload::new("lines-long", workload::long_lines(w, h, lines.1)),
    ];
    let meshes = options
        .meshes
        .iter()
        .map(|path| Mesh::load(path).map(|mesh| (mesh_name(path), mesh)))
        .collect::<Result<Vec<_>>>()?;
    let mesh_backends: Vec<_> = triangle_backends()
        .iter()
        // As for the triangle workloads: at most two tests per pixel.
        .filter(|b| {
            meshes
                .iter()
                .all(|(_, mesh)| b.affordable(mesh.triangles.len() as u64, 1, 2))
        })
        .collect();
    let total = triangle_workloads
        .iter()
        .map(|work| {
            triangle_backends()
                .iter()
                .filter(|b| work.suits(**b))
                .count()
        })
        .sum::<usize>()
        + line_workloads.len() * (line_backends().len() + 1)
        + meshes.len() * mesh_backends.len();
    let mut done = 0;
    let mut step = |workload: &str, backend: &str| {
        progress(Progress {
            done,
            total,
            pair: &format!("{workload} / {backend}"),
        });
        done += 1;
    };

    for work in &triangle_workloads {
        for b in triangle_backends().iter().filter(|b| work.suits(**b)) {
            step(&work.name, b.name());
            let (time, pixels) = median_time(options.samples, || work.run(*b, &mut target));
            measure(&work.name, b.name(), work.triangles() as u64, time, pixels);
        }
    }

    for work in &line_workloads {
        let count = work.lines.len() as u64;
        for b in line_backends() {
            step(&work.name, b.name());
            let (time, pixels) =
                median_time(options.samples, || work.run(*b, &mut target).fragments);
            measure(&work.name, b.name(), count, time, pixels);
        }
        step(&work.name, "fast-bresenham");
        let (time, pixels) = median_time(options.samples, || work.run_fast(&mut target));
        measure(&work.name, "fast-bresenham", count, time, pixels);
    }

    for (name, mesh) in &meshes {
        let mut settings = RenderSettings {
            width: w,
            height: h,
            azimuth: 30.0,
            ..RenderSettings::default()
        };
        settings.pipeline.cull = CullMode::Back;
        let renderer = MeshRenderer::new(mesh, settings)?;
        let mut target = RenderTarget::without_coverage(w, h)?;
        for b in &mesh_backends {
            step(name, b.name());
            let mut error = None;
            let (time, pixels) = median_time(options.samples, || {
                match renderer.render_into(**b, &mut target) {
                    Ok(stats) => stats.work.fragments,
                    Err(e) => {
                        error = Some(e);
                        0
                    }
                }
            });
            if let Some(e) = error {
                return Err(e);
            }
            measure(name, b.name(), mesh.triangles.len() as u64, time, pixels);
        }
    }

    // Ratios to the slowest back-end of each workload.
    for i in 0..results.len() {
        let slowest = results
            .iter()
            .filter(|m| m.workload == results[i].workload)
            .map(|m| m.median_ms)
            .fold(0.0, f64::max);
        results[i].vs_slowest = slowest / results[i].median_ms;
    }
    Ok(results)
}

/// A mesh file's name without its extensions.
fn mesh_name(path: &Path) -> String {
    let name = path
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    name.split('.').next().unwrap_or_default().to_string()
}

/// The results as a plain-text table.
pub fn table(results: &[Measurement]) -> String {
    let mut out = format!(
        "{:<14} {:<16} {:>10} {:>11} {:>9} {:>9} {:>8}\n",
        "workload", "back-end", "median ms", "Mprim/s", "Gpix/s", "pixels", "x slowest"
    );
    for m in results {
        out += &format!(
            "{:<14} {:<16} {:>10.3} {:>11.2} {:>9.3} {:>9} {:>8.1}x\n",
            m.workload,
            m.backend,
            m.median_ms,
            m.mprims_per_s,
            m.gpixels_per_s,
            m.pixels,
            m.vs_slowest
        );
    }
    out
}

/// The results as JSON.
pub fn to_json(results: &[Measurement]) -> String {
    serde_json::to_string_pretty(results).expect("measurements serialise")
}

/// One colour per back-end, in a fixed order.
/// One colour per back-end (up to eleven, distinct), in registry order.
const PALETTE: [[u8; 3]; 11] = [
    [120, 120, 120],
    [230, 159, 0],
    [86, 180, 233],
    [0, 158, 115],
    [213, 94, 0],
    [0, 114, 178],
    [204, 121, 167],
    [190, 175, 20],
    [110, 60, 160],
    [160, 30, 60],
    [40, 40, 40],
];

/// The distinct values of `field` over the results, in first-seen order.
fn distinct(results: &[Measurement], field: fn(&Measurement) -> &str) -> Vec<&str> {
    let mut names: Vec<&str> = Vec::new();
    for m in results {
        let name = field(m);
        if !names.contains(&name) {
            names.push(name);
        }
    }
    names
}

/// The back-end names in first-seen order, for the chart's colours.
fn backend_names(results: &[Measurement]) -> Vec<&str> {
    distinct(results, |m| &m.backend)
}

/// The workload names in first-seen order, one group of bars each.
fn workload_names(results: &[Measurement]) -> Vec<&str> {
    distinct(results, |m| &m.workload)
}

/// The measurements of `workload`, and the best Gpix/s among them (the
/// chart's full bar height).
fn group<'a>(results: &'a [Measurement], workload: &str) -> (Vec<&'a Measurement>, f64) {
    let group: Vec<&Measurement> = results.iter().filter(|m| m.workload == workload).collect();
    let fastest = group.iter().map(|m| m.gpixels_per_s).fold(0.0, f64::max);
    (group, fastest)
}

/// The font the PNG chart's text is drawn with (DejaVu Sans, bundled in
/// `assets/fonts` with its licence), so the picture looks the same on any
/// machine.
const CHART_FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

/// The chart as an image: [`chart_svg`] rendered by `resvg` with the
/// bundled font, so the PNG has the same axis, labels and values.
pub fn chart_png(results: &[Measurement]) -> image::RgbaImage {
    let svg = chart_svg(results);
    let mut options = resvg::usvg::Options::default();
    options.fontdb_mut().load_font_data(CHART_FONT.to_vec());
    options.font_family = "DejaVu Sans".into();
    let blank = || image::RgbaImage::from_pixel(1, 1, image::Rgba([255, 255, 255, 255]));
    let Ok(tree) = resvg::usvg::Tree::from_str(&svg, &options) else {
        return blank();
    };
    let size = tree.size().to_int_size();
    let Some(mut pixmap) = resvg::tiny_skia::Pixmap::new(size.width(), size.height()) else {
        return blank();
    };
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::default(),
        &mut pixmap.as_mut(),
    );
    // The background is opaque white, so premultiplied and straight RGBA agree.
    image::RgbaImage::from_raw(size.width(), size.height(), pixmap.take()).unwrap_or_else(blank)
}

/// A horizontal bar chart: one group per workload, one labelled bar per
/// back-end, bar length the speed relative to the fastest back-end on that
/// workload (the axis at the bottom, 0 to 1), each bar's median time and
/// throughput written beside it.
pub fn chart_svg(results: &[Measurement]) -> String {
    let names = backend_names(results);
    let workloads = workload_names(results);
    let (label_w, bar_w, value_w) = (110.0, 460.0, 230.0);
    let (row, header, top) = (17.0, 24.0, 44.0);
    let x0 = 10.0 + label_w;
    let rows: usize = workloads.iter().map(|w| group(results, w).0.len()).sum();
    let plot_h = workloads.len() as f64 * header + rows as f64 * row;
    let width = x0 + bar_w + value_w;
    let height = top + plot_h + 50.0;
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" viewBox=\"0 0 {width} {height}\" font-family=\"DejaVu Sans, sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<text x=\"10\" y=\"22\" font-size=\"14\" font-weight=\"bold\">rasterlab bench: speed relative to the fastest back-end on each workload</text>\n"
    );
    // Vertical grid lines and the axis.
    let axis_y = top + plot_h + 4.0;
    for k in 0..=4 {
        let f = f64::from(k) / 4.0;
        let x = x0 + f * bar_w;
        svg += &format!(
            "<line x1=\"{x:.1}\" y1=\"{top}\" x2=\"{x:.1}\" y2=\"{axis_y:.1}\" stroke=\"#ddd\"/><text x=\"{x:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{f}</text>\n",
            axis_y + 14.0
        );
    }
    svg += &format!(
        "<line x1=\"{x0}\" y1=\"{axis_y:.1}\" x2=\"{:.1}\" y2=\"{axis_y:.1}\" stroke=\"#333\"/><text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">speed relative to the fastest (1 = fastest; median time and throughput beside each bar)</text>\n",
        x0 + bar_w,
        x0 + bar_w / 2.0,
        axis_y + 32.0
    );
    let mut y = top;
    for wl in &workloads {
        let (members, fastest) = group(results, wl);
        let prims = members.first().map_or(0, |m| m.primitives);
        y += header;
        svg += &format!(
            "<text x=\"10\" y=\"{:.1}\" font-weight=\"bold\">{wl} ({prims} primitives)</text>\n",
            y - 7.0
        );
        for m in members {
            let k = names.iter().position(|n| *n == m.backend).unwrap_or(0);
            let [r, gr, b] = PALETTE[k % PALETTE.len()];
            let rel = if fastest > 0.0 {
                m.gpixels_per_s / fastest
            } else {
                0.0
            };
            let w = (rel * bar_w).max(1.0);
            svg += &format!(
                "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\">{}</text><rect x=\"{x0}\" y=\"{:.1}\" width=\"{w:.1}\" height=\"{:.1}\" fill=\"rgb({r},{gr},{b})\"><title>{} {}: {:.3} ms</title></rect><text x=\"{:.1}\" y=\"{:.1}\">{:.3} ms, {:.3} Gpix/s</text>\n",
                x0 - 6.0,
                y + row - 5.0,
                m.backend,
                y + 2.0,
                row - 4.0,
                m.workload,
                m.backend,
                m.median_ms,
                x0 + w + 6.0,
                y + row - 5.0,
                m.median_ms,
                m.gpixels_per_s
            );
            y += row;
        }
    }
    svg += "</svg>\n";
    svg
}

/// Writes `bench.json`, `bench.png` and `bench.svg` into `dir`.
pub fn write_outputs(results: &[Measurement], dir: &Path) -> Result<()> {
    crate::output::check_dir(dir)?;
    crate::output::write_file(&dir.join("bench.json"), to_json(results).as_bytes())?;
    crate::output::write_file(&dir.join("bench.svg"), chart_svg(results).as_bytes())?;
    crate::output::write_png(&dir.join("bench.png"), &chart_png(results))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tiny_run_measures_every_pair_and_charts_it() {
        let options = BenchOptions {
            set: WorkloadSet::Quick,
            width: 64,
            height: 48,
            samples: 1,
            meshes: vec![],
        };
        let (mut steps, mut total) = (0, 0);
        let results = run(&options, &mut |p| {
            assert_eq!(p.done, steps);
            (steps, total) = (steps + 1, p.total);
        })
        .unwrap();
        assert_eq!(steps, total);
        assert_eq!(results.len(), steps);
        let fill: Vec<&Measurement> = results.iter().filter(|m| m.workload == "fill-1").collect();
        assert_eq!(fill.len(), triangle_backends().len());
        assert!(fill.iter().all(|m| m.pixels == 64 * 48));
        assert!(results.iter().any(|m| (m.vs_slowest - 1.0).abs() < 1e-12));
        assert!(results.iter().all(|m| m.vs_slowest >= 1.0));
        let json: serde_json::Value = serde_json::from_str(&to_json(&results)).unwrap();
        assert_eq!(json.as_array().unwrap().len(), results.len());
        let png = chart_png(&results);
        let coloured = png.pixels().filter(|p| p.0 != [255, 255, 255, 255]).count();
        assert!(coloured > 100);
        assert!(chart_svg(&results).matches("<title>").count() == results.len());
    }
}
