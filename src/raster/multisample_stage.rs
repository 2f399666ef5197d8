//! The multisampled fragment stage: coverage masks through the depth test,
//! shading once per pixel, and a box-filter resolve.
//!
//! With multisampling (MSAA, see [`SamplePattern`]) a pixel keeps a colour
//! and a depth per sample, in a [`MultisampleTarget`]. A draw
//! ([`draw_multisampled`]) goes through the same steps as the one-sample
//! stage ([`FragmentStage`](crate::raster::FragmentStage)), per pixel and
//! triangle, as Direct3D and Vulkan define them by default:
//!
//! 1. **coverage**: the triangle's coverage mask at the pixel, one bit per
//!    sample, each decided as a pixel centre is (the back-end's own walk,
//!    once per sample, on the triangles moved so that the sample falls on
//!    the centre: [`masks_of`](crate::raster::masks_of));
//! 2. **depth per sample**: the triangle's depth plane evaluated at each
//!    covered sample, tested against that sample's stored depth; the
//!    samples that pass form the surviving mask;
//! 3. **shading once per pixel**, at the pixel centre, only when some
//!    sample survived: the barycentrics come from the exact edge values
//!    at the centre, extrapolated when the centre lies outside the
//!    triangle (the APIs' default, without `centroid`);
//! 4. **merge**: that one colour blended into each surviving sample by
//!    the draw's [`Blend`], and each sample's own depth written;
//! 5. **resolve** ([`MultisampleTarget::resolve`]): each pixel's colour is
//!    the mean of its samples' colours (a box filter) in linear light,
//!    encoded to the nearest 8-bit sRGB value.
//!
//! Triangles are taken in order, so every pixel sees its triangles in
//! primitive order, as in the one-sample stage; the image does not
//! depend on the back-end. With one sample (the pattern's only point is
//! the centre) every step is the one-sample stage's, and the resolved
//! image is bit-identical to a [`draw`](crate::geometry::draw) of the same
//! triangles.
//!
//! ```
//! use glam::Vec4;
//! use rasterlab::raster::{draw_multisampled, triangle_backend, Blend, DepthState, FillRule, FixedPoint, MixSpace};
//! use rasterlab::raster::{Flat, Interpolation, MultisampleTarget, SamplePattern, ShadedVertex};
//! use rasterlab::raster::{TriangleData, TriangleSetup};
//!
//! // A white triangle whose long edge crosses pixel (2, 1), leaving its
//! // centre out but 2 of its 4 samples in: the pixel resolves to half white.
//! let v = [(0.0, 0.0), (4.0, 0.0), (0.0, 3.7)].map(|(x, y)| FixedPoint::snap_f64(x, y).unwrap());
//! let setups = [TriangleSetup::new(0, v, FillRule::TopLeft).unwrap()];
//! let white = ShadedVertex::flat(0.5, Vec4::ONE);
//! let data = TriangleData::of_triangles(&setups, &[[white; 3]]);
//! let mut target = MultisampleTarget::new(4, 4, SamplePattern::standard(4).unwrap()).unwrap();
//! let backend = triangle_backend("bbox").unwrap();
//! let (depth, lerp) = (DepthState::DEFAULT, Interpolation::PerspectiveCorrect);
//! draw_multisampled(&setups, &data, backend, &Flat, (depth, Blend::REPLACE), lerp, &mut target);
//! let image = target.resolve();
//! assert_eq!(image.color[image.index(2, 1)], [188, 188, 188, 255]);
//! let encoded = target.resolve_in(MixSpace::Encoded);
//! assert_eq!(encoded.color[encoded.index(2, 1)], [128, 128, 128, 255]);
//! assert_eq!(image.color[image.index(0, 0)], [255, 255, 255, 255]);
//! ```

use crate::error::{Error, Result};
use crate::raster::edge::{PixelRect, TriangleSetup};
use crate::raster::fragment::{FragmentList, TriangleFragment, WorkCounters};
use crate::raster::multisample::{moved, SamplePattern, SIXTEENTH};
use crate::raster::primitive::TriangleData;
use crate::raster::shader::FragmentShader;
use crate::raster::srgb::MixSpace;
use crate::raster::stage::{merge_pixel, shade_triangle_fragment, Blend, Interpolation, Source};
use crate::raster::target::{DepthState, RenderTarget};
use crate::raster::triangle::TriangleRasterizer;
use glam::Vec4;

/// The most samples a [`MultisampleTarget`] holds (colour and depth, 8
/// bytes each): 2^27, 1 GiB of buffers.
pub const MAX_TARGET_SAMPLES: u64 = 1 << 27;

/// Triangles whose masks are gathered together before they go through the
/// stage, in order.
const CHUNK: usize = 4096;

/// A colour and a depth buffer with a value per sample of each pixel.
///
/// Two targets are equal when their size, pattern and buffers are.
#[derive(Clone, Debug)]
pub struct MultisampleTarget {
    width: u32,
    height: u32,
    pattern: SamplePattern,
    /// Colour of sample `i` of pixel `(x, y)` at `(y * width + x) * N + i`,
    /// `N` the pattern's count.
    pub color: Vec<[u8; 4]>,
    /// Depth of each sample, laid out as `color`.
    pub depth: Vec<f32>,
    /// Per pixel (`y * width + x`), how many triangles covered at least
    /// one of its samples: the one-sample stage's coverage count, counted
    /// before the depth test.
    pub coverage: Vec<u16>,
    /// The draw's buffers, kept from one draw to the next so that a frame
    /// after the first allocates nothing.
    scratch: Scratch,
}

impl PartialEq for MultisampleTarget {
    fn eq(&self, other: &Self) -> bool {
        (self.width, self.height, self.pattern) == (other.width, other.height, other.pattern)
            && self.color == other.color
            && self.depth == other.depth
            && self.coverage == other.coverage
    }
}

/// What [`draw_multisampled`] fills and empties for each chunk of
/// triangles.
#[derive(Clone, Debug, Default)]
struct Scratch {
    list: FragmentList,
    shifted: Vec<TriangleSetup>,
    hits: Vec<u64>,
}

impl MultisampleTarget {
    /// A `width` x `height` target with the samples of `pattern`, cleared
    /// to black and the far depth. Errors on a size
    /// [`RenderTarget::new`] refuses, and on more than
    /// [`MAX_TARGET_SAMPLES`] samples, with the memory it would take.
    pub fn new(width: u32, height: u32, pattern: SamplePattern) -> Result<MultisampleTarget> {
        RenderTarget::check_size(width, height)?;
        let samples = u64::from(width) * u64::from(height) * u64::from(pattern.count());
        if samples > MAX_TARGET_SAMPLES {
            return Err(Error::TooMuchWork(format!(
                "{width}x{height} pixels with {} samples each need {:.1} GB of sample buffers; \
                 at most {:.1} GB ({MAX_TARGET_SAMPLES} samples) are allowed: \
                 ask for fewer samples or a smaller target",
                pattern.count(),
                (samples * 8) as f64 / 1e9,
                (MAX_TARGET_SAMPLES * 8) as f64 / 1e9,
            )));
        }
        Ok(MultisampleTarget {
            width,
            height,
            pattern,
            color: vec![RenderTarget::BLACK; samples as usize],
            depth: vec![RenderTarget::FAR_DEPTH; samples as usize],
            coverage: vec![0; width as usize * height as usize],
            scratch: Scratch::default(),
        })
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Where each pixel's samples are.
    pub fn pattern(&self) -> SamplePattern {
        self.pattern
    }

    /// Index of sample 0 of pixel `(x, y)`; sample `i` follows at `+ i`.
    pub fn index(&self, x: u32, y: u32) -> usize {
        (y as usize * self.width as usize + x as usize) * self.pattern.count() as usize
    }

    /// Every sample set to `color` and the far depth, every coverage
    /// count to 0.
    pub fn clear(&mut self, color: [u8; 4]) {
        self.color.fill(color);
        self.depth.fill(RenderTarget::FAR_DEPTH);
        self.coverage.fill(0);
    }

    /// The image: each pixel's colour the mean of its samples' (a box
    /// filter) in linear light, encoded to the nearest sRGB value (see
    /// [`MixSpace`]); its depth the nearest of its samples'; its coverage
    /// count as drawn.
    pub fn resolve(&self) -> RenderTarget {
        self.resolve_in(MixSpace::Linear)
    }

    /// [`resolve`](Self::resolve), the mean taken in `space`: in the
    /// stored, encoded values with [`MixSpace::Encoded`], each channel's
    /// sum rounded to nearest in integers.
    pub fn resolve_in(&self, space: MixSpace) -> RenderTarget {
        let n = self.pattern.count() as usize;
        let mut image = RenderTarget::new(self.width, self.height)
            .expect("the size was checked when the target was made");
        image.coverage.copy_from_slice(&self.coverage);
        for (pixel, (colors, depths)) in self
            .color
            .chunks_exact(n)
            .zip(self.depth.chunks_exact(n))
            .enumerate()
        {
            image.color[pixel] = match space {
                MixSpace::Encoded => {
                    let mut sum = [0u32; 4];
                    for c in colors {
                        for (s, v) in sum.iter_mut().zip(c) {
                            *s += u32::from(*v);
                        }
                    }
                    sum.map(|s| ((s + n as u32 / 2) / n as u32) as u8)
                }
                MixSpace::Linear => {
                    let sum: Vec4 = colors.iter().map(|&c| space.decode(c)).sum();
                    space.encode(sum / n as f32)
                }
            };
            image.depth[pixel] = depths.iter().copied().fold(f32::INFINITY, f32::min);
        }
        image
    }
}

/// Draws `setups` (whose stage data is `data`, indexed by triangle id)
/// with `backend` into `target` through the multisampled stage: coverage
/// masks on the target's pattern, depth tested per sample with `depth`,
/// colour from `shader` once per pixel at its centre, merged into each
/// surviving sample by `blend`. The counters give
/// the back-end's tests and spans over all the passes, the triangles
/// (`primitives`) and the (pixel, triangle) pairs with a mask
/// (`fragments`).
pub fn draw_multisampled<S: FragmentShader + ?Sized>(
    setups: &[TriangleSetup],
    data: &TriangleData,
    backend: &dyn TriangleRasterizer,
    shader: &S,
    (depth, blend): (DepthState, Blend),
    interpolation: Interpolation,
    target: &mut MultisampleTarget,
) -> WorkCounters {
    let pattern = target.pattern;
    let rect = PixelRect::of_target(target.width, target.height);
    let mut work = WorkCounters {
        primitives: setups.len() as u64,
        ..WorkCounters::default()
    };
    let Scratch {
        mut list,
        mut shifted,
        // One entry per covered sample: the triangle's index in `setups`,
        // its pixel and the sample, packed so that sorting puts a pixel's
        // samples together and the triangles in order.
        mut hits,
    } = std::mem::take(&mut target.scratch);
    for (c, chunk) in setups.chunks(CHUNK).enumerate() {
        let first = (c * CHUNK) as u64;
        hits.clear();
        for i in 0..pattern.count() as usize {
            let (dx, dy) = pattern.offset(i);
            let (dx, dy) = (i64::from(dx) * SIXTEENTH, i64::from(dy) * SIXTEENTH);
            shifted.clear();
            // Each moved copy is numbered by its place in the chunk, which
            // its fragments then carry.
            shifted.extend(chunk.iter().enumerate().map(|(j, s)| TriangleSetup {
                id: j as u32,
                ..moved(s, -dx, -dy)
            }));
            list.triangles.clear();
            let passes = backend.rasterize(&shifted, rect, &mut list);
            work.samples_tested += passes.samples_tested;
            work.spans += passes.spans;
            // The index is under 2^32, the coordinates under 2^14 each
            // (the largest target side) and the sample under 2^4.
            hits.extend(list.triangles.iter().map(|f| {
                let index = first + u64::from(f.triangle);
                index << 32 | u64::from(f.y) << 18 | u64::from(f.x) << 4 | i as u64
            }));
        }
        // Each pass gave its hits nearly in order, triangle by triangle:
        // the stable sort finds those runs and merges them.
        hits.sort();
        let mut k = 0;
        while k < hits.len() {
            let key = hits[k] >> 4;
            let mut mask = 0u32;
            while k < hits.len() && hits[k] >> 4 == key {
                mask |= 1 << (hits[k] & 15);
                k += 1;
            }
            let setup = &setups[(key >> 28) as usize];
            let (y, x) = ((key >> 14 & 0x3fff) as u32, (key & 0x3fff) as u32);
            work.fragments += 1;
            shade_pixel(
                setup,
                data,
                shader,
                (depth, blend),
                interpolation,
                target,
                x,
                y,
                mask,
            );
        }
    }
    target.scratch = Scratch {
        list,
        shifted,
        hits,
    };
    work
}

/// Steps 2 to 4 for one pixel `(x, y)` of triangle `setup`, whose
/// coverage mask there is `mask`.
#[allow(clippy::too_many_arguments)]
#[inline]
fn shade_pixel<S: FragmentShader + ?Sized>(
    setup: &TriangleSetup,
    data: &TriangleData,
    shader: &S,
    (depth, blend): (DepthState, Blend),
    interpolation: Interpolation,
    target: &mut MultisampleTarget,
    x: u32,
    y: u32,
    mask: u32,
) {
    let Some(t) = data.triangles.get(setup.id as usize) else {
        return;
    };
    let pixel = y as usize * target.width as usize + x as usize;
    target.coverage[pixel] = target.coverage[pixel].saturating_add(1);
    let base = target.index(x, y);
    let mut passed = 0u32;
    let mut depths = [0.0f32; 16];
    let mut left = mask;
    while left != 0 {
        let i = left.trailing_zeros() as usize;
        left &= left - 1;
        let (dx, dy) = target.pattern.offset(i);
        let z = t
            .depth
            .at_offset(x, y, f32::from(dx) / 16.0, f32::from(dy) / 16.0);
        if depth.test.passes(z, target.depth[base + i]) {
            passed |= 1 << i;
            depths[i] = z;
        }
    }
    if passed == 0 {
        return;
    }
    let [Some(&a), Some(&b), Some(&c)] = t.vertices.map(|v| data.vertices.get(v as usize)) else {
        return;
    };
    let centre = TriangleFragment {
        x,
        y,
        triangle: setup.id,
        edges: setup.edge_values_at_pixel(i64::from(x), i64::from(y)),
    };
    let color =
        shade_triangle_fragment(shader, interpolation, [a, b, c], t.depth.at(x, y), &centre);
    let mut left = passed;
    while left != 0 {
        let i = left.trailing_zeros() as usize;
        left &= left - 1;
        let slot = depth
            .write
            .then(|| (&mut target.depth[base + i], depths[i]));
        merge_pixel(
            blend,
            Source::Rgba8(color),
            &mut target.color[base + i],
            slot,
        );
    }
}
