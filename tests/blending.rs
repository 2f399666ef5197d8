//! Blending through the shared stage: the blend equations against the
//! courses' known answers and cases worked out by hand, the order
//! transparent triangles are drawn in, the same image from every back-end
//! with and without multisampling, and linear light.

use glam::Vec4;
use rasterlab::geometry::Scene2D;
use rasterlab::raster::triangle::TriangleRasterizer;
use rasterlab::raster::{
    linear_to_srgb8, triangle_backends, Blend, BlendMode, DepthState, DepthTest, FillRule, Flat,
    MixSpace, MultisampleTarget, RenderTarget, SamplePattern,
};

/// Scotty3D's tolerance for blended colours (`Test::differs`).
const TOLERANCE: f32 = 1e-3;

fn close(got: Vec4, want: Vec4) -> bool {
    (got - want).abs().max_element() <= TOLERANCE
}

/// Scotty3D A1 task 4's public tests of blending (`tests/a1/test.a1.task4.cpp`,
/// `a1.task4.blend.add.1` and `a1.task4.blend.over.1`): a fragment of
/// colour (0.1, 0.2, 0.3) at opacity 1 on a framebuffer of (0.4, 0.5,
/// 0.6). Its framebuffer holds linear colour with no alpha, so the alpha
/// here is the opaque buffer's 1. `add` sums, `over` at opacity 1
/// replaces.
#[test]
fn scotty3d_task4_blend_cases_hold() {
    let fragment = Vec4::new(0.1, 0.2, 0.3, 1.0);
    let framebuffer = Vec4::new(0.4, 0.5, 0.6, 1.0);
    let add = BlendMode::Add.mix(fragment, 1.0, framebuffer);
    assert!(
        close(add.truncate().extend(1.0), Vec4::new(0.5, 0.7, 0.9, 1.0)),
        "{add}"
    );
    let over = BlendMode::OverStraight.mix(fragment, 1.0, framebuffer);
    assert!(close(over, Vec4::new(0.1, 0.2, 0.3, 1.0)), "{over}");
    // Its replace cases write the fragment's colour whatever its opacity
    // (`a1.task4.depth.always.25_50`: (0.75, 0.5, 0.25) at opacity 0.5).
    let replaced = BlendMode::Replace.mix(Vec4::new(0.75, 0.5, 0.25, 0.5), 1.0, framebuffer);
    assert!(close(
        replaced.truncate().extend(1.0),
        Vec4::new(0.75, 0.5, 0.25, 1.0)
    ));
}

/// Straight fragments over a premultiplied framebuffer, as Scotty3D has
/// it, at opacities below 1, worked out by hand; `over` on the same
/// fragment premultiplied gives the same; `add` and `multiply`.
#[test]
fn hand_worked_blends_below_full_opacity() {
    let opaque = Vec4::new(0.2, 0.4, 0.6, 1.0);
    let quarter = Vec4::new(0.8, 0.4, 0.2, 0.25);
    // rgb = 0.25 s + 0.75 d; a = 0.25 + 1 * 0.75.
    let want = Vec4::new(0.35, 0.4, 0.5, 1.0);
    assert!(close(
        BlendMode::OverStraight.mix(quarter, 1.0, opaque),
        want
    ));
    let premultiplied = Vec4::new(0.2, 0.1, 0.05, 0.25);
    assert!(close(BlendMode::Over.mix(premultiplied, 1.0, opaque), want));
    // Onto a transparent buffer the result is premultiplied: (0.2, 0.1,
    // 0.05, 0.25); then blue at opacity 0.5 over it: (0, 0, 0.5) + half
    // of it, alpha 0.5 + 0.25 * 0.5.
    let first = BlendMode::OverStraight.mix(quarter, 1.0, Vec4::ZERO);
    assert!(close(first, premultiplied), "{first}");
    let blue = Vec4::new(0.0, 0.0, 1.0, 0.5);
    let second = BlendMode::OverStraight.mix(blue, 1.0, first);
    assert!(
        close(second, Vec4::new(0.1, 0.05, 0.525, 0.625)),
        "{second}"
    );
    // add at opacity 0.5: d + 0.5 s.
    let add = BlendMode::Add.mix(
        Vec4::new(0.1, 0.2, 0.3, 0.5),
        1.0,
        Vec4::new(0.4, 0.5, 0.6, 0.5),
    );
    assert!(close(add, Vec4::new(0.45, 0.6, 0.75, 1.0)), "{add}");
    // multiply: s * d.
    let multiply = BlendMode::Multiply.mix(
        Vec4::new(0.5, 1.0, 0.25, 1.0),
        1.0,
        Vec4::new(0.8, 0.4, 0.2, 1.0),
    );
    assert!(
        close(multiply, Vec4::new(0.4, 0.4, 0.05, 1.0)),
        "{multiply}"
    );
    // A fragment covering half its pixel counts as half as opaque.
    let half_covered = BlendMode::OverStraight.mix(Vec4::new(1.0, 1.0, 1.0, 1.0), 0.5, Vec4::W);
    assert!(close(half_covered, Vec4::new(0.5, 0.5, 0.5, 1.0)));
}

/// `over` is not commutative: red then blue differs from blue then red.
#[test]
fn over_depends_on_the_order() {
    let black = Vec4::W;
    let red = Vec4::new(1.0, 0.0, 0.0, 0.5);
    let blue = Vec4::new(0.0, 0.0, 1.0, 0.5);
    let over = |s, d| BlendMode::OverStraight.mix(s, 1.0, d);
    let red_then_blue = over(blue, over(red, black));
    let blue_then_red = over(red, over(blue, black));
    assert!(close(red_then_blue, Vec4::new(0.25, 0.0, 0.5, 1.0)));
    assert!(close(blue_then_red, Vec4::new(0.5, 0.0, 0.25, 1.0)));
}

/// What `draw` gives with every triangle back-end, after checking they
/// all give the same.
fn same_on_every_back_end<T: PartialEq>(
    what: &str,
    draw: impl Fn(&dyn TriangleRasterizer) -> T,
) -> T {
    let first = draw(triangle_backends()[0]);
    for &b in &triangle_backends()[1..] {
        assert!(draw(b) == first, "{} differs, {what}", b.name());
    }
    first
}

/// The blended scene through the one-sample stage, the same on every
/// back-end.
fn render(scene: &Scene2D, depth: DepthState, blend: Blend) -> RenderTarget {
    same_on_every_back_end(&format!("{blend:?}"), |b| {
        let mut target = RenderTarget::new(scene.width, scene.height).unwrap();
        let black = RenderTarget::BLACK;
        let state = (depth, blend);
        scene.render_frame(b, FillRule::TopLeft, state, &Flat, black, &mut target);
        target
    })
}

/// The blended scene through the multisampled stage on the standard
/// pattern of `samples`, the same on every back-end.
fn render_multisampled(
    scene: &Scene2D,
    depth: DepthState,
    blend: Blend,
    samples: u32,
) -> MultisampleTarget {
    let pattern = SamplePattern::standard(samples).unwrap();
    same_on_every_back_end(&format!("multisampled, {blend:?}"), |b| {
        let mut target = MultisampleTarget::new(scene.width, scene.height, pattern).unwrap();
        let black = RenderTarget::BLACK;
        let state = (depth, blend);
        scene.render_frame_multisampled(b, FillRule::TopLeft, state, &Flat, black, &mut target);
        target
    })
}

fn blends() -> Vec<Blend> {
    let mut all = Vec::new();
    for mode in BlendMode::ALL {
        for mix_in in [MixSpace::Linear, MixSpace::Encoded] {
            all.push(Blend {
                mode,
                mix_in,
                ..Blend::default()
            });
        }
    }
    all
}

/// Transparent triangles: bit-identical on every back-end under every
/// mode and space, with and without multisampling; the one-sample
/// multisampled draw equals the one-sample stage's.
#[test]
fn every_back_end_blends_the_same_image() {
    let scene = Scene2D::transparent();
    for blend in blends() {
        for depth in [DepthState::OFF, DepthState::DEFAULT] {
            let image = render(&scene, depth, blend);
            let one = render_multisampled(&scene, depth, blend, 1).resolve_in(blend.mix_in);
            assert!(one.color == image.color, "{blend:?}");
            render_multisampled(&scene, depth, blend, 4);
        }
    }
}

/// Drawn as listed (nearest first) and sorted back to front, `over` gives
/// two images; with the depth test the nearest triangle hides the others
/// as if opaque, and sorted the three show through each other. The
/// sorted draw's pixel where all three overlap is worked out by hand.
#[test]
fn transparent_triangles_in_two_orders_give_two_images() {
    let scene = Scene2D::transparent();
    let sorted = scene.sorted_back_to_front();
    let over = Blend {
        mode: BlendMode::OverStraight,
        ..Blend::default()
    };
    for depth in [DepthState::OFF, DepthState::DEFAULT] {
        let listed = render(&scene, depth, over);
        let back_to_front = render(&sorted, depth, over);
        assert!(listed.color != back_to_front.color, "{depth:?}");
        // The same order again is the same image.
        assert!(render(&sorted, depth, over).color == back_to_front.color);
    }
    // Pixel (20, 18) lies in all three. Back to front: blue, green, red,
    // each at opacity 0.5 over black, in linear light.
    let image = render(&sorted, DepthState::DEFAULT, over);
    let [red, green, blue] = [0, 1, 2].map(|i| scene.vertices[i][0].varyings.color);
    // As the stage sees them: the colour stored as RGBA8 (opacity 0.5 is
    // 128/255), decoded to linear light. The buffer stores 8-bit sRGB
    // after each blend, so the hand composite encodes and decodes between
    // the steps too.
    let linear = |c: Vec4| MixSpace::Linear.decode(rasterlab::raster::to_rgba8(c));
    let mut stored = [0, 0, 0, 255];
    for c in [blue, green, red] {
        let d = MixSpace::Linear.decode(stored);
        stored = MixSpace::Linear.encode(BlendMode::OverStraight.mix(linear(c), 1.0, d));
    }
    let expected = stored;
    assert_eq!(image.color[image.index(20, 18)], expected);
    // With the depth test and nearest first, red alone covers that pixel.
    let listed = render(&scene, DepthState::DEFAULT, over);
    let red_alone = BlendMode::OverStraight.mix(linear(red), 1.0, Vec4::W);
    let red_alone = [
        linear_to_srgb8(red_alone.x),
        linear_to_srgb8(red_alone.y),
        linear_to_srgb8(red_alone.z),
        255,
    ];
    assert_eq!(listed.color[listed.index(20, 18)], red_alone);
}

/// Each pixel's fragments composited far to near, whatever order the
/// triangles come in: the per-pixel sort (what depth peeling or an
/// A-buffer gives), with the stage's own arithmetic (colours stored as
/// RGBA8, the buffer encoded to 8-bit sRGB after each blend).
fn per_pixel_sort(scene: &Scene2D) -> Vec<[u8; 4]> {
    let (w, h) = (scene.width, scene.height);
    // Each triangle alone: where it covers, and its depth there.
    let alone: Vec<RenderTarget> = (0..scene.triangles.len())
        .map(|i| {
            let one = Scene2D {
                triangles: vec![scene.triangles[i]],
                vertices: vec![scene.vertices[i]],
                ..scene.clone()
            };
            let mut t = RenderTarget::new(w, h).unwrap();
            let always = DepthState {
                test: DepthTest::Always,
                write: true,
            };
            one.draw(
                triangle_backends()[0],
                FillRule::TopLeft,
                always,
                &Flat,
                &mut t,
            );
            t
        })
        .collect();
    let colour = |i: usize| {
        MixSpace::Linear.decode(rasterlab::raster::to_rgba8(
            scene.vertices[i][0].varyings.color,
        ))
    };
    (0..(w * h) as usize)
        .map(|p| {
            let mut here: Vec<(f32, usize)> = (0..alone.len())
                .filter(|&i| alone[i].coverage[p] > 0)
                .map(|i| (alone[i].depth[p], i))
                .collect();
            here.sort_by(|a, b| b.0.total_cmp(&a.0));
            here.iter().fold([0, 0, 0, 255], |stored, &(_, i)| {
                let d = MixSpace::Linear.decode(stored);
                MixSpace::Linear.encode(BlendMode::OverStraight.mix(colour(i), 1.0, d))
            })
        })
        .collect()
}

/// No order of the cycle's three wedges composites them as a per-pixel
/// sort does: each of the six orders is wrong somewhere, by far more than
/// rounding, which is the limit of sorting whole triangles. Where sorting
/// works (the `transparent` scene, one depth per triangle) the per-pixel
/// sort and the sorted draw agree exactly.
#[test]
fn no_order_of_the_cycle_is_right() {
    let over = Blend {
        mode: BlendMode::OverStraight,
        ..Blend::default()
    };
    let transparent = Scene2D::transparent();
    let sorted = render(&transparent.sorted_back_to_front(), DepthState::OFF, over);
    assert!(sorted.color == per_pixel_sort(&transparent));
    let scene = Scene2D::cycle();
    let right = per_pixel_sort(&scene);
    for order in [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ] {
        let image = render(&scene.reordered(&order), DepthState::OFF, over);
        let worst = image
            .color
            .iter()
            .zip(&right)
            .flat_map(|(a, b)| (0..3).map(move |k| a[k].abs_diff(b[k])))
            .max()
            .unwrap();
        assert!(worst >= 32, "order {order:?} is off by {worst} at most");
    }
}

/// A half-covered white-on-black pixel, multisampled: the resolve in
/// linear light writes the encoding of 0.5 (187.5, so 188); in the
/// encoded values, 128.
#[test]
fn a_half_covered_edge_resolves_to_half_the_light() {
    let white = rasterlab::raster::ShadedVertex::flat(0.5, Vec4::ONE);
    let snap = |x: f32, y: f32| rasterlab::raster::FixedPoint::snap(x, y).unwrap();
    // A 4 x 4 square's lower-left half: pixel (2, 1) has 2 of 4 samples in.
    let scene = Scene2D {
        width: 4,
        height: 4,
        triangles: vec![[snap(0.0, 0.0), snap(4.0, 0.0), snap(0.0, 3.7)]],
        vertices: vec![[white; 3]],
    };
    let target = render_multisampled(&scene, DepthState::DEFAULT, Blend::REPLACE, 4);
    let i = target.index(2, 1);
    let covered = target.color[i..i + 4]
        .iter()
        .filter(|c| c[0] == 255)
        .count();
    assert_eq!(covered, 2);
    let linear = target.resolve();
    assert_eq!(linear.color[linear.index(2, 1)], [188, 188, 188, 255]);
    let encoded = target.resolve_in(MixSpace::Encoded);
    assert_eq!(encoded.color[encoded.index(2, 1)], [128, 128, 128, 255]);
}
