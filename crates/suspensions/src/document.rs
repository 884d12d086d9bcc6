//! One way in for every model document: an elastokin model file or a Project Chrono suspension file,
//! told apart by its content, read by its format's reader and then built once, so that a document that
//! reads but cannot be built is refused with the builder's named error before anything is analysed.
//! Above the file format ([`crate::file`]), the importers ([`crate::import`]) and the builder.

use crate::assembly::rig::Rig;
use crate::description::Side;
use crate::file::{FileError, InDocument, SuspensionFile};
use crate::import::chrono::{self, is_chrono, ImportError, Imported};
use std::path::Path;

impl SuspensionFile {
    /// Parses JSON text; `origin` names the source in errors. Refuses values no suspension has (see
    /// [`SuspensionFile::check_ranges`]) with the key, its line and column, and the accepted range, and a
    /// model that cannot be built with the builder's error.
    pub fn from_json(text: &str, origin: &str) -> Result<Self, FileError> {
        let file = Self::parse_checked(text, origin, true)?;
        build_check(&file, origin)?;
        Ok(file)
    }

    /// [`SuspensionFile::from_json`] without the range checks: for studies that scale a model beyond
    /// plausible values on purpose (bushing rates ×10⁶, the same corner in millimetres).
    pub fn from_json_any_magnitude(text: &str, origin: &str) -> Result<Self, FileError> {
        let file = Self::parse_checked(text, origin, false)?;
        build_check(&file, origin)?;
        Ok(file)
    }

    /// Reads a model file.
    pub fn read(path: &Path) -> Result<Self, FileError> {
        let text =
            std::fs::read_to_string(path).map_err(|source| FileError::Io { path: path.to_path_buf(), source })?;
        Self::from_json(&text, &path.display().to_string())
    }
}

/// Building validates the geometry (coincident points, …) with named errors.
fn build_check(file: &SuspensionFile, origin: &str) -> Result<(), FileError> {
    file.suspension
        .build(Side::Left, Rig::Free)
        .map(drop)
        .map_err(|source| FileError::Model { origin: origin.to_string(), source })
}

/// Reads a Project Chrono suspension file into the general form ([`chrono::read`]) and builds it, as every
/// model is: `origin` names it in errors, `loaded_radius` (m) is the tyre's (Chrono's suspension files have
/// none).
pub fn import_chrono(text: &str, origin: &str, loaded_radius: Option<f64>) -> Result<Imported, ImportError> {
    let imported = chrono::read(text, origin, loaded_radius)?;
    build_check(&imported.file, origin)?;
    Ok(imported)
}

/// A model document refused, in its format's reader's words.
#[derive(Debug, thiserror::Error)]
pub enum DocumentError {
    /// A Project Chrono suspension file refused by the importer or the builder.
    #[error("{0} (read as a Project Chrono suspension file)")]
    Chrono(ImportError),
    /// An elastokin model file refused.
    #[error(transparent)]
    File(#[from] FileError),
    /// An elastokin model document that is no file refused, placed by its keys.
    #[error(transparent)]
    Document(#[from] InDocument),
    /// A parsed document that could not be written as text to be read, in the JSON writer's words.
    #[error("{0}")]
    Json(serde_json::Error),
}

/// A model file's text as a model: an elastokin model file, or a Project Chrono suspension file (recognised
/// by its `"Type": "Suspension"` and `"Template"`), then with how it was read.
pub fn parse_model(text: &str, origin: &str) -> Result<(SuspensionFile, Option<Imported>), DocumentError> {
    if is_chrono(text) {
        let imported = import_chrono(text, origin, None).map_err(DocumentError::Chrono)?;
        return Ok((imported.file.clone(), Some(imported)));
    }
    Ok((SuspensionFile::from_json(text, origin)?, None))
}

/// [`parse_model`] of a document that is no file (a Python dict, a variant's edited model): its errors name
/// the place by its keys ([`FileError::in_document`]).
pub fn parse_document(text: &str, origin: &str) -> Result<(SuspensionFile, Option<Imported>), DocumentError> {
    parse_document_of_kind(text, is_chrono(text), origin)
}

/// An elastokin model document already parsed (not Project Chrono's), read as [`parse_document`] reads its
/// text, without writing it as text first: the same file, checked the same way, and built unless `built`
/// is false (a caller that builds the model at once and says why a build fails in the builder's words: a
/// sensitivity's moved models, each built for the analyses that replay it, where a build to check it first
/// would double the builds). What it refuses is read from the text after all, for the message that places
/// the key.
pub(crate) fn parse_value(
    document: &serde_json::Value,
    origin: &str,
    built: bool,
) -> Result<SuspensionFile, DocumentError> {
    if let Ok(file) = <SuspensionFile as serde::Deserialize>::deserialize(document) {
        if file.check_ranges().is_ok() && (!built || build_check(&file, origin).is_ok()) {
            return Ok(file);
        }
    }
    let text = serde_json::to_string(document).map_err(DocumentError::Json)?;
    parse_document_of_kind(&text, false, origin).map(|(file, _)| file)
}

/// [`parse_document`] of a text whose kind is known already (from its parsed value, which a variant's edit
/// has at hand), so that the text is not parsed once more to tell.
pub(crate) fn parse_document_of_kind(
    text: &str,
    chrono: bool,
    origin: &str,
) -> Result<(SuspensionFile, Option<Imported>), DocumentError> {
    if chrono {
        return parse_model(text, origin);
    }
    SuspensionFile::from_json(text, origin).map(|file| (file, None)).map_err(|e| e.in_document(text).into())
}
