//! The 3D pipeline's properties as functions of their input, shared by
//! the property tests (`tests/pipeline.rs`) and the named regression
//! tests of the cases they shrank to (`tests/regressions.rs`).
#![allow(dead_code)]

use glam::Vec4;
use proptest::prelude::*;
use rasterlab::geometry::pipeline::clip::ClipVertex;
use rasterlab::geometry::pipeline::{draw, process_triangles, Geometry, PipelineOptions, Viewport};
use rasterlab::raster::backend::triangle_backends;
use rasterlab::raster::fragment::FragmentList;
use rasterlab::raster::primitive::Varyings;
use rasterlab::raster::shader::Flat;
use rasterlab::raster::stage::Interpolation;
use rasterlab::raster::target::{DepthState, RenderTarget};

/// A triangle in clip space, as `(x, y, z, w)` per vertex.
pub type ClipTriangle = [(f32, f32, f32, f32); 3];

/// One clip-space triangle through the pipeline (positions as given, no
/// varyings, default options) onto a `width` x `height` viewport.
pub fn clip_space_geometry(tri: &[Vec4; 3], width: u32, height: u32) -> Geometry {
    let shader = |v: &Vec4| ClipVertex {
        position: *v,
        varyings: Varyings::default(),
    };
    process_triangles(
        tri,
        &[[0, 1, 2]],
        &shader,
        Viewport { width, height },
        &PipelineOptions::default(),
    )
    .unwrap()
}

/// A triangle anywhere in clip space (across the near plane, behind the
/// camera, huge, with w near zero) is no error, every fragment lies where
/// the clip-space triangle really is inside the frustum, and every pixel
/// the triangle clearly covers inside the frustum is drawn.
pub fn clipping_draws_exactly_the_visible_part(t: ClipTriangle) -> Result<(), TestCaseError> {
    let (w, h) = (24u32, 16u32);
    let tri = t.map(|(x, y, z, w)| Vec4::new(x, y, z, w));
    let geometry = clip_space_geometry(&tri, w, h);
    let mut list = FragmentList::default();
    triangle_backends()[2].rasterize(
        &geometry.setups,
        rasterlab::raster::edge::PixelRect::of_target(w, h),
        &mut list,
    );
    let mut covered = vec![false; (w * h) as usize];
    for f in &list.triangles {
        prop_assert!(
            !covered[(f.y * w + f.x) as usize],
            "pixel ({}, {}) drawn twice",
            f.x,
            f.y
        );
        covered[(f.y * w + f.x) as usize] = true;
        let z = geometry.shaded.triangles[f.triangle as usize]
            .depth
            .at(f.x, f.y);
        prop_assert!((-1e-3..=1.001).contains(&z), "depth {z} outside [0, 1]");
    }
    for y in 0..h {
        for x in 0..w {
            // The oracle at the pixel centre and 1/50 px around it: a
            // pixel is checked only when all five agree, so snapping
            // (1/512 px) cannot decide it.
            let probe = |dx: f64, dy: f64| {
                oracle(
                    &tri,
                    (
                        (x as f64 + 0.5 + dx) / w as f64 * 2. - 1.,
                        1. - (y as f64 + 0.5 + dy) / h as f64 * 2.,
                    ),
                )
            };
            let d = 0.02;
            let probes = [
                probe(0., 0.),
                probe(d, 0.),
                probe(-d, 0.),
                probe(0., d),
                probe(0., -d),
            ];
            if probes.iter().all(|p| *p == probes[0]) {
                let Some(inside) = probes[0] else { continue };
                prop_assert_eq!(
                    covered[(y * w + x) as usize],
                    inside,
                    "pixel ({}, {}), stats {:?}",
                    x,
                    y,
                    geometry.stats
                );
            }
        }
    }
    Ok(())
}

/// Extreme coordinates (up to f32::MAX) are no error and no panic; what
/// is drawn stays on the target with depths in range.
pub fn extreme_coordinates_never_fail(t: ClipTriangle) -> Result<(), TestCaseError> {
    let tri = t.map(|(x, y, z, w)| Vec4::new(x, y, z, w));
    let geometry = clip_space_geometry(&tri, 24, 16);
    let mut target = RenderTarget::new(24, 16).unwrap();
    for b in triangle_backends() {
        draw(
            &geometry,
            *b,
            &Flat,
            DepthState::DEFAULT,
            Interpolation::PerspectiveCorrect,
            &mut target,
        );
    }
    prop_assert!(target.depth.iter().all(|z| (-1e-3..=1.001).contains(z)));
    Ok(())
}

/// Solves for the clip-space barycentrics of the point of the triangle that
/// projects to `ndc`, and says whether it is in the triangle and in the
/// frustum; `None` when the pixel is too close to a border to decide, or
/// when f64 cannot solve for the point accurately enough to say.
fn oracle(t: &[Vec4; 3], ndc: (f64, f64)) -> Option<bool> {
    let p = t.map(|v| v.as_dvec4());
    // sum b_i (x_i - nx w_i) = 0, sum b_i (y_i - ny w_i) = 0, sum b_i = 1.
    let row = |f: &dyn Fn(glam::DVec4) -> f64| glam::DVec3::new(f(p[0]), f(p[1]), f(p[2]));
    let m = glam::DMat3::from_cols(
        row(&|v| v.x - ndc.0 * v.w),
        row(&|v| v.y - ndc.1 * v.w),
        glam::DVec3::ONE,
    )
    .transpose();
    if m.determinant().abs() < 1e-9 {
        return None;
    }
    let b = m.inverse() * glam::DVec3::new(0., 0., 1.);
    let q = p[0] * b.x + p[1] * b.y + p[2] * b.z;
    // An ill-conditioned system (w of 10^5 beside x of 10^-7) loses the
    // answer to cancellation even in f64: the point found must really
    // project to `ndc`, or the oracle cannot decide.
    let off = (q.x - ndc.0 * q.w).abs().max((q.y - ndc.1 * q.w).abs());
    // (NaN, from entries that overflow, abstains too.)
    if off.is_nan() || off > 1e-6 * q.w.abs() {
        return None;
    }
    // Inside the triangle, beyond the w >= W_MIN plane, between near and far.
    let w_min = f64::from(rasterlab::geometry::pipeline::clip::W_MIN);
    let margins = [
        b.x,
        b.y,
        b.z,
        (q.w - w_min) / w_min,
        (q.z + q.w) / q.w.abs().max(1e-300),
        (q.w - q.z) / q.w.abs().max(1e-300),
    ];
    if margins.iter().any(|m| m.abs() < 1e-3) {
        return None;
    }
    Some(margins.iter().all(|m| *m > 0.0))
}
