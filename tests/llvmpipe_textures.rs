//! Mesa's llvmpipe draws the textured floor, and rasterlab's samplers are
//! set beside it and beside the ground truth.
//!
//! Both draw `rasterlab::geometry::Floor` at its default 320x200: the same
//! four corners and texture coordinates through the same camera matrix
//! (clip-space y negated for GL, see `benches/support/gl.rs`), and the
//! same mip pyramid: rasterlab's, each level rounded to RGBA8 and
//! uploaded to llvmpipe level by level (`glTexImage2D` per level, no
//! `glGenerateMipmap`), and the rasterlab side samples those very rounded
//! levels, so the box filter and the texels are shared and only the
//! filtering differs. The texture is plain RGBA8, filtered as stored
//! values, no sRGB decoding, as rasterlab filters its texels.
//!
//! Exact agreement is not possible, and not asked for: llvmpipe's
//! filtering of an RGBA8 texture runs in 8-bit fixed point (texel
//! weights and the weight between two levels quantised to 1/256), it
//! takes the level of detail once per 2x2 quad from the quad's
//! first-pixel differences and a fast log2, where rasterlab takes
//! the exact `log2` of each pixel's own (fine) differences in `f32`/`f64`.
//! So the images agree within a stated tolerance, and both are measured
//! against `Floor::ground_truth` (16x16 bilinear samples of level 0 a
//! pixel, box-filtered).
//!
//! Without Mesa each test prints why it is skipped and passes, unless
//! `RASTERLAB_REQUIRE_MESA=1`, where a missing Mesa fails.

// The meshes, masks and fragment counts of the other suites go unused.
#[allow(dead_code)]
#[path = "../benches/support/gl.rs"]
mod gl;

use glam::Vec4;
use rasterlab::geometry::{Floor, SKY};
use rasterlab::raster::{
    to_rgba8, triangle_backends, Anisotropic, Derivatives, Image, LevelMode, Sampler, Texture,
};

/// llvmpipe, or `None` with the reason printed (a failure when
/// `RASTERLAB_REQUIRE_MESA=1`).
fn llvmpipe(width: u32, height: u32) -> Option<gl::Llvmpipe> {
    match gl::Llvmpipe::new(width, height, 1) {
        Ok(llvmpipe) => Some(llvmpipe),
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

/// The floor's pyramid rounded to RGBA8: the levels llvmpipe is given,
/// and the texture rasterlab samples them as.
fn rounded(texture: &Texture) -> (Vec<gl::Level>, Texture) {
    let mut upload = Vec::new();
    let mut levels = Vec::new();
    for level in texture.levels() {
        let bytes: Vec<[u8; 4]> = level.texels().iter().map(|&c| to_rgba8(c)).collect();
        let texels = bytes
            .iter()
            .map(|b| Vec4::from_array(b.map(f32::from)) / 255.0)
            .collect();
        levels.push(Image::new(level.width(), level.height(), texels).unwrap());
        upload.push(gl::Level {
            width: level.width(),
            height: level.height(),
            rgba: bytes.concat(),
        });
    }
    (upload, Texture::from_levels(levels).unwrap())
}

/// The floor drawn by llvmpipe with trilinear filtering and `anisotropy`,
/// RGBA8 row by row.
fn llvmpipe_floor(
    gl: &gl::Llvmpipe,
    floor: &Floor,
    levels: &[gl::Level],
    anisotropy: f32,
) -> Vec<[u8; 4]> {
    let vertices = floor.vertices().map(|(p, uv)| gl::TexturedVertex {
        position: p.to_array(),
        uv: uv.to_array(),
    });
    let indices: Vec<u32> = Floor::TRIANGLES.concat();
    let shape = gl.textured_shape(&vertices, &indices);
    let texture = gl.mipmapped(levels, anisotropy).unwrap();
    let transform = gl::Llvmpipe::mesh_transform(floor.mvp().to_cols_array());
    gl.draw_textured(&shape, &transform, texture, SKY, gl::DrawState::NONE);
    let rgba = gl.rgba();
    gl.delete_texture(texture);
    gl.delete(shape);
    rgba.chunks_exact(4)
        .map(|p| [p[0], p[1], p[2], p[3]])
        .collect()
}

/// How closely two images agree: the share of pixels whose largest
/// channel difference is at most `within`, and the largest difference.
fn agreement(a: &[[u8; 4]], b: &[[u8; 4]], within: u8) -> (f64, u8) {
    let differences: Vec<u8> = a
        .iter()
        .zip(b)
        .map(|(p, q)| (0..4).map(|i| p[i].abs_diff(q[i])).max().unwrap())
        .collect();
    let close = differences.iter().filter(|&&d| d <= within).count();
    (
        close as f64 / differences.len() as f64,
        differences.into_iter().max().unwrap_or(0),
    )
}

/// The ground truth of every pixel the floor covers (16x16 samples).
fn truth(floor: &Floor) -> Vec<Option<Vec4>> {
    let (w, h) = (floor.width(), floor.height());
    (0..w * h)
        .map(|i| floor.ground_truth(i % w, i / w, 16).unwrap())
        .collect()
}

/// An image's RMS and worst error against the truth, over the RGB
/// channels of the pixels that have one, in units of 1/255.
fn error(image: &[[u8; 4]], truth: &[Option<Vec4>]) -> (f64, f64) {
    let (mut sum, mut n, mut worst) = (0.0, 0usize, 0.0f64);
    for (p, t) in image.iter().zip(truth) {
        let Some(t) = t else { continue };
        for c in 0..3 {
            let e = f64::from(p[c]) - f64::from(t[c]) * 255.0;
            sum += e * e;
            n += 1;
            worst = worst.max(e.abs());
        }
    }
    ((sum / n as f64).sqrt(), worst)
}

fn rasterlab_floor(floor: &Floor, sampler: Sampler) -> Vec<[u8; 4]> {
    floor
        .render(triangle_backends()[0], sampler, Derivatives::Quad)
        .0
        .color
}

/// The floor, its texture rounded to RGBA8 as llvmpipe is given it, and
/// the levels to upload.
fn rounded_floor() -> (Floor, Vec<gl::Level>) {
    let (width, height) = Floor::SIZE;
    let floor = Floor::new(width, height).unwrap();
    let (levels, texture) = rounded(floor.texture());
    (floor.with_texture(texture), levels)
}

const TRILINEAR: Sampler = Sampler {
    filter: rasterlab::raster::Filter::Bilinear,
    levels: LevelMode::Linear,
    wrap: rasterlab::raster::Wrap::Repeat,
    anisotropy: 1,
    anisotropic: Anisotropic::Probes,
};

/// Trilinear: 81.6% of the pixels are the same bytes, 95.8% within
/// 1/255 a channel, 99.98% within 4/255, the worst 5/255 (Mesa 22.3.6,
/// LLVM 15). Against the truth both have an RMS error of about 14/255
/// (llvmpipe 14.20, rasterlab 14.34) and the same worst, 99/255, at the
/// horizon, where every isotropic filter blurs the checkerboard to grey
/// while a pixel's true footprint, a long thin sliver, still crosses
/// few squares.
#[test]
fn llvmpipe_draws_the_trilinear_floor_as_rasterlab_does() {
    let Some(gl) = llvmpipe(Floor::SIZE.0, Floor::SIZE.1) else {
        return;
    };
    let (floor, levels) = rounded_floor();
    let theirs = llvmpipe_floor(&gl, &floor, &levels, 1.0);
    let ours = rasterlab_floor(&floor, TRILINEAR);
    let (within_1, worst) = agreement(&ours, &theirs, 1);
    let (within_4, _) = agreement(&ours, &theirs, 4);
    eprintln!(
        "trilinear: {within_1:.4} within 1/255, {within_4:.4} within 4/255, worst {worst}/255"
    );
    assert!(within_1 >= 0.95, "{within_1} of the pixels within 1/255");
    assert!(within_4 >= 0.999, "{within_4} of the pixels within 4/255");
    assert!(worst <= 6, "worst difference {worst}/255");
    let truth = truth(&floor);
    let (their_rms, their_worst) = error(&theirs, &truth);
    let (our_rms, our_worst) = error(&ours, &truth);
    eprintln!("against the truth: llvmpipe RMS {their_rms:.2} worst {their_worst:.1}, rasterlab RMS {our_rms:.2} worst {our_worst:.1} (1/255)");
    for rms in [their_rms, our_rms] {
        assert!((13.0..16.0).contains(&rms), "RMS {rms}/255");
    }
    assert!(
        (their_rms - our_rms).abs() < 0.5,
        "{their_rms} against {our_rms}"
    );
    assert!(
        (their_worst - our_worst).abs() <= 6.0,
        "{their_worst} against {our_worst}"
    );
}

/// 16x anisotropy: llvmpipe's EWA (`lp_build_sample_aniso`) against
/// rasterlab's (`--anisotropic ewa`). Two implementations of the same
/// idea, with their own ellipse, Gaussian width and level choice, so the
/// pictures agree only loosely (65.5% the same bytes, 94.4% within
/// 16/255, the worst 42/255), but both are much closer to the truth than
/// trilinear: RMS 8.96/255 for llvmpipe, 6.92/255 for rasterlab, against
/// about 14/255.
#[test]
fn llvmpipe_and_rasterlab_ewa_both_beat_trilinear() {
    let Some(gl) = llvmpipe(Floor::SIZE.0, Floor::SIZE.1) else {
        return;
    };
    let Some(max) = gl.max_anisotropy() else {
        panic!("llvmpipe (Mesa 22.3 on) offers GL_EXT_texture_filter_anisotropic");
    };
    assert!(max >= 16.0, "llvmpipe offers {max}x anisotropy");
    let (floor, levels) = rounded_floor();
    let theirs = llvmpipe_floor(&gl, &floor, &levels, 16.0);
    let ewa = Sampler {
        anisotropy: 16,
        anisotropic: Anisotropic::Ewa,
        ..TRILINEAR
    };
    let ours = rasterlab_floor(&floor, ewa);
    let (within_16, worst) = agreement(&ours, &theirs, 16);
    eprintln!("EWA 16x: {within_16:.4} within 16/255, worst {worst}/255");
    assert!(within_16 >= 0.9, "{within_16} of the pixels within 16/255");
    assert!(worst <= 64, "worst difference {worst}/255");
    let truth = truth(&floor);
    let trilinear = error(&llvmpipe_floor(&gl, &floor, &levels, 1.0), &truth).0;
    let (their_rms, their_worst) = error(&theirs, &truth);
    let (our_rms, our_worst) = error(&ours, &truth);
    eprintln!("against the truth: llvmpipe RMS {their_rms:.2} worst {their_worst:.1}, rasterlab RMS {our_rms:.2} worst {our_worst:.1}, trilinear RMS {trilinear:.2} (1/255)");
    assert!(
        our_rms < their_rms && their_rms < trilinear * 0.75,
        "RMS: rasterlab's EWA {our_rms}, llvmpipe's {their_rms}, trilinear {trilinear}"
    );
}

/// The `GALLIVM_PERF` options llvmpipe reads once, when gallivm starts:
/// each is measured in a child process (this test's executable, running
/// this test alone with the option set), which draws the trilinear floor
/// and writes its bytes to a file. Measured (share of pixels the same as
/// rasterlab's, within 1/255, worst; RMS against the truth):
///
/// | `GALLIVM_PERF` | same | within 1/255 | worst | RMS |
/// |---|---|---|---|---|
/// | (none) | 81.6% | 95.8% | 5/255 | 14.20/255 |
/// | `no_quad_lod` | 81.6% | 95.8% | 5/255 | 14.20/255 |
/// | `rho_approx` | 78.9% | 88.4% | 48/255 | 13.56/255 |
/// | `brilinear` | 80.3% | 90.3% | 24/255 | 14.57/255 |
#[test]
fn gallivm_perf_options_move_llvmpipe_from_rasterlab() {
    const CHILD: &str = "RASTERLAB_FLOOR_OUTPUT";
    const TEST: &str = "gallivm_perf_options_move_llvmpipe_from_rasterlab";
    if let Some(path) = std::env::var_os(CHILD) {
        let gl = llvmpipe(Floor::SIZE.0, Floor::SIZE.1).expect("llvmpipe, as in the parent");
        let (floor, levels) = rounded_floor();
        std::fs::write(path, llvmpipe_floor(&gl, &floor, &levels, 1.0).concat()).unwrap();
        return;
    }
    let Some(gl) = llvmpipe(Floor::SIZE.0, Floor::SIZE.1) else {
        return;
    };
    let (floor, levels) = rounded_floor();
    let here = llvmpipe_floor(&gl, &floor, &levels, 1.0);
    let ours = rasterlab_floor(&floor, TRILINEAR);
    let truth = truth(&floor);
    let mut plain_image = None;
    let dir = tempfile::tempdir().unwrap();
    let mut figures = Vec::new();
    for option in ["", "no_quad_lod", "rho_approx", "brilinear"] {
        let path = dir.path().join(format!("floor-{option}.rgba"));
        let status = std::process::Command::new(std::env::current_exe().unwrap())
            .args(["--exact", TEST, "--nocapture", "--test-threads", "1"])
            .env(CHILD, &path)
            .env("GALLIVM_PERF", option)
            .status()
            .unwrap();
        assert!(
            status.success(),
            "the child with GALLIVM_PERF={option:?}: {status}"
        );
        let bytes = std::fs::read(&path).unwrap();
        let image: Vec<[u8; 4]> = bytes
            .chunks_exact(4)
            .map(|p| [p[0], p[1], p[2], p[3]])
            .collect();
        assert_eq!(image.len(), here.len(), "GALLIVM_PERF={option:?}");
        let (exact, worst) = agreement(&ours, &image, 0);
        let (within_1, _) = agreement(&ours, &image, 1);
        let (rms, _) = error(&image, &truth);
        let plain_image = plain_image.get_or_insert_with(|| image.clone());
        let (same, _) = agreement(plain_image, &image, 0);
        eprintln!("GALLIVM_PERF={option:?}: against rasterlab {exact:.4} exact, {within_1:.4} within 1/255, worst {worst}/255; truth RMS {rms:.2}/255; {same:.4} as without");
        figures.push((option, exact, within_1, worst, rms, same));
    }
    let [plain, no_quad_lod, rho_approx, brilinear] = figures[..] else {
        unreachable!("four options")
    };
    // This process compares its own image with the children's only when
    // it runs without options too.
    if std::env::var_os("GALLIVM_PERF").is_none_or(|v| v.is_empty()) {
        let (same, _) = agreement(&here, &plain_image.unwrap_or_default(), 0);
        assert_eq!(
            same, 1.0,
            "a child without options draws what this process draws"
        );
    }
    assert_eq!(plain.0, "");
    // `texture()` takes implicit derivatives, whose level of detail
    // llvmpipe computes per quad whatever no_quad_lod says (it applies to
    // explicit derivatives and levels): the very same image.
    assert_eq!(no_quad_lod.5, 1.0, "no_quad_lod changed the floor");
    for (option, _, within_1, worst, ..) in [rho_approx, brilinear] {
        assert!(
            within_1 < plain.2 - 0.03 && worst >= 16,
            "{option}: {within_1} within 1/255 (without: {}), worst {worst}/255",
            plain.2
        );
    }
    // rho_approx's rho, max(|du|, |dv|) over both axes, is at most the
    // true one: lower levels, a sharper and here truer horizon.
    // brilinear's level weights round towards the nearer level: a worse one.
    assert!(
        rho_approx.4 < plain.4,
        "rho_approx RMS {} against {}",
        rho_approx.4,
        plain.4
    );
    assert!(
        brilinear.4 > plain.4,
        "brilinear RMS {} against {}",
        brilinear.4,
        plain.4
    );
}
