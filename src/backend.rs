//! The registry of back-ends, by name.
//!
//! `rasterlab backends` prints [`all_backends`], one per line, as
//! `NAME KIND DESCRIPTION`.

use crate::error::{Error, Result};
use crate::triangle::{
    bbox::BoundingBox, incremental::Incremental, naive::Naive, scanline::Scanline,
    TriangleRasterizer,
};
use std::fmt;

/// Which kind of primitive a back-end draws.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum BackendKind {
    /// Filled triangles.
    Triangle,
    /// Line segments.
    Line,
}

impl fmt::Display for BackendKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            BackendKind::Triangle => "triangle",
            BackendKind::Line => "line",
        })
    }
}

/// A back-end's name, kind and description.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct BackendInfo {
    /// Command-line name.
    pub name: &'static str,
    /// Triangle or line.
    pub kind: BackendKind,
    /// One-line description.
    pub description: &'static str,
}

static TRIANGLE_BACKENDS: [&dyn TriangleRasterizer; 4] =
    [&Naive, &BoundingBox, &Scanline, &Incremental];

/// Every triangle back-end; `naive`, the reference, first.
pub fn triangle_backends() -> &'static [&'static dyn TriangleRasterizer] {
    &TRIANGLE_BACKENDS
}

/// The triangle back-end called `name`.
pub fn triangle_backend(name: &str) -> Result<&'static dyn TriangleRasterizer> {
    triangle_backends()
        .iter()
        .copied()
        .find(|b| b.name() == name)
        .ok_or_else(|| Error::UnknownBackend {
            name: name.to_string(),
            kind: "triangle",
            known: triangle_backends()
                .iter()
                .map(|b| b.name())
                .collect::<Vec<_>>()
                .join(", "),
        })
}

/// Every back-end of every kind, triangles first.
pub fn all_backends() -> Vec<BackendInfo> {
    triangle_backends()
        .iter()
        .map(|b| BackendInfo {
            name: b.name(),
            kind: BackendKind::Triangle,
            description: b.description(),
        })
        .collect()
}
