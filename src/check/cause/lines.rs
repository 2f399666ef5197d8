//! The line causes: another tie rule, a line walked from its other end, an
//! endpoint pixel left out or drawn twice (changes to the reference), and
//! two conditions on the pixels drawn (one pixel per column for a steep
//! line, a 4-connected staircase).

use super::End;
use crate::check::case::Case;
use crate::check::property::{LineConvention, Property};
use crate::check::{reference, Fragment};
use std::collections::{BTreeMap, BTreeSet};

/// The changes a hypothesis makes to the reference's lines.
#[derive(Clone, Debug, Default)]
pub(super) struct Model {
    convention: Option<LineConvention>,
    reversed: bool,
    missing: Option<End>,
    doubled: Option<End>,
}

impl Model {
    /// Adds a cause's change; false when it is not a change to the lines'
    /// reference, or conflicts with one already made.
    pub(super) fn add(&mut self, cause: &super::Cause) -> bool {
        use super::Cause;
        match *cause {
            Cause::Convention(c) if self.convention.is_none() => {
                self.convention = Some(c);
                true
            }
            Cause::Reversed => !std::mem::replace(&mut self.reversed, true),
            Cause::EndpointMissing(e) if self.missing.is_none() && self.doubled.is_none() => {
                self.missing = Some(e);
                true
            }
            Cause::EndpointDoubled(e) if self.missing.is_none() && self.doubled.is_none() => {
                self.doubled = Some(e);
                true
            }
            _ => false,
        }
    }

    /// What the convention (the model's, or `base`) draws with these
    /// changes, every fragment once (twice where doubled).
    pub(super) fn fragments(&self, case: &Case, base: LineConvention) -> Vec<Fragment> {
        let convention = self.convention.unwrap_or(base);
        let mut walked = case.clone();
        if self.reversed {
            for l in &mut walked.lines {
                l.swap(0, 1);
            }
        }
        let mut out = reference(Property::Line(convention), &walked);
        let ends = |id: usize| endpoint_pixels(case, convention, id, &out);
        let mut changed: Vec<Fragment> = Vec::new();
        if let Some(end) = self.missing.or(self.doubled) {
            for id in 0..case.lines.len() {
                let (first, last) = ends(id);
                // A zero-length line has one pixel, the first and the
                // last: a loop that leaves out either end (`0..n`,
                // `1..=n`, n = 0) draws nothing of it; one that draws an
                // end twice draws it twice once.
                if self.missing.is_some() && first.is_some() && first == last {
                    changed.extend(first);
                    continue;
                }
                let chosen: Vec<Fragment> = match end {
                    End::First => first.into_iter().collect(),
                    End::Last => last.into_iter().collect(),
                    End::Both => first.into_iter().chain(last).collect(),
                };
                changed.extend(chosen);
            }
        }
        if self.missing.is_some() {
            let drop: BTreeSet<Fragment> = changed.into_iter().collect();
            out.retain(|f| !drop.contains(f));
        } else {
            changed.dedup();
            out.extend(changed);
        }
        out
    }
}

/// The pixels of line `id`'s start and end in `answer` (the same pixel
/// twice for a zero-length line): for whole-pixel
/// conventions the endpoint pixels themselves, for screen ones the pixel
/// of the answer nearest each endpoint, where the endpoint lies on the
/// target (an endpoint off the target has no pixel to leave out).
fn endpoint_pixels(
    case: &Case,
    convention: LineConvention,
    id: usize,
    answer: &[Fragment],
) -> (Option<Fragment>, Option<Fragment>) {
    let Some(line) = case.lines.get(id) else {
        return (None, None);
    };
    let mine: Vec<&Fragment> = answer.iter().filter(|f| f.id as usize == id).collect();
    let (w, h) = (f64::from(case.width), f64::from(case.height));
    let pixel_of = |p: (f64, f64)| -> Option<Fragment> {
        if convention.whole_pixels() {
            let (x, y) = (p.0.round() as i64, p.1.round() as i64);
            return mine.iter().find(|f| (f.x, f.y) == (x, y)).map(|f| **f);
        }
        if !(0.0..w).contains(&p.0) || !(0.0..h).contains(&p.1) {
            return None;
        }
        mine.iter()
            .min_by(|a, b| {
                let d = |f: &Fragment| (f.x as f64 + 0.5 - p.0).hypot(f.y as f64 + 0.5 - p.1);
                d(a).total_cmp(&d(b))
            })
            .map(|f| **f)
    };
    (pixel_of(line[0]), pixel_of(line[1]))
}

/// The pixels drawn for each line.
fn by_line(drawn: &[Fragment]) -> BTreeMap<u32, BTreeSet<(i64, i64)>> {
    let mut out: BTreeMap<u32, BTreeSet<(i64, i64)>> = BTreeMap::new();
    for f in drawn {
        out.entry(f.id).or_default().insert((f.x, f.y));
    }
    out
}

/// Whether every line in `ids` is steep and drawn one pixel per column
/// (the walk along x used for a line that runs along y: the octant swap
/// left out): one pixel in each column of a contiguous run of columns
/// within the line's, or, in each column of its run, the pixel nearest
/// the ideal line (either one at a tie) wherever that pixel is on the
/// target, and nothing else. `whole_pixels`: the endpoints name pixels, whose centres the
/// line joins; otherwise they are screen coordinates.
pub(super) fn one_per_column(
    case: &Case,
    whole_pixels: bool,
    drawn: &[Fragment],
    ids: &BTreeSet<u32>,
) -> bool {
    let pixels = by_line(drawn);
    let (w, h) = (i64::from(case.width), i64::from(case.height));
    let empty = BTreeSet::new();
    !ids.is_empty()
        && ids.iter().all(|id| {
            let Some(line) = case.lines.get(*id as usize) else {
                return false;
            };
            // In pixel units whose whole numbers are pixel centres.
            let shift = if whole_pixels { 0.0 } else { 0.5 };
            let [(x0, y0), (x1, y1)] = line.map(|p| (p.0 - shift, p.1 - shift));
            let (dx, dy) = (x1 - x0, y1 - y0);
            if dy.abs() <= dx.abs() {
                return false;
            }
            let p = pixels.get(id).unwrap_or(&empty);
            if dx == 0.0 {
                // A vertical line has one column: one of its endpoint
                // pixels drawn, or none where one lies off the target.
                let ends = [(x0, y0), (x1, y1)].map(|q| (q.0.round() as i64, q.1.round() as i64));
                let on = |q: &(i64, i64)| (0..w).contains(&q.0) && (0..h).contains(&q.1);
                return match p.len() {
                    0 => ends.iter().any(|q| !on(q)),
                    1 => p.iter().all(|q| ends.contains(q)),
                    _ => false,
                };
            }
            let (lo, hi) = (x0.min(x1).round() as i64, x0.max(x1).round() as i64);
            if p.iter().any(|q| q.0 < lo || q.0 > hi) {
                return false;
            }
            // One pixel in each column of a contiguous run, wherever the
            // walk went (a first-octant Bresenham on a steep line runs
            // diagonally and stops short)...
            let columns: BTreeSet<i64> = p.iter().map(|q| q.0).collect();
            let contiguous = columns.len() == p.len()
                && columns
                    .first()
                    .zip(columns.last())
                    .is_some_and(|(a, b)| (b - a + 1) as usize == p.len());
            // ... or the pixel nearest the line in each column, which may
            // lie off the target (then nothing is drawn there).
            contiguous
                || (lo.max(0)..=hi.min(w - 1)).all(|c| {
                    let y = y0 + (c as f64 - x0) * dy / dx;
                    let rows: Vec<i64> = p.iter().filter(|q| q.0 == c).map(|q| q.1).collect();
                    let nearest = |r: i64| (r as f64 - y).abs() <= 0.5 + 1e-9;
                    match rows.as_slice() {
                        [] => !(0..h).any(nearest),
                        [r] => nearest(*r),
                        _ => false,
                    }
                })
        })
}

/// Whether every line in `ids` is drawn as a 4-connected staircase: its
/// pixels joined through left, right, up and down neighbours only, as
/// many as its width plus its height less one (each step one axis), from
/// the rule's first endpoint pixel to its last, on a line that is not
/// axis-parallel.
pub(super) fn four_connected(
    case: &Case,
    convention: LineConvention,
    drawn: &[Fragment],
    answer: &[Fragment],
    ids: &BTreeSet<u32>,
) -> bool {
    let pixels = by_line(drawn);
    !ids.is_empty()
        && ids.iter().all(|id| {
            let Some(p) = pixels.get(id) else {
                return false;
            };
            // It reaches both of the rule's endpoint pixels.
            let (first, last) = endpoint_pixels(case, convention, *id as usize, answer);
            let ends: Vec<(i64, i64)> = first.into_iter().chain(last).map(|f| (f.x, f.y)).collect();
            let xs = p.iter().map(|q| q.0);
            let ys = p.iter().map(|q| q.1);
            let span = |v: &mut dyn Iterator<Item = i64>| {
                let (mut lo, mut hi) = (i64::MAX, i64::MIN);
                for x in v {
                    lo = lo.min(x);
                    hi = hi.max(x);
                }
                hi - lo
            };
            let (wide, tall) = (span(&mut xs.clone()), span(&mut ys.clone()));
            // An axis-parallel line is 4-connected whatever the rule.
            if wide == 0 || tall == 0 || p.len() as i64 != wide + tall + 1 {
                return false;
            }
            if !ends.iter().all(|e| p.contains(e)) {
                return false;
            }
            // Connected through 4-neighbours.
            let start = *p.first().expect("a line with pixels");
            let mut seen = BTreeSet::from([start]);
            let mut todo = vec![start];
            while let Some((x, y)) = todo.pop() {
                for q in [(x + 1, y), (x - 1, y), (x, y + 1), (x, y - 1)] {
                    if p.contains(&q) && seen.insert(q) {
                        todo.push(q);
                    }
                }
            }
            seen.len() == p.len()
        })
}
