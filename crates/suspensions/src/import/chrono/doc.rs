//! A Chrono document being read: its values by key path, each key marked as read, so that every key
//! left unread is reported in the notes.

use super::error::{Expected, KeyPath, Refusal};
use elastokin_core::Vec3;
use serde_json::Value;
use std::cell::RefCell;
use std::collections::BTreeSet;

/// A Chrono document, with the keys read so far (every other key is reported).
pub(crate) struct Doc<'a> {
    root: &'a Value,
    read: RefCell<BTreeSet<String>>,
}

/// What a key is for, when it is read only to be left out.
pub(crate) const FOR_DYNAMICS: &str = "mass, inertia and sizes: read and left out (statics)";

impl<'a> Doc<'a> {
    pub(crate) fn new(root: &'a Value) -> Self {
        Doc { root, read: RefCell::new(BTreeSet::new()) }
    }

    /// The value at `path`: keys joined by `/`, an index into an array as its number (`Bodies/0/Name`).
    pub(crate) fn at(&self, path: &str) -> Option<&'a Value> {
        path.split('/').try_fold(self.root, |v, key| match v {
            Value::Array(items) => key.parse::<usize>().ok().and_then(|i| items.get(i)),
            _ => v.get(key),
        })
    }

    /// `path` split for messages: each key, and after it the element of an array it indexes, by its `Name`
    /// when it has one (`[RevoluteUCA]`), else by its index (`[0]`).
    pub(crate) fn segments(&self, path: &str) -> Vec<(String, String)> {
        let mut out: Vec<(String, String)> = Vec::new();
        let mut at = Some(self.root);
        for key in path.split('/') {
            match (at, out.last_mut()) {
                (Some(Value::Array(items)), Some(last)) => {
                    let item = key.parse::<usize>().ok().and_then(|i| items.get(i));
                    let name = item.and_then(|v| v.get("Name")).and_then(Value::as_str).unwrap_or(key);
                    last.1.push_str(&format!("[{name}]"));
                    at = item;
                }
                _ => {
                    out.push((key.to_string(), String::new()));
                    at = at.and_then(|v| v.get(key));
                }
            }
        }
        out
    }

    /// `path` as the notes show it: `Joints[RevoluteUCA] / Bushing Data`.
    pub(crate) fn shown(&self, path: &str) -> String {
        self.segments(path).iter().map(|(k, element)| format!("{k}{element}")).collect::<Vec<_>>().join(" / ")
    }

    /// `path` as the errors show it, keys quoted: `"Joints"[RevoluteUCA] / "Position"`.
    pub(crate) fn quoted(&self, path: &str) -> String {
        self.segments(path).iter().map(|(k, element)| format!("\"{k}\"{element}")).collect::<Vec<_>>().join(" / ")
    }

    /// `path` as a refusal names and places it.
    pub(crate) fn key_path(&self, path: &str) -> KeyPath {
        KeyPath { shown: self.quoted(path), keys: self.segments(path).into_iter().map(|(k, _)| k).collect() }
    }

    /// The refusal of `path` missing.
    pub(crate) fn missing(&self, path: &str) -> Refusal {
        Refusal::Missing { at: self.key_path(path) }
    }

    /// The refusal of the value at `path`, which is not what the key takes.
    pub(crate) fn wrong(&self, path: &str, expected: Expected) -> Refusal {
        Refusal::WrongType { at: self.key_path(path), expected }
    }

    /// Marks `path` (keys joined by `/`) as read.
    pub(crate) fn expect(&self, path: &str) {
        self.read.borrow_mut().insert(path.to_string());
    }

    pub(crate) fn has(&self, path: &str) -> bool {
        self.at(path).is_some()
    }

    /// The template's name.
    pub(crate) fn template(&self) -> Result<String, Refusal> {
        self.expect("Template");
        self.at("Template").and_then(Value::as_str).map(str::to_string).ok_or(Refusal::NoTemplate)
    }

    pub(crate) fn optional_str(&self, path: &str) -> Option<String> {
        self.expect(path);
        self.at(path).and_then(Value::as_str).map(str::to_string)
    }

    /// A number at `path`.
    pub(crate) fn number(&self, path: &str) -> Result<f64, Refusal> {
        self.expect(path);
        match self.at(path) {
            Some(v) => v.as_f64().ok_or_else(|| self.wrong(path, Expected::Number { got: v.to_string() })),
            None => Err(self.missing(path)),
        }
    }

    /// A number at `path`, when given.
    pub(crate) fn optional_number(&self, path: &str) -> Result<Option<f64>, Refusal> {
        if self.has(path) {
            self.number(path).map(Some)
        } else {
            Ok(None)
        }
    }

    /// A point `[x, y, z]` at `path`.
    pub(crate) fn point(&self, path: &str) -> Result<Vec3, Refusal> {
        self.expect(path);
        let v = self.at(path).ok_or_else(|| self.missing(path))?;
        match v.as_array().map(|a| a.iter().map(Value::as_f64).collect::<Option<Vec<f64>>>()) {
            Some(Some(c)) if c.len() == 3 => Ok(Vec3::new(c[0], c[1], c[2])),
            _ => Err(self.wrong(path, Expected::Point { got: v.to_string() })),
        }
    }

    /// A table `[[x, y], …]` at `path`.
    pub(crate) fn table(&self, path: &str) -> Result<Vec<[f64; 2]>, Refusal> {
        self.expect(path);
        let v = self.at(path).ok_or_else(|| self.missing(path))?;
        let rows = v.as_array().ok_or_else(|| self.wrong(path, Expected::Table))?;
        rows.iter()
            .map(|r| match r.as_array().map(|a| a.iter().map(Value::as_f64).collect::<Option<Vec<f64>>>()) {
                Some(Some(p)) if p.len() == 2 => Ok([p[0], p[1]]),
                _ => Err(self.wrong(path, Expected::TableRow { got: r.to_string() })),
            })
            .collect()
    }

    /// Marks the keys under `object` that carry only dynamics as read, with their reason.
    pub(crate) fn dynamics(&self, object: &str, keys: &[&str], notes: &mut Vec<String>) {
        self.left_out(object, keys, FOR_DYNAMICS, notes);
    }

    /// Marks those of `keys` under `object` that the file gives as read, and notes them with `why` they are
    /// left out.
    pub(crate) fn left_out(&self, object: &str, keys: &[&str], why: &str, notes: &mut Vec<String>) {
        let given: Vec<&str> = keys.iter().copied().filter(|k| self.has(&format!("{object}/{k}"))).collect();
        for k in &given {
            self.expect(&format!("{object}/{k}"));
        }
        if !given.is_empty() {
            notes.push(format!("{}: {} — {why}", self.shown(object), given.join(", ")));
        }
    }

    /// Every key of the document that was not read, as [`Doc::shown`] shows it. A list of objects (Chrono's
    /// `Bodies`, `Joints`, …) is walked element by element.
    pub(crate) fn unread(&self) -> Vec<String> {
        fn walk(v: &Value, path: String, read: &BTreeSet<String>, out: &mut Vec<String>) {
            if read.contains(&path) {
                return;
            }
            let join = |k: &str| if path.is_empty() { k.to_string() } else { format!("{path}/{k}") };
            match v {
                Value::Object(map) if !map.is_empty() => {
                    for (k, child) in map {
                        walk(child, join(k), read, out);
                    }
                }
                Value::Array(items) if !items.is_empty() && items.iter().all(Value::is_object) => {
                    for (i, child) in items.iter().enumerate() {
                        walk(child, join(&i.to_string()), read, out);
                    }
                }
                _ => out.push(path),
            }
        }
        let mut out = Vec::new();
        walk(self.root, String::new(), &self.read.borrow(), &mut out);
        out.into_iter().map(|p| self.shown(&p)).collect()
    }
}
