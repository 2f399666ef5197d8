//! A grid picture as an image: drawn cell by cell at a zoom (the cells,
//! their borders and centres, the edges in their line patterns, the
//! blocks' frames and the samples), or the SVG picture rendered with the
//! bundled font; and a rendered target enlarged, each pixel a framed
//! cell, into a picture large enough for a person to see its pixels.

use super::{block_style, GridPicture, MIN_SHORT_SIDE};
use crate::error::Result;
use crate::raster::target::RenderTarget;
use crate::teaching::palette::{Mark, Role};

/// The largest grid [`GridPicture::to_picture_png`] renders with its
/// labels and legend (256 x 256 cells).
pub const MAX_LABELLED_CELLS: u64 = 256 * 256;

impl GridPicture {
    /// The grid alone as an image, `zoom` image pixels per grid cell (for
    /// a page that shows the legend beside it; [`GridPicture::save`]
    /// writes the whole picture). At a zoom of 6 or more the cell borders
    /// and centres are drawn too, and the outlines and segments at any
    /// zoom; labels, axes and legend are in [`GridPicture::to_svg`].
    pub fn to_png(&self, zoom: u32) -> Result<image::RgbImage> {
        let zoom = zoom.max(1);
        let (w, h) = (self.width * zoom, self.height * zoom);
        RenderTarget::check_size(w, h)?;
        let mut img = image::RgbImage::from_fn(w, h, |px, py| {
            let c = self.cells[((py / zoom) * self.width + px / zoom) as usize];
            if zoom >= 6 {
                let (ix, iy) = (px % zoom, py % zoom);
                let (mid, r) = (zoom / 2, zoom / 12 + 1);
                if ix == 0 || iy == 0 {
                    return image::Rgb([154, 154, 154]);
                }
                if ix.abs_diff(mid) < r && iy.abs_diff(mid) < r && self.labels.is_empty() {
                    return image::Rgb([51, 51, 51]);
                }
            }
            image::Rgb(c)
        });
        let z = zoom as f64;
        let mut stroke =
            |(x0, y0): (f64, f64), (x1, y1): (f64, f64), color: [u8; 3], mark: Mark| {
                let steps = ((x1 - x0).abs().max((y1 - y0).abs()) * z * 2.0)
                    .ceil()
                    .max(1.0) as u32;
                // The dash pattern, in image pixels, as the SVG draws it.
                let dashes: Vec<f64> = mark
                    .dasharray()
                    .map(|d| d.split(' ').filter_map(|v| v.parse().ok()).collect())
                    .unwrap_or_default();
                let period: f64 = dashes.iter().sum();
                let length = (x1 - x0).hypot(y1 - y0) * z;
                for i in 0..=steps {
                    let t = i as f64 / steps as f64;
                    if period > 0.0 {
                        // In a gap: the odd entries of the pattern.
                        let mut along = (t * length) % period;
                        let mut k = 0;
                        while along >= dashes[k] {
                            along -= dashes[k];
                            k += 1;
                        }
                        if k % 2 == 1 {
                            continue;
                        }
                    }
                    let (x, y) = ((x0 + (x1 - x0) * t) * z, (y0 + (y1 - y0) * t) * z);
                    for (dx, dy) in [(0.0, 0.0), (-1.0, 0.0), (0.0, -1.0), (-1.0, -1.0)] {
                        let (px, py) = ((x + dx).round(), (y + dy).round());
                        if px >= 0.0 && py >= 0.0 && px < w as f64 && py < h as f64 {
                            img.put_pixel(px as u32, py as u32, image::Rgb(color));
                        }
                    }
                }
            };
        for (t, outline) in self.outlines.iter().enumerate() {
            let (colour, mark) = self.edge_style(t);
            for k in 0..outline.len() {
                stroke(outline[k], outline[(k + 1) % outline.len()], colour, mark);
            }
        }
        for &[a, b] in &self.segments {
            stroke(a, b, Role::Geometry.rgb(), Mark::Line);
        }
        let (quad_lines, crosses) = self.quad_strokes();
        for &[a, b] in &quad_lines {
            stroke(a, b, Role::Geometry.rgb(), Mark::Dashed);
        }
        for &[a, b] in &crosses {
            stroke(a, b, Role::Geometry.rgb(), Mark::Line);
        }
        for (r, class) in &self.blocks {
            let colour = block_style(*class).0.rgb();
            // Just inside the block, so neighbouring frames do not overlap.
            let inset = 2.0 / z;
            let (x0, y0) = (r.x0 as f64 + inset, r.y0 as f64 + inset);
            let (x1, y1) = ((r.x1 + 1) as f64 - inset, (r.y1 + 1) as f64 - inset);
            for (a, b) in [
                ((x0, y0), (x1, y0)),
                ((x1, y0), (x1, y1)),
                ((x1, y1), (x0, y1)),
                ((x0, y1), (x0, y0)),
            ] {
                stroke(a, b, colour, Mark::Block);
            }
        }
        if zoom >= 8 {
            // Each sample a 3 x 3 square: filled when covered, hollow not.
            let black = image::Rgb(Role::SampleCovered.rgb());
            for &(x, y, inside) in &self.samples {
                let (cx, cy) = ((x * z).round() as i64, (y * z).round() as i64);
                for dy in -1..=1i64 {
                    for dx in -1..=1i64 {
                        let (px, py) = (cx + dx, cy + dy);
                        if (0..i64::from(w)).contains(&px) && (0..i64::from(h)).contains(&py) {
                            let ring = dx != 0 || dy != 0;
                            let c = if inside || ring {
                                black
                            } else {
                                image::Rgb([255, 255, 255])
                            };
                            img.put_pixel(px as u32, py as u32, c);
                        }
                    }
                }
            }
        }
        Ok(img)
    }

    /// The picture as an image: with the `png-text` feature (on by
    /// default), the SVG picture rendered with the bundled font (the same
    /// caption, axes, labels and legend). Without it, or for a grid of
    /// more than [`MAX_LABELLED_CELLS`] cells, the grid is drawn cell by
    /// cell ([`GridPicture::to_png`]) at the SVG's cell size, at most about
    /// 2048 pixels on its long side.
    pub fn to_picture_png(&self) -> Result<image::RgbaImage> {
        let cells = u64::from(self.width) * u64::from(self.height);
        #[cfg(feature = "png-text")]
        if cells <= MAX_LABELLED_CELLS {
            if let Some(picture) = crate::output::svg_to_png(&self.to_svg()) {
                return Ok(picture);
            }
        }
        let zoom = if cells <= MAX_LABELLED_CELLS {
            self.svg_cell() as u32
        } else {
            (2048 / self.width.max(self.height)).max(1)
        };
        Ok(image::DynamicImage::ImageRgb8(self.to_png(zoom)?).into_rgba8())
    }
}

/// The scale that enlarges a `width` x `height` image until its short
/// side is at least [`MIN_SHORT_SIDE`] pixels (1 for an image that large
/// already; at most 64).
pub fn scale_for_people(width: u32, height: u32) -> u32 {
    MIN_SHORT_SIDE
        .div_ceil(width.min(height).max(1))
        .clamp(1, 64)
}

/// A rendered target as a picture meant for a person: small scenes
/// enlarged by [`scale_for_people`], each pixel a framed cell
/// ([`RenderTarget::to_image_scaled`]), so that the short side is at least
/// [`MIN_SHORT_SIDE`] pixels.
///
/// ```
/// use rasterlab::geometry::Scene2D;
/// use rasterlab::raster::{triangle_backend, FillRule, Flat};
/// use rasterlab::teaching::{for_people, MIN_SHORT_SIDE};
///
/// let scene = Scene2D::split_square();
/// let (target, _) = scene.render(triangle_backend("bbox")?, FillRule::TopLeft, &Flat)?;
/// let picture = for_people(&target);
/// assert!(picture.width().min(picture.height()) >= MIN_SHORT_SIDE);
/// # Ok::<(), rasterlab::Error>(())
/// ```
pub fn for_people(target: &RenderTarget) -> image::RgbaImage {
    target.to_image_scaled(scale_for_people(target.width(), target.height()))
}
