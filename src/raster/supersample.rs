//! Supersampling: the triangles drawn at `k` times the resolution, each
//! pixel's coverage the share of its `k x k` fine pixels drawn.
//!
//! Supersampling anti-aliasing (SSAA) is the plainest way to approximate
//! [area coverage](crate::raster::area_coverage): render the picture `k`
//! times wider and taller, one sample per fine pixel, then average each
//! `k x k` block into one pixel (a box filter). Seen from the coarse
//! pixel, its samples form a regular grid at `((i + 1/2) / k, (j + 1/2)
//! / k)`, where multisampling's standard patterns
//! ([`SamplePattern`](crate::raster::SamplePattern)) scatter theirs so that
//! no two share a row or a column.
//!
//! Here the back-end itself draws the fine picture: each snapped vertex
//! is scaled by `k` (exactly: a multiple of 1/256 px stays one), and the
//! back-end walks the scaled triangles under the fill rule, so a sample
//! on an edge is decided by the rule's ties as a pixel centre is, and a
//! mesh's samples are covered exactly once under a watertight rule.
//!
//! ```
//! use rasterlab::raster::{supersample, triangle_backend, FillRule, FixedPoint, PixelRect};
//!
//! // Half a 2 x 2 square, below its diagonal: at 4 x 4 samples a pixel,
//! // each pixel the diagonal crosses keeps the 6 samples of 16 strictly
//! // below it. The 4 on it go to the other half: the diagonal is this
//! // triangle's right edge, which owns no ties under the top-left rule.
//! let v = [(0.0, 0.0), (2.0, 2.0), (0.0, 2.0)].map(|(x, y)| FixedPoint::snap_f64(x, y).unwrap());
//! let counts = supersample(triangle_backend("bbox").unwrap(), &[v], FillRule::TopLeft,
//!                          PixelRect::of_target(2, 2), 4).unwrap();
//! let at = |x, y| counts.iter().find(|c| (c.x, c.y) == (x, y)).map_or(0, |c| c.count);
//! assert_eq!((at(0, 0), at(1, 1), at(0, 1), at(1, 0)), (6, 6, 16, 0));
//! ```

use crate::error::{Error, Result};
use crate::raster::edge::{FillRule, PixelRect, TriangleSetup};
use crate::raster::fixed::FixedPoint;
use crate::raster::fragment::FragmentList;
use crate::raster::triangle::TriangleRasterizer;
use std::collections::BTreeMap;

/// The largest `k`: 16 x 16 = 256 samples a pixel.
pub const MAX_SUPERSAMPLING: u32 = 16;

/// How many of a pixel's `k x k` samples one triangle covers.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct SampleCount {
    /// Row.
    pub y: i64,
    /// Column.
    pub x: i64,
    /// The triangle's index in the input.
    pub triangle: u32,
    /// Samples covered, of `k * k`.
    pub count: u32,
}

/// The samples `backend` covers in each pixel of `rect`, at `k x k`
/// samples a pixel on a regular grid, under `rule`; sorted by row, column
/// and triangle. A `k` outside `1..=16`, or a triangle that no longer
/// fits the guard band once scaled, is an error.
pub fn supersample(
    backend: &dyn TriangleRasterizer,
    triangles: &[[FixedPoint; 3]],
    rule: FillRule,
    rect: PixelRect,
    k: u32,
) -> Result<Vec<SampleCount>> {
    if !(1..=MAX_SUPERSAMPLING).contains(&k) {
        return Err(Error::InvalidArgument(format!(
            "supersampling takes 1 to {MAX_SUPERSAMPLING} samples a side, not {k}"
        )));
    }
    let s = i64::from(k);
    let scaled = triangles
        .iter()
        .map(|t| {
            let mut out = [FixedPoint::default(); 3];
            for (o, p) in out.iter_mut().zip(t) {
                *o = FixedPoint::from_raw(p.x.raw() * s, p.y.raw() * s).map_err(|_| {
                    Error::InvalidArgument(format!(
                        "a vertex at {:?} px leaves the guard band when scaled by {k}",
                        p.to_f64()
                    ))
                })?;
            }
            Ok(out)
        })
        .collect::<Result<Vec<_>>>()?;
    let fine = PixelRect {
        x0: rect.x0 * s,
        y0: rect.y0 * s,
        x1: rect.x1 * s + s - 1,
        y1: rect.y1 * s + s - 1,
    };
    let mut list = FragmentList::default();
    let setups: Vec<TriangleSetup> = scaled
        .iter()
        .enumerate()
        .filter_map(|(i, v)| TriangleSetup::new(i as u32, *v, rule))
        .collect();
    backend.rasterize(&setups, fine, &mut list);
    let mut counts: BTreeMap<(i64, i64, u32), u32> = BTreeMap::new();
    for f in &list.triangles {
        let (x, y) = (i64::from(f.x).div_euclid(s), i64::from(f.y).div_euclid(s));
        *counts.entry((y, x, f.triangle)).or_default() += 1;
    }
    Ok(counts
        .into_iter()
        .map(|((y, x, triangle), count)| SampleCount {
            y,
            x,
            triangle,
            count,
        })
        .collect())
}
