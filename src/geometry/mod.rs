//! Geometry input: where the triangles and lines the core draws come from.
//!
//! * [`pipeline`]: the 3D pipeline, the course's five steps (vertex
//!   shader, assembly, clipping, perspective divide, viewport, culling,
//!   set-up), and drawing its result, on one thread or band by band;
//! * [`render`]: a mesh rendered end to end (camera, shading, wireframe);
//! * [`FrameTimes`]: a frame's time in parts that add up to it;
//! * [`mesh`]: PLY and OBJ meshes;
//! * [`polygon`]: simple polygons with holes and their spade triangulation;
//! * [`input`]: the text inputs of the command line (triangle soups,
//!   polygons, line sets);
//! * [`scene`]: small 2D scenes of screen-space triangles;
//! * [`listing`]: the fragments a back-end emits for a text file's shapes.

mod frame_times;
pub mod input;
pub mod listing;
pub mod mesh;
pub mod pipeline;
pub mod polygon;
pub mod render;
pub mod scene;

pub(crate) use frame_times::milliseconds;
pub use frame_times::FrameTimes;
