//! How this run was made: the provenance, a JSON object shown as a definition list (nested objects nested);
//! every page ends with it, and the K&C report shows it beside the hardpoints.

use crate::markup::text;
use serde_json::Value;
use std::fmt::Write;

/// The section "How this run was made": `provenance` in words, or that none was given.
pub(super) fn write_provenance(out: &mut String, provenance: &Value) -> std::fmt::Result {
    writeln!(out, "<section id=\"provenance\">")?;
    writeln!(out, "<h2>How this run was made</h2>")?;
    match provenance {
        Value::Object(map) if map.is_empty() => writeln!(out, "<p class=\"none\">no provenance given</p>")?,
        Value::Object(_) => write_value(out, provenance)?,
        Value::Null => writeln!(out, "<p class=\"none\">no provenance given</p>")?,
        other => writeln!(out, "<p>{}</p>", text(&scalar(other)))?,
    }
    writeln!(out, "</section>")
}

/// A JSON value in words: an object as a definition list (nested ones nested), anything else as text.
fn write_value(out: &mut String, value: &Value) -> std::fmt::Result {
    match value {
        Value::Object(map) => {
            writeln!(out, "<dl>")?;
            for (key, v) in map {
                write!(out, "<dt>{}</dt><dd>", text(&key.replace('_', " ")))?;
                write_value(out, v)?;
                writeln!(out, "</dd>")?;
            }
            writeln!(out, "</dl>")
        }
        other => write!(out, "{}", text(&scalar(other))),
    }
}

/// A JSON value that is not an object, as text: a string without its quotes, an array of plain values
/// joined by commas, anything else as compact JSON.
fn scalar(value: &Value) -> String {
    match value {
        Value::String(s) => s.clone(),
        Value::Null => "—".into(),
        Value::Array(items) if items.iter().all(|v| !v.is_object() && !v.is_array()) => {
            items.iter().map(scalar).collect::<Vec<_>>().join(", ")
        }
        other => other.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn provenance_values_read_as_words() {
        assert_eq!(scalar(&serde_json::json!("corrected")), "corrected");
        assert_eq!(scalar(&serde_json::json!([1, 2.5])), "1, 2.5");
        assert_eq!(scalar(&serde_json::json!(null)), "—");
    }
}
