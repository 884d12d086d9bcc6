//! Places in a JSON text: the line and column of a key path (`locate`), and the key path at a line and
//! column (`key_path_at`), so that an error names what the user wrote, in a file by line and column and in
//! a document no one reads as text by its keys.

/// The byte offset of the quote that closes the JSON string whose opening quote is at `open` (the end of
/// `text` when it is unclosed): escapes are stepped over.
fn string_end(text: &str, open: usize) -> usize {
    let bytes = text.as_bytes();
    let mut i = open + 1;
    while i < bytes.len() && bytes[i] != b'"' {
        i += if bytes[i] == b'\\' { 2 } else { 1 };
    }
    i.min(bytes.len())
}

/// Whether the string that closes at `close` is an object key: a colon follows it.
fn is_key(text: &str, close: usize) -> bool {
    text.get(close + 1..)
        .is_some_and(|rest| rest.trim_start_matches(|c: char| c.is_ascii_whitespace()).starts_with(':'))
}

/// Every object key in `text` with its byte offset, in order.
fn keys(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut i = 0;
    while let Some(found) = text.get(i..).and_then(|rest| rest.find('"')) {
        let open = i + found;
        let close = string_end(text, open);
        if is_key(text, close) {
            out.push((open, text[open + 1..close].to_string()));
        }
        i = close + 1;
    }
    out
}

/// Line and column (from 1) of the key path `path` in `text`: each key the first after the previous one
/// (or, for a part's name in the general form, the string value itself); the last found when the rest are
/// absent.
pub(crate) fn locate(text: &str, path: &[&str]) -> (usize, usize) {
    let all = keys(text);
    let mut at = 0;
    let mut from = 0;
    for key in path {
        if let Some(k) = all[from..].iter().position(|(_, k)| k == key) {
            at = all[from + k].0;
            from += k + 1;
        } else if let Some(offset) = text[at..].find(&format!("\"{key}\"")) {
            // A part's name (a string value, not a key): the keys after it are that part's.
            at += offset;
            from = all.iter().position(|(o, _)| *o > at).unwrap_or(all.len());
        }
    }
    let before = &text[..at];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}

/// The byte offset of line `line`, column `column` (from 1, in characters, as serde_json counts them).
fn offset_of(text: &str, line: usize, column: usize) -> usize {
    let line_start: usize = text.split_inclusive('\n').take(line.saturating_sub(1)).map(str::len).sum();
    let within: usize = text[line_start.min(text.len())..].chars().take(column).map(char::len_utf8).sum();
    line_start + within
}

/// The last key before line `line`, column `column` (from 1) of `text`.
pub(crate) fn key_before(text: &str, line: usize, column: usize) -> Option<String> {
    let offset = offset_of(text, line, column);
    keys(text).into_iter().take_while(|(at, _)| *at < offset).last().map(|(_, k)| k)
}

/// The keys and indices that lead to line `line`, column `column` (from 1) of JSON text, as a reader of the
/// document names a place in it: `suspension.general.bodies[0].mass`. For documents no one reads as text —
/// a Python dict, a variant's edited model — where a line and column would name nothing the user wrote.
pub fn key_path_at(text: &str, line: usize, column: usize) -> String {
    enum Frame {
        Object(Option<String>),
        Array(usize),
    }
    let end = offset_of(text, line, column).min(text.len());
    let bytes = text.as_bytes();
    let mut stack: Vec<Frame> = Vec::new();
    let mut i = 0;
    while i < end {
        match bytes[i] {
            b'"' => {
                let close = string_end(text, i);
                // A string in an object is its key when a colon follows it.
                if let (Some(Frame::Object(key)), true) = (stack.last_mut(), is_key(text, close)) {
                    *key = Some(text[i + 1..close].to_string());
                }
                i = close;
            }
            b'{' => stack.push(Frame::Object(None)),
            b'[' => stack.push(Frame::Array(0)),
            b'}' | b']' => {
                stack.pop();
            }
            b',' => match stack.last_mut() {
                Some(Frame::Array(k)) => *k += 1,
                Some(Frame::Object(key)) => *key = None,
                None => {}
            },
            _ => {}
        }
        i += 1;
    }
    let mut path = String::new();
    for frame in &stack {
        match frame {
            Frame::Object(Some(key)) if path.is_empty() => path.push_str(key),
            Frame::Object(Some(key)) => {
                path.push('.');
                path.push_str(key);
            }
            Frame::Object(None) => {}
            Frame::Array(k) => path.push_str(&format!("[{k}]")),
        }
    }
    path
}

/// Whether `c` is a character no name is written with, and no terminal, SVG or HTML page shows as text: a
/// control character (C0, DEL, C1: an escape sequence recolours a terminal, most make XML ill-formed), a
/// line or paragraph separator, or a noncharacter (U+FFFE…).
pub fn unprintable(c: char) -> bool {
    let code = c as u32;
    c.is_control()
        || matches!(c, '\u{2028}' | '\u{2029}')
        || (0xFDD0..=0xFDEF).contains(&code)
        || code & 0xFFFE == 0xFFFE
}

/// `text` as it can be shown (on a terminal, in an SVG or HTML page): each [`unprintable`] character
/// written as its escape, `\u{1b}`; line breaks kept.
pub fn printable(text: &str) -> std::borrow::Cow<'_, str> {
    let bad = |c: char| c != '\n' && unprintable(c);
    if !text.chars().any(bad) {
        return text.into();
    }
    text.chars().map(|c| if bad(c) { c.escape_unicode().to_string() } else { c.to_string() }).collect()
}

/// The first key or string value of `value`, depth first, that holds an [`unprintable`] character: the
/// keys leading to it (a string in a list is named by its place) and the string.
pub fn first_unprintable(value: &serde_json::Value) -> Option<(Vec<String>, String)> {
    use serde_json::Value;
    let bad = |s: &str| s.chars().any(unprintable);
    match value {
        Value::String(s) if bad(s) => Some((Vec::new(), s.clone())),
        Value::Array(items) => items.iter().enumerate().find_map(|(k, v)| {
            first_unprintable(v).map(|(mut path, s)| {
                path.insert(0, k.to_string());
                (path, s)
            })
        }),
        Value::Object(map) => map.iter().find_map(|(key, v)| {
            if bad(key) {
                return Some((vec![key.clone()], key.clone()));
            }
            first_unprintable(v).map(|(mut path, s)| {
                path.insert(0, key.clone());
                (path, s)
            })
        }),
        _ => None,
    }
}

/// The keys leading to the first key that an object of the JSON `text` names twice (the last of them the
/// key itself), if any: a JSON reader keeps one of the two silently. `None` too where `text` is no JSON
/// (its reader says why).
pub fn first_duplicate_key(text: &str) -> Option<Vec<String>> {
    use serde::de::{DeserializeSeed, Deserializer, IgnoredAny, MapAccess, SeqAccess, Visitor};
    use std::fmt;

    /// Walks a value, keeping in `found` the path to the first key named twice.
    struct Walk<'a> {
        path: &'a mut Vec<String>,
        found: &'a mut Option<Vec<String>>,
    }
    impl<'de> DeserializeSeed<'de> for Walk<'_> {
        type Value = ();
        fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<(), D::Error> {
            d.deserialize_any(self)
        }
    }
    impl<'de> Visitor<'de> for Walk<'_> {
        type Value = ();
        fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
            f.write_str("a JSON value")
        }
        fn visit_bool<E>(self, _: bool) -> Result<(), E> {
            Ok(())
        }
        fn visit_i64<E>(self, _: i64) -> Result<(), E> {
            Ok(())
        }
        fn visit_u64<E>(self, _: u64) -> Result<(), E> {
            Ok(())
        }
        fn visit_f64<E>(self, _: f64) -> Result<(), E> {
            Ok(())
        }
        fn visit_str<E>(self, _: &str) -> Result<(), E> {
            Ok(())
        }
        fn visit_unit<E>(self) -> Result<(), E> {
            Ok(())
        }
        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<(), A::Error> {
            let mut k = 0;
            loop {
                self.path.push(k.to_string());
                let more = seq.next_element_seed(Walk { path: self.path, found: self.found })?.is_some();
                self.path.pop();
                if !more {
                    return Ok(());
                }
                k += 1;
            }
        }
        fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<(), A::Error> {
            let mut seen = std::collections::HashSet::new();
            while let Some(key) = map.next_key::<String>()? {
                self.path.push(key.clone());
                if self.found.is_none() && !seen.insert(key) {
                    *self.found = Some(self.path.clone());
                }
                if self.found.is_some() {
                    map.next_value::<IgnoredAny>()?;
                } else {
                    map.next_value_seed(Walk { path: self.path, found: self.found })?;
                }
                self.path.pop();
            }
            Ok(())
        }
    }

    let mut found = None;
    let mut d = serde_json::Deserializer::from_str(text);
    Walk { path: &mut Vec::new(), found: &mut found }.deserialize(&mut d).ok()?;
    found
}
