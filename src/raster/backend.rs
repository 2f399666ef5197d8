//! The registry of back-ends, by name.
//!
//! `rasterlab backends` prints [`all_backends`], one per line, as
//! `NAME KIND DESCRIPTION`.

use crate::error::{Error, Result};
use crate::raster::line::{
    bresenham::Bresenham, dda::Dda, diamond::Diamond, direct::Direct, wu::Wu, LineRasterizer,
};
use crate::raster::triangle::{
    bbox::BoundingBox, incremental::Incremental, naive::Naive, scanline::Scanline, tiled::Tiled,
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

static TRIANGLE_BACKENDS: [&dyn TriangleRasterizer; 5] =
    [&Naive, &BoundingBox, &Scanline, &Incremental, &Tiled];

/// Every triangle back-end; `naive`, the reference, first.
pub fn triangle_backends() -> &'static [&'static dyn TriangleRasterizer] {
    &TRIANGLE_BACKENDS
}

/// The reference every triangle back-end is compared with: the one that
/// says it [is](TriangleRasterizer::is_reference) (`naive`).
pub fn reference_triangle_backend() -> &'static dyn TriangleRasterizer {
    triangle_backends()
        .iter()
        .copied()
        .find(|b| b.is_reference())
        .expect("the registry holds the reference back-end")
}

/// The triangle back-end called `name`.
pub fn triangle_backend(name: &str) -> Result<&'static dyn TriangleRasterizer> {
    triangle_backends()
        .iter()
        .copied()
        .find(|b| b.name() == name)
        .ok_or_else(|| unknown(name, "triangle"))
}

static LINE_BACKENDS: [&dyn LineRasterizer; 5] = [&Direct, &Dda, &Bresenham, &Wu, &Diamond];

/// Every line back-end.
pub fn line_backends() -> &'static [&'static dyn LineRasterizer] {
    &LINE_BACKENDS
}

/// The line back-end called `name`.
pub fn line_backend(name: &str) -> Result<&'static dyn LineRasterizer> {
    line_backends()
        .iter()
        .copied()
        .find(|b| b.name() == name)
        .ok_or_else(|| unknown(name, "line"))
}

/// A back-end of either kind.
#[derive(Copy, Clone)]
pub enum Backend {
    /// A triangle back-end.
    Triangle(&'static dyn TriangleRasterizer),
    /// A line back-end.
    Line(&'static dyn LineRasterizer),
}

impl fmt::Debug for Backend {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Backend::Triangle(b) => write!(f, "Triangle({})", b.name()),
            Backend::Line(b) => write!(f, "Line({})", b.name()),
        }
    }
}

/// The back-end of either kind called `name`.
pub fn backend(name: &str) -> Result<Backend> {
    triangle_backend(name)
        .map(Backend::Triangle)
        .or_else(|_| line_backend(name).map(Backend::Line))
        .map_err(|_| unknown(name, "rasterizer"))
}

fn unknown(name: &str, kind: &'static str) -> Error {
    let names: Vec<&str> = match kind {
        "triangle" => triangle_backends().iter().map(|b| b.name()).collect(),
        "line" => line_backends().iter().map(|b| b.name()).collect(),
        _ => all_backends().iter().map(|b| b.name).collect(),
    };
    Error::UnknownBackend {
        name: name.to_string(),
        kind,
        known: names.join(", "),
    }
}

/// Every back-end of every kind, triangles first.
pub fn all_backends() -> Vec<BackendInfo> {
    let triangles = triangle_backends().iter().map(|b| BackendInfo {
        name: b.name(),
        kind: BackendKind::Triangle,
        description: b.description(),
    });
    let lines = line_backends().iter().map(|b| BackendInfo {
        name: b.name(),
        kind: BackendKind::Line,
        description: b.description(),
    });
    triangles.chain(lines).collect()
}
