//! How long one update of the lab takes on the server: a 64 x 64 grid
//! with a few triangles (or lines), every back-end, its trace and the heat
//! map, as the page asks while a vertex is dragged.
//!
//! `cargo bench --bench lab`

use criterion::{criterion_group, criterion_main, Criterion};
use rasterlab::lab::{answer, LabRequest};
use std::hint::black_box;

fn updates(c: &mut Criterion) {
    let triangles = LabRequest::parse(
        r#"{"width": 64, "height": 64, "kind": "triangles",
            "triangles": [[[3.5, 2.25], [60.75, 20.5], [14.25, 61.5]],
                          [[60.75, 20.5], [62, 62], [14.25, 61.5]],
                          [[3.5, 2.25], [14.25, 61.5], [1, 40]]],
            "backends": ["naive", "bbox", "scanline", "incremental", "tiled"],
            "trace": "scanline"}"#,
    )
    .unwrap();
    let depth = LabRequest {
        depths: vec![0.5, 0.8, 0.3],
        ..triangles.clone()
    };
    let lines = LabRequest::parse(
        r#"{"width": 64, "height": 64, "kind": "lines",
            "lines": [[[0.5, 0.5], [63.5, 20.5]], [[10, 60], [50, 3]], [[2, 30], [62, 31]]],
            "backends": ["direct", "dda", "bresenham", "wu", "diamond"],
            "trace": "bresenham"}"#,
    )
    .unwrap();
    let mut group = c.benchmark_group("lab-update-64x64");
    for (name, request) in [
        ("triangles", &triangles),
        ("triangles-depth", &depth),
        ("lines", &lines),
    ] {
        group.bench_function(name, |b| {
            b.iter(|| black_box(answer(request, None).unwrap()))
        });
        // The whole round trip on the server: parse, answer, serialize.
        let text = serde_json::to_string(request).unwrap();
        group.bench_function(format!("{name}-json"), |b| {
            b.iter(|| {
                let r = LabRequest::parse(black_box(&text)).unwrap();
                black_box(serde_json::to_string(&answer(&r, None).unwrap()).unwrap())
            })
        });
    }
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = updates
}
criterion_main!(benches);
