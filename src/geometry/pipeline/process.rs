//! Running the pipeline: the vertex shader on every vertex (once, however
//! many triangles share it), then the per-triangle work of [`setup`](super::setup)
//! on chunks of the triangles in parallel, joined in input order so that
//! the result, ids included, does not depend on the number of threads.

use super::bands::{chunk_len, Bands};
use super::clip::{ClipVertex, ClipVolume, W_MIN};
use super::geometry::{Geometry, GeometryInParts, Scratch};
use super::setup::{
    AssemblyInput, GeometryStats, ScreenPoint, MIN_TRIANGLE_CHUNK, TRIANGLE_CHUNKS_PER_THREAD,
};
use super::vertex::{MeshVertex, Transform, VertexShader};
use super::viewport::to_screen_vertex;
use super::{PipelineOptions, Viewport};
use crate::error::{Error, Result};
use crate::raster::edge::TriangleSetup;
use crate::raster::fixed::{Fixed, FixedPoint};
use crate::raster::primitive::{ShadedLine, ShadedVertex, TriangleData, Varyings};
use crate::raster::vector::{self, transform};
use glam::{Vec3, Vec4};
use rayon::prelude::*;

/// Out-code bit for a vertex the pipeline refuses (the seven clip planes
/// use the bits below): a vertex shader output that is not finite, or one
/// inside the clip volume that the viewport transform cannot snap.
const REFUSED: u8 = 1 << 7;

/// Vertices shaded per task.
const VERTEX_CHUNK: usize = 4096;

/// Shades one vertex and, when it lies inside every clip plane, divides
/// and snaps it: its assembly record and its stage vertex.
#[inline(always)]
fn screen_vertex<V, S: VertexShader<V>>(
    shader: &S,
    clip: &ClipVolume,
    viewport: &Viewport,
    vertex: &V,
) -> (ScreenPoint, ShadedVertex) {
    let out = shader.shade(vertex);
    let outcode = if out.position.is_finite() {
        clip.outcode(out.position)
    } else {
        REFUSED
    };
    // Outside a clip plane (or refused): no screen position. The stage
    // vertex is a placeholder no triangle refers to: a triangle with such a
    // corner is clipped, from its corners shaded again.
    let off_screen = |outcode| {
        let shaded = ShadedVertex {
            depth: 0.0,
            inv_w: 0.0,
            varyings: out.varyings,
        };
        let screen = ScreenPoint {
            outcode,
            ..ScreenPoint::default()
        };
        (screen, shaded)
    };
    if outcode != 0 {
        return off_screen(outcode);
    }
    match to_screen_vertex(viewport, &out) {
        Ok((point, shaded)) => {
            let depth = shaded.depth;
            (
                ScreenPoint {
                    point,
                    depth,
                    outcode,
                },
                shaded,
            )
        }
        Err(_) => off_screen(REFUSED),
    }
}

/// One task's vertices to shade, divide and snap: a loop compiled for the
/// baseline and for AVX2, the copy picked at run time (the same bits
/// either way).
struct ShadeVertices<'a, V, S> {
    shader: &'a S,
    clip: &'a ClipVolume,
    viewport: &'a Viewport,
    input: &'a [V],
    screen: &'a mut [ScreenPoint],
    shaded: &'a mut [ShadedVertex],
}

impl<V, S: VertexShader<V>> vector::Kernel for ShadeVertices<'_, V, S> {
    /// The out-codes of all the vertices, or-ed.
    type Output = u8;

    #[inline(always)]
    fn run(mut self) -> u8 {
        if let Some((transform, mesh)) = self.shader.as_transform(self.input) {
            if let Some(outcodes) = shade_in_lanes(transform, mesh, &mut self) {
                return outcodes;
            }
        }
        let mut outcodes = 0;
        let vertices = self.screen.iter_mut().zip(self.shaded).zip(self.input);
        for ((s, v), vertex) in vertices {
            let (point, shaded) = screen_vertex(self.shader, self.clip, self.viewport, vertex);
            outcodes |= point.outcode;
            (*s, *v) = (point, shaded);
        }
        outcodes
    }
}

/// [`ShadeVertices`] for the model-view-projection [`Transform`] of
/// `mesh` (the task's vertices): eight at a time by
/// [`transform::shade`], each lane it leaves (outside a plane, refused)
/// and the last few by the one-vertex path. The out-codes or-ed, or
/// `None` (nothing written) when the CPU has no AVX2.
#[inline(always)]
fn shade_in_lanes<V, S: VertexShader<V>>(
    shader: &Transform,
    mesh: &[MeshVertex],
    task: &mut ShadeVertices<'_, V, S>,
) -> Option<u8> {
    let (clip, viewport) = (task.clip, task.viewport);
    let uniforms = transform::Uniforms {
        mvp: shader.mvp.to_cols_array_2d(),
        normal_matrix: shader.normal_matrix.to_cols_array_2d(),
        light: shader
            .vertex_light
            .map(|l| (l.direction.to_array(), l.ambient, l.diffuse)),
        guard: clip.guard(),
        w_min: W_MIN,
        size: [viewport.width.into(), viewport.height.into()],
    };
    let mut outcodes = 0;
    let mut lanes = transform::Lanes::default();
    // Only the task's last group can be short, so this is filled once.
    let mut padded = transform::Records::default();
    let groups = task
        .screen
        .chunks_mut(8)
        .zip(task.shaded.chunks_mut(8))
        .zip(mesh.chunks(8));
    for ((screen, shaded), mesh) in groups {
        // The group's vertices as records of floats; a last group of
        // fewer than eight is copied, its other lanes left zero (their
        // results are not read).
        let rows: &[[f32; 12]] = bytemuck::cast_slice(mesh);
        let records = match <&transform::Records>::try_from(rows) {
            Ok(whole) => whole,
            Err(_) => {
                padded[..rows.len()].copy_from_slice(rows);
                &padded
            }
        };
        if !transform::shade(&uniforms, records, &mut lanes) {
            return None;
        }
        for (i, ((s, d), v)) in screen.iter_mut().zip(shaded).zip(mesh).enumerate() {
            if lanes.on_screen & (1 << i) == 0 {
                let (point, vertex) = screen_vertex(shader, clip, viewport, v);
                outcodes |= point.outcode;
                (*s, *d) = (point, vertex);
                continue;
            }
            let point = FixedPoint {
                x: Fixed::from_snapped(lanes.x[i]),
                y: Fixed::from_snapped(lanes.y[i]),
            };
            let depth = lanes.depth[i];
            *s = ScreenPoint {
                point,
                depth,
                outcode: 0,
            };
            // Element by element: `lanes.rgb.map(..)` would copy all
            // eight lanes of each component for every vertex, stores whose
            // loads then stalled (docs/performance-log.md, "2026-12-03,
            // `0acb613` to `4dfac5a`").
            let (rgb, normal) = (&lanes.rgb, &lanes.normal);
            *d = ShadedVertex {
                depth,
                inv_w: lanes.inv_w[i],
                varyings: Varyings {
                    color: Vec4::new(rgb[0][i], rgb[1][i], rgb[2][i], v.color.w),
                    uv: v.uv,
                    normal: Vec3::new(normal[0][i], normal[1][i], normal[2][i]),
                },
            };
        }
    }
    Some(outcodes)
}

/// Runs the vertex shader on every vertex, assembles `triangles` (indices
/// into `vertices`), clips, divides, maps to the viewport, snaps, culls and
/// sets up what is left.
///
/// Triangles whose bounding box holds no pixel centre of the viewport are
/// dropped here too (counted in [`GeometryStats::empty_bounds`]), and so
/// are those whose box holds at most 2x2 pixel centres, none of them
/// inside ([`GeometryStats::no_sample`]): they could not produce a
/// fragment.
///
/// The work is spread over rayon's threads: vertices are shaded in
/// parallel, triangles are processed in chunks in parallel, and the chunks'
/// results are joined in input order, so the result (ids included) does not
/// depend on the number of threads.
///
/// Errors: an index out of range, or a vertex shader output that is not
/// finite.
pub fn process_triangles<V: Sync, S: VertexShader<V>>(
    vertices: &[V],
    triangles: &[[u32; 3]],
    shader: &S,
    viewport: Viewport,
    options: &PipelineOptions,
) -> Result<Geometry> {
    let mut geometry = Geometry::default();
    process_triangles_into(
        &mut geometry,
        vertices,
        triangles,
        shader,
        viewport,
        options,
    )?;
    Ok(geometry)
}

/// [`process_triangles`] into an existing [`Geometry`], whose contents are
/// replaced and whose memory is reused: what a renderer drawing frame
/// after frame calls.
pub fn process_triangles_into<V: Sync, S: VertexShader<V>>(
    geometry: &mut Geometry,
    vertices: &[V],
    triangles: &[[u32; 3]],
    shader: &S,
    viewport: Viewport,
    options: &PipelineOptions,
) -> Result<()> {
    Error::check_indices(triangles.iter().flatten(), vertices.len())?;
    let input = DrawInput {
        vertices,
        triangles,
        shader,
        viewport,
        options,
    };
    let (stats, _) = assemble(
        &mut geometry.scratch,
        &mut geometry.shaded.vertices,
        &input,
        false,
    )?;
    geometry.stats = stats;
    geometry.gather(vertices.len());
    Ok(())
}

impl GeometryInParts {
    /// [`process_triangles_into`] for a draw that reads the triangles as
    /// runs ([`draw_binned`](super::draw_binned)): they stay in the parts
    /// the tasks assembled, one run per part, instead of being copied into
    /// one array; with several parts, each bins what it keeps into the
    /// bands of a draw on rayon's threads. The image drawn is the same.
    ///
    /// The caller has checked that every index is below `vertices.len()`
    /// ([`MeshRenderer::new`](crate::geometry::render::MeshRenderer::new)
    /// does, once for all its frames): the check is a pass over every
    /// index, on one thread whatever the draw's count, which a renderer
    /// need not pay frame after frame. (A bad index would stop the draw
    /// with a panic, never draw wrong.)
    pub(crate) fn process_into<V: Sync, S: VertexShader<V>>(
        &mut self,
        input: &DrawInput<'_, V, S>,
    ) -> Result<()> {
        let (stats, bands) = assemble(&mut self.scratch, &mut self.shaded.vertices, input, true)?;
        self.stats = stats;
        let binned = bands.map(|b| (b, input.viewport));
        self.keep_in_parts(input.vertices.len(), binned);
        Ok(())
    }

    /// The geometry stages of a draw on one thread, batch by batch:
    /// shades every vertex, then assembles, clips, culls and sets up the
    /// triangles `batch` at a time, and hands each batch's set-ups and
    /// stage data to `draw` before the next is assembled into the same
    /// buffers. The batches come in the triangles' order, so a draw that
    /// rasterizes each as it comes draws what one of the whole
    /// [`Geometry`] draws, the same bits.
    ///
    /// A whole mesh's set-ups and stage triangles (40 MB for the full
    /// dragon zoomed) do not stay in any cache between the assembly that
    /// writes them and the draw that reads them back; a batch's do.
    ///
    /// The caller has checked the indices, as for [`process_into`](Self::process_into).
    pub(crate) fn process_in_batches<V: Sync, S: VertexShader<V>>(
        &mut self,
        input: &DrawInput<'_, V, S>,
        batch: usize,
        mut draw: impl FnMut(&TriangleData, &[TriangleSetup]),
    ) -> Result<()> {
        let clip = input.clip_volume();
        shade_vertices(&mut self.scratch, &mut self.shaded.vertices, input, &clip)?;
        self.scratch.use_parts(1);
        let (screen, part) = (&self.scratch.screen, &mut self.scratch.parts[0]);
        let assembly = input.assembly(screen, &clip, None);
        let vertices = input.vertices;
        let mut stats = GeometryStats::default();
        let shaded = &mut self.shaded;
        for (b, list) in input.triangles.chunks(batch.max(1)).enumerate() {
            assembly.process(list, b * batch, part);
            stats.add(&part.stats);
            // The batch's clip vertices are numbered from the mesh's
            // vertex count, where they go.
            shaded.vertices.truncate(vertices.len());
            shaded.vertices.extend_from_slice(&part.clip_vertices);
            std::mem::swap(&mut shaded.triangles, &mut part.triangles);
            draw(shaded, &part.setups);
            std::mem::swap(&mut shaded.triangles, &mut part.triangles);
        }
        self.stats = stats;
        self.binned = None;
        Ok(())
    }
}

/// One draw's input to the geometry stages.
pub(crate) struct DrawInput<'a, V, S> {
    /// The vertices, as the vertex shader takes them.
    pub vertices: &'a [V],
    /// The triangles, as indices into `vertices`.
    pub triangles: &'a [[u32; 3]],
    /// The vertex shader.
    pub shader: &'a S,
    /// The target's size.
    pub viewport: Viewport,
    /// Fill rule, culling and the rest.
    pub options: &'a PipelineOptions,
}

impl<V, S> DrawInput<'_, V, S> {
    /// The clip volume of the draw's viewport.
    fn clip_volume(&self) -> ClipVolume {
        ClipVolume::with_planes(self.viewport.width, self.viewport.height, self.options.clip)
    }

    /// What the assembly tasks read, once the vertices are shaded into
    /// `screen`: the draw's triangles are clipped by `clip` and binned
    /// into `bands`, if any.
    fn assembly<'b>(
        &'b self,
        screen: &'b [ScreenPoint],
        clip: &'b ClipVolume,
        bands: Option<Bands>,
    ) -> AssemblyInput<'b, V, S> {
        AssemblyInput {
            vertices: self.vertices,
            shader: self.shader,
            screen,
            mesh_vertices: self.vertices.len() as u32,
            clip,
            viewport: &self.viewport,
            options: self.options,
            bands,
        }
    }
}

/// The pipeline's geometry stages, for triangles whose indices were
/// checked: shades every vertex into `shaded`, and
/// assembles, clips, culls and sets up the triangles into the parts of
/// `scratch`, one per task. With `bin`, and more than one part, the parts
/// also bin what they keep into the bands of a draw on rayon's threads,
/// which are returned with the counts of what happened.
fn assemble<V: Sync, S: VertexShader<V>>(
    scratch: &mut Scratch,
    shaded: &mut Vec<ShadedVertex>,
    draw: &DrawInput<'_, V, S>,
    bin: bool,
) -> Result<(GeometryStats, Option<Bands>)> {
    let clip = draw.clip_volume();
    shade_vertices(scratch, shaded, draw, &clip)?;
    let (triangles, viewport) = (draw.triangles, draw.viewport);
    let chunk = chunk_len(
        triangles.len(),
        TRIANGLE_CHUNKS_PER_THREAD,
        MIN_TRIANGLE_CHUNK,
    );
    let chunks = triangles.len().div_ceil(chunk).max(1);
    // Parts that stay parts bin their triangles for the draw as they keep
    // them, sparing it a pass over the set-ups.
    let bands = (bin && chunks > 1)
        .then(|| Bands::for_threads(viewport.height, rayon::current_num_threads()));
    scratch.use_parts(chunks);
    let input = draw.assembly(&scratch.screen, &clip, bands);
    scratch
        .parts
        .par_iter_mut()
        .zip(triangles.par_chunks(chunk.max(1)))
        .enumerate()
        .for_each(|(c, (part, list))| input.process(list, c * chunk, part));
    if triangles.is_empty() {
        scratch.parts[0].clear(None);
    }
    let mut stats = GeometryStats::default();
    for p in &scratch.parts {
        stats.add(&p.stats);
    }
    Ok((stats, bands))
}

/// The vertex stage of a draw whose indices were checked: shades every
/// vertex into `shaded`, and divides and snaps those inside the clip
/// volume `clip` into `scratch.screen`. Errors on the first vertex refused.
fn shade_vertices<V: Sync, S: VertexShader<V>>(
    scratch: &mut Scratch,
    shaded: &mut Vec<ShadedVertex>,
    draw: &DrawInput<'_, V, S>,
    clip: &ClipVolume,
) -> Result<()> {
    let DrawInput {
        vertices,
        shader,
        viewport,
        ..
    } = *draw;
    // Each vertex is shaded once, however many triangles share it; those
    // inside the clip volume are divided and snapped once too. Both
    // buffers are sized first (reused from the last draw) and filled in
    // place, chunk by chunk.
    let n = vertices.len();
    size_for_overwrite(&mut scratch.screen, n);
    size_for_overwrite(shaded, n);
    let refused = scratch
        .screen
        .par_chunks_mut(VERTEX_CHUNK)
        .zip(shaded.par_chunks_mut(VERTEX_CHUNK))
        .zip(vertices.par_chunks(VERTEX_CHUNK))
        .map(|((screen, shaded), input)| {
            let chunk = ShadeVertices {
                shader,
                clip,
                viewport: &viewport,
                input,
                screen,
                shaded,
            };
            vector::run(chunk) & REFUSED != 0
        })
        .reduce(|| false, |a, b| a | b);
    // Only a draw with a refused vertex looks for the first one: a scan of
    // every vertex would cost every frame a pass over its vertices.
    if let Some(i) = refused
        .then(|| scratch.screen.iter().position(|s| s.outcode & REFUSED != 0))
        .flatten()
    {
        // Shade the first refused vertex again to say why.
        let out = shader.shade(&vertices[i]);
        Error::check_finite(out.position.to_array())?;
        to_screen_vertex(&viewport, &out)?;
    }
    Ok(())
}

/// Gives `buffer` `n` elements, which the caller then overwrites.
///
/// A first frame's buffers are fresh memory, which the kernel zeroes page
/// by page as it is first written. Grown with placeholder values, they
/// were written twice, once by one thread; a buffer too small for `n` is
/// replaced by a zeroed allocation instead, which the allocator hands out
/// from fresh pages without writing them, so that the vertex stage's own
/// writes, on every thread, are the first: sizing the buffers by filling
/// them had cost a first frame more than the stage itself
/// (docs/performance-log.md, "2026-12-06, `f354b8e` to `b4efcdc`").
fn size_for_overwrite<T: bytemuck::Zeroable + Copy>(buffer: &mut Vec<T>, n: usize) {
    if buffer.capacity() < n {
        *buffer = vector::zeroed_in_huge_pages(n);
    } else {
        buffer.truncate(n);
        buffer.resize(n, T::zeroed());
    }
}

/// Runs the vertex shader on the end points of `segments` (index pairs
/// into `vertices`), clips each segment, divides and maps it to the viewport.
/// Segments entirely outside the clip volume are dropped; the rest keep
/// their order (segment `i` of the result has id `i`).
pub fn process_lines<V, S: VertexShader<V>>(
    vertices: &[V],
    segments: &[[u32; 2]],
    shader: &S,
    viewport: Viewport,
) -> Result<Vec<ShadedLine>> {
    Error::check_indices(segments.iter().flatten(), vertices.len())?;
    let clip = ClipVolume::new(viewport.width, viewport.height);
    let mut lines = Vec::with_capacity(segments.len());
    // Each vertex is shaded once, however many segments share it.
    let shaded: Vec<ClipVertex> = vertices.iter().map(|v| shader.shade(v)).collect();
    for s in segments {
        let [a, b] = s.map(|i| shaded[i as usize]);
        Error::check_finite(
            a.position
                .to_array()
                .into_iter()
                .chain(b.position.to_array()),
        )?;
        if let Some([a, b]) = clip.clip_segment(&a, &b) {
            let (a, b) = (
                to_screen_vertex(&viewport, &a)?,
                to_screen_vertex(&viewport, &b)?,
            );
            lines.push(ShadedLine {
                from: a.0,
                to: b.0,
                vertices: [a.1, b.1],
            });
        }
    }
    Ok(lines)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::pipeline::{CullMode, FrontFace};
    use crate::raster::edge::FillRule;
    use crate::raster::shader::DirectionalLight;
    use crate::raster::vector::Width;
    use glam::{Mat3, Mat4, Vec2};
    use proptest::prelude::*;

    /// Every bit of what the vertex stage wrote for one vertex: the screen
    /// record, and the stage vertex. A NaN is any NaN: Rust, as IEEE 754,
    /// leaves the sign and payload of a computed NaN unspecified (x86 keeps
    /// the first operand's, so swapping the operands of a product changes
    /// them).
    fn bits(s: &ScreenPoint, v: &ShadedVertex) -> Vec<u32> {
        let float = |x: f32| {
            if x.is_nan() {
                f32::NAN.to_bits()
            } else {
                x.to_bits()
            }
        };
        let c = v.varyings;
        let mut out = vec![
            s.point.x.raw() as u32,
            s.point.y.raw() as u32,
            float(s.depth),
            s.outcode.into(),
            float(v.depth),
            float(v.inv_w),
        ];
        out.extend(c.color.to_array().map(float));
        out.extend(c.uv.to_array().map(float));
        out.extend(c.normal.to_array().map(float));
        out
    }

    /// Shades `vertices` with `shader` on a `width` x `height` viewport,
    /// with the loop's `copy`: every vertex's bits, and the out-codes or-ed.
    fn shade_with(
        copy: Width,
        shader: &Transform,
        vertices: &[MeshVertex],
        (width, height): (u32, u32),
    ) -> (Vec<Vec<u32>>, u8) {
        let viewport = Viewport { width, height };
        let clip = ClipVolume::new(width, height);
        let n = vertices.len();
        let mut screen = vec![ScreenPoint::default(); n];
        let mut shaded = vec![ShadedVertex::flat(0.0, Vec4::ZERO); n];
        let task = ShadeVertices {
            shader,
            clip: &clip,
            viewport: &viewport,
            input: vertices,
            screen: &mut screen,
            shaded: &mut shaded,
        };
        let outcodes = vector::limited_to(copy, || vector::run(task));
        let bits = screen.iter().zip(&shaded).map(|(s, v)| bits(s, v));
        (bits.collect(), outcodes)
    }

    /// A float for a matrix entry or a coordinate: mostly ordinary, with
    /// the values that end up on a plane, beyond the guard band, or not
    /// finite.
    fn float() -> impl Strategy<Value = f32> {
        prop_oneof![
            6 => -2.0f32..2.0,
            1 => prop::sample::select(vec![
                0.0, -0.0, 1.0, -1.0, 0.5, W_MIN, -W_MIN, 1e-30, 1e30, -1e30,
                f32::MIN_POSITIVE, 1e-40, f32::MAX, f32::INFINITY, f32::NAN,
            ]),
            1 => any::<f32>(),
        ]
    }

    fn vector3() -> impl Strategy<Value = Vec3> {
        [float(), float(), float()].prop_map(Vec3::from_array)
    }

    fn mesh_vertex() -> impl Strategy<Value = MeshVertex> {
        (vector3(), vector3(), vector3()).prop_map(|(position, normal, rgb)| MeshVertex {
            position,
            normal,
            uv: Vec2::new(position.x, rgb.y),
            color: rgb.extend(0.75),
        })
    }

    fn transform() -> impl Strategy<Value = Transform> {
        let matrix = prop::array::uniform16(float());
        let light = prop::option::of((vector3(), float(), float()));
        (matrix, prop::array::uniform9(float()), light, any::<bool>()).prop_map(
            |(m, n, light, camera)| {
                // Half the cases a real camera (mostly on screen), half
                // any matrix.
                let mut t = if camera {
                    let view = Mat4::look_at_rh(Vec3::new(0.3, 0.2, 3.0), Vec3::ZERO, Vec3::Y);
                    let projection = Mat4::perspective_rh_gl(0.8, 1.5, 0.1, 10.0);
                    Transform::new(Mat4::IDENTITY, view, projection)
                } else {
                    let mut t = Transform::identity();
                    t.mvp = Mat4::from_cols_array(&m);
                    t.normal_matrix = Mat3::from_cols_array(&n);
                    t
                };
                if let Some((d, a, b)) = light {
                    t = t.with_vertex_light(DirectionalLight::new(d, a, b));
                }
                t
            },
        )
    }

    /// A camera's vertices: in and around the view, so that most are on
    /// screen and some cross a plane.
    fn seen_vertex() -> impl Strategy<Value = MeshVertex> {
        let finite = [-2.0f32..2.0, -2.0f32..2.0, -2.0f32..2.0];
        ([-6.0f32..6.0, -6.0f32..6.0, -12.0f32..4.0], finite).prop_map(|(p, normal)| MeshVertex {
            position: Vec3::from_array(p),
            normal: Vec3::from_array(normal),
            uv: Vec2::ZERO,
            color: Vec4::new(0.8, 0.6, 0.4, 1.0),
        })
    }

    proptest! {
        #![proptest_config(crate::test_support::proptest_config(3000, "tests/proptest-regressions/src-geometry-pipeline-process.txt"))]

        /// The vertex stage eight at a time (AVX2 lanes) writes the bits of
        /// the one-vertex path, for every vertex: on screen, outside a
        /// plane, not finite, or beyond the guard band; lit or not; and a
        /// count that leaves a group of fewer than eight.
        #[test]
        fn vertices_in_lanes_get_the_bits_of_one_at_a_time(
            shader in transform(),
            vertices in prop::collection::vec(prop_oneof![mesh_vertex(), seen_vertex()], 1..40),
            width in 1u32..5000,
            height in 1u32..5000,
        ) {
            let size = (width, height);
            let one_at_a_time = shade_with(Width::Baseline, &shader, &vertices, size);
            for copy in vector::copies() {
                prop_assert_eq!(&shade_with(copy, &shader, &vertices, size), &one_at_a_time);
            }
        }
    }

    /// The largest `f32` at most `v`.
    fn at_most(v: f64) -> f32 {
        let near = v as f32;
        if f64::from(near) > v {
            near.next_down()
        } else {
            near
        }
    }

    /// Runs the whole geometry stage with the loops' `copy`.
    fn geometry_with(
        copy: Width,
        vertices: &[MeshVertex],
        triangles: &[[u32; 3]],
        options: &PipelineOptions,
    ) -> Geometry {
        let view = Mat4::look_at_rh(Vec3::new(0.3, 0.2, 3.0), Vec3::ZERO, Vec3::Y);
        let projection = Mat4::perspective_rh_gl(0.8, 1.5, 0.1, 10.0);
        let shader = Transform::new(Mat4::IDENTITY, view, projection);
        let viewport = Viewport {
            width: 64,
            height: 48,
        };
        vector::limited_to(copy, || {
            process_triangles(vertices, triangles, &shader, viewport, options).unwrap()
        })
    }

    proptest! {
        #![proptest_config(crate::test_support::proptest_config(300, "tests/proptest-regressions/src-geometry-pipeline-process.txt"))]

        /// Assembly with its first tests in lanes (eight triangles at a
        /// time) keeps, sets up and counts what the one-at-a-time loop
        /// does, under every culling rule, front face and fill rule, with
        /// triangles on and off screen, clipped, and a last group of
        /// fewer than eight.
        #[test]
        fn triangles_in_lanes_assemble_as_one_at_a_time(
            vertices in prop::collection::vec(seen_vertex(), 24),
            triangles in prop::collection::vec(prop::array::uniform3(0u32..24), 1..60),
        ) {
            for cull in [CullMode::None, CullMode::Back, CullMode::Front] {
                for front_face in [FrontFace::CounterClockwise, FrontFace::Clockwise] {
                    for rule in [FillRule::TopLeft, FillRule::BottomRight] {
                        let options = PipelineOptions { rule, cull, front_face, ..Default::default() };
                        let expected = geometry_with(Width::Baseline, &vertices, &triangles, &options);
                        for copy in vector::copies() {
                            let lanes = geometry_with(copy, &vertices, &triangles, &options);
                            prop_assert_eq!(&lanes.setups, &expected.setups);
                            prop_assert_eq!(&lanes.shaded, &expected.shaded);
                            prop_assert_eq!(&lanes.source, &expected.source);
                            prop_assert_eq!(lanes.stats, expected.stats);
                        }
                    }
                }
            }
        }
    }

    /// The planes' bounds to the last bit: `z = -w`, `z = w`, `w = W_MIN`
    /// and the largest `|x| <= g w`, `|y| <= g w` are inside; one step of
    /// an `f32` further is outside. The lanes agree with the one-vertex
    /// path on both sides (whose out-codes are checked too).
    #[test]
    fn lanes_agree_on_each_plane_and_one_step_past_it() {
        let size = (1920, 1080);
        let [gx, gy] = ClipVolume::new(size.0, size.1).guard();
        // clip = (x, y, z, w) from the position (x, y, z) and w = W_MIN.
        let mut shader = Transform::identity();
        let at_w_min = Mat4::from_cols(Vec4::X, Vec4::Y, Vec4::Z, Vec4::W * W_MIN);
        let mut points = Vec::new();
        for w in [1.0, W_MIN] {
            let up = |v: f32| v.next_up();
            let down = |v: f32| v.next_down();
            let (x, y) = (
                at_most(f64::from(gx) * f64::from(w)),
                at_most(f64::from(gy) * f64::from(w)),
            );
            for (p, inside) in [
                (Vec3::new(0.0, 0.0, -w), true),
                (Vec3::new(0.0, 0.0, down(-w)), false),
                (Vec3::new(0.0, 0.0, w), true),
                (Vec3::new(0.0, 0.0, up(w)), false),
                (Vec3::new(x, 0.0, 0.0), true),
                (Vec3::new(up(x), 0.0, 0.0), false),
                (Vec3::new(-x, 0.0, 0.0), true),
                (Vec3::new(down(-x), 0.0, 0.0), false),
                (Vec3::new(0.0, y, 0.0), true),
                (Vec3::new(0.0, up(y), 0.0), false),
                (Vec3::new(0.0, -y, 0.0), true),
                (Vec3::new(0.0, down(-y), 0.0), false),
            ] {
                points.push((w, p, inside));
            }
        }
        for (w, p, inside) in points {
            shader.mvp = if w == 1.0 { Mat4::IDENTITY } else { at_w_min };
            let vertex = MeshVertex {
                position: p,
                ..MeshVertex::default()
            };
            let (bits, outcodes) = shade_with(Width::Baseline, &shader, &[vertex; 9], size);
            assert_eq!(outcodes == 0, inside, "{p} at w = {w}");
            for copy in vector::copies() {
                assert_eq!(
                    shade_with(copy, &shader, &[vertex; 9], size),
                    (bits.clone(), outcodes),
                    "{p} at w = {w}"
                );
            }
        }
        // And w just under W_MIN is outside.
        shader.mvp = Mat4::from_cols(Vec4::X, Vec4::Y, Vec4::Z, Vec4::W * W_MIN.next_down());
        let (_, outcodes) = shade_with(Width::Baseline, &shader, &[MeshVertex::default()], size);
        assert_ne!(outcodes, 0);
    }
}
