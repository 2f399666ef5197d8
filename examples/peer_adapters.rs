//! Published rasterizers behind the `rasterlab check --exec` protocol, so
//! the check can judge them:
//!
//! ```sh
//! cargo build --release --example peer_adapters
//! rasterlab check --rule watertight --exec "target/release/examples/peer_adapters tiny-skia {input} {width} {height}"
//! rasterlab check --rule watertight --exec "target/release/examples/peer_adapters euc {input} {width} {height}"
//! rasterlab check --rule watertight --exec "target/release/examples/peer_adapters embedded-graphics {input} {width} {height}"
//! rasterlab check --rule any --exec "target/release/examples/peer_adapters opengl {input} {width} {height}"
//! rasterlab check --rule any --exec "target/release/examples/peer_adapters opengl-wide {input} {width} {height}"
//! ```
//!
//! Each adapter reads the input file (triangles `x0 y0 x1 y1 x2 y2` in
//! screen pixels, one per line, `#` comments), draws every triangle alone
//! into a cleared target of the given size with the library's own filling,
//! and prints the pixels it covered as `x y t`.
//!
//! * `tiny-skia`: a path of three points filled aliased (`anti_alias =
//!   false`), non-zero winding;
//! * `euc`: its triangle pipeline, the screen points mapped to its
//!   normalised device coordinates (x right, y up), back faces drawn;
//! * `embedded-graphics`: a filled `Triangle`, whose vertices are whole
//!   pixels: each coordinate is rounded down to the pixel it lies in (the
//!   crate's points name pixels, as a display's do);
//! * `opengl`: OpenGL 3.3 through EGL's surfaceless platform (no window,
//!   no GPU), with Mesa's llvmpipe, the software driver Debian's
//!   `libegl1 libegl-mesa0 libgl1-mesa-dri` install (the context is made
//!   by the benchmarks' `benches/support/gl.rs`). GL's window coordinates
//!   have their origin at the *lower* left, y up, pixel centres at +0.5,
//!   and a framebuffer's row 0 is its bottom row; the screen's y runs
//!   down. So the adapter flips y: the screen point `(x, y)` of a `W x H`
//!   target is GL's window point `(x, H - y)`, and the screen's pixel
//!   `(i, j)` is GL's pixel `(i, H - 1 - j)`, read back from the bottom.
//!   GL's specification leaves the tie rule to the driver. llvmpipe
//!   applies the top-left rule to the framebuffer's rows as stored, row 0
//!   first, and row 0 is GL's bottom row: a centre on an edge goes to the
//!   triangle when the edge is a left edge, or an edge below the triangle
//!   in GL's window (lower y). Seen through the flip, in the screen's
//!   y-down coordinates, those are the left and bottom edges: the
//!   **bottom-left** rule, which `rasterlab check --rule any` names. The
//!   target lies inside a larger viewport, with a margin of 64 px on
//!   every side and a side a power of two, so that the viewport transform
//!   is exact in `f32` and every vertex lands on the 1/256 px grid it was
//!   given on: a triangle crossing the target's edge is not clipped
//!   there; only one reaching beyond the margin is, with vertices the
//!   driver makes of its own.
//! * `opengl-wide`: the same context and y flip, but drawn the way
//!   applications that rely on a wide clipping range draw: the viewport
//!   is far larger than the framebuffer, `glViewport(-8192, -8192, 16384,
//!   16384)` (its side is the smaller of 16,384 and `GL_MAX_VIEWPORT_DIMS`,
//!   rounded down to a power of two: 16,384 on llvmpipe; the adapter reads
//!   `GL_VIEWPORT` back and refuses to run when GL changed it). The
//!   framebuffer is a square of side the larger of 64 and the target's
//!   side rounded up to a power of two, one 64x64 tile of llvmpipe's for
//!   the check's targets, whatever size shrinking cuts them to; the target
//!   is its bottom-left corner: the screen's pixel `(i, j)` is GL's pixel
//!   `(i, H - 1 - j)`, the screen point `(x, y)` GL's window point
//!   `(x, H - y)`, sent as the clip-space point `(x, H - y) * 2 / 16384`,
//!   which the viewport maps back to `(x, H - y)`. Each step is exact in
//!   `f32` for coordinates on the 1/256 grid with `|x|, |y| < 2^15` (the
//!   guard band): at most 24 significant bits, `H - y` as well while
//!   `|H - y| < 2^16`, and the scales are powers of two. GL's clipper
//!   cuts nothing within 8,192 px of GL's window origin (the target's
//!   bottom-left corner), so such triangles reach llvmpipe's rasterizer
//!   whole, on the grid they were given on, and the framebuffer's edges
//!   only bound the pixels written. A triangle reaching farther is clipped
//!   at the viewport's edge, 8,192 px off, with vertices the driver makes.

// The support module serves the benchmarks and tests too: this adapter
// uses part of it.
#[allow(dead_code)]
#[path = "../benches/support/gl.rs"]
mod gl;

use std::process::ExitCode;

type Triangle = [(f32, f32); 3];

/// Draws one triangle alone on a `w x h` target: the pixels it covers.
type Draw<'a> = Box<dyn Fn(&Triangle, u32, u32) -> Vec<(u32, u32)> + 'a>;

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

/// The margin around the target inside OpenGL's viewport, in pixels.
const GL_MARGIN: u32 = 64;

/// OpenGL: a context on a square framebuffer holding the target and its
/// margin, and the transform from window pixels to clip space.
struct OpenGl {
    gl: gl::Llvmpipe,
    side: u32,
    transform: [f32; 16],
}

impl OpenGl {
    fn new(w: u32, h: u32) -> Result<OpenGl, String> {
        let side = (w.max(h) + 2 * GL_MARGIN).next_power_of_two();
        let gl = gl::Llvmpipe::new(side, side, 0)?;
        let transform = gl.window_transform();
        Ok(OpenGl {
            gl,
            side,
            transform,
        })
    }

    /// The pixels of the `w x h` target GL covers drawing `t` alone.
    fn pixels(&self, t: &Triangle, w: u32, h: u32) -> Vec<(u32, u32)> {
        let m = GL_MARGIN as f32;
        // The y flip of the module docs, then the margin: exact in f32
        // for coordinates on the 1/256 grid within the guard band.
        let vertices = t.map(|(x, y)| gl::Vertex {
            position: [x + m, (h as f32 - y) + m, 0.5],
            light: 1.0,
        });
        let shape = self.gl.shape(&vertices, &[0, 1, 2]);
        self.gl.draw(
            &shape,
            &self.transform,
            gl::DrawState {
                depth: false,
                cull_back: false,
            },
        );
        let coverage = self.gl.coverage();
        self.gl.delete(shape);
        let (side, margin) = (self.side, GL_MARGIN);
        covered(w, h, |i| {
            let (x, y) = (i as u32 % w, i as u32 / w);
            coverage[((margin + h - 1 - y) * side + margin + x) as usize]
        })
    }
}

/// The side of the wide viewport asked for (`opengl-wide`): GL clips
/// nothing within half of it around the framebuffer's origin.
const WIDE_VIEWPORT: i32 = 16384;

/// OpenGL with a viewport far larger than the framebuffer, which holds
/// the target in its bottom-left corner (`opengl-wide`, see the module
/// docs).
struct WideGl {
    gl: gl::Llvmpipe,
    side: u32,
    transform: [f32; 16],
}

impl WideGl {
    fn new(w: u32, h: u32) -> Result<WideGl, String> {
        let side = w.max(h).next_power_of_two().max(64);
        let gl = gl::Llvmpipe::new(side, side, 0)?;
        let viewport = wide_viewport(WIDE_VIEWPORT)?;
        // Clip space from GL's window coordinates, for the viewport
        // (-v/2, -v/2, v, v): x_ndc = x_window * 2 / v, a power of two;
        // depth 0.5 to 0.
        let s = 2.0 / viewport as f32;
        let transform = [
            s, 0.0, 0.0, 0.0, //
            0.0, s, 0.0, 0.0, //
            0.0, 0.0, 2.0, 0.0, //
            0.0, 0.0, -1.0, 1.0,
        ];
        Ok(WideGl {
            gl,
            side,
            transform,
        })
    }

    /// The pixels of the `w x h` target GL covers drawing `t` alone.
    fn pixels(&self, t: &Triangle, w: u32, h: u32) -> Vec<(u32, u32)> {
        // The y flip of the module docs: exact in f32 within the guard band.
        let vertices = t.map(|(x, y)| gl::Vertex {
            position: [x, h as f32 - y, 0.5],
            light: 1.0,
        });
        let shape = self.gl.shape(&vertices, &[0, 1, 2]);
        self.gl.draw(
            &shape,
            &self.transform,
            gl::DrawState {
                depth: false,
                cull_back: false,
            },
        );
        let coverage = self.gl.coverage();
        self.gl.delete(shape);
        let side = self.side;
        covered(w, h, |i| {
            let (x, y) = (i as u32 % w, i as u32 / w);
            coverage[((h - 1 - y) * side + x) as usize]
        })
    }
}

/// Sets the current GL context's viewport to `(-s/2, -s/2, s, s)`, with
/// `s` the smaller of `wanted` and `GL_MAX_VIEWPORT_DIMS` rounded down to
/// a power of two, and returns `s`. The support module keeps its GL
/// function table to itself, so this one is looked up again through EGL
/// (the same driver, the context current on this thread).
fn wide_viewport(wanted: i32) -> Result<i32, String> {
    use glow::HasContext;
    // SAFETY: libEGL is the system's EGL loader, already loaded by the
    // support module; khronos-egl checks its EGL 1.5 entry points.
    let egl = unsafe { khronos_egl::DynamicInstance::<khronos_egl::EGL1_5>::load_required() }
        .map_err(|e| format!("no libEGL.so.1: {e}"))?;
    // SAFETY: an llvmpipe context is current on this thread (made so by
    // `gl::Llvmpipe::new`); the entry points are its driver's.
    let gl = unsafe {
        glow::Context::from_loader_function(|name| {
            egl.get_proc_address(name)
                .map_or(std::ptr::null(), |f| f as *const std::ffi::c_void)
        })
    };
    // SAFETY: plain GL calls on the current context.
    unsafe {
        let mut dims = [0i32; 2];
        gl.get_parameter_i32_slice(glow::MAX_VIEWPORT_DIMS, &mut dims);
        let most = wanted.min(dims[0]).min(dims[1]);
        if most < 2 {
            return Err(format!("GL_MAX_VIEWPORT_DIMS is {dims:?}"));
        }
        let side = 1 << (31 - most.leading_zeros());
        let asked = [-side / 2, -side / 2, side, side];
        gl.viewport(asked[0], asked[1], asked[2], asked[3]);
        let mut got = [0i32; 4];
        gl.get_parameter_i32_slice(glow::VIEWPORT, &mut got);
        if got != asked {
            return Err(format!("glViewport{asked:?} gave the viewport {got:?}"));
        }
        Ok(side)
    }
}

fn covered(w: u32, h: u32, is_set: impl Fn(usize) -> bool) -> Vec<(u32, u32)> {
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .filter(|&(x, y)| is_set((y * w + x) as usize))
        .collect()
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().collect();
    let usage =
        "usage: peer_adapters tiny-skia|euc|embedded-graphics|opengl|opengl-wide INPUT WIDTH HEIGHT";
    let [_, crate_name, input, width, height] = args.as_slice() else {
        eprintln!("{usage}");
        return ExitCode::from(2);
    };
    let (Ok(w), Ok(h)) = (width.parse::<u32>(), height.parse::<u32>()) else {
        eprintln!("{usage}");
        return ExitCode::from(2);
    };
    if w == 0 || h == 0 {
        eprintln!("the target is empty: {w}x{h}");
        return ExitCode::from(2);
    }
    let triangles = match read(input) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(2);
        }
    };
    let opengl;
    let opengl_wide;
    let draw: Draw = match crate_name.as_str() {
        "tiny-skia" => Box::new(tiny_skia_pixels),
        "euc" => Box::new(euc_pixels),
        "embedded-graphics" => Box::new(embedded_graphics_pixels),
        "opengl" => {
            opengl = match OpenGl::new(w, h) {
                Ok(gl) => gl,
                Err(e) => {
                    eprintln!("OpenGL unavailable: {e}");
                    return ExitCode::from(2);
                }
            };
            Box::new(|t: &Triangle, w, h| opengl.pixels(t, w, h))
        }
        "opengl-wide" => {
            opengl_wide = match WideGl::new(w, h) {
                Ok(gl) => gl,
                Err(e) => {
                    eprintln!("OpenGL unavailable: {e}");
                    return ExitCode::from(2);
                }
            };
            Box::new(|t: &Triangle, w, h| opengl_wide.pixels(t, w, h))
        }
        _ => {
            eprintln!("{usage}");
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
