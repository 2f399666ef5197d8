//! Why the PLY reader is more than `ply-rs-bw`: the same bytes read into
//! the same arrays by `rasterlab::geometry::read_ply` and by `ply-rs-bw`'s
//! general reader, which makes every value a dynamically typed property in
//! a map per element (the vertices' positions and the faces' triangles are
//! then copied out, as a mesh needs them).
//!
//! ```text
//! cargo bench --bench ply_load                 # 5 rounds
//! cargo bench --bench ply_load -- --rounds 9
//! ```
//!
//! The inputs are the bundled bunny and small dragon, and the full dragon
//! (`dragon_vrip.ply.gz`, 871,414 triangles) when it is found (see the
//! README's data section); each file is inflated into memory first, so
//! only parsing is timed. `read_ply` is timed on one thread and on every
//! thread (it parses a large element in blocks on several). Rounds are
//! interleaved; the table gives each reader's median and range over the
//! rounds, and its time over `read_ply` on one thread.

use flate2::read::MultiGzDecoder;
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{DefaultElement, Property};
use rasterlab::geometry::read_ply;
use rasterlab::measure::{find, Table, FULL_DRAGON};
use std::io::Read;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The file's bytes, inflated when it is gzip-compressed.
fn bytes(path: &Path) -> Vec<u8> {
    let raw = std::fs::read(path).expect("the model reads");
    if raw.starts_with(&[0x1f, 0x8b]) {
        let mut out = Vec::new();
        MultiGzDecoder::new(raw.as_slice())
            .read_to_end(&mut out)
            .expect("the model inflates");
        out
    } else {
        raw
    }
}

/// `ply-rs-bw` alone: the general reader, then positions and triangles
/// copied out of its maps. Returns the number of triangles.
fn ply_rs_bw_alone(bytes: &[u8]) -> usize {
    let ply = Parser::<DefaultElement>::new()
        .read_ply(&mut &bytes[..])
        .expect("ply-rs-bw reads the model");
    let coordinate = |v: &DefaultElement, k: &str| v.get(k).and_then(Property::to_f32_lossy);
    let positions: Vec<[f32; 3]> = ply.payload["vertex"]
        .iter()
        .map(|v| ["x", "y", "z"].map(|k| coordinate(v, k).expect("a vertex has x, y and z")))
        .collect();
    let mut triangles: Vec<[u32; 3]> = Vec::new();
    for face in &ply.payload["face"] {
        let indices: Vec<u32> = match face.get("vertex_indices") {
            Some(Property::ListInt(l)) => l.iter().map(|&i| i as u32).collect(),
            Some(Property::ListUInt(l)) => l.clone(),
            other => panic!("unexpected face list {other:?}"),
        };
        for k in 1..indices.len() - 1 {
            triangles.push([indices[0], indices[k], indices[k + 1]]);
        }
    }
    assert!(triangles
        .iter()
        .flatten()
        .all(|&i| (i as usize) < positions.len()));
    triangles.len()
}

/// `read_ply`, on the current thread pool. Returns the number of triangles.
fn rasterlab_reader(bytes: &[u8]) -> usize {
    read_ply(bytes, Path::new("model.ply"))
        .expect("read_ply reads the model")
        .triangles
        .len()
}

/// A reader by name: the bytes in, the number of triangles out.
type Reader<'a> = (&'static str, &'a dyn Fn(&[u8]) -> usize);

fn median(samples: &mut [f64]) -> f64 {
    samples.sort_by(f64::total_cmp);
    samples[samples.len() / 2]
}

fn main() {
    let mut rounds = 5usize;
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        if arg == "--rounds" {
            rounds = args
                .next()
                .and_then(|r| r.parse().ok())
                .filter(|&r| r > 0)
                .expect("--rounds takes a number above 0");
        }
    }
    let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets");
    let mut models: Vec<(String, PathBuf)> = vec![
        ("bunny.ply".into(), assets.join("bunny.ply")),
        (
            "dragon_vrip_res4.ply.gz".into(),
            assets.join("dragon_vrip_res4.ply.gz"),
        ),
    ];
    match find(FULL_DRAGON) {
        Ok(path) => models.push((FULL_DRAGON.into(), path)),
        Err(skipped) => println!("{skipped}"),
    }
    let one_thread = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a one-thread pool");
    let threads = rayon::current_num_threads();
    let readers: [Reader; 3] = [
        ("ply-rs-bw alone", &ply_rs_bw_alone),
        ("read_ply, 1 thread", &|b| {
            one_thread.install(|| rasterlab_reader(b))
        }),
        ("read_ply, all threads", &rasterlab_reader),
    ];
    let mut table = Table::new(&[
        "model",
        "triangles",
        "reader",
        "median ms",
        "range ms",
        "x read_ply 1 thread",
    ]);
    for (name, path) in &models {
        let data = bytes(path);
        let mut times = vec![Vec::new(); readers.len()];
        let mut counts = vec![0; readers.len()];
        for _ in 0..rounds {
            for (i, (_, read)) in readers.iter().enumerate() {
                let start = Instant::now();
                counts[i] = read(&data);
                times[i].push(start.elapsed().as_secs_f64() * 1e3);
            }
        }
        assert!(
            counts.iter().all(|&c| c == counts[0]),
            "{name}: the readers disagree on the triangles: {counts:?}"
        );
        let base = median(&mut times[1].clone());
        for (i, (reader, _)) in readers.iter().enumerate() {
            let (lo, hi) = (
                times[i].iter().copied().fold(f64::INFINITY, f64::min),
                times[i].iter().copied().fold(0.0, f64::max),
            );
            let m = median(&mut times[i]);
            table.row(vec![
                name.clone(),
                counts[i].to_string(),
                reader.to_string(),
                format!("{m:.1}"),
                format!("{lo:.1}-{hi:.1}"),
                format!("{:.2}", m / base),
            ]);
        }
    }
    println!(
        "PLY parsing from memory, {rounds} interleaved rounds, {threads} threads for \"all threads\""
    );
    print!("{table}");
}
