//! The comparison report as one self-contained HTML page: the input and
//! its reference, the work table, each back-end's image and its
//! difference image, the fill-rule heat maps (the input's, then the
//! pinwheel's), the anti-aliasing table, chart and pictures, and the
//! zoomed grid pictures, each coloured section with its legend. Every
//! picture is embedded (PNG as a data URL, or SVG inline); the page's
//! script is `report.js`.

use super::{Antialiasing, Report, RulePicture};
use crate::error::Result;
use crate::markup::Markup;
use crate::teaching::antialias_chart::{antialias_chart_svg, ChartPoint};
use crate::teaching::palette::{self, Legend, Role};
use base64::Engine;
use std::path::{Path, PathBuf};

/// The page's script: once the page has loaded, it writes on `<body>`'s
/// data attributes how many images it holds and how many of them
/// decoded, and how many tables, SVG pictures and legends, for a browser
/// to check the page by.
const PAGE_SCRIPT: &str = include_str!("report.js");

impl Report {
    /// The report as one self-contained HTML page.
    pub fn to_html(&self) -> String {
        let zoom = (288 / self.width.max(self.height)).clamp(1, 16);
        let shown = |w: u32| w * zoom;
        let mut m = Markup::new();
        m.raw("<!DOCTYPE html>\n");
        m.open("html", &[("lang", &"en")]).open("head", &[]);
        m.empty("meta", &[("charset", &"utf-8")]);
        m.element("title", &[], &format!("rasterlab compare: {}", self.input))
            .newline();
        m.open("style", &[]).newline();
        m.raw(&format!(
            r#"body {{ font-family: sans-serif; margin: 1.5em; color: #222; }}
.row {{ display: flex; flex-wrap: wrap; gap: 1.2em; }}
figure {{ margin: 0; }}
figcaption {{ font-size: 0.9em; max-width: {cap}px; }}
img.px {{ image-rendering: pixelated; border: 1px solid #999; }}
table {{ border-collapse: collapse; margin: 0.5em 0 1.5em; }}
td, th {{ border: 1px solid #bbb; padding: 0.25em 0.6em; text-align: right; }}
td:first-child, th:first-child {{ text-align: left; }}
.ok {{ color: {ok}; }} .bad {{ color: {bad}; font-weight: bold; }}
figure.grid figcaption {{ font-size: 1.05em; max-width: none; }}
figure.grid figcaption b {{ font-size: 1.1em; }}
figure.grid svg {{ max-width: 100%; height: auto; }}
{palette}"#,
            cap = shown(self.width).max(240),
            ok = Role::Drawn.hex(),
            bad = Role::Differs.hex(),
            palette = palette::css(),
        ));
        m.close("style").close("head").open("body", &[]).newline();
        m.element("h1", &[], "rasterlab compare").newline();
        m.open("p", &[]).text(&format!(
            "Input: {}, drawn on a {} x {} target {} through the shared fragment stage. Reference: ",
            self.input,
            self.width,
            self.height,
            if self.lines {
                "by every line back-end"
            } else {
                "with the top-left fill rule"
            },
        ));
        m.element("b", &[], &self.reference_note)
            .text(".")
            .close("p")
            .newline();

        m.element("h2", &[], "Work").newline();
        m.open("table", &[("id", &"work")]).open("tr", &[]);
        for head in [
            "back-end",
            "fragments",
            "samples tested",
            "tests per fragment",
            "rows / blocks",
            "time (median)",
            "pixels differing from the reference",
        ] {
            m.element("th", &[], head);
        }
        m.close("tr").newline();
        for run in &self.runs {
            m.open("tr", &[]);
            m.element("td", &[("title", &run.description)], run.name);
            for cell in [
                run.work.fragments.to_string(),
                run.work.samples_tested.to_string(),
                run.tests_per_fragment_text(),
                // Rows or blocks only mean something to the back-ends
                // that hand spans to the stage.
                if run.work.spans == 0 {
                    "—".to_string()
                } else {
                    run.work.spans.to_string()
                },
                format!("{:.3} ms", run.time.as_secs_f64() * 1e3),
            ] {
                m.element("td", &[], &cell);
            }
            m.open("td", &[]);
            match run.differing_pixels {
                0 => m.element("span", &[("class", &"ok")], "0 (identical)"),
                n => m.element("span", &[("class", &"bad")], &n.to_string()),
            };
            m.close("td").close("tr").newline();
        }
        m.close("table").newline();
        m.open("p", &[]).text("Times are for a rough idea; ");
        m.element("code", &[], "rasterlab bench")
            .text(" and ")
            .element("code", &[], "cargo bench")
            .text(" measure properly.")
            .close("p")
            .newline();

        m.element("h2", &[], "Images").newline();
        m.open("div", &[("class", &"row")]).newline();
        for run in &self.runs {
            figure(
                &mut m,
                &png_data(&run.target.to_image()),
                shown(self.width),
                &format!("{}: {}", run.name, run.description),
            );
        }
        m.close("div").newline();
        m.element("h2", &[], "Differences from the reference")
            .newline();
        m.element(
            "p",
            &[],
            &format!(
                "Colour, depth or coverage compared with {}'s, pixel by pixel.",
                self.reference
            ),
        )
        .newline();
        m.raw(&Legend::new(&[Role::Differs]).to_html()).newline();
        m.open("div", &[("class", &"row")]).newline();
        for run in self.runs.iter().skip(1) {
            figure(
                &mut m,
                &png_data(&self.difference_image(run)),
                shown(self.width),
                &format!("{}: {} pixels differ", run.name, run.differing_pixels),
            );
        }
        m.close("div").newline();

        if !self.rules.is_empty() {
            m.element("h2", &[], "Fill rules").newline();
            m.raw(&heat_map_legend(zoom.min(24)).to_html()).newline();
            rule_table(&mut m, "rules", &self.rules);
            m.open("div", &[("class", &"row")]).newline();
            for r in &self.rules {
                heat_figure(&mut m, r, zoom);
            }
            m.close("div").newline();
        }
        if !self.lines {
            m.element("h2", &[], "The line-drawing slides' edge-drawing problem")
                .newline();
            m.element("p", &[], "Eight triangles around one pixel centre, every shared edge through pixel centres. Drawing every edge (inclusive) draws them twice; drawing none (exclusive) leaves holes; the top-left, bottom-right and off-screen point rules give each edge pixel to exactly one triangle.").newline();
            m.raw(&heat_map_legend(24).to_html()).newline();
            rule_table(&mut m, "pinwheel", &self.pinwheel_rules);
            m.open("div", &[("class", &"row")]).newline();
            for r in &self.pinwheel_rules {
                heat_figure(&mut m, r, 24);
            }
            m.close("div").newline();
        }

        if let Some(aa) = &self.antialias {
            antialias_section(&mut m, aa);
        } else if let Some(why) = &self.antialias_skipped {
            m.element("h2", &[], "Anti-aliasing").newline();
            m.element("p", &[], why).newline();
        }

        if let Some((_, first)) = self.grids.first() {
            m.element("h2", &[], "Pixels tested and emitted").newline();
            m.element("p", &[], "Which pixel centres each back-end tested, and which became fragments; pixel indices on the axes.").newline();
            m.raw(&first.legend.to_html()).newline();
            m.open("div", &[("class", &"row")]).newline();
            for (name, grid) in &self.grids {
                m.open("figure", &[("class", &"grid")])
                    .open("figcaption", &[]);
                m.element("b", &[], name)
                    .text(&format!(": {}", grid.caption))
                    .close("figcaption");
                m.raw(&grid.to_svg_bare()).close("figure").newline();
            }
            m.close("div").newline();
        }
        m.open("script", &[]).raw("\n").raw(PAGE_SCRIPT);
        m.close("script").newline();
        m.close("body").close("html").newline();

        m.finish()
    }

    /// Writes `index.html` into `dir` (created if missing) and returns
    /// its path.
    pub fn write(&self, dir: &Path) -> Result<PathBuf> {
        crate::output::check_dir(dir)?;
        let path = dir.join("index.html");
        crate::output::write_file(&path, self.to_html().as_bytes())?;
        Ok(path)
    }
}

/// The legend of fill-rule heat maps drawn at `zoom`
/// ([`GridPicture::to_png`](crate::teaching::GridPicture::to_png)
/// dots the pixel centres from a zoom of 6).
fn heat_map_legend(zoom: u32) -> Legend {
    let legend = Legend::new(&[
        Role::AsReference,
        Role::Gap,
        Role::DoubleDraw,
        Role::DrawnTwiceMore,
        Role::Untested,
    ]);
    if zoom >= 6 {
        legend.with(Role::PixelCentre)
    } else {
        legend
    }
}

fn png_data<P: image::PixelWithColorType, C: std::ops::Deref<Target = [P::Subpixel]>>(
    img: &image::ImageBuffer<P, C>,
) -> String
where
    [P::Subpixel]: image::EncodableLayout,
{
    let mut bytes = Vec::new();
    img.write_to(
        &mut std::io::Cursor::new(&mut bytes),
        image::ImageFormat::Png,
    )
    .expect("encoding a PNG in memory does not fail");
    format!(
        "data:image/png;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(bytes)
    )
}

fn figure(m: &mut Markup, src: &str, width: u32, caption: &str) {
    m.open("figure", &[]);
    m.empty(
        "img",
        &[
            ("class", &"px"),
            ("src", &src),
            ("width", &width),
            ("alt", &caption),
        ],
    );
    m.element("figcaption", &[], caption)
        .close("figure")
        .newline();
}

fn heat_figure(m: &mut Markup, r: &RulePicture, zoom: u32) {
    let png = r
        .picture
        .to_png(zoom.min(24))
        .expect("a heat map of a checked target size can be drawn");
    let src = png_data(&png);
    figure(m, &src, png.width(), &r.picture.caption);
}

fn antialias_section(m: &mut Markup, aa: &Antialiasing) {
    m.element("h2", &[], "Anti-aliasing").newline();
    m.element(
        "p",
        &[],
        "How much of each pixel each triangle covers, estimated from samples (one at the centre; \
         multisampling, MSAA, on the standard patterns; supersampling, SSAA, on a regular grid), \
         against the exact area of the triangle inside the pixel. Per triangle: over every \
         (pixel, triangle) pair either covers. In the picture: each pixel's triangles summed, \
         which for triangles that share edges and never overlap is exact inside them.",
    )
    .newline();
    m.open("table", &[("id", &"antialias")]).open("tr", &[]);
    for head in [
        "method",
        "samples a pixel",
        "RMS error per triangle",
        "worst per triangle",
        "RMS error in the picture",
        "worst in the picture",
        "ns per pair (median of 3 runs)",
    ] {
        m.element("th", &[], head);
    }
    m.close("tr").newline();
    for r in &aa.rows {
        let samples = if r.samples == 0 {
            "exact".to_string()
        } else {
            r.samples.to_string()
        };
        m.open("tr", &[]);
        m.element("td", &[], &r.name)
            .element("td", &[], &samples)
            .element("td", &[], &format!("{:.4}", r.per_triangle.rms))
            .element("td", &[], &format!("{:.3}", r.per_triangle.worst))
            .element("td", &[], &format!("{:.4}", r.picture.rms))
            .element("td", &[], &format!("{:.3}", r.picture.worst))
            .element("td", &[], &format!("{:.0}", r.ns_per_pair));
        m.close("tr").newline();
    }
    m.close("table").newline();
    let points: Vec<ChartPoint> = aa
        .rows
        .iter()
        .map(|r| ChartPoint {
            name: r.name.clone(),
            ns_per_pair: r.ns_per_pair,
            rms: r.per_triangle.rms,
            peer: false,
        })
        .collect();
    m.open("figure", &[("class", &"chart")]);
    m.raw(&antialias_chart_svg(
        "this input, median of 3 runs",
        &points,
    ));
    m.close("figure").newline();
    let legend = Legend::default().with_mark(
        Role::Drawn,
        palette::Mark::Fill,
        "covered: the shade is the share of the pixel covered, from none (white) to all",
    );
    m.raw(&legend.to_html()).newline();
    m.open("div", &[("class", &"row")]).newline();
    for (method, picture) in &aa.pictures {
        // Each pixel a square of at least 4 screen pixels, the picture
        // about 360 wide.
        let zoom = (360 / picture.width().max(picture.height())).max(4);
        let caption = format!(
            "{method}: pixels ({}, {}) to ({}, {})",
            aa.origin.0,
            aa.origin.1,
            aa.origin.0 + picture.width() - 1,
            aa.origin.1 + picture.height() - 1
        );
        figure(m, &png_data(picture), picture.width() * zoom, &caption);
    }
    m.close("div").newline();
}

fn rule_table(m: &mut Markup, id: &str, rules: &[RulePicture]) {
    m.open("table", &[("id", &id)]).open("tr", &[]);
    for head in [
        "fill rule",
        "gap pixels",
        "overdrawn pixels",
        "watertight here",
    ] {
        m.element("th", &[], head);
    }
    m.close("tr").newline();
    for r in rules {
        let ok = r.gaps == 0 && r.overdrawn == 0;
        m.open("tr", &[]);
        m.element("td", &[], r.rule.name())
            .element("td", &[], &r.gaps.to_string())
            .element("td", &[], &r.overdrawn.to_string())
            .element(
                "td",
                &[("class", &if ok { "ok" } else { "bad" })],
                if ok { "yes" } else { "no" },
            );
        m.close("tr").newline();
    }
    m.close("table").newline();
}
