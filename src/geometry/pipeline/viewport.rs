//! The perspective divide and the viewport transform (the course's step 3,
//! after clipping): clip space to normalised device coordinates to pixels,
//! snapped to the fixed-point grid.

use super::clip::ClipVertex;
use crate::error::{Error, Result};
use crate::raster::fixed::{Fixed, FixedPoint};
use crate::raster::primitive::ShadedVertex;

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
    #[inline]
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

/// Divides by `w`, maps to the viewport and snaps a clip-space vertex.
#[inline(always)]
pub(super) fn to_screen_vertex(
    viewport: &Viewport,
    v: &ClipVertex,
) -> Result<(FixedPoint, ShadedVertex)> {
    let (point, depth, inv_w) = viewport.to_screen(v.position)?;
    Ok((
        point,
        ShadedVertex {
            depth,
            inv_w,
            varyings: v.varyings,
        },
    ))
}
