//! Fragment shaders: the trait the shared stage calls, colour conversions,
//! and the built-in shaders.
//!
//! A fragment shader calculates the colour of a fragment (the course chapter, step 5).
//! [`Flat`] colours the whole primitive with its first (provoking)
//! vertex's colour; [`Gouraud`] interpolates the vertex colours with the
//! barycentric coordinates (the line-drawing slides: `c = alpha c_a + beta c_b + gamma c_c`).
//! [`Diffuse`] lights each fragment with its interpolated normal (the
//! software-rasterizer article), [`Textured`] samples a [`Texture`] at the interpolated UV (nearest
//! or bilinear; textures, their mipmaps and filters live in
//! [`texture`](crate::raster::texture)), [`Mipmapped`] samples one with its
//! mip pyramid at the level of detail of each fragment's derivatives, and
//! [`NormalColors`] shows the normals themselves.

use crate::raster::derivatives::{Derivatives, Gradient, UvPlanes};
use crate::raster::edge::TriangleSetup;
use crate::raster::primitive::{TriangleData, Varyings};
use crate::raster::texture::{isotropic_lambdas, Anisotropic, Sampler};
pub use crate::raster::texture::{Filter, Texture};
use glam::{Vec2, Vec3, Vec4};

/// What a fragment shader is given.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct FragmentInput {
    /// Pixel column.
    pub x: u32,
    /// Pixel row.
    pub y: u32,
    /// Interpolated depth (already tested).
    pub depth: f32,
    /// Interpolated varyings.
    pub varyings: Varyings,
    /// The provoking (first) vertex's varyings, for flat shading.
    pub flat: Varyings,
    /// Index of the primitive in its draw.
    pub primitive: u32,
}

/// Computes a fragment's colour (the course chapter, step 5).
pub trait FragmentShader: Sync {
    /// The fragment's linear RGBA colour; components are clamped to `[0, 1]`.
    fn shade(&self, input: &FragmentInput) -> Vec4;

    /// True when the colour depends only on the primitive (`flat` and
    /// `primitive`), never on the pixel: the stage then shades a span once
    /// and writes that colour to every pixel of the span that passes the
    /// depth test. The default, `false`, shades every fragment.
    fn uniform_per_primitive(&self) -> bool {
        false
    }

    /// The colours of eight fragments of one span at once, lane `k` being
    /// [`input`](FragmentLanes::input)`(k)`; lanes that are not
    /// [`active`](FragmentLanes::active) may hold anything.
    ///
    /// The stage calls it for spans long enough to fill the lanes, in code
    /// compiled for the CPU's widest vectors. Each lane must be the very
    /// bits [`shade`](Self::shade) gives its input: the default calls
    /// `shade` on each active lane; a shader overrides it with the same
    /// equations written over the lanes (see [`Gouraud`] and [`Diffuse`]),
    /// which the compiler then runs eight at a time.
    ///
    /// A shader of its own, its lanes the same equation as its `shade`:
    ///
    /// ```
    /// use glam::Vec4;
    /// use rasterlab::raster::{
    ///     ColorLanes, FragmentInput, FragmentLanes, FragmentShader, Varyings, LANES,
    /// };
    ///
    /// /// The interpolated colour's red, as grey.
    /// struct Red;
    ///
    /// impl FragmentShader for Red {
    ///     fn shade(&self, input: &FragmentInput) -> Vec4 {
    ///         let r = input.varyings.color.x;
    ///         Vec4::new(r, r, r, 1.0)
    ///     }
    ///
    ///     #[inline(always)]
    ///     fn shade_lanes(&self, lanes: &FragmentLanes) -> ColorLanes {
    ///         let red = lanes.color[0];
    ///         [red, red, red, [1.0; LANES]]
    ///     }
    /// }
    ///
    /// let lanes = FragmentLanes {
    ///     x0: 10,
    ///     y: 3,
    ///     depth: [0.5; LANES],
    ///     color: [[0.25; LANES], [0.5; LANES], [0.75; LANES], [1.0; LANES]],
    ///     uv: [[0.0; LANES]; 2],
    ///     normal: [[0.0; LANES]; 3],
    ///     flat: Varyings::color(Vec4::ONE),
    ///     primitive: 0,
    ///     active: [true; LANES],
    /// };
    /// let shaded = Red.shade_lanes(&lanes);
    /// for k in 0..LANES {
    ///     let one = Red.shade(&lanes.input(k)).to_array();
    ///     assert_eq!([0, 1, 2, 3].map(|c| shaded[c][k]), one);
    /// }
    /// ```
    #[inline(always)]
    fn shade_lanes(&self, lanes: &FragmentLanes) -> ColorLanes {
        let mut out = [[0.0; LANES]; 4];
        for k in 0..LANES {
            if lanes.active[k] {
                let c = self.shade(&lanes.input(k)).to_array();
                for (channel, value) in out.iter_mut().zip(c) {
                    channel[k] = value;
                }
            }
        }
        out
    }
}

/// How many fragments [`FragmentShader::shade_lanes`] shades at a time:
/// one AVX2 vector of `f32`.
pub const LANES: usize = 8;

/// Red, green, blue and alpha of [`LANES`] fragments, one array per channel.
pub type ColorLanes = [[f32; LANES]; 4];

/// What a fragment shader is given for [`LANES`] fragments of one span,
/// pixels `x0 + k` of row `y`: one array per component, lane `k` in
/// element `k` (the layout that vector code reads whole).
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct FragmentLanes {
    /// Column of lane 0.
    pub x0: u32,
    /// Pixel row.
    pub y: u32,
    /// Interpolated depths (already tested).
    pub depth: [f32; LANES],
    /// Interpolated colour, one array per channel.
    pub color: [[f32; LANES]; 4],
    /// Interpolated texture coordinates.
    pub uv: [[f32; LANES]; 2],
    /// Interpolated normal, one array per axis.
    pub normal: [[f32; LANES]; 3],
    /// The provoking (first) vertex's varyings, for flat shading.
    pub flat: Varyings,
    /// Index of the primitive in its draw.
    pub primitive: u32,
    /// Which lanes are fragments that passed the depth test.
    pub active: [bool; LANES],
}

impl FragmentLanes {
    /// Lane `k` as the input [`FragmentShader::shade`] takes.
    #[inline(always)]
    pub fn input(&self, k: usize) -> FragmentInput {
        FragmentInput {
            x: self.x0 + k as u32,
            y: self.y,
            depth: self.depth[k],
            varyings: Varyings {
                color: Vec4::new(
                    self.color[0][k],
                    self.color[1][k],
                    self.color[2][k],
                    self.color[3][k],
                ),
                uv: Vec2::new(self.uv[0][k], self.uv[1][k]),
                normal: Vec3::new(self.normal[0][k], self.normal[1][k], self.normal[2][k]),
            },
            flat: self.flat,
            primitive: self.primitive,
        }
    }
}

/// Converts a colour in `[0, 1]` to RGBA8 (clamped, rounded; NaN gives 0).
///
/// The four channels go through one vector each step: clamp, `* 255 +
/// 0.5`, truncate. Per channel that is `(v.clamp(0.0, 1.0) * 255.0 + 0.5)
/// as u8`, bit for bit, except that a NaN channel becomes 0 at the clamp
/// rather than at the final conversion: the same byte.
///
/// ```
/// use glam::Vec4;
/// use rasterlab::raster::to_rgba8;
///
/// assert_eq!(to_rgba8(Vec4::new(0.0, 0.5, 1.0, 2.0)), [0, 128, 255, 255]);
/// assert_eq!(to_rgba8(Vec4::new(f32::NAN, -1.0, 0.998, 0.002)), [0, 0, 254, 1]);
/// ```
#[inline]
pub fn to_rgba8(c: Vec4) -> [u8; 4] {
    let scaled = c.clamp(Vec4::ZERO, Vec4::ONE) * 255.0 + Vec4::splat(0.5);
    // Every lane lies in [0.5, 255.5]: truncating to i32 then keeping the
    // low byte is `as u8` (255.5 truncates to 255).
    crate::raster::vector::truncate_to_bytes(scaled)
}

/// Converts RGBA8 to a colour in `[0, 1]`.
#[inline]
pub fn from_rgba8(c: [u8; 4]) -> Vec4 {
    Vec4::new(c[0] as f32, c[1] as f32, c[2] as f32, c[3] as f32) / 255.0
}

/// A directional light for diffuse (Lambert) shading: intensity
/// `ambient + diffuse * max(0, n . l)`.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct DirectionalLight {
    /// Unit vector from the surface towards the light (world space).
    pub direction: Vec3,
    /// Light reaching every surface.
    pub ambient: f32,
    /// Strength of the directional part.
    pub diffuse: f32,
}

impl DirectionalLight {
    /// A light from `direction` (normalised here).
    pub fn new(direction: Vec3, ambient: f32, diffuse: f32) -> DirectionalLight {
        DirectionalLight {
            direction: direction.normalize_or(Vec3::Z),
            ambient,
            diffuse,
        }
    }

    /// The intensity on a surface with normal `n` (not necessarily unit).
    #[inline]
    pub fn intensity(&self, n: Vec3) -> f32 {
        self.intensity_of(n.to_array())
    }

    /// [`intensity`](Self::intensity) of the normal `[x, y, z]`:
    /// `ambient + diffuse * max(0, n / |n| . l)`, with a normal counted as
    /// zero where glam's `normalize_or_zero` gives zero: a length of zero,
    /// one so small that its reciprocal is not finite, or one not finite.
    /// Written out as plain arithmetic on `f32` (glam's `normalize_or_zero`
    /// and `dot`, step by step, the same bits) so that a loop over lanes
    /// runs on vectors.
    #[inline(always)]
    pub(crate) fn intensity_of(&self, [x, y, z]: [f32; 3]) -> f32 {
        let length = (x * x + y * y + z * z).sqrt();
        let rcp = 1.0 / length;
        let [x, y, z] = if rcp.is_finite() && rcp > 0.0 {
            [x * rcp, y * rcp, z * rcp]
        } else {
            [0.0; 3]
        };
        let d = self.direction;
        let dot = x * d.x + y * d.y + z * d.z;
        self.ambient + self.diffuse * dot.max(0.0)
    }
}

impl Default for DirectionalLight {
    /// Light from the upper left, in front.
    fn default() -> Self {
        DirectionalLight::new(Vec3::new(-0.4, 0.6, 0.7), 0.15, 0.85)
    }
}

/// One colour per primitive: the provoking (first) vertex's.
#[derive(Copy, Clone, Debug, Default)]
pub struct Flat;

impl FragmentShader for Flat {
    fn shade(&self, input: &FragmentInput) -> Vec4 {
        input.flat.color
    }

    fn uniform_per_primitive(&self) -> bool {
        true
    }
}

/// Vertex colours interpolated across the primitive.
#[derive(Copy, Clone, Debug, Default)]
pub struct Gouraud;

impl FragmentShader for Gouraud {
    fn shade(&self, input: &FragmentInput) -> Vec4 {
        input.varyings.color
    }

    #[inline(always)]
    fn shade_lanes(&self, lanes: &FragmentLanes) -> ColorLanes {
        lanes.color
    }
}

/// A fixed colour for everything (the course chapter's blue triangle, wireframes).
#[derive(Copy, Clone, Debug)]
pub struct Constant(pub Vec4);

impl FragmentShader for Constant {
    fn shade(&self, _input: &FragmentInput) -> Vec4 {
        self.0
    }

    fn uniform_per_primitive(&self) -> bool {
        true
    }
}

/// Diffuse (Lambert) lighting per fragment: the interpolated colour times
/// `ambient + diffuse * max(0, n . l)`, with the interpolated normal
/// re-normalised (the software-rasterizer article's diffuse shading).
#[derive(Copy, Clone, Debug, Default)]
pub struct Diffuse(pub DirectionalLight);

impl FragmentShader for Diffuse {
    fn shade(&self, input: &FragmentInput) -> Vec4 {
        let c = input.varyings.color;
        (c.truncate() * self.0.intensity(input.varyings.normal)).extend(c.w)
    }

    /// [`shade`](Self::shade) lane by lane, each step in `shade`'s order.
    #[inline(always)]
    fn shade_lanes(&self, lanes: &FragmentLanes) -> ColorLanes {
        let mut out = lanes.color;
        for k in 0..LANES {
            let n = [0, 1, 2].map(|axis| lanes.normal[axis][k]);
            let intensity = self.0.intensity_of(n);
            for channel in &mut out[..3] {
                channel[k] *= intensity;
            }
        }
        out
    }
}

/// The interpolated normal as a colour, `(n + 1) / 2`, to see the normals.
#[derive(Copy, Clone, Debug, Default)]
pub struct NormalColors;

impl FragmentShader for NormalColors {
    fn shade(&self, input: &FragmentInput) -> Vec4 {
        ((input.varyings.normal.normalize_or_zero() + Vec3::ONE) * 0.5).extend(1.0)
    }
}

/// A texture sampled at the interpolated UV, optionally lit per fragment.
#[derive(Clone, Debug)]
pub struct Textured {
    /// The texture.
    pub texture: Texture,
    /// Nearest or bilinear sampling.
    pub filter: Filter,
    /// Diffuse lighting applied to the texel colour, if any.
    pub light: Option<DirectionalLight>,
}

impl FragmentShader for Textured {
    fn shade(&self, input: &FragmentInput) -> Vec4 {
        let c = self.texture.sample(input.varyings.uv, self.filter);
        match self.light {
            Some(light) => (c.truncate() * light.intensity(input.varyings.normal)).extend(c.w),
            None => c,
        }
    }
}

/// A texture sampled with its mipmaps: each fragment's level of detail
/// (and anisotropic footprint) from the screen-space derivatives of its
/// texture coordinate, which a [`Derivatives`] method computes from the
/// fragment's triangle and pixel alone, so every back-end draws the same
/// image. Made for one draw of triangles: it keeps each triangle's
/// [`UvPlanes`], by triangle id.
#[derive(Clone, Debug)]
pub struct Mipmapped {
    /// The texture and its pyramid.
    pub texture: Texture,
    /// Pixel filter, level mode, wrap mode and anisotropy.
    pub sampler: Sampler,
    /// How the derivatives are computed.
    pub derivatives: Derivatives,
    /// Diffuse lighting applied to the texel colour, if any.
    pub light: Option<DirectionalLight>,
    planes: Vec<Option<UvPlanes>>,
}

impl Mipmapped {
    /// The shader for the triangles `setups` whose stage data is `data`;
    /// `perspective` as the draw's interpolation is perspective-correct.
    pub fn new(
        texture: Texture,
        sampler: Sampler,
        derivatives: Derivatives,
        setups: &[TriangleSetup],
        data: &TriangleData,
        perspective: bool,
    ) -> Mipmapped {
        let mut shader = Mipmapped {
            texture,
            sampler,
            derivatives,
            light: None,
            planes: Vec::new(),
        };
        shader.set_triangles(setups, data, perspective);
        shader
    }

    /// Makes the shader one for the triangles `setups` whose stage data is
    /// `data`, as [`new`](Self::new) does, in the memory it already has:
    /// what a renderer drawing frame after frame calls, so that a frame
    /// does not allocate (and the system zero) the planes of every
    /// triangle again.
    pub fn set_triangles(
        &mut self,
        setups: &[TriangleSetup],
        data: &TriangleData,
        perspective: bool,
    ) {
        self.planes.clear();
        self.planes.resize(data.triangles.len(), None);
        for s in setups {
            let Some(t) = data.triangles.get(s.id as usize) else {
                continue;
            };
            let vertices = t.vertices.map(|i| data.vertices.get(i as usize).copied());
            if let [Some(a), Some(b), Some(c)] = vertices {
                self.planes[s.id as usize] = Some(UvPlanes::new(s, [a, b, c], perspective));
            }
        }
    }

    /// The derivatives of `input`'s texture coordinate; zero for a
    /// primitive this shader was not made for.
    pub fn gradient(&self, input: &FragmentInput) -> Gradient {
        match self.planes.get(input.primitive as usize) {
            Some(Some(planes)) => {
                planes.derivatives(self.derivatives, i64::from(input.x), i64::from(input.y))
            }
            _ => Gradient::default(),
        }
    }
}

impl Mipmapped {
    /// The colour of a fragment at `uv` with normal `normal` whose
    /// derivatives are `g`: the lookup, lit.
    #[inline(always)]
    fn lookup(&self, uv: Vec2, normal: Vec3, g: Gradient) -> Vec4 {
        self.light(
            self.texture.sample_grad(uv, g.dx, g.dy, &self.sampler),
            normal,
        )
    }

    /// The texel colour `c` lit, for a fragment whose normal is `normal`.
    #[inline(always)]
    fn light(&self, c: Vec4, normal: Vec3) -> Vec4 {
        match self.light {
            Some(light) => (c.truncate() * light.intensity(normal)).extend(c.w),
            None => c,
        }
    }
}

impl FragmentShader for Mipmapped {
    fn shade(&self, input: &FragmentInput) -> Vec4 {
        let v = &input.varyings;
        self.lookup(v.uv, v.normal, self.gradient(input))
    }

    /// [`shade`](Self::shade) on each lane, the derivatives of the eight
    /// pixels found together ([`UvPlanes::derivatives_lanes`]): the
    /// planes are looked up once, stepped along the row, and each
    /// coordinate a neighbour's difference reads is computed once.
    #[inline(always)]
    fn shade_lanes(&self, lanes: &FragmentLanes) -> ColorLanes {
        let gradients = match self.planes.get(lanes.primitive as usize) {
            Some(Some(planes)) => {
                planes.derivatives_lanes(self.derivatives, i64::from(lanes.x0), i64::from(lanes.y))
            }
            _ => [Gradient::default(); LANES],
        };
        // Isotropic, the level of detail of the eight too, as
        // `Texture::sample_grad` finds it.
        let isotropic =
            self.sampler.anisotropy == 1 && self.sampler.anisotropic == Anisotropic::Probes;
        let lambdas = isotropic.then(|| {
            let (dx, dy) = (gradients.map(|g| g.dx), gradients.map(|g| g.dy));
            isotropic_lambdas(&dx, &dy, self.texture.width(), self.texture.height())
        });
        let mut out = [[0.0; LANES]; 4];
        for k in 0..LANES {
            if lanes.active[k] {
                let uv = Vec2::new(lanes.uv[0][k], lanes.uv[1][k]);
                let normal = Vec3::new(lanes.normal[0][k], lanes.normal[1][k], lanes.normal[2][k]);
                let c = match lambdas {
                    Some(lambda) => self.light(
                        self.texture.sample_lod(uv, lambda[k], &self.sampler),
                        normal,
                    ),
                    None => self.lookup(uv, normal, gradients[k]),
                }
                .to_array();
                for (channel, value) in out.iter_mut().zip(c) {
                    channel[k] = value;
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The intensity, written out so that lanes run it, is glam's
    /// normalise-and-dot bit for bit: on random normals, zero, tiny and
    /// huge ones, and non-finite ones.
    #[test]
    fn intensity_of_lanes_is_the_intensity_bit_for_bit() {
        let light = DirectionalLight::default();
        let mut rng = fastrand::Rng::with_seed(7);
        let special = [
            0.0,
            -0.0,
            1e-30,
            -1e-30,
            1e30,
            f32::INFINITY,
            f32::NAN,
            1e-20,
        ];
        for n in 0..100_000 {
            let mut f = || match n % 4 {
                0 => special[rng.usize(0..special.len())],
                _ => (rng.f32() - 0.5) * [1.0, 1e-10, 1e10][n % 3],
            };
            let normal = [f(), f(), f()];
            let glam = Vec3::from(normal)
                .normalize_or_zero()
                .dot(light.direction)
                .max(0.0);
            assert_eq!(
                light.intensity_of(normal).to_bits(),
                (light.ambient + light.diffuse * glam).to_bits(),
                "{normal:?}"
            );
        }
    }

    /// The channel-by-channel conversion [`to_rgba8`] stands for.
    fn per_channel(c: Vec4) -> [u8; 4] {
        let q = |v: f32| (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
        [q(c.x), q(c.y), q(c.z), q(c.w)]
    }

    /// The vector conversion gives the per-channel bytes for every kind of
    /// value: each rounding boundary `(k + 0.5) / 255` and its neighbours,
    /// values out of range, infinities, NaN, and random ones.
    #[test]
    fn the_vector_conversion_to_rgba8_is_the_per_channel_one() {
        let mut values = vec![0.0, -0.0, 1.0, -1.0, 2.0, f32::INFINITY, f32::NEG_INFINITY];
        values.extend([
            f32::NAN,
            f32::MIN_POSITIVE,
            f32::MAX,
            f32::MIN,
            1.0 + f32::EPSILON,
        ]);
        for k in 0..=255 {
            let edge = (k as f32 + 0.5) / 255.0;
            values.extend([edge, edge.next_down(), edge.next_up(), k as f32 / 255.0]);
        }
        let mut rng = fastrand::Rng::with_seed(8);
        values.extend((0..100_000).map(|_| rng.f32() * 1.2 - 0.1));
        for (i, &v) in values.iter().enumerate() {
            let w = values[(i * 7 + 3) % values.len()];
            let c = Vec4::new(v, w, 1.0 - v, 0.5 * w);
            assert_eq!(to_rgba8(c), per_channel(c), "{c:?}");
        }
    }
}
