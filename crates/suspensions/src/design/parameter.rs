//! Parameters: numbers of a model file by JSON pointer (`/suspension/macpherson/hardpoints/tie_rod_inner/2`,
//! `/suspension/general/bushings/0/rates/radial`, a Chrono file's own keys), the vocabulary batch variants,
//! sensitivities, tuning and tolerances share. A parameter moved is the model file edited there and read
//! again, so it means exactly what the number means in the file.

use crate::file::SuspensionFile;
use serde_json::Value;

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
    pub fn new(document: &Value, pointers: &[String]) -> Result<Parameters, String> {
        let mut values = Vec::with_capacity(pointers.len());
        for (k, pointer) in pointers.iter().enumerate() {
            if pointers[..k].contains(pointer) {
                return Err(format!("parameter '{pointer}' is given twice"));
            }
            let value = match document.pointer(pointer) {
                None => {
                    return Err(format!(
                        "parameter '{pointer}' names nothing in the model: a JSON pointer into the model file \
                         (keys and array indices from the top, e.g. /suspension/macpherson/hardpoints/tie_rod_inner/2)"
                    ))
                }
                Some(Value::Number(n)) => n.as_f64().filter(|v| v.is_finite()),
                Some(other) => {
                    let what = match other {
                        Value::Array(a) => format!("a list of {} values (name one of them: '{pointer}/0')", a.len()),
                        Value::Object(_) => "a section of the model, not a number".to_string(),
                        _ => format!("{other}, not a number"),
                    };
                    return Err(format!("parameter '{pointer}' names {what}"));
                }
            };
            values.push(value.ok_or_else(|| format!("parameter '{pointer}' is not a finite number"))?);
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
    pub fn file_moved(&self, k: usize, delta: f64) -> Result<SuspensionFile, String> {
        let mut values = self.values.clone();
        values[k] += delta;
        read(&self.document_at(&values)?, &format!("the model with '{}' at {}", self.pointers[k], values[k]))
    }

    /// The model's document with the parameters at `values` (in order; the file's units): every other key,
    /// and the order of keys, as they were.
    pub fn document_at(&self, values: &[f64]) -> Result<Value, String> {
        let mut document = self.document.clone();
        for (pointer, &value) in self.pointers.iter().zip(values) {
            let number = serde_json::Number::from_f64(value)
                .ok_or_else(|| format!("parameter '{pointer}' at {value:e}, which is no number"))?;
            *document.pointer_mut(pointer).ok_or_else(|| format!("parameter '{pointer}' names nothing"))? =
                Value::Number(number);
        }
        Ok(document)
    }

    /// The same parameters of the model with them at `values`.
    pub fn at(&self, values: &[f64]) -> Result<Parameters, String> {
        Ok(Parameters { document: self.document_at(values)?, pointers: self.pointers.clone(), values: values.to_vec() })
    }

    /// The model as it is (its parameters at their values).
    pub fn file(&self) -> Result<SuspensionFile, String> {
        read(&self.document, "the model")
    }
}

/// A model document read as the command reads its file; `origin` names it in errors (a moved model is no
/// file the user has: its errors name keys).
fn read(document: &Value, origin: &str) -> Result<SuspensionFile, String> {
    let text = serde_json::to_string(document).map_err(|e| e.to_string())?;
    let chrono = crate::import::chrono::is_chrono_document(document);
    crate::document::parse_document_of_kind(&text, chrono, origin).map(|(file, _)| file)
}

/// Whether the key names a point of a Project Chrono part (`Location Chassis`, `Location Upright`, …).
pub fn is_chrono_point(key: &str) -> bool {
    key.starts_with("Location")
}

/// Every coordinate of every named hardpoint of a model document, as pointers: `--hardpoints`. The
/// templates' and the general form's `hardpoints` sections; in a Project Chrono file, every part's
/// `Location …` points.
pub fn hardpoint_pointers(document: &Value) -> Vec<String> {
    let mut out = Vec::new();
    let escape = |name: &str| name.replace('~', "~0").replace('/', "~1");
    let is_point = |v: &Value| v.as_array().is_some_and(|a| a.len() == 3 && a.iter().all(Value::is_number));
    let Some(suspension) = document.get("suspension").and_then(Value::as_object) else {
        for (part, body) in document.as_object().into_iter().flatten() {
            for (key, xyz) in body.as_object().into_iter().flatten() {
                if is_chrono_point(key) && is_point(xyz) {
                    out.extend((0..3).map(|k| format!("/{}/{}/{k}", escape(part), escape(key))));
                }
            }
        }
        return out;
    };
    for (form, body) in suspension {
        let Some(points) = body.get("hardpoints").and_then(Value::as_object) else {
            continue;
        };
        for (name, xyz) in points {
            if is_point(xyz) {
                out.extend((0..3).map(|k| format!("/suspension/{form}/hardpoints/{}/{k}", escape(name))));
            }
        }
    }
    out
}
