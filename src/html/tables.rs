//! Tables in a page: shown open, every row, or folded and cut at [`TABLE_ROW_LIMIT`] rows; and the cells
//! and parameters as numbers a person reads.

use crate::markup::text;
use crate::suspensions::kc::{significant, Cell, Table};
use std::fmt::Write;

/// Rows of an analysis table shown in the page; a longer table is cut there with a note (the CSV beside
/// the report holds every row), so a fine sweep does not make a file too large to mail.
pub const TABLE_ROW_LIMIT: usize = 400;

/// A table shown open (not folded), every row.
pub(super) fn write_open_table(out: &mut String, table: &Table) -> std::fmt::Result {
    writeln!(out, "<div class=\"scroll\"><table class=\"numbers\">")?;
    write!(out, "<thead><tr>")?;
    for c in &table.columns {
        write!(out, "<th>{}</th>", text(c))?;
    }
    writeln!(out, "</tr></thead><tbody>")?;
    for row in &table.rows {
        write!(out, "<tr>")?;
        for c in row {
            write!(out, "<td>{}</td>", cell(c, 6))?;
        }
        writeln!(out, "</tr>")?;
    }
    writeln!(out, "</tbody></table></div>")
}

/// `table` folded under a summary naming `what` it holds and its CSV file, cut at [`TABLE_ROW_LIMIT`] rows.
pub(super) fn write_table(out: &mut String, table: &Table, what: &str) -> std::fmt::Result {
    let shown = table.rows.len().min(TABLE_ROW_LIMIT);
    writeln!(out, "<details>")?;
    writeln!(
        out,
        "<summary>{what}: <code>{}.csv</code>, {} rows × {} columns</summary>",
        text(&table.name),
        table.rows.len(),
        table.columns.len()
    )?;
    if shown < table.rows.len() {
        writeln!(
            out,
            "<p class=\"note\">the first {shown} of {} rows; every row is in {}.csv</p>",
            table.rows.len(),
            text(&table.name)
        )?;
    }
    writeln!(out, "<div class=\"scroll\"><table class=\"numbers\">")?;
    write!(out, "<thead><tr>")?;
    for c in &table.columns {
        write!(out, "<th>{}</th>", text(c))?;
    }
    writeln!(out, "</tr></thead>")?;
    writeln!(out, "<tbody>")?;
    for row in &table.rows[..shown] {
        write!(out, "<tr>")?;
        for c in row {
            write!(out, "<td>{}</td>", cell(c, 6))?;
        }
        writeln!(out, "</tr>")?;
    }
    writeln!(out, "</tbody></table></div>")?;
    writeln!(out, "</details>")
}

/// A table cell as text: numbers to `digits` significant digits, names escaped, nothing for an empty cell.
pub(super) fn cell(c: &Cell, digits: usize) -> String {
    match c {
        Cell::Number(v) if v.is_finite() => significant(*v, digits),
        Cell::Number(_) | Cell::Empty => String::new(),
        Cell::Text(t) => text(t),
    }
}

/// `v` to six significant digits without trailing zeros (`-0.08`, `3800`, `2071.43`): a parameter as
/// a person would type it.
pub(super) fn plain(v: f64) -> String {
    let s = significant(v, 6);
    if s.contains('.') && !s.contains('e') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::suspensions::kc::fixed;

    #[test]
    fn numbers_never_print_non_finite_or_negative_zero() {
        assert_eq!(fixed(f64::NAN, 2), "");
        assert_eq!(fixed(f64::INFINITY, 2), "");
        assert_eq!(fixed(-0.001, 2), "0.00");
        assert_eq!(fixed(-1.234, 2), "-1.23");
        assert_eq!(cell(&Cell::Number(f64::NAN), 6), "");
        assert_eq!(significant(0.000123456, 2), "0.00012");
        assert_eq!(significant(1.2e-9, 2), "1.2e-9");
        assert_eq!(plain(-0.08), "-0.08");
        assert_eq!(plain(3800.0), "3800");
        assert_eq!(plain(2071.431612), "2071.43");
        assert_eq!(plain(0.0), "0");
        assert_eq!(plain(f64::NAN), "");
    }
}
