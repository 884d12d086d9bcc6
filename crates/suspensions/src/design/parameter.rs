//! Parameters: numbers of a model file by JSON pointer (`/suspension/macpherson/hardpoints/tie_rod_inner/2`,
//! `/suspension/general/bushings/0/rates/radial`, a Chrono file's own keys), the vocabulary batch variants,
//! sensitivities, tuning and tolerances share. A parameter moved is the model file edited there and read
//! again, so it means exactly what the number means in the file.

use crate::document::DocumentError;
use crate::file::SuspensionFile;
use serde_json::Value;
use std::sync::Arc;

/// Numbers of one model document, each named by its pointer, with the document they are read from.
#[derive(Debug, Clone)]
pub struct Parameters {
    document: Value,
    /// The pointers, in the order given.
    pub pointers: Vec<String>,
    /// Their values in the document.
    pub values: Vec<f64>,
}

impl Parameters {
    /// The numbers at `pointers` of `document` (a model file as [`crate::study::batch::base_document`]
    /// reads it); a pointer that names nothing, or something that is not a number, is refused by name, with
    /// what is there.
    pub fn new(document: &Value, pointers: &[String]) -> Result<Parameters, ParameterError> {
        let mut values = Vec::with_capacity(pointers.len());
        for (k, pointer) in pointers.iter().enumerate() {
            let named = || pointer.clone();
            if pointers[..k].contains(pointer) {
                return Err(ParameterError::Twice { pointer: named() });
            }
            let value =
                number_at(document, pointer).map_err(|why| ParameterError::NoNumber { pointer: named(), why })?;
            if value.fract() == 0.0 && is_count(document, pointer, value) {
                return Err(ParameterError::Count { pointer: named() });
            }
            values.push(value);
        }
        Ok(Parameters { document: document.clone(), pointers: pointers.to_vec(), values })
    }

    /// How many parameters there are.
    pub fn len(&self) -> usize {
        self.pointers.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.pointers.is_empty()
    }

    /// The model with parameter `k` moved by `delta` (in the file's units), read as the command reads it.
    pub fn file_moved(&self, k: usize, delta: f64) -> Result<SuspensionFile, ParameterError> {
        self.moved(k, delta, true)
    }

    /// [`Parameters::file_moved`] not built to check it, for a caller that builds it at once and says why a
    /// build fails.
    pub(crate) fn file_moved_to_build(&self, k: usize, delta: f64) -> Result<SuspensionFile, ParameterError> {
        self.moved(k, delta, false)
    }

    /// The model with parameter `k` moved by `delta`, built to check it if `built` ([`read`]).
    /// Only parameter `k` is written: the document holds the others' values already.
    fn moved(&self, k: usize, delta: f64, built: bool) -> Result<SuspensionFile, ParameterError> {
        let (pointer, value) = (&self.pointers[k], self.values[k] + delta);
        let mut document = self.document.clone();
        set(&mut document, pointer, value)?;
        read(&document, &format!("the model with '{pointer}' at {value}"), built)
    }

    /// The model's document with the parameters at `values` (in order; the file's units): every other key,
    /// and the order of keys, as they were.
    pub fn document_at(&self, values: &[f64]) -> Result<Value, ParameterError> {
        let mut document = self.document.clone();
        for (pointer, &value) in self.pointers.iter().zip(values) {
            set(&mut document, pointer, value)?;
        }
        Ok(document)
    }

    /// The model's document, the parameters at their values.
    pub fn document(&self) -> &Value {
        &self.document
    }

    /// The same parameters of the model with them at `values`.
    pub fn at(&self, values: &[f64]) -> Result<Parameters, ParameterError> {
        Ok(Parameters { document: self.document_at(values)?, pointers: self.pointers.clone(), values: values.to_vec() })
    }

    /// The model as it is (its parameters at their values).
    pub fn file(&self) -> Result<SuspensionFile, ParameterError> {
        read(&self.document, "the model", true)
    }
}

/// Whether the number at `pointer` (whole, `value`) is a count the model reads only whole (a beam's
/// segments): the model reads it with one more but not half a one more, or with one less but not half a one
/// less. (A fraction at the end of its range reads neither one nor half a one beyond it.)
fn is_count(document: &Value, pointer: &str, value: f64) -> bool {
    // A whole number written as a JSON integer, as a count is written (`7`, not `7.0`).
    let reads = |v: Value| {
        let mut moved = document.clone();
        moved.pointer_mut(pointer).map(|slot| *slot = v).is_some() && read(&moved, "", false).is_ok()
    };
    let whole = |v: f64| Value::from(v as i64);
    let half = |v: f64| serde_json::Number::from_f64(v).map(Value::Number);
    [1.0, -1.0]
        .into_iter()
        .any(|side| half(value + 0.5 * side).is_some_and(|h| !reads(h)) && reads(whole(value + side)))
}

/// Writes `value` at `pointer` of `document`.
pub(super) fn set(document: &mut Value, pointer: &str, value: f64) -> Result<(), ParameterError> {
    let number = serde_json::Number::from_f64(value)
        .ok_or_else(|| ParameterError::NotFinite { pointer: pointer.to_string(), value })?;
    *document.pointer_mut(pointer).ok_or_else(|| ParameterError::Gone { pointer: pointer.to_string() })? =
        Value::Number(number);
    Ok(())
}

/// A model document read as the command reads its file, built to check it unless not `built` (see
/// [`crate::document::parse_value`]; a Project Chrono file is read, and so built, as the command reads it);
/// `origin` names it in errors (a moved model is no file the user has: its errors name keys).
fn read(document: &Value, origin: &str, built: bool) -> Result<SuspensionFile, ParameterError> {
    let refused = |why: DocumentError| ParameterError::Model(Arc::new(why));
    if crate::import::chrono::is_chrono_document(document) {
        let text = serde_json::to_string(document).map_err(|e| refused(DocumentError::Json(e)))?;
        return crate::document::parse_document_of_kind(&text, true, origin).map(|(file, _)| file).map_err(refused);
    }
    crate::document::parse_value(document, origin, built).map_err(refused)
}

/// The number at `pointer` of `document`, or what is there instead, in words that follow the pointer
/// ("names nothing in the model …", "names a list of 3 values …"): a caller says whose pointer it is.
pub fn number_at(document: &Value, pointer: &str) -> Result<f64, NoNumber> {
    match document.pointer(pointer) {
        None => Err(NoNumber::Nothing),
        Some(Value::Number(n)) => n.as_f64().filter(|v| v.is_finite()).ok_or(NoNumber::NotFinite),
        Some(Value::Array(a)) => Err(NoNumber::List { len: a.len(), pointer: pointer.to_string() }),
        Some(Value::Object(_)) => Err(NoNumber::Section),
        Some(other) => Err(NoNumber::Other { found: other.to_string() }),
    }
}

/// What a pointer names where a number is asked for, in words that follow the pointer: a caller says whose
/// pointer it is.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum NoNumber {
    /// Nothing in the document.
    #[error(
        "names nothing in the model: a JSON pointer into the model file (keys and array indices from the top, e.g. \
         /suspension/macpherson/hardpoints/tie_rod_inner/2)"
    )]
    Nothing,
    /// A number that is not finite.
    #[error("is not a finite number")]
    NotFinite,
    /// A list of values.
    #[error("names a list of {len} values (name one of them: '{pointer}/0')")]
    List {
        /// How many.
        len: usize,
        /// The pointer to the list.
        pointer: String,
    },
    /// A section of the model (an object).
    #[error("names a section of the model, not a number")]
    Section,
    /// A string, a flag or null, as written in JSON.
    #[error("names {found}, not a number")]
    Other {
        /// The value, as JSON.
        found: String,
    },
}

/// Why a parameter is refused, or a model with parameters moved cannot be read. Each names the parameter by
/// its pointer.
#[derive(Debug, Clone, thiserror::Error)]
pub enum ParameterError {
    /// A pointer given twice.
    #[error("parameter '{pointer}' is given twice")]
    Twice {
        /// The pointer.
        pointer: String,
    },
    /// A pointer that names no number of the model.
    #[error("parameter '{pointer}' {why}")]
    NoNumber {
        /// The pointer.
        pointer: String,
        /// What it names instead.
        why: NoNumber,
    },
    /// A count: a whole number of things, which does not move by parts.
    #[error(
        "parameter '{pointer}' is a count (a whole number of things), which does not move by parts and has no \
         derivative: give a number that places a part or sets a rate, a force or a size"
    )]
    Count {
        /// The pointer.
        pointer: String,
    },
    /// A parameter moved to a value JSON cannot write.
    #[error("parameter '{pointer}' at {value:e}, which is no number")]
    NotFinite {
        /// The pointer.
        pointer: String,
        /// The value.
        value: f64,
    },
    /// A pointer that names nothing in the document it is written to.
    #[error("parameter '{pointer}' names nothing")]
    Gone {
        /// The pointer.
        pointer: String,
    },
    /// The model with the parameters moved is refused as a model document is.
    #[error(transparent)]
    Model(Arc<DocumentError>),
}

/// A key as a JSON pointer token (RFC 6901: `~` and `/` escaped).
fn token(key: &str) -> String {
    key.replace('~', "~0").replace('/', "~1")
}

/// Whether a value is a point: three numbers.
fn is_point(v: &Value) -> bool {
    v.as_array().is_some_and(|a| a.len() == 3 && a.iter().all(Value::is_number))
}

/// The named hardpoints of a template's or the general form's `hardpoints` section: each name and its
/// pointer (`/suspension/<form>/hardpoints/<name>`).
fn named_hardpoints(document: &Value) -> impl Iterator<Item = (&String, String)> {
    let forms = document.get("suspension").and_then(Value::as_object).into_iter().flatten();
    forms.flat_map(|(form, body)| {
        let points = body.get("hardpoints").and_then(Value::as_object).into_iter().flatten();
        points
            .filter(|(_, xyz)| is_point(xyz))
            .map(move |(name, _)| (name, format!("/suspension/{form}/hardpoints/{}", token(name))))
    })
}

/// The pointer of hardpoint `name` of a template or the general form, if the model has it.
pub fn hardpoint_pointer(document: &Value, name: &str) -> Option<String> {
    named_hardpoints(document).find(|(n, _)| *n == name).map(|(_, pointer)| pointer)
}

/// Whether the parameter is a length (a hardpoint coordinate, a Chrono part's `Location …` point, a loaded
/// radius, a stop's clearance, a spring's free length), in the file's metres: an engineer moves it and
/// reads it in millimetres.
pub fn is_length(pointer: &str) -> bool {
    let chrono_point = pointer.split('/').any(is_chrono_point);
    let length = ["/loaded_radius", "/clearance", "/free_length"].iter().any(|end| pointer.ends_with(end));
    pointer.contains("/hardpoints/") || chrono_point || length
}

/// How a parameter's effect is told: per millimetre of a length ([`is_length`]), per percent of anything
/// else (a rate, a force, a section's property).
pub fn effect_unit(pointer: &str) -> &'static str {
    if is_length(pointer) {
        "mm"
    } else {
        "%"
    }
}

/// A parameter as an engineer names it: a hardpoint's coordinate as the point and its axis
/// (`/suspension/macpherson/hardpoints/tie_rod_inner/2` is `tie_rod_inner z`, an axle's point
/// `axle tube_left y`, a Chrono file's `/Tierod/Location Chassis/2` `Tierod Location Chassis z`); any
/// other number by its pointer, which is how the file names it.
pub fn parameter_words(pointer: &str) -> String {
    let segments: Vec<&str> = pointer.split('/').collect();
    let axis = match segments.last() {
        Some(&"0") => "x",
        Some(&"1") => "y",
        Some(&"2") => "z",
        _ => return pointer.to_string(),
    };
    match segments.len().checked_sub(4).map(|k| &segments[k..segments.len() - 1]) {
        Some(["axle", "hardpoints", name]) => format!("axle {name} {axis}"),
        Some([_, "hardpoints", name]) => format!("{name} {axis}"),
        Some([_, part, point]) if is_chrono_point(point) => format!("{part} {point} {axis}"),
        _ => pointer.to_string(),
    }
}

/// A parameter's value as an engineer writes it: a length (a hardpoint's coordinate, in the file's metres)
/// in millimetres, with its unit; any other number as the file gives it.
pub fn parameter_value_words(pointer: &str, value: f64) -> String {
    if is_length(pointer) {
        format!("{} mm", crate::kc::significant(value * 1e3, 6))
    } else {
        crate::kc::significant(value, 6)
    }
}

/// The keys a model file gives a rate under: a spring's or a bar's `rate`, a bushing's four, the tyre's.
const RATE_KEYS: [&str; 6] = ["rate", "radial", "axial", "torsion", "conical", "tyre_rate"];

/// Every rate of a model document written as a number, as pointers in the file's order: springs' and
/// anti-roll bars' `rate`, bushings' `radial`, `axial`, `torsion` and `conical`, the tyre's `tyre_rate`
/// (a rate given as a measured curve is no one number, and is left out).
pub fn rate_pointers(document: &Value) -> Vec<String> {
    fn walk(value: &Value, at: &str, out: &mut Vec<String>) {
        match value {
            Value::Object(map) => {
                for (key, v) in map {
                    let pointer = format!("{at}/{}", token(key));
                    if v.is_number() && RATE_KEYS.contains(&key.as_str()) {
                        out.push(pointer);
                    } else {
                        walk(v, &pointer, out);
                    }
                }
            }
            Value::Array(items) => {
                for (k, v) in items.iter().enumerate() {
                    walk(v, &format!("{at}/{k}"), out);
                }
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    walk(document, "", &mut out);
    out
}

/// Whether the key names a point of a Project Chrono part (`Location Chassis`, `Location Upright`, …).
pub fn is_chrono_point(key: &str) -> bool {
    key.starts_with("Location")
}

/// Every coordinate of every named hardpoint of a model document, as pointers: `--hardpoints`. The
/// templates' and the general form's `hardpoints` sections; in a Project Chrono file, every part's
/// `Location …` points.
pub fn hardpoint_pointers(document: &Value) -> Vec<String> {
    let coordinates = |point: String| (0..3).map(move |k| format!("{point}/{k}"));
    if document.get("suspension").is_some() {
        return named_hardpoints(document).flat_map(|(_, point)| coordinates(point)).collect();
    }
    let parts = document.as_object().into_iter().flatten();
    parts
        .flat_map(|(part, body)| {
            let keys = body.as_object().into_iter().flatten();
            keys.filter(|(key, xyz)| is_chrono_point(key) && is_point(xyz))
                .flat_map(move |(key, _)| coordinates(format!("/{}/{}", token(part), token(key))))
        })
        .collect()
}
