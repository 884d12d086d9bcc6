//! What the commands read: input files whole, a model file of either format, and the document its numbers
//! are edited in.

use super::strict::strict_model;
use crate::output::{Failure, Stdout};
use elastokin::suspensions::design::targets::{read_targets_as, Reading, Targets};
use elastokin::suspensions::import::chrono::Imported;
use elastokin::suspensions::study::batch::base_document;
use elastokin::suspensions::SuspensionFile;
use std::path::Path;

/// Reads the model file at `path` for a command that runs it: refused under `--strict` (`strict`) when its
/// checks warn, and, for another tool's file, the line saying how it was read printed to `out`.
pub fn open_model(path: &Path, out: &Stdout, strict: bool) -> Result<ModelInput, Failure> {
    let read = read_model(path)?;
    strict_model(path, &read.file, strict)?;
    if let Some(line) = read.format_line() {
        out.line(line)?;
    }
    Ok(read)
}

/// Reads an input file whole; errors name the file and what it is for.
pub fn read_input(path: &Path, what: &str) -> Result<(Vec<u8>, String), Failure> {
    elastokin::suspensions::file::read_input(path, what).map_err(|e| Failure::Input(e.to_string()))
}

/// A model read from a file: its bytes (for the provenance hash), the model parsed from them and, for
/// another tool's file, how it was read.
pub struct ModelInput {
    pub bytes: Vec<u8>,
    pub file: SuspensionFile,
    pub imported: Option<Imported>,
}

impl ModelInput {
    /// The line that says which format the file was read as (another tool's only), with the count of notes.
    pub fn format_line(&self) -> Option<String> {
        self.imported.as_ref().map(|i| {
            format!(
                "read as a Project Chrono {} suspension ({} notes: `elastokin import chrono FILE` lists them)",
                i.template,
                i.notes.len()
            )
        })
    }

    /// The model file at `path` as written, the document a parameter or variant edits: a Chrono file's own
    /// keys (its comments removed).
    pub fn document(&self, path: &Path) -> Result<serde_json::Value, Failure> {
        base_document(&String::from_utf8_lossy(&self.bytes), &path.display().to_string())
            .map_err(|e| Failure::Input(e.to_string()))
    }
}

/// The model file: an elastokin model file, or a Project Chrono suspension file (recognised by its
/// `"Type": "Suspension"` and `"Template"`).
pub fn read_model(path: &Path) -> Result<ModelInput, Failure> {
    let (bytes, text) = read_input(path, "MODEL")?;
    let (file, imported) = elastokin::suspensions::document::parse_model(&text, &path.display().to_string())
        .map_err(|e| Failure::Input(e.to_string()))?;
    Ok(ModelInput { bytes, file, imported })
}

/// The TARGETS file at `path`, read for `reading` against the model's document `base`, with its bytes (for
/// the provenance hash); a measured file it names is read beside it.
pub fn read_targets_file(
    path: &Path,
    base: &serde_json::Value,
    reading: Reading,
) -> Result<(Vec<u8>, Targets), Failure> {
    let (bytes, text) = read_input(path, "TARGETS")?;
    // A measured file is named relative to the targets file.
    let beside = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let read_file = |name: &str| {
        std::fs::read_to_string(beside.join(name))
            .map_err(|e| format!("cannot read {}: {e}", beside.join(name).display()))
    };
    let targets = read_targets_as(reading, &text, &path.display().to_string(), base, read_file)
        .map_err(|e| Failure::Input(e.to_string()))?;
    Ok((bytes, targets))
}
