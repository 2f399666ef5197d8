//! Whole frames, side by side with published crates doing the same work.
//!
//! * `dragon`: the Stanford dragon (871,414 triangles; and `dragon_res2`)
//!   at 1920x1080, back faces culled, depth test, Gouraud shading (lit per
//!   vertex), against `euc` doing the same; rasterlab on one thread per
//!   back-end, and `tiled` on two;
//!   The full dragon is also drawn zoomed 2.5x (`dragon_zoom2.5`, the
//!   camera of `render --zoom 2.5`), about 1.5 M fragments;
//! * `fill`, `size`, `sliver`: 2D triangles with depth test and colour
//!   write (see `rasterlab::measure::workload`), against `tiny-skia` filling the same
//!   triangles without anti-aliasing (colour only, no depth buffer); the
//!   two-triangle fills are also drawn colour only (`*-colour-only`:
//!   colour cleared, `DepthState::OFF`), the very work tiny-skia does;
//! * `lines`: a million short and ten thousand long lines, every line
//!   back-end through the stage and the fast path, against the
//!   `line_drawing` crate's Bresenham writing into a colour buffer.
//!
//! Every rasterlab figure is measured on one thread (a rayon pool of one,
//! so the target clears too stay on one core) except `tiled-2-threads`.
//! rasterlab draws into one reused target made
//! `RenderTarget::without_coverage`: colour and depth, as the peers, without
//! the per-pixel fragment count that the correctness tests read.
//!
//! `cargo bench --bench side_by_side` (needs `../shared/data` for the full
//! dragon; without it, only the bundled `dragon_vrip_res4` is run).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use glam::{Mat4, Vec3};
use rasterlab::geometry::mesh::Mesh;
use rasterlab::geometry::pipeline::CullMode;
use rasterlab::geometry::render::{MeshRenderer, RenderSettings, Shading};
use rasterlab::measure::workload::{self, LineWorkload, TriangleWorkload};
use rasterlab::raster::backend::{line_backends, triangle_backend, triangle_backends};
use rasterlab::raster::fixed::FixedPoint;
use rasterlab::raster::line::pixel_containing;
use rasterlab::raster::target::RenderTarget;
use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

const W: u32 = 1920;
const H: u32 = 1080;

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
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

fn dragon(c: &mut Criterion) {
    let shared = Path::new("../shared/data");
    let mut meshes = vec![(
        "dragon_res4",
        Path::new("assets/dragon_vrip_res4.ply.gz").to_path_buf(),
    )];
    if shared.exists() {
        meshes.push(("dragon_res2", shared.join("dragon_vrip_res2.ply.gz")));
        meshes.push(("dragon", shared.join("dragon_vrip.ply.gz")));
    }
    let meshes = meshes.into_iter().flat_map(|(name, path)| {
        // The full dragon also zoomed 2.5x: 1.5 M fragments, larger triangles.
        let zoomed = (name == "dragon").then(|| ("dragon_zoom2.5".to_string(), path.clone(), 2.5));
        std::iter::once((name.to_string(), path, 1.0)).chain(zoomed)
    });
    for (name, path, zoom) in meshes {
        let mesh = Mesh::load(&path).unwrap();
        let mut settings = RenderSettings {
            width: W,
            height: H,
            azimuth: 30.0,
            zoom,
            shading: Shading::Gouraud,
            ..RenderSettings::default()
        };
        settings.pipeline.cull = CullMode::Back;
        let renderer = MeshRenderer::new(&mesh, settings).unwrap();
        let mut group = c.benchmark_group(format!("mesh/{name}"));
        group.throughput(Throughput::Elements(mesh.triangles.len() as u64));
        let mut target = RenderTarget::without_coverage(W, H).unwrap();
        let one = pool(1);
        let pixels = u64::from(W) * u64::from(H);
        let affordable = |b: &&&dyn rasterlab::raster::triangle::TriangleRasterizer| {
            b.affordable(mesh.triangles.len() as u64, pixels, 2 * pixels)
        };
        for b in triangle_backends().iter().filter(affordable) {
            group.bench_function(BenchmarkId::from_parameter(b.name()), |bench| {
                bench.iter(|| {
                    one.install(|| {
                        renderer
                            .render_into(*b, &mut target)
                            .unwrap()
                            .work
                            .fragments
                    })
                })
            });
        }
        let two = pool(2);
        let tiled = triangle_backend("tiled").unwrap();
        group.bench_function(BenchmarkId::from_parameter("tiled-2-threads"), |bench| {
            bench.iter(|| {
                two.install(|| {
                    renderer
                        .render_into(tiled, &mut target)
                        .unwrap()
                        .work
                        .fragments
                })
            })
        });
        // The same camera, the same per-vertex light, through euc.
        let transform = renderer.transform();
        let light = settings.light;
        let intensity: Vec<f32> = mesh
            .normals
            .iter()
            .map(|n| light.intensity(transform.normal_matrix * *n))
            .collect();
        let indices: Vec<u32> = mesh.triangles.iter().flatten().copied().collect();
        let euc_mesh = EucMesh {
            mvp: transform.mvp,
            positions: &mesh.positions,
            intensity: &intensity,
        };
        let mut color = euc::buffer::Buffer2d::new([W as usize, H as usize], 0u32);
        let mut depth = euc::buffer::Buffer2d::new([W as usize, H as usize], 1.0f32);
        group.bench_function(BenchmarkId::from_parameter("peer-euc"), |bench| {
            bench.iter(|| {
                use euc::{Pipeline, Target};
                color.clear(0);
                depth.clear(1.0);
                euc_mesh.draw::<euc::rasterizer::Triangles<_, euc::rasterizer::BackfaceCullingEnabled>, _>(
                    &indices,
                    &mut color,
                    Some(&mut depth),
                );
                black_box(color.as_ref()[0])
            })
        });
        group.finish();
    }
}

/// The workload's triangles filled by tiny-skia, aliased, in one colour.
fn tiny_skia_fill(work: &TriangleWorkload, pixmap: &mut tiny_skia::Pixmap) {
    let mut paint = tiny_skia::Paint::default();
    paint.set_color_rgba8(51, 128, 230, 255);
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

fn triangles(c: &mut Criterion) {
    let mut workloads = vec![workload::fill(W, H, 1), workload::fill(W, H, 4)];
    for size in [1.0, 4.0, 16.0, 64.0, 250.0, 500.0] {
        workloads.push(workload::sized(W, H, size));
    }
    for angle in [0.0, 45.0, 90.0] {
        workloads.push(workload::slivers(W, H, angle));
    }
    let mut target = RenderTarget::without_coverage(W, H).unwrap();
    let mut pixmap = tiny_skia::Pixmap::new(W, H).unwrap();
    let one = pool(1);
    for work in &workloads {
        let mut group = c.benchmark_group(format!("triangles/{}", work.name));
        let pixels = work.run(triangle_backends()[1], &mut target);
        group.throughput(Throughput::Elements(pixels));
        for b in triangle_backends().iter().filter(|b| work.suits(**b)) {
            group.bench_function(BenchmarkId::from_parameter(b.name()), |bench| {
                bench.iter(|| one.install(|| work.run(*b, &mut target)))
            });
        }
        // The same work as tiny-skia's: clear the colour, fill, no depth.
        if work.name.starts_with("fill") {
            for b in triangle_backends().iter().filter(|b| work.suits(**b)) {
                let id = format!("{}-colour-only", b.name());
                group.bench_function(BenchmarkId::from_parameter(id), |bench| {
                    bench.iter(|| one.install(|| work.run_colour_only(*b, &mut target)))
                });
            }
        }
        group.bench_function(BenchmarkId::from_parameter("peer-tiny-skia"), |bench| {
            bench.iter(|| {
                tiny_skia_fill(work, &mut pixmap);
                black_box(pixmap.data()[0])
            })
        });
        group.finish();
    }
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

fn lines(c: &mut Criterion) {
    let sets = [
        LineWorkload::new("lines/short-1M", workload::short_lines(W, H, 1_000_000)),
        LineWorkload::new("lines/long-10k", workload::long_lines(W, H, 10_000)),
    ];
    let mut target = RenderTarget::without_coverage(W, H).unwrap();
    let one = pool(1);
    for work in &sets {
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
        let mut group = c.benchmark_group(&work.name);
        group.throughput(Throughput::Elements(work.run_fast(&mut target)));
        for b in line_backends() {
            group.bench_function(BenchmarkId::from_parameter(b.name()), |bench| {
                bench.iter(|| one.install(|| work.run(*b, &mut target)))
            });
        }
        group.bench_function(BenchmarkId::from_parameter("fast-bresenham"), |bench| {
            bench.iter(|| one.install(|| work.run_fast(&mut target)))
        });
        let mut buffer = vec![[0u8; 4]; (W * H) as usize];
        group.bench_function(BenchmarkId::from_parameter("peer-line_drawing"), |bench| {
            bench.iter(|| line_drawing_lines(&ints, &mut buffer))
        });
        group.finish();
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10).warm_up_time(Duration::from_millis(500)).measurement_time(Duration::from_secs(2));
    targets = dragon, triangles, lines
}
criterion_main!(benches);
