//! Two images compared as a course's image grader compares them
//! (`check --image`): per pixel the largest difference over its red,
//! green and blue channels (0 to 255), then over the image the mean of
//! that difference (UCR CS 130's graders' measure), the share of pixels
//! whose difference is past a threshold, and the PSNR of the channels'
//! mean squared error; and the diff picture, each pixel coloured by the
//! palette's "correct" or "differs from the reference", with its legend.
//!
//! ```
//! use rasterlab::check::ImageMetrics;
//!
//! let a = image::RgbaImage::from_pixel(2, 2, image::Rgba([10, 20, 30, 255]));
//! let mut b = a.clone();
//! b.put_pixel(0, 0, image::Rgba([10, 120, 30, 255]));
//! let m = ImageMetrics::compare(&a, &b, 32);
//! assert_eq!(m.mean, 25.0);
//! assert_eq!(m.share_past, 0.25);
//! // The squared error 100² over 3 channels of 4 pixels.
//! let mse = 100.0 * 100.0 / 12.0;
//! assert!((m.psnr.unwrap() - 10.0 * (255.0f64 * 255.0 / mse).log10()).abs() < 1e-9);
//! ```

use crate::markup::Markup;
use crate::teaching::palette::{Legend, Role};
use base64::Engine as _;
use image::RgbaImage;
use serde::Serialize;

/// What two images of one size differ by.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ImageMetrics {
    /// The mean over pixels of the largest channel difference, 0 to 255.
    pub mean: f64,
    /// The largest channel difference of any pixel, 0 to 255.
    pub max: u8,
    /// The share of pixels (0 to 1) whose largest channel difference is
    /// past `threshold`.
    pub share_past: f64,
    /// The threshold `share_past` counts against.
    pub threshold: u8,
    /// The peak signal-to-noise ratio of the channels, in dB; `None`
    /// when the images are equal (an infinite ratio).
    pub psnr: Option<f64>,
}

/// A pixel's largest difference over red, green and blue.
fn largest_difference(a: &image::Rgba<u8>, b: &image::Rgba<u8>) -> u8 {
    (0..3).map(|c| a.0[c].abs_diff(b.0[c])).max().unwrap_or(0)
}

impl ImageMetrics {
    /// The metrics of `actual` against `expected` (the same size), a
    /// pixel counted past `threshold` when its largest channel difference
    /// is greater than it. Alpha is not compared: a PNG without it is
    /// opaque, as rasterlab's images are.
    pub fn compare(expected: &RgbaImage, actual: &RgbaImage, threshold: u8) -> ImageMetrics {
        let (mut sum, mut max, mut past, mut squares) = (0u64, 0u8, 0u64, 0u64);
        for (a, b) in expected.pixels().zip(actual.pixels()) {
            let d = largest_difference(a, b);
            sum += u64::from(d);
            max = max.max(d);
            past += u64::from(d > threshold);
            squares += (0..3)
                .map(|c| u64::from(a.0[c].abs_diff(b.0[c])).pow(2))
                .sum::<u64>();
        }
        let pixels = (u64::from(expected.width()) * u64::from(expected.height())).max(1) as f64;
        let mse = squares as f64 / (3.0 * pixels);
        ImageMetrics {
            mean: sum as f64 / pixels,
            max,
            share_past: past as f64 / pixels,
            threshold,
            psnr: (mse > 0.0).then(|| 10.0 * (255.0 * 255.0 / mse).log10()),
        }
    }
}

/// The diff image at one pixel a pixel: "correct" where the largest
/// channel difference is at most `threshold`, "differs from the
/// reference" past it.
pub fn diff_image(expected: &RgbaImage, actual: &RgbaImage, threshold: u8) -> RgbaImage {
    let [same, differs] = [Role::Correct, Role::Differs].map(|r| {
        let [r, g, b] = r.rgb();
        image::Rgba([r, g, b, 255])
    });
    RgbaImage::from_fn(expected.width(), expected.height(), |x, y| {
        let d = largest_difference(expected.get_pixel(x, y), actual.get_pixel(x, y));
        if d > threshold {
            differs
        } else {
            same
        }
    })
}

/// The diff image as an SVG picture: a caption, the image enlarged to
/// about 480 pixels across (each pixel a square), its legend below.
pub fn diff_svg(diff: &RgbaImage, caption: &str) -> String {
    let mut png = Vec::new();
    // Encoding into memory fails only on a zero-size image, which no
    // render has.
    let _ = diff.write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png);
    let data = base64::engine::general_purpose::STANDARD.encode(&png);
    let side = f64::from(diff.width().max(diff.height()).max(1));
    let scale = (480.0 / side).clamp(0.25, 40.0);
    let (w, h) = (
        f64::from(diff.width()) * scale,
        f64::from(diff.height()) * scale,
    );
    let top = 26.0;
    let legend_width = w.max(420.0);
    let legend = Legend::new(&[Role::Correct, Role::Differs]);
    let (legend, legend_height) = legend.to_svg(4.0, top + h + 10.0, legend_width);
    let width = (w + 8.0)
        .max(legend_width + 8.0)
        .max(caption.chars().count() as f64 * 8.4 + 12.0);
    let height = top + h + 12.0 + legend_height;
    let mut m = Markup::new();
    m.open_svg(width, height, None).newline();
    m.element("title", &[], caption).newline();
    m.empty(
        "path",
        &[
            ("d", &format_args!("M0 0H{width}V{height}H0Z")),
            ("fill", &"white"),
        ],
    )
    .newline();
    m.element(
        "text",
        &[
            ("class", &"caption"),
            ("x", &4),
            ("y", &18),
            ("font-size", &15),
        ],
        caption,
    )
    .newline();
    m.empty(
        "image",
        &[
            ("x", &4),
            ("y", &top),
            ("width", &w),
            ("height", &h),
            ("style", &"image-rendering:pixelated"),
            ("href", &format_args!("data:image/png;base64,{data}")),
        ],
    )
    .newline();
    m.raw(&legend).newline();
    m.close("svg").newline();
    m.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_images_have_no_error_and_an_infinite_psnr() {
        let a = RgbaImage::from_pixel(3, 2, image::Rgba([1, 2, 3, 255]));
        let m = ImageMetrics::compare(&a, &a, 0);
        assert_eq!((m.mean, m.max, m.share_past, m.psnr), (0.0, 0, 0.0, None));
        let d = diff_image(&a, &a, 0);
        assert!(d.pixels().all(|p| p.0[..3] == Role::Correct.rgb()));
        let svg = diff_svg(&d, "diff");
        assert!(svg.contains("data:image/png;base64,") && svg.contains(&Role::Correct.hex()));
    }

    #[test]
    fn only_the_largest_channel_counts_and_alpha_is_ignored() {
        let a = RgbaImage::from_pixel(1, 1, image::Rgba([100, 100, 100, 255]));
        let b = RgbaImage::from_pixel(1, 1, image::Rgba([90, 140, 100, 0]));
        let m = ImageMetrics::compare(&a, &b, 40);
        assert_eq!((m.mean, m.max, m.share_past), (40.0, 40, 0.0));
        assert_eq!(ImageMetrics::compare(&a, &b, 39).share_past, 1.0);
    }
}
