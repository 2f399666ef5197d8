//! The command-line contract: `backends`, `fragments` and error handling.

mod common;
use common::rasterlab;

use std::process::Output;

/// Asserts that the command succeeded (showing its stderr when not) and
/// returns its standard output.
fn success_stdout(out: Output) -> String {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// Writes `text` to the file `name` in `dir` (a test's own temporary
/// folder, removed when the test ends, whether it passes or panics).
fn temp_file(dir: &std::path::Path, name: &str, text: &str) -> std::path::PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn backends_lists_name_kind_and_description() {
    let out = rasterlab(&["backends"]);
    let text = success_stdout(out);
    let names: Vec<&str> = text
        .lines()
        .map(|l| l.split_whitespace().next().unwrap())
        .collect();
    for expected in ["naive", "bbox", "scanline", "incremental", "edge-table"] {
        assert!(names.contains(&expected), "{expected} missing from {text}");
    }
    for line in text.lines() {
        let fields: Vec<&str> = line.split_whitespace().collect();
        assert!(fields.len() >= 3, "{line}");
        assert!(
            ["triangle", "line", "polygon"].contains(&fields[1]),
            "{line}"
        );
    }
}

#[test]
fn fragments_prints_x_y_t_in_emission_order() {
    let tmp = tempfile::tempdir().unwrap();
    let soup = temp_file(
        tmp.path(),
        "split.txt",
        "# split square\n0 0 5 0 5 5\n\n0 5 0 0 5 5\n",
    );
    let out = rasterlab(&[
        "fragments",
        "--backend",
        "bbox",
        "--size",
        "5x5",
        soup.to_str().unwrap(),
    ]);
    let text = success_stdout(out);
    let rows: Vec<(u32, u32, u32)> = text
        .lines()
        .map(|l| {
            let v: Vec<u32> = l.split(' ').map(|n| n.parse().unwrap()).collect();
            (v[0], v[1], v[2])
        })
        .collect();
    assert_eq!(rows.len(), 25);
    assert_eq!(rows.iter().filter(|r| r.2 == 0).count(), 15);
    // bbox emits triangle 0 row by row, then triangle 1.
    assert_eq!(rows[0], (0, 0, 0));
    assert_eq!(rows[15], (0, 1, 1)); // (0, 0) is on the diagonal, which triangle 0 owns
    let naive = rasterlab(&[
        "fragments",
        "--backend",
        "naive",
        "--size",
        "5x5",
        "--rule",
        "bottom-right",
        soup.to_str().unwrap(),
    ]);
    assert_eq!(success_stdout(naive).lines().count(), 25);
}

#[test]
fn fragments_clips_to_the_target() {
    let tmp = tempfile::tempdir().unwrap();
    let soup = temp_file(tmp.path(), "big.txt", "-10 -10 100 -10 -10 100\n");
    let out = rasterlab(&[
        "fragments",
        "--backend",
        "scanline",
        "--size",
        "3x2",
        soup.to_str().unwrap(),
    ]);
    assert_eq!(String::from_utf8(out.stdout).unwrap().lines().count(), 6);
}

#[test]
fn malformed_input_names_the_file_and_line_exits_2_and_prints_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let soup = temp_file(
        tmp.path(),
        "bad.txt",
        "0 0 5 0 5 5\n# ok so far\n0 0 5 zero 5 5\n",
    );
    let out = rasterlab(&[
        "fragments",
        "--backend",
        "naive",
        "--size",
        "8x8",
        soup.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.contains("bad.txt:3:") && err.contains("`zero` is not a number"),
        "{err}"
    );

    let nan = temp_file(tmp.path(), "nan.txt", "0 0 5 0 NaN 5\n");
    let out = rasterlab(&[
        "fragments",
        "--backend",
        "naive",
        "--size",
        "8x8",
        nan.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8(out.stderr)
        .unwrap()
        .contains("nan.txt:1:"));

    let out = rasterlab(&[
        "fragments",
        "--backend",
        "naive",
        "--size",
        "8x8",
        "/nonexistent/soup.txt",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8(out.stderr)
        .unwrap()
        .contains("/nonexistent/soup.txt"));
}

#[test]
fn unknown_backends_rules_and_zero_sizes_fail_cleanly() {
    let tmp = tempfile::tempdir().unwrap();
    let soup = temp_file(tmp.path(), "ok.txt", "0 0 5 0 5 5\n");
    for args in [
        vec!["fragments", "--backend", "zbuffer", "--size", "8x8"],
        vec!["fragments", "--backend", "naive", "--size", "0x8"],
        vec![
            "fragments",
            "--backend",
            "naive",
            "--size",
            "8x8",
            "--rule",
            "diagonal",
        ],
    ] {
        let mut args = args.clone();
        args.push(soup.to_str().unwrap());
        let out = rasterlab(&args);
        assert!(!out.status.success(), "{args:?}");
        assert!(out.stdout.is_empty());
        assert!(String::from_utf8(out.stderr)
            .unwrap()
            .starts_with("rasterlab: error:"));
    }
}

#[test]
fn render_draws_a_bundled_mesh() {
    let tmp = tempfile::tempdir().unwrap();
    let out_png = tmp.path().join("bunny.png");
    let bunny = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/bunny.ply");
    let out = rasterlab(&[
        "render",
        bunny,
        "--backend",
        "incremental",
        "--size",
        "80x60",
        "--frames",
        "2",
        "--wireframe",
        "dda",
        "--out",
        out_png.to_str().unwrap(),
    ]);
    let text = success_stdout(out);
    assert!(text.contains("3674 triangles"), "{text}");
    assert!(text.contains("time per frame (median of 2)"), "{text}");
    let image = image::open(&out_png).unwrap();
    assert_eq!((image.width(), image.height()), (80, 60));
}

/// `render` culls back faces unless told otherwise, as its help says; a
/// bare `RenderSettings::default()` culls none, and the command must not
/// inherit that.
#[test]
fn render_culls_back_faces_by_default() {
    let dragon = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/dragon_vrip_res4.ply.gz"
    );
    let tmp = tempfile::tempdir().unwrap();
    let out_png = tmp.path().join("cull.png");
    let culled = |extra: &[&str]| -> String {
        let mut args = vec!["render", dragon, "--size", "320x240", "--azimuth", "30"];
        args.extend_from_slice(extra);
        args.extend_from_slice(&["--out", out_png.to_str().unwrap()]);
        let text = success_stdout(rasterlab(&args));
        let line = text.lines().find(|l| l.starts_with("pipeline:")).unwrap();
        line.split(", ")
            .find(|p| p.ends_with("culled"))
            .unwrap()
            .to_string()
    };
    assert_eq!(culled(&[]), "5962 culled");
    assert_eq!(culled(&["--cull", "back"]), "5962 culled");
    assert_eq!(culled(&["--cull", "none"]), "0 culled");
}

/// Malformed meshes: the error names the file and the line, exit code 2,
/// no panic.
#[test]
fn malformed_meshes_name_file_and_line() {
    let tmp = tempfile::tempdir().unwrap();
    let header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    let cases = [
        ("short.ply", format!("{header}0 0 0\n1 0 0\n"), ":12"),
        (
            "word.ply",
            format!("{header}0 0 0\n1 one 0\n0 1 0\n3 0 1 2\n"),
            ":11:",
        ),
        (
            "index.ply",
            format!("{header}0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n"),
            ":13:",
        ),
        (
            "header.ply",
            "ply\nformat ascii 1.0\nelement vertex x\n".to_string(),
            ":3:",
        ),
        (
            "index.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 4\n".to_string(),
            ":5:",
        ),
        ("number.obj", "v 0 0 0\nv 1 0 zero\n".to_string(), ":2:"),
    ];
    for (name, text, line) in cases {
        let path = temp_file(tmp.path(), name, &text);
        let out = rasterlab(&["render", path.to_str().unwrap(), "--out", "/dev/null"]);
        let stderr = String::from_utf8(out.stderr).unwrap();
        assert_eq!(out.status.code(), Some(2), "{name}: {stderr}");
        assert!(
            stderr.contains(&format!("{name}{line}")),
            "{name}: {stderr}"
        );
        assert!(!stderr.contains("panicked"), "{name}: {stderr}");
    }
    let out = rasterlab(&["render", "/nonexistent/mesh.ply", "--out", "/dev/null"]);
    assert_eq!(out.status.code(), Some(2));
    let out = rasterlab(&[
        "render",
        concat!(env!("CARGO_MANIFEST_DIR"), "/assets/bunny.ply"),
        "--shading",
        "glossy",
        "--out",
        "/dev/null",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("unknown shading `glossy`"));
}

#[test]
fn bench_prints_a_table_and_writes_json_and_charts() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("bench");
    let out = rasterlab(&[
        "--threads",
        "1",
        "bench",
        "--size",
        "64x48",
        "--samples",
        "1",
        "--json",
        "--out",
        dir.to_str().unwrap(),
    ]);
    let printed: serde_json::Value = serde_json::from_str(&success_stdout(out)).unwrap();
    let rows = printed["results"].as_array().unwrap();
    assert!(rows.iter().any(|r| r["backend"] == "fast-bresenham"));
    assert!(rows.iter().any(|r| r["workload"] == "dragon_vrip_res4"));
    let written: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("bench.json")).unwrap()).unwrap();
    assert_eq!(written["results"].as_array().unwrap().len(), rows.len());
    assert!(image::open(dir.join("bench.png")).is_ok());
}

#[test]
fn zero_threads_is_an_error() {
    let out = rasterlab(&["--threads", "0", "backends"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--threads"));
}

#[test]
fn explain_scanline_and_depth_buffer_print_their_tables_and_pictures() {
    let tmp = tempfile::tempdir().unwrap();
    let out = rasterlab(&[
        "explain",
        "--backend",
        "scanline",
        "1",
        "1",
        "9",
        "2",
        "3",
        "7",
    ]);
    let text = success_stdout(out);
    assert!(text.ends_with("6 rows, 24 fragments; a left edge (E rising to the right) gives the first pixel, a right edge the last\n"), "{text}");

    let svg = temp_file(tmp.path(), "depth.svg", "");
    let out = rasterlab(&[
        "explain",
        "--backend",
        "depth-buffer",
        "--picture",
        svg.to_str().unwrap(),
    ]);
    let text = success_stdout(out);
    assert!(
        text.contains("triangle 2 (z = 0.8, 0.8, 0.8): 12 fragments, 8 kept"),
        "{text}"
    );
    assert_eq!(
        std::fs::read_to_string(&svg)
            .unwrap()
            .matches(">0.8</text>")
            .count(),
        8
    );

    // Back-ends without a text trace still draw their picture.
    let png = temp_file(tmp.path(), "tiled.png", "");
    let out = rasterlab(&[
        "explain",
        "--backend",
        "tiled",
        "--size",
        "20x20",
        "--picture",
        png.to_str().unwrap(),
        "1",
        "1",
        "18",
        "3",
        "4",
        "17",
    ]);
    success_stdout(out);
    // At least 32 pixels a cell, with the axes and legend around.
    let picture = image::open(&png).unwrap();
    assert!(picture.width() >= 20 * 32 && picture.height() >= 20 * 32);

    for (args, message) in [
        (
            vec![
                "explain",
                "--backend",
                "nonesuch",
                "1",
                "1",
                "5",
                "1",
                "1",
                "5",
            ],
            // Every back-end has a trace now (tiled's lists its blocks).
            "unknown rasterizer back-end `nonesuch`",
        ),
        (
            vec![
                "explain",
                "--backend",
                "depth-buffer",
                "0",
                "0",
                "4",
                "0",
                "0",
                "4",
            ],
            "7 numbers each",
        ),
        (
            vec![
                "explain",
                "--backend",
                "depth-buffer",
                "0",
                "0",
                "4",
                "0",
                "0",
                "4",
                "2",
            ],
            "depth 2 is outside [0, 1]",
        ),
        (
            vec![
                "explain",
                "--backend",
                "bbox",
                "--picture",
                "/tmp/x.gif",
                "0",
                "0",
                "4",
                "0",
                "0",
                "4",
            ],
            "written as .svg or .png",
        ),
    ] {
        let out = rasterlab(&args);
        // Bad arguments exit 2; an output path of the wrong kind exits 3.
        let code = if message.contains(".svg") { 3 } else { 2 };
        assert_eq!(out.status.code(), Some(code), "{args:?}");
        let err = String::from_utf8(out.stderr).unwrap();
        assert!(err.contains(message), "{err}");
    }
}

#[test]
fn compare_writes_a_self_contained_report_for_polygons_lines_and_meshes() {
    let tmp = tempfile::tempdir().unwrap();
    let polygon = temp_file(
        tmp.path(),
        "polygon.txt",
        "# a pentagon with a hole\npolygon 2 2 30 3 28 20 16 28 3 22\nhole 10 8 20 9 14 16\n",
    );
    let lines = temp_file(tmp.path(), "lines.txt", "0 0 30 11\n5 30 25 2\n");
    let mesh = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/bunny.ply");
    let (triangle_rows, line_rows) = (
        rasterlab::raster::triangle_backends().len(),
        rasterlab::raster::line_backends().len(),
    );
    for (i, (input, size, rows)) in [
        (polygon.to_str().unwrap(), "32x32", triangle_rows),
        (lines.to_str().unwrap(), "32x32", line_rows),
        (mesh, "96x72", triangle_rows),
    ]
    .into_iter()
    .enumerate()
    {
        let out_dir = temp_file(tmp.path(), "unused", "").with_file_name(format!("report-{i}"));
        let out = rasterlab(&[
            "compare",
            input,
            "--size",
            size,
            "--samples",
            "1",
            "--out",
            out_dir.to_str().unwrap(),
        ]);
        let table = success_stdout(out);
        // The reference line, the header, a row per back-end, the report
        // line; for 2D triangles the anti-aliasing table's title, header
        // and a row per method.
        let two_d = input == polygon.to_str().unwrap();
        let antialias = if two_d {
            2 + rasterlab::measure::METHODS.len()
        } else {
            0
        };
        // For a polygon file, the scan-convert or triangulate table: its
        // title, header, a row per polygon back-end and one per triangle
        // back-end.
        let scan = if two_d {
            2 + rasterlab::raster::polygon_backends().len() + rows
        } else {
            0
        };
        assert_eq!(
            table.lines().count(),
            rows + 3 + antialias + scan,
            "{table}"
        );
        assert!(table.starts_with("reference: "), "{table}");
        let html = std::fs::read_to_string(out_dir.join("index.html")).unwrap();
        assert!(html.contains("<table id=\"work\">"));
        assert_eq!(html.contains("<table id=\"antialias\">"), two_d, "{input}");
        assert!(
            !html.contains("src=\"http"),
            "the report loads nothing from outside"
        );
        if input != lines.to_str().unwrap() {
            // Every triangle back-end is identical to the reference.
            assert_eq!(html.matches("0 (identical)").count(), rows, "{input}");
        }
    }
    let bad = temp_file(tmp.path(), "bad.txt", "polygon 0 0 1 0\n");
    let out = rasterlab(&["compare", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8(out.stderr)
        .unwrap()
        .contains("bad.txt:1: a polygon ring takes at least 3 points"));
    let out = rasterlab(&["compare", polygon.to_str().unwrap(), "--size", "0x4"]);
    assert_eq!(out.status.code(), Some(2));
}

/// Two triangles covering a full-HD target are drawn band by band (they
/// are few), on one thread or two; each still counts as one primitive.
#[test]
fn render_counts_each_triangle_once_whatever_the_bands() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let soup = dir.join("two.txt");
    std::fs::write(&soup, "0 0 1920 0 0 1080\n1920 0 1920 1080 0 1080\n").unwrap();
    let out = dir.join("two.png");
    for threads in ["1", "2"] {
        let text = success_stdout(rasterlab(&[
            "--threads",
            threads,
            "render",
            soup.to_str().unwrap(),
            "--size",
            "1920x1080",
            "--out",
            out.to_str().unwrap(),
        ]));
        assert!(
            text.contains("2 primitives, 0 samples tested, 2073600 fragments"),
            "{threads} threads: {text}"
        );
    }
}
