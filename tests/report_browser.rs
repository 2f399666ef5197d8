//! The comparison report, loaded in a real browser (headless Chromium):
//! every embedded image decodes, the tables and grid pictures are in the
//! page, and a screenshot shows them.
//!
//! Chromium is found as `$RASTERLAB_CHROMIUM`, `chromium` or
//! `chromium-browser`. Without one the test says so and passes, unless
//! `RASTERLAB_REQUIRE_BROWSER` is set (as `.ci/run` does, after installing
//! Debian's `chromium`), in which case a missing browser is a failure.

mod common;

use common::{chromium, HEADLESS};
use rasterlab::geometry::Scene2D;
use rasterlab::teaching::{CompareInput, Report, Role};
use std::path::Path;
use std::process::Command;

/// Runs headless Chromium on `page` with extra arguments; returns stdout.
fn run_chromium(browser: &Path, profile: &Path, page: &Path, extra: &[&str]) -> String {
    let output = Command::new(browser)
        .args(HEADLESS)
        .args(["--hide-scrollbars", "--virtual-time-budget=10000"])
        .arg(format!("--user-data-dir={}", profile.display()))
        .args(extra)
        .arg(format!("file://{}", page.display()))
        .output()
        .expect("chromium starts");
    assert!(
        output.status.success(),
        "chromium failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8_lossy(&output.stdout).into_owned()
}

/// The value of `data-NAME="..."` on the page's body.
fn body_data(dom: &str, name: &str) -> usize {
    let key = format!("data-{name}=\"");
    let start = dom
        .find(&key)
        .unwrap_or_else(|| panic!("the page did not set {key}: its script did not run"))
        + key.len();
    let end = start + dom[start..].find('"').expect("closing quote");
    dom[start..end].parse().expect("a count")
}

#[test]
fn the_report_renders_its_images_and_tables_in_chromium() {
    let Some(browser) = chromium() else {
        common::part_missing(
            "the report's browser test",
            "chromium (Debian's package `chromium`)",
            "RASTERLAB_REQUIRE_BROWSER",
        );
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let report = Report::compare(&CompareInput::Triangles(Scene2D::pinwheel()), 12, 12, 1).unwrap();
    let page = report.write(&dir.join("report")).unwrap();
    let profile = dir.join("profile");

    let dom = run_chromium(&browser, &profile, &page, &["--dump-dom"]);
    let images = body_data(&dom, "images");
    // An image per back-end, a difference image per back-end but the
    // reference, a heat map per fill rule for the input and for the
    // pinwheel, and the anti-aliasing section's five coverage pictures.
    let backends = rasterlab::raster::triangle_backends().len();
    let rules = rasterlab::raster::FillRule::ALL.len();
    assert_eq!(images, backends + (backends - 1) + 2 * rules + 5);
    assert_eq!(
        body_data(&dom, "images-loaded"),
        images,
        "an image failed to decode"
    );
    // Work table, the input's fill rules, the pinwheel's, anti-aliasing.
    assert_eq!(body_data(&dom, "tables"), 4);
    // One grid picture per back-end, and the anti-aliasing chart.
    assert_eq!(body_data(&dom, "svgs"), backends + 1);
    // Every section with coloured pictures shows the palette's legend:
    // differences, the input's fill rules, the pinwheel's,
    // anti-aliasing, the grids; and the chart has its own.
    assert_eq!(body_data(&dom, "legends"), 6);
    for role in [
        Role::Differs,
        Role::Gap,
        Role::DoubleDraw,
        Role::Drawn,
        Role::TestedOutside,
    ] {
        let swatch = format!(
            "data-role=\"{}\" data-colour=\"{}\" data-mark=\"{}\"><svg class=\"swatch\"",
            role.key(),
            role.hex(),
            role.mark().key()
        );
        assert!(dom.contains(&swatch), "no legend entry for {role:?}");
        assert!(dom.contains(role.label()), "{role:?}");
    }

    let shot = dir.join("shot.png");
    run_chromium(
        &browser,
        &profile,
        &page,
        &[
            &format!("--screenshot={}", shot.display()),
            "--window-size=1200,1400",
        ],
    );
    let img = image::open(&shot)
        .expect("a screenshot was written")
        .to_rgb8();
    assert_eq!(img.dimensions(), (1200, 1400));
    let mut colours: Vec<[u8; 3]> = img.pixels().map(|p| p.0).collect();
    colours.sort_unstable();
    colours.dedup();
    assert!(
        colours.len() > 50,
        "the screenshot has only {} colours: the page did not render",
        colours.len()
    );
    // The pinwheel's palette colour (first triangle) is on screen: the
    // images were painted, not just decoded.
    let blue = rasterlab::raster::to_rgba8(rasterlab::geometry::scene_colour(0));
    assert!(img.pixels().any(|p| p.0 == [blue[0], blue[1], blue[2]]));
}
