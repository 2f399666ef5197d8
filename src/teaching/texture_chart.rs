//! The texture filtering chart: each method of the comparison on the
//! receding floor ([`compare_textures`](crate::measure::compare_textures))
//! as a point, its error against the ground truth up the page and its cost
//! per pixel across, so the table's trade-off is seen at a glance.
//!
//! The colour is the level mode (level 0, the nearest level, the two
//! levels around lambda, and those with anisotropic probes or EWA); a filled dot
//! is the bilinear pixel filter, an open ring the nearest. The three
//! derivative methods of one filter and level mode lie close together;
//! the anisotropic points are named by their probes.
//!
//! ```
//! use rasterlab::geometry::Floor;
//! use rasterlab::measure::compare_textures;
//! use rasterlab::teaching::texture_chart_svg;
//!
//! let comparison = compare_textures(&Floor::new(32, 24).unwrap(), 2, None, 1).unwrap();
//! let svg = texture_chart_svg(&comparison);
//! assert!(svg.contains("class=\"legend\"") && svg.contains(">16x<"));
//! ```

use crate::measure::{TextureComparison, TextureMethod};
use crate::raster::derivatives::Derivatives;
use crate::raster::texture::{Anisotropic, Filter, LevelMode};
use crate::teaching::antialias_chart::{error_cost_svg, Labels, Plotted};
use crate::teaching::palette::{Legend, LegendEntry, Mark, LEVEL_COLOURS, TRIANGLE_COLOURS};

/// The groups of methods by colour, in legend order.
const GROUPS: [(&str, &str); 5] = [
    ("level-zero", "level 0 only"),
    ("level-nearest", "nearest level"),
    ("level-linear", "linear levels (trilinear when filled)"),
    ("anisotropic", "anisotropic probes, linear levels"),
    ("ewa", "EWA, linear levels"),
];

/// The groups' colours, from the palette.
const COLOURS: [[u8; 3]; 5] = [
    TRIANGLE_COLOURS[0],
    TRIANGLE_COLOURS[1],
    TRIANGLE_COLOURS[2],
    TRIANGLE_COLOURS[3],
    LEVEL_COLOURS[2],
];

/// The index in [`GROUPS`] of `method`.
fn group(method: &TextureMethod) -> usize {
    match (method.levels, method.anisotropy) {
        _ if method.anisotropic == Anisotropic::Ewa => 4,
        (_, a) if a > 1 => 3,
        (LevelMode::Zero, _) => 0,
        (LevelMode::Nearest, _) => 1,
        (LevelMode::Linear, _) => 2,
    }
}

/// The point's name: the probes of the anisotropic points with analytic
/// derivatives; the others go unnamed (the three derivative methods of
/// one filter and level mode lie close together).
fn name(method: &TextureMethod) -> String {
    if method.anisotropy > 1 && method.derivatives == Some(Derivatives::Analytic) {
        match method.anisotropic {
            Anisotropic::Probes => format!("{}x", method.anisotropy),
            Anisotropic::Ewa => format!("EWA {}x", method.anisotropy),
        }
    } else {
        String::new()
    }
}

/// The chart of `comparison` as an SVG picture, with its axes and legend.
pub fn texture_chart_svg(comparison: &TextureComparison) -> String {
    let points: Vec<Plotted> = comparison
        .rows
        .iter()
        .map(|r| Plotted {
            name: name(&r.method),
            cost: r.ns_per_pixel,
            error: r.rms,
            rgb: COLOURS[group(&r.method)],
            filled: r.method.filter == Filter::Bilinear,
        })
        .collect();
    let mut legend = Legend::default();
    for (i, (key, label)) in GROUPS.iter().enumerate() {
        legend.entries.push(LegendEntry {
            key: key.to_string(),
            rgb: COLOURS[i],
            mark: Mark::Fill,
            label: label.to_string(),
        });
    }
    legend.entries.push(LegendEntry {
        key: "nearest-filter".into(),
        rgb: COLOURS[0],
        mark: Mark::Ring,
        label: "open: the nearest pixel filter".into(),
    });
    let labels = Labels {
        heading: format!(
            "Texture filtering on the floor: error against cost ({} x {}, {} pixels)",
            comparison.width, comparison.height, comparison.pixels
        ),
        cost: "cost: ns per pixel drawn, log scale",
        error: "error: RMS against the texture over each pixel",
    };
    error_cost_svg(&labels, &points, &legend)
}
