//! `rasterlab check --kind polygons`: rasterlab's own polygon back-ends
//! pass under both fill rules; a Python filler passes the rule it fills
//! by and fails the other with the other fill rule named, and its
//! inclusive-edges and holes-ignored mistakes are named too; every report
//! validates against the schema; a bad polygon case file is refused with
//! its file and line; the polygon adapters of `examples/adapters/` are
//! judged, not broken, and the rings their headers were measured on get
//! the verdicts the headers state.

mod common;
use common::rasterlab;

use rasterlab::check::{run, CheckRequest, Kind, SubjectSpec};
use rasterlab::raster::polygon::WindingRule;
use std::process::Command;

fn schema() -> jsonschema::Validator {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/docs/check-report.schema.json"
    ))
    .unwrap();
    jsonschema::validator_for(&serde_json::from_str(&text).unwrap()).unwrap()
}

fn valid(schema: &jsonschema::Validator, json: &serde_json::Value) {
    let errors: Vec<String> = schema
        .iter_errors(json)
        .map(|e| format!("{e} at {}", e.instance_path()))
        .collect();
    assert!(errors.is_empty(), "{errors:#?}\n{json:#}");
}

fn polygons(subject: SubjectSpec, fill: WindingRule, cases: u32) -> serde_json::Value {
    let mut request = CheckRequest::new(subject);
    request.kind = Some(Kind::Polygons);
    request.fill = Some(fill);
    request.cases = cases;
    let json = serde_json::to_value(run(&request).unwrap()).unwrap();
    valid(&schema(), &json);
    json
}

#[test]
fn the_polygon_back_ends_pass_under_both_fill_rules() {
    for backend in ["edge-table", "crossings"] {
        for fill in WindingRule::ALL {
            let json = polygons(SubjectSpec::Backend(backend.into()), fill, 800);
            assert_eq!(json["verdict"], "pass", "{backend} {fill}: {json:#}");
            assert_eq!(json["property"], format!("polygon-{fill}"));
            assert_eq!(json["families"].as_array().unwrap().len(), 8);
        }
    }
    // Named without --kind, a polygon back-end is checked on polygons.
    let out = rasterlab(&["check", "--backend", "edge-table", "--cases", "40"]);
    assert!(out.status.success(), "{out:?}");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("PASS: 40 cases, polygons, the even-odd fill rule"),
        "{text}"
    );
}

/// The student's filler, started once, with its arguments.
fn student(arguments: &str) -> SubjectSpec {
    SubjectSpec::Persistent(format!(
        "python3 examples/student/polygon_fill.py {arguments}"
    ))
}

fn causes(json: &serde_json::Value) -> Vec<String> {
    json["counterexample"]["cause"]["causes"]
        .as_array()
        .map(|a| a.iter().map(|c| c.as_str().unwrap().to_string()).collect())
        .unwrap_or_default()
}

#[test]
fn a_filler_passes_its_rule_and_fails_the_other_with_that_cause_named() {
    for fill in WindingRule::ALL {
        let json = polygons(student("{rule}"), fill, 150);
        assert_eq!(json["verdict"], "pass", "{fill}: {json:#}");
    }
    let json = polygons(student("nonzero"), WindingRule::EvenOdd, 150);
    assert_eq!(json["verdict"], "fail", "{json:#}");
    assert_eq!(causes(&json), ["fill:nonzero"], "{json:#}");
    let cause = &json["counterexample"]["cause"];
    assert_eq!(cause["confirmed_on"], cause["failing_cases"], "{json:#}");
    assert!(json["counterexample"]["input"]
        .as_str()
        .unwrap()
        .contains("\npolygon "));
    let json = polygons(student("even-odd"), WindingRule::Nonzero, 150);
    assert_eq!(causes(&json), ["fill:even-odd"], "{json:#}");
}

#[test]
fn inclusive_edges_and_ignored_holes_are_named() {
    let json = polygons(student("{rule} inclusive"), WindingRule::EvenOdd, 150);
    assert_eq!(causes(&json), ["boundary:inclusive"], "{json:#}");
    let json = polygons(student("{rule} no-holes"), WindingRule::Nonzero, 150);
    assert_eq!(causes(&json), ["hole-ignored"], "{json:#}");
}

#[test]
fn a_bad_polygon_case_is_refused_with_its_file_and_line() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("out");
    for (text, message) in [
        (
            "# size 4x4\npolygon 0 0 4 0 4 x\n",
            "line 2: `x` is not a number",
        ),
        (
            "# size 4x4\nhole 0 0 4 0 4 4\n",
            "line 2: `hole` before any `polygon`",
        ),
        (
            "# size 4x4\npolygon 0 0 4 0 4 4\nhole 1 1 2 1\n",
            "line 3: a hole ring takes at least 3 points as x y pairs, found 4 numbers",
        ),
        ("# size 4x4\npolygon 0 0 4 0 4 1e9\n", "line 2: "),
        ("# size 4x4\n0 0 4 0 0 4\n", "the case must hold polygons"),
    ] {
        let path = dir.path().join("case.txt");
        std::fs::write(&path, text).unwrap();
        let out = rasterlab(&[
            "check",
            "--kind",
            "polygons",
            "--backend",
            "edge-table",
            "--case",
            path.to_str().unwrap(),
            "--out",
            out_dir.to_str().unwrap(),
        ]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{text}: {err}");
        assert!(err.contains(path.to_str().unwrap()), "{text}: {err}");
        assert!(err.contains(message), "{text}: {err}");
    }
    // --fill is for polygons, --rule for triangles.
    let out = rasterlab(&["check", "--backend", "scanline", "--fill", "nonzero"]);
    assert_eq!(out.status.code(), Some(2));
    let out = rasterlab(&["check", "--backend", "edge-table", "--rule", "top-left"]);
    assert_eq!(out.status.code(), Some(2));
}

/// The polygon adapters of `examples/adapters/`, the module each needs.
const ADAPTERS: [(&str, &str); 7] = [
    ("pillow_polygon", "PIL"),
    ("opencv_polygon", "cv2"),
    ("skimage_polygon", "skimage"),
    ("matplotlib_polygon", "matplotlib"),
    ("cairo_polygon", "cairo"),
    ("gdal_polygon", "rasterio"),
    ("skia_polygon", "skia"),
];

#[test]
fn the_polygon_adapters_are_judged_not_broken() {
    let require = std::env::var("RASTERLAB_REQUIRE_PYTHON").is_ok_and(|v| v == "1");
    for (adapter, module) in ADAPTERS {
        let present = Command::new("python3")
            .args(["-c", &format!("import numpy, {module}")])
            .output()
            .is_ok_and(|o| o.status.success());
        if !present {
            // pycairo needs cairo's headers to build: not required.
            assert!(
                !require || module == "cairo",
                "RASTERLAB_REQUIRE_PYTHON=1 but python3 cannot import {module}"
            );
            eprintln!("SKIPPED: the {adapter} adapter (python3 cannot import {module})");
            continue;
        }
        for fill in WindingRule::ALL {
            let mut request = CheckRequest::new(SubjectSpec::Persistent(format!(
                "python3 examples/adapters/{adapter}.py {{rule}}"
            )));
            request.kind = Some(Kind::Polygons);
            request.fill = Some(fill);
            request.cases = 16;
            request.keep_going = true;
            request.shrink_runs = 3;
            let json = serde_json::to_value(run(&request).unwrap()).unwrap();
            valid(&schema(), &json);
            assert_ne!(json["verdict"], "broken", "{adapter}: {json:#}");
            eprintln!("{adapter} {fill}: {}/16", json["passed"]);
        }
    }
}

#[test]
fn a_configuration_names_the_fill_rule_and_weighs_polygon_families() {
    use rasterlab::check::CheckConfig;
    let config = CheckConfig::from_json(
        r#"{ "kind": "polygons", "fill": "nonzero", "weights": { "crossing": 5, "ties": 0 } }"#,
    )
    .unwrap();
    let mut request = CheckRequest::new(SubjectSpec::Backend("edge-table".into()));
    config.apply(&mut request).unwrap();
    assert_eq!(request.fill, Some(WindingRule::Nonzero));
    assert_eq!(request.kind, Some(Kind::Polygons));
    // A triangle family is no polygon family, and a rule must be known.
    for json in [
        r#"{ "kind": "polygons", "weights": { "soup": 1 } }"#,
        r#"{ "kind": "polygons", "fill": "odd" }"#,
    ] {
        let config = CheckConfig::from_json(json).unwrap();
        let mut request = CheckRequest::new(SubjectSpec::Backend("edge-table".into()));
        assert!(config.apply(&mut request).is_err(), "{json}");
    }
}

/// The rings the polygon adapters' headers were measured on, each with
/// the verdict the header states: Pillow (its vertices rounded to whole
/// pixels by the adapter, which Pillow would otherwise truncate) and
/// OpenCV fill the square 1.2..5.8 exactly as the reference does, cairo
/// the pentagram under both rules, while Pillow and OpenCV add pixels
/// beside a slanted edge and cairo inside a hexagon whose edges cross.
#[test]
fn the_adapters_measured_rings_get_the_verdicts_their_headers_state() {
    let square = "polygon 1.2 1.2 5.8 1.2 5.8 5.8 1.2 5.8";
    let triangle = "polygon 0.8 0.3 7.9 2.6 2.2 7.7";
    let pentagram = "polygon 6 0.5 9.23 10.45 0.77 4.3 11.23 4.3 2.77 10.45";
    let hexagon = "polygon 13.4453125 8.4296875 4.94140625 0.30859375 4.84765625 \
                   7.59765625 8.41796875 0.578125 2.82421875 12.109375 9.74609375 1.99609375";
    let dir = tempfile::tempdir().unwrap();
    let require = std::env::var("RASTERLAB_REQUIRE_PYTHON").is_ok_and(|v| v == "1");
    for (adapter, module, ring, passes) in [
        ("pillow_polygon", "PIL", square, true),
        ("pillow_polygon", "PIL", triangle, false),
        ("opencv_polygon", "cv2", square, true),
        ("opencv_polygon", "cv2", triangle, false),
        ("cairo_polygon", "cairo", pentagram, true),
        ("cairo_polygon", "cairo", hexagon, false),
    ] {
        let present = Command::new("python3")
            .args(["-c", &format!("import numpy, {module}")])
            .output()
            .is_ok_and(|o| o.status.success());
        if !present {
            assert!(
                !require || module == "cairo",
                "RASTERLAB_REQUIRE_PYTHON=1 but python3 cannot import {module}"
            );
            eprintln!("SKIPPED: the {adapter} adapter (python3 cannot import {module})");
            continue;
        }
        let path = dir.path().join("case.txt");
        std::fs::write(&path, format!("# size 12x12\n{ring}\n")).unwrap();
        for fill in ["even-odd", "nonzero"] {
            let out = rasterlab(&[
                "check",
                "--kind",
                "polygons",
                "--fill",
                fill,
                "--case",
                path.to_str().unwrap(),
                "--out",
                dir.path().join("out").to_str().unwrap(),
                "--persistent",
                "--exec",
                &format!("python3 examples/adapters/{adapter}.py {{rule}}"),
            ]);
            let text = String::from_utf8_lossy(&out.stdout);
            let expected = if passes { 0 } else { 1 };
            assert_eq!(
                out.status.code(),
                Some(expected),
                "{adapter} {fill} {ring}: {text}"
            );
            if !passes {
                assert!(text.contains("(extra)"), "{adapter} {fill} {ring}: {text}");
            }
        }
    }
}
