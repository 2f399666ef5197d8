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
//! Beside them, at the root: [`Error`] and [`Result`], and the file
//! writers every command uses ([`check_file`], [`check_dir`] before the
//! work, [`write_file`] and [`write_png`] to write whole files); inside
//! the crate, the one writer every SVG picture and HTML page goes
//! through (one escaping of text for all of them).
//!
//! Every public name has one path: its room's (`rasterlab::raster::FillRule`,
//! `rasterlab::check::Property`). The modules inside a room are private,
//! except the algorithms' own: each back-end's module under
//! [`raster::triangle`] and [`raster::line`](mod@raster::line) is a page
//! of the course. [`prelude`] re-exports the names most uses need.
//!
//! ## Where to start
//!
//! * **Studying an algorithm**: its module under [`raster::triangle`] or
//!   [`raster::line`](mod@raster::line) explains it in the course's terms;
//!   [`teaching::trace_triangle`] and [`teaching::trace_line`] print each
//!   step; [`teaching::GridPicture`] draws the pixel grid.
//!   [`geometry::Scene2D`] holds the course's examples (the depth-buffer
//!   example, the blue triangle).
//! * **Checking a rasterizer**: [`check`] runs generated cases against the
//!   rules and shrinks a failure; wrap yours as a [`check::Subject`] (or a
//!   closure), or run `rasterlab check --exec` on a program in any language.
//! * **Comparing performance**: [`measure::TriangleWorkload`] prepares the
//!   inputs, [`measure::run`] times every back-end; meshes are drawn by
//!   [`geometry::MeshRenderer`].
//! * **Adding a back-end**: implement
//!   [`TriangleAlgorithm`](raster::triangle::TriangleAlgorithm) (or
//!   [`AliasedLine`](raster::line::AliasedLine)) in a file of its own under `raster/triangle/`
//!   (or `raster/line/`), declare it in that folder's `mod.rs` with one `pub mod` line, and
//!   list it in the registry, `raster/registry.rs` ([`raster::triangle_backends`]);
//!   every command, check, report,
//!   benchmark, trace and test picks it up from there.
//!
//! ```
//! use rasterlab::geometry::Scene2D;
//! use rasterlab::raster::{triangle_backends, FillRule, Flat};
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
#![warn(unnameable_types)]

mod names;

pub mod check;
mod error;
pub mod geometry;
pub mod lab;
pub(crate) mod markup;
pub mod measure;
mod output;
pub mod raster;
pub mod teaching;
#[cfg(test)]
mod test_support;

pub use error::{Error, Result};
pub use output::{check_dir, check_file, write_file, write_png};

/// The names most uses need, for `use rasterlab::prelude::*;`.
///
/// Each is its room's name, re-exported: `prelude::FillRule` is
/// [`raster::FillRule`], documented there.
pub mod prelude {
    pub use crate::geometry::{
        process_triangles, Geometry, Mesh, MeshRenderer, PipelineOptions, Polygon, RenderSettings,
        Scene2D, Viewport,
    };
    pub use crate::raster::line::{LineOptions, LineRasterizer, LineSetup};
    pub use crate::raster::triangle::{TriangleRasterizer, TriangleSelection};
    pub use crate::raster::{
        backend, line_backend, line_backends, triangle_backend, triangle_backends, Backend,
        FillRule, FixedPoint, FragmentShader, FragmentSink, FragmentStage, PixelRect, RenderTarget,
        TriangleSetup,
    };
    pub use crate::{Error, Result};
}
