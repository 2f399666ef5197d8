//! Liang-Barsky line clipping (Y.-D. Liang and B. A. Barsky, "A new
//! concept and method for line clipping", ACM Transactions on Graphics
//! 3(1), 1984; Foley, van Dam, Feiner and Hughes, section 3.12.4, the
//! parametric line clipping they present with Cyrus and Beck's).
//!
//! The segment is written `P(t) = P0 + t (P1 - P0)`, `0 <= t <= 1`, with
//! `dx = x1 - x0`, `dy = y1 - y0`. Being inside the window is four
//! inequalities `p_k t <= q_k`:
//!
//! ```text
//! k = 1, left:    p = -dx   q = x0 - xmin
//! k = 2, right:   p =  dx   q = xmax - x0
//! k = 3, top:     p = -dy   q = y0 - ymin      (y grows down)
//! k = 4, bottom:  p =  dy   q = ymax - y0
//! ```
//!
//! Start with `[t0, t1] = [0, 1]`. For each `k`: if `p = 0` the segment
//! is parallel to that edge, and wholly outside when `q < 0`; otherwise
//! `r = q / p` is where it crosses the edge's line: entering when `p < 0`
//! (`t0 = max(t0, r)`), leaving when `p > 0` (`t1 = min(t1, r)`). Once
//! `t0 > t1` nothing is left. The points are computed once, at the end,
//! from `t0` and `t1`, where Cohen-Sutherland computes a point per
//! intersection.
//!
//! Here `r` is kept as an exact fraction ([`Param`]): the endpoints lie
//! on the 1/256 px grid, so `p` and `q` are integers.

use super::{ClipWindow, ClipWork, Clipped, Param};
use crate::raster::fixed::FixedPoint;

/// One boundary's test, for traces.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Step {
    /// The boundary, 1 to 4: left, right, top, bottom.
    pub k: usize,
    /// `p_k`, fixed-point units.
    pub p: i64,
    /// `q_k`, fixed-point units.
    pub q: i64,
    /// `q_k / p_k`, `None` when the segment is parallel to the edge.
    pub r: Option<Param>,
    /// The interval after this boundary.
    pub t0: Param,
    /// The interval after this boundary.
    pub t1: Param,
    /// True when this boundary leaves nothing.
    pub rejects: bool,
}

/// The boundaries' names, in the order `k = 1..=4`.
pub const BOUNDARIES: [&str; 4] = ["left", "right", "top", "bottom"];

/// Clips `from -> to` to `window`, giving each boundary's test to
/// `observe`; `None` when nothing is inside.
pub fn clip(
    from: FixedPoint,
    to: FixedPoint,
    window: ClipWindow,
    work: &mut ClipWork,
    mut observe: impl FnMut(Step),
) -> Option<Clipped> {
    work.segments += 1;
    let (x0, y0) = (from.x.raw(), from.y.raw());
    let (dx, dy) = (to.x.raw() - x0, to.y.raw() - y0);
    let boundaries = [
        (-dx, x0 - window.x0),
        (dx, window.x1 - x0),
        (-dy, y0 - window.y0),
        (dy, window.y1 - y0),
    ];
    let (mut t0, mut t1) = (Param::ZERO, Param::ONE);
    for (n, (p, q)) in boundaries.into_iter().enumerate() {
        work.boundary_tests += 1;
        let (r, rejects) = if p == 0 {
            (None, q < 0)
        } else {
            work.intersections += 1;
            let r = Param::ratio(q, p);
            if p < 0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
            (Some(r), t0 > t1)
        };
        observe(Step {
            k: n + 1,
            p,
            q,
            r,
            t0,
            t1,
            rejects,
        });
        if rejects {
            work.rejected += 1;
            return None;
        }
    }
    Some(Clipped { t0, t1 })
}
