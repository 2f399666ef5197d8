//! The core: everything a pixel goes through, from snapped vertices to the
//! colour and depth buffers.
//!
//! * [`fixed`]: snapping to 1/256 pixel and the guard band;
//! * [`edge`]: the course's implicit line equation as exact `i64` edge
//!   functions, fill rules (top-left, bottom-right, off-screen point,
//!   inclusive, exclusive) and triangle set-up;
//! * [`compact`]: the same edge functions in 32 bits for small triangles,
//!   relative to their box's corner, and the bound that keeps them exact;
//! * [`triangle`]: the triangle back-ends, one file each, and the
//!   [`TriangleRasterizer`](triangle::TriangleRasterizer) trait;
//! * [`line`](mod@line): the line back-ends, one file each, the
//!   [`LineRasterizer`](line::LineRasterizer) trait and line options;
//! * [`descriptor`]: what a back-end is, as data (name, description,
//!   walk, role, cost class), and the one work budget;
//! * [`backend`]: the registry of back-ends by name and by role;
//! * [`fragment`]: fragments, the [`FragmentSink`](fragment::FragmentSink)
//!   they go into, work counters;
//! * [`primitive`]: what the stage reads of a draw (per vertex depth,
//!   `1 / w` and varyings; per triangle its vertices and depth plane);
//! * [`stage`]: the shared fragment stage (depth test, interpolation,
//!   shading, writes);
//! * [`shader`]: fragment shaders and lights;
//! * [`target`]: colour, depth and coverage buffers.
//!
//! Nothing here depends on the rest of the crate: geometry input,
//! teaching and measurement are built on this.

pub mod backend;
pub mod compact;
pub mod descriptor;
pub mod edge;
pub mod fixed;
pub mod fragment;
pub mod line;
pub mod primitive;
pub mod shader;
pub mod stage;
pub mod target;
pub mod triangle;
pub(crate) mod vector;
