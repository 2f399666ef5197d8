//! The 3D pipeline: from vertices to the triangle back-ends.
//!
//! The course's five steps (seed 000) with the article's frame changes
//! (seed 003):
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

use crate::edge::{EdgeFunction, FillRule, PixelRect, TriangleSetup};
use crate::error::{Error, Result};
use crate::fixed::{Fixed, FixedPoint};
use crate::fragment::WorkCounters;
use crate::stage::{
    FragmentShader, FragmentStage, Interpolation, ShadedLine, ShadedTriangle, ShadedVertex,
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
        self.triangles += other.triangles;
    }
}

/// Triangles ready for a back-end, and their data for the fragment stage.
#[derive(Clone, Debug, Default)]
pub struct Geometry {
    /// Set-up triangles; triangle `i` has id `i`.
    pub setups: Vec<TriangleSetup>,
    /// The fragment stage's data for triangle id `i`.
    pub triangles: Vec<ShadedTriangle>,
    /// The assembled primitive each triangle came from.
    pub source: Vec<u32>,
    /// Counts of what happened.
    pub stats: GeometryStats,
}

/// A vertex after the divide and viewport transform.
#[derive(Copy, Clone, Debug)]
struct ScreenVertex {
    point: FixedPoint,
    shaded: ShadedVertex,
}

fn to_screen_vertex(viewport: &Viewport, v: &ClipVertex) -> Result<ScreenVertex> {
    let (point, depth, inv_w) = viewport.to_screen(v.position)?;
    Ok(ScreenVertex {
        point,
        shaded: ShadedVertex {
            depth,
            inv_w,
            varyings: v.varyings,
        },
    })
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
            triangles: crate::stage::shade_triangles(&setups, vertices),
            source: (0..setups.len() as u32).collect(),
            stats: GeometryStats {
                primitives: vertices.len() as u64,
                degenerate: (vertices.len() - setups.len()) as u64,
                triangles: setups.len() as u64,
                ..GeometryStats::default()
            },
            setups,
        }
    }

    /// The parts one after the other, triangle ids renumbered from 0; the
    /// copying is spread over rayon's threads.
    fn join(parts: &[Geometry]) -> Geometry {
        let mut starts = Vec::with_capacity(parts.len());
        let mut total = 0;
        let mut stats = GeometryStats::default();
        for p in parts {
            starts.push(total);
            total += p.setups.len();
            stats.add(&p.stats);
        }
        // The part holding triangle i, and i's index in it.
        let locate = |i: usize| {
            let part = starts.partition_point(|&s| s <= i) - 1;
            (&parts[part], i - starts[part])
        };
        Geometry {
            setups: (0..total)
                .into_par_iter()
                .map(|i| {
                    let (p, j) = locate(i);
                    TriangleSetup {
                        id: i as u32,
                        ..p.setups[j]
                    }
                })
                .collect(),
            triangles: (0..total)
                .into_par_iter()
                .map(|i| {
                    let (p, j) = locate(i);
                    p.triangles[j]
                })
                .collect(),
            source: (0..total)
                .into_par_iter()
                .map(|i| {
                    let (p, j) = locate(i);
                    p.source[j]
                })
                .collect(),
            stats,
        }
    }

    /// Sets up one screen-space triangle and keeps it unless it is
    /// degenerate, of a winding other than `winding` (when given), or culled.
    fn push(
        &mut self,
        v: [ScreenVertex; 3],
        source: u32,
        winding: Option<i8>,
        options: &PipelineOptions,
    ) {
        let id = self.setups.len() as u32;
        let Some(setup) = TriangleSetup::new(id, v.map(|s| s.point), options.rule)
            .filter(|s| winding.is_none_or(|w| w == s.winding))
        else {
            self.stats.degenerate += 1;
            return;
        };
        let facing_viewer =
            (setup.winding > 0) == (options.front_face == FrontFace::CounterClockwise);
        let culled = match options.cull {
            CullMode::None => false,
            CullMode::Back => !facing_viewer,
            CullMode::Front => facing_viewer,
        };
        if culled {
            self.stats.culled += 1;
            return;
        }
        self.triangles
            .push(ShadedTriangle::new(&setup, v.map(|s| s.shaded)));
        self.setups.push(setup);
        self.source.push(source);
        self.stats.triangles += 1;
    }
}

/// Triangles assembled per task, at least.
const MIN_TRIANGLE_CHUNK: usize = 16_384;

/// The shaded vertices of a draw, shared by the tasks that assemble its
/// triangles.
struct AssemblyInput<'a> {
    shaded: &'a [ClipVertex],
    codes: &'a [u8],
    screen: &'a [Option<ScreenVertex>],
    clip: &'a ClipVolume,
    viewport: &'a Viewport,
    options: &'a PipelineOptions,
}

impl AssemblyInput<'_> {
    /// Assembles, clips, culls and sets up `triangles`, the first of which
    /// is primitive number `first` of the draw; ids start at 0.
    fn process(&self, triangles: &[[u32; 3]], first: usize) -> Geometry {
        let (viewport, options) = (self.viewport, self.options);
        let mut geometry = Geometry {
            setups: Vec::with_capacity(triangles.len()),
            triangles: Vec::with_capacity(triangles.len()),
            source: Vec::with_capacity(triangles.len()),
            stats: GeometryStats::default(),
        };
        let mut polygon = Vec::with_capacity(10);
        for (index, t) in triangles.iter().enumerate() {
            geometry.stats.primitives += 1;
            let source = (first + index) as u32;
            let idx = t.map(|i| i as usize);
            if let [Some(a), Some(b), Some(c)] = idx.map(|i| self.screen[i]) {
                geometry.push([a, b, c], source, None, options);
                continue;
            }
            let corners = idx.map(|i| self.shaded[i]);
            let codes = idx.map(|i| self.codes[i]);
            match self.clip.clip_triangle(&corners, codes, &mut polygon) {
                ClipResult::Inside => unreachable!("inside vertices all have screen positions"),
                ClipResult::Outside => geometry.stats.rejected += 1,
                ClipResult::Cut(_) => {
                    geometry.stats.clipped += 1;
                    // A cut vertex can miss its plane when the triangle's
                    // coordinates differ by more than f64 resolves (say 1e30
                    // next to 1e-5); such a polygon is dropped, never drawn wrong.
                    let Ok(screen) = polygon
                        .iter()
                        .map(|v| to_screen_vertex(viewport, v))
                        .collect::<Result<Vec<ScreenVertex>>>()
                    else {
                        geometry.stats.unresolvable += 1;
                        continue;
                    };
                    // The fan of a convex polygon keeps one winding. Cut points
                    // that are nearly collinear can snap into a sliver of the
                    // opposite winding, which would overlap its neighbour; the
                    // polygon's winding (the sign of its area, the sum of its fan
                    // triangles' signed areas) decides which slivers are dropped.
                    let fan: Vec<[ScreenVertex; 3]> = (1..screen.len().saturating_sub(1))
                        .map(|i| [screen[0], screen[i], screen[i + 1]])
                        .collect();
                    let twice_area: i64 = fan
                        .iter()
                        .map(|[a, b, c]| EdgeFunction::through(b.point, c.point).eval(a.point))
                        .sum();
                    let winding = if twice_area < 0 { -1 } else { 1 };
                    for triangle in fan {
                        geometry.push(triangle, source, Some(winding), options);
                    }
                }
            }
        }
        geometry
    }
}

/// Runs the vertex shader on every vertex, assembles `triangles` (indices
/// into `vertices`), clips, divides, maps to the viewport, snaps, culls and
/// sets up what is left.
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
    Error::check_indices(triangles.iter().flatten(), vertices.len())?;
    let clip = ClipVolume::new(viewport.width, viewport.height);
    let shaded: Vec<ClipVertex> = vertices.par_iter().map(|v| shader.shade(v)).collect();
    Error::check_finite(shaded.iter().flat_map(|v| v.position.to_array()))?;
    let codes: Vec<u8> = shaded
        .par_iter()
        .map(|v| clip.outcode(v.position))
        .collect();
    // Vertices inside the clip volume are divided and snapped once, however
    // many triangles share them.
    let screen: Vec<Option<ScreenVertex>> = shaded
        .par_iter()
        .zip(&codes)
        .map(|(v, &c)| {
            if c == 0 {
                to_screen_vertex(&viewport, v).map(Some)
            } else {
                Ok(None)
            }
        })
        .collect::<Result<_>>()?;
    let vertices = AssemblyInput {
        shaded: &shaded,
        codes: &codes,
        screen: &screen,
        clip: &clip,
        viewport: &viewport,
        options,
    };
    let chunk = crate::binning::chunk_len(triangles.len(), MIN_TRIANGLE_CHUNK);
    let mut parts: Vec<Geometry> = triangles
        .par_chunks(chunk)
        .enumerate()
        .map(|(c, part)| vertices.process(part, c * chunk))
        .collect();
    if parts.len() <= 1 {
        return Ok(parts.pop().unwrap_or_default());
    }
    Ok(Geometry::join(&parts))
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
                from: a.point,
                to: b.point,
                vertices: [a.shaded, b.shaded],
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
        .with_triangles(&geometry.triangles)
        .with_depth(depth)
        .with_interpolation(interpolation);
    backend.rasterize(&geometry.setups, viewport, &mut stage)
}
