//! Plain-text 2D inputs: triangle soups and line sets.
//!
//! One primitive per line, coordinates in screen pixels (x right, y down):
//!
//! ```text
//! # a triangle soup: x0 y0 x1 y1 x2 y2
//! 0 0  5 0  5 5
//! 0 5  0 0  5 5
//! ```
//!
//! ```text
//! # a line set: x0 y0 x1 y1
//! 0 0 7 3
//! ```
//!
//! ```text
//! # a polygon (any number of x y pairs), then its holes; spade triangulates it
//! polygon 0 0  20 0  20 14  0 14
//! hole 6 4  14 4  10 10
//! ```
//!
//! A triangle or polygon line may end with its look: `rgba R G B A`, its
//! colour (sRGB-encoded) and opacity, each in `[0, 1]`, and `depth Z`, its
//! depth in `[0, 1]` (0 nearest; 0 when not given), for transparent
//! triangles drawn with a blend mode:
//!
//! ```text
//! 4 4  40 4  4 40  rgba 1 0 0 0.5  depth 0.25
//! ```
//!
//! Blank lines and `#` comments are ignored. A file holds either triangles
//! (triangles and polygons may be mixed) or lines. A polygon's triangles
//! all carry the polygon line's number. Every coordinate is snapped when read, so NaN, infinities and
//! coordinates beyond the guard band are reported with the file and line.
//!
//! [`read_shapes`] triangulates each polygon (spade takes simple ones
//! only); [`read_polygons`] keeps them whole for a polygon back-end, which
//! fills them directly, and, given a winding rule, takes rings that cross
//! themselves or each other too.

use crate::error::{Error, Result};
use crate::geometry::outline::Outline;
use crate::geometry::polygon::Polygon;
use crate::raster::fixed::FixedPoint;
use crate::raster::polygon::WindingRule;
use glam::Vec4;
use std::path::Path;

/// Snapped primitives read from a text file, with their source lines.
#[derive(Clone, Debug, PartialEq)]
pub enum Shapes {
    /// A triangle soup.
    Triangles {
        /// The snapped triangles, in file order.
        triangles: Vec<[FixedPoint; 3]>,
        /// The 1-based line each triangle came from.
        lines: Vec<usize>,
        /// Each triangle's look, as its line gave it.
        looks: Vec<Look>,
    },
    /// A set of line segments.
    Lines {
        /// The snapped segments, in file order.
        segments: Vec<[FixedPoint; 2]>,
        /// The 1-based line each segment came from.
        lines: Vec<usize>,
    },
}

/// The colour and depth a triangle line gives its triangles.
#[derive(Copy, Clone, Debug, Default, PartialEq)]
pub struct Look {
    /// `rgba R G B A`: the colour, sRGB-encoded, and its opacity; `None`:
    /// the scene's colour for its place in the file.
    pub color: Option<Vec4>,
    /// `depth Z`, in `[0, 1]`; 0 when not given.
    pub depth: f32,
}

/// Splits a line's content into its numbers and its look (`rgba` and
/// `depth`, after the numbers).
fn split_look(content: &str) -> std::result::Result<(&str, Look), String> {
    // The look starts at the first word `rgba` or `depth`; any other word
    // stays with the numbers, which say it is not one.
    let mut offset = 0;
    let mut start = None;
    for word in content.split_inclusive(char::is_whitespace) {
        if matches!(word.trim(), "rgba" | "depth") {
            start = Some(offset);
            break;
        }
        offset += word.len();
    }
    let Some(start) = start else {
        return Ok((content, Look::default()));
    };
    let (numbers, rest) = content.split_at(start);
    let mut look = Look::default();
    let mut words = rest.split_whitespace().peekable();
    while let Some(word) = words.next() {
        let count = match word {
            "rgba" => 4,
            "depth" => 1,
            other => {
                return Err(format!(
                    "`{other}`: after the coordinates a line takes `rgba R G B A` and `depth Z`"
                ))
            }
        };
        let mut values = Vec::with_capacity(count);
        for _ in 0..count {
            let Some(token) = words.next_if(|w| *w != "rgba" && *w != "depth") else {
                return Err(format!("`{word}` takes {count} number(s) in [0, 1]"));
            };
            match token.parse::<f32>() {
                Ok(v) if (0.0..=1.0).contains(&v) => values.push(v),
                _ => return Err(format!("`{word}`: `{token}` is not a number in [0, 1]")),
            }
        }
        if word == "rgba" {
            look.color = Some(Vec4::from_slice(&values));
        } else {
            look.depth = values[0];
        }
    }
    Ok((numbers, look))
}

impl Shapes {
    /// Number of primitives.
    pub fn len(&self) -> usize {
        match self {
            Shapes::Triangles { triangles, .. } => triangles.len(),
            Shapes::Lines { segments, .. } => segments.len(),
        }
    }

    /// True when the file held no primitive.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// One primitive of a file, as read: a triangle, a segment, or a
/// polygon's rings (the outer ring first), each with its 1-based line.
enum Record {
    Triangle([FixedPoint; 3], usize, Look),
    Segment([FixedPoint; 2], usize),
    Polygon(PolygonRings, Look),
}

/// A polygon being read: its rings (the outer ring first, then the holes),
/// each with its line.
type PolygonRings = Vec<(usize, Vec<FixedPoint>)>;

/// Parses the text of a triangle soup or line set. `path` is used in
/// error messages only.
pub fn parse_shapes(text: &str, path: &Path) -> Result<Shapes> {
    let (mut triangles, mut segments, mut lines, mut looks) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for record in parse_records(text, path)? {
        match record {
            Record::Triangle(t, line, look) => {
                triangles.push(t);
                lines.push(line);
                looks.push(look);
            }
            Record::Segment(s, line) => {
                segments.push(s);
                lines.push(line);
            }
            Record::Polygon(rings, look) => {
                let line_no = rings[0].0;
                let pieces = simple_polygon(rings, path)?
                    .triangulate()
                    .map_err(|e| e.at_line(path, line_no))?;
                lines.extend(std::iter::repeat_n(line_no, pieces.len()));
                looks.extend(std::iter::repeat_n(look, pieces.len()));
                triangles.extend(pieces);
            }
        }
    }
    Ok(if segments.is_empty() {
        Shapes::Triangles {
            triangles,
            lines,
            looks,
        }
    } else {
        Shapes::Lines { segments, lines }
    })
}

/// The polygons of a file, to be filled directly by a polygon back-end.
#[derive(Clone, Debug, PartialEq)]
pub struct PolygonFile {
    /// Each polygon's rings, its holes wound against its outer ring; a
    /// triangle line is a polygon of one ring of 3 vertices.
    pub outlines: Vec<Outline>,
    /// The 1-based line each polygon came from.
    pub lines: Vec<usize>,
    /// Each polygon's look.
    pub looks: Vec<Look>,
}

/// Parses the text of a polygon file (triangles and polygons) for a
/// polygon back-end. With a winding rule given (`fill`), any rings are
/// taken, crossing themselves and each other; without one, each polygon
/// must be simple, as for triangulation, and is refused with the same
/// message. A line set is refused.
pub fn parse_polygons(text: &str, path: &Path, fill: Option<WindingRule>) -> Result<PolygonFile> {
    let mut file = PolygonFile {
        outlines: Vec::new(),
        lines: Vec::new(),
        looks: Vec::new(),
    };
    for record in parse_records(text, path)? {
        let (outline, line, look) = match record {
            Record::Triangle(t, line, look) => (Outline::new(vec![t.to_vec()])?, line, look),
            Record::Segment(_, line) => return Err(Error::Parse {
                path: path.to_path_buf(),
                line: Some(line),
                message:
                    "a polygon back-end fills triangles and polygons; this file holds line segments"
                        .into(),
            }),
            Record::Polygon(rings, look) => {
                let line = rings[0].0;
                let outline = match fill {
                    Some(_) => {
                        let mut points = rings.into_iter().map(|r| r.1);
                        let outer = points.next().unwrap_or_default();
                        Outline::with_holes(outer, points.collect())
                            .map_err(|e| e.at_line(path, line))?
                    }
                    None => Outline::of_polygon(&simple_polygon(rings, path)?),
                };
                (outline, line, look)
            }
        };
        file.outlines.push(outline);
        file.lines.push(line);
        file.looks.push(look);
    }
    Ok(file)
}

/// The rings read, checked to be a simple polygon (the error at the
/// faulty ring's line).
fn simple_polygon(rings: PolygonRings, path: &Path) -> Result<Polygon> {
    let ring_lines: Vec<usize> = rings.iter().map(|r| r.0).collect();
    let mut points = rings.into_iter().map(|r| r.1);
    let outer = points.next().unwrap_or_default();
    Polygon::with_faulty_ring(outer, points.collect())
        .map_err(|(ring, e)| e.at_line(path, ring_lines[ring]))
}

/// Reads the records of a file: the grammar of triangles, polygons and
/// segments, and the rule that a file holds either triangles and polygons
/// or segments.
fn parse_records(text: &str, path: &Path) -> Result<Vec<Record>> {
    let mut records = Vec::new();
    let (mut triangles, mut segments) = (false, false);
    let mut polygon: Option<(PolygonRings, Look)> = None;
    // A UTF-8 byte-order mark, as some editors write, is not content.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    for (index, raw_line) in text.lines().enumerate() {
        let line_no = index + 1;
        let content = raw_line.split('#').next().unwrap_or("").trim();
        if content.is_empty() {
            continue;
        }
        let at = |message: String| Error::Parse {
            path: path.to_path_buf(),
            line: Some(line_no),
            message,
        };
        let (keyword, numbers_text) = match content.split_once(char::is_whitespace) {
            Some((k @ ("polygon" | "hole"), rest)) => (Some(k), rest),
            _ => (None, content),
        };
        let given = numbers_text.len();
        let (numbers_text, look) = split_look(numbers_text).map_err(at)?;
        let has_look = numbers_text.len() < given;
        if has_look && keyword == Some("hole") {
            return Err(at(
                "a hole takes its polygon's look: give it on the `polygon` line".into(),
            ));
        }
        let numbers = numbers_text
            .split_whitespace()
            .map(|tok| {
                tok.parse::<f64>()
                    .map_err(|_| at(format!("`{tok}` is not a number")))
            })
            .collect::<Result<Vec<f64>>>()?;
        let points = numbers
            .chunks(2)
            .filter(|c| c.len() == 2)
            .map(|c| {
                Ok(FixedPoint {
                    x: crate::raster::fixed::Fixed::snap_f64(c[0])?,
                    y: crate::raster::fixed::Fixed::snap_f64(c[1])?,
                })
            })
            .collect::<Result<Vec<FixedPoint>>>()
            .map_err(|e| e.at_line(path, line_no))?;
        if let Some(keyword) = keyword {
            if segments {
                return Err(at(
                    "a file holds either triangles and polygons, or lines, not both".into(),
                ));
            }
            if numbers.len() % 2 != 0 || numbers.len() < 6 {
                return Err(at(format!(
                    "a {keyword} ring takes at least 3 points as x y pairs, found {} numbers",
                    numbers.len()
                )));
            }
            match (keyword, polygon.as_mut()) {
                ("hole", None) => return Err(at("`hole` before any `polygon`".into())),
                ("hole", Some((rings, _))) => rings.push((line_no, points)),
                _ => {
                    records.extend(polygon.take().map(|(r, l)| Record::Polygon(r, l)));
                    polygon = Some((vec![(line_no, points)], look));
                    triangles = true;
                }
            }
            continue;
        }
        records.extend(polygon.take().map(|(r, l)| Record::Polygon(r, l)));
        if has_look && numbers.len() == 4 {
            return Err(at(
                "`rgba` and `depth` are for triangles and polygons".into()
            ));
        }
        match numbers.len() {
            6 if !segments => {
                records.push(Record::Triangle(
                    [points[0], points[1], points[2]],
                    line_no,
                    look,
                ));
                triangles = true;
            }
            4 if !triangles => {
                records.push(Record::Segment([points[0], points[1]], line_no));
                segments = true;
            }
            6 | 4 => {
                return Err(at(
                    "a file holds either triangles (6 numbers) or lines (4 numbers), not both"
                        .to_string(),
                ))
            }
            n => {
                return Err(at(format!(
                    "expected 6 numbers (x0 y0 x1 y1 x2 y2) or 4 numbers (x0 y0 x1 y1), found {n}"
                )))
            }
        }
    }
    records.extend(polygon.map(|(r, l)| Record::Polygon(r, l)));
    Ok(records)
}

/// Reads and parses a triangle soup or line set file; `-` reads standard
/// input. A mesh file is refused with a message that says so, and so is a
/// file with nothing to draw (only blank lines and comments), as an empty
/// mesh is.
pub fn read_shapes(path: &Path) -> Result<Shapes> {
    let text = read_text(path)?;
    let shapes = parse_shapes(&text, path)?;
    if shapes.is_empty() {
        return Err(Error::Parse {
            path: path.to_path_buf(),
            line: None,
            message: "no triangle, polygon or line segment in it (only blank lines and comments)"
                .into(),
        });
    }
    Ok(shapes)
}

/// Reads and parses a polygon file for a polygon back-end
/// ([`parse_polygons`]); `-` reads standard input. A file with no
/// polygon is refused, as [`read_shapes`] refuses an empty one.
pub fn read_polygons(path: &Path, fill: Option<WindingRule>) -> Result<PolygonFile> {
    let text = read_text(path)?;
    let file = parse_polygons(&text, path, fill)?;
    if file.outlines.is_empty() {
        return Err(Error::Parse {
            path: path.to_path_buf(),
            line: None,
            message: "no triangle or polygon in it (only blank lines and comments)".into(),
        });
    }
    Ok(file)
}

/// The text of a file, or of standard input for `-`; a mesh refused.
fn read_text(path: &Path) -> Result<String> {
    if crate::geometry::mesh::Mesh::is_mesh_path(path) {
        return Err(Error::Parse {
            path: path.to_path_buf(),
            line: None,
            message: "this is a mesh; this command reads triangle soups, polygons and line sets (`render` and `compare` read meshes)".into(),
        });
    }
    if path.as_os_str() == "-" {
        std::io::read_to_string(std::io::stdin().lock())
    } else {
        std::fs::read_to_string(path)
    }
    .map_err(|e| Error::io(path, &e))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Shapes> {
        parse_shapes(text, Path::new("soup.txt"))
    }

    #[test]
    fn comments_and_blank_lines_are_skipped() {
        let s = parse("# header\n\n0 0 5 0 5 5 # first\n  0 5 0 0 5 5\n").unwrap();
        match s {
            Shapes::Triangles {
                triangles, lines, ..
            } => {
                assert_eq!(triangles.len(), 2);
                assert_eq!(lines, vec![3, 4]);
            }
            other => panic!("expected triangles, got {other:?}"),
        }
    }

    #[test]
    fn errors_name_the_file_and_line() {
        let cases = [
            ("0 0 1 1 2\n", "soup.txt:1: expected 6 numbers"),
            (
                "0 0 5 0 5 5\n0 0 x 0 5 5\n",
                "soup.txt:2: `x` is not a number",
            ),
            (
                "0 0 5 0 5 5\n\n0 0 NaN 0 5 5\n",
                "soup.txt:3: coordinate NaN is not a finite",
            ),
            (
                "0 0 5 0 inf 5\n",
                "soup.txt:1: coordinate inf is not a finite",
            ),
            (
                "0 0 5 0 1e9 5\n",
                "soup.txt:1: coordinate 1000000000 px is outside the guard band",
            ),
            ("0 0 5 0 5 5\n0 0 1 1\n", "soup.txt:2: a file holds either"),
        ];
        for (text, expected) in cases {
            let msg = parse(text).unwrap_err().to_string();
            assert!(
                msg.starts_with(expected),
                "{msg:?} should start with {expected:?}"
            );
        }
    }

    #[test]
    fn polygons_are_triangulated_with_their_holes() {
        let s =
            parse("polygon 0 0 20 0 20 14 0 14\nhole 6 4 14 4 10 10\n0 20 4 20 0 24\n").unwrap();
        match s {
            Shapes::Triangles {
                triangles, lines, ..
            } => {
                // A square with a triangular hole: 7 vertices, 7 triangles
                // (n + 2h - 2 = 7 + 2 - 2), then the loose triangle.
                assert_eq!(triangles.len(), 8);
                assert_eq!(lines, vec![1, 1, 1, 1, 1, 1, 1, 3]);
            }
            other => panic!("expected triangles, got {other:?}"),
        }
        for (text, expected) in [
            (
                "hole 0 0 1 0 0 1\n",
                "soup.txt:1: `hole` before any `polygon`",
            ),
            (
                "polygon 0 0 1 0\n",
                "soup.txt:1: a polygon ring takes at least 3 points",
            ),
            (
                "0 0 1 1\npolygon 0 0 1 0 0 1\n",
                "soup.txt:2: a file holds either",
            ),
        ] {
            let msg = parse(text).unwrap_err().to_string();
            assert!(
                msg.starts_with(expected),
                "{msg:?} should start with {expected:?}"
            );
        }
    }

    /// A line's look: colour and depth, in either order, on triangles and
    /// on a polygon's every triangle; bad looks named with their line.
    #[test]
    fn triangles_carry_their_colour_and_depth() {
        let text = "0 0 5 0 5 5 rgba 1 0 0 0.5 depth 0.25\n\
                    0 5 0 0 5 5 depth 1\n\
                    polygon 0 0 9 0 9 9 0 9 rgba 0 0 1 1\n";
        let Shapes::Triangles { looks, .. } = parse(text).unwrap() else {
            panic!("expected triangles");
        };
        let red = Some(Vec4::new(1.0, 0.0, 0.0, 0.5));
        let blue = Some(Vec4::new(0.0, 0.0, 1.0, 1.0));
        assert_eq!(looks.len(), 4);
        assert_eq!(
            looks[0],
            Look {
                color: red,
                depth: 0.25
            }
        );
        assert_eq!(
            looks[1],
            Look {
                color: None,
                depth: 1.0
            }
        );
        assert_eq!(
            looks[2..],
            [Look {
                color: blue,
                depth: 0.0
            }; 2]
        );
        for (text, expected) in [
            (
                "0 0 5 0 5 5 rgba 1 0 0\n",
                "soup.txt:1: `rgba` takes 4 number(s)",
            ),
            (
                "0 0 5 0 5 5 depth 2\n",
                "soup.txt:1: `depth`: `2` is not a number in [0, 1]",
            ),
            (
                "0 0 5 0 5 5 depth NaN\n",
                "soup.txt:1: `depth`: `NaN` is not",
            ),
            (
                "0 0 5 0 5 5 rgb 1 0 0\n",
                "soup.txt:1: `rgb` is not a number",
            ),
            (
                "0 0 5 0 5 5 depth 0.5 red\n",
                "soup.txt:1: `red`: after the coordinates",
            ),
            (
                "0 0 7 3 depth 0.5\n",
                "soup.txt:1: `rgba` and `depth` are for triangles",
            ),
            (
                "polygon 0 0 9 0 9 9\nhole 1 1 2 1 1 2 depth 0\n",
                "soup.txt:2: a hole takes",
            ),
        ] {
            let msg = parse(text).unwrap_err().to_string();
            assert!(
                msg.starts_with(expected),
                "{msg:?} should start with {expected:?}"
            );
        }
    }

    /// A self-intersecting polygon: filled when a winding rule is given,
    /// refused for triangulation and without a rule with today's message.
    #[test]
    fn polygons_read_for_filling_take_crossing_rings_given_a_rule() {
        let bowtie = "polygon 0 0 4 4 4 0 0 4\n0 9 3 9 0 12\n";
        let path = Path::new("soup.txt");
        let file = parse_polygons(bowtie, path, Some(WindingRule::Nonzero)).unwrap();
        assert_eq!(file.lines, vec![1, 2]);
        assert_eq!(
            file.outlines[1].rings,
            vec![vec![p(0, 9), p(3, 9), p(0, 12)]]
        );
        for refused in [
            parse(bowtie).unwrap_err(),
            parse_polygons(bowtie, path, None).unwrap_err(),
        ] {
            assert_eq!(
                refused.to_string(),
                "soup.txt:1: polygon is not simple: two edges touch or cross"
            );
        }
        let lines = parse_polygons("0 0 7 3\n", path, Some(WindingRule::EvenOdd));
        assert!(lines
            .unwrap_err()
            .to_string()
            .contains("holds line segments"));
        // A hole wound as its outer ring is turned against it.
        let holed = "polygon 0 0 9 0 9 9 0 9\nhole 3 3 6 3 6 6 3 6\n";
        let file = parse_polygons(holed, path, None).unwrap();
        let rings = &file.outlines[0].rings;
        assert_eq!(rings[1], vec![p(3, 6), p(6, 6), p(6, 3), p(3, 3)]);
    }

    fn p(x: i64, y: i64) -> FixedPoint {
        FixedPoint::from_raw(x * 256, y * 256).unwrap()
    }

    #[test]
    fn line_sets_are_recognised() {
        let s = parse("0 0 7 3\n1 1 2 9\n").unwrap();
        assert!(matches!(s, Shapes::Lines { ref segments, .. } if segments.len() == 2));
    }
}
