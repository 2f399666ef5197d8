//! The rasterization slides' depth-buffer example: a blue triangle at depth 0.5 and a red
//! one at depth 0.8 on a 14 x 9 grid, drawn in both orders. The depth
//! buffer starts at 1.0 and keeps a fragment only if `f.z < depthBuffer`,
//! so both orders give the same picture.
//!
//! `cargo run --release --example depth_buffer`

use rasterlab::geometry::Scene2D;
use rasterlab::raster::{triangle_backend, FillRule, Flat};

fn print_depth(title: &str, depth: &[f32]) {
    println!("{title}");
    for row in depth.chunks(14) {
        let cells: Vec<String> = row.iter().map(|z| format!("{z:.1}")).collect();
        println!("  {}", cells.join(" "));
    }
}

fn main() -> rasterlab::Result<()> {
    let bbox = triangle_backend("bbox")?;
    // Blue first, then red: red is behind blue where they overlap.
    let (blue_first, _) = Scene2D::depth_example(true).render(bbox, FillRule::TopLeft, &Flat)?;
    print_depth(
        "depth buffer, blue (z = 0.5) drawn first:",
        &blue_first.depth,
    );
    // Red first, then blue: blue overwrites red where it is nearer.
    let (red_first, _) = Scene2D::depth_example(false).render(bbox, FillRule::TopLeft, &Flat)?;
    print_depth("depth buffer, red (z = 0.8) drawn first:", &red_first.depth);
    println!(
        "same depth and colour buffers in both orders: {}",
        blue_first == red_first
    );
    Ok(())
}
