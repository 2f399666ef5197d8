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
//! * llvmpipe through a viewport of 16,384 px around a 64x64 framebuffer
//!   (`glViewport(-8192, -8192, 16384, 16384)`, as `peer_adapters
//!   opengl-wide` draws), so that GL clips nothing within 8,192 px and far
//!   vertices reach the rasterizer whole: a triangle whose bounding box
//!   reaches only GL's first 64x64 tile (all of it at negative window
//!   coordinates but that corner) loses pixels once its far edge's length
//!   times its distance passes about 2^23 px². In GL's window coordinates
//!   `10 10 -3000 10 10 -3000` draws nothing where the rules draw 100
//!   pixels (through a viewport the framebuffer's size, which clips the
//!   triangle first, llvmpipe draws them all); with the screen's y flipped
//!   into GL's window (the adapter's way, the bottom-left rule) its mirror
//!   image `10 54 -3000 54 10 3064` does. And the check's `overflow`
//!   family catches it: through the flip, the check fails on an overflow
//!   case, shrunk to at most two triangles.
//!
//! * Multisampling, in an OpenGL 4.0 context: llvmpipe's 4 sample
//!   positions (`glGetMultisamplefv`) are the standard pattern's, and
//!   the mask of every pixel of 500 random triangles, read from
//!   `gl_SampleMaskIn` and from the samples written, is rasterlab's
//!   (`rasterlab::raster::masks_of`): on the standard pattern under the
//!   top-left rule with GL's window y as rasterlab's y, and on the pattern
//!   mirrored in y under the bottom-left rule through the adapters' flip.
//!
//! Without Mesa (`libEGL.so.1`, Mesa's EGL and DRI drivers) each test
//! prints why it is skipped and passes, unless `RASTERLAB_REQUIRE_MESA=1`
//! (set by `.ci/run`, which installs Mesa), where a missing Mesa fails.

#[path = "../benches/support/gl.rs"]
mod gl;

use rasterlab::check;
use rasterlab::check::{Case, CheckOptions, Fragment, Property, SubjectError, Verdict};
use rasterlab::geometry::{setup_triangles, CullMode, Mesh, MeshRenderer, RenderSettings};
use rasterlab::measure::{find, FULL_DRAGON};
use rasterlab::raster::{
    masks_of, triangle_backend, FillRule, FixedPoint, FragmentSink, LineFragment, PixelRect,
    RenderTarget, SamplePattern, TriangleFragment,
};

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
        gl.draw(&shape, &transform, gl::DrawState::NONE);
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

/// llvmpipe multisampling against rasterlab's masks: with 4 samples
/// (llvmpipe's `GL_MAX_SAMPLES`; a 2-sample target is given its 4-sample
/// positions), 500 random triangles on a
/// 32x32 target, vertices on grids of 1/2, 1/16 and 1/256 px (so samples
/// fall on edges), each drawn alone. Mapped as the first test maps them
/// (GL's window y is rasterlab's y), every pixel's mask, as the fragment
/// shader sees it (`gl_SampleMaskIn`) and as the samples written show it,
/// is rasterlab's on the standard pattern under the top-left rule; with
/// GL's window y running up from rasterlab's bottom row (the adapters'
/// way), rasterlab's on the pattern mirrored in y under the bottom-left
/// rule. `glGetMultisamplefv` gives the standard table's positions.
#[test]
fn llvmpipe_multisamples_on_the_standard_pattern() {
    const SIZE: u32 = 32;
    for samples in [4] {
        let reader = match gl::MaskReader::new(SIZE, SIZE, samples) {
            Ok(reader) => reader,
            Err(reason) => {
                assert!(
                    std::env::var("RASTERLAB_REQUIRE_MESA").as_deref() != Ok("1"),
                    "RASTERLAB_REQUIRE_MESA=1 but llvmpipe multisampling is unavailable: {reason}"
                );
                eprintln!("skipped: llvmpipe multisampling unavailable: {reason}");
                return;
            }
        };
        let standard = SamplePattern::standard(samples as u32).unwrap();
        for i in 0..samples as usize {
            let (x, y) = standard.offset(i);
            let (gx, gy) = reader.sample_position(i as u32);
            assert_eq!(
                (gx, gy),
                (0.5 + f32::from(x) / 16.0, 0.5 + f32::from(y) / 16.0),
                "{samples} samples: sample {i}'s position"
            );
        }
        let naive = triangle_backend("naive").unwrap();
        let mut rng = fastrand::Rng::with_seed(11);
        let (mut partial, mut ties) = (0, 0);
        for case in 0..500 {
            let steps = [128, 16, 1][case % 3];
            let mut corner = || {
                let k = |rng: &mut fastrand::Rng| rng.i32(0..=SIZE as i32 * 256);
                let (x, y) = (k(&mut rng) / steps * steps, k(&mut rng) / steps * steps);
                (x as f32 / 256.0, y as f32 / 256.0)
            };
            let corners = [corner(), corner(), corner()];
            let points = corners.map(|(x, y)| FixedPoint::snap(x, y).unwrap());
            for flipped in [false, true] {
                let (rule, pattern) = if flipped {
                    (FillRule::BottomLeft, standard.mirrored_y())
                } else {
                    (FillRule::TopLeft, standard)
                };
                let setups = setup_triangles(&[points], rule);
                let mut expected = vec![0u32; (SIZE * SIZE) as usize];
                for m in masks_of(naive, &setups, PixelRect::of_target(SIZE, SIZE), &pattern) {
                    expected[(m.y as u32 * SIZE + m.x as u32) as usize] = m.mask;
                }
                let window = corners.map(|(x, y)| {
                    if flipped {
                        (x, SIZE as f32 - y)
                    } else {
                        (x, y)
                    }
                });
                let got = reader.masks(window);
                for (i, &(written, seen)) in got.iter().enumerate() {
                    let (x, row) = (i as u32 % SIZE, i as u32 / SIZE);
                    let y = if flipped { SIZE - 1 - row } else { row };
                    let want = expected[(y * SIZE + x) as usize];
                    assert_eq!(
                        (written, seen),
                        (want, want),
                        "{samples} samples, case {case} {corners:?}, flipped {flipped}: pixel ({x}, {y})"
                    );
                    partial += usize::from(want != 0 && want != standard.full_mask());
                }
            }
            ties += usize::from(setups_have_a_sample_on_an_edge(points, &standard));
        }
        eprintln!(
            "llvmpipe ({}, {samples} samples): the masks of 500 random triangles, both ways up, are rasterlab's ({partial} partial masks, {ties} triangles with a sample on an edge)",
            reader.renderer()
        );
        assert!(ties > 50, "too few ties to test the rule: {ties}");
    }
}

/// Whether some sample of the pattern lies exactly on an edge of the
/// triangle (within the target of the multisampling test).
fn setups_have_a_sample_on_an_edge(points: [FixedPoint; 3], pattern: &SamplePattern) -> bool {
    let Some(s) = setup_triangles(&[points], FillRule::TopLeft)
        .first()
        .copied()
    else {
        return false;
    };
    (0..32i64).any(|y| {
        (0..32i64).any(|x| {
            (0..pattern.count() as usize).any(|i| {
                let (px, py) = pattern.sample_point(x, y, i);
                let e = s.edges.map(|e| e.eval_raw(px, py));
                e.contains(&0) && e.iter().all(|&v| v >= 0)
            })
        })
    })
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
    models.push(("dragon_vrip".to_string(), find(FULL_DRAGON)));
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

/// llvmpipe on a 64x64 framebuffer holding the target in its bottom-left
/// corner, through a square viewport: that of `peer_adapters
/// opengl-wide` (16,384 px centred on GL's window origin) or one the
/// framebuffer's size, where GL clips at its edges. With `flip`, the
/// adapter's y flip: the screen point `(x, y)` of a `W x H` target is
/// GL's `(x, H - y)`, the screen's pixel `(i, j)` GL's `(i, H - 1 - j)`,
/// and llvmpipe's top-left rule the screen's bottom-left. Without, GL's
/// window coordinates are the screen's, as in the first test.
struct Window {
    gl: gl::Llvmpipe,
    transform: [f32; 16],
    flip: bool,
}

/// The framebuffer's side: one llvmpipe tile, more than the check's
/// targets (at most 40x40).
const WINDOW_SIDE: u32 = 64;

impl Window {
    /// With the viewport `(origin, origin, side, side)`, `side` a power of
    /// two; `None` when Mesa is missing (see [`llvmpipe`]).
    fn new(origin: i32, side: i32, flip: bool) -> Option<Window> {
        let gl = llvmpipe(WINDOW_SIDE, WINDOW_SIDE)?;
        set_viewport(origin, side);
        // x_ndc = (x_window - origin) * 2 / side - 1, exact in f32: a power
        // of two and a constant, 0 for the wide viewport.
        let (k, t) = (
            2.0 / side as f32,
            -(2.0 * origin as f32 / side as f32 + 1.0),
        );
        let transform = [
            k, 0.0, 0.0, 0.0, //
            0.0, k, 0.0, 0.0, //
            0.0, 0.0, 2.0, 0.0, //
            t, t, -1.0, 1.0,
        ];
        Some(Window {
            gl,
            transform,
            flip,
        })
    }

    /// `peer_adapters opengl-wide`'s viewport: `glViewport(-8192, -8192,
    /// 16384, 16384)`.
    fn wide(flip: bool) -> Option<Window> {
        Window::new(-8192, 16384, flip)
    }

    /// The fill rule llvmpipe follows in the screen's coordinates.
    fn rule(&self) -> FillRule {
        if self.flip {
            FillRule::BottomLeft
        } else {
            FillRule::TopLeft
        }
    }

    /// The fragments of `case`, each triangle drawn alone.
    fn draw(&self, case: &Case) -> Vec<Fragment> {
        let (w, h) = (case.width, case.height);
        assert!(w <= WINDOW_SIDE && h <= WINDOW_SIDE, "a {w}x{h} target");
        let mut out = Vec::new();
        for (id, t) in case.triangles.iter().enumerate() {
            let vertices = t.map(|(x, y)| gl::Vertex {
                // Exact in f32 on the 1/256 grid within the guard band.
                position: [
                    x as f32,
                    if self.flip {
                        h as f32 - y as f32
                    } else {
                        y as f32
                    },
                    0.5,
                ],
                light: 1.0,
            });
            let shape = self.gl.shape(&vertices, &[0, 1, 2]);
            self.gl.draw(&shape, &self.transform, gl::DrawState::NONE);
            let coverage = self.gl.coverage();
            self.gl.delete(shape);
            for y in 0..h {
                let row = if self.flip { h - 1 - y } else { y };
                for x in 0..w {
                    if coverage[(row * WINDOW_SIDE + x) as usize] {
                        out.push(Fragment {
                            x: i64::from(x),
                            y: i64::from(y),
                            id: id as u32,
                            mask: 0,
                        });
                    }
                }
            }
        }
        out.sort();
        out
    }
}

/// Sets the current context's viewport to `(origin, origin, side, side)`,
/// after checking `GL_MAX_VIEWPORT_DIMS` allows it, and reads it back.
/// The support module keeps its GL function table to itself, so this one
/// is looked up again through EGL (the same driver, the context current
/// on this thread).
fn set_viewport(origin: i32, side: i32) {
    use glow::HasContext;
    // SAFETY: libEGL is loaded already (an llvmpipe context exists).
    let egl = unsafe { khronos_egl::DynamicInstance::<khronos_egl::EGL1_5>::load_required() }
        .expect("libEGL.so.1, loaded already");
    // SAFETY: an llvmpipe context is current on this thread.
    let gl = unsafe {
        glow::Context::from_loader_function(|name| {
            egl.get_proc_address(name)
                .map_or(std::ptr::null(), |f| f as *const std::ffi::c_void)
        })
    };
    // SAFETY: plain GL calls on the current context.
    unsafe {
        let mut dims = [0i32; 2];
        gl.get_parameter_i32_slice(glow::MAX_VIEWPORT_DIMS, &mut dims);
        assert!(
            dims[0] >= side && dims[1] >= side,
            "GL_MAX_VIEWPORT_DIMS {dims:?}"
        );
        gl.viewport(origin, origin, side, side);
        let mut got = [0i32; 4];
        gl.get_parameter_i32_slice(glow::VIEWPORT, &mut got);
        assert_eq!(got, [origin, origin, side, side], "the viewport GL kept");
    }
}

/// The rules' fragments of `case` under `rule`, sorted.
fn exact(rule: FillRule, case: &Case) -> Vec<Fragment> {
    let mut fragments = check::reference(Property::Exact(rule), case);
    fragments.sort();
    fragments
}

#[test]
fn llvmpipe_drops_a_far_corner_in_its_first_tile_through_a_wide_viewport() {
    let windows = (
        Window::wide(false),
        Window::new(0, WINDOW_SIDE as i32, false),
        Window::wide(true),
    );
    let (Some(wide), Some(clipping), Some(flipped)) = windows else {
        return;
    };
    let corner = Case::from_text("# size 64x64\n10 10 -3000 10 10 -3000\n").unwrap();
    let mirrored = Case::from_text("# size 64x64\n10 54 -3000 54 10 3064\n").unwrap();
    // GL's window coordinates: the corner at GL's origin, llvmpipe's
    // first tile.
    let answer = exact(wide.rule(), &corner);
    assert_eq!(answer.len(), 100, "the rules draw the 10x10 corner");
    assert_eq!(
        clipping.draw(&corner),
        answer,
        "clipped at the framebuffer first, llvmpipe draws the corner"
    );
    let drawn = wide.draw(&corner);
    eprintln!(
        "10 10 -3000 10 10 -3000 on 64x64 in GL's window coordinates: the rules draw {}, llvmpipe through a wide viewport {}",
        answer.len(),
        drawn.len()
    );
    assert!(
        drawn.is_empty(),
        "llvmpipe drew {drawn:?}: fixed in this Mesa?"
    );
    // Through the adapter's y flip the same corner is GL's top-left,
    // another tile's reach, and is drawn; its mirror image is the one lost.
    assert_eq!(flipped.draw(&corner), exact(flipped.rule(), &corner));
    assert_eq!(exact(flipped.rule(), &mirrored).len(), 100);
    let drawn = flipped.draw(&mirrored);
    assert!(
        drawn.is_empty(),
        "llvmpipe drew {drawn:?}: fixed in this Mesa?"
    );
}

#[test]
fn the_overflow_family_catches_llvmpipe_through_a_wide_viewport() {
    let Some(wide) = Window::wide(true) else {
        return;
    };
    let property = Property::Exact(wide.rule());
    let options = CheckOptions {
        cases: 1000,
        ..CheckOptions::new(property)
    };
    let mut subject = |case: &Case| -> Result<Vec<Fragment>, SubjectError> { Ok(wide.draw(case)) };
    let verdict = check::check(&options, &mut subject).unwrap();
    eprintln!("{verdict}");
    let Verdict::Fail {
        case_index,
        finding,
        ..
    } = verdict
    else {
        panic!(
            "llvmpipe passed {} cases through a wide viewport",
            options.cases
        );
    };
    let shrunk = &finding.case;
    eprintln!(
        "case {case_index}, shrunk:\n{}the rules draw {} fragments, llvmpipe {}",
        shrunk.to_text(),
        exact(wide.rule(), shrunk).len(),
        wide.draw(shrunk).len()
    );
    assert_eq!(
        check::family(property, case_index),
        "overflow",
        "the first failure comes from the overflow family"
    );
    assert!(
        shrunk.triangles.len() <= 2,
        "shrunk to {} triangles",
        shrunk.triangles.len()
    );
}
