//! The library's error type.
//!
//! Every failure mode of bad input (NaN, infinities, coordinates beyond the
//! guard band, `w <= 0`, bad indices, malformed files, unknown back-end
//! names, zero-size targets) is a variant here. Nothing in the library
//! panics on bad input; the CLI prints these errors and exits non-zero.

use std::path::PathBuf;

/// Result alias used throughout the crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Everything that can go wrong in rasterlab.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// A coordinate was NaN or infinite.
    #[error("coordinate {value} is not a finite number")]
    NonFinite {
        /// The offending value.
        value: f64,
    },
    /// A screen coordinate lies outside the guard band, so its edge
    /// functions could not be evaluated exactly.
    #[error("coordinate {value} px is outside the guard band (|coordinate| < {limit} px)")]
    OutsideGuardBand {
        /// The offending value, in pixels.
        value: f64,
        /// The guard band half-width, in pixels.
        limit: i64,
    },
    /// A render target of zero or excessive size was requested.
    #[error(
        "target size {width}x{height} is invalid: both sides must be between 1 and {max} pixels"
    )]
    InvalidTargetSize {
        /// Requested width.
        width: u64,
        /// Requested height.
        height: u64,
        /// Largest allowed side.
        max: u32,
    },
    /// A texture of zero or excessive size, whose texels do not fill it,
    /// or whose mip levels break the pyramid rule.
    #[error("texture {width}x{height} is invalid: {reason}")]
    InvalidTexture {
        /// Width of level 0.
        width: u64,
        /// Height of level 0.
        height: u64,
        /// What is wrong.
        reason: String,
    },
    /// No back-end of that name (and kind) exists.
    #[error("unknown {kind} back-end `{name}` (known: {known})")]
    UnknownBackend {
        /// The name asked for.
        name: String,
        /// `triangle`, `line`, `polygon`, or `rasterizer` when any would do.
        kind: &'static str,
        /// Comma-separated list of the names that exist.
        known: String,
    },
    /// A named option (fill rule, depth test, ...) was not recognised.
    #[error("unknown {what} `{name}` (known: {known})")]
    UnknownName {
        /// What kind of name it was.
        what: &'static str,
        /// The name given.
        name: String,
        /// The names that exist.
        known: String,
    },
    /// An index referred to a vertex that does not exist.
    #[error("index {index} is out of range for {count} vertices")]
    IndexOutOfRange {
        /// The bad index.
        index: u64,
        /// How many vertices there are.
        count: usize,
    },
    /// A vertex array's length is not a whole number of elements.
    #[error("{what}: {len} values do not make whole {unit}s")]
    BadArrayLength {
        /// What was being assembled.
        what: &'static str,
        /// Number of values given.
        len: usize,
        /// The unit (vertex, triangle, ...).
        unit: &'static str,
    },
    /// A mesh or scene with nothing in it.
    #[error("{0} is empty")]
    Empty(String),
    /// A clip-space vertex with `w <= 0` reached a stage that needs `w > 0`.
    #[error("vertex has w = {w}, but w must be > 0 after clipping")]
    NonPositiveW {
        /// The offending w.
        w: f32,
    },
    /// A file could not be parsed; names the file and, where known, the line.
    #[error("{}{}: {message}", path.display(), line.map(|l| format!(":{l}")).unwrap_or_default())]
    Parse {
        /// The file.
        path: PathBuf,
        /// 1-based line number, where the format has lines.
        line: Option<usize>,
        /// What was wrong.
        message: String,
    },
    /// Reading a file failed.
    #[error("{}: {message}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's message.
        message: String,
    },
    /// Writing an output (a file, a directory, standard output) failed.
    #[error("cannot write {}: {message}", path.display())]
    Write {
        /// The file or directory (`<stdout>` for standard output).
        path: PathBuf,
        /// What went wrong.
        message: String,
        /// True when the reader went away (a closed pipe): the CLI stops
        /// without a message, as `head` expects.
        closed: bool,
    },
    /// The work asked for is beyond a bound; the message gives the estimate.
    #[error("{0}")]
    TooMuchWork(String),
    /// Results that should agree do not (back-ends in the demo, a checked
    /// rasterizer against the rules).
    #[error("{0}")]
    Mismatch(String),
    /// An argument had a value the operation cannot use.
    #[error("{0}")]
    InvalidArgument(String),
}

impl Error {
    /// Wraps an I/O error with the path it happened on.
    pub fn io(path: impl Into<PathBuf>, err: &std::io::Error) -> Self {
        Error::Io {
            path: path.into(),
            message: err.to_string(),
        }
    }

    /// Errors with [`Error::NonFinite`] on the first value that is NaN or
    /// infinite.
    pub fn check_finite(values: impl IntoIterator<Item = f32>) -> Result<()> {
        match values.into_iter().find(|v| !v.is_finite()) {
            Some(v) => Err(Error::NonFinite {
                value: f64::from(v),
            }),
            None => Ok(()),
        }
    }

    /// Errors with [`Error::IndexOutOfRange`] on the first index that does
    /// not name one of `count` vertices.
    pub fn check_indices<'a>(
        indices: impl IntoIterator<Item = &'a u32>,
        count: usize,
    ) -> Result<()> {
        match indices.into_iter().find(|&&i| i as usize >= count) {
            Some(&index) => Err(Error::IndexOutOfRange {
                index: u64::from(index),
                count,
            }),
            None => Ok(()),
        }
    }

    /// Wraps an error met while writing `path`.
    pub fn write(path: impl Into<PathBuf>, err: &std::io::Error) -> Self {
        Error::Write {
            path: path.into(),
            message: err.to_string(),
            closed: err.kind() == std::io::ErrorKind::BrokenPipe,
        }
    }

    /// The exit status the command line gives this error (the README's
    /// table): 1 a mismatch found, 2 bad input or arguments, 3 an output
    /// that cannot be written, 4 work refused as too large.
    pub fn exit_code(&self) -> u8 {
        match self {
            Error::Mismatch(_) => 1,
            Error::Write { .. } => 3,
            Error::TooMuchWork(_) => 4,
            _ => 2,
        }
    }

    /// Attaches a file and line to an error found while reading that line.
    pub fn at_line(self, path: impl Into<PathBuf>, line: usize) -> Self {
        Error::Parse {
            path: path.into(),
            line: Some(line),
            message: self.to_string(),
        }
    }
}
