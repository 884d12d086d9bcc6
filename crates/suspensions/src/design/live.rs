//! A design edited live: the model file as read, the numbers moved from it (each by its JSON pointer, in
//! the file's SI units), the chosen analyses run on every design made, undo and redo, and the file's text
//! with the moved numbers rewritten where they stand. `elastokin live` serves it over HTTP; everything
//! here is testable without a socket.
//!
//! A design is made by an edit only when its analyses solve: an edit whose model does not read or build,
//! or on which an analysis fails that the current design ran, is refused with the reason and the current
//! design stays. Every design made, undone or redone counts one more version, so that every view of the
//! design can tell that it changed.
//!
//! An edit answers first and estimates after: its analyses are walked without the error estimates (one
//! factorization less per row, and the same figures and curves to the bit), and
//! [`LiveDesign::estimate`] walks them again with them once the user rests on the design, so that a run of
//! moves is not slowed by estimates of designs passed through.

use super::judge::judge;
use super::parameter::{hardpoint_pointers, number_at, rate_pointers, ParameterError, Parameters};
use super::sensitivity::{suite_sensitivity, Rate};
use super::targets::{Aim, Targets};
use crate::document::DocumentError;
use crate::file::numbers::{with_numbers, NumberEditError};
use crate::file::SuspensionFile;
use crate::kc::{self, Analysis, Chart, Failed, Figure, KcReport, Settings, Skipped, Warning};
use crate::study::batch::{base_document, BaseDocumentError};
use serde::Serialize;
use serde_json::Value;
use std::sync::Arc;

/// A design and the designs it was made from.
#[derive(Debug)]
pub struct LiveDesign {
    /// The model file's text as read: what a save rewrites.
    text: String,
    /// Its document: what an edit moves numbers of.
    base: Value,
    /// The analyses run (every one the suite runs on the model when empty).
    which: Vec<Analysis>,
    settings: Settings,
    /// Every design made, in order; `at` is the current one, those after it are undone ones to redo.
    history: Vec<Design>,
    at: usize,
    version: u64,
    /// What every design is judged against, when given.
    targets: Option<Targets>,
}

/// One design: the numbers moved from the file as read, and its analyses' report.
#[derive(Debug, Clone)]
pub struct Design {
    /// Each moved number's pointer and value (SI, as the file stores it), in the order first moved; a
    /// number moved back to its value in the file is no longer listed.
    pub moved: Vec<(String, f64)>,
    /// The analyses run on it, with the settings they were walked with (`report.settings`).
    pub report: KcReport,
}

impl LiveDesign {
    /// The design of the model file `text` (named `origin` in messages), its analyses `which` (the suite
    /// when empty) walked with `settings`. A file that does not read or build is refused; an analysis that
    /// fails on it is reported as failed in its report and does not stop the design from being edited.
    pub fn open(text: &str, origin: &str, which: &[Analysis], settings: Settings) -> Result<LiveDesign, LiveError> {
        let base = base_document(text, origin).map_err(LiveError::Document)?;
        let (file, _) = crate::document::parse_model(text, origin).map_err(|e| LiveError::Model(Arc::new(e)))?;
        let report = kc::run_suite_on_threads(&file, which, &settings);
        Ok(LiveDesign {
            text: text.to_string(),
            base,
            which: which.to_vec(),
            settings,
            history: vec![Design { moved: Vec::new(), report }],
            at: 0,
            version: 1,
            targets: None,
        })
    }

    /// The same design, each of its designs judged against `targets` (a TARGETS file read against the
    /// model's document) in its state: each figure and curve target and each packaging constraint, met or
    /// not, as `run --targets` judges them.
    pub fn judged_against(mut self, targets: Targets) -> LiveDesign {
        self.targets = Some(targets);
        self
    }

    /// The current design.
    pub fn current(&self) -> &Design {
        &self.history[self.at]
    }

    /// How many times the design changed since it was opened, plus one.
    pub fn version(&self) -> u64 {
        self.version
    }

    /// The number at `pointer` set to `value` (SI, as the model file stores it): a new design when its
    /// model reads and builds and no analysis fails on it that the current design ran; the designs undone
    /// before it can no longer be redone. Refused with the reason otherwise, the current design kept.
    pub fn edit(&mut self, pointer: &str, value: f64) -> Result<&Design, LiveError> {
        self.edit_all(&[(pointer.to_string(), value)])
    }

    /// Each number of `edits` (pointer, value) set at once, as one design: as [`LiveDesign::edit`] sets one.
    fn edit_all(&mut self, edits: &[(String, f64)]) -> Result<&Design, LiveError> {
        if let Some((pointer, _)) = edits.iter().find(|(_, v)| !v.is_finite()) {
            return Err(LiveError::NotFinite { pointer: pointer.clone() });
        }
        let document = self.document()?;
        let (pointers, values): (Vec<String>, Vec<f64>) = edits.iter().cloned().unzip();
        // Refused here: a pointer that names anything but a number, or a count (a whole number of things).
        let parameters = Parameters::new(&document, &pointers).map_err(LiveError::Parameter)?;
        let file = parameters.at(&values).and_then(|p| p.file()).map_err(LiveError::Parameter)?;
        let quick = Settings { error_estimate: false, ..self.settings };
        let report = kc::run_suite_on_threads(&file, &self.which, &quick);
        let ran = &self.current().report.analyses;
        let newly_failed: Vec<Failed> =
            report.failed.iter().filter(|f| ran.iter().any(|a| a.analysis == f.analysis)).cloned().collect();
        if !newly_failed.is_empty() {
            let (pointer, value) = edits[0].clone();
            return Err(LiveError::Solve { pointer, value, failed: newly_failed });
        }
        let mut moved = self.current().moved.clone();
        for (pointer, value) in edits {
            let in_file = number_at(&self.base, pointer).ok();
            match moved.iter().position(|(p, _)| p == pointer) {
                _ if in_file.map(f64::to_bits) == Some(value.to_bits()) => moved.retain(|(p, _)| p != pointer),
                Some(k) => moved[k].1 = *value,
                None => moved.push((pointer.clone(), *value)),
            }
        }
        self.history.truncate(self.at + 1);
        self.history.push(Design { moved, report });
        self.at += 1;
        self.version += 1;
        Ok(self.current())
    }

    /// The free numbers of the TARGETS file tuned to its targets from the current design (as `elastokin
    /// tune` tunes the current design's file), set as one new design; how the tune ended, in words. Refused
    /// without targets, without free numbers, or with a free number the edits have moved outside its bounds.
    pub fn tune(&mut self) -> Result<String, LiveError> {
        let targets = self.targets.as_ref().ok_or(LiveError::NoTargets)?;
        if targets.free.is_empty() {
            return Err(LiveError::NothingFree);
        }
        let document = self.document()?;
        let pointers: Vec<String> = targets.free.iter().map(|f| f.pointer.clone()).collect();
        let parameters = Parameters::new(&document, &pointers).map_err(LiveError::Parameter)?;
        for (f, &x) in targets.free.iter().zip(&parameters.values) {
            if !(f.min..=f.max).contains(&x) {
                return Err(LiveError::OutsideBounds { pointer: f.pointer.clone(), value: x, min: f.min, max: f.max });
            }
        }
        let tuned = super::tune::tune(&parameters, targets, |_| {}).map_err(|e| LiveError::Tune(e.to_string()))?;
        let met = tuned.verdicts.iter().filter(|v| v.met).count();
        let said = format!("{met} of {} targets met; {}", tuned.verdicts.len(), tuned.stopped);
        let edits: Vec<(String, f64)> = pointers.into_iter().zip(tuned.end.x.iter().copied()).collect();
        self.edit_all(&edits)?;
        Ok(said)
    }

    /// Whether the current design carries the error estimates the settings ask for: its report was walked
    /// with them, or none are asked.
    pub fn estimated(&self) -> bool {
        self.current().report.settings.error_estimate || !self.settings.error_estimate
    }

    /// The current design with the error estimates its settings ask for: its analyses walked again with
    /// them, once, when an edit made it without ([`LiveDesign::estimated`]). The figures and curves are
    /// those it had, to the bit; the version stays, as the design does.
    pub fn estimate(&mut self) -> Result<&Design, LiveError> {
        if !self.estimated() {
            let file = self.file()?;
            self.history[self.at].report = kc::run_suite_on_threads(&file, &self.which, &self.settings);
        }
        Ok(self.current())
    }

    /// Back to the design before the current one.
    pub fn undo(&mut self) -> Result<&Design, LiveError> {
        if self.at == 0 {
            return Err(LiveError::NothingToUndo);
        }
        self.at -= 1;
        self.version += 1;
        Ok(self.current())
    }

    /// On to the design last undone.
    pub fn redo(&mut self) -> Result<&Design, LiveError> {
        if self.at + 1 == self.history.len() {
            return Err(LiveError::NothingToRedo);
        }
        self.at += 1;
        self.version += 1;
        Ok(self.current())
    }

    /// The model file's text of the current design: the file as read with each moved number rewritten
    /// where it stands, every other byte as it was.
    pub fn text(&self) -> Result<String, LiveError> {
        with_numbers(&self.text, &self.current().moved).map_err(LiveError::Text)
    }

    /// The current design's document: the file's with the moved numbers set.
    pub fn document(&self) -> Result<Value, LiveError> {
        let mut document = self.base.clone();
        for (pointer, value) in &self.current().moved {
            super::parameter::set(&mut document, pointer, *value).map_err(LiveError::Parameter)?;
        }
        Ok(document)
    }

    /// The current design as a view of it shows it: its version, what was moved, its figures in SI with
    /// what they are written in, its charts, its hardpoints.
    pub fn state(&self) -> Result<State<'_>, LiveError> {
        let design = self.current();
        let document = self.document()?;
        let report = &design.report;
        let analyses = report
            .analyses
            .iter()
            .map(|a| AnalysisState {
                name: a.analysis.name(),
                parameter: &a.parameter,
                description: &a.description,
                figures: a.figures.iter().map(|f| FigureState::of(f, a.units)).collect(),
                charts: &a.charts,
            })
            .collect();
        let numbers = |pointers: Vec<String>| -> Vec<Number> {
            pointers
                .into_iter()
                .filter_map(|pointer| number_at(&document, &pointer).ok().map(|value| Number { pointer, value }))
                .collect()
        };
        let (hardpoints, rates) = (numbers(hardpoint_pointers(&document)), numbers(rate_pointers(&document)));
        // Every moved number was read from the file before it was moved.
        let moved = design
            .moved
            .iter()
            .map(|(pointer, value)| {
                let in_file = number_at(&self.base, pointer)
                    .map_err(|_| LiveError::Parameter(ParameterError::Gone { pointer: pointer.clone() }))?;
                Ok(Moved { pointer: pointer.clone(), value: *value, in_file })
            })
            .collect::<Result<_, LiveError>>()?;
        let (points, constraints) = match &self.targets {
            Some(targets) => judge(report, &document, targets),
            None => (Vec::new(), Vec::new()),
        };
        let targets = points
            .iter()
            .map(|p| JudgedTarget {
                label: p.target.label.clone(),
                analysis: p.target.analysis.name(),
                figure: match &p.target.aim {
                    Aim::Figure { key, .. } => Some(key.clone()),
                    Aim::Curve { .. } => None,
                },
                column: match &p.target.aim {
                    Aim::Curve { column, .. } => Some(column.clone()),
                    Aim::Figure { .. } => None,
                },
                at: p.at,
                aim: p.aim,
                tolerance: p.target.tolerance,
                reached: p.reached.as_ref().ok().copied(),
                why_not: p.reached.as_ref().err().cloned(),
                met: p.met(),
            })
            .collect();
        let constraints = constraints
            .iter()
            .map(|c| JudgedConstraint {
                said: c.constraint.said(),
                reached: c.reached.as_ref().ok().map(|r| r.0),
                min: c.reached.as_ref().ok().map(|r| r.1),
                max: c.reached.as_ref().ok().map(|r| r.2),
                why_not: c.reached.as_ref().err().cloned(),
                met: c.met(),
            })
            .collect();
        Ok(State {
            version: self.version,
            estimated: self.estimated(),
            model: &report.model,
            moved,
            can_undo: self.at > 0,
            can_redo: self.at + 1 < self.history.len(),
            analyses,
            skipped: &report.skipped,
            failed: &report.failed,
            warnings: report.all_warnings().collect(),
            hardpoints,
            rates,
            targets,
            constraints,
        })
    }

    /// How each figure of the current design moves with the hardpoint at `point` (its pointer, e.g.
    /// `/suspension/macpherson/hardpoints/tie_rod_inner`): the derivatives of every figure to its x, y and
    /// z through the equilibrium, with their error estimates (`design::sensitivity`, figures only).
    /// Refused when `point` names no hardpoint of the model.
    pub fn guidance(&self, point: &str) -> Result<Guidance, LiveError> {
        let document = self.document()?;
        let pointers: Vec<String> = (0..3).map(|k| format!("{point}/{k}")).collect();
        let hardpoints = hardpoint_pointers(&document);
        if !pointers.iter().all(|p| hardpoints.contains(p)) {
            return Err(LiveError::NoHardpoint { point: point.to_string() });
        }
        let parameters = Parameters::new(&document, &pointers).map_err(LiveError::Parameter)?;
        let settings = Settings { figures_only: true, motion: false, ..self.settings };
        let suite = suite_sensitivity(&parameters, &self.which, &settings).map_err(LiveError::Parameter)?;
        let analyses = suite
            .analyses
            .iter()
            .map(|a| GuidedAnalysis {
                name: a.report.analysis.name(),
                figures: a
                    .report
                    .figures
                    .iter()
                    .enumerate()
                    .map(|(f, figure)| {
                        let rate = |k: usize| a.figures.get(k).and_then(|row| row.get(f)).copied();
                        let xyz: Vec<Option<Rate>> = (0..3).map(rate).collect();
                        GuidedFigure {
                            key: figure.key.clone(),
                            per_metre: xyz.iter().map(|r| r.and_then(|r| r.ok()).map(|d| d.value)).collect(),
                            error: xyz.iter().map(|r| r.and_then(|r| r.ok()).map(|d| d.error)).collect(),
                            why_not: xyz
                                .iter()
                                .map(|r| match r {
                                    Some(Err(no)) => Some(no.reason()),
                                    Some(Ok(_)) => None,
                                    None => Some("no derivative was made"),
                                })
                                .collect(),
                        }
                    })
                    .collect(),
            })
            .collect();
        Ok(Guidance { point: point.to_string(), version: self.version, analyses })
    }

    /// The current design's model, read afresh from its document as the command reads a file.
    pub fn file(&self) -> Result<SuspensionFile, LiveError> {
        let document = self.document()?;
        Parameters::new(&document, &[]).and_then(|p| p.file()).map_err(LiveError::Parameter)
    }
}

/// The current design as a view shows it ([`LiveDesign::state`]), written as JSON.
#[derive(Debug, Serialize)]
pub struct State<'a> {
    /// Counts every change of design: a view showing an older one is behind.
    pub version: u64,
    /// Whether the figures carry their error estimates yet ([`LiveDesign::estimated`]).
    pub estimated: bool,
    /// The model's name.
    pub model: &'a str,
    /// The numbers moved from the file as read.
    pub moved: Vec<Moved>,
    /// Whether there is a design to go back to.
    pub can_undo: bool,
    /// Whether there is an undone design to go on to.
    pub can_redo: bool,
    /// Each analysis run.
    pub analyses: Vec<AnalysisState<'a>>,
    /// Analyses left out, and why.
    pub skipped: &'a [Skipped],
    /// Analyses that failed on the design, and why.
    pub failed: &'a [Failed],
    /// The model's and the results' warnings.
    pub warnings: Vec<&'a Warning>,
    /// Every coordinate of every hardpoint of the design (m).
    pub hardpoints: Vec<Number>,
    /// Every rate of the design written as a number: springs', bars', bushings', the tyre's (SI: N/m,
    /// N·m/rad).
    pub rates: Vec<Number>,
    /// Each point of each target judged on the design (none without targets).
    pub targets: Vec<JudgedTarget>,
    /// Each packaging constraint judged on the design.
    pub constraints: Vec<JudgedConstraint>,
}

/// A point of a target judged on a design: a figure target, or one point of a curve target. Its numbers are
/// in the unit the target is given in (a figure's as written under the default units, a column's).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct JudgedTarget {
    /// Where the target was given (`targets[1] (parallel-travel/bump_steer)`).
    pub label: String,
    /// Its analysis.
    pub analysis: &'static str,
    /// The figure's key, for a figure target.
    pub figure: Option<String>,
    /// The column, for a curve target.
    pub column: Option<String>,
    /// The load parameter of a curve target's point.
    pub at: Option<f64>,
    /// What the target asks.
    pub aim: f64,
    /// The miss that counts as met (or the measured data's noise).
    pub tolerance: f64,
    /// What the design gives.
    pub reached: Option<f64>,
    /// Why the design gives nothing to judge.
    pub why_not: Option<String>,
    /// Whether the design meets it.
    pub met: bool,
}

/// A packaging constraint judged on a design (m).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct JudgedConstraint {
    /// What it keeps, in the TARGETS file's words.
    pub said: String,
    /// Its value on the design.
    pub reached: Option<f64>,
    /// The least it may be.
    pub min: Option<f64>,
    /// The most it may be.
    pub max: Option<f64>,
    /// Why it could not be read.
    pub why_not: Option<String>,
    /// Whether the design keeps it.
    pub met: bool,
}

/// How the figures of a design move with one hardpoint ([`LiveDesign::guidance`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Guidance {
    /// The hardpoint's pointer.
    pub point: String,
    /// The version of the design it is of.
    pub version: u64,
    /// Each analysis's figures.
    pub analyses: Vec<GuidedAnalysis>,
}

/// The derivatives of one analysis's figures to a hardpoint.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GuidedAnalysis {
    /// The analysis's name.
    pub name: &'static str,
    /// Its figures, in its report's order.
    pub figures: Vec<GuidedFigure>,
}

/// One figure's derivatives to a hardpoint's x, y and z: SI per metre, each with its error estimate, or
/// why there is none.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GuidedFigure {
    /// The figure's key.
    pub key: String,
    /// The derivatives to x, y and z (the figure's SI unit per metre).
    pub per_metre: Vec<Option<f64>>,
    /// Their error estimates.
    pub error: Vec<Option<f64>>,
    /// Why a derivative is missing.
    pub why_not: Vec<Option<&'static str>>,
}

/// A number of the design by its pointer.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Number {
    /// Its JSON pointer in the model file.
    pub pointer: String,
    /// Its value (SI).
    pub value: f64,
}

/// A number moved from the file as read.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Moved {
    /// Its JSON pointer in the model file.
    pub pointer: String,
    /// Its value in the design (SI).
    pub value: f64,
    /// Its value in the file as read (SI).
    pub in_file: f64,
}

/// One analysis of the design: its figures and charts.
#[derive(Debug, Serialize)]
pub struct AnalysisState<'a> {
    /// Its name, as the command names it.
    pub name: &'static str,
    /// Its load parameter, with its unit.
    pub parameter: &'a str,
    /// What was run, in one line.
    pub description: &'a str,
    /// Its headline figures.
    pub figures: Vec<FigureState<'a>>,
    /// Its charts, in the axes' units.
    pub charts: &'a [Chart],
}

/// A headline figure: its value and error estimate in SI, and how it is written (its unit under the
/// run's units, the factor from SI to it and its decimals), or the reason it has no value.
#[derive(Debug, Serialize)]
pub struct FigureState<'a> {
    /// Its key.
    pub key: &'a str,
    /// What it is, in words.
    pub label: &'a str,
    /// Its value in SI.
    pub value: Option<f64>,
    /// Its error estimate in SI.
    pub error: Option<f64>,
    /// Why there is no value.
    pub reason: Option<&'a str>,
    /// The unit it is written in.
    pub unit: &'static str,
    /// Written value per SI value.
    pub factor: f64,
    /// Decimals it is written with.
    pub decimals: usize,
}

impl<'a> FigureState<'a> {
    fn of(figure: &'a Figure, units: kc::Units) -> FigureState<'a> {
        let written = figure.written(units);
        FigureState {
            key: &figure.key,
            label: &figure.label,
            value: figure.value,
            error: figure.error,
            reason: figure.reason.as_deref(),
            unit: written.unit,
            factor: written.factor,
            decimals: written.decimals,
        }
    }
}

/// Why a design cannot be opened, or an edit, undo or redo is refused. The current design stays.
#[derive(Debug, Clone, thiserror::Error)]
pub enum LiveError {
    /// The model file's text is no document to edit.
    #[error("{0}")]
    Document(BaseDocumentError),
    /// The model file does not read or build.
    #[error("{0}")]
    Model(Arc<DocumentError>),
    /// A pointer that names no number, a count, or a model that does not read or build once moved.
    #[error("{0}")]
    Parameter(ParameterError),
    /// A value that is no finite number.
    #[error("'{pointer}' needs a finite number")]
    NotFinite {
        /// The pointer.
        pointer: String,
    },
    /// An analysis that the current design ran fails on the edited one.
    #[error(
        "with '{pointer}' at {value} {}: the design is kept as it was",
        failed.iter().map(|f| f.to_string()).collect::<Vec<_>>().join("; ")
    )]
    Solve {
        /// The number moved.
        pointer: String,
        /// The value asked for.
        value: f64,
        /// Each analysis that failed, with the reason.
        failed: Vec<Failed>,
    },
    /// A pointer that names no hardpoint of the model.
    #[error(
        "'{point}' names no hardpoint of the model: give a point's pointer, its three coordinates under it \
         (e.g. /suspension/macpherson/hardpoints/tie_rod_inner)"
    )]
    NoHardpoint {
        /// The pointer given.
        point: String,
    },
    /// Undo at the design as opened.
    #[error("nothing to undo: this is the design as the file was read")]
    NothingToUndo,
    /// Redo with nothing undone.
    #[error("nothing to redo: no design was undone since the last edit")]
    NothingToRedo,
    /// The file's text cannot take a moved number.
    #[error("{0}")]
    Text(NumberEditError),
    /// A tune asked for without a TARGETS file.
    #[error("nothing to tune to: start the server with a TARGETS file (--targets FILE, or targets= in Python)")]
    NoTargets,
    /// A tune asked for with a TARGETS file that frees no number.
    #[error("nothing to tune: the TARGETS file's \"free\" names no number")]
    NothingFree,
    /// A free number the edits have moved outside its bounds.
    #[error("'{pointer}' is at {value}, outside its bounds [{min}, {max}] in the TARGETS file: move it back inside, or widen them")]
    OutsideBounds {
        /// The number.
        pointer: String,
        /// Its value in the current design.
        value: f64,
        /// Its lower bound.
        min: f64,
        /// Its upper bound.
        max: f64,
    },
    /// The tune could not run.
    #[error("the tune could not run: {0}")]
    Tune(String),
}
