//! Tolerance stack-up: how far the figures of a suspension spread when its numbers are made within their
//! tolerances (a hardpoint's ±1 mm each axis, a bushing rate's ±15 %) and the car is assembled and aligned.
//! First order, from the exact sensitivities: each figure's worst case (every source at the end of its band
//! that moves the figure the same way; a normal band's end taken at 3σ) and its standard deviation (the
//! sources independent: `σ = t/√3` of a uniform band ±t, σ of a normal one), with the sources that
//! contribute most ranked. A source is one number's band, or a group's shift along one axis: one draw that
//! moves every point of a bracket or a subframe together. An adjustment is a number set at alignment so a
//! figure is back at its nominal value (toe set by the tie rod, camber by an eccentric): first order, the
//! adjusted figure's rates are removed through the adjusters' own; sampled, the adjusters are solved on each
//! car. Checked by Monte Carlo: the model sampled within the bands, adjusted, every sample run, the spread
//! and the share of cars outside each limit counted.
//!
//! The TOLERANCES file (every key: docs/design-files.md):
//!
//! ```json
//! { "tolerances": { "/suspension/twist_beam/spring/rate": "5%",
//!                   "/suspension/twist_beam/toe": { "uniform": 0.1 } },
//!   "hardpoints": { "normal": 0.0004 },
//!   "groups": [ { "name": "wheel carrier", "points": ["wheel_centre", "arm_end"], "shift": 0.0005 } ],
//!   "adjust": [ { "figure": "static-load/toe", "by": "/suspension/twist_beam/toe" } ],
//!   "limits": { "static-load/camber": [-1.2, -1.1] },
//!   "analyses": ["parallel-travel", "static-load"],
//!   "steps": 32 }
//! ```
//!
//! `hardpoints` gives every coordinate of every hardpoint that tolerance (a number named in
//! `tolerances` keeps its own); `analyses` defaults to the whole suite.

use super::keys::{analysis_named, name_in, number, only, steps, KeyRefusal};
use super::parameter::{
    hardpoint_pointer, hardpoint_pointers, number_at, parameter_words, NoNumber, ParameterError, Parameters,
};
use super::sensitivity::{sensitivity_settings, suite_sensitivity, SuiteSensitivity};
use crate::kc::report::Column;
use crate::kc::{self, Analysis, AnalysisReport, Cell, Failed, Settings, Table, Unit};
use rand::{Rng, SeedableRng};
use rayon::prelude::*;
use serde_json::{Map, Value};

/// How a source is spread about its nominal value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Band {
    /// Uniform over ± this half-width (a part made anywhere within its drawing's band).
    Uniform(f64),
    /// Normal with this standard deviation (a process whose spread is measured).
    Normal(f64),
}

impl Band {
    /// Its standard deviation: `t/√3` of a uniform band ±t.
    pub fn sigma(self) -> f64 {
        match self {
            Band::Uniform(t) => t / 3f64.sqrt(),
            Band::Normal(s) => s,
        }
    }

    /// Its end in a worst case: the half-width of a uniform band, 3σ of a normal one.
    pub fn end(self) -> f64 {
        match self {
            Band::Uniform(t) => t,
            Band::Normal(s) => 3.0 * s,
        }
    }

    /// The number the file gives: the half-width or σ.
    pub fn width(self) -> f64 {
        match self {
            Band::Uniform(t) | Band::Normal(t) => t,
        }
    }

    /// `uniform` or `normal`, as the file names it.
    pub fn distribution(self) -> &'static str {
        match self {
            Band::Uniform(_) => "uniform",
            Band::Normal(_) => "normal",
        }
    }

    /// One draw about zero.
    fn draw(self, rng: &mut impl Rng) -> f64 {
        match self {
            Band::Uniform(t) => t * (2.0 * rng.random::<f64>() - 1.0),
            Band::Normal(s) => s * rng.sample::<f64, _>(rand_distr::StandardNormal),
        }
    }
}

/// One independent draw of the stack-up: a number's band, or a group's shift along one axis.
#[derive(Debug, Clone, PartialEq)]
pub struct Source {
    /// How the CSVs name it: the number's pointer, or `group NAME x`.
    pub name: String,
    /// How people read it: `tie_rod_inner z`, `subframe shifted x`.
    pub words: String,
    /// Its band, in the file's units.
    pub band: Band,
    /// The parameters it moves and by how much per unit of the draw (indices into [`Tolerances::pointers`]:
    /// 1 for a number's band and a shift, the lever of a rotation).
    pub moves: Vec<(usize, f64)>,
}

/// A number set at alignment so that a figure is back at its nominal value.
#[derive(Debug, Clone, PartialEq)]
pub struct Adjustment {
    /// The analysis of the figure held.
    pub analysis: Analysis,
    /// The figure's key.
    pub figure: String,
    /// The number set (an index into [`Tolerances::pointers`]).
    pub by: usize,
}

/// The band a figure must stay within, in the unit the figure is written in (as a TARGETS file's values).
#[derive(Debug, Clone, PartialEq)]
pub struct Limit {
    /// The analysis.
    pub analysis: Analysis,
    /// The figure's key.
    pub figure: String,
    /// Lowest allowed, if any.
    pub min: Option<f64>,
    /// Highest allowed, if any.
    pub max: Option<f64>,
}

/// The stack-up asked for: the numbers moved, the sources that move them, the adjustments and limits, the
/// analyses, the steps.
#[derive(Debug, Clone, PartialEq)]
pub struct Tolerances {
    /// Every number the stack-up moves or sets, as a JSON pointer: the sources' and the adjusters'.
    pub pointers: Vec<String>,
    /// The independent draws, in the order given (numbers first, then the groups' axes).
    pub sources: Vec<Source>,
    /// The alignment's adjustments.
    pub adjustments: Vec<Adjustment>,
    /// The limits whose share of cars outside is counted.
    pub limits: Vec<Limit>,
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
    /// A pointer that names no number of the model.
    #[error("{key}: '{pointer}' {why}")]
    NoNumber {
        /// The key the pointer is given at (`hardpoints`, `tolerances["…"]`, `adjust[0].by`).
        key: String,
        /// The pointer.
        pointer: String,
        /// What it names instead.
        why: NoNumber,
    },
    /// A band that is neither a number, a percent nor a distribution's.
    #[error(
        "{key}: give ± in the file's units (0.001), a percent (\"15%\"), or {{\"normal\": σ}} or {{\"uniform\": ±}} \
         of either, got {}",
        as_written(got)
    )]
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
    /// A group's shift or rotation given as a percent, which neither is.
    #[error("{key}: a shift is a length and a rotation an angle: give it in the file's units (m) or in rad, not as a percent")]
    ShiftPercent {
        /// The key.
        key: String,
    },
    /// A band for every hardpoint of a model that has none.
    #[error("hardpoints: the model has no hardpoints (a template's or the general form's)")]
    NoHardpoints,
    /// No band at all.
    #[error("no tolerances: give \"tolerances\" {{\"/json/pointer\": ±band, …}}, \"hardpoints\": ±band or \"groups\"")]
    NoTolerances,
    /// An empty list of analyses (which would read as no choice: the whole suite).
    #[error("analyses: give one analysis name at least, or leave the key out for the whole suite")]
    NoAnalyses,
    /// A key that must hold a list.
    #[error("{key}: give a list of {what}")]
    NotList {
        /// The key.
        key: String,
        /// What the list holds.
        what: &'static str,
    },
    /// A list entry that must be an object.
    #[error("{key}: give an object {what}")]
    NotObjectAt {
        /// The key.
        key: String,
        /// What it must hold.
        what: &'static str,
    },
    /// A required key left out.
    #[error("{key}: give \"{missing}\" ({what})")]
    Missing {
        /// The object's key.
        key: String,
        /// The key left out.
        missing: &'static str,
        /// What it is.
        what: &'static str,
    },
    /// A group's point that names no point of the model.
    #[error(
        "{key}: '{point}' is no point of the model: give a hardpoint's name ({}) or a JSON pointer to three \
         numbers",
        if names.is_empty() { "the model names none".to_string() } else { names.join(", ") }
    )]
    NoPoint {
        /// The key.
        key: String,
        /// What was given.
        point: String,
        /// The model's hardpoints' names.
        names: Vec<String>,
    },
    /// A point named twice in a group, or a figure or number adjusted twice.
    #[error("{key}: '{what}' is given twice: give each once")]
    Twice {
        /// The key.
        key: String,
        /// What is given twice.
        what: String,
    },
    /// A figure named without its analysis.
    #[error("{key}: give the figure as \"analysis/figure\" (\"parallel-travel/bump_steer\"), got '{path}'")]
    NotFigurePath {
        /// The key.
        key: String,
        /// What was given.
        path: String,
    },
    /// A limit with neither end, or its ends the wrong way round.
    #[error("{key}: give [min, max] in the figure's written unit, min below max (null for an open end), got {got}")]
    NotLimit {
        /// The key.
        key: String,
        /// What it holds.
        got: Value,
    },
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

/// A band as the file writes it, `v` at `key`: a number (±), a percent of `value` (`"15%"`), or
/// `{"normal": …}` / `{"uniform": …}` of either; a percent refused where `value` is `None` (a shift).
fn band_of(v: &Value, key: &str, value: Option<f64>) -> Result<Band, TolerancesRefusal> {
    use TolerancesRefusal as R;
    let not_band = || R::NotBand { key: key.into(), got: v.clone() };
    let (make, width): (fn(f64) -> Band, &Value) = match v {
        Value::Object(o) if o.len() == 1 && o.contains_key("normal") => (Band::Normal, &o["normal"]),
        Value::Object(o) if o.len() == 1 && o.contains_key("uniform") => (Band::Uniform, &o["uniform"]),
        Value::Object(_) => return Err(not_band()),
        other => (Band::Uniform, other),
    };
    let t = match width {
        Value::Number(n) => n.as_f64().unwrap_or(f64::NAN),
        Value::String(s) => match s.trim().strip_suffix('%').map(|p| p.trim().parse::<f64>()) {
            Some(Ok(p)) => match value {
                Some(value) => p * 1e-2 * value.abs(),
                None => return Err(R::ShiftPercent { key: key.into() }),
            },
            _ => return Err(not_band()),
        },
        _ => return Err(not_band()),
    };
    if t.is_finite() && t > 0.0 {
        Ok(make(t))
    } else {
        Err(R::NotPositive { key: key.into(), got: v.clone() })
    }
}

/// A group's band per axis at `key`: one band for each of x, y and z, or an object of `x`, `y`, `z` → band
/// for those axes alone (`(axis, band)`); a percent refused (a shift is a length, a rotation an angle).
fn by_axes(v: &Value, key: &str) -> Result<Vec<(usize, Band)>, TolerancesRefusal> {
    match v.as_object() {
        Some(by_axis) if ["x", "y", "z"].iter().any(|a| by_axis.contains_key(*a)) => {
            only(by_axis, &["x", "y", "z"], key)?;
            let mut axes = Vec::new();
            for (k, axis) in ["x", "y", "z"].iter().enumerate() {
                if let Some(b) = by_axis.get(*axis) {
                    axes.push((k, band_of(b, &format!("{key}.{axis}"), None)?));
                }
            }
            Ok(axes)
        }
        _ => {
            let band = band_of(v, key, None)?;
            Ok((0..3).map(|k| (k, band)).collect())
        }
    }
}

/// An `"analysis/figure"` path at `key`.
fn figure_path(v: &Value, key: &str) -> Result<(Analysis, String), TolerancesRefusal> {
    let path = name_in(v, key)?;
    let (analysis, figure) =
        path.split_once('/').ok_or_else(|| TolerancesRefusal::NotFigurePath { key: key.into(), path: path.into() })?;
    Ok((analysis_named(analysis, key)?, figure.to_string()))
}

/// The list at `key` of `object` (empty when the key is left out).
fn list<'a>(object: &'a Map<String, Value>, key: &str, what: &'static str) -> Result<&'a [Value], TolerancesRefusal> {
    match object.get(key) {
        None => Ok(&[]),
        Some(v) => v.as_array().map(Vec::as_slice).ok_or_else(|| TolerancesRefusal::NotList { key: key.into(), what }),
    }
}

/// The pointer of number `pointer` among `pointers`, added if new.
fn index_of(pointers: &mut Vec<String>, pointer: &str) -> usize {
    match pointers.iter().position(|p| p == pointer) {
        Some(k) => k,
        None => {
            pointers.push(pointer.to_string());
            pointers.len() - 1
        }
    }
}

fn tolerances_in(text: &str, document: &Value) -> Result<Tolerances, TolerancesRefusal> {
    use TolerancesRefusal as R;
    let root = super::keys::read_json(text)?;
    let object = root.as_object().ok_or(R::NotObject)?;
    only(object, &["tolerances", "hardpoints", "groups", "adjust", "limits", "analyses", "steps"], "the top level")?;
    let value_at = |pointer: &str, key: &str| {
        number_at(document, pointer).map_err(|why| R::NoNumber { key: key.into(), pointer: pointer.into(), why })
    };
    // Each number's own band, by pointer: every hardpoint's, then those named (which replace a hardpoint's).
    let mut bands: Vec<(String, Band)> = Vec::new();
    if let Some(h) = object.get("hardpoints") {
        for pointer in hardpoint_pointers(document) {
            let value = value_at(&pointer, "hardpoints")?;
            bands.push((pointer, band_of(h, "hardpoints", Some(value))?));
        }
        if bands.is_empty() {
            return Err(R::NoHardpoints);
        }
    }
    for (pointer, v) in object.get("tolerances").and_then(Value::as_object).into_iter().flatten() {
        let key = format!("tolerances[\"{pointer}\"]");
        let t = band_of(v, &key, Some(value_at(pointer, &key)?))?;
        match bands.iter_mut().find(|(p, _)| p == pointer) {
            Some(b) => b.1 = t,
            None => bands.push((pointer.clone(), t)),
        }
    }
    let mut pointers: Vec<String> = bands.iter().map(|(p, _)| p.clone()).collect();
    let mut sources: Vec<Source> = bands
        .iter()
        .enumerate()
        .map(|(k, (p, band))| Source { name: p.clone(), words: parameter_words(p), band: *band, moves: vec![(k, 1.0)] })
        .collect();
    for (g, entry) in list(object, "groups", "groups {\"name\", \"points\", \"shift\"}")?.iter().enumerate() {
        let key = format!("groups[{g}]");
        let o = entry
            .as_object()
            .ok_or_else(|| R::NotObjectAt { key: key.clone(), what: "{\"name\", \"points\", \"shift\"}" })?;
        only(o, &["name", "points", "shift", "rotate"], &key)?;
        let missing = |missing, what| R::Missing { key: key.clone(), missing, what };
        let name = name_in(
            o.get("name").ok_or_else(|| missing("name", "what the group is: \"subframe\""))?,
            &format!("{key}.name"),
        )?;
        let points_key = format!("{key}.points");
        let points = o
            .get("points")
            .ok_or_else(|| missing("points", "the hardpoints that move together, by name or JSON pointer"))?
            .as_array()
            .filter(|p| !p.is_empty())
            .ok_or_else(|| R::NotList {
                key: points_key.clone(),
                what: "one point at least, by name or JSON pointer",
            })?;
        let mut members: Vec<String> = Vec::new();
        for (i, p) in points.iter().enumerate() {
            let at = format!("{points_key}[{i}]");
            let said = name_in(p, &at)?;
            let pointer = if said.starts_with('/') {
                document.pointer(said).filter(|v| is_point(v)).map(|_| said.to_string())
            } else {
                hardpoint_pointer(document, said)
            };
            let pointer = pointer.ok_or_else(|| R::NoPoint {
                key: at.clone(),
                point: said.into(),
                names: hardpoint_pointers(document)
                    .iter()
                    .filter_map(|p| p.strip_suffix("/0").and_then(|p| p.rsplit('/').next()).map(String::from))
                    .collect(),
            })?;
            if members.contains(&pointer) {
                return Err(R::Twice { key: at, what: said.into() });
            }
            members.push(pointer);
        }
        let (shift, rotate) = (o.get("shift"), o.get("rotate"));
        if shift.is_none() && rotate.is_none() {
            return Err(missing("shift", "the band of the whole group's shift, m, or \"rotate\", rad"));
        }
        // A shift along axis k moves each point's coordinate k by the draw.
        for (k, band) in shift.map(|v| by_axes(v, &format!("{key}.shift"))).transpose()?.into_iter().flatten() {
            let axis = ["x", "y", "z"][k];
            let moves = members.iter().map(|m| (index_of(&mut pointers, &format!("{m}/{k}")), 1.0)).collect();
            sources.push(Source {
                name: format!("group {name} {axis}"),
                words: format!("{name} shifted {axis}"),
                band,
                moves,
            });
        }
        // A small rotation ω about axis k through the points' centroid c moves point p by ω e_k × (p − c).
        let at: Vec<[f64; 3]> = members
            .iter()
            .map(|m| {
                std::array::from_fn(|k| document.pointer(&format!("{m}/{k}")).and_then(Value::as_f64).unwrap_or(0.0))
            })
            .collect();
        let centre: [f64; 3] = std::array::from_fn(|k| at.iter().map(|p| p[k]).sum::<f64>() / at.len() as f64);
        for (k, band) in rotate.map(|v| by_axes(v, &format!("{key}.rotate"))).transpose()?.into_iter().flatten() {
            let axis = ["x", "y", "z"][k];
            let (i, j) = ((k + 1) % 3, (k + 2) % 3);
            let mut moves = Vec::new();
            for (m, p) in members.iter().zip(&at) {
                let r = [p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]];
                // e_k × r: its i-th coordinate −r_j, its j-th r_i.
                moves.push((index_of(&mut pointers, &format!("{m}/{i}")), -r[j]));
                moves.push((index_of(&mut pointers, &format!("{m}/{j}")), r[i]));
            }
            sources.push(Source {
                name: format!("group {name} r{axis}"),
                words: format!("{name} rotated about {axis}"),
                band,
                moves,
            });
        }
    }
    if sources.is_empty() {
        return Err(R::NoTolerances);
    }
    let mut adjustments: Vec<Adjustment> = Vec::new();
    for (a, entry) in list(object, "adjust", "adjustments {\"figure\", \"by\"}")?.iter().enumerate() {
        let key = format!("adjust[{a}]");
        let o = entry.as_object().ok_or_else(|| R::NotObjectAt { key: key.clone(), what: "{\"figure\", \"by\"}" })?;
        only(o, &["figure", "by"], &key)?;
        let missing = |missing, what| R::Missing { key: key.clone(), missing, what };
        let figure =
            o.get("figure").ok_or_else(|| missing("figure", "the figure set at alignment: \"static-load/toe\""))?;
        let (analysis, figure) = figure_path(figure, &format!("{key}.figure"))?;
        let by_key = format!("{key}.by");
        let by =
            name_in(o.get("by").ok_or_else(|| missing("by", "the JSON pointer of the number that sets it"))?, &by_key)?;
        value_at(by, &by_key)?;
        let by = index_of(&mut pointers, by);
        if adjustments.iter().any(|x| x.by == by) {
            return Err(R::Twice { key: by_key, what: pointers[by].clone() });
        }
        if adjustments.iter().any(|x| x.analysis == analysis && x.figure == figure) {
            return Err(R::Twice { key: format!("{key}.figure"), what: format!("{}/{figure}", analysis.name()) });
        }
        adjustments.push(Adjustment { analysis, figure, by });
    }
    let mut limits = Vec::new();
    for (path, v) in object
        .get("limits")
        .map(|l| {
            l.as_object().ok_or(R::NotObjectAt { key: "limits".into(), what: "of \"analysis/figure\": [min, max]" })
        })
        .transpose()?
        .into_iter()
        .flatten()
    {
        let key = format!("limits[\"{path}\"]");
        let (analysis, figure) = figure_path(&Value::String(path.clone()), &key)?;
        let not_limit = || R::NotLimit { key: key.clone(), got: v.clone() };
        let end = |e: &Value| if e.is_null() { Ok(None) } else { number(e, &key).map(Some) };
        let (min, max) = match v.as_array().map(Vec::as_slice) {
            Some([a, b]) => (end(a)?, end(b)?),
            _ => return Err(not_limit()),
        };
        match (min, max) {
            (None, None) => return Err(not_limit()),
            (Some(a), Some(b)) if a >= b => return Err(not_limit()),
            _ => {}
        }
        limits.push(Limit { analysis, figure, min, max });
    }
    let analyses = match object.get("analyses") {
        None => Vec::new(),
        // An empty list would be read as no choice: the whole suite.
        Some(list) if list.as_array().is_some_and(Vec::is_empty) => return Err(R::NoAnalyses),
        Some(list) => list
            .as_array()
            .ok_or(R::NotList { key: "analyses".into(), what: "analysis names" })?
            .iter()
            .map(|v| analysis_named(name_in(v, "analyses")?, "analyses"))
            .collect::<Result<_, _>>()?,
    };
    let steps = steps(object)?;
    Ok(Tolerances { pointers, sources, adjustments, limits, analyses, steps })
}

/// Whether a value is a point: three numbers.
fn is_point(v: &Value) -> bool {
    v.as_array().is_some_and(|a| a.len() == 3 && a.iter().all(Value::is_number))
}

impl Tolerances {
    /// The numbers of sample `i` of a Monte Carlo seeded by `seed`, `values` being the numbers' nominal
    /// values ([`Tolerances::pointers`]' order): each source drawn in turn and added to every number it moves
    /// (before any adjustment). Each sample has its own stream, so a sample is the same whichever thread,
    /// process or machine draws it (a study on Ray or Dask from Python draws the command's samples).
    pub fn sample(&self, values: &[f64], seed: u64, i: usize) -> Vec<f64> {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed ^ (i as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15));
        let mut x = values.to_vec();
        for s in &self.sources {
            let d = s.band.draw(&mut rng);
            for &(p, lever) in &s.moves {
                x[p] += lever * d;
            }
        }
        x
    }

    /// The analyses the stack-up runs: those asked for, and those of the figures adjusted or limited (every
    /// analysis when none is asked for).
    pub fn analyses_run(&self) -> Vec<Analysis> {
        if self.analyses.is_empty() {
            return Vec::new();
        }
        let more = self.adjustments.iter().map(|a| a.analysis).chain(self.limits.iter().map(|l| l.analysis));
        distinct(self.analyses.iter().copied().chain(more))
    }
}

/// Each analysis of `analyses` once, in the order first met.
fn distinct(analyses: impl IntoIterator<Item = Analysis>) -> Vec<Analysis> {
    let mut once = Vec::new();
    for a in analyses {
        if !once.contains(&a) {
            once.push(a);
        }
    }
    once
}

impl Limit {
    /// Its ends in SI, for a figure written in `unit`.
    fn in_si(&self, unit: Unit) -> (Option<f64>, Option<f64>) {
        let factor = unit.shown().factor;
        (self.min.map(|a| a / factor), self.max.map(|b| b / factor))
    }
}

/// One source's share of a figure's spread.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contribution {
    /// The source (an index into [`StackUp::sources`]).
    pub source: usize,
    /// The figure's rate times the band's end (its share of the worst case, signed; SI).
    pub worst: f64,
    /// The figure's rate times the band's σ (its share of the standard deviation, signed; SI).
    pub sigma: f64,
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
    /// First order, every source at the end of its band that moves the figure the same way: ±.
    pub worst_case: f64,
    /// First order, the sources independent: the standard deviation.
    pub sigma: f64,
    /// Each source's share, the largest share of the variance first.
    pub contributions: Vec<Contribution>,
    /// Its limit, if the file gives one (in the written unit).
    pub limit: Option<Limit>,
    /// First order, the share of cars outside the limit, the figure taken as normal with σ about its value.
    pub outside: Option<f64>,
    /// By Monte Carlo, when run.
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
    /// With a limit: the share of the samples outside it, and its standard error `√(p(1−p)/n)`.
    pub outside: Option<(f64, f64)>,
}

/// An adjuster's spread: how far the alignment sets it from nominal (the range the adjustment must have).
#[derive(Debug, Clone, PartialEq)]
pub struct AdjusterSpread {
    /// The adjustment.
    pub adjustment: Adjustment,
    /// First order: its set value's worst case, ± about nominal (file units).
    pub worst_case: f64,
    /// First order: its set value's standard deviation (file units).
    pub sigma: f64,
    /// By Monte Carlo, when run: the set values' statistics (file units).
    pub sampled: Option<Sampled>,
}

/// One sample of a Monte Carlo run: its figures (in the order of [`StackUp::spreads`], SI) and the
/// adjusters' values as set (file units), or why it failed.
pub type SampleRun = Result<(Vec<Option<f64>>, Vec<f64>), String>;

/// A stack-up's result.
#[derive(Debug, Clone)]
pub struct StackUp {
    /// The numbers moved and set.
    pub parameters: Parameters,
    /// The sources, as read.
    pub sources: Vec<Source>,
    /// The figures' spreads (those with a value and a derivative for every number), after the adjustments.
    pub spreads: Vec<Spread>,
    /// The adjusters' spreads, in the file's order.
    pub adjusters: Vec<AdjusterSpread>,
    /// Figures left out, with why: `(analysis, figure, why)`.
    pub left_out: Vec<(String, String, String)>,
    /// Analyses that failed.
    pub failed: Vec<Failed>,
    /// The Monte Carlo's samples, in order, when run.
    pub samples: Vec<SampleRun>,
    /// Samples of the Monte Carlo run that failed (a model that would not build or solve), with why.
    pub failed_samples: Vec<String>,
    /// How the analyses were run (their load steps): the Monte Carlo's samples are run alike.
    pub settings: Settings,
    /// What the analyses warned of on the model as it is (a toe beyond ±10° over the travel, an error
    /// estimate over the tolerance): the spreads are of those results.
    pub warnings: Vec<kc::Warning>,
    /// The stack-up asked for.
    tolerances: Tolerances,
    /// Per adjustment: the rates of its figure and the adjusters' first-order solve (`A⁻¹`, adjusters ×
    /// figures), and the adjusted figures' nominal values and first-order σ before adjustment.
    alignment: Alignment,
}

/// What the Monte Carlo's alignment needs of the first order.
#[derive(Debug, Clone, Default)]
struct Alignment {
    /// `A⁻¹`: the adjusters' moves per miss of the adjusted figures (adjusters × figures).
    inverse: Vec<Vec<f64>>,
    /// The adjusted figures' nominal values (SI).
    nominal: Vec<f64>,
    /// The adjusted figures' first-order σ before adjustment (SI): what the alignment's residual is
    /// measured against.
    sigma: Vec<f64>,
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
        /// The source it is of.
        pointer: String,
        /// The analysis of the figure.
        analysis: &'static str,
        /// The figure's key.
        figure: String,
    },
    /// A figure adjusted or limited that the stack-up has no spread of.
    #[error("{key}: {analysis} has no spread of '{figure}': {why}")]
    NoFigure {
        /// The key of the file it is named at.
        key: String,
        /// The analysis.
        analysis: &'static str,
        /// The figure's key.
        figure: String,
        /// Why.
        why: String,
    },
    /// Adjusters that cannot set their figures (one moves none of them, or two move them alike).
    #[error(
        "adjust: the numbers given do not set their figures independently ({which} moves {figure} by nothing the \
         others do not): give for each figure a number that moves it"
    )]
    Unadjustable {
        /// The adjuster.
        which: String,
        /// Its figure.
        figure: String,
    },
}

/// The share of a normal distribution of mean `mean` and deviation `sigma` outside `[min, max]`.
fn outside_normal(mean: f64, sigma: f64, min: Option<f64>, max: Option<f64>) -> f64 {
    // A tail beyond `d` deviations: ½ erfc(d/√2).
    let tail = |d: f64| 0.5 * libm::erfc(d / std::f64::consts::SQRT_2);
    let below = min.map_or(0.0, |a| if sigma > 0.0 { tail((mean - a) / sigma) } else { f64::from(mean < a) });
    let above = max.map_or(0.0, |b| if sigma > 0.0 { tail((b - mean) / sigma) } else { f64::from(mean > b) });
    (below + above).min(1.0)
}

/// `m⁻¹` by LU with partial pivoting, or the first column whose pivot vanishes (a column no combination of
/// the columns before it leaves room for).
fn inverse(m: &[Vec<f64>]) -> Result<Vec<Vec<f64>>, usize> {
    let n = m.len();
    let a = nalgebra::DMatrix::from_fn(n, n, |i, j| m[i][j]);
    let scale = a.amax();
    let lu = a.lu();
    let u = lu.u();
    if let Some(c) = (0..n).find(|&c| u[(c, c)].is_nan() || u[(c, c)].abs() <= 1e-12 * scale) {
        return Err(c);
    }
    let inverse = lu.try_inverse().ok_or(0usize)?;
    Ok((0..n).map(|i| (0..n).map(|j| inverse[(i, j)]).collect()).collect())
}

/// The first-order stack-up of `tolerances` on the model `document`. Refused, naming the number: a band that
/// spreads a figure beyond any finite number; naming the key: a figure adjusted or limited that has no
/// spread, adjusters that cannot set their figures.
pub fn stack_up(document: &Value, tolerances: &Tolerances) -> Result<StackUp, StackUpError> {
    let parameters = Parameters::new(document, &tolerances.pointers)?;
    // Spreads are of figures: the rows are read as far as the figures read them.
    let settings =
        sensitivity_settings(&Settings { steps: tolerances.steps, figures_only: true, ..Settings::default() });
    let suite: SuiteSensitivity = suite_sensitivity(&parameters, &tolerances.analyses_run(), &settings)?;
    // Every figure with a value and every rate: (analysis, figure, unit, value, rates per parameter).
    let (mut figures, mut left_out) = (Vec::new(), Vec::new());
    for a in &suite.analyses {
        for (j, figure) in a.report.figures.iter().enumerate() {
            let analysis = a.report.analysis;
            let Some(value) = figure.value else { continue };
            match a.figures.iter().map(|d| d[j]).collect::<Result<Vec<_>, _>>() {
                Ok(rates) => {
                    let (rates, errors): (Vec<f64>, Vec<f64>) = rates.iter().map(|d| (d.value, d.error)).unzip();
                    figures.push((analysis, figure.key.clone(), figure.unit, value, rates, errors))
                }
                Err(e) => left_out.push((analysis.name().to_string(), figure.key.clone(), e.reason().to_string())),
            }
        }
    }
    let find = |key: String, analysis: Analysis, figure: &str| -> Result<usize, StackUpError> {
        figures.iter().position(|f| f.0 == analysis && f.1 == figure).ok_or_else(|| {
            let why = left_out
                .iter()
                .find(|l| l.0 == analysis.name() && l.1 == figure)
                .map(|l| l.2.clone())
                .or_else(|| suite.failed.iter().find(|f| f.analysis == analysis).map(|f| f.reason.clone()))
                .unwrap_or_else(|| {
                    "it gives no such figure with a value on this model (the keys: docs/figures.md)".into()
                });
            StackUpError::NoFigure { key, analysis: analysis.name(), figure: figure.into(), why }
        })
    };
    // Each figure's rate per source: the sum of the rates of the numbers it moves, each times its lever.
    let by_source = |rates: &[f64]| -> Vec<f64> {
        tolerances.sources.iter().map(|s| s.moves.iter().map(|&(p, lever)| lever * rates[p]).sum()).collect()
    };
    // The alignment: the adjusted figures' rates per adjuster `A` and per source `B`; every figure's rates
    // per source lose their part through the adjusters, `g − g_a A⁻¹ B`.
    let adjusted: Vec<usize> = tolerances
        .adjustments
        .iter()
        .enumerate()
        .map(|(k, a)| find(format!("adjust[{k}].figure"), a.analysis, &a.figure))
        .collect::<Result<_, _>>()?;
    let by_adjuster = |rates: &[f64]| -> Vec<f64> { tolerances.adjustments.iter().map(|a| rates[a.by]).collect() };
    // A rate within ten times its error estimate is no rate: noise an adjuster cannot set its figure by.
    let a_matrix: Vec<Vec<f64>> = adjusted
        .iter()
        .map(|&f| {
            let errors = by_adjuster(&figures[f].5);
            by_adjuster(&figures[f].4)
                .iter()
                .zip(errors)
                .map(|(r, e)| if r.abs() > 10.0 * e { *r } else { 0.0 })
                .collect()
        })
        .collect();
    let a_inverse = inverse(&a_matrix).map_err(|c| {
        let adjustment = &tolerances.adjustments[c];
        StackUpError::Unadjustable {
            which: format!("'{}'", tolerances.pointers[adjustment.by]),
            figure: format!("{} {}", adjustment.analysis.name(), adjustment.figure),
        }
    })?;
    let b_matrix: Vec<Vec<f64>> = adjusted.iter().map(|&f| by_source(&figures[f].4)).collect();
    // The adjusters' moves per source: `−A⁻¹ B` (adjusters × sources).
    let sources_n = tolerances.sources.len();
    let moves: Vec<Vec<f64>> = a_inverse
        .iter()
        .map(|row| (0..sources_n).map(|s| -row.iter().zip(&b_matrix).map(|(x, b)| x * b[s]).sum::<f64>()).collect())
        .collect();
    let spread_of = |rates: &[f64]| -> (f64, f64) {
        let w = rates.iter().zip(&tolerances.sources).map(|(r, s)| (r * s.band.end()).abs()).sum();
        let v: f64 = rates.iter().zip(&tolerances.sources).map(|(r, s)| (r * s.band.sigma()).powi(2)).sum();
        (w, v.sqrt())
    };
    let alignment = Alignment {
        inverse: a_inverse,
        nominal: adjusted.iter().map(|&f| figures[f].3).collect(),
        sigma: b_matrix.iter().map(|b| spread_of(b).1).collect(),
    };
    let mut spreads = Vec::new();
    for (analysis, figure, unit, value, rates, _) in &figures {
        let mut g = by_source(rates);
        for (j, adjuster_rate) in by_adjuster(rates).iter().enumerate() {
            g.iter_mut().zip(&moves[j]).for_each(|(g, m)| *g += adjuster_rate * m);
        }
        let (worst_case, sigma) = spread_of(&g);
        let mut contributions: Vec<Contribution> = g
            .iter()
            .zip(&tolerances.sources)
            .enumerate()
            .map(|(source, (r, s))| Contribution { source, worst: r * s.band.end(), sigma: r * s.band.sigma() })
            .collect();
        contributions.sort_by(|a, b| b.sigma.abs().total_cmp(&a.sigma.abs()));
        // A band no part is made to spreads the figure past any number: refused by the source it is of.
        if !(worst_case.is_finite() && sigma.is_finite()) {
            let s = &tolerances.sources[contributions[0].source];
            return Err(StackUpError::Unbounded {
                band: s.band.width(),
                pointer: s.name.clone(),
                analysis: analysis.name(),
                figure: figure.clone(),
            });
        }
        spreads.push(Spread {
            analysis: *analysis,
            figure: figure.clone(),
            unit: *unit,
            value: *value,
            worst_case,
            sigma,
            contributions,
            limit: None,
            outside: None,
            sampled: None,
        });
    }
    for limit in &tolerances.limits {
        let k = find(format!("limits[\"{}/{}\"]", limit.analysis.name(), limit.figure), limit.analysis, &limit.figure)?;
        let s = &mut spreads[k];
        let (min, max) = limit.in_si(s.unit);
        s.outside = Some(outside_normal(s.value, s.sigma, min, max));
        s.limit = Some(limit.clone());
    }
    // An adjuster is set to its draw (if a source moves it) and then moved: its offset from nominal.
    let adjusters = tolerances
        .adjustments
        .iter()
        .zip(&moves)
        .map(|(adjustment, m)| {
            let set: Vec<f64> = tolerances
                .sources
                .iter()
                .zip(m)
                .map(|(s, m)| {
                    m + s.moves.iter().filter(|(p, _)| *p == adjustment.by).map(|(_, lever)| lever).sum::<f64>()
                })
                .collect();
            let (worst_case, sigma) = spread_of(&set);
            AdjusterSpread { adjustment: adjustment.clone(), worst_case, sigma, sampled: None }
        })
        .collect();
    let warnings = suite.analyses.iter().flat_map(|a| a.report.warnings.iter().cloned()).collect();
    Ok(StackUp {
        parameters,
        sources: tolerances.sources.clone(),
        spreads,
        adjusters,
        left_out,
        failed: suite.failed,
        samples: Vec::new(),
        failed_samples: Vec::new(),
        settings,
        warnings,
        tolerances: tolerances.clone(),
        alignment,
    })
}

/// How many times the alignment sets its adjusters on a sample at most: a chord iteration on the nominal
/// rates, which meets a figure linear in its adjuster at once and a smooth one in two or three.
const ALIGNMENT_ITERATIONS: usize = 12;

/// The alignment's residual, over the adjusted figure's first-order σ before adjustment, within which the
/// figure counts as back at nominal (or, for a figure the sources do not move, over its value).
const ALIGNED: f64 = 1e-6;

/// The statistics of `v`, with its share outside `[min, max]` (SI) when limited; `None` for fewer than two.
fn statistics(v: &[f64], limit: Option<(Option<f64>, Option<f64>)>) -> Option<Sampled> {
    if v.len() < 2 {
        return None;
    }
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / (n - 1.0);
    let (min, max) = v.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(*x), b.max(*x)));
    let outside = limit.map(|(a, b)| {
        let out = v.iter().filter(|x| a.is_some_and(|a| **x < a) || b.is_some_and(|b| **x > b)).count() as f64;
        let p = out / n;
        (p, (p * (1.0 - p) / n).sqrt())
    });
    Some(Sampled { sigma: var.sqrt(), mean, min, max, count: v.len(), outside })
}

impl StackUp {
    /// The source `k` in words.
    pub fn source_words(&self, k: usize) -> &str {
        &self.sources[k].words
    }

    /// Checks the first-order spreads by Monte Carlo: `samples` models, each source drawn within its band
    /// (seeded by `seed`, so a run is repeated exactly), each aligned (its adjusters set until their figures
    /// are back at nominal) and run on rayon's threads as the first order's analyses were; the samples'
    /// spread of every figure and adjuster, and their share outside each limit, kept beside the first order's.
    pub fn monte_carlo(&mut self, samples: usize, seed: u64) {
        // The analyses the spreads are of, each once; the samples read their figures alone, so no error
        // estimate (a Newton iteration more per row).
        let which = distinct(self.spreads.iter().map(|s| s.analysis));
        if which.is_empty() {
            return;
        }
        let settings = Settings { error_estimate: false, ..self.settings };
        let runs: Vec<SampleRun> = (0..samples)
            .into_par_iter()
            .map(|i| self.run_sample(&which, &settings, seed, i).map_err(|e| format!("sample {i}: {e}")))
            .collect();
        self.failed_samples = runs.iter().filter_map(|r| r.as_ref().err().cloned()).collect();
        let values: Vec<&(Vec<Option<f64>>, Vec<f64>)> = runs.iter().filter_map(|r| r.as_ref().ok()).collect();
        for (j, s) in self.spreads.iter_mut().enumerate() {
            let v: Vec<f64> = values.iter().filter_map(|r| r.0[j]).collect();
            let limit = s.limit.as_ref().map(|l| l.in_si(s.unit));
            s.sampled = statistics(&v, limit);
        }
        for (k, a) in self.adjusters.iter_mut().enumerate() {
            let nominal = self.parameters.values[a.adjustment.by];
            let v: Vec<f64> = values.iter().map(|r| r.1[k] - nominal).collect();
            a.sampled = statistics(&v, None);
        }
        self.samples = runs;
    }

    /// Sample `i`: drawn, aligned, run; its figures in the order of the spreads and its adjusters' values.
    fn run_sample(&self, which: &[Analysis], settings: &Settings, seed: u64, i: usize) -> SampleRun {
        let mut x = self.tolerances.sample(&self.parameters.values, seed, i);
        let adjustments = &self.tolerances.adjustments;
        let run = |x: &[f64], analyses: &mut dyn Iterator<Item = Analysis>| -> Result<Vec<AnalysisReport>, String> {
            let file = self.parameters.at(x).and_then(|p| p.file()).map_err(|e| e.to_string())?;
            let models = kc::Models::owning(file);
            analyses.map(|a| kc::run_on(a, &models, settings).map_err(|e| e.to_string())).collect()
        };
        let mut adjusted_reports: Vec<AnalysisReport> = Vec::new();
        if !adjustments.is_empty() {
            let adjusted = distinct(adjustments.iter().map(|a| a.analysis));
            let mut aligned = false;
            for _ in 0..ALIGNMENT_ITERATIONS {
                adjusted_reports = run(&x, &mut adjusted.iter().copied())?;
                let misses: Vec<f64> = adjustments
                    .iter()
                    .zip(&self.alignment.nominal)
                    .map(|(a, nominal)| {
                        let r = adjusted_reports.iter().find(|r| r.analysis == a.analysis);
                        let value = r.and_then(|r| r.figure(&a.figure)).and_then(|f| f.value);
                        value.map(|v| v - nominal).ok_or_else(|| {
                            format!("{} {} has no value, so the alignment cannot set it", a.analysis.name(), a.figure)
                        })
                    })
                    .collect::<Result<_, _>>()?;
                aligned = misses.iter().zip(&self.alignment.sigma).zip(&self.alignment.nominal).all(
                    |((miss, sigma), nominal)| {
                        miss.abs() <= ALIGNED * sigma.max(1e-9 * nominal.abs()).max(f64::MIN_POSITIVE)
                    },
                );
                if aligned {
                    break;
                }
                for (row, a) in self.alignment.inverse.iter().zip(adjustments) {
                    x[a.by] -= row.iter().zip(&misses).map(|(r, m)| r * m).sum::<f64>();
                }
            }
            if !aligned {
                let names: Vec<String> =
                    adjustments.iter().map(|a| format!("{} {}", a.analysis.name(), a.figure)).collect();
                return Err(format!(
                    "the alignment did not bring {} back to nominal in {ALIGNMENT_ITERATIONS} settings",
                    names.join(" and ")
                ));
            }
        }
        let rest: Vec<Analysis> =
            which.iter().copied().filter(|a| !adjusted_reports.iter().any(|r| r.analysis == *a)).collect();
        let mut reports = run(&x, &mut rest.into_iter())?;
        reports.extend(adjusted_reports);
        let figures = self
            .spreads
            .iter()
            .map(|s| reports.iter().find(|r| r.analysis == s.analysis)?.figure(&s.figure)?.value)
            .collect();
        Ok((figures, adjustments.iter().map(|a| x[a.by]).collect()))
    }

    /// `tolerance.csv`: one row per figure — its value, first-order worst case and standard deviation,
    /// the Monte Carlo's when run, its limit and the share of cars outside it, and its three largest
    /// contributors, in the figure's written unit.
    pub fn table(&self) -> Table {
        // A number of the figure in SI, written in the figure's unit.
        let shown = |s: &Spread, v: Option<f64>| Cell::from(v.map(|v| v * s.unit.shown().factor));
        let sampled = |f: fn(Sampled) -> f64| move |s: &Spread| shown(s, s.sampled.map(f));
        let outside = |f: fn((f64, f64)) -> f64| move |s: &Spread| Cell::from(s.sampled.and_then(|m| m.outside).map(f));
        let mut columns: Vec<Column<Spread>> = vec![
            Column::new("analysis", |s: &Spread| Cell::Text(s.analysis.name().into())),
            Column::new("figure", |s: &Spread| Cell::Text(s.figure.clone())),
            Column::new("unit", |s: &Spread| Cell::Text(s.unit.shown().symbol.into())),
            Column::new("value", move |s: &Spread| shown(s, Some(s.value))),
            Column::new("worst_case", move |s: &Spread| shown(s, Some(s.worst_case))),
            Column::new("sigma", move |s: &Spread| shown(s, Some(s.sigma))),
            Column::new("sampled_sigma", sampled(|m| m.sigma)),
            Column::new("sampled_mean", sampled(|m| m.mean)),
            Column::new("sampled_min", sampled(|m| m.min)),
            Column::new("sampled_max", sampled(|m| m.max)),
            Column::new("samples", |s: &Spread| Cell::from(s.sampled.map(|m| m.count as f64))),
            Column::new("limit_min", |s: &Spread| Cell::from(s.limit.as_ref().and_then(|l| l.min))),
            Column::new("limit_max", |s: &Spread| Cell::from(s.limit.as_ref().and_then(|l| l.max))),
            Column::new("outside", |s: &Spread| Cell::from(s.outside)),
            Column::new("sampled_outside", outside(|o| o.0)),
            Column::new("sampled_outside_error", outside(|o| o.1)),
        ];
        for (k, name) in ["first_contributor", "second_contributor", "third_contributor"].into_iter().enumerate() {
            columns.push(Column::new(name, move |s: &Spread| {
                s.contributions.get(k).map_or(Cell::Empty, |c| {
                    let w = kc::significant(c.worst * s.unit.shown().factor, 3);
                    Cell::Text(format!("{} ({w})", self.sources[c.source].name))
                })
            }));
        }
        Table::of_columns("tolerance", &columns, &self.spreads)
    }

    /// `tolerance_contributions.csv`: every figure and source — the source's distribution and band (file
    /// units), the figure's rate times the band's end (its first-order share of the worst case, signed) and
    /// times its σ, in the figure's written unit, and its share of the figure's variance.
    pub fn contribution_table(&self) -> Table {
        type Row<'s> = (&'s Spread, Contribution);
        let in_unit = |(s, _): &Row, v: f64| Cell::from(v * s.unit.shown().factor);
        let columns: [Column<Row>; 9] = [
            Column::new("analysis", |(s, _): &Row| Cell::Text(s.analysis.name().into())),
            Column::new("figure", |(s, _): &Row| Cell::Text(s.figure.clone())),
            Column::new("unit", |(s, _): &Row| Cell::Text(s.unit.shown().symbol.into())),
            Column::new("source", |(_, c): &Row| Cell::Text(self.sources[c.source].name.clone())),
            Column::new("distribution", |(_, c): &Row| Cell::Text(self.sources[c.source].band.distribution().into())),
            Column::new("tolerance", |(_, c): &Row| Cell::from(self.sources[c.source].band.width())),
            Column::new("contribution", move |r: &Row| in_unit(r, r.1.worst)),
            Column::new("sigma_contribution", move |r: &Row| in_unit(r, r.1.sigma)),
            Column::new("variance_share", |(s, c): &Row| {
                Cell::from((s.sigma > 0.0).then(|| (c.sigma / s.sigma).powi(2)))
            }),
        ];
        let mut rows: Vec<Row> = Vec::new();
        for s in &self.spreads {
            let mut by_source = s.contributions.clone();
            by_source.sort_by_key(|c| c.source);
            rows.extend(by_source.into_iter().map(|c| (s, c)));
        }
        Table::of_columns("tolerance_contributions", &columns, &rows)
    }

    /// `tolerance_adjustments.csv`: per adjustment, the figure it holds, the number that sets it and how far
    /// from nominal the alignment sets it (first order and sampled, file units); `None` without adjustments.
    pub fn adjustment_table(&self) -> Option<Table> {
        if self.adjusters.is_empty() {
            return None;
        }
        let sampled = |f: fn(Sampled) -> f64| move |a: &AdjusterSpread| Cell::from(a.sampled.map(f));
        let columns: [Column<AdjusterSpread>; 9] = [
            Column::new("analysis", |a: &AdjusterSpread| Cell::Text(a.adjustment.analysis.name().into())),
            Column::new("figure", |a: &AdjusterSpread| Cell::Text(a.adjustment.figure.clone())),
            Column::new("by", |a: &AdjusterSpread| Cell::Text(self.parameters.pointers[a.adjustment.by].clone())),
            Column::new("nominal", |a: &AdjusterSpread| Cell::from(self.parameters.values[a.adjustment.by])),
            Column::new("worst_case", |a: &AdjusterSpread| Cell::from(a.worst_case)),
            Column::new("sigma", |a: &AdjusterSpread| Cell::from(a.sigma)),
            Column::new("sampled_sigma", sampled(|m| m.sigma)),
            Column::new("sampled_min", sampled(|m| m.min)),
            Column::new("sampled_max", sampled(|m| m.max)),
        ];
        Some(Table::of_columns("tolerance_adjustments", &columns, &self.adjusters))
    }

    /// `tolerance_samples.csv`: one row per sample of the Monte Carlo — every figure (`analysis/figure`, in
    /// its written unit), the adjusters as set (file units, by pointer) and why it failed; `None` when none
    /// was run.
    pub fn sample_table(&self) -> Option<Table> {
        if self.samples.is_empty() {
            return None;
        }
        let mut columns = vec!["sample".to_string()];
        columns.extend(self.spreads.iter().map(|s| kc::figure_column(s.analysis, &s.figure, s.unit)));
        columns.extend(self.adjusters.iter().map(|a| self.parameters.pointers[a.adjustment.by].clone()));
        columns.push("error".into());
        let width = columns.len();
        let rows = self
            .samples
            .iter()
            .enumerate()
            .map(|(i, r)| {
                let mut row = vec![Cell::from(i as f64)];
                match r {
                    Ok((figures, adjusters)) => {
                        row.extend(
                            figures
                                .iter()
                                .zip(&self.spreads)
                                .map(|(v, s)| Cell::from(v.map(|v| v * s.unit.shown().factor))),
                        );
                        row.extend(adjusters.iter().map(|v| Cell::from(*v)));
                        row.push(Cell::Empty);
                    }
                    Err(e) => {
                        row.resize(width - 1, Cell::Empty);
                        row.push(Cell::Text(e.clone()));
                    }
                }
                row
            })
            .collect();
        Some(Table { name: "tolerance_samples".into(), columns, rows })
    }

    /// Figure `j`'s sampled values (SI), in sample order, those with a value.
    pub fn sampled_values(&self, j: usize) -> Vec<f64> {
        self.samples.iter().filter_map(|r| r.as_ref().ok()?.0[j]).collect()
    }
}
