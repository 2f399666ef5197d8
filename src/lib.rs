//! # rasterlab
//!
//! Interchangeable rasterizer back-ends, all feeding **one shared fragment
//! / z-buffer stage**, for teaching, checking and comparing rasterization
//! algorithms.
//!
//! ```text
//! vertices ──► vertex shader ──► assembly ──► clip ──► divide ──► cull ──► viewport + snap
//!                                                                               │
//!        ┌──────────────────────────────────────────────────────────────────────┘
//!        ▼
//! a rasterizer back-end (line or triangle, chosen by name at run time)
//!        │  emits fragments: pixel (x, y) + the exact integer edge values
//!        ▼
//! the shared fragment stage: barycentrics ─► depth test ─► fragment shader ─► colour buffer
//!                                                │
//!                                       depth buffer (starts at 1.0)
//! ```
//!
//! ## The map
//!
//! The crate is in rooms; each depends only on the rooms above it.
//!
//! | room | what lives there |
//! |---|---|
//! | [`raster`] (the core) | fixed-point snapping, edge functions and fill rules, the triangle and line back-ends (one file each) and their registry, fragments, the shared fragment stage, shaders, render targets |
//! | [`geometry`] | where primitives come from: the 3D pipeline (vertex shader, assembly, clipping, divide, viewport, culling, drawing on one or many threads), meshes (PLY, OBJ), polygons (spade triangulation), text inputs, 2D scenes, mesh rendering |
//! | [`measure`] | workloads and the benchmark |
//! | [`teaching`] | step-by-step traces, grid pictures and heat maps, the side-by-side report |
//! | [`check`] | checking any rasterizer (a back-end, a closure, another program) against the rules, with shrunk counterexamples |
//! | [`lab`] | the interactive lab's requests, answers and server |
//!
//! Beside them: [`Error`] and [`Result`], and [`output`] (files checked
//! before the work and written whole). The names most uses need are
//! re-exported here, at the root.
//!
//! ## Where to start
//!
//! * **Studying an algorithm**: its file under [`raster::triangle`] or
//!   [`raster::line`](mod@raster::line) explains it in the course's terms; its trace in
//!   [`teaching::trace`] prints each step; [`teaching::grid_picture`] draws
//!   the pixel grid. [`Scene2D`] holds the course's examples (the
//!   depth-buffer example, the blue triangle).
//! * **Checking a rasterizer**: [`check`] runs generated cases against the
//!   rules and shrinks a failure; wrap yours as a [`check::Subject`] (or a
//!   closure), or run `rasterlab check --exec` on a program in any language.
//! * **Comparing performance**: [`measure::workload`] prepares the inputs,
//!   [`measure::benchmark`] times every back-end; meshes are drawn by
//!   [`MeshRenderer`].
//! * **Adding a back-end**: implement
//!   [`TriangleAlgorithm`](raster::triangle::TriangleAlgorithm) (or
//!   [`AliasedLine`](raster::line::AliasedLine)) in a file of its own under `raster/triangle/`
//!   (or `raster/line/`), declare it there with one `pub mod` line, and
//!   list it in [`raster::backend`]; every command, check, report,
//!   benchmark, trace and test picks it up from there.
//!
//! ```
//! use rasterlab::raster::shader::Flat;
//! use rasterlab::{triangle_backends, FillRule, Scene2D};
//!
//! // The rasterization slides' depth-buffer example, drawn by every triangle back-end.
//! let scene = Scene2D::depth_example(true);
//! let reference = scene.render(triangle_backends()[0], FillRule::TopLeft, &Flat).unwrap().0;
//! for b in triangle_backends() {
//!     let (image, _work) = scene.render(*b, FillRule::TopLeft, &Flat).unwrap();
//!     assert_eq!(image, reference, "{} differs", b.name());
//! }
//! ```

#![deny(missing_docs)]
#![deny(unsafe_code)]

mod names;

pub mod check;
mod error;
pub mod geometry;
pub mod lab;
pub mod measure;
pub mod output;
pub mod raster;
pub mod teaching;

pub use error::{Error, Result};
pub use geometry::mesh::Mesh;
pub use geometry::pipeline::{Geometry, PipelineOptions, Viewport};
pub use geometry::polygon::Polygon;
pub use geometry::render::{MeshRenderer, RenderSettings};
pub use geometry::scene::Scene2D;
pub use measure::render_request::{RenderInput, RenderReport, RenderRequest};
pub use raster::backend::{
    backend, line_backend, line_backends, triangle_backend, triangle_backends, Backend,
};
pub use raster::edge::{FillRule, PixelRect, TriangleSetup};
pub use raster::fixed::{Fixed, FixedPoint};
pub use raster::fragment::{FragmentSink, LineFragment, TriangleFragment, WorkCounters};
pub use raster::line::{LineOptions, LineRasterizer, LineSetup};
pub use raster::primitive::ShadedVertex;
pub use raster::shader::FragmentShader;
pub use raster::stage::FragmentStage;
pub use raster::target::RenderTarget;
pub use raster::triangle::{TriangleRasterizer, TriangleSelection};
