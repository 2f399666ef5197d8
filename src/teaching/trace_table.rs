//! A trace as data: the lines that introduce it, its table (column names
//! and rows, each row with the pixels it is about) and the lines that sum
//! it up. `rasterlab explain` prints it as text ([`Trace::to_text`], the
//! hand-worked tables' layout); the lab receives it as JSON and highlights
//! a row by its pixels when the student points at one.
//!
//! ```
//! use rasterlab::teaching::{Column, Trace, TraceRow};
//!
//! let mut trace = Trace::default();
//! trace.header.push("two pixels".to_string());
//! trace.columns = vec![Column::right("x", 4, 0), Column::left("verdict", 0, 2)];
//! trace.rows.push(TraceRow::at_pixel(vec!["3".into(), "inside".into()], 3, 1));
//! trace.footer.push("1 pixel tested".to_string());
//! assert_eq!(trace.to_text(), "two pixels\n   x  verdict\n   3  inside\n1 pixel tested\n");
//! assert!(trace.rows[0].is_about(3, 1) && !trace.rows[0].is_about(3, 2));
//! ```

use serde::Serialize;
use std::fmt::Write;

/// One column of a trace's table.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Column {
    /// Its name, printed above it.
    pub name: String,
    /// Its width in characters in the text (0: as wide as its cell).
    pub width: usize,
    /// Right-aligned (numbers) or left-aligned (words).
    pub right: bool,
    /// Spaces before it in the text (none before the first column).
    pub gap: usize,
}

impl Column {
    /// A right-aligned column (numbers).
    pub fn right(name: &str, width: usize, gap: usize) -> Column {
        Column {
            name: name.to_string(),
            width,
            right: true,
            gap,
        }
    }

    /// A left-aligned column (words).
    pub fn left(name: &str, width: usize, gap: usize) -> Column {
        Column {
            right: false,
            ..Column::right(name, width, gap)
        }
    }

    fn write(&self, out: &mut String, first: bool, cell: &str) {
        if !first {
            out.extend(std::iter::repeat_n(' ', self.gap));
        }
        let width = self.width;
        let _ = if self.right {
            write!(out, "{cell:>width$}")
        } else {
            write!(out, "{cell:<width$}")
        };
    }
}

/// One row of a trace's table, or a line of words between its rows.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct TraceRow {
    /// Its cells, one per column from the first (a row may stop short).
    pub cells: Vec<String>,
    /// The pixels it is about, as inclusive rectangles `[x0, y0, x1, y1]`:
    /// a sample's pixel, a row of pixels, a block; empty when it is about
    /// none.
    pub about: Vec<[i64; 4]>,
    /// A line of words between rows (its one cell printed as it is),
    /// rather than a row of the table.
    pub note: bool,
}

impl TraceRow {
    /// A row about no pixel in particular.
    pub fn new(cells: Vec<String>) -> TraceRow {
        TraceRow {
            cells,
            ..TraceRow::default()
        }
    }

    /// A row about pixel `(x, y)`.
    pub fn at_pixel(cells: Vec<String>, x: i64, y: i64) -> TraceRow {
        TraceRow::new(cells).about(x, y, x, y)
    }

    /// This row, also about the pixels `x0..=x1` x `y0..=y1`.
    pub fn about(mut self, x0: i64, y0: i64, x1: i64, y1: i64) -> TraceRow {
        self.about.push([x0, y0, x1, y1]);
        self
    }

    /// A line of words between rows.
    pub fn note(text: String) -> TraceRow {
        TraceRow {
            cells: vec![text],
            note: true,
            ..TraceRow::default()
        }
    }

    /// Whether the row is about pixel `(x, y)`.
    pub fn is_about(&self, x: i64, y: i64) -> bool {
        self.about
            .iter()
            .any(|&[x0, y0, x1, y1]| (x0..=x1).contains(&x) && (y0..=y1).contains(&y))
    }
}

/// A trace: lines, a table, lines.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Trace {
    /// The lines before the table: what is traced, the set-up.
    pub header: Vec<String>,
    /// The table's columns (none: the rows are printed with their cells
    /// one space apart and no line of column names).
    pub columns: Vec<Column>,
    /// The table's rows, in the order of the walk.
    pub rows: Vec<TraceRow>,
    /// The lines after the table: the totals.
    pub footer: Vec<String>,
}

impl Trace {
    /// A trace of one header line and nothing else.
    pub fn saying(line: String) -> Trace {
        Trace {
            header: vec![line],
            ..Trace::default()
        }
    }

    /// The trace as text, each column at its width: what `rasterlab
    /// explain` prints.
    pub fn to_text(&self) -> String {
        let mut out = String::new();
        for line in &self.header {
            let _ = writeln!(out, "{line}");
        }
        if !self.columns.is_empty() {
            for (i, c) in self.columns.iter().enumerate() {
                c.write(&mut out, i == 0, &c.name);
            }
            out.push('\n');
        }
        for row in &self.rows {
            if row.note || self.columns.is_empty() {
                out.push_str(&row.cells.join(" "));
            } else {
                for (i, (c, cell)) in self.columns.iter().zip(&row.cells).enumerate() {
                    c.write(&mut out, i == 0, cell);
                }
            }
            out.push('\n');
        }
        for line in &self.footer {
            let _ = writeln!(out, "{line}");
        }
        out
    }
}
