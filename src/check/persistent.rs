//! A rasterizer started once, answering case after case on its standard
//! input: the `rasterlab check --persistent` protocol.
//!
//! Starting a program costs more than most cases do (an interpreter and
//! the libraries it imports start far more slowly than a case is drawn;
//! docs/check.md gives the figures), so a check that starts the program
//! once per case spends its time starting programs. Under this protocol
//! the program is started once, through `sh -c`, with `{rule}` and
//! `{msaa}` in its command line replaced (there is no `{input}`,
//! `{width}` or `{height}`: each case says its own), and then:
//!
//! 1. rasterlab writes a case on the program's standard input, exactly as
//!    the per-case protocol's input file holds it (a first line
//!    `# size WxH`, under `--msaa N` a line `# msaa N`, then one
//!    primitive per line; other `#` lines are comments), then a line
//!    `end`;
//! 2. the program answers on its standard output with one fragment per
//!    line, `x y id` (under `--msaa N`, `x y id mask`), as under the
//!    per-case protocol, then a line `end`,
//!    and flushes; or, when it cannot draw the case, with one line
//!    `error MESSAGE` instead;
//! 3. and so on, until its standard input closes: then it exits.
//!
//! What it writes on standard error is kept (its last 4 KiB) and shown
//! when it fails. A program that exits, prints more than the output cap,
//! or takes longer than the time limit on a case is stopped (with every
//! process it started), the case is reported with its input as under the
//! per-case protocol, and the next case starts a fresh copy. Shrinking a
//! counterexample reuses the running program.

use super::case::Case;
use super::process::{in_own_group, kill_tree, parse_fragments};
use super::{Fragment, SubjectError};
use std::io::{BufRead, BufReader, Read, Write};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError, Sender};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// The most bytes of one output line kept; a longer line is cut into
/// pieces (and read as malformed).
const MAX_LINE: u64 = 4096;
/// The most bytes of standard error kept (the last ones).
const STDERR_KEPT: usize = 4096;

/// What the reader thread sees on the program's standard output.
enum Output {
    /// One line, without its line end.
    Line(String),
    /// The output closed: the program exited (or closed it).
    Closed,
}

/// One running copy of the program.
pub(crate) struct Session {
    child: Child,
    /// Cases to the writer thread, which writes them on standard input
    /// (so that a program that does not read cannot block the check).
    input: Option<Sender<Vec<u8>>>,
    /// Lines from the reader thread (behind a lock only so that a
    /// [`Program`](super::Program) not yet started can be shared).
    output: Mutex<Receiver<Output>>,
    stderr: Arc<Mutex<Vec<u8>>>,
    /// Cases answered so far.
    answered: u32,
    /// Out of step with the protocol (it exited, hung or printed too
    /// much): the caller drops the session and starts a fresh one.
    pub(crate) finished: bool,
}

impl Session {
    /// Starts `command` through `sh -c`, in a process group of its own.
    pub(crate) fn start(command: &str) -> Result<Session, SubjectError> {
        let mut cmd = Command::new("sh");
        cmd.arg("-c")
            .arg(command)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped());
        in_own_group(&mut cmd);
        let mut child = cmd
            .spawn()
            .map_err(|e| SubjectError::Start(format!("{command}: {e}")))?;
        let mut stdin = child.stdin.take().expect("piped");
        let stdout = child.stdout.take().expect("piped");
        let mut stderr = child.stderr.take().expect("piped");
        let (input, cases) = mpsc::channel::<Vec<u8>>();
        std::thread::spawn(move || {
            for bytes in cases {
                if stdin
                    .write_all(&bytes)
                    .and_then(|()| stdin.flush())
                    .is_err()
                {
                    break;
                }
            }
        });
        let (lines, output) = mpsc::channel();
        std::thread::spawn(move || {
            let mut reader = BufReader::new(stdout);
            let mut buf = Vec::new();
            loop {
                buf.clear();
                match (&mut reader).take(MAX_LINE).read_until(b'\n', &mut buf) {
                    Ok(0) | Err(_) => {
                        let _ = lines.send(Output::Closed);
                        break;
                    }
                    Ok(_) => {
                        let text = String::from_utf8_lossy(&buf);
                        let text = text.trim_end_matches(['\n', '\r']).to_string();
                        if lines.send(Output::Line(text)).is_err() {
                            break;
                        }
                    }
                }
            }
        });
        let kept = Arc::new(Mutex::new(Vec::new()));
        let sink = Arc::clone(&kept);
        std::thread::spawn(move || {
            let mut chunk = [0u8; 1024];
            while let Ok(n) = stderr.read(&mut chunk) {
                if n == 0 {
                    break;
                }
                if let Ok(mut kept) = sink.lock() {
                    kept.extend_from_slice(&chunk[..n]);
                    let extra = kept.len().saturating_sub(STDERR_KEPT);
                    kept.drain(..extra);
                }
            }
        });
        Ok(Session {
            child,
            input: Some(input),
            output: Mutex::new(output),
            stderr: kept,
            answered: 0,
            finished: false,
        })
    }

    /// Sends `case` and reads the answer, within `timeout` and `cap`
    /// bytes. After a timeout, an exit or too much output the session is
    /// [`finished`](Session::finished).
    pub(crate) fn draw(
        &mut self,
        case: &Case,
        timeout: Duration,
        cap: usize,
    ) -> Result<Vec<Fragment>, SubjectError> {
        let deadline = Instant::now() + timeout;
        let mut text = case.to_text();
        text.push_str("end\n");
        if let Some(input) = &self.input {
            // A send fails only when the writer has stopped: the program
            // closed its input, which the read below reports.
            let _ = input.send(text.into_bytes());
        }
        let mut answer = String::new();
        loop {
            let wait = deadline.saturating_duration_since(Instant::now());
            let next = match self.output.lock() {
                Ok(output) => output.recv_timeout(wait),
                Err(_) => Err(RecvTimeoutError::Disconnected),
            };
            match next {
                Ok(Output::Line(line)) => {
                    let word = line.trim();
                    if word == "end" {
                        self.answered += 1;
                        return parse_fragments(&answer, case.samples);
                    }
                    if word == "error" || word.starts_with("error ") {
                        self.answered += 1;
                        // What it wrote on standard error for this case.
                        let stderr = self.take_stderr();
                        return Err(SubjectError::Refused {
                            message: word["error".len()..].trim().to_string(),
                            stderr,
                        });
                    }
                    answer.push_str(&line);
                    answer.push('\n');
                    if answer.len() > cap {
                        self.finished = true;
                        return Err(SubjectError::TooMuchOutput { bytes: cap });
                    }
                }
                Ok(Output::Closed) | Err(RecvTimeoutError::Disconnected) => {
                    self.finished = true;
                    return Err(self.exited());
                }
                Err(RecvTimeoutError::Timeout) => {
                    self.finished = true;
                    return Err(SubjectError::Timeout {
                        seconds: timeout.as_secs_f64(),
                    });
                }
            }
        }
    }

    /// What the program has written on standard error since it was last
    /// taken (its last 4 KiB), emptied, after a moment for the reader of
    /// standard error to catch up.
    fn take_stderr(&self) -> String {
        std::thread::sleep(Duration::from_millis(20));
        self.stderr
            .lock()
            .map(|mut kept| {
                let text = String::from_utf8_lossy(&kept).trim_end().to_string();
                kept.clear();
                text
            })
            .unwrap_or_default()
    }

    /// The error for a program whose output closed before its answer's
    /// `end`.
    fn exited(&mut self) -> SubjectError {
        // Give it a moment to exit, so that its status can be told.
        let deadline = Instant::now() + Duration::from_millis(500);
        let status = loop {
            match self.child.try_wait() {
                Ok(Some(status)) => break Some(status),
                Ok(None) if Instant::now() < deadline => {
                    std::thread::sleep(Duration::from_millis(5))
                }
                _ => break None,
            }
        };
        let stderr = self.take_stderr();
        let mut how = match status {
            Some(s) => format!("it exited before its answer's `end` line, {s}"),
            None => "it closed its output before its answer's `end` line".to_string(),
        };
        if self.answered > 0 && status.is_some_and(|s| s.success()) {
            how.push_str(&format!(
                ", after answering {} case(s): under --persistent a program reads \
                 case after case until its input closes",
                self.answered
            ));
        }
        SubjectError::Failed {
            status: how,
            stderr,
        }
    }
}

impl Drop for Session {
    fn drop(&mut self) {
        // Closing its input asks the program to exit; whatever is still
        // running a moment later is stopped.
        self.input = None;
        let deadline = Instant::now() + Duration::from_millis(200);
        while Instant::now() < deadline {
            if let Ok(Some(_)) = self.child.try_wait() {
                return;
            }
            std::thread::sleep(Duration::from_millis(2));
        }
        kill_tree(&mut self.child);
    }
}
