//! The blend trace: one pixel's fragments in the order they arrive, each
//! one's depth test, and the colour of the pixel after each blend, with
//! the values the blend equation mixed (Porter and Duff 1984; the
//! premultiplied buffer of Scotty3D A1's task 4).

use crate::error::{Error, Result};
use crate::geometry::scene::Scene2D;
use crate::raster::edge::FillRule;
use crate::raster::shader::{to_rgba8, Flat};
use crate::raster::srgb::MixSpace;
use crate::raster::stage::{Blend, BlendMode};
use crate::raster::target::{DepthState, DepthTest, RenderTarget};
use crate::raster::triangle::TriangleRasterizer;
use crate::teaching::trace_table::{Column, Trace, TraceRow};
use glam::Vec4;

/// Traces pixel `(x, y)` of `scene` drawn by `backend` triangle after
/// triangle with `depth` and `blend`: a row per triangle that covers the
/// pixel, with its colour and depth, the depth test's verdict, the
/// pixel's colour before and after, and the mix in `blend`'s space.
///
/// ```
/// use rasterlab::geometry::Scene2D;
/// use rasterlab::raster::{triangle_backend, Blend, BlendMode, DepthState, FillRule};
/// use rasterlab::teaching::trace_blend;
///
/// let scene = Scene2D::transparent().sorted_back_to_front();
/// let over = Blend { mode: BlendMode::OverStraight, ..Blend::default() };
/// let bbox = triangle_backend("bbox").unwrap();
/// let trace = trace_blend(&scene, (20, 18), bbox, FillRule::TopLeft, DepthState::DEFAULT, over).unwrap();
/// // Blue, green and red reach the pixel, farthest first, and all pass.
/// assert_eq!(trace.rows.iter().filter(|r| !r.note).count(), 3);
/// assert!(trace.to_text().contains("over-straight"));
/// ```
pub fn trace_blend(
    scene: &Scene2D,
    (x, y): (u32, u32),
    backend: &dyn TriangleRasterizer,
    rule: FillRule,
    depth: DepthState,
    blend: Blend,
) -> Result<Trace> {
    if x >= scene.width || y >= scene.height {
        return Err(Error::InvalidArgument(format!(
            "pixel ({x}, {y}) is outside the {} x {} scene",
            scene.width, scene.height
        )));
    }
    let space = blend.mix_in;
    let mut target = RenderTarget::new(scene.width, scene.height)?;
    let pixel = target.index(x, y);
    let mut out = Trace::saying(format!(
        "pixel ({x}, {y}): each fragment in primitive order, depth test {}, blend {}, mixed in {}",
        depth_name(depth),
        blend.mode.name(),
        match space {
            MixSpace::Linear => "linear light (sRGB decoded, mixed, encoded)",
            MixSpace::Encoded => "the sRGB-encoded values",
        }
    ));
    out.header.push(equation(blend.mode).to_string());
    out.header.push(format!(
        "s = the fragment's colour and opacity, d = the pixel's colour, both as the mix sees them; the buffer starts at {}",
        rgba(target.color[pixel])
    ));
    out.columns = vec![
        Column::right("triangle", 8, 0),
        Column::left("depth test", 24, 2),
        Column::left("fragment rgba8", 20, 2),
        Column::left("pixel before", 20, 2),
        Column::left("s", 30, 2),
        Column::left("d", 30, 2),
        Column::left("mixed", 30, 2),
        Column::left("pixel after", 20, 2),
    ];
    let mut fragments = 0;
    for (i, (triangle, vertices)) in scene.triangles.iter().zip(&scene.vertices).enumerate() {
        let one = Scene2D {
            triangles: vec![*triangle],
            vertices: vec![*vertices],
            ..scene.clone()
        };
        // The fragment's depth at the pixel, from a draw of the triangle
        // alone that always writes it.
        let mut probe = RenderTarget::new(scene.width, scene.height)?;
        let always = DepthState {
            test: DepthTest::Always,
            write: true,
        };
        one.draw(backend, rule, always, &Flat, &mut probe);
        if probe.coverage[pixel] == 0 {
            continue;
        }
        fragments += 1;
        let z = probe.depth[pixel];
        let before = target.color[pixel];
        let stored_depth = target.depth[pixel];
        one.draw_blended(backend, rule, (depth, blend), &Flat, &mut target);
        let after = target.color[pixel];
        let passed = depth.is_off() || depth.test.passes(z, stored_depth);
        let colour = to_rgba8(vertices[0].varyings.color);
        let (s, d) = (space.decode(colour), space.decode(before));
        let mut cells = vec![
            format!("{}", i + 1),
            depth_test(depth, z, stored_depth, passed),
            rgba(colour),
            rgba(before),
        ];
        if passed {
            cells.extend([
                values(s),
                values(d),
                values(blend.mode.mix(s, 1.0, d)),
                rgba(after),
            ]);
        } else {
            cells.extend(["".into(), "".into(), "(not blended)".into(), rgba(after)]);
        }
        out.rows
            .push(TraceRow::at_pixel(cells, i64::from(x), i64::from(y)));
    }
    out.footer.push(format!(
        "{fragments} fragment(s) reached the pixel; it ends at {}",
        rgba(target.color[pixel])
    ));
    Ok(out)
}

/// The blend equation in the course's symbols.
fn equation(mode: BlendMode) -> &'static str {
    match mode {
        BlendMode::Replace => "replace: result = s",
        BlendMode::Add => "add: rgb = d.rgb + s.rgb * s.a, a = d.a + s.a",
        BlendMode::Over => "over (s premultiplied): result = s + d * (1 - s.a)",
        BlendMode::OverStraight => {
            "over-straight (s straight, d premultiplied): rgb = s.rgb * s.a + d.rgb * (1 - s.a), a = s.a + d.a * (1 - s.a)"
        }
        BlendMode::Multiply => "multiply: result = s * d",
    }
}

fn depth_name(depth: DepthState) -> &'static str {
    if depth.is_off() {
        "off"
    } else {
        depth.test.name()
    }
}

/// The depth test as the slides write it: `f.z < depthBuffer`, with the
/// two values.
fn depth_test(depth: DepthState, z: f32, stored: f32, passed: bool) -> String {
    let verdict = if passed { "passes" } else { "fails" };
    let op = match depth.test {
        _ if depth.is_off() => return format!("z {z:.3}, off: passes"),
        DepthTest::Less => "<",
        DepthTest::LessEqual => "<=",
        DepthTest::Greater => ">",
        DepthTest::GreaterEqual => ">=",
        DepthTest::Equal => "==",
        DepthTest::NotEqual => "!=",
        DepthTest::Always | DepthTest::Never => {
            return format!("z {z:.3}, {}: {verdict}", depth.test.name())
        }
    };
    format!("{z:.3} {op} {stored:.3}: {verdict}")
}

fn rgba(c: [u8; 4]) -> String {
    format!("({}, {}, {}, {})", c[0], c[1], c[2], c[3])
}

fn values(v: Vec4) -> String {
    format!("({:.3}, {:.3}, {:.3}, {:.3})", v.x, v.y, v.z, v.w)
}
