//! Mipmapped textures through the stage: a receding checkerboard floor,
//! the plane that aliases in every course, drawn under each pixel filter,
//! level mode, derivative method and anisotropy by every triangle
//! back-end.

use glam::Vec4;
use rasterlab::geometry::{draw, setup_triangles, Floor};
use rasterlab::measure::compare_textures;
use rasterlab::raster::{
    quad_helpers, triangle_backends, Anisotropic, DepthState, Derivatives, FillRule, Filter,
    FixedPoint, FragmentList, Interpolation, LevelMode, Mipmapped, PixelRect, RenderTarget,
    Sampler, Texture, Wrap,
};
use rasterlab::teaching::GridPicture;

const SIZE: (u32, u32) = (96, 64);

/// The bundled receding floor (`render --scene floor`), at 96 x 64.
fn floor() -> rasterlab::geometry::Geometry {
    Floor::new(SIZE.0, SIZE.1).unwrap().geometry().clone()
}

fn checkerboard() -> Texture {
    Floor::checkerboard()
}

/// Under each of the six filter x level combinations, each derivative
/// method and anisotropy 1, 4 and 16, every triangle back-end draws the
/// floor bit for bit as the first: a derivative depends on the triangle
/// and the pixel, never on the walk.
#[test]
fn every_backend_draws_the_mipmapped_floor_alike() {
    let geometry = floor();
    let mut distinct = Vec::new();
    for filter in [Filter::Nearest, Filter::Bilinear] {
        for levels in [LevelMode::Zero, LevelMode::Nearest, LevelMode::Linear] {
            for method in [
                Derivatives::Analytic,
                Derivatives::Quad,
                Derivatives::Forward,
            ] {
                for (anisotropy, anisotropic) in [
                    (1, Anisotropic::Probes),
                    (4, Anisotropic::Probes),
                    (16, Anisotropic::Probes),
                    (8, Anisotropic::Ewa),
                ] {
                    // EWA reads the pyramid; on level 0 alone it is refused.
                    if anisotropic == Anisotropic::Ewa && levels == LevelMode::Zero {
                        continue;
                    }
                    let sampler = Sampler {
                        filter,
                        levels,
                        wrap: Wrap::Repeat,
                        anisotropy,
                        anisotropic,
                    };
                    let shader = Mipmapped::new(
                        checkerboard(),
                        sampler,
                        method,
                        &geometry.setups,
                        &geometry.shaded,
                        true,
                    );
                    let mut first: Option<Vec<[u8; 4]>> = None;
                    for backend in triangle_backends() {
                        let mut target = RenderTarget::new(SIZE.0, SIZE.1).unwrap();
                        draw(
                            &geometry,
                            *backend,
                            &shader,
                            DepthState::DEFAULT,
                            Interpolation::PerspectiveCorrect,
                            &mut target,
                        );
                        match &first {
                            None => first = Some(target.color.clone()),
                            Some(f) => assert!(
                                *f == target.color,
                                "{} differs under {filter} {levels} {method} x{anisotropy} {anisotropic}",
                                backend.name()
                            ),
                        }
                    }
                    distinct.push(first.unwrap());
                }
            }
        }
    }
    // The options do change the picture: mipmapping greys the distance.
    distinct.sort();
    distinct.dedup();
    assert!(distinct.len() > 20, "{} distinct images", distinct.len());
}

/// Towards the horizon the floor's squares shrink below a pixel: level 0
/// alone aliases (neighbouring pixels far apart in colour), trilinear
/// filtering averages them to the checkerboard's mean.
#[test]
fn trilinear_filtering_greys_the_horizon_that_level_zero_aliases() {
    let geometry = floor();
    let render = |levels| {
        let sampler = Sampler {
            levels,
            ..Sampler::default()
        };
        let shader = Mipmapped::new(
            checkerboard(),
            sampler,
            Derivatives::Analytic,
            &geometry.setups,
            &geometry.shaded,
            true,
        );
        let mut target = RenderTarget::new(SIZE.0, SIZE.1).unwrap();
        let backend = triangle_backends()[0];
        draw(
            &geometry,
            backend,
            &shader,
            DepthState::DEFAULT,
            Interpolation::PerspectiveCorrect,
            &mut target,
        );
        target
    };
    // The sum of the colour jumps between horizontal neighbours in the
    // floor's most distant covered rows.
    let jumps = |t: &RenderTarget| {
        let rows: Vec<u32> = (0..SIZE.1)
            .filter(|&y| (0..SIZE.0).all(|x| t.coverage[t.index(x, y)] > 0))
            .take(4)
            .collect();
        assert_eq!(rows.len(), 4);
        let mut sum = 0u64;
        for y in rows {
            for x in 1..SIZE.0 {
                let (a, b) = (t.color[t.index(x - 1, y)], t.color[t.index(x, y)]);
                sum += u64::from(a[2].abs_diff(b[2]));
            }
        }
        sum
    };
    let (aliased, filtered) = (
        jumps(&render(LevelMode::Zero)),
        jumps(&render(LevelMode::Linear)),
    );
    assert!(
        filtered * 3 < aliased,
        "level 0: {aliased}, trilinear: {filtered}"
    );
}

/// Shading in 2x2 quads brings in helper pixels: on the floor's two
/// triangles, the quads they touch hold more pixels than they cover.
#[test]
fn quads_bring_helper_pixels_along_the_edges() {
    let geometry = floor();
    let mut helpers = 0;
    let mut fragments = 0;
    for setup in &geometry.setups {
        let mut list = FragmentList::default();
        triangle_backends()[0].rasterize(
            std::slice::from_ref(setup),
            PixelRect::of_target(SIZE.0, SIZE.1),
            &mut list,
        );
        fragments += list.triangles.len() as u64;
        helpers += quad_helpers(list.triangles.iter().map(|f| (f.x, f.y)));
    }
    assert!(
        helpers > 0 && helpers < fragments / 4,
        "{helpers} helpers, {fragments} fragments"
    );
}

/// The grid picture under quad derivatives (`explain --derivatives quad
/// --picture`): every back-end's picture crosses the same helper pixels,
/// as many as the work counters count for a triangle inside the grid,
/// each in a quad the triangle touches and none a fragment; the trace
/// says how many, and the SVG draws one cross per helper.
#[test]
fn the_grid_picture_crosses_each_quads_helper_pixels() {
    let corners = [(1.0, 1.0), (9.0, 2.0), (3.0, 7.0)];
    let snapped = corners.map(|(x, y)| FixedPoint::snap_f64(x, y).unwrap());
    let mut seen = None;
    for backend in triangle_backends() {
        let picture = GridPicture::of_triangles(*backend, &[corners], FillRule::TopLeft, 11, 9)
            .unwrap()
            .with_quads(*backend, &[snapped], FillRule::TopLeft);
        let helpers = picture.quad_helpers.clone().unwrap();
        let mut list = FragmentList::default();
        let setups = setup_triangles(&[snapped], FillRule::TopLeft);
        backend.rasterize(&setups, PixelRect::of_target(11, 9), &mut list);
        let fragments: Vec<(u32, u32)> = list.triangles.iter().map(|f| (f.x, f.y)).collect();
        assert_eq!(
            helpers.len() as u64,
            quad_helpers(fragments.iter().copied())
        );
        for h in &helpers {
            assert!(!fragments.contains(h), "{h:?} is a fragment");
            let quad = |p: &(u32, u32)| (p.0 / 2, p.1 / 2);
            assert!(fragments.iter().any(|f| quad(f) == quad(h)), "{h:?}");
        }
        let svg = picture.to_svg();
        assert_eq!(svg.matches("class=\"helper\"").count(), helpers.len());
        assert!(svg.contains("helper pixel"));
        match &seen {
            None => seen = Some(helpers),
            Some(first) => assert_eq!(first, &helpers, "{}", backend.name()),
        }
    }
    assert_eq!(seen.unwrap().len(), 16);
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_rasterlab"))
        .args([
            "explain",
            "--backend",
            "scanline",
            "--derivatives",
            "quad",
            "--size",
            "11x9",
        ])
        .args(["1", "1", "9", "2", "3", "7"])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("16 helper pixel(s) beside 24 fragment(s)"),
        "{text}"
    );
    // Other derivative methods are the texture trace's.
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_rasterlab"))
        .args([
            "explain",
            "--backend",
            "scanline",
            "--derivatives",
            "forward",
        ])
        .args(["1", "1", "9", "2", "3", "7"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
}

/// The comparison of `compare --textures` on the 96 x 64 floor: every
/// method's RMS and worst error against the ground truth (the texture over
/// each pixel, 16x16 bilinear samples of level 0, box-filtered).
/// Mipmapping comes closer to it than level 0, anisotropic filtering
/// closer than trilinear, and under each level mode the three derivative
/// methods land near each other. The table is printed
/// (`cargo test --release --test textures -- --nocapture`).
#[test]
fn mipmapping_comes_closer_to_the_ground_truth_than_level_zero() {
    let floor = Floor::new(SIZE.0, SIZE.1).unwrap();
    let c = compare_textures(&floor, 16, None, 1).unwrap();
    eprint!("{c}");
    assert_eq!(c.rows.len(), 38);
    let rms = |name: &str| {
        c.rows
            .iter()
            .find(|r| r.method.to_string() == name)
            .unwrap_or_else(|| panic!("{name}"))
            .rms
    };
    let level0 = rms("bilinear, level 0");
    let trilinear = rms("bilinear, linear levels, analytic");
    let anisotropic = rms("bilinear, linear levels, analytic, 16x");
    let ewa = rms("ewa, linear levels, analytic, 16x");
    assert!(ewa < trilinear, "EWA 16x {ewa}, trilinear {trilinear}");
    assert!(
        trilinear < level0,
        "trilinear {trilinear}, level 0 {level0}"
    );
    assert!(
        anisotropic < trilinear,
        "16x {anisotropic}, trilinear {trilinear}"
    );
    for d in ["quad", "forward"] {
        let other = rms(&format!("bilinear, linear levels, {d}"));
        assert!(
            (other - trilinear).abs() < 0.02,
            "{d}: {other}, analytic {trilinear}"
        );
    }
}

/// The ground truth is itself an estimate: on a 32 x 12 crop of the
/// 160 x 100 floor just below the horizon, where a pixel's square spans
/// the most texels, 32x32 samples a pixel instead of 16x16 move every
/// method's RMS and worst error by the bounds asserted here (docs/teaching.md
/// quotes the figures this prints).
#[test]
fn the_ground_truth_moves_little_from_16_to_32_samples_a_side() {
    let floor = Floor::new(160, 100).unwrap();
    let top = (0..100)
        .find(|&y| (0..160).all(|x| floor.uv_at(x, y).is_some()))
        .unwrap();
    let crop = PixelRect {
        x0: 64,
        y0: i64::from(top),
        x1: 95,
        y1: i64::from(top) + 11,
    };
    let c16 = compare_textures(&floor, 16, Some(crop), 1).unwrap();
    let c32 = compare_textures(&floor, 32, Some(crop), 1).unwrap();
    assert_eq!(c16.pixels, 32 * 12);
    let (mut rms_move, mut worst_move, mut largest) = (0.0f64, 0.0f64, 0.0f64);
    for (a, b) in c16.rows.iter().zip(&c32.rows) {
        rms_move = rms_move.max((a.rms - b.rms).abs());
        worst_move = worst_move.max((a.worst - b.worst).abs());
        largest = largest.max(a.rms);
    }
    eprintln!(
        "rows {top} to {}: from 16x16 to 32x32 samples, RMS moves at most {rms_move:.4} \
         (the largest RMS is {largest:.4}), the worst error at most {worst_move:.4}",
        top + 11
    );
    assert!(rms_move < 0.01, "{rms_move}");
    assert!(worst_move < 0.05, "{worst_move}");
}

/// `render --scene floor`: the bundled receding floor at 320 x 200, level
/// 0 by default and trilinear with `--mip linear`; options it cannot take
/// are refused by name, and EWA on level 0 alone with the reason.
#[test]
fn the_floor_renders_from_the_command_line() {
    let dir = tempfile::tempdir().unwrap();
    let run = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_rasterlab"))
            .args(["render", "--scene", "floor"])
            .args(args)
            .current_dir(dir.path())
            .output()
            .unwrap()
    };
    for (file, mip) in [("zero.png", "zero"), ("linear.png", "linear")] {
        let out = run(&["--mip", mip, "--derivatives", "quad", "--out", file]);
        assert!(out.status.success(), "{out:?}");
    }
    let zero = image::open(dir.path().join("zero.png")).unwrap().to_rgba8();
    let linear = image::open(dir.path().join("linear.png"))
        .unwrap()
        .to_rgba8();
    assert_eq!(zero.dimensions(), (320, 200));
    assert_ne!(zero, linear);
    let refused = run(&["--zoom", "2", "--out", "z.png"]);
    assert!(!refused.status.success());
    let why = String::from_utf8_lossy(&refused.stderr);
    assert!(why.contains("--zoom") && why.contains("--mip"), "{why}");
    let ewa = run(&["--anisotropic", "ewa", "--out", "e.png"]);
    let why = String::from_utf8_lossy(&ewa.stderr);
    assert!(
        !ewa.status.success() && why.contains("--mip nearest or linear"),
        "{why}"
    );
}

/// `render --shading texture --mip linear --anisotropy 4 --derivatives
/// quad` on the bundled bunny: every back-end draws the same frame, which
/// differs from level 0's; a multisampled one is refused, not drawn at
/// level 0 silently.
#[test]
fn a_mipmapped_mesh_is_the_same_frame_from_every_backend() {
    use rasterlab::geometry::{Mesh, MeshRenderer, RenderSettings, Shading};
    use rasterlab::raster::{MultisampleTarget, SamplePattern};
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/bunny.ply");
    let mesh = Mesh::load(&path).unwrap();
    let settings = RenderSettings {
        width: 160,
        height: 120,
        zoom: 3.0,
        shading: Shading::Texture,
        mip: LevelMode::Linear,
        anisotropy: 4,
        derivatives: Derivatives::Quad,
        ..RenderSettings::default()
    };
    let renderer = MeshRenderer::new(&mesh, settings).unwrap();
    let first = renderer.render(triangle_backends()[0]).unwrap().target;
    for backend in triangle_backends() {
        let frame = renderer.render(*backend).unwrap().target;
        assert!(frame.color == first.color, "{}", backend.name());
    }
    let level0 = RenderSettings {
        mip: LevelMode::Zero,
        anisotropy: 1,
        ..settings
    };
    let plain = MeshRenderer::new(&mesh, level0).unwrap();
    assert!(plain.render(triangle_backends()[0]).unwrap().target.color != first.color);
    let mut msaa = MultisampleTarget::new(160, 120, SamplePattern::standard(4).unwrap()).unwrap();
    let refused = renderer.render_multisampled_into(triangle_backends()[0], &mut msaa);
    assert!(refused.unwrap_err().to_string().contains("--msaa"));
    let bad = RenderSettings {
        anisotropy: 17,
        ..settings
    };
    assert!(MeshRenderer::new(&mesh, bad).is_err());
}

/// `render --texture FILE.png`: an image file becomes a texture, channel
/// by channel `c / 255`; a missing file, a file that is no image and an
/// image too wide are errors naming the problem.
#[test]
fn textures_load_from_png_files_or_say_why_not() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.png");
    let mut png = image::RgbaImage::new(4, 2);
    png.put_pixel(3, 1, image::Rgba([255, 51, 0, 255]));
    png.save(&path).unwrap();
    let texture = Texture::load(&path).unwrap();
    assert_eq!(
        (texture.width(), texture.height(), texture.levels().len()),
        (4, 2, 3)
    );
    assert_eq!(
        texture.levels()[0].texel(3, 1),
        Vec4::new(1.0, 0.2, 0.0, 1.0)
    );
    let missing = Texture::load(&dir.path().join("none.png")).unwrap_err();
    assert!(missing.to_string().contains("none.png"), "{missing}");
    let text = dir.path().join("not.png");
    std::fs::write(&text, "not an image").unwrap();
    let garbage = Texture::load(&text).unwrap_err();
    assert!(garbage.to_string().contains("not.png"), "{garbage}");
    let wide = dir.path().join("wide.png");
    image::GrayImage::new(16385, 1).save(&wide).unwrap();
    let refused = Texture::load(&wide).unwrap_err().to_string();
    assert!(refused.contains("longer than 16384"), "{refused}");
}

/// Helper pixels in the work counters: a textured frame whose derivatives
/// are taken in quads counts them, the same on every back-end; with
/// analytic derivatives there are none.
#[test]
fn quad_frames_count_their_helper_pixels() {
    use rasterlab::geometry::{Mesh, MeshRenderer, RenderSettings, Shading};
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/bunny.ply");
    let mesh = Mesh::load(&path).unwrap();
    let settings = RenderSettings {
        width: 160,
        height: 120,
        shading: Shading::Texture,
        mip: LevelMode::Linear,
        derivatives: Derivatives::Quad,
        ..RenderSettings::default()
    };
    let quad = MeshRenderer::new(&mesh, settings).unwrap();
    let first = quad.render(triangle_backends()[0]).unwrap().stats.work;
    assert!(
        first.helpers > 0 && first.helpers < 3 * first.fragments,
        "{first:?}"
    );
    assert!(first.helper_share() > 0.0 && first.helper_share() < 0.75);
    for backend in triangle_backends() {
        let work = quad.render(*backend).unwrap().stats.work;
        assert_eq!(work.helpers, first.helpers, "{}", backend.name());
    }
    let analytic = RenderSettings {
        derivatives: Derivatives::Analytic,
        ..settings
    };
    let plain = MeshRenderer::new(&mesh, analytic).unwrap();
    assert_eq!(
        plain
            .render(triangle_backends()[0])
            .unwrap()
            .stats
            .work
            .helpers,
        0
    );
}

/// `explain --backend texture X Y`: the trace's colour is the one the
/// floor's frame stores at the pixel (within one step of 255: the trace
/// takes the coordinate from the planes in f64, the stage interpolates
/// it in f32); a pixel of the sky is refused with the reason.
#[test]
fn the_texture_trace_ends_at_the_stored_colour() {
    use rasterlab::teaching::trace_texture;
    let floor = Floor::new(160, 100).unwrap();
    for (sampler, method) in [
        (Sampler::default(), Derivatives::Analytic),
        (
            Sampler {
                filter: Filter::Nearest,
                levels: LevelMode::Nearest,
                ..Sampler::default()
            },
            Derivatives::Forward,
        ),
        (
            Sampler {
                levels: LevelMode::Linear,
                ..Sampler::default()
            },
            Derivatives::Quad,
        ),
        (
            Sampler {
                levels: LevelMode::Linear,
                anisotropy: 8,
                ..Sampler::default()
            },
            Derivatives::Quad,
        ),
        (
            Sampler {
                levels: LevelMode::Linear,
                anisotropy: 8,
                anisotropic: Anisotropic::Ewa,
                ..Sampler::default()
            },
            Derivatives::Analytic,
        ),
    ] {
        for pixel in [(80, 60), (17, 99), (131, 50)] {
            let text = trace_texture(&floor, pixel, sampler, method).unwrap();
            let last = text.lines().last().unwrap();
            let numbers = |part: &str| -> Vec<i32> {
                part.split(|c: char| !c.is_ascii_digit())
                    .filter(|s| !s.is_empty())
                    .map(|s| s.parse().unwrap())
                    .collect()
            };
            let (traced, stored) = last.split_once("stored by the frame").unwrap();
            let traced = numbers(traced.rsplit_once("rgba8").unwrap().1);
            let stored = numbers(stored);
            assert_eq!(traced.len(), 4, "{last}");
            for (a, b) in traced.iter().zip(&stored) {
                assert!((a - b).abs() <= 1, "{text}");
            }
        }
    }
    let sky = trace_texture(&floor, (80, 2), Sampler::default(), Derivatives::Quad);
    assert!(sky.unwrap_err().to_string().contains("below the horizon"));
    // A pixel off the picture is named as such, not as sky.
    let off = trace_texture(&floor, (999, 999), Sampler::default(), Derivatives::Quad);
    let why = off.unwrap_err().to_string();
    assert!(
        why.contains("outside the floor's") && !why.contains("horizon"),
        "{why}"
    );
}

/// `compare --textures`: a ground truth of no samples is refused before
/// anything is written; a small run writes its chart and prints every
/// method's row.
#[test]
fn compare_textures_writes_its_chart_or_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let compare = |truth: &str, out: &str| {
        std::process::Command::new(env!("CARGO_BIN_EXE_rasterlab"))
            .args(["compare", "--textures", "--size", "48x32", "--samples", "1"])
            .args(["--truth", truth, "--out", out])
            .current_dir(dir.path())
            .output()
            .unwrap()
    };
    let refused = compare("0", "none");
    let why = String::from_utf8_lossy(&refused.stderr);
    assert!(
        !refused.status.success() && why.contains("1 to 256"),
        "{why}"
    );
    assert!(!dir.path().join("none").exists());
    let ran = compare("4", "out");
    assert!(ran.status.success(), "{ran:?}");
    let table = String::from_utf8_lossy(&ran.stdout);
    let rows = table
        .lines()
        .filter(|l| {
            ["nearest, ", "bilinear, ", "ewa, "]
                .iter()
                .any(|m| l.starts_with(m))
        })
        .count();
    assert_eq!(rows, 38, "{table}");
    assert!(dir.path().join("out/textures.svg").exists());
    // An hour's work or more is refused with an estimate (exit 4).
    let huge = std::process::Command::new(env!("CARGO_BIN_EXE_rasterlab"))
        .args([
            "compare",
            "--textures",
            "--size",
            "16384x16384",
            "--samples",
            "1",
        ])
        .current_dir(dir.path())
        .output()
        .unwrap();
    let why = String::from_utf8_lossy(&huge.stderr);
    assert_eq!(huge.status.code(), Some(4), "{why}");
    assert!(why.contains("hours") && why.contains("--size"), "{why}");
}
