//! What a check requires of every case: a [`Property`] of the triangles
//! (a fill rule exactly, watertight, crack-free), the lines (a
//! [`LineConvention`]) or the polygons (a winding rule).

use super::pixel_index;
use super::snapping::Snapping;
use crate::raster::edge::FillRule;
use crate::raster::multisample::SamplePattern;
use crate::raster::polygon::WindingRule;
use std::fmt;

/// How lines are judged.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum LineConvention {
    /// Exactly the midpoint (Bresenham) rule of the `bresenham` back-end,
    /// on sub-pixel endpoints: the columns (rows, for a steep line) run
    /// from the pixel containing the start's major coordinate to the one
    /// containing the end's (a coordinate on a pixel boundary belongs to
    /// the pixel after it); in each, the pixel whose centre is nearest
    /// the ideal line (extended past the segment where needed) at the
    /// column's centre, a tie going to the pixel on the start's side
    /// (for an axis-parallel line, the smaller coordinate).
    Midpoint,
    /// Exactly the diamond-exit rule of the `diamond` back-end.
    Diamond,
    /// The diamond-exit rule with Scotty3D's tie-break, exactly as the
    /// `diamond-nudged` back-end draws it: both ends moved by an
    /// infinitesimal `(e, e^2)`, y up.
    DiamondNudged,
    /// Vulkan's tolerance around the diamond-exit answer: every fragment
    /// within one pixel of it, as many fragments give or take one, one
    /// fragment per step along the major axis.
    Vulkan,
    /// Endpoints are pixel indices (whole numbers: the input's `3 4` is
    /// pixel (3, 4)), drawn by classic integer Bresenham: every pixel of
    /// the major axis from the start's to the end's, both included; in
    /// each, the minor coordinate nearest the ideal line through the two
    /// pixels' centres, a tie going toward the start (the decision
    /// variable steps only when it is positive). Drawn from its start in
    /// either direction, so `a -> b` and `b -> a` differ only at ties.
    PixelIndex,
    /// Pixel-index endpoints, integer Bresenham with a tie going toward
    /// the end (the decision variable steps when it is zero too).
    PixelIndexTowardEnd,
    /// Pixel-index endpoints as the course's midpoint pseudocode draws
    /// them: the endpoints swapped so that the walk runs along the major
    /// axis increasing (left to right for a line along x, top to bottom
    /// for one along y), a tie keeping the current row (column): toward
    /// the endpoint with the smaller major coordinate, whichever was
    /// given first.
    PixelIndexLeftToRight,
    /// Pixel-index endpoints as OpenCV's `cv::line` draws them with
    /// `LINE_8` and no `shift`: clipped to the target first, then walked
    /// from the endpoint with the smaller x, a tie toward it.
    PixelIndexOpenCv,
    /// OpenCV's `LINE_4` without `shift`: clipped, then a 4-connected
    /// staircase from the endpoint with the smaller x.
    PixelIndexOpenCv4,
}

impl LineConvention {
    /// Every convention, default first.
    pub const ALL: [LineConvention; 9] = [
        LineConvention::Midpoint,
        LineConvention::Diamond,
        LineConvention::DiamondNudged,
        LineConvention::Vulkan,
        LineConvention::PixelIndex,
        LineConvention::PixelIndexTowardEnd,
        LineConvention::PixelIndexLeftToRight,
        LineConvention::PixelIndexOpenCv,
        LineConvention::PixelIndexOpenCv4,
    ];

    /// Whether the convention's endpoints are whole pixel indices (the
    /// input's `3 4` naming pixel (3, 4)), not screen coordinates.
    pub fn whole_pixels(self) -> bool {
        matches!(
            self,
            LineConvention::PixelIndex
                | LineConvention::PixelIndexTowardEnd
                | LineConvention::PixelIndexLeftToRight
                | LineConvention::PixelIndexOpenCv
                | LineConvention::PixelIndexOpenCv4
        )
    }

    /// How a whole-pixel convention walks its lines.
    pub(crate) fn walk(self) -> Option<pixel_index::WholePixelWalk> {
        match self {
            LineConvention::PixelIndex => Some(pixel_index::WholePixelWalk::TowardStart),
            LineConvention::PixelIndexTowardEnd => Some(pixel_index::WholePixelWalk::TowardEnd),
            LineConvention::PixelIndexLeftToRight => Some(pixel_index::WholePixelWalk::LeftToRight),
            LineConvention::PixelIndexOpenCv => Some(pixel_index::WholePixelWalk::OpenCv8),
            LineConvention::PixelIndexOpenCv4 => Some(pixel_index::WholePixelWalk::OpenCv4),
            _ => None,
        }
    }
}

crate::names::named_enum!(
    LineConvention,
    "line convention",
    Midpoint = "midpoint",
    Diamond = "diamond",
    DiamondNudged = "diamond-nudged",
    Vulkan = "vulkan",
    PixelIndex = "pixel-index",
    PixelIndexTowardEnd = "pixel-index-toward-end",
    PixelIndexLeftToRight = "pixel-index-left-to-right",
    PixelIndexOpenCv = "pixel-index-opencv",
    PixelIndexOpenCv4 = "pixel-index-opencv-4"
);

/// What a check requires of every case.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum Property {
    /// Triangles: exactly the rules' fragments under this fill rule.
    Exact(FillRule),
    /// Triangles of a mesh: no gaps, no double draws, nothing outside,
    /// whatever consistent tie rule is used (see the module docs).
    Watertight,
    /// Triangles of a mesh: every centre on a shared edge or vertex inside
    /// the mesh drawn exactly once, no pixel drawn twice (see the module
    /// docs).
    CrackFree,
    /// Lines under a convention.
    Line(LineConvention),
    /// Polygons filled by a winding rule, exactly, under the polygon
    /// back-ends' boundary convention: a pixel is filled when its centre,
    /// moved right by an infinitesimal and down by a smaller one, has a
    /// winding number the rule fills (a centre on a left or top edge is
    /// inside, on a right or bottom edge outside: the top-left rule).
    Polygon(WindingRule),
}

impl Property {
    /// A stable identifier, for JSON: `exact-top-left` (and so on for
    /// every fill rule), `watertight`, `crack-free`, `line-midpoint`,
    /// `line-diamond`, `line-vulkan`, `line-pixel-index`, `polygon-even-odd`,
    /// `polygon-nonzero`.
    pub fn id(self) -> String {
        match self {
            Property::Exact(rule) => format!("exact-{}", rule.name()),
            Property::Watertight => "watertight".into(),
            Property::CrackFree => "crack-free".into(),
            Property::Line(c) => format!("line-{}", c.name()),
            Property::Polygon(r) => format!("polygon-{}", r.name()),
        }
    }

    /// Whether the cases hold polygons.
    pub fn is_polygons(self) -> bool {
        matches!(self, Property::Polygon(_))
    }

    /// Whether the cases hold lines.
    pub fn is_lines(self) -> bool {
        matches!(self, Property::Line(_))
    }

    /// Whether the cases must be meshes (triangles sharing edges, never
    /// overlapping).
    pub fn needs_mesh(self) -> bool {
        matches!(self, Property::Watertight | Property::CrackFree)
    }
}

impl fmt::Display for Property {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Property::Exact(rule) => write!(f, "exact under the {} rule", rule.name()),
            Property::Watertight => f.write_str("watertight"),
            Property::CrackFree => f.write_str("crack-free"),
            Property::Line(LineConvention::Midpoint) => f.write_str("lines, midpoint rule"),
            Property::Line(LineConvention::Diamond) => f.write_str("lines, diamond exit rule"),
            Property::Line(LineConvention::DiamondNudged) => f.write_str(
                "lines, diamond exit rule with Scotty3D's tie-break (both ends moved by (e, e^2), y up)",
            ),
            Property::Line(LineConvention::Vulkan) => {
                f.write_str("lines, Vulkan's tolerance of the diamond exit rule")
            }
            Property::Line(LineConvention::PixelIndex) => {
                f.write_str("lines, pixel-index endpoints (integer Bresenham, ties toward the start)")
            }
            Property::Line(LineConvention::PixelIndexTowardEnd) => {
                f.write_str("lines, pixel-index endpoints (integer Bresenham, ties toward the end)")
            }
            Property::Line(LineConvention::PixelIndexLeftToRight) => f.write_str(
                "lines, pixel-index endpoints (the course's midpoint walk, left to right, ties kept on the row)",
            ),
            Property::Line(LineConvention::PixelIndexOpenCv) => f.write_str(
                "lines, pixel-index endpoints as OpenCV's LINE_8 (clipped, walked from the left endpoint)",
            ),
            Property::Line(LineConvention::PixelIndexOpenCv4) => f.write_str(
                "lines, pixel-index endpoints as OpenCV's LINE_4 (clipped, a 4-connected staircase)",
            ),
            Property::Polygon(rule) => write!(
                f,
                "polygons, the {} fill rule, a centre on an edge by the top-left convention",
                rule.name()
            ),
        }
    }
}

/// A property in words, with the snapping where it is not the rules' own
/// 1/256 px: `exact under the top-left rule, vertices not snapped: judged
/// as given`.
pub(crate) fn with_snapping(words: String, snapping: Snapping) -> String {
    if snapping == Snapping::default() {
        words
    } else {
        format!("{words}, vertices {}", snapping.describe())
    }
}

/// A property in words, with the samples per pixel of a multisampled
/// check: `exact under the top-left rule, 4 samples per pixel (the
/// standard pattern)`.
pub(crate) fn with_samples(words: String, samples: Option<SamplePattern>) -> String {
    match samples {
        Some(p) if p.count() == 1 => format!("{words}, 1 sample per pixel (the pixel centre)"),
        Some(p) => format!(
            "{words}, {} samples per pixel (the standard pattern)",
            p.count()
        ),
        None => words,
    }
}
