//! What produced a result: the elastokin version, the model file and its SHA-256, the stepping and the
//! command line, written into every result (`summary.json`, the first line of every CSV, the HTML report)
//! so that a file found later still says how it was made.

use sha2::{Digest, Sha256};
use std::path::Path;

/// What produced a result: written into `summary.json` and as the first line of every CSV, so a file
/// found later still says which program, model and settings made it.
#[derive(Debug, Clone, PartialEq)]
pub struct Provenance {
    /// The elastokin version.
    pub elastokin: &'static str,
    /// The model file's path as given on the command line.
    pub model: String,
    /// SHA-256 of the model file's bytes (lower-case hex), the bytes that were parsed.
    pub model_sha256: String,
    /// `batch`: the variants file's path and SHA-256.
    pub variants: Option<(String, String)>,
    /// `tune`: the targets file's path and SHA-256.
    pub targets: Option<(String, String)>,
    /// `corrected` or `paper`.
    pub mode: &'static str,
    /// Load steps per sweep.
    pub steps: usize,
    /// Road loads: `held` or `free`; `None` where no road load is run.
    pub wheel: Option<&'static str>,
    /// Load analyses: `contact_patch` or `wheel_centre`; `None` where no load is run.
    pub load_point: Option<&'static str>,
    /// The `--range` given, if any (each analysis otherwise has its own default, in `summary.json`).
    pub range: Option<(f64, f64)>,
    /// The command line, arguments joined by spaces.
    pub command: String,
    /// When it was made (RFC 3339, UTC, to the second).
    pub date: String,
    /// The error tolerance the run was checked against, when it ran analyses.
    pub tolerance: Option<elastokin_suspensions::kc::Tolerance>,
    /// `batch --shard`: which part of a batch this is; `merge`: how many shards it joined.
    pub part: Option<Part>,
    /// The other files the result was read from, each path and SHA-256: `compare`'s designs after the
    /// first (`model`), `vehicle`'s front and rear models (`model` the vehicle file).
    pub other_files: Vec<(String, String)>,
}

/// A result that is one part of a batch, or the shards of one joined.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// Shard `index` of `count` (1-based) of a batch of `variants` variants.
    Shard { index: usize, count: usize, variants: usize },
    /// The `shards` shards of a batch, merged.
    Merged { shards: usize },
}

impl Part {
    /// What the comment line ends with: `, shard 2/3 of 6 variants` or `, merged from 3 shards`; the merge
    /// reads the first back.
    pub fn suffix(self) -> String {
        match self {
            Part::Shard { index, count, variants } => format!(", shard {index}/{count} of {variants} variants"),
            Part::Merged { shards } => format!(", merged from {shards} shards"),
        }
    }
}

impl Provenance {
    /// The provenance of a run on the model file whose bytes are `model_bytes`.
    pub fn new(model: &Path, model_bytes: &[u8], mode: &'static str, steps: usize) -> Provenance {
        Provenance {
            elastokin: env!("CARGO_PKG_VERSION"),
            model: model.display().to_string(),
            model_sha256: sha256_hex(model_bytes),
            variants: None,
            targets: None,
            mode,
            steps,
            wheel: None,
            load_point: None,
            range: None,
            command: std::env::args_os().map(|a| a.to_string_lossy().into_owned()).collect::<Vec<_>>().join(" "),
            date: humantime::format_rfc3339_seconds(std::time::SystemTime::now()).to_string(),
            tolerance: None,
            part: None,
            other_files: Vec::new(),
        }
    }

    /// The JSON object for `summary.json`.
    pub fn to_json(&self) -> serde_json::Value {
        let mut v = serde_json::json!({
            "elastokin": self.elastokin,
            "model": self.model,
            "model_sha256": self.model_sha256,
            "mode": self.mode,
            "steps": self.steps,
            "wheel": self.wheel,
            "load_point": self.load_point,
            "range": self.range.map(|(a, b)| [a, b]),
            "command": self.command,
            "date": self.date,
        });
        if let Some(t) = self.tolerance {
            v["tolerance"] = serde_json::json!({
                "angle_deg": t.angle_deg,
                "length_mm": t.length_m * 1e3,
                "figures_percent": t.relative * 1e2,
            });
        }
        if let Some((path, sha)) = &self.variants {
            v["variants"] = path.as_str().into();
            v["variants_sha256"] = sha.as_str().into();
        }
        if let Some((path, sha)) = &self.targets {
            v["targets"] = path.as_str().into();
            v["targets_sha256"] = sha.as_str().into();
        }
        if !self.other_files.is_empty() {
            v["other_files"] = self
                .other_files
                .iter()
                .map(|(path, sha)| serde_json::json!({ "file": path, "sha256": sha }))
                .collect::<Vec<_>>()
                .into();
        }
        match self.part {
            Some(Part::Shard { index, count, variants }) => {
                v["shard"] = serde_json::json!({ "index": index, "count": count, "variants": variants });
            }
            Some(Part::Merged { shards }) => v["merged_from_shards"] = shards.into(),
            None => {}
        }
        v
    }

    /// The comment line that opens every CSV (without the line end):
    /// `# elastokin 0.1.0, model examples/macpherson.json (sha256 0123456789abcdef), corrected mode, 32 steps`.
    pub fn comment_line(&self) -> String {
        let mut line = format!(
            "# elastokin {}, model {} (sha256 {}), {} mode, {} steps",
            self.elastokin,
            self.model,
            &self.model_sha256[..16.min(self.model_sha256.len())],
            self.mode,
            self.steps
        );
        if let Some((path, sha)) = &self.variants {
            line += &format!(", variants {path} (sha256 {})", &sha[..16.min(sha.len())]);
        }
        for (path, sha) in &self.other_files {
            line += &format!(", with {path} (sha256 {})", &sha[..16.min(sha.len())]);
        }
        if let Some(part) = self.part {
            line += &part.suffix();
        }
        // A line break in a path would end the comment early and leave a broken first row.
        line.chars().map(|c| if c.is_control() { '?' } else { c }).collect()
    }

    /// `svg` with the provenance as an XML comment before its root element, so a plot found alone still
    /// says what made it (a comment may not hold `--`, so a path's double hyphen is spaced).
    pub fn stamp_svg(&self, svg: &str) -> String {
        let line = self.comment_line();
        let text = line.trim_start_matches("# ").replace("--", "- -");
        match svg.find("<svg") {
            Some(at) => format!("{}<!-- {text} -->\n{}", &svg[..at], &svg[at..]),
            None => svg.to_string(),
        }
    }
}

/// SHA-256 of `bytes` as lower-case hex.
pub fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes).iter().map(|b| format!("{b:02x}")).collect()
}
