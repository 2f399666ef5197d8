//! `wu`: Xiaolin Wu's anti-aliased lines (the line-drawing slides: "multiple shades of a
//! color can be used to draw anti-aliased lines").
//!
//! At every column the ideal line's exact height `y` falls between two
//! pixel centres, rows `floor(y)` and `floor(y) + 1`. Both are drawn, with
//! intensities `1 - frac(y)` and `frac(y)`: the nearer the line passes to a
//! pixel centre, the more of that pixel it gets. Each fragment carries its
//! intensity as its coverage, and the shared stage blends with it.
//! Fragments of zero coverage are not emitted. The columns are those of the
//! aliased algorithms; endpoints get no special weighting.

use super::{
    walk_frame, Endpoints, LineDescriptor, LineOptions, LineRasterizer, LineSetup, LineWalk,
    PixelEmitter,
};
use crate::error::{Error, Result};
use crate::raster::descriptor::{CostClass, Role};
use crate::raster::edge::PixelRect;
use crate::raster::fixed::SUBPIXEL_SCALE;
use crate::raster::fragment::{FragmentSink, WorkCounters};

/// Xiaolin Wu's anti-aliased line algorithm.
#[derive(Copy, Clone, Debug, Default)]
pub struct Wu;

impl Wu {
    /// The pixels of one segment with their coverage, in the order of travel.
    pub fn pixels(line: &LineSetup, options: &LineOptions) -> Vec<((i64, i64), f32)> {
        let mut pixels = Vec::new();
        Self::pixels_into(line, options, &mut pixels);
        pixels
    }

    /// [`pixels`](Self::pixels) into `pixels` (emptied first), so that a
    /// draw reuses its memory from one segment to the next.
    pub fn pixels_into(
        line: &LineSetup,
        options: &LineOptions,
        pixels: &mut Vec<((i64, i64), f32)>,
    ) {
        pixels.clear();
        let (frame, reversed) = walk_frame(line, options);
        let du = frame.du() as i128;
        let s = SUBPIXEL_SCALE as i128;
        // The columns in the order of travel, the last left out when the
        // end is open; each gives its one or two pixels, into one array.
        let columns = (frame.i1 - frame.i0 + 1).max(0);
        let count = columns - i64::from(options.endpoints == Endpoints::HalfOpen && columns > 0);
        let (first, step) = if reversed {
            (frame.i1, -1)
        } else {
            (frame.i0, 1)
        };
        pixels.reserve(2 * count as usize);
        for n in 0..count {
            let i = first + step * n;
            // y = scaled / du fixed units; row below = floor(y / 256).
            let (k, frac) = if du == 0 {
                (
                    frame.v0.div_euclid(SUBPIXEL_SCALE),
                    frame.v0.rem_euclid(SUBPIXEL_SCALE) as f64 / s as f64,
                )
            } else {
                let scaled = i128::from(frame.scaled_v_at(i));
                let k = scaled.div_euclid(s * du);
                let rem = scaled.rem_euclid(s * du);
                (k as i64, rem as f64 / (s * du) as f64)
            };
            for (row, weight) in [(k, 1.0 - frac), (k + 1, frac)] {
                if weight > 0.0 {
                    pixels.push((frame.to_screen(i, row), weight as f32));
                }
            }
        }
    }
}

impl LineRasterizer for Wu {
    fn descriptor(&self) -> LineDescriptor {
        LineDescriptor {
            name: "wu",
            description:
                "Xiaolin Wu anti-aliased: two pixels per column weighted by distance to the line",
            walk: LineWalk::AntiAliased,
            role: Role::Alternative,
            cost: CostClass::FollowsSize,
        }
    }

    fn check_options(&self, options: &LineOptions) -> Result<()> {
        if options.connectivity != super::Connectivity::Eight {
            return Err(Error::InvalidArgument(
                "wu draws two pixels per column; 4-connectivity does not apply".into(),
            ));
        }
        Ok(())
    }

    fn rasterize(
        &self,
        lines: &[LineSetup],
        options: &LineOptions,
        viewport: PixelRect,
        sink: &mut dyn FragmentSink,
    ) -> WorkCounters {
        let mut work = WorkCounters::default();
        let mut emitter = PixelEmitter::default();
        let mut pixels = Vec::new();
        for line in lines {
            work.primitives += 1;
            Self::pixels_into(line, options, &mut pixels);
            work.samples_tested += pixels.len() as u64;
            emitter.emit_weighted(line, pixels.iter().copied(), viewport, sink, &mut work);
        }
        work
    }
}
