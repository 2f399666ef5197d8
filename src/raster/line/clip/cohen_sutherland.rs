//! Cohen-Sutherland line clipping (Sproull and Sutherland, 1968; Newman
//! and Sproull, *Principles of Interactive Computer Graphics*, 1973;
//! Foley, van Dam, Feiner and Hughes, section 3.12.3).
//!
//! The plane is cut by the window's four edges into nine regions, and
//! each point gets a 4-bit **outcode**, written `TBRL`: top (`y` above
//! the top edge; `y` grows down), bottom, right, left, a bit set for each
//! edge the point lies beyond. Then, until the segment is decided:
//!
//! ```text
//! code0 = outcode(P0), code1 = outcode(P1)
//! loop:
//!     if code0 | code1 == 0: accept          (both inside)
//!     if code0 & code1 != 0: reject          (both beyond one edge)
//!     pick an endpoint outside, and the first edge its code names
//!         (top, bottom, right, left)
//!     move it to where the segment meets that edge's line; recompute its code
//! ```
//!
//! Each move clears the bit of the edge, so a segment is decided after at
//! most four intersections. The first test decides most segments of a
//! scene (trivial acceptance and trivial rejection); the others pay an
//! intersection, and sometimes one that is clipped away again (a point
//! moved to the top edge's line beyond the right edge).
//!
//! Here every point is kept as its parameter `t` on the original segment,
//! an exact fraction ([`Param`]): the point moved to the top edge `y = y0`
//! is `t = (y0 - Py) / (Qy - Py)`, and its outcode is computed from
//! `P + t (Q - P)` in integers, so no rounding ever moves it off the edge.

use super::{ClipWindow, ClipWork, Clipped, ExactPoint, Param};
use crate::raster::fixed::FixedPoint;

/// A point's outcode: bits `T B R L` (8, 4, 2, 1).
#[derive(Copy, Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct Outcode(pub u8);

impl Outcode {
    /// Above the top edge (`y < y0`, y down).
    pub const TOP: Outcode = Outcode(8);
    /// Below the bottom edge.
    pub const BOTTOM: Outcode = Outcode(4);
    /// Right of the right edge.
    pub const RIGHT: Outcode = Outcode(2);
    /// Left of the left edge.
    pub const LEFT: Outcode = Outcode(1);
    /// Inside the window.
    pub const INSIDE: Outcode = Outcode(0);

    /// The outcode of an exact point.
    pub fn of(p: ExactPoint, window: ClipWindow) -> Outcode {
        let edge = |e: i64| i128::from(e) * p.den;
        let mut code = 0;
        if p.y < edge(window.y0) {
            code |= Self::TOP.0;
        } else if p.y > edge(window.y1) {
            code |= Self::BOTTOM.0;
        }
        if p.x > edge(window.x1) {
            code |= Self::RIGHT.0;
        } else if p.x < edge(window.x0) {
            code |= Self::LEFT.0;
        }
        Outcode(code)
    }

    /// Is the point inside?
    pub fn is_inside(self) -> bool {
        self.0 == 0
    }

    /// The first edge the code names, in the order top, bottom, right,
    /// left; `None` inside.
    pub fn first_edge(self) -> Option<Edge> {
        [Edge::Top, Edge::Bottom, Edge::Right, Edge::Left]
            .into_iter()
            .find(|e| self.0 & e.bit().0 != 0)
    }
}

/// The code as its four bits, `TBRL` (`1001`: above and left).
impl std::fmt::Display for Outcode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{:04b}", self.0)
    }
}

/// An edge of the window.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub enum Edge {
    /// `y = y0`.
    Top,
    /// `y = y1`.
    Bottom,
    /// `x = x1`.
    Right,
    /// `x = x0`.
    Left,
}

impl Edge {
    /// The outcode bit of the points beyond this edge.
    pub fn bit(self) -> Outcode {
        match self {
            Edge::Top => Outcode::TOP,
            Edge::Bottom => Outcode::BOTTOM,
            Edge::Right => Outcode::RIGHT,
            Edge::Left => Outcode::LEFT,
        }
    }

    /// The edge's name.
    pub fn name(self) -> &'static str {
        match self {
            Edge::Top => "top",
            Edge::Bottom => "bottom",
            Edge::Right => "right",
            Edge::Left => "left",
        }
    }

    /// Where the segment `from -> to` meets this edge's line, for a
    /// segment that crosses it.
    fn crossing(self, from: FixedPoint, to: FixedPoint, window: ClipWindow) -> Param {
        let (a, b, e) = match self {
            Edge::Top => (from.y.raw(), to.y.raw(), window.y0),
            Edge::Bottom => (from.y.raw(), to.y.raw(), window.y1),
            Edge::Right => (from.x.raw(), to.x.raw(), window.x1),
            Edge::Left => (from.x.raw(), to.x.raw(), window.x0),
        };
        Param::ratio(e - a, b - a)
    }
}

/// What one pass of the loop decided.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Decision {
    /// Both codes zero: the segment between the two points is drawn.
    Accept,
    /// The codes share a bit: nothing is drawn.
    Reject,
    /// Endpoint `end` (0 the start, 1 the end) moved to `edge`, at `t`.
    Move {
        /// Which endpoint: 0 or 1.
        end: usize,
        /// The edge named by its code.
        edge: Edge,
        /// The new point's parameter on the original segment.
        t: Param,
        /// The new point's outcode.
        code: Outcode,
    },
}

/// One pass of the loop, for traces: the two points' parameters and
/// codes, and what was decided.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Step {
    /// The two points' parameters on the original segment.
    pub t: [Param; 2],
    /// Their outcodes.
    pub codes: [Outcode; 2],
    /// The decision.
    pub decision: Decision,
}

/// Clips `from -> to` to `window`, giving each pass of the loop to
/// `observe`; `None` when nothing is inside.
pub fn clip(
    from: FixedPoint,
    to: FixedPoint,
    window: ClipWindow,
    work: &mut ClipWork,
    mut observe: impl FnMut(Step),
) -> Option<Clipped> {
    work.segments += 1;
    let mut t = [Param::ZERO, Param::ONE];
    let code_at = |t: Param| Outcode::of(t.point(from, to), window);
    let mut codes = [code_at(t[0]), code_at(t[1])];
    work.outcodes += 2;
    for pass in 0.. {
        let (either, both) = (codes[0].0 | codes[1].0, codes[0].0 & codes[1].0);
        let decision = if either == 0 {
            Decision::Accept
        } else if both != 0 {
            Decision::Reject
        } else {
            let end = usize::from(codes[0].is_inside());
            let edge = codes[end].first_edge().expect("an endpoint outside");
            let at = edge.crossing(from, to, window);
            work.intersections += 1;
            work.outcodes += 1;
            Decision::Move {
                end,
                edge,
                t: at,
                code: code_at(at),
            }
        };
        observe(Step { t, codes, decision });
        match decision {
            Decision::Accept => {
                work.trivially_accepted += u64::from(pass == 0);
                return Some(Clipped { t0: t[0], t1: t[1] });
            }
            Decision::Reject => {
                work.trivially_rejected += u64::from(pass == 0);
                work.rejected += 1;
                return None;
            }
            Decision::Move {
                end, t: at, code, ..
            } => {
                t[end] = at;
                codes[end] = code;
            }
        }
    }
    unreachable!("every pass clears a bit or decides")
}
