//! The depth-buffer trace: the rasterization slides' loop (`if f.z <
//! depthBuffer[f.xy]: draw f, depthBuffer[f.xy] = f.z`) on a scene drawn
//! triangle after triangle, the buffer printed as the slides' matrix
//! before the first triangle and after each, with each triangle's
//! fragments kept and hidden.

use super::check_trace_length;
use crate::error::Result;
use crate::geometry::scene::Scene2D;
use crate::raster::edge::FillRule;
use crate::raster::shader::Flat;
use crate::raster::target::{DepthState, DepthTest, RenderTarget};
use crate::raster::triangle::TriangleRasterizer;
use crate::teaching::trace_table::{Trace, TraceRow};

/// The rasterization slides' depth-buffer loop on a scene: each triangle in turn drawn by
/// `backend` through the shared stage (`if f.z < depthBuffer[f.xy]: draw
/// f, depthBuffer[f.xy] = f.z`), and the depth buffer after each, as the
/// slides' matrix: one row of the trace per row of pixels.
pub fn trace_depth_buffer(
    scene: &Scene2D,
    backend: &dyn TriangleRasterizer,
    rule: FillRule,
) -> Result<Trace> {
    let mut target = RenderTarget::new(scene.width, scene.height)?;
    let matrices = scene.triangles.len() as u64 + 1;
    check_trace_length(
        matrices * u64::from(scene.width) * u64::from(scene.height),
        "depth-buffer cells",
    )?;
    let depth = DepthState {
        test: DepthTest::Less,
        write: true,
    };
    let mut out = Trace::saying(format!(
        "depth buffer, {} x {}, initialised with 1.0; each fragment f is kept if f.z < depthBuffer[f.xy]",
        scene.width, scene.height
    ));
    print_matrix(&mut out, &target.depth, scene.width);
    for (i, (triangle, vertices)) in scene.triangles.iter().zip(&scene.vertices).enumerate() {
        let one = Scene2D {
            triangles: vec![*triangle],
            vertices: vec![*vertices],
            ..scene.clone()
        };
        let before = target.depth.clone();
        let work = one.draw(backend, rule, depth, &Flat, &mut target);
        let kept = before
            .iter()
            .zip(&target.depth)
            .filter(|(b, a)| a != b)
            .count();
        let z: Vec<String> = vertices.iter().map(|v| format!("{}", v.depth)).collect();
        out.rows.push(TraceRow::note(String::new()));
        out.rows.push(TraceRow::note(format!(
            "triangle {} (z = {}): {} fragments, {kept} kept (nearer than the buffer), {} hidden",
            i + 1,
            z.join(", "),
            work.fragments,
            work.fragments - kept as u64
        )));
        print_matrix(&mut out, &target.depth, scene.width);
    }
    Ok(out)
}

/// The depth buffer as the slides' matrix, a row of the trace per row of
/// pixels.
fn print_matrix(out: &mut Trace, depth: &[f32], width: u32) {
    for (y, row) in depth.chunks(width as usize).enumerate() {
        let cells: Vec<String> = row.iter().map(|z| format!("{z:.1}")).collect();
        out.rows
            .push(TraceRow::new(cells).about(0, y as i64, i64::from(width) - 1, y as i64));
    }
}
