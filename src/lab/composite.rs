//! The lab's compositing view: the triangles filled with their palette
//! colours at one opacity and merged by a blend mode through the shared
//! stage, as `render --blend` draws them, so that a student sees `over`
//! change with the order, the opacity and the space colours are mixed in.

use super::LabRequest;
use crate::error::{Error, Result};
use crate::geometry::scene::Scene2D;
use crate::raster::edge::FillRule;
use crate::raster::primitive::ShadedVertex;
use crate::raster::registry::default_triangle_backend;
use crate::raster::shader::Flat;
use crate::raster::srgb::MixSpace;
use crate::raster::stage::{Blend, BlendMode};
use crate::raster::target::{DepthState, RenderTarget};
use crate::teaching::palette::triangle_colour;
use glam::Vec4;
use serde::Serialize;

/// The opacity of every triangle when the request gives none.
pub const DEFAULT_OPACITY: f64 = 0.5;

/// The composited image of the request's triangles.
#[derive(Clone, Debug, Serialize)]
pub struct CompositeView {
    /// The blend mode's name.
    pub blend: String,
    /// Where colours were mixed: `linear` or `srgb`.
    pub mix_in: String,
    /// Every triangle's opacity.
    pub opacity: f64,
    /// Whether the triangles were sorted back to front first.
    pub sorted: bool,
    /// The order the triangles were drawn in, by their index in the
    /// request.
    pub order: Vec<usize>,
    /// Each pixel's RGBA8 colour (sRGB-encoded), row by row, over a black
    /// target.
    pub pixels: Vec<[u8; 4]>,
    /// What the view shows, in the course's words.
    pub caption: String,
}

/// Checks the request's compositing fields: a known blend mode and
/// space, an opacity in `[0, 1]`.
pub(super) fn check(request: &LabRequest) -> Result<()> {
    if let Some(mode) = &request.blend {
        BlendMode::from_name(mode).map_err(Error::InvalidArgument)?;
    }
    if let Some(space) = &request.mix_in {
        MixSpace::from_name(space).map_err(Error::InvalidArgument)?;
    }
    if let Some(opacity) = request.opacity {
        if !(0.0..=1.0).contains(&opacity) {
            return Err(Error::InvalidArgument(format!(
                "opacity {opacity} is outside [0, 1]"
            )));
        }
    }
    Ok(())
}

impl CompositeView {
    /// The view of `request`'s triangles, when it names a blend mode
    /// (triangles only). Triangles with depths are drawn with the depth
    /// test, the others without.
    pub(super) fn of(request: &LabRequest, rule: FillRule) -> Result<Option<CompositeView>> {
        let Some(mode) = &request.blend else {
            return Ok(None);
        };
        if request.kind != "triangles" {
            return Ok(None);
        }
        let mode = BlendMode::from_name(mode).map_err(Error::InvalidArgument)?;
        let space = match &request.mix_in {
            Some(name) => MixSpace::from_name(name).map_err(Error::InvalidArgument)?,
            None => MixSpace::Linear,
        };
        let opacity = request.opacity.unwrap_or(DEFAULT_OPACITY);
        let snapped = request.case().snapped_triangles();
        let vertices = (0..snapped.len())
            .map(|i| {
                let [r, g, b] = triangle_colour(i).map(|c| f32::from(c) / 255.0);
                let depth = request.depths.get(i).map_or(0.0, |z| *z as f32);
                [ShadedVertex::flat(depth, Vec4::new(r, g, b, opacity as f32)); 3]
            })
            .collect();
        let scene = Scene2D {
            width: request.width,
            height: request.height,
            triangles: snapped,
            vertices,
        };
        let order: Vec<usize> = if request.sort {
            scene.back_to_front_order()
        } else {
            (0..scene.triangles.len()).collect()
        };
        let scene = scene.reordered(&order);
        let depth = if request.depths.is_empty() {
            DepthState::OFF
        } else {
            DepthState::DEFAULT
        };
        let blend = Blend {
            mode,
            mix_in: space,
            ..Blend::REPLACE
        };
        let mut target = RenderTarget::new(request.width, request.height)?;
        scene.draw_blended(
            default_triangle_backend(),
            rule,
            (depth, blend),
            &Flat,
            &mut target,
        );
        let caption = format!(
            "composited: each triangle in its outline's colour at opacity {opacity}, merged by {} in {}, drawn {} over black{}",
            mode.name(),
            match space {
                MixSpace::Linear => "linear light",
                MixSpace::Encoded => "the sRGB-encoded values",
            },
            if request.sort { "back to front" } else { "in order" },
            if depth.is_off() { "" } else { ", with the depth test" },
        );
        Ok(Some(CompositeView {
            blend: mode.name().to_string(),
            mix_in: space.name().to_string(),
            opacity,
            sorted: request.sort,
            order,
            pixels: target.color,
            caption,
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn request(extra: &str) -> LabRequest {
        LabRequest::parse(&format!(
            r#"{{"width": 8, "height": 8, "kind": "triangles",
                "triangles": [[[0, 0], [8, 0], [0, 8]], [[8, 0], [8, 8], [0, 8]], [[0, 0], [8, 0], [8, 8]]]{extra}}}"#
        ))
        .unwrap()
    }

    /// Straight `over` of the first two triangles at opacity 1/2 over
    /// black, in linear light: where only the first lies, half its light;
    /// the order changes the pixel both cover.
    #[test]
    fn over_composites_the_triangles_in_order() {
        let view = CompositeView::of(&request(r#", "blend": "over-straight""#), FillRule::TopLeft)
            .unwrap()
            .unwrap();
        // Pixel (1, 5) is in the first triangle only.
        let [r, g, b] = triangle_colour(0);
        let half = |c: u8| crate::raster::linear_to_srgb8(0.5 * crate::raster::srgb8_to_linear(c));
        assert_eq!(view.pixels[5 * 8 + 1], [half(r), half(g), half(b), 255]);
        let sorted = CompositeView::of(
            &request(r#", "blend": "over-straight", "depths": [0.2, 0.5, 0.8], "sort": true"#),
            FillRule::TopLeft,
        )
        .unwrap()
        .unwrap();
        assert_eq!(sorted.order, [2, 1, 0]);
        assert!(view.caption.contains("linear light"));
        assert!(CompositeView::of(&request(""), FillRule::TopLeft)
            .unwrap()
            .is_none());
    }

    /// Unknown modes and spaces, and opacities outside [0, 1], are
    /// refused with a message.
    #[test]
    fn bad_compositing_fields_are_refused() {
        let base = r#"{"width": 8, "height": 8, "kind": "triangles""#;
        for (extra, says) in [
            (r#", "blend": "screen"}"#, "unknown blend mode"),
            (
                r#", "blend": "over", "mix_in": "cmyk"}"#,
                "unknown colour space",
            ),
            (r#", "blend": "over", "opacity": 1.5}"#, "outside [0, 1]"),
        ] {
            let error = LabRequest::parse(&format!("{base}{extra}"))
                .unwrap_err()
                .to_string();
            assert!(error.contains(says), "{error}");
        }
    }
}
