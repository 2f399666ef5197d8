//! Binned, multi-threaded drawing and the stage's span path give the very
//! same bits as the single-threaded, fragment-by-fragment path.

mod common;
#[path = "properties/parallel.rs"]
mod properties;

use glam::{Mat4, Vec3, Vec4};
use properties::soup_geometry;
use proptest::prelude::*;
use rasterlab::geometry::{
    draw, draw_binned, draw_clearing, process_triangles, process_triangles_into, CullMode,
    Geometry, Mesh, MeshRenderer, PipelineOptions, RenderSettings, Shading, Transform, Viewport,
};
use rasterlab::raster::{
    triangle_backends, Clear, Constant, DepthState, DepthTest, Flat, FragmentList, FragmentShader,
    FragmentSink, FragmentStage, Gouraud, Interpolation, PixelRect, RenderTarget,
};
use std::path::Path;

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
}

/// Twelve bunnies, the k-th moved by `offset(k)`: 44k triangles, so
/// several chunks of geometry work on two threads or more.
fn twelve_bunnies(offset: impl Fn(u32) -> Vec3) -> Mesh {
    let one = Mesh::load(Path::new("assets/bunny.ply")).unwrap();
    let n = one.positions.len() as u32;
    Mesh::new(
        (0..12)
            .flat_map(|k| {
                one.positions
                    .iter()
                    .map(|p| *p + offset(k))
                    .collect::<Vec<_>>()
            })
            .collect(),
        (0..12)
            .flat_map(|k| one.triangles.iter().map(move |t| t.map(|i| i + k * n)))
            .collect(),
    )
    .unwrap()
}

/// Twelve bunnies seen from a camera inside them: many triangles meet the
/// near plane, so clipping makes vertices of its own in every chunk. The
/// geometry is the same on 1, 2 and 3 threads, and the same whether it is
/// built fresh or into buffers used for another draw.
#[test]
fn clipped_geometry_is_the_same_on_any_number_of_threads_and_when_reused() {
    let bunny = twelve_bunnies(|k| Vec3::splat(k as f32 * 0.002));
    let (lo, hi) = bunny.bounds();
    // The near plane runs through the middle of the bunnies.
    let centre = (lo + hi) * 0.5;
    let distance = (hi - lo).length();
    let eye = centre + Vec3::new(0.3, 0.2, 1.0).normalize() * distance;
    let view = Mat4::look_at_rh(eye, centre, Vec3::Y);
    let projection = Mat4::perspective_rh_gl(0.8, 4.0 / 3.0, distance, 10.0 * distance);
    let shader = Transform::new(Mat4::IDENTITY, view, projection);
    let viewport = Viewport {
        width: 160,
        height: 120,
    };
    let options = PipelineOptions::default();
    let process = |threads: usize| {
        pool(threads).install(|| {
            process_triangles(
                &bunny.positions,
                &bunny.triangles,
                &shader,
                viewport,
                &options,
            )
            .unwrap()
        })
    };
    let reference = process(1);
    assert!(reference.stats.clipped > 2000, "{:?}", reference.stats);
    assert!(reference.stats.triangles > 2000, "{:?}", reference.stats);
    assert!(reference.shaded.vertices.len() > bunny.positions.len() + 2000);
    for threads in [2, 3] {
        let parallel = process(threads);
        assert_eq!(parallel.setups, reference.setups, "{threads} threads");
        assert_eq!(parallel.shaded, reference.shaded, "{threads} threads");
        assert_eq!(parallel.source, reference.source, "{threads} threads");
        assert_eq!(parallel.stats, reference.stats, "{threads} threads");
    }
    // Buffers that held another draw (the bunny from outside, with
    // culling) give the same result as fresh ones.
    for threads in [1, 2] {
        let mut reused = Geometry::default();
        let other = Transform::new(
            Mat4::IDENTITY,
            Mat4::from_translation(-eye - Vec3::Z),
            projection,
        );
        let culled = PipelineOptions {
            cull: CullMode::Back,
            ..options
        };
        pool(threads).install(|| {
            process_triangles_into(
                &mut reused,
                &bunny.positions,
                &bunny.triangles,
                &other,
                viewport,
                &culled,
            )
            .unwrap();
            assert_ne!(reused.setups, reference.setups);
            process_triangles_into(
                &mut reused,
                &bunny.positions,
                &bunny.triangles,
                &shader,
                viewport,
                &options,
            )
            .unwrap();
        });
        assert_eq!(reused.setups, reference.setups, "{threads} threads");
        assert_eq!(reused.shaded, reference.shaded, "{threads} threads");
        assert_eq!(reused.source, reference.source, "{threads} threads");
        assert_eq!(reused.stats, reference.stats, "{threads} threads");
    }
}

/// Twelve bunnies side by side in a 4 x 3 grid, framed from so close (zoom
/// 8) that the near plane cuts through every one of them. On several
/// threads the renderer leaves the triangles in the chunks that assembled
/// them, clipped ones included, and bins and draws them from there; every
/// back-end's frame equals the single-threaded one, frame after frame.
#[test]
fn frames_drawn_from_assembly_chunks_equal_the_single_threaded_frame() {
    let bunnies = twelve_bunnies(|k| Vec3::new((k % 4) as f32, (k / 4) as f32, 0.0) * 0.15);
    let settings = RenderSettings {
        width: 320,
        height: 240,
        zoom: 8.0,
        elevation: 0.0,
        shading: Shading::Gouraud,
        ..RenderSettings::default()
    };
    let renderer = MeshRenderer::new(&bunnies, settings).unwrap();
    let reference = pool(1).install(|| renderer.render(triangle_backends()[2]).unwrap());
    let stats = reference.stats.geometry;
    assert!(stats.clipped > 1000, "{stats:?}");
    assert!(stats.triangles > 3000, "{stats:?}");
    for threads in [2, 3] {
        for b in triangle_backends().iter().skip(1) {
            for frame in 0..2 {
                let drawn = pool(threads).install(|| renderer.render(*b).unwrap());
                assert!(
                    drawn.target == reference.target,
                    "{threads} threads, {}, frame {frame}",
                    b.name()
                );
                assert_eq!(drawn.stats.geometry, stats);
                assert_eq!(drawn.stats.work.fragments, reference.stats.work.fragments);
            }
        }
    }
}

/// On one thread the renderer assembles and draws the triangles a batch
/// at a time, each batch's set-ups drawn before the next batch is
/// assembled into the same buffers. Twelve bunnies (44k triangles, many
/// batches), cut by the near plane (clip vertices in every batch) or
/// framed whole (rows above and below them that no batch writes), drawn
/// so by every back-end, into a fresh and into a used target, give the
/// buffers, the counts and the work of the whole geometry drawn at once.
#[test]
fn frames_drawn_batch_by_batch_equal_the_whole_geometry_drawn_at_once() {
    let bunnies = twelve_bunnies(|k| Vec3::new((k % 4) as f32, (k / 4) as f32, 0.0) * 0.15);
    for zoom in [8.0, 1.0] {
        frame_batch_by_batch_equals_whole_geometry(&bunnies, zoom);
    }
}

fn frame_batch_by_batch_equals_whole_geometry(bunnies: &Mesh, zoom: f32) {
    let settings = RenderSettings {
        width: 320,
        height: 240,
        zoom,
        elevation: 0.0,
        shading: Shading::Gouraud,
        ..RenderSettings::default()
    };
    let renderer = MeshRenderer::new(bunnies, settings).unwrap();
    let geometry = pool(1).install(|| renderer.geometry().unwrap());
    let stats = geometry.stats;
    assert!(stats.triangles > 3000, "{stats:?}");
    if zoom > 1.0 {
        assert!(stats.clipped > 1000, "{stats:?}");
    }
    // All but the naive loop, which tests every pixel for every triangle.
    for b in triangle_backends().iter().skip(1) {
        let mut whole = RenderTarget::new(320, 240).unwrap();
        let clear = Clear::all(settings.background);
        let work = draw_clearing(
            &geometry,
            *b,
            &Gouraud,
            settings.depth,
            settings.interpolation,
            clear,
            &mut whole,
        );
        let mut used = whole.clone();
        used.color.iter_mut().for_each(|c| c[1] ^= 0x33);
        used.depth.iter_mut().for_each(|d| *d *= 0.5);
        used.coverage.iter_mut().for_each(|k| *k += 2);
        for target in [RenderTarget::new(320, 240).unwrap(), used] {
            let mut target = target;
            let stats = pool(1).install(|| renderer.render_into(*b, &mut target).unwrap());
            assert!(target == whole, "zoom {zoom}, {}", b.name());
            assert_eq!(stats.geometry, geometry.stats, "zoom {zoom}, {}", b.name());
            assert_eq!(stats.work, work, "zoom {zoom}, {}", b.name());
        }
    }
}

/// The bunny (3.7k triangles) is processed and drawn identically on 1, 2
/// and 3 threads by every back-end.
#[test]
fn meshes_render_identically_on_any_number_of_threads() {
    let bunny = Mesh::load(Path::new("assets/bunny.ply")).unwrap();
    for (shading, cull) in [
        (Shading::Flat, CullMode::None),
        (Shading::Diffuse, CullMode::Back),
    ] {
        let mut settings = RenderSettings {
            width: 200,
            height: 150,
            azimuth: 30.0,
            shading,
            ..RenderSettings::default()
        };
        settings.pipeline.cull = cull;
        let renderer = MeshRenderer::new(&bunny, settings).unwrap();
        let reference = pool(1).install(|| renderer.render(triangle_backends()[2]).unwrap());
        assert!(reference.stats.work.fragments > 5000);
        let geometry = pool(1).install(|| renderer.geometry().unwrap());
        for threads in [2, 3] {
            let parallel = pool(threads).install(|| renderer.geometry().unwrap());
            assert_eq!(parallel.setups, geometry.setups, "{threads} threads");
            assert_eq!(parallel.shaded, geometry.shaded, "{threads} threads");
            assert_eq!(parallel.source, geometry.source, "{threads} threads");
            assert_eq!(parallel.stats, geometry.stats, "{threads} threads");
            for b in triangle_backends().iter().skip(1) {
                let frame = pool(threads).install(|| renderer.render(*b).unwrap());
                assert!(
                    frame.target == reference.target,
                    "{shading}, {threads} threads, {}",
                    b.name()
                );
                assert_eq!(frame.stats.work.fragments, reference.stats.work.fragments);
                // Into a used target, whose clear is folded into the draw
                // band by band: the same frame.
                let mut used = reference.target.clone();
                used.color.iter_mut().for_each(|c| c[0] ^= 0x55);
                used.depth.iter_mut().for_each(|d| *d *= 0.5);
                used.coverage.iter_mut().for_each(|k| *k += 3);
                pool(threads).install(|| renderer.render_into(*b, &mut used).unwrap());
                assert!(
                    used == reference.target,
                    "{shading}, {threads} threads, {}, used target",
                    b.name()
                );
            }
        }
    }
}

/// A mipmapped frame (trilinear, quad derivatives) is drawn band by band
/// on rayon's threads: the bunny textured, and the receding floor, are
/// the same bits on 1, 2 and 3 threads, by the scanline and tiled
/// back-ends, into a fresh target and into a used one.
#[test]
fn mipmapped_frames_are_the_same_on_any_number_of_threads() {
    use rasterlab::geometry::Floor;
    use rasterlab::raster::triangle::TriangleRasterizer;
    use rasterlab::raster::{Derivatives, LevelMode, Sampler};
    let bunny = Mesh::load(Path::new("assets/bunny.ply")).unwrap();
    let settings = RenderSettings {
        width: 200,
        height: 150,
        zoom: 3.0,
        shading: Shading::Texture,
        mip: LevelMode::Linear,
        derivatives: Derivatives::Quad,
        ..RenderSettings::default()
    };
    let renderer = MeshRenderer::new(&bunny, settings).unwrap();
    let floor = Floor::new(160, 100).unwrap();
    let trilinear = Sampler {
        levels: LevelMode::Linear,
        ..Sampler::default()
    };
    let shader = floor.shader(trilinear, Derivatives::Quad);
    let draw_floor = |b: &dyn TriangleRasterizer, target: &mut RenderTarget| {
        floor.draw(b, &shader, target);
    };
    let backends = triangle_backends()
        .iter()
        .filter(|b| ["scanline", "tiled"].contains(&b.name()));
    for b in backends {
        let reference = pool(1).install(|| renderer.render(*b).unwrap());
        assert!(reference.stats.work.fragments > 5000);
        let mut floor_reference = RenderTarget::new(160, 100).unwrap();
        pool(1).install(|| draw_floor(*b, &mut floor_reference));
        for threads in [2, 3] {
            let frame = pool(threads).install(|| renderer.render(*b).unwrap());
            assert!(
                frame.target == reference.target,
                "bunny, {threads} threads, {}",
                b.name()
            );
            let mut used = reference.target.clone();
            used.color.iter_mut().for_each(|c| c[0] ^= 0x55);
            used.depth.iter_mut().for_each(|d| *d *= 0.5);
            pool(threads).install(|| renderer.render_into(*b, &mut used).unwrap());
            assert!(
                used.color == reference.target.color,
                "bunny, {threads} threads, used target"
            );
            let mut floor_frame = floor_reference.clone();
            floor_frame.color.iter_mut().for_each(|c| c[1] ^= 0x0f);
            pool(threads).install(|| draw_floor(*b, &mut floor_frame));
            assert!(
                floor_frame.color == floor_reference.color,
                "floor, {threads} threads, {}",
                b.name()
            );
        }
    }
}

/// Feeds the fragments of `list` to a stage one at a time.
fn replay(
    list: &FragmentList,
    geometry: &Geometry,
    shader: &dyn FragmentShader,
    depth: DepthState,
    target: &mut RenderTarget,
) {
    let mut stage = FragmentStage::new(target, shader)
        .with_triangles(&geometry.shaded)
        .with_depth(depth);
    for f in &list.triangles {
        stage.triangle_fragment(f);
    }
}

proptest! {
    #![proptest_config(crate::common::proptest_config(600, "tests/proptest-regressions/parallel.txt"))]

    /// Soups drawn in bands on 2 and 3 threads (8-row bands on this small
    /// target, so triangles cross bands) equal the single-threaded draw.
    #[test]
    fn binned_soups_equal_the_single_threaded_draw(
        soup in common::triangle_soup(24),
        depths in proptest::collection::vec(0.0f32..1.0, 1..8),
        backend in 0..rasterlab::raster::triangle_backends().len(),
    ) {
        let geometry = soup_geometry(&soup, &depths);
        let b = triangle_backends()[backend];
        for shader in [&Flat as &dyn FragmentShader, &Gouraud] {
            let mut reference = RenderTarget::new(common::SIZE, common::SIZE).unwrap();
            draw(&geometry, b, shader, DepthState::DEFAULT, Interpolation::PerspectiveCorrect, &mut reference);
            for threads in [2, 3] {
                let mut target = RenderTarget::new(common::SIZE, common::SIZE).unwrap();
                pool(threads).install(|| draw_binned(&geometry, b, shader, DepthState::DEFAULT, Interpolation::PerspectiveCorrect, &mut target));
                prop_assert!(target == reference, "{} on {} threads", b.name(), threads);
            }
        }
    }

    /// A clear folded into the draw (each row cleared at its first
    /// fragment, the rest when the draw ends) leaves a dirty target exactly
    /// as a clear and then the draw do, for every back-end, clear and
    /// depth state.
    #[test]
    fn clears_folded_into_the_draw_equal_a_clear_then_the_draw(
        soup in common::triangle_soup(12),
        depths in proptest::collection::vec(0.0f32..1.0, 1..8),
        backend in 0..rasterlab::raster::triangle_backends().len(),
        counts in any::<bool>(),
    ) {
        properties::clears_folded_into_the_draw_equal_a_clear_then_the_draw(&soup, &depths, backend, counts)?;
    }

    /// A draw of a few triangles on one thread goes band by band (bands
    /// of 32 rows on a target 4096 pixels wide, so the soup crosses a band
    /// edge at row 32): the same bits as every triangle drawn over the
    /// whole target in turn, for every back-end, with the clear folded in.
    #[test]
    fn few_triangles_drawn_band_by_band_equal_triangle_by_triangle(
        soup in common::triangle_soup(24),
        depths in proptest::collection::vec(0.0f32..1.0, 1..8),
        backend in 0..rasterlab::raster::triangle_backends().len(),
    ) {
        let geometry = soup_geometry(&soup, &depths);
        let b = triangle_backends()[backend];
        let (w, h) = (4096, 48);
        for shader in [&Flat as &dyn FragmentShader, &Gouraud] {
            let mut whole = RenderTarget::new(w, h).unwrap();
            whole.color.fill([9, 9, 9, 9]);
            let mut banded = whole.clone();
            whole.clear();
            let mut stage = FragmentStage::new(&mut whole, shader).with_triangles(&geometry.shaded);
            b.rasterize(&geometry.setups, PixelRect::of_target(w, h), &mut stage);
            drop(stage);
            let clear = Clear::all(RenderTarget::BLACK);
            pool(1).install(|| draw_clearing(&geometry, b, shader, DepthState::DEFAULT, Interpolation::PerspectiveCorrect, clear, &mut banded));
            prop_assert!(banded == whole, "{}", b.name());
        }
    }

    /// With no depth buffer (`DepthState::OFF`, which skips every depth
    /// read and write), every back-end draws what a test that every
    /// fragment passes draws through the full depth path (`less-equal`
    /// against a buffer of 2.0, without writes), and the buffer is left
    /// as it was.
    #[test]
    fn no_depth_buffer_equals_a_test_every_fragment_passes(
        soup in common::triangle_soup(16),
        depths in proptest::collection::vec(0.0f32..1.0, 1..8),
        backend in 0..rasterlab::raster::triangle_backends().len(),
    ) {
        let geometry = soup_geometry(&soup, &depths);
        let b = triangle_backends()[backend];
        let passes = DepthState { test: DepthTest::LessEqual, write: false };
        for shader in [&Flat as &dyn FragmentShader, &Gouraud] {
            let mut off = RenderTarget::new(common::SIZE, common::SIZE).unwrap();
            off.depth.fill(2.0);
            let mut tested = off.clone();
            draw(&geometry, b, shader, DepthState::OFF, Interpolation::PerspectiveCorrect, &mut off);
            draw(&geometry, b, shader, passes, Interpolation::PerspectiveCorrect, &mut tested);
            prop_assert!(off == tested, "{}", b.name());
            prop_assert!(off.depth.iter().all(|&d| d == 2.0));
        }
    }

    /// The stage's span path (one shading per span for uniform shaders,
    /// one loop per depth comparison) writes what the fragment-by-fragment
    /// path writes, for every depth comparison, with and without depth writes.
    #[test]
    fn spans_equal_fragment_by_fragment(
        soup in common::triangle_soup(16),
        depths in proptest::collection::vec(0.0f32..1.0, 1..8),
        write in any::<bool>(),
    ) {
        let geometry = soup_geometry(&soup, &depths);
        let scanline = triangle_backends()[2];
        let mut list = FragmentList::default();
        scanline.rasterize(&geometry.setups, common::viewport(), &mut list);
        let constant = Constant(Vec4::new(0.2, 0.4, 0.6, 1.0));
        for shader in [&Flat as &dyn FragmentShader, &constant, &Gouraud] {
            for test in DepthTest::ALL {
                let depth = DepthState { test, write };
                let mut spans = RenderTarget::new(common::SIZE, common::SIZE).unwrap();
                spans.depth.fill(0.5);
                let mut fragments = spans.clone();
                draw(&geometry, scanline, shader, depth, Interpolation::PerspectiveCorrect, &mut spans);
                replay(&list, &geometry, shader, depth, &mut fragments);
                prop_assert!(spans == fragments, "{} {}", test, write);
            }
        }
    }
}
