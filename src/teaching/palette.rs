//! The one palette every picture, page and legend uses.
//!
//! A picture says two kinds of things: **states** (this pixel was drawn,
//! tested, left as a gap, drawn twice, hidden by the depth test...) and
//! **identities** (this is triangle 3). Each is told by a pair: a colour
//! and a [`Mark`], the way the colour is put on the picture. States fill
//! a pixel's cell (or mark part of it: a corner, a frame, a cross, a
//! dot); identities are edges, drawn as lines with a dash pattern and
//! named `T1`, `T2`, ... at the triangle's centre. So a colour may serve
//! a state and a triangle at once (vermillion fills a cell drawn once too
//! often, and outlines triangle 2 in dashes), but a (colour, mark) pair
//! has one meaning everywhere, and a picture's legend lists exactly the
//! pairs it draws ([`Legend`]).
//!
//! The colours are Okabe and Ito's colour-blind safe set. Two entries
//! of one picture with the same mark must differ by colour for every
//! reader: `tests/legends.rs` simulates protanopia, deuteranopia and
//! tritanopia (Machado, Oliveira and Fernandes 2009) on every picture's
//! legend and requires such colours to stay at least 15 CIELAB units
//! (CIE76 ΔE) apart.
//!
//! | legend entry | colour | mark |
//! |---|---|---|
//! | never looked at | white | fill |
//! | fragment (drawn); correct | bluish green | fill |
//! | tested, outside | sky blue | fill |
//! | as a watertight rule | bluish green, faded 60 % towards white | fill |
//! | gap; missing | orange | fill |
//! | drawn once too often; extra; differs from the reference | vermillion | fill |
//! | drawn twice or more too often | reddish purple | fill |
//! | kept by the depth test | yellow | fill |
//! | hidden by the depth test | grey | corner (with the count) |
//! | off the target | light grey | fill |
//! | my rasterizer: missing (lab) | orange | frame |
//! | my rasterizer: extra (lab) | vermillion | cross |
//! | pixel centre | dark grey | dot |
//! | true edges and vertices | black | solid line |
//! | block inside / outside / partly covered (`I`, `O`, `P`) | blue / grey / vermillion | block frame |
//! | triangle `T1` ... `T16` | blue, vermillion, reddish purple, orange | solid, dashed, dotted, dash-dot line |
//!
//! Where two states share a pair they mean the same thing seen from two
//! tools (a gap in a heat map is a pixel missing from the answer). The
//! triangles' pairs ([`triangle_colour`], [`triangle_mark`]) form a
//! Latin square: triangles 1-4 differ by colour *and* dash, and the 16
//! pairs are all different. A picture of more than [`MAX_TRIANGLES`]
//! triangles draws their edges as the true geometry, without names.
//!
//! Every picture carries its legend: [`Legend::to_svg`] draws one into an
//! SVG picture (and so into the PNG rendered from it), [`Legend::to_html`]
//! writes one into a page, styled by [`css`]; both draw each swatch the
//! way the picture draws its entry.
//!
//! ```
//! use rasterlab::teaching::{triangle_mark, Legend, Mark, Role};
//!
//! assert_eq!(Role::Drawn.hex(), "#009e73");
//! assert_eq!(Role::Gap.rgb(), Role::Missing.rgb());
//! assert_eq!(triangle_mark(1), Mark::Dashed);
//! let legend = Legend::new(&[Role::Drawn, Role::TestedOutside]);
//! assert!(legend.to_html().contains("tested, outside"));
//! let (svg, height) = legend.to_svg(0.0, 0.0, 400.0);
//! assert!(svg.contains("#56b4e9") && height > 0.0);
//! ```

use crate::markup::Markup;
use serde::Serialize;
use std::fmt::Write;

/// Okabe and Ito's bluish green.
const BLUISH_GREEN: [u8; 3] = [0, 158, 115];
/// Okabe and Ito's sky blue.
const SKY_BLUE: [u8; 3] = [86, 180, 233];
/// Okabe and Ito's orange.
const ORANGE: [u8; 3] = [230, 159, 0];
/// Okabe and Ito's vermillion.
const VERMILLION: [u8; 3] = [213, 94, 0];
/// Okabe and Ito's reddish purple.
const REDDISH_PURPLE: [u8; 3] = [204, 121, 167];
/// Okabe and Ito's blue.
const BLUE: [u8; 3] = [0, 114, 178];
/// Okabe and Ito's yellow.
const YELLOW: [u8; 3] = [240, 228, 66];
/// The grey beside the set.
const GREY: [u8; 3] = [153, 153, 153];
/// Dark grey: the dots of pixel centres.
const DARK_GREY: [u8; 3] = [51, 51, 51];
/// The grey faded towards white: the background off the target.
const LIGHT_GREY: [u8; 3] = [224, 224, 224];
/// Black.
const BLACK: [u8; 3] = [0, 0, 0];
/// White: a pixel no one looked at.
const WHITE: [u8; 3] = [255, 255, 255];

/// How a colour is put on a picture: with the colour, it makes the pair
/// that has one meaning.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Mark {
    /// The pixel's cell filled with the colour.
    Fill,
    /// A triangle in the cell's top right corner, with a count.
    Corner,
    /// A frame just inside the cell.
    Frame,
    /// A diagonal stroke across the cell.
    Cross,
    /// A dot at the cell's centre.
    Dot,
    /// A ring: a hollow dot.
    Ring,
    /// A block's dashed frame, with the block's letter.
    Block,
    /// A solid line: an edge.
    Line,
    /// A dashed line.
    Dashed,
    /// A dotted line.
    Dotted,
    /// A dash-dot line.
    DashDot,
}

impl Mark {
    /// The mark's name in pages and scripts (`dash-dot`).
    pub fn key(self) -> &'static str {
        match self {
            Mark::Fill => "fill",
            Mark::Corner => "corner",
            Mark::Frame => "frame",
            Mark::Cross => "cross",
            Mark::Dot => "dot",
            Mark::Ring => "ring",
            Mark::Block => "block",
            Mark::Line => "line",
            Mark::Dashed => "dashed",
            Mark::Dotted => "dotted",
            Mark::DashDot => "dash-dot",
        }
    }

    /// The SVG `stroke-dasharray` of a line or frame mark (`None`: solid,
    /// or not a line).
    pub fn dasharray(self) -> Option<&'static str> {
        match self {
            Mark::Dashed => Some("9 5"),
            Mark::Dotted => Some("2 4"),
            Mark::DashDot => Some("10 4 2 4"),
            Mark::Block => Some("6 3"),
            _ => None,
        }
    }

    /// Whether the mark is an edge: a line, solid or dashed.
    pub fn is_line(self) -> bool {
        matches!(
            self,
            Mark::Line | Mark::Dashed | Mark::Dotted | Mark::DashDot
        )
    }
}

/// What a colour says, the same in every picture and page.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Role {
    /// A pixel never looked at.
    Untested,
    /// A fragment emitted.
    Drawn,
    /// A sample tested and found outside.
    TestedOutside,
    /// A heat map's pixel covered as often as a watertight rule covers it.
    AsReference,
    /// A pixel inside the triangles' union that no triangle draws.
    Gap,
    /// A pixel drawn once more than a watertight rule draws it.
    DoubleDraw,
    /// A pixel drawn two or more times more than a watertight rule.
    DrawnTwiceMore,
    /// A pixel an answer has and the rasterizer under test did not draw.
    Missing,
    /// A pixel drawn that the answer does not have (or drawn twice).
    Extra,
    /// A pixel drawn that the answer has.
    Correct,
    /// A fragment the depth test kept (its depth is the one stored).
    Kept,
    /// A fragment the depth test hid behind a nearer one.
    Hidden,
    /// The true geometry: triangle edges, vertices, the ideal line.
    Geometry,
    /// A block wholly inside the triangle (every pixel drawn untested).
    BlockInside,
    /// A block wholly outside the triangle (no pixel tested).
    BlockOutside,
    /// A block the triangle's edges cross (tested pixel by pixel).
    BlockPartial,
    /// A pixel whose colour, depth or coverage differs from a reference
    /// back-end's.
    Differs,
    /// A pixel centre: the point where the pixel's sample is taken.
    PixelCentre,
    /// A pixel off the target, shown around it (a counterexample's
    /// margin).
    OffTarget,
    /// A sample of a pixel's multisample pattern that the triangle covers.
    SampleCovered,
    /// A sample of a pixel's multisample pattern that no triangle covers.
    SampleOutside,
}

impl Role {
    /// Every role, in legend order.
    pub const ALL: [Role; 21] = [
        Role::Untested,
        Role::Drawn,
        Role::TestedOutside,
        Role::AsReference,
        Role::Gap,
        Role::DoubleDraw,
        Role::DrawnTwiceMore,
        Role::Missing,
        Role::Extra,
        Role::Correct,
        Role::Kept,
        Role::Hidden,
        Role::Geometry,
        Role::BlockInside,
        Role::BlockOutside,
        Role::BlockPartial,
        Role::Differs,
        Role::PixelCentre,
        Role::OffTarget,
        Role::SampleCovered,
        Role::SampleOutside,
    ];

    /// The role's colour.
    pub const fn rgb(self) -> [u8; 3] {
        match self {
            Role::Untested => WHITE,
            Role::Drawn | Role::Correct => BLUISH_GREEN,
            Role::TestedOutside => SKY_BLUE,
            // Bluish green faded 60 % towards white: "as it must be".
            Role::AsReference => [153, 216, 199],
            // Light, so the depth printed on it reads, and apart from the
            // back-ends' drawn and tested cells shown beside it.
            Role::Kept => YELLOW,
            Role::Gap | Role::Missing => ORANGE,
            Role::DoubleDraw | Role::Extra | Role::Differs | Role::BlockPartial => VERMILLION,
            Role::DrawnTwiceMore => REDDISH_PURPLE,
            Role::Hidden | Role::BlockOutside => GREY,
            Role::BlockInside => BLUE,
            Role::Geometry | Role::SampleCovered | Role::SampleOutside => BLACK,
            Role::PixelCentre => DARK_GREY,
            Role::OffTarget => LIGHT_GREY,
        }
    }

    /// How the role's colour is put on a picture.
    pub const fn mark(self) -> Mark {
        match self {
            Role::Hidden => Mark::Corner,
            Role::Geometry => Mark::Line,
            Role::BlockInside | Role::BlockOutside | Role::BlockPartial => Mark::Block,
            Role::PixelCentre | Role::SampleCovered => Mark::Dot,
            Role::SampleOutside => Mark::Ring,
            _ => Mark::Fill,
        }
    }

    /// The colour as `#rrggbb`.
    pub fn hex(self) -> String {
        colour_hex(self.rgb())
    }

    /// The role's name in pages and scripts (`tested-outside`).
    pub fn key(self) -> &'static str {
        match self {
            Role::Untested => "untested",
            Role::Drawn => "drawn",
            Role::TestedOutside => "tested-outside",
            Role::AsReference => "as-reference",
            Role::Gap => "gap",
            Role::DoubleDraw => "double-draw",
            Role::DrawnTwiceMore => "drawn-twice-more",
            Role::Missing => "missing",
            Role::Extra => "extra",
            Role::Correct => "correct",
            Role::Kept => "kept",
            Role::Hidden => "hidden",
            Role::Geometry => "geometry",
            Role::BlockInside => "block-inside",
            Role::BlockOutside => "block-outside",
            Role::BlockPartial => "block-partial",
            Role::Differs => "differs",
            Role::PixelCentre => "pixel-centre",
            Role::OffTarget => "off-target",
            Role::SampleCovered => "sample-covered",
            Role::SampleOutside => "sample-outside",
        }
    }

    /// What the colour says, as the legend writes it.
    pub fn label(self) -> &'static str {
        match self {
            Role::Untested => "never looked at",
            Role::Drawn => "fragment (drawn)",
            Role::TestedOutside => "tested, outside",
            Role::AsReference => "as a watertight rule",
            Role::Gap => "gap: inside, drawn by no triangle",
            Role::DoubleDraw => "drawn once too often",
            Role::DrawnTwiceMore => "drawn twice or more too often",
            Role::Missing => "missing: expected, not drawn",
            Role::Extra => "extra: drawn, not expected",
            Role::Correct => "correct",
            Role::Kept => "kept by the depth test",
            Role::Hidden => "hidden by the depth test (how many)",
            Role::Geometry => "true edges and vertices",
            Role::BlockInside => "block inside (I)",
            Role::BlockOutside => "block outside (O)",
            Role::BlockPartial => "block partly covered (P)",
            Role::Differs => "differs from the reference",
            Role::PixelCentre => "pixel centre (the sample point)",
            Role::OffTarget => "off the target",
            Role::SampleCovered => "sample covered (multisampling)",
            Role::SampleOutside => "sample not covered",
        }
    }
}

/// The most triangles a picture tells apart: four colours, each with
/// four line patterns.
pub const MAX_TRIANGLES: usize = 16;

/// The triangles' colours: blue and vermillion first, the course's blue
/// and red triangles of the depth-buffer example.
pub const TRIANGLE_COLOURS: [[u8; 3]; 4] = [BLUE, VERMILLION, REDDISH_PURPLE, ORANGE];

/// The mip levels' colours on the level picture, level 0 first.
pub const LEVEL_COLOURS: [[u8; 3]; 7] = [
    BLUE,
    ORANGE,
    BLUISH_GREEN,
    VERMILLION,
    SKY_BLUE,
    YELLOW,
    REDDISH_PURPLE,
];

/// The triangles' line patterns.
pub const TRIANGLE_MARKS: [Mark; 4] = [Mark::Line, Mark::Dashed, Mark::Dotted, Mark::DashDot];

/// Triangle `index`'s colour (from 0; they repeat after
/// [`MAX_TRIANGLES`]).
pub fn triangle_colour(index: usize) -> [u8; 3] {
    TRIANGLE_COLOURS[index % TRIANGLE_COLOURS.len()]
}

/// Triangle `index`'s line pattern: shifted by one for each round of
/// the colours, so that no two of [`MAX_TRIANGLES`] triangles share
/// colour and pattern, and the first four differ in both.
pub fn triangle_mark(index: usize) -> Mark {
    let n = TRIANGLE_MARKS.len();
    TRIANGLE_MARKS[(index % n + index / n) % n]
}

/// Triangle `index`'s name on pictures: `T1` for the first.
pub fn triangle_name(index: usize) -> String {
    format!("T{}", index + 1)
}

/// A colour as `#rrggbb`.
pub fn colour_hex([r, g, b]: [u8; 3]) -> String {
    format!("#{r:02x}{g:02x}{b:02x}")
}

/// One swatch of a legend.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LegendEntry {
    /// The role's key (`drawn`), or `triangle-N` (from 0).
    pub key: String,
    /// The colour.
    pub rgb: [u8; 3],
    /// How the colour is drawn.
    pub mark: Mark,
    /// What it says.
    pub label: String,
}

/// The legend of one picture or page: the roles it shows, in order.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Legend {
    /// The swatches, in order.
    pub entries: Vec<LegendEntry>,
}

/// Legend text size in SVG pictures, in pixels.
const LEGEND_FONT: f64 = 13.0;
/// Height of one legend row in SVG pictures.
const LEGEND_ROW: f64 = 20.0;
/// A swatch's side; line swatches are twice as wide, to show the dashes.
const SWATCH: f64 = 14.0;

impl Legend {
    /// A legend of `roles`.
    pub fn new(roles: &[Role]) -> Legend {
        let mut legend = Legend::default();
        for &r in roles {
            legend = legend.with(r);
        }
        legend
    }

    /// This legend and one more role's swatch.
    pub fn with(self, role: Role) -> Legend {
        self.with_mark(role, role.mark(), role.label())
    }

    /// This legend and a swatch of `role`'s colour drawn as `mark`, saying
    /// `label` (the lab's "my rasterizer: missing", a frame).
    pub fn with_mark(mut self, role: Role, mark: Mark, label: &str) -> Legend {
        self.entries.push(LegendEntry {
            key: role.key().to_string(),
            rgb: role.rgb(),
            mark,
            label: label.to_string(),
        });
        self
    }

    /// This legend and a swatch per triangle, in its colour and line
    /// pattern, triangle `i` labelled `labels[i]` (`T1 (z = 0.5)`, say).
    pub fn with_triangles(mut self, labels: &[String]) -> Legend {
        for (i, label) in labels.iter().enumerate() {
            self.entries.push(LegendEntry {
                key: format!("triangle-{i}"),
                rgb: triangle_colour(i),
                mark: triangle_mark(i),
                label: label.clone(),
            });
        }
        self
    }

    /// Whether the legend has a swatch for `role`.
    pub fn has(&self, role: Role) -> bool {
        self.entries.iter().any(|e| e.key == role.key())
    }

    /// The legend as HTML (`<div class="legend" data-palette="okabe-ito">`,
    /// one `<span class="entry" data-role=... data-colour=... data-mark=...>`
    /// per swatch, the swatch a small SVG), styled by the palette's style
    /// sheet.
    pub fn to_html(&self) -> String {
        let mut m = Markup::new();
        m.open(
            "div",
            &[("class", &"legend"), ("data-palette", &"okabe-ito")],
        );
        for e in &self.entries {
            open_entry(&mut m, "span", e);
            let width = swatch_width(e.mark);
            m.open(
                "svg",
                &[
                    ("class", &"swatch"),
                    ("xmlns", &"http://www.w3.org/2000/svg"),
                    ("width", &(width + 2.0)),
                    ("height", &(SWATCH + 2.0)),
                    (
                        "viewBox",
                        &format_args!("0 0 {} {}", width + 2.0, SWATCH + 2.0),
                    ),
                ],
            );
            swatch(&mut m, e, 1.0, 1.0);
            m.close("svg");
            m.text(&e.label).close("span");
        }
        m.close("div");
        m.finish()
    }

    /// The legend drawn into an SVG picture, its top left corner at `(x,
    /// y)`, wrapped to rows at most `width` wide; returns the SVG and the
    /// height it takes.
    pub fn to_svg(&self, x: f64, y: f64, width: f64) -> (String, f64) {
        if self.entries.is_empty() {
            return (String::new(), 0.0);
        }
        let mut m = Markup::new();
        m.open("g", &[("class", &"legend"), ("data-palette", &"okabe-ito")]);
        let (mut cx, mut row) = (x, 0.0);
        for e in &self.entries {
            let sw = swatch_width(e.mark);
            // DejaVu Sans averages about 0.55 em per character.
            let w = sw + 5.0 + e.label.chars().count() as f64 * LEGEND_FONT * 0.56 + 14.0;
            if cx > x && cx + w > x + width {
                cx = x;
                row += LEGEND_ROW;
            }
            let top = y + row + 3.0;
            open_entry(&mut m, "g", e);
            swatch(&mut m, e, cx, top);
            m.element(
                "text",
                &[
                    ("x", &(cx + sw + 5.0)),
                    ("y", &(top + 11.5)),
                    ("font-size", &LEGEND_FONT),
                ],
                &e.label,
            );
            m.close("g");
            cx += w;
        }
        m.close("g").newline();
        (m.finish(), row + LEGEND_ROW + 4.0)
    }
}

/// Opens element `name` of an entry, with the attributes that name its
/// meaning and its pair, for pages, scripts and tests.
fn open_entry(m: &mut Markup, name: &str, e: &LegendEntry) {
    m.open(
        name,
        &[
            ("class", &"entry"),
            ("data-role", &e.key),
            ("data-colour", &colour_hex(e.rgb)),
            ("data-mark", &e.mark),
        ],
    );
}

impl std::fmt::Display for Mark {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.key())
    }
}

/// How wide `mark`'s swatch is.
fn swatch_width(mark: Mark) -> f64 {
    if mark.is_line() {
        2.0 * SWATCH
    } else {
        SWATCH
    }
}

/// One swatch, its top left corner at `(x, y)`, drawn as the picture
/// draws the entry.
fn swatch(m: &mut Markup, e: &LegendEntry, x: f64, y: f64) {
    let colour = colour_hex(e.rgb);
    let s = SWATCH;
    let frame = |m: &mut Markup, fill: &str| {
        m.empty(
            "rect",
            &[
                ("x", &x),
                ("y", &y),
                ("width", &s),
                ("height", &s),
                ("fill", &fill),
                ("stroke", &"#555"),
                ("stroke-width", &1),
            ],
        );
    };
    match e.mark {
        Mark::Fill => frame(m, &colour),
        Mark::Corner => {
            frame(m, "white");
            m.empty(
                "path",
                &[
                    (
                        "d",
                        &format_args!("M{} {y}h{}v{}Z", x + s * 0.4, s * 0.6, s * 0.6),
                    ),
                    ("fill", &colour),
                ],
            );
        }
        Mark::Frame => {
            frame(m, "white");
            m.empty(
                "rect",
                &[
                    ("x", &(x + 2.5)),
                    ("y", &(y + 2.5)),
                    ("width", &(s - 5.0)),
                    ("height", &(s - 5.0)),
                    ("fill", &"none"),
                    ("stroke", &colour),
                    ("stroke-width", &2.5),
                ],
            );
        }
        Mark::Cross => {
            frame(m, "white");
            m.empty(
                "line",
                &[
                    ("x1", &(x + 2.0)),
                    ("y1", &(y + 2.0)),
                    ("x2", &(x + s - 2.0)),
                    ("y2", &(y + s - 2.0)),
                    ("stroke", &colour),
                    ("stroke-width", &2.5),
                ],
            );
        }
        Mark::Dot => {
            frame(m, "white");
            m.empty(
                "circle",
                &[
                    ("cx", &(x + s / 2.0)),
                    ("cy", &(y + s / 2.0)),
                    ("r", &2.5),
                    ("fill", &colour),
                ],
            );
        }
        Mark::Ring => {
            frame(m, "white");
            m.empty(
                "circle",
                &[
                    ("cx", &(x + s / 2.0)),
                    ("cy", &(y + s / 2.0)),
                    ("r", &3.0),
                    ("fill", &"white"),
                    ("stroke", &colour),
                    ("stroke-width", &1.2),
                ],
            );
        }
        Mark::Block => {
            m.empty(
                "rect",
                &[
                    ("x", &(x + 1.0)),
                    ("y", &(y + 1.0)),
                    ("width", &(s - 2.0)),
                    ("height", &(s - 2.0)),
                    ("fill", &"none"),
                    ("stroke", &colour),
                    ("stroke-width", &2.5),
                    ("stroke-dasharray", &"4 2"),
                ],
            );
        }
        Mark::Line | Mark::Dashed | Mark::Dotted | Mark::DashDot => {
            m.empty(
                "line",
                &[
                    ("x1", &x),
                    ("y1", &(y + s / 2.0)),
                    ("x2", &(x + 2.0 * s)),
                    ("y2", &(y + s / 2.0)),
                    ("stroke", &colour),
                    ("stroke-width", &2.5),
                    ("stroke-dasharray", &e.mark.dasharray().unwrap_or("none")),
                ],
            );
        }
    }
}

/// The palette for pages: CSS custom properties (`--drawn: #009e73;`, one
/// per role, and `--triangle-0` ...) and the legend's style.
pub fn css() -> String {
    let mut css = String::from(":root {");
    for role in Role::ALL {
        let _ = write!(css, " --{}: {};", role.key(), role.hex());
    }
    for (i, &c) in TRIANGLE_COLOURS.iter().enumerate() {
        let _ = write!(css, " --triangle-{i}: {};", colour_hex(c));
    }
    css.push_str(" }\n");
    css.push_str(".legend { display: flex; flex-wrap: wrap; gap: .3em 1.2em; margin: .4em 0; font-size: .95em; }\n.legend .swatch { display: inline-block; margin-right: .35em; vertical-align: middle; }\n");
    css
}

/// The palette for scripts, as JSON: every role's colour and label by
/// key, each triangle's colour and line pattern (its `stroke-dasharray`,
/// `null` for solid), up to [`MAX_TRIANGLES`] (`{"roles": {"drawn":
/// "#009e73", ...}, "labels": {...}, "triangles": [{"colour": "#0072b2",
/// "dash": null}, ...]}`).
pub fn json() -> String {
    let roles: serde_json::Map<String, serde_json::Value> = Role::ALL
        .iter()
        .map(|r| (r.key().to_string(), r.hex().into()))
        .collect();
    let labels: serde_json::Map<String, serde_json::Value> = Role::ALL
        .iter()
        .map(|r| (r.key().to_string(), r.label().into()))
        .collect();
    let triangles: Vec<serde_json::Value> = (0..MAX_TRIANGLES)
        .map(|i| {
            serde_json::json!({
                "colour": colour_hex(triangle_colour(i)),
                "dash": triangle_mark(i).dasharray(),
            })
        })
        .collect();
    serde_json::json!({ "roles": roles, "labels": labels, "triangles": triangles }).to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roles_that_share_a_colour_and_mark_mean_the_same_thing() {
        // Every pair of roles drawn alike is a pair listed here.
        let same = [
            [Role::Drawn, Role::Correct],
            [Role::Gap, Role::Missing],
            [Role::DoubleDraw, Role::Extra],
            [Role::DoubleDraw, Role::Differs],
            [Role::Extra, Role::Differs],
        ];
        for a in Role::ALL {
            for b in Role::ALL {
                if a != b && (a.rgb(), a.mark()) == (b.rgb(), b.mark()) {
                    assert!(
                        same.contains(&[a, b]) || same.contains(&[b, a]),
                        "{a:?} {b:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn no_two_of_sixteen_triangles_and_no_role_are_drawn_alike() {
        let pairs: std::collections::HashSet<([u8; 3], Mark)> = (0..MAX_TRIANGLES)
            .map(|i| (triangle_colour(i), triangle_mark(i)))
            .collect();
        assert_eq!(pairs.len(), MAX_TRIANGLES);
        for r in Role::ALL {
            assert!(!pairs.contains(&(r.rgb(), r.mark())), "{r:?}");
        }
        // The first four differ in colour and in pattern.
        for i in 0..4 {
            for j in 0..i {
                assert_ne!(triangle_colour(i), triangle_colour(j));
                assert_ne!(triangle_mark(i), triangle_mark(j));
            }
        }
    }

    #[test]
    fn the_css_and_json_name_every_role() {
        let (css, json) = (css(), json());
        for r in Role::ALL {
            assert!(
                css.contains(&format!("--{}: {};", r.key(), r.hex())),
                "{r:?}"
            );
            assert!(
                json.contains(&format!("\"{}\":\"{}\"", r.key(), r.hex())),
                "{r:?}"
            );
        }
        assert!(
            json.contains("{\"colour\":\"#d55e00\",\"dash\":\"9 5\"}"),
            "{json}"
        );
    }

    #[test]
    fn a_long_legend_wraps_to_its_width() {
        let legend = Legend::new(&Role::ALL);
        let (_, one_row) = Legend::new(&[Role::Drawn]).to_svg(0.0, 0.0, 2000.0);
        let (_, narrow) = legend.to_svg(0.0, 0.0, 300.0);
        assert!(narrow >= 8.0 * one_row - 8.0 * 4.0, "{narrow} {one_row}");
    }
}
