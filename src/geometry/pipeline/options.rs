//! The pipeline's choices: the fill rule of the set-up, back-face culling
//! and which winding faces the viewer.

use crate::raster::edge::FillRule;

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

crate::names::named_enum!(
    CullMode,
    "cull mode",
    None = "none",
    Back = "back",
    Front = "front"
);
crate::names::named_enum!(
    FrontFace,
    "front face",
    CounterClockwise = "ccw",
    Clockwise = "cw"
);

/// Which side planes clipping cuts triangles at (the near and far
/// planes and `w > 0` are always clipped).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum ClipPlanes {
    /// The guard band, far outside the viewport: only triangles reaching
    /// thousands of pixels off screen are cut, and the rasterizer's
    /// bounding box, clamped to the viewport, does the rest.
    #[default]
    GuardBand,
    /// The viewport's own sides, `|x| <= w` and `|y| <= w`: every
    /// triangle crossing a side of the screen is cut there, its new
    /// vertices snapped like any other.
    Viewport,
}

crate::names::named_enum!(
    ClipPlanes,
    "clip planes",
    GuardBand = "guard-band",
    Viewport = "viewport"
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
    /// Keep every triangle that may cover a sample of a multisample
    /// pattern (any point of its pixels), not only a pixel centre: the
    /// set-up for [`draw_multisampled`](crate::raster::draw_multisampled).
    /// Triangles are then dropped only when their box, one pixel wider
    /// each way, misses the viewport.
    pub multisample: bool,
    /// The side planes triangles are clipped at.
    pub clip: ClipPlanes,
}
