//! What a benchmark section hands back — tables, tracked figures, targets, plots, notes — and how it is
//! written: a markdown report, one CSV per table.

use std::fmt::Write as _;

/// One table cell.
#[derive(Debug, Clone, PartialEq)]
pub enum Cell {
    /// Text as is.
    Text(String),
    /// A number with the significant digits to show in markdown (CSV keeps every digit). A non-finite
    /// number is written as an empty cell.
    Num(f64, usize),
    /// Nothing measured here.
    Empty,
}

impl Cell {
    /// A number with 3 significant digits.
    pub fn num(v: f64) -> Cell {
        Cell::Num(v, 3)
    }

    /// An optional number (empty when absent).
    pub fn opt(v: Option<f64>) -> Cell {
        v.map_or(Cell::Empty, Cell::num)
    }

    /// Text.
    pub fn text(s: impl Into<String>) -> Cell {
        Cell::Text(s.into())
    }

    /// An integer count.
    pub fn count(v: impl Into<u64>) -> Cell {
        Cell::Text(v.into().to_string())
    }

    fn markdown(&self) -> String {
        match self {
            Cell::Text(s) => s.replace('|', "\\|"),
            Cell::Num(v, digits) if v.is_finite() => significant(*v, *digits),
            Cell::Num(..) | Cell::Empty => String::new(),
        }
    }

    fn csv(&self) -> String {
        match self {
            Cell::Text(s) if s.contains([',', '"', '\n']) => format!("\"{}\"", s.replace('"', "\"\"")),
            Cell::Text(s) => s.clone(),
            Cell::Num(v, _) if v.is_finite() => format!("{v:e}"),
            Cell::Num(..) | Cell::Empty => String::new(),
        }
    }
}

/// `v` with `digits` significant digits: plain notation between 1e-3 and 1e6, else scientific.
pub fn significant(v: f64, digits: usize) -> String {
    if !v.is_finite() {
        return String::new();
    }
    if v == 0.0 {
        return "0".into();
    }
    let digits = digits.max(1);
    let exp = v.abs().log10().floor() as i32;
    if (-3..6).contains(&exp) {
        let decimals = (digits as i32 - 1 - exp).max(0) as usize;
        format!("{v:.decimals$}")
    } else {
        format!("{v:.*e}", digits - 1)
    }
}

/// A table for the report and its CSV file.
#[derive(Debug, Clone)]
pub struct Table {
    /// Heading in the report.
    pub title: String,
    /// CSV file name (under the output directory).
    pub csv: String,
    /// Column headers (with units).
    pub headers: Vec<String>,
    /// Rows of cells, one per header.
    pub rows: Vec<Vec<Cell>>,
}

impl Table {
    /// An empty table.
    pub fn new(title: &str, csv: &str, headers: &[&str]) -> Table {
        Table {
            title: title.into(),
            csv: csv.into(),
            headers: headers.iter().map(|h| h.to_string()).collect(),
            rows: Vec::new(),
        }
    }

    /// Adds a row (padded or cut to the header count).
    pub fn row(&mut self, mut cells: Vec<Cell>) {
        cells.resize(self.headers.len(), Cell::Empty);
        self.rows.push(cells);
    }

    /// Adds a row for a case that failed: `leading` cells, then empty ones, and "failed: …" in the last
    /// column (the status column of the tables that have one).
    pub fn failed_row(&mut self, mut leading: Vec<Cell>, error: impl std::fmt::Display) {
        leading.resize(self.headers.len().saturating_sub(1), Cell::Empty);
        leading.push(Cell::text(format!("failed: {error}")));
        self.rows.push(leading);
    }

    /// The table in markdown.
    pub fn markdown(&self) -> String {
        let mut s = format!("| {} |\n|{}\n", self.headers.join(" | "), "---|".repeat(self.headers.len()));
        for r in &self.rows {
            let cells: Vec<String> = r.iter().map(Cell::markdown).collect();
            let _ = writeln!(s, "| {} |", cells.join(" | "));
        }
        s
    }

    /// The table as CSV.
    pub fn csv_text(&self) -> String {
        let quote = |h: &String| Cell::Text(h.clone()).csv();
        let mut s = self.headers.iter().map(quote).collect::<Vec<_>>().join(",") + "\n";
        for r in &self.rows {
            s += &(r.iter().map(Cell::csv).collect::<Vec<_>>().join(",") + "\n");
        }
        s
    }
}

/// What kind of quantity a tracked figure is: decides which way is worse when runs are compared.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A time: larger is slower.
    Time,
    /// A throughput: smaller is slower.
    Rate,
    /// Bytes: larger is worse.
    Memory,
    /// An error or residual: shown, not flagged (rounding-level values move by large factors).
    Accuracy,
    /// A count, ratio or exponent: shown, not flagged.
    Other,
}

impl Kind {
    /// Name used in saved results.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Time => "time",
            Kind::Rate => "rate",
            Kind::Memory => "memory",
            Kind::Accuracy => "accuracy",
            Kind::Other => "other",
        }
    }

    /// Inverse of [`Kind::name`].
    pub fn from_name(s: &str) -> Option<Kind> {
        [Kind::Time, Kind::Rate, Kind::Memory, Kind::Accuracy, Kind::Other].into_iter().find(|k| k.name() == s)
    }
}

/// One tracked figure: a measured number with a stable key.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// Stable key, `section.case.quantity`.
    pub key: String,
    /// The value (finite).
    pub value: f64,
    /// Unit.
    pub unit: String,
    /// Kind.
    pub kind: Kind,
}

/// How a target is judged.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Judge {
    /// Measured at most the limit; a miss is told as a factor over it.
    AtMost,
    /// An exponent at most the limit; a miss is told as the difference.
    ExponentAtMost,
    /// Measured at least the limit (a speed-up: more is better); a miss is told as the fraction of the
    /// limit reached.
    AtLeast,
}

/// A target of the issue, measured.
#[derive(Debug, Clone)]
pub struct Target {
    /// What is asked.
    pub goal: String,
    /// The measured value, or why there is none.
    pub measured: Result<f64, String>,
    /// The limit.
    pub limit: f64,
    /// Unit of measured and limit.
    pub unit: String,
    /// How it is judged.
    pub judge: Judge,
    /// What exactly was measured.
    pub detail: String,
}

impl Target {
    /// "PASS", "MISS" or "FAILED".
    pub fn status(&self) -> &'static str {
        match (&self.measured, self.judge) {
            (Ok(v), Judge::AtLeast) if *v >= self.limit => "PASS",
            (Ok(v), Judge::AtMost | Judge::ExponentAtMost) if *v <= self.limit => "PASS",
            (Ok(_), _) => "MISS",
            (Err(_), _) => "FAILED",
        }
    }

    /// How far from the limit, in words.
    pub fn margin(&self) -> String {
        match (&self.measured, self.judge) {
            (Ok(v), Judge::AtMost) if *v <= self.limit => format!("{:.2}× the limit", v / self.limit),
            (Ok(v), Judge::AtMost) => {
                format!("{:.2}× the limit: over by {:.0}%", v / self.limit, (v / self.limit - 1.0) * 100.0)
            }
            (Ok(v), Judge::ExponentAtMost) if *v <= self.limit => format!("{:.2} below", self.limit - v),
            (Ok(v), Judge::ExponentAtMost) => format!("missed by {:.2} in the exponent", v - self.limit),
            (Ok(v), Judge::AtLeast) if *v >= self.limit => format!("{:.2}× the limit", v / self.limit),
            (Ok(v), Judge::AtLeast) => {
                format!("{:.2}× the limit: short by {:.0}%", v / self.limit, (1.0 - v / self.limit) * 100.0)
            }
            (Err(e), _) => e.clone(),
        }
    }

    /// The targets as a table.
    pub fn table(targets: &[Target]) -> Table {
        let mut t = Table::new(
            "Targets",
            "targets.csv",
            &["target", "measured", "limit", "unit", "status", "margin", "measured on"],
        );
        for g in targets {
            t.row(vec![
                Cell::text(&g.goal),
                g.measured.as_ref().map_or(Cell::Empty, |v| Cell::num(*v)),
                Cell::num(g.limit),
                Cell::text(&g.unit),
                Cell::text(g.status()),
                Cell::text(g.margin()),
                Cell::text(&g.detail),
            ]);
        }
        t
    }
}

/// Everything one section produced.
#[derive(Debug, Default)]
pub struct SectionOutput {
    /// Section heading.
    pub title: String,
    /// What it measures, for the report.
    pub intro: String,
    /// Tables.
    pub tables: Vec<Table>,
    /// Tracked figures.
    pub figures: Vec<Figure>,
    /// Targets it measured.
    pub targets: Vec<Target>,
    /// SVG plots: (file name, document, caption).
    pub plots: Vec<(String, String, String)>,
    /// Findings and caveats, one line each.
    pub notes: Vec<String>,
}

impl SectionOutput {
    /// Records a figure if it is finite (a failed measurement has no figure).
    pub fn figure(&mut self, key: &str, value: f64, unit: &str, kind: Kind) {
        if value.is_finite() {
            self.figures.push(Figure { key: key.into(), value, unit: unit.into(), kind });
        }
    }
}

/// A name for keys and files: lower case, words joined by `_`.
pub fn slug(s: &str) -> String {
    let mut out = String::new();
    for c in s.chars() {
        if c.is_ascii_alphanumeric() {
            out.push(c.to_ascii_lowercase());
        } else if !out.ends_with('_') && !out.is_empty() {
            out.push('_');
        }
    }
    out.trim_end_matches('_').to_string()
}

#[cfg(test)]
mod tests {

    #[test]
    fn a_failed_row_keeps_its_leading_cells_and_names_the_failure_last() {
        let mut t = Table::new("t", "t.csv", &["threads", "time", "rate", "status"]);
        t.failed_row(vec![Cell::count(2u64)], "pool could not start");
        let csv = t.csv_text();
        let row = csv.lines().nth(1).unwrap();
        assert!(row.starts_with('2') && row.ends_with(",failed: pool could not start"), "{row}");
        assert_eq!(t.rows[0].len(), 4);
    }

    use super::*;

    #[test]
    fn no_nan_reaches_a_table() {
        let mut t = Table::new("t", "t.csv", &["a", "b", "c"]);
        t.row(vec![Cell::num(f64::NAN), Cell::num(f64::INFINITY), Cell::text("x, \"y\"")]);
        t.row(vec![Cell::num(1.5)]);
        let (md, csv) = (t.markdown(), t.csv_text());
        assert!(!md.to_lowercase().contains("nan") && !md.contains("inf"), "{md}");
        assert!(!csv.to_lowercase().contains("nan") && !csv.contains("inf"), "{csv}");
        assert!(csv.contains("\"x, \"\"y\"\"\""), "{csv}");
        assert_eq!(csv.lines().nth(2), Some("1.5e0,,"));
    }

    #[test]
    fn significant_digits() {
        assert_eq!(significant(1234.5678, 3), "1235");
        assert_eq!(significant(0.012345, 3), "0.0123");
        assert_eq!(significant(2.5e-9, 2), "2.5e-9");
        assert_eq!(significant(3.0e7, 3), "3.00e7");
        assert_eq!(significant(0.0, 3), "0");
    }

    #[test]
    fn targets_say_pass_miss_and_by_how_much() {
        let t = |v: Result<f64, String>, judge| Target {
            goal: "g".into(),
            measured: v,
            limit: 2.0,
            unit: "ms".into(),
            judge,
            detail: String::new(),
        };
        assert_eq!(t(Ok(1.0), Judge::AtMost).status(), "PASS");
        let miss = t(Ok(5.0), Judge::AtMost);
        assert_eq!(miss.status(), "MISS");
        assert!(miss.margin().contains("2.50×"), "{}", miss.margin());
        let exp = t(Ok(2.3), Judge::ExponentAtMost);
        assert!(exp.margin().contains("0.30"), "{}", exp.margin());
        assert_eq!(t(Err("no run".into()), Judge::AtMost).status(), "FAILED");
    }

    #[test]
    fn an_at_least_target_passes_above_its_limit_and_says_how_far_short_below() {
        let t = |v: f64| Target {
            goal: "g".into(),
            measured: Ok(v),
            limit: 30.0,
            unit: "×".into(),
            judge: Judge::AtLeast,
            detail: String::new(),
        };
        assert_eq!(t(30.0).status(), "PASS");
        assert_eq!(t(45.0).status(), "PASS");
        assert!(t(45.0).margin().contains("1.50×"), "{}", t(45.0).margin());
        let miss = t(7.5);
        assert_eq!(miss.status(), "MISS");
        assert!(miss.margin().contains("0.25×") && miss.margin().contains("short by 75%"), "{}", miss.margin());
        // The same figure under an at-most target is judged the other way.
        let at_most = Target { judge: Judge::AtMost, ..t(7.5) };
        assert_eq!(at_most.status(), "PASS");
    }

    #[test]
    fn slugs_are_stable_keys() {
        assert_eq!(slug("MacPherson, vertical force (N)"), "macpherson_vertical_force_n");
        assert_eq!(Kind::from_name(Kind::Rate.name()), Some(Kind::Rate));
    }
}
