//! A model file's text with some of its numbers rewritten where they stand: each number named by its JSON
//! pointer is found at its byte span in the text and replaced there, so that every other byte (the order of
//! keys, the spacing, the way each untouched number is written, a Chrono file's comments) stays as written.
//! The spans come from jsonc-parser's syntax tree, which keeps every value's place in the text.

use jsonc_parser::ast::{ObjectPropName, Value};
use jsonc_parser::common::Ranged;
use jsonc_parser::{parse_to_ast, CollectOptions, ParseOptions};
use std::ops::Range;

/// `text` (a model file) with the number at each pointer of `edits` replaced by its new value, written as
/// the model's JSON writer writes a number (the shortest text that reads back to the same `f64`). A pointer
/// given twice, one that names nothing or something that is no number, and a value that is no finite
/// number are refused by name; the text is then returned by no one.
pub fn with_numbers(text: &str, edits: &[(String, f64)]) -> Result<String, NumberEditError> {
    let mut spans: Vec<(Range<usize>, String)> = Vec::with_capacity(edits.len());
    for (k, (pointer, value)) in edits.iter().enumerate() {
        if edits[..k].iter().any(|(p, _)| p == pointer) {
            return Err(NumberEditError::Twice { pointer: pointer.clone() });
        }
        let written = serde_json::Number::from_f64(*value)
            .ok_or_else(|| NumberEditError::NotFinite { pointer: pointer.clone(), value: *value })?
            .to_string();
        spans.push((number_span(text, pointer)?, written));
    }
    // Replaced from the last span back, each replacement leaves the spans before it where they were.
    spans.sort_by_key(|(span, _)| std::cmp::Reverse(span.start));
    let mut out = text.to_string();
    for (span, written) in spans {
        out.replace_range(span, &written);
    }
    Ok(out)
}

/// The byte span in `text` of the number at `pointer` (RFC 6901: `/`-separated keys and array indices, `~1`
/// for `/` and `~0` for `~` within a key). A key given twice in one object is read as the JSON reader reads
/// it, the last one.
pub fn number_span(text: &str, pointer: &str) -> Result<Range<usize>, NumberEditError> {
    // A byte-order mark is skipped as the model file's reader skips it; the spans count it.
    let skip = if text.starts_with('\u{feff}') { '\u{feff}'.len_utf8() } else { 0 };
    let parsed = parse_to_ast(&text[skip..], &CollectOptions::default(), &ParseOptions::default())
        .map_err(|e| NumberEditError::Text { why: e.to_string() })?;
    let missing = || NumberEditError::Nothing { pointer: pointer.to_string() };
    let mut value = parsed.value.as_ref().ok_or_else(missing)?;
    if !pointer.is_empty() {
        let Some(tokens) = pointer.strip_prefix('/') else { return Err(missing()) };
        for token in tokens.split('/') {
            let key = token.replace("~1", "/").replace("~0", "~");
            value = match value {
                Value::Object(object) => {
                    let name = |n: &ObjectPropName| match n {
                        ObjectPropName::String(s) => s.value.as_ref() == key,
                        ObjectPropName::Word(w) => w.value == key,
                    };
                    &object.properties.iter().rev().find(|p| name(&p.name)).ok_or_else(missing)?.value
                }
                Value::Array(array) => {
                    let index = array_index(&key).ok_or_else(missing)?;
                    array.elements.get(index).ok_or_else(missing)?
                }
                _ => return Err(missing()),
            };
        }
    }
    match value {
        Value::NumberLit(n) => Ok(n.start() + skip..n.end() + skip),
        _ => Err(NumberEditError::NoNumber { pointer: pointer.to_string() }),
    }
}

/// An array index as a pointer writes it: decimal digits, no leading zero but for `0` itself.
fn array_index(token: &str) -> Option<usize> {
    let digits = !token.is_empty() && token.bytes().all(|b| b.is_ascii_digit());
    (digits && (token == "0" || !token.starts_with('0'))).then(|| token.parse().ok()).flatten()
}

/// Why a number of a model file's text cannot be rewritten ([`with_numbers`]). Each names the number by
/// its pointer.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum NumberEditError {
    /// The text is no JSON.
    #[error("the model file is no JSON any more: {why}")]
    Text {
        /// What the reader says, with the place.
        why: String,
    },
    /// A pointer that names nothing in the text.
    #[error("'{pointer}' names nothing in the model file")]
    Nothing {
        /// The pointer.
        pointer: String,
    },
    /// A pointer that names a section, a list, a string, a flag or null.
    #[error("'{pointer}' names no number of the model file")]
    NoNumber {
        /// The pointer.
        pointer: String,
    },
    /// A pointer given twice.
    #[error("'{pointer}' is given twice: give each number once")]
    Twice {
        /// The pointer.
        pointer: String,
    },
    /// A value that is no finite number.
    #[error("'{pointer}' cannot be {value}: give a finite number")]
    NotFinite {
        /// The pointer.
        pointer: String,
        /// The value.
        value: f64,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str =
        "{\n  \"name\": \"a/b\",\n  \"p\": [1.50, -2e-3,  3],\n  \"a/b\": {\"~x\": 7.0, \"q\": 1}, \"q\": 2\n}\n";

    #[test]
    fn every_number_is_found_at_its_span_and_nothing_else_is() {
        let at = |p: &str| number_span(TEXT, p).map(|r| &TEXT[r]);
        assert_eq!(at("/p/0"), Ok("1.50"));
        assert_eq!(at("/p/1"), Ok("-2e-3"));
        assert_eq!(at("/p/2"), Ok("3"));
        assert_eq!(at("/a~1b/~0x"), Ok("7.0"));
        assert_eq!(at("/a~1b/q"), Ok("1"));
        assert_eq!(at("/q"), Ok("2"));
        assert!(matches!(at("/name"), Err(NumberEditError::NoNumber { .. })));
        assert!(matches!(at("/p"), Err(NumberEditError::NoNumber { .. })));
        for nothing in ["/p/3", "/p/01", "/p/-1", "/r", "p/0", "/q/0"] {
            assert!(matches!(at(nothing), Err(NumberEditError::Nothing { .. })), "{nothing}");
        }
    }

    #[test]
    fn an_edit_rewrites_its_number_alone_and_reads_back_to_the_value() {
        let edits = vec![("/p/1".to_string(), 0.1 + 0.2), ("/p/0".to_string(), -4.0)];
        let out = with_numbers(TEXT, &edits).unwrap();
        assert_eq!(out, TEXT.replace("1.50", "-4.0").replace("-2e-3", "0.30000000000000004"));
        let read: serde_json::Value = serde_json::from_str(&out).unwrap();
        assert_eq!(read.pointer("/p/1").and_then(serde_json::Value::as_f64), Some(0.1 + 0.2));
        assert_eq!(with_numbers(TEXT, &[]).unwrap(), TEXT);
    }

    #[test]
    fn comments_and_a_byte_order_mark_stay_where_they_are() {
        let text = "\u{feff}{ // a Chrono file's comment\n \"x\": /* here */ 1.25 }";
        let out = with_numbers(text, &[("/x".to_string(), 2.5)]).unwrap();
        assert_eq!(out, "\u{feff}{ // a Chrono file's comment\n \"x\": /* here */ 2.5 }");
    }

    #[test]
    fn bad_edits_are_refused_by_name() {
        let twice = vec![("/q".to_string(), 1.0), ("/q".to_string(), 2.0)];
        assert!(matches!(with_numbers(TEXT, &twice), Err(NumberEditError::Twice { .. })));
        let nan = with_numbers(TEXT, &[("/q".to_string(), f64::NAN)]).unwrap_err();
        assert!(nan.to_string().contains("'/q'"), "{nan}");
        assert!(matches!(with_numbers("{", &[("/q".to_string(), 1.0)]), Err(NumberEditError::Text { .. })));
    }
}
