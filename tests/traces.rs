//! Traces checked against answers worked by hand from the course notes.

use rasterlab::edge::FillRule;
use rasterlab::trace::{bresenham_trace, line_trace, triangle_trace};

/// Seed 004's midpoint loop on (0, 0) -> (7, 3): f(x, y) = -3 x + 7 y, so
/// d starts at f(1, 1/2) = 0.5 and then adds -3 (keep y) or -3 + 7 (step).
#[test]
fn bresenham_0_0_7_3_matches_the_hand_worked_table() {
    let expected = "\
bresenham (midpoint) from pixel (0, 0) to (7, 3); first octant: no symmetry needed
   x      y  pixel            d  choice
   0      0    0,0        0.500  d >= 0: midpoint on or above the line, keep y
   1      0    1,0       -2.500  d < 0: midpoint below the line, y = y + 1
   2      1    2,1        1.500  d >= 0: midpoint on or above the line, keep y
   3      1    3,1       -1.500  d < 0: midpoint below the line, y = y + 1
   4      2    4,2        2.500  d >= 0: midpoint on or above the line, keep y
   5      2    5,2       -0.500  d < 0: midpoint below the line, y = y + 1
   6      3    6,3        3.500  d >= 0: midpoint on or above the line, keep y
   7      3    7,3        0.500  d >= 0: midpoint on or above the line, keep y
d = f(x + 1, y + 1/2) with f(x, y) = (y0 - y1) x + (x1 - x0) y + x0 y1 - x1 y0, in the walking frame
";
    assert_eq!(bresenham_trace(0.0, 0.0, 7.0, 3.0).unwrap(), expected);
}

/// y = 3/7 x: exact values k * 3/7 and their nearest rows, the same rows
/// for direct evaluation and for the incremental DDA.
#[test]
fn direct_and_dda_round_the_exact_y() {
    for backend in ["direct", "dda"] {
        let text = line_trace(backend, 0.0, 0.0, 7.0, 3.0).unwrap();
        let rows: Vec<(String, String)> = text
            .lines()
            .skip(2)
            .take(8)
            .map(|l| {
                let f: Vec<&str> = l.split_whitespace().collect();
                (f[1].to_string(), f[2].to_string())
            })
            .collect();
        let expected = [
            ("0.0000", "0"),
            ("0.4286", "0"),
            ("0.8571", "1"),
            ("1.2857", "1"),
            ("1.7143", "2"),
            ("2.1429", "2"),
            ("2.5714", "3"),
            ("3.0000", "3"),
        ];
        for (got, want) in rows.iter().zip(expected) {
            assert_eq!((got.0.as_str(), got.1.as_str()), want, "{backend}");
        }
    }
}

/// The bounding-box trace of a right triangle: its box (5 x 4 pixels) tested, and the
/// verdicts name the edge and the tie rule.
#[test]
fn bbox_trace_counts_and_explains() {
    let text = triangle_trace(
        "bbox",
        [(0.5, 0.5), (4.5, 0.5), (0.5, 3.5)],
        FillRule::TopLeft,
        6,
        4,
    )
    .unwrap();
    // Box 5 x 4; inside: 4 + 3 + 2 (row 3 only touches v2, on the right edge).
    assert!(text.ends_with("20 pixels tested, 9 fragments\n"), "{text}");
    assert!(text.contains("   4    0    0.0000   12.0000    0.0000   0.000   1.000   0.000  outside: on E0, a right edge that does not own its ties"));
    assert!(text.contains(
        "   3    1   -1.0000    9.0000    4.0000  -0.083   0.750   0.333  outside: E0 < 0"
    ));
    let naive = triangle_trace(
        "naive",
        [(0.5, 0.5), (4.5, 0.5), (0.5, 3.5)],
        FillRule::TopLeft,
        6,
        4,
    )
    .unwrap();
    assert!(
        naive.ends_with("24 pixels tested, 9 fragments\n"),
        "{naive}"
    );
    assert!(triangle_trace(
        "scanline",
        [(0., 0.), (1., 0.), (0., 1.)],
        FillRule::TopLeft,
        4,
        4
    )
    .is_err());
}
