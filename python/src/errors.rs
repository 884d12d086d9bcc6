//! The exceptions the module raises: one base class, and what a model or an analysis failed at.

use pyo3::create_exception;
use pyo3::exceptions::PyException;

create_exception!(elastokin._native, Error, PyException, "Every error elastokin raises.");
create_exception!(
    elastokin._native,
    ModelError,
    Error,
    "A model file, model dict or variant edit that cannot be read as a suspension model."
);
create_exception!(
    elastokin._native,
    AnalysisError,
    Error,
    "An analysis that failed on the model: the solver's reason."
);
