//! `Model.live`: the library's live server (`elastokin::live::LiveServer`, the one `elastokin live` starts)
//! started on a model's file from Python, and its handle: the page's address, and a stop that waits until
//! the server's thread has ended and its port is free.

use crate::errors::ModelError;
use elastokin::live::{reachable_from_elsewhere, FrameAncestors, OpenError, ServeError, Served};
use elastokin_suspensions::design::targets::{read_targets_as, Reading};
use elastokin_suspensions::kc::Analysis;
use pyo3::exceptions::{PyOSError, PyRuntimeWarning, PyValueError};
use pyo3::prelude::*;
use std::net::{IpAddr, SocketAddr};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// What `Model.live` asks for: the model file, the analyses (the suite when empty) and their steps, the
/// TARGETS file's text (files it names read from `directory`), where to listen and who may frame the page.
#[derive(Debug)]
pub(crate) struct Asked<'a> {
    pub path: &'a Path,
    pub which: Vec<Analysis>,
    pub steps: usize,
    pub targets: Option<&'a str>,
    pub directory: &'a str,
    pub port: u16,
    pub bind: &'a str,
    pub frame_ancestors: Vec<String>,
}

/// A live server started from Python: stopped by `stop`, or when it is garbage collected.
#[pyclass(frozen, module = "elastokin._native")]
#[derive(Debug)]
pub(crate) struct LiveServer {
    address: String,
    port: u16,
    server: Mutex<Option<elastokin::live::LiveServer>>,
}

/// Starts the server `asked` for: the model file read as it is now and its design run, judged against the
/// targets when given, served on its own thread. Bad settings, a bad bind address or frame ancestor and
/// bad targets raise `ValueError`; a file that does not read or build, `ModelError`; a port that cannot be
/// listened on, `OSError`. A bind address beyond this machine warns (`RuntimeWarning`), as the command
/// does.
pub(crate) fn start(py: Python<'_>, asked: Asked) -> PyResult<LiveServer> {
    let ip: IpAddr = asked.bind.parse().map_err(|_| {
        PyValueError::new_err(format!("bind '{}': give an IP address, such as 127.0.0.1 (this machine alone)", asked.bind))
    })?;
    let ancestors =
        FrameAncestors::new(&asked.frame_ancestors).map_err(|e| PyValueError::new_err(e.to_string()))?;
    let mut served = py.detach(|| Served::open(asked.path, &asked.which, asked.steps)).map_err(|e| match e {
        OpenError::Settings(e) => PyValueError::new_err(e.to_string()),
        e @ (OpenError::Input(_) | OpenError::Design(_)) => ModelError::new_err(e.to_string()),
    })?;
    if let Some(text) = asked.targets {
        let document = served.design.document().map_err(|e| ModelError::new_err(e.to_string()))?;
        let beside = PathBuf::from(asked.directory);
        let read_file = |name: &str| {
            let path = beside.join(name);
            std::fs::read_to_string(&path).map_err(|e| format!("cannot read {}: {e}", path.display()))
        };
        let targets = read_targets_as(Reading::ToJudge, text, "targets", &document, read_file)
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        served.design = served.design.judged_against(targets);
    }
    if let Some(warning) = reachable_from_elsewhere(ip, &asked.path.display().to_string()) {
        PyErr::warn(py, &py.get_type::<PyRuntimeWarning>(), &std::ffi::CString::new(warning)?, 1)?;
    }
    let server = elastokin::live::LiveServer::start(served, SocketAddr::new(ip, asked.port), ancestors).map_err(
        |e| match e {
            e @ ServeError::Listen { .. } => PyOSError::new_err(format!("{e} (choose another port=, or 0 for any free one)")),
            e => PyOSError::new_err(e.to_string()),
        },
    )?;
    Ok(LiveServer { address: server.address().to_string(), port: server.bound().port(), server: Mutex::new(Some(server)) })
}

#[pymethods]
impl LiveServer {
    /// The page's address, token included.
    #[getter]
    fn address(&self) -> &str {
        &self.address
    }

    /// The port listened on.
    #[getter]
    fn port(&self) -> u16 {
        self.port
    }

    /// Whether the server is serving (not yet stopped).
    #[getter]
    fn serving(&self) -> bool {
        self.server.lock().is_ok_and(|s| s.is_some())
    }

    /// Stops the server: the request being served is finished, its thread ends and its port is free when
    /// this returns. Whether the edits since the last save were left unsaved (False when it was stopped
    /// already).
    fn stop(&self, py: Python<'_>) -> bool {
        let taken = self.server.lock().ok().and_then(|mut s| s.take());
        py.detach(move || taken.and_then(|mut s| s.stop()).is_some_and(|live| live.unsaved()))
    }
}
