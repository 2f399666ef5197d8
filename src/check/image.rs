//! Whole renders graded within a tolerance (`check --image`), as UCR
//! CS 130's graders grade them: for each test (a scene, its size and its
//! render settings) the program under test renders the scene to a PNG,
//! rasterlab renders it itself (as `rasterlab render` does), and the two
//! images are compared ([`ImageMetrics`]): a test passes when the mean of
//! the largest channel difference, the share of pixels past the
//! threshold and the PSNR are all within the test's bounds.
//!
//! The program is started once per test through `sh -c`, its command
//! line's placeholders replaced: `{scene}` (a scene file's path, or a
//! built-in scene's name), `{size}` (`WxH`), `{width}`, `{height}`,
//! `{settings}` (the test's `rasterlab render` options, as words) and
//! `{out}` (the PNG file to write). A program that fails, hangs, writes
//! nothing, writes what is not a PNG or a PNG of another size fails that
//! test with what it did; one that gives no image on any test is broken.
//!
//! ```
//! use rasterlab::check::{run_images, ImageOutcome, ImageRequest, ImageTest};
//!
//! // A program that writes no image: each test says so, and the program,
//! // giving no image on any test, is broken (exit status 2).
//! let out = tempfile::tempdir().unwrap();
//! let mut request = ImageRequest::new("true {out}", out.path());
//! request.tests = vec![ImageTest::new("depth-example")];
//! let report = run_images(&request).unwrap();
//! assert_eq!(report.results[0].size, (14, 9));
//! assert_eq!(report.results[0].outcome, ImageOutcome::NoImage("wrote no image".into()));
//! assert_eq!(report.exit_code(), 2);
//! ```

use super::grader::{gradescope_of, junit_of, rerun_command, GraderTest};
use super::image_diff::{diff_image, diff_svg, ImageMetrics};
use super::process::{in_own_group, kill_tree};
use crate::error::{Error, Result};
use crate::geometry::Floor;
use crate::geometry::{CullMode, FrontFace, Scene2D, Shading};
use crate::measure::{RenderInput, RenderRequest};
use crate::raster::{BlendMode, DepthState, FillRule, Interpolation, MixSpace, SamplePattern};
use image::RgbaImage;
use serde::Deserialize;
use std::fmt;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Duration;
use wait_timeout::ChildExt;

/// The scenes tested when the configuration names none: the built-in
/// opaque 2D scenes, each at its own size.
pub const DEFAULT_IMAGE_SCENES: [&str; 5] =
    ["depth-example", "split-square", "pinwheel", "fan", "cycle"];

/// When a test's images are close enough.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageThresholds {
    /// A pixel's largest channel difference (0 to 255) past which it
    /// counts as differing.
    pub threshold: u8,
    /// The largest mean over pixels of the largest channel difference.
    pub max_mean: f64,
    /// The largest share of pixels (0 to 1) past `threshold`.
    pub max_share: f64,
    /// The least PSNR in dB, if any.
    pub min_psnr: Option<f64>,
}

impl Default for ImageThresholds {
    /// A pixel differs past 32 of 255 in a channel; a test passes at a
    /// mean of at most 1 and at most 1 % of its pixels past that, with
    /// no bound on the PSNR.
    fn default() -> ImageThresholds {
        ImageThresholds {
            threshold: 32,
            max_mean: 1.0,
            max_share: 0.01,
            min_psnr: None,
        }
    }
}

impl fmt::Display for ImageThresholds {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "a pixel past {}/255 in a channel; mean <= {}, share past <= {} %, PSNR >= {}",
            self.threshold,
            self.max_mean,
            self.max_share * 100.0,
            self.min_psnr
                .map_or("none".to_string(), |p| format!("{p} dB"))
        )
    }
}

/// The thresholds a configuration may give, for every test or one.
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThresholdConfig {
    /// See [`ImageThresholds::threshold`].
    pub threshold: Option<u8>,
    /// See [`ImageThresholds::max_mean`].
    pub max_mean: Option<f64>,
    /// See [`ImageThresholds::max_share`].
    pub max_share: Option<f64>,
    /// See [`ImageThresholds::min_psnr`].
    pub min_psnr: Option<f64>,
}

impl ThresholdConfig {
    fn over(&self, base: ImageThresholds) -> Result<ImageThresholds> {
        let t = ImageThresholds {
            threshold: self.threshold.unwrap_or(base.threshold),
            max_mean: self.max_mean.unwrap_or(base.max_mean),
            max_share: self.max_share.unwrap_or(base.max_share),
            min_psnr: self.min_psnr.or(base.min_psnr),
        };
        if !(t.max_mean.is_finite() && (0.0..=255.0).contains(&t.max_mean)) {
            return Err(Error::InvalidArgument(format!(
                "max_mean must be from 0 to 255, not {}",
                t.max_mean
            )));
        }
        if !(t.max_share.is_finite() && (0.0..=1.0).contains(&t.max_share)) {
            return Err(Error::InvalidArgument(format!(
                "max_share must be from 0 to 1, not {}",
                t.max_share
            )));
        }
        if t.min_psnr.is_some_and(|p| !p.is_finite()) {
            return Err(Error::InvalidArgument("min_psnr must be a number".into()));
        }
        Ok(t)
    }
}

/// One test as a configuration gives it.
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImageTestConfig {
    /// The test's name (default: the scene).
    pub name: Option<String>,
    /// A built-in scene's name, or a scene or mesh file.
    pub scene: String,
    /// `WxH` (default: the scene's own size, 640x480 for a mesh).
    pub size: Option<String>,
    /// `rasterlab render` options, as words.
    #[serde(default)]
    pub settings: String,
    /// The test's points in a grader's report (default 1).
    pub weight: Option<f64>,
    /// The test's own thresholds.
    #[serde(flatten)]
    pub thresholds: ThresholdConfig,
}

/// The `images` part of a teacher's configuration (`check --config`).
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImageConfig {
    /// The thresholds of every test that does not give its own.
    #[serde(flatten)]
    pub thresholds: ThresholdConfig,
    /// The tests (default: [`DEFAULT_IMAGE_SCENES`]).
    #[serde(default)]
    pub tests: Vec<ImageTestConfig>,
}

/// One test: a scene rendered at a size with settings.
#[derive(Clone, Debug, PartialEq)]
pub struct ImageTest {
    /// Its name in the report.
    pub name: String,
    /// A built-in scene's name, or a scene or mesh file.
    pub scene: String,
    /// The size; `None`: the scene's own (640x480 for a mesh).
    pub size: Option<(u32, u32)>,
    /// `rasterlab render` options, as words.
    pub settings: String,
    /// Its thresholds; `None`: the request's.
    pub thresholds: Option<ImageThresholds>,
    /// Its points in a grader's report.
    pub weight: f64,
}

impl ImageTest {
    /// A test of `scene` at its own size, default settings and thresholds.
    pub fn new(scene: &str) -> ImageTest {
        ImageTest {
            name: scene.to_string(),
            scene: scene.to_string(),
            size: None,
            settings: String::new(),
            thresholds: None,
            weight: 1.0,
        }
    }
}

/// What `check --image` is asked.
#[derive(Clone, Debug, PartialEq)]
pub struct ImageRequest {
    /// The program's command line, with placeholders.
    pub command: String,
    /// The tests, in order.
    pub tests: Vec<ImageTest>,
    /// The thresholds of tests without their own.
    pub thresholds: ImageThresholds,
    /// Whether `thresholds` are the defaults (the report says so).
    pub default_thresholds: bool,
    /// How long the program may take on one test.
    pub timeout: Duration,
    /// The folder of the diff images.
    pub out: PathBuf,
    /// The command line that ran the check, for the rerun hint.
    pub check_command: String,
}

impl ImageRequest {
    /// The default tests and thresholds, a 5 s limit, the diff images
    /// written to `out`.
    pub fn new(command: &str, out: &Path) -> ImageRequest {
        ImageRequest {
            command: command.to_string(),
            tests: DEFAULT_IMAGE_SCENES
                .iter()
                .map(|s| ImageTest::new(s))
                .collect(),
            thresholds: ImageThresholds::default(),
            default_thresholds: true,
            timeout: Duration::from_secs(5),
            out: out.to_path_buf(),
            check_command: String::new(),
        }
    }

    /// Sets what a configuration's `images` part gives.
    pub fn configure(&mut self, config: &ImageConfig) -> Result<()> {
        self.thresholds = config.thresholds.over(ImageThresholds::default())?;
        self.default_thresholds = config.thresholds == ThresholdConfig::default();
        if !config.tests.is_empty() {
            self.tests = config
                .tests
                .iter()
                .map(|t| {
                    let size = match &t.size {
                        Some(s) => Some(parse_size(s)?),
                        None => None,
                    };
                    let weight = t.weight.unwrap_or(1.0);
                    if !(weight.is_finite() && (0.0..=1e6).contains(&weight)) {
                        return Err(Error::InvalidArgument(format!(
                            "the weight of image test {} must be from 0 to 1000000",
                            t.name.as_deref().unwrap_or(&t.scene)
                        )));
                    }
                    Ok(ImageTest {
                        name: t.name.clone().unwrap_or_else(|| t.scene.clone()),
                        scene: t.scene.clone(),
                        size,
                        settings: t.settings.clone(),
                        thresholds: (t.thresholds != ThresholdConfig::default())
                            .then(|| t.thresholds.over(self.thresholds))
                            .transpose()?,
                        weight,
                    })
                })
                .collect::<Result<_>>()?;
        }
        Ok(())
    }
}

/// `WxH`, each side at least 1.
fn parse_size(text: &str) -> Result<(u32, u32)> {
    let bad = || Error::InvalidArgument(format!("size `{text}`: expected WxH, e.g. 64x48"));
    let (w, h) = text.split_once('x').ok_or_else(bad)?;
    match (w.trim().parse(), h.trim().parse()) {
        (Ok(w), Ok(h)) if w > 0 && h > 0 => Ok((w, h)),
        _ => Err(bad()),
    }
}

/// The reference render of `test`, its settings read as `rasterlab
/// render` reads them.
fn reference_request(test: &ImageTest, out: &Path) -> Result<RenderRequest> {
    let input = if Scene2D::BUILT_IN.contains(&test.scene.as_str()) || test.scene == Floor::NAME {
        RenderInput::Scene(test.scene.clone())
    } else {
        RenderInput::File(PathBuf::from(&test.scene))
    };
    let mut r = RenderRequest::new(input, out);
    r.size = test.size;
    let mut words = test.settings.split_whitespace();
    while let Some(option) = words.next() {
        if option == "--sort" {
            r.sort = true;
            continue;
        }
        let value = words.next().ok_or_else(|| {
            Error::InvalidArgument(format!("image test {}: {option} takes a value", test.name))
        })?;
        let bad =
            |e: String| Error::InvalidArgument(format!("image test {}: {option}: {e}", test.name));
        let number = |v: &str| v.parse::<f32>().map_err(|e| bad(e.to_string()));
        match option {
            "--backend" => r.backend = Some(value.to_string()),
            "--rule" => r.rule = value.parse::<FillRule>()?,
            "--depth-test" => r.depth = DepthState::from_name(value)?,
            "--blend" => r.blend.mode = BlendMode::from_name(value).map_err(bad)?,
            "--mix-in" => r.blend.mix_in = MixSpace::from_name(value).map_err(bad)?,
            "--msaa" => {
                let n = value.parse::<u32>().map_err(|e| bad(e.to_string()))?;
                r.msaa = (n > 1).then(|| SamplePattern::standard(n)).transpose()?;
            }
            "--shading" => r.mesh.shading = Some(value.parse::<Shading>()?),
            "--cull" => r.mesh.cull = Some(value.parse::<CullMode>()?),
            "--front-face" => r.mesh.front_face = Some(value.parse::<FrontFace>()?),
            "--interpolation" => r.mesh.interpolation = Some(value.parse::<Interpolation>()?),
            "--azimuth" => r.mesh.azimuth = Some(number(value)?),
            "--elevation" => r.mesh.elevation = Some(number(value)?),
            "--zoom" => r.mesh.zoom = Some(number(value)?),
            other => {
                return Err(Error::UnknownName {
                    what: "image test setting",
                    name: other.to_string(),
                    known: "--backend, --rule, --depth-test, --blend, --mix-in, --msaa, --sort, \
                            --shading, --cull, --front-face, --interpolation, --azimuth, \
                            --elevation, --zoom"
                        .into(),
                })
            }
        }
    }
    Ok(r)
}

/// A PNG file read as RGBA; `Err` says what the file is instead.
fn read_png(path: &Path) -> std::result::Result<RgbaImage, String> {
    let bytes = std::fs::read(path).map_err(|_| "wrote no image".to_string())?;
    if !bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
        return Err(format!(
            "wrote a file that is not a PNG ({} bytes)",
            bytes.len()
        ));
    }
    image::load_from_memory_with_format(&bytes, image::ImageFormat::Png)
        .map(|i| i.to_rgba8())
        .map_err(|e| format!("wrote a PNG that cannot be read: {e}"))
}

/// Quotes a word for `sh`.
fn shell_quote(word: &str) -> String {
    format!("'{}'", word.replace('\'', r"'\''"))
}

/// Runs the program on one test; its image, or what went wrong.
fn run_subject(
    request: &ImageRequest,
    test: &ImageTest,
    (width, height): (u32, u32),
    out: &Path,
) -> std::result::Result<RgbaImage, String> {
    let line = request
        .command
        .replace("{scene}", &shell_quote(&test.scene))
        .replace("{size}", &format!("{width}x{height}"))
        .replace("{width}", &width.to_string())
        .replace("{height}", &height.to_string())
        .replace("{settings}", &test.settings)
        .replace("{out}", &shell_quote(&out.to_string_lossy()));
    let mut command = Command::new("sh");
    command
        .arg("-c")
        .arg(&line)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    in_own_group(&mut command);
    let mut child = command
        .spawn()
        .map_err(|e| format!("cannot start `{line}`: {e}"))?;
    let mut stderr = child.stderr.take().expect("piped");
    let err_thread = std::thread::spawn(move || {
        let mut buf = Vec::new();
        let _ = (&mut stderr).take(4096).read_to_end(&mut buf);
        let _ = std::io::copy(&mut stderr, &mut std::io::sink());
        buf
    });
    let status = match child.wait_timeout(request.timeout) {
        Ok(Some(status)) => status,
        Ok(None) | Err(_) => {
            kill_tree(&mut child);
            return Err(format!(
                "ran past the time limit of {} s",
                request.timeout.as_secs_f64()
            ));
        }
    };
    let err = String::from_utf8_lossy(&err_thread.join().unwrap_or_default())
        .trim_end()
        .to_string();
    if !status.success() {
        return Err(format!(
            "failed ({status}){}",
            if err.is_empty() {
                String::new()
            } else {
                format!(": {err}")
            }
        ));
    }
    let image = read_png(out)?;
    if image.dimensions() != (width, height) {
        return Err(format!(
            "wrote a {}x{} PNG where {width}x{height} was asked",
            image.width(),
            image.height()
        ));
    }
    Ok(image)
}

/// What one test found.
#[derive(Clone, Debug, PartialEq)]
pub enum ImageOutcome {
    /// The images compared: the metrics, the bounds they broke (none:
    /// the test passes), the diff picture's files.
    Compared {
        /// The metrics.
        metrics: ImageMetrics,
        /// Each bound broken, in words.
        broken: Vec<String>,
        /// The diff image (PNG) and its picture with the legend (SVG).
        diff: [PathBuf; 2],
    },
    /// The program gave no image to compare: what it did.
    NoImage(String),
}

/// One test's result.
#[derive(Clone, Debug, PartialEq)]
pub struct ImageResult {
    /// The test.
    pub test: ImageTest,
    /// The size rendered.
    pub size: (u32, u32),
    /// The thresholds applied.
    pub thresholds: ImageThresholds,
    /// What it found.
    pub outcome: ImageOutcome,
}

impl ImageResult {
    /// Whether the test passes.
    pub fn passed(&self) -> bool {
        matches!(&self.outcome, ImageOutcome::Compared { broken, .. } if broken.is_empty())
    }
}

/// What `check --image` answers.
#[derive(Clone, Debug, PartialEq)]
pub struct ImageReport {
    /// The request.
    pub request: ImageRequest,
    /// One result per test, in order.
    pub results: Vec<ImageResult>,
}

/// Gradescope's `results.json` for `check --image`: a test per image
/// test, worth its weight.
pub fn image_gradescope(report: &ImageReport) -> serde_json::Value {
    gradescope_of(report.grader_tests(), report.summary())
}

/// JUnit XML for `check --image`: a testcase per image test.
pub fn image_junit(report: &ImageReport) -> String {
    junit_of(
        &report.grader_tests(),
        "image",
        &report.summary(),
        report.broken(),
    )
}

/// A test's name as part of a file name.
fn slug(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// Runs every test of `request`: rasterlab's render, the program's, the
/// comparison and the diff picture. A test whose scene or settings
/// rasterlab cannot render (a malformed file names its line) is an error
/// of the request, before the program runs on it.
pub fn run_images(request: &ImageRequest) -> Result<ImageReport> {
    crate::output::check_dir(&request.out)?;
    let temp = tempfile::Builder::new()
        .prefix("rasterlab-image-")
        .tempdir()
        .map_err(|e| Error::Io {
            path: std::env::temp_dir(),
            message: e.to_string(),
        })?;
    let mut results = Vec::new();
    for (i, test) in request.tests.iter().enumerate() {
        let expected_path = temp.path().join(format!("expected-{i}.png"));
        reference_request(test, &expected_path)?.run()?;
        let expected = read_png(&expected_path).map_err(|e| Error::Io {
            path: expected_path.clone(),
            message: e,
        })?;
        let size = expected.dimensions();
        let thresholds = test.thresholds.unwrap_or(request.thresholds);
        let actual_path = temp.path().join(format!("actual-{i}.png"));
        let outcome = match run_subject(request, test, size, &actual_path) {
            Err(what) => ImageOutcome::NoImage(what),
            Ok(actual) => {
                let metrics = ImageMetrics::compare(&expected, &actual, thresholds.threshold);
                let mut broken = Vec::new();
                if metrics.mean > thresholds.max_mean {
                    broken.push(format!(
                        "mean {:.3} > {}",
                        metrics.mean, thresholds.max_mean
                    ));
                }
                if metrics.share_past > thresholds.max_share {
                    broken.push(format!(
                        "{:.2} % of pixels past {} > {} %",
                        metrics.share_past * 100.0,
                        thresholds.threshold,
                        thresholds.max_share * 100.0
                    ));
                }
                if let (Some(least), psnr) = (thresholds.min_psnr, metrics.psnr) {
                    if psnr.is_some_and(|p| p < least) {
                        broken.push(format!("PSNR {:.2} dB < {least} dB", psnr.unwrap_or(0.0)));
                    }
                }
                let stem = request.out.join(format!("image-{}", slug(&test.name)));
                let diff = diff_image(&expected, &actual, thresholds.threshold);
                let png = stem.with_file_name(format!("image-{}-diff.png", slug(&test.name)));
                let svg = stem.with_file_name(format!("image-{}-diff.svg", slug(&test.name)));
                crate::output::write_png(&png, &diff)?;
                let caption = format!(
                    "Image test {}: {} of {} pixels past {}/255",
                    test.name,
                    (metrics.share_past * f64::from(size.0) * f64::from(size.1)).round(),
                    u64::from(size.0) * u64::from(size.1),
                    thresholds.threshold
                );
                crate::output::write_file(&svg, diff_svg(&diff, &caption).as_bytes())?;
                if !broken.is_empty() {
                    for (what, image) in [("expected", &expected), ("actual", &actual)] {
                        let path =
                            stem.with_file_name(format!("image-{}-{what}.png", slug(&test.name)));
                        crate::output::write_png(&path, image)?;
                    }
                }
                ImageOutcome::Compared {
                    metrics,
                    broken,
                    diff: [png, svg],
                }
            }
        };
        results.push(ImageResult {
            test: test.clone(),
            size,
            thresholds,
            outcome,
        });
    }
    Ok(ImageReport {
        request: request.clone(),
        results,
    })
}

impl ImageReport {
    /// Whether the program gave no image on any test: broken, not wrong.
    pub fn broken(&self) -> bool {
        !self.results.is_empty()
            && self
                .results
                .iter()
                .all(|r| matches!(r.outcome, ImageOutcome::NoImage(_)))
    }

    /// 0: every test passes; 1: one fails; 2: the program is broken.
    pub fn exit_code(&self) -> u8 {
        if self.broken() {
            2
        } else if self.results.iter().all(ImageResult::passed) {
            0
        } else {
            1
        }
    }

    /// The report as the program's result: `Err` with the first failure.
    pub fn outcome(&self) -> Result<()> {
        let first = self.results.iter().find(|r| !r.passed());
        match (self.exit_code(), first) {
            (0, _) | (_, None) => Ok(()),
            (2, Some(r)) => Err(Error::InvalidArgument(format!(
                "the program gave no image on any test: broken, not wrong; on {}: it {}",
                r.test.name,
                match &r.outcome {
                    ImageOutcome::NoImage(what) => what.as_str(),
                    ImageOutcome::Compared { .. } => "",
                }
            ))),
            (_, Some(r)) => Err(Error::Mismatch(format!(
                "the image check failed: {}: {}",
                r.test.name,
                r.verdict_words()
            ))),
        }
    }

    /// One grader test per image test, worth its weight.
    pub(crate) fn grader_tests(&self) -> Vec<GraderTest> {
        let rerun = rerun_command(&self.request.check_command);
        self.results
            .iter()
            .map(|r| {
                let passed = r.passed();
                let mut output = r.to_string();
                if !passed {
                    output.push_str(&format!("\nrerun: {rerun}"));
                }
                GraderTest {
                    name: format!("image {}", r.test.name),
                    passed: u32::from(passed),
                    total: 1,
                    points: r.test.weight,
                    message: if passed {
                        String::new()
                    } else {
                        r.verdict_words()
                    },
                    kind: match r.outcome {
                        ImageOutcome::NoImage(_) => "no-image",
                        ImageOutcome::Compared { .. } => "image-differs",
                    }
                    .into(),
                    output,
                }
            })
            .collect()
    }

    /// The summary line graders show.
    pub(crate) fn summary(&self) -> String {
        let passed = self.results.iter().filter(|r| r.passed()).count();
        let mut s = format!(
            "rasterlab check --image of {}: {passed} of {} image test(s) pass",
            self.request.command,
            self.results.len()
        );
        if self.broken() {
            s.push_str("\nthe program could not be judged: it gave no image on any test");
        }
        s
    }
}

impl ImageResult {
    /// Why the test fails, in one line (empty when it passes).
    fn verdict_words(&self) -> String {
        match &self.outcome {
            ImageOutcome::NoImage(what) => format!("the program {what}"),
            ImageOutcome::Compared { broken, .. } => broken.join("; "),
        }
    }
}

impl fmt::Display for ImageResult {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let word = match (&self.outcome, self.passed()) {
            (ImageOutcome::NoImage(_), _) => "NO IMAGE",
            (_, true) => "PASS",
            (_, false) => "FAIL",
        };
        write!(
            f,
            "{word}: {} ({} at {}x{}{})",
            self.test.name,
            self.test.scene,
            self.size.0,
            self.size.1,
            if self.test.settings.is_empty() {
                String::new()
            } else {
                format!(", {}", self.test.settings)
            }
        )?;
        match &self.outcome {
            ImageOutcome::NoImage(what) => write!(f, "\n  the program {what}"),
            ImageOutcome::Compared {
                metrics,
                broken,
                diff,
            } => {
                write!(
                    f,
                    "\n  mean {:.3}, {:.2} % of pixels past {}/255 (largest {}), PSNR {}",
                    metrics.mean,
                    metrics.share_past * 100.0,
                    metrics.threshold,
                    metrics.max,
                    metrics
                        .psnr
                        .map_or("infinite (equal)".to_string(), |p| format!("{p:.2} dB"))
                )?;
                if !broken.is_empty() {
                    write!(f, "\n  beyond the bounds: {}", broken.join("; "))?;
                }
                write!(f, "\n  diff: {}", diff[1].display())
            }
        }
    }
}

impl fmt::Display for ImageReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "thresholds{}: {}",
            if self.request.default_thresholds {
                " (the defaults)"
            } else {
                ""
            },
            self.request.thresholds
        )?;
        for r in &self.results {
            writeln!(f, "{r}")?;
            if r.thresholds != self.request.thresholds {
                writeln!(f, "  this test's thresholds: {}", r.thresholds)?;
            }
        }
        write!(f, "{}", self.summary())
    }
}
