//! A polygon with a hole, triangulated by `spade` (constrained Delaunay),
//! then drawn by every triangle back-end: the line-drawing slides' "more general polygons
//! can be broken down into triangles". The triangles share their edges
//! exactly, and under the top-left rule every pixel inside is drawn once:
//! no gaps, no double draws. Under the inclusive rule the shared edges'
//! pixels are drawn twice.
//!
//! `cargo run --release --example polygon`

use rasterlab::geometry::{Polygon, Scene2D};
use rasterlab::raster::{triangle_backends, FillRule, FixedPoint, Flat};

fn main() -> rasterlab::Result<()> {
    let p = |x: f32, y: f32| FixedPoint::snap(x, y);
    // Outer ring and one hole, in screen pixels.
    let outer = vec![
        p(2., 2.)?,
        p(30., 3.)?,
        p(28., 20.)?,
        p(16., 28.)?,
        p(3., 22.)?,
    ];
    let hole = vec![p(10., 8.)?, p(20., 9.)?, p(14., 16.)?];
    let polygon = Polygon::new(outer, vec![hole])?;
    let triangles = polygon.triangulate()?;
    println!("spade cut the polygon into {} triangles", triangles.len());

    let scene = Scene2D::from_triangles(32, 32, triangles);
    for rule in [FillRule::TopLeft, FillRule::Inclusive] {
        for backend in triangle_backends() {
            let (target, work) = scene.render(*backend, rule, &Flat)?;
            println!(
                "{:<9} {:<12} {:>4} fragments, {:>3} pixels drawn once, {:>2} drawn twice or more",
                rule.name(),
                backend.name(),
                work.fragments,
                target.pixels_with_coverage(1),
                target.coverage.iter().filter(|&&c| c > 1).count()
            );
        }
    }
    Ok(())
}
