//! Mipmapped textures through the stage: a receding checkerboard floor,
//! the plane that aliases in every course, drawn under each pixel filter,
//! level mode, derivative method and anisotropy by every triangle
//! back-end.

use glam::{Mat4, Vec2, Vec3, Vec4};
use rasterlab::geometry::{
    draw, process_triangles, ClipVertex, PipelineOptions, Transform, Viewport,
};
use rasterlab::raster::{
    quad_helpers, triangle_backends, DepthState, Derivatives, Filter, FragmentList, Interpolation,
    LevelMode, Mipmapped, PixelRect, RenderTarget, Sampler, Texture, Varyings, Wrap,
};

const SIZE: (u32, u32) = (96, 64);

/// The floor y = 0, x in [-4, 4], z in [-1, -60], seen from one unit above
/// it; its uv repeats the texture 4 times across and 30 times along.
fn floor() -> rasterlab::geometry::Geometry {
    let (w, h) = SIZE;
    let projection = Mat4::perspective_rh_gl(60f32.to_radians(), w as f32 / h as f32, 0.5, 100.0);
    let view = Mat4::look_at_rh(Vec3::new(0., 1., 0.), Vec3::new(0., 0.3, -10.), Vec3::Y);
    let transform = Transform::new(Mat4::IDENTITY, view, projection);
    let corners = [(-4., -1.), (4., -1.), (4., -60.), (-4., -60.)];
    let vertices: Vec<(Vec3, Vec2)> = corners
        .iter()
        .map(|&(x, z)| {
            (
                Vec3::new(x, 0., z),
                Vec2::new((x + 4.) / 2., (z + 1.) / -2.),
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
    process_triangles(
        &vertices,
        &[[0, 1, 2], [0, 2, 3]],
        &shader,
        Viewport {
            width: w,
            height: h,
        },
        &PipelineOptions::default(),
    )
    .unwrap()
}

fn checkerboard() -> Texture {
    Texture::checkerboard(8, 4, Vec4::ONE, Vec4::new(0.1, 0.2, 0.6, 1.0))
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
                for anisotropy in [1, 4, 16] {
                    let sampler = Sampler {
                        filter,
                        levels,
                        wrap: Wrap::Repeat,
                        anisotropy,
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
                                "{} differs under {filter} {levels} {method} x{anisotropy}",
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
