//! Anti-aliasing compared: how far each way of sampling a pixel lands
//! from the exact area the triangle covers there.
//!
//! An anti-aliased picture gives an edge pixel the share of it a
//! triangle covers. The exact share is the area of the triangle inside
//! the pixel ([`area_coverage`]); the methods the APIs and libraries use
//! estimate it from samples:
//!
//! | method | samples a pixel | where |
//! |---|---|---|
//! | one sample | 1 | the pixel centre: aliased, coverage 0 or 1 |
//! | multisampling, MSAA N | 2, 4, 8, 16 | the standard patterns ([`SamplePattern`]) |
//! | supersampling, SSAA k x k | 4, 9, 16, 64 | a regular grid: the picture drawn k times larger, then averaged ([`supersample()`]) |
//!
//! Every sample is decided as a pixel centre is (snapped vertices, exact
//! edge functions, the fill rule's ties), by a back-end's own walk.
//! [`coverage_of`] gives each method's coverage of each pixel by each
//! triangle, and [`coverage_error`] its error against the exact area, two
//! ways:
//!
//! * **per triangle**: over every (pixel, triangle) pair that either
//!   covers, the root mean square and the worst of `estimate - exact`.
//!   This is what a resolve weights each triangle's colour by;
//! * **in the picture**: a pixel's coverage summed over its triangles
//!   (at most 1), against the exact sum. For a mesh (triangles that
//!   share edges and never overlap) a sampling method's picture is exact
//!   inside it, each sample there covered once, and its errors are at
//!   the mesh's outline only. A renderer that draws each
//!   triangle anti-aliased on its own and blends them over each other
//!   (coverage `a + b (1 - a)`, as 2D libraries do) loses coverage on
//!   every shared edge, where two half-covered triangles give 3/4:
//!   conflation, which this error shows and the per-triangle one does
//!   not.
//!
//! Both errors are in **coverage**, the fraction of a pixel covered: the
//! linear light of a white triangle on black, the space the stage mixes
//! and resolves in ([`MixSpace::Linear`](crate::raster::MixSpace)). An
//! error of 0.1 is a tenth of the light; stored, it is a different number
//! of sRGB steps at each level (from coverage 0.5, 0.1 more is about 16
//! steps, 0.1 less about 18).
//!
//! [`compare_antialiasing`] runs every method of [`METHODS`] on the same
//! triangles; `cargo bench --bench antialias` adds each method's cost and
//! tiny-skia's anti-aliased fill, measured the same way.
//!
//! ```
//! use rasterlab::measure::{compare_antialiasing, Method};
//! use rasterlab::raster::{FillRule, FixedPoint};
//!
//! let v = [(0.5, 0.3), (7.7, 2.1), (2.2, 6.9)].map(|(x, y)| FixedPoint::snap_f64(x, y).unwrap());
//! let rows = compare_antialiasing(&[v], 8, 8, FillRule::TopLeft).unwrap();
//! let rms = |m: Method| rows.iter().find(|r| r.method == m).unwrap().per_triangle.rms;
//! // More samples, closer to the exact area; the exact area has no error.
//! assert!(rms(Method::Multisample(16)) < rms(Method::Multisample(1)));
//! assert_eq!(rms(Method::Area), 0.0);
//! ```

use crate::error::Result;
use crate::raster::triangle::TriangleRasterizer;
use crate::raster::{
    area_coverage, default_triangle_backend, masks_of, supersample, FillRule, FixedPoint,
    PixelRect, SamplePattern, TriangleSetup,
};
use serde::Serialize;
use std::collections::BTreeMap;
use std::fmt;

/// A way of estimating how much of a pixel a triangle covers.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// N samples on the standard pattern (1: the pixel centre).
    Multisample(u32),
    /// k x k samples on a regular grid.
    Supersample(u32),
    /// The exact area.
    Area,
}

/// The methods compared, fewest samples first; the exact area last.
pub const METHODS: [Method; 10] = [
    Method::Multisample(1),
    Method::Multisample(2),
    Method::Multisample(4),
    Method::Supersample(2),
    Method::Multisample(8),
    Method::Supersample(3),
    Method::Multisample(16),
    Method::Supersample(4),
    Method::Supersample(8),
    Method::Area,
];

impl Method {
    /// Samples a pixel (0 for the exact area).
    pub fn samples(self) -> u32 {
        match self {
            Method::Multisample(n) => n,
            Method::Supersample(k) => k * k,
            Method::Area => 0,
        }
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Method::Multisample(1) => f.write_str("one sample (the centre)"),
            Method::Multisample(n) => write!(f, "MSAA {n}"),
            Method::Supersample(k) => write!(f, "SSAA {k}x{k}"),
            Method::Area => f.write_str("exact area"),
        }
    }
}

/// How much of pixel `(x, y)` triangle `triangle` covers, from 0 to 1.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Coverage {
    /// Column.
    pub x: i64,
    /// Row.
    pub y: i64,
    /// The triangle's index in the input.
    pub triangle: u32,
    /// The share of the pixel covered.
    pub value: f64,
}

/// Each pixel's coverage by each triangle under `method`, drawn by
/// `backend` under `rule` within `rect` (the rule and the back-end do
/// not matter to the exact area).
pub fn coverage_of(
    method: Method,
    backend: &dyn TriangleRasterizer,
    triangles: &[[FixedPoint; 3]],
    rect: PixelRect,
    rule: FillRule,
) -> Result<Vec<Coverage>> {
    Ok(match method {
        Method::Multisample(n) => {
            let pattern = SamplePattern::standard(n)?;
            let setups: Vec<TriangleSetup> = triangles
                .iter()
                .enumerate()
                .filter_map(|(i, v)| TriangleSetup::new(i as u32, *v, rule))
                .collect();
            masks_of(backend, &setups, rect, &pattern)
                .into_iter()
                .map(|m| Coverage {
                    x: m.x,
                    y: m.y,
                    triangle: m.triangle,
                    value: f64::from(m.mask.count_ones()) / f64::from(n),
                })
                .collect()
        }
        Method::Supersample(k) => supersample(backend, triangles, rule, rect, k)?
            .into_iter()
            .map(|c| Coverage {
                x: c.x,
                y: c.y,
                triangle: c.triangle,
                value: f64::from(c.count) / f64::from(k * k),
            })
            .collect(),
        Method::Area => area_coverage(triangles, rect)
            .into_iter()
            .map(|a| Coverage {
                x: a.x,
                y: a.y,
                triangle: a.triangle,
                value: a.area,
            })
            .collect(),
    })
}

/// An error's root mean square and its worst case.
#[derive(Copy, Clone, Debug, Default, PartialEq, Serialize)]
pub struct ErrorSummary {
    /// How many values were compared.
    pub count: usize,
    /// The root mean square of `estimate - exact`.
    pub rms: f64,
    /// The largest `|estimate - exact|`.
    pub worst: f64,
}

impl ErrorSummary {
    fn of(pairs: impl Iterator<Item = (f64, f64)>) -> ErrorSummary {
        let (mut count, mut sum, mut worst) = (0, 0.0, 0.0f64);
        for (estimate, exact) in pairs {
            let e = estimate - exact;
            count += 1;
            sum += e * e;
            worst = worst.max(e.abs());
        }
        ErrorSummary {
            count,
            rms: if count == 0 {
                0.0
            } else {
                (sum / count as f64).sqrt()
            },
            worst,
        }
    }
}

/// One method's error against the exact area.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct AntialiasRow {
    /// The method.
    pub method: Method,
    /// Its name as the table gives it.
    pub name: String,
    /// Samples a pixel (0 for the exact area).
    pub samples: u32,
    /// Over every (pixel, triangle) pair either covers.
    pub per_triangle: ErrorSummary,
    /// Over every pixel either covers, its triangles' coverage summed
    /// (at most 1).
    pub picture: ErrorSummary,
    /// Its cost: the time it took, in nanoseconds per (pixel, triangle)
    /// pair of the exact area (the median of three runs; `cargo bench
    /// --bench antialias` gives interleaved rounds).
    pub ns_per_pair: f64,
}

/// The error of `estimate` against `exact`, per triangle and in the
/// picture (see the module docs). `picture` gives the estimate's own
/// picture where it is not the sum of its triangles (a renderer that
/// blends each anti-aliased triangle over the others); `None` sums them.
pub fn coverage_error(
    estimate: &[Coverage],
    exact: &[Coverage],
    picture: Option<&BTreeMap<(i64, i64), f64>>,
) -> (ErrorSummary, ErrorSummary) {
    let by_pair = |v: &[Coverage]| -> BTreeMap<(i64, i64, u32), f64> {
        let mut m = BTreeMap::new();
        for c in v {
            *m.entry((c.y, c.x, c.triangle)).or_insert(0.0) += c.value;
        }
        m
    };
    let (e, x) = (by_pair(estimate), by_pair(exact));
    let per_triangle = ErrorSummary::of(union_pairs(&e, &x));
    let summed = |m: &BTreeMap<(i64, i64, u32), f64>| -> BTreeMap<(i64, i64), f64> {
        let mut out = BTreeMap::new();
        for (&(y, x, _), v) in m {
            let p: &mut f64 = out.entry((y, x)).or_insert(0.0);
            *p = (*p + v).min(1.0);
        }
        out
    };
    let estimate_picture = match picture {
        Some(p) => p.clone(),
        None => summed(&e),
    };
    let picture = ErrorSummary::of(union_pairs(&estimate_picture, &summed(&x)));
    (per_triangle, picture)
}

/// `(estimate, exact)` for every key of either map, 0 where one lacks it.
fn union_pairs<'a, K: Ord + Copy>(
    estimate: &'a BTreeMap<K, f64>,
    exact: &'a BTreeMap<K, f64>,
) -> impl Iterator<Item = (f64, f64)> + 'a {
    let only_exact = exact
        .iter()
        .filter(|(k, _)| !estimate.contains_key(k))
        .map(|(_, &v)| (0.0, v));
    estimate
        .iter()
        .map(|(k, &v)| (v, exact.get(k).copied().unwrap_or(0.0)))
        .chain(only_exact)
}

/// Every method of [`METHODS`] on `triangles` in a `width` x `height`
/// target, drawn by the default triangle back-end under `rule`, against
/// the exact area.
pub fn compare_antialiasing(
    triangles: &[[FixedPoint; 3]],
    width: u32,
    height: u32,
    rule: FillRule,
) -> Result<Vec<AntialiasRow>> {
    let rect = PixelRect::of_target(width, height);
    let backend = default_triangle_backend();
    let exact = coverage_of(Method::Area, backend, triangles, rect, rule)?;
    let pairs = exact.len().max(1) as f64;
    METHODS
        .iter()
        .map(|&method| {
            // The median of three runs: the first often pays for
            // memory the others find ready.
            let mut times = [0.0; 3];
            let mut estimate = Vec::new();
            for t in &mut times {
                let start = std::time::Instant::now();
                estimate = coverage_of(method, backend, triangles, rect, rule)?;
                *t = start.elapsed().as_secs_f64() * 1e9 / pairs;
            }
            times.sort_by(f64::total_cmp);
            let ns_per_pair = times[1];
            let (per_triangle, picture) = coverage_error(&estimate, &exact, None);
            Ok(AntialiasRow {
                method,
                name: method.to_string(),
                samples: method.samples(),
                per_triangle,
                picture,
                ns_per_pair,
            })
        })
        .collect()
}
