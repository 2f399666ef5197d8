//! Lines with pixel-index endpoints: classic integer Bresenham, the
//! reference of [`LineConvention::PixelIndex`](super::judge::LineConvention).
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

use super::case::Case;
use super::Fragment;

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

/// The reference fragments of a case's lines, clipped to the target.
pub fn fragments(case: &Case) -> Vec<Fragment> {
    let (w, h) = (i64::from(case.width), i64::from(case.height));
    case.lines
        .iter()
        .enumerate()
        .flat_map(|(id, line)| {
            let (a, b) = endpoints(line);
            bresenham(a, b)
                .into_iter()
                .filter(move |&(x, y)| (0..w).contains(&x) && (0..h).contains(&y))
                .map(move |(x, y)| Fragment {
                    x,
                    y,
                    id: id as u32,
                })
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
}
