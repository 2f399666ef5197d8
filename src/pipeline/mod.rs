//! The 3D pipeline: from vertices to the triangle back-ends.
//!
//! The course's five steps (the course chapter) with the article's frame changes
//! (the software-rasterizer article):
//!
//! ```text
//! 1. vertex specification   positions (+ normals, UVs, colours), index buffer   vertex::MeshVertex, mesh::Mesh
//! 2. vertex shader          model -> world -> view -> clip space (P V M p)       vertex::VertexShader, vertex::Transform
//! 3. primitive assembly     list / strip / fan, indexed or not                  assembly::assemble
//!    clipping               near and far planes, w > 0, guard band (clip space) clip::ClipVolume
//!    perspective divide     (x, y, z) / w, keep 1 / w for interpolation         Viewport::to_screen
//!    viewport transform     NDC -> pixels, y down; depth (z/w + 1) / 2; snap    Viewport::to_screen
//!    back-face culling      winding of the snapped triangle                     CullMode, FrontFace
//! 4. rasterization          any triangle back-end                               crate::triangle
//! 5. fragment shader        the shared fragment stage                           crate::stage
//! ```
//!
//! [`process_triangles`] runs steps 2 and 3 and returns a [`Geometry`]: the
//! set-up triangles for a back-end, their vertex data for the fragment
//! stage, and counts of what was clipped, culled and dropped. [`draw`]
//! then rasterizes it with a back-end through the shared stage. Nothing
//! with `w <= 0` reaches the rasterizer: such vertices are clipped away
//! first, and [`Viewport::to_screen`] refuses them.

pub mod assembly;
pub mod camera;
pub mod clip;
pub mod vertex;

use crate::edge::{FillRule, PixelRect, TriangleSetup};
use crate::error::{Error, Result};
use crate::fixed::{Fixed, FixedPoint};
use crate::fragment::WorkCounters;
use crate::stage::{
    FragmentShader, FragmentStage, Interpolation, ShadedLine, ShadedTriangle, ShadedVertex,
    TriangleData,
};
use crate::target::{DepthState, RenderTarget};
use crate::triangle::TriangleRasterizer;
use clip::{ClipResult, ClipVertex, ClipVolume};
use rayon::prelude::*;
use vertex::VertexShader;

/// Which faces back-face culling removes.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum CullMode {
    /// Keep every triangle.
    #[default]
    None,
    /// Drop triangles facing away from the viewer.
    Back,
    /// Drop triangles facing the viewer.
    Front,
}

/// Which winding, as seen on screen, faces the viewer.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum FrontFace {
    /// Counter-clockwise triangles face the viewer (OpenGL's default).
    #[default]
    CounterClockwise,
    /// Clockwise triangles face the viewer.
    Clockwise,
}

macro_rules! named_enum {
    ($ty:ident, $what:literal, $($variant:ident = $name:literal),+) => {
        impl $ty {
            /// The name used on the command line.
            pub fn name(self) -> &'static str {
                match self { $($ty::$variant => $name),+ }
            }
        }
        impl std::fmt::Display for $ty {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.name())
            }
        }
        impl std::str::FromStr for $ty {
            type Err = $crate::Error;
            fn from_str(s: &str) -> $crate::Result<Self> {
                match s {
                    $($name => Ok($ty::$variant),)+
                    _ => Err($crate::Error::UnknownName {
                        what: $what,
                        name: s.to_string(),
                        known: [$($name),+].join(", "),
                    }),
                }
            }
        }
    };
}
pub(crate) use named_enum;

named_enum!(
    CullMode,
    "cull mode",
    None = "none",
    Back = "back",
    Front = "front"
);
named_enum!(
    FrontFace,
    "front face",
    CounterClockwise = "ccw",
    Clockwise = "cw"
);

/// How geometry is turned into set-up triangles.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub struct PipelineOptions {
    /// Fill rule for the set-up.
    pub rule: FillRule,
    /// Back-face culling.
    pub cull: CullMode,
    /// Which winding faces the viewer.
    pub front_face: FrontFace,
}

/// The perspective divide and viewport transform for a target size.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Viewport {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

impl Viewport {
    /// Divides by `w` and maps normalised device coordinates to pixels:
    /// `x_px = (x/w + 1) width / 2`, `y_px = (1 - y/w) height / 2` (y grows
    /// down on screen), depth `(z/w + 1) / 2` clamped to `[0, 1]`, and
    /// snaps the position. Returns the snapped point, the depth and `1/w`.
    ///
    /// Errors: `w <= 0` ([`Error::NonPositiveW`]), a non-finite value, or a
    /// point beyond the guard band.
    #[inline]
    pub fn to_screen(&self, clip: glam::Vec4) -> Result<(FixedPoint, f32, f32)> {
        if clip.w.is_nan() || clip.w <= 0.0 {
            return Err(Error::NonPositiveW { w: clip.w });
        }
        let w = f64::from(clip.w);
        let x = (f64::from(clip.x) / w + 1.0) * 0.5 * f64::from(self.width);
        let y = (1.0 - f64::from(clip.y) / w) * 0.5 * f64::from(self.height);
        let depth = ((f64::from(clip.z) / w + 1.0) * 0.5).clamp(0.0, 1.0) as f32;
        let point = FixedPoint {
            x: Fixed::snap_f64(x)?,
            y: Fixed::snap_f64(y)?,
        };
        Ok((point, depth, (1.0 / w) as f32))
    }
}

/// What happened to the primitives of a draw.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub struct GeometryStats {
    /// Triangles assembled.
    pub primitives: u64,
    /// Of those, entirely outside the clip volume.
    pub rejected: u64,
    /// Of those, cut by a clip plane (each may give several triangles).
    pub clipped: u64,
    /// Triangles removed by back-face culling.
    pub culled: u64,
    /// Triangles of zero area after snapping.
    pub degenerate: u64,
    /// Cut triangles dropped because their coordinates span more orders of
    /// magnitude than `f64` can intersect exactly enough (e.g. 1e30 and 1e-5).
    pub unresolvable: u64,
    /// Triangles whose bounding box holds no pixel centre of the viewport
    /// (too small to cover a sample, or off-screen): dropped, as they
    /// could not produce a fragment.
    pub empty_bounds: u64,
    /// Triangles handed to the rasterizer.
    pub triangles: u64,
}

impl GeometryStats {
    /// Adds another set of counts to these.
    pub fn add(&mut self, other: &GeometryStats) {
        self.primitives += other.primitives;
        self.rejected += other.rejected;
        self.clipped += other.clipped;
        self.culled += other.culled;
        self.degenerate += other.degenerate;
        self.unresolvable += other.unresolvable;
        self.empty_bounds += other.empty_bounds;
        self.triangles += other.triangles;
    }
}

/// Triangles ready for a back-end, and their data for the fragment stage.
///
/// A `Geometry` can be filled again and again by [`process_triangles_into`]
/// (one frame after the other): its buffers keep their memory, so a frame
/// costs no allocation once the first is done.
#[derive(Clone, Debug, Default)]
pub struct Geometry {
    /// Set-up triangles; triangle `i` has id `i`.
    pub setups: Vec<TriangleSetup>,
    /// The fragment stage's data: the vertices, and for triangle id `i`
    /// its vertex indices and depth plane.
    pub shaded: TriangleData,
    /// The assembled primitive each triangle came from.
    pub source: Vec<u32>,
    /// Counts of what happened.
    pub stats: GeometryStats,
    /// Buffers kept from one draw to the next.
    scratch: Scratch,
    /// When the triangles were left in the parts that assembled them (see
    /// [`Geometry::runs`]; `setups`, `shaded.triangles` and `source` are
    /// then empty): the rows per band and the viewport of the bins the
    /// parts filled as they kept their triangles.
    in_parts: Option<(u32, Viewport)>,
}

/// A run of set-up triangles and their stage data: the set-up with id `i`
/// in the run belongs to `triangles[i]`. A draw is one run, or, when the
/// pipeline left its triangles in the parts its tasks assembled, one run
/// per part, in order.
#[derive(Copy, Clone, Debug)]
pub(crate) struct TriangleRun<'a> {
    pub setups: &'a [TriangleSetup],
    pub triangles: &'a [ShadedTriangle],
}

/// The working buffers of [`process_triangles_into`].
#[derive(Clone, Debug, Default)]
struct Scratch {
    /// Per vertex: its snapped screen position and clip out-code.
    screen: Vec<ScreenPoint>,
    /// What each task made of its chunk of the triangles.
    parts: Vec<Part>,
}

/// A vertex's place after the vertex shader: out-code, and when that is 0
/// (inside every clip plane) its snapped screen position and depth (kept
/// here too, so that assembly reads only these 16 bytes per vertex).
#[derive(Copy, Clone, Debug, Default)]
struct ScreenPoint {
    point: FixedPoint,
    depth: f32,
    outcode: u8,
}

/// Out-code bit for a vertex the pipeline refuses (the seven clip planes
/// use the bits below): a vertex shader output that is not finite, or one
/// inside the clip volume that the viewport transform cannot snap.
const REFUSED: u8 = 1 << 7;

/// What one task makes of a chunk of the triangles: set-ups with ids
/// counted from 0 in the chunk, the vertices made by clipping in a
/// list of their own (the k-th is vertex `n + k` of a draw of `n`
/// vertices), and, when binning, per band the ids of the triangles whose
/// bounds meet it.
#[derive(Clone, Debug, Default)]
struct Part {
    setups: Vec<TriangleSetup>,
    triangles: Vec<ShadedTriangle>,
    source: Vec<u32>,
    clip_vertices: Vec<ShadedVertex>,
    stats: GeometryStats,
    /// Rows per band, 0 when not binning.
    band_rows: u32,
    bins: Vec<Vec<u32>>,
}

/// Divides by `w`, maps to the viewport and snaps a clip-space vertex.
fn to_screen_vertex(viewport: &Viewport, v: &ClipVertex) -> Result<(FixedPoint, ShadedVertex)> {
    let (point, depth, inv_w) = viewport.to_screen(v.position)?;
    Ok((
        point,
        ShadedVertex {
            depth,
            inv_w,
            varyings: v.varyings,
        },
    ))
}

impl Geometry {
    /// A draw of screen-space triangles (2D input): `setups` (those of the
    /// `vertices.len()` triangles that are not degenerate) with their vertex
    /// data, `vertices[i]` for triangle id `i`, each its own source.
    pub fn of_screen_triangles(
        setups: Vec<TriangleSetup>,
        vertices: &[[ShadedVertex; 3]],
    ) -> Geometry {
        Geometry {
            shaded: TriangleData::of_triangles(&setups, vertices),
            source: (0..setups.len() as u32).collect(),
            stats: GeometryStats {
                primitives: vertices.len() as u64,
                degenerate: (vertices.len() - setups.len()) as u64,
                triangles: setups.len() as u64,
                ..GeometryStats::default()
            },
            setups,
            scratch: Scratch::default(),
            in_parts: None,
        }
    }

    /// The triangles in runs, in id order: one run when gathered, one per
    /// part otherwise.
    pub(crate) fn runs(&self) -> Vec<TriangleRun<'_>> {
        if self.in_parts.is_some() {
            self.scratch
                .parts
                .iter()
                .map(|p| TriangleRun {
                    setups: &p.setups,
                    triangles: &p.triangles,
                })
                .collect()
        } else {
            vec![TriangleRun {
                setups: &self.setups,
                triangles: &self.shaded.triangles,
            }]
        }
    }

    /// When the triangles are in parts that binned them into bands of
    /// `band_rows` rows of `viewport`: per run, per band, the indices of
    /// the run's triangles meeting the band.
    pub(crate) fn bins_of_parts(
        &self,
        band_rows: u32,
        viewport: Viewport,
    ) -> Option<Vec<&[Vec<u32>]>> {
        (self.in_parts == Some((band_rows, viewport)))
            .then(|| self.scratch.parts.iter().map(|p| &p.bins[..]).collect())
    }

    /// Empties the triangle arrays, keeping their memory.
    fn clear_triangles(&mut self) {
        self.setups.clear();
        self.shaded.triangles.clear();
        self.source.clear();
    }

    /// Leaves several parts where they are, for a draw that reads them as
    /// runs: only their clip vertices are appended after the
    /// `mesh_vertices` shaded ones, and the parts' references to them
    /// renumbered. Saves the copy of [`gather`](Self::gather). The parts
    /// binned their triangles into bands of `band_rows` rows of `viewport`.
    fn keep_in_parts(
        &mut self,
        parts: &mut [Part],
        mesh_vertices: usize,
        band_rows: u32,
        viewport: Viewport,
    ) {
        self.clear_triangles();
        let n = mesh_vertices as u32;
        for p in parts.iter_mut() {
            if !p.clip_vertices.is_empty() {
                let clip_start = self.shaded.vertices.len() as u32;
                for t in &mut p.triangles {
                    t.vertices = t.vertices.map(|v| index_in_draw(v, n, clip_start));
                }
                self.shaded.vertices.extend_from_slice(&p.clip_vertices);
            }
        }
        self.in_parts = Some((band_rows, viewport));
    }

    /// Gathers the parts into this geometry, one after the other, with
    /// triangle ids renumbered from 0 and clip vertices appended after the
    /// `mesh_vertices` shaded ones. Each part copies its triangles into its
    /// own range of the result, on rayon's threads. A single part is moved
    /// in without copying.
    fn gather(&mut self, parts: &mut [Part], mesh_vertices: usize) {
        self.in_parts = None;
        if let [part] = parts {
            std::mem::swap(&mut self.setups, &mut part.setups);
            std::mem::swap(&mut self.shaded.triangles, &mut part.triangles);
            std::mem::swap(&mut self.source, &mut part.source);
            self.shaded.vertices.extend_from_slice(&part.clip_vertices);
            return;
        }
        // A set-up and its stage triangle to size the arrays with.
        let filler = parts
            .iter()
            .find_map(|p| Some((*p.setups.first()?, *p.triangles.first()?)));
        let total = parts.iter().map(|p| p.setups.len()).sum();
        let Some((setup, triangle)) = filler else {
            self.clear_triangles();
            return;
        };
        // Sized without clearing: from one frame to the next the lengths
        // barely change, so the filler is written only past the old length.
        resize_keeping(&mut self.setups, total, setup);
        resize_keeping(&mut self.shaded.triangles, total, triangle);
        resize_keeping(&mut self.source, total, 0);
        // Each part's range of the three arrays, its first id, and where
        // its clip vertices start.
        let mut ranges = Vec::with_capacity(parts.len());
        let (mut setups, mut triangles, mut source) = (
            &mut self.setups[..],
            &mut self.shaded.triangles[..],
            &mut self.source[..],
        );
        let (mut id, mut clip_start) = (0u32, mesh_vertices as u32);
        for p in parts.iter() {
            let n = p.setups.len();
            let (s, rest_s) = std::mem::take(&mut setups).split_at_mut(n);
            let (t, rest_t) = std::mem::take(&mut triangles).split_at_mut(n);
            let (o, rest_o) = std::mem::take(&mut source).split_at_mut(n);
            (setups, triangles, source) = (rest_s, rest_t, rest_o);
            ranges.push((s, t, o, id, clip_start));
            id += n as u32;
            clip_start += p.clip_vertices.len() as u32;
            self.shaded.vertices.extend_from_slice(&p.clip_vertices);
        }
        let n = mesh_vertices as u32;
        parts.par_iter().zip(ranges).for_each(
            |(p, (setups, triangles, source, first_id, clip_start))| {
                for (k, (d, s)) in setups.iter_mut().zip(&p.setups).enumerate() {
                    *d = TriangleSetup {
                        id: first_id + k as u32,
                        ..*s
                    };
                }
                for (d, t) in triangles.iter_mut().zip(&p.triangles) {
                    *d = ShadedTriangle {
                        vertices: t.vertices.map(|v| index_in_draw(v, n, clip_start)),
                        ..*t
                    };
                }
                source.copy_from_slice(&p.source);
            },
        );
    }
}

/// A part's vertex index `v` in the draw of `n` mesh vertices: those keep
/// their index; the part's clip vertices, numbered from `n` in the part,
/// start at `clip_start` in the draw.
#[inline]
fn index_in_draw(v: u32, n: u32, clip_start: u32) -> u32 {
    if v < n {
        v
    } else {
        v - n + clip_start
    }
}

/// Sets the length of `v` to `len`, writing `filler` only into the
/// entries past its old length (which the caller then overwrites).
fn resize_keeping<T: Copy>(v: &mut Vec<T>, len: usize, filler: T) {
    v.truncate(len);
    v.resize(len, filler);
}

impl Part {
    /// Empties the part, keeping its memory, to bin what it keeps into
    /// `bands` bands of `band_rows` rows (none: no binning).
    fn clear(&mut self, band_rows: u32, bands: usize) {
        self.setups.clear();
        self.triangles.clear();
        self.source.clear();
        self.clip_vertices.clear();
        self.stats = GeometryStats::default();
        self.band_rows = band_rows;
        self.bins.truncate(bands);
        self.bins.iter_mut().for_each(Vec::clear);
        self.bins.resize_with(bands, Vec::new);
    }

    /// Keeps the triangle with these vertices (indices, snapped positions
    /// and depths) and sets it up, unless it is degenerate, of a winding
    /// other than `winding` (when given), culled, or without a pixel sample
    /// of the viewport in its bounding box.
    #[allow(clippy::too_many_arguments)]
    fn push(
        &mut self,
        vertices: [u32; 3],
        points: [FixedPoint; 3],
        depths: [f32; 3],
        source: u32,
        winding: Option<i8>,
        options: &PipelineOptions,
        viewport: PixelRect,
    ) {
        let signed_area = TriangleSetup::signed_area(points);
        let this_winding = signed_area.signum() as i8;
        if signed_area == 0 || winding.is_some_and(|w| w != this_winding) {
            self.stats.degenerate += 1;
            return;
        }
        let facing_viewer =
            (this_winding > 0) == (options.front_face == FrontFace::CounterClockwise);
        let culled = match options.cull {
            CullMode::None => false,
            CullMode::Back => !facing_viewer,
            CullMode::Front => facing_viewer,
        };
        if culled {
            self.stats.culled += 1;
            return;
        }
        let bounds = TriangleSetup::sample_bounds(points).intersect(viewport);
        if bounds.is_empty() {
            self.stats.empty_bounds += 1;
            return;
        }
        let id = self.setups.len() as u32;
        if self.band_rows > 0 {
            crate::binning::bin(&mut self.bins, self.band_rows, bounds, id);
        }
        let Some(setup) = TriangleSetup::new(id, points, options.rule) else {
            unreachable!("the area was checked to be non-zero");
        };
        self.triangles
            .push(ShadedTriangle::new(&setup, vertices, depths));
        self.setups.push(setup);
        self.source.push(source);
        self.stats.triangles += 1;
    }
}

/// Vertices shaded per task.
const VERTEX_CHUNK: usize = 4096;

/// Shades one vertex and, when it lies inside every clip plane, divides
/// and snaps it: its assembly record and its stage vertex.
#[inline]
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

/// Triangles assembled per task, at least.
const MIN_TRIANGLE_CHUNK: usize = 4096;

/// Chunks of triangles per thread. The cost of a triangle varies along a
/// mesh (culled runs are cheap, kept runs are set up), so a few large
/// chunks leave one thread waiting: on the full dragon with two threads,
/// assembly took 14.2 ms in 8 chunks, 10.4 ms in 64 (one thread: 20 ms).
const TRIANGLE_CHUNKS_PER_THREAD: usize = 32;

/// The shaded vertices of a draw, shared by the tasks that assemble its
/// triangles.
struct AssemblyInput<'a, V, S> {
    /// The draw's vertices and vertex shader, to shade again the corners
    /// of the (few) triangles that must be clipped.
    vertices: &'a [V],
    shader: &'a S,
    screen: &'a [ScreenPoint],
    /// The number of vertices of the draw: vertices made by clipping are
    /// numbered after them.
    mesh_vertices: u32,
    clip: &'a ClipVolume,
    viewport: &'a Viewport,
    options: &'a PipelineOptions,
    /// Rows per band when the parts bin what they keep, else 0.
    band_rows: u32,
}

impl<V, S: VertexShader<V>> AssemblyInput<'_, V, S> {
    /// Assembles, clips, culls and sets up `triangles`, the first of which
    /// is primitive number `first` of the draw, into `part`.
    fn process(&self, triangles: &[[u32; 3]], first: usize, part: &mut Part) {
        let (viewport, options) = (self.viewport, self.options);
        let pixels = PixelRect::of_target(viewport.width, viewport.height);
        let mesh_vertices = self.mesh_vertices;
        let bands = match self.band_rows {
            0 => 0,
            rows => viewport.height.div_ceil(rows) as usize,
        };
        part.clear(self.band_rows, bands);
        part.setups.reserve(triangles.len());
        part.triangles.reserve(triangles.len());
        part.source.reserve(triangles.len());
        let mut polygon = Vec::with_capacity(10);
        for (index, t) in triangles.iter().enumerate() {
            part.stats.primitives += 1;
            let source = (first + index) as u32;
            let idx = t.map(|i| i as usize);
            let screen = idx.map(|i| self.screen[i]);
            let codes = screen.map(|s| s.outcode);
            if codes == [0; 3] {
                let depths = screen.map(|s| s.depth);
                part.push(
                    *t,
                    screen.map(|s| s.point),
                    depths,
                    source,
                    None,
                    options,
                    pixels,
                );
                continue;
            }
            if codes[0] & codes[1] & codes[2] != 0 {
                part.stats.rejected += 1;
                continue;
            }
            let corners = idx.map(|i| self.shader.shade(&self.vertices[i]));
            let ClipResult::Cut(_) = self.clip.clip_triangle(&corners, codes, &mut polygon) else {
                unreachable!("the out-codes say the triangle straddles a plane");
            };
            part.stats.clipped += 1;
            // A cut vertex can miss its plane when the triangle's
            // coordinates differ by more than f64 resolves (say 1e30
            // next to 1e-5); such a polygon is dropped, never drawn wrong.
            let Ok(screen) = polygon
                .iter()
                .map(|v| to_screen_vertex(viewport, v))
                .collect::<Result<Vec<(FixedPoint, ShadedVertex)>>>()
            else {
                part.stats.unresolvable += 1;
                continue;
            };
            let base = mesh_vertices + part.clip_vertices.len() as u32;
            part.clip_vertices.extend(screen.iter().map(|(_, v)| *v));
            // The fan of a convex polygon keeps one winding. Cut points
            // that are nearly collinear can snap into a sliver of the
            // opposite winding, which would overlap its neighbour; the
            // polygon's winding (the sign of its area, the sum of its fan
            // triangles' signed areas) decides which slivers are dropped.
            let fan: Vec<[usize; 3]> = (1..screen.len().saturating_sub(1))
                .map(|i| [0, i, i + 1])
                .collect();
            let twice_area: i64 = fan
                .iter()
                .map(|f| TriangleSetup::signed_area(f.map(|k| screen[k].0)))
                .sum();
            let winding = if twice_area < 0 { -1 } else { 1 };
            for f in fan {
                part.push(
                    f.map(|k| base + k as u32),
                    f.map(|k| screen[k].0),
                    f.map(|k| screen[k].1.depth),
                    source,
                    Some(winding),
                    options,
                    pixels,
                );
            }
        }
    }
}

/// Runs the vertex shader on every vertex, assembles `triangles` (indices
/// into `vertices`), clips, divides, maps to the viewport, snaps, culls and
/// sets up what is left.
///
/// Triangles whose bounding box holds no pixel centre of the viewport are
/// dropped here too (counted in [`GeometryStats::empty_bounds`]): they
/// could not produce a fragment.
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
    process(
        geometry, vertices, triangles, shader, viewport, options, true,
    )
}

/// [`process_triangles_into`] for a draw that reads the triangles as
/// [`Geometry::runs`] (what [`crate::binning::draw_binned`] does): on
/// several threads they stay in the parts the tasks assembled, one run per
/// part, instead of being copied into one array. The image drawn is the
/// same.
pub(crate) fn process_triangles_in_runs<V: Sync, S: VertexShader<V>>(
    geometry: &mut Geometry,
    vertices: &[V],
    triangles: &[[u32; 3]],
    shader: &S,
    viewport: Viewport,
    options: &PipelineOptions,
) -> Result<()> {
    process(
        geometry, vertices, triangles, shader, viewport, options, false,
    )
}

/// The pipeline's geometry stages; `gather` joins the parts into one run.
fn process<V: Sync, S: VertexShader<V>>(
    geometry: &mut Geometry,
    vertices: &[V],
    triangles: &[[u32; 3]],
    shader: &S,
    viewport: Viewport,
    options: &PipelineOptions,
    gather: bool,
) -> Result<()> {
    Error::check_indices(triangles.iter().flatten(), vertices.len())?;
    let clip = ClipVolume::new(viewport.width, viewport.height);
    let mut scratch = std::mem::take(&mut geometry.scratch);
    // Each vertex is shaded once, however many triangles share it; those
    // inside the clip volume are divided and snapped once too. Both
    // buffers are sized first (reused from the last draw) and filled in
    // place, chunk by chunk.
    let n = vertices.len();
    let placeholder = ShadedVertex::flat(0.0, glam::Vec4::ZERO);
    scratch.screen.truncate(n);
    scratch.screen.resize(n, ScreenPoint::default());
    geometry.shaded.vertices.truncate(n);
    geometry.shaded.vertices.resize(n, placeholder);
    let refused = scratch
        .screen
        .par_chunks_mut(VERTEX_CHUNK)
        .zip(geometry.shaded.vertices.par_chunks_mut(VERTEX_CHUNK))
        .zip(vertices.par_chunks(VERTEX_CHUNK))
        .map(|((screen, shaded), input)| {
            let mut outcodes = 0;
            for ((s, v), vertex) in screen.iter_mut().zip(shaded).zip(input) {
                let (point, shaded) = screen_vertex(shader, &clip, &viewport, vertex);
                outcodes |= point.outcode;
                (*s, *v) = (point, shaded);
            }
            outcodes & REFUSED != 0
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
    let chunk = crate::binning::chunk_len(
        triangles.len(),
        TRIANGLE_CHUNKS_PER_THREAD,
        MIN_TRIANGLE_CHUNK,
    );
    let chunks = triangles.len().div_ceil(chunk).max(1);
    // Parts that stay parts bin their triangles for the draw as they keep
    // them, sparing it a pass over the set-ups.
    let in_parts = !gather && chunks > 1;
    let band_rows = if in_parts {
        crate::binning::band_rows(viewport.height, rayon::current_num_threads())
    } else {
        0
    };
    let input = AssemblyInput {
        vertices,
        shader,
        screen: &scratch.screen,
        mesh_vertices: vertices.len() as u32,
        clip: &clip,
        viewport: &viewport,
        options,
        band_rows,
    };
    scratch.parts.resize_with(chunks, Part::default);
    scratch
        .parts
        .par_iter_mut()
        .zip(triangles.par_chunks(chunk.max(1)))
        .enumerate()
        .for_each(|(c, (part, list))| input.process(list, c * chunk, part));
    if triangles.is_empty() {
        scratch.parts[0].clear(0, 0);
    }
    geometry.stats = GeometryStats::default();
    for p in &scratch.parts {
        geometry.stats.add(&p.stats);
    }
    let mesh_vertices = vertices.len();
    if in_parts {
        geometry.keep_in_parts(&mut scratch.parts, mesh_vertices, band_rows, viewport);
    } else {
        geometry.gather(&mut scratch.parts, mesh_vertices);
    }
    geometry.scratch = scratch;
    Ok(())
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

/// Rasterizes `geometry` with `backend` into `target` through the shared
/// fragment stage.
pub fn draw(
    geometry: &Geometry,
    backend: &dyn TriangleRasterizer,
    shader: &dyn FragmentShader,
    depth: DepthState,
    interpolation: Interpolation,
    target: &mut RenderTarget,
) -> WorkCounters {
    let viewport = PixelRect::of_target(target.width(), target.height());
    let mut stage = FragmentStage::new(target, shader)
        .with_triangles(&geometry.shaded)
        .with_depth(depth)
        .with_interpolation(interpolation);
    let mut work = WorkCounters::default();
    for run in geometry.runs() {
        stage.use_triangles(run.triangles);
        work.add(&backend.rasterize(run.setups, viewport, &mut stage));
    }
    work
}
