//! `rasterlab check`: a rasterizer judged against the rules on generated
//! cases, a failure shrunk to a counterexample.

use super::print::progress_bar;
use clap::Args;
use rasterlab::raster::backend::{backend, Backend};
use rasterlab::{Error, Result};
use std::io::Write;
use std::path::PathBuf;
use std::time::Duration;

#[derive(Args, Debug)]
#[command(group(clap::ArgGroup::new("subject").required(true).args(["exec", "backend"])))]
pub struct CheckArgs {
    /// The program under test: a command line run once per case, with
    /// {input}, {width}, {height} and {rule} replaced; it prints `x y id`
    /// per fragment.
    #[arg(long)]
    exec: Option<String>,
    /// Check a built-in back-end instead (see `rasterlab backends`).
    #[arg(long)]
    backend: Option<String>,
    /// What the cases hold: triangles or lines (default: the back-end's
    /// kind, or triangles).
    #[arg(long)]
    kind: Option<String>,
    /// Triangles: the fill rule the answer must follow exactly, or
    /// `watertight` (no gaps, no double draws, under any consistent rule).
    /// Default: top-left.
    #[arg(long)]
    rule: Option<String>,
    /// Lines: midpoint (exactly `bresenham`), diamond (exactly `diamond`)
    /// or vulkan (Vulkan's tolerance of the diamond rule). Default:
    /// midpoint.
    #[arg(long)]
    convention: Option<String>,
    /// How many cases.
    #[arg(long, default_value_t = 150)]
    cases: u32,
    /// Seed of the case generator (the same seed gives the same cases).
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Seconds a program may take on one case.
    #[arg(long, default_value_t = 5.0)]
    timeout: f64,
    /// Directory for counterexample.txt, counterexample.svg and report.html.
    #[arg(long, default_value = "check-output")]
    out: PathBuf,
    /// Print the verdict as JSON on standard output (for autograders).
    #[arg(long)]
    json: bool,
}

/// More cases than this are refused: a check is for minutes, not hours.
const MAX_CHECK_CASES: u32 = 1_000_000;

pub fn run(args: &CheckArgs) -> Result<()> {
    use rasterlab::check::{self, judge::LineConvention, Builtin, CheckOptions, Program, Property};
    let chosen = args.backend.as_deref().map(backend).transpose()?;
    let kind = match (args.kind.as_deref(), chosen) {
        (Some("triangles"), _) | (None, None | Some(Backend::Triangle(_))) => "triangles",
        (Some("lines"), _) | (None, Some(Backend::Line(_))) => "lines",
        (Some(other), _) => {
            return Err(Error::UnknownName {
                what: "kind",
                name: other.to_string(),
                known: "triangles, lines".into(),
            })
        }
    };
    if kind == "lines" && args.rule.is_some() {
        return Err(Error::InvalidArgument(
            "--rule is for triangles; lines are judged by --convention".into(),
        ));
    }
    if kind == "triangles" && args.convention.is_some() {
        return Err(Error::InvalidArgument(
            "--convention is for lines; triangles are judged by --rule".into(),
        ));
    }
    let property = if kind == "lines" {
        Property::Line(match args.convention.as_deref().unwrap_or("midpoint") {
            "midpoint" => LineConvention::Midpoint,
            "diamond" => LineConvention::Diamond,
            "vulkan" => LineConvention::Vulkan,
            other => {
                return Err(Error::UnknownName {
                    what: "line convention",
                    name: other.to_string(),
                    known: "midpoint, diamond, vulkan".into(),
                })
            }
        })
    } else {
        match args.rule.as_deref().unwrap_or("top-left") {
            "watertight" => Property::Watertight,
            rule => Property::Exact(rule.parse()?),
        }
    };
    if !(1..=MAX_CHECK_CASES).contains(&args.cases) {
        return Err(Error::InvalidArgument(format!(
            "--cases must be between 1 and {MAX_CHECK_CASES}, not {}",
            args.cases
        )));
    }
    if !(args.timeout > 0.0 && args.timeout <= 3600.0) {
        return Err(Error::InvalidArgument(format!(
            "--timeout must be between 0 and 3600 seconds, not {}",
            args.timeout
        )));
    }
    rasterlab::output::check_dir(&args.out)?;
    let rule_word = match property {
        Property::Exact(rule) => rule.name(),
        _ => "top-left",
    };
    let mut subject: Box<dyn check::Subject> = match (chosen, &args.exec) {
        (Some(Backend::Triangle(b)), _) if kind == "triangles" => {
            Box::new(Builtin::triangles(b, rule_word.parse()?))
        }
        (Some(Backend::Line(b)), _) if kind == "lines" => Box::new(Builtin::Lines(b)),
        (Some(_), _) => {
            return Err(Error::InvalidArgument(format!(
                "back-end `{}` does not draw {kind}",
                args.backend.as_deref().unwrap_or_default()
            )))
        }
        (None, Some(command)) => {
            let mut program = Program::new(command, rule_word);
            program.timeout = Duration::from_secs_f64(args.timeout);
            Box::new(program)
        }
        (None, None) => {
            return Err(Error::InvalidArgument(
                "give --exec CMD or --backend NAME".into(),
            ))
        }
    };
    let options = CheckOptions {
        cases: args.cases,
        seed: args.seed,
        ..CheckOptions::new(property)
    };
    let bar = progress_bar(u64::from(args.cases), "cases");
    let verdict = check::check_with_progress(&options, subject.as_mut(), &mut |done| {
        bar.set_position(u64::from(done));
    });
    bar.finish_and_clear();
    let counterexample = args.out.join("counterexample.txt");
    match verdict {
        Ok(check::Verdict::Pass { cases }) => {
            if args.json {
                say!(
                    "{}",
                    serde_json::json!({"verdict": "pass", "property": property.to_string(), "cases": cases, "seed": args.seed})
                )
            } else {
                say!("PASS: {cases} cases, {property} (seed {})", args.seed)
            }
        }
        Ok(check::Verdict::Fail {
            case_index,
            original,
            finding,
        }) => {
            rasterlab::output::write_file(
                &counterexample,
                finding.counterexample_text().as_bytes(),
            )?;
            let report = args.out.join("report.html");
            rasterlab::output::write_file(&report, finding.to_html().as_bytes())?;
            rasterlab::output::write_file(
                &args.out.join("counterexample.svg"),
                finding.to_svg().as_bytes(),
            )?;
            if args.json {
                let pixels = |v: &[check::Fragment]| -> Vec<[i64; 3]> {
                    v.iter().map(|f| [f.x, f.y, i64::from(f.id)]).collect()
                };
                say!(
                    "{}",
                    serde_json::json!({
                        "verdict": "fail",
                        "property": property.to_string(),
                        "case": case_index,
                        "seed": args.seed,
                        "problems": finding.problems,
                        "diagnosis": finding.diagnosis,
                        "missing": pixels(&finding.missing),
                        "extra": pixels(&finding.extra),
                        "counterexample": finding.counterexample_text(),
                    })
                )?;
            } else {
                say!(
                    "FAIL: {property}, case {case_index} of seed {}; shrunk from {} to {} primitive(s) on a {}x{} target",
                    args.seed,
                    original.len(),
                    finding.case.len(),
                    finding.case.width,
                    finding.case.height
                )?;
                for p in finding.problems.iter().take(5) {
                    say!("  {p}")?;
                }
                if finding.problems.len() > 5 {
                    say!("  ... and {} more", finding.problems.len() - 5)?;
                }
                say!("# correct   ! extra (or drawn twice)   ? missing")?;
                say_raw!("{}", finding.ascii_grid())?;
                if let Some(d) = &finding.diagnosis {
                    say!("diagnosis: {d}")?;
                }
                say!(
                    "counterexample: {} (rerun: give it to the program as its input)\nreport: {}",
                    counterexample.display(),
                    report.display()
                )?;
            }
            Err(Error::Mismatch(format!(
                "the check failed: {}",
                finding.problems[0]
            )))
        }
        Err(broken) => {
            rasterlab::output::write_file(&counterexample, broken.case.to_text().as_bytes())?;
            if args.json {
                say!(
                    "{}",
                    serde_json::json!({"verdict": "broken", "error": broken.error.to_string(), "input": broken.case.to_text()})
                )?;
            }
            Err(Error::InvalidArgument(format!(
                "{}\nthe input that triggers it ({} primitive(s), {}x{}): {}",
                broken.error,
                broken.case.len(),
                broken.case.width,
                broken.case.height,
                counterexample.display()
            )))
        }
    }
}
