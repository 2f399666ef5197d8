//! Plain-text tables whose columns line up whatever their contents: each
//! column is as wide as its widest cell (header included), names aligned
//! left, figures right.
//!
//! ```
//! use rasterlab::measure::Table;
//! let mut table = Table::new(&["workload", "ms"]);
//! table.row(vec!["dragon_vrip_res4".into(), "12.5".into()]);
//! table.row(vec!["fill-1".into(), "1.25".into()]);
//! assert_eq!(
//!     table.to_string(),
//!     "workload            ms\n\
//!      dragon_vrip_res4  12.5\n\
//!      fill-1            1.25\n"
//! );
//! ```

use std::fmt;

/// A table: a header and rows of cells.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Table {
    text_columns: usize,
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl Table {
    /// A table with these column names; the first column is aligned left,
    /// the others right.
    pub fn new(header: &[&str]) -> Table {
        Table::with_text_columns(1, header)
    }

    /// A table whose first `text` columns are aligned left, the others
    /// right.
    pub fn with_text_columns(text: usize, header: &[&str]) -> Table {
        Table {
            text_columns: text,
            header: header.iter().map(|h| h.to_string()).collect(),
            rows: Vec::new(),
        }
    }

    /// Adds a row (missing cells are blank; a row may have fewer cells
    /// when its last ones say why it has no figures).
    pub fn row(&mut self, cells: Vec<String>) {
        self.rows.push(cells);
    }
}

impl fmt::Display for Table {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let columns = self.header.len();
        let mut widths: Vec<usize> = self.header.iter().map(|h| h.chars().count()).collect();
        for row in &self.rows {
            // A row with fewer cells than columns ends in free text (a
            // skipped row's reason), which does not widen the columns.
            if row.len() == columns {
                for (w, cell) in widths.iter_mut().zip(row) {
                    *w = (*w).max(cell.chars().count());
                }
            } else if let Some(first) = row.first() {
                widths[0] = widths[0].max(first.chars().count());
            }
        }
        for row in std::iter::once(&self.header).chain(&self.rows) {
            let mut line = String::new();
            for (i, cell) in row.iter().enumerate() {
                let width = if row.len() == columns || i == 0 {
                    widths[i.min(columns - 1)]
                } else {
                    0
                };
                if i > 0 {
                    line.push_str("  ");
                }
                if i < self.text_columns || row.len() != columns {
                    line += &format!("{cell:<width$}");
                } else {
                    line += &format!("{cell:>width$}");
                }
            }
            writeln!(f, "{}", line.trim_end())?;
        }
        Ok(())
    }
}

/// `x` with three significant digits (at least the units), so small and
/// large figures alike keep their information: `0.00123`, `1.23`, `123`,
/// `1235`.
pub fn significant(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let mut digits = x.abs().log10().floor() as i32;
    // 99.96 rounds to 100.0 at one decimal: one digit more before the point.
    let rounded = format!("{:.*}", (2 - digits).max(0) as usize, x.abs());
    if rounded
        .parse::<f64>()
        .is_ok_and(|r| r >= 10f64.powi(digits + 1))
    {
        digits += 1;
    }
    let decimals = (2 - digits).max(0) as usize;
    format!("{x:.decimals$}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_line_up_and_a_short_row_keeps_its_reason_whole() {
        let mut table = Table::new(&["workload", "back-end", "ms"]);
        table.row(vec![
            "dragon_vrip_res4".into(),
            "scanline".into(),
            "3.5".into(),
        ]);
        table.row(vec!["x".into(), "skipped: not found".into()]);
        let text = table.to_string();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], "workload          back-end   ms");
        assert_eq!(lines[1], "dragon_vrip_res4  scanline  3.5");
        assert_eq!(lines[2], "x                 skipped: not found");
    }
}
