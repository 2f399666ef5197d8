//! The multisampled fragment stage: with one sample it is the one-sample
//! stage bit for bit; with 4, 8 and 16 every back-end gives the same
//! samples and the same resolved image; each sample keeps the colour of
//! the nearest triangle covering it (depth tested per sample, ties to the
//! first drawn); shading happens once per pixel, at its centre.

mod common;

use common::*;
use glam::Vec4;
use proptest::prelude::*;
use rasterlab::geometry::{draw, setup_triangles, Geometry};
use rasterlab::raster::{
    draw_multisampled, linear_to_srgb8, reference_masks, srgb8_to_linear, triangle_backends, Blend,
    DepthState, FillRule, FixedPoint, Flat, FragmentShader, Gouraud, Interpolation, MixSpace,
    MultisampleTarget, RenderTarget, SamplePattern, ShadedVertex, SAMPLE_COUNTS,
};

const LERP: Interpolation = Interpolation::PerspectiveCorrect;

/// A vertex of colour `rgb` at depth `z`.
fn vertex(z: f32, rgb: [f32; 3]) -> ShadedVertex {
    ShadedVertex::flat(z, Vec4::new(rgb[0], rgb[1], rgb[2], 1.0))
}

/// Triangles with a colour and depth per vertex, 1 to 6 of them.
fn shaded_soup() -> impl Strategy<Value = Vec<([FixedPoint; 3], [ShadedVertex; 3])>> {
    let channel = 0.0f32..=1.0;
    let v = (0.05f32..0.95, [channel.clone(), channel.clone(), channel])
        .prop_map(|(z, c)| vertex(z, c));
    let p = point(-4.0, SIZE as f32 + 4.0, Some(1.0 / 16.0));
    proptest::collection::vec(
        ([p.clone(), p.clone(), p], [v.clone(), v.clone(), v]),
        1..=6,
    )
}

/// The set-ups of `soup` under the top-left rule and their stage data.
fn setup(soup: &[([FixedPoint; 3], [ShadedVertex; 3])]) -> Geometry {
    let triangles: Vec<[FixedPoint; 3]> = soup.iter().map(|(t, _)| *t).collect();
    let vertices: Vec<[ShadedVertex; 3]> = soup.iter().map(|(_, v)| *v).collect();
    Geometry::of_screen_triangles(setup_triangles(&triangles, FillRule::TopLeft), &vertices)
}

/// `geometry` drawn with `shader` by every back-end on `pattern`: the
/// first back-end's target, after checking the others give the same.
fn multisampled(
    geometry: &Geometry,
    shader: &dyn FragmentShader,
    pattern: SamplePattern,
) -> Result<MultisampleTarget, String> {
    let mut first: Option<MultisampleTarget> = None;
    for b in triangle_backends() {
        let mut target = MultisampleTarget::new(SIZE, SIZE, pattern).unwrap();
        let (setups, data) = (&geometry.setups, &geometry.shaded);
        draw_multisampled(
            setups,
            data,
            *b,
            shader,
            (DepthState::DEFAULT, Blend::REPLACE),
            LERP,
            &mut target,
        );
        match &first {
            None => first = Some(target),
            Some(f) if *f != target => {
                return Err(format!(
                    "{} draws other samples than the first back-end",
                    b.name()
                ))
            }
            Some(_) => {}
        }
    }
    Ok(first.expect("there are back-ends"))
}

proptest! {
    #![proptest_config(crate::common::proptest_config(200, "tests/proptest-regressions/multisample_stage.txt"))]

    /// One sample: the resolved colour and depth buffers are those of the
    /// one-sample stage, bit for bit, for every back-end.
    #[test]
    fn one_sample_is_the_one_sample_stage(soup in shaded_soup()) {
        let geometry = setup(&soup);
        let target = multisampled(&geometry, &Gouraud, SamplePattern::standard(1).unwrap())
            .map_err(TestCaseError::fail)?;
        let mut one = RenderTarget::new(SIZE, SIZE).unwrap();
        draw(&geometry, triangle_backends()[0], &Gouraud, DepthState::DEFAULT, LERP, &mut one);
        let resolved = target.resolve();
        prop_assert_eq!(&resolved.color, &one.color);
        prop_assert_eq!(&resolved.depth, &one.depth);
        prop_assert_eq!(&resolved.coverage, &one.coverage);
    }

    /// Constant depth and one colour per triangle: each sample holds the
    /// colour of the nearest triangle covering it by the reference masks
    /// (the first drawn among equals, as `less` keeps it), or the clear
    /// colour; every back-end gives the same samples.
    #[test]
    fn each_sample_keeps_its_nearest_triangle(
        soup in shaded_soup(),
        count in proptest::sample::select(&SAMPLE_COUNTS[1..]),
        mirrored in any::<bool>(),
    ) {
        // Flat shading: the first vertex's colour, exactly (Gouraud
        // weights extrapolated to a centre outside the triangle need not
        // sum to exactly 1).
        let flat: Vec<_> = soup.iter().map(|(t, v)| (*t, [v[0]; 3])).collect();
        let geometry = setup(&flat);
        let mut pattern = SamplePattern::standard(count).unwrap();
        if mirrored {
            pattern = pattern.mirrored_y();
        }
        let target = multisampled(&geometry, &Flat, pattern).map_err(TestCaseError::fail)?;
        let n = count as usize;
        let mut expected = vec![(RenderTarget::FAR_DEPTH, RenderTarget::BLACK); (SIZE * SIZE) as usize * n];
        for m in reference_masks(&geometry.setups, viewport(), &pattern) {
            let v = flat[m.triangle as usize].1[0];
            let colour = rasterlab::raster::to_rgba8(v.varyings.color);

            for i in 0..n {
                let slot = &mut expected[(m.y as usize * SIZE as usize + m.x as usize) * n + i];
                if m.mask & (1 << i) != 0 && v.depth < slot.0 {
                    *slot = (v.depth, colour);
                }
            }
        }
        for (k, (depth, colour)) in expected.iter().enumerate() {
            prop_assert_eq!(target.color[k], *colour, "sample {} of pixel {}", k % n, k / n);
            prop_assert_eq!(target.depth[k], *depth, "sample {} of pixel {}", k % n, k / n);
        }
    }
}

/// A Gouraud triangle alone: a pixel whose centre it covers has, in each
/// covered sample, the colour the one-sample stage gives the pixel, and
/// the clear colour in the others; the resolve is the mean, rounded.
#[test]
fn shading_is_once_per_pixel_at_its_centre() {
    let p = |x: f32, y: f32| FixedPoint::snap(x, y).unwrap();
    let triangle = [p(1.3, 0.7), p(33.1, 9.4), p(7.9, 36.2)];
    let colours = [[1.0, 0.2, 0.0], [0.0, 0.9, 0.3], [0.1, 0.0, 1.0]];
    let soup = [(triangle, [0, 1, 2].map(|i| vertex(0.5, colours[i])))];
    let geometry = setup(&soup);
    let mut one = RenderTarget::without_coverage(SIZE, SIZE).unwrap();
    draw(
        &geometry,
        triangle_backends()[0],
        &Gouraud,
        DepthState::DEFAULT,
        LERP,
        &mut one,
    );
    let pattern = SamplePattern::standard(8).unwrap();
    let target = multisampled(&geometry, &Gouraud, pattern).unwrap();
    let resolved = target.resolve();
    let encoded = target.resolve_in(MixSpace::Encoded);
    let masks = reference_masks(&geometry.setups, viewport(), &pattern);
    let mut partial = 0;
    for m in &masks {
        let (x, y) = (m.x as u32, m.y as u32);
        let centre = one.color[one.index(x, y)];
        if centre == RenderTarget::BLACK {
            continue;
        }
        let base = target.index(x, y);
        for i in 0..8 {
            let want = if m.mask & (1 << i) != 0 {
                centre
            } else {
                RenderTarget::BLACK
            };
            assert_eq!(
                target.color[base + i],
                want,
                "sample {i} of pixel ({x}, {y})"
            );
        }
        let covered = m.mask.count_ones();
        partial += usize::from(covered < 8);
        // The mean of the samples over black: in the encoded values, the
        // integer mean; in linear light, the light times the share.
        let mean = centre.map(|c| ((u32::from(c) * covered + 4) / 8) as u8);
        assert_eq!(
            encoded.color[encoded.index(x, y)][..3],
            mean[..3],
            "pixel ({x}, {y})"
        );
        let share = covered as f32 / 8.0;
        let light = centre.map(|c| linear_to_srgb8(srgb8_to_linear(c) * share));
        assert_eq!(
            resolved.color[resolved.index(x, y)][..3],
            light[..3],
            "pixel ({x}, {y}) in linear light"
        );
    }
    assert!(
        partial > 20,
        "the edges cross {partial} pixels whose centre is inside"
    );
}

/// A target beyond the sample budget is refused with the memory it
/// would take, never allocated.
#[test]
fn a_huge_multisample_target_is_refused_with_its_size() {
    let pattern = SamplePattern::standard(16).unwrap();
    let err = MultisampleTarget::new(16_384, 16_384, pattern)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("34.4 GB") && err.contains("fewer samples"),
        "{err}"
    );
    assert!(MultisampleTarget::new(0, 4, pattern).is_err());
    // Within the budget: a full HD frame at 16 samples.
    let target = MultisampleTarget::new(1920, 1080, pattern).unwrap();
    assert_eq!(target.color.len(), 1920 * 1080 * 16);
}

/// `render --msaa`: one sample writes the very image of a render without
/// it; four samples resolve edge pixels to shades between; a line set, a
/// wireframe and a count without a standard pattern are refused with
/// exit code 2 and a message.
#[test]
fn render_msaa_writes_the_resolved_image() {
    let dir = tempfile::tempdir().unwrap();
    let out = |name: &str| dir.path().join(name).to_str().unwrap().to_string();
    let render = |extra: &[&str], file: &str| {
        let o = out(file);
        let mut args = vec!["render", "--scene", "pinwheel", "--out", o.as_str()];
        args.extend_from_slice(extra);
        let run = rasterlab(&args);
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        (
            image::open(&o).unwrap().to_rgba8(),
            String::from_utf8(run.stdout).unwrap(),
        )
    };
    let (plain, _) = render(&[], "plain.png");
    let (one, _) = render(&["--msaa", "1"], "one.png");
    assert_eq!(plain, one);
    let (four, said) = render(&["--msaa", "4", "--backend", "tiled"], "four.png");
    assert!(said.starts_with("tiled, 4 samples per pixel:"), "{said}");
    let shades = |img: &image::RgbaImage| {
        img.pixels()
            .map(|p| p.0)
            .collect::<std::collections::BTreeSet<_>>()
            .len()
    };
    assert!(
        shades(&four) > shades(&plain) + 8,
        "{} against {}",
        shades(&four),
        shades(&plain)
    );
    let (again, _) = render(&["--msaa", "4", "--backend", "naive"], "naive.png");
    assert_eq!(four, again, "the resolved image depends on the back-end");

    let o = out("x.png");
    for (args, says) in [
        (
            vec![
                "render",
                "assets/lines.txt",
                "--size",
                "32x32",
                "--msaa",
                "4",
            ],
            "not multisampled",
        ),
        (
            vec![
                "render",
                "assets/bunny.ply",
                "--msaa",
                "4",
                "--wireframe",
                "bresenham",
            ],
            "not multisampled",
        ),
        (
            vec!["render", "--scene", "fan", "--msaa", "3"],
            "1, 2, 4, 8 and 16",
        ),
    ] {
        let mut args = args;
        args.extend(["--out", o.as_str()]);
        let run = rasterlab(&args);
        let err = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
    }
}

/// A mesh through the 3D pipeline: one sample gives the one-sample
/// frame's colour and depth, although the multisampled set-up keeps the
/// triangles that cover no pixel centre; four samples give the same
/// image from every back-end, and keep more pixels than one.
#[test]
fn a_mesh_multisampled_through_the_pipeline() {
    use rasterlab::geometry::{Mesh, MeshRenderer, RenderSettings, Shading};
    let bunny = Mesh::load(std::path::Path::new("assets/bunny.ply")).unwrap();
    let settings = RenderSettings {
        width: 160,
        height: 120,
        shading: Shading::Gouraud,
        ..RenderSettings::default()
    };
    let renderer = MeshRenderer::new(&bunny, settings).unwrap();
    let frame = renderer.render(triangle_backends()[0]).unwrap();
    let one = SamplePattern::standard(1).unwrap();
    let mut target = MultisampleTarget::new(160, 120, one).unwrap();
    let stats = renderer
        .render_multisampled_into(triangle_backends()[0], &mut target)
        .unwrap();
    assert!(stats.geometry.triangles > frame.stats.geometry.triangles);
    let resolved = target.resolve();
    assert_eq!(resolved.color, frame.target.color);
    assert_eq!(resolved.depth, frame.target.depth);
    assert_eq!(resolved.coverage, frame.target.coverage);

    let four = SamplePattern::standard(4).unwrap();
    let mut first: Option<(MultisampleTarget, u64)> = None;
    for b in triangle_backends() {
        let mut target = MultisampleTarget::new(160, 120, four).unwrap();
        let stats = renderer.render_multisampled_into(*b, &mut target).unwrap();
        match &first {
            None => first = Some((target, stats.work.fragments)),
            Some((f, _)) => assert!(*f == target, "{} differs", b.name()),
        }
    }
    let (_, pixels) = first.unwrap();
    assert!(
        pixels > frame.stats.work.fragments,
        "{pixels} (pixel, triangle) masks"
    );
}

/// `compare --msaa 4`: every back-end's resolved image equals the
/// reference's, and the summary says the images are multisampled; a line
/// set is refused.
#[test]
fn compare_msaa_finds_the_backends_agree() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let run = rasterlab(&[
        "compare",
        "assets/polygon.txt",
        "--msaa",
        "4",
        "--samples",
        "1",
        "--out",
        out,
    ]);
    let said = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "{said}{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(
        said.starts_with("multisampled: 4 samples per pixel"),
        "{said}"
    );
    let rows: Vec<&str> = said
        .lines()
        .skip_while(|l| !l.starts_with("back-end"))
        .skip(1)
        .take_while(|l| !l.starts_with("anti-aliasing"))
        .collect();
    assert_eq!(rows.len(), triangle_backends().len(), "{said}");
    for row in rows {
        assert!(
            row.trim_end().ends_with(" 0"),
            "differs from the reference: {row}"
        );
    }
    // Refused before anything is written: no report folder is made.
    let folder = dir.path().join("refused");
    let folder = folder.to_str().unwrap();
    let run = rasterlab(&[
        "compare",
        "assets/lines.txt",
        "--msaa",
        "4",
        "--out",
        folder,
    ]);
    assert_eq!(run.status.code(), Some(2));
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(
        err.contains("assets/lines.txt: --msaa") && err.contains("not multisampled"),
        "{err}"
    );
    let huge = ["--size", "4096x4096", "--msaa", "16", "--out", folder];
    let run = rasterlab(&[&["compare", "assets/polygon.txt"][..], &huge[..]].concat());
    assert_eq!(
        run.status.code(),
        Some(4),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(!std::path::Path::new(folder).exists());
}
