//! Straight against premultiplied alpha: the dark fringe.
//!
//! A small texture holds an opaque orange disc on transparent texels.
//! Stored *straight*, a transparent texel still has a colour, here black
//! (what most paint programs save under alpha 0). Magnified with bilinear
//! filtering, the texels at the disc's rim are averaged with those black
//! ones, so the rim turns brown *and* half transparent: composited over
//! white with `over`, a dark ring appears. Premultiplied first (colour
//! times alpha, so a transparent texel is (0, 0, 0, 0) whatever it was),
//! the filter averages light and coverage together and the rim fades
//! cleanly into white. Porter and Duff (1984) give the algebra; every
//! texture-filtering course names the fringe.
//!
//! Everything is mixed in linear light (the texels decoded from sRGB
//! first), as the stage mixes by default.
//!
//! `cargo run --release --example alpha_fringe -- fringe.png` writes the
//! two side by side: straight on the left, premultiplied on the right.

use glam::{Vec2, Vec4};
use rasterlab::raster::{linear_to_srgb8, srgb8_to_linear, BlendMode, Filter, Texture};

/// Texels a side of the texture.
const TEXELS: u32 = 8;
/// Pixels a side of each half of the picture.
const SIDE: u32 = 192;

fn main() -> rasterlab::Result<()> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "fringe.png".into());
    rasterlab::check_file(std::path::Path::new(&out), &["png"])?;
    // The disc, in linear light, alpha 1 inside and 0 outside.
    let orange = Vec4::new(
        srgb8_to_linear(255),
        srgb8_to_linear(150),
        srgb8_to_linear(40),
        1.0,
    );
    let straight: Vec<Vec4> = (0..TEXELS * TEXELS)
        .map(|i| {
            let (x, y) = ((i % TEXELS) as f32 + 0.5, (i / TEXELS) as f32 + 0.5);
            let r = ((x - 4.0).powi(2) + (y - 4.0).powi(2)).sqrt();
            if r < 2.6 {
                orange
            } else {
                Vec4::ZERO
            }
        })
        .collect();
    let premultiplied: Vec<Vec4> = straight
        .iter()
        .map(|c| (c.truncate() * c.w).extend(c.w))
        .collect();
    let textures = [
        (
            Texture::new(TEXELS, TEXELS, straight),
            BlendMode::OverStraight,
        ),
        (Texture::new(TEXELS, TEXELS, premultiplied), BlendMode::Over),
    ];
    let white = Vec4::ONE;
    let mut picture = image::RgbaImage::new(2 * SIDE, SIDE);
    for (half, (texture, mode)) in textures.into_iter().enumerate() {
        let texture = texture.expect("an 8 x 8 texture is valid");
        for y in 0..SIDE {
            for x in 0..SIDE {
                let uv = Vec2::new(
                    (x as f32 + 0.5) / SIDE as f32,
                    (y as f32 + 0.5) / SIDE as f32,
                );
                let texel = texture.sample(uv, Filter::Bilinear);
                let c = mode.mix(texel, 1.0, white);
                let encoded = [c.x, c.y, c.z].map(linear_to_srgb8);
                picture.put_pixel(
                    half as u32 * SIDE + x,
                    y,
                    image::Rgba([encoded[0], encoded[1], encoded[2], 255]),
                );
            }
        }
    }
    rasterlab::write_png(std::path::Path::new(&out), &picture)?;
    println!("{out}: straight alpha (left) has a dark rim; premultiplied (right) none");
    Ok(())
}
