//! Bad input gets a clear error or a documented discard, never a panic.

use rasterlab::raster::{
    triangle_backend, triangle_backends, FillRule, Fixed, FixedPoint, FragmentList, PixelRect,
    RenderTarget, TriangleSetup,
};
use rasterlab::Error;

#[test]
fn non_finite_and_out_of_band_coordinates_are_errors() {
    for v in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        assert!(
            matches!(Fixed::snap(v), Err(Error::NonFinite { .. })),
            "{v}"
        );
    }
    for v in [32768.0, -32768.0, 1e30, f32::MAX, -f32::MAX] {
        assert!(
            matches!(Fixed::snap(v), Err(Error::OutsideGuardBand { .. })),
            "{v}"
        );
    }
    let msg = Fixed::snap(1e6).unwrap_err().to_string();
    assert!(msg.contains("guard band"), "{msg}");
}

#[test]
fn degenerate_triangles_are_discarded() {
    let p = |x, y| FixedPoint::snap(x, y).unwrap();
    for tri in [
        [p(1., 1.), p(1., 1.), p(1., 1.)],
        [p(0., 0.), p(10., 10.), p(20., 20.)],
        [p(0., 0.), p(0.0001, 0.0), p(0.0, 0.0001)],
    ] {
        assert!(TriangleSetup::new(0, tri, FillRule::TopLeft).is_none());
    }
}

#[test]
fn zero_size_targets_are_errors() {
    for (w, h) in [(0, 0), (0, 5), (5, 0), (100_000, 1)] {
        let err = RenderTarget::new(w, h).unwrap_err();
        assert!(matches!(err, Error::InvalidTargetSize { .. }));
        assert!(err.to_string().contains(&format!("{w}x{h}")));
    }
}

#[test]
fn unknown_names_are_errors_listing_the_known_ones() {
    let err = triangle_backend("z-order").err().unwrap().to_string();
    assert!(
        err.contains("z-order") && err.contains("naive") && err.contains("scanline"),
        "{err}"
    );
    assert!("diagonal"
        .parse::<FillRule>()
        .unwrap_err()
        .to_string()
        .contains("top-left"));
}

#[test]
fn an_empty_viewport_or_no_triangles_emit_nothing() {
    let p = |x, y| FixedPoint::snap(x, y).unwrap();
    let t = TriangleSetup::new(0, [p(0., 0.), p(9., 0.), p(0., 9.)], FillRule::TopLeft).unwrap();
    let empty = PixelRect {
        x0: 5,
        y0: 5,
        x1: 4,
        y1: 4,
    };
    for b in triangle_backends() {
        let mut list = FragmentList::default();
        b.rasterize(&[t], empty, &mut list);
        b.rasterize(&[], PixelRect::of_target(10, 10), &mut list);
        assert!(list.triangles.is_empty(), "{}", b.name());
    }
}

#[test]
fn triangles_spanning_the_whole_guard_band_do_not_overflow() {
    let p = |x, y| FixedPoint::snap(x, y).unwrap();
    let huge = TriangleSetup::new(
        0,
        [
            p(-32767.996, -32767.996),
            p(32767.996, -100.0),
            p(-100.0, 32767.996),
        ],
        FillRule::TopLeft,
    )
    .unwrap();
    for b in triangle_backends() {
        let mut list = FragmentList::default();
        b.rasterize(&[huge], PixelRect::of_target(16, 16), &mut list);
        assert_eq!(list.triangles.len(), 256, "{}", b.name());
    }
}

#[test]
fn rendering_into_a_target_of_another_size_is_an_error() {
    use rasterlab::geometry::{Mesh, MeshRenderer, RenderSettings};
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/bunny.ply");
    let settings = RenderSettings {
        width: 32,
        height: 24,
        ..RenderSettings::default()
    };
    let renderer = MeshRenderer::new(&Mesh::load(&path).unwrap(), settings).unwrap();
    let scanline = triangle_backend("scanline").unwrap();
    let mut wrong = RenderTarget::without_coverage(24, 32).unwrap();
    let err = renderer.render_into(scanline, &mut wrong).unwrap_err();
    assert!(matches!(err, Error::InvalidArgument(_)), "{err}");
    assert!(err.to_string().contains("24x32"), "{err}");
    let mut right = RenderTarget::without_coverage(32, 24).unwrap();
    assert!(
        renderer
            .render_into(scanline, &mut right)
            .unwrap()
            .work
            .fragments
            > 0
    );
}
