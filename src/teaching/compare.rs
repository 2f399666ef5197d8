//! `compare`: every back-end on one input file, as a self-contained HTML
//! report (see [`Report`]) and a table of their work and time.
//!
//! ```no_run
//! use rasterlab::teaching::{compare, CompareRequest};
//! use std::path::Path;
//!
//! let summary = compare(&CompareRequest {
//!     input: Path::new("assets/polygon.txt"),
//!     width: 64,
//!     height: 64,
//!     samples: 3,
//!     out: Path::new("compare-output"),
//!     msaa: None,
//! })
//! .unwrap();
//! print!("{summary}");
//! ```

use crate::error::{Error, Result};
use crate::geometry::input::{read_shapes, Shapes};
use crate::geometry::mesh::Mesh;
use crate::geometry::scene::Scene2D;
use crate::raster::line::LineSetup;
use crate::raster::multisample::SamplePattern;
use crate::teaching::report::{CompareInput, Report};
use crate::teaching::scan_or_triangulate::ScanOrTriangulate;
use std::fmt;
use std::path::{Path, PathBuf};

/// What to compare, and where the report goes.
#[derive(Clone, Copy, Debug)]
pub struct CompareRequest<'a> {
    /// A triangle soup or polygon file, a line set file, or a mesh.
    pub input: &'a Path,
    /// Target width in pixels.
    pub width: u32,
    /// Target height in pixels.
    pub height: u32,
    /// Timed runs per back-end (the median is reported).
    pub samples: usize,
    /// The folder the report (`index.html`) is written to.
    pub out: &'a Path,
    /// Multisample the triangles on this pattern (`--msaa N`); `None`:
    /// one sample per pixel.
    pub msaa: Option<SamplePattern>,
}

/// The comparison, and where its report was written.
pub struct CompareSummary {
    /// The comparison.
    pub report: Report,
    /// The report's HTML file.
    pub path: PathBuf,
    /// For a file of polygons, the same polygons filled directly beside
    /// their triangulation.
    pub polygons: Option<ScanOrTriangulate>,
}

/// The target size a comparison defaults to: for a mesh, 320 x 240,
/// enough to show its shape (at 64 x 64 the res2 dragon is 1,195
/// fragments); for 2D triangles and lines, given in pixels, 64 x 64.
///
/// ```
/// use rasterlab::teaching::default_compare_size;
/// use std::path::Path;
/// assert_eq!(default_compare_size(Path::new("dragon.ply.gz")), (320, 240));
/// assert_eq!(default_compare_size(Path::new("assets/polygon.txt")), (64, 64));
/// ```
pub fn default_compare_size(input: &Path) -> (u32, u32) {
    if Mesh::is_mesh_path(input) {
        (320, 240)
    } else {
        (64, 64)
    }
}

/// Reads the input, runs every back-end on it, and writes the report.
pub fn compare(request: &CompareRequest<'_>) -> Result<CompareSummary> {
    let (width, height) = (request.width, request.height);
    crate::raster::target::RenderTarget::check_size(width, height)?;
    Report::check_memory(width, height)?;
    // The input first: bad input leaves nothing behind, not even the
    // output directory, which is checked (and created) before the work.
    let input = load(request.input, width, height)?;
    Report::check_multisampled(&input, width, height, request.msaa).map_err(|e| match e {
        Error::InvalidArgument(why) => {
            Error::InvalidArgument(format!("{}: {why}", request.input.display()))
        }
        e => e,
    })?;
    crate::output::check_dir(request.out)?;
    let report =
        Report::compare_multisampled(&input, width, height, request.samples, request.msaa)?;
    let path = report.write(request.out)?;
    let polygons = match Mesh::is_mesh_path(request.input) || request.input.as_os_str() == "-" {
        true => None,
        false => ScanOrTriangulate::of_file(request.input, width, height, request.samples)?,
    };
    Ok(CompareSummary {
        report,
        path,
        polygons,
    })
}

/// A mesh (by its extension), a triangle soup or polygon file, or a line set.
fn load(path: &Path, width: u32, height: u32) -> Result<CompareInput> {
    if Mesh::is_mesh_path(path) {
        return Ok(CompareInput::Mesh(Box::new(Mesh::load(path)?)));
    }
    Ok(match read_shapes(path)? {
        Shapes::Triangles { triangles, .. } => {
            CompareInput::Triangles(Scene2D::from_triangles(width, height, triangles))
        }
        Shapes::Lines { segments, .. } => CompareInput::Lines(LineSetup::numbered(&segments)),
    })
}

impl fmt::Display for CompareSummary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let report = &self.report;
        if report.samples_per_pixel > 1 {
            writeln!(
                f,
                "multisampled: {} samples per pixel, the images resolved by a box filter",
                report.samples_per_pixel
            )?;
        }
        writeln!(f, "reference: {}", report.reference_note)?;
        writeln!(
            f,
            "{:<12} {:>10} {:>10} {:>9} {:>10}  differing pixels vs {}",
            "back-end", "fragments", "tested", "tests/frag", "time", report.reference
        )?;
        for run in &report.runs {
            writeln!(
                f,
                "{:<12} {:>10} {:>10} {:>9} {:>8.3}ms  {}",
                run.name,
                run.work.fragments,
                run.work.samples_tested,
                run.tests_per_fragment_text(),
                run.time.as_secs_f64() * 1e3,
                run.differing_pixels
            )?;
        }
        if let Some(why) = &report.antialias_skipped {
            writeln!(f, "{why}")?;
        }
        if let Some(aa) = &report.antialias {
            writeln!(
                f,
                "anti-aliasing, each method's coverage against the exact area (per triangle, in the picture):"
            )?;
            writeln!(
                f,
                "{:<24} {:>7} {:>9} {:>7} {:>9} {:>7} {:>8}",
                "method", "samples", "RMS/tri", "worst", "RMS/pic", "worst", "ns/pair"
            )?;
            for r in &aa.rows {
                writeln!(
                    f,
                    "{:<24} {:>7} {:>9.4} {:>7.3} {:>9.4} {:>7.3} {:>8.0}",
                    r.name,
                    if r.samples == 0 {
                        "exact".to_string()
                    } else {
                        r.samples.to_string()
                    },
                    r.per_triangle.rms,
                    r.per_triangle.worst,
                    r.picture.rms,
                    r.picture.worst,
                    r.ns_per_pair
                )?;
            }
        }
        if let Some(polygons) = &self.polygons {
            write!(f, "{polygons}")?;
        }
        writeln!(f, "report: {}", self.path.display())
    }
}

/// The texture filters compared on the receding floor (`compare
/// --textures`): the table, and where its chart was written.
pub struct TextureSummary {
    /// Every method's error and cost.
    pub comparison: crate::measure::TextureComparison,
    /// The chart (`textures.svg` in the output folder).
    pub chart: PathBuf,
}

/// [`compare_textures`](crate::measure::compare_textures) on the floor at
/// `width` x `height`, the ground truth `truth_samples` a side, each frame
/// timed `samples` times; the chart written to `out/textures.svg`.
pub fn compare_texture_filters(
    width: u32,
    height: u32,
    truth_samples: u32,
    samples: usize,
    out: &Path,
) -> Result<TextureSummary> {
    // Bad input first: it leaves no output directory behind.
    crate::geometry::Floor::check_truth_samples(truth_samples)?;
    check_texture_work(width, height, truth_samples, samples)?;
    let floor = crate::geometry::Floor::new(width, height)?;
    crate::output::check_dir(out)?;
    let comparison = crate::measure::compare_textures(&floor, truth_samples, None, samples)?;
    let chart = out.join("textures.svg");
    let svg = crate::teaching::texture_chart::texture_chart_svg(&comparison);
    crate::output::write_file(&chart, svg.as_bytes())?;
    Ok(TextureSummary { comparison, chart })
}

/// Seconds a pixel of the floor costs the texture comparison: its ground
/// truth per bilinear sample, and each round of the 38 methods. Measured
/// on a 2-core machine of the benchmarks, rounded up; the bound below is
/// an order of magnitude, not a promise.
const TRUTH_SECONDS_PER_SAMPLE: f64 = 2.5e-8;
const METHODS_SECONDS_PER_ROUND: f64 = 2e-5;

/// Refuses, with an estimate, a texture comparison that would run for
/// more than an hour.
fn check_texture_work(width: u32, height: u32, truth: u32, samples: usize) -> Result<()> {
    let pixels = f64::from(width) * f64::from(height);
    let seconds = pixels
        * (TRUTH_SECONDS_PER_SAMPLE * f64::from(truth) * f64::from(truth)
            + METHODS_SECONDS_PER_ROUND * samples as f64);
    if seconds > 3600.0 {
        return Err(Error::TooMuchWork(format!(
            "comparing the texture filters on {width}x{height} with --truth {truth} and \
             --samples {samples} would take about {:.1} hours: give a smaller --size, --truth \
             or --samples",
            seconds / 3600.0
        )));
    }
    Ok(())
}

impl fmt::Display for TextureSummary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.comparison)?;
        writeln!(f, "chart: {}", self.chart.display())
    }
}
