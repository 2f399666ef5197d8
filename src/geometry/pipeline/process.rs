//! Running the pipeline: the vertex shader on every vertex (once, however
//! many triangles share it), then the per-triangle work of [`setup`](super::setup)
//! on chunks of the triangles in parallel, joined in input order so that
//! the result, ids included, does not depend on the number of threads.

use super::bands::{chunk_len, Bands};
use super::clip::{ClipVertex, ClipVolume};
use super::geometry::{Geometry, GeometryInParts, Scratch};
use super::setup::{
    AssemblyInput, GeometryStats, Part, ScreenPoint, MIN_TRIANGLE_CHUNK, TRIANGLE_CHUNKS_PER_THREAD,
};
use super::vertex::VertexShader;
use super::viewport::to_screen_vertex;
use super::{PipelineOptions, Viewport};
use crate::error::{Error, Result};
use crate::raster::primitive::{ShadedLine, ShadedVertex};
use crate::raster::vector;
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
    fn run(self) -> u8 {
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
    pub(crate) fn process_into<V: Sync, S: VertexShader<V>>(
        &mut self,
        vertices: &[V],
        triangles: &[[u32; 3]],
        shader: &S,
        viewport: Viewport,
        options: &PipelineOptions,
    ) -> Result<()> {
        let input = DrawInput {
            vertices,
            triangles,
            shader,
            viewport,
            options,
        };
        let (stats, bands) = assemble(&mut self.scratch, &mut self.shaded.vertices, &input, true)?;
        self.stats = stats;
        self.keep_in_parts(vertices.len(), bands.map(|b| (b, viewport)));
        Ok(())
    }
}

/// One draw's input to the geometry stages.
struct DrawInput<'a, V, S> {
    vertices: &'a [V],
    triangles: &'a [[u32; 3]],
    shader: &'a S,
    viewport: Viewport,
    options: &'a PipelineOptions,
}

/// The pipeline's geometry stages: shades every vertex into `shaded`, and
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
    let DrawInput {
        vertices,
        triangles,
        shader,
        viewport,
        options,
    } = *draw;
    Error::check_indices(triangles.iter().flatten(), vertices.len())?;
    let clip = ClipVolume::new(viewport.width, viewport.height);
    // Each vertex is shaded once, however many triangles share it; those
    // inside the clip volume are divided and snapped once too. Both
    // buffers are sized first (reused from the last draw) and filled in
    // place, chunk by chunk.
    let n = vertices.len();
    let placeholder = ShadedVertex::flat(0.0, glam::Vec4::ZERO);
    scratch.screen.truncate(n);
    scratch.screen.resize(n, ScreenPoint::default());
    shaded.truncate(n);
    shaded.resize(n, placeholder);
    let refused = scratch
        .screen
        .par_chunks_mut(VERTEX_CHUNK)
        .zip(shaded.par_chunks_mut(VERTEX_CHUNK))
        .zip(vertices.par_chunks(VERTEX_CHUNK))
        .map(|((screen, shaded), input)| {
            let chunk = ShadeVertices {
                shader,
                clip: &clip,
                viewport: &viewport,
                input,
                screen,
                shaded,
            };
            vector::run(chunk) & REFUSED != 0
        })
        .reduce(|| false, |a, b| a | b);
    // Only a draw with a refused vertex looks for the first one (a scan of
    // every vertex costs the dragon 0.5 ms a frame).
    if let Some(i) = refused
        .then(|| scratch.screen.iter().position(|s| s.outcode & REFUSED != 0))
        .flatten()
    {
        // Shade the first refused vertex again to say why.
        let out = shader.shade(&vertices[i]);
        Error::check_finite(out.position.to_array())?;
        to_screen_vertex(&viewport, &out)?;
    }
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
    let input = AssemblyInput {
        vertices,
        shader,
        screen: &scratch.screen,
        mesh_vertices: vertices.len() as u32,
        clip: &clip,
        viewport: &viewport,
        options,
        bands,
    };
    scratch.parts.resize_with(chunks, Part::default);
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
