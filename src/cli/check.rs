//! `rasterlab check`: a rasterizer judged against the rules on generated
//! cases, a failure shrunk to a counterexample. Wiring only: the check is
//! [`rasterlab::check::run`].

use super::args::msaa;
use clap::Args;
use rasterlab::check::{
    timeout_from_seconds, CheckConfig, CheckRequest, ConventionChoice, ImageRequest, Kind, Origin,
    Progress, ReportFormat, RuleChoice, Snapping, SubjectSpec,
};
use rasterlab::raster::polygon::WindingRule;
use rasterlab::raster::SamplePattern;
use rasterlab::{check, Error, Result};
use std::path::PathBuf;

#[derive(Args, Debug)]
#[command(group(clap::ArgGroup::new("subject").required(true).args(["exec", "backend"])))]
pub struct CheckArgs {
    /// The program under test: a command line run once per case, with
    /// {input}, {width}, {height}, {rule} and {msaa} replaced; it prints
    /// `x y id` per fragment.
    #[arg(long)]
    exec: Option<String>,
    /// Start the --exec program once: it reads case after case on its
    /// standard input (the case as in the input file, then a line `end`)
    /// and answers each with its fragments, then a line `end` (or one
    /// line `error MESSAGE`). Many times faster for programs slow to
    /// start; {rule} and {msaa} are still replaced.
    #[arg(long)]
    persistent: bool,
    /// Grade whole renders instead of coverage: the --exec program is run
    /// once per image test with {scene} (a scene file, or a built-in
    /// scene's name), {size} (WxH), {width}, {height}, {settings} (the
    /// test's `rasterlab render` options) and {out} (the PNG to write)
    /// replaced, and its image compared with rasterlab's render of the
    /// same scene within the configuration's thresholds
    /// (docs/check-image.md).
    #[arg(long, requires = "exec", conflicts_with_all = ["persistent", "backend", "case"])]
    image: bool,
    /// Check a built-in back-end instead (see `rasterlab backends`).
    #[arg(long)]
    backend: Option<String>,
    /// What the cases hold: triangles, lines or polygons (default: the
    /// back-end's kind, or triangles).
    #[arg(long)]
    kind: Option<Kind>,
    /// Triangles: the fill rule the answer must follow exactly
    /// (top-left, bottom-right, top-right, bottom-left, offscreen-point,
    /// inclusive, exclusive), `watertight` (no gaps, no double draws,
    /// under any consistent rule), `crack-free` (shared edges drawn once,
    /// nothing twice) or `any` (which rule does it follow?). Default:
    /// top-left.
    #[arg(long)]
    rule: Option<RuleChoice>,
    /// Lines: midpoint (exactly `bresenham`), diamond (exactly `diamond`),
    /// vulkan (Vulkan's tolerance of the diamond rule); with whole-number
    /// endpoints naming pixels, integer Bresenham breaking ties toward the
    /// start (pixel-index), toward the end (pixel-index-toward-end) or as
    /// the course's midpoint walk, left to right
    /// (pixel-index-left-to-right), as OpenCV's LINE_8 and LINE_4 without
    /// `shift` (pixel-index-opencv, pixel-index-opencv-4); or `any`
    /// (which convention does it follow?). Default: midpoint.
    #[arg(long)]
    convention: Option<ConventionChoice>,
    /// Polygons (--kind polygons): the winding rule they are filled by,
    /// even-odd or nonzero, a centre on an edge by the top-left
    /// convention (inside on a left or top edge). Default: even-odd.
    #[arg(long, value_name = "RULE")]
    fill: Option<WindingRule>,
    /// Triangles under one fill rule, multisampled: N samples per pixel
    /// on the standard pattern (1, 2, 4, 8 or 16). The program is told N
    /// by {msaa} (and a line `# msaa N` in the case) and prints `x y id
    /// mask`, bit i of the mask for sample i; the masks are judged exactly.
    #[arg(long, value_name = "N", value_parser = msaa, allow_negative_numbers = true)]
    msaa: Option<SamplePattern>,
    /// How many cases, 1 to 1,000,000 (default: 150, or the
    /// configuration's).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=i64::from(check::MAX_CASES)))]
    cases: Option<u32>,
    /// Seed of the case generator (the same seed gives the same cases;
    /// default: 0, or the configuration's).
    #[arg(long)]
    seed: Option<u64>,
    /// Seconds a program may take on one case (default: 5, or the
    /// configuration's).
    #[arg(long)]
    timeout: Option<f64>,
    /// Where the program's origin is: top-left (y down, the protocol's;
    /// the default) or bottom-left (y up: OpenGL's window coordinates,
    /// Scotty3D). A y-up program is given y as height - y and answers
    /// with row 0 at the bottom; the rules are named as the picture shows
    /// them.
    #[arg(long)]
    origin: Option<Origin>,
    /// How vertices are snapped before judging: 1/256 (the default, as
    /// Direct3D and Vulkan hardware snap), a coarser power of two down to
    /// 1, or none: judged as given, in exact arithmetic, as the courses'
    /// floating-point rasterizers compute (every case's coordinates are
    /// then multiples of 1/256 px, exact in floating point).
    #[arg(long, value_name = "GRID")]
    snap: Option<Snapping>,
    /// A well-known assignment's conventions, by what they are:
    /// direct3d (the default), opengl-window (Scotty3D A1's triangles),
    /// inclusive-float (CS184 HW1, CS248 A1), opengl-window-lines
    /// (Scotty3D A1's lines). --config and the options given win over it.
    #[arg(long, value_name = "NAME")]
    preset: Option<String>,
    /// A teacher's configuration (JSON): the rule or convention, the
    /// cases, the seed, the time limit and each family's weight in the
    /// grader formats (docs/check.md). An option given on the command
    /// line wins over the file.
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
    /// Cases run at once.
    #[arg(long, default_value_t = 1)]
    jobs: usize,
    /// Run every case and report each family's passed/total and a score,
    /// instead of stopping at the first failure.
    #[arg(long)]
    keep_going: bool,
    /// Judge this one case (a counterexample file, a case of your own)
    /// instead of generated ones.
    #[arg(long, value_name = "FILE")]
    case: Option<PathBuf>,
    /// Directory for counterexample.txt, counterexample.svg and report.html.
    #[arg(long, default_value = "check-output")]
    out: PathBuf,
    /// How the report is printed: text; json (rasterlab's report,
    /// docs/check-report.schema.json); gradescope (Gradescope's
    /// results.json) or junit (JUnit XML), a test per case family, which
    /// run every case as --keep-going does.
    #[arg(
        long,
        value_name = "FORMAT",
        default_value = "text",
        conflicts_with = "json"
    )]
    format: ReportFormat,
    /// The same as --format json.
    #[arg(long)]
    json: bool,
}

pub fn run(args: &CheckArgs) -> Result<()> {
    let format = if args.json {
        ReportFormat::Json
    } else {
        args.format
    };
    if args.image {
        return run_images(args, format);
    }
    if args.persistent && args.exec.is_none() {
        return Err(Error::InvalidArgument(
            "--persistent starts an --exec program once; a --backend runs in rasterlab".into(),
        ));
    }
    let subject = match (&args.exec, &args.backend) {
        (Some(command), _) if args.persistent => SubjectSpec::Persistent(command.clone()),
        (Some(command), _) => SubjectSpec::Exec(command.clone()),
        (None, Some(name)) => SubjectSpec::Backend(name.clone()),
        (None, None) => {
            return Err(Error::InvalidArgument(
                "give --exec CMD or --backend NAME".into(),
            ))
        }
    };
    let mut request = CheckRequest::new(subject);
    if let Some(name) = &args.preset {
        check::preset(name)?.config.apply(&mut request)?;
    }
    if let Some(path) = &args.config {
        // A value the configuration names wrongly is its file's error.
        CheckConfig::read(path)?
            .apply(&mut request)
            .map_err(|e| Error::Parse {
                path: path.clone(),
                line: None,
                message: e.to_string(),
            })?;
    }
    let request = CheckRequest {
        kind: args.kind.or(request.kind),
        rule: args.rule.or(request.rule),
        convention: args.convention.or(request.convention),
        fill: args.fill.or(request.fill),
        origin: args.origin.unwrap_or(request.origin),
        snapping: args.snap.unwrap_or(request.snapping),
        msaa: args.msaa.map(SamplePattern::count),
        cases: args.cases.unwrap_or(request.cases),
        seed: args.seed.unwrap_or(request.seed),
        timeout: match args.timeout {
            Some(t) => timeout_from_seconds(t)?,
            None => request.timeout,
        },
        jobs: args.jobs,
        keep_going: args.keep_going || format.for_graders(),
        case_file: args.case.clone(),
        out: Some(args.out.clone()),
        command: check::shell_words(std::env::args()),
        ..request
    };
    // Ctrl-C removes the program's input files.
    if matches!(
        request.subject,
        SubjectSpec::Exec(_) | SubjectSpec::Persistent(_)
    ) {
        let _ = ctrlc::set_handler(|| {
            check::remove_live_input_folders();
            std::process::exit(130);
        });
    }
    let report = if format == ReportFormat::Text {
        let bars = Bars::default();
        let report = check::run_with_progress(&request, &mut |p| bars.show(p));
        bars.clear();
        report?
    } else {
        check::run(&request)?
    };
    let json = |text: serde_json::Result<String>| {
        text.map_err(|e| Error::InvalidArgument(format!("the report as JSON: {e}")))
    };
    match format {
        ReportFormat::Text if report.exit_code() != 2 => super::print::line(&report)?,
        ReportFormat::Text => {}
        ReportFormat::Json => super::print::line(json(serde_json::to_string(&report))?)?,
        ReportFormat::Gradescope => super::print::line(json(serde_json::to_string_pretty(
            &check::gradescope(&report),
        ))?)?,
        ReportFormat::Junit => super::print::out(check::junit(&report))?,
    }
    report.outcome()
}

/// `check --image`: the program's renders graded against rasterlab's.
fn run_images(args: &CheckArgs, format: ReportFormat) -> Result<()> {
    if format == ReportFormat::Json {
        return Err(Error::InvalidArgument(
            "--image reports as text, gradescope or junit; its JSON is Gradescope's (--format gradescope)"
                .into(),
        ));
    }
    let command = args.exec.clone().unwrap_or_default();
    let mut request = ImageRequest::new(&command, &args.out);
    if let Some(path) = &args.config {
        let config = CheckConfig::read(path)?;
        let mut timeout = request.timeout;
        if let Some(t) = config.timeout {
            timeout = timeout_from_seconds(t).map_err(|e| config_error(path, e))?;
        }
        if let Some(images) = &config.images {
            request
                .configure(images)
                .map_err(|e| config_error(path, e))?;
        }
        request.timeout = timeout;
    }
    if let Some(t) = args.timeout {
        request.timeout = timeout_from_seconds(t)?;
    }
    request.check_command = check::shell_words(std::env::args());
    let report = check::run_images(&request)?;
    match format {
        ReportFormat::Gradescope => super::print::line(
            serde_json::to_string_pretty(&check::image_gradescope(&report))
                .map_err(|e| Error::InvalidArgument(format!("the report as JSON: {e}")))?,
        )?,
        ReportFormat::Junit => super::print::out(check::image_junit(&report))?,
        _ if report.exit_code() != 2 => super::print::line(&report)?,
        _ => {}
    }
    report.outcome()
}

/// A value a configuration file names wrongly: its file's error.
fn config_error(path: &std::path::Path, e: Error) -> Error {
    Error::Parse {
        path: path.to_path_buf(),
        line: None,
        message: e.to_string(),
    }
}

/// The progress bars of a check on standard error: cases, the cases run
/// to confirm a cause, the shrinking runs.
#[derive(Default)]
struct Bars {
    bar: std::cell::RefCell<Option<(&'static str, indicatif::ProgressBar)>>,
}

impl Bars {
    fn show(&self, p: Progress) {
        let (what, pos, len) = match p {
            Progress::Cases { done, total } => ("cases", done, total),
            Progress::Confirming { done, total } => ("cases confirming the cause", done, total),
            Progress::Shrinking { runs, budget } => ("shrinking runs", runs, budget),
            Progress::Done => return self.clear(),
        };
        let mut slot = self.bar.borrow_mut();
        if slot.as_ref().is_none_or(|(w, _)| *w != what) {
            if let Some((_, old)) = slot.take() {
                old.finish_and_clear();
            }
            *slot = Some((what, super::print::progress_bar(u64::from(len), what)));
        }
        if let Some((_, bar)) = slot.as_ref() {
            bar.set_position(u64::from(pos));
        }
    }

    fn clear(&self) {
        if let Some((_, bar)) = self.bar.borrow_mut().take() {
            bar.finish_and_clear();
        }
    }
}
