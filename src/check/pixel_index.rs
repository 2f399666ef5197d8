//! Lines with pixel-index endpoints: classic integer Bresenham, the
//! reference of the whole-pixel conventions of
//! [`LineConvention`](super::judge::LineConvention).
//!
//! Libraries that take whole-pixel endpoints (scikit-image's `line`,
//! Pillow's `ImageDraw.line`, OpenCV's `line` without `shift`) mean pixel
//! `(x, y)` by the numbers `x y`, not the point `(x, y)` on the pixel grid.
//! The line runs between the two pixels' centres. Integer Bresenham walks
//! its major axis (x when `|dx| >= |dy|`) from the start pixel to the end
//! pixel, both drawn, and in each step keeps or advances the minor
//! coordinate by the sign of the decision variable
//!
//! ```text
//! D = 2 |dy| - |dx|
//! for each step: draw; if D > 0 { minor += sign(dy); D -= 2 |dx| }; D += 2 |dy|
//! ```
//!
//! which draws, `t` steps from the start, the minor coordinate
//! `start + sign(dy) * round(t |dy| / |dx|)`, a tie (exactly halfway
//! between two pixels) going **toward the start** (`D == 0` does not
//! step). The walk goes from the first endpoint to the second in either
//! direction, so `a -> b` and `b -> a` give the same pixels except at ties.
//! Pixels off the target are left out.
//!
//! Integer Bresenham breaks that tie more than one way in the wild, and
//! each way is a [`WholePixelWalk`]: toward the start as above; toward the end
//! (`D >= 0` steps, or the walk from the other end); and as the course's
//! midpoint pseudocode does, which swaps the endpoints so as to walk along
//! the major axis increasing (left to right, x increasing, for a line
//! along x) and keeps a tie on the current row, so toward the endpoint
//! with the smaller major coordinate whichever was given first.

use super::case::Case;
use super::Fragment;

/// How a whole-pixel line is walked: chiefly how its tie (the ideal line
/// exactly halfway between two pixels of a step) is broken.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum WholePixelWalk {
    /// Toward the first endpoint given.
    TowardStart,
    /// Toward the second endpoint given.
    TowardEnd,
    /// Toward the endpoint with the smaller major coordinate (the
    /// course's walk, left to right).
    LeftToRight,
    /// OpenCV's `cv::line` with `LINE_8` and no `shift`: an endpoint off
    /// the target first moved onto it by `cv::clipLine` (in integers, a
    /// quotient taken in `f64` and truncated), then the walk from the
    /// endpoint with the smaller x, whichever axis is major, a tie toward
    /// that endpoint.
    OpenCv8,
    /// OpenCV's `LINE_4` without `shift`: clipped as [`OpenCv8`], then a
    /// 4-connected staircase from the endpoint with the smaller x, a step
    /// along the major axis first: at major offset `k` the minor offsets
    /// `ceil((k - 1) m / n)` to `ceil(k m / n)`.
    ///
    /// [`OpenCv8`]: WholePixelWalk::OpenCv8
    OpenCv4,
}

/// `cv::clipLine` on a `w` x `h` target: the endpoints moved onto the
/// target, or `None` when the line misses it.
fn opencv_clip(w: i64, h: i64, a: (i64, i64), b: (i64, i64)) -> Option<((i64, i64), (i64, i64))> {
    let (right, bottom) = (w - 1, h - 1);
    let ((mut x1, mut y1), (mut x2, mut y2)) = (a, b);
    let code = |x: i64, y: i64| {
        i64::from(x < 0)
            | i64::from(x > right) << 1
            | i64::from(y < 0) << 2
            | i64::from(y > bottom) << 3
    };
    // `(int64)((double)p / q)`, as OpenCV divides.
    let div = |p: i64, q: i64| (p as f64 / q as f64) as i64;
    let (mut c1, mut c2) = (code(x1, y1), code(x2, y2));
    if c1 & c2 == 0 && c1 | c2 != 0 {
        if c1 & 12 != 0 {
            let to = if c1 < 8 { 0 } else { bottom };
            x1 += div((to - y1) * (x2 - x1), y2 - y1);
            y1 = to;
            c1 = code(x1, 0) & 3;
        }
        if c2 & 12 != 0 {
            let to = if c2 < 8 { 0 } else { bottom };
            x2 += div((to - y2) * (x2 - x1), y2 - y1);
            y2 = to;
            c2 = code(x2, 0) & 3;
        }
        if c1 & c2 == 0 && c1 | c2 != 0 {
            if c1 != 0 {
                let to = if c1 == 1 { 0 } else { right };
                y1 += div((to - x1) * (y2 - y1), x2 - x1);
                x1 = to;
                c1 = 0;
            }
            if c2 != 0 {
                let to = if c2 == 1 { 0 } else { right };
                y2 += div((to - x2) * (y2 - y1), x2 - x1);
                x2 = to;
                c2 = 0;
            }
        }
    }
    (c1 | c2 == 0).then_some(((x1, y1), (x2, y2)))
}

/// OpenCV's 4-connected staircase from `a` to `b` (see
/// [`WholePixelWalk::OpenCv4`]).
fn staircase(a: (i64, i64), b: (i64, i64)) -> Vec<(i64, i64)> {
    let ((x0, y0), (x1, y1)) = if b.0 < a.0 { (b, a) } else { (a, b) };
    let (dx, dy) = (x1 - x0, (y1 - y0).abs());
    let sy = if y1 >= y0 { 1 } else { -1 };
    let vertical = dy > dx;
    let (n, m) = if vertical { (dy, dx) } else { (dx, dy) };
    let ceil = |p: i64| -((-p).div_euclid(n.max(1)));
    let mut out = vec![(x0, y0)];
    for k in 1..=n {
        for j in ceil((k - 1) * m)..=ceil(k * m) {
            out.push(if vertical {
                (x0 + j, y0 + sy * k)
            } else {
                (x0 + k, y0 + sy * j)
            });
        }
    }
    out
}

/// The pixels of the line from pixel `a` to pixel `b` with ties broken
/// by `tie`, in the order of travel from `a`, both ends included.
pub fn walk(a: (i64, i64), b: (i64, i64), walk: WholePixelWalk) -> Vec<(i64, i64)> {
    let backward = |a, b| {
        let mut v = bresenham(b, a);
        v.reverse();
        v
    };
    match walk {
        WholePixelWalk::TowardStart => bresenham(a, b),
        WholePixelWalk::TowardEnd => backward(a, b),
        WholePixelWalk::LeftToRight => {
            let x_major = (b.0 - a.0).abs() >= (b.1 - a.1).abs();
            let forward = if x_major { a.0 <= b.0 } else { a.1 <= b.1 };
            if forward {
                bresenham(a, b)
            } else {
                backward(a, b)
            }
        }
        WholePixelWalk::OpenCv8 if b.0 < a.0 => backward(a, b),
        WholePixelWalk::OpenCv8 => bresenham(a, b),
        WholePixelWalk::OpenCv4 => staircase(a, b),
    }
}

/// The endpoints of a line of a case as pixel indices (the input's numbers,
/// rounded to whole numbers if they are not whole).
pub fn endpoints(line: &[(f64, f64); 2]) -> ((i64, i64), (i64, i64)) {
    let p = |q: (f64, f64)| (q.0.round() as i64, q.1.round() as i64);
    (p(line[0]), p(line[1]))
}

/// The pixels of the line from pixel `a` to pixel `b`, in the order of
/// travel, both ends included.
pub fn bresenham(a: (i64, i64), b: (i64, i64)) -> Vec<(i64, i64)> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let x_major = dx.abs() >= dy.abs();
    let (d_major, d_minor) = if x_major { (dx, dy) } else { (dy, dx) };
    let (n, m) = (d_major.abs(), d_minor.abs());
    (0..=n)
        .map(|t| {
            // round(t m / n), a tie toward zero: ceil((2 t m - n) / (2 n)).
            let q = if n == 0 {
                0
            } else {
                -((n - 2 * t * m).div_euclid(2 * n))
            };
            let major = t * d_major.signum();
            let minor = q * d_minor.signum();
            if x_major {
                (a.0 + major, a.1 + minor)
            } else {
                (a.0 + minor, a.1 + major)
            }
        })
        .collect()
}

/// The reference fragments of a case's lines with ties broken by `tie`,
/// clipped to the target.
pub fn fragments(case: &Case, walk: WholePixelWalk) -> Vec<Fragment> {
    let (w, h) = (i64::from(case.width), i64::from(case.height));
    case.lines
        .iter()
        .enumerate()
        .flat_map(|(id, line)| {
            let (a, b) = endpoints(line);
            let on = |p: (i64, i64)| (0..w).contains(&p.0) && (0..h).contains(&p.1);
            let clips = matches!(walk, WholePixelWalk::OpenCv8 | WholePixelWalk::OpenCv4);
            // OpenCV moves an endpoint off the target onto it first; a line
            // that misses the target draws nothing.
            let ends = if clips && !(on(a) && on(b)) {
                opencv_clip(w, h, a, b)
            } else {
                Some((a, b))
            };
            ends.map(|(a, b)| self::walk(a, b, walk))
                .unwrap_or_default()
                .into_iter()
                .filter(move |&(x, y)| (0..w).contains(&x) && (0..h).contains(&y))
                .map(move |(x, y)| Fragment::at(x, y, id as u32))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Classic integer Bresenham, as textbooks give it for every octant.
    fn textbook(a: (i64, i64), b: (i64, i64)) -> Vec<(i64, i64)> {
        let (dx, dy) = ((b.0 - a.0).abs(), (b.1 - a.1).abs());
        let (sx, sy) = ((b.0 - a.0).signum(), (b.1 - a.1).signum());
        let mut out = Vec::new();
        let (mut x, mut y) = a;
        if dx >= dy {
            let mut d = 2 * dy - dx;
            for _ in 0..=dx {
                out.push((x, y));
                if d > 0 {
                    y += sy;
                    d -= 2 * dx;
                }
                d += 2 * dy;
                x += sx;
            }
        } else {
            let mut d = 2 * dx - dy;
            for _ in 0..=dy {
                out.push((x, y));
                if d > 0 {
                    x += sx;
                    d -= 2 * dy;
                }
                d += 2 * dx;
                y += sy;
            }
        }
        out
    }

    #[test]
    fn the_closed_form_is_the_textbook_loop_in_every_direction() {
        for x0 in -3..4 {
            for y0 in -3..4 {
                for x1 in -7..8 {
                    for y1 in -7..8 {
                        let (a, b) = ((x0, y0), (x1, y1));
                        assert_eq!(bresenham(a, b), textbook(a, b), "{a:?} -> {b:?}");
                    }
                }
            }
        }
        // A tie: (0, 0) -> (2, 1) is halfway at x = 1; toward the start.
        assert_eq!(bresenham((0, 0), (2, 1)), vec![(0, 0), (1, 0), (2, 1)]);
        assert_eq!(bresenham((2, 1), (0, 0)), vec![(2, 1), (1, 1), (0, 0)]);
    }

    #[test]
    fn each_tie_rule_breaks_the_course_tie_its_own_way() {
        let (a, b) = ((0, 0), (2, 1));
        assert_eq!(
            walk(a, b, WholePixelWalk::TowardStart),
            vec![(0, 0), (1, 0), (2, 1)]
        );
        assert_eq!(
            walk(a, b, WholePixelWalk::TowardEnd),
            vec![(0, 0), (1, 1), (2, 1)]
        );
        assert_eq!(
            walk(a, b, WholePixelWalk::LeftToRight),
            vec![(0, 0), (1, 0), (2, 1)]
        );
        // Given right to left, the course still walks left to right.
        assert_eq!(
            walk(b, a, WholePixelWalk::LeftToRight),
            vec![(2, 1), (1, 0), (0, 0)]
        );
        assert_eq!(
            walk(b, a, WholePixelWalk::TowardStart),
            vec![(2, 1), (1, 1), (0, 0)]
        );
        // Off ties, all three agree.
        for tie in [
            WholePixelWalk::TowardStart,
            WholePixelWalk::TowardEnd,
            WholePixelWalk::LeftToRight,
        ] {
            assert_eq!(
                walk((0, 0), (3, 1), tie),
                vec![(0, 0), (1, 0), (2, 1), (3, 1)]
            );
        }
    }
}
