//! The keys of a design file (TARGETS, TOLERANCES): each read as what it must be, or refused with the key
//! it is at (`key`, the file's name and the path within it) and what to give instead.

use crate::kc::{self, Analysis};
use serde_json::{Map, Value};

/// The JSON `text` of a design file (`origin` names it in errors), refused where an object names a key
/// twice (a JSON reader keeps the last silently, and which one the user meant is a guess) and where a key
/// or text holds a character no name is written with, as a model file is.
pub(super) fn read_json(text: &str, origin: &str) -> Result<Value, String> {
    use crate::file::key_path::{first_duplicate_key, first_unprintable, printable};
    let root: Value = serde_json::from_str(text).map_err(|e| format!("{origin}: {e}"))?;
    if let Some((path, said)) = first_unprintable(&root) {
        return Err(format!("{origin}: {}", crate::file::unprintable_message(&path, &said)));
    }
    match first_duplicate_key(text) {
        Some(path) => {
            Err(format!("{origin}: {}: the key is given twice: give each key once", printable(&path.join("."))))
        }
        None => Ok(root),
    }
}

pub(super) fn number(v: &Value, key: &str) -> Result<f64, String> {
    v.as_f64().filter(|x| x.is_finite()).ok_or_else(|| format!("{key}: give a finite number, got {v}"))
}

pub(super) fn pair(v: &Value, key: &str) -> Result<(f64, f64), String> {
    match v.as_array().map(Vec::as_slice) {
        Some([a, b]) => Ok((number(a, key)?, number(b, key)?)),
        _ => Err(format!("{key}: give two numbers [a, b], got {v}")),
    }
}

pub(super) fn triple(v: &Value, key: &str) -> Result<[f64; 3], String> {
    match v.as_array().map(Vec::as_slice) {
        Some([a, b, c]) => Ok([number(a, key)?, number(b, key)?, number(c, key)?]),
        _ => Err(format!("{key}: give three numbers [x, y, z] in m, got {v}")),
    }
}

pub(super) fn name_in<'a>(v: &'a Value, key: &str) -> Result<&'a str, String> {
    v.as_str().ok_or_else(|| format!("{key}: give a name as a string, got {v}"))
}

/// Only `allowed` keys in `object` at `key`.
pub(super) fn only(object: &Map<String, Value>, allowed: &[&str], key: &str) -> Result<(), String> {
    match object.keys().find(|k| !allowed.contains(&k.as_str())) {
        Some(k) => Err(format!("{key}: unknown key '{k}' (the keys are: {})", allowed.join(", "))),
        None => Ok(()),
    }
}

pub(super) fn analysis_named(name: &str, key: &str) -> Result<Analysis, String> {
    Analysis::from_name(name).ok_or_else(|| {
        let names: Vec<&str> = kc::ALL.iter().map(|a| a.name()).collect();
        format!("{key}: no analysis '{name}' (the suite's are: {})", names.join(", "))
    })
}

/// The load steps of every sweep (`steps`, 32 when not given), refused beyond what a sweep takes.
pub(super) fn steps(object: &Map<String, Value>, at: impl Fn(&str) -> String) -> Result<usize, String> {
    match object.get("steps") {
        None => Ok(32),
        Some(v) => {
            let s = v.as_u64().ok_or_else(|| at(&format!("steps: give a whole number of load steps, got {v}")))?;
            let s = usize::try_from(s).unwrap_or(usize::MAX);
            elastokin_solver::LoadPath::check_steps(s).map_err(|e| at(&format!("steps: {e}")))?;
            Ok(s)
        }
    }
}
