//! The core: everything a pixel goes through, from snapped vertices to the
//! colour and depth buffers.
//!
//! * snapping to 1/256 pixel and the guard band: [`FixedPoint`],
//!   [`SUBPIXEL_SCALE`], [`GUARD_BAND`];
//! * the course's implicit line equation as exact `i64` edge functions
//!   ([`EdgeFunction`]), the fill rules that break ties ([`FillRule`]:
//!   top-left, bottom-right, off-screen point, inclusive, exclusive) and
//!   triangle set-up ([`TriangleSetup`]); the same edge functions in 32
//!   bits for small triangles ([`SmallTriangle`], [`MAX_SPAN`]);
//! * the back-ends, one module each: [`triangle`] (with the
//!   [`TriangleRasterizer`](triangle::TriangleRasterizer) trait) and
//!   [`line`](mod@line) (with [`LineRasterizer`](line::LineRasterizer) and
//!   the line options), and [`polygon`] (polygons filled directly, by
//!   the edge table, under a [`WindingRule`](polygon::WindingRule));
//! * what a back-end is, as data ([`Descriptor`]: name, walk, role, cost
//!   class), the one work budget ([`WorkBudget`]), and the registry by
//!   name and by role ([`triangle_backends`], [`line_backends`],
//!   [`backend`]);
//! * multisampling: a triangle's coverage mask at the standard sample
//!   patterns of Direct3D and Vulkan ([`SamplePattern`], [`masks_of`],
//!   checked against [`reference_masks`]); supersampling on a regular
//!   `k x k` grid ([`supersample()`]); and the exact area each triangle
//!   covers in each pixel ([`area_coverage`]), which anti-aliasing
//!   approximates; the multisampled stage, with a depth and a colour per
//!   sample and a resolve ([`draw_multisampled`], [`MultisampleTarget`]);
//! * fragments and the [`FragmentSink`] they go into, with
//!   [`WorkCounters`];
//! * what the stage reads of a draw ([`ShadedVertex`], [`ShadedTriangle`],
//!   [`Varyings`]), the shared fragment stage ([`FragmentStage`]: depth
//!   test, interpolation, shading, writes), fragment shaders
//!   ([`FragmentShader`], [`Flat`], [`Gouraud`], [`Textured`]...) and the
//!   colour, depth and coverage buffers ([`RenderTarget`]);
//! * textures ([`texture`]): wrap modes, nearest and bilinear filters, the
//!   mip pyramid, the level of detail and anisotropic filtering
//!   ([`Texture`], [`Sampler`]).
//!
//! Nothing here depends on the rest of the crate: geometry input,
//! teaching and measurement are built on this.
//!
//! ```
//! use rasterlab::raster::{triangle_backends, FillRule, FixedPoint, FragmentList, PixelRect, TriangleSetup};
//!
//! // One triangle, snapped to 1/256 pixel and set up for the top-left rule,
//! // drawn by every triangle back-end: the same fragments from each.
//! let v = [(0.5, 0.5), (6.0, 1.0), (2.0, 5.5)].map(|(x, y)| FixedPoint::snap_f64(x, y).unwrap());
//! let setup = TriangleSetup::new(0, v, FillRule::TopLeft).unwrap();
//! let mut reference = FragmentList::default();
//! triangle_backends()[0].rasterize(&[setup], PixelRect::of_target(8, 8), &mut reference);
//! for b in triangle_backends() {
//!     let mut list = FragmentList::default();
//!     b.rasterize(&[setup], PixelRect::of_target(8, 8), &mut list);
//!     assert_eq!(list.triangles, reference.triangles, "{}", b.name());
//! }
//! ```

pub(crate) mod area;
pub(crate) mod compact;
pub(crate) mod derivatives;
pub(crate) mod descriptor;
pub(crate) mod edge;
pub(crate) mod fixed;
pub(crate) mod fragment;
pub mod line;
pub(crate) mod multisample;
pub(crate) mod multisample_stage;
pub mod polygon;
pub(crate) mod primitive;
pub(crate) mod registry;
pub(crate) mod shader;
pub(crate) mod srgb;
pub(crate) mod stage;
pub(crate) mod supersample;
pub(crate) mod target;
pub mod texture;
pub mod triangle;
pub(crate) mod vector;

pub use area::{area_coverage, AreaFragment};
pub use compact::{SmallTriangle, MAX_SPAN};
pub use derivatives::{
    count_quad_helpers, quad_helper_pixels, quad_helpers, Derivatives, Gradient, UvPlanes,
};
pub use descriptor::{within_budget, CostClass, Descriptor, Role, WorkBudget};
pub use edge::{
    EdgeFunction, EdgeKind, FillRule, PixelRect, TriangleSetup, OFFSCREEN_POINT,
    SECONDARY_OFFSCREEN_POINT,
};
pub use fixed::{Fixed, FixedPoint, GUARD_BAND, SUBPIXEL_SCALE};
pub use fragment::{
    FragmentList, FragmentSink, LineFragment, TriangleFragment, TriangleSpan, WorkCounters,
};
pub use multisample::{masks_of, reference_masks, MaskFragment, SamplePattern, SAMPLE_COUNTS};
pub use multisample_stage::{draw_multisampled, MultisampleTarget, MAX_TARGET_SAMPLES};
pub use primitive::{DepthPlane, ShadedLine, ShadedTriangle, ShadedVertex, TriangleData, Varyings};
pub use registry::{
    backend, default_line_backend, default_triangle_backend, fallback_triangle_backend,
    line_backend, line_backends, polygon_backend, polygon_backends, reference_triangle_backend,
    reference_triangle_backend_within, triangle_backend, triangle_backends, Backend,
};
pub use shader::{
    to_rgba8, ColorLanes, Constant, Diffuse, DirectionalLight, Flat, FragmentInput, FragmentLanes,
    FragmentShader, Gouraud, Mipmapped, Textured, LANES,
};
pub use srgb::{linear_to_srgb8, srgb8_to_linear, MixSpace};
pub use stage::{Blend, BlendMode, FragmentStage, Interpolation, WriteMask};
pub use supersample::{supersample, SampleCount};
pub use target::{Clear, DepthState, DepthTest, RenderTarget, TargetRows, MAX_TARGET_SIDE};
pub use texture::{
    Anisotropic, Ellipse, Filter, Footprint, Image, LevelMode, Sampler, Texture, Wrap,
    MAX_ANISOTROPY, MAX_TEXTURE_SIDE, MAX_TEXTURE_TEXELS,
};
// What only the `rasterlab` program uses; absent without the `cli` feature.
#[cfg(feature = "cli")]
pub use self::registry::{all_backends, BackendInfo, BackendKind};
