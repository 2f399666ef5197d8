//! The folded clear's property as a function of its input, shared by the
//! property test (`tests/parallel.rs`) and the named regression tests of
//! the cases it shrank to (`tests/regressions.rs`).
#![allow(dead_code)]

use glam::Vec4;
use proptest::prelude::*;
use rasterlab::geometry::{draw, draw_clearing, setup_triangles, Geometry};
use rasterlab::raster::{
    triangle_backends, Clear, DepthState, FillRule, FixedPoint, Gouraud, Interpolation,
    RenderTarget, ShadedVertex,
};

/// A 2D soup as a draw: depths and colours per triangle from `depths`.
pub fn soup_geometry(soup: &[[FixedPoint; 3]], depths: &[f32]) -> Geometry {
    let setups = setup_triangles(soup, FillRule::TopLeft);
    let vertices: Vec<[ShadedVertex; 3]> = (0..soup.len())
        .map(|i| {
            let z = depths[i % depths.len()];
            let c = Vec4::new(z, 1.0 - z, (i % 7) as f32 / 7.0, 1.0);
            [0.0, 0.1, 0.2].map(|dz| ShadedVertex::flat((z + dz).min(1.0), c + Vec4::splat(dz)))
        })
        .collect();
    Geometry::of_screen_triangles(setups, &vertices)
}

/// A clear folded into the draw (each row cleared at its first fragment,
/// the rest when the draw ends) leaves a dirty target exactly as a clear
/// and then the draw do, for the `backend`-th back-end, every clear and
/// depth state, with coverage counted or not.
pub fn clears_folded_into_the_draw_equal_a_clear_then_the_draw(
    soup: &[[FixedPoint; 3]],
    depths: &[f32],
    backend: usize,
    counts: bool,
) -> Result<(), TestCaseError> {
    let geometry = soup_geometry(soup, depths);
    let b = triangle_backends()[backend];
    let mut dirty = RenderTarget::new(crate::common::SIZE, crate::common::SIZE).unwrap();
    if !counts {
        dirty.coverage = Vec::new();
    }
    for (i, (c, d)) in dirty
        .color
        .iter_mut()
        .zip(dirty.depth.iter_mut())
        .enumerate()
    {
        *c = [i as u8, 7, (i / 256) as u8, 200];
        *d = (i % 11) as f32 / 10.0;
    }
    dirty.coverage.fill(5);
    let clears = [
        Clear::NOTHING,
        Clear::DEPTH_AND_COVERAGE,
        Clear::color([9, 8, 7, 255]),
        Clear::all([1, 2, 3, 255]),
    ];
    for clear in clears {
        for depth in [DepthState::DEFAULT, DepthState::OFF] {
            let mut eager = dirty.clone();
            eager.clear_now(clear);
            draw(
                &geometry,
                b,
                &Gouraud,
                depth,
                Interpolation::PerspectiveCorrect,
                &mut eager,
            );
            let mut folded = dirty.clone();
            draw_clearing(
                &geometry,
                b,
                &Gouraud,
                depth,
                Interpolation::PerspectiveCorrect,
                clear,
                &mut folded,
            );
            prop_assert!(folded == eager, "{} {:?} {:?}", b.name(), clear, depth);
        }
    }
    Ok(())
}
