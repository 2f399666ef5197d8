//! One triangle's samples traced: multisampling, pixel by pixel.
//!
//! With N samples a pixel, each sample is decided exactly as the course
//! decides a pixel centre: the three edge values at the sample point
//! (`E0`, `E1`, `E2`, in px², the same edge functions), inside when each
//! is positive, or zero on an edge that owns its ties under the fill
//! rule. A pixel's coverage mask has bit `i` set when sample `i` is
//! inside. Where a triangle covers every sample of a pixel, or none,
//! multisampling draws what one sample draws; the trace therefore lists,
//! sample by sample, the pixels it covers in part, and maps every
//! pixel's count of covered samples.
//!
//! ```
//! use rasterlab::raster::{FillRule, SamplePattern};
//! use rasterlab::teaching::trace_samples;
//!
//! let pattern = SamplePattern::standard(4).unwrap();
//! let trace = trace_samples([(0.0, 0.0), (4.0, 0.0), (0.0, 3.7)], FillRule::TopLeft, 6, 5, &pattern)
//!     .unwrap()
//!     .to_text();
//! // Pixel (2, 1): its centre is outside, samples 0 and 2 inside.
//! assert!(trace.contains("pixel (2, 1): mask 5 = 0b0101, 2 of 4 samples"));
//! ```

use super::trace::{check_trace_length, snapped_or_say, verdict, AREA_UNIT};
use super::trace_table::{Column, Trace, TraceRow};
use crate::error::Result;
use crate::raster::edge::{FillRule, PixelRect};
use crate::raster::fixed::SUBPIXEL_SCALE;
use crate::raster::multisample::{reference_masks, SamplePattern};
use std::collections::BTreeMap;

/// The samples of a `width` x `height` grid that the triangle `vertices`
/// (screen coordinates, snapped to 1/256 px) covers under `rule`, on
/// `pattern`: the masks as a map of counts, then each partly covered
/// pixel's samples with their edge values and verdicts.
pub fn trace_samples(
    vertices: [(f64, f64); 3],
    rule: FillRule,
    width: u32,
    height: u32,
    pattern: &SamplePattern,
) -> Result<Trace> {
    let n = pattern.count();
    let mut out = Trace::default();
    let Some(t) = snapped_or_say(vertices, rule, &mut out, "no sample is covered")? else {
        return Ok(out);
    };
    let grid = PixelRect::of_target(width, height);
    let masks: BTreeMap<(i64, i64), u32> = reference_masks(&[t], grid, pattern)
        .into_iter()
        .map(|m| ((m.x, m.y), m.mask))
        .collect();
    // Row by row, as the pixels are read.
    let mut partial: Vec<((i64, i64), u32)> = masks
        .iter()
        .filter(|(_, &m)| m != pattern.full_mask())
        .map(|(&p, &m)| (p, m))
        .collect();
    partial.sort_by_key(|&((x, y), _)| (y, x));
    check_trace_length(partial.len() as u64 * u64::from(n + 1), "sample lines")?;
    let offsets: Vec<String> = (0..n as usize)
        .map(|i| {
            let (dx, dy) = pattern.offset(i);
            format!("{i} ({dx}, {dy})")
        })
        .collect();
    out.header.push(format!(
        "multisampling, {n} samples a pixel on the standard pattern; offsets in 1/16 px from the pixel centre, y down: {}",
        offsets.join(", ")
    ));
    for k in 0..3 {
        out.header.push(format!(
            "E{k} (opposite v{k}): {} edge; {}",
            t.edges[k].kind(),
            rule.explain_tie(&t.edges[k])
        ));
    }
    out.header.push(format!(
        "covered samples a pixel ('.' none, 1 to {} some, '#' all {n}):",
        if n > 9 { "f in hex" } else { "9" }
    ));
    out.header.push(format!("     x 0..{}", width - 1));
    for y in 0..i64::from(height) {
        let row: String = (0..i64::from(width))
            .map(|x| match masks.get(&(x, y)) {
                None => '.',
                Some(&m) if m == pattern.full_mask() => '#',
                Some(&m) => char::from_digit(m.count_ones(), 16).unwrap_or('?'),
            })
            .collect();
        out.header.push(format!("{y:>4}  {row}"));
    }
    out.header.push(format!(
        "the {} pixel(s) covered in part, sample by sample:",
        partial.len()
    ));
    out.columns = vec![
        Column::right("sample", 6, 2),
        Column::right("at x", 9, 1),
        Column::right("at y", 9, 1),
        Column::right("E0", 9, 1),
        Column::right("E1", 9, 1),
        Column::right("E2", 9, 1),
        Column::left("verdict", 0, 2),
    ];
    for ((x, y), mask) in &partial {
        out.rows.push(
            TraceRow::note(format!(
                "pixel ({x}, {y}): mask {mask} = {mask:#0width$b}, {} of {n} samples",
                mask.count_ones(),
                width = n as usize + 2
            ))
            .about(*x, *y, *x, *y),
        );
        for i in 0..n as usize {
            let (px, py) = pattern.sample_point(*x, *y, i);
            let e = t.edges.map(|edge| edge.eval_raw(px, py));
            let at = |v: i64| format!("{:.4}", v as f64 / SUBPIXEL_SCALE as f64);
            let edge = |k: usize| format!("{:.4}", e[k] as f64 / AREA_UNIT);
            out.rows.push(TraceRow::at_pixel(
                vec![
                    i.to_string(),
                    at(px),
                    at(py),
                    edge(0),
                    edge(1),
                    edge(2),
                    verdict(&t, e),
                ],
                *x,
                *y,
            ));
        }
    }
    let full = masks.len() - partial.len();
    out.footer.push(format!(
        "{} pixel(s) touched: {full} covered whole, {} in part; {} sample(s) covered of {} in those pixels",
        masks.len(),
        partial.len(),
        masks.values().map(|m| m.count_ones()).sum::<u32>(),
        masks.len() as u32 * n
    ));
    Ok(out)
}
