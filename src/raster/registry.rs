//! The registry of back-ends, by name.
//!
//! `rasterlab backends` prints [`all_backends`], one per line, as
//! `NAME KIND DESCRIPTION`. The tools find the reference, its fallback and
//! the default back-ends here, by the [`Role`] each back-end's descriptor
//! gives, never by name.
//!
//! A new back-end takes three places: its file (the algorithm and its
//! [`Descriptor`](crate::raster::descriptor::Descriptor)), one `pub mod`
//! line beside the others, and one entry in the lists below.

use crate::error::{Error, Result};
use crate::raster::descriptor::{within_budget, Role, WorkBudget};
use crate::raster::line::{
    bresenham::Bresenham, dda::Dda, diamond::Diamond, diamond_nudged::DiamondNudged,
    direct::Direct, wu::Wu, LineRasterizer,
};
use crate::raster::polygon::{crossings::Crossings, edge_table::EdgeTable, PolygonRasterizer};
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

/// The triangle back-end whose descriptor has `role`.
fn triangle_backend_in(role: Role) -> &'static dyn TriangleRasterizer {
    triangle_backends()
        .iter()
        .copied()
        .find(|b| b.descriptor().role == role)
        .expect("the registry holds a triangle back-end of every role")
}

/// The reference every triangle back-end is compared with: the one whose
/// role is [`Role::Reference`] (`naive`, the course's loop).
pub fn reference_triangle_backend() -> &'static dyn TriangleRasterizer {
    triangle_backend_in(Role::Reference)
}

/// The reference where the reference is beyond a budget: the one whose
/// role is [`Role::Fallback`] (`bbox`).
pub fn fallback_triangle_backend() -> &'static dyn TriangleRasterizer {
    triangle_backend_in(Role::Fallback)
}

/// The reference for drawing `triangles` triangles on `pixels` pixels
/// within `budget`: the [reference](reference_triangle_backend) when it
/// fits, its [fallback](fallback_triangle_backend) when not.
pub fn reference_triangle_backend_within(
    triangles: u64,
    pixels: u64,
    budget: WorkBudget,
) -> &'static dyn TriangleRasterizer {
    let reference = reference_triangle_backend();
    match within_budget(&reference.descriptor(), triangles, pixels, budget) {
        Ok(()) => reference,
        Err(_) => fallback_triangle_backend(),
    }
}

/// The triangle back-end tools draw with when none is named (`scanline`).
pub fn default_triangle_backend() -> &'static dyn TriangleRasterizer {
    triangle_backend_in(Role::Default)
}

/// The triangle back-end called `name`.
pub fn triangle_backend(name: &str) -> Result<&'static dyn TriangleRasterizer> {
    triangle_backends()
        .iter()
        .copied()
        .find(|b| b.name() == name)
        .ok_or_else(|| unknown(name, "triangle"))
}

static LINE_BACKENDS: [&dyn LineRasterizer; 6] =
    [&Direct, &Dda, &Bresenham, &Wu, &Diamond, &DiamondNudged];

/// Every line back-end.
pub fn line_backends() -> &'static [&'static dyn LineRasterizer] {
    &LINE_BACKENDS
}

/// The line back-end tools draw with when none is named (`bresenham`).
pub fn default_line_backend() -> &'static dyn LineRasterizer {
    line_backends()
        .iter()
        .copied()
        .find(|b| b.descriptor().role == Role::Default)
        .expect("the registry holds a default line back-end")
}

/// The line back-end called `name`.
pub fn line_backend(name: &str) -> Result<&'static dyn LineRasterizer> {
    line_backends()
        .iter()
        .copied()
        .find(|b| b.name() == name)
        .ok_or_else(|| unknown(name, "line"))
}

static POLYGON_BACKENDS: [&dyn PolygonRasterizer; 2] = [&EdgeTable, &Crossings];

/// Every polygon back-end (they fill polygons without triangulating them).
pub fn polygon_backends() -> &'static [&'static dyn PolygonRasterizer] {
    &POLYGON_BACKENDS
}

/// The polygon back-end called `name`.
pub fn polygon_backend(name: &str) -> Result<&'static dyn PolygonRasterizer> {
    polygon_backends()
        .iter()
        .copied()
        .find(|b| b.name() == name)
        .ok_or_else(|| unknown(name, "polygon"))
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
        "polygon" => polygon_backends().iter().map(|b| b.name()).collect(),
        _ => all_backends()
            .iter()
            .map(|b| b.name)
            .chain(polygon_backends().iter().map(|b| b.name()))
            .collect(),
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The roles the tools look up are each held by exactly one back-end
    /// of the kind, and names are unique.
    #[test]
    fn every_role_is_held_once_and_every_name_is_unique() {
        let count = |roles: Vec<Role>, role: Role| roles.iter().filter(|r| **r == role).count();
        let triangles: Vec<Role> = triangle_backends()
            .iter()
            .map(|b| b.descriptor().role)
            .collect();
        for role in [Role::Reference, Role::Fallback, Role::Default] {
            assert_eq!(count(triangles.clone(), role), 1, "{role:?}");
        }
        let lines: Vec<Role> = line_backends()
            .iter()
            .map(|b| b.descriptor().role)
            .collect();
        assert_eq!(count(lines, Role::Default), 1);
        let mut names: Vec<&str> = all_backends().iter().map(|b| b.name).collect();
        let all = names.len();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), all, "{names:?}");
    }

    #[test]
    fn the_reference_falls_back_beyond_the_budget() {
        let within = |triangles| {
            reference_triangle_backend_within(triangles, 1000 * 1000, WorkBudget::Report).name()
        };
        assert_eq!(within(50), "naive");
        assert_eq!(within(51), "bbox");
        assert_eq!(default_triangle_backend().name(), "scanline");
        assert_eq!(default_line_backend().name(), "bresenham");
    }
}
