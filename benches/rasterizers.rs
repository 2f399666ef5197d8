//! Side-by-side timings of the back-ends on 2D workloads, one benchmark id
//! per back-end: fill rate (two full-screen triangles), a sweep of triangle
//! sizes, thin slivers, and short and long lines.
//!
//! `cargo bench --bench rasterizers`

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use rasterlab::raster::line::{LineOptions, LineSetup};
use rasterlab::raster::{
    line_backends, triangle_backends, within_budget, FillRule, FixedPoint, FragmentSink,
    LineFragment, PixelRect, TriangleFragment, TriangleSetup, WorkBudget,
};
use std::hint::black_box;

/// Counts fragments, so only the rasterizers are measured.
#[derive(Default)]
struct Count(u64);

impl FragmentSink for Count {
    fn triangle_fragment(&mut self, f: &TriangleFragment) {
        self.0 += u64::from(f.x & 1) + 1;
    }
    fn line_fragment(&mut self, f: &LineFragment) {
        self.0 += u64::from(f.x & 1) + 1;
    }
}

const W: u32 = 1920;
const H: u32 = 1080;

fn p(x: f32, y: f32) -> FixedPoint {
    FixedPoint::snap(x, y).unwrap()
}

fn setups(tris: &[[FixedPoint; 3]]) -> Vec<TriangleSetup> {
    rasterlab::geometry::setup_triangles(tris, FillRule::TopLeft)
}

/// A grid of right triangles of side `size` covering about 200,000 pixels.
fn sized(size: f32) -> Vec<[FixedPoint; 3]> {
    let n = ((200_000.0 / (size * size)).sqrt().ceil() as usize).max(1);
    let mut v = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (
                0.3 + i as f32 * (size + 1.0) % 1800.0,
                0.7 + j as f32 * (size + 1.0) % 1000.0,
            );
            v.push([p(x, y), p(x + size, y), p(x, y + size)]);
        }
    }
    v
}

fn triangles(c: &mut Criterion) {
    let full_screen = vec![
        [p(0., 0.), p(W as f32, 0.), p(W as f32, H as f32)],
        [p(0., 0.), p(W as f32, H as f32), p(0., H as f32)],
    ];
    let slivers: Vec<[FixedPoint; 3]> = (0..20)
        .flat_map(|k| {
            let o = 20.0 + k as f32 * 40.0;
            [
                [p(o, 50.), p(o + 500., 51.5), p(o, 51.5)],
                [p(o, o), p(o + 353.6, o + 353.6), p(o + 1.4, o)],
                [p(o + 900., 20.), p(o + 901.5, 20.), p(o + 901.5, 520.)],
            ]
        })
        .collect();
    let mut workloads: Vec<(String, Vec<TriangleSetup>)> = vec![
        ("fill-2-full-screen".into(), setups(&full_screen)),
        ("slivers-60".into(), setups(&slivers)),
    ];
    for size in [2.0, 8.0, 32.0, 128.0, 500.0] {
        workloads.push((format!("size-{size}px"), setups(&sized(size))));
    }
    let viewport = PixelRect::of_target(W, H);
    for (name, work) in &workloads {
        let mut group = c.benchmark_group(format!("triangles/{name}"));
        let mut probe = Count::default();
        let pixels = triangle_backends()[1]
            .rasterize(work, viewport, &mut probe)
            .fragments;
        group.throughput(Throughput::Elements(pixels));
        for b in triangle_backends() {
            // The naive loop tests every pixel against every triangle:
            // 2 million x thousands of triangles is beyond a benchmark.
            if within_budget(
                &b.descriptor(),
                work.len() as u64,
                viewport.area(),
                WorkBudget::Timing,
            )
            .is_err()
            {
                continue;
            }
            group.bench_function(BenchmarkId::from_parameter(b.name()), |bench| {
                bench.iter(|| {
                    let mut sink = Count::default();
                    b.rasterize(black_box(work), viewport, &mut sink);
                    sink.0
                })
            });
        }
        group.finish();
    }
}

fn lines(c: &mut Criterion) {
    let mut state = 1u64;
    let mut next = move |m: f32| {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 40) as f32 / (1u64 << 24) as f32 * m
    };
    let short: Vec<LineSetup> = (0..100_000)
        .map(|i| {
            let (x, y) = (next(1900.0), next(1060.0));
            LineSetup {
                id: i,
                from: p(x, y),
                to: p(x + 2.0 + next(14.0), y + next(16.0)),
            }
        })
        .collect();
    let long: Vec<LineSetup> = (0..1_000)
        .map(|i| {
            let y = next(80.0);
            LineSetup {
                id: i,
                from: p(10.0, y),
                to: p(1010.0, y + next(1000.0)),
            }
        })
        .collect();
    let viewport = PixelRect::of_target(W, H);
    for (name, work) in [("short-100k", &short), ("long-1k", &long)] {
        let mut group = c.benchmark_group(format!("lines/{name}"));
        let mut probe = Count::default();
        let pixels = line_backends()[2]
            .rasterize(work, &LineOptions::DEFAULT, viewport, &mut probe)
            .fragments;
        group.throughput(Throughput::Elements(pixels));
        for b in line_backends() {
            group.bench_function(BenchmarkId::from_parameter(b.name()), |bench| {
                bench.iter(|| {
                    let mut sink = Count::default();
                    b.rasterize(black_box(work), &LineOptions::DEFAULT, viewport, &mut sink);
                    sink.0
                })
            });
        }
        group.finish();
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10).measurement_time(std::time::Duration::from_secs(2));
    targets = triangles, lines
}
criterion_main!(benches);
