//! The trace beside the lab's grid: what `rasterlab explain` prints for
//! the first primitive, and for a line with a clipper chosen, the
//! clipper's steps (Cohen-Sutherland's outcodes, Liang-Barsky's `t`
//! interval) before the walk from the entry column, as `explain --clip`
//! prints them.

use super::LabRequest;
use crate::error::Result;
use crate::raster::edge::FillRule;
use crate::raster::line::clip::Clipper;
use crate::raster::registry::Backend;
use crate::teaching::trace::{self, LineEnds};
use crate::teaching::trace_table::Trace;

/// The trace of `backend` on the request's first primitive.
pub(super) fn trace_of(request: &LabRequest, backend: &str, rule: FillRule) -> Result<Trace> {
    let (w, h) = (request.width, request.height);
    match crate::raster::registry::backend(backend)? {
        Backend::Line(b) => {
            let Some(l) = request.lines.first().filter(|_| request.kind == "lines") else {
                return Ok(Trace::default());
            };
            let ends = LineEnds::screen([l[0][0], l[0][1], l[1][0], l[1][1]])?;
            match &request.clip {
                Some(clipper) => trace::trace_clip(clipper.parse::<Clipper>()?, b, &ends, w, h),
                None => trace::trace_line(b, &ends),
            }
        }
        Backend::Triangle(b) => {
            let Some(t) = request
                .triangles
                .first()
                .filter(|_| request.kind == "triangles")
            else {
                return Ok(Trace::default());
            };
            trace::trace_triangle(b, t.map(|p| (p[0], p[1])), rule, w, h)
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::lab::{answer, LabRequest};

    fn lines(clip: &str) -> crate::Result<LabRequest> {
        LabRequest::parse(&format!(
            r#"{{"width": 8, "height": 8, "kind": "lines",
                "lines": [[[-2.3, 1.7], [12.4, 6.1]]],
                "backends": ["bresenham"], "trace": "bresenham"{clip}}}"#
        ))
    }

    /// A dragged segment crossing the grid's sides is traced as
    /// `explain --clip` traces it: each clipper's steps, then the walk
    /// from the entry column; an unknown clipper is refused.
    #[test]
    fn a_clipped_line_is_traced_by_its_clipper() {
        let plain = answer(&lines("").unwrap(), None).unwrap().trace.to_text();
        for (name, says) in [("cohen-sutherland", "TBRL"), ("liang-barsky", "t0")] {
            let request = lines(&format!(r#", "clip": "{name}""#)).unwrap();
            let text = answer(&request, None).unwrap().trace.to_text();
            assert!(text.contains(says), "{name}: {text}");
            assert!(text.contains("entry column x = 0"), "{name}: {text}");
            assert_ne!(text, plain);
        }
        assert!(lines(r#", "clip": "sutherland""#).is_err());
    }
}
