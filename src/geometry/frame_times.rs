//! A frame's time, part by part: clear, geometry, raster and the rest,
//! which add up to the frame.
//!
//! A renderer times its frame as a whole and each part inside it, one
//! after the other; **the rest** is what the parts leave of the whole
//! (taking the lock on the reused buffers, gathering the work counts,
//! drawing a wireframe's set-up), so the parts always add up to the
//! frame. When the clear is folded into the draw (each row cleared just
//! before its first fragment), it is part of the raster time and is shown
//! so.
//!
//! Over several frames, [`FrameTimes::median`] is the frame of the median
//! total, with its own parts: medians taken part by part would not add
//! up to the median total. Shown, a frame is its total and then each
//! part, in milliseconds to two decimals.
//!
//! ```
//! use rasterlab::geometry::FrameTimes;
//! use std::time::Duration;
//!
//! let ms = Duration::from_millis;
//! let frame = FrameTimes::new(ms(10), None, ms(4), ms(5));
//! assert_eq!(frame.rest, ms(1));
//! assert_eq!(frame.clear + frame.geometry + frame.raster + frame.rest, frame.total());
//! assert!(frame.to_string().contains("clear (folded into raster)"));
//! let frames = [frame, FrameTimes::new(ms(30), Some(ms(3)), ms(20), ms(6)), FrameTimes::new(ms(12), None, ms(3), ms(8))];
//! assert_eq!(FrameTimes::median(&frames), Some(frames[2]));
//! ```

use std::fmt;
use std::time::Duration;

/// Where one frame's time went; the parts add up to [`total`](Self::total).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct FrameTimes {
    /// Clearing the target as a pass of its own (zero when folded into
    /// the draw, see [`clear_folded`](Self::clear_folded)).
    #[serde(serialize_with = "milliseconds")]
    pub clear: Duration,
    /// Whether the clear was folded into the draw, and so is part of
    /// [`raster`](Self::raster).
    pub clear_folded: bool,
    /// Vertex shading, clipping, culling and set-up.
    #[serde(serialize_with = "milliseconds")]
    pub geometry: Duration,
    /// Rasterizing and shading the fragments (with a folded clear, the
    /// clear too).
    #[serde(serialize_with = "milliseconds")]
    pub raster: Duration,
    /// The frame's time outside the named parts.
    #[serde(serialize_with = "milliseconds")]
    pub rest: Duration,
}

impl FrameTimes {
    /// The parts of a frame that took `total` in all: `clear` as a pass of
    /// its own (`None`: folded into the raster), `geometry` and `raster`,
    /// each timed inside the frame; the rest is what they leave of it.
    pub fn new(
        total: Duration,
        clear: Option<Duration>,
        geometry: Duration,
        raster: Duration,
    ) -> FrameTimes {
        let clear_time = clear.unwrap_or_default();
        let named = clear_time + geometry + raster;
        // Parts timed one after the other inside the frame never exceed
        // it; should a clock say otherwise, the frame is their sum.
        let total = total.max(named);
        FrameTimes {
            clear: clear_time,
            clear_folded: clear.is_none(),
            geometry,
            raster,
            rest: total - named,
        }
    }

    /// The frame's time: the sum of its parts.
    pub fn total(&self) -> Duration {
        self.clear + self.geometry + self.raster + self.rest
    }

    /// The frame of the median total among `frames` (the upper one of an
    /// even count), with its parts; `None` for no frames.
    pub fn median(frames: &[FrameTimes]) -> Option<FrameTimes> {
        let mut sorted = frames.to_vec();
        sorted.sort_by_key(FrameTimes::total);
        sorted.get(sorted.len() / 2).copied()
    }
}

/// A duration as milliseconds, in the JSON of a report.
pub(crate) fn milliseconds<S: serde::Serializer>(d: &Duration, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_f64(d.as_secs_f64() * 1e3)
}

/// A duration as milliseconds, or `null`, in the JSON of a report.
pub(crate) fn optional_milliseconds<S: serde::Serializer>(
    d: &Option<Duration>,
    s: S,
) -> Result<S::Ok, S::Error> {
    match d {
        Some(d) => milliseconds(d, s),
        None => s.serialize_none(),
    }
}

impl fmt::Display for FrameTimes {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let ms = |d: Duration| d.as_secs_f64() * 1e3;
        write!(f, "{:.2} ms = ", ms(self.total()))?;
        if self.clear_folded {
            write!(f, "clear (folded into raster)")?;
        } else {
            write!(f, "clear {:.2} ms", ms(self.clear))?;
        }
        write!(
            f,
            " + geometry {:.2} ms + raster {:.2} ms + rest {:.2} ms",
            ms(self.geometry),
            ms(self.raster),
            ms(self.rest)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The parts add up to the frame, whatever the frame, and the median
    /// frame keeps its own parts (medians part by part would not add up:
    /// here they would give 2 + 2 against a median total of 6).
    #[test]
    fn the_parts_add_up_to_the_frame_and_the_median_frame() {
        let us = Duration::from_micros;
        for (total, clear, geometry, raster) in [
            (us(1000), None, us(300), us(600)),
            (us(1000), Some(us(100)), us(300), us(600)),
            (us(900), Some(us(100)), us(300), us(600)),
            (us(0), None, us(0), us(0)),
        ] {
            let t = FrameTimes::new(total, clear, geometry, raster);
            let named = clear.unwrap_or_default() + geometry + raster;
            assert_eq!(t.total(), total.max(named));
            assert_eq!(t.clear + t.geometry + t.raster + t.rest, t.total());
            assert_eq!(t.clear_folded, clear.is_none());
        }
        let ms = Duration::from_millis;
        let frames = [
            FrameTimes::new(ms(6), None, ms(4), ms(2)),
            FrameTimes::new(ms(6), None, ms(2), ms(4)),
            FrameTimes::new(ms(9), None, ms(2), ms(2)),
        ];
        let median = FrameTimes::median(&frames).unwrap();
        assert_eq!(median.total(), ms(6));
        assert_eq!(median.geometry + median.raster + median.rest, ms(6));
        assert_eq!(FrameTimes::median(&[]), None);
    }

    /// Shown, the total comes first, then each part, a folded clear named
    /// as such.
    #[test]
    fn a_frame_is_shown_total_first_in_milliseconds() {
        let ms = Duration::from_millis;
        assert_eq!(
            FrameTimes::new(ms(10), None, ms(4), ms(5)).to_string(),
            "10.00 ms = clear (folded into raster) + geometry 4.00 ms + raster 5.00 ms + rest 1.00 ms"
        );
        assert_eq!(
            FrameTimes::new(ms(10), Some(ms(1)), ms(4), ms(5)).to_string(),
            "10.00 ms = clear 1.00 ms + geometry 4.00 ms + raster 5.00 ms + rest 0.00 ms"
        );
    }
}
