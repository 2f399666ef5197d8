//! Whole frames, side by side with published rasterizers doing the same
//! work, timed in interleaved rounds, and the ratio table read off them.
//!
//! * `dragon_res4`, `dragon_res2`, `dragon`: the Stanford dragon (11,102,
//!   202,520 and 871,414 triangles) at 1920x1080, back faces culled, depth
//!   test, Gouraud shading (lit per vertex); `dragon_zoom2.5` is the full
//!   dragon with the camera of `render --zoom 2.5` (about 1.5 M
//!   fragments). Peers: `euc`, and Mesa's llvmpipe (OpenGL) on one and on
//!   two rasterizer threads. rasterlab: every back-end on one thread, and
//!   `tiled` on two;
//! * `fill-L`, `size-S`, `sliver-A`: 2D triangles with depth test and
//!   colour write (see `rasterlab::measure::workload`), against llvmpipe
//!   doing the same and `tiny-skia` filling the same triangles without
//!   anti-aliasing (colour only, no depth buffer); `fill-L-colour-only` is
//!   the fill with colour cleared and no depth (`DepthState::OFF`), the
//!   very work tiny-skia does, and llvmpipe without depth test; the
//!   fills are also drawn by `tiled` on two threads; `fill-L-over` is the
//!   fill half transparent, composited by `over` without depth, in linear
//!   light (`scanline`) and in encoded values (`scanline-srgb`, tiny-skia's
//!   work), beside tiny-skia's `source-over` of the same colour;
//! * `floor-trilinear`: the textured floor of `render --scene floor`,
//!   trilinear with quad derivatives, against llvmpipe sampling the same
//!   pyramid with `GL_LINEAR_MIPMAP_LINEAR` (see `fn floor`);
//! * `dragon_res4-trilinear`, `dragon-trilinear`: the dragons textured
//!   with their planar coordinates, trilinear with quad derivatives, depth
//!   test and back faces culled, against llvmpipe the same way (see
//!   `fn textured_dragon`);
//! * `lines-short-1M`, `lines-long-10k`: every line back-end through the
//!   stage and the fast path, against the `line_drawing` crate's Bresenham
//!   writing into a colour buffer.
//!
//! Every rasterlab figure is measured on one thread (a rayon pool of one,
//! so the target clears too stay on one core) except `tiled-2-threads`;
//! rasterlab draws into one reused target made
//! `RenderTarget::without_coverage` (colour and depth, as the peers).
//! The two workers of `tiled-2-threads`, and the two rasterizer threads
//! of `llvmpipe-2-threads`, are bound to a core each: left to the
//! scheduler, they sometimes shared one core for the first 12 ms or so
//! of a frame (`support/cores.rs` says how that was seen). The printed
//! context says whether they were bound.
//!
//! Each workload runs its contenders once to warm up, then in `--rounds`
//! rounds (default 10), each contender once per round, the order turning
//! each round (`rasterlab::measure::rounds`): cold, each run finding the
//! caches as another contender left them. The 2D workloads are then also
//! timed warm: each contender `--rounds` times back to back, as an
//! application redraws frame after frame. Printed per workload: each
//! contender's median [min-max] ms, the CPU time per working thread and
//! the time waited for a core; at the end, the context (commit, machine,
//! load) and the ratio table: each peer against rasterlab's best on as
//! many threads, the median of the per-round ratios with their minimum
//! and maximum. llvmpipe is timed only after it has drawn the same
//! fragments as rasterlab (give or take 3).
//!
//! ```text
//! cargo bench --bench side_by_side                       # everything
//! cargo bench --bench side_by_side -- --rounds 5 dragon  # workloads named *dragon*
//! ```
//!
//! The Stanford models beyond the bundled one are looked for in
//! `$RASTERLAB_DATA` or `../shared/data` (`rasterlab::measure::data`);
//! llvmpipe needs Mesa at run time (Debian: `libegl1 libegl-mesa0
//! libgl1-mesa-dri`). What is missing is printed as skipped, with why.

#[path = "support/cores.rs"]
mod cores;
#[path = "support/gl.rs"]
mod gl;

use glam::{Mat4, Vec3};
use rasterlab::geometry::{CullMode, Floor, Mesh, MeshRenderer, RenderSettings, Shading, SKY};
use rasterlab::measure::{
    fill, find, long_lines, ratio_header, short_lines, sized, slivers, Contender, Context,
    LineWorkload, Side, Skipped, TriangleWorkload, Workload, WorkloadResult, DRAGON_RES2,
    FULL_DRAGON,
};
use rasterlab::raster::line::pixel_containing;
use rasterlab::raster::triangle::TriangleRasterizer;
use rasterlab::raster::{
    line_backends, to_rgba8, triangle_backend, triangle_backends, within_budget, Derivatives,
    FixedPoint, LevelMode, MixSpace, RenderTarget, Sampler, Texture, WorkBudget,
};
use std::cell::RefCell;
use std::path::PathBuf;

const W: u32 = 1920;
const H: u32 = 1080;

use cores::{pool, Binding, LlvmpipeThreads};

/// What the command line asks for: rounds, and name filters.
struct Options {
    rounds: usize,
    filters: Vec<String>,
}

impl Options {
    fn parse() -> Options {
        let mut options = Options {
            rounds: 10,
            filters: Vec::new(),
        };
        let mut args = std::env::args().skip(1);
        while let Some(arg) = args.next() {
            match arg.as_str() {
                "--rounds" => {
                    options.rounds = args
                        .next()
                        .and_then(|n| n.parse().ok())
                        .filter(|n| *n >= 1)
                        .expect("--rounds takes a whole number of at least 1");
                }
                // cargo bench passes --bench; other flags are criterion's.
                a if a.starts_with("--") => {}
                a => options.filters.push(a.to_string()),
            }
        }
        options
    }

    fn wants(&self, name: &str) -> bool {
        self.filters.is_empty() || self.filters.iter().any(|f| name.contains(f.as_str()))
    }
}

/// llvmpipe on one and on two rasterizer threads, or why not.
type Gl = Result<Vec<gl::Llvmpipe>, Skipped>;

/// llvmpipe on one and on two rasterizer threads, the two-thread one's
/// bound to a core each ([`cores`]), and how they were placed.
fn llvmpipe() -> (Gl, Binding) {
    let open = |threads| {
        gl::Llvmpipe::new(W, H, threads).map_err(|reason| Skipped {
            reason: format!("llvmpipe unavailable: {reason}"),
        })
    };
    let mut binding = Binding::Unbound;
    let gls = open(1).and_then(|one| {
        let before = LlvmpipeThreads::now();
        let two = open(2)?;
        binding = before.bind_new(two.threads());
        Ok(vec![one, two])
    });
    if let Ok(gls) = &gls {
        eprintln!("llvmpipe: {}", gls[0].renderer());
    }
    (gls, binding)
}

fn llvmpipe_name(gl: &gl::Llvmpipe) -> String {
    match gl.threads() {
        1 => "llvmpipe-1-thread".to_string(),
        n => format!("llvmpipe-{n}-threads"),
    }
}

/// llvmpipe's contexts, once the first is seen to draw `theirs`
/// fragments within `tolerance` of rasterlab's `ours`; otherwise
/// llvmpipe is marked skipped in `work`, with why, and `None`.
fn same_work<'a>(
    work: &mut Workload<'_>,
    gls: &'a Gl,
    ours: u64,
    tolerance: u64,
    workload: &str,
    theirs: impl FnOnce(&gl::Llvmpipe) -> u64,
) -> Option<&'a [gl::Llvmpipe]> {
    let gls = match gls {
        Ok(gls) => gls,
        Err(why) => {
            work.skip("llvmpipe", why.clone());
            return None;
        }
    };
    let theirs = theirs(&gls[0]);
    eprintln!("{workload}: fragments rasterlab {ours}, llvmpipe {theirs}");
    if ours.abs_diff(theirs) > tolerance {
        let reason = format!(
            "llvmpipe drew {theirs} fragments where rasterlab drew {ours}: not the same work"
        );
        work.skip("llvmpipe", Skipped { reason });
        return None;
    }
    Some(gls)
}

/// Adds llvmpipe's contenders, drawing `shapes` (one per context), once
/// it is seen to draw `ours` fragments give or take `tolerance`.
#[allow(clippy::too_many_arguments)]
fn add_llvmpipe<'a>(
    work: &mut Workload<'a>,
    gls: &'a Gl,
    shapes: &'a [gl::Shape],
    transform: &'a [f32; 16],
    state: gl::DrawState,
    ours: u64,
    tolerance: u64,
    workload: &str,
) {
    let theirs = |gl: &gl::Llvmpipe| gl.fragments(&shapes[0], transform, state.cull_back);
    let Some(gls) = same_work(work, gls, ours, tolerance, workload, theirs) else {
        return;
    };
    for (gl, shape) in gls.iter().zip(shapes) {
        let name = llvmpipe_name(gl);
        work.add(Contender::new(&name, Side::Peer, gl.threads(), move || {
            gl.draw(shape, transform, state)
        }));
    }
}

fn delete_shapes(gls: &Gl, shapes: Vec<gl::Shape>) {
    if let Ok(gls) = gls {
        for (gl, shape) in gls.iter().zip(shapes) {
            gl.delete(shape);
        }
    }
}

/// `euc`'s pipeline for a mesh: positions by index, a per-vertex diffuse
/// intensity interpolated across the triangle.
struct EucMesh<'a> {
    mvp: Mat4,
    positions: &'a [Vec3],
    intensity: &'a [f32],
}

impl euc::Pipeline for EucMesh<'_> {
    type Vertex = u32;
    type VsOut = f32;
    type Pixel = u32;

    fn vert(&self, i: &u32) -> ([f32; 4], f32) {
        let p = self.mvp * self.positions[*i as usize].extend(1.0);
        (p.to_array(), self.intensity[*i as usize])
    }

    fn frag(&self, light: &f32) -> u32 {
        let c = (light.clamp(0.0, 1.0) * 255.0) as u32;
        0xff00_0000 | c << 16 | c << 8 | c
    }
}

/// The dragons: the bundled one, then those of the data folder.
fn dragons(options: &Options, gls: &Gl) -> Vec<WorkloadResult> {
    let bundled = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/dragon_vrip_res4.ply.gz");
    let models = [
        ("dragon_res4", Ok(bundled), vec![1.0]),
        ("dragon_res2", find(DRAGON_RES2), vec![1.0]),
        ("dragon", find(FULL_DRAGON), vec![1.0, 2.5]),
    ];
    let mut results = Vec::new();
    for (name, path, zooms) in models {
        let names: Vec<String> = zooms
            .iter()
            .map(|&z| {
                if z == 1.0 {
                    name.to_string()
                } else {
                    format!("{name}_zoom{z}")
                }
            })
            .collect();
        if !names.iter().any(|n| options.wants(n)) {
            continue;
        }
        let mesh = match path {
            Ok(path) => Mesh::load(&path).unwrap(),
            Err(why) => {
                for n in names.iter().filter(|n| options.wants(n)) {
                    let result = Workload::skipped(n, &why);
                    print!("{}", result.figure_table());
                    results.push(result);
                }
                continue;
            }
        };
        for (zoom, name) in zooms.into_iter().zip(names) {
            if options.wants(&name) {
                let result = dragon(&name, &mesh, zoom, options.rounds, gls);
                print!("{}", result.figure_table());
                results.push(result);
            }
        }
    }
    results
}

fn dragon(name: &str, mesh: &Mesh, zoom: f32, rounds: usize, gls: &Gl) -> WorkloadResult {
    let mut settings = RenderSettings {
        width: W,
        height: H,
        azimuth: 30.0,
        zoom,
        shading: Shading::Gouraud,
        ..RenderSettings::default()
    };
    settings.pipeline.cull = CullMode::Back;
    let renderer = MeshRenderer::new(mesh, settings).unwrap();
    let target = RefCell::new(RenderTarget::without_coverage(W, H).unwrap());
    let (one, two) = (pool(1), pool(2));
    let pixels = u64::from(W) * u64::from(H);
    let draw = |b: &dyn TriangleRasterizer, pool: &rayon::ThreadPool| {
        let target = &mut *target.borrow_mut();
        pool.install(|| renderer.render_into(b, target).unwrap().work.fragments)
    };
    let ours = draw(triangle_backend("scanline").unwrap(), &one);

    // The same camera, the same per-vertex light, for the peers.
    let transform = renderer.transform();
    let intensity: Vec<f32> = mesh
        .normals
        .iter()
        .map(|n| settings.light.intensity(transform.normal_matrix * *n))
        .collect();
    let indices: Vec<u32> = mesh.triangles.iter().flatten().copied().collect();
    let euc_mesh = EucMesh {
        mvp: transform.mvp,
        positions: &mesh.positions,
        intensity: &intensity,
    };
    let euc_buffers = RefCell::new((
        euc::buffer::Buffer2d::new([W as usize, H as usize], 0u32),
        euc::buffer::Buffer2d::new([W as usize, H as usize], 1.0f32),
    ));
    let vertices: Vec<gl::Vertex> = mesh
        .positions
        .iter()
        .zip(&intensity)
        .map(|(p, light)| gl::Vertex {
            position: p.to_array(),
            light: *light,
        })
        .collect();
    let shapes: Vec<gl::Shape> = gls
        .iter()
        .flatten()
        .map(|gl| gl.shape(&vertices, &indices))
        .collect();
    let gl_transform = gl::Llvmpipe::mesh_transform(transform.mvp.to_cols_array());

    let mut work = Workload::new(name);
    let affordable = |b: &&&dyn TriangleRasterizer| {
        let triangles = mesh.triangles.len() as u64;
        within_budget(&b.descriptor(), triangles, pixels, WorkBudget::Timing).is_ok()
    };
    let (draw, one, two) = (&draw, &one, &two);
    for &b in triangle_backends().iter().filter(affordable) {
        work.add(Contender::new(b.name(), Side::Rasterlab, 1, move || {
            draw(b, one)
        }));
    }
    let tiled = triangle_backend("tiled").unwrap();
    work.add(Contender::new(
        "tiled-2-threads",
        Side::Rasterlab,
        2,
        move || draw(tiled, two),
    ));
    work.add(Contender::new("peer-euc", Side::Peer, 1, || {
        use euc::{Pipeline, Target};
        let (color, depth) = &mut *euc_buffers.borrow_mut();
        color.clear(0);
        depth.clear(1.0);
        euc_mesh.draw::<euc::rasterizer::Triangles<_, euc::rasterizer::BackfaceCullingEnabled>, _>(
            &indices,
            color,
            Some(depth),
        );
        color.as_ref()[0]
    }));
    let state = gl::DrawState {
        depth: true,
        cull_back: true,
    };
    add_llvmpipe(&mut work, gls, &shapes, &gl_transform, state, ours, 3, name);
    let result = work.run(rounds);
    delete_shapes(gls, shapes);
    result
}

/// The dragons textured and filtered trilinearly: `dragon_res4-trilinear`
/// (bundled) and `dragon-trilinear` (the full dragon, from the data
/// folder), the camera and culling of their Gouraud rows.
fn textured_dragons(options: &Options, gls: &Gl) -> Vec<WorkloadResult> {
    let bundled = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/dragon_vrip_res4.ply.gz");
    let models = [
        ("dragon_res4-trilinear", Ok(bundled)),
        ("dragon-trilinear", find(FULL_DRAGON)),
    ];
    let mut results = Vec::new();
    for (name, path) in models {
        if !options.wants(name) {
            continue;
        }
        let result = match path {
            Ok(path) => textured_dragon(name, &Mesh::load(&path).unwrap(), options.rounds, gls),
            Err(why) => Workload::skipped(name, &why),
        };
        print!("{}", result.figure_table());
        results.push(result);
    }
    results
}

/// A dragon under `render --shading texture --mip linear --derivatives
/// quad`: its planar texture coordinates (`Mesh::uvs_or_generated`), a
/// checkerboard of 16 squares of 8 texels, trilinear, with the depth test
/// and back faces culled; llvmpipe draws the same triangles and
/// coordinates through the same camera with `GL_LINEAR_MIPMAP_LINEAR`
/// from the same pyramid, uploaded level by level.
fn textured_dragon(name: &str, mesh: &Mesh, rounds: usize, gls: &Gl) -> WorkloadResult {
    let mut settings = RenderSettings {
        width: W,
        height: H,
        azimuth: 30.0,
        shading: Shading::Texture,
        mip: LevelMode::Linear,
        derivatives: Derivatives::Quad,
        ..RenderSettings::default()
    };
    settings.pipeline.cull = CullMode::Back;
    let texture = Texture::checkerboard(16, 8, settings.color, settings.color * 0.35);
    let renderer = MeshRenderer::new(mesh, settings)
        .and_then(|r| r.with_texture(texture.clone()))
        .unwrap();
    let target = RefCell::new(RenderTarget::without_coverage(W, H).unwrap());
    let (one, two) = (pool(1), pool(2));
    let draw = |b: &dyn TriangleRasterizer, pool: &rayon::ThreadPool| {
        let target = &mut *target.borrow_mut();
        pool.install(|| renderer.render_into(b, target).unwrap().work.fragments)
    };
    let ours = draw(triangle_backend("scanline").unwrap(), &one);
    let uvs = mesh.uvs_or_generated();
    let vertices: Vec<gl::TexturedVertex> = mesh
        .positions
        .iter()
        .zip(&uvs)
        .map(|(p, uv)| gl::TexturedVertex {
            position: p.to_array(),
            uv: uv.to_array(),
        })
        .collect();
    let indices: Vec<u32> = mesh.triangles.iter().flatten().copied().collect();
    let transform = gl::Llvmpipe::mesh_transform(renderer.transform().mvp.to_cols_array());
    let state = gl::DrawState {
        depth: true,
        cull_back: true,
    };
    let uploaded = upload_textured(gls, &texture, &vertices, &indices);
    let mut work = Workload::new(name);
    add_textured_rasterlab(&mut work, &draw, &one, &two);
    add_textured_llvmpipe(&mut work, gls, &uploaded, &transform, state, ours, 3, name);
    let result = work.run(rounds);
    delete_textured(gls, uploaded);
    result
}

/// rasterlab's contenders of a textured workload: `scanline` and `tiled`
/// on the one-thread pool `one`, `tiled` on the two-thread pool `two`,
/// each running `draw`.
fn add_textured_rasterlab<'a, D>(
    work: &mut Workload<'a>,
    draw: &'a D,
    one: &'a rayon::ThreadPool,
    two: &'a rayon::ThreadPool,
) where
    D: Fn(&dyn TriangleRasterizer, &rayon::ThreadPool) -> u64,
{
    for name in ["scanline", "tiled"] {
        let b = triangle_backend(name).unwrap();
        work.add(Contender::new(name, Side::Rasterlab, 1, move || {
            draw(b, one)
        }));
    }
    let tiled = triangle_backend("tiled").unwrap();
    work.add(Contender::new(
        "tiled-2-threads",
        Side::Rasterlab,
        2,
        move || draw(tiled, two),
    ));
}

/// A textured shape and its mipmapped texture, one per llvmpipe context.
type Uploaded = Vec<(gl::Shape, glow::Texture)>;

/// `texture`'s pyramid (as RGBA8, level by level, `GL_LINEAR_MIPMAP_LINEAR`)
/// and the shape of `vertices` and `indices`, uploaded to every llvmpipe
/// context, outside the timing, as an application keeps them.
fn upload_textured(
    gls: &Gl,
    texture: &Texture,
    vertices: &[gl::TexturedVertex],
    indices: &[u32],
) -> Uploaded {
    let levels: Vec<gl::Level> = texture
        .levels()
        .iter()
        .map(|level| gl::Level {
            width: level.width(),
            height: level.height(),
            rgba: level.texels().iter().flat_map(|&c| to_rgba8(c)).collect(),
        })
        .collect();
    gls.iter()
        .flatten()
        .map(|gl| {
            let texture = gl.mipmapped(&levels, 1.0).expect("the pyramid uploaded");
            (gl.textured_shape(vertices, indices), texture)
        })
        .collect()
}

/// Adds llvmpipe's contenders drawing `uploaded` under `state`, once it
/// is seen to draw `ours` fragments give or take `tolerance`.
#[allow(clippy::too_many_arguments)]
fn add_textured_llvmpipe<'a>(
    work: &mut Workload<'a>,
    gls: &'a Gl,
    uploaded: &'a Uploaded,
    transform: &'a [f32; 16],
    state: gl::DrawState,
    ours: u64,
    tolerance: u64,
    workload: &str,
) {
    let theirs = |gl: &gl::Llvmpipe| gl.fragments(&uploaded[0].0, transform, state.cull_back);
    let Some(gls) = same_work(work, gls, ours, tolerance, workload, theirs) else {
        return;
    };
    for (gl, (shape, texture)) in gls.iter().zip(uploaded) {
        let name = llvmpipe_name(gl);
        work.add(Contender::new(&name, Side::Peer, gl.threads(), move || {
            gl.draw_textured(shape, transform, *texture, SKY, state)
        }));
    }
}

fn delete_textured(gls: &Gl, uploaded: Uploaded) {
    if let Ok(gls) = gls {
        for (gl, (shape, texture)) in gls.iter().zip(uploaded) {
            gl.delete_texture(texture);
            gl.delete(shape);
        }
    }
}

/// `floor-trilinear`: the textured floor (`render --scene floor`) at
/// 1920x1080, trilinear (level mode linear, bilinear, quad derivatives),
/// against llvmpipe drawing the same plane through the same camera with
/// `GL_LINEAR_MIPMAP_LINEAR` from the same pyramid, uploaded level by
/// level. The shader (rasterlab) and the texture (llvmpipe) are made once,
/// outside the timing, as an application keeps them from frame to frame.
fn floor(options: &Options, gls: &Gl) -> Vec<WorkloadResult> {
    const NAME: &str = "floor-trilinear";
    if !options.wants(NAME) {
        return Vec::new();
    }
    let floor = Floor::new(W, H).unwrap();
    let trilinear = Sampler {
        levels: LevelMode::Linear,
        ..Sampler::default()
    };
    let shader = floor.shader(trilinear, Derivatives::Quad);
    let target = RefCell::new(RenderTarget::without_coverage(W, H).unwrap());
    let (one, two) = (pool(1), pool(2));
    let draw = |b: &dyn TriangleRasterizer, pool: &rayon::ThreadPool| {
        let target = &mut *target.borrow_mut();
        pool.install(|| floor.draw(b, &shader, target).fragments)
    };
    let ours = draw(triangle_backend("scanline").unwrap(), &one);
    let vertices = floor.vertices().map(|(p, uv)| gl::TexturedVertex {
        position: p.to_array(),
        uv: uv.to_array(),
    });
    let indices: Vec<u32> = Floor::TRIANGLES.concat();
    let transform = gl::Llvmpipe::mesh_transform(floor.mvp().to_cols_array());
    let uploaded = upload_textured(gls, floor.texture(), &vertices, &indices);
    let mut work = Workload::new(NAME);
    add_textured_rasterlab(&mut work, &draw, &one, &two);
    // The horizon's row of pixels, where a centre lies within rounding of
    // the far edge, may go either way.
    let state = gl::DrawState::NONE;
    add_textured_llvmpipe(
        &mut work,
        gls,
        &uploaded,
        &transform,
        state,
        ours,
        u64::from(W),
        NAME,
    );
    let result = work.run(options.rounds);
    print!("{}", result.figure_table());
    delete_textured(gls, uploaded);
    vec![result]
}

/// The workload's triangles filled by tiny-skia, aliased, in one colour
/// of opacity `alpha` (255: opaque), composited by its default blend,
/// `source-over`.
fn tiny_skia_fill(work: &TriangleWorkload, alpha: u8, pixmap: &mut tiny_skia::Pixmap) {
    let mut paint = tiny_skia::Paint::default();
    paint.set_color_rgba8(51, 128, 230, alpha);
    paint.anti_alias = false;
    pixmap.fill(tiny_skia::Color::BLACK);
    for t in &work.geometry.setups {
        let mut path = tiny_skia::PathBuilder::new();
        let [a, b, c] = t.vertices.map(|v| {
            let (x, y) = v.to_f64();
            (x as f32, y as f32)
        });
        path.move_to(a.0, a.1);
        path.line_to(b.0, b.1);
        path.line_to(c.0, c.1);
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
    }
}

/// The workload's triangles for GL: window coordinates and depth.
fn gl_triangles(work: &TriangleWorkload) -> (Vec<gl::Vertex>, Vec<u32>) {
    let vertices: Vec<gl::Vertex> = work
        .geometry
        .setups
        .iter()
        .flat_map(|t| {
            let depth = work.depths[t.id as usize];
            t.vertices.map(|v| {
                let (x, y) = v.to_f64();
                gl::Vertex {
                    position: [x as f32, y as f32, depth],
                    light: 1.0,
                }
            })
        })
        .collect();
    let indices = (0..vertices.len() as u32).collect();
    (vertices, indices)
}

fn triangles(options: &Options, gls: &Gl) -> Vec<WorkloadResult> {
    let mut workloads = vec![fill(W, H, 1), fill(W, H, 4)];
    for size in [1.0, 4.0, 16.0, 64.0, 250.0, 500.0] {
        workloads.push(sized(W, H, size));
    }
    for angle in [0.0, 45.0, 90.0] {
        workloads.push(slivers(W, H, angle));
    }
    let target = RefCell::new(RenderTarget::without_coverage(W, H).unwrap());
    let pixmap = RefCell::new(tiny_skia::Pixmap::new(W, H).unwrap());
    let (one, two) = (pool(1), pool(2));
    let tiled = triangle_backend("tiled").unwrap();
    let mut results = Vec::new();
    for work in &workloads {
        // With depth, as a frame is drawn; the fills also colour only.
        let colour_only = format!("{}-colour-only", work.name);
        let variants = [(work.name.clone(), true), (colour_only, false)];
        for (name, depth) in variants {
            if !options.wants(&name) || (!depth && !work.name.starts_with("fill")) {
                continue;
            }
            let run_on = |b: &dyn TriangleRasterizer, pool: &rayon::ThreadPool| {
                let target = &mut *target.borrow_mut();
                pool.install(|| {
                    if depth {
                        work.run(b, target)
                    } else {
                        work.run_colour_only(b, target)
                    }
                })
            };
            let run = |b: &dyn TriangleRasterizer| run_on(b, &one);
            let ours = run(triangle_backend("scanline").unwrap());
            let (vertices, indices) = gl_triangles(work);
            let shapes: Vec<gl::Shape> = gls
                .iter()
                .flatten()
                .map(|gl| gl.shape(&vertices, &indices))
                .collect();
            let window = gls.as_ref().map_or([0.0; 16], |g| g[0].window_transform());
            let mut contest = Workload::new(&name);
            // Frame after frame too, as an application redraws.
            contest.also_warm();
            let run = &run;
            for &b in triangle_backends().iter().filter(|b| work.suits(**b)) {
                contest.add(Contender::new(b.name(), Side::Rasterlab, 1, move || run(b)));
            }
            // The fills on two threads too, band by band.
            if work.name.starts_with("fill") {
                let (run_on, two) = (&run_on, &two);
                contest.add(Contender::new(
                    "tiled-2-threads",
                    Side::Rasterlab,
                    2,
                    move || run_on(tiled, two),
                ));
            }
            contest.add(Contender::new("peer-tiny-skia", Side::Peer, 1, || {
                let pixmap = &mut pixmap.borrow_mut();
                tiny_skia_fill(work, 255, pixmap);
                pixmap.data()[0]
            }));
            let state = gl::DrawState {
                depth,
                cull_back: false,
            };
            // GL maps pixels to clip space and back in f32: a vertex can
            // land 1/256 px from rasterlab's.
            let tolerance = (ours / 100_000).max(3);
            add_llvmpipe(
                &mut contest,
                gls,
                &shapes,
                &window,
                state,
                ours,
                tolerance,
                &name,
            );
            let result = contest.run(options.rounds);
            delete_shapes(gls, shapes);
            print!("{}", result.figure_table());
            results.push(result);
        }
        let over = format!("{}-over", work.name);
        if work.name.starts_with("fill") && options.wants(&over) {
            results.push(blended_fill(
                work,
                &over,
                options.rounds,
                &target,
                &pixmap,
                &one,
            ));
        }
    }
    results
}

/// The fill composited half transparent by `over`, colour only: rasterlab
/// mixing in linear light (its default, the cost of being right) and in
/// the encoded values (tiny-skia's work), beside tiny-skia's
/// `source-over` fill, which mixes encoded values.
fn blended_fill(
    work: &TriangleWorkload,
    name: &str,
    rounds: usize,
    target: &RefCell<RenderTarget>,
    pixmap: &RefCell<tiny_skia::Pixmap>,
    one: &rayon::ThreadPool,
) -> WorkloadResult {
    let scanline = triangle_backend("scanline").unwrap();
    let mut contest = Workload::new(name);
    contest.also_warm();
    for (label, space) in [
        ("scanline", MixSpace::Linear),
        ("scanline-srgb", MixSpace::Encoded),
    ] {
        contest.add(Contender::new(label, Side::Rasterlab, 1, move || {
            let target = &mut *target.borrow_mut();
            one.install(|| work.run_blended(scanline, space, target))
        }));
    }
    contest.add(Contender::new("peer-tiny-skia", Side::Peer, 1, || {
        let pixmap = &mut pixmap.borrow_mut();
        tiny_skia_fill(work, 128, pixmap);
        pixmap.data()[0]
    }));
    let result = contest.run(rounds);
    print!("{}", result.figure_table());
    result
}

/// line_drawing's Bresenham on the pixels containing the endpoints,
/// written into an RGBA8 buffer with a bounds test per pixel.
fn line_drawing_lines(lines: &[(i32, i32, i32, i32)], buffer: &mut [[u8; 4]]) -> u64 {
    let mut n = 0;
    for &(x0, y0, x1, y1) in lines {
        for (x, y) in line_drawing::Bresenham::new((x0, y0), (x1, y1)) {
            if (0..W as i32).contains(&x) && (0..H as i32).contains(&y) {
                buffer[y as usize * W as usize + x as usize] = [51, 128, 230, 255];
                n += 1;
            }
        }
    }
    n
}

fn lines(options: &Options) -> Vec<WorkloadResult> {
    let sets = [
        ("lines-short-1M", 1_000_000, true),
        ("lines-long-10k", 10_000, false),
    ];
    let target = RefCell::new(RenderTarget::without_coverage(W, H).unwrap());
    let buffer = RefCell::new(vec![[0u8; 4]; (W * H) as usize]);
    let one = pool(1);
    let mut results = Vec::new();
    for (name, count, short) in sets {
        if !options.wants(name) {
            continue;
        }
        let lines = if short {
            short_lines(W, H, count)
        } else {
            long_lines(W, H, count)
        };
        let work = LineWorkload::new(name, lines);
        let ints: Vec<(i32, i32, i32, i32)> = work
            .lines
            .iter()
            .map(|l| {
                let px = |p: FixedPoint| {
                    (
                        pixel_containing(p.x.raw()) as i32,
                        pixel_containing(p.y.raw()) as i32,
                    )
                };
                let (a, b) = (px(l.from), px(l.to));
                (a.0, a.1, b.0, b.1)
            })
            .collect();
        let mut contest = Workload::new(name);
        let (work, one, target) = (&work, &one, &target);
        for &b in line_backends() {
            contest.add(Contender::new(b.name(), Side::Rasterlab, 1, move || {
                let target = &mut *target.borrow_mut();
                one.install(|| work.run(b, target))
            }));
        }
        contest.add(Contender::new("fast-bresenham", Side::Rasterlab, 1, || {
            let target = &mut *target.borrow_mut();
            one.install(|| work.run_fast(target))
        }));
        contest.add(Contender::new("peer-line_drawing", Side::Peer, 1, || {
            line_drawing_lines(&ints, &mut buffer.borrow_mut())
        }));
        let result = contest.run(options.rounds);
        print!("{}", result.figure_table());
        results.push(result);
    }
    results
}

fn main() {
    let options = Options::parse();
    let mut context = Context::start(1, options.rounds, W, H);
    let (gls, llvmpipe_binding) = llvmpipe();
    if let Err(why) = &gls {
        eprintln!("llvmpipe: {why}");
    }
    let mut results = dragons(&options, &gls);
    results.extend(floor(&options, &gls));
    results.extend(textured_dragons(&options, &gls));
    results.extend(triangles(&options, &gls));
    results.extend(lines(&options));
    context.finish();
    let mut ratios = ratio_header();
    for result in &results {
        result.ratio_rows(&mut ratios);
    }
    println!();
    println!(
        "cargo bench --bench side_by_side -- --rounds {}{}",
        options.rounds,
        options
            .filters
            .iter()
            .map(|f| format!(" {f}"))
            .collect::<String>()
    );
    print!("{context}");
    println!("rasterlab on 1 thread unless the name says otherwise; llvmpipe-1-thread is one rasterizer thread beside the drawing thread");
    println!(
        "two threads: rasterlab's workers {}",
        cores::pool_binding(2).describe()
    );
    if gls.is_ok() {
        println!(
            "two threads: llvmpipe's rasterizer threads {}",
            llvmpipe_binding.describe()
        );
    }
    println!("peer / best: the peer's time over rasterlab's best on as many threads (on any number when none ran on that many), median of the per-round ratios [min-max]; above 1, rasterlab is faster");
    println!("cpu peer / best: the same with the CPU time of all their threads per run, steadier when the cores were busy");
    println!("warm peer / best (2D workloads): from runs back to back, as an application redraws (its buffers in the caches): the peer's median over that of rasterlab's fastest (named) on as many threads");
    print!("{ratios}");
}
