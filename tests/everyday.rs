//! What a student meets in everyday use of the command line: line sets
//! rendered with a line back-end, small scenes enlarged pixel by pixel,
//! options refused where they do not apply, `compare` saying which
//! reference it uses.

mod common;
use common::rasterlab;

/// The path of `name` in `dir` (a test's own temporary folder, removed
/// when the test ends, whether it passes or panics), as text.
fn temp(dir: &std::path::Path, name: &str) -> String {
    dir.join(name).to_str().unwrap().to_string()
}

const LINES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/lines.txt");
const POLYGON: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/polygon.txt");
const BUNNY: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/bunny.ply");

#[test]
fn a_line_set_renders_the_pixels_fragments_lists() {
    let tmp = tempfile::tempdir().unwrap();
    let png = temp(tmp.path(), "lines.png");
    let out = rasterlab(&["render", LINES, "--size", "32x32", "--out", &png]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        String::from_utf8_lossy(&out.stdout).starts_with("bresenham: "),
        "the summary is on stdout"
    );
    let image = image::open(&png).unwrap().to_rgba8();
    let mut lit: Vec<(u32, u32)> = image
        .enumerate_pixels()
        .filter(|(_, _, p)| p.0[..3] != [0, 0, 0])
        .map(|(x, y, _)| (x, y))
        .collect();
    let listed = rasterlab(&[
        "fragments",
        "--backend",
        "bresenham",
        "--size",
        "32x32",
        LINES,
    ]);
    let mut want: Vec<(u32, u32)> = String::from_utf8(listed.stdout)
        .unwrap()
        .lines()
        .map(|l| {
            let v: Vec<u32> = l
                .split_whitespace()
                .take(2)
                .map(|n| n.parse().unwrap())
                .collect();
            (v[0], v[1])
        })
        .collect();
    lit.sort();
    want.sort();
    want.dedup();
    assert_eq!(lit, want);
    // A triangle back-end for lines, and a line back-end for triangles, are refused.
    let out = rasterlab(&[
        "render",
        LINES,
        "--size",
        "32x32",
        "--backend",
        "scanline",
        "--out",
        &png,
    ]);
    assert_eq!(out.status.code(), Some(2));
    let out = rasterlab(&[
        "render",
        POLYGON,
        "--size",
        "32x32",
        "--backend",
        "bresenham",
        "--out",
        &png,
    ]);
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn scale_enlarges_a_scene_pixel_by_pixel() {
    let tmp = tempfile::tempdir().unwrap();
    let png = temp(tmp.path(), "pinwheel.png");
    let out = rasterlab(&[
        "render", "--scene", "pinwheel", "--scale", "32", "--out", &png,
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let big = image::open(&png).unwrap().to_rgba8();
    let small_png = temp(tmp.path(), "pinwheel-1.png");
    assert!(
        rasterlab(&["render", "--scene", "pinwheel", "--out", &small_png])
            .status
            .success()
    );
    let small = image::open(&small_png).unwrap().to_rgba8();
    assert_eq!(big.dimensions(), (small.width() * 32, small.height() * 32));
    for (x, y, p) in small.enumerate_pixels() {
        // The inside of each cell is the pixel; its first row and column the grey border.
        assert_eq!(big.get_pixel(x * 32 + 16, y * 32 + 16), p);
        assert_eq!(big.get_pixel(x * 32, y * 32 + 16).0, [96, 96, 96, 255]);
    }
    let out = rasterlab(&[
        "render", "--scene", "pinwheel", "--scale", "1000", "--out", &png,
    ]);
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn options_that_do_not_apply_are_refused_not_ignored() {
    let tmp = tempfile::tempdir().unwrap();
    let png = temp(tmp.path(), "x.png");
    for args in [
        vec![
            "render", POLYGON, "--size", "32x32", "--zoom", "2", "--out", &png,
        ],
        vec![
            "render",
            "--scene",
            "fan",
            "--shading",
            "flat",
            "--cull",
            "none",
            "--out",
            &png,
        ],
        vec![
            "render",
            LINES,
            "--size",
            "32x32",
            "--azimuth",
            "30",
            "--out",
            &png,
        ],
    ] {
        let out = rasterlab(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(
            String::from_utf8_lossy(&out.stderr).contains("to meshes only"),
            "{args:?}"
        );
    }
    let out = rasterlab(&["render", BUNNY, "--scale", "4", "--out", &png]);
    assert_eq!(out.status.code(), Some(2));
    let out = rasterlab(&[
        "check",
        "--backend",
        "bresenham",
        "--rule",
        "watertight",
        "--cases",
        "1",
    ]);
    assert_eq!(out.status.code(), Some(2));
    // --frames times 2D inputs too.
    let out = rasterlab(&[
        "render", POLYGON, "--size", "32x32", "--frames", "5", "--out", &png,
    ]);
    assert!(String::from_utf8_lossy(&out.stdout).contains("time per frame (median of 5)"));
}

#[test]
fn compare_says_which_reference_it_uses_and_why() {
    let tmp = tempfile::tempdir().unwrap();
    let dragon = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/dragon_vrip_res4.ply.gz"
    );
    let out = rasterlab(&[
        "compare",
        dragon,
        "--size",
        "160x120",
        "--samples",
        "1",
        "--out",
        &temp(tmp.path(), "cd"),
    ]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.starts_with("reference: bbox: naive was left out"),
        "{text}"
    );
    let dir = temp(tmp.path(), "cl");
    let out = rasterlab(&[
        "compare",
        LINES,
        "--size",
        "32x32",
        "--samples",
        "1",
        "--out",
        &dir,
    ]);
    assert!(String::from_utf8(out.stdout)
        .unwrap()
        .starts_with("reference: direct"));
    let html = std::fs::read_to_string(format!("{dir}/index.html")).unwrap();
    assert!(
        !html.to_lowercase().contains("fill rule") && !html.contains("top-left"),
        "a line report says nothing of fill rules"
    );
    assert!(
        html.contains("<td>—</td>"),
        "not-applicable cells are dashes"
    );
}
