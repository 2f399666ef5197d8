//! What both of `check`'s protocols share with the program they run
//! (`program.rs` once per case, `persistent.rs` once for the whole
//! check): the program started in a process group of its own and stopped
//! with every process it started, and its answer read as `x y id` lines.

use super::{Fragment, SubjectError};
use crate::raster::multisample::SamplePattern;
use std::process::{Child, Command};

/// Starts `command`'s program in a process group of its own, so that
/// [`kill_tree`] can stop what it starts too.
pub(crate) fn in_own_group(command: &mut Command) {
    #[cfg(unix)]
    std::os::unix::process::CommandExt::process_group(command, 0);
    #[cfg(not(unix))]
    let _ = command;
}

/// Stops a program started in a process group of its own (as
/// [`in_own_group`] starts them), with every process it started, and reaps it.
pub(crate) fn kill_tree(child: &mut Child) {
    #[cfg(unix)]
    {
        // `sh`'s own `kill` stops the whole group: the program may have
        // started others (the shell itself runs the command line).
        let _ = Command::new("sh")
            .arg("-c")
            .arg(format!("kill -9 -{} 2>/dev/null", child.id()))
            .status();
    }
    let _ = child.kill();
    let _ = child.wait();
}

/// Reads `x y id` lines. A fourth number is a coverage, allowed and
/// ignored, for a case with one sample per pixel; for a multisampled case
/// (`samples`) it is required, the coverage mask: a whole number from 1
/// to 2^N - 1 whose bit `i` is sample `i` of the N-sample pattern.
pub fn parse_fragments(
    text: &str,
    samples: Option<SamplePattern>,
) -> Result<Vec<Fragment>, SubjectError> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let words: Vec<&str> = line.split_whitespace().collect();
        if words.is_empty() {
            continue;
        }
        let malformed = || SubjectError::Malformed {
            line: i + 1,
            text: line.chars().take(120).collect(),
        };
        let columns = if samples.is_some() { 4..=4 } else { 3..=4 };
        if !columns.contains(&words.len()) {
            return Err(malformed());
        }
        let x = whole(words[0]).ok_or_else(malformed)?;
        let y = whole(words[1]).ok_or_else(malformed)?;
        let id = whole(words[2]).ok_or_else(malformed)?;
        let mask = match samples {
            Some(pattern) => words[3]
                .parse::<u32>()
                .ok()
                .filter(|m| (1..=pattern.full_mask()).contains(m))
                .ok_or_else(malformed)?,
            None if words.len() == 4 && words[3].parse::<f64>().is_err() => return Err(malformed()),
            None => 0,
        };
        out.push(Fragment {
            x,
            y,
            // A negative or huge index names no primitive: judged as such.
            id: u32::try_from(id).unwrap_or(u32::MAX),
            mask,
        });
    }
    Ok(out)
}

/// A whole number; one too large for `i64` saturates (a pixel far off the
/// target).
fn whole(word: &str) -> Option<i64> {
    let digits = word.strip_prefix('-').unwrap_or(word);
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    Some(word.parse::<i64>().unwrap_or(if word.starts_with('-') {
        i64::MIN
    } else {
        i64::MAX
    }))
}
