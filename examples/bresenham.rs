//! The line-drawing slides' midpoint / Bresenham algorithm, step by step, on the line from
//! pixel (0, 0) to pixel (7, 3): each column's decision variable
//! `d = f(x + 1, y + 0.5)` and the choice it makes.
//!
//! `d` is in the course's units, the same as `rasterlab explain --backend
//! bresenham 0 0 7 3` prints: the line function
//! `f(x, y) = (y0 - y1) x + (x1 - x0) y + x0 y1 - x1 y0`, coordinates in
//! pixels, not divided by the line's length. For this line `d` starts at
//! `f(1, 0.5) = -3 + 3.5 = 0.5` (in the walking frame, whose origin is the
//! first pixel's centre) and changes by `-3` when y is kept, `+4` when it
//! steps. The back-end keeps `d` as an integer in (1/256 pixel)^2; this
//! example divides by 256 x 256.
//!
//! `cargo run --release --example bresenham`

use rasterlab::raster::line::bresenham::Bresenham;
use rasterlab::raster::line::OctantFrame;
use rasterlab::raster::{FixedPoint, SUBPIXEL_SCALE};

fn main() -> rasterlab::Result<()> {
    // Pixel (i, j) has its centre at (i + 0.5, j + 0.5).
    let from = FixedPoint::snap(0.5, 0.5)?;
    let to = FixedPoint::snap(7.5, 3.5)?;
    let frame = OctantFrame::new(from, to);
    // From (1/256 pixel)^2 to pixels^2: the course's f, unnormalised.
    let scale = (SUBPIXEL_SCALE * SUBPIXEL_SCALE) as f64;
    println!("  x  y  d = f(x+1, y+0.5) (pixels^2, as explain prints)  choice");
    for step in Bresenham::steps(&frame) {
        let (x, y) = frame.to_screen(step.i, step.k);
        let choice = if step.step_up {
            "d < 0: y = y + 1"
        } else {
            "d >= 0: keep y"
        };
        println!("{x:>3} {y:>2} {:>51.3}  {choice}", step.d as f64 / scale);
    }
    Ok(())
}
