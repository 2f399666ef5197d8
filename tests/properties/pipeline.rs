//! The 3D pipeline's properties as functions of their input, shared by
//! the property tests (`tests/pipeline.rs`) and the named regression
//! tests of the cases they shrank to (`tests/regressions.rs`).
#![allow(dead_code)]

use glam::Vec4;
use proptest::prelude::*;
use rasterlab::geometry::{
    draw, process_triangles, ClipVertex, Geometry, PipelineOptions, Viewport,
};
use rasterlab::raster::{
    triangle_backends, DepthState, Flat, FragmentList, Interpolation, RenderTarget, Varyings,
};

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
        rasterlab::raster::PixelRect::of_target(w, h),
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
            let centre = (f64::from(x) + 0.5, f64::from(y) + 0.5);
            if let Some(inside) = oracle(&tri, centre, (w, h)) {
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

/// Pixels nearer than this to a border of the visible part are not
/// judged: snapping moves a vertex by up to 1/512 px, and the clipper's
/// `f32` vertices, up to 16,384 px from the origin, are off by up to
/// about 1/1000 px.
const UNDECIDED_PX: f64 = 0.01;

/// Says whether the pixel centre `centre` (in pixels, on a `size` target)
/// sees the clip-space triangle `t` inside the frustum; `None` when a
/// border of the visible part passes within [`UNDECIDED_PX`] of it.
///
/// The point of the triangle seen at normalized device coordinates
/// `(nx, ny)` has barycentrics `b` with `sum b_i (x_i - nx w_i) = 0`,
/// `sum b_i (y_i - ny w_i) = 0` and `sum b_i = 1`. By Cramer's rule
/// `b_i = A_i / D`, where `A_i = r1_j r2_k - r1_k r2_j` (`i, j, k` in
/// cyclic order, `r1 = x - nx w`, `r2 = y - ny w`) and `D = sum A_i`;
/// the `nx ny` terms cancel, so every `A_i` is affine in the pixel
/// position. Each condition of visibility (`b_i > 0`, `w > W_MIN`,
/// `z > -w`, `z < w`) is linear in `b`, so it holds where an affine
/// function `N` has the sign of `D`: every border, the horizon `D = 0`
/// included, is a straight line on the screen, and the distance to it is
/// `|N| / |grad N|`, with no system to solve. The coefficients are
/// differences of exact products of `f32` inputs, so they are accurate
/// whatever the magnitudes.
pub fn oracle(t: &[Vec4; 3], centre: (f64, f64), size: (u32, u32)) -> Option<bool> {
    let p = t.map(|v| v.as_dvec4());
    // A_i = a0_i + ax_i nx + ay_i ny.
    let a = [0, 1, 2].map(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        [
            p[j].x * p[k].y - p[k].x * p[j].y,
            p[k].w * p[j].y - p[j].w * p[k].y,
            p[k].x * p[j].w - p[j].x * p[k].w,
        ]
    });
    let w_min = f64::from(rasterlab::geometry::W_MIN);
    // Each condition as its coefficients on b; the horizon D = sum A_i last.
    let conditions: [[f64; 3]; 7] = [
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        p.map(|v| v.w - w_min),
        p.map(|v| v.z + v.w),
        p.map(|v| v.w - v.z),
        [1.0, 1.0, 1.0],
    ];
    let (width, height) = (f64::from(size.0), f64::from(size.1));
    let (nx, ny) = (centre.0 / width * 2.0 - 1.0, 1.0 - centre.1 / height * 2.0);
    let mut values = [0.0f64; 7];
    for (value, c) in values.iter_mut().zip(conditions) {
        let n = |term: usize| (0..3).map(|i| c[i] * a[i][term]).sum::<f64>();
        let (n0, n_x, n_y) = (n(0), n(1), n(2));
        *value = n0 + n_x * nx + n_y * ny;
        let magnitude = (0..3)
            .map(|i| c[i].abs() * (a[i][0].abs() + (a[i][1] * nx).abs() + (a[i][2] * ny).abs()))
            .sum::<f64>();
        // The gradient in pixels: nx = 2 px / width - 1, ny = 1 - 2 py / height.
        let gradient = (n_x * 2.0 / width).hypot(n_y * 2.0 / height);
        if !value.is_finite()
            || value.abs() <= 1e-12 * magnitude
            || value.abs() < UNDECIDED_PX * gradient
        {
            return None;
        }
    }
    let horizon = values[6];
    Some(values[..6].iter().all(|v| v.signum() == horizon.signum()))
}
