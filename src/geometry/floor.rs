//! The receding plane: a checkerboard floor running to the horizon, the
//! picture of texture aliasing every course shows (Williams 1983,
//! "Pyramidal parametrics", opens with it).
//!
//! The floor is the plane `y = 0` from `x = -100` to `100` and `z = -1` to
//! `-200`, seen by a camera one unit above it at the origin, looking
//! towards `(0, 0.3, -10)` with a vertical field of view of 60 degrees.
//! Its texture coordinate repeats the texture once every two units each
//! way, so a square of the checkerboard spans many pixels at the bottom
//! of the picture and many squares fall in one pixel towards the horizon:
//! with level 0 alone the distance is noise (the texture is undersampled),
//! with mipmaps it fades to the checkerboard's mean.
//!
//! The texture is generated, not read: [`Floor::checkerboard`], 8 x 8
//! squares of 4 x 4 texels in white and blue, a 32 x 32 image whose
//! pyramid has six levels. [`Floor::with_texture`] puts another on it
//! (`render --scene floor --texture FILE.png`).
//!
//! The two triangles go through the 3D pipeline (clipping, the
//! perspective divide, set-up) as a mesh does; [`Floor::render`] draws
//! them with the [`Mipmapped`] shader, so every filter, level mode,
//! derivative method and anisotropy can be shown, and
//! [`Floor::ground_truth`] gives what a pixel should be: the texture over
//! its square.
//!
//! ```
//! use rasterlab::geometry::Floor;
//! use rasterlab::raster::{triangle_backends, Derivatives, LevelMode, Sampler};
//!
//! let floor = Floor::new(64, 40).unwrap();
//! let trilinear = Sampler { levels: LevelMode::Linear, ..Sampler::default() };
//! let (a, _) = floor.render(triangle_backends()[0], trilinear, Derivatives::Quad);
//! let (b, _) = floor.render(triangle_backends()[1], trilinear, Derivatives::Quad);
//! assert_eq!(a.color, b.color);
//! ```

use crate::error::{Error, Result};
use crate::geometry::pipeline::{
    draw_binned_clearing, process_triangles, ClipVertex, Geometry, PipelineOptions, Transform,
    Viewport,
};
use crate::raster::derivatives::{Derivatives, UvPlanes};
use crate::raster::fragment::WorkCounters;
use crate::raster::primitive::Varyings;
use crate::raster::shader::{FragmentShader, Mipmapped};
use crate::raster::stage::Interpolation;
use crate::raster::target::{Clear, DepthState, RenderTarget};
use crate::raster::texture::{Filter, Sampler, Texture, Wrap};
use crate::raster::triangle::TriangleRasterizer;
use glam::{DVec2, Mat4, Vec2, Vec3, Vec4};

/// The sky's colour, where the floor is not.
pub const SKY: [u8; 4] = [24, 26, 32, 255];

/// The checkerboard floor and its texture, framed for one target size.
#[derive(Clone, Debug)]
pub struct Floor {
    width: u32,
    height: u32,
    geometry: Geometry,
    texture: Texture,
    planes: Vec<(crate::raster::edge::TriangleSetup, UvPlanes)>,
}

impl Floor {
    /// The name of the floor among the built-in scenes (`render --scene floor`).
    pub const NAME: &'static str = "floor";

    /// The most ground truth samples a pixel side, 256 (65,536 a pixel).
    pub const MAX_TRUTH_SAMPLES: u32 = 256;

    /// An error unless `n` samples a side are 1 to
    /// [`MAX_TRUTH_SAMPLES`](Self::MAX_TRUTH_SAMPLES).
    pub fn check_truth_samples(n: u32) -> Result<()> {
        if (1..=Floor::MAX_TRUTH_SAMPLES).contains(&n) {
            Ok(())
        } else {
            Err(Error::InvalidArgument(format!(
                "the ground truth takes 1 to {} samples a side, not {n}",
                Floor::MAX_TRUTH_SAMPLES
            )))
        }
    }

    /// The size `render --scene floor` draws when none is given.
    pub const SIZE: (u32, u32) = (320, 200);

    /// The floor's white and blue checkerboard: 8 x 8 squares of 4 x 4
    /// texels.
    pub fn checkerboard() -> Texture {
        Texture::checkerboard(8, 4, Vec4::ONE, Vec4::new(0.1, 0.2, 0.6, 1.0))
    }

    /// The floor seen on a `width` x `height` target, under
    /// [`Floor::checkerboard`]. An error for a size a target cannot have.
    pub fn new(width: u32, height: u32) -> Result<Floor> {
        RenderTarget::check_size(width, height)?;
        let transform = Floor::camera(width, height);
        let vertices = Floor::corners();
        let shader = |v: &(Vec3, Vec2)| ClipVertex {
            position: transform.mvp * v.0.extend(1.0),
            varyings: Varyings {
                uv: v.1,
                ..Varyings::default()
            },
        };
        let geometry = process_triangles(
            &vertices,
            &Floor::TRIANGLES,
            &shader,
            Viewport { width, height },
            &PipelineOptions::default(),
        )?;
        let planes = geometry
            .setups
            .iter()
            .map(|s| {
                let t = &geometry.shaded.triangles[s.id as usize];
                let v = t.vertices.map(|i| geometry.shaded.vertices[i as usize]);
                (*s, UvPlanes::new(s, v, true))
            })
            .collect();
        Ok(Floor {
            width,
            height,
            geometry,
            texture: Floor::checkerboard(),
            planes,
        })
    }

    /// The plane's corners `(x, z)`, drawn as the triangles
    /// [`TRIANGLES`](Self::TRIANGLES).
    const CORNERS: [(f32, f32); 4] = [(-100., -1.), (100., -1.), (100., -200.), (-100., -200.)];

    /// The two triangles of [`vertices`](Self::vertices), counter-clockwise.
    pub const TRIANGLES: [[u32; 3]; 2] = [[0, 1, 2], [0, 2, 3]];

    fn camera(width: u32, height: u32) -> Transform {
        let projection =
            Mat4::perspective_rh_gl(60f32.to_radians(), width as f32 / height as f32, 0.5, 500.0);
        let view = Mat4::look_at_rh(Vec3::new(0., 1., 0.), Vec3::new(0., 0.3, -10.), Vec3::Y);
        Transform::new(Mat4::IDENTITY, view, projection)
    }

    /// The plane's four corners in world space, each with its texture
    /// coordinate: what another renderer is given to draw the same floor.
    pub fn vertices(&self) -> [(Vec3, Vec2); 4] {
        Floor::corners()
    }

    fn corners() -> [(Vec3, Vec2); 4] {
        Floor::CORNERS.map(|(x, z): (f32, f32)| {
            let uv = Vec2::new((x + 100.) / 2., (z + 1.) / -2.);
            (Vec3::new(x, 0., z), uv)
        })
    }

    /// The camera's model-view-projection matrix (OpenGL's clip space,
    /// y up, depth -1 to 1), which the floor's vertices go through.
    pub fn mvp(&self) -> Mat4 {
        Floor::camera(self.width, self.height).mvp
    }

    /// The same floor under another texture.
    pub fn with_texture(self, texture: Texture) -> Floor {
        Floor { texture, ..self }
    }

    /// Target width.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Target height.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The floor's triangles, through the pipeline.
    pub fn geometry(&self) -> &Geometry {
        &self.geometry
    }

    /// The texture on the floor.
    pub fn texture(&self) -> &Texture {
        &self.texture
    }

    /// The mipmapped shader that samples the floor's texture with
    /// `sampler`, its derivatives by `derivatives`.
    pub fn shader(&self, sampler: Sampler, derivatives: Derivatives) -> Mipmapped {
        Mipmapped::new(
            self.texture.clone(),
            sampler,
            derivatives,
            &self.geometry.setups,
            &self.geometry.shaded,
            true,
        )
    }

    /// The floor drawn by `backend` into `target` with `shader`, the
    /// target cleared to the [`SKY`] first, band by band on rayon's
    /// threads; the back-end's work.
    pub fn draw<S: FragmentShader>(
        &self,
        backend: &dyn TriangleRasterizer,
        shader: &S,
        target: &mut RenderTarget,
    ) -> WorkCounters {
        draw_binned_clearing(
            &self.geometry,
            backend,
            shader,
            DepthState::DEFAULT,
            Interpolation::PerspectiveCorrect,
            Clear::all(SKY),
            target,
        )
    }

    /// The floor drawn by `backend` with `sampler`, derivatives by
    /// `derivatives`, on a new target; the target and the work.
    pub fn render(
        &self,
        backend: &dyn TriangleRasterizer,
        sampler: Sampler,
        derivatives: Derivatives,
    ) -> (RenderTarget, WorkCounters) {
        let mut target = RenderTarget::new(self.width, self.height)
            .expect("the size was checked when the floor was made");
        let work = self.draw(backend, &self.shader(sampler, derivatives), &mut target);
        (target, work)
    }

    /// The plane equations of the triangle whose inside holds the centre
    /// of pixel `(x, y)`, if one does.
    pub fn planes_at(&self, x: u32, y: u32) -> Option<&UvPlanes> {
        let (x, y) = (i64::from(x), i64::from(y));
        self.planes
            .iter()
            .find(|(s, _)| s.bounds.contains(x, y) && s.inside(s.edge_values_at_pixel(x, y)))
            .map(|(_, p)| p)
    }

    /// The texture coordinate at the centre of pixel `(x, y)`, where the
    /// floor covers it.
    pub fn uv_at(&self, x: u32, y: u32) -> Option<DVec2> {
        self.planes_at(x, y)?.uv_at(i64::from(x), i64::from(y))
    }

    /// What pixel `(x, y)` should be: the texture over the pixel's square,
    /// `n` x `n` bilinear samples of level 0 on a regular grid (each at
    /// the centre of its cell), box-filtered. `None` where the floor does
    /// not cover the pixel's centre, or the plane does not reach a
    /// sample (past the horizon). `n` is 1 to
    /// [`MAX_TRUTH_SAMPLES`](Self::MAX_TRUTH_SAMPLES).
    pub fn ground_truth(&self, x: u32, y: u32, n: u32) -> Result<Option<Vec4>> {
        Floor::check_truth_samples(n)?;
        let Some(planes) = self.planes_at(x, y) else {
            return Ok(None);
        };
        let level0 = &self.texture.levels()[0];
        let mut sum = Vec4::ZERO;
        for j in 0..n {
            for i in 0..n {
                let px = f64::from(x) + (f64::from(i) + 0.5) / f64::from(n);
                let py = f64::from(y) + (f64::from(j) + 0.5) / f64::from(n);
                let Some(uv) = planes.uv_at_point(px, py) else {
                    return Ok(None);
                };
                sum += level0.sample(uv.as_vec2(), Filter::Bilinear, Wrap::Repeat);
            }
        }
        Ok(Some(sum / (n * n) as f32))
    }
}
