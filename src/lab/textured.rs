//! The lab's textured view: the request's triangles drawn through the
//! shared stage with a mipmapped checkerboard, as `render --scene floor`
//! samples it, so that a student drags a vertex and sees the level of
//! detail follow. Each vertex carries a texture coordinate (the first at
//! `(0, 0)`, the second at `(r, 0)`, the third at `(0, r)`, `r` the
//! request's repeats) and a `w`, which tilts the triangle away from the
//! viewer: with every `w` at 1 it lies flat on the screen, its
//! derivatives are the same at every pixel, and one level is read all
//! over; with the third vertex far (`w` > 1) the texture recedes towards
//! it, perspective-correct, and the levels change across it, as on the
//! receding floor.
//!
//! Per pixel the view gives what `explain --backend texture` traces: the
//! texture coordinate, its screen-space derivatives by the chosen method
//! (analytic, 2x2 quads, or CS184's forward differences), `rho` and
//! `lambda` (OpenGL 3.3, section 3.8.11), the levels read and their
//! weights (Williams 1983). Under quad derivatives it lists the helper
//! pixels: the pixels of each touched 2x2 quad outside the triangle,
//! shaded for their differences and never written.

use super::LabRequest;
use crate::error::{Error, Result};
use crate::geometry::scene::Scene2D;
use crate::raster::derivatives::{
    each_triangle_pixels, quad_helper_pixels, quad_helpers, Derivatives, UvPlanes,
};
use crate::raster::edge::{FillRule, PixelRect};
use crate::raster::primitive::{ShadedVertex, TriangleData, Varyings};
use crate::raster::registry::default_triangle_backend;
use crate::raster::shader::Mipmapped;
use crate::raster::target::{DepthState, RenderTarget};
use crate::raster::texture::{Anisotropic, Filter, Footprint, LevelMode, Sampler, Texture};
use crate::teaching::palette::{LegendEntry, Mark, Role, LEVEL_COLOURS};
use glam::{Vec2, Vec4};
use serde::{Deserialize, Serialize};

/// Squares along each side of the checkerboard.
const SQUARES: u32 = 8;
/// Texels along each side of one square: a 64x64 texture, whose pyramid
/// has seven levels.
const SQUARE_TEXELS: u32 = 8;
/// The repeats when the request gives none: the texture once across the
/// triangle's legs.
const DEFAULT_REPEATS: f64 = 1.0;
/// The most repeats: 64 textures across a leg of a 128-pixel grid is
/// already 32 texels a pixel, past the last level.
const MAX_REPEATS: f64 = 64.0;
/// The farthest a vertex may be: `w` from 1 to this.
const MAX_W: f64 = 64.0;

/// The texture controls of a request: the sampler and derivative method
/// by the names `render` takes.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct TextureControls {
    /// The pixel filter: `nearest` or `bilinear`.
    pub filter: String,
    /// The level mode: `zero`, `nearest` or `linear` (with `bilinear`,
    /// trilinear).
    pub levels: String,
    /// The derivative method: `analytic`, `quad` or `forward`.
    pub derivatives: String,
    /// The most anisotropy, 1 (isotropic, the default) to 16.
    #[serde(default)]
    pub anisotropy: Option<u32>,
    /// The anisotropic filter: `probes` (the default) or `ewa`.
    #[serde(default)]
    pub anisotropic: Option<String>,
    /// How many times the texture repeats along each leg (default 1).
    #[serde(default)]
    pub repeats: Option<f64>,
    /// Each triangle's three `w`, 1 to 64 (default all 1: flat on the
    /// screen).
    #[serde(default)]
    pub w: Vec<[f64; 3]>,
}

impl TextureControls {
    /// The sampler and derivative method the controls name, or an error
    /// naming the one that is not known or out of range.
    fn sampler(&self) -> Result<(Sampler, Derivatives)> {
        let sampler = Sampler {
            filter: self.filter.parse::<Filter>()?,
            levels: self.levels.parse::<LevelMode>()?,
            anisotropy: self.anisotropy.unwrap_or(1),
            anisotropic: match &self.anisotropic {
                Some(name) => name.parse::<Anisotropic>()?,
                None => Anisotropic::Probes,
            },
            ..Sampler::default()
        };
        sampler.check()?;
        Ok((sampler, self.derivatives.parse::<Derivatives>()?))
    }
}

/// Checks the request's texture controls: known names, an anisotropy of
/// 1 to 16, repeats in (0, 64], one `[w0, w1, w2]` per triangle or none,
/// each `w` in [1, 64].
pub(super) fn check(request: &LabRequest) -> Result<()> {
    let Some(controls) = &request.texture else {
        return Ok(());
    };
    let bad = |m: String| Err(Error::InvalidArgument(m));
    controls.sampler()?;
    if let Some(r) = controls.repeats {
        if !(r > 0.0 && r <= MAX_REPEATS) {
            return bad(format!("repeats {r} is outside (0, {MAX_REPEATS}]"));
        }
    }
    if !controls.w.is_empty() && controls.w.len() != request.triangles.len() {
        return bad("give three w per triangle, or none".into());
    }
    if let Some(w) = controls
        .w
        .iter()
        .flatten()
        .find(|w| !(1.0..=MAX_W).contains(*w))
    {
        return bad(format!("w {w} is outside [1, {MAX_W}]"));
    }
    Ok(())
}

/// One drawn pixel's texture lookup, as the trace gives it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Lookup {
    /// The pixel, `[x, y]`.
    pub pixel: [u32; 2],
    /// The triangle whose fragment the pixel stores (from 0).
    pub triangle: usize,
    /// The texture coordinate at the pixel centre.
    pub uv: [f32; 2],
    /// `(du/dx, dv/dx)` in texels of level 0.
    pub dx: [f32; 2],
    /// `(du/dy, dv/dy)` in texels of level 0.
    pub dy: [f32; 2],
    /// The longer derivative's length, in texels.
    pub rho: f32,
    /// The level of detail the levels are chosen by: `log2(rho)`, or
    /// with anisotropic probes `log2(rho_max / N)`; not yet clamped.
    pub lambda: f32,
    /// The anisotropic probes taken (1: isotropic).
    pub probes: u32,
    /// The finer level read.
    pub fine: usize,
    /// The coarser level read (`fine` when one level is read).
    pub coarse: usize,
    /// The coarser level's weight.
    pub weight: f32,
}

/// The textured image of the request's triangles, and each pixel's
/// lookup.
#[derive(Clone, Debug, Serialize)]
pub struct TexturedView {
    /// The sampler in words: filter, level mode, derivatives, anisotropy.
    pub sampler: String,
    /// The texture's side in texels and its levels.
    pub texture: [u32; 3],
    /// Each pixel's RGBA8 colour (sRGB-encoded), row by row, over black.
    pub pixels: Vec<[u8; 4]>,
    /// The lookup of every pixel drawn, row by row.
    pub lookups: Vec<Lookup>,
    /// Under quad derivatives: each triangle's helper pixels on the grid,
    /// `[x, y, triangle]`.
    pub helpers: Vec<[u32; 3]>,
    /// The helper pixels of every triangle, those off the grid too (the
    /// count the work counters report).
    pub helper_count: u64,
    /// The colour of each level in the level map, from level 0; coarser
    /// levels share the last.
    pub level_colours: Vec<[u8; 3]>,
    /// What the view shows, in the course's words.
    pub caption: String,
}

impl TexturedView {
    /// The level map's legend entries: a swatch per level read, and the
    /// helper pixels' cross when there are any.
    pub fn legend_entries(&self) -> Vec<LegendEntry> {
        let last = LEVEL_COLOURS.len() - 1;
        let mut levels: Vec<usize> = self.lookups.iter().map(|l| l.fine.min(last)).collect();
        levels.sort_unstable();
        levels.dedup();
        let mut entries: Vec<LegendEntry> = levels
            .into_iter()
            .map(|l| LegendEntry {
                key: format!("level-{l}"),
                rgb: LEVEL_COLOURS[l],
                mark: Mark::Fill,
                label: if l == last {
                    format!("level map: level {l} and coarser")
                } else {
                    format!("level map: level {l} (the finer level read)")
                },
            })
            .collect();
        if !self.helpers.is_empty() {
            entries.push(LegendEntry {
                key: "helper".into(),
                rgb: Role::Geometry.rgb(),
                mark: Mark::Cross,
                label: "helper pixel: shaded for its 2x2 quad's differences, never written".into(),
            });
        }
        entries
    }

    /// The view of `request`'s triangles, when it gives texture controls
    /// (triangles only).
    pub(super) fn of(request: &LabRequest, rule: FillRule) -> Result<Option<TexturedView>> {
        let Some(controls) = &request.texture else {
            return Ok(None);
        };
        if request.kind != "triangles" {
            return Ok(None);
        }
        let (sampler, method) = controls.sampler()?;
        let r = controls.repeats.unwrap_or(DEFAULT_REPEATS) as f32;
        let uvs = [Vec2::ZERO, Vec2::new(r, 0.0), Vec2::new(0.0, r)];
        let snapped = request.case().snapped_triangles();
        let vertices: Vec<[ShadedVertex; 3]> = (0..snapped.len())
            .map(|i| {
                let w = controls.w.get(i).copied().unwrap_or([1.0; 3]);
                std::array::from_fn(|k| ShadedVertex {
                    depth: 0.0,
                    inv_w: (1.0 / w[k]) as f32,
                    varyings: Varyings {
                        uv: uvs[k],
                        ..Varyings::color(Vec4::ONE)
                    },
                })
            })
            .collect();
        let scene = Scene2D {
            width: request.width,
            height: request.height,
            triangles: snapped,
            vertices,
        };
        let texture = Texture::checkerboard(SQUARES, SQUARE_TEXELS, Vec4::ONE, Vec4::splat(0.0));
        let (tw, th, count) = (texture.width(), texture.height(), texture.levels().len());
        let setups = scene.setups(rule);
        let data = TriangleData::of_triangles(&setups, &scene.vertices);
        let shader = Mipmapped::new(texture, sampler, method, &setups, &data, true);
        let backend = default_triangle_backend();
        let mut target = RenderTarget::new(request.width, request.height)?;
        scene.draw(backend, rule, DepthState::OFF, &shader, &mut target);

        // Each pixel's lookup, by the triangle drawn last there (as the
        // stage stores it, with no depth test), and the helper pixels.
        let rect = PixelRect::of_target(request.width, request.height);
        let (w, h) = (request.width as usize, request.height as usize);
        let mut by_pixel: Vec<Option<Lookup>> = vec![None; w * h];
        let (mut helpers, mut helper_count) = (Vec::new(), 0);
        each_triangle_pixels(&setups, backend, rect, |setup, pixels| {
            let t = setup.id as usize;
            let planes = UvPlanes::new(setup, scene.vertices[t], true);
            for &(x, y) in pixels {
                let (ix, iy) = (i64::from(x), i64::from(y));
                let g = planes.derivatives(method, ix, iy);
                let uv = planes.uv_at(ix, iy).unwrap_or_default().as_vec2();
                let footprint = Footprint::new(g.dx, g.dy, tw, th);
                let probes = footprint.probes(sampler.anisotropy);
                let choice = sampler.levels.choose(probes.lambda, count);
                by_pixel[y as usize * w + x as usize] = Some(Lookup {
                    pixel: [x, y],
                    triangle: t,
                    uv: uv.to_array(),
                    dx: footprint.dx.to_array(),
                    dy: footprint.dy.to_array(),
                    rho: footprint.rho(),
                    lambda: probes.lambda,
                    probes: probes.count,
                    fine: choice.fine,
                    coarse: choice.coarse,
                    weight: choice.weight,
                });
            }
            if method == Derivatives::Quad {
                helper_count += quad_helpers(pixels.iter().copied());
                helpers.extend(
                    quad_helper_pixels(pixels)
                        .into_iter()
                        .filter(|&(x, y)| x < request.width && y < request.height)
                        .map(|(x, y)| [x, y, t as u32]),
                );
            }
        });
        let words = |s: String| s.replace('-', " ");
        let mut described = format!(
            "{} filter, {} levels{}, {} derivatives",
            sampler.filter,
            sampler.levels,
            match (sampler.filter, sampler.levels) {
                (Filter::Bilinear, LevelMode::Linear) => " (trilinear)",
                _ => "",
            },
            method
        );
        if sampler.anisotropy > 1 {
            described.push_str(&format!(
                ", anisotropic up to {}x by {}",
                sampler.anisotropy,
                words(sampler.anisotropic.to_string())
            ));
        }
        let caption = format!(
            "textured: a {tw}x{th} checkerboard ({count} levels), {described}; \
             uv (0, 0), ({r}, 0), (0, {r}) at the vertices, perspective-correct{}",
            if method == Derivatives::Quad {
                format!("; {helper_count} helper pixel(s) shaded for the quads, never written")
            } else {
                String::new()
            }
        );
        Ok(Some(TexturedView {
            sampler: described,
            texture: [tw, th, count as u32],
            pixels: target.color,
            lookups: by_pixel.into_iter().flatten().collect(),
            helpers,
            helper_count,
            level_colours: LEVEL_COLOURS.to_vec(),
            caption,
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn request(texture: &str) -> LabRequest {
        LabRequest::parse(&format!(
            r#"{{"width": 32, "height": 32, "kind": "triangles",
                "triangles": [[[0, 0], [32, 0], [0, 32]]], "texture": {texture}}}"#
        ))
        .unwrap()
    }

    /// Flat on the screen, a 64-texel texture across a 32-pixel leg is
    /// two texels a pixel: lambda 1 at every pixel, under every method
    /// (Scotty3D's task-6 range for two texels a pixel, [0.5, 1.5]),
    /// and a quad's helper pixels are exactly the quads' pixels outside
    /// the triangle along its long edge.
    #[test]
    fn two_texels_a_pixel_is_level_one_everywhere() {
        for method in ["analytic", "quad", "forward"] {
            let view = TexturedView::of(
                &request(&format!(
                    r#"{{"filter": "bilinear", "levels": "nearest", "derivatives": "{method}"}}"#
                )),
                FillRule::TopLeft,
            )
            .unwrap()
            .unwrap();
            assert_eq!(view.texture, [64, 64, 7]);
            assert!(!view.lookups.is_empty());
            for l in &view.lookups {
                assert!((l.lambda - 1.0).abs() < 1e-4, "{method}: {l:?}");
                assert_eq!((l.fine, l.coarse), (1, 1), "{method}: {l:?}");
            }
            let keys: Vec<String> = view.legend_entries().into_iter().map(|e| e.key).collect();
            assert!(keys.contains(&"level-1".to_string()), "{keys:?}");
            assert_eq!(keys.contains(&"helper".to_string()), method == "quad");
            if method == "quad" {
                assert!(view.helper_count > 0);
                assert_eq!(view.helpers.len() as u64, view.helper_count);
                assert!(view.caption.contains("helper pixel"));
            } else {
                assert!(view.helpers.is_empty());
            }
        }
    }

    /// With the third vertex four times as far, lambda grows towards it:
    /// more levels are read, and trilinear blends two of them.
    #[test]
    fn a_far_vertex_makes_the_levels_change_across_the_triangle() {
        let view = TexturedView::of(
            &request(
                r#"{"filter": "bilinear", "levels": "linear", "derivatives": "analytic", "w": [[1, 1, 4]]}"#,
            ),
            FillRule::TopLeft,
        )
        .unwrap()
        .unwrap();
        let near = view.lookups.iter().find(|l| l.pixel == [1, 1]).unwrap();
        let far = view.lookups.iter().find(|l| l.pixel == [1, 28]).unwrap();
        assert!(far.lambda > near.lambda + 1.0, "{near:?} {far:?}");
        assert!(view
            .lookups
            .iter()
            .any(|l| l.coarse == l.fine + 1 && l.weight > 0.0));
        assert!(view.caption.contains("trilinear"));
    }

    /// Unknown names, an anisotropy past 16, EWA without mip levels,
    /// repeats and w out of range are refused with a message.
    #[test]
    fn bad_texture_controls_are_refused() {
        let base = r#"{"width": 8, "height": 8, "kind": "triangles", "triangles": [[[0, 0], [8, 0], [0, 8]]], "texture": "#;
        for (texture, says) in [
            (
                r#"{"filter": "cubic", "levels": "zero", "derivatives": "quad"}"#,
                "cubic",
            ),
            (
                r#"{"filter": "nearest", "levels": "all", "derivatives": "quad"}"#,
                "all",
            ),
            (
                r#"{"filter": "nearest", "levels": "zero", "derivatives": "backward"}"#,
                "backward",
            ),
            (
                r#"{"filter": "nearest", "levels": "linear", "derivatives": "quad", "anisotropy": 32}"#,
                "anisotropy",
            ),
            (
                r#"{"filter": "nearest", "levels": "zero", "derivatives": "quad", "anisotropy": 4, "anisotropic": "ewa"}"#,
                "mip",
            ),
            (
                r#"{"filter": "nearest", "levels": "zero", "derivatives": "quad", "repeats": 0}"#,
                "repeats",
            ),
            (
                r#"{"filter": "nearest", "levels": "zero", "derivatives": "quad", "w": [[1, 1, 0.5]]}"#,
                "w 0.5",
            ),
            (
                r#"{"filter": "nearest", "levels": "zero", "derivatives": "quad", "w": [[1, 1, 2], [1, 1, 2]]}"#,
                "three w per triangle",
            ),
        ] {
            let error = LabRequest::parse(&format!("{base}{texture}}}"))
                .unwrap_err()
                .to_string();
            assert!(error.contains(says), "{says}: {error}");
        }
    }
}
