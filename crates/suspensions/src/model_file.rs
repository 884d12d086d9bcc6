//! Model files: a suspension template in JSON, SI units, ISO 8855 axes (x forward, y left, z up), left
//! corner (the right is mirrored).
//!
//! ```json
//! { "name": "generic double wishbone",
//!   "suspension": { "double_wishbone": {
//!       "hardpoints": { "wheel_centre": [-0.04, 1.1, -0.026], … },
//!       "upper_arm_mounts": "ideal",
//!       "lower_arm_mounts": { "bushing": { "radial": 5e6, "axial": 1e6, "torsion": 573, "conical": 5730 } },
//!       "spring": { "rate": 30000, "design_force": 4000 } } } }
//! ```
//!
//! Unknown keys and missing hardpoints are errors that name the key and the line and column in the file.

use crate::analysis::VehicleParameters;
use crate::corner::{Corner, CornerParts, CornerTemplate, Rig};
use crate::double_wishbone::DoubleWishbone;
use crate::hardpoint::Side;
use crate::macpherson::MacPherson;
use elastokin_core::{Model, ModelError};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Which template a file describes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Template {
    /// A double-wishbone corner.
    DoubleWishbone(DoubleWishbone),
    /// A MacPherson strut corner.
    #[serde(rename = "macpherson")]
    MacPherson(MacPherson),
}

impl Template {
    /// Builds the corner (see [`Corner::build`]).
    pub fn build(&self, side: Side, rig: Rig) -> Result<Corner, ModelError> {
        Corner::build(self, side, rig)
    }
}

impl CornerTemplate for Template {
    fn add_corner(&self, model: &mut Model, side: Side, prefix: &str) -> Result<CornerParts, ModelError> {
        match self {
            Template::DoubleWishbone(t) => t.add_corner(model, side, prefix),
            Template::MacPherson(t) => t.add_corner(model, side, prefix),
        }
    }
}

/// The content of a model file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SuspensionFile {
    /// A name for reports.
    pub name: String,
    /// The suspension.
    pub suspension: Template,
    /// The vehicle around it, for the static load case, the road loads and the anti-pitch figures;
    /// optional (those analyses are then skipped or take the design wheel load).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vehicle: Option<VehicleParameters>,
}

/// A model file that cannot be read.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum FileError {
    /// The file could not be opened or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The file is not a valid model (bad JSON, unknown key, missing hardpoint, wrong type).
    #[error("{origin}:{line}:{column}: {message}")]
    Invalid {
        /// The file (or the origin given to [`SuspensionFile::from_json`]).
        origin: String,
        /// Line, from 1.
        line: usize,
        /// Column, from 1.
        column: usize,
        /// What is wrong, naming the key.
        message: String,
    },
    /// The file parses but describes an inconsistent model.
    #[error("{origin}: {source}")]
    Model {
        /// The file.
        origin: String,
        /// The model error.
        source: ModelError,
    },
}

impl SuspensionFile {
    /// Parses JSON text; `origin` names the source in errors.
    pub fn from_json(text: &str, origin: &str) -> Result<Self, FileError> {
        let file: SuspensionFile = serde_json::from_str(text).map_err(|e| FileError::Invalid {
            origin: origin.to_string(),
            line: e.line(),
            column: e.column(),
            message: e.to_string().split(" at line ").next().unwrap_or_default().to_string(),
        })?;
        if let Some(vehicle) = &file.vehicle {
            vehicle.validate().map_err(|e| FileError::Invalid {
                origin: origin.to_string(),
                line: text.lines().position(|l| l.contains("\"vehicle\"")).map_or(1, |k| k + 1),
                column: 1,
                message: format!("vehicle: {e}"),
            })?;
        }
        // Building validates the geometry (coincident points, non-positive rates, …) with named errors.
        file.suspension
            .build(Side::Left, Rig::Free)
            .map_err(|source| FileError::Model { origin: origin.to_string(), source })?;
        Ok(file)
    }

    /// Reads a model file.
    pub fn read(path: &Path) -> Result<Self, FileError> {
        let text =
            std::fs::read_to_string(path).map_err(|source| FileError::Io { path: path.to_path_buf(), source })?;
        Self::from_json(&text, &path.display().to_string())
    }

    /// The file as pretty JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("a model of plain numbers and strings always serialises")
    }

    /// Writes the file.
    pub fn write(&self, path: &Path) -> Result<(), FileError> {
        std::fs::write(path, self.to_json()).map_err(|source| FileError::Io { path: path.to_path_buf(), source })
    }
}
