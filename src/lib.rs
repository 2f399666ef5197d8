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
//! * [`fixed`]: snapping to 1/256 pixel and the guard band;
//! * [`edge`]: the course's implicit line equation as exact `i64` edge
//!   functions, fill rules (top-left, bottom-right, off-screen point,
//!   inclusive, exclusive) and triangle set-up;
//! * [`triangle`]: the triangle back-ends, one file each;
//! * [`fragment`]: fragments, the [`FragmentSink`](fragment::FragmentSink)
//!   they go into, work counters;
//! * [`stage`] and [`shader`]: the shared fragment stage and its shaders;
//! * [`target`]: colour, depth and coverage buffers;
//! * [`backend`]: the registry of back-ends by name;
//! * [`line`](mod@line): the line back-ends, one file each, and their options;
//! * [`polygon`]: simple polygons and their spade triangulation;
//! * [`input`] and [`scene`]: text inputs and small 2D scenes;
//! * [`mesh`]: PLY and OBJ meshes;
//! * [`pipeline`]: vertex shaders, assembly, clipping, divide, culling,
//!   viewport (the course's five steps for 3D input);
//! * [`render`]: a mesh rendered end to end (camera, shading, wireframe);
//! * [`trace`]: step-by-step traces of the algorithms for teaching;
//! * [`grid_picture`]: zoomed pictures of the pixel grid (tested, emitted)
//!   and fill-rule heat maps;
//! * [`report`]: the side-by-side HTML comparison of every back-end;
//! * [`output`]: output files checked before the work and written whole;
//! * [`lab`]: the interactive lab's requests, answers and server;
//! * [`check`]: check any rasterizer (a back-end, a closure, another
//!   program) against the rules, with shrunk counterexamples.
//!
//! ```
//! use rasterlab::{backend, edge::FillRule, scene::Scene2D, shader::Flat};
//!
//! // The rasterization slides' depth-buffer example, drawn by every triangle back-end.
//! let scene = Scene2D::depth_example(true);
//! let reference = scene.render(backend::triangle_backends()[0], FillRule::TopLeft, &Flat).unwrap().0;
//! for b in backend::triangle_backends() {
//!     let (image, _work) = scene.render(*b, FillRule::TopLeft, &Flat).unwrap();
//!     assert_eq!(image, reference, "{} differs", b.name());
//! }
//! ```

#![deny(missing_docs)]
#![forbid(unsafe_code)]

pub mod backend;
pub mod benchmark;
pub mod binning;
pub mod check;
pub mod edge;
pub mod error;
pub mod fixed;
pub mod fragment;
pub mod grid_picture;
pub mod input;
pub mod lab;
pub mod line;
pub mod mesh;
pub mod output;
pub mod pipeline;
pub mod polygon;
pub mod render;
pub mod report;
pub mod scene;
pub mod shader;
pub mod stage;
pub mod target;
pub mod trace;
pub mod triangle;
pub mod workload;

pub use error::{Error, Result};
