//! One pixel's texture lookup on the receding floor, step by step, as
//! `explain --backend texture X Y` prints it: the texture coordinate at
//! the pixel centre, its screen-space derivatives by each method
//! (analytic, quad, forward), `rho` and `lambda` (OpenGL 3.3, section
//! 3.8.11), the levels the level mode reads (Williams 1983), each level's
//! bilinear texels and weights (or, under EWA, Heckbert 1989, the
//! ellipse and the texels it weighs), the level weights, and the colour,
//! which is the colour the floor's frame stores there.
//!
//! ```
//! use rasterlab::geometry::Floor;
//! use rasterlab::raster::{Derivatives, LevelMode, Sampler};
//! use rasterlab::teaching::trace_texture;
//!
//! let floor = Floor::new(160, 100).unwrap();
//! let trilinear = Sampler { levels: LevelMode::Linear, ..Sampler::default() };
//! let text = trace_texture(&floor, (80, 60), trilinear, Derivatives::Quad).unwrap();
//! assert!(text.contains("lambda") && text.contains("stored"));
//! ```

use crate::error::{Error, Result};
use crate::geometry::Floor;
use crate::raster::derivatives::Derivatives;
use crate::raster::registry::default_triangle_backend;
use crate::raster::shader::to_rgba8;
use crate::raster::texture::{Anisotropic, Ellipse, Filter, Footprint, Image, LevelMode, Sampler};
use glam::{Vec2, Vec4};
use std::fmt::Write;

/// `(x, y)` with three decimals.
fn pair(v: Vec2) -> String {
    format!("({:.3}, {:.3})", v.x, v.y)
}

/// An RGBA colour with three decimals.
fn rgba(c: Vec4) -> String {
    format!("({:.3}, {:.3}, {:.3}, {:.3})", c.x, c.y, c.z, c.w)
}

/// One level read at `uv`: its texels and weights written to `out`, and
/// the level's colour.
fn trace_level(out: &mut String, image: &Image, level: usize, uv: Vec2, s: &Sampler) -> Vec4 {
    let (w, h) = (image.width(), image.height());
    let (u, v) = (
        f64::from(uv.x) * f64::from(w),
        f64::from(uv.y) * f64::from(h),
    );
    let fetch = |x: i64, y: i64| {
        let (i, j) = (s.wrap.index(x, w), s.wrap.index(y, h));
        (i, j, image.texel(i, j))
    };
    let colour = image.sample(uv, s.filter, s.wrap);
    let _ = write!(
        out,
        "  level {level} ({w}x{h}): (u, v) = ({u:.3}, {v:.3}) texels; "
    );
    match s.filter {
        Filter::Nearest => {
            let (i, j, _) = fetch(u.floor() as i64, v.floor() as i64);
            let _ = writeln!(out, "nearest: texel ({i}, {j}) = {}", rgba(colour));
        }
        Filter::Bilinear => {
            // Texel centres sit at half-integers.
            let (x0, y0) = ((u - 0.5).floor(), (v - 0.5).floor());
            let (fx, fy) = (u - 0.5 - x0, v - 0.5 - y0);
            let _ = writeln!(out, "bilinear, fractions ({fx:.3}, {fy:.3}):");
            for (dx, dy, weight) in [
                (0, 0, (1.0 - fx) * (1.0 - fy)),
                (1, 0, fx * (1.0 - fy)),
                (0, 1, (1.0 - fx) * fy),
                (1, 1, fx * fy),
            ] {
                let (i, j, c) = fetch(x0 as i64 + dx, y0 as i64 + dy);
                let _ = writeln!(out, "    texel ({i}, {j}) x {weight:.3}: {}", rgba(c));
            }
            let _ = writeln!(out, "    = {}", rgba(colour));
        }
    }
    colour
}

/// The lookup of pixel `(x, y)` of `floor` with `sampler`, the
/// derivatives by `method`, as text. An error when the floor does not
/// cover the pixel's centre.
pub fn trace_texture(
    floor: &Floor,
    (x, y): (u32, u32),
    sampler: Sampler,
    method: Derivatives,
) -> Result<String> {
    if x >= floor.width() || y >= floor.height() {
        return Err(Error::InvalidArgument(format!(
            "pixel ({x}, {y}) is outside the floor's {}x{} picture: take x below {} and y \
             below {} (or give a larger --size)",
            floor.width(),
            floor.height(),
            floor.width(),
            floor.height()
        )));
    }
    let (Some(planes), Some(uv)) = (floor.planes_at(x, y), floor.uv_at(x, y)) else {
        return Err(Error::InvalidArgument(format!(
            "the floor does not cover the centre of pixel ({x}, {y}) of its {}x{} picture: \
             take a pixel below the horizon",
            floor.width(),
            floor.height()
        )));
    };
    let texture = floor.texture();
    let (w, h) = (texture.width(), texture.height());
    let size = Vec2::new(w as f32, h as f32);
    let uv = uv.as_vec2();
    let mut out = String::new();
    let _ = writeln!(
        out,
        "texture lookup at pixel ({x}, {y}) of the floor ({}x{}), a {w}x{h} texture of {} levels",
        floor.width(),
        floor.height(),
        texture.levels().len()
    );
    let _ = writeln!(
        out,
        "texture coordinate at the pixel centre: (s, t) = {}, (u, v) = {} texels",
        pair(uv),
        pair(uv * size)
    );
    let _ = writeln!(
        out,
        "derivatives of (u, v) in texels, one pixel right (dx) and down (dy):"
    );
    let _ = writeln!(
        out,
        "  {:<9} {:>18} {:>18} {:>8} {:>8}",
        "method", "d(u,v)/dx", "d(u,v)/dy", "rho", "lambda"
    );
    for m in [
        Derivatives::Analytic,
        Derivatives::Quad,
        Derivatives::Forward,
    ] {
        let g = planes.derivatives(m, i64::from(x), i64::from(y));
        let f = Footprint::new(g.dx, g.dy, w, h);
        let chosen = if m == method { "  <- used" } else { "" };
        let _ = writeln!(
            out,
            "  {:<9} {:>18} {:>18} {:>8.3} {:>8.3}{chosen}",
            m.to_string(),
            pair(f.dx),
            pair(f.dy),
            f.rho(),
            f.lambda()
        );
    }
    let (qx, qy) = (x & !1, y & !1);
    let helpers: Vec<String> = [(qx, qy), (qx + 1, qy), (qx, qy + 1), (qx + 1, qy + 1)]
        .iter()
        .filter(|&&(i, j)| floor.planes_at(i, j).map(|p| std::ptr::eq(p, planes)) != Some(true))
        .map(|(i, j)| format!("({i}, {j})"))
        .collect();
    let _ = writeln!(
        out,
        "  quad: the 2x2 quad at ({qx}, {qy}), fine differences on the pixel's own row and column; \
         helper pixels (outside this triangle): {}",
        if helpers.is_empty() {
            "none".to_string()
        } else {
            helpers.join(", ")
        }
    );
    let g = planes.derivatives(method, i64::from(x), i64::from(y));
    let footprint = Footprint::new(g.dx, g.dy, w, h);
    let probes = footprint.probes(sampler.anisotropy);
    let last = texture.levels().len() - 1;
    let ellipse = Ellipse::new(footprint.dx, footprint.dy, sampler.anisotropy);
    let ewa = sampler.anisotropic == Anisotropic::Ewa;
    let lambda = if ewa { ellipse.lambda() } else { probes.lambda };
    let _ = writeln!(
        out,
        "rho = max(|d(u,v)/dx|, |d(u,v)/dy|) = {:.3}; lambda = log2(rho) = {:.3}",
        footprint.rho(),
        footprint.lambda()
    );
    if ewa {
        let _ = writeln!(
            out,
            "EWA, at most {}x: the ellipse's axes {} and {} texels, lambda = log2(|minor|) = {lambda:.3}",
            sampler.anisotropy,
            pair(ellipse.major),
            pair(ellipse.minor)
        );
    } else if sampler.anisotropy > 1 {
        let _ = writeln!(
            out,
            "anisotropic, at most {}x: N = {} probes along {} texels, each at lambda = log2(rho_max / N) = {lambda:.3}",
            sampler.anisotropy,
            probes.count,
            pair(probes.axis)
        );
    }
    let choice = sampler.levels.choose(lambda, last + 1);
    let mode = match sampler.levels {
        LevelMode::Zero => "zero: level 0 whatever lambda",
        LevelMode::Nearest => "nearest: the level within a half of lambda",
        LevelMode::Linear => "linear: the two levels around lambda",
    };
    let _ = writeln!(
        out,
        "level mode {mode}; lambda clamped to [0, {last}]: level {} x {:.3}, level {} x {:.3}",
        choice.fine,
        1.0 - choice.weight,
        choice.coarse,
        choice.weight
    );
    let colour = if ewa {
        let levels = texture.levels();
        let mut at = |level: usize| {
            let image = &levels[level];
            let scale = Vec2::new(image.width() as f32, image.height() as f32) / size;
            let (c, n) = ellipse.filter(image, uv, scale, sampler.wrap);
            let _ = writeln!(
                out,
                "  level {level} ({}x{}): {n} texels inside the ellipse, each weighted \
                 exp(-2 r^2) - exp(-2): {}",
                image.width(),
                image.height(),
                rgba(c)
            );
            c
        };
        let fine = at(choice.fine);
        if choice.coarse == choice.fine {
            fine
        } else {
            fine.lerp(at(choice.coarse), choice.weight)
        }
    } else if probes.count > 1 {
        let axis = probes.axis / size;
        let mut sum = Vec4::ZERO;
        for i in 1..=probes.count {
            let at = uv + axis * probes.offset(i);
            let c = texture.sample_lod(at, lambda, &sampler);
            let _ = writeln!(out, "  probe {i} at (s, t) = {}: {}", pair(at), rgba(c));
            sum += c;
        }
        sum / probes.count as f32
    } else {
        let levels = texture.levels();
        let fine = trace_level(&mut out, &levels[choice.fine], choice.fine, uv, &sampler);
        if choice.coarse == choice.fine {
            fine
        } else {
            let coarse = trace_level(
                &mut out,
                &levels[choice.coarse],
                choice.coarse,
                uv,
                &sampler,
            );
            fine.lerp(coarse, choice.weight)
        }
    };
    let (target, _) = floor.render(default_triangle_backend(), sampler, method);
    let stored = target.color[target.index(x, y)];
    let _ = writeln!(
        out,
        "colour: {} -> rgba8 {:?}; stored by the frame: {stored:?}",
        rgba(colour),
        to_rgba8(colour)
    );
    Ok(out)
}
