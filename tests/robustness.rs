//! Hostile use of the command line: every defect found by trying the CLI as
//! a new user and as an adversarial tester, each with the command that
//! showed it, and the README's table of exit codes, row by row.

mod common;
use common::rasterlab;

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Asserts the exit code, that nothing panicked, and that the message (if
/// any is expected) is on stderr.
fn expect(out: &Output, code: i32, message: &str) {
    let err = stderr(out);
    assert_eq!(out.status.code(), Some(code), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(err.contains(message), "wanted `{message}` in: {err}");
}

/// Writes `bytes` to the file `name` in `dir` (a test's own temporary
/// folder, removed when the test ends, whether it passes or panics).
fn temp_file(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

const BUNNY: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/bunny.ply");
const DRAGON: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/assets/dragon_vrip_res4.ply.gz"
);

/// Item 1: a reader that goes away (`| head -1`) stops the command quietly
/// with exit 3, and a full disk is reported with exit 3; no panic.
#[test]
fn closed_and_full_standard_output_exit_3_without_a_panic() {
    let tmp = tempfile::tempdir().unwrap();
    for args in [
        vec![
            "explain",
            "--backend",
            "naive",
            "--size",
            "256x256",
            "1",
            "1",
            "200",
            "2",
            "3",
            "200",
        ],
        vec!["backends"],
        vec!["render", BUNNY, "--size", "32x32", "--out"],
    ] {
        let mut args: Vec<String> = args.iter().map(|a| a.to_string()).collect();
        if args.last().map(String::as_str) == Some("--out") {
            args.push(s(&tmp.path().join("pipe.png")).to_string());
        }
        // A pipe whose reading end is already closed.
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let out = Command::new(env!("CARGO_BIN_EXE_rasterlab"))
            .args(&args)
            .stdout(writer)
            .output()
            .unwrap();
        expect(&out, 3, "");
        assert!(
            stderr(&out).is_empty(),
            "a closed pipe is not an error to report"
        );
        let full = std::fs::File::create("/dev/full").unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_rasterlab"))
            .args(&args)
            .stdout(full)
            .output()
            .unwrap();
        expect(&out, 3, "No space left on device");
    }
}

/// Item 2: `explain` snaps the same f64 input as `fragments` (its x,
/// 100.50195313, snaps to 100.50390625; in f32 it used to snap to 100.5).
#[test]
fn explain_and_fragments_snap_the_same_coordinates() {
    let tmp = tempfile::tempdir().unwrap();
    let coords = ["100.50195313", "0", "100.50195313", "10", "105", "5"];
    let mut args = vec!["explain", "--backend", "bbox", "--size", "128x16"];
    args.extend(coords);
    let out = rasterlab(&args);
    expect(&out, 0, "");
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.trim_end().ends_with("20 fragments"), "{text}");
    let file = temp_file(tmp.path(), "snap.txt", coords.join(" ").as_bytes());
    let out = rasterlab(&[
        "fragments",
        "--backend",
        "bbox",
        "--size",
        "128x16",
        s(&file),
    ]);
    assert_eq!(String::from_utf8(out.stdout).unwrap().lines().count(), 20);
}

/// Item 3: `explain` says how it reads line endpoints, and `--screen`
/// reads them as `fragments` does: the same pixels.
#[test]
fn explain_screen_coordinates_draw_what_fragments_draws() {
    let tmp = tempfile::tempdir().unwrap();
    let file = temp_file(tmp.path(), "line.txt", b"0.7 0.2 9.3 4.9\n");
    let out = rasterlab(&[
        "fragments",
        "--backend",
        "bresenham",
        "--size",
        "16x16",
        s(&file),
    ]);
    let mut want: Vec<String> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| l.split_whitespace().take(2).collect::<Vec<_>>().join(","))
        .collect();
    let out = rasterlab(&[
        "explain",
        "--screen",
        "--backend",
        "bresenham",
        "0.7",
        "0.2",
        "9.3",
        "4.9",
    ]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.lines()
            .next()
            .unwrap()
            .contains("in screen coordinates"),
        "{text}"
    );
    let mut got: Vec<String> = text
        .lines()
        .skip(2)
        .filter_map(|l| l.split_whitespace().nth(2).map(str::to_string))
        .filter(|p| p.contains(','))
        .collect();
    want.sort();
    got.sort();
    assert_eq!(got, want);
    let out = rasterlab(&["explain", "--backend", "bresenham", "0", "0", "7", "3"]);
    assert!(String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .next()
        .unwrap()
        .contains("pixel indices"));
}

/// Item 4: a hole outside its polygon, or inside another hole, is an error
/// at the hole's line.
#[test]
fn misplaced_holes_are_errors_at_their_line() {
    let tmp = tempfile::tempdir().unwrap();
    let outside = temp_file(
        tmp.path(),
        "hole-out.txt",
        b"polygon 0 0 10 0 10 10 0 10\nhole 20 20 30 20 20 30\n",
    );
    let out = rasterlab(&[
        "fragments",
        "--backend",
        "bbox",
        "--size",
        "40x40",
        s(&outside),
    ]);
    expect(&out, 2, "hole-out.txt:2: hole 1 lies outside its polygon");
    let nested = temp_file(
        tmp.path(),
        "hole-in-hole.txt",
        b"polygon 0 0 10 0 10 10 0 10\nhole 2 2 8 2 8 8 2 8\n# nested\nhole 3 3 5 3 5 5\n",
    );
    let out = rasterlab(&[
        "fragments",
        "--backend",
        "bbox",
        "--size",
        "40x40",
        s(&nested),
    ]);
    expect(&out, 2, "hole-in-hole.txt:4: hole 2 lies inside hole 1");
    let good = temp_file(
        tmp.path(),
        "hole-ok.txt",
        b"polygon 0 0 10 0 10 10 0 10\nhole 2 2 8 2 8 8\n",
    );
    let out = rasterlab(&[
        "fragments",
        "--backend",
        "bbox",
        "--size",
        "40x40",
        s(&good),
    ]);
    expect(&out, 0, "");
}

/// Item 5: an L-shaped OBJ face covers what the same L split by hand
/// covers (a fan made a notched square of it); a self-crossing face is an
/// error at its line.
#[test]
fn concave_obj_faces_are_triangulated_not_fanned() {
    let tmp = tempfile::tempdir().unwrap();
    let corners = "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\n";
    let l_face = temp_file(
        tmp.path(),
        "l.obj",
        format!("{corners}f 1 2 3 4 5 6\n").as_bytes(),
    );
    let by_hand = temp_file(
        tmp.path(),
        "l-split.obj",
        format!("{corners}f 1 2 3\nf 1 3 4\nf 1 4 5\nf 1 5 6\n").as_bytes(),
    );
    let render = |path: &Path| {
        let png = tmp.path().join(format!(
            "{}.png",
            path.file_stem().unwrap().to_str().unwrap()
        ));
        let out = rasterlab(&[
            "render",
            s(path),
            "--size",
            "64x64",
            "--cull",
            "none",
            "--elevation",
            "0",
            "--out",
            s(&png),
        ]);
        expect(&out, 0, "");
        image::open(png).unwrap().to_rgba8()
    };
    assert_eq!(render(&l_face), render(&by_hand));
    let bow = temp_file(
        tmp.path(),
        "bow.obj",
        b"v 0 0 0\nv 3 2 0\nv 3 0 0\nv 0 1 0\n\nf 1 2 3 4\n",
    );
    let out = rasterlab(&["render", s(&bow), "--out", s(&tmp.path().join("bow.png"))]);
    expect(&out, 2, "bow.obj:6: the face crosses itself");
}

/// Item 6: unbounded requests are refused (exit 4 with an estimate, or
/// exit 2 for an argument out of range) before any work.
#[test]
fn requests_beyond_the_bounds_are_refused_with_an_estimate() {
    let tmp = tempfile::tempdir().unwrap();
    let out = rasterlab(&["--threads", "100000", "backends"]);
    expect(&out, 2, "--threads must be between 1 and 256");
    let out = rasterlab(&[
        "explain",
        "--backend",
        "naive",
        "--size",
        "16384x16384",
        "1",
        "1",
        "200",
        "2",
        "3",
        "200",
    ]);
    expect(&out, 4, "268435456 pixel lines");
    assert!(out.stdout.is_empty());
    let out = rasterlab(&[
        "explain",
        "--backend",
        "bbox",
        "--picture",
        "/nonexistent/p.png",
        "0",
        "0",
        "4",
        "0",
        "0",
        "4",
    ]);
    expect(&out, 3, "/nonexistent");
    assert!(
        out.stdout.is_empty(),
        "the picture's path is checked before the trace"
    );
    let out = rasterlab(&[
        "render",
        DRAGON,
        "--backend",
        "naive",
        "--size",
        "16384x16384",
        "--out",
        s(&tmp.path().join("n.png")),
    ]);
    expect(&out, 4, "give --force");
    let polygon = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/polygon.txt");
    let out = rasterlab(&[
        "compare",
        polygon,
        "--size",
        "16384x16384",
        "--out",
        s(&tmp.path().join("big")),
    ]);
    expect(&out, 4, "64.0 GiB");
}

/// Item 6: the simplicity check sweeps instead of testing every pair, so a
/// polygon of 20,000 vertices is read at once (it took 4 s); it still
/// finds a crossing between the first and last edges of such a polygon.
#[test]
fn large_polygons_are_checked_and_triangulated() {
    let tmp = tempfile::tempdir().unwrap();
    let n = 20_000;
    let ring: Vec<String> = (0..n)
        .map(|i| {
            let a = i as f64 / n as f64 * std::f64::consts::TAU;
            format!(
                "{:.4} {:.4}",
                500.0 + 400.0 * a.cos(),
                500.0 + 400.0 * a.sin()
            )
        })
        .collect();
    let circle = temp_file(
        tmp.path(),
        "circle.txt",
        format!("polygon {}\n", ring.join(" ")).as_bytes(),
    );
    let out = rasterlab(&[
        "fragments",
        "--backend",
        "scanline",
        "--size",
        "1000x1000",
        s(&circle),
    ]);
    expect(&out, 0, "");
    let mut crossed = ring.clone();
    crossed.swap(0, n / 2);
    let crossed = temp_file(
        tmp.path(),
        "crossed.txt",
        format!("polygon {}\n", crossed.join(" ")).as_bytes(),
    );
    let out = rasterlab(&[
        "fragments",
        "--backend",
        "scanline",
        "--size",
        "1000x1000",
        s(&crossed),
    ]);
    expect(&out, 2, "crossed.txt:1: polygon is not simple");
}

fn gzip(bytes: &[u8]) -> Vec<u8> {
    let mut e = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
    e.write_all(bytes).unwrap();
    e.finish().unwrap()
}

/// Item 7: every member of a multi-member gzip file is read; a cut file
/// and a bad CRC are errors.
#[test]
fn gzip_members_are_all_read_and_their_trailers_checked() {
    let tmp = tempfile::tempdir().unwrap();
    let bunny = std::fs::read(BUNNY).unwrap();
    let (a, b) = bunny.split_at(bunny.len() / 2);
    let whole = rasterlab::geometry::Mesh::load(Path::new(BUNNY)).unwrap();
    let multi = temp_file(tmp.path(), "multi.ply.gz", &[gzip(a), gzip(b)].concat());
    assert_eq!(rasterlab::geometry::Mesh::load(&multi).unwrap(), whole);
    let packed = gzip(&bunny);
    let cut = temp_file(tmp.path(), "cut.ply.gz", &packed[..packed.len() - 3]);
    let err = rasterlab::geometry::Mesh::load(&cut)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("cut.ply.gz") && err.contains("end of file"),
        "{err}"
    );
    let mut bad = packed.clone();
    let at = bad.len() - 6;
    bad[at] ^= 0xff;
    let crc = temp_file(tmp.path(), "crc.ply.gz", &bad);
    let err = rasterlab::geometry::Mesh::load(&crc)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("crc.ply.gz") && err.contains("checksum"),
        "{err}"
    );
}

/// Items 8 and 11: messages that say what is wrong, where.
#[test]
fn errors_name_the_real_cause() {
    let tmp = tempfile::tempdir().unwrap();
    let huge = temp_file(tmp.path(),
        "huge.ply",
        b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1e20 0 0\n0 1 0\n3 0 1 2\n",
    );
    let out = rasterlab(&["render", s(&huge), "--out", s(&tmp.path().join("h.png"))]);
    expect(
        &out,
        2,
        "huge.ply:11: `vertex` 1: coordinate 100000000000000000000 is beyond",
    );
    let out = rasterlab(&[
        "render",
        BUNNY,
        "--zoom",
        "nan",
        "--out",
        s(&tmp.path().join("z.png")),
    ]);
    expect(&out, 2, "zoom must be > 0");
    // A negative zoom is a value out of range, not an unknown flag.
    let out = rasterlab(&[
        "render",
        BUNNY,
        "--zoom",
        "-1",
        "--out",
        s(&tmp.path().join("z.png")),
    ]);
    expect(&out, 2, "zoom must be > 0 and at most 1000000, not -1");
    let bom = temp_file(tmp.path(), "bom.txt", "\u{feff}0 0 5 0 5 5\n".as_bytes());
    let out = rasterlab(&["fragments", "--backend", "bbox", "--size", "8x8", s(&bom)]);
    expect(&out, 0, "");
    assert_eq!(String::from_utf8(out.stdout).unwrap().lines().count(), 15);
    let out = rasterlab(&["fragments", "--backend", "bbox", "--size", "8x8", BUNNY]);
    expect(&out, 2, "this is a mesh");
    // A 2D file with nothing to draw is refused, as an empty mesh is.
    let empty = temp_file(tmp.path(), "empty.txt", b"# nothing here\n\n");
    for command in [
        vec!["fragments", "--backend", "bbox", "--size", "8x8", s(&empty)],
        vec![
            "render",
            s(&empty),
            "--size",
            "8x8",
            "--out",
            s(&tmp.path().join("empty.png")),
        ],
    ] {
        let out = rasterlab(&command);
        expect(
            &out,
            2,
            "empty.txt: no triangle, polygon or line segment in it (only blank lines and comments)",
        );
    }
    assert!(
        !tmp.path().join("empty.png").exists(),
        "no picture of nothing"
    );
    // Faces beyond the header's count are an error, not dropped.
    let bunny = std::fs::read(BUNNY).unwrap();
    let extra = temp_file(
        tmp.path(),
        "extra.ply",
        &[bunny.as_slice(), b"3 0 1 2\n"].concat(),
    );
    let out = rasterlab(&["render", s(&extra), "--out", s(&tmp.path().join("e.png"))]);
    expect(&out, 2, "extra.ply:5524: data after the last element");
    // `-` reads standard input.
    let mut child = Command::new(env!("CARGO_BIN_EXE_rasterlab"))
        .args(["fragments", "--backend", "bbox", "--size", "8x8", "-"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(b"0 0 5 0 5 5\n")
        .unwrap();
    let out = child.wait_with_output().unwrap();
    assert_eq!(String::from_utf8(out.stdout).unwrap().lines().count(), 15);
}

/// Items 9 and 10: output paths are checked before the work, files are
/// written whole or not at all, and `.PNG` is a PNG everywhere.
#[test]
fn outputs_are_checked_first_and_never_left_half_written() {
    let tmp = tempfile::tempdir().unwrap();
    let jpg = tmp.path().join("x.jpg");
    let out = rasterlab(&["render", BUNNY, "--out", s(&jpg)]);
    expect(&out, 3, "written as .png");
    assert!(!jpg.exists(), "no empty file is left behind");
    let out = rasterlab(&["bench", "--out", "/proc/b"]);
    expect(&out, 3, "/proc/b");
    assert!(out.stdout.is_empty(), "refused before the benchmark ran");
    let upper = tmp.path().join("grid.PNG");
    let out = rasterlab(&[
        "explain",
        "--backend",
        "bbox",
        "--picture",
        s(&upper),
        "0",
        "0",
        "4",
        "0",
        "0",
        "4",
    ]);
    expect(&out, 0, "");
    assert!(image::open(&upper).is_ok());
    let out = rasterlab(&[
        "explain",
        "--backend",
        "bbox",
        "--size",
        "0x0",
        "0",
        "0",
        "1",
        "0",
        "0",
        "1",
    ]);
    expect(&out, 2, "target size 0x0 is invalid");
    for command in ["bench", "compare"] {
        let mut args = vec![command, "--samples", "0"];
        if command == "compare" {
            args.push(BUNNY);
        }
        expect(&rasterlab(&args), 2, "--samples must be between 1");
    }
}

/// `compare` with bad input does nothing: not even its output directory
/// is left behind (exit 2: "nothing was done").
#[test]
fn compare_with_bad_input_leaves_no_output_directory() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let out = dir.join("report");
    let out_arg = out.to_str().unwrap();
    let missing = dir.join("missing.txt");
    for args in [
        vec!["compare", missing.to_str().unwrap(), "--out", out_arg],
        vec![
            "compare",
            "assets/polygon.txt",
            "--size",
            "0x0",
            "--out",
            out_arg,
        ],
    ] {
        let run = rasterlab(&args);
        assert_eq!(run.status.code(), Some(2), "{args:?}");
        assert!(!out.exists(), "{args:?} left {}", out.display());
    }
    // Good input writes the report there.
    let good = rasterlab(&[
        "compare",
        "assets/polygon.txt",
        "--size",
        "8x8",
        "--out",
        out_arg,
    ]);
    assert_eq!(good.status.code(), Some(0), "{}", stderr(&good));
    assert!(out.join("index.html").is_file());
}

/// The README's exit-code table, one row each: 0 done, 2 bad input or
/// argument (clap's usage errors too), 3 output not written, 4 refused.
/// Row 1 (a mismatch found) is checked on the library's error in
/// `exit_codes_follow_the_kind_of_error`.
#[test]
fn exit_codes_follow_the_readme_table() {
    let tmp = tempfile::tempdir().unwrap();
    expect(&rasterlab(&["backends"]), 0, "");
    expect(
        &rasterlab(&["fragments", "--backend", "nope", "--size", "4x4", "x"]),
        2,
        "back-end `nope`",
    );
    expect(
        &rasterlab(&["render", "--nonsense"]),
        2,
        "unexpected argument",
    );
    expect(
        &rasterlab(&[
            "render",
            "/nonexistent.ply",
            "--out",
            s(&tmp.path().join("a.png")),
        ]),
        2,
        "/nonexistent.ply",
    );
    expect(
        &rasterlab(&["render", "--scene", "fan", "--out", "/nonexistent/a.png"]),
        3,
        "/nonexistent",
    );
    expect(
        &rasterlab(&[
            "explain",
            "--backend",
            "naive",
            "--size",
            "1000x1000",
            "0",
            "0",
            "9",
            "0",
            "0",
            "9",
        ]),
        4,
        "at most 65536",
    );
}

#[test]
fn exit_codes_follow_the_kind_of_error() {
    use rasterlab::Error;
    assert_eq!(Error::Mismatch("x".into()).exit_code(), 1);
    assert_eq!(Error::InvalidArgument("x".into()).exit_code(), 2);
    assert_eq!(Error::io("f", &std::io::Error::other("x")).exit_code(), 2);
    assert_eq!(
        Error::write("f", &std::io::Error::other("x")).exit_code(),
        3
    );
    assert_eq!(Error::TooMuchWork("x".into()).exit_code(), 4);
}

/// No argument makes any subcommand panic: every subcommand with hostile
/// values in every option.
#[test]
fn no_hostile_argument_panics_any_subcommand() {
    let tmp = tempfile::tempdir().unwrap();
    let hostile = [
        "nan",
        "inf",
        "-inf",
        "-1",
        "0",
        "1e308",
        "-1e308",
        "99999999999999999999",
        "0x0",
        "1x99999999",
        "",
        "-",
        "\u{feff}",
        "../../../../etc/passwd",
        "/dev/null",
        "/proc/b",
    ];
    let commands: &[(&str, &[&str])] = &[
        (
            "fragments",
            &[
                "--backend",
                "--size",
                "--rule",
                "--connectivity",
                "--endpoints",
            ],
        ),
        (
            "render",
            &[
                "--backend",
                "--size",
                "--rule",
                "--depth-test",
                "--scene",
                "--shading",
                "--filter",
                "--interpolation",
                "--cull",
                "--front-face",
                "--wireframe",
                "--azimuth",
                "--elevation",
                "--zoom",
                "--frames",
            ],
        ),
        ("explain", &["--backend", "--rule", "--size", "--picture"]),
        ("compare", &["--size", "--samples", "--out"]),
        ("bench", &["--set", "--size", "--samples", "--mesh"]),
        (
            "check",
            &[
                "--backend",
                "--kind",
                "--rule",
                "--convention",
                "--cases",
                "--seed",
                "--timeout",
                "--exec",
            ],
        ),
    ];
    let check_out = tmp.path().join("check-hostile");
    let check_out = s(&check_out);
    let polygon = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/polygon.txt");
    let mut runs = 0;
    for (command, options) in commands {
        for option in *options {
            for value in hostile {
                // A small valid base, so the hostile value is what is tested.
                let mut args: Vec<&str> = match *command {
                    "fragments" => vec![command, "--backend", "bbox", "--size", "8x8", polygon],
                    "render" => vec![command, "--scene", "fan", "--out", "/dev/null/x.png"],
                    "explain" => vec![command, "--backend", "bbox", "0", "0", "4", "0", "0", "4"],
                    "compare" => vec![command, polygon, "--out", "/dev/null/r"],
                    "check" => vec![command, "--cases", "2", "--out", check_out],
                    _ => vec![
                        command,
                        "--set",
                        "quick",
                        "--size",
                        "8x8",
                        "--samples",
                        "1",
                        "--out",
                        "/dev/null/b",
                    ],
                };
                args.push(option);
                args.push(value);
                let out = rasterlab(&args);
                let err = stderr(&out);
                assert!(!err.contains("panicked"), "{args:?}: {err}");
                assert!(
                    matches!(out.status.code(), Some(0..=4)),
                    "{args:?}: {:?} {err}",
                    out.status
                );
                runs += 1;
            }
        }
    }
    assert_eq!(runs, 39 * hostile.len());
}
