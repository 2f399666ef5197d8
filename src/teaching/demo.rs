//! The demo: the experiment behind the crate's central claim. The bundled
//! 2D scenes (the course's depth-buffer example, a split square, a
//! pinwheel, a fan) and meshes (the Stanford bunny and a dragon) are drawn
//! by every triangle back-end through the shared stage, and every image
//! is compared, buffer for buffer, with the reference's.
//!
//! ```no_run
//! use rasterlab::teaching::{bundled_assets, run_demo};
//! use std::path::Path;
//!
//! let report = run_demo(Path::new("demo-output"), &bundled_assets()).unwrap();
//! print!("{report}");
//! assert!(report.all_identical());
//! ```

use crate::error::Result;
use crate::geometry::mesh::Mesh;
use crate::geometry::pipeline::{CullMode, PipelineOptions};
use crate::geometry::render::{MeshRenderer, RenderSettings};
use crate::geometry::scene::Scene2D;
use crate::raster::edge::FillRule;
use crate::raster::registry::triangle_backends;
use crate::raster::shader::Flat;
use crate::raster::target::RenderTarget;
use serde::Serialize;
use std::fmt;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The bundled meshes the demo renders, relative to the assets folder.
const MESHES: [(&str, &str); 2] = [
    ("bunny", "bunny.ply"),
    ("dragon-res4", "dragon_vrip_res4.ply.gz"),
];

/// The folder of the bundled assets (the crate's `assets/`).
pub fn bundled_assets() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets")
}

/// One back-end on one scene or mesh.
#[derive(Clone, Debug, Serialize)]
pub struct DemoRow {
    /// The scene or mesh.
    pub scene: String,
    /// The back-end.
    pub backend: &'static str,
    /// Samples it tested.
    pub samples_tested: u64,
    /// Fragments it emitted.
    pub fragments: u64,
    /// Its time (a scene: the whole render; a mesh: the raster part), in ms.
    pub time_ms: f64,
    /// Whether its colour, depth and coverage buffers equal the reference's.
    pub identical: bool,
}

/// Every back-end on every bundled scene and mesh.
#[derive(Clone, Debug, Serialize)]
pub struct DemoReport {
    /// One row per scene and back-end, the reference first in each scene.
    pub rows: Vec<DemoRow>,
    /// Where the reference's pictures were written.
    pub out: PathBuf,
}

impl DemoReport {
    /// True when every back-end's buffers equal the reference's on every scene.
    pub fn all_identical(&self) -> bool {
        self.rows.iter().all(|r| r.identical)
    }
}

/// Draws every bundled scene and mesh (meshes read from `assets`) with
/// every triangle back-end, compares each with the first (the reference)
/// and writes the reference's pictures in `out`, one PNG per scene.
pub fn run_demo(out: &Path, assets: &Path) -> Result<DemoReport> {
    crate::output::check_dir(out)?;
    let mut rows = Vec::new();
    for name in Scene2D::BUILT_IN {
        let scene = Scene2D::built_in(name)?;
        let mut reference: Option<RenderTarget> = None;
        for backend in triangle_backends() {
            let start = Instant::now();
            let (target, work) = scene.render(*backend, FillRule::TopLeft, &Flat)?;
            rows.push(DemoRow {
                scene: name.to_string(),
                backend: backend.name(),
                samples_tested: work.samples_tested,
                fragments: work.fragments,
                time_ms: start.elapsed().as_secs_f64() * 1e3,
                identical: reference.as_ref().is_none_or(|r| *r == target),
            });
            if reference.is_none() {
                // Enlarged, each pixel a framed cell: the scenes are 5 to 14
                // pixels a side.
                crate::output::write_png(
                    &out.join(format!("{name}.png")),
                    &crate::teaching::grid_picture::for_people(&target),
                )?;
                reference = Some(target);
            }
        }
    }
    for (name, file) in MESHES {
        let mesh = Mesh::load(&assets.join(file))?;
        let settings = RenderSettings {
            width: 320,
            height: 240,
            azimuth: 30.0,
            pipeline: PipelineOptions {
                cull: CullMode::Back,
                ..PipelineOptions::default()
            },
            ..RenderSettings::default()
        };
        let renderer = MeshRenderer::new(&mesh, settings)?;
        let mut reference: Option<RenderTarget> = None;
        for backend in triangle_backends() {
            let frame = renderer.render(*backend)?;
            rows.push(DemoRow {
                scene: name.to_string(),
                backend: backend.name(),
                samples_tested: frame.stats.work.samples_tested,
                fragments: frame.stats.work.fragments,
                time_ms: frame.stats.raster_time.as_secs_f64() * 1e3,
                identical: reference.as_ref().is_none_or(|r| *r == frame.target),
            });
            if reference.is_none() {
                frame.target.save_png(&out.join(format!("{name}.png")))?;
                reference = Some(frame.target);
            }
        }
    }
    Ok(DemoReport {
        rows,
        out: out.to_path_buf(),
    })
}

impl fmt::Display for DemoReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "{:<16} {:<12} {:>10} {:>10} {:>9}  identical to {}",
            "scene",
            "back-end",
            "tested",
            "fragments",
            "time",
            self.rows.first().map_or("the reference", |r| r.backend)
        )?;
        for r in &self.rows {
            writeln!(
                f,
                "{:<16} {:<12} {:>10} {:>10} {:>7.2}ms  {}",
                r.scene,
                r.backend,
                r.samples_tested,
                r.fragments,
                r.time_ms,
                if r.identical { "yes" } else { "NO" }
            )?;
        }
        writeln!(
            f,
            "pictures in {}/ (meshes: Stanford 3D Scanning Repository)",
            self.out.display()
        )?;
        if self.all_identical() {
            writeln!(
                f,
                "every back-end produced bit-identical colour, depth and coverage buffers"
            )
        } else {
            writeln!(f, "back-ends disagree: see the rows marked NO")
        }
    }
}
