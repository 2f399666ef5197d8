//! A grid picture as SVG, sharp at any zoom: the caption, pixel indices
//! on both axes, each pixel a cell with its centre (the sample point)
//! marked, the multisample points, the hidden fragments' corners, the
//! true geometry (edges, ideal lines, blocks with their classes) with the
//! names the traces use (`v0`-`v2`, `E0`-`E2`, or `T1`, `T2`, ...), and
//! the legend below.

use super::{block_style, GridPicture, MIN_SHORT_SIDE};
use crate::markup::Markup;
use crate::teaching::palette::{colour_hex, triangle_colour, triangle_name, Mark, Role};

/// Pixels per cell in the SVG, at least.
const SVG_CELL: f64 = 32.0;
/// Pixels per cell in the SVG, at most (a grid of one cell).
const SVG_CELL_MAX: f64 = 256.0;
/// The longest side of the grid drawn in an SVG picture, in pixels: large
/// grids get smaller cells.
const SVG_GRID_MAX: f64 = 4096.0;

impl GridPicture {
    /// Pixels per cell in the SVG: at least 32, more for a small grid (its
    /// short side at least [`MIN_SHORT_SIDE`]), fewer for a grid whose
    /// long side would pass 4096 pixels.
    pub fn svg_cell(&self) -> f64 {
        let short = f64::from(self.width.min(self.height));
        let long = f64::from(self.width.max(self.height));
        (f64::from(MIN_SHORT_SIDE) / short)
            .ceil()
            .clamp(SVG_CELL, SVG_CELL_MAX)
            .min((SVG_GRID_MAX / long).floor())
            .max(1.0)
    }

    /// The picture as a standalone SVG document: caption, pixel indices on
    /// both axes, the grid, and the legend below.
    pub fn to_svg(&self) -> String {
        self.svg(true)
    }

    /// The picture as an SVG document without its caption and legend, for
    /// a page that writes them in HTML (the axes stay).
    pub fn to_svg_bare(&self) -> String {
        self.svg(false)
    }

    fn svg(&self, framed: bool) -> String {
        let s = self.svg_cell();
        let (w, h) = (f64::from(self.width) * s, f64::from(self.height) * s);
        // Room for the row numbers left, the column numbers above.
        let digits = self.width.max(self.height).to_string().len() as f64;
        let left = 8.0 + 7.5 * digits;
        let caption_height = if framed { 26.0 } else { 0.0 };
        let top = caption_height + 18.0;
        let legend_width = (w + left).max(420.0) - 8.0;
        let dots = s >= 12.0;
        let (legend, legend_height) = if framed {
            // Pixel centres are dotted only where the cells are large enough.
            let mut legend = self.legend.clone();
            legend
                .entries
                .retain(|e| dots || e.key != Role::PixelCentre.key());
            legend.to_svg(4.0, top + h + 8.0, legend_width)
        } else {
            (String::new(), 0.0)
        };
        // DejaVu Sans at 15 px: about 8.4 px a character.
        let caption_width = if framed {
            self.caption.chars().count() as f64 * 8.4 + 12.0
        } else {
            0.0
        };
        let width = (left + w + 8.0).max(legend_width + 8.0).max(caption_width);
        let height = top + h + 8.0 + legend_height;
        let mut m = Markup::new();
        m.open_svg(width, height, None).newline();
        m.element("title", &[], &self.caption).newline();
        m.empty(
            "path",
            &[
                ("d", &format_args!("M0 0H{width}V{height}H0Z")),
                ("fill", &"white"),
            ],
        )
        .newline();
        if framed {
            m.element(
                "text",
                &[
                    ("class", &"caption"),
                    ("x", &4),
                    ("y", &18),
                    ("font-size", &15),
                ],
                &self.caption,
            )
            .newline();
        }
        // Pixel indices: every one while they fit, else every 2nd, 5th, 10th ...
        let step = [1u32, 2, 5, 10, 20, 50, 100, 200, 500, 1000]
            .into_iter()
            .find(|&k| f64::from(k) * s >= 7.0 * digits + 4.0)
            .unwrap_or(1000);
        m.open(
            "g",
            &[("class", &"axes"), ("font-size", &11), ("fill", &"#444")],
        );
        for x in (0..self.width).step_by(step as usize) {
            m.element(
                "text",
                &[
                    ("x", &(left + (f64::from(x) + 0.5) * s)),
                    ("y", &(top - 5.0)),
                    ("text-anchor", &"middle"),
                ],
                &x.to_string(),
            );
        }
        for y in (0..self.height).step_by(step as usize) {
            m.element(
                "text",
                &[
                    ("x", &(left - 4.0)),
                    ("y", &(top + (f64::from(y) + 0.5) * s + 4.0)),
                    ("text-anchor", &"end"),
                ],
                &y.to_string(),
            );
        }
        m.close("g").newline();
        m.open(
            "g",
            &[("transform", &format_args!("translate({left} {top})"))],
        );
        m.open("clipPath", &[("id", &"grid-view")])
            .empty("path", &[("d", &format_args!("M0 0H{w}V{h}H0Z"))])
            .close("clipPath")
            .newline();
        let label_size = format!("{:.1}", (s / 2.9).min(13.0));
        let centre_colour = Role::PixelCentre.hex();
        for y in 0..self.height {
            for x in 0..self.width {
                let i = (y * self.width + x) as usize;
                m.empty(
                    "rect",
                    &[
                        ("x", &(f64::from(x) * s)),
                        ("y", &(f64::from(y) * s)),
                        ("width", &s),
                        ("height", &s),
                        ("fill", &colour_hex(self.cells[i])),
                        ("stroke", &"#9a9a9a"),
                        ("stroke-width", &1),
                    ],
                )
                .newline();
                let (cx, cy) = ((f64::from(x) + 0.5) * s, (f64::from(y) + 0.5) * s);
                let label = self.labels.get(i).filter(|l| !l.is_empty());
                if let Some(label) = label.filter(|_| s >= 20.0) {
                    // Below the centre, so the sample point stays visible.
                    m.element(
                        "text",
                        &[
                            ("x", &cx),
                            ("y", &(cy + s * 0.34)),
                            ("font-size", &label_size),
                            ("text-anchor", &"middle"),
                        ],
                        label,
                    );
                    m.empty(
                        "circle",
                        &[
                            ("cx", &cx),
                            ("cy", &(cy - s * 0.12)),
                            ("r", &1.8),
                            ("fill", &centre_colour),
                        ],
                    )
                    .newline();
                } else if dots {
                    m.empty(
                        "circle",
                        &[
                            ("cx", &cx),
                            ("cy", &cy),
                            ("r", &2.2),
                            ("fill", &centre_colour),
                        ],
                    )
                    .newline();
                }
            }
        }
        let sample_colour = Role::SampleCovered.hex();
        let r = (s * 0.07).clamp(1.2, 4.0);
        for &(x, y, inside) in &self.samples {
            let (fill, stroke) = if inside {
                (sample_colour.as_str(), "none")
            } else {
                ("white", sample_colour.as_str())
            };
            m.empty(
                "circle",
                &[
                    ("class", &if inside { "sample covered" } else { "sample" }),
                    ("cx", &(x * s)),
                    ("cy", &(y * s)),
                    ("r", &r),
                    ("fill", &fill),
                    ("stroke", &stroke),
                    ("stroke-width", &(r * 0.45)),
                ],
            )
            .newline();
        }
        for &(x, y, n) in &self.hidden {
            // A grey corner: a fragment hidden here, with how many.
            let (x0, y0) = (f64::from(x) * s, f64::from(y) * s);
            let k = s * 0.42;
            m.empty(
                "path",
                &[
                    ("class", &"hidden"),
                    ("d", &format_args!("M{} {y0}h{k}v{k}Z", x0 + s - k)),
                    ("fill", &Role::Hidden.hex()),
                ],
            );
            m.element(
                "text",
                &[
                    ("x", &(x0 + s - 2.0)),
                    ("y", &(y0 + k * 0.55)),
                    ("font-size", &format_args!("{:.1}", k * 0.55)),
                    ("text-anchor", &"end"),
                    ("fill", &"white"),
                ],
                &n.to_string(),
            )
            .newline();
        }
        m.open("g", &[("clip-path", &"url(#grid-view)")]).newline();
        for (t, outline) in self.outlines.iter().enumerate() {
            let (colour, mark) = self.edge_style(t);
            let points: Vec<String> = outline
                .iter()
                .map(|(x, y)| format!("{},{}", x * s, y * s))
                .collect();
            m.empty(
                "polygon",
                &[
                    ("class", &"outline"),
                    ("data-mark", &mark),
                    ("points", &points.join(" ")),
                    ("fill", &"none"),
                    ("stroke", &colour_hex(colour)),
                    ("stroke-width", &2.5),
                    ("stroke-dasharray", &mark.dasharray().unwrap_or("none")),
                ],
            )
            .newline();
        }
        for (r, class) in &self.blocks {
            let (role, letter) = block_style(*class);
            let colour = role.hex();
            let (x, y) = (r.x0 as f64 * s, r.y0 as f64 * s);
            m.empty(
                "rect",
                &[
                    ("class", &"block"),
                    ("x", &(x + 2.5)),
                    ("y", &(y + 2.5)),
                    ("width", &((r.x1 - r.x0 + 1) as f64 * s - 5.0)),
                    ("height", &((r.y1 - r.y0 + 1) as f64 * s - 5.0)),
                    ("fill", &"none"),
                    ("stroke", &colour),
                    ("stroke-width", &3),
                    (
                        "stroke-dasharray",
                        &Mark::Block.dasharray().unwrap_or("none"),
                    ),
                ],
            );
            m.element(
                "text",
                &[
                    ("x", &(x + 5.0)),
                    ("y", &(y + 15.0)),
                    ("font-size", &12),
                    ("font-weight", &"bold"),
                    ("fill", &colour),
                ],
                &letter.to_string(),
            )
            .newline();
        }
        let (quad_lines, crosses) = self.quad_strokes();
        let geometry = Role::Geometry.hex();
        for (class, mark, strokes) in [
            ("quad", Mark::Dashed, &quad_lines),
            ("helper", Mark::Cross, &crosses),
        ] {
            for [(x0, y0), (x1, y1)] in strokes {
                m.empty(
                    "line",
                    &[
                        ("class", &class),
                        ("x1", &(x0 * s)),
                        ("y1", &(y0 * s)),
                        ("x2", &(x1 * s)),
                        ("y2", &(y1 * s)),
                        ("stroke", &geometry),
                        ("stroke-width", &2),
                        ("stroke-dasharray", &mark.dasharray().unwrap_or("none")),
                    ],
                )
                .newline();
            }
        }
        for [(x0, y0), (x1, y1)] in &self.segments {
            m.empty(
                "line",
                &[
                    ("x1", &(x0 * s)),
                    ("y1", &(y0 * s)),
                    ("x2", &(x1 * s)),
                    ("y2", &(y1 * s)),
                    ("stroke", &Role::Geometry.hex()),
                    ("stroke-width", &2.5),
                ],
            )
            .newline();
        }
        m.close("g").newline();
        self.geometry_labels(&mut m, s, w, h);
        m.close("g").newline();
        m.raw(&legend);
        m.close("svg").newline();
        m.finish()
    }

    /// The names the traces use, on a picture of one triangle: its
    /// vertices `v0`-`v2` and edges `E0`-`E2` (`Ek` opposite `vk`).
    /// Several triangles are named `T1`, `T2`, ... at their centres
    /// instead, in their colours (up to
    /// [`MAX_TRIANGLES`](crate::teaching::MAX_TRIANGLES)).
    fn geometry_labels(&self, m: &mut Markup, s: f64, w: f64, h: f64) {
        let label = |m: &mut Markup, (x, y): (f64, f64), text: &str, colour: &str| {
            // Kept inside the grid, on a white halo.
            let (x, y) = (x.clamp(8.0, w - 8.0), y.clamp(12.0, h - 4.0));
            m.halo_label("geometry-label", (x, y), colour, text)
                .newline();
        };
        if self.names_triangles() {
            for (t, outline) in self.outlines.iter().enumerate() {
                let n = outline.len() as f64;
                let (x, y) = outline
                    .iter()
                    .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
                label(
                    m,
                    (x * s, y * s + 5.0),
                    &triangle_name(t),
                    &colour_hex(triangle_colour(t)),
                );
            }
        }
        if let [outline] = self.outlines.as_slice() {
            let n = outline.len() as f64;
            let centre = outline
                .iter()
                .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
            let away = |(x, y): (f64, f64), by: f64| {
                let (dx, dy) = (x - centre.0, y - centre.1);
                let len = (dx * dx + dy * dy).sqrt().max(1e-9);
                (x * s + dx / len * by, y * s + dy / len * by + 5.0)
            };
            let colour = Role::Geometry.hex();
            for (k, &p) in outline.iter().enumerate() {
                let (x, y) = p;
                m.empty(
                    "circle",
                    &[
                        ("class", &"vertex"),
                        ("cx", &(x * s)),
                        ("cy", &(y * s)),
                        ("r", &4),
                        ("fill", &colour),
                    ],
                )
                .newline();
                label(m, away(p, 14.0), &format!("v{k}"), &colour);
                let (a, b) = (outline[(k + 1) % 3], outline[(k + 2) % 3]);
                let mid = ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0);
                label(m, away(mid, 13.0), &format!("E{k}"), &colour);
            }
        }
    }
}
