//! The words a Python caller gives for the library's choices (an analysis, a solver mode), read as the
//! library's values, or a `ValueError` that lists the words there are.

use elastokin_solver::Mode;
use elastokin_suspensions::kc::{self, Analysis};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// An analysis by its command-line name; a name that is none is a `ValueError` listing the names.
pub(crate) fn analysis(name: &str) -> PyResult<Analysis> {
    Analysis::from_name(name).ok_or_else(|| {
        let names: Vec<&str> = kc::ALL.iter().map(|a| a.name()).collect();
        PyValueError::new_err(format!("no analysis '{name}': give one of {}", names.join(", ")))
    })
}

/// The solver mode a word names ("corrected" or "paper"), or a `ValueError` saying which words there are.
pub(crate) fn mode_from_word(word: &str) -> PyResult<Mode> {
    kc::mode_from_word(word).ok_or_else(|| PyValueError::new_err(format!("mode '{word}': give 'corrected' or 'paper'")))
}
