//! The one palette every picture, page and legend uses.
//!
//! A colour means the same thing in every tool: the grid pictures, the
//! fill-rule heat maps, the `compare` report, the lab, the depth-buffer
//! picture and the check report. The colours are Okabe and Ito's
//! colour-blind safe set (distinguishable with any of the common colour
//! vision deficiencies), each given one [`Role`]:
//!
//! | colour | roles |
//! |---|---|
//! | bluish green | a fragment drawn; a correct pixel; a fragment kept by the depth test |
//! | sky blue | a sample tested and found outside |
//! | orange | a gap (no triangle draws the pixel); a pixel missing from an answer |
//! | vermillion | drawn once too often; an extra pixel in an answer; a pixel that differs from the reference |
//! | reddish purple | drawn two or more times too often; a partially covered block |
//! | grey | a fragment hidden by the depth test; a block outside the triangle |
//! | light grey | a pixel off the target, shown around it |
//! | blue | a block inside the triangle |
//! | black | the true geometry: edges, vertices, the ideal line |
//! | dark grey | a pixel centre, where the sample is taken |
//!
//! Where two roles share a colour they mean the same thing seen from two
//! tools (a gap in a heat map is a pixel missing from the answer). Each
//! triangle of a picture with several has its own colour,
//! [`triangle_colour`], in the same set.
//!
//! Every picture carries its legend: [`Legend::to_svg`] draws one into an
//! SVG picture (and so into the PNG rendered from it), [`Legend::to_html`]
//! writes one into a page, styled by [`css`].
//!
//! ```
//! use rasterlab::teaching::palette::{Legend, Role};
//!
//! assert_eq!(Role::Drawn.hex(), "#009e73");
//! assert_eq!(Role::Gap.rgb(), Role::Missing.rgb());
//! let legend = Legend::new(&[Role::Drawn, Role::TestedOutside]);
//! assert!(legend.to_html().contains("tested, outside"));
//! let (svg, height) = legend.to_svg(0.0, 0.0, 400.0);
//! assert!(svg.contains("#56b4e9") && height > 0.0);
//! ```

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
}

impl Role {
    /// Every role, in legend order.
    pub const ALL: [Role; 19] = [
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
    ];

    /// The role's colour.
    pub const fn rgb(self) -> [u8; 3] {
        match self {
            Role::Untested => WHITE,
            Role::Drawn | Role::Correct | Role::Kept => BLUISH_GREEN,
            Role::TestedOutside => SKY_BLUE,
            // Bluish green faded three quarters towards white: "as it must be".
            Role::AsReference => [191, 231, 220],
            Role::Gap | Role::Missing => ORANGE,
            Role::DoubleDraw | Role::Extra | Role::Differs => VERMILLION,
            Role::DrawnTwiceMore | Role::BlockPartial => REDDISH_PURPLE,
            Role::Hidden | Role::BlockOutside => GREY,
            Role::BlockInside => BLUE,
            Role::Geometry => BLACK,
            Role::PixelCentre => DARK_GREY,
            Role::OffTarget => LIGHT_GREY,
        }
    }

    /// The colour as `#rrggbb`.
    pub fn hex(self) -> String {
        hex(self.rgb())
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
            Role::Missing => "missing: in the answer, not drawn",
            Role::Extra => "extra: drawn, not in the answer",
            Role::Correct => "correct",
            Role::Kept => "kept by the depth test",
            Role::Hidden => "hidden by the depth test",
            Role::Geometry => "true edges and vertices",
            Role::BlockInside => "block inside (I)",
            Role::BlockOutside => "block outside (O)",
            Role::BlockPartial => "block partly covered (P)",
            Role::Differs => "differs from the reference",
            Role::PixelCentre => "pixel centre (the sample point)",
            Role::OffTarget => "off the target",
        }
    }
}

/// The colours of triangles 0, 1, 2, ... in a picture of several (after
/// the eighth they repeat): blue and vermillion first, the course's blue
/// and red triangles of the depth-buffer example.
pub const TRIANGLE_COLOURS: [[u8; 3]; 8] = [
    BLUE,
    VERMILLION,
    BLUISH_GREEN,
    REDDISH_PURPLE,
    ORANGE,
    SKY_BLUE,
    YELLOW,
    GREY,
];

/// Triangle `index`'s colour.
pub fn triangle_colour(index: usize) -> [u8; 3] {
    TRIANGLE_COLOURS[index % TRIANGLE_COLOURS.len()]
}

/// A colour as `#rrggbb`.
pub fn hex([r, g, b]: [u8; 3]) -> String {
    format!("#{r:02x}{g:02x}{b:02x}")
}

/// `colour` faded towards white by `t` (0: unchanged, 1: white): cells
/// filled with a colour that labels can be read on.
pub fn faded(colour: [u8; 3], t: f32) -> [u8; 3] {
    colour.map(|c| (f32::from(c) + (255.0 - f32::from(c)) * t.clamp(0.0, 1.0)).round() as u8)
}

/// One swatch of a legend.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LegendEntry {
    /// The role's key (`drawn`), or `triangle-N`.
    pub key: String,
    /// The colour.
    pub rgb: [u8; 3],
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
    pub fn with(mut self, role: Role) -> Legend {
        self.entries.push(LegendEntry {
            key: role.key().to_string(),
            rgb: role.rgb(),
            label: role.label().to_string(),
        });
        self
    }

    /// This legend and a swatch per triangle, triangle `i` labelled
    /// `labels[i]` (`triangle 0, z = 0.5`, say).
    pub fn with_triangles(mut self, labels: &[String]) -> Legend {
        for (i, label) in labels.iter().enumerate() {
            self.entries.push(LegendEntry {
                key: format!("triangle-{i}"),
                rgb: triangle_colour(i),
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
    /// one `<span class="entry" data-role=...>` per swatch), styled by
    /// [`css`].
    pub fn to_html(&self) -> String {
        let mut h = String::from("<div class=\"legend\" data-palette=\"okabe-ito\">");
        for e in &self.entries {
            let _ = write!(
                h,
                "<span class=\"entry\" data-role=\"{}\"><span class=\"swatch\" style=\"background:{}\"></span>{}</span>",
                e.key,
                hex(e.rgb),
                escape(&e.label)
            );
        }
        h.push_str("</div>");
        h
    }

    /// The legend drawn into an SVG picture, its top left corner at `(x,
    /// y)`, wrapped to rows at most `width` wide; returns the SVG and the
    /// height it takes.
    pub fn to_svg(&self, x: f64, y: f64, width: f64) -> (String, f64) {
        if self.entries.is_empty() {
            return (String::new(), 0.0);
        }
        let mut svg = String::from("<g class=\"legend\" data-palette=\"okabe-ito\">");
        let (mut cx, mut row) = (x, 0.0);
        for e in &self.entries {
            // DejaVu Sans averages about 0.55 em per character.
            let w = 18.0 + e.label.chars().count() as f64 * LEGEND_FONT * 0.56 + 14.0;
            if cx > x && cx + w > x + width {
                cx = x;
                row += LEGEND_ROW;
            }
            let top = y + row + 3.0;
            let _ = write!(
                svg,
                "<path class=\"swatch\" d=\"M{cx} {top}h13v13h-13Z\" fill=\"{}\" stroke=\"#555\" stroke-width=\"1\"/><text x=\"{}\" y=\"{}\" font-size=\"{LEGEND_FONT}\">{}</text>",
                hex(e.rgb),
                cx + 18.0,
                top + 11.5,
                escape(&e.label)
            );
            cx += w;
        }
        svg.push_str("</g>\n");
        (svg, row + LEGEND_ROW + 4.0)
    }
}

/// Text made safe for XML and HTML.
pub(crate) fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The palette for pages: CSS custom properties (`--drawn: #009e73;`, one
/// per role, and `--triangle-0` ...) and the legend's style.
pub fn css() -> String {
    let mut css = String::from(":root {");
    for role in Role::ALL {
        let _ = write!(css, " --{}: {};", role.key(), role.hex());
    }
    for (i, &c) in TRIANGLE_COLOURS.iter().enumerate() {
        let _ = write!(css, " --triangle-{i}: {};", hex(c));
    }
    css.push_str(" }\n");
    css.push_str(".legend { display: flex; flex-wrap: wrap; gap: .3em 1.2em; margin: .4em 0; font-size: .95em; }\n.legend .swatch { display: inline-block; width: 1em; height: 1em; margin-right: .35em; vertical-align: middle; border: 1px solid #555; }\n");
    css
}

/// The palette for scripts: every role's colour by key, and the triangle
/// colours, as JSON (`{"roles": {"drawn": "#009e73", ...}, "labels": {...},
/// "triangles": [...]}`).
pub fn json() -> String {
    let roles: serde_json::Map<String, serde_json::Value> = Role::ALL
        .iter()
        .map(|r| (r.key().to_string(), r.hex().into()))
        .collect();
    let labels: serde_json::Map<String, serde_json::Value> = Role::ALL
        .iter()
        .map(|r| (r.key().to_string(), r.label().into()))
        .collect();
    let triangles: Vec<String> = TRIANGLE_COLOURS.iter().map(|&c| hex(c)).collect();
    serde_json::json!({ "roles": roles, "labels": labels, "triangles": triangles }).to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roles_that_share_a_colour_mean_the_same_thing() {
        // Every pair of roles with one colour is a pair listed here.
        let same = [
            [Role::Drawn, Role::Correct],
            [Role::Drawn, Role::Kept],
            [Role::Correct, Role::Kept],
            [Role::Gap, Role::Missing],
            [Role::DoubleDraw, Role::Extra],
            [Role::DoubleDraw, Role::Differs],
            [Role::Extra, Role::Differs],
            [Role::DrawnTwiceMore, Role::BlockPartial],
            [Role::Hidden, Role::BlockOutside],
        ];
        for a in Role::ALL {
            for b in Role::ALL {
                if a != b && a.rgb() == b.rgb() {
                    assert!(
                        same.contains(&[a, b]) || same.contains(&[b, a]),
                        "{a:?} {b:?}"
                    );
                }
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
    }

    #[test]
    fn a_long_legend_wraps_to_its_width() {
        let legend = Legend::new(&Role::ALL);
        let (_, one_row) = Legend::new(&[Role::Drawn]).to_svg(0.0, 0.0, 2000.0);
        let (_, narrow) = legend.to_svg(0.0, 0.0, 300.0);
        assert!(narrow >= 8.0 * one_row - 8.0 * 4.0, "{narrow} {one_row}");
    }
}
