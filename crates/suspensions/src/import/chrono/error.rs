//! Why a Chrono suspension file is not read: what is wrong ([`Refusal`]), at the keys that place it in the
//! file ([`ImportError::At`]), or the file format's own error ([`ImportError::File`]).

use super::templates::SUPPORTED;
use crate::file::FileError;
use std::fmt;

/// Why a Chrono suspension file is not read.
#[derive(Debug, thiserror::Error)]
pub enum ImportError {
    /// The text is no JSON or holds an unprintable character, the general model read from it fails a model
    /// file's checks, or it cannot be built.
    #[error(transparent)]
    File(#[from] FileError),
    /// A value of the file the importer refuses, placed at the line and column of the keys it names.
    #[error("{origin}:{line}:{column}: {refusal}")]
    At {
        /// The file (or the origin given to the reader).
        origin: String,
        /// Line, from 1.
        line: usize,
        /// Column, from 1.
        column: usize,
        /// What is wrong there.
        refusal: Refusal,
    },
}

/// What the importer refuses in a Chrono file, naming the keys as the file writes them. Each says what to
/// change.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Refusal {
    /// The file names no template.
    #[error("\"Template\" is missing: a Chrono suspension file names its template")]
    NoTemplate,
    /// A template this importer does not read.
    #[error("Project Chrono template '{template}': {}; it reads {}", unread_template(template), SUPPORTED.join(", "))]
    Template {
        /// The file's `"Template"`.
        template: String,
    },
    /// A key the template needs is not in the file.
    #[error("{at} is missing")]
    Missing {
        /// The key.
        at: KeyPath,
    },
    /// A value that is not of the kind its key takes.
    #[error("{}", expected.said_of(at))]
    WrongType {
        /// The key.
        at: KeyPath,
        /// What the key takes, and the value found.
        expected: Expected,
    },
    /// Values read that make no model: points that coincide, a rate out of the engine's range, a part
    /// Chrono builds that the general model has no place for.
    #[error("{why}")]
    Unusable {
        /// The keys the message names first, in the file's order, which place it (none: at the template).
        at: Vec<String>,
        /// What is wrong and what to change, naming the keys.
        why: String,
    },
    /// A point the importer itself should have added before it is used.
    #[error("{what}")]
    Unwritten {
        /// Which point.
        what: String,
    },
}

impl Refusal {
    /// An [`Refusal::Unusable`] at `at`, the keys its message names first.
    pub(crate) fn unusable(at: &[&str], why: impl Into<String>) -> Refusal {
        Refusal::Unusable { at: at.iter().map(|k| k.to_string()).collect(), why: why.into() }
    }

    /// The importer's own hardpoint `name` not found where it was added.
    pub(crate) fn no_hardpoint(name: &str) -> Refusal {
        Refusal::Unwritten { what: format!("no hardpoint {name}") }
    }

    /// The keys that place the refusal in the file, outermost first; none places it at the template.
    pub fn keys(&self) -> &[String] {
        match self {
            Refusal::Missing { at } | Refusal::WrongType { at, .. } => &at.keys,
            Refusal::Unusable { at, .. } => at,
            Refusal::NoTemplate | Refusal::Template { .. } | Refusal::Unwritten { .. } => &[],
        }
    }
}

/// Why a template is not read.
fn unread_template(template: &str) -> &'static str {
    match template {
        "RigidSuspension" => "it has no suspension motion to analyse",
        _ => "not a template this importer reads",
    }
}

/// A key of a Chrono file as a message names it (`"Joints"[RevoluteUCA] / "Position"`), and the keys that
/// lead to it.
#[derive(Debug, Clone, PartialEq)]
pub struct KeyPath {
    /// As the message writes it.
    pub shown: String,
    /// The keys, outermost first (no array indices).
    pub keys: Vec<String>,
}

impl KeyPath {
    /// The key path `path` (keys joined by `/`) written as its keys quoted, each after the last: `"Lateral" /
    /// "Universal Joint Axis Chassis"`.
    pub(crate) fn written(path: &str) -> KeyPath {
        KeyPath {
            shown: format!("\"{}\"", path.replace('/', "\" / \"")),
            keys: path.split('/').map(String::from).collect(),
        }
    }
}

impl fmt::Display for KeyPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.shown)
    }
}

/// What a key takes, with the value found where it is shown.
#[derive(Debug, Clone, PartialEq)]
pub enum Expected {
    /// A number.
    Number { got: String },
    /// A point `[x, y, z]` in metres.
    Point { got: String },
    /// A direction `[x, y, z]`, of any length but zero.
    Direction,
    /// A direction given as `[0, 0, 0]`.
    NonZeroDirection,
    /// A table `[[x, y], …]`.
    Table,
    /// A row `[x, y]` of a table.
    TableRow { got: String },
    /// A name (a string).
    Name,
    /// `true` or `false`.
    Flag,
    /// A body's name, or `[name, "Left" | "Right"]`.
    Body { got: String },
    /// A quaternion `[e0, e1, e2, e3]`, not zero.
    Rotation { got: String },
}

impl Expected {
    /// The message of a value at `at` that is not what the key takes.
    fn said_of(&self, at: &KeyPath) -> String {
        match self {
            Expected::Number { got } => format!("{at} must be a number, got {got}"),
            Expected::Point { got } => format!("{at} must be a point [x, y, z] in metres, got {got}"),
            Expected::Direction => format!("{at} must be a direction [x, y, z], of any length but zero"),
            Expected::NonZeroDirection => {
                format!("{at} is [0, 0, 0]: give the direction [x, y, z], of any length but zero")
            }
            Expected::Table => format!("{at} must be a table [[x, y], …]"),
            Expected::TableRow { got } => format!("{at}: every row is [x, y], got {got}"),
            Expected::Name => format!("{at} must be a name (a string)"),
            Expected::Flag => format!("{at} must be true or false"),
            Expected::Body { got } => format!("{at} must be a body's name or [name, \"Left\" | \"Right\"], got {got}"),
            Expected::Rotation { got } => {
                format!("{at} must be a rotation, a quaternion [e0, e1, e2, e3] not zero; got {got}")
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::read;
    use super::*;

    /// A Chrono double wishbone whose spindle's centre is a word, not a point, on line 4.
    const BAD_SPINDLE: &str = "{\n  \"Type\": \"Suspension\",\n  \"Template\": \"DoubleWishbone\",\n  \"Spindle\": \
                               {\"COM\": \"centre\"}\n}";

    #[test]
    fn a_value_of_the_wrong_kind_is_refused_as_such_at_its_key() {
        let Err(e) = read(BAD_SPINDLE, "front.json", None) else { panic!("a spindle at \"centre\" was read") };
        let ImportError::At { line, refusal: Refusal::WrongType { at, expected }, .. } = &e else {
            panic!("not a value of the wrong kind: {e:?}")
        };
        assert_eq!((*line, at.keys.as_slice()), (4, ["Spindle".to_string(), "COM".to_string()].as_slice()));
        assert_eq!(*expected, Expected::Point { got: "\"centre\"".into() });
        assert_eq!(
            e.to_string(),
            "front.json:4:15: \"Spindle\" / \"COM\" must be a point [x, y, z] in metres, got \"centre\""
        );
    }

    #[test]
    fn a_template_not_read_is_refused_by_its_name() {
        let text = "{\"Type\": \"Suspension\", \"Template\": \"RigidSuspension\"}";
        let Err(ImportError::At { refusal, .. }) = read(text, "rigid.json", None) else { panic!("read") };
        assert_eq!(refusal, Refusal::Template { template: "RigidSuspension".into() });
        assert!(
            refusal.to_string().starts_with(
                "Project Chrono template 'RigidSuspension': it has no suspension motion to analyse; it reads \
                 DoubleWishbone, "
            ),
            "{refusal}"
        );
    }
}
