//! Multisampling: a triangle's coverage at several sample points per
//! pixel, on the standard patterns.
//!
//! With one sample a pixel is drawn or not, which is what makes edges
//! stair-step. Multisample anti-aliasing (MSAA) takes `N` samples per
//! pixel at fixed points and records, per pixel and triangle, which of
//! them the triangle covers: a **coverage mask** of `N` bits, bit `i` for
//! sample `i`. The APIs fix the points. Direct3D 11's standard patterns
//! (`D3D11_STANDARD_MULTISAMPLE_PATTERN`) for 1, 2, 4, 8 and 16 samples
//! are Vulkan's standard sample locations (where the device's
//! `standardSampleLocations` is true) and the table Mesa uses
//! (`u_sample_positions.c`). In 1/16 pixel from the pixel centre, y down,
//! the 4-sample pattern is
//!
//! ```text
//!        x:  -8  -6  -4  -2   0   2   4   6   8
//!   y = -6           .   0   .                        sample 0 (-2, -6)
//!   y = -2           .   .   .   .   .   1            sample 1 ( 6, -2)
//!   y =  2       2   .   .   .   .                    sample 2 (-6,  2)
//!   y =  6                   .   3                    sample 3 ( 2,  6)
//! ```
//!
//! ([`SamplePattern::standard`] holds all five tables.) OpenGL gives the
//! same numbers in window coordinates, whose y runs up; seen on the
//! screen, y down, its pattern is the standard one mirrored
//! ([`SamplePattern::mirrored_y`]).
//!
//! **The rule per sample.** A sample is decided exactly as a pixel centre
//! is: the snapped vertices, the exact edge functions, and the fill rule's
//! tie-breaking (a sample exactly on an edge belongs to the triangle whose
//! edge owns its ties). The offsets are whole multiples of 1/16 px, so of
//! the 1/256 px snapping grid: moving the triangle by `-offset` moves
//! sample `i` onto the pixel centre *exactly*. So [`masks_of`] runs the
//! back-end once per sample on the triangles moved that way, each pass
//! deciding one bit of every mask with the back-end's own walk, keeping
//! each edge's tie ownership as the triangle in place has it (the
//! off-screen point rule decides it by the point's side of the edge,
//! which a move must not change). Every back-end gives the same masks,
//! and the same as [`reference_masks`], which tests every sample of every
//! pixel of each triangle's box directly.
//!
//! ```
//! use rasterlab::raster::{masks_of, reference_masks, triangle_backend, FillRule, FixedPoint};
//! use rasterlab::raster::{PixelRect, SamplePattern, TriangleSetup};
//!
//! // A triangle whose long edge x / 4 + y / 3.7 = 1 crosses pixel (2, 1),
//! // leaving its centre out but samples 0 and 2 in.
//! let v = [(0.0, 0.0), (4.0, 0.0), (0.0, 3.7)].map(|(x, y)| FixedPoint::snap_f64(x, y).unwrap());
//! let setup = TriangleSetup::new(0, v, FillRule::TopLeft).unwrap();
//! let pattern = SamplePattern::standard(4).unwrap();
//! let rect = PixelRect::of_target(4, 4);
//! let masks = masks_of(triangle_backend("scanline").unwrap(), &[setup], rect, &pattern);
//! assert_eq!(masks, reference_masks(&[setup], rect, &pattern));
//! let partial = masks.iter().find(|m| (m.x, m.y) == (2, 1)).unwrap();
//! assert_eq!(partial.mask, 0b0101);
//! ```

use crate::error::{Error, Result};
use crate::raster::edge::{EdgeFunction, PixelRect, TriangleSetup};
use crate::raster::fixed::{Fixed, FixedPoint, HALF_PIXEL, SUBPIXEL_SCALE};
use crate::raster::fragment::FragmentList;
use crate::raster::triangle::TriangleRasterizer;
use std::collections::BTreeMap;

/// The standard patterns, in 1/16 pixel from the pixel centre, y down,
/// sample `i` at index `i` (Direct3D 11's standard multisample patterns,
/// Vulkan's standard sample locations).
const STANDARD: [&[(i8, i8)]; 5] = [
    &[(0, 0)],
    &[(4, 4), (-4, -4)],
    &[(-2, -6), (6, -2), (-6, 2), (2, 6)],
    &[
        (1, -3),
        (-1, 3),
        (5, 1),
        (-3, -5),
        (-5, 5),
        (-7, -1),
        (3, 7),
        (7, -7),
    ],
    &[
        (1, 1),
        (-1, -3),
        (-3, 2),
        (4, -1),
        (-5, -2),
        (2, 5),
        (5, 3),
        (3, -5),
        (-2, 6),
        (0, -7),
        (-4, -6),
        (-6, 4),
        (-8, 0),
        (7, -4),
        (6, 7),
        (-7, -8),
    ],
];

/// The sample counts with a standard pattern.
pub const SAMPLE_COUNTS: [u32; 5] = [1, 2, 4, 8, 16];

/// Fixed-point units in 1/16 pixel.
pub(crate) const SIXTEENTH: i64 = SUBPIXEL_SCALE / 16;

/// Where a pixel's samples are: offsets from the pixel centre.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct SamplePattern {
    /// The standard table, sample `i`'s offset at index `i`, in 1/16
    /// pixel, y down.
    table: &'static [(i8, i8)],
    /// Whether the table is mirrored in y.
    mirrored: bool,
}

impl SamplePattern {
    /// The standard pattern of `count` samples (1, 2, 4, 8 or 16); an
    /// error names the counts there are.
    pub fn standard(count: u32) -> Result<SamplePattern> {
        match SAMPLE_COUNTS.iter().position(|&c| c == count) {
            Some(i) => Ok(SamplePattern {
                table: STANDARD[i],
                mirrored: false,
            }),
            None => Err(Error::InvalidArgument(format!(
                "there is no standard pattern of {count} samples (there are 1, 2, 4, 8 and 16)"
            ))),
        }
    }

    /// The pattern mirrored in y: the standard pattern as an OpenGL
    /// implementation places it in window coordinates (y up), seen on the
    /// screen (y down).
    pub fn mirrored_y(self) -> SamplePattern {
        SamplePattern {
            mirrored: !self.mirrored,
            ..self
        }
    }

    /// The number of samples per pixel.
    pub fn count(self) -> u32 {
        self.table.len() as u32
    }

    /// Sample `i`'s offset from the pixel centre, in 1/16 pixel, y down.
    pub fn offset(self, i: usize) -> (i8, i8) {
        let (x, y) = self.table[i];
        (x, if self.mirrored { -y } else { y })
    }

    /// Whether this is the standard pattern mirrored in y.
    pub fn is_mirrored(self) -> bool {
        self.mirrored
    }

    /// Sample `i` of pixel `(x, y)`, in fixed-point units.
    pub fn sample_point(self, x: i64, y: i64, i: usize) -> (i64, i64) {
        let (dx, dy) = self.offset(i);
        (
            x * SUBPIXEL_SCALE + HALF_PIXEL + i64::from(dx) * SIXTEENTH,
            y * SUBPIXEL_SCALE + HALF_PIXEL + i64::from(dy) * SIXTEENTH,
        )
    }

    /// The mask with every sample covered.
    pub fn full_mask(self) -> u32 {
        (1 << self.count()) - 1
    }
}

/// One pixel a triangle covers at least one sample of, with which.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct MaskFragment {
    /// Pixel row (first, so that fragments sort row by row).
    pub y: i64,
    /// Pixel column.
    pub x: i64,
    /// The triangle's id.
    pub triangle: u32,
    /// Bit `i` set when sample `i` of the pattern is covered; never 0.
    pub mask: u32,
}

/// The set-up of the triangle moved by `(dx, dy)` fixed-point units, its
/// edges' tie ownership kept as `setup` has it.
pub(crate) fn moved(setup: &TriangleSetup, dx: i64, dy: i64) -> TriangleSetup {
    // The offsets are under a pixel and the vertices inside the guard
    // band, so the moved coordinates fit the fixed-point type.
    let vertices = setup.vertices.map(|v| FixedPoint {
        x: Fixed::from_snapped((v.x.raw() + dx) as i32),
        y: Fixed::from_snapped((v.y.raw() + dy) as i32),
    });
    let edges = setup.edges.map(|e| EdgeFunction {
        // E(p - d) for the moved triangle is E(p) - a dx - b dy.
        c: e.c - e.a * dx - e.b * dy,
        ..e
    });
    TriangleSetup {
        vertices,
        edges,
        bounds: TriangleSetup::sample_bounds(vertices),
        ..*setup
    }
}

/// The coverage masks `backend` gives `setups` within `rect`: one pass of
/// the back-end per sample, on the triangles moved so that the sample
/// falls on the pixel centre. Sorted by row, column and triangle.
pub fn masks_of(
    backend: &dyn TriangleRasterizer,
    setups: &[TriangleSetup],
    rect: PixelRect,
    pattern: &SamplePattern,
) -> Vec<MaskFragment> {
    let mut masks: BTreeMap<(i64, i64, u32), u32> = BTreeMap::new();
    let mut list = FragmentList::default();
    for i in 0..pattern.count() as usize {
        let (dx, dy) = pattern.offset(i);
        let (dx, dy) = (i64::from(dx) * SIXTEENTH, i64::from(dy) * SIXTEENTH);
        let shifted: Vec<TriangleSetup> = setups.iter().map(|s| moved(s, -dx, -dy)).collect();
        list.triangles.clear();
        backend.rasterize(&shifted, rect, &mut list);
        for f in &list.triangles {
            *masks
                .entry((i64::from(f.y), i64::from(f.x), f.triangle))
                .or_default() |= 1 << i;
        }
    }
    collect(masks)
}

/// The coverage masks of `setups` within `rect`, every sample of every
/// pixel of each triangle's box tested directly: the reference the
/// back-ends' masks are checked against.
pub fn reference_masks(
    setups: &[TriangleSetup],
    rect: PixelRect,
    pattern: &SamplePattern,
) -> Vec<MaskFragment> {
    let mut masks: BTreeMap<(i64, i64, u32), u32> = BTreeMap::new();
    for setup in setups {
        // A sample is within 8/16 px of its centre: the box of pixels
        // whose samples may be covered is one pixel wider each way.
        let b = setup.bounds;
        let grown = PixelRect {
            x0: b.x0 - 1,
            y0: b.y0 - 1,
            x1: b.x1 + 1,
            y1: b.y1 + 1,
        }
        .intersect(rect);
        for y in grown.y0..=grown.y1 {
            for x in grown.x0..=grown.x1 {
                let mut mask = 0;
                for i in 0..pattern.count() as usize {
                    let (px, py) = pattern.sample_point(x, y, i);
                    let e = setup.edges.map(|e| e.eval_raw(px, py));
                    if setup.inside(e) {
                        mask |= 1 << i;
                    }
                }
                if mask != 0 {
                    *masks.entry((y, x, setup.id)).or_default() |= mask;
                }
            }
        }
    }
    collect(masks)
}

fn collect(masks: BTreeMap<(i64, i64, u32), u32>) -> Vec<MaskFragment> {
    masks
        .into_iter()
        .map(|((y, x, triangle), mask)| MaskFragment {
            y,
            x,
            triangle,
            mask,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every pattern as the Vulkan specification's table gives it, in
    /// [0, 1) from the pixel's top-left corner (Mesa's
    /// `u_sample_positions.c` holds the same numbers).
    #[test]
    fn the_patterns_are_the_standard_tables() {
        let table: [&[(f64, f64)]; 5] = [
            &[(0.5, 0.5)],
            &[(0.75, 0.75), (0.25, 0.25)],
            &[
                (0.375, 0.125),
                (0.875, 0.375),
                (0.125, 0.625),
                (0.625, 0.875),
            ],
            &[
                (0.5625, 0.3125),
                (0.4375, 0.6875),
                (0.8125, 0.5625),
                (0.3125, 0.1875),
                (0.1875, 0.8125),
                (0.0625, 0.4375),
                (0.6875, 0.9375),
                (0.9375, 0.0625),
            ],
            &[
                (0.5625, 0.5625),
                (0.4375, 0.3125),
                (0.3125, 0.625),
                (0.75, 0.4375),
                (0.1875, 0.375),
                (0.625, 0.8125),
                (0.8125, 0.6875),
                (0.6875, 0.1875),
                (0.375, 0.875),
                (0.5, 0.0625),
                (0.25, 0.125),
                (0.125, 0.75),
                (0.0, 0.5),
                (0.9375, 0.25),
                (0.875, 0.9375),
                (0.0625, 0.0),
            ],
        ];
        for (count, points) in SAMPLE_COUNTS.iter().zip(table) {
            let pattern = SamplePattern::standard(*count).unwrap();
            assert_eq!(pattern.count() as usize, points.len());
            for (i, (fx, fy)) in points.iter().enumerate() {
                let (x, y) = pattern.sample_point(0, 0, i);
                assert_eq!(
                    (
                        x as f64 / SUBPIXEL_SCALE as f64,
                        y as f64 / SUBPIXEL_SCALE as f64
                    ),
                    (*fx, *fy),
                    "{count} samples, sample {i}"
                );
            }
        }
        assert!(SamplePattern::standard(3).is_err());
        // OpenGL's 4 samples in window coordinates, seen with y down.
        let gl = SamplePattern::standard(4).unwrap().mirrored_y();
        assert_eq!(gl.offset(0), (-2, 6));
        assert!(gl.is_mirrored() && !gl.mirrored_y().is_mirrored());
    }
}
