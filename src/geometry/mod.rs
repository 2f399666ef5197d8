//! Geometry input: where the triangles and lines the core draws come from.
//!
//! * the 3D pipeline, the course's five steps: vertices ([`MeshVertex`]),
//!   the vertex shader ([`VertexShader`], [`Transform`]), assembly
//!   ([`assemble`], [`Topology`]), clipping ([`ClipVolume`]), perspective
//!   divide and viewport ([`Viewport`]), culling ([`CullMode`],
//!   [`FrontFace`]) and set-up, run by [`process_triangles`] into a
//!   [`Geometry`], then drawn by [`draw`] on one thread or band by band
//!   ([`draw_binned`]);
//! * a mesh rendered end to end ([`MeshRenderer`]: camera, shading,
//!   wireframe), and a frame's time in parts that add up to it
//!   ([`FrameTimes`]);
//! * meshes ([`Mesh`], from PLY with [`load_ply`] or OBJ with
//!   [`load_obj`]);
//! * simple polygons with holes and their spade triangulation
//!   ([`Polygon`]); outlines of any shape filled by a winding rule, with
//!   the exact winding-number oracle ([`Outline`]);
//! * the text inputs of the command line (triangle soups, polygons, line
//!   sets: [`read_shapes`]), small 2D scenes of screen-space triangles
//!   ([`Scene2D`]: the course's examples), and the fragments a back-end
//!   emits for a text file's shapes ([`list_fragments`]);
//! * the receding checkerboard floor that texture filtering is taught
//!   on, with each pixel's ground truth ([`Floor`]).
//!
//! ```
//! use rasterlab::geometry::{process_triangles, ClipVertex, PipelineOptions, Viewport};
//! use rasterlab::raster::Varyings;
//! use glam::Vec4;
//!
//! // A clip-space triangle crossing the near plane: clipped, divided,
//! // mapped to a 16 x 16 viewport and set up for a back-end.
//! let positions = [Vec4::new(-0.5, -0.5, 0.0, 1.0), Vec4::new(0.5, -0.5, 0.0, 1.0), Vec4::new(0.0, 0.5, -3.0, 1.0)];
//! let shader = |p: &Vec4| ClipVertex { position: *p, varyings: Varyings::default() };
//! let viewport = Viewport { width: 16, height: 16 };
//! let geometry = process_triangles(&positions, &[[0, 1, 2]], &shader, viewport, &PipelineOptions::default()).unwrap();
//! assert_eq!(geometry.stats.clipped, 1);
//! assert!(!geometry.setups.is_empty());
//! ```

pub(crate) mod floor;
mod frame_times;
pub(crate) mod input;
// Some of it only the program calls: unused without the `cli` feature.
#[cfg_attr(not(feature = "cli"), allow(dead_code))]
pub(crate) mod listing;
pub(crate) mod mesh;
pub(crate) mod outline;
pub(crate) mod pipeline;
pub(crate) mod polygon;
pub(crate) mod render;
pub(crate) mod scene;

pub use floor::{Floor, SKY};
pub use frame_times::FrameTimes;
pub(crate) use frame_times::{milliseconds, optional_milliseconds};
pub use input::{
    parse_polygons, parse_shapes, read_polygons, read_shapes, Look, PolygonFile, Shapes,
};
pub use listing::{list_fragments, FragmentListing, FragmentsRequest};
pub use mesh::{load_obj, load_ply, parse_obj, read_ply, triangulate_face, Mesh};
pub use outline::{twice_signed_area, Outline};
pub use pipeline::{
    assemble, draw, draw_binned, draw_clearing, positions_from_floats, process_triangles,
    process_triangles_into, ClipPlanes, ClipResult, ClipVertex, ClipVolume, CullMode, FrontFace,
    Geometry, GeometryStats, MeshVertex, PipelineOptions, Topology, Transform, VertexShader,
    Viewport, GUARD_LIMIT_PX, PLANE_NAMES, W_MIN,
};
pub use polygon::{Polygon, Side};
pub use render::{Frame, FrameStats, MeshRenderer, RenderSettings, Shading};
pub use scene::{collect_fragments, scene_colour, setup_triangles, Scene2D, BLUE, RED};
// What only the `rasterlab` program uses; absent without the `cli` feature.
#[cfg(feature = "cli")]
pub use self::listing::{
    list_fragments_in_file, list_polygon_fragments_in_file, PolygonFragmentsRequest,
};
