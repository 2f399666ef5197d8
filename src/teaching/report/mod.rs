//! The side-by-side comparison report (`rasterlab compare`).
//!
//! Every back-end of the input's kind draws the same input through the
//! shared fragment stage. The report puts side by side:
//!
//! * each back-end's image, and its **difference image** against the
//!   reference (`naive` for triangles when it runs in reasonable time,
//!   else `bbox`; `bresenham` for lines): pixels whose colour, depth or
//!   coverage differ are vermillion, the others a faded copy of the
//!   reference.
//!   Triangle back-ends must all be identical; line back-ends are
//!   different algorithms and may differ;
//! * the **work table**: fragments emitted, samples tested, tests per
//!   fragment, rows or blocks visited, time (median of a few runs, for a
//!   rough idea; `rasterlab bench` and `cargo bench` measure properly);
//! * the **fill-rule pictures**: the input drawn under every fill rule, as
//!   heat maps of each pixel's fragment count against the watertight
//!   rules ([`GridPicture::coverage_heat_map`]), then the same for the line-drawing
//!   slides' edge-drawing problem (the pinwheel);
//! * for 2D triangles, **anti-aliasing**: each way of sampling a pixel
//!   (one sample, multisampling on the standard patterns, supersampling
//!   on regular grids) against the exact area each triangle covers
//!   ([`compare_antialiasing`]), as a table of errors and as pictures
//!   shaded by coverage;
//! * for small targets, the **zoomed grid pictures** of each back-end
//!   ([`GridPicture`]): which pixels it tested, which it emitted.
//!
//! Every colour is [the one palette](super::palette)'s, and every section
//! with coloured pictures shows its legend. The HTML file is
//! self-contained: pictures are embedded as PNG or SVG.
//!
//! ```
//! use rasterlab::geometry::Scene2D;
//! use rasterlab::teaching::{CompareInput, Report};
//!
//! let report = Report::compare(&CompareInput::Triangles(Scene2D::split_square()), 8, 8, 1).unwrap();
//! assert!(report.runs.iter().all(|r| r.differing_pixels == 0));
//! assert!(report.to_html().contains("<table"));
//! ```

mod html;

use crate::error::{Error, Result};
use crate::geometry::mesh::Mesh;
use crate::geometry::render::{MeshRenderer, RenderSettings};
use crate::geometry::scene::Scene2D;
use crate::measure::antialias::{compare_antialiasing, coverage_of, AntialiasRow, Method};
use crate::measure::benchmark::median_time;
use crate::measure::workload::LineWorkload;
use crate::raster::descriptor::{within_budget, WorkBudget};
use crate::raster::edge::FillRule;
use crate::raster::fragment::WorkCounters;
use crate::raster::line::LineSetup;
use crate::raster::multisample::SamplePattern;
use crate::raster::multisample_stage::MultisampleTarget;
use crate::raster::registry::{
    default_triangle_backend, fallback_triangle_backend, line_backends, reference_triangle_backend,
    triangle_backends,
};
use crate::raster::shader::Flat;
use crate::raster::stage::Blend;
use crate::raster::target::{DepthState, RenderTarget};
use crate::raster::triangle::TriangleRasterizer;
use crate::teaching::grid_picture::{GridPicture, GAP, OVERDRAWN, OVERDRAWN_MORE};
use crate::teaching::palette::Role;
use std::time::Duration;

/// Largest target (in pixels) that gets zoomed grid pictures.
pub const GRID_PICTURE_PIXELS: u32 = 48 * 48;

/// Largest target (in pixels) whose anti-aliasing is compared: 8 x 8
/// supersampling draws 64 samples a pixel.
pub const ANTIALIAS_PIXELS: u32 = 512 * 512;

/// The methods whose pictures the anti-aliasing section shows.
const ANTIALIAS_PICTURES: [Method; 5] = [
    Method::Multisample(1),
    Method::Multisample(4),
    Method::Multisample(16),
    Method::Supersample(4),
    Method::Area,
];

/// The anti-aliasing section: each method's error against the exact
/// area, and pictures shaded by coverage.
#[derive(Clone, Debug)]
pub struct Antialiasing {
    /// One row per method ([`compare_antialiasing`]).
    pub rows: Vec<AntialiasRow>,
    /// Each pixel shaded by its triangles' coverage summed, for the
    /// methods of the pictures: the drawn colour over white, cut to the
    /// pixels the triangles cover and a margin of one.
    pub pictures: Vec<(Method, image::RgbImage)>,
    /// The first column and row of the pictures in the target.
    pub origin: (u32, u32),
}

impl Antialiasing {
    /// The comparison on `triangles` in a `width` x `height` target, under
    /// the top-left rule.
    pub fn of(
        triangles: &[[crate::raster::fixed::FixedPoint; 3]],
        width: u32,
        height: u32,
    ) -> Result<Antialiasing> {
        let rows = compare_antialiasing(triangles, width, height, FillRule::TopLeft)?;
        let rect = crate::raster::edge::PixelRect::of_target(width, height);
        let backend = default_triangle_backend();
        let [r, g, b] = Role::Drawn.rgb();
        // The pixels the triangles touch, and a margin of one.
        let touched = coverage_of(Method::Area, backend, triangles, rect, FillRule::TopLeft)?;
        let (x0, y0, x1, y1) = touched.iter().fold(
            (i64::from(width), i64::from(height), -1, -1),
            |(x0, y0, x1, y1), c| (x0.min(c.x), y0.min(c.y), x1.max(c.x), y1.max(c.y)),
        );
        let (x0, y0) = ((x0 - 1).max(0) as u32, (y0 - 1).max(0) as u32);
        let (x1, y1) = (
            (x1 + 1).clamp(0, i64::from(width) - 1) as u32,
            (y1 + 1).clamp(0, i64::from(height) - 1) as u32,
        );
        let (w, h) = (
            (x1 + 1).saturating_sub(x0).max(1),
            (y1 + 1).saturating_sub(y0).max(1),
        );
        let pictures = ANTIALIAS_PICTURES
            .iter()
            .map(|&method| {
                let mut shade = vec![0.0f64; (width * height) as usize];
                for c in coverage_of(method, backend, triangles, rect, FillRule::TopLeft)? {
                    let i = (c.y * i64::from(width) + c.x) as usize;
                    shade[i] = (shade[i] + c.value).min(1.0);
                }
                let mix = |ink: u8, a: f64| (255.0 + (f64::from(ink) - 255.0) * a).round() as u8;
                let picture = image::RgbImage::from_fn(w, h, |x, y| {
                    let a = shade[((y + y0) * width + x + x0) as usize];
                    image::Rgb([mix(r, a), mix(g, a), mix(b, a)])
                });
                Ok((method, picture))
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(Antialiasing {
            rows,
            pictures,
            origin: (x0, y0),
        })
    }
}

/// What to compare.
#[derive(Clone, Debug)]
pub enum CompareInput {
    /// 2D triangles (a soup, or a triangulated polygon).
    Triangles(Scene2D),
    /// 2D line segments.
    Lines(Vec<LineSetup>),
    /// A mesh, rendered by the 3D pipeline with the default camera.
    Mesh(Box<Mesh>),
}

/// One back-end's result.
#[derive(Clone, Debug)]
pub struct BackendRun {
    /// Back-end name.
    pub name: &'static str,
    /// What it does.
    pub description: &'static str,
    /// Its work counters.
    pub work: WorkCounters,
    /// Median drawing time.
    pub time: Duration,
    /// The buffers it produced.
    pub target: RenderTarget,
    /// Pixels whose colour, depth or coverage differ from the reference
    /// (0 for the reference itself).
    pub differing_pixels: usize,
}

impl BackendRun {
    /// Samples tested per fragment, to two decimals, or a dash when no
    /// fragment was drawn (the ratio means nothing then).
    pub fn tests_per_fragment_text(&self) -> String {
        if self.work.fragments == 0 {
            "—".to_string()
        } else {
            format!("{:.2}", self.work.tests_per_fragment())
        }
    }

    /// A run, not yet compared with the reference.
    fn new(
        name: &'static str,
        description: &'static str,
        work: WorkCounters,
        time: Duration,
        target: RenderTarget,
    ) -> BackendRun {
        BackendRun {
            name,
            description,
            work,
            time,
            target,
            differing_pixels: 0,
        }
    }
}

/// One fill-rule heat map with its counts.
#[derive(Clone, Debug)]
pub struct RulePicture {
    /// The fill rule.
    pub rule: FillRule,
    /// The heat map.
    pub picture: GridPicture,
    /// Pixels drawn less often than by every watertight rule.
    pub gaps: usize,
    /// Pixels drawn more often than by any watertight rule.
    pub overdrawn: usize,
}

/// A comparison of every back-end on one input.
#[derive(Clone, Debug)]
pub struct Report {
    /// A short description of the input.
    pub input: String,
    /// Target width.
    pub width: u32,
    /// Target height.
    pub height: u32,
    /// The reference back-end's name.
    pub reference: &'static str,
    /// Why it is the reference (and what was left out, if anything).
    pub reference_note: String,
    /// Samples per pixel the triangles were drawn with (1 without
    /// multisampling).
    pub samples_per_pixel: u32,
    /// True for a line set: no fill rules apply.
    pub lines: bool,
    /// One entry per back-end, the reference first.
    pub runs: Vec<BackendRun>,
    /// The input's fill-rule heat maps (triangles and meshes).
    pub rules: Vec<RulePicture>,
    /// The line-drawing slides' edge-drawing problem: the pinwheel's heat maps.
    pub pinwheel_rules: Vec<RulePicture>,
    /// Zoomed grid pictures per back-end (small targets only).
    pub grids: Vec<(&'static str, GridPicture)>,
    /// Anti-aliasing compared (2D triangles on targets of at most
    /// [`ANTIALIAS_PIXELS`] pixels).
    pub antialias: Option<Antialiasing>,
    /// Why 2D triangles' anti-aliasing was not compared, when it was not.
    pub antialias_skipped: Option<String>,
}

/// Whether pixel `i` of two targets differs in colour, depth or coverage.
fn pixel_differs(a: &RenderTarget, b: &RenderTarget, i: usize) -> bool {
    a.color[i] != b.color[i]
        || a.depth[i].to_bits() != b.depth[i].to_bits()
        || a.coverage[i] != b.coverage[i]
}

/// The triangle back-ends a report runs: all of them, but those whose work
/// does not follow the triangles' size (the naive loop) only while it stays
/// within [a report's budget](WorkBudget::Report); the reference is then
/// left out, and its fallback (listed next) is the reference.
fn triangle_backends_within_budget(
    pixels: u64,
    triangles: usize,
) -> impl Iterator<Item = &'static dyn TriangleRasterizer> {
    triangle_backends().iter().copied().filter(move |b| {
        within_budget(
            &b.descriptor(),
            triangles as u64,
            pixels,
            WorkBudget::Report,
        )
        .is_ok()
    })
}

/// The heat maps of `coverage_of(rule)` for every rule.
fn rule_pictures(
    width: u32,
    height: u32,
    mut coverage_of: impl FnMut(FillRule) -> Result<Vec<u16>>,
) -> Result<Vec<RulePicture>> {
    let coverages = FillRule::ALL
        .iter()
        .map(|&r| coverage_of(r))
        .collect::<Result<Vec<_>>>()?;
    let watertight = [coverages[0].as_slice(), coverages[1].as_slice()];
    FillRule::ALL
        .iter()
        .zip(&coverages)
        .map(|(&rule, coverage)| {
            let mut picture = GridPicture::coverage_heat_map(
                width,
                height,
                coverage,
                &watertight,
                String::new(),
            )?;
            let gaps = picture.count(GAP);
            let overdrawn = picture.count(OVERDRAWN) + picture.count(OVERDRAWN_MORE);
            picture.caption = format!("{}: {gaps} gap pixels, {overdrawn} overdrawn", rule.name());
            Ok(RulePicture {
                rule,
                picture,
                gaps,
                overdrawn,
            })
        })
        .collect()
}

/// Memory a report holds per target pixel, about: each back-end's target
/// (colour, depth, coverage), its difference image and the pictures
/// encoded in the page.
pub const REPORT_BYTES_PER_PIXEL: u64 = 256;

/// The most memory a report may need, by [`REPORT_BYTES_PER_PIXEL`].
pub const MAX_REPORT_BYTES: u64 = 4 << 30;

impl Report {
    /// Refuses, with an estimate, a report on a target so large that its
    /// images would not fit in [`MAX_REPORT_BYTES`].
    pub fn check_memory(width: u32, height: u32) -> Result<()> {
        let bytes = u64::from(width) * u64::from(height) * REPORT_BYTES_PER_PIXEL;
        if bytes > MAX_REPORT_BYTES {
            return Err(Error::TooMuchWork(format!(
                "a {width}x{height} report would hold about {:.1} GiB of images (at most {} GiB): give a smaller --size",
                bytes as f64 / f64::from(1u32 << 30),
                MAX_REPORT_BYTES >> 30
            )));
        }
        Ok(())
    }

    /// Runs every back-end of the input's kind on a `width` x `height`
    /// target, timing each as the median of `samples` runs.
    pub fn compare(
        input: &CompareInput,
        width: u32,
        height: u32,
        samples: usize,
    ) -> Result<Report> {
        Self::compare_multisampled(input, width, height, samples, None)
    }

    /// Errors unless `input` can be compared multisampled on `msaa`'s
    /// pattern at `width` x `height`: lines are not multisampled, and the
    /// sample buffers of one back-end at a time must be within
    /// [`MAX_TARGET_SAMPLES`](crate::raster::MAX_TARGET_SAMPLES).
    pub fn check_multisampled(
        input: &CompareInput,
        width: u32,
        height: u32,
        msaa: Option<SamplePattern>,
    ) -> Result<()> {
        let Some(pattern) = msaa else {
            return Ok(());
        };
        if let CompareInput::Lines(_) = input {
            return Err(Error::InvalidArgument(
                "--msaa multisamples triangles; a line set is drawn with lines, which are not multisampled".into(),
            ));
        }
        MultisampleTarget::new(width, height, pattern).map(drop)
    }

    /// [`compare`](Self::compare), each triangle back-end drawing through
    /// the multisampled stage on `msaa`'s pattern when it is given (the
    /// images are the resolved ones, and the grid pictures show the
    /// samples). Lines are not multisampled: a line set is refused.
    pub fn compare_multisampled(
        input: &CompareInput,
        width: u32,
        height: u32,
        samples: usize,
        msaa: Option<SamplePattern>,
    ) -> Result<Report> {
        Self::check_multisampled(input, width, height, msaa)?;
        RenderTarget::check_size(width, height)?;
        Self::check_memory(width, height)?;
        let pixels = u64::from(width) * u64::from(height);
        let small = width * height <= GRID_PICTURE_PIXELS;
        let mut runs = Vec::new();
        let mut rules = Vec::new();
        let mut grids = Vec::new();
        let mut antialias = None;
        let mut antialias_skipped = None;
        let description;
        match input {
            CompareInput::Triangles(scene) => {
                let scene = Scene2D {
                    width,
                    height,
                    ..scene.clone()
                };
                description = format!("{} triangles", scene.triangles.len());
                for b in triangle_backends_within_budget(pixels, scene.triangles.len()) {
                    let (time, drawn) = median_time(samples, || match msaa {
                        None => scene.render(b, FillRule::TopLeft, &Flat),
                        Some(pattern) => {
                            let mut target = MultisampleTarget::new(width, height, pattern)?;
                            let (work, _) = scene.render_frame_multisampled(
                                b,
                                FillRule::TopLeft,
                                (DepthState::DEFAULT, Blend::REPLACE),
                                &Flat,
                                RenderTarget::BLACK,
                                &mut target,
                            );
                            Ok((target.resolve(), work))
                        }
                    });
                    let (target, work) = drawn?;
                    runs.push(BackendRun::new(
                        b.name(),
                        b.description(),
                        work,
                        time,
                        target,
                    ));
                    if small {
                        let picture = GridPicture::of_snapped_triangles(
                            b,
                            &scene.triangles,
                            FillRule::TopLeft,
                            width,
                            height,
                        )?;
                        let picture = match &msaa {
                            Some(pattern) => {
                                picture.with_samples(&scene.triangles, FillRule::TopLeft, pattern)
                            }
                            None => picture,
                        };
                        grids.push((b.name(), picture));
                    }
                }
                let scanline = default_triangle_backend();
                rules = rule_pictures(width, height, |rule| {
                    Ok(scene.render(scanline, rule, &Flat)?.0.coverage)
                })?;
                if width * height > ANTIALIAS_PIXELS {
                    antialias_skipped = Some(format!(
                        "anti-aliasing not compared: the target has more than {ANTIALIAS_PIXELS} pixels"
                    ));
                } else {
                    match Antialiasing::of(&scene.triangles, width, height) {
                        Ok(a) => antialias = Some(a),
                        // A vertex too far off for 8 x 8 supersampling.
                        Err(e) => {
                            antialias_skipped = Some(format!("anti-aliasing not compared: {e}"))
                        }
                    }
                }
            }
            CompareInput::Lines(lines) => {
                description = format!("{} line segments", lines.len());
                let work = LineWorkload::new("input", lines.clone());
                for b in line_backends() {
                    let mut target = RenderTarget::new(width, height)?;
                    let (time, counters) = median_time(samples, || work.run(*b, &mut target));
                    runs.push(BackendRun::new(
                        b.name(),
                        b.description(),
                        counters,
                        time,
                        target,
                    ));
                }
            }
            CompareInput::Mesh(mesh) => {
                description = format!(
                    "mesh of {} triangles, default camera, back faces culled",
                    mesh.triangles.len()
                );
                let settings = |rule| {
                    let mut s = RenderSettings {
                        width,
                        height,
                        ..RenderSettings::default()
                    };
                    s.pipeline.rule = rule;
                    s.pipeline.cull = crate::geometry::pipeline::CullMode::Back;
                    s
                };
                let renderer = MeshRenderer::new(mesh, settings(FillRule::TopLeft))?;
                for b in triangle_backends_within_budget(pixels, mesh.triangles.len()) {
                    let (time, frame) = median_time(samples, || match msaa {
                        None => renderer.render(b).map(|f| (f.target, f.stats.work)),
                        Some(pattern) => {
                            let mut target = MultisampleTarget::new(width, height, pattern)?;
                            let stats = renderer.render_multisampled_into(b, &mut target)?;
                            Ok((target.resolve(), stats.work))
                        }
                    });
                    let (target, work) = frame?;
                    runs.push(BackendRun::new(
                        b.name(),
                        b.description(),
                        work,
                        time,
                        target,
                    ));
                }
                let scanline = default_triangle_backend();
                rules = rule_pictures(width, height, |rule| {
                    let frame = MeshRenderer::new(mesh, settings(rule))?.render(scanline)?;
                    Ok(frame.target.coverage)
                })?;
            }
        }
        let (reference, others) = runs
            .split_first_mut()
            .ok_or_else(|| Error::InvalidArgument("no back-end ran".into()))?;
        for run in others {
            run.differing_pixels = (0..run.target.color.len())
                .filter(|&i| pixel_differs(&reference.target, &run.target, i))
                .count();
        }
        let triangles_in = match input {
            CompareInput::Triangles(scene) => scene.triangles.len(),
            CompareInput::Mesh(mesh) => mesh.triangles.len(),
            CompareInput::Lines(_) => 0,
        };
        let reference_note = match input {
            CompareInput::Lines(_) => format!(
                "{}, the first line back-end; lines have no single exact answer, so the others' differences are their algorithms'",
                reference.name
            ),
            _ if reference.name == reference_triangle_backend().name() => format!(
                "{}, the course's loop over every pixel for every triangle",
                reference.name
            ),
            _ => format!(
                "{}: {} was left out, as its {triangles_in} triangles x {pixels} pixels = {} tests are beyond the report's budget of {}",
                reference.name,
                reference_triangle_backend().name(),
                triangles_in as u64 * pixels,
                WorkBudget::Report.tests(pixels)
            ),
        };
        let pinwheel = Scene2D::pinwheel();
        let bbox = fallback_triangle_backend();
        let pinwheel_rules = rule_pictures(pinwheel.width, pinwheel.height, |rule| {
            Ok(pinwheel.render(bbox, rule, &Flat)?.0.coverage)
        })?;
        let description = match msaa {
            Some(pattern) => format!(
                "{description}, multisampled: {} samples per pixel on the standard pattern, resolved by a box filter",
                pattern.count()
            ),
            None => description,
        };
        Ok(Report {
            input: description,
            width,
            height,
            reference: runs[0].name,
            reference_note,
            samples_per_pixel: msaa.map_or(1, SamplePattern::count),
            lines: matches!(input, CompareInput::Lines(_)),
            runs,
            rules,
            pinwheel_rules,
            grids,
            antialias,
            antialias_skipped,
        })
    }

    /// The difference image of `run` against the reference: differing
    /// pixels in [`Role::Differs`]' colour, the others a faded copy of the
    /// reference.
    pub fn difference_image(&self, run: &BackendRun) -> image::RgbaImage {
        let reference = &self.runs[0].target;
        let mut img = reference.to_image();
        for (i, p) in img.pixels_mut().enumerate() {
            p.0 = if !pixel_differs(reference, &run.target, i) {
                let [r, g, b, _] = p.0;
                let fade = |c: u8| (c as u16 / 3 + 150) as u8;
                [fade(r), fade(g), fade(b), 255]
            } else {
                let [r, g, b] = Role::Differs.rgb();
                [r, g, b, 255]
            };
        }
        img
    }
}
