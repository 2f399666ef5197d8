//! Published rasterizers behind the `rasterlab check --exec` protocol, so
//! the check can judge them:
//!
//! ```sh
//! cargo build --release --example peer_adapters
//! rasterlab check --rule watertight --exec "target/release/examples/peer_adapters tiny-skia {input} {width} {height}"
//! rasterlab check --rule watertight --exec "target/release/examples/peer_adapters euc {input} {width} {height}"
//! rasterlab check --rule watertight --exec "target/release/examples/peer_adapters embedded-graphics {input} {width} {height}"
//! ```
//!
//! Each adapter reads the input file (triangles `x0 y0 x1 y1 x2 y2` in
//! screen pixels, one per line, `#` comments), draws every triangle alone
//! into a cleared target of the given size with the crate's own filling,
//! and prints the pixels it covered as `x y t`.
//!
//! * `tiny-skia`: a path of three points filled aliased (`anti_alias =
//!   false`), non-zero winding;
//! * `euc`: its triangle pipeline, the screen points mapped to its
//!   normalised device coordinates (x right, y up), back faces drawn;
//! * `embedded-graphics`: a filled `Triangle`, whose vertices are whole
//!   pixels: each coordinate is rounded down to the pixel it lies in (the
//!   crate's points name pixels, as a display's do).

use std::process::ExitCode;

type Triangle = [(f32, f32); 3];

fn read(path: &str) -> Result<Vec<Triangle>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let content = line.split('#').next().unwrap_or("").trim();
        if content.is_empty() {
            continue;
        }
        let v: Vec<f32> = content
            .split_whitespace()
            .map(|w| {
                w.parse()
                    .map_err(|_| format!("{path}:{}: `{w}` is not a number", i + 1))
            })
            .collect::<Result<_, _>>()?;
        if v.len() != 6 {
            return Err(format!("{path}:{}: a triangle takes 6 numbers", i + 1));
        }
        out.push([(v[0], v[1]), (v[2], v[3]), (v[4], v[5])]);
    }
    Ok(out)
}

/// tiny-skia: the pixels one aliased path fill covers.
fn tiny_skia_pixels(t: &Triangle, w: u32, h: u32) -> Vec<(u32, u32)> {
    let mut pixmap = tiny_skia::Pixmap::new(w, h).expect("a non-empty target");
    let mut paint = tiny_skia::Paint::default();
    paint.set_color_rgba8(255, 255, 255, 255);
    paint.anti_alias = false;
    let mut path = tiny_skia::PathBuilder::new();
    path.move_to(t[0].0, t[0].1);
    path.line_to(t[1].0, t[1].1);
    path.line_to(t[2].0, t[2].1);
    path.close();
    if let Some(path) = path.finish() {
        pixmap.fill_path(
            &path,
            &paint,
            tiny_skia::FillRule::Winding,
            tiny_skia::Transform::identity(),
            None,
        );
    }
    covered(w, h, |i| pixmap.pixels()[i].alpha() > 0)
}

/// euc's pipeline for one flat triangle.
struct Flat {
    w: f32,
    h: f32,
}

impl euc::Pipeline for Flat {
    type Vertex = (f32, f32);
    type VsOut = f32;
    type Pixel = u32;

    fn vert(&self, p: &(f32, f32)) -> ([f32; 4], f32) {
        (
            [2.0 * p.0 / self.w - 1.0, 1.0 - 2.0 * p.1 / self.h, 0.5, 1.0],
            1.0,
        )
    }

    fn frag(&self, _: &f32) -> u32 {
        1
    }
}

/// euc: the pixels its triangle rasterizer writes.
fn euc_pixels(t: &Triangle, w: u32, h: u32) -> Vec<(u32, u32)> {
    use euc::{Pipeline, Target};
    let mut color = euc::buffer::Buffer2d::new([w as usize, h as usize], 0u32);
    color.clear(0);
    let pipeline = Flat {
        w: w as f32,
        h: h as f32,
    };
    pipeline.draw::<euc::rasterizer::Triangles<_, euc::rasterizer::BackfaceCullingDisabled>, _>(
        t,
        &mut color,
        None::<&mut euc::buffer::Buffer2d<f32>>,
    );
    covered(w, h, |i| color.as_ref()[i] != 0)
}

/// embedded-graphics draws into any `DrawTarget`: this one records pixels.
struct Recorder {
    w: u32,
    h: u32,
    set: Vec<bool>,
}

impl embedded_graphics::geometry::OriginDimensions for Recorder {
    fn size(&self) -> embedded_graphics::geometry::Size {
        embedded_graphics::geometry::Size::new(self.w, self.h)
    }
}

impl embedded_graphics::draw_target::DrawTarget for Recorder {
    type Color = embedded_graphics::pixelcolor::BinaryColor;
    type Error = std::convert::Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = embedded_graphics::Pixel<Self::Color>>,
    {
        for embedded_graphics::Pixel(p, _) in pixels {
            if (0..self.w as i32).contains(&p.x) && (0..self.h as i32).contains(&p.y) {
                self.set[(p.y as u32 * self.w + p.x as u32) as usize] = true;
            }
        }
        Ok(())
    }
}

/// embedded-graphics: the pixels a filled triangle covers.
fn embedded_graphics_pixels(t: &Triangle, w: u32, h: u32) -> Vec<(u32, u32)> {
    use embedded_graphics::prelude::*;
    use embedded_graphics::primitives::{PrimitiveStyle, Triangle as EgTriangle};
    let mut recorder = Recorder {
        w,
        h,
        set: vec![false; (w * h) as usize],
    };
    let p = |(x, y): (f32, f32)| Point::new(x.floor() as i32, y.floor() as i32);
    let _ = EgTriangle::new(p(t[0]), p(t[1]), p(t[2]))
        .into_styled(PrimitiveStyle::with_fill(
            embedded_graphics::pixelcolor::BinaryColor::On,
        ))
        .draw(&mut recorder);
    covered(w, h, |i| recorder.set[i])
}

fn covered(w: u32, h: u32, is_set: impl Fn(usize) -> bool) -> Vec<(u32, u32)> {
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .filter(|&(x, y)| is_set((y * w + x) as usize))
        .collect()
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().collect();
    let usage = "usage: peer_adapters tiny-skia|euc|embedded-graphics INPUT WIDTH HEIGHT";
    let [_, crate_name, input, width, height] = args.as_slice() else {
        eprintln!("{usage}");
        return ExitCode::from(2);
    };
    let (Ok(w), Ok(h)) = (width.parse::<u32>(), height.parse::<u32>()) else {
        eprintln!("{usage}");
        return ExitCode::from(2);
    };
    let draw: fn(&Triangle, u32, u32) -> Vec<(u32, u32)> = match crate_name.as_str() {
        "tiny-skia" => tiny_skia_pixels,
        "euc" => euc_pixels,
        "embedded-graphics" => embedded_graphics_pixels,
        _ => {
            eprintln!("{usage}");
            return ExitCode::from(2);
        }
    };
    let triangles = match read(input) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(2);
        }
    };
    let mut out = String::new();
    for (id, t) in triangles.iter().enumerate() {
        for (x, y) in draw(t, w, h) {
            out.push_str(&format!("{x} {y} {id}\n"));
        }
    }
    print!("{out}");
    ExitCode::SUCCESS
}
