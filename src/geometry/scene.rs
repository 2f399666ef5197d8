//! Small 2D scenes in screen pixels, and helpers to draw them.
//!
//! A [`Scene2D`] is a list of snapped triangles with a depth and colour per
//! vertex. The built-in scenes are the course's examples: the rasterization slides'
//! depth-buffer example, the rules' split square, a pinwheel of triangles
//! around one pixel centre and a fan.

use crate::error::{Error, Result};
use crate::geometry::frame_times::FrameTimes;
use crate::geometry::input::Look;
use crate::geometry::pipeline::{draw_runs, Geometry, Pass};
use crate::raster::edge::{FillRule, PixelRect, TriangleSetup};
use crate::raster::fixed::FixedPoint;
use crate::raster::fragment::{FragmentList, WorkCounters};
use crate::raster::multisample_stage::{draw_multisampled, MultisampleTarget};
use crate::raster::primitive::{ShadedVertex, TriangleData};
use crate::raster::shader::FragmentShader;
use crate::raster::stage::{Blend, FragmentStage, Interpolation};
use crate::raster::target::{Clear, DepthState, RenderTarget};
use crate::raster::triangle::TriangleRasterizer;
use glam::Vec4;
use std::time::Instant;

/// A set of 2D triangles with per-vertex depth and colour.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene2D {
    /// Suggested target width.
    pub width: u32,
    /// Suggested target height.
    pub height: u32,
    /// Snapped triangles, drawn in this order.
    pub triangles: Vec<[FixedPoint; 3]>,
    /// Depth and colour of each triangle's vertices.
    pub vertices: Vec<[ShadedVertex; 3]>,
}

/// The blue of the course chapter's triangle and the rasterization slides' first triangle.
pub const BLUE: Vec4 = Vec4::new(0.0, 0.25, 1.0, 1.0);
/// The red of the rasterization slides' second triangle.
pub const RED: Vec4 = Vec4::new(0.9, 0.1, 0.1, 1.0);

/// The colour a scene gives its triangle number `i`, from a cycle of eight.
pub fn scene_colour(i: usize) -> Vec4 {
    const COLORS: [[f32; 3]; 8] = [
        [0.12, 0.47, 0.71],
        [1.00, 0.50, 0.05],
        [0.17, 0.63, 0.17],
        [0.84, 0.15, 0.16],
        [0.58, 0.40, 0.74],
        [0.55, 0.34, 0.29],
        [0.89, 0.47, 0.76],
        [0.74, 0.74, 0.13],
    ];
    let [r, g, b] = COLORS[i % COLORS.len()];
    Vec4::new(r, g, b, 1.0)
}

fn snap(x: f32, y: f32) -> FixedPoint {
    FixedPoint::snap(x, y).expect("built-in scene coordinates are inside the guard band")
}

impl Scene2D {
    /// A scene from snapped triangles, coloured by index with the
    /// [`scene_colour`], all at depth 0.
    pub fn from_triangles(width: u32, height: u32, triangles: Vec<[FixedPoint; 3]>) -> Scene2D {
        let vertices = (0..triangles.len())
            .map(|i| [ShadedVertex::flat(0.0, scene_colour(i)); 3])
            .collect();
        Scene2D {
            width,
            height,
            triangles,
            vertices,
        }
    }

    /// The scene with each triangle's colour and depth set by its look
    /// (a colour left out keeps the triangle's): the looks of a file's
    /// lines ([`Look`]).
    pub fn with_looks(mut self, looks: &[Look]) -> Scene2D {
        for (vertices, look) in self.vertices.iter_mut().zip(looks) {
            let color = look.color.unwrap_or(vertices[0].varyings.color);
            *vertices = [ShadedVertex::flat(look.depth, color); 3];
        }
        self
    }

    /// The scene's triangles sorted back to front: by their mean depth,
    /// the farthest first, those at the same depth in their order. The
    /// painter's algorithm, which transparent triangles drawn with `over`
    /// need. It cannot order triangles that pass through each other, nor
    /// three that overlap in a cycle; no order of whole triangles draws
    /// those right (see [`Scene2D::built_in`]'s `cycle`).
    pub fn sorted_back_to_front(&self) -> Scene2D {
        self.reordered(&self.back_to_front_order())
    }

    /// The order [`sorted_back_to_front`](Self::sorted_back_to_front)
    /// draws the triangles in, as their indices here.
    pub fn back_to_front_order(&self) -> Vec<usize> {
        let mean = |v: &[ShadedVertex; 3]| v.iter().map(|v| v.depth).sum::<f32>() / 3.0;
        let mut order: Vec<usize> = (0..self.triangles.len()).collect();
        order.sort_by(|&a, &b| mean(&self.vertices[b]).total_cmp(&mean(&self.vertices[a])));
        order
    }

    /// The scene with its triangles drawn in `order`, given as indices.
    pub fn reordered(&self, order: &[usize]) -> Scene2D {
        Scene2D {
            triangles: order.iter().map(|&i| self.triangles[i]).collect(),
            vertices: order.iter().map(|&i| self.vertices[i]).collect(),
            ..*self
        }
    }

    /// Triangles with one depth each, from numbers in groups of seven
    /// (`x0 y0 x1 y1 x2 y2 z`, screen pixels and a depth in `[0, 1]`),
    /// coloured by index with [`scene_colour`].
    ///
    /// ```
    /// use rasterlab::geometry::Scene2D;
    /// let scene = Scene2D::with_depths(8, 8, &[0., 0., 4., 0., 0., 4., 0.5]).unwrap();
    /// assert_eq!(scene.vertices[0][0].depth, 0.5);
    /// assert!(Scene2D::with_depths(8, 8, &[0., 0., 4., 0., 0., 4., 1.5]).is_err());
    /// ```
    pub fn with_depths(width: u32, height: u32, numbers: &[f64]) -> Result<Scene2D> {
        if !numbers.len().is_multiple_of(7) {
            return Err(Error::InvalidArgument(format!(
                "triangles with a depth take 7 numbers each (x0 y0 x1 y1 x2 y2 z), not {}",
                numbers.len()
            )));
        }
        let mut triangles = Vec::new();
        let mut vertices = Vec::new();
        for (i, t) in numbers.chunks(7).enumerate() {
            let z = t[6] as f32;
            if !(0.0..=1.0).contains(&t[6]) {
                return Err(Error::InvalidArgument(format!(
                    "triangle {}: depth {z} is outside [0, 1]",
                    i + 1
                )));
            }
            triangles.push([
                FixedPoint::snap_f64(t[0], t[1])?,
                FixedPoint::snap_f64(t[2], t[3])?,
                FixedPoint::snap_f64(t[4], t[5])?,
            ]);
            vertices.push([ShadedVertex::flat(z, scene_colour(i)); 3]);
        }
        Ok(Scene2D {
            width,
            height,
            triangles,
            vertices,
        })
    }

    /// The rasterization slides' depth-buffer example on its 14 x 9 grid: a blue triangle
    /// at depth 0.5 and a red one at depth 0.8, drawn in that order
    /// (`blue_first`) or the other.
    pub fn depth_example(blue_first: bool) -> Scene2D {
        let blue = [snap(2.75, 3.0), snap(12.3359375, 3.0), snap(1.9296875, 6.9)];
        let red = [snap(3.6, 1.0), snap(6.8, 1.0), snap(10.0, 9.0)];
        let mut triangles = vec![blue, red];
        let mut vertices = vec![
            [ShadedVertex::flat(0.5, BLUE); 3],
            [ShadedVertex::flat(0.8, RED); 3],
        ];
        if !blue_first {
            triangles.reverse();
            vertices.reverse();
        }
        Scene2D {
            width: 14,
            height: 9,
            triangles,
            vertices,
        }
    }

    /// the rules' known answer: a 5 x 5 square split along its diagonal
    /// into triangles covering 15 and 10 pixels.
    pub fn split_square() -> Scene2D {
        Scene2D::from_triangles(
            5,
            5,
            vec![
                [snap(0., 0.), snap(5., 0.), snap(5., 5.)],
                [snap(0., 5.), snap(0., 0.), snap(5., 5.)],
            ],
        )
    }

    /// Eight triangles around the centre of pixel (4, 4): every shared edge
    /// runs through a pixel centre.
    pub fn pinwheel() -> Scene2D {
        let c = (4.5f32, 4.5f32);
        let ring: Vec<(f32, f32)> = vec![
            (0.5, 0.5),
            (4.5, 0.5),
            (8.5, 0.5),
            (8.5, 4.5),
            (8.5, 8.5),
            (4.5, 8.5),
            (0.5, 8.5),
            (0.5, 4.5),
        ];
        let tris = (0..8)
            .map(|i| {
                let a = ring[i];
                let b = ring[(i + 1) % 8];
                [snap(c.0, c.1), snap(a.0, a.1), snap(b.0, b.1)]
            })
            .collect();
        Scene2D::from_triangles(9, 9, tris)
    }

    /// A fan of thin triangles with non-integer steps around one vertex.
    pub fn fan() -> Scene2D {
        let centre = (3.3f32, 28.7f32);
        let n = 12;
        let tris = (0..n)
            .map(|i| {
                let a0 = (i as f32) / (n as f32) * std::f32::consts::FRAC_PI_2;
                let a1 = ((i + 1) as f32) / (n as f32) * std::f32::consts::FRAC_PI_2;
                let p = |a: f32| snap(centre.0 + 27.0 * a.cos(), centre.1 - 27.0 * a.sin());
                [snap(centre.0, centre.1), p(a0), p(a1)]
            })
            .collect();
        Scene2D::from_triangles(32, 32, tris)
    }

    /// Three overlapping half-transparent triangles, red, green and blue,
    /// listed nearest first (depths 0.2, 0.5, 0.8): the order in which
    /// `over` draws them wrong. Drawn with the depth test, the nearest
    /// hides the others as if it were opaque; without it, the farthest
    /// lands on top. [`sorted_back_to_front`](Self::sorted_back_to_front)
    /// draws them right.
    pub fn transparent() -> Scene2D {
        let half = |c: Vec4| c.truncate().extend(0.5);
        let triangles = vec![
            [snap(4.0, 4.0), snap(36.0, 8.0), snap(10.0, 28.0)],
            [snap(14.0, 6.0), snap(44.0, 12.0), snap(26.0, 30.0)],
            [snap(8.0, 14.0), snap(40.0, 20.0), snap(20.0, 31.0)],
        ];
        let colours = [
            Vec4::new(0.9, 0.1, 0.1, 1.0),
            Vec4::new(0.1, 0.75, 0.2, 1.0),
            BLUE,
        ];
        let vertices = [0.2, 0.5, 0.8]
            .into_iter()
            .zip(colours)
            .map(|(z, c)| [ShadedVertex::flat(z, half(c)); 3])
            .collect();
        Scene2D {
            width: 48,
            height: 32,
            triangles,
            vertices,
        }
    }

    /// Three half-transparent wedges that overlap in a cycle: each one's
    /// far tip lies under the next one's near base, so green is over red
    /// where they meet, blue over green, and red over blue. No order of
    /// whole triangles composites them right; only a per-pixel order
    /// (depth peeling, or an A-buffer) can.
    pub fn cycle() -> Scene2D {
        let wedges = [
            // Three wedges 120 degrees apart around (24, 25), each from its
            // near base to a far tip 12 px past the next one's base.
            // Red: base on the left, tip at the top right.
            [(12.0, 33.75), (2.0, 16.25), (43.0, 4.25)],
            // Green: base at the top, tip at the bottom.
            [(22.5, 10.25), (42.5, 10.25), (32.5, 51.75)],
            // Blue: base at the bottom right, tip on the left.
            [(37.5, 31.0), (27.5, 48.5), (-3.5, 19.0)],
        ];
        let colours = [
            Vec4::new(0.9, 0.1, 0.1, 0.5),
            Vec4::new(0.1, 0.75, 0.2, 0.5),
            BLUE.truncate().extend(0.5),
        ];
        let triangles = wedges.map(|w| w.map(|(x, y)| snap(x, y))).to_vec();
        let vertices = colours
            .into_iter()
            .map(|c| {
                [
                    ShadedVertex::flat(0.1, c),
                    ShadedVertex::flat(0.1, c),
                    ShadedVertex::flat(0.9, c),
                ]
            })
            .collect();
        Scene2D {
            width: 48,
            height: 48,
            triangles,
            vertices,
        }
    }

    /// The names of the built-in scenes.
    pub const BUILT_IN: [&'static str; 6] = [
        "depth-example",
        "split-square",
        "pinwheel",
        "fan",
        "transparent",
        "cycle",
    ];

    /// A built-in scene by name.
    pub fn built_in(name: &str) -> Result<Scene2D> {
        match name {
            "depth-example" => Ok(Scene2D::depth_example(true)),
            "split-square" => Ok(Scene2D::split_square()),
            "pinwheel" => Ok(Scene2D::pinwheel()),
            "fan" => Ok(Scene2D::fan()),
            "transparent" => Ok(Scene2D::transparent()),
            "cycle" => Ok(Scene2D::cycle()),
            _ => Err(Error::UnknownName {
                what: "scene",
                name: name.to_string(),
                known: format!(
                    "{}, {}",
                    Scene2D::BUILT_IN.join(", "),
                    crate::geometry::Floor::NAME
                ),
            }),
        }
    }

    /// Sets up every triangle under `rule`; zero-area ones are dropped
    /// (they cover nothing), the others keep their index as id.
    pub fn setups(&self, rule: FillRule) -> Vec<TriangleSetup> {
        setup_triangles(&self.triangles, rule)
    }

    /// Draws the scene with a back-end into `target` through the shared
    /// fragment stage.
    pub fn draw(
        &self,
        backend: &dyn TriangleRasterizer,
        rule: FillRule,
        depth: DepthState,
        shader: &dyn FragmentShader,
        target: &mut RenderTarget,
    ) -> WorkCounters {
        self.draw_blended(backend, rule, (depth, Blend::REPLACE), shader, target)
    }

    /// [`draw`](Self::draw), each fragment merged by `blend`.
    pub fn draw_blended(
        &self,
        backend: &dyn TriangleRasterizer,
        rule: FillRule,
        (depth, blend): (DepthState, Blend),
        shader: &dyn FragmentShader,
        target: &mut RenderTarget,
    ) -> WorkCounters {
        let setups = self.setups(rule);
        let viewport = PixelRect::of_target(target.width(), target.height());
        let triangles = TriangleData::of_triangles(&setups, &self.vertices);
        let mut stage = FragmentStage::new(target, shader)
            .with_triangles(&triangles)
            .with_depth(depth)
            .with_blend(blend);
        backend.rasterize(&setups, viewport, &mut stage)
    }

    /// Draws one frame of the scene into `target` as a renderer redraws
    /// its framebuffer, on the path of the mesh renderer and the
    /// benchmark workloads: the triangles are set up (the frame's
    /// geometry), then drawn by the pipeline's draw with the clear to
    /// `background` (colour, depth and coverage) folded into it, band by
    /// band while the triangles are few. Returns the back-end's work and
    /// the frame's times, the whole frame included.
    ///
    /// The buffers end as after a clear and [`draw`](Self::draw):
    ///
    /// ```
    /// use rasterlab::geometry::Scene2D;
    /// use rasterlab::raster::{Blend, DepthState, FillRule, Flat, RenderTarget};
    ///
    /// let scene = Scene2D::depth_example(false);
    /// let scanline = rasterlab::raster::triangle_backend("scanline").unwrap();
    /// let (rule, depth) = (FillRule::TopLeft, DepthState::DEFAULT);
    /// let mut eager = RenderTarget::new(scene.width, scene.height).unwrap();
    /// scene.draw(scanline, rule, depth, &Flat, &mut eager);
    /// let mut folded = RenderTarget::new(scene.width, scene.height).unwrap();
    /// folded.color.fill([9, 9, 9, 9]);
    /// let (_, times) =
    ///     scene.render_frame(scanline, rule, (depth, Blend::REPLACE), &Flat, RenderTarget::BLACK, &mut folded);
    /// assert_eq!(folded, eager);
    /// assert!(times.clear_folded);
    /// ```
    pub fn render_frame(
        &self,
        backend: &dyn TriangleRasterizer,
        rule: FillRule,
        (depth, blend): (DepthState, Blend),
        shader: &dyn FragmentShader,
        background: [u8; 4],
        target: &mut RenderTarget,
    ) -> (WorkCounters, FrameTimes) {
        self.timed_frame(rule, |geometry| {
            let pass = Pass {
                shader,
                depth,
                interpolation: Interpolation::PerspectiveCorrect,
                clear: Clear::all(background),
                blend,
            };
            draw_runs(&geometry.runs(), backend, pass, target)
        })
    }

    /// One frame timed whole: the triangles set up under `rule` (the
    /// frame's geometry), then `draw` (its raster part).
    fn timed_frame(
        &self,
        rule: FillRule,
        draw: impl FnOnce(&Geometry) -> WorkCounters,
    ) -> (WorkCounters, FrameTimes) {
        let start = Instant::now();
        let geometry = Geometry::of_screen_triangles(self.setups(rule), &self.vertices);
        let geometry_time = start.elapsed();
        let raster_start = Instant::now();
        let work = draw(&geometry);
        let raster_time = raster_start.elapsed();
        drop(geometry);
        let times = FrameTimes::new(start.elapsed(), None, geometry_time, raster_time);
        (work, times)
    }

    /// [`render_frame`](Self::render_frame) multisampled: the target
    /// (of the scene's size) cleared to `background`, then the triangles
    /// drawn through the multisampled stage on its pattern
    /// ([`draw_multisampled`]). Resolve the target for the image.
    pub fn render_frame_multisampled(
        &self,
        backend: &dyn TriangleRasterizer,
        rule: FillRule,
        (depth, blend): (DepthState, Blend),
        shader: &dyn FragmentShader,
        background: [u8; 4],
        target: &mut MultisampleTarget,
    ) -> (WorkCounters, FrameTimes) {
        self.timed_frame(rule, |geometry| {
            target.clear(background);
            let (setups, data) = (&geometry.setups, &geometry.shaded);
            let lerp = Interpolation::PerspectiveCorrect;
            draw_multisampled(setups, data, backend, shader, (depth, blend), lerp, target)
        })
    }

    /// Renders the scene into a new target of its own size.
    pub fn render(
        &self,
        backend: &dyn TriangleRasterizer,
        rule: FillRule,
        shader: &dyn FragmentShader,
    ) -> Result<(RenderTarget, WorkCounters)> {
        let mut target = RenderTarget::new(self.width, self.height)?;
        let work = self.draw(backend, rule, DepthState::DEFAULT, shader, &mut target);
        Ok((target, work))
    }
}

/// Sets up snapped triangles under `rule`, dropping zero-area ones; each
/// keeps its index in `triangles` as its id.
pub fn setup_triangles(triangles: &[[FixedPoint; 3]], rule: FillRule) -> Vec<TriangleSetup> {
    triangles
        .iter()
        .enumerate()
        .filter_map(|(i, v)| TriangleSetup::new(i as u32, *v, rule))
        .collect()
}

/// Runs a back-end over triangles and keeps every fragment in emission order.
pub fn collect_fragments(
    backend: &dyn TriangleRasterizer,
    setups: &[TriangleSetup],
    width: u32,
    height: u32,
) -> (FragmentList, WorkCounters) {
    let mut list = FragmentList::default();
    let work = backend.rasterize(setups, PixelRect::of_target(width, height), &mut list);
    (list, work)
}
