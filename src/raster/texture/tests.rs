//! The texture core against published expectations and hand-computed
//! answers: Scotty3D's A1 task-6 tests (`tests/a1/test.a1.task6.cpp` of
//! CMU-Graphics/Scotty3D, the handout at commit 48e8399), pyramids worked
//! out by hand, and properties.

use super::*;
use proptest::prelude::*;

const R: Vec4 = Vec4::new(1.0, 0.0, 0.0, 1.0);
const G: Vec4 = Vec4::new(0.0, 1.0, 0.0, 1.0);
const B: Vec4 = Vec4::new(0.0, 0.0, 1.0, 1.0);
const W: Vec4 = Vec4::new(1.0, 1.0, 1.0, 1.0);

fn rgb(r: f32, g: f32, b: f32) -> Vec4 {
    Vec4::new(r, g, b, 1.0)
}

fn close(got: Vec4, expected: Vec4, what: &str) {
    assert!(
        (got - expected).abs().max_element() < 1e-5,
        "{what}: got {got}, expected {expected}"
    );
}

fn image(width: u32, height: u32, texels: Vec<Vec4>) -> Image {
    Image::new(width, height, texels).unwrap()
}

/// Scotty3D's 3x5 test image of `a1.task6.sample.nearest.simple` and
/// `a1.task6.sample.bilinear.simple`.
fn scotty_3x5() -> Image {
    image(3, 5, vec![R, R, R, G, G, G, R, B, R, G, W, G, B, B, B])
}

/// Scotty3D's `px_to_uv * Vec2(x, y)` for its 3x5 image.
fn px(x: f32, y: f32) -> Vec2 {
    Vec2::new(x / 3.0, y / 5.0)
}

/// `a1.task6.sample.nearest.simple`: the texel containing the point.
#[test]
fn scotty3d_nearest_returns_the_texel_containing_the_point() {
    let image = scotty_3x5();
    for (uv, what) in [(px(1.5, 3.5), "at center"), (px(1.1, 3.1), "low corner")]
        .into_iter()
        .chain([(px(1.9, 3.9), "high corner")])
    {
        close(
            image.sample(uv, Filter::Nearest, Wrap::ClampToEdge),
            W,
            what,
        );
    }
}

/// `a1.task6.sample.bilinear.simple`: the four texels around the point,
/// centres at half-integers.
#[test]
fn scotty3d_bilinear_mixes_the_four_texels_around_the_point() {
    let image = scotty_3x5();
    let sample = |uv| image.sample(uv, Filter::Bilinear, Wrap::ClampToEdge);
    close(sample(px(1.5, 3.5)), W, "at center");
    close(sample(px(1.25, 2.5)), rgb(0.25, 0.0, 0.75), "linear x");
    close(sample(px(0.5, 2.75)), rgb(0.75, 0.25, 0.0), "linear y");
    close(sample(px(2.4, 3.25)), rgb(0.3, 0.75, 0.1), "bilinear xy");
}

fn trilinear() -> Sampler {
    Sampler {
        filter: Filter::Bilinear,
        levels: LevelMode::Linear,
        wrap: Wrap::ClampToEdge,
        anisotropy: 1,
        anisotropic: Anisotropic::Probes,
    }
}

/// `a1.task6.sample.trilinear.simple`: a red 3x5 level 0, a green 1x2
/// level 1, a blue 1x1 level 2, mixed at levels 0.25 and 1.7.
#[test]
fn scotty3d_trilinear_mixes_the_two_levels_around_the_lod() {
    let texture = Texture::from_levels(vec![
        image(3, 5, vec![R; 15]),
        image(1, 2, vec![G; 2]),
        image(1, 1, vec![B]),
    ])
    .unwrap();
    let at = |lod| texture.sample_lod(Vec2::splat(0.5), lod, &trilinear());
    close(at(0.0), R, "base");
    close(at(1.0), G, "levels[0]");
    close(at(2.0), B, "levels[1]");
    close(at(0.25), rgb(0.75, 0.25, 0.0), "base - levels[0]");
    close(at(1.7), rgb(0.0, 0.3, 0.7), "levels[0] - levels[1]");
}

/// `a1.task6.generate_mipmap`: a 4x6 image of 2x2 red and blue blocks
/// has levels of 2x3 and 1x1, the last its average.
#[test]
fn scotty3d_pyramid_of_4x6_is_2x3_then_1x1() {
    let (a, b) = ([R, R, B, B], [B, B, R, R]);
    let texels: Vec<Vec4> = [a, a, b, b, a, a].concat();
    let texture = Texture::new(4, 6, texels).unwrap();
    let sizes: Vec<_> = texture.levels()[1..]
        .iter()
        .map(|l| (l.width(), l.height()))
        .collect();
    assert_eq!(sizes, [(2, 3), (1, 1)]);
    close(
        texture.levels()[2].texel(0, 0),
        rgb(0.5, 0.0, 0.5),
        "last level",
    );
    let level1 = texture.levels()[1].texels();
    for (got, expected) in level1.iter().zip([R, B, B, R, R, B]) {
        close(*got, expected, "2x3 level");
    }
}

/// Scotty3D's `test_mipmap_texture`: 256x512, each level's texels
/// coloured `((x + 0.5) / w, (y + 0.5) / h, level)`, so that blue, sampled
/// trilinearly, is the level of detail.
fn scotty_lod_texture() -> Texture {
    let sizes = pyramid::sizes(256, 512);
    assert_eq!(sizes.len(), 10);
    let levels = sizes
        .iter()
        .enumerate()
        .map(|(level, &(w, h))| {
            let texels = (0..w * h)
                .map(|i| {
                    let (x, y) = ((i % w) as f32, (i / w) as f32);
                    rgb((x + 0.5) / w as f32, (y + 0.5) / h as f32, level as f32)
                })
                .collect();
            image(w, h, texels)
        })
        .collect();
    Texture::from_levels(levels).unwrap()
}

/// The level of detail Scotty3D's `a1.task6.lod.simple` reads: blue at
/// uv (0.5, 0.5) with derivatives `d(u, v)/dx` and `d(u, v)/dy` given in
/// texels of level 0.
fn lod_at(texture: &Texture, dx_texels: Vec2, dy_texels: Vec2) -> f32 {
    let size = Vec2::new(texture.width() as f32, texture.height() as f32);
    let sampled = texture.sample_grad(
        Vec2::splat(0.5),
        dx_texels / size,
        dy_texels / size,
        &trilinear(),
    );
    sampled.z
}

/// `a1.task6.lod.simple`: 0, 1, 2 and 4 texels a pixel give levels of
/// detail in [-0.001, 0.001], [-0.001, 0.501], [0.5, 1.5] and [1.5, 2.5];
/// on an axis-aligned square and on squares rotated on screen (rho is the
/// length of each screen axis's image, which turning does not change).
#[test]
fn scotty3d_lod_ranges_hold_axis_aligned_and_rotated() {
    let texture = scotty_lod_texture();
    let ranges = [
        (0.0, -0.001, 0.001),
        (1.0, -0.001, 0.501),
        (2.0, 0.5, 1.5),
        (4.0, 1.5, 2.5),
    ];
    for degrees in [0.0f32, 10.0, 30.0, 45.0, 60.0, 90.0, 135.0, 200.0] {
        let (sin, cos) = degrees.to_radians().sin_cos();
        for (texels, min, max) in ranges {
            // The screen axes' images: the square turned by `degrees`.
            let dx = Vec2::new(cos, sin) * texels;
            let dy = Vec2::new(-sin, cos) * texels;
            let lod = lod_at(&texture, dx, dy);
            assert!(
                (min..=max).contains(&lod),
                "{texels} texels a pixel at {degrees} degrees: lod {lod} outside [{min}, {max}]"
            );
        }
    }
}

/// The same ranges from drawn squares: a square of 40 pixels, turned on
/// screen by each angle, whose texture coordinate spans `texels` texels a
/// pixel; at every pixel inside, each derivative method's derivatives give
/// a level of detail in Scotty3D's range.
#[test]
fn scotty3d_lod_ranges_hold_for_every_derivative_method_on_drawn_squares() {
    use crate::raster::{Derivatives, FillRule, FixedPoint, ShadedVertex, TriangleSetup, UvPlanes};
    let texture = scotty_lod_texture();
    let size = Vec2::new(256.0, 512.0);
    let ranges = [
        (0.0, -0.001, 0.001),
        (1.0, -0.001, 0.501),
        (2.0, 0.5, 1.5),
        (4.0, 1.5, 2.5),
    ];
    for degrees in [0.0f32, 30.0, 45.0, 100.0] {
        let (sin, cos) = degrees.to_radians().sin_cos();
        let corner = |a: f32, b: f32| {
            let (x, y) = (a * cos - b * sin + 32.0, a * sin + b * cos + 32.0);
            FixedPoint::snap_f64(f64::from(x), f64::from(y)).unwrap()
        };
        for (texels, min, max) in ranges {
            // Corner (a, b) of the square, in pixels from its centre, has
            // the texture coordinate 0.5 + (a, b) * texels / size.
            let vertex = |a: f32, b: f32| ShadedVertex {
                depth: 0.5,
                inv_w: 1.0,
                varyings: crate::raster::Varyings {
                    uv: Vec2::splat(0.5) + Vec2::new(a, b) * texels / size,
                    ..Default::default()
                },
            };
            let (h, l) = (20.0, -20.0);
            let halves = [[(l, l), (h, l), (h, h)], [(l, l), (h, h), (l, h)]];
            for (id, half) in halves.iter().enumerate() {
                let setup = TriangleSetup::new(
                    id as u32,
                    half.map(|(a, b)| corner(a, b)),
                    FillRule::TopLeft,
                )
                .unwrap();
                let planes = UvPlanes::new(&setup, half.map(|(a, b)| vertex(a, b)), true);
                let b = setup.bounds;
                for y in b.y0..=b.y1 {
                    for x in b.x0..=b.x1 {
                        if !setup.inside(setup.edge_values_at_pixel(x, y)) {
                            continue;
                        }
                        for method in [
                            Derivatives::Analytic,
                            Derivatives::Quad,
                            Derivatives::Forward,
                        ] {
                            let d = planes.derivatives(method, x, y);
                            let lod = lod_at(&texture, d.dx * size, d.dy * size);
                            assert!(
                                (min..=max).contains(&lod),
                                "{method}, {texels} texels a pixel at {degrees} degrees, pixel ({x}, {y}): lod {lod}"
                            );
                        }
                    }
                }
            }
        }
    }
}

/// A 5x3 texture, by hand: red `x + 5y`, green 1, blue `x`, alpha `y`.
/// Its next level is 2x1: columns weighted 2/5, 2/5, 1/5 and 1/5, 2/5,
/// 2/5, the three rows 1/3 each; then 1x1, the two halves' mean.
#[test]
fn the_pyramid_of_5x3_is_the_hand_computed_one() {
    let texels = (0..15)
        .map(|i| {
            let (x, y) = ((i % 5) as f32, (i / 5) as f32);
            Vec4::new(x + 5.0 * y, 1.0, x, y)
        })
        .collect();
    let texture = Texture::new(5, 3, texels).unwrap();
    let levels = texture.levels();
    assert_eq!(levels.len(), 3);
    assert_eq!((levels[1].width(), levels[1].height()), (2, 1));
    // Red, left: (0 * 2 + 1 * 2 + 2 * 1) / 5 + 5 (the mean of 5y) = 5.8;
    // right: (2 * 1 + 3 * 2 + 4 * 2) / 5 + 5 = 8.2.
    close(levels[1].texel(0, 0), Vec4::new(5.8, 1.0, 0.8, 1.0), "left");
    close(
        levels[1].texel(1, 0),
        Vec4::new(8.2, 1.0, 3.2, 1.0),
        "right",
    );
    close(levels[2].texel(0, 0), Vec4::new(7.0, 1.0, 2.0, 1.0), "1x1");
}

/// 1x7 and 1x6 textures, red `y`, by hand: the side of 1 stays 1.
/// 7 rows become 3 with weights 3/7, 3/7, 1/7; 2/7, 3/7, 2/7; 1/7, 3/7,
/// 3/7; then 1 with 1/3 each. 6 become 3 by pairs, then 1.
#[test]
fn the_pyramids_of_1xn_are_the_hand_computed_ones() {
    let column = |n: u32| {
        let texels = (0..n).map(|y| Vec4::new(y as f32, 0.0, 0.0, 1.0)).collect();
        Texture::new(1, n, texels).unwrap()
    };
    let reds = |t: &Texture, level: usize| -> Vec<f32> {
        t.levels()[level].texels().iter().map(|c| c.x).collect()
    };
    let seven = column(7);
    assert_eq!(seven.levels().len(), 3);
    for (got, expected) in reds(&seven, 1).iter().zip([5.0 / 7.0, 3.0, 37.0 / 7.0]) {
        assert!((got - expected).abs() < 1e-6, "{got} vs {expected}");
    }
    assert!((reds(&seven, 2)[0] - 3.0).abs() < 1e-6);
    let six = column(6);
    assert_eq!(reds(&six, 1), [0.5, 2.5, 4.5]);
    assert!((reds(&six, 2)[0] - 2.5).abs() < 1e-6);
}

#[test]
fn wrap_modes_pick_the_texel_opengl_picks() {
    let picks = |wrap: Wrap| (-4..=6).map(|i| wrap.index(i, 3)).collect::<Vec<_>>();
    assert_eq!(picks(Wrap::Repeat), [2, 0, 1, 2, 0, 1, 2, 0, 1, 2, 0]);
    assert_eq!(picks(Wrap::ClampToEdge), [0, 0, 0, 0, 0, 1, 2, 2, 2, 2, 2]);
    assert_eq!(
        picks(Wrap::MirroredRepeat),
        [2, 2, 1, 0, 0, 1, 2, 2, 1, 0, 0]
    );
    assert_eq!(
        Wrap::Repeat.index(i64::MIN, 7),
        (i64::MIN).rem_euclid(7) as u32
    );
    assert_eq!("mirror".parse::<Wrap>().unwrap(), Wrap::MirroredRepeat);
}

/// Bad sizes are errors that say what is wrong, never panics.
#[test]
fn bad_textures_are_clear_errors() {
    let message = |r: Result<Texture>| r.unwrap_err().to_string();
    assert!(message(Texture::new(0, 4, vec![])).contains("at least 1 texel"));
    assert!(message(Texture::new(MAX_TEXTURE_SIDE + 1, 1, vec![])).contains("longer than"));
    assert!(message(Texture::new(4097, 4097, vec![])).contains("more than"));
    assert!(message(Texture::new(2, 2, vec![W; 3])).contains("3 texels were given for 4"));
    assert!(message(Texture::from_levels(vec![])).contains("no level"));
    let wrong = Texture::from_levels(vec![image(4, 4, vec![W; 16]), image(1, 1, vec![W])]);
    assert!(message(wrong).contains("pyramid rule"));
    let full = Texture::new(MAX_TEXTURE_SIDE, 1, vec![W; MAX_TEXTURE_SIDE as usize]).unwrap();
    assert_eq!(full.levels().len(), 15);
}

/// Level 0 with repeating addressing is the texture as it was sampled
/// before mipmaps, whatever the derivatives, under the default sampler.
#[test]
fn the_default_sampler_reads_level_zero_whatever_the_derivatives() {
    let texture = Texture::checkerboard(4, 3, R, B);
    let s = Sampler::default();
    for uv in [
        Vec2::new(0.1, 0.7),
        Vec2::new(-1.3, 2.2),
        Vec2::splat(f32::NAN),
    ] {
        let grad = texture.sample_grad(uv, Vec2::new(9.0, 0.0), Vec2::new(0.0, 5.0), &s);
        assert_eq!(grad, texture.sample(uv, Filter::Bilinear));
    }
}

fn samplers() -> impl Strategy<Value = Sampler> {
    (
        0..2usize,
        0..3usize,
        0..3usize,
        0..=MAX_ANISOTROPY,
        0..2usize,
    )
        .prop_map(|(f, l, w, anisotropy, a)| Sampler {
            filter: [Filter::Nearest, Filter::Bilinear][f],
            levels: [LevelMode::Zero, LevelMode::Nearest, LevelMode::Linear][l],
            wrap: [Wrap::Repeat, Wrap::ClampToEdge, Wrap::MirroredRepeat][w],
            anisotropy,
            anisotropic: [Anisotropic::Probes, Anisotropic::Ewa][a],
        })
}

proptest! {
    #![proptest_config(crate::test_support::proptest_config(500, "tests/proptest-regressions/src-raster-texture-tests.txt"))]

    /// Every level of the pyramid keeps level 0's mean: the box filter
    /// weighs every texel alike, odd sides included (a rule that dropped
    /// an odd side's last texel, or weighted it twice, fails here).
    #[test]
    fn every_level_keeps_the_mean(w in 1u32..40, h in 1u32..40, seed in any::<u64>()) {
        let mut rng = fastrand::Rng::with_seed(seed);
        let texels = (0..w * h).map(|_| Vec4::new(rng.f32(), rng.f32(), rng.f32(), 1.0)).collect();
        let texture = Texture::new(w, h, texels).unwrap();
        let mean = |l: &Image| l.texels().iter().sum::<Vec4>() / l.texels().len() as f32;
        let base = mean(&texture.levels()[0]);
        for level in texture.levels() {
            prop_assert!((mean(level) - base).abs().max_element() < 1e-5);
        }
        prop_assert_eq!(texture.levels().len(), pyramid::sizes(w, h).len());
    }

    /// A texture of one colour samples as that colour under every
    /// sampler, coordinate and footprint: the filters' and levels'
    /// weights sum to one, and no probe reads outside the texture.
    #[test]
    fn a_uniform_texture_samples_as_its_colour(
        sampler in samplers(),
        w in 1u32..20, h in 1u32..20,
        uv in prop::array::uniform2(-50.0f32..50.0),
        d in prop::array::uniform4(-3.0f32..3.0),
    ) {
        let c = Vec4::new(0.25, 0.5, 0.75, 1.0);
        let texture = Texture::new(w, h, vec![c; (w * h) as usize]).unwrap();
        let got = texture.sample_grad(Vec2::from(uv), Vec2::new(d[0], d[1]), Vec2::new(d[2], d[3]), &sampler);
        prop_assert!((got - c).abs().max_element() < 1e-5, "{}", got);
    }

    /// `lambda` of a square footprint `s` texels wide is `log2(s)` at any
    /// turn on screen.
    #[test]
    fn lambda_of_a_turned_square_is_log2_of_its_side(s in 0.01f32..1000.0, turn in 0.0f32..6.3) {
        let (sin, cos) = turn.sin_cos();
        let f = Footprint { dx: Vec2::new(cos, sin) * s, dy: Vec2::new(-sin, cos) * s };
        prop_assert!((f.lambda() - s.log2()).abs() < 1e-4);
    }

    /// Mirrored repeat is symmetric about each edge and has period `2n`;
    /// every mode stays in the texture.
    #[test]
    fn wrap_modes_stay_inside(i in -100_000i64..100_000, n in 1u32..50) {
        for wrap in [Wrap::Repeat, Wrap::ClampToEdge, Wrap::MirroredRepeat] {
            prop_assert!(wrap.index(i, n) < n);
        }
        let m = |i| Wrap::MirroredRepeat.index(i, n);
        prop_assert_eq!(m(i), m(-1 - i));
        prop_assert_eq!(m(i), m(i + 2 * i64::from(n)));
    }
}

/// The texel addressing's floor is `f64::floor` bit for bit, and the
/// masked wrap of a power-of-two side the Euclidean remainder.
#[test]
fn floor_and_masked_wrap_are_the_plain_ones() {
    let mut values = vec![
        0.0,
        -0.0,
        0.5,
        -0.5,
        1.0,
        -1.0,
        -1e-300,
        1e-300,
        2f64.powi(52),
        -2f64.powi(52),
    ];
    values.extend([
        2f64.powi(52) - 0.5,
        -(2f64.powi(52) - 0.5),
        1e300,
        -1e300,
        f64::MAX,
        f64::MIN,
    ]);
    let mut rng = fastrand::Rng::with_seed(3);
    values.extend((0..100_000).map(|_| (rng.f64() - 0.5) * 10f64.powi(rng.i32(-3..20))));
    for x in values {
        assert_eq!(super::floor(x).to_bits(), x.floor().to_bits(), "{x}");
    }
    for n in [1u32, 2, 4, 32, 1 << 14] {
        for i in -100_000i64..100_000 {
            let n64 = i64::from(n);
            assert_eq!(
                i64::from(Wrap::Repeat.index(i, n)),
                i.rem_euclid(n64),
                "{i} {n}"
            );
            let k = i.rem_euclid(2 * n64);
            let mirrored = if k < n64 { k } else { 2 * n64 - 1 - k };
            assert_eq!(
                i64::from(Wrap::MirroredRepeat.index(i, n)),
                mirrored,
                "{i} {n}"
            );
        }
    }
}
