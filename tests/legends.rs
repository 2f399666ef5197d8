//! One meaning per colour and mark, in every picture and page.
//!
//! Each picture is produced as the tools produce it (`explain --picture`,
//! the lab's answers, the `compare` report, the check report's picture
//! and page), its legend is read back from the SVG or HTML, and
//! [`check_legend`] fails when:
//!
//! * one (colour, mark) pair is given two meanings, or
//! * two entries drawn with the same mark, told apart by colour alone,
//!   come closer than [`MIN_DELTA_E`] (CIE76 ΔE in CIELAB) for a reader
//!   with protanopia, deuteranopia or tritanopia, simulated with Machado,
//!   Oliveira and Fernandes' (2009) matrices at severity 1.0, applied in
//!   linear RGB. Entries told apart by their marks may share a colour.
//!
//! The grid pictures are also checked the other way: every triangle's
//! edge and every cell colour they draw is in their legend.

use rasterlab::check::{judge, reference, Case, Fragment, Property};
use rasterlab::geometry::Floor;
use rasterlab::geometry::Scene2D;
use rasterlab::lab::{answer, LabRequest};
use rasterlab::measure::compare_textures;
use rasterlab::raster::line::LineOptions;
use rasterlab::raster::{line_backend, triangle_backend, FillRule};
use rasterlab::raster::{Derivatives, Sampler};
use rasterlab::teaching::{
    texture_chart_svg, CompareInput, GridPicture, LevelPicture, LineEnds, Report,
};
use std::collections::BTreeSet;

/// The least CIE76 distance between two colours that only their colour
/// tells apart, for every simulated reader. 15 units keeps two swatches
/// side by side clearly different; Okabe and Ito's own closest pairs
/// (orange and vermillion under deuteranopia: 18.3) stay above it.
const MIN_DELTA_E: f64 = 15.0;

/// One legend entry as a picture writes it.
#[derive(Clone, Debug, PartialEq)]
struct Entry {
    key: String,
    colour: [u8; 3],
    mark: String,
    label: String,
}

fn entry(key: &str, colour: [u8; 3], mark: &str, label: &str) -> Entry {
    Entry {
        key: key.into(),
        colour,
        mark: mark.into(),
        label: label.into(),
    }
}

fn parse_hex(text: &str) -> [u8; 3] {
    let t = text.strip_prefix('#').unwrap_or_else(|| panic!("{text}"));
    [0, 2, 4].map(|i| u8::from_str_radix(&t[i..i + 2], 16).unwrap())
}

/// The entries of every legend in `xml` (an SVG picture, or a legend's
/// HTML): the elements of class `entry` under a `legend` with the
/// palette's mark, with their pair and the text they show.
fn legend_entries(xml: &str) -> Vec<Entry> {
    let doc = roxmltree::Document::parse(xml).unwrap_or_else(|e| panic!("{e}: {xml}"));
    let mut entries = Vec::new();
    for legend in doc
        .descendants()
        .filter(|n| n.attribute("class") == Some("legend"))
    {
        assert_eq!(legend.attribute("data-palette"), Some("okabe-ito"));
        for e in legend
            .descendants()
            .filter(|n| n.attribute("class") == Some("entry"))
        {
            let label: String = e
                .descendants()
                .filter(|n| n.is_text())
                .filter_map(|n| n.text())
                .collect();
            entries.push(entry(
                e.attribute("data-role").unwrap(),
                parse_hex(e.attribute("data-colour").unwrap()),
                e.attribute("data-mark").unwrap(),
                label.trim(),
            ));
        }
    }
    entries
}

/// Every `<div class="legend" ...>...</div>` of an HTML page, each parsed.
fn html_legends(html: &str) -> Vec<Vec<Entry>> {
    let mut legends = Vec::new();
    let mut rest = html;
    while let Some(i) = rest.find("<div class=\"legend\"") {
        let end = i + rest[i..].find("</div>").unwrap() + "</div>".len();
        legends.push(legend_entries(&rest[i..end]));
        rest = &rest[end..];
    }
    legends
}

/// The colour-vision deficiencies simulated, by name: Machado, Oliveira
/// and Fernandes (2009), severity 1.0, on linear RGB.
const DEFICIENCIES: [(&str, [[f64; 3]; 3]); 3] = [
    (
        "protanopia",
        [
            [0.152286, 1.052583, -0.204868],
            [0.114503, 0.786281, 0.099216],
            [-0.003882, -0.048116, 1.051998],
        ],
    ),
    (
        "deuteranopia",
        [
            [0.367322, 0.860646, -0.227968],
            [0.280085, 0.672501, 0.047413],
            [-0.011820, 0.042940, 0.968881],
        ],
    ),
    (
        "tritanopia",
        [
            [1.255528, -0.076749, -0.178779],
            [-0.078411, 0.930809, 0.147602],
            [0.004733, 0.691367, 0.303900],
        ],
    ),
];

/// An sRGB colour as seen through `matrix` (the identity: unchanged), in
/// CIELAB (D65).
fn lab(colour: [u8; 3], matrix: &[[f64; 3]; 3]) -> [f64; 3] {
    let linear = colour.map(|c| {
        let c = f64::from(c) / 255.0;
        if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    });
    let [r, g, b] = matrix.map(|row| {
        (0..3)
            .map(|k| row[k] * linear[k])
            .sum::<f64>()
            .clamp(0.0, 1.0)
    });
    let x = (0.4124 * r + 0.3576 * g + 0.1805 * b) / 0.95047;
    let y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
    let z = (0.0193 * r + 0.1192 * g + 0.9505 * b) / 1.08883;
    let f = |t: f64| {
        if t > 216.0 / 24389.0 {
            t.cbrt()
        } else {
            (24389.0 / 27.0 * t + 16.0) / 116.0
        }
    };
    let (fx, fy, fz) = (f(x), f(y), f(z));
    [116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)]
}

/// CIE76 ΔE between two colours, as seen through `matrix`.
fn delta_e(a: [u8; 3], b: [u8; 3], matrix: &[[f64; 3]; 3]) -> f64 {
    let (p, q) = (lab(a, matrix), lab(b, matrix));
    (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>().sqrt()
}

/// The smallest distance met per deficiency, in [`DEFICIENCIES`]' order
/// (infinite where no two entries shared a mark).
type Closest = [f64; 3];

/// Fails when a (colour, mark) pair of `entries` has two meanings, or
/// when two entries with one mark and different colours come closer than
/// [`MIN_DELTA_E`] for a simulated reader; else the closest distances.
fn check_legend(entries: &[Entry]) -> Result<Closest, String> {
    let mut closest = [f64::INFINITY; 3];
    for (i, a) in entries.iter().enumerate() {
        for b in &entries[..i] {
            if a.mark != b.mark {
                continue;
            }
            if a.colour == b.colour {
                if a.label != b.label {
                    return Err(format!(
                        "#{:02x}{:02x}{:02x} {} means both \"{}\" and \"{}\"",
                        a.colour[0], a.colour[1], a.colour[2], a.mark, b.label, a.label
                    ));
                }
                continue;
            }
            for (k, (name, matrix)) in DEFICIENCIES.iter().enumerate() {
                let d = delta_e(a.colour, b.colour, matrix);
                if d < MIN_DELTA_E {
                    return Err(format!(
                        "\"{}\" and \"{}\" ({}) are {d:.1} apart under {name}, less than {MIN_DELTA_E}",
                        b.label, a.label, a.mark
                    ));
                }
                closest[k] = closest[k].min(d);
            }
        }
    }
    Ok(closest)
}

/// Checks one picture's legend, naming the picture on failure, and
/// folds its closest distances into `closest`.
fn checked(what: &str, entries: &[Entry], closest: &mut Closest) {
    assert!(!entries.is_empty(), "{what}: no legend");
    let found = check_legend(entries).unwrap_or_else(|e| panic!("{what}: {e}"));
    for k in 0..3 {
        closest[k] = closest[k].min(found[k]);
    }
}

/// Whether `c` is `base` faded towards white (Wu's fragments are as
/// green as their coverage).
fn is_shade_of(c: [u8; 3], base: [u8; 3]) -> bool {
    let k = (0..3).max_by_key(|&k| 255 - base[k]).unwrap();
    let t = f64::from(255 - c[k]) / f64::from(255 - base[k]);
    (0.0..=1.0).contains(&t)
        && (0..3).all(|k| {
            let shade = 255.0 - (255.0 - f64::from(base[k])) * t;
            (shade - f64::from(c[k])).abs() <= 1.5
        })
}

/// The grid picture's own drawing against its legend: each outline's
/// (colour, mark) and each cell's colour (but white: no one looked; and
/// shades of a fill, for Wu's coverage) is a legend entry's.
fn uses_only_its_legend(what: &str, svg: &str, entries: &[Entry]) {
    let doc = roxmltree::Document::parse(svg).unwrap();
    let has =
        |colour: [u8; 3], mark: &str| entries.iter().any(|e| e.colour == colour && e.mark == mark);
    for n in doc.descendants() {
        if n.attribute("class") == Some("outline") {
            let (colour, mark) = (
                parse_hex(n.attribute("stroke").unwrap()),
                n.attribute("data-mark").unwrap(),
            );
            assert!(has(colour, mark), "{what}: outline {colour:?} {mark}");
        }
        // The cells: rects of one pixel, filled.
        if n.tag_name().name() == "rect" && n.attribute("stroke") == Some("#9a9a9a") {
            let colour = parse_hex(n.attribute("fill").unwrap());
            let shade = entries
                .iter()
                .any(|e| e.mark == "fill" && is_shade_of(colour, e.colour));
            assert!(
                colour == [255, 255, 255] || has(colour, "fill") || shade,
                "{what}: cell {colour:?}"
            );
        }
    }
}

/// A grid picture as `explain --picture` writes it, by the program.
fn explain_svg(args: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let path = dir
        .path()
        .join(format!("{}.svg", args.join("_").replace(' ', "")));
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_rasterlab"))
        .arg("explain")
        .args(args)
        .arg("--picture")
        .arg(&path)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .status()
        .unwrap();
    assert!(status.success(), "{args:?}");
    std::fs::read_to_string(&path).unwrap()
}

/// Sixteen triangles around the grid's centre, as a fan.
fn fan(n: usize) -> Vec<[(f64, f64); 3]> {
    let corner = |k: usize| {
        let a = k as f64 * std::f64::consts::TAU / n as f64;
        (12.0 + 11.0 * a.cos(), 12.0 + 11.0 * a.sin())
    };
    (0..n)
        .map(|k| [(12.0, 12.0), corner(k), corner(k + 1)])
        .collect()
}

#[test]
fn every_picture_gives_each_pair_one_meaning_readable_by_every_reader() {
    let mut closest = [f64::INFINITY; 3];

    // explain --picture: one triangle, tiled's blocks, a Wu line, a
    // polygon with a hole under nonzero, a triangle's samples.
    for args in [
        &[
            "--backend",
            "bbox",
            "--size",
            "11x9",
            "1",
            "1",
            "9",
            "2",
            "3",
            "7",
        ][..],
        &[
            "--backend",
            "tiled",
            "--size",
            "32x24",
            "1",
            "1",
            "31",
            "2",
            "2",
            "23",
        ],
        &["--backend", "wu", "--size", "14x8", "0", "1", "13", "6"],
        &[
            "--backend",
            "edge-table",
            "--fill",
            "nonzero",
            "--size",
            "16x12",
            "1",
            "1",
            "15",
            "2",
            "14",
            "11",
            "2",
            "10",
            "--ring",
            "5 4 11 4 10 8 6 8",
        ],
        &[
            "--backend",
            "bbox",
            "--size",
            "8x6",
            "--msaa",
            "4",
            "0.5",
            "0.2",
            "7.3",
            "1.9",
            "1.4",
            "5.8",
        ],
    ] {
        let svg = explain_svg(args);
        let entries = legend_entries(&svg);
        checked(&format!("explain {args:?}"), &entries, &mut closest);
        uses_only_its_legend(&format!("explain {args:?}"), &svg, &entries);
    }
    // Grid pictures of 2, 16 and 17 triangles (tiled: with its blocks),
    // the depth buffer, a heat map.
    let bbox = triangle_backend("bbox").unwrap();
    let tiled = triangle_backend("tiled").unwrap();
    let mut pictures = Vec::new();
    for n in [2, 16, 17] {
        for b in [bbox, tiled] {
            let p = GridPicture::of_triangles(b, &fan(n), FillRule::TopLeft, 24, 24).unwrap();
            pictures.push((format!("{} triangles, {}", n, b.name()), p));
        }
    }
    let depth = GridPicture::depth_buffer(&Scene2D::depth_example(true), FillRule::TopLeft);
    pictures.push(("the depth buffer".into(), depth.unwrap()));
    let line = LineEnds::pixels([0.0, 0.0, 9.0, 4.0]).unwrap();
    let wu = line_backend("wu").unwrap();
    let lines = GridPicture::of_lines(wu, &[line], &LineOptions::DEFAULT, 10, 5).unwrap();
    pictures.push(("a wu line".into(), lines));
    let pinwheel = Scene2D::pinwheel();
    let coverage = |rule| pinwheel.render(bbox, rule, &rasterlab::raster::Flat);
    let inclusive = coverage(FillRule::Inclusive).unwrap().0.coverage;
    let watertight = [
        coverage(FillRule::TopLeft).unwrap().0.coverage,
        coverage(FillRule::BottomRight).unwrap().0.coverage,
    ];
    let heat = GridPicture::coverage_heat_map(
        pinwheel.width,
        pinwheel.height,
        &inclusive,
        &[&watertight[0], &watertight[1]],
        "inclusive".into(),
    );
    pictures.push(("a heat map".into(), heat.unwrap()));
    for (what, p) in &pictures {
        let svg = p.to_svg();
        let entries = legend_entries(&svg);
        checked(what, &entries, &mut closest);
        uses_only_its_legend(what, &svg, &entries);
    }
    // Sixteen triangles: sixteen named edges, each its own pair.
    let sixteen = legend_entries(&pictures[2].1.to_svg());
    let edges: BTreeSet<_> = sixteen
        .iter()
        .filter(|e| e.key.starts_with("triangle-"))
        .map(|e| (e.colour, e.mark.clone()))
        .collect();
    assert_eq!(edges.len(), 16);
    assert!(pictures[2].1.to_svg().contains(">T16</text>"));
    // Seventeen: the edges are the true geometry, unnamed.
    let seventeen = legend_entries(&pictures[4].1.to_svg());
    assert!(!seventeen.iter().any(|e| e.key.starts_with("triangle-")));
    assert!(seventeen.iter().any(|e| e.key == "geometry"));

    // The lab's answers, as the page gets them: the legend's data and its
    // HTML, which must say the same.
    let presets = [
        r#"{"width": 16, "height": 16, "kind": "triangles", "triangles": [[[1.5, 1.25], [13.75, 4.5], [4.25, 13.5]]], "backends": ["bbox", "scanline"]}"#.to_string(),
        r#"{"width": 12, "height": 12, "kind": "triangles", "triangles": [[[1, 1], [11, 1], [1, 11]], [[11, 1], [11, 11], [1, 11]]], "backends": ["bbox"], "rule": "inclusive"}"#.to_string(),
        r#"{"width": 14, "height": 9, "kind": "triangles", "triangles": [[[2.75, 3], [12.3359375, 3], [1.9296875, 6.9]], [[3.6, 1], [6.8, 1], [10, 9]]], "depths": [0.5, 0.8], "backends": ["bbox"]}"#.to_string(),
        r#"{"width": 16, "height": 12, "kind": "lines", "lines": [[[0.5, 0.5], [14.5, 6.5]]], "backends": ["wu", "bresenham"]}"#.to_string(),
        serde_json::json!({"width": 24, "height": 24, "kind": "triangles", "backends": ["bbox"],
            "triangles": fan(16).iter().map(|t| t.map(|(x, y)| [x, y])).collect::<Vec<_>>()}).to_string(),
        serde_json::json!({"width": 24, "height": 24, "kind": "triangles", "backends": ["bbox"],
            "triangles": fan(16).iter().map(|t| t.map(|(x, y)| [x, y])).collect::<Vec<_>>(),
            "depths": (0..16).map(|i| f64::from(i) / 16.0).collect::<Vec<_>>()}).to_string(),
    ];
    let mut program = rasterlab::check::Program::new("echo 0 0 0", "top-left");
    for (i, text) in presets.iter().enumerate() {
        for student in [false, true] {
            let mut request = LabRequest::parse(text).unwrap();
            request.student = student;
            let response = answer(&request, Some(&mut program)).unwrap();
            let entries = legend_entries(&response.legend_html);
            let data: Vec<Entry> = response
                .legend
                .entries
                .iter()
                .map(|e| entry(&e.key, e.rgb, e.mark.key(), &e.label))
                .collect();
            assert_eq!(entries, data, "lab preset {i}: the HTML is the data");
            checked(
                &format!("lab preset {i}, student {student}"),
                &entries,
                &mut closest,
            );
            let keys: Vec<&str> = entries.iter().map(|e| e.key.as_str()).collect();
            assert_eq!(
                keys.contains(&"extra") && keys.contains(&"missing"),
                student,
                "{keys:?}"
            );
            // Exactly what is drawn: two triangles sharing an edge under
            // the inclusive rule draw it twice, and leave no gap.
            if i == 1 && student {
                assert_eq!(
                    keys,
                    [
                        "drawn",
                        "tested-outside",
                        "double-draw",
                        "triangle-0",
                        "triangle-1",
                        "pixel-centre",
                        "missing",
                        "extra"
                    ]
                );
            }
        }
    }

    // compare's report: every legend of the page, as the program writes
    // it for the bundled polygon, and for two triangles.
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("report");
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_rasterlab"))
        .args([
            "compare",
            concat!(env!("CARGO_MANIFEST_DIR"), "/assets/polygon.txt"),
        ])
        .args(["--size", "32x32", "--out"])
        .arg(&out)
        .stdout(std::process::Stdio::null())
        .status()
        .unwrap();
    assert!(status.success());
    let polygon = std::fs::read_to_string(out.join("index.html")).unwrap();
    let two = Report::compare(&CompareInput::Triangles(Scene2D::split_square()), 16, 16, 1)
        .unwrap()
        .to_html();
    for html in [polygon, two] {
        let legends = html_legends(&html);
        // Differences, fill rules, the pinwheel, anti-aliasing, the grids.
        assert_eq!(legends.len(), 5);
        for (k, entries) in legends.iter().enumerate() {
            checked(&format!("compare, legend {k}"), entries, &mut closest);
        }
        // The anti-aliasing chart, a picture with its own legend.
        let figure = html.find("<figure class=\"chart\">").expect("the chart");
        let start = figure + html[figure..].find("<svg").unwrap();
        let end = start + html[start..].find("</svg>").unwrap() + "</svg>".len();
        let entries = legend_entries(&html[start..end]);
        checked("compare, the anti-aliasing chart", &entries, &mut closest);
    }

    // The texture pictures: the comparison's chart (from a small run)
    // and the floor coloured by mip level, with the traced pixel framed.
    let floor = Floor::new(48, 32).unwrap();
    let comparison = compare_textures(&floor, 2, None, 1).unwrap();
    let entries = legend_entries(&texture_chart_svg(&comparison));
    assert_eq!(entries.len(), 6);
    checked("the texture chart", &entries, &mut closest);
    let big = Floor::new(160, 100).unwrap();
    let levels = LevelPicture::new(&big, Sampler::default(), Derivatives::Quad, Some((80, 60)));
    let entries = legend_entries(&levels.to_svg());
    assert!(entries.len() >= 6, "{entries:?}");
    checked("the mip level picture", &entries, &mut closest);

    // check's report: the counterexample picture and its page. Two
    // triangles sharing a diagonal, one fragment missing, one drawn off
    // the target.
    let case = Case::from_text("# size 3x2\n0 0 3 0 0 2\n3 0 3 2 0 2\n").unwrap();
    let property = Property::Exact(FillRule::TopLeft);
    let mut drawn = reference(property, &case);
    drawn.remove(0);
    drawn.push(Fragment::at(-1, 0, 1));
    let finding = judge(property, &case, &drawn).expect("a failure");
    let svg = finding.to_svg();
    let entries = legend_entries(&svg);
    checked("the counterexample picture", &entries, &mut closest);
    // check --image's diff picture: one pixel past the threshold.
    let expected = image::RgbaImage::from_pixel(4, 3, image::Rgba([0, 0, 0, 255]));
    let mut actual = expected.clone();
    actual.put_pixel(1, 1, image::Rgba([200, 0, 0, 255]));
    let diff = rasterlab::check::diff_image(&expected, &actual, 32);
    let diff_entries = legend_entries(&rasterlab::check::diff_svg(&diff, "diff"));
    checked(
        "the image check's diff picture",
        &diff_entries,
        &mut closest,
    );
    let html = finding.to_html();
    let start = html.find("<svg").unwrap();
    let end = html.rfind("</svg>").unwrap() + "</svg>".len();
    assert_eq!(legend_entries(&html[start..end]), entries);

    eprintln!(
        "closest colours told apart by colour alone, CIE76 ΔE: protanopia {:.1}, deuteranopia {:.1}, tritanopia {:.1} (at least {MIN_DELTA_E})",
        closest[0], closest[1], closest[2]
    );
}

#[test]
fn a_pair_with_two_meanings_is_rejected() {
    let green = [0, 158, 115];
    let bad = [
        entry("drawn", green, "fill", "fragment (drawn)"),
        entry("gap", green, "fill", "gap"),
    ];
    let error = check_legend(&bad).unwrap_err();
    assert!(error.contains("means both"), "{error}");
    // The same colour with another mark is another pair.
    let good = [
        entry("drawn", green, "fill", "fragment (drawn)"),
        entry("triangle-0", green, "dashed", "T1"),
    ];
    assert!(check_legend(&good).is_ok());
}

#[test]
fn colours_that_collapse_under_deuteranopia_are_rejected() {
    // Okabe and Ito's reddish purple and a middle grey: 40 apart for
    // most readers, 7 apart under deuteranopia.
    let (purple, grey) = ([204, 121, 167], [153, 153, 153]);
    let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    assert!(delta_e(purple, grey, &identity) > 2.0 * MIN_DELTA_E);
    let bad = [
        entry("a", purple, "fill", "one thing"),
        entry("b", grey, "fill", "another"),
    ];
    let error = check_legend(&bad).unwrap_err();
    assert!(error.contains("deuteranopia"), "{error}");
    // Told apart by their marks, they may share colours this close.
    let marked = [
        entry("a", purple, "fill", "one thing"),
        entry("b", grey, "corner", "another"),
    ];
    assert!(check_legend(&marked).is_ok());
}

#[test]
fn the_simulation_keeps_greys_and_measures_black_to_white_as_100() {
    for (name, matrix) in DEFICIENCIES {
        assert!(
            (delta_e([0, 0, 0], [255, 255, 255], &matrix) - 100.0).abs() < 0.1,
            "{name}"
        );
        let grey = lab([128, 128, 128], &matrix);
        assert!(
            grey[1].abs() < 0.5 && grey[2].abs() < 0.5,
            "{name}: {grey:?}"
        );
    }
}
