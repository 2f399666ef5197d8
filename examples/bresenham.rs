//! The line-drawing slides' midpoint / Bresenham algorithm, step by step, on the line from
//! pixel (0, 0) to pixel (7, 3): each column's decision variable
//! `d = f(x + 1, y + 0.5)` and the choice it makes.
//!
//! `cargo run --release --example bresenham`

use rasterlab::raster::fixed::FixedPoint;
use rasterlab::raster::line::bresenham::Bresenham;
use rasterlab::raster::line::OctantFrame;

fn main() -> rasterlab::Result<()> {
    // Pixel (i, j) has its centre at (i + 0.5, j + 0.5).
    let from = FixedPoint::snap(0.5, 0.5)?;
    let to = FixedPoint::snap(7.5, 3.5)?;
    let frame = OctantFrame::new(from, to);
    // d is kept in fixed-point units (1/256 pixel) times du, as an integer.
    let scale = 256.0 * 256.0 * (frame.du() as f64 / 256.0);
    println!("  x  y  d = f(x+1, y+0.5) (pixels)  choice");
    for step in Bresenham::steps(&frame) {
        let (x, y) = frame.to_screen(step.i, step.k);
        let choice = if step.step_up {
            "d < 0: y = y + 1"
        } else {
            "d >= 0: keep y"
        };
        println!("{x:>3} {y:>2} {:>27.3}  {choice}", step.d as f64 / scale);
    }
    Ok(())
}
