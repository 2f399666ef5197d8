//! The benchmark workloads, shared by `cargo bench` and `rasterlab bench`.
//!
//! Every triangle workload is drawn through the shared stage as a real
//! frame is: depth test `less` with depth writes, a constant colour
//! written, coverage counted. Every line workload is drawn in a constant
//! colour with the depth test off. So the figures are pixels *finished*
//! per second, not fragments found.
//!
//! | workload | what it measures |
//! |---|---|
//! | `fill-L` | two triangles covering the target, `L` layers drawn back to front (every layer passes the depth test) |
//! | `size-S` | right triangles of side `S` px, about 200,000 pixels in all |
//! | `sliver-A` | 60 slivers 1.5 px wide and 500 px long at angle `A` degrees |
//! | `lines-short` | short segments, 2 to 16 px |
//! | `lines-long` | 1000 px segments |

use crate::geometry::pipeline::{draw_clearing, draw_runs, Geometry, Pass};
use crate::geometry::scene::setup_triangles;
use crate::measure::fast_lines::draw_lines;
use crate::raster::descriptor::{within_budget, WorkBudget};
use crate::raster::edge::FillRule;
use crate::raster::edge::PixelRect;
use crate::raster::fixed::FixedPoint;
use crate::raster::fragment::WorkCounters;
use crate::raster::line::LineSetup;
use crate::raster::line::{LineOptions, LineRasterizer};
use crate::raster::primitive::{ShadedLine, ShadedVertex};
use crate::raster::shader::to_rgba8;
use crate::raster::shader::Constant;
use crate::raster::srgb::MixSpace;
use crate::raster::stage::{Blend, BlendMode, FragmentStage, Interpolation};
use crate::raster::target::{Clear, DepthState, DepthTest, RenderTarget};
use crate::raster::triangle::TriangleRasterizer;
use glam::Vec4;

/// The colour every workload writes.
pub const WORKLOAD_COLOR: Vec4 = Vec4::new(0.2, 0.5, 0.9, 1.0);

/// The colour of the blended fills: `WORKLOAD_COLOR` at opacity 1/2.
pub const BLENDED_COLOR: Vec4 = Vec4::new(0.2, 0.5, 0.9, 0.5);

fn p(x: f32, y: f32) -> FixedPoint {
    FixedPoint::snap(x, y).expect("workload coordinates lie inside the guard band")
}

/// Triangles ready to draw: set-up and stage data.
#[derive(Clone, Debug)]
pub struct TriangleWorkload {
    /// Short name, e.g. `fill-4`.
    pub name: String,
    /// The triangles, in drawing order.
    pub geometry: Geometry,
    /// Each triangle's depth (all three corners), by triangle id, for
    /// peers that draw the same triangles.
    pub depths: Vec<f32>,
}

impl TriangleWorkload {
    /// Triangles at depths `depth(i)`, set up under the top-left rule.
    pub fn new(name: String, triangles: &[[FixedPoint; 3]], depth: impl Fn(usize) -> f32) -> Self {
        let setups = setup_triangles(triangles, FillRule::TopLeft);
        let vertices: Vec<[ShadedVertex; 3]> = (0..triangles.len())
            .map(|i| [ShadedVertex::flat(depth(i), WORKLOAD_COLOR); 3])
            .collect();
        TriangleWorkload {
            name,
            geometry: Geometry::of_screen_triangles(setups, &vertices),
            depths: (0..triangles.len()).map(&depth).collect(),
        }
    }

    /// The number of triangles.
    pub fn triangles(&self) -> usize {
        self.geometry.setups.len()
    }

    /// Whether timing `backend` on this workload is sensible: within a
    /// [timing's budget](WorkBudget::Timing), so a back-end whose work does
    /// not follow the triangles' size (the naive loop tests every pixel
    /// against every triangle) runs only on the two-triangle fills. The
    /// budget is per pixel, so the target's size does not matter (1 pixel).
    pub fn suits(&self, backend: &dyn TriangleRasterizer) -> bool {
        within_budget(
            &backend.descriptor(),
            self.triangles() as u64,
            1,
            WorkBudget::Timing,
        )
        .is_ok()
    }

    /// Clears `target`'s depth and coverage and draws the workload with
    /// `backend`; returns the fragments drawn. The clear is folded into the
    /// draw ([`draw_clearing`]), as a renderer does it.
    pub fn run(&self, backend: &dyn TriangleRasterizer, target: &mut RenderTarget) -> u64 {
        draw_clearing(
            &self.geometry,
            backend,
            &Constant(WORKLOAD_COLOR),
            DepthState::DEFAULT,
            Interpolation::PerspectiveCorrect,
            Clear::DEPTH_AND_COVERAGE,
            target,
        )
        .fragments
    }

    /// Clears `target`'s colour and draws the workload with `backend` and
    /// no depth buffer ([`DepthState::OFF`]): the colour-only fill a 2D
    /// library does. Returns the fragments drawn.
    pub fn run_colour_only(
        &self,
        backend: &dyn TriangleRasterizer,
        target: &mut RenderTarget,
    ) -> u64 {
        draw_clearing(
            &self.geometry,
            backend,
            &Constant(WORKLOAD_COLOR),
            DepthState::OFF,
            Interpolation::PerspectiveCorrect,
            Clear::color(RenderTarget::BLACK),
            target,
        )
        .fragments
    }

    /// [`run_colour_only`](Self::run_colour_only) with
    /// the workload colour at opacity 1/2, composited by `over` of a
    /// straight fragment mixed in `mix_in`: the alpha-blended fill of a
    /// 2D library. Returns the fragments drawn.
    pub fn run_blended(
        &self,
        backend: &dyn TriangleRasterizer,
        mix_in: MixSpace,
        target: &mut RenderTarget,
    ) -> u64 {
        let pass = Pass {
            shader: &Constant(BLENDED_COLOR),
            depth: DepthState::OFF,
            interpolation: Interpolation::PerspectiveCorrect,
            clear: Clear::color(RenderTarget::BLACK),
            blend: Blend {
                mode: BlendMode::OverStraight,
                mix_in,
                ..Blend::REPLACE
            },
        };
        draw_runs(&self.geometry.runs(), backend, pass, target).fragments
    }
}

/// Line segments ready to draw: set-up and stage data.
#[derive(Clone, Debug)]
pub struct LineWorkload {
    /// Short name, e.g. `lines-short`.
    pub name: String,
    /// The segments, in drawing order.
    pub lines: Vec<LineSetup>,
    /// Their stage data (depth 0.5, the workload colour).
    pub shaded: Vec<ShadedLine>,
}

impl LineWorkload {
    /// The segments `lines`.
    pub fn new(name: &str, lines: Vec<LineSetup>) -> LineWorkload {
        let shaded = lines
            .iter()
            .map(|l| ShadedLine {
                from: l.from,
                to: l.to,
                vertices: [ShadedVertex::flat(0.5, WORKLOAD_COLOR); 2],
            })
            .collect();
        LineWorkload {
            name: name.to_string(),
            lines,
            shaded,
        }
    }

    /// Clears depth and coverage of `target` and draws the segments with
    /// `backend` (default options) through the stage, depth test off;
    /// returns the back-end's work.
    pub fn run(&self, backend: &dyn LineRasterizer, target: &mut RenderTarget) -> WorkCounters {
        self.run_blended(backend, Blend::REPLACE, target)
    }

    /// [`run`](Self::run), each fragment merged by `blend` (an
    /// anti-aliased line's coverage mixed in its space).
    pub fn run_blended(
        &self,
        backend: &dyn LineRasterizer,
        blend: Blend,
        target: &mut RenderTarget,
    ) -> WorkCounters {
        target.clear_depth_and_coverage();
        let shader = Constant(WORKLOAD_COLOR);
        let viewport = PixelRect::of_target(target.width(), target.height());
        let mut stage = FragmentStage::new(target, &shader)
            .with_lines(&self.shaded)
            .with_blend(blend)
            .with_depth(DepthState {
                test: DepthTest::Always,
                write: false,
            });
        backend.rasterize(&self.lines, &LineOptions::DEFAULT, viewport, &mut stage)
    }

    /// Clears the coverage of `target` and draws the segments with the
    /// fast line path; returns the pixels written. The same colour and
    /// coverage as [`run`](Self::run) with `bresenham`; depth, which lines
    /// drawn with the test `always` and no depth write never touch, is left
    /// as it is.
    pub fn run_fast(&self, target: &mut RenderTarget) -> u64 {
        target.coverage.fill(0);
        draw_lines(target, &self.lines, to_rgba8(WORKLOAD_COLOR))
    }
}

/// Two triangles covering a `width` x `height` target, `layers` times,
/// each layer nearer than the one before.
pub fn fill(width: u32, height: u32, layers: usize) -> TriangleWorkload {
    let (w, h) = (width as f32, height as f32);
    let tris: Vec<[FixedPoint; 3]> = (0..layers)
        .flat_map(|_| {
            [
                [p(0., 0.), p(w, 0.), p(w, h)],
                [p(0., 0.), p(w, h), p(0., h)],
            ]
        })
        .collect();
    TriangleWorkload::new(format!("fill-{layers}"), &tris, |i| {
        1.0 - (i / 2 + 1) as f32 / (layers + 1) as f32
    })
}

/// Right triangles of side `size` px laid on a `width` x `height` target,
/// about 200,000 pixels in all (so each size does the same pixel work).
pub fn sized(width: u32, height: u32, size: f32) -> TriangleWorkload {
    let per_side = ((400_000.0 / (size * size)).sqrt().ceil() as usize).max(1);
    let (w, h) = (
        (width as f32 - size - 1.0).max(1.0),
        (height as f32 - size - 1.0).max(1.0),
    );
    let mut tris = Vec::with_capacity(per_side * per_side);
    for j in 0..per_side {
        for i in 0..per_side {
            let x = 0.3 + (i as f32 * (size + 1.0)) % w;
            let y = 0.7 + (j as f32 * (size + 1.0)) % h;
            tris.push([p(x, y), p(x + size, y), p(x, y + size)]);
        }
    }
    TriangleWorkload::new(format!("size-{size}"), &tris, |i| {
        1.0 - (i % 1000) as f32 * 1e-4
    })
}

/// 60 slivers, 1.5 px wide and 500 px long, at `angle` degrees.
pub fn slivers(width: u32, height: u32, angle: f32) -> TriangleWorkload {
    let (dx, dy) = (angle.to_radians().cos(), angle.to_radians().sin());
    let (nx, ny) = (-dy * 1.5, dx * 1.5);
    let tris: Vec<[FixedPoint; 3]> = (0..60)
        .map(|k| {
            let t = k as f32 / 60.0;
            let x = 5.3 + t * (width as f32 - 10.0 - 500.0 * dx);
            let y = 5.7 + t * (height as f32 - 10.0 - 500.0 * dy);
            let far = (x + 500.0 * dx, y + 500.0 * dy);
            [p(x, y), p(far.0, far.1), p(x + nx, y + ny)]
        })
        .collect();
    TriangleWorkload::new(format!("sliver-{angle}"), &tris, |i| 0.9 - i as f32 * 1e-3)
}

/// A repeatable stream of numbers in `[0, 1)` (a linear congruential
/// generator), so every run draws the same lines.
fn numbers() -> impl FnMut() -> f32 {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// `count` segments 2 to 16 px long in every direction.
pub fn short_lines(width: u32, height: u32, count: usize) -> Vec<LineSetup> {
    let mut next = numbers();
    (0..count)
        .map(|i| {
            let (x, y) = (next() * width as f32, next() * height as f32);
            let (len, angle) = (2.0 + next() * 14.0, next() * std::f32::consts::TAU);
            LineSetup {
                id: i as u32,
                from: p(x, y),
                to: p(x + len * angle.cos(), y + len * angle.sin()),
            }
        })
        .collect()
}

/// `count` segments 1000 px long in every direction, from near the centre.
pub fn long_lines(width: u32, height: u32, count: usize) -> Vec<LineSetup> {
    let mut next = numbers();
    let (cx, cy) = (width as f32 / 2.0, height as f32 / 2.0);
    (0..count)
        .map(|i| {
            let (x, y) = (cx + (next() - 0.5) * 100.0, cy + (next() - 0.5) * 100.0);
            let angle = next() * std::f32::consts::TAU;
            let (ex, ey) = (x + 1000.0 * angle.cos(), y + 1000.0 * angle.sin());
            LineSetup {
                id: i as u32,
                from: p(x - 500.0 * angle.cos(), y - 500.0 * angle.sin()),
                to: p(ex - 500.0 * angle.cos(), ey - 500.0 * angle.sin()),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::registry::triangle_backends;

    #[test]
    fn workloads_draw_what_they_say() {
        let mut target = RenderTarget::new(64, 48).unwrap();
        let fill = fill(64, 48, 3);
        for b in triangle_backends() {
            assert_eq!(fill.run(*b, &mut target), 3 * 64 * 48);
            assert_eq!(target.pixels_with_coverage(3), 64 * 48);
        }
        let sliver = slivers(640, 640, 45.0);
        assert_eq!(sliver.triangles(), 60);
        let lines = long_lines(1920, 1080, 10);
        let len = |l: &LineSetup| {
            let (a, b) = (l.from.to_f64(), l.to.to_f64());
            ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt()
        };
        assert!(lines.iter().all(|l| (len(l) - 1000.0).abs() < 0.01));
        assert!(short_lines(100, 100, 100)
            .iter()
            .all(|l| (1.99..16.01).contains(&len(l))));
    }
}
