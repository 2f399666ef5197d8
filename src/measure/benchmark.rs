//! `rasterlab bench`: every back-end on the same workloads, timed in one
//! run, with a table, JSON and a bar chart, and the context that makes the
//! figures readable (commit, machine, load, threads, samples, size).
//!
//! Each (workload, back-end) pair is run `samples` times after one warm-up
//! run; its figure is the **median** time, shown with the minimum and
//! maximum beside it (the machine is shared and noisy: the spread says how
//! far a figure can be trusted, and two back-ends whose spreads overlap
//! are not ranked), and the CPU time its threads got per run with the time
//! they waited for a core ([`crate::measure::CpuUse`]). From the median: a
//! throughput in the workload's own unit (pixels for the fills, triangle
//! sizes and slivers, triangles for meshes, lines for lines), and the ratio
//! to the **fastest** back-end on that workload, the baseline of both the
//! table and the chart. For published crates side by side, rounds
//! interleaved, `cargo bench --bench side_by_side`.

use crate::error::Result;
use crate::geometry::mesh::Mesh;
use crate::geometry::pipeline::CullMode;
use crate::geometry::render::{MeshRenderer, RenderSettings, Shading};
use crate::markup::Markup;
use crate::measure::context::Context;
use crate::measure::cpu::CpuUse;
use crate::measure::table::significant;
use crate::measure::table::Table;
use crate::measure::timing::{time_runs, Spread, Timing};
use crate::measure::workload::{self, LineWorkload};
use crate::raster::derivatives::Derivatives;
use crate::raster::descriptor::{within_budget, WorkBudget};
use crate::raster::registry::{default_triangle_backend, line_backends, triangle_backends};
use crate::raster::target::RenderTarget;
use crate::raster::texture::LevelMode;
use serde::Serialize;
use std::fmt;
use std::path::Path;
use std::time::Duration;

/// What the ratio column and the chart's bars compare with.
pub const BASELINE: &str = "the fastest back-end on the same workload";

/// One measured (workload, back-end) pair.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Measurement {
    /// Workload name.
    pub workload: String,
    /// Back-end name.
    pub backend: String,
    /// Threads it drew on.
    pub threads: usize,
    /// Primitives (triangles or lines) per run.
    pub primitives: u64,
    /// Pixels written per run.
    pub pixels: u64,
    /// Wall time of the timed runs: minimum, median, maximum.
    pub spread: Spread,
    /// Median time of one run, in milliseconds (`spread.median_ms`).
    pub median_ms: f64,
    /// Throughput at the median time, in [`unit`](Self::unit).
    pub rate: f64,
    /// The throughput's unit, chosen per workload: `Gpix/s` (fills),
    /// `Mpix/s` (triangle sizes, slivers), `Mtri/s` (meshes) or
    /// `Mlines/s`.
    pub unit: String,
    /// Billions of pixels per second at the median time.
    pub gpixels_per_s: f64,
    /// The median time over the fastest back-end's on this workload
    /// ([`BASELINE`]): 1 for the fastest, 2 for half its speed.
    pub vs_fastest: f64,
    /// CPU time per run of each working thread, and time spent waiting
    /// for a core (`None` where the system does not tell).
    pub cpu: Option<CpuUse>,
    /// The helper pixels a run shaded beside its `pixels`, where its
    /// texture's derivatives are taken in 2x2 quads (the meshes'
    /// `-textured` workloads); `None` elsewhere.
    pub helpers: Option<u64>,
}

/// A whole `rasterlab bench` run: its context and its figures. Its
/// `Display` is the table, its JSON the same with every field.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BenchReport {
    /// Commit, machine, load, threads, samples, target size.
    pub context: Context,
    /// What `vs_fastest` and the chart compare with ([`BASELINE`]).
    pub baseline: String,
    /// One figure per (workload, back-end).
    pub results: Vec<Measurement>,
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
pub(crate) fn median_time<T>(samples: usize, run: impl FnMut() -> T) -> (Duration, T) {
    let (timing, first) = time_runs(samples, run);
    (
        Duration::from_secs_f64(timing.spread.median_ms / 1e3),
        first,
    )
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

/// The throughput unit of a workload, its scale (items per unit), and
/// whether it counts pixels (else primitives): the fills in Gpix/s; the
/// triangle sizes, which all draw about the same pixels, and the slivers
/// in Mpix/s; meshes in Mtri/s; lines in Mlines/s.
fn unit_of(workload: &str) -> (&'static str, f64, bool) {
    if workload.starts_with("fill") {
        ("Gpix/s", 1e9, true)
    } else if workload.starts_with("size") || workload.starts_with("sliver") {
        ("Mpix/s", 1e6, true)
    } else if workload.starts_with("lines") {
        ("Mlines/s", 1e6, false)
    } else {
        ("Mtri/s", 1e6, false)
    }
}

/// Runs the benchmark on the current rayon pool's threads; `progress` is
/// called before each pair is timed.
pub fn run(options: &BenchOptions, progress: &mut dyn FnMut(Progress)) -> Result<BenchReport> {
    RenderTarget::check_size(options.width, options.height)?;
    let (w, h) = (options.width, options.height);
    let threads = rayon::current_num_threads();
    let mut context = Context::start(threads, options.samples.max(1), w, h);
    let mut results = Vec::new();
    // Colour and depth, as the peers draw: the coverage count is a
    // checking aid that a renderer does not need.
    let mut target = RenderTarget::without_coverage(w, h)?;
    let mut measure = |workload: &str, backend: &str, prims: u64, timing: Timing, pixels: u64| {
        let s = (timing.spread.median_ms / 1e3).max(1e-12);
        let (unit, scale, of_pixels) = unit_of(workload);
        let items = if of_pixels { pixels } else { prims };
        results.push(Measurement {
            workload: workload.to_string(),
            backend: backend.to_string(),
            threads,
            primitives: prims,
            pixels,
            median_ms: timing.spread.median_ms,
            spread: timing.spread,
            rate: items as f64 / s / scale,
            unit: unit.to_string(),
            gpixels_per_s: pixels as f64 / s / 1e9,
            vs_fastest: 1.0,
            cpu: timing.cpu,
            helpers: None,
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
            meshes.iter().all(|(_, mesh)| {
                let triangles = mesh.triangles.len() as u64;
                within_budget(&b.descriptor(), triangles, 1, WorkBudget::Timing).is_ok()
            })
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
        + meshes.len() * (mesh_backends.len() + 1);
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
            let (timing, pixels) = time_runs(options.samples, || work.run(*b, &mut target));
            measure(
                &work.name,
                b.name(),
                work.triangles() as u64,
                timing,
                pixels,
            );
        }
    }

    for work in &line_workloads {
        let count = work.lines.len() as u64;
        for b in line_backends() {
            step(&work.name, b.name());
            let (timing, pixels) =
                time_runs(options.samples, || work.run(*b, &mut target).fragments);
            measure(&work.name, b.name(), count, timing, pixels);
        }
        step(&work.name, "fast-bresenham");
        let (timing, pixels) = time_runs(options.samples, || work.run_fast(&mut target));
        measure(&work.name, "fast-bresenham", count, timing, pixels);
    }

    let mut helpers = Vec::new();
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
            let (timing, pixels) = time_runs(options.samples, || {
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
            measure(name, b.name(), mesh.triangles.len() as u64, timing, pixels);
        }
        // Textured, trilinear, the derivatives in 2x2 quads as GPUs take
        // them: the helper pixels the quads shade beside the fragments.
        let textured = RenderSettings {
            shading: Shading::Texture,
            mip: LevelMode::Linear,
            derivatives: Derivatives::Quad,
            ..settings
        };
        let renderer = MeshRenderer::new(mesh, textured)?;
        let backend = default_triangle_backend();
        let workload = format!("{name}-textured");
        step(&workload, backend.name());
        let (timing, work) = time_runs(options.samples, || {
            renderer.render_into(backend, &mut target)
        });
        let work = work?.work;
        measure(
            &workload,
            backend.name(),
            mesh.triangles.len() as u64,
            timing,
            work.fragments,
        );
        helpers.push((workload, work.helpers));
    }
    for (workload, count) in helpers {
        for m in results.iter_mut().filter(|m| m.workload == workload) {
            m.helpers = Some(count);
        }
    }

    // Ratios to the fastest back-end of each workload.
    for i in 0..results.len() {
        let fastest = results
            .iter()
            .filter(|m| m.workload == results[i].workload)
            .map(|m| m.median_ms)
            .fold(f64::INFINITY, f64::min);
        results[i].vs_fastest = results[i].median_ms / fastest.max(1e-12);
    }
    context.finish();
    Ok(BenchReport {
        context,
        baseline: BASELINE.to_string(),
        results,
    })
}

/// A mesh file's name without its extensions.
fn mesh_name(path: &Path) -> String {
    let name = path
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    name.split('.').next().unwrap_or_default().to_string()
}

impl BenchReport {
    /// The figures as a table with aligned columns: median [min-max] ms,
    /// throughput, pixels, time over the fastest's, CPU per thread.
    pub fn table(&self) -> Table {
        let mut table = Table::with_text_columns(
            2,
            &[
                "workload",
                "back-end",
                "ms median [min-max]",
                "throughput",
                "pixels",
                "vs fastest",
                "cpu ms per thread, waited",
            ],
        );
        for m in &self.results {
            table.row(vec![
                m.workload.clone(),
                m.backend.clone(),
                m.spread.summary(),
                format!("{} {}", significant(m.rate), m.unit),
                m.pixels.to_string(),
                format!("{}x", significant(m.vs_fastest)),
                m.cpu
                    .as_ref()
                    .map_or_else(|| "unknown".to_string(), CpuUse::summary),
            ]);
        }
        table
    }
}

impl fmt::Display for BenchReport {
    /// The context, the table, and what "vs fastest" means.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}{}", self.context, self.table())?;
        for m in &self.results {
            if let Some(helpers) = m.helpers {
                let shaded = (m.pixels + helpers).max(1);
                writeln!(
                    f,
                    "{} (trilinear, quad derivatives): {} fragments and {helpers} helper pixels shaded, helpers {:.1}% of them",
                    m.workload,
                    m.pixels,
                    100.0 * helpers as f64 / shaded as f64
                )?;
            }
        }
        writeln!(
            f,
            "vs fastest: the median time over that of {} (1x = fastest; the chart's baseline too)",
            self.baseline
        )
    }
}

/// The report as JSON: the context, the baseline, and every figure.
pub fn to_json(report: &BenchReport) -> String {
    serde_json::to_string_pretty(report).expect("measurements serialise")
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

/// The measurements of `workload`.
fn group<'a>(results: &'a [Measurement], workload: &str) -> Vec<&'a Measurement> {
    results.iter().filter(|m| m.workload == workload).collect()
}

/// The chart as an image: [`chart_svg`] rendered with the bundled font
/// (`resvg`), so the PNG has the same axis, labels
/// and values. Only with the `png-text` feature (on by default).
#[cfg(feature = "png-text")]
pub fn chart_png(report: &BenchReport) -> image::RgbaImage {
    crate::output::svg_to_png(&chart_svg(report))
        .unwrap_or_else(|| image::RgbaImage::from_pixel(1, 1, image::Rgba([255, 255, 255, 255])))
}

/// A horizontal bar chart: one group per workload, one labelled bar per
/// back-end, bar length the speed relative to the fastest back-end on that
/// workload ([`BASELINE`], as the table's), the axis at the bottom, 0 to
/// 1, each bar's median time with its minimum and maximum and its
/// throughput written beside it, the run's context under the title.
pub fn chart_svg(report: &BenchReport) -> String {
    let results = &report.results;
    let names = backend_names(results);
    let workloads = workload_names(results);
    let (label_w, bar_w, value_w) = (130.0, 440.0, 330.0);
    let (row, header, top) = (17.0, 24.0, 60.0);
    let x0 = 10.0 + label_w;
    let rows: usize = workloads.iter().map(|w| group(results, w).len()).sum();
    let plot_h = workloads.len() as f64 * header + rows as f64 * row;
    let width = x0 + bar_w + value_w;
    let height = top + plot_h + 50.0;
    let mut m = Markup::new();
    m.open_svg(width, height, Some(11)).newline();
    m.empty(
        "rect",
        &[("width", &"100%"), ("height", &"100%"), ("fill", &"white")],
    )
    .newline();
    m.element(
        "text",
        &[
            ("x", &10),
            ("y", &22),
            ("font-size", &14),
            ("font-weight", &"bold"),
        ],
        "rasterlab bench: speed relative to the fastest back-end on each workload",
    )
    .newline();
    let c = &report.context;
    let load = c
        .machine
        .load_average
        .map_or_else(|| "unknown".to_string(), |l| format!("{:.2}", l[0]));
    m.element(
        "text",
        &[("x", &10), ("y", &40)],
        &format!(
            "commit {}, {}x{}, {} thread(s), {} timed runs per bar; {}, {} cores, load average {load} at start",
            c.commit, c.width, c.height, c.threads, c.samples, c.machine.cpu, c.machine.cores
        ),
    )
    .newline();
    // Vertical grid lines and the axis.
    let axis_y = top + plot_h + 4.0;
    let one = |v: f64| format!("{v:.1}");
    for k in 0..=4 {
        let f = f64::from(k) / 4.0;
        let x = one(x0 + f * bar_w);
        m.empty(
            "line",
            &[
                ("x1", &x),
                ("y1", &top),
                ("x2", &x),
                ("y2", &one(axis_y)),
                ("stroke", &"#ddd"),
            ],
        );
        m.element(
            "text",
            &[
                ("x", &x),
                ("y", &one(axis_y + 14.0)),
                ("text-anchor", &"middle"),
            ],
            &f.to_string(),
        )
        .newline();
    }
    m.empty(
        "line",
        &[
            ("x1", &x0),
            ("y1", &one(axis_y)),
            ("x2", &one(x0 + bar_w)),
            ("y2", &one(axis_y)),
            ("stroke", &"#333"),
        ],
    );
    m.element(
        "text",
        &[
            ("x", &one(x0 + bar_w / 2.0)),
            ("y", &one(axis_y + 32.0)),
            ("text-anchor", &"middle"),
        ],
        "speed relative to the fastest (1 = fastest; median [min-max] ms and throughput beside each bar)",
    )
    .newline();
    let mut y = top;
    for wl in &workloads {
        let members = group(results, wl);
        let prims = members.first().map_or(0, |m| m.primitives);
        y += header;
        m.element(
            "text",
            &[("x", &10), ("y", &one(y - 7.0)), ("font-weight", &"bold")],
            &format!("{wl} ({prims} primitives)"),
        )
        .newline();
        for r in members {
            let k = names.iter().position(|n| *n == r.backend).unwrap_or(0);
            let [red, green, blue] = PALETTE[k % PALETTE.len()];
            let rel = 1.0 / r.vs_fastest.max(1.0);
            let w = (rel * bar_w).max(1.0);
            m.element(
                "text",
                &[
                    ("x", &one(x0 - 6.0)),
                    ("y", &one(y + row - 5.0)),
                    ("text-anchor", &"end"),
                ],
                &r.backend,
            );
            m.open(
                "rect",
                &[
                    ("x", &x0),
                    ("y", &one(y + 2.0)),
                    ("width", &one(w)),
                    ("height", &one(row - 4.0)),
                    ("fill", &format_args!("rgb({red},{green},{blue})")),
                ],
            );
            m.element(
                "title",
                &[],
                &format!("{} {}: {} ms", r.workload, r.backend, r.spread.summary()),
            );
            m.close("rect");
            m.element(
                "text",
                &[("x", &one(x0 + w + 6.0)), ("y", &one(y + row - 5.0))],
                &format!(
                    "{} ms, {} {}",
                    r.spread.summary(),
                    significant(r.rate),
                    r.unit
                ),
            )
            .newline();
            y += row;
        }
    }
    m.close("svg").newline();
    m.finish()
}

/// Writes `bench.json`, `bench.svg` and (with the `png-text` feature, on
/// by default) `bench.png` into `dir`.
pub fn write_outputs(report: &BenchReport, dir: &Path) -> Result<()> {
    crate::output::check_dir(dir)?;
    crate::output::write_file(&dir.join("bench.json"), to_json(report).as_bytes())?;
    crate::output::write_file(&dir.join("bench.svg"), chart_svg(report).as_bytes())?;
    #[cfg(feature = "png-text")]
    crate::output::write_png(&dir.join("bench.png"), &chart_png(report))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One tiny run with the bundled dragon, shared by the tests.
    fn tiny_run() -> &'static BenchReport {
        static REPORT: std::sync::OnceLock<BenchReport> = std::sync::OnceLock::new();
        REPORT.get_or_init(run_tiny)
    }

    fn run_tiny() -> BenchReport {
        let dragon = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/dragon_vrip_res4.ply.gz");
        let options = BenchOptions {
            set: WorkloadSet::Quick,
            width: 64,
            height: 48,
            samples: 1,
            meshes: vec![dragon],
        };
        let (mut steps, mut total) = (0, 0);
        let results = run(&options, &mut |p| {
            assert_eq!(p.done, steps);
            (steps, total) = (steps + 1, p.total);
        })
        .unwrap();
        assert_eq!(steps, total);
        assert_eq!(results.results.len(), steps);
        results
    }

    #[test]
    fn a_tiny_run_measures_every_pair_and_charts_it() {
        let report = tiny_run();
        let results = &report.results;
        let fill: Vec<&Measurement> = results.iter().filter(|m| m.workload == "fill-1").collect();
        assert_eq!(fill.len(), triangle_backends().len());
        assert!(fill.iter().all(|m| m.pixels == 64 * 48));
        assert!(results.iter().any(|m| (m.vs_fastest - 1.0).abs() < 1e-12));
        assert!(results.iter().all(|m| m.vs_fastest >= 1.0));
        let json: serde_json::Value = serde_json::from_str(&to_json(report)).unwrap();
        assert_eq!(json["results"].as_array().unwrap().len(), results.len());
        #[cfg(feature = "png-text")]
        {
            let png = chart_png(report);
            let coloured = png.pixels().filter(|p| p.0 != [255, 255, 255, 255]).count();
            assert!(coloured > 100);
        }
        assert!(chart_svg(report).matches("<title>").count() == results.len());
    }

    #[test]
    fn the_json_records_the_context_and_the_spread_of_every_figure() {
        let report = tiny_run();
        let json: serde_json::Value = serde_json::from_str(&to_json(report)).unwrap();
        let context = &json["context"];
        assert_eq!(context["commit"], crate::measure::context::COMMIT);
        assert_ne!(context["commit"], "");
        assert_eq!(context["threads"], rayon::current_num_threads());
        assert_eq!(context["samples"], 1);
        assert_eq!(
            (context["width"].as_u64(), context["height"].as_u64()),
            (Some(64), Some(48))
        );
        let machine = &context["machine"];
        assert!(!machine["cpu"].as_str().unwrap().is_empty());
        assert!(machine["cores"].as_u64().unwrap() >= 1);
        assert!(machine.get("load_average").is_some());
        assert!(context.get("load_average_at_end").is_some());
        assert_eq!(json["baseline"], BASELINE);
        for row in json["results"].as_array().unwrap() {
            let spread = &row["spread"];
            let (min, median, max) = (
                spread["min_ms"].as_f64().unwrap(),
                spread["median_ms"].as_f64().unwrap(),
                spread["max_ms"].as_f64().unwrap(),
            );
            assert!(min <= median && median <= max, "{row}");
            assert_eq!(spread["runs"], 1);
            assert_eq!(row["median_ms"].as_f64(), Some(median));
            assert_eq!(row["threads"], rayon::current_num_threads());
            assert!(row["rate"].as_f64().unwrap() > 0.0, "{row}");
            assert!(row["vs_fastest"].as_f64().unwrap() >= 1.0);
            assert!(row.get("cpu").is_some());
            let unit = row["unit"].as_str().unwrap();
            let workload = row["workload"].as_str().unwrap();
            let expected = match workload {
                w if w.starts_with("fill") => "Gpix/s",
                w if w.starts_with("size") || w.starts_with("sliver") => "Mpix/s",
                w if w.starts_with("lines") => "Mlines/s",
                _ => "Mtri/s",
            };
            assert_eq!(unit, expected, "{workload}");
        }
    }

    #[test]
    fn the_table_keeps_its_columns_aligned_and_shows_no_zero_rates() {
        let report = tiny_run();
        assert!(report
            .results
            .iter()
            .any(|m| m.workload == "dragon_vrip_res4"));
        let table = report.table().to_string();
        let widths: Vec<usize> = table.lines().map(|l| l.chars().count()).collect();
        // The last column is aligned right: every line ends at one column.
        assert!(widths.iter().all(|w| *w == widths[0]), "{table}");
        let header = table.lines().next().unwrap();
        let column = header.find("throughput").unwrap() + "throughput".len();
        for line in table.lines().skip(1) {
            assert!(line[..column].ends_with("/s"), "{line}");
            assert!(!line.contains(" 0.00 "), "{line}");
        }
        let text = report.to_string();
        assert!(text.starts_with(&format!("commit {}", report.context.commit)));
        assert!(text.contains("load average"));
        assert!(text
            .trim_end()
            .ends_with("(1x = fastest; the chart's baseline too)"));
    }
}
