//! Every command the README and `docs/*.md` show runs: each line of a
//! fenced `sh` block, and each `$ ` line of a fenced `console` block, is
//! run by `sh` with the built `rasterlab` first on the `PATH`, in a fresh
//! folder per page holding links to `assets/` and `examples/`, and must
//! exit with the status expected of it (0 unless [`EXPECTED_STATUS`] says
//! otherwise). `cargo run --release -- ` stands for `rasterlab `.
//!
//! A command that needs an optional part (Mesa, Chromium, the Python
//! packages), runs for minutes (the benchmarks, the survey) or does not
//! stop by itself (the lab's server) is in [`SKIPPED`] with the reason;
//! `sh docs/regenerate.sh` runs those. A command that is neither run nor
//! skipped cannot exist, and a skip entry that no longer matches a
//! command fails the test, so the list stays the list of what is shown.
//! The outputs pasted under the commands are not compared here: the
//! regeneration script rewrites them.
//!
//! The relative links of the same pages are checked too: every file a
//! link names exists, and every `#anchor` is a heading of its page.

mod common;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Duration;
use wait_timeout::ChildExt;

/// Commands not run here, by the start of their text (whitespace
/// collapsed), each with the reason.
const SKIPPED: &[(&str, &str)] = &[
    (
        "cargo test --release",
        "the test suite itself, which runs this test",
    ),
    (
        "cargo install --path .",
        "installs into the user's cargo folder; the test runs the binary cargo built",
    ),
    (
        "rasterlab lab",
        "the lab's server runs until Ctrl-C (tests/lab_browser.rs drives it)",
    ),
    (
        "rasterlab bench",
        "a benchmark: minutes, and its figures are timings (docs/regenerate.sh runs it)",
    ),
    (
        "cargo bench",
        "a benchmark: minutes, with Mesa and the Stanford data as optional parts",
    ),
    (
        "sh examples/adapters/survey_polygons.sh",
        "the polygon survey: the Python packages, seven fillers on 150 cases under two rules",
    ),
    (
        "sh examples/adapters/survey.sh",
        "the survey: the Python packages and Mesa, every rasterizer on 150 cases, minutes",
    ),
    (
        "rasterlab check --kind lines --convention any --keep-going --persistent --exec \"python3 examples/adapters/skimage_line.py",
        "part of the line drawers' survey: scikit-image from pip",
    ),
    (
        "rasterlab check --rule bottom-left --cases 300 --timeout 60 --exec \"target/release/examples/peer_adapters opengl-wide",
        "Mesa's llvmpipe through the wide viewport (tests/llvmpipe.rs checks its failure)",
    ),
];

/// Commands that exit with another status than 0, by the start of their
/// text (whitespace collapsed).
const EXPECTED_STATUS: &[(&str, i32)] = &[
    // rasterlab's render without the depth test: the image check fails it.
    (
        "rasterlab check --image --exec \"rasterlab render --scene {scene} --size {size} {settings} --depth-test always",
        1,
    ),
    // The polygon filler asked to fill by the other rule.
    (
        "rasterlab check --kind polygons --fill even-odd --persistent --exec \"python3 examples/student/polygon_fill.py nonzero",
        1,
    ),
    // The student's rasterizer double draws: the check fails it.
    (
        "rasterlab check --rule watertight --persistent --exec \"python3 examples/student/rasterizer.py",
        1,
    ),
    // The starters as shipped are the course's naive loop: they fail.
    (
        "rasterlab check --persistent --exec \"python3 examples/starters/python/rasterizer.py",
        1,
    ),
    ("rasterlab check --persistent --exec \"./rasterizer", 1),
    // The multisampler asked to decide every sample at the centre.
    (
        "rasterlab check --msaa 4 --persistent --exec \"python3 examples/student/multisample.py {msaa} centre",
        1,
    ),
    (
        "rasterlab check --persistent --exec \"node examples/starters/js/rasterizer.js",
        1,
    ),
    (
        "rasterlab check --kind lines --convention pixel-index-left-to-right --persistent",
        1,
    ),
];

/// The longest a command may run.
const TIMEOUT: Duration = Duration::from_secs(120);

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The README and every page of `docs/`, as paths relative to the root.
fn pages() -> Vec<PathBuf> {
    let mut pages = vec![PathBuf::from("README.md")];
    let mut docs: Vec<_> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .map(|p| p.strip_prefix(root()).unwrap().to_path_buf())
        .collect();
    docs.sort();
    pages.extend(docs);
    pages
}

/// A command as a page shows it.
#[derive(Debug, Clone)]
struct Shown {
    page: PathBuf,
    line: usize,
    text: String,
}

impl Shown {
    /// The text as `sh` runs it: `cargo run --release -- ` at the start
    /// of a line is `rasterlab `.
    fn runnable(&self) -> String {
        self.text
            .lines()
            .map(
                |line| match line.trim_start().strip_prefix("cargo run --release -- ") {
                    Some(rest) => format!("rasterlab {rest}"),
                    None => line.to_string(),
                },
            )
            .collect::<Vec<_>>()
            .join("\n")
    }

    /// The runnable text with runs of whitespace as one space, as the skip
    /// list and the expected statuses name commands.
    fn normalized(&self) -> String {
        self.runnable()
            .replace("\\\n", " ")
            .split_whitespace()
            .collect::<Vec<_>>()
            .join(" ")
    }
}

/// The commands of one page: the lines of its `sh` blocks (a line ending
/// in `\` continues on the next; a `for` runs to its `done`; blank lines
/// and comments are not commands) and the `$ ` lines of its `console`
/// blocks.
fn shown_commands(page: &Path, text: &str) -> Vec<Shown> {
    let mut shown = Vec::new();
    let mut block: Option<&str> = None;
    let mut pending: Option<Shown> = None;
    let mut depth = 0usize;
    for (i, line) in text.lines().enumerate() {
        if let Some(fence) = line.strip_prefix("```") {
            block = match block {
                None => Some(fence.trim()),
                Some(_) => None,
            };
            assert!(
                pending.is_none(),
                "{}:{}: a command runs past its block",
                page.display(),
                i + 1
            );
            continue;
        }
        let body = match block {
            Some("sh") if pending.is_some() => Some(line),
            Some("sh") => {
                let trimmed = line.trim();
                (!trimmed.is_empty() && !trimmed.starts_with('#')).then_some(line)
            }
            Some("console") if pending.is_some() => Some(line),
            Some("console") => line.strip_prefix("$ "),
            _ => None,
        };
        let Some(body) = body else { continue };
        let command = pending.get_or_insert_with(|| Shown {
            page: page.to_path_buf(),
            line: i + 1,
            text: String::new(),
        });
        match body.split_whitespace().next() {
            Some("for" | "while") => depth += 1,
            Some("done") => depth = depth.saturating_sub(1),
            _ => {}
        }
        let continued = body.trim_end().ends_with('\\');
        command.text.push_str(body.trim_end());
        command.text.push('\n');
        if !continued && depth == 0 {
            shown.push(pending.take().unwrap());
        }
    }
    assert!(
        block.is_none(),
        "{}: a fenced block is not closed",
        page.display()
    );
    shown
}

fn skip_reason(command: &str) -> Option<&'static str> {
    SKIPPED
        .iter()
        .find(|(start, _)| command.starts_with(start))
        .map(|(_, reason)| *reason)
}

fn expected_status(command: &str) -> i32 {
    EXPECTED_STATUS
        .iter()
        .find(|(start, _)| command.starts_with(start))
        .map_or(0, |(_, status)| *status)
}

/// A folder to run a page's commands in, with the repository's inputs.
fn workspace() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for name in ["assets", "examples"] {
        std::os::unix::fs::symlink(root().join(name), dir.path().join(name)).unwrap();
    }
    dir
}

/// Runs `script` by `sh` in `dir`; `Err` says how it went wrong. `command`
/// is its normalized text, which says the status expected.
fn run(script: &str, command: &str, dir: &Path) -> Result<(), String> {
    let bin = Path::new(env!("CARGO_BIN_EXE_rasterlab")).parent().unwrap();
    let path = std::env::var_os("PATH").unwrap_or_default();
    let mut paths = vec![bin.to_path_buf()];
    paths.extend(std::env::split_paths(&path));
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(script)
        .current_dir(dir)
        .env("PATH", std::env::join_paths(paths).unwrap())
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("sh could not start: {e}"))?;
    let stderr = child.stderr.take().unwrap();
    let reader = std::thread::spawn(move || std::io::read_to_string(stderr).unwrap_or_default());
    let status = match child.wait_timeout(TIMEOUT).unwrap() {
        Some(status) => status,
        None => {
            let _ = child.kill();
            let _ = child.wait();
            return Err(format!("still running after {} s", TIMEOUT.as_secs()));
        }
    };
    let stderr = reader.join().unwrap();
    let expected = expected_status(command);
    match status.code() {
        Some(code) if code == expected => Ok(()),
        code => Err(format!(
            "exit status {code:?}, expected {expected}; its standard error:\n{}",
            stderr
                .lines()
                .rev()
                .take(20)
                .collect::<Vec<_>>()
                .into_iter()
                .rev()
                .collect::<Vec<_>>()
                .join("\n")
        )),
    }
}

fn python3_available() -> bool {
    Command::new("python3")
        .arg("--version")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

#[test]
fn every_command_the_docs_show_runs_or_is_skipped_with_a_reason() {
    let python = python3_available();
    let mut failures = Vec::new();
    let mut skips_used = BTreeSet::new();
    let mut ran = 0;
    for page in pages() {
        let text = std::fs::read_to_string(root().join(&page)).unwrap();
        let dir = workspace();
        for shown in shown_commands(&page, &text) {
            let command = shown.normalized();
            if let Some(reason) = skip_reason(&command) {
                skips_used.insert(reason);
                continue;
            }
            if command.contains("python3 ") && !python {
                common::part_missing(&command, "python3", "RASTERLAB_REQUIRE_PYTHON");
                continue;
            }
            ran += 1;
            if let Err(why) = run(&shown.runnable(), &command, dir.path()) {
                failures.push(format!(
                    "{}:{}: {command}\n{why}",
                    shown.page.display(),
                    shown.line
                ));
            }
        }
    }
    let stale: Vec<_> = SKIPPED
        .iter()
        .filter(|(_, reason)| !skips_used.contains(reason))
        .map(|(start, _)| *start)
        .collect();
    assert!(
        stale.is_empty(),
        "skip entries that match no command of the docs (remove them): {stale:?}"
    );
    eprintln!(
        "docs_commands: {ran} commands run, {} skip entries used",
        skips_used.len()
    );
    assert!(ran >= 20, "only {ran} commands found in the docs");
    assert!(
        failures.is_empty(),
        "{} of {ran} commands failed:\n\n{}",
        failures.len(),
        failures.join("\n\n")
    );
}

#[test]
fn the_commands_are_found_as_the_pages_write_them() {
    let page = "```sh\ncargo run --release -- demo      # the main job\n\nfor s in a b; do\n  rasterlab x \\\n    --y \"$s\"\ndone\n```\n\n```console\n$ rasterlab explain --backend wu 0 0 7 3\nwu ...\n$ printf 'a' > b.txt\n```\n\n```text\nrasterlab not a command\n```\n";
    let shown: Vec<_> = shown_commands(Path::new("p.md"), page)
        .iter()
        .map(Shown::normalized)
        .collect();
    assert_eq!(
        shown,
        [
            "rasterlab demo # the main job",
            "for s in a b; do rasterlab x --y \"$s\" done",
            "rasterlab explain --backend wu 0 0 7 3",
            "printf 'a' > b.txt",
        ]
    );
    assert_eq!(skip_reason("cargo test --release"), Some(SKIPPED[0].1));
    assert_eq!(expected_status("rasterlab backends"), 0);
}

/// The anchor GitHub gives a heading: lower case, punctuation but `-` and
/// `_` dropped, spaces as `-`.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || *c == '-' || *c == '_' || *c == ' ')
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

fn anchors(text: &str) -> BTreeSet<String> {
    let mut inside = false;
    let mut out = BTreeSet::new();
    for line in text.lines() {
        if line.starts_with("```") {
            inside = !inside;
        } else if !inside && line.starts_with('#') {
            out.insert(anchor(line.trim_start_matches('#')));
        }
    }
    out
}

#[test]
fn every_relative_link_of_the_docs_leads_somewhere() {
    let mut broken = Vec::new();
    let mut pages = pages();
    pages.push(PathBuf::from("CHANGELOG.md"));
    for page in pages {
        let text = std::fs::read_to_string(root().join(&page)).unwrap();
        let mut inside = false;
        for (i, line) in text.lines().enumerate() {
            if line.starts_with("```") {
                inside = !inside;
                continue;
            }
            if inside {
                continue;
            }
            for link in line.split("](").skip(1) {
                let Some(end) = link.find(')') else { continue };
                let target = &link[..end];
                if target.contains("://") || target.starts_with("mailto:") {
                    continue;
                }
                let (file, fragment) = target.split_once('#').unwrap_or((target, ""));
                let path = if file.is_empty() {
                    root().join(&page)
                } else {
                    root().join(page.parent().unwrap()).join(file)
                };
                if !path.exists() {
                    broken.push(format!(
                        "{}:{}: {target}: no such file",
                        page.display(),
                        i + 1
                    ));
                } else if !fragment.is_empty() && path.extension().is_some_and(|e| e == "md") {
                    let headings = anchors(&std::fs::read_to_string(&path).unwrap());
                    if !headings.contains(fragment) {
                        broken.push(format!(
                            "{}:{}: {target}: no such heading",
                            page.display(),
                            i + 1
                        ));
                    }
                }
            }
        }
    }
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}
