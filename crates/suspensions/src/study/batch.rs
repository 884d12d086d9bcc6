//! Design variants of one model (`elastokin batch MODEL VARIANTS`): edits of the model file by JSON pointer,
//! each variant judged by its bump steer, camber gain and wheel rate at design, and, when asked, by every
//! figure of analyses of the K&C suite ([`evaluate_suite`]).
//!
//! A variants file has one variant per line: an optional `name:` and then `pointer=value` edits separated
//! by `;`, where `pointer` is a JSON pointer into the model file and `value` is JSON. Blank lines and lines
//! starting with `#` are skipped.
//!
//! ```text
//! # raise the inner tie-rod point by 10 mm
//! tie rod up: /suspension/macpherson/hardpoints/tie_rod_inner/2=-0.049
//! soft spring: /suspension/macpherson/spring/rate=20000
//! ```

use crate::analysis::{parallel_wheel_travel_with, SweepExtras};
use crate::assembly::Rig;
use crate::description::Side;
use crate::document::DocumentError;
use crate::file::SuspensionFile;
use crate::kc::{self, Analysis, Figure, Unit};
use elastokin_core::ModelError;
use elastokin_solver::{Mode, SolverError};
use std::sync::Arc;

/// Each variant walks parallel wheel travel ±`HALF_RANGE` (m)…
pub const HALF_RANGE: f64 = 0.02;
/// …in `STEPS` steps (even, so design is a step).
pub const STEPS: usize = 8;
/// The most variants a file may hold: each is a sweep of its own, and all results are kept until the
/// table is written.
pub const MAX_VARIANTS: usize = 10_000;

/// Why a variants file is not read: a wrong line, too many variants, none.
#[derive(Debug, Clone, thiserror::Error)]
pub enum VariantsError {
    /// A line that is no variant ([`parse_variants`]).
    #[error(transparent)]
    Line(#[from] LineError),
    /// Every wrong line of the file, the first [`WRONG_LINES_LISTED`] listed and the rest counted
    /// ([`read_and_apply`]).
    #[error("{}", wrong_lines(lines, *more))]
    WrongLines {
        /// The wrong lines listed.
        lines: Vec<LineError>,
        /// How many more there are.
        more: usize,
    },
    /// More variants than a batch runs.
    #[error(
        "{place}: more than {most} variants; split the file and run a batch for each part (or run them as a \
         study from Python, which splits them itself)"
    )]
    TooMany {
        /// The file and line of the first variant too many.
        place: String,
        /// The most a batch runs.
        most: usize,
    },
    /// No variant at all.
    #[error("{origin}: no variants (one per line: name: /json/pointer=value; …)")]
    NoVariants {
        /// The file.
        origin: String,
    },
}

/// The wrong lines one per line, and how many more there are.
fn wrong_lines(lines: &[LineError], more: usize) -> String {
    let mut text: Vec<String> = lines.iter().map(ToString::to_string).collect();
    if more > 0 {
        text.push(format!("… and {more} more wrong lines"));
    }
    text.join("\n")
}

/// A line of a variants file that is no variant, at its place (the file and line).
#[derive(Debug, Clone, thiserror::Error)]
#[error("{place}: {refusal}")]
pub struct LineError {
    /// The file and line.
    pub place: String,
    /// What is wrong with it.
    pub refusal: LineRefusal,
}

/// What is wrong with a line of a variants file.
#[derive(Debug, Clone, thiserror::Error)]
pub enum LineRefusal {
    /// An edit without `=`.
    #[error("'{edit}' is not pointer=value")]
    NotEdit {
        /// The edit as written.
        edit: String,
    },
    /// A value that is no JSON.
    #[error("value of '{pointer}' is not JSON: {error}")]
    NotJson {
        /// The edit's pointer.
        pointer: String,
        /// What the JSON reader says.
        error: String,
    },
    /// A labelled line with no edit.
    #[error("no edits in '{line}'")]
    NoEdits {
        /// The line, trimmed.
        line: String,
    },
    /// A variant that makes no model of the base.
    #[error(transparent)]
    Variant(VariantError),
}

/// One parsed variant: its name and its edits.
#[derive(Debug, Clone, PartialEq)]
pub struct Variant {
    /// Name (the line's label, or `line N`).
    pub name: String,
    /// `(JSON pointer, value)` edits.
    pub edits: Vec<(String, serde_json::Value)>,
}

/// Parses a variants file of at most [`MAX_VARIANTS`] variants; errors name the line.
pub fn parse_variants(text: &str, origin: &str) -> Result<Vec<Variant>, VariantsError> {
    parse_variants_at_most(text, origin, Some(MAX_VARIANTS))
}

/// Parses a variants file of at most `most` variants (`None`: any number, for a study that splits them into
/// batches itself); errors name the line.
pub fn parse_variants_at_most(text: &str, origin: &str, most: Option<usize>) -> Result<Vec<Variant>, VariantsError> {
    let mut out = Vec::new();
    for (k, raw) in text.lines().enumerate() {
        let place = format!("{origin}:{}", k + 1);
        let Some(variant) = parse_variant(raw, &format!("line {}", k + 1), &place)? else {
            continue;
        };
        if let Some(most) = most.filter(|&most| out.len() == most) {
            return Err(VariantsError::TooMany { place, most });
        }
        out.push(variant);
    }
    if out.is_empty() {
        return Err(VariantsError::NoVariants { origin: origin.to_string() });
    }
    Ok(out)
}

/// How many wrong lines of a variants file [`read_and_apply`] lists; it counts the rest.
const WRONG_LINES_LISTED: usize = 20;

/// Reads a variants file of at most [`MAX_VARIANTS`] variants and applies each to `base` ([`apply`]), as
/// `elastokin batch` runs them: the variants and their models, or every wrong line (one that is no variant,
/// or one whose variant edits a key the model lacks or makes no model), each with its line, the first
/// [`WRONG_LINES_LISTED`] listed and the rest counted, so that one reading finds them all.
pub fn read_and_apply(
    base: &serde_json::Value,
    text: &str,
    origin: &str,
) -> Result<(Vec<Variant>, Vec<SuspensionFile>), VariantsError> {
    let (mut variants, mut files, mut wrong) = (Vec::new(), Vec::new(), Vec::new());
    for (k, raw) in text.lines().enumerate() {
        let place = format!("{origin}:{}", k + 1);
        let variant = match parse_variant(raw, &format!("line {}", k + 1), &place) {
            Ok(Some(variant)) => variant,
            Ok(None) => continue,
            Err(e) => {
                wrong.push(e);
                continue;
            }
        };
        if variants.len() + wrong.len() == MAX_VARIANTS {
            return Err(VariantsError::TooMany { place, most: MAX_VARIANTS });
        }
        match apply(base, &variant) {
            Ok(file) => {
                variants.push(variant);
                files.push(file);
            }
            Err(e) => wrong.push(LineError { place, refusal: LineRefusal::Variant(e) }),
        }
    }
    if !wrong.is_empty() {
        let more = wrong.len().saturating_sub(WRONG_LINES_LISTED);
        wrong.truncate(WRONG_LINES_LISTED);
        return Err(VariantsError::WrongLines { lines: wrong, more });
    }
    if variants.is_empty() {
        return Err(VariantsError::NoVariants { origin: origin.to_string() });
    }
    Ok((variants, files))
}

/// One line of a variants file: `None` for a blank line or a `#` comment. A line without a `name:` label is
/// named `unnamed`; errors start with `place` (the file and line).
pub fn parse_variant(line: &str, unnamed: &str, place: &str) -> Result<Option<Variant>, LineError> {
    let line = line.trim();
    if line.is_empty() || line.starts_with('#') {
        return Ok(None);
    }
    let (name, body) = match line.split_once(':') {
        Some((n, b)) if !n.trim_start().starts_with('/') => (n.trim().to_string(), b),
        _ => (unnamed.to_string(), line),
    };
    let mut edits = Vec::new();
    for edit in body.split(';').map(str::trim).filter(|e| !e.is_empty()) {
        let refused = |refusal| LineError { place: place.to_string(), refusal };
        let (pointer, value) =
            edit.split_once('=').ok_or_else(|| refused(LineRefusal::NotEdit { edit: edit.to_string() }))?;
        let value: serde_json::Value = serde_json::from_str(value.trim())
            .map_err(|e| refused(LineRefusal::NotJson { pointer: pointer.trim().to_string(), error: e.to_string() }))?;
        edits.push((pointer.trim().to_string(), value));
    }
    if edits.is_empty() {
        return Err(LineError { place: place.to_string(), refusal: LineRefusal::NoEdits { line: line.to_string() } });
    }
    Ok(Some(Variant { name, edits }))
}

/// The model file's text as the document the variants edit: the file as written (a Project Chrono file's own
/// keys, its comments removed).
pub fn base_document(text: &str, origin: &str) -> Result<serde_json::Value, BaseDocumentError> {
    let text = crate::import::chrono::without_comments(text);
    let document = serde_json::from_str(&text)
        .map_err(|e| BaseDocumentError::Json { origin: origin.to_string(), error: e.to_string() })?;
    // Read as a value, a key given twice would be one of the two silently.
    match crate::file::key_path::first_duplicate_key(&text) {
        Some(keys) => Err(BaseDocumentError::KeyTwice { origin: origin.to_string(), keys }),
        None => Ok(document),
    }
}

/// Why a model file's text is no document for variants to edit ([`base_document`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BaseDocumentError {
    /// The text is no JSON.
    #[error("{origin}: {error}")]
    Json {
        /// The file.
        origin: String,
        /// What the JSON reader says, with its line and column.
        error: String,
    },
    /// A key given twice.
    #[error("{origin}: {}: the key is given twice: give each key once", keys.join("."))]
    KeyTwice {
        /// The file.
        origin: String,
        /// The keys that lead to it, outermost first.
        keys: Vec<String>,
    },
}

/// The base model with a variant's edits applied; an edit to a pointer the model lacks is an error. A
/// Project Chrono suspension file (the pointers then name its own keys: `/Spring/Spring Coefficient`) is read
/// after the edits, as `run` reads it.
pub fn apply(base: &serde_json::Value, v: &Variant) -> Result<SuspensionFile, VariantError> {
    let mut doc = base.clone();
    for (pointer, value) in &v.edits {
        *doc.pointer_mut(pointer).ok_or_else(|| no_such_key(v, pointer))? = value.clone();
    }
    let text = serde_json::to_string(&doc).map_err(|e| VariantError::Json(Arc::new(e)))?;
    // The edited model is no file the user has: its errors name keys, not a line and column of it. Its kind
    // is read off the document in hand (parsing its text again to tell cost a fifth of this function).
    let chrono = crate::import::chrono::is_chrono_document(&doc);
    crate::document::parse_document_of_kind(&text, chrono, &format!("variant '{}'", v.name))
        .map(|(file, _)| file)
        .map_err(|e| VariantError::Model(Arc::new(e)))
}

/// Refuses a variant that edits a key the base model lacks, as [`apply`] does, without reading the model: a
/// study checks its whole table so before it sends any of it away.
pub fn check_keys(base: &serde_json::Value, v: &Variant) -> Result<(), VariantError> {
    match v.edits.iter().find(|(pointer, _)| base.pointer(pointer).is_none()) {
        Some((pointer, _)) => Err(no_such_key(v, pointer)),
        None => Ok(()),
    }
}

fn no_such_key(v: &Variant, pointer: &str) -> VariantError {
    VariantError::NoKey { variant: v.name.clone(), pointer: pointer.to_string() }
}

/// Why a variant makes no model: an edit of a key the model lacks, or the edited model refused as a model
/// document is (its errors naming the variant).
#[derive(Debug, Clone, thiserror::Error)]
pub enum VariantError {
    /// An edit of a key the base model lacks.
    #[error("variant '{variant}': the model has no '{pointer}'")]
    NoKey {
        /// The variant's name.
        variant: String,
        /// The edit's pointer.
        pointer: String,
    },
    /// The edited document could not be written as text to be read, in the JSON writer's words.
    #[error("{0}")]
    Json(Arc<serde_json::Error>),
    /// The edited model refused by its reader.
    #[error(transparent)]
    Model(Arc<DocumentError>),
}

/// Why a variant's model, read, did not run ([`evaluate`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum VariantFailed {
    /// Its model could not be built.
    #[error(transparent)]
    Model(#[from] ModelError),
    /// Its sweep or the reading at design failed.
    #[error(transparent)]
    Solver(#[from] SolverError),
    /// An analysis of the suite failed on it.
    #[error(transparent)]
    Analysis(#[from] kc::AnalysisError),
}

/// Headline figures of one variant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Outcome {
    /// Bump steer at design, deg per metre of travel.
    pub bump_steer: f64,
    /// Camber gain at design, deg per metre.
    pub camber_gain: f64,
    /// Wheel rate at design, N/m.
    pub wheel_rate: f64,
}

/// The names of a variant's figures, in the order of [`Outcome::figures`]: batch.csv's columns, and the
/// keys every front end gives them.
pub const FIGURES: [&str; 3] = ["bump_steer_deg_per_m", "camber_gain_deg_per_m", "wheel_rate_n_per_m"];

impl Outcome {
    /// The figures in the order [`FIGURES`] names them.
    pub fn figures(&self) -> [f64; 3] {
        [self.bump_steer, self.camber_gain, self.wheel_rate]
    }
}

/// Runs one variant: parallel travel ±`half_range` in `steps` (even) steps, its figures the rates at design
/// read off the path there, as the K&C suite reads them.
pub fn evaluate(file: &SuspensionFile, half_range: f64, steps: usize) -> Result<Outcome, VariantFailed> {
    let corner = file.suspension.build(Side::Left, Rig::WheelTravel)?;
    let extras = SweepExtras { at_design: Some(0.0), ..SweepExtras::default() };
    let out = parallel_wheel_travel_with(&corner, -half_range, half_range, steps, Mode::Corrected, extras)?;
    let design = match out.design {
        Some(Ok(design)) => design,
        Some(Err(e)) => return Err(e.into()),
        None => unreachable!("the design is asked for"),
    };
    Ok(Outcome {
        bump_steer: design.rate(|r| r.attitude.toe.to_degrees()),
        camber_gain: design.rate(|r| r.attitude.camber.to_degrees()),
        wheel_rate: design.rate(|r| r.wheel_load),
    })
}

/// Every figure of `analyses` of one variant as the suite reports it (SI; a figure without a value kept,
/// with its reason), each analysis over its default range in `steps` steps, its figures read at design
/// (the same at any steps and range); an analysis the model does not take (a steering without a tie rod)
/// is left out as the suite leaves it out.
pub fn evaluate_suite(
    file: &SuspensionFile,
    analyses: &[Analysis],
    steps: usize,
) -> Result<Vec<(Analysis, Figure)>, VariantFailed> {
    let models = kc::Models::owning(file.clone());
    let settings = kc::Settings { steps, figures_only: true, error_estimate: false, ..kc::Settings::default() };
    let mut out = Vec::new();
    for analysis in kc::planned(file, analyses).into_iter().flatten() {
        let report = kc::run_on(analysis, &models, &settings)?;
        out.extend(report.figures.into_iter().map(|f| (analysis, f)));
    }
    Ok(out)
}

/// The figures of a batch's variants run by [`evaluate_suite`], as columns: every figure any variant
/// reports, `(analysis, key, unit)`, in the order they first appear, variant by variant.
pub fn suite_columns<E>(results: &[Result<Vec<(Analysis, Figure)>, E>]) -> Vec<(Analysis, String, Unit)> {
    let mut columns: Vec<(Analysis, String, Unit)> = Vec::new();
    for (analysis, figure) in results.iter().filter_map(|r| r.as_ref().ok()).flatten() {
        if !columns.iter().any(|(a, key, _)| a == analysis && *key == figure.key) {
            columns.push((*analysis, figure.key.clone(), figure.unit));
        }
    }
    columns
}

#[cfg(test)]
mod tests {
    use super::*;

    const MODEL: &str = include_str!("../../../../examples/generic/macpherson.json");
    const VARIANTS: &str = include_str!("../../../../examples/generic/macpherson_variants.txt");

    #[test]
    fn checking_keys_refuses_what_applying_refuses_with_the_same_words() {
        let base = base_document(MODEL, "macpherson.json").unwrap();
        for v in parse_variants(VARIANTS, "variants").unwrap() {
            assert!(check_keys(&base, &v).is_ok(), "{}", v.name);
            assert!(apply(&base, &v).is_ok(), "{}", v.name);
        }
        let lacking = parse_variant("soft: /suspension/macpherson/spring/rate=2e4; /suspension/nope/0=1", "x", "y")
            .unwrap()
            .unwrap();
        let said = "variant 'soft': the model has no '/suspension/nope/0'";
        assert!(matches!(check_keys(&base, &lacking), Err(VariantError::NoKey { .. })));
        assert_eq!(check_keys(&base, &lacking).unwrap_err().to_string(), said);
        assert_eq!(apply(&base, &lacking).unwrap_err().to_string(), said);
    }

    #[test]
    fn a_chrono_variant_is_read_as_run_reads_its_file_and_says_so_when_it_cannot_be() {
        const CHRONO: &str = include_str!("../../../../tests/data/chrono/SemiTrailingArm.json");
        let base = base_document(CHRONO, "SemiTrailingArm.json").unwrap();
        let stiff = parse_variant("stiff: /Spring/Spring Coefficient=400000", "x", "y").unwrap().unwrap();
        let file = apply(&base, &stiff).unwrap();
        let (run, _) =
            crate::document::parse_model(&CHRONO.replace("350000.000", "400000"), "variant 'stiff'").unwrap();
        assert_eq!(file.suspension, run.suspension);
        let broken = parse_variant("broken: /Spring/Spring Coefficient=\"stiff\"", "x", "y").unwrap().unwrap();
        let said = apply(&base, &broken).unwrap_err().to_string();
        assert!(said.starts_with("variant 'broken'"), "{said}");
        assert!(said.ends_with(" (read as a Project Chrono suspension file)"), "{said}");
    }

    #[test]
    fn a_file_of_any_length_is_read_when_no_limit_is_set() {
        let many: String = (0..MAX_VARIANTS + 1).map(|k| format!("/a/{k}=1\n")).collect();
        let err = parse_variants(&many, "many").unwrap_err();
        assert!(matches!(&err, VariantsError::TooMany { most: MAX_VARIANTS, .. }), "{err:?}");
        let err = err.to_string();
        assert!(err.starts_with(&format!("many:{}: more than {MAX_VARIANTS} variants", MAX_VARIANTS + 1)), "{err}");
        assert_eq!(parse_variants_at_most(&many, "many", None).unwrap().len(), MAX_VARIANTS + 1);
        assert!(parse_variants_at_most(&many, "many", Some(3)).is_err());
        let err = parse_variants_at_most(&many, "many", Some(3)).unwrap_err().to_string();
        assert!(err.starts_with("many:4: more than 3 variants; split the file"), "{err}");
    }
}
