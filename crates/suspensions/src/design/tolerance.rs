//! Tolerance stack-up: how far the figures of a suspension spread when its numbers are made within their
//! tolerances (a hardpoint's ±1 mm each axis, a bushing rate's ±15 %). First order, from the exact
//! sensitivities: each figure's worst case (every number at the end of its band that moves the figure the
//! same way) and its standard deviation (the numbers independent, each uniform over its band: `σ = t/√3`),
//! with the numbers that contribute most ranked. Checked by Monte Carlo: the model sampled within the
//! bands, every sample run, the spread measured.
//!
//! The TOLERANCES file:
//!
//! ```json
//! { "tolerances": { "/suspension/macpherson/hardpoints/tie_rod_inner/2": 0.001,
//!                   "/suspension/macpherson/lower_arm_mounts/bushing/radial": "15%" },
//!   "hardpoints": 0.001,
//!   "analyses": ["parallel-travel"],
//!   "steps": 32 }
//! ```
//!
//! `hardpoints` gives every coordinate of every hardpoint that tolerance (a number named in
//! `tolerances` keeps its own); `analyses` defaults to the whole suite.

use super::keys::{analysis_named, name_in, only, steps, KeyRefusal};
use super::parameter::{hardpoint_pointers, number_at, NoNumber, ParameterError, Parameters};
use super::sensitivity::{sensitivity_settings, suite_sensitivity, SuiteSensitivity};
use crate::kc::{self, Analysis, Cell, Failed, Settings, Table, Unit};
use rand::{Rng, SeedableRng};
use rayon::prelude::*;
use serde_json::Value;

/// The stack-up asked for: each number's tolerance (±, in the file's units), the analyses, the steps.
#[derive(Debug, Clone, PartialEq)]
pub struct Tolerances {
    /// `(pointer, ±tolerance)`, in the order given.
    pub bands: Vec<(String, f64)>,
    /// The analyses (every one the suite runs when empty).
    pub analyses: Vec<Analysis>,
    /// Load steps per sweep.
    pub steps: usize,
}

/// A TOLERANCES file refused: the file, and what is wrong where in it.
#[derive(Debug, Clone, thiserror::Error)]
#[error("{origin}: {refusal}")]
pub struct TolerancesError {
    /// The file.
    pub origin: String,
    /// What is wrong, naming the key (boxed: a refusal carries the key, what it holds and what it may).
    pub refusal: Box<TolerancesRefusal>,
}

/// What is wrong in a TOLERANCES file, naming the key (`tolerances["/…/rate"]`) and what to give instead.
#[derive(Debug, Clone, thiserror::Error)]
pub enum TolerancesRefusal {
    /// A key that holds what no key of its name may.
    #[error(transparent)]
    Key(#[from] KeyRefusal),
    /// The file is no JSON object.
    #[error("the file must be a JSON object with \"tolerances\"")]
    NotObject,
    /// A toleranced pointer that names no number of the model.
    #[error("{key}: '{pointer}' {why}")]
    NoNumber {
        /// The key the band is given at (`hardpoints` or `tolerances["…"]`).
        key: String,
        /// The pointer.
        pointer: String,
        /// What it names instead.
        why: NoNumber,
    },
    /// A band that is neither a number nor a percent.
    #[error("{key}: give ± in the file's units (0.001) or a percent (\"15%\"), got {}", as_written(got))]
    NotBand {
        /// The key.
        key: String,
        /// What it holds.
        got: Value,
    },
    /// A band that is not positive (or not finite).
    #[error("{key}: a tolerance must be a positive band, got {got}")]
    NotPositive {
        /// The key.
        key: String,
        /// What it holds.
        got: Value,
    },
    /// A band for every hardpoint of a model that has none.
    #[error("hardpoints: the model has no hardpoints (a template's or the general form's)")]
    NoHardpoints,
    /// No band at all.
    #[error("no tolerances: give \"tolerances\" {{\"/json/pointer\": ±band, …}} or \"hardpoints\": ±band")]
    NoTolerances,
    /// An empty list of analyses (which would read as no choice: the whole suite).
    #[error("analyses: give one analysis name at least, or leave the key out for the whole suite")]
    NoAnalyses,
    /// `analyses` that is not a list.
    #[error("analyses: give a list of analysis names")]
    AnalysesNotList,
}

/// A JSON value as the file's text has it: a string in its quotes, as it is.
fn as_written(v: &Value) -> String {
    match v {
        Value::String(s) => format!("\"{s}\""),
        other => other.to_string(),
    }
}

/// Reads a TOLERANCES file against the model `document`; errors name the key and the fix.
pub fn read_tolerances(text: &str, origin: &str, document: &Value) -> Result<Tolerances, TolerancesError> {
    tolerances_in(text, document)
        .map_err(|refusal| TolerancesError { origin: origin.into(), refusal: Box::new(refusal) })
}

fn tolerances_in(text: &str, document: &Value) -> Result<Tolerances, TolerancesRefusal> {
    use TolerancesRefusal as R;
    let root = super::keys::read_json(text)?;
    let object = root.as_object().ok_or(R::NotObject)?;
    only(object, &["tolerances", "hardpoints", "analyses", "steps"], "the top level")?;
    let band = |pointer: &str, v: &Value, key: &str| -> Result<f64, TolerancesRefusal> {
        let value = number_at(document, pointer).map_err(|why| R::NoNumber {
            key: key.into(),
            pointer: pointer.into(),
            why,
        })?;
        let not_band = || R::NotBand { key: key.into(), got: v.clone() };
        let t = match v {
            Value::Number(n) => n.as_f64().unwrap_or(f64::NAN),
            Value::String(s) => match s.trim().strip_suffix('%').map(|p| p.trim().parse::<f64>()) {
                Some(Ok(p)) => p * 1e-2 * value.abs(),
                _ => return Err(not_band()),
            },
            _ => return Err(not_band()),
        };
        if t.is_finite() && t > 0.0 {
            Ok(t)
        } else {
            Err(R::NotPositive { key: key.into(), got: v.clone() })
        }
    };
    let mut bands: Vec<(String, f64)> = Vec::new();
    if let Some(h) = object.get("hardpoints") {
        for pointer in hardpoint_pointers(document) {
            bands.push((pointer.clone(), band(&pointer, h, "hardpoints")?));
        }
        if bands.is_empty() {
            return Err(R::NoHardpoints);
        }
    }
    for (pointer, v) in object.get("tolerances").and_then(Value::as_object).into_iter().flatten() {
        let t = band(pointer, v, &format!("tolerances[\"{pointer}\"]"))?;
        match bands.iter_mut().find(|(p, _)| p == pointer) {
            Some(b) => b.1 = t,
            None => bands.push((pointer.clone(), t)),
        }
    }
    if bands.is_empty() {
        return Err(R::NoTolerances);
    }
    let analyses = match object.get("analyses") {
        None => Vec::new(),
        // An empty list would be read as no choice: the whole suite.
        Some(list) if list.as_array().is_some_and(Vec::is_empty) => return Err(R::NoAnalyses),
        Some(list) => list
            .as_array()
            .ok_or(R::AnalysesNotList)?
            .iter()
            .map(|v| analysis_named(name_in(v, "analyses")?, "analyses"))
            .collect::<Result<_, _>>()?,
    };
    let steps = steps(object)?;
    Ok(Tolerances { bands, analyses, steps })
}

/// Sample `i` of a Monte Carlo seeded by `seed`: each number drawn uniformly within its band about its
/// value. Each sample has its own stream, so a sample is the same whichever thread, process or machine
/// draws it (a study on Ray or Dask from Python draws the command's samples).
pub fn sample(values: &[f64], bands: &[f64], seed: u64, i: usize) -> Vec<f64> {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed ^ (i as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15));
    values.iter().zip(bands).map(|(v, t)| v + t * (2.0 * rng.random::<f64>() - 1.0)).collect()
}

/// One figure's spread.
#[derive(Debug, Clone, PartialEq)]
pub struct Spread {
    /// The analysis.
    pub analysis: Analysis,
    /// The figure's key.
    pub figure: String,
    /// The unit it is written in; every number below is in its SI unit.
    pub unit: Unit,
    /// Its value at nominal.
    pub value: f64,
    /// First order, every number at the end of its band that moves the figure the same way: ±.
    pub worst_case: f64,
    /// First order, the numbers independent and uniform over their bands: the standard deviation.
    pub sigma: f64,
    /// Each number's share: `(parameter, derivative × tolerance)`, largest first.
    pub contributions: Vec<(usize, f64)>,
    /// By Monte Carlo, when run: the standard deviation, lowest and highest of the samples.
    pub sampled: Option<Sampled>,
}

/// What the samples of a Monte Carlo run gave for a figure.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sampled {
    /// Standard deviation.
    pub sigma: f64,
    /// Mean.
    pub mean: f64,
    /// Lowest.
    pub min: f64,
    /// Highest.
    pub max: f64,
    /// Samples with a value.
    pub count: usize,
}

/// A stack-up's result.
#[derive(Debug, Clone)]
pub struct StackUp {
    /// The numbers and their tolerances.
    pub parameters: Parameters,
    /// The bands, as read.
    pub bands: Vec<f64>,
    /// The figures' spreads (those with a value and a derivative for every number).
    pub spreads: Vec<Spread>,
    /// Figures left out, with why: `(analysis, figure, why)`.
    pub left_out: Vec<(String, String, String)>,
    /// Analyses that failed.
    pub failed: Vec<Failed>,
    /// Samples of the Monte Carlo run that failed (a model that would not build or solve), with why.
    pub failed_samples: Vec<String>,
    /// How the analyses were run (their load steps): the Monte Carlo's samples are run alike.
    pub settings: Settings,
    /// What the analyses warned of on the model as it is (a toe beyond ±10° over the travel, an error
    /// estimate over the tolerance): the spreads are of those results.
    pub warnings: Vec<kc::Warning>,
}

/// Why a stack-up cannot be had.
#[derive(Debug, Clone, thiserror::Error)]
pub enum StackUpError {
    /// A toleranced number the model does not read as a parameter.
    #[error(transparent)]
    Parameter(#[from] ParameterError),
    /// A band that spreads a figure beyond any finite number.
    #[error(
        "the band ±{band:e} of '{pointer}' spreads {analysis} {figure} beyond any number: give a band a part can be \
         made to, in the file's units"
    )]
    Unbounded {
        /// The band.
        band: f64,
        /// The number it is of.
        pointer: String,
        /// The analysis of the figure.
        analysis: &'static str,
        /// The figure's key.
        figure: String,
    },
}

/// The first-order stack-up of `tolerances` on the model `document`. Refused, naming the number: a band that
/// spreads a figure beyond any finite number.
pub fn stack_up(document: &Value, tolerances: &Tolerances) -> Result<StackUp, StackUpError> {
    let pointers: Vec<String> = tolerances.bands.iter().map(|(p, _)| p.clone()).collect();
    let bands: Vec<f64> = tolerances.bands.iter().map(|(_, t)| *t).collect();
    let parameters = Parameters::new(document, &pointers)?;
    // Spreads are of figures: the rows are read as far as the figures read them.
    let settings =
        sensitivity_settings(&Settings { steps: tolerances.steps, figures_only: true, ..Settings::default() });
    let suite: SuiteSensitivity = suite_sensitivity(&parameters, &tolerances.analyses, &settings)?;
    let (mut spreads, mut left_out) = (Vec::new(), Vec::new());
    for a in &suite.analyses {
        for (j, figure) in a.report.figures.iter().enumerate() {
            let analysis = a.report.analysis;
            let Some(value) = figure.value else { continue };
            let rates: Result<Vec<f64>, _> = a.figures.iter().map(|d| d[j].map(|d| d.value)).collect();
            let rates = match rates {
                Ok(r) => r,
                Err(e) => {
                    left_out.push((analysis.name().to_string(), figure.key.clone(), e.reason().to_string()));
                    continue;
                }
            };
            let mut contributions: Vec<(usize, f64)> =
                rates.iter().zip(&bands).map(|(d, t)| d * t).enumerate().collect();
            let worst_case: f64 = contributions.iter().map(|(_, c)| c.abs()).sum();
            let sigma = (contributions.iter().map(|(_, c)| c * c).sum::<f64>() / 3.0).sqrt();
            contributions.sort_by(|a, b| b.1.abs().total_cmp(&a.1.abs()));
            // A band no part is made to spreads the figure past any number: refused by the number it is of.
            if !(worst_case.is_finite() && sigma.is_finite()) {
                let k = contributions[0].0;
                return Err(StackUpError::Unbounded {
                    band: bands[k],
                    pointer: pointers[k].clone(),
                    analysis: analysis.name(),
                    figure: figure.key.clone(),
                });
            }
            spreads.push(Spread {
                analysis,
                figure: figure.key.clone(),
                unit: figure.unit,
                value,
                worst_case,
                sigma,
                contributions,
                sampled: None,
            });
        }
    }
    let warnings = suite.analyses.iter().flat_map(|a| a.report.warnings.iter().cloned()).collect();
    Ok(StackUp {
        parameters,
        bands,
        spreads,
        left_out,
        failed: suite.failed,
        failed_samples: Vec::new(),
        settings,
        warnings,
    })
}

impl StackUp {
    /// Checks the first-order spreads by Monte Carlo: `samples` models, each number drawn uniformly within
    /// its band (seeded by `seed`, so a run is repeated exactly), each run on rayon's threads as the
    /// first order's analyses were; the samples' spread of every figure is kept beside the first-order one.
    pub fn monte_carlo(&mut self, samples: usize, seed: u64) {
        // The analyses the spreads are of, each once; the samples read their figures alone, so no error
        // estimate (a Newton iteration more per row).
        let mut which: Vec<Analysis> = Vec::new();
        for s in &self.spreads {
            if !which.contains(&s.analysis) {
                which.push(s.analysis);
            }
        }
        if which.is_empty() {
            return;
        }
        let settings = Settings { error_estimate: false, ..self.settings };
        let runs: Vec<Result<Vec<Option<f64>>, String>> = (0..samples)
            .into_par_iter()
            .map(|i| {
                let x = sample(&self.parameters.values, &self.bands, seed, i);
                // Written in the stack-up as the sample's failure.
                let file = self.parameters.at(&x).and_then(|p| p.file()).map_err(|e| e.to_string())?;
                let models = kc::Models::owning(file);
                let mut reports = Vec::new();
                for &a in &which {
                    reports.push(kc::run_on(a, &models, &settings).map_err(|e| format!("sample {i}: {e}"))?);
                }
                Ok(self
                    .spreads
                    .iter()
                    .map(|s| {
                        let r = reports.iter().find(|r| r.analysis == s.analysis)?;
                        r.figure(&s.figure)?.value
                    })
                    .collect())
            })
            .collect();
        self.failed_samples = runs.iter().filter_map(|r| r.as_ref().err().cloned()).collect();
        let values: Vec<&Vec<Option<f64>>> = runs.iter().filter_map(|r| r.as_ref().ok()).collect();
        for (j, s) in self.spreads.iter_mut().enumerate() {
            let v: Vec<f64> = values.iter().filter_map(|r| r[j]).collect();
            if v.len() < 2 {
                continue;
            }
            let mean = v.iter().sum::<f64>() / v.len() as f64;
            let var = v.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / (v.len() - 1) as f64;
            let (min, max) = v.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(*x), b.max(*x)));
            s.sampled = Some(Sampled { sigma: var.sqrt(), mean, min, max, count: v.len() });
        }
    }

    /// `tolerance.csv`: one row per figure — its value, first-order worst case and standard deviation,
    /// the Monte Carlo's when run, and its three largest contributors, in the figure's written unit.
    pub fn table(&self) -> Table {
        let columns = [
            "analysis",
            "figure",
            "unit",
            "value",
            "worst_case",
            "sigma",
            "sampled_sigma",
            "sampled_mean",
            "sampled_min",
            "sampled_max",
            "samples",
            "first_contributor",
            "second_contributor",
            "third_contributor",
        ];
        let rows = self
            .spreads
            .iter()
            .map(|s| {
                let m = s.sampled;
                let unit = s.unit.shown();
                let shown = |v: Option<f64>| Cell::from(v.map(|v| v * unit.factor));
                let mut row = vec![
                    Cell::Text(s.analysis.name().into()),
                    Cell::Text(s.figure.clone()),
                    Cell::Text(unit.symbol.into()),
                    shown(Some(s.value)),
                    shown(Some(s.worst_case)),
                    shown(Some(s.sigma)),
                    shown(m.map(|m| m.sigma)),
                    shown(m.map(|m| m.mean)),
                    shown(m.map(|m| m.min)),
                    shown(m.map(|m| m.max)),
                    Cell::from(m.map(|m| m.count as f64)),
                ];
                for k in 0..3 {
                    row.push(s.contributions.get(k).map_or(Cell::Empty, |(p, c)| {
                        let c = kc::significant(*c * unit.factor, 3);
                        Cell::Text(format!("{} ({c})", self.parameters.pointers[*p]))
                    }));
                }
                row
            })
            .collect();
        Table { name: "tolerance".into(), columns: columns.map(String::from).to_vec(), rows }
    }

    /// `tolerance_contributions.csv`: every figure and number — the number's tolerance, the figure's
    /// derivative times it (its first-order share, signed, in the figure's written unit).
    pub fn contribution_table(&self) -> Table {
        let columns = ["analysis", "figure", "unit", "parameter", "tolerance", "contribution"];
        let mut rows = Vec::new();
        for s in &self.spreads {
            let unit = s.unit.shown();
            let mut by_parameter = s.contributions.clone();
            by_parameter.sort_by_key(|(p, _)| *p);
            for (p, c) in by_parameter {
                rows.push(vec![
                    Cell::Text(s.analysis.name().into()),
                    Cell::Text(s.figure.clone()),
                    Cell::Text(unit.symbol.into()),
                    Cell::Text(self.parameters.pointers[p].clone()),
                    Cell::from(self.bands[p]),
                    Cell::from(c * unit.factor),
                ]);
            }
        }
        Table { name: "tolerance_contributions".into(), columns: columns.map(String::from).to_vec(), rows }
    }
}
