//! What the depth test (`if f.z < depthBuffer[f.xy]`) did at each pixel
//! of a scene drawn triangle after triangle: the depth stored, the
//! triangles whose fragments were kept, and those whose fragments were
//! hidden behind a nearer one. The depth-buffer picture and the lab's
//! depth view are drawn from these cells.

use super::check_grid;
use crate::error::Result;
use crate::geometry::scene::Scene2D;
use crate::raster::edge::FillRule;
use crate::raster::shader::Flat;
use crate::raster::target::{DepthState, RenderTarget};
use crate::raster::triangle::TriangleRasterizer;

/// What the depth test did at each pixel of a scene drawn in order: the
/// depth stored, the triangle whose fragment is stored, and the triangles
/// whose fragments were hidden (farther than the depth already stored,
/// or equal to it: the test is `f.z < depthBuffer`). Triangles are
/// numbered from 0 in drawing order.
#[derive(Clone, Debug, PartialEq)]
pub struct DepthCells {
    /// Grid width.
    pub width: u32,
    /// Grid height.
    pub height: u32,
    /// The depth stored, row by row (1.0: nothing drawn).
    pub depth: Vec<f32>,
    /// The triangles whose fragments the depth test kept, per pixel, in
    /// drawing order: the last one's depth and colour are stored (the
    /// others' were kept, then overwritten by a nearer fragment).
    pub kept: Vec<Vec<u32>>,
    /// The triangles whose fragments the depth test hid, per pixel.
    pub hidden: Vec<Vec<u32>>,
}

impl DepthCells {
    /// Draws `scene` by `backend` under `rule` through the shared stage
    /// with the rasterization slides' depth test (`less`, writes on), one
    /// triangle at a time, and records each pixel's outcome.
    pub fn of_scene(
        scene: &Scene2D,
        backend: &dyn TriangleRasterizer,
        rule: FillRule,
    ) -> Result<DepthCells> {
        check_grid(scene.width, scene.height)?;
        let n = (scene.width * scene.height) as usize;
        let mut target = RenderTarget::new(scene.width, scene.height)?;
        let mut kept = vec![Vec::new(); n];
        let mut hidden = vec![Vec::new(); n];
        for (t, (triangle, vertices)) in scene.triangles.iter().zip(&scene.vertices).enumerate() {
            let one = Scene2D {
                triangles: vec![*triangle],
                vertices: vec![*vertices],
                ..scene.clone()
            };
            // The triangle's own fragments, then what the test did to them.
            let (alone, _) = one.render(backend, rule, &Flat)?;
            let before = target.depth.clone();
            one.draw(backend, rule, DepthState::DEFAULT, &Flat, &mut target);
            for i in 0..n {
                if alone.coverage[i] == 0 {
                    continue;
                }
                if target.depth[i].to_bits() != before[i].to_bits() {
                    kept[i].push(t as u32);
                } else {
                    hidden[i].push(t as u32);
                }
            }
        }
        Ok(DepthCells {
            width: scene.width,
            height: scene.height,
            depth: target.depth,
            kept,
            hidden,
        })
    }
}
