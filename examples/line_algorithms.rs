//! The line-drawing slides' line algorithms side by side on one line, from pixel (1, 1)
//! to pixel (13, 6): direct evaluation of y = m x + b, the incremental
//! DDA, midpoint / Bresenham, Wu's anti-aliased line and the
//! Direct3D / Vulkan diamond-exit rule, plain and with Scotty3D's
//! tie-break. Each prints the pixels it chose,
//! as a small grid (`#` chosen, for Wu a digit 1-9 for the coverage).
//!
//! `cargo run --release --example line_algorithms`

use rasterlab::raster::line::{LineOptions, LineSetup};
use rasterlab::raster::{line_backends, FixedPoint, FragmentList, PixelRect};

fn main() -> rasterlab::Result<()> {
    let (width, height) = (15u32, 8u32);
    // Pixel (i, j) has its centre at (i + 0.5, j + 0.5).
    let line = LineSetup {
        id: 0,
        from: FixedPoint::snap(1.5, 1.5)?,
        to: FixedPoint::snap(13.5, 6.5)?,
    };
    for backend in line_backends() {
        let mut fragments = FragmentList::default();
        let work = backend.rasterize(
            &[line],
            &LineOptions::DEFAULT,
            PixelRect::of_target(width, height),
            &mut fragments,
        );
        // One character per pixel, '.' where the line left it alone.
        let mut grid = vec![vec!['.'; width as usize]; height as usize];
        for f in &fragments.lines {
            grid[f.y as usize][f.x as usize] = if f.coverage >= 1.0 {
                '#'
            } else {
                // Wu's shades: coverage 0.1 .. 0.9 as the digits 1 .. 9.
                char::from_digit((f.coverage * 10.0).clamp(1.0, 9.0) as u32, 10).unwrap_or('#')
            };
        }
        println!(
            "{} ({} fragments): {}",
            backend.name(),
            work.fragments,
            backend.description()
        );
        for row in grid {
            println!("  {}", row.into_iter().collect::<String>());
        }
    }
    Ok(())
}
