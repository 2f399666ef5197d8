//! Mesa's llvmpipe against rasterlab, before `side_by_side` times one
//! against the other: the same work must give the same fragments.
//!
//! * 3,000 random triangles, each drawn alone on a 64x64 target by
//!   llvmpipe and by rasterlab's reference (`naive`, top-left rule), with
//!   both mapping window coordinates the same way (GL's window y is
//!   rasterlab's screen y): the same pixels, triangle for triangle. The
//!   vertices lie on grids of 1/2, 1/16 and 1/256 pixel, so many pixel
//!   centres fall exactly on edges and vertices, where the tie-breaking
//!   rule decides. They lie inside the target: llvmpipe clips a triangle
//!   that crosses the viewport's edge, and the vertices it makes there are
//!   its own. (Mapped the other way, GL's window y running up from
//!   rasterlab's bottom row, about 16 in 3,000 differ, on ties.)
//! * The bundled dragon (and the full one when the Stanford models are
//!   found, see `rasterlab::measure::data`) with rasterlab's camera at
//!   1920x1080, back faces culled: the fragments llvmpipe rasterizes
//!   (an occlusion query with every fragment passing) are rasterlab's,
//!   give or take 3 (GL computes the viewport transform in `f32`,
//!   rasterlab in `f64`, so a vertex can snap one 1/256 px apart).
//!
//! Without Mesa (`libEGL.so.1`, Mesa's EGL and DRI drivers) each test
//! prints why it is skipped and passes, unless `RASTERLAB_REQUIRE_MESA=1`
//! (set by `.ci/run`, which installs Mesa), where a missing Mesa fails.

#[path = "../benches/support/gl.rs"]
mod gl;

use rasterlab::geometry::mesh::Mesh;
use rasterlab::geometry::pipeline::CullMode;
use rasterlab::geometry::render::{MeshRenderer, RenderSettings};
use rasterlab::geometry::scene::setup_triangles;
use rasterlab::measure::data;
use rasterlab::raster::backend::triangle_backend;
use rasterlab::raster::edge::{FillRule, PixelRect};
use rasterlab::raster::fixed::FixedPoint;
use rasterlab::raster::fragment::{FragmentSink, LineFragment, TriangleFragment};
use rasterlab::raster::target::RenderTarget;

/// llvmpipe, or `None` with the reason printed (a failure when
/// `RASTERLAB_REQUIRE_MESA=1`).
fn llvmpipe(width: u32, height: u32) -> Option<gl::Llvmpipe> {
    match gl::Llvmpipe::new(width, height, 1) {
        Ok(llvmpipe) => {
            assert_eq!(llvmpipe.threads(), 1);
            Some(llvmpipe)
        }
        Err(reason) => {
            assert!(
                std::env::var("RASTERLAB_REQUIRE_MESA").as_deref() != Ok("1"),
                "RASTERLAB_REQUIRE_MESA=1 but llvmpipe is unavailable: {reason}"
            );
            eprintln!("skipped: llvmpipe unavailable: {reason}");
            None
        }
    }
}

/// The pixels a back-end emits, as a coverage mask.
struct Mask {
    width: u32,
    covered: Vec<bool>,
}

impl FragmentSink for Mask {
    fn triangle_fragment(&mut self, f: &TriangleFragment) {
        self.covered[(f.y * self.width + f.x) as usize] = true;
    }
    fn line_fragment(&mut self, _: &LineFragment) {}
}

#[test]
fn llvmpipe_agrees_with_the_top_left_rule_on_random_triangles() {
    const SIZE: u32 = 64;
    let Some(gl) = llvmpipe(SIZE, SIZE) else {
        return;
    };
    let naive = triangle_backend("naive").unwrap();
    let mut rng = fastrand::Rng::with_seed(7);
    let transform = gl.window_transform();
    let (mut agree, mut ties) = (0, 0);
    for case in 0..3000 {
        // Grids of 1/2, 1/16 and 1/256 px: pixel centres on edges often.
        let steps = [128, 16, 1][case % 3];
        let mut corner = || {
            let k = |rng: &mut fastrand::Rng| rng.i32(0..=SIZE as i32 * 256);
            let (x, y) = (k(&mut rng) / steps * steps, k(&mut rng) / steps * steps);
            (x as f32 / 256.0, y as f32 / 256.0)
        };
        let corners = [corner(), corner(), corner()];
        let points = corners.map(|(x, y)| FixedPoint::snap(x, y).unwrap());
        let setups = setup_triangles(&[points], FillRule::TopLeft);
        let mut expected = Mask {
            width: SIZE,
            covered: vec![false; (SIZE * SIZE) as usize],
        };
        naive.rasterize(&setups, PixelRect::of_target(SIZE, SIZE), &mut expected);
        ties += usize::from(setups.first().is_some_and(|s| {
            (0..SIZE * SIZE).any(|i| {
                let p = FixedPoint::snap((i % SIZE) as f32 + 0.5, (i / SIZE) as f32 + 0.5).unwrap();
                let e = s.edge_values(p);
                e.iter().any(|&v| v == 0 || v == -1) && e.iter().all(|&v| v >= -1)
            })
        }));
        let vertices = corners.map(|(x, y)| gl::Vertex {
            position: [x, y, 0.5],
            light: 1.0,
        });
        let shape = gl.shape(&vertices, &[0, 1, 2]);
        gl.draw(
            &shape,
            &transform,
            gl::DrawState {
                depth: false,
                cull_back: false,
            },
        );
        let got = gl.coverage();
        gl.delete(shape);
        if got == expected.covered {
            agree += 1;
        } else {
            let differ: Vec<(u32, u32)> = (0..SIZE * SIZE)
                .filter(|&i| got[i as usize] != expected.covered[i as usize])
                .map(|i| (i % SIZE, i / SIZE))
                .collect();
            eprintln!("case {case}: {corners:?}: pixels differ at {differ:?}");
        }
    }
    eprintln!(
        "llvmpipe ({}) and the top-left rule agree on {agree} of 3000 random triangles ({ties} with a pixel centre on an edge)",
        gl.renderer()
    );
    assert_eq!(agree, 3000);
    assert!(ties > 300, "too few ties to test the rule: {ties}");
}

/// rasterlab's fragments and llvmpipe's for `mesh` at 1920x1080, with
/// the benchmarks' camera (azimuth 30 degrees, back faces culled).
fn fragments(gl: &gl::Llvmpipe, mesh: &Mesh) -> (u64, u64) {
    let mut settings = RenderSettings {
        width: 1920,
        height: 1080,
        azimuth: 30.0,
        ..RenderSettings::default()
    };
    settings.pipeline.cull = CullMode::Back;
    let renderer = MeshRenderer::new(mesh, settings).unwrap();
    let mut target = RenderTarget::without_coverage(1920, 1080).unwrap();
    let ours = renderer
        .render_into(triangle_backend("scanline").unwrap(), &mut target)
        .unwrap()
        .work
        .fragments;
    let vertices: Vec<gl::Vertex> = mesh
        .positions
        .iter()
        .map(|p| gl::Vertex {
            position: p.to_array(),
            light: 1.0,
        })
        .collect();
    let indices: Vec<u32> = mesh.triangles.iter().flatten().copied().collect();
    let shape = gl.shape(&vertices, &indices);
    let transform = gl::Llvmpipe::mesh_transform(renderer.transform().mvp.to_cols_array());
    let theirs = gl.fragments(&shape, &transform, true);
    gl.delete(shape);
    (ours, theirs)
}

#[test]
fn llvmpipe_draws_the_dragons_fragments() {
    let Some(gl) = llvmpipe(1920, 1080) else {
        return;
    };
    let mut models = vec![(
        "dragon_vrip_res4".to_string(),
        Ok(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/dragon_vrip_res4.ply.gz")),
    )];
    models.push(("dragon_vrip".to_string(), data::find(data::FULL_DRAGON)));
    for (name, path) in models {
        let path = match path {
            Ok(path) => path,
            Err(skipped) => {
                eprintln!("{name}: {skipped}");
                continue;
            }
        };
        let mesh = Mesh::load(&path).unwrap();
        let (ours, theirs) = fragments(&gl, &mesh);
        eprintln!("{name}: rasterlab {ours} fragments, llvmpipe {theirs}");
        assert!(
            ours.abs_diff(theirs) <= 3,
            "{name}: rasterlab {ours}, llvmpipe {theirs}"
        );
    }
}
