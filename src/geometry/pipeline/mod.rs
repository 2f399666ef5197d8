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
//! 4. rasterization          any triangle back-end                               crate::raster::triangle
//! 5. fragment shader        the shared fragment stage                           crate::raster::stage
//! ```
//!
//! [`process_triangles`] runs steps 2 and 3 and returns a [`Geometry`]: the
//! set-up triangles for a back-end, their vertex data for the fragment
//! stage, and counts of what was clipped, culled and dropped. [`draw()`]
//! then rasterizes it with a back-end through the shared stage. Nothing
//! with `w <= 0` reaches the rasterizer: such vertices are clipped away
//! first, and [`Viewport::to_screen`] refuses them.

//!
//! The files follow the steps: [`vertex`], [`assembly`], [`clip`],
//! `viewport` (divide and viewport transform), `setup` (per triangle: clip,
//! cull, set up), `process` (the steps run in parallel chunks),
//! `geometry` (the result), `draw` and `bands` (drawing it, on one thread
//! or band by band).

pub(crate) mod assembly;
mod camera;
pub(crate) mod clip;
pub(crate) mod vertex;

mod bands;
mod draw;
mod geometry;
mod options;
mod process;
mod setup;
mod viewport;

pub use assembly::{assemble, Topology};
pub use camera::Camera;
pub use clip::{ClipResult, ClipVertex, ClipVolume, GUARD_LIMIT_PX, PLANE_NAMES, W_MIN};
pub use draw::{draw, draw_binned, draw_binned_clearing, draw_clearing};
pub use geometry::Geometry;
pub use options::{ClipPlanes, CullMode, FrontFace, PipelineOptions};
pub use process::{process_lines, process_triangles, process_triangles_into};
pub use setup::GeometryStats;
pub use vertex::{positions_from_floats, MeshVertex, Transform, VertexShader};
pub use viewport::Viewport;

pub(crate) use draw::{draw_runs, draw_runs_binned, BatchDraw, Pass};
pub(crate) use geometry::GeometryInParts;
pub(crate) use process::DrawInput;
