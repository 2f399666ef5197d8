//! Pixel grids as text, one character a pixel: how the tests state an
//! expected pattern, and how `check` prints a counterexample in a
//! terminal.
//!
//! ```
//! use rasterlab::teaching::{ascii_count, ascii_mark, ascii_rows};
//!
//! let covered = [(0, 0), (1, 0), (1, 1)];
//! let rows = ascii_rows(0..3, 0..2, |x, y| ascii_mark(covered.contains(&(x, y))));
//! assert_eq!(rows, ["##.", ".#."]);
//! assert_eq!(ascii_count(2), '2');
//! ```

use std::fmt::Write;
use std::ops::Range;

/// `#` for a covered pixel, `.` for one that is not.
pub fn ascii_mark(covered: bool) -> char {
    if covered {
        '#'
    } else {
        '.'
    }
}

/// A pixel drawn `n` times: `.` never, `#` once, the digit from 2 to 9,
/// `+` more often.
pub fn ascii_count(n: u32) -> char {
    match n {
        0 => '.',
        1 => '#',
        2..=9 => char::from_digit(n, 10).expect("a digit"),
        _ => '+',
    }
}

/// The rows `ys` of columns `xs`, each pixel as `cell(x, y)` says.
pub fn ascii_rows(xs: Range<i64>, ys: Range<i64>, cell: impl Fn(i64, i64) -> char) -> Vec<String> {
    ys.map(|y| xs.clone().map(|x| cell(x, y)).collect())
        .collect()
}

/// [`ascii_rows`] with the column range above them and each row's index
/// before it, for a reader to find a pixel:
///
/// ```text
///      x 0..2
///    0  ##.
///    1  .#.
/// ```
pub fn ascii_framed(xs: Range<i64>, ys: Range<i64>, cell: impl Fn(i64, i64) -> char) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "     x {}..{}", xs.start, xs.end - 1);
    for (y, row) in ys.clone().zip(ascii_rows(xs, ys, cell)) {
        let _ = writeln!(out, "{y:>4}  {row}");
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn framed_rows_carry_their_indices() {
        let text = ascii_framed(2..5, 7..9, |x, y| ascii_count(((x + y) % 3) as u32));
        assert_eq!(text, "     x 2..4\n   7  .#2\n   8  #2.\n");
    }

    #[test]
    fn counts_above_nine_are_a_plus() {
        assert_eq!((0..12).map(ascii_count).collect::<String>(), ".#23456789++");
    }
}
