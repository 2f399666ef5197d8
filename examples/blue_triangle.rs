//! The course chapter's blue triangle through the course's five steps:
//!
//! 1. vertex specification: the C array `float vertices[] = {-1,0,0, 0,-1,0, -1,-1,0}`;
//! 2. the vertex shader: here the identity (the positions are already in
//!    clip space, w = 1);
//! 3. primitive assembly: three vertices make one triangle;
//! 4. rasterisation: the per-pixel loop (the `naive` back-end) finds the
//!    pixels whose centres are inside;
//! 5. the fragment shader: every fragment is blue.
//!
//! The picture is printed as text (`#` = a blue pixel) and written to
//! `blue_triangle.png`, enlarged so that each of its 16 x 16 pixels is a
//! framed 16 x 16 cell.
//!
//! `cargo run --release --example blue_triangle`

use rasterlab::geometry::{
    assemble, draw, positions_from_floats, process_triangles, PipelineOptions, Topology, Transform,
    Viewport, BLUE,
};
use rasterlab::raster::{triangle_backend, Constant, DepthState, Interpolation, RenderTarget};

fn main() -> rasterlab::Result<()> {
    // Step 1: the vertex array, three floats (x, y, z) per vertex.
    let vertices = [-1.0, 0.0, 0.0, 0.0, -1.0, 0.0, -1.0, -1.0, 0.0];
    let positions = positions_from_floats(&vertices)?;
    // Step 3: assembly, every three vertices one triangle.
    let triangles = assemble(Topology::List, None, positions.len())?;
    // Step 2 (vertex shader: identity), then clipping, the perspective
    // divide and the viewport transform onto a 16 x 16 target.
    let viewport = Viewport {
        width: 16,
        height: 16,
    };
    let geometry = process_triangles(
        &positions,
        &triangles,
        &Transform::identity(),
        viewport,
        &PipelineOptions::default(),
    )?;
    // Steps 4 and 5: the naive loop emits fragments, the shader colours them blue.
    let mut target = RenderTarget::new(viewport.width, viewport.height)?;
    let work = draw(
        &geometry,
        triangle_backend("naive")?,
        &Constant(BLUE),
        DepthState::DEFAULT,
        Interpolation::PerspectiveCorrect,
        &mut target,
    );
    for y in 0..target.height() {
        let row: String = (0..target.width())
            .map(|x| {
                if target.coverage[target.index(x, y)] > 0 {
                    '#'
                } else {
                    '.'
                }
            })
            .collect();
        println!("{row}");
    }
    println!(
        "{} pixels tested, {} fragments; written to blue_triangle.png",
        work.samples_tested, work.fragments
    );
    // Enlarged to 256 x 256, each pixel a framed cell, so it can be seen.
    rasterlab::write_png(
        std::path::Path::new("blue_triangle.png"),
        &rasterlab::teaching::for_people(&target),
    )
}
