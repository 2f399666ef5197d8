//! One input of a check: a target size, its samples per pixel, and
//! triangles, line segments or polygons in screen pixels, as written in a
//! counterexample file and read back.
//! The generators make cases, the judge and the shrinker read them.

use super::snapping::Snapping;
use crate::error::{Error, Result};
use crate::raster::fixed::FixedPoint;
use crate::raster::multisample::SamplePattern;
use std::fmt::Write;

/// A point in screen pixels, as written in the input file.
pub type Point = (f64, f64);

/// One input: a target size and triangles or line segments, in screen
/// pixels (snapped by whoever reads them).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Case {
    /// Target width in pixels.
    pub width: u32,
    /// Target height in pixels.
    pub height: u32,
    /// Triangles (empty for a line case).
    pub triangles: Vec<[Point; 3]>,
    /// Line segments (empty for a triangle case).
    pub lines: Vec<[Point; 2]>,
    /// Polygons (empty for a triangle or line case): each its rings, the
    /// outer ring first, then its holes, each ring closed implicitly
    /// (last vertex to first). Written `polygon x0 y0 x1 y1 ...` and
    /// `hole x0 y0 ...` lines, as the polygon file format is.
    pub polygons: Vec<Vec<Vec<Point>>>,
    /// The samples per pixel under `check --msaa N` (`None`: one sample,
    /// at the pixel centre). A multisampled case's fragments carry a
    /// coverage mask.
    pub samples: Option<SamplePattern>,
    /// How the vertices are snapped before they are judged (`check
    /// --snap`; 1/256 px by default).
    pub snapping: Snapping,
}

impl Case {
    /// How many primitives the case holds.
    pub fn len(&self) -> usize {
        self.triangles.len() + self.lines.len() + self.polygons.len()
    }

    /// True when the case holds no primitive.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Every vertex of every primitive, as given: the triangles' then the
    /// segments'.
    pub(crate) fn points(&self) -> impl Iterator<Item = Point> + '_ {
        self.triangles
            .iter()
            .flat_map(|t| t.iter().copied())
            .chain(self.lines.iter().flat_map(|l| l.iter().copied()))
            .chain(self.polygons.iter().flatten().flatten().copied())
    }

    /// The polygons as judged, each its rings snapped like
    /// [`Case::snapped_triangles`].
    pub fn snapped_polygons(&self) -> Vec<Vec<Vec<FixedPoint>>> {
        let s = self.snapping;
        self.polygons
            .iter()
            .map(|rings| {
                rings
                    .iter()
                    .map(|r| r.iter().map(|&p| snap(s.apply(p))).collect())
                    .collect()
            })
            .collect()
    }

    /// Every point mapped by `f`, the target kept.
    pub(crate) fn map_points(&self, f: impl Fn(Point) -> Point) -> Case {
        Case {
            triangles: self.triangles.iter().map(|t| t.map(&f)).collect(),
            lines: self.lines.iter().map(|l| l.map(&f)).collect(),
            polygons: self
                .polygons
                .iter()
                .map(|rings| {
                    rings
                        .iter()
                        .map(|r| r.iter().map(|&p| f(p)).collect())
                        .collect()
                })
                .collect(),
            ..self.clone()
        }
    }

    /// The triangles as judged: snapped as the case's [`Snapping`] says,
    /// on the 1/256 pixel grid.
    pub fn snapped_triangles(&self) -> Vec<[FixedPoint; 3]> {
        let s = self.snapping;
        self.triangles
            .iter()
            .map(|t| t.map(|p| snap(s.apply(p))))
            .collect()
    }

    /// The segments as judged, like [`Case::snapped_triangles`].
    pub fn snapped_lines(&self) -> Vec<[FixedPoint; 2]> {
        let s = self.snapping;
        self.lines
            .iter()
            .map(|l| l.map(|p| snap(s.apply(p))))
            .collect()
    }

    /// The input file: `# size WxH`, under `--msaa N` a line `# msaa N`,
    /// under a snapping other than 1/256 px a line `# snap S`, then one
    /// primitive per line (`-0` written as `0`).
    pub fn to_text(&self) -> String {
        self.to_text_for(Origin::TopLeft)
    }

    /// The input file as a program with this [`Origin`] is given the
    /// case: under [`Origin::BottomLeft`], y measured up from the bottom
    /// edge (`height - y`) and a line `# origin bottom-left` after the
    /// size, which [`Case::from_text`] reads to turn y back.
    pub fn to_text_for(&self, origin: Origin) -> String {
        let clean = match origin {
            Origin::TopLeft => self.without_negative_zeros(),
            Origin::BottomLeft => self.flipped_y().without_negative_zeros(),
        };
        let mut out = format!("# size {}x{}\n", clean.width, clean.height);
        if origin == Origin::BottomLeft {
            let _ = writeln!(out, "# origin {origin}");
        }
        if let Some(p) = self.samples {
            let _ = writeln!(out, "# msaa {}", p.count());
        }
        if self.snapping != Snapping::default() {
            let _ = writeln!(out, "# snap {}", self.snapping);
        }
        for t in &clean.triangles {
            let _ = writeln!(
                out,
                "{} {} {} {} {} {}",
                t[0].0, t[0].1, t[1].0, t[1].1, t[2].0, t[2].1
            );
        }
        for l in &clean.lines {
            let _ = writeln!(out, "{} {} {} {}", l[0].0, l[0].1, l[1].0, l[1].1);
        }
        for rings in &clean.polygons {
            for (k, ring) in rings.iter().enumerate() {
                out.push_str(if k == 0 { "polygon" } else { "hole" });
                for p in ring {
                    let _ = write!(out, " {} {}", p.0, p.1);
                }
                out.push('\n');
            }
        }
        out
    }

    /// The same case seen from the bottom-left corner: every y made
    /// `height - y` (exact for the coordinates a case holds, multiples
    /// of 1/256 px well inside `f64`'s 53 bits, so that flipping twice
    /// gives the case back).
    pub(crate) fn flipped_y(&self) -> Case {
        let h = f64::from(self.height);
        self.map_points(|p: Point| (p.0, h - p.1))
    }

    /// The same case with every `-0.0` made `0.0` (adding zero does it).
    fn without_negative_zeros(&self) -> Case {
        self.map_points(|p: Point| (p.0 + 0.0, p.1 + 0.0))
    }

    /// Reads a case written by [`Case::to_text`] (a counterexample file),
    /// or any soup, line set or polygon set (`polygon` and `hole`
    /// lines) with a `# size WxH` line (and a `# msaa N`
    /// line for a multisampled one, `N` one of 1, 2, 4, 8 and 16; a
    /// `# snap S` line for a snapping other than 1/256 px; a line
    /// `# origin bottom-left` for one whose y runs up from the bottom
    /// edge, turned back to the protocol's y down).
    pub fn from_text(text: &str) -> Result<Case> {
        let mut case = Case::default();
        let mut origin = Origin::TopLeft;
        // The line of each triangle and of each segment, for the errors.
        let (mut triangle_lines, mut segment_lines) = (Vec::new(), Vec::new());
        // The line of each polygon's ring, for the errors.
        let mut ring_lines: Vec<usize> = Vec::new();
        for (i, line) in text.lines().enumerate() {
            let bad = |m: String| Error::InvalidArgument(format!("line {}: {m}", i + 1));
            if let Some(size) = line.trim().strip_prefix("# size ") {
                let (w, h) = size
                    .split_once('x')
                    .ok_or_else(|| bad("expected # size WxH".into()))?;
                case.width = w.trim().parse().map_err(|_| bad("bad width".into()))?;
                case.height = h.trim().parse().map_err(|_| bad("bad height".into()))?;
                continue;
            }
            if let Some(o) = line.trim().strip_prefix("# origin ") {
                origin = o.trim().parse().map_err(|e: Error| bad(e.to_string()))?;
                continue;
            }
            if let Some(s) = line.trim().strip_prefix("# snap ") {
                case.snapping = s.parse().map_err(|e: Error| bad(e.to_string()))?;
                continue;
            }
            if let Some(n) = line.trim().strip_prefix("# msaa ") {
                let n: u32 = n
                    .trim()
                    .parse()
                    .map_err(|_| bad(format!("`{}` is not a sample count", n.trim())))?;
                case.samples = Some(SamplePattern::standard(n).map_err(|e| bad(e.to_string()))?);
                continue;
            }
            let content = line.split('#').next().unwrap_or("").trim();
            if content.is_empty() {
                continue;
            }
            let (keyword, content) = match content.split_once(char::is_whitespace) {
                Some((k @ ("polygon" | "hole"), rest)) => (Some(k), rest),
                _ if content == "polygon" || content == "hole" => (Some(content), ""),
                _ => (None, content),
            };
            let v = content
                .split_whitespace()
                .map(|t| {
                    t.parse::<f64>()
                        .map_err(|_| bad(format!("`{t}` is not a number")))
                })
                .collect::<Result<Vec<f64>>>()?;
            if let Some(keyword) = keyword {
                if v.len() % 2 != 0 || v.len() < 6 {
                    return Err(bad(format!(
                        "a {keyword} ring takes at least 3 points as x y pairs, found {} numbers",
                        v.len()
                    )));
                }
                let ring: Vec<Point> = v.chunks(2).map(|c| (c[0], c[1])).collect();
                match (keyword, case.polygons.last_mut()) {
                    ("hole", None) => return Err(bad("`hole` before any `polygon`".into())),
                    ("hole", Some(rings)) => rings.push(ring),
                    _ => case.polygons.push(vec![ring]),
                }
                ring_lines.push(i + 1);
                continue;
            }
            match v.len() {
                6 => {
                    case.triangles
                        .push([(v[0], v[1]), (v[2], v[3]), (v[4], v[5])]);
                    triangle_lines.push(i + 1);
                }
                4 => {
                    case.lines.push([(v[0], v[1]), (v[2], v[3])]);
                    segment_lines.push(i + 1);
                }
                n => {
                    return Err(bad(format!(
                        "expected 6 or 4 numbers, or a `polygon` or `hole` ring, found {n} numbers"
                    )))
                }
            }
        }
        if !text.lines().any(|l| l.trim().starts_with("# size ")) {
            return Err(Error::InvalidArgument("no `# size WxH` line".into()));
        }
        if case.width == 0 || case.height == 0 {
            return Err(Error::InvalidArgument(format!(
                "the target is {}x{}: give it at least one pixel a side",
                case.width, case.height
            )));
        }
        let case = match origin {
            Origin::TopLeft => case,
            Origin::BottomLeft => case.flipped_y(),
        };
        // Every vertex, as judged (y down), finite and inside the guard
        // band, as every generated one is.
        let vertices = case
            .triangles
            .iter()
            .zip(&triangle_lines)
            .flat_map(|(t, &line)| t.iter().map(move |p| (p, line)))
            .chain(
                case.lines
                    .iter()
                    .zip(&segment_lines)
                    .flat_map(|(l, &line)| l.iter().map(move |p| (p, line))),
            )
            .chain(
                case.polygons
                    .iter()
                    .flatten()
                    .zip(&ring_lines)
                    .flat_map(|(r, &line)| r.iter().map(move |p| (p, line))),
            );
        for (p, line) in vertices {
            FixedPoint::snap_f64(p.0, p.1)
                .map_err(|e| Error::InvalidArgument(format!("line {line}: {e}")))?;
        }
        Ok(case)
    }
}

/// Snaps a generated point (always finite and inside the guard band).
pub(crate) fn snap(p: Point) -> FixedPoint {
    FixedPoint::snap_f64(p.0, p.1).unwrap_or_default()
}

/// Where the subject puts the origin of its screen coordinates, and so
/// which way its y grows: the protocol's top-left corner with y down
/// (Direct3D, Vulkan, image rows), or the bottom-left corner with y up
/// (OpenGL's window coordinates, Scotty3D). A y-up subject is given each
/// case with y measured up from the bottom of the target (`height - y`)
/// and answers with rows counted up from the bottom row (row 0 the
/// lowest); rasterlab turns both back before judging, so the rules and
/// their names (a top edge, a left edge) are those of the picture as it
/// is seen, whatever way the subject counts.
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq)]
pub enum Origin {
    /// At the top-left corner, y down: the protocol's own.
    #[default]
    TopLeft,
    /// At the bottom-left corner, y up.
    BottomLeft,
}

crate::names::named_enum!(
    Origin,
    "origin",
    TopLeft = "top-left",
    BottomLeft = "bottom-left"
);
