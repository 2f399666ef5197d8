//! The 3D pipeline: assembly, clipping, culling, interpolation, depth and
//! meshes, each rendered by every triangle back-end.

mod common;
#[path = "properties/pipeline.rs"]
mod properties;

use glam::{Mat4, Vec2, Vec3, Vec4};
use proptest::prelude::*;
use rasterlab::geometry::{
    assemble, draw, positions_from_floats, process_triangles, ClipPlanes, ClipVertex, CullMode,
    FrontFace, Mesh, MeshRenderer, PipelineOptions, RenderSettings, Scene2D, Shading, Topology,
    Transform, Viewport,
};
use rasterlab::raster::{
    triangle_backend, triangle_backends, Blend, Constant, DepthState, FillRule, Filter, Flat,
    Interpolation, RenderTarget, ShadedVertex, Texture, Textured, Varyings,
};
use rasterlab::teaching::{ascii_mark, ascii_rows};
use rasterlab::Error;
use std::path::Path;

fn asset(name: &str) -> Mesh {
    Mesh::load(
        &Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("assets")
            .join(name),
    )
    .unwrap()
}

fn ascii(target: &RenderTarget) -> Vec<String> {
    let (w, h) = (i64::from(target.width()), i64::from(target.height()));
    ascii_rows(0..w, 0..h, |x, y| {
        ascii_mark(target.coverage[target.index(x as u32, y as u32)] > 0)
    })
}

/// The course chapter's vertex array, `-1,0,0, 0,-1,0, -1,-1,0`, taken unchanged by
/// the vertex shader (positions are clip space, w = 1), lands on the
/// screen at (0, 4), (4, 8), (0, 8) of an 8x8 target. Its diagonal is a
/// right edge, so pixel centres on it belong to the neighbour: six pixels.
#[test]
fn seed_000_vertex_array_renders_exactly() {
    let positions = positions_from_floats(&[-1., 0., 0., 0., -1., 0., -1., -1., 0.]).unwrap();
    let triangles = assemble(Topology::List, None, positions.len()).unwrap();
    let geometry = process_triangles(
        &positions,
        &triangles,
        &Transform::identity(),
        Viewport {
            width: 8,
            height: 8,
        },
        &PipelineOptions::default(),
    )
    .unwrap();
    let expected = [
        "........", "........", "........", "........", "........", "#.......", "##......",
        "###.....",
    ];
    for b in triangle_backends() {
        let mut target = RenderTarget::new(8, 8).unwrap();
        draw(
            &geometry,
            *b,
            &Flat,
            DepthState::DEFAULT,
            Interpolation::PerspectiveCorrect,
            &mut target,
        );
        assert_eq!(ascii(&target), expected, "{}", b.name());
    }
    // v0 top-left, v1 bottom-right, v2 bottom-left: clockwise as seen, so
    // a back face under the default counter-clockwise front face.
    let stats = |options: PipelineOptions| {
        let viewport = Viewport {
            width: 8,
            height: 8,
        };
        process_triangles(
            &positions,
            &triangles,
            &Transform::identity(),
            viewport,
            &options,
        )
        .unwrap()
        .stats
    };
    let g = stats(PipelineOptions {
        cull: CullMode::Back,
        ..PipelineOptions::default()
    });
    assert_eq!((g.culled, g.triangles), (1, 0));
    let g = stats(PipelineOptions {
        cull: CullMode::Back,
        front_face: FrontFace::Clockwise,
        ..PipelineOptions::default()
    });
    assert_eq!((g.culled, g.triangles), (0, 1));
}

/// A triangle whose bounding box holds no pixel centre, and one off the
/// side of the screen, are dropped before the rasterizer and counted; a
/// triangle covering one pixel centre is kept.
#[test]
fn triangles_without_a_pixel_centre_in_their_bounds_are_dropped() {
    // Pixels of an 8x8 viewport are 0.25 wide in NDC; pixel (4, 3)'s centre
    // is at x = 0.125, y = 0.125.
    let positions = vec![
        // Between the centres at x = 0.125 and x = 0.375.
        Vec3::new(0.15, 0.0, 0.0),
        Vec3::new(0.35, 0.0, 0.0),
        Vec3::new(0.25, 0.3, 0.0),
        // Right of the screen (x > 1), inside the guard band.
        Vec3::new(1.5, 0.0, 0.0),
        Vec3::new(1.9, 0.0, 0.0),
        Vec3::new(1.7, 0.5, 0.0),
        // Around the centre of pixel (4, 3).
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(0.3, 0.0, 0.0),
        Vec3::new(0.1, 0.3, 0.0),
    ];
    let viewport = Viewport {
        width: 8,
        height: 8,
    };
    let triangles = [[0, 1, 2], [3, 4, 5], [6, 7, 8]];
    let g = process_triangles(
        &positions,
        &triangles,
        &Transform::identity(),
        viewport,
        &PipelineOptions::default(),
    )
    .unwrap();
    assert_eq!(
        (g.stats.empty_bounds, g.stats.triangles),
        (2, 1),
        "{:?}",
        g.stats
    );
    assert_eq!(g.source, vec![2]);
    let b = g.setups[0].bounds;
    assert_eq!((b.x0, b.y0, b.x1, b.y1), (4, 3, 4, 3));
}

#[test]
fn bad_indices_and_arrays_are_errors() {
    let positions = vec![Vec3::ZERO, Vec3::X, Vec3::Y];
    let vp = Viewport {
        width: 4,
        height: 4,
    };
    let opts = PipelineOptions::default();
    assert!(matches!(
        process_triangles(&positions, &[[0, 1, 3]], &Transform::identity(), vp, &opts),
        Err(Error::IndexOutOfRange { index: 3, count: 3 })
    ));
    assert!(matches!(
        assemble(Topology::List, None, 4),
        Err(Error::BadArrayLength { .. })
    ));
    assert!(matches!(
        assemble(Topology::Strip, Some(&[0, 1, 2, 7]), 3),
        Err(Error::IndexOutOfRange { index: 7, .. })
    ));
    let nan = vec![Vec3::ZERO, Vec3::new(f32::NAN, 0., 0.), Vec3::Y];
    assert!(matches!(
        process_triangles(&nan, &[[0, 1, 2]], &Transform::identity(), vp, &opts),
        Err(Error::NonFinite { .. })
    ));
    assert!(matches!(
        vp.to_screen(Vec4::new(0., 0., 0., 0.)),
        Err(Error::NonPositiveW { .. })
    ));
    assert!(matches!(
        vp.to_screen(Vec4::new(0., 0., 0., -1.)),
        Err(Error::NonPositiveW { .. })
    ));
}

#[test]
fn strips_and_fans_keep_one_winding() {
    // A strip and a fan over the same square: with back-face culling on,
    // nothing is culled, and both cover the same pixels as the list.
    let square = vec![
        Vec3::new(-1., -1., 0.),
        Vec3::new(1., -1., 0.),
        Vec3::new(-1., 1., 0.),
        Vec3::new(1., 1., 0.),
    ];
    let opts = PipelineOptions {
        cull: CullMode::Back,
        ..PipelineOptions::default()
    };
    let vp = Viewport {
        width: 6,
        height: 6,
    };
    for (topology, indices) in [
        (Topology::Strip, vec![0, 1, 2, 3]),
        (Topology::Fan, vec![0, 1, 3, 2]),
    ] {
        let tris = assemble(topology, Some(&indices), 4).unwrap();
        let g = process_triangles(&square, &tris, &Transform::identity(), vp, &opts).unwrap();
        assert_eq!((g.stats.culled, g.stats.triangles), (0, 2), "{topology}");
        let mut target = RenderTarget::new(6, 6).unwrap();
        draw(
            &g,
            triangle_backends()[1],
            &Flat,
            DepthState::DEFAULT,
            Interpolation::Linear,
            &mut target,
        );
        assert_eq!(
            target.pixels_with_coverage(1),
            36,
            "{topology}: every pixel exactly once"
        );
    }
}

fn small_settings(shading: Shading) -> RenderSettings {
    RenderSettings {
        width: 96,
        height: 72,
        azimuth: 40.0,
        shading,
        ..RenderSettings::default()
    }
}

/// A rendered mesh is bit-identical across every triangle back-end, for
/// every shading, both interpolations, culling on and off.
#[test]
fn meshes_are_bit_identical_across_backends() {
    for (mesh, name) in [
        (asset("bunny.ply"), "bunny"),
        (asset("dragon_vrip_res4.ply.gz"), "dragon"),
    ] {
        for shading in [
            Shading::Flat,
            Shading::Gouraud,
            Shading::Diffuse,
            Shading::Normals,
            Shading::Texture,
        ] {
            for (interpolation, cull) in [
                (Interpolation::PerspectiveCorrect, CullMode::Back),
                (Interpolation::Linear, CullMode::None),
            ] {
                let mut settings = small_settings(shading);
                settings.interpolation = interpolation;
                settings.pipeline.cull = cull;
                let renderer = MeshRenderer::new(&mesh, settings).unwrap();
                let reference = renderer.render(triangle_backends()[0]).unwrap();
                assert!(reference.stats.work.fragments > 500, "{name} is drawn");
                // One framebuffer without coverage count, redrawn by each
                // back-end: the same colour and depth as a fresh target.
                let (w, h) = (settings.width, settings.height);
                let mut reused = RenderTarget::without_coverage(w, h).unwrap();
                for b in &triangle_backends()[1..] {
                    let frame = renderer.render(*b).unwrap();
                    assert!(
                        frame.target == reference.target,
                        "{name}, {shading}, {interpolation}, {cull}: {} differs from naive",
                        b.name()
                    );
                    renderer.render_into(*b, &mut reused).unwrap();
                    assert!(
                        reused.color == reference.target.color
                            && reused.depth == reference.target.depth,
                        "{name}, {shading}, {interpolation}, {cull}: {} into a reused target",
                        b.name()
                    );
                }
            }
        }
    }
}

/// Golden images, compared exactly. `RASTERLAB_BLESS=1 cargo test` rewrites them.
#[test]
fn golden_images() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden");
    let bless = std::env::var_os("RASTERLAB_BLESS").is_some();
    let mut cases: Vec<(&str, RenderTarget)> = Vec::new();
    let bunny = asset("bunny.ply");
    let dragon = asset("dragon_vrip_res4.ply.gz");
    let render = |mesh: &Mesh, settings: RenderSettings| {
        MeshRenderer::new(mesh, settings)
            .unwrap()
            .render(triangle_backend("scanline").unwrap())
            .unwrap()
            .target
    };
    cases.push((
        "bunny-diffuse",
        render(&bunny, small_settings(Shading::Diffuse)),
    ));
    cases.push((
        "bunny-gouraud-cull-back",
        render(
            &bunny,
            RenderSettings {
                pipeline: PipelineOptions {
                    cull: CullMode::Back,
                    ..PipelineOptions::default()
                },
                ..small_settings(Shading::Gouraud)
            },
        ),
    ));
    cases.push((
        "dragon-texture-nearest",
        render(
            &dragon,
            RenderSettings {
                filter: Filter::Nearest,
                zoom: 1.5,
                ..small_settings(Shading::Texture)
            },
        ),
    ));
    cases.push((
        "bunny-wireframe",
        render(
            &bunny,
            RenderSettings {
                width: 160,
                height: 120,
                zoom: 2.0,
                wireframe: Some(rasterlab::raster::line_backend("bresenham").unwrap()),
                ..small_settings(Shading::Flat)
            },
        ),
    ));
    cases.push((
        "depth-example",
        Scene2D::depth_example(true)
            .render(triangle_backends()[0], FillRule::TopLeft, &Flat)
            .unwrap()
            .0,
    ));
    for (name, target) in cases {
        let path = dir.join(format!("{name}.png"));
        if bless {
            target.save_png(&path).unwrap();
            continue;
        }
        let golden = image::open(&path)
            .unwrap_or_else(|e| {
                panic!(
                    "{}: {e} (run with RASTERLAB_BLESS=1 to create it)",
                    path.display()
                )
            })
            .to_rgba8();
        assert!(
            golden == target.to_image(),
            "{name} differs from {}",
            path.display()
        );
    }
}

/// A floor quad receding from the camera, textured with an 8x8
/// checkerboard sampled nearest. Perspective-correct interpolation puts
/// every pixel's colour where the analytic ray-plane intersection says;
/// linear interpolation gets many wrong.
#[test]
fn perspective_correct_checkerboard_matches_the_analytic_answer() {
    let (w, h) = (64u32, 48u32);
    let projection = Mat4::perspective_rh_gl(60f32.to_radians(), w as f32 / h as f32, 0.5, 50.0);
    let view = Mat4::look_at_rh(Vec3::new(0., 1., 0.), Vec3::new(0., 0., -6.), Vec3::Y);
    let transform = Transform::new(Mat4::IDENTITY, view, projection);
    // The floor y = 0 for x in [-2, 2], z in [-1, -9]; uv = ((x+2)/4, (z+1)/-8).
    let corners = [(-2., -1.), (2., -1.), (2., -9.), (-2., -9.)];
    let vertices: Vec<(Vec3, Vec2)> = corners
        .iter()
        .map(|&(x, z)| {
            (
                Vec3::new(x, 0., z),
                Vec2::new((x + 2.) / 4., (z + 1.) / -8.),
            )
        })
        .collect();
    let shader = |v: &(Vec3, Vec2)| ClipVertex {
        position: transform.mvp * v.0.extend(1.0),
        varyings: Varyings {
            uv: v.1,
            ..Varyings::default()
        },
    };
    let geometry = process_triangles(
        &vertices,
        &[[0, 1, 2], [0, 2, 3]],
        &shader,
        Viewport {
            width: w,
            height: h,
        },
        &PipelineOptions::default(),
    )
    .unwrap();
    let (black, white) = (Vec4::new(0., 0., 0., 1.), Vec4::ONE);
    let texture = Textured {
        texture: Texture::checkerboard(8, 1, white, black),
        filter: Filter::Nearest,
        light: None,
    };
    let inverse = transform.mvp.inverse();
    let mut wrong = [0usize; 2];
    let mut checked = 0;
    for (k, interpolation) in [Interpolation::PerspectiveCorrect, Interpolation::Linear]
        .into_iter()
        .enumerate()
    {
        let mut target = RenderTarget::new(w, h).unwrap();
        draw(
            &geometry,
            triangle_backends()[2],
            &texture,
            DepthState::DEFAULT,
            interpolation,
            &mut target,
        );
        for y in 0..h {
            for x in 0..w {
                if target.coverage[target.index(x, y)] == 0 {
                    continue;
                }
                // The ray through the pixel centre, intersected with y = 0.
                let ndc = Vec2::new(
                    (x as f32 + 0.5) / w as f32 * 2. - 1.,
                    1. - (y as f32 + 0.5) / h as f32 * 2.,
                );
                let near = inverse.project_point3(ndc.extend(-1.0));
                let far = inverse.project_point3(ndc.extend(1.0));
                let t = near.y / (near.y - far.y);
                let p = near + (far - near) * t;
                let (u, v) = (((p.x + 2.) / 4.) * 8., ((p.z + 1.) / -8.) * 8.);
                // Skip pixels whose centre is within a hair of a square's border.
                if (u - u.round()).abs() < 0.02 || (v - v.round()).abs() < 0.02 {
                    continue;
                }
                let expected = if (u.floor() as i64 + v.floor() as i64) % 2 == 0 {
                    [255, 255, 255, 255]
                } else {
                    [0, 0, 0, 255]
                };
                if k == 0 {
                    checked += 1;
                }
                if target.color[target.index(x, y)] != expected {
                    wrong[k] += 1;
                }
            }
        }
    }
    assert!(checked > 1000, "{checked} pixels checked");
    assert_eq!(
        wrong[0], 0,
        "perspective-correct interpolation misplaces {} pixels",
        wrong[0]
    );
    assert!(
        wrong[1] > 100,
        "linear interpolation should visibly differ, only {} pixels did",
        wrong[1]
    );
}

/// Clip-space coordinates: ordinary ones, large ones (a million times the
/// screen), and ones near zero (w near zero).
fn clip_coordinate() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => -3.0f32..3.0,
        1 => -1e6f32..1e6,
        1 => -1e-6f32..1e-6,
        1 => Just(0.0f32),
    ]
}

/// Extreme clip-space coordinates, beyond what f64 intersects exactly.
fn extreme_coordinate() -> impl Strategy<Value = f32> {
    prop_oneof![
        Just(f32::MAX),
        Just(-f32::MAX),
        Just(1e30f32),
        Just(-1e30f32),
        Just(1e-30f32),
        Just(0.0f32),
        -3.0f32..3.0,
    ]
}

proptest! {
    #![proptest_config(crate::common::proptest_config(4000, "tests/proptest-regressions/pipeline.txt"))]

    /// Triangles anywhere in clip space (across the near plane, behind the
    /// camera, huge, with w near zero): no error, every fragment lies where
    /// the clip-space triangle really is inside the frustum, and every pixel
    /// the triangle clearly covers inside the frustum is drawn.
    #[test]
    fn clipping_draws_exactly_the_visible_part(
        t in proptest::array::uniform3((clip_coordinate(), clip_coordinate(), clip_coordinate(), clip_coordinate()))
    ) {
        properties::clipping_draws_exactly_the_visible_part(t)?;
    }

    /// Extreme coordinates (up to f32::MAX) are no error and no panic; what
    /// is drawn stays on the target with depths in range.
    #[test]
    fn extreme_coordinates_never_fail(
        t in proptest::array::uniform3((extreme_coordinate(), extreme_coordinate(), extreme_coordinate(), extreme_coordinate()))
    ) {
        properties::extreme_coordinates_never_fail(t)?;
    }

    /// With a depth test and no two triangles at equal depth, the image
    /// does not depend on the drawing order.
    #[test]
    fn the_depth_buffer_makes_drawing_order_irrelevant(
        soup in common::triangle_soup(12),
        order in Just((0..12usize).collect::<Vec<_>>()).prop_shuffle(),
    ) {
        let n = soup.len();
        let vertex = |i: usize| {
            // Distinct constant depths, distinct colours.
            [ShadedVertex::flat((i as f32 + 1.0) / 16.0, rasterlab::geometry::scene_colour(i)); 3]
        };
        let order: Vec<usize> = order.into_iter().filter(|&i| i < n).collect();
        let scene = |idx: &[usize]| Scene2D {
            width: common::SIZE,
            height: common::SIZE,
            triangles: idx.iter().map(|&i| soup[i]).collect(),
            vertices: idx.iter().map(|&i| vertex(i)).collect(),
        };
        let identity: Vec<usize> = (0..n).collect();
        for b in &triangle_backends()[1..] {
            let render = |s: Scene2D| {
                let mut t = RenderTarget::new(common::SIZE, common::SIZE).unwrap();
                s.draw(*b, FillRule::TopLeft, DepthState::DEFAULT, &Flat, &mut t);
                t
            };
            prop_assert!(render(scene(&identity)) == render(scene(&order)), "{}", b.name());
        }
    }
}

/// A wall crossing the near plane: the part in front of the camera is
/// drawn, to the bottom edge of the screen.
#[test]
fn a_triangle_through_the_camera_is_cut_at_the_near_plane() {
    let (w, h) = (32u32, 24u32);
    let projection = Mat4::perspective_rh_gl(90f32.to_radians(), w as f32 / h as f32, 0.1, 100.0);
    let transform = Transform::new(Mat4::IDENTITY, Mat4::IDENTITY, projection);
    // A floor under the camera reaching from behind it (z = +5) to z = -20.
    let floor = [
        Vec3::new(-30., -1., 5.),
        Vec3::new(30., -1., 5.),
        Vec3::new(0., -1., -20.),
    ];
    let geometry = process_triangles(
        &floor,
        &[[0, 1, 2]],
        &transform,
        Viewport {
            width: w,
            height: h,
        },
        &PipelineOptions::default(),
    )
    .unwrap();
    assert_eq!(geometry.stats.clipped, 1);
    let mut target = RenderTarget::new(w, h).unwrap();
    draw(
        &geometry,
        triangle_backends()[3],
        &Constant(Vec4::ONE),
        DepthState::DEFAULT,
        Interpolation::PerspectiveCorrect,
        &mut target,
    );
    // The whole bottom half is floor; the top half is sky.
    for x in 0..w {
        assert!(
            target.coverage[target.index(x, h - 1)] == 1,
            "bottom row, column {x}"
        );
        assert!(
            target.coverage[target.index(x, 0)] == 0,
            "top row, column {x}"
        );
    }
}

/// Shrunk from `clipping_draws_exactly_the_visible_part`: a vertex at
/// infinity (w = 0) whose edge, clipped at the guard band 16,000 px away,
/// passes 1/200 px from pixel (9, 10)'s centre. The pixel is inside.
#[test]
fn regression_edge_to_a_point_at_infinity_passes_a_hair_above_a_pixel_centre() {
    let tri = [
        Vec4::new(-2.7202687, 0.5258993, 0.0, 0.0),
        Vec4::new(0.66660595, -1.158189, 0.0, 2.9193134),
        Vec4::new(0.0, -0.72356486, 0.0, 2.8196368),
    ];
    let geometry = properties::clip_space_geometry(&tri, 24, 16);
    assert_eq!((geometry.stats.clipped, geometry.stats.triangles), (1, 2));
    let mut target = RenderTarget::new(24, 16).unwrap();
    draw(
        &geometry,
        triangle_backends()[0],
        &Flat,
        DepthState::DEFAULT,
        Interpolation::PerspectiveCorrect,
        &mut target,
    );
    assert_eq!(target.coverage[target.index(9, 10)], 1);
    assert_eq!(target.coverage[target.index(9, 11)], 0);
}

/// The clipping property's oracle is no check that cannot fail: on a
/// triangle in front of the camera it decides every pixel but those
/// within 1/100 px of an edge (here, the centres the edges pass through),
/// and agrees with the 2D triangle drawn at the projected vertices;
/// beyond the far plane it says "not visible".
#[test]
fn the_clipping_oracle_decides_what_it_can_and_is_right() {
    // Projected: (6, 4), (20, 6), (8, 14) on a 24 x 16 target, w = 2.
    let to_clip = |(x, y): (f64, f64), z: f32| {
        Vec4::new(
            ((x / 24.0 * 2.0 - 1.0) * 2.0) as f32,
            ((1.0 - y / 16.0 * 2.0) * 2.0) as f32,
            z,
            2.0,
        )
    };
    let corners = [(6.0, 4.0), (20.0, 6.0), (8.0, 14.0)];
    let tri = corners.map(|c| to_clip(c, 0.5));
    // The signed distance in pixels to the edge from a to b.
    let edge = |a: (f64, f64), b: (f64, f64), p: (f64, f64)| {
        ((b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0)) / (b.0 - a.0).hypot(b.1 - a.1)
    };
    let mut undecided = Vec::new();
    for y in 0..16 {
        for x in 0..24 {
            let centre = (f64::from(x) + 0.5, f64::from(y) + 0.5);
            let distances = [0, 1, 2].map(|i| edge(corners[i], corners[(i + 1) % 3], centre));
            let near_an_edge = distances.iter().any(|d| d.abs() < 0.01);
            match properties::oracle(&tri, centre, (24, 16)) {
                Some(answer) => {
                    assert!(!near_an_edge, "pixel ({x}, {y}) decided on an edge");
                    assert_eq!(
                        answer,
                        distances.iter().all(|d| *d > 0.0),
                        "pixel ({x}, {y})"
                    );
                }
                None => {
                    assert!(near_an_edge, "pixel ({x}, {y}) undecided");
                    undecided.push((x, y));
                }
            }
        }
    }
    assert_eq!(undecided.len(), 7, "{undecided:?}");
    let beyond_far = corners.map(|c| to_clip(c, 3.0));
    assert_eq!(
        properties::oracle(&beyond_far, (10.5, 7.5), (24, 16)),
        Some(false)
    );
}

/// Shrunk from `clipping_draws_exactly_the_visible_part`: one vertex
/// behind the camera (w = -416,380), two in front with x and y below
/// 10^-6. The part with w >= `W_MIN` covers no pixel centre (the
/// triangle's point at any centre has w of at most 4.5 x 10^-6), so
/// nothing is drawn; the test's f64 oracle, solving a system whose
/// entries span twelve orders of magnitude, once found a point at
/// w = 0.17 at pixel (20, 0), and now abstains where its solution does
/// not project back to the pixel.
#[test]
fn regression_a_triangle_whose_visible_part_is_below_w_min_draws_nothing() {
    let t = [
        (0.0, 0.0, 0.0, -416380.22),
        (0.0, 4.3147924e-7, 0.0, 34757.68),
        (8.0172055e-7, 0.0, 0.0, 107224.08),
    ];
    let tri = t.map(|(x, y, z, w)| Vec4::new(x, y, z, w));
    let geometry = properties::clip_space_geometry(&tri, 24, 16);
    assert_eq!((geometry.stats.clipped, geometry.stats.triangles), (1, 0));
    properties::clipping_draws_exactly_the_visible_part(t).unwrap();
}

/// A frame's parts add up to its time: the mesh renderer's geometry and
/// raster times, the clear folded into the raster, and the rest; a 2D
/// scene drawn frame by frame on the same path ends in the buffers of a
/// clear and a draw, for every back-end and depth state.
#[test]
fn a_frames_parts_add_up_and_the_2d_path_draws_the_same() {
    let bunny = Mesh::load(Path::new("assets/bunny.ply")).unwrap();
    let settings = RenderSettings {
        width: 96,
        height: 72,
        ..RenderSettings::default()
    };
    let renderer = MeshRenderer::new(&bunny, settings).unwrap();
    let mut target = RenderTarget::without_coverage(96, 72).unwrap();
    for &b in triangle_backends() {
        let stats = renderer.render_into(b, &mut target).unwrap();
        let t = stats.times;
        assert!(t.clear_folded);
        assert_eq!(
            (t.geometry, t.raster),
            (stats.geometry_time, stats.raster_time)
        );
        assert_eq!(t.clear + t.geometry + t.raster + t.rest, t.total());
    }
    for scene in [
        Scene2D::depth_example(true),
        Scene2D::pinwheel(),
        Scene2D::fan(),
    ] {
        for depth in [DepthState::DEFAULT, DepthState::OFF] {
            for &b in triangle_backends() {
                let mut expected = RenderTarget::new(scene.width, scene.height).unwrap();
                scene.draw(b, FillRule::TopLeft, depth, &Flat, &mut expected);
                let mut used = expected.clone();
                used.color.fill([1, 2, 3, 4]);
                used.depth.fill(0.0);
                let (work, times) = scene.render_frame(
                    b,
                    FillRule::TopLeft,
                    (depth, Blend::REPLACE),
                    &Flat,
                    RenderTarget::BLACK,
                    &mut used,
                );
                assert!(used == expected, "{}", b.name());
                assert!(work.fragments > 0);
                assert_eq!(times.geometry + times.raster + times.rest, times.total());
            }
        }
    }
}

/// Clipping at the viewport's own sides (`render --clip viewport`)
/// against the guard band (the default), on the bundled dragon at
/// 1280x720, zoomed so that it crosses every side (2.5) and with the
/// camera among its coils (12). The viewport planes cut every triangle
/// crossing a side, and the new vertices are snapped to 1/256 px like
/// any other: where a cut edge meets the side it moves by up to 1/512
/// px (further in along an edge nearly parallel to the side), so a pixel
/// centre close to it can change sides, and the fan's new triangles
/// interpolate from rounded vertices. Measured: at 2.5, 52 pixels differ,
/// one of them in coverage, by at most 1/255 in colour; at 12, 68, one in
/// coverage, the others where two neighbouring triangles trade a pixel
/// (at most 2/255). Both are far from a visible change, and every back-end
/// draws the clipped frame alike.
#[test]
fn viewport_clipping_differs_from_the_guard_band_only_where_vertices_snap() {
    let dragon = asset("dragon_vrip_res4.ply.gz");
    for zoom in [2.5, 12.0] {
        let frame = |clip: ClipPlanes, backend: &str| {
            let settings = RenderSettings {
                width: 1280,
                height: 720,
                zoom,
                pipeline: PipelineOptions {
                    cull: CullMode::Back,
                    clip,
                    ..PipelineOptions::default()
                },
                ..RenderSettings::default()
            };
            MeshRenderer::new(&dragon, settings)
                .unwrap()
                .render(triangle_backend(backend).unwrap())
                .unwrap()
        };
        let guard = frame(ClipPlanes::GuardBand, "scanline");
        let viewport = frame(ClipPlanes::Viewport, "scanline");
        assert!(
            viewport.stats.geometry.clipped > guard.stats.geometry.clipped,
            "{zoom}: the viewport cuts more triangles"
        );
        let background = guard.target.color[0];
        let (mut differ, mut coverage, mut worst) = (0, 0, 0);
        for (a, b) in guard.target.color.iter().zip(&viewport.target.color) {
            if a != b {
                differ += 1;
                if (*a == background) != (*b == background) {
                    coverage += 1;
                } else {
                    worst = worst.max((0..3).map(|k| a[k].abs_diff(b[k])).max().unwrap());
                }
            }
        }
        assert!(differ > 0, "{zoom}: some new vertex snaps");
        assert!(
            differ <= 200 && coverage <= 4 && worst <= 2,
            "{zoom}: {differ} pixels, {coverage} in coverage, {worst}/255"
        );
        for name in ["bbox", "incremental", "tiled"] {
            assert!(
                frame(ClipPlanes::Viewport, name).target == viewport.target,
                "{zoom}: {name}"
            );
        }
    }
}
