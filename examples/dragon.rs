//! The Stanford dragon (the bundled quarter-resolution scan, `dragon_vrip_res4`)
//! rendered by the 3D pipeline, as in the software-rasterizer article: camera, vertex shader,
//! clipping, perspective divide, back-face culling, viewport, a
//! rasterizer back-end, the depth test and diffuse shading. Every triangle
//! back-end renders it; the buffers are compared bit for bit and the
//! picture is written to `dragon.png`.
//!
//! `cargo run --release --example dragon`

use rasterlab::geometry::{CullMode, Mesh, MeshRenderer, RenderSettings};
use rasterlab::raster::triangle_backends;
use std::path::Path;

fn main() -> rasterlab::Result<()> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/dragon_vrip_res4.ply.gz");
    let mesh = Mesh::load(&path)?;
    let mut settings = RenderSettings {
        width: 480,
        height: 360,
        azimuth: 30.0,
        zoom: 1.3,
        ..RenderSettings::default()
    };
    settings.pipeline.cull = CullMode::Back;
    let renderer = MeshRenderer::new(&mesh, settings)?;

    let mut reference = None;
    for backend in triangle_backends().iter().filter(|b| b.name() != "naive") {
        let frame = renderer.render(*backend)?;
        println!(
            "{:<12} {:>6} triangles drawn, {:>7} fragments, {:>7} samples tested, {:.2} ms",
            backend.name(),
            frame.stats.geometry.triangles,
            frame.stats.work.fragments,
            frame.stats.work.samples_tested,
            frame.stats.raster_time.as_secs_f64() * 1e3
        );
        match &reference {
            None => reference = Some(frame.target),
            Some(first) => assert!(*first == frame.target, "{} differs", backend.name()),
        }
    }
    if let Some(target) = reference {
        target.save_png(Path::new("dragon.png"))?;
        println!("bit-identical buffers from every back-end; written to dragon.png");
    }
    Ok(())
}
