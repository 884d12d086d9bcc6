//! Designs side by side: the K&C suites of several models (and measured K&C files standing in for a
//! model) overlaid curve by curve, their figures tabulated with the differences to the first and each
//! one's error estimate. What `elastokin compare` writes and `elastokin.compare` returns.
//!
//! Every curve of every analysis the models share is overlaid: each chart of an analysis is split into one
//! chart per curve (toe, camber, …), in which each model is one curve in its own colour, named by the
//! model's name. A measured file (a load-parameter column and any of an analysis's table columns, as
//! `docs/kc-rig-data.md` says) adds, per column it has, a chart of that column against the load parameter
//! with each model's rows and its points.

use crate::design::targets::Measured;
use crate::file::SuspensionFile;
use crate::kc::report::slug;
use crate::kc::{Analysis, AnalysisReport, Cell, Chart, Figure, KcReport, Series, Table, Units, YAxis};

/// One design in a comparison: a model's K&C suite, or a measured file of one analysis.
#[derive(Debug, Clone)]
pub enum Design {
    /// A model and its suite.
    Model {
        /// Its name in legends and columns.
        name: String,
        /// Whether it is a solid axle (its corners share parts), for the refusal of a mixed comparison.
        solid_axle: bool,
        /// Its suite.
        report: Box<KcReport>,
    },
    /// A measured K&C file.
    Measured {
        /// Its name in legends (the file's).
        name: String,
        /// The file read.
        measured: Measured,
    },
}

impl Design {
    /// A model's suite as a design, named by the model.
    pub fn model(file: &SuspensionFile, report: KcReport) -> Design {
        let solid_axle = file.suspension.expand().axle.is_some();
        Design::Model { name: file.name.clone(), solid_axle, report: Box::new(report) }
    }

    /// Names it `name` (a design whose model's name another design shares, told apart by its file).
    pub fn rename(&mut self, to: String) {
        match self {
            Design::Model { name, .. } | Design::Measured { name, .. } => *name = to,
        }
    }

    /// Its name.
    pub fn name(&self) -> &str {
        match self {
            Design::Model { name, .. } | Design::Measured { name, .. } => name,
        }
    }
}

/// Designs compared: the figures side by side, the overlaid charts.
#[derive(Debug, Clone, PartialEq)]
pub struct Comparison {
    /// The designs' names, made distinct (a repeated name gets ` (2)`, …), in the order given.
    pub names: Vec<String>,
    /// Which of the designs are models (indices into `names`), in order: the figures' columns.
    pub models: Vec<usize>,
    /// Per analysis every model ran and figure of it, each model's, in SI ([`Comparison::table`] writes
    /// them as `compare.csv`).
    pub figures: Vec<ComparedFigure>,
    /// The units the first model's report is written in, which the table and page write every model's in.
    pub units: Units,
    /// The overlaid charts.
    pub charts: Vec<Chart>,
}

/// One figure of an analysis every model compared ran: each model's own, in SI with its error estimate, in
/// the models' order; `None` where a model reports no such figure.
#[derive(Debug, Clone, PartialEq)]
pub struct ComparedFigure {
    /// The analysis.
    pub analysis: Analysis,
    /// Each model's figure; the first model's is always there (it names the row).
    pub figures: Vec<Option<Figure>>,
}

impl ComparedFigure {
    /// The first model's figure, which names the row: its key, words, unit and decimals.
    pub fn first(&self) -> &Figure {
        self.figures[0].as_ref().expect("a compared figure is one the first model reports")
    }

    /// Model `k`'s value less the first model's, as a figure of the first's kind (SI; no estimate).
    pub fn difference(&self, k: usize) -> Option<Figure> {
        let (first, other) = (self.first().value?, self.figures[k].as_ref()?.value?);
        Some(Figure { value: Some(other - first), error: None, ..self.first().clone() })
    }
}

impl Comparison {
    /// `compare.csv`: every figure compared, each model's value and error estimate, and each later model's
    /// difference to the first (empty where either has no value), written in the first model's units.
    pub fn table(&self) -> Table {
        let mut columns: Vec<String> = ["analysis", "figure", "unit"].map(String::from).to_vec();
        for &k in &self.models {
            columns.push(self.names[k].clone());
            columns.push(format!("{} error", self.names[k]));
        }
        let first = &self.names[self.models[0]];
        for &k in &self.models[1..] {
            columns.push(format!("{} − {first}", self.names[k]));
        }
        let rows = self
            .figures
            .iter()
            .map(|c| {
                let mut row = vec![
                    Cell::Text(c.analysis.name().into()),
                    Cell::Text(c.first().key.clone()),
                    Cell::Text(c.first().written(self.units).unit.into()),
                ];
                for f in &c.figures {
                    let w = f.as_ref().map(|f| f.written(self.units));
                    row.push(Cell::from(w.as_ref().and_then(|w| w.value)));
                    row.push(Cell::from(w.as_ref().and_then(|w| w.error)));
                }
                for k in 1..c.figures.len() {
                    let difference = c.difference(k);
                    row.push(Cell::from(difference.as_ref().and_then(|d| d.written(self.units).value)));
                }
                row
            })
            .collect();
        Table { name: "compare".into(), columns, rows }
    }

    /// The models among `designs` (the designs compared, in their order), each by its name here, with its
    /// suite: what the pages draw the geometry and the failures of.
    pub fn models<'a>(&'a self, designs: &'a [Design]) -> Vec<(&'a str, &'a KcReport)> {
        designs
            .iter()
            .zip(&self.names)
            .filter_map(|(d, name)| match d {
                Design::Model { report, .. } => Some((name.as_str(), &**report)),
                Design::Measured { .. } => None,
            })
            .collect()
    }
}

/// Why designs cannot be compared ([`compare`]), naming the design.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CompareError {
    /// Fewer than two designs.
    #[error("compare needs two designs at least: give two or more model files (or a model and a measured K&C file)")]
    TooFew,
    /// Measured files alone.
    #[error("compare needs a model among the designs: measured files are compared with a model's curves")]
    NoModel,
    /// A solid axle beside an independent corner.
    #[error(
        "'{first}' is {} and '{other}' {}: their K&C curves do not mean the same motions (a solid axle's wheels \
         move together); compare models of one kind",
        kind(*first_solid),
        kind(!*first_solid)
    )]
    MixedKinds {
        /// The first model's name.
        first: String,
        /// Whether the first model is a solid axle.
        first_solid: bool,
        /// The first model of the other kind.
        other: String,
    },
    /// Models with no analysis in common.
    #[error("'{first}' and the other models ran no analysis in common: there is nothing to overlay")]
    NothingInCommon {
        /// The first model's name.
        first: String,
    },
    /// A measured file that names no analysis.
    #[error(
        "'{name}' does not say which analysis it measured: add a comment line `# analysis: NAME` (as \
         docs/kc-rig-data.md shows)"
    )]
    NoAnalysisNamed {
        /// The measured file's name.
        name: String,
    },
    /// A measured file of an analysis no model ran.
    #[error("'{name}' measured {analysis}, which no model ran: run it on the models or leave the file out")]
    AnalysisNotRun {
        /// The measured file's name.
        name: String,
        /// The analysis it names.
        analysis: String,
    },
    /// A measured file whose first column is not the analysis's load parameter.
    #[error(
        "'{name}': its first column is '{first}', but {analysis}'s load parameter is '{parameter}': give the \
         load parameter first, in the table's units"
    )]
    FirstColumn {
        /// The measured file's name.
        name: String,
        /// Its first column.
        first: String,
        /// The analysis it names.
        analysis: String,
        /// That analysis's load parameter column.
        parameter: String,
    },
    /// A measured column the analysis's table lacks.
    #[error(
        "'{name}': {analysis}'s table has no column '{column}' (it has {}): name the file's columns as the table \
         does, or leave that column out",
        columns.join(", ")
    )]
    UnknownColumn {
        /// The measured file's name.
        name: String,
        /// The analysis it names.
        analysis: String,
        /// The column the table lacks.
        column: String,
        /// The table's columns after its load parameter.
        columns: Vec<String>,
    },
}

/// A model's kind in words.
fn kind(solid: bool) -> &'static str {
    if solid {
        "a solid axle"
    } else {
        "an independent corner"
    }
}

/// Compares `designs` (at least two, at least one a model). Refused, by name: fewer than two, no model, a
/// solid axle with an independent corner, models with no analysis in common, a measured file naming no
/// analysis a model ran, or with a load parameter or a column that analysis's table lacks.
pub fn compare(designs: &[Design]) -> Result<Comparison, CompareError> {
    if designs.len() < 2 {
        return Err(CompareError::TooFew);
    }
    let names = distinct_names(designs);
    let models: Vec<(usize, &KcReport, bool)> = designs
        .iter()
        .enumerate()
        .filter_map(|(k, d)| match d {
            Design::Model { report, solid_axle, .. } => Some((k, &**report, *solid_axle)),
            Design::Measured { .. } => None,
        })
        .collect();
    let Some(&(first, _, first_solid)) = models.first() else {
        return Err(CompareError::NoModel);
    };
    if let Some(&(other, _, _)) = models.iter().find(|m| m.2 != first_solid) {
        return Err(CompareError::MixedKinds { first: names[first].clone(), first_solid, other: names[other].clone() });
    }
    let analyses: Vec<Analysis> = models[0]
        .1
        .analyses
        .iter()
        .map(|a| a.analysis)
        .filter(|&a| models.iter().all(|(_, r, _)| r.analyses.iter().any(|b| b.analysis == a)))
        .collect();
    if analyses.is_empty() {
        return Err(CompareError::NothingInCommon { first: names[first].clone() });
    }
    let of = |r: &KcReport, a: Analysis| r.analyses.iter().find(|b| b.analysis == a).cloned();
    let mut charts = Vec::new();
    for &analysis in &analyses {
        let reports: Vec<(usize, AnalysisReport)> =
            models.iter().filter_map(|(k, r, _)| Some((*k, of(r, analysis)?))).collect();
        charts.extend(overlaid(&reports, &names));
    }
    for (k, d) in designs.iter().enumerate() {
        if let Design::Measured { measured, .. } = d {
            charts.extend(measured_charts(k, measured, &models, &names)?);
        }
    }
    let figures = compared_figures(&analyses, &models);
    let units = models[0].1.settings.units;
    Ok(Comparison { names, models: models.iter().map(|m| m.0).collect(), figures, units, charts })
}

/// The designs' names, a repeated one numbered.
fn distinct_names(designs: &[Design]) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for d in designs {
        let base = d.name().to_string();
        let mut name = base.clone();
        let mut n = 2;
        while names.contains(&name) {
            name = format!("{base} ({n})");
            n += 1;
        }
        names.push(name);
    }
    names
}

/// Each curve of each chart of one analysis, as a chart of its own with one curve per model.
fn overlaid(reports: &[(usize, AnalysisReport)], names: &[String]) -> Vec<Chart> {
    let Some((_, first)) = reports.first() else { return Vec::new() };
    let mut out = Vec::new();
    for chart in &first.charts {
        let axes = std::iter::once((&chart.left, false)).chain(chart.right.as_ref().map(|r| (r, true)));
        for (axis, right) in axes {
            for (s, series) in axis.series.iter().enumerate() {
                let curves = reports
                    .iter()
                    .filter_map(|(k, r)| {
                        let theirs = r.charts.iter().find(|c| c.name == chart.name)?;
                        let axis = if right { theirs.right.as_ref()? } else { &theirs.left };
                        let curve = axis.series.iter().find(|c| c.name == series.name).or(axis.series.get(s))?;
                        Some(Series { name: names[*k].clone(), points: curve.points.clone() })
                    })
                    .collect();
                out.push(Chart {
                    name: format!("compare_{}_{}", chart.name, slug(&series.name)),
                    title: format!("{}: {}", series.name, chart.title),
                    subtitle: String::new(),
                    x_label: chart.x_label.clone(),
                    x_scale: chart.x_scale,
                    left: YAxis { label: axis.label.clone(), scale: axis.scale, series: curves },
                    right: None,
                    design_x: chart.design_x,
                });
            }
        }
    }
    out
}

/// The charts of a measured file: per column (each one of its analysis's table), that column against
/// the load parameter, each model's rows and the measured points.
fn measured_charts(
    k: usize,
    measured: &Measured,
    models: &[(usize, &KcReport, bool)],
    names: &[String],
) -> Result<Vec<Chart>, CompareError> {
    let name = &names[k];
    let Some(analysis_name) = &measured.analysis else {
        return Err(CompareError::NoAnalysisNamed { name: name.clone() });
    };
    let tables: Vec<(usize, &Table)> = models
        .iter()
        .filter_map(|(j, r, _)| {
            Some((*j, &r.analyses.iter().find(|a| a.analysis.name() == analysis_name.as_str())?.table))
        })
        .collect();
    let Some(&(_, table)) = tables.first() else {
        return Err(CompareError::AnalysisNotRun { name: name.clone(), analysis: analysis_name.clone() });
    };
    let parameter = &table.columns[0];
    if measured.columns.first() != Some(parameter) {
        return Err(CompareError::FirstColumn {
            name: name.clone(),
            first: measured.columns.first().cloned().unwrap_or_default(),
            analysis: analysis_name.clone(),
            parameter: parameter.clone(),
        });
    }
    // Every measured column is drawn: one the table lacks is refused, not left out unseen.
    if let Some(unknown) = measured.columns[1..].iter().find(|c| !table.columns.contains(c)) {
        return Err(CompareError::UnknownColumn {
            name: name.clone(),
            analysis: analysis_name.clone(),
            column: unknown.clone(),
            columns: table.columns[1..].to_vec(),
        });
    }
    let mut out = Vec::new();
    for (m, column) in measured.columns.iter().enumerate().skip(1) {
        let mut series: Vec<Series> = tables
            .iter()
            .map(|(j, t)| {
                let c = t.columns.iter().position(|x| x == column).unwrap_or(0);
                let points = t.rows.iter().filter_map(|r| Some((r[0].number()?, r[c].number()?))).collect();
                Series { name: names[*j].clone(), points }
            })
            .collect();
        series.push(Series { name: name.clone(), points: measured.rows.iter().map(|r| (r[0], r[m])).collect() });
        out.push(Chart {
            name: format!("compare_measured_{}_{}", k + 1, slug(column)),
            title: format!("{column} in {analysis_name}: the models and {name}"),
            subtitle: String::new(),
            x_label: parameter.clone(),
            x_scale: Default::default(),
            left: YAxis { label: column.clone(), scale: Default::default(), series },
            right: None,
            design_x: None,
        });
    }
    Ok(out)
}

/// Every figure of the `analyses` compared, each of the `models`' own (by the first model's figures' keys).
fn compared_figures(analyses: &[Analysis], models: &[(usize, &KcReport, bool)]) -> Vec<ComparedFigure> {
    let mut out = Vec::new();
    for &analysis in analyses {
        let reports: Vec<Option<&AnalysisReport>> =
            models.iter().map(|(_, r, _)| r.analyses.iter().find(|a| a.analysis == analysis)).collect();
        let Some(Some(base)) = reports.first() else { continue };
        for figure in &base.figures {
            let figures = reports.iter().map(|r| r.and_then(|r| r.figure(&figure.key)).cloned()).collect();
            out.push(ComparedFigure { analysis, figures });
        }
    }
    out
}
