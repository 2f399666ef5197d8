//! A rasterizer in another program: the `rasterlab check --exec` protocol.
//!
//! For each case the program is started once, through `sh -c`, with the
//! placeholders of its command line replaced:
//!
//! * `{input}`: the path of a file holding the case's primitives: a first
//!   line `# size WxH` (the target), then one primitive per line, a
//!   triangle as six numbers `x0 y0 x1 y1 x2 y2`, a line segment as four
//!   `x0 y0 x1 y1`, in screen coordinates: pixels, x right, y down, pixel
//!   `(i, j)` covering `[i, i + 1) x [j, j + 1)` with its centre at
//!   `(i + 0.5, j + 0.5)` (under the pixel-index line convention the
//!   numbers are whole and name pixels). Other lines starting with `#`
//!   are comments;
//! * `{width}` and `{height}`: the target's size;
//! * `{rule}`: what the check asks for: the fill rule under an exact
//!   check (`top-left`, ...), otherwise the property's name (`watertight`,
//!   `crack-free`, `any`) or the line convention (`midpoint`, `diamond`,
//!   `vulkan`, `pixel-index`);
//! * `{msaa}`: the samples per pixel, 1 unless `check --msaa N` asks for
//!   N on the standard pattern (the input file then says `# msaa N` on its
//!   second line).
//!
//! It prints one fragment per line, `x y id` (`id` the 0-based index of
//! the primitive), in any order; a fourth number (a coverage weight) is
//! allowed and ignored, and so are blank lines. Under `--msaa N` the
//! fourth number is required: the pixel's coverage mask, bit `i` for
//! sample `i`, and a pixel with no sample covered is not printed.
//!
//! With [`Program::persistent`] the program is instead started once and
//! answers case after case on its standard input (the protocol is in
//! `persistent.rs`'s docs and the check guide).
//!
//! The program is not trusted: it is stopped after a time limit (with
//! every process it started, as it runs in a process group of its own),
//! its output is read up to a cap, and a number too large for 64 bits is read
//! as a pixel far off the target (a defect the check reports), not as a
//! crash of the check. Its input files live in a temporary folder removed
//! when the last clone of the [`Program`] is dropped, and on Ctrl-C once
//! `remove_temporary_files_on_interrupt` (with the `cli` feature) has
//! been called.

use super::case::Case;
use super::persistent::Session;
pub(crate) use super::process::parse_fragments;
use super::process::{in_own_group, kill_tree};
use super::{Fragment, Subject, SubjectError};
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::{Arc, Mutex, OnceLock};
use std::time::Duration;
use wait_timeout::ChildExt;

/// An outside program under test.
#[derive(Clone, Debug)]
pub struct Program {
    /// The command line, with placeholders.
    pub command: String,
    /// The value of `{rule}`.
    pub rule: String,
    /// How long one case may run.
    pub timeout: Duration,
    /// The most bytes of output read.
    pub output_cap: usize,
    /// Started once, reading case after case on standard input (the
    /// `--persistent` protocol), instead of once per case: set only by
    /// [`Program::persistent`], which checks the command line for it.
    persistent: bool,
    /// The folder of the input files, made at the first run and shared by
    /// clones (each run writes a file of its own).
    dir: Arc<OnceLock<Result<Folder, String>>>,
    /// The running copy under the persistent protocol (a clone starts
    /// its own).
    session: SessionSlot,
}

/// A running program under the persistent protocol, if started; a clone
/// of it is empty.
#[derive(Default)]
struct SessionSlot(Option<Session>);

impl Clone for SessionSlot {
    fn clone(&self) -> SessionSlot {
        SessionSlot(None)
    }
}

impl std::fmt::Debug for SessionSlot {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(if self.0.is_some() {
            "running"
        } else {
            "not started"
        })
    }
}

/// A temporary folder, removed when dropped and listed for removal on
/// Ctrl-C meanwhile.
#[derive(Debug)]
struct Folder(tempfile::TempDir);

/// The folders of live programs, for the Ctrl-C handler.
fn live_folders() -> &'static Mutex<Vec<PathBuf>> {
    static LIVE: OnceLock<Mutex<Vec<PathBuf>>> = OnceLock::new();
    LIVE.get_or_init(|| Mutex::new(Vec::new()))
}

impl Folder {
    fn new() -> std::io::Result<Folder> {
        let dir = tempfile::Builder::new()
            .prefix("rasterlab-check-")
            .tempdir()?;
        if let Ok(mut live) = live_folders().lock() {
            live.push(dir.path().to_path_buf());
        }
        Ok(Folder(dir))
    }

    fn path(&self) -> &Path {
        self.0.path()
    }
}

impl Drop for Folder {
    fn drop(&mut self) {
        if let Ok(mut live) = live_folders().lock() {
            live.retain(|p| p != self.0.path());
        }
    }
}

/// Removes the input folders of every live [`Program`]: what a program's
/// Ctrl-C handler calls before it exits (the folders of programs dropped
/// normally are removed by their drop).
pub fn remove_live_input_folders() {
    if let Ok(live) = live_folders().lock() {
        for dir in live.iter() {
            let _ = std::fs::remove_dir_all(dir);
        }
    }
}

impl Program {
    /// A program with a 5 s limit and a 64 MiB output cap, writing its
    /// inputs in a fresh folder under the system's temporary folder.
    pub fn new(command: &str, rule: &str) -> Program {
        Program {
            command: command.to_string(),
            rule: rule.to_string(),
            timeout: Duration::from_secs(5),
            output_cap: 64 << 20,
            persistent: false,
            dir: Arc::new(OnceLock::new()),
            session: SessionSlot::default(),
        }
    }

    /// A program started once, answering case after case on its standard
    /// input (see `persistent.rs`); its command line may hold `{rule}`
    /// but not `{input}`, `{width}` or `{height}`, which each case gives.
    pub fn persistent(command: &str, rule: &str) -> crate::Result<Program> {
        if let Some(p) = ["{input}", "{width}", "{height}"]
            .into_iter()
            .find(|p| command.contains(p))
        {
            return Err(crate::Error::InvalidArgument(format!(
                "{p} in a --persistent command: the program reads each case, its size \
                 included, on its standard input"
            )));
        }
        Ok(Program {
            persistent: true,
            ..Program::new(command, rule)
        })
    }

    /// One case through the persistent protocol: a copy is started when
    /// none runs, and one out of step after a failure is stopped.
    fn draw_persistent(&mut self, case: &Case) -> Result<Vec<Fragment>, SubjectError> {
        let session = match &mut self.session.0 {
            Some(s) => s,
            slot => {
                let line = self
                    .command
                    .replace("{rule}", &shell_quote(&self.rule))
                    .replace("{msaa}", &samples(case));
                slot.insert(Session::start(&line)?)
            }
        };
        let answer = session.draw(case, self.timeout, self.output_cap);
        if session.finished {
            self.session.0 = None;
        }
        answer
    }

    /// The folder of the input files, made at the first call.
    fn folder(&self) -> Result<&Path, SubjectError> {
        self.dir
            .get_or_init(|| Folder::new().map_err(|e| e.to_string()))
            .as_ref()
            .map(Folder::path)
            .map_err(|e| SubjectError::Start(format!("cannot make a temporary folder: {e}")))
    }

    /// The command line for one case, its input written to `input`.
    fn command_line(&self, case: &Case, input: &str) -> String {
        self.command
            .replace("{input}", &shell_quote(input))
            .replace("{width}", &case.width.to_string())
            .replace("{height}", &case.height.to_string())
            .replace("{rule}", &shell_quote(&self.rule))
            .replace("{msaa}", &samples(case))
    }
}

/// The value of `{msaa}`: the case's samples per pixel.
fn samples(case: &Case) -> String {
    case.samples.map_or(1, |p| p.count()).to_string()
}

/// Quotes a word for `sh`.
fn shell_quote(word: &str) -> String {
    format!("'{}'", word.replace('\'', r"'\''"))
}

/// A command line as a shell reads it back: each word quoted where it
/// holds more than letters, digits and `-_./=:,+@%` (so that a command a
/// report records can be pasted).
///
/// ```
/// let line = rasterlab::check::shell_words(["check", "--exec", "python3 r.py"]);
/// assert_eq!(line, "check --exec 'python3 r.py'");
/// ```
pub fn shell_words<S: AsRef<str>>(words: impl IntoIterator<Item = S>) -> String {
    words
        .into_iter()
        .map(|w| {
            let w = w.as_ref();
            let plain = !w.is_empty()
                && w.chars()
                    .all(|c| c.is_ascii_alphanumeric() || "-_./=:,+@%".contains(c));
            if plain {
                w.to_string()
            } else {
                shell_quote(w)
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

impl Subject for Program {
    fn draw(&mut self, case: &Case) -> Result<Vec<Fragment>, SubjectError> {
        if self.persistent {
            return self.draw_persistent(case);
        }
        let start = |e: std::io::Error| SubjectError::Start(format!("cannot write the input: {e}"));
        let mut input = tempfile::Builder::new()
            .prefix("input-")
            .suffix(".txt")
            .tempfile_in(self.folder()?)
            .map_err(start)?;
        std::io::Write::write_all(&mut input, case.to_text().as_bytes()).map_err(start)?;
        let line = self.command_line(case, &input.path().to_string_lossy());
        let mut command = Command::new("sh");
        command
            .arg("-c")
            .arg(&line)
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped());
        in_own_group(&mut command);
        let mut child = command
            .spawn()
            .map_err(|e| SubjectError::Start(format!("{line}: {e}")))?;
        let cap = self.output_cap;
        let mut stdout = child.stdout.take().expect("piped");
        let mut stderr = child.stderr.take().expect("piped");
        // Read both streams on their own threads, each up to its cap, so a
        // program that fills a pipe is not blocked and cannot fill memory.
        let out_thread = std::thread::spawn(move || {
            let mut buf = Vec::new();
            let read = (&mut stdout).take(cap as u64 + 1).read_to_end(&mut buf);
            // Drain the rest, so the program is not stuck on a full pipe.
            let _ = std::io::copy(&mut stdout, &mut std::io::sink());
            read.map(|_| buf)
        });
        let err_thread = std::thread::spawn(move || {
            let mut buf = Vec::new();
            let _ = (&mut stderr).take(4096).read_to_end(&mut buf);
            let _ = std::io::copy(&mut stderr, &mut std::io::sink());
            buf
        });
        let status = match child.wait_timeout(self.timeout) {
            Ok(Some(status)) => status,
            Ok(None) | Err(_) => {
                kill_tree(&mut child);
                return Err(SubjectError::Timeout {
                    seconds: self.timeout.as_secs_f64(),
                });
            }
        };
        let out = out_thread
            .join()
            .ok()
            .and_then(Result::ok)
            .unwrap_or_default();
        let err = err_thread.join().unwrap_or_default();
        if !status.success() {
            return Err(SubjectError::Failed {
                status: status.to_string(),
                stderr: String::from_utf8_lossy(&err).trim_end().to_string(),
            });
        }
        if out.len() > cap {
            return Err(SubjectError::TooMuchOutput { bytes: cap });
        }
        parse_fragments(&String::from_utf8_lossy(&out), case.samples)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::multisample::SamplePattern;

    #[test]
    fn output_lines_are_read_strictly_and_huge_numbers_saturate() {
        let parse = |text: &str| parse_fragments(text, None);
        let f = parse("1 2 0\n\n3 4 1 0.5\n").unwrap();
        assert_eq!(f.len(), 2);
        assert_eq!(f[1], Fragment::at(3, 4, 1));
        let f = parse("99999999999999999999999 -5 7\n").unwrap();
        assert_eq!((f[0].x, f[0].y), (i64::MAX, -5));
        assert!(matches!(
            parse("1 2\n"),
            Err(SubjectError::Malformed { line: 1, .. })
        ));
        assert!(parse("1.5 2 0\n").is_err());
        assert!(parse("a b c\n").is_err());
        assert_eq!(parse("1 2 -1\n").unwrap()[0].id, u32::MAX);
        assert_eq!(shell_quote("it's"), r"'it'\''s'");
    }

    #[test]
    fn under_msaa_the_fourth_number_is_a_mask_of_the_pattern() {
        let four = SamplePattern::standard(4).ok();
        let f = parse_fragments("1 2 0 5\n3 4 1 15\n", four).unwrap();
        assert_eq!((f[0].mask, f[1].mask), (5, 15));
        for bad in [
            "1 2 0\n",
            "1 2 0 0\n",
            "1 2 0 16\n",
            "1 2 0 0.5\n",
            "1 2 0 -1\n",
        ] {
            assert!(
                matches!(
                    parse_fragments(bad, four),
                    Err(SubjectError::Malformed { line: 1, .. })
                ),
                "{bad:?}"
            );
        }
    }
}
