//! The courses' conventions: a rasterizer whose y grows up (Scotty3D,
//! OpenGL's window coordinates) passes with `--origin bottom-left` and
//! fails without it with the y flip named; one of the inclusive rule
//! (CS184, CS248) passes `--rule inclusive` and fails the default
//! top-left rule with the inclusive rule named; Scotty3D's lines, the
//! diamond rule with its (e, e^2) tie-break, are told apart from the plain
//! diamond rule. Each is checked twice: as
//! a Rust subject through the library, and as the Python students of
//! `examples/student/` through the command line.

mod common;

use common::{part_missing, rasterlab};
use rasterlab::check::triangle_fragments;
use rasterlab::check::{
    preset, run_with, Builtin, Case, CheckReport, CheckRequest, Fragment, Origin, RuleChoice,
    Snapping, Subject, SubjectError, SubjectSpec, VerdictWord,
};
use rasterlab::raster::{triangle_backend, FillRule};
use std::process::Command;

/// A rasterizer whose y grows up, of the top-left rule as its own
/// picture shows it (a top edge has the triangle below it, at smaller y),
/// in integers on the snapped vertices.
fn y_up(case: &Case) -> Result<Vec<Fragment>, SubjectError> {
    let edge = |a: (i64, i64), b: (i64, i64), p: (i64, i64)| {
        i128::from(b.0 - a.0) * i128::from(p.1 - a.1)
            - i128::from(b.1 - a.1) * i128::from(p.0 - a.0)
    };
    let mut out = Vec::new();
    // Snapped to 1/256 px, halfway to even; not clamped to the guard
    // band, which y measured up can leave (a Python int does not wrap).
    let snap = |v: f64| (v * 256.0).round_ties_even() as i64;
    for (id, t) in case.triangles.iter().enumerate() {
        let mut v = t.map(|(x, y)| (snap(x), snap(y)));
        let area = edge(v[0], v[1], v[2]);
        if area == 0 {
            continue;
        }
        if area < 0 {
            v.swap(1, 2);
        }
        let owns = |a: (i64, i64), b: (i64, i64)| {
            if a.1 == b.1 {
                b.0 < a.0
            } else {
                b.1 < a.1
            }
        };
        for y in 0..i64::from(case.height) {
            for x in 0..i64::from(case.width) {
                let p = (x * 256 + 128, y * 256 + 128);
                let inside = (0..3).all(|k| {
                    let (a, b) = (v[k], v[(k + 1) % 3]);
                    let e = edge(a, b, p);
                    e > 0 || (e == 0 && owns(a, b))
                });
                if inside {
                    out.push(Fragment::at(x, y, id as u32));
                }
            }
        }
    }
    Ok(out)
}

fn report(
    origin: Origin,
    rule: FillRule,
    make: &(dyn Fn() -> Box<dyn Subject + Send> + Sync),
) -> CheckReport {
    let mut request = CheckRequest::new(SubjectSpec::Backend(String::new()));
    request.cases = 200;
    request.origin = origin;
    request.rule = Some(RuleChoice::Exact(rule));
    run_with(&request, "mine", make).unwrap()
}

fn diagnosis(report: &CheckReport) -> String {
    report
        .counterexample
        .as_ref()
        .and_then(|c| c.diagnosis.clone())
        .unwrap_or_default()
}

#[test]
fn a_y_up_rasterizer_passes_with_its_origin_and_is_named_flipped_without() {
    let up = report(Origin::BottomLeft, FillRule::TopLeft, &|| Box::new(y_up));
    assert_eq!(up.verdict, VerdictWord::Pass, "{up}");
    let down = report(Origin::TopLeft, FillRule::TopLeft, &|| Box::new(y_up));
    assert_eq!(down.verdict, VerdictWord::Fail);
    let d = diagnosis(&down);
    assert!(
        d.contains("top-left rule with y flipped") && d.contains("--origin bottom-left"),
        "{d}"
    );
    // A y-down back-end told its y grows up fails the other way round.
    let bbox = triangle_backend("bbox").unwrap();
    let make =
        move || Box::new(Builtin::triangles(bbox, FillRule::TopLeft)) as Box<dyn Subject + Send>;
    let flipped = report(Origin::BottomLeft, FillRule::TopLeft, &make);
    assert_eq!(flipped.verdict, VerdictWord::Fail);
    let d = diagnosis(&flipped);
    assert!(d.contains("without --origin bottom-left"), "{d}");
    // The rule is named as the picture shows it: a y-up subject judged
    // by the bottom-left rule is the y-down back-end's mirror, and fails.
    let mirror = report(Origin::BottomLeft, FillRule::BottomLeft, &|| Box::new(y_up));
    assert_eq!(mirror.verdict, VerdictWord::Fail);
}

/// Under `--origin bottom-left` the counterexample file is the program's
/// input, y up, as the text says ("give it to the program as its input"):
/// its primitives are the case seen from the bottom edge, its missing and
/// extra pixels count rows up from the bottom, and `--case` reads it back
/// (its `# origin bottom-left` line turns y down again) to the same
/// failure.
#[test]
fn a_y_up_counterexample_file_is_the_programs_own_input() {
    let out = std::env::temp_dir().join(format!("rasterlab-y-up-{}", std::process::id()));
    let mut request = CheckRequest::new(SubjectSpec::Backend(String::new()));
    request.cases = 200;
    request.origin = Origin::BottomLeft;
    request.rule = Some(RuleChoice::Exact(FillRule::BottomLeft));
    request.out = Some(out.clone());
    let failed = run_with(&request, "mine", &|| Box::new(y_up)).unwrap();
    assert_eq!(failed.verdict, VerdictWord::Fail, "{failed}");
    let finding = failed.finding.as_deref().unwrap();
    let file = out.join("counterexample.txt");
    let text = std::fs::read_to_string(&file).unwrap();
    assert!(text.contains("\n# origin bottom-left\n"), "{text}");
    // The primitives as a program reads them, skipping the comments.
    let given: Vec<Vec<f64>> = text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| l.split_whitespace().map(|t| t.parse().unwrap()).collect())
        .collect();
    let h = f64::from(finding.case.height);
    let seen_up: Vec<Vec<f64>> = finding
        .case
        .triangles
        .iter()
        .map(|t| t.iter().flat_map(|&(x, y)| [x, h - y]).collect())
        .collect();
    assert_eq!(given, seen_up, "{text}");
    // The missing and extra pixels as the program names them.
    let last = i64::from(finding.case.height) - 1;
    for (word, list) in [("missing", &finding.missing), ("extra", &finding.extra)] {
        let line = text
            .lines()
            .find(|l| l.starts_with(&format!("# {word}:")))
            .unwrap();
        for f in list.iter().take(40) {
            let named = format!("({},{}) t{}", f.x, last - f.y, f.id);
            assert!(line.contains(&named), "{named} not in {line}");
        }
    }
    assert!(failed.to_string().contains("y up as it is given the case"));
    let json = serde_json::to_value(&failed).unwrap();
    assert_eq!(json["origin"], "bottom-left");
    // The picture names the vertices as the file gives them.
    let svg = std::fs::read_to_string(out.join("counterexample.svg")).unwrap();
    let t = &given[0];
    let v0 = format!("v0 ({}, {})", t[0], t[1]);
    assert!(svg.contains(&v0), "{v0} not in the picture's legend");
    // Read back: the same case, the same failure.
    assert_eq!(Case::from_text(&text).unwrap(), finding.case);
    let mut rerun = request.clone();
    rerun.case_file = Some(file.clone());
    rerun.out = None;
    let again = run_with(&rerun, "mine", &|| Box::new(y_up)).unwrap();
    let again = again.finding.as_deref().expect("the file fails again");
    assert_eq!(again.case.triangles, finding.case.triangles);
    assert_eq!(again.missing, finding.missing);
    assert_eq!(again.extra, finding.extra);
    std::fs::remove_dir_all(&out).unwrap();
}

/// Under `--origin bottom-left` the samples stay where they are on the
/// screen: a program that uses the y-down sample list in its y-up
/// coordinates (a y-down back-end given the case y up) is told its
/// pattern is mirrored.
#[test]
fn a_y_up_program_with_the_y_down_sample_list_is_told_it_is_mirrored() {
    let out = rasterlab(&[
        "check",
        "--origin",
        "bottom-left",
        "--msaa",
        "4",
        "--backend",
        "bbox",
        "--cases",
        "60",
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{text}");
    assert!(text.contains("the sample pattern mirrored in y"), "{text}");
}

/// `rasterlab check` on a Python student of `examples/student/`, with
/// more options; the exit status and what it printed (both streams).
fn student(file: &str, options: &[&str]) -> Option<(i32, String)> {
    let python = Command::new("python3")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    if !python {
        part_missing(
            "the convention students",
            "python3",
            "RASTERLAB_REQUIRE_STARTERS",
        );
        return None;
    }
    let command = format!(
        "python3 {}/examples/student/{file}",
        env!("CARGO_MANIFEST_DIR")
    );
    let out_dir = tempfile::tempdir().unwrap();
    let mut args = vec!["check", "--persistent", "--exec", &command, "--out"];
    args.push(out_dir.path().to_str().unwrap());
    args.extend_from_slice(options);
    let out = rasterlab(&args);
    Some((
        out.status.code().unwrap_or(-1),
        format!(
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        ),
    ))
}

#[test]
fn the_python_students_pass_in_their_convention_and_fail_for_the_named_reason() {
    let Some((code, text)) = student("y_up.py", &["--origin", "bottom-left", "--cases", "300"])
    else {
        return;
    };
    assert_eq!(code, 0, "{text}");
    assert!(text.starts_with("PASS: 300 cases"), "{text}");
    let (code, text) = student("y_up.py", &[]).unwrap();
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("y flipped"), "{text}");
    let (code, text) = student("inclusive.py", &["--rule", "inclusive", "--cases", "300"]).unwrap();
    assert_eq!(code, 0, "{text}");
    let (code, text) = student("inclusive.py", &[]).unwrap();
    assert_eq!(code, 1, "{text}");
    assert!(
        text.contains("diagnosis: cause: ties decided by the inclusive rule"),
        "{text}"
    );
    // An origin that is not one is refused.
    let out = rasterlab(&["check", "--backend", "bbox", "--origin", "middle"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("bottom-left"));
}

/// The top-left rule in floating point on the vertices as given, as the
/// courses' rasterizers compute it: edge functions `a x + b y + c` of the
/// rules' own form, in `f64` (or `f32`), a centre on an edge decided by
/// the top-left rule, no snapping.
fn float_top_left<F: Float>(case: &Case) -> Result<Vec<Fragment>, SubjectError> {
    float_rule::<F, false>(case)
}

/// [`float_top_left`], or with `INCLUSIVE` every centre on an edge drawn.
fn float_rule<F: Float, const INCLUSIVE: bool>(case: &Case) -> Result<Vec<Fragment>, SubjectError> {
    let mut out = Vec::new();
    for (id, t) in case.triangles.iter().enumerate() {
        let v = t.map(|(x, y)| (F::of(x), F::of(y)));
        // Edge k from v[k+1] to v[k+2], opposite vertex k.
        let edge = |k: usize| {
            let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
            (b.1 - a.1, a.0 - b.0, b.0 * a.1 - a.0 * b.1)
        };
        let mut edges = [edge(0), edge(1), edge(2)];
        let area = {
            let (a, b, c) = edges[0];
            a * v[0].0 + b * v[0].1 + c
        };
        if area == F::of(0.0) {
            continue;
        }
        if area < F::of(0.0) {
            for e in &mut edges {
                *e = (-e.0, -e.1, -e.2);
            }
        }
        // Whether each edge owns the centres on it, decided once.
        let owns = edges
            .map(|(a, b, _)| INCLUSIVE || a > F::of(0.0) || (a == F::of(0.0) && b > F::of(0.0)));
        for y in 0..case.height {
            for x in 0..case.width {
                let p = (F::of(f64::from(x) + 0.5), F::of(f64::from(y) + 0.5));
                let inside = edges.iter().zip(owns).all(|(&(a, b, c), owns)| {
                    let e = a * p.0 + b * p.1 + c;
                    e > F::of(0.0) || (e == F::of(0.0) && owns)
                });
                if inside {
                    out.push(Fragment::at(i64::from(x), i64::from(y), id as u32));
                }
            }
        }
    }
    Ok(out)
}

/// `f64` or `f32`, for [`float_top_left`].
trait Float:
    Copy
    + PartialOrd
    + std::ops::Add<Output = Self>
    + std::ops::Sub<Output = Self>
    + std::ops::Mul<Output = Self>
    + std::ops::Neg<Output = Self>
{
    fn of(v: f64) -> Self;
}

impl Float for f64 {
    fn of(v: f64) -> f64 {
        v
    }
}

impl Float for f32 {
    fn of(v: f64) -> f32 {
        v as f32
    }
}

/// `--snap none`: a top-left rasterizer in `f64` on the vertices as given
/// passes 1,000 cases of every family (their coordinates, multiples of
/// 1/256 px, are exact in `f64`, and so are its edge functions); with the
/// default 1/256 px snapping it fails the ties family, whose vertices lie
/// halfway between two steps. In `f32` it fails, and the cause names
/// floating point (and not snapping, as nothing was snapped).
#[test]
fn a_floating_point_rasterizer_passes_when_nothing_is_snapped() {
    let run = |snapping: Snapping,
               cases: u32,
               subject: fn(&Case) -> Result<Vec<Fragment>, SubjectError>| {
        let mut request = CheckRequest::new(SubjectSpec::Backend(String::new()));
        request.cases = cases;
        request.keep_going = true;
        request.snapping = snapping;
        request.rule = Some(RuleChoice::Exact(FillRule::TopLeft));
        run_with(&request, "float", &move || Box::new(subject)).unwrap()
    };
    let none = run(Snapping::AsGiven, 10_000, float_top_left::<f64>);
    assert_eq!(none.verdict, VerdictWord::Pass, "{none}");
    assert_eq!(none.families.len(), 10);
    for f in &none.families {
        assert_eq!((f.passed, f.total), (1000, 1000), "{}", f.family);
    }
    assert!(
        none.description
            .ends_with("vertices not snapped: judged as given"),
        "{}",
        none.description
    );

    let snapped = run(Snapping::default(), 200, float_top_left::<f64>);
    assert_eq!(snapped.verdict, VerdictWord::Fail);
    let ties = snapped
        .families
        .iter()
        .find(|f| f.family == "ties")
        .unwrap();
    assert!(ties.passed < ties.total, "{ties:?}");

    let single = run(Snapping::AsGiven, 10_000, float_top_left::<f32>);
    assert_eq!(single.verdict, VerdictWord::Fail);
    let d = diagnosis(&single);
    assert!(d.contains("floating-point"), "{d}");
    // Nothing was snapped, so no snapping is suspected.
    assert!(!d.contains("not snapped"), "{d}");
}

/// `--snap 1/16`: a rasterizer that snaps to 1/16 px passes it, and fails
/// the default 1/256 with the coarse snapping named. Under `--snap none`
/// a case file off the 1/256 px grid is refused, naming the file; an
/// unknown grid is refused with the choices.
#[test]
fn a_coarser_grid_is_judged_on_its_own_grid_and_wrong_grids_are_refused() {
    fn sixteenth(case: &Case) -> Result<Vec<Fragment>, SubjectError> {
        let snapped = Case {
            triangles: case
                .triangles
                .iter()
                .map(|t| {
                    t.map(|(x, y)| {
                        (
                            (x * 16.0).round_ties_even() / 16.0,
                            (y * 16.0).round_ties_even() / 16.0,
                        )
                    })
                })
                .collect(),
            ..case.clone()
        };
        Ok(triangle_fragments(
            triangle_backend("tiled").unwrap(),
            &snapped,
            FillRule::TopLeft,
        ))
    }
    let run = |snapping: Snapping| {
        let mut request = CheckRequest::new(SubjectSpec::Backend(String::new()));
        request.cases = 300;
        request.snapping = snapping;
        run_with(&request, "sixteenth", &|| Box::new(sixteenth)).unwrap()
    };
    let coarse = run("1/16".parse().unwrap());
    assert_eq!(coarse.verdict, VerdictWord::Pass, "{coarse}");
    let fine = run(Snapping::default());
    assert_eq!(fine.verdict, VerdictWord::Fail);
    let d = diagnosis(&fine);
    assert!(
        d.contains("vertices snapped to 1/16 px instead of 1/256"),
        "{d}"
    );

    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("off-grid.txt");
    std::fs::write(&file, "# size 4x4\n0.1 0 3 0 0 3\n").unwrap();
    let out = rasterlab(&[
        "check",
        "--backend",
        "bbox",
        "--snap",
        "none",
        "--case",
        file.to_str().unwrap(),
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("off-grid.txt") && err.contains("1/256 px grid"),
        "{err}"
    );
    let out = rasterlab(&["check", "--backend", "bbox", "--snap", "1/3"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("1/256") && err.contains("none"), "{err}");
}

/// The presets: Scotty3D's triangles (y up, nothing snapped) pass the
/// y-up subject; CS184's and CS248's (the inclusive rule, nothing
/// snapped) pass the inclusive rule in `f64` on the vertices as given;
/// an unknown preset is refused with the names.
#[test]
fn the_presets_pass_the_subjects_of_their_courses() {
    let under = |name: &str, make: &(dyn Fn() -> Box<dyn Subject + Send> + Sync)| {
        let mut request = CheckRequest::new(SubjectSpec::Backend(String::new()));
        preset(name).unwrap().config.apply(&mut request).unwrap();
        request.cases = 1000;
        run_with(&request, name, make).unwrap()
    };
    let scotty = under("opengl-window", &|| Box::new(y_up));
    assert_eq!(scotty.verdict, VerdictWord::Pass, "{scotty}");
    let cs184 = under("inclusive-float", &|| Box::new(float_rule::<f64, true>));
    assert_eq!(cs184.verdict, VerdictWord::Pass, "{cs184}");
    let d3d = under("inclusive-float", &|| Box::new(float_top_left::<f64>));
    assert_eq!(d3d.verdict, VerdictWord::Fail);
    let out = rasterlab(&["check", "--backend", "bbox", "--preset", "cs184"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("opengl-window") && err.contains("inclusive-float"),
        "{err}"
    );
}

/// Scotty3D's lines: the diamond rule with the ends moved by (e, e^2).
/// The back-end of that convention passes it; the plain diamond rule
/// fails it, and the other way round, each with the other named.
#[test]
fn scotty3d_lines_are_the_diamond_rule_nudged_and_told_apart_from_it() {
    let check = |backend: &str, convention: &str| {
        let out_dir = tempfile::tempdir().unwrap();
        let out = rasterlab(&[
            "check",
            "--kind",
            "lines",
            "--backend",
            backend,
            "--convention",
            convention,
            "--cases",
            "300",
            "--out",
            out_dir.path().to_str().unwrap(),
        ]);
        (
            out.status.code(),
            String::from_utf8_lossy(&out.stdout).into_owned(),
        )
    };
    let (code, text) = check("diamond-nudged", "diamond-nudged");
    assert_eq!(code, Some(0), "{text}");
    assert!(text.starts_with("PASS: 300 cases"), "{text}");
    let (code, text) = check("diamond", "diamond-nudged");
    assert_eq!(code, Some(1), "{text}");
    assert!(
        text.contains("diagnosis: cause: the diamond convention's pixels"),
        "{text}"
    );
    let (code, text) = check("diamond-nudged", "diamond");
    assert_eq!(code, Some(1), "{text}");
    assert!(
        text.contains("diagnosis: cause: the diamond-nudged convention's pixels"),
        "{text}"
    );
}

#[test]
fn every_list_of_fill_rules_names_all_seven() {
    let rules = FillRule::ALL.map(FillRule::name);
    for command in ["fragments", "explain"] {
        let help = rasterlab(&[command, "--help"]);
        let text = String::from_utf8_lossy(&help.stdout);
        for rule in rules {
            assert!(
                text.contains(rule),
                "{command} --help has no {rule}:\n{text}"
            );
        }
    }
    let page = rasterlab::lab::page();
    for rule in rules {
        assert!(
            page.contains(&format!("<option>{rule}</option>")),
            "the lab's rule menu has no {rule}"
        );
    }
    // A rule given to a line back-end is refused, not ignored.
    for args in [
        &[
            "fragments",
            "--backend",
            "bresenham",
            "--size",
            "4x4",
            "--rule",
            "inclusive",
            "x",
        ][..],
        &[
            "explain",
            "--backend",
            "bresenham",
            "--rule",
            "inclusive",
            "0",
            "0",
            "7",
            "3",
        ],
    ] {
        let out = rasterlab(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("--rule is a triangle fill rule"), "{err}");
    }
    let out = rasterlab(&["explain", "--backend", "bresenham", "0", "0", "7", "3"]);
    assert_eq!(out.status.code(), Some(0));
    // A rule the list does not hold is refused with the list.
    let out = rasterlab(&[
        "fragments",
        "--backend",
        "bbox",
        "--size",
        "4x4",
        "--rule",
        "sideways",
        "x",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("top-right"));
}
