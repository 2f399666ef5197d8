//! `check --image`: whole renders graded within a tolerance. rasterlab's
//! own `render` driven as the program under test passes every default
//! scene and a mesh; the same render without the depth test fails the
//! depth-buffer example with its diff picture written; a program that
//! crashes, writes nothing, writes what is not a PNG or a PNG of another
//! size gets a verdict saying so; a malformed scene file names its line;
//! the thresholds come from the configuration; the graders get a test
//! per scene.

mod common;

use common::rasterlab;
use std::path::Path;

/// The command line that renders a built-in scene with rasterlab itself,
/// `extra` added to the test's settings.
fn own_render(extra: &str) -> String {
    format!(
        "{} render --scene {{scene}} --size {{size}} {{settings}} {extra} --out {{out}}",
        env!("CARGO_BIN_EXE_rasterlab")
    )
}

/// `rasterlab check --image --exec COMMAND --out OUT` and `more`.
fn check_image(command: &str, out: &Path, more: &[&str]) -> std::process::Output {
    let out = out.to_str().unwrap();
    let mut args = vec!["check", "--image", "--exec", command, "--out", out];
    args.extend_from_slice(more);
    rasterlab(&args)
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// A configuration file in `dir`.
fn config(dir: &Path, json: &str) -> String {
    let path = dir.join("config.json");
    std::fs::write(&path, json).unwrap();
    path.to_str().unwrap().to_string()
}

#[test]
fn rasterlab_s_own_render_passes_every_default_scene() {
    let dir = tempfile::tempdir().unwrap();
    let output = check_image(&own_render(""), dir.path(), &[]);
    let stdout = text(&output.stdout);
    assert_eq!(
        output.status.code(),
        Some(0),
        "{stdout}{}",
        text(&output.stderr)
    );
    assert!(
        stdout.contains("thresholds (the defaults): a pixel past 32/255"),
        "{stdout}"
    );
    for scene in rasterlab::check::DEFAULT_IMAGE_SCENES {
        assert!(stdout.contains(&format!("PASS: {scene} ")), "{stdout}");
    }
    assert!(stdout.contains("PSNR infinite (equal)"), "{stdout}");
    assert!(stdout.contains("5 of 5 image test(s) pass"), "{stdout}");
    assert!(dir.path().join("image-depth-example-diff.svg").exists());
}

#[test]
fn a_render_without_the_depth_test_fails_with_its_diff_picture() {
    let dir = tempfile::tempdir().unwrap();
    let output = check_image(&own_render("--depth-test always"), dir.path(), &[]);
    let stdout = text(&output.stdout);
    let stderr = text(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stdout}{stderr}");
    assert!(stdout.contains("FAIL: depth-example "), "{stdout}");
    // The scenes without overlapping triangles still pass.
    assert!(stdout.contains("PASS: split-square "), "{stdout}");
    assert!(stdout.contains("beyond the bounds: mean "), "{stdout}");
    assert!(
        stderr.contains("the image check failed: depth-example"),
        "{stderr}"
    );
    let png = dir.path().join("image-depth-example-diff.png");
    let diff = image::open(&png).unwrap().to_rgba8();
    assert_eq!(diff.dimensions(), (14, 9));
    let vermillion = rasterlab::teaching::Role::Differs.rgb();
    let differing = diff.pixels().filter(|p| p.0[..3] == vermillion).count();
    assert!(differing > 0);
    let svg = std::fs::read_to_string(dir.path().join("image-depth-example-diff.svg")).unwrap();
    assert!(svg.contains("differs from the reference") && svg.contains("correct"));
    for what in ["expected", "actual"] {
        let path = dir.path().join(format!("image-depth-example-{what}.png"));
        assert_eq!(image::open(path).unwrap().width(), 14);
    }
}

#[test]
fn thresholds_come_from_the_configuration_per_test() {
    let dir = tempfile::tempdir().unwrap();
    let file = config(
        dir.path(),
        r#"{ "images": { "threshold": 8, "tests": [
            { "scene": "depth-example", "max_mean": 255, "max_share": 1 },
            { "name": "depth-twice", "scene": "depth-example", "size": "28x18" }
        ] } }"#,
    );
    let output = check_image(
        &own_render("--depth-test always"),
        dir.path(),
        &["--config", &file],
    );
    let stdout = text(&output.stdout);
    assert_eq!(output.status.code(), Some(1), "{stdout}");
    assert!(
        stdout.contains("thresholds: a pixel past 8/255"),
        "{stdout}"
    );
    assert!(
        stdout.contains("PASS: depth-example (depth-example at 14x9)"),
        "{stdout}"
    );
    assert!(
        stdout.contains("FAIL: depth-twice (depth-example at 28x18)"),
        "{stdout}"
    );
    assert!(stdout.contains("this test's thresholds: a pixel past 8/255 in a channel; mean <= 255"));

    let bad = config(dir.path(), r#"{ "images": { "max_share": 2 } }"#);
    let output = check_image(&own_render(""), dir.path(), &["--config", &bad]);
    assert_eq!(output.status.code(), Some(2));
    assert!(text(&output.stderr).contains("max_share must be from 0 to 1"));
}

#[test]
fn a_mesh_is_graded_too() {
    let dir = tempfile::tempdir().unwrap();
    let bunny = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/bunny.ply");
    let file = config(
        dir.path(),
        &format!(
            r#"{{ "images": {{ "tests": [ {{ "scene": "{bunny}", "name": "bunny", "size": "96x72", "settings": "--shading diffuse" }} ] }} }}"#
        ),
    );
    let command = format!(
        "{} render {{scene}} --size {{size}} {{settings}} --out {{out}}",
        env!("CARGO_BIN_EXE_rasterlab")
    );
    let output = check_image(&command, dir.path(), &["--config", &file]);
    let stdout = text(&output.stdout);
    assert_eq!(
        output.status.code(),
        Some(0),
        "{stdout}{}",
        text(&output.stderr)
    );
    assert!(stdout.contains("PASS: bunny ("), "{stdout}");
    // Seen from another side, the bunny fails.
    let other = format!("{command} --azimuth 90");
    let output = check_image(&other, dir.path(), &["--config", &file]);
    assert_eq!(output.status.code(), Some(1), "{}", text(&output.stdout));
}

#[test]
fn a_program_that_gives_no_image_gets_a_verdict_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let exe = env!("CARGO_BIN_EXE_rasterlab");
    let cases = [
        (
            "echo oops >&2; exit 3".to_string(),
            "failed (exit status: 3): oops",
        ),
        ("true {out}".to_string(), "wrote no image"),
        (
            "echo hello > {out}".to_string(),
            "wrote a file that is not a PNG (6 bytes)",
        ),
        (
            format!("{exe} render --scene {{scene}} --size 3x3 --out {{out}}"),
            "wrote a 3x3 PNG where 14x9 was asked",
        ),
    ];
    let file = config(
        dir.path(),
        r#"{ "images": { "tests": [ { "scene": "depth-example" } ] } }"#,
    );
    for (command, says) in cases {
        let output = check_image(&command, dir.path(), &["--config", &file]);
        let stderr = text(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{command}: {stderr}");
        assert!(stderr.contains("broken, not wrong"), "{command}: {stderr}");
        assert!(stderr.contains(says), "{command}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
    // Wrong on one test only: that test fails, the program is not broken.
    let wrong_once = format!(
        "if [ {{scene}} = fan ]; then exit 1; fi; {}",
        own_render("")
    );
    let output = check_image(&wrong_once, dir.path(), &[]);
    let stdout = text(&output.stdout);
    assert_eq!(output.status.code(), Some(1), "{stdout}");
    assert!(
        stdout.contains("NO IMAGE: fan (fan at 32x32)\n  the program failed"),
        "{stdout}"
    );
    assert!(stdout.contains("4 of 5 image test(s) pass"), "{stdout}");
}

#[test]
fn a_malformed_scene_file_names_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("scene.txt");
    std::fs::write(&scene, "0 0 8 0 0 8\n0 0 8 zero 8 8\n").unwrap();
    let file = config(
        dir.path(),
        &format!(
            r#"{{ "images": {{ "tests": [ {{ "scene": "{}", "size": "8x8" }} ] }} }}"#,
            scene.display()
        ),
    );
    let output = check_image(&own_render(""), dir.path(), &["--config", &file]);
    let stderr = text(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains(&format!("{}:2", scene.display())),
        "{stderr}"
    );
    // An unknown setting is refused by name.
    let file = config(
        dir.path(),
        r#"{ "images": { "tests": [ { "scene": "fan", "settings": "--speed 3" } ] } }"#,
    );
    let output = check_image(&own_render(""), dir.path(), &["--config", &file]);
    assert_eq!(output.status.code(), Some(2));
    assert!(text(&output.stderr).contains("--speed"));
}

#[test]
fn graders_get_a_test_per_scene() {
    let dir = tempfile::tempdir().unwrap();
    let file = config(
        dir.path(),
        r#"{ "images": { "tests": [
            { "scene": "depth-example", "weight": 5 },
            { "scene": "pinwheel", "weight": 2 }
        ] } }"#,
    );
    let command = own_render("--depth-test always");
    let output = check_image(
        &command,
        dir.path(),
        &["--config", &file, "--format", "gradescope"],
    );
    assert_eq!(output.status.code(), Some(1));
    let results: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(results["score"], 2.0);
    let tests = results["tests"].as_array().unwrap();
    assert_eq!(tests.len(), 2);
    assert_eq!(tests[0]["name"], "image depth-example");
    assert_eq!(tests[0]["max_score"], 5.0);
    assert_eq!(tests[0]["status"], "failed");
    assert!(tests[0]["output"].as_str().unwrap().contains("rerun: "));
    assert_eq!(tests[1]["status"], "passed");

    let output = check_image(
        &command,
        dir.path(),
        &["--config", &file, "--format", "junit"],
    );
    let xml = text(&output.stdout);
    let doc = roxmltree::Document::parse(&xml).unwrap();
    let failures: Vec<_> = doc
        .descendants()
        .filter(|n| n.has_tag_name("failure"))
        .collect();
    assert_eq!(failures.len(), 1);
    assert_eq!(failures[0].attribute("type"), Some("image-differs"));
    let json = check_image(&command, dir.path(), &["--format", "json"]);
    assert_eq!(json.status.code(), Some(2));
}
