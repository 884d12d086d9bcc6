//! The keys of a design file (TARGETS, TOLERANCES): each read as what it must be, or refused with the key
//! it is at (`key`, the path within the file) and what to give instead.

use crate::kc::{self, Analysis};
use serde_json::{Map, Value};
use std::sync::Arc;

/// Why a key of a design file is refused: what it holds is not what it must be. Each names the key by its
/// path within the file; the file's own error names the file.
#[derive(Debug, Clone, thiserror::Error)]
pub enum KeyRefusal {
    /// The text is no JSON, in the JSON reader's words.
    #[error("{0}")]
    Json(Arc<serde_json::Error>),
    /// A key or text with a character no name is written with.
    #[error("{}", crate::file::unprintable_message(path, said))]
    Unprintable {
        /// The keys down to it.
        path: Vec<String>,
        /// The key or text.
        said: String,
    },
    /// An object that names a key twice (a JSON reader keeps the last silently, and which one the user
    /// meant is a guess).
    #[error("{}: the key is given twice: give each key once", crate::file::key_path::printable(&path.join(".")))]
    Twice {
        /// The keys down to it.
        path: Vec<String>,
    },
    /// Not a finite number.
    #[error("{key}: give a finite number, got {got}")]
    NotNumber {
        /// The key.
        key: String,
        /// What it holds.
        got: Value,
    },
    /// Not two numbers.
    #[error("{key}: give two numbers [a, b], got {got}")]
    NotPair {
        /// The key.
        key: String,
        /// What it holds.
        got: Value,
    },
    /// Not three numbers.
    #[error("{key}: give three numbers [x, y, z] in m, got {got}")]
    NotTriple {
        /// The key.
        key: String,
        /// What it holds.
        got: Value,
    },
    /// Not a name.
    #[error("{key}: give a name as a string, got {got}")]
    NotName {
        /// The key.
        key: String,
        /// What it holds.
        got: Value,
    },
    /// A key the object it is in does not have.
    #[error("{key}: unknown key '{found}' (the keys are: {})", allowed.join(", "))]
    Unknown {
        /// The object's key.
        key: String,
        /// The key found.
        found: String,
        /// The keys it may have.
        allowed: &'static [&'static str],
    },
    /// An analysis the suite has not.
    #[error("{key}: no analysis '{name}' (the suite's are: {})", analysis_names())]
    NoAnalysis {
        /// The key.
        key: String,
        /// The name given.
        name: String,
    },
    /// Load steps that are not a whole number.
    #[error("steps: give a whole number of load steps, got {got}")]
    StepsNotWhole {
        /// What `steps` holds.
        got: Value,
    },
    /// Load steps a sweep does not take, in the solver's words.
    #[error("steps: {why}")]
    Steps {
        /// Why.
        why: elastokin_solver::StepsError,
    },
}

/// The suite's analyses' names, listed.
fn analysis_names() -> String {
    kc::ALL.iter().map(|a| a.name()).collect::<Vec<_>>().join(", ")
}

/// The JSON `text` of a design file, refused where an object names a key twice and where a key or text
/// holds a character no name is written with, as a model file is.
pub(super) fn read_json(text: &str) -> Result<Value, KeyRefusal> {
    use crate::file::key_path::{first_duplicate_key, first_unprintable};
    let root: Value = serde_json::from_str(text).map_err(|e| KeyRefusal::Json(Arc::new(e)))?;
    if let Some((path, said)) = first_unprintable(&root) {
        return Err(KeyRefusal::Unprintable { path, said });
    }
    match first_duplicate_key(text) {
        Some(path) => Err(KeyRefusal::Twice { path }),
        None => Ok(root),
    }
}

pub(super) fn number(v: &Value, key: &str) -> Result<f64, KeyRefusal> {
    v.as_f64().filter(|x| x.is_finite()).ok_or_else(|| KeyRefusal::NotNumber { key: key.into(), got: v.clone() })
}

pub(super) fn pair(v: &Value, key: &str) -> Result<(f64, f64), KeyRefusal> {
    match v.as_array().map(Vec::as_slice) {
        Some([a, b]) => Ok((number(a, key)?, number(b, key)?)),
        _ => Err(KeyRefusal::NotPair { key: key.into(), got: v.clone() }),
    }
}

pub(super) fn triple(v: &Value, key: &str) -> Result<[f64; 3], KeyRefusal> {
    match v.as_array().map(Vec::as_slice) {
        Some([a, b, c]) => Ok([number(a, key)?, number(b, key)?, number(c, key)?]),
        _ => Err(KeyRefusal::NotTriple { key: key.into(), got: v.clone() }),
    }
}

pub(super) fn name_in<'a>(v: &'a Value, key: &str) -> Result<&'a str, KeyRefusal> {
    v.as_str().ok_or_else(|| KeyRefusal::NotName { key: key.into(), got: v.clone() })
}

/// Only `allowed` keys in `object` at `key`.
pub(super) fn only(object: &Map<String, Value>, allowed: &'static [&'static str], key: &str) -> Result<(), KeyRefusal> {
    match object.keys().find(|k| !allowed.contains(&k.as_str())) {
        Some(k) => Err(KeyRefusal::Unknown { key: key.into(), found: k.clone(), allowed }),
        None => Ok(()),
    }
}

pub(super) fn analysis_named(name: &str, key: &str) -> Result<Analysis, KeyRefusal> {
    Analysis::from_name(name).ok_or_else(|| KeyRefusal::NoAnalysis { key: key.into(), name: name.into() })
}

/// The load steps of every sweep (`steps`, 32 when not given), refused beyond what a sweep takes.
pub(super) fn steps(object: &Map<String, Value>) -> Result<usize, KeyRefusal> {
    match object.get("steps") {
        None => Ok(32),
        Some(v) => {
            let s = v.as_u64().ok_or_else(|| KeyRefusal::StepsNotWhole { got: v.clone() })?;
            let s = usize::try_from(s).unwrap_or(usize::MAX);
            elastokin_solver::LoadPath::check_steps(s).map_err(|why| KeyRefusal::Steps { why })?;
            Ok(s)
        }
    }
}
