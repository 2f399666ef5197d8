//! The anti-aliasing chart: each method's error against its cost, one
//! point a method, so the trade-off of the comparison's table can be seen
//! at a glance.
//!
//! The error (up the page) is the root mean square, per triangle, of the
//! method's coverage against the exact area ([`coverage_error`](crate::measure::coverage_error));
//! the cost (across, on a log scale: the methods span two orders of
//! magnitude) is the time per (pixel, triangle) pair of the exact area.
//! rasterlab's methods are filled dots, the 2D libraries' anti-aliased
//! fills (where measured) open ones; each point is named beside it.
//!
//! ```
//! use rasterlab::teaching::{antialias_chart_svg, ChartPoint};
//!
//! let points = [
//!     ChartPoint { name: "one sample".into(), ns_per_pair: 70.0, rms: 0.21, peer: false },
//!     ChartPoint { name: "MSAA 4".into(), ns_per_pair: 220.0, rms: 0.08, peer: false },
//!     ChartPoint { name: "cairo".into(), ns_per_pair: 44.0, rms: 0.011, peer: true },
//! ];
//! let svg = antialias_chart_svg("delaunay, 320 x 240", &points);
//! assert!(svg.contains("MSAA 4") && svg.contains("class=\"legend\""));
//! ```

use crate::markup::Markup;
use crate::teaching::palette::{Legend, Mark, Role};

/// One method on the chart.
#[derive(Clone, Debug, PartialEq)]
pub struct ChartPoint {
    /// The method's name, written beside its point.
    pub name: String,
    /// Its cost: nanoseconds per (pixel, triangle) pair of the exact area.
    pub ns_per_pair: f64,
    /// Its error: RMS per triangle against the exact area.
    pub rms: f64,
    /// A 2D library's fill rather than one of rasterlab's methods.
    pub peer: bool,
}

const WIDTH: f64 = 760.0;
const LEFT: f64 = 70.0;
const RIGHT: f64 = 170.0;
const TOP: f64 = 50.0;
const PLOT_H: f64 = 300.0;

/// The chart of `points` as an SVG picture, titled `title`, with its axes
/// and a legend. Points whose cost is not a positive number are left out.
pub fn antialias_chart_svg(title: &str, points: &[ChartPoint]) -> String {
    let method = Role::Drawn.rgb();
    let peer = Role::Geometry.rgb();
    let mut legend = Legend::default().with_mark(Role::Drawn, Mark::Fill, "rasterlab's methods");
    if points.iter().any(|p| p.peer) {
        legend = legend.with_mark(
            Role::Geometry,
            Mark::Ring,
            "2D libraries' anti-aliased fills",
        );
    }
    let plotted: Vec<Plotted> = points
        .iter()
        .map(|p| Plotted {
            name: p.name.clone(),
            cost: p.ns_per_pair,
            error: p.rms,
            rgb: if p.peer { peer } else { method },
            filled: !p.peer,
        })
        .collect();
    let labels = Labels {
        heading: format!("Anti-aliasing: error against cost ({title})"),
        cost: "cost: ns per (pixel, triangle) pair, log scale",
        error: "error: RMS per triangle against the exact area",
    };
    error_cost_svg(&labels, &plotted, &legend)
}

/// A point of an error-against-cost chart, drawn as it says.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Plotted {
    /// Written beside the point.
    pub name: String,
    /// Across, on a log scale.
    pub cost: f64,
    /// Up the page.
    pub error: f64,
    /// Its colour, one of the palette's.
    pub rgb: [u8; 3],
    /// A filled dot, or an open ring.
    pub filled: bool,
}

/// The texts of an error-against-cost chart.
pub(crate) struct Labels {
    /// The title.
    pub heading: String,
    /// Under the cost axis.
    pub cost: &'static str,
    /// Beside the error axis.
    pub error: &'static str,
}

/// The chart of `points`, error up and cost across on a log scale, with
/// `legend` under it. Points whose cost is not a positive number are left
/// out.
pub(crate) fn error_cost_svg(labels: &Labels, points: &[Plotted], legend: &Legend) -> String {
    let shown: Vec<&Plotted> = points
        .iter()
        .filter(|p| p.cost > 0.0 && p.cost.is_finite() && p.error.is_finite())
        .collect();
    let plot_w = WIDTH - LEFT - RIGHT;
    // Whole decades around the costs, the error from 0 to a round top.
    let (lo, hi) = shown.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| {
        (lo.min(p.cost), hi.max(p.cost))
    });
    let (d0, d1) = if shown.is_empty() {
        (1.0, 3.0)
    } else {
        (
            lo.log10().floor(),
            hi.log10().ceil().max(lo.log10().floor() + 1.0),
        )
    };
    let top_error = shown.iter().map(|p| p.error).fold(0.0, f64::max);
    let y_max = (top_error * 10.0).ceil().max(1.0) / 10.0;
    let x_of = |ns: f64| LEFT + (ns.log10() - d0) / (d1 - d0) * plot_w;
    let y_of = |e: f64| TOP + PLOT_H - e / y_max * PLOT_H;
    let one = |v: f64| format!("{v:.1}");
    let (legend_svg, legend_h) = legend.to_svg(LEFT, TOP + PLOT_H + 48.0, WIDTH - LEFT - 10.0);
    let height = TOP + PLOT_H + 52.0 + legend_h;
    let mut m = Markup::new();
    m.open_svg(WIDTH, height, Some(12)).newline();
    m.empty(
        "rect",
        &[("width", &"100%"), ("height", &"100%"), ("fill", &"white")],
    );
    m.element(
        "text",
        &[
            ("x", &10),
            ("y", &22),
            ("font-size", &15),
            ("font-weight", &"bold"),
        ],
        &labels.heading,
    )
    .newline();
    // The grid: decades across, tenths of the error up.
    let bottom = TOP + PLOT_H;
    let mut decade = d0;
    while decade <= d1 {
        let x = one(x_of(10f64.powf(decade)));
        m.empty(
            "line",
            &[
                ("x1", &x),
                ("y1", &TOP),
                ("x2", &x),
                ("y2", &one(bottom)),
                ("stroke", &"#ddd"),
            ],
        );
        m.element(
            "text",
            &[
                ("x", &x),
                ("y", &one(bottom + 16.0)),
                ("text-anchor", &"middle"),
            ],
            &format!("{}", 10f64.powf(decade)),
        );
        decade += 1.0;
    }
    let steps = (y_max * 10.0).round() as i32;
    for k in 0..=steps {
        let e = f64::from(k) / 10.0;
        let y = one(y_of(e));
        m.empty(
            "line",
            &[
                ("x1", &LEFT),
                ("y1", &y),
                ("x2", &one(LEFT + plot_w)),
                ("y2", &y),
                ("stroke", &"#ddd"),
            ],
        );
        m.element(
            "text",
            &[
                ("x", &(LEFT - 6.0)),
                ("y", &one(y_of(e) + 4.0)),
                ("text-anchor", &"end"),
            ],
            &format!("{e:.1}"),
        );
    }
    m.element(
        "text",
        &[
            ("x", &one(LEFT + plot_w / 2.0)),
            ("y", &one(bottom + 36.0)),
            ("text-anchor", &"middle"),
        ],
        labels.cost,
    );
    m.element(
        "text",
        &[
            ("x", &16),
            ("y", &one(TOP + PLOT_H / 2.0)),
            ("text-anchor", &"middle"),
            (
                "transform",
                &format_args!("rotate(-90 16 {})", one(TOP + PLOT_H / 2.0)),
            ),
        ],
        labels.error,
    )
    .newline();
    // Labels are placed from the top down, each moved down below any
    // earlier one it would overwrite.
    let mut order: Vec<&&Plotted> = shown.iter().collect();
    order.sort_by(|a, b| b.error.total_cmp(&a.error));
    let mut placed: Vec<(f64, f64, f64)> = Vec::new();
    let mut labels = Vec::new();
    for p in order {
        let (x, y) = (x_of(p.cost), y_of(p.error));
        dot(&mut m, p, x, y);
        if p.name.is_empty() {
            continue;
        }
        let width = p.name.chars().count() as f64 * 7.0;
        let mut label_y = y + 4.0;
        while let Some(&(_, py, _)) = placed.iter().find(|&&(px, py, pw)| {
            (label_y - py).abs() < 13.0 && x + 8.0 < px + pw && px < x + 8.0 + width
        }) {
            label_y = py + 13.0;
        }
        placed.push((x + 8.0, label_y, width));
        labels.push((x + 8.0, label_y, &p.name));
    }
    // The names over every dot, so that no dot hides one.
    for (x, y, name) in labels {
        m.element("text", &[("x", &one(x)), ("y", &one(y))], name)
            .newline();
    }
    m.raw(&legend_svg);
    m.close("svg");
    m.finish()
}

/// Point `p`'s dot at `(x, y)`: filled, or an open ring.
fn dot(m: &mut Markup, p: &Plotted, x: f64, y: f64) {
    let colour = crate::teaching::palette::colour_hex(p.rgb);
    let (fill, stroke) = if p.filled {
        (colour.as_str(), colour.as_str())
    } else {
        ("white", colour.as_str())
    };
    m.empty(
        "circle",
        &[
            ("class", &"point"),
            ("cx", &format!("{x:.1}")),
            ("cy", &format!("{y:.1}")),
            ("r", &5),
            ("fill", &fill),
            ("stroke", &stroke),
            ("stroke-width", &2),
        ],
    );
}
