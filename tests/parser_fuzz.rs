//! The parsers under mutated files: valid inputs with bytes flipped, cut,
//! duplicated and spliced. Every parse ends in a mesh or shapes, or in an
//! error that names the file (and the line, for the formats with lines);
//! none panics, and none takes long or allocates much (the header counts
//! of a PLY file allocate nothing until their data is read).
//!
//! At the end each suite prints its figures: cases, distinct error
//! messages (with numbers masked), and the slowest parse.

use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};
use rasterlab::geometry::{parse_obj, parse_shapes, read_ply};
use std::collections::BTreeSet;
use std::path::Path;
use std::time::{Duration, Instant};

/// One mutation of a byte string.
#[derive(Clone, Debug)]
enum Mutation {
    Flip { at: usize, bit: u8 },
    Cut { at: usize },
    Duplicate { from: usize, len: usize, to: usize },
    Splice { at: usize, bytes: Vec<u8> },
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let pos = any::<prop::sample::Index>();
    prop_oneof![
        (pos.clone(), 0u8..8).prop_map(|(at, bit)| Mutation::Flip {
            at: at.index(usize::MAX),
            bit
        }),
        pos.clone().prop_map(|at| Mutation::Cut {
            at: at.index(usize::MAX)
        }),
        (pos.clone(), 1usize..64, pos.clone()).prop_map(|(from, len, to)| Mutation::Duplicate {
            from: from.index(usize::MAX),
            len,
            to: to.index(usize::MAX),
        }),
        (
            pos,
            prop::collection::vec(
                prop_oneof![
                    any::<u8>(),
                    Just(b'\n'),
                    Just(b' '),
                    Just(b'-'),
                    Just(b'9'),
                    Just(b'e'),
                    Just(b'.'),
                    Just(b'/'),
                ],
                1..12
            )
        )
            .prop_map(|(at, bytes)| Mutation::Splice {
                at: at.index(usize::MAX),
                bytes
            }),
    ]
}

fn apply(data: &[u8], mutations: &[Mutation]) -> Vec<u8> {
    let mut d = data.to_vec();
    for m in mutations {
        if d.is_empty() {
            break;
        }
        let n = d.len();
        match m {
            Mutation::Flip { at, bit } => d[at % n] ^= 1 << bit,
            Mutation::Cut { at } => d.truncate(at % n),
            Mutation::Duplicate { from, len, to } => {
                let from = from % n;
                let piece = d[from..(from + len).min(n)].to_vec();
                let to = to % (n + 1);
                d.splice(to..to, piece);
            }
            Mutation::Splice { at, bytes } => {
                let at = at % (n + 1);
                d.splice(at..at, bytes.iter().copied());
            }
        }
    }
    d
}

/// Error text with its numbers masked, to count distinct kinds of error.
fn kind(message: &str) -> String {
    let mut out = String::new();
    let mut in_number = false;
    for c in message.chars() {
        if c.is_ascii_digit() {
            if !in_number {
                out.push('#');
            }
            in_number = true;
        } else {
            in_number = false;
            out.push(c);
        }
    }
    out.chars().take(90).collect()
}

/// Runs `cases` mutated copies of `valid` through `parse`, which returns
/// the error message, if any. Checks every message names `file` (and a
/// line, when `lines`), and prints the figures.
fn fuzz(
    name: &str,
    valid: &[u8],
    file: &str,
    lines: bool,
    cases: u32,
    parse: impl Fn(&[u8]) -> Option<String>,
) {
    let mut runner = TestRunner::new(Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    });
    let errors = std::cell::RefCell::new(BTreeSet::new());
    let slowest = std::cell::Cell::new(Duration::ZERO);
    let strategy = prop::collection::vec(mutation(), 1..4);
    runner
        .run(&strategy, |mutations| {
            let data = apply(valid, &mutations);
            let start = Instant::now();
            let result = parse(&data);
            slowest.set(slowest.get().max(start.elapsed()));
            if let Some(message) = result {
                prop_assert!(message.starts_with(file), "{message}");
                if lines {
                    let after = &message[file.len()..];
                    let has_line = after.starts_with(':')
                        && after[1..]
                            .chars()
                            .next()
                            .is_some_and(|c| c.is_ascii_digit());
                    // Errors about the file as a whole (no faces, no data,
                    // not UTF-8) have no line.
                    prop_assert!(has_line || after.starts_with(": "), "{message}");
                }
                errors.borrow_mut().insert(kind(&message));
            }
            Ok(())
        })
        .unwrap();
    // The process's peak resident memory so far (all suites together).
    let peak = std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM"))
                .map(str::to_string)
        })
        .unwrap_or_default();
    eprintln!(
        "{name}: {cases} mutated files, {} distinct errors, slowest parse {:.2} ms, {peak}",
        errors.borrow().len(),
        slowest.get().as_secs_f64() * 1e3
    );
    assert!(
        !errors.borrow().is_empty(),
        "{name}: mutations never produced an error"
    );
}

fn text_shapes(data: &[u8], file: &str) -> Option<String> {
    let text = match std::str::from_utf8(data) {
        Ok(t) => t,
        Err(_) => return None, // read_shapes refuses it before parsing
    };
    parse_shapes(text, Path::new(file))
        .err()
        .map(|e| e.to_string())
}

#[test]
fn triangle_soups_polygons_and_line_sets_survive_mutation() {
    let soup = b"# soup\n0 0 5 0 5 5\n0 5 0 0 5 5\n10.25 3 20 7.5 12 19\n";
    fuzz("soup", soup, "soup.txt", true, 1500, |d| {
        text_shapes(d, "soup.txt")
    });
    let polygon =
        std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/polygon.txt")).unwrap();
    fuzz("polygon", &polygon, "polygon.txt", true, 1500, |d| {
        text_shapes(d, "polygon.txt")
    });
    let lines = std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/lines.txt")).unwrap();
    fuzz("lines", &lines, "lines.txt", true, 1500, |d| {
        text_shapes(d, "lines.txt")
    });
}

/// A small ASCII PLY (the course's vertex array as a mesh, one quad) and
/// the same mesh in binary little-endian.
fn small_plys() -> (Vec<u8>, Vec<u8>) {
    let header = |format: &str| {
        format!(
            "ply\nformat {format} 1.0\ncomment fuzz\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
        )
    };
    let vertices = [
        [0.0f32, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.5, 2.0, 0.5],
    ];
    let faces: [&[i32]; 2] = [&[0, 1, 2, 3], &[2, 4, 3]];
    let mut ascii = header("ascii").into_bytes();
    let mut binary = header("binary_little_endian").into_bytes();
    for v in vertices {
        ascii.extend(format!("{} {} {} 200 100 50\n", v[0], v[1], v[2]).bytes());
        for c in v {
            binary.extend(c.to_le_bytes());
        }
        binary.extend([200, 100, 50]);
    }
    for f in faces {
        let idx: Vec<String> = f.iter().map(|i| i.to_string()).collect();
        ascii.extend(format!("{} {}\n", f.len(), idx.join(" ")).bytes());
        binary.push(f.len() as u8);
        for i in f {
            binary.extend(i.to_le_bytes());
        }
    }
    (ascii, binary)
}

#[test]
fn ply_files_survive_mutation() {
    let (ascii, binary) = small_plys();
    assert!(read_ply(std::io::Cursor::new(&ascii), Path::new("a.ply")).is_ok());
    assert!(read_ply(std::io::Cursor::new(&binary), Path::new("b.ply")).is_ok());
    let parse = |file: &'static str| {
        move |d: &[u8]| {
            read_ply(std::io::Cursor::new(d), Path::new(file))
                .err()
                .map(|e| e.to_string())
        }
    };
    fuzz("ply ascii", &ascii, "a.ply", false, 2000, parse("a.ply"));
    fuzz("ply binary", &binary, "b.ply", false, 2000, parse("b.ply"));
}

#[test]
fn gzip_compressed_ply_files_survive_mutation() {
    use std::io::Write;
    let (ascii, _) = small_plys();
    let mut e = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
    e.write_all(&ascii).unwrap();
    let packed = e.finish().unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("m.ply.gz");
    let file = path.to_str().unwrap().to_string();
    fuzz("ply.gz", &packed, &file, false, 800, |d| {
        std::fs::write(&path, d).unwrap();
        rasterlab::geometry::Mesh::load(&path)
            .err()
            .map(|e| e.to_string())
    });
}

#[test]
fn obj_files_survive_mutation() {
    let obj = b"# an L and a quad\nv 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nvt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1 4/1/1 5/2/1 6/3/1\nf 1 2 3\nf -1 -2 -3\n";
    fuzz("obj", obj, "m.obj", true, 2000, |d| {
        let text = std::str::from_utf8(d).ok()?;
        parse_obj(text, Path::new("m.obj"))
            .err()
            .map(|e| e.to_string())
    });
}
