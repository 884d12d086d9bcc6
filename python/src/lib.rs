//! `elastokin._native`: the Python extension. A thin layer over the library: every number comes from
//! `elastokin_suspensions` (the same calls the `elastokin` command makes); this only converts arguments and
//! results, maps the library's errors to Python exceptions with the command's messages, and lets go of the
//! GIL while the solver works so that Python threads run analyses side by side.

use elastokin_suspensions::analysis::wheel_compliance;
use elastokin_suspensions::document::{parse_document, parse_model};
use elastokin_suspensions::file::read_input;
use elastokin_suspensions::kc::{self, Analysis, Cell, Settings, Table};
use elastokin_suspensions::study::batch::{self, Variant};
use elastokin_suspensions::study::shard::Shard;
use elastokin_suspensions::{LoadPoint, Rig, Side, SuspensionFile};
use numpy::{PyArray1, PyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyFloat, PyList, PyString};
use rayon::prelude::*;
use std::path::Path;

mod errors;
mod live;
mod scene;
mod words;

use errors::{AnalysisError, Error, ModelError};
use words::{analysis, mode_from_word};

/// The time one chunk of a batch's variants takes, between which Python hears its signals (s).
const CHUNK_SECONDS: f64 = 0.1;

/// A suspension model read from a model file or a dict, with the document that batch variants edit.
#[pyclass(frozen, module = "elastokin._native")]
struct Model {
    file: SuspensionFile,
    base: serde_json::Value,
    /// Where it came from, for error messages (a path, or the origin given with a dict).
    origin: String,
    /// The model file it was read from, made absolute when read (None for a dict or text): what `live`
    /// serves and saves.
    path: Option<std::path::PathBuf>,
}

/// The command's options of `run` as the library's settings.
#[allow(clippy::too_many_arguments, reason = "run and suite pass on their Python keyword arguments")]
fn settings(
    range: Option<(f64, f64)>,
    steps: usize,
    mode: &str,
    wheel: &str,
    load_point: &str,
    compliance: bool,
    through_limits: bool,
    arc_step: Option<f64>,
) -> PyResult<Settings> {
    let mode = mode_from_word(mode)?;
    let height_held = match wheel {
        "held" => true,
        "free" => false,
        _ => return Err(PyValueError::new_err(format!("wheel '{wheel}': give 'held' or 'free'"))),
    };
    // The command's spelling (`--load-point wheel-centre`) is taken too.
    let load_point = match load_point {
        "contact_patch" | "contact-patch" => LoadPoint::ContactPatch,
        "wheel_centre" | "wheel-centre" => LoadPoint::WheelCentre,
        _ => {
            return Err(PyValueError::new_err(format!(
                "load_point '{load_point}': give 'contact_patch' or 'wheel_centre'"
            )))
        }
    };
    Ok(Settings {
        range,
        steps,
        mode,
        height_held,
        load_point,
        compliance,
        through_limits,
        arc_step,
        ..Settings::default()
    })
}

/// A variant as a study sends it: its name and its `(JSON pointer, JSON text of the value)` edits.
type VariantEdits = (String, Vec<(String, String)>);

/// A table's columns for Python: `(column name, values)` pairs.
type Columns<'py> = Vec<(String, Bound<'py, PyAny>)>;

/// A table as `(column name, values)` pairs in the table's order: a column of numbers is a float array
/// (NaN where a row has no value, as the CSV leaves the cell empty), a column of names a list of its cells
/// (str, float, or None for an empty one).
fn columns<'py>(py: Python<'py>, table: &Table) -> PyResult<Columns<'py>> {
    let mut out = Vec::with_capacity(table.columns.len());
    for (k, name) in table.columns.iter().enumerate() {
        let cells: Vec<&Cell> = table.rows.iter().map(|row| row.get(k).unwrap_or(&Cell::Empty)).collect();
        let values = if cells.iter().all(|c| !matches!(c, Cell::Text(_))) {
            let numbers: Vec<f64> = cells.iter().map(|c| c.number().unwrap_or(f64::NAN)).collect();
            PyArray1::from_vec(py, numbers).into_any()
        } else {
            let texts: Vec<Bound<'py, PyAny>> = cells
                .iter()
                .map(|c| match c {
                    Cell::Number(v) => PyFloat::new(py, *v).into_any(),
                    Cell::Text(t) => PyString::new(py, t).into_any(),
                    Cell::Empty => py.None().into_bound(py),
                })
                .collect();
            PyList::new(py, texts)?.into_any()
        };
        out.push((name.clone(), values));
    }
    Ok(out)
}

/// A table as a dict of its columns (see [`columns`]).
fn column_dict<'py>(py: Python<'py>, table: &Table) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (name, values) in columns(py, table)? {
        d.set_item(name, values)?;
    }
    Ok(d)
}

fn to_json<T: serde::Serialize>(value: &T) -> PyResult<String> {
    serde_json::to_string(value).map_err(|e| AnalysisError::new_err(e.to_string()))
}

#[pymethods]
impl Model {
    /// Reads a model file (an elastokin model file or a Project Chrono suspension file), as `elastokin run`
    /// reads it.
    #[staticmethod]
    fn read(py: Python<'_>, path: &str) -> PyResult<Model> {
        py.detach(|| {
            let (_, text) = read_input(Path::new(path), "MODEL").map_err(|e| e.to_string())?;
            let (file, _) = parse_model(&text, path).map_err(|e| e.to_string())?;
            let base = batch::base_document(&text, path).map_err(|e| e.to_string())?;
            let absolute = std::path::absolute(path).map_err(|e| format!("{path}: {e}"))?;
            Ok::<_, String>(Model { file, base, origin: path.to_string(), path: Some(absolute) })
        })
        .map_err(ModelError::new_err)
    }

    /// A model from a document in the model-file format (a dict's JSON text); `origin` names it in error
    /// messages, which name a mistake's place by its keys (`bodies[1].mass`), not a line and column of text
    /// the user never saw.
    #[staticmethod]
    fn from_json(py: Python<'_>, text: &str, origin: &str) -> PyResult<Model> {
        py.detach(|| {
            let (file, _) = parse_document(text, origin).map_err(|e| e.to_string())?;
            let base = batch::base_document(text, origin).map_err(|e| e.to_string())?;
            Ok::<_, String>(Model { file, base, origin: origin.to_string(), path: None })
        })
        .map_err(ModelError::new_err)
    }

    /// The model's name.
    #[getter]
    fn name(&self) -> &str {
        &self.file.name
    }

    /// The model in the model-file format (JSON text).
    fn to_json(&self) -> String {
        self.file.to_json()
    }

    /// Variants in any form `batch` takes, in any number, read and checked against this model as `batch`
    /// checks them but without reading a model for each: `(name, [(pointer, JSON text of the value)])` for
    /// each, the form a study sends to its workers.
    fn read_variants(&self, variants: &Bound<'_, PyAny>) -> PyResult<Vec<VariantEdits>> {
        let list = parse_variants(variants, None)?;
        list.iter()
            .try_for_each(|v| batch::check_keys(&self.base, v))
            .map_err(|e| ModelError::new_err(e.to_string()))?;
        list.into_iter()
            .map(|v| {
                let edits =
                    v.edits.iter().map(|(p, value)| Ok((p.clone(), to_json(value)?))).collect::<PyResult<_>>()?;
                Ok((v.name, edits))
            })
            .collect()
    }

    /// The document as read — the text batch variants edit (a Project Chrono file's own keys) — and its
    /// origin: what `from_json` takes to make this model again, in another process or on another machine.
    fn document(&self) -> PyResult<(String, String)> {
        Ok((to_json(&self.base)?, self.origin.clone()))
    }

    /// One analysis: `(report as JSON text, table columns, compliance table columns or None)`.
    #[pyo3(signature = (name, range=None, steps=32, mode="corrected", wheel="held", load_point="contact_patch",
                        compliance=false, through_limits=false, arc_step=None))]
    #[allow(clippy::too_many_arguments, reason = "a Python method's keyword arguments, each named by its caller")]
    fn run<'py>(
        &self,
        py: Python<'py>,
        name: &str,
        range: Option<(f64, f64)>,
        steps: usize,
        mode: &str,
        wheel: &str,
        load_point: &str,
        compliance: bool,
        through_limits: bool,
        arc_step: Option<f64>,
    ) -> PyResult<(String, Columns<'py>, Option<Columns<'py>>)> {
        let analysis = analysis(name)?;
        let settings = settings(range, steps, mode, wheel, load_point, compliance, through_limits, arc_step)?;
        let report = py
            .detach(|| kc::run(analysis, &self.file, &settings))
            .map_err(|e| AnalysisError::new_err(e.to_string()))?;
        let table = columns(py, &report.table)?;
        let compliance = report.compliance.as_ref().map(|c| columns(py, c)).transpose()?;
        Ok((to_json(&report)?, table, compliance))
    }

    /// The K&C suite (every analysis that applies, or those named) as JSON text: the content of the
    /// command's summary.json but its provenance.
    #[pyo3(signature = (analyses=None, range=None, steps=32, mode="corrected", wheel="held",
                        load_point="contact_patch", compliance=false, through_limits=false, arc_step=None))]
    #[allow(clippy::too_many_arguments, reason = "a Python method's keyword arguments, each named by its caller")]
    fn suite(
        &self,
        py: Python<'_>,
        analyses: Option<Vec<String>>,
        range: Option<(f64, f64)>,
        steps: usize,
        mode: &str,
        wheel: &str,
        load_point: &str,
        compliance: bool,
        through_limits: bool,
        arc_step: Option<f64>,
    ) -> PyResult<String> {
        let which = analyses.unwrap_or_default().iter().map(|n| analysis(n)).collect::<PyResult<Vec<_>>>()?;
        if range.is_some() && which.len() != 1 {
            return Err(PyValueError::new_err(
                "range needs one analysis: each analysis has its own load parameter and units",
            ));
        }
        let settings = settings(range, steps, mode, wheel, load_point, compliance, through_limits, arc_step)?;
        let report = py
            .detach(|| kc::run_suite(&self.file, &which, &settings, |_| {}).complete())
            .map_err(|e| AnalysisError::new_err(e.to_string()))?;
        to_json(&report)
    }

    /// The model file served as `elastokin live` serves it, on `bind` and `port` (0: any free one), its
    /// page framed by its own origin and `frame_ancestors`: see [`live::start`].
    #[pyo3(signature = (analyses=None, steps=32, targets=None, directory=".", port=0, bind="127.0.0.1",
                        frame_ancestors=Vec::new()))]
    #[allow(clippy::too_many_arguments, reason = "a Python method's keyword arguments, each named by its caller")]
    fn live(
        &self,
        py: Python<'_>,
        analyses: Option<Vec<String>>,
        steps: usize,
        targets: Option<&str>,
        directory: &str,
        port: u16,
        bind: &str,
        frame_ancestors: Vec<String>,
    ) -> PyResult<live::LiveServer> {
        let Some(path) = &self.path else {
            return Err(ModelError::new_err(format!(
                "{}: the model was not read from a file, and the live server edits and saves a model file: write \
                 the model to a file (json.dump(model.to_dict(), f)) and serve that (elastokin.load(path).live())",
                self.origin
            )));
        };
        let which = analyses.unwrap_or_default().iter().map(|n| analysis(n)).collect::<PyResult<Vec<_>>>()?;
        let asked = live::Asked { path, which, steps, targets, directory, port, bind, frame_ancestors };
        live::start(py, asked)
    }

    /// Every coordinate of every hardpoint, as parameter pointers (the command's `--hardpoints`).
    fn hardpoint_parameters(&self) -> Vec<String> {
        elastokin_suspensions::design::hardpoint_pointers(&self.base)
    }

    /// Tunes the model to the TARGETS file's text `targets` (measured files named in it are read from
    /// `directory`), as the command's `tune`: a dict of `stopped` (why the iterations ended), `all_met`,
    /// `verdicts` (each target's label, largest miss over its tolerance, whether met and why not),
    /// `parameters`, their values `before` and `after`, `iterations` (`tune.csv`'s columns by name) and
    /// `tuned` (the model file's text with the numbers moved).
    #[pyo3(signature = (targets, directory="."))]
    fn tune<'py>(&self, py: Python<'py>, targets: &str, directory: &str) -> PyResult<Bound<'py, PyDict>> {
        use elastokin_suspensions::design::{targets::read_targets, tune::tune, tune::TuneError, Parameters};
        let read_file = |name: &str| {
            let path = Path::new(directory).join(name);
            std::fs::read_to_string(&path).map_err(|e| format!("cannot read {}: {e}", path.display()))
        };
        let t = read_targets(targets, "targets", &self.base, read_file)
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        let pointers: Vec<String> = t.free.iter().map(|f| f.pointer.clone()).collect();
        let p = Parameters::new(&self.base, &pointers).map_err(|e| ModelError::new_err(e.to_string()))?;
        let tuned = py.detach(|| tune(&p, &t, |_| {})).map_err(|e| match e {
            // The targets ask what the model's analyses do not give: a bad TARGETS text, as above.
            TuneError::Targets(why) => PyValueError::new_err(why.to_string()),
            e @ (TuneError::Model(_) | TuneError::Parameters(_) | TuneError::Analysis { .. }) => {
                AnalysisError::new_err(e.to_string())
            }
        })?;
        let d = PyDict::new(py);
        d.set_item("stopped", &tuned.stopped)?;
        d.set_item("all_met", tuned.all_met())?;
        let verdicts = PyList::empty(py);
        for v in &tuned.verdicts {
            let e = PyDict::new(py);
            e.set_item("target", &v.target)?;
            e.set_item("worst", v.worst)?;
            e.set_item("met", v.met)?;
            e.set_item("judged", &v.judged)?;
            e.set_item("why", v.why.as_deref())?;
            verdicts.append(e)?;
        }
        d.set_item("verdicts", verdicts)?;
        let packaging = PyList::empty(py);
        for p in &tuned.packaging {
            let e = PyDict::new(py);
            e.set_item("constraint", &p.constraint)?;
            e.set_item("broken_by", p.broken_by)?;
            packaging.append(e)?;
        }
        d.set_item("packaging", packaging)?;
        d.set_item("parameters", &pointers)?;
        d.set_item("before", PyArray1::from_vec(py, tuned.start.x.clone()))?;
        d.set_item("after", PyArray1::from_vec(py, tuned.end.x.clone()))?;
        d.set_item("iterations", column_dict(py, &tuned.iteration_table())?)?;
        match &tuned.uncertainty {
            Some(u) => d.set_item("uncertainty", uncertainty_dict(py, u, &pointers)?)?,
            None => d.set_item("uncertainty", py.None())?,
        }
        match &tuned.objective {
            Some(o) => {
                let e = PyDict::new(py);
                e.set_item("objective", &o.label)?;
                e.set_item("before", o.start)?;
                e.set_item("after", o.end)?;
                e.set_item("unit", &o.unit)?;
                e.set_item("held_by", &o.held_by)?;
                d.set_item("objective", e)?;
            }
            None => d.set_item("objective", py.None())?,
        }
        let text = serde_json::to_string_pretty(&tuned.document).map_err(|e| AnalysisError::new_err(e.to_string()))?;
        d.set_item("tuned", text)?;
        Ok(d)
    }

    /// The tolerance stack-up of the TOLERANCES file's text `tolerances`, as the command's `tolerance`:
    /// `tolerance.csv`'s columns by name (each figure's value, first-order `worst_case` and `sigma`, the
    /// share `outside` a limit, and with `monte_carlo` samples the sampled spread beside them), the same seed
    /// giving the same samples; and, as tables of columns by name, `contributions`
    /// (tolerance_contributions.csv), `adjustments` (tolerance_adjustments.csv, None without adjustments)
    /// and `samples` (tolerance_samples.csv, None without a Monte Carlo).
    #[pyo3(signature = (tolerances, monte_carlo=None, seed=1))]
    fn tolerance<'py>(
        &self,
        py: Python<'py>,
        tolerances: &str,
        monte_carlo: Option<usize>,
        seed: u64,
    ) -> PyResult<Bound<'py, PyDict>> {
        use elastokin_suspensions::design::tolerance::{read_tolerances, stack_up, StackUpError};
        let t =
            read_tolerances(tolerances, "tolerances", &self.base).map_err(|e| PyValueError::new_err(e.to_string()))?;
        let stack = py
            .detach(|| {
                let mut stack = stack_up(&self.base, &t)?;
                if let Some(n) = monte_carlo {
                    stack.monte_carlo(n, seed);
                }
                Ok(stack)
            })
            .map_err(|e: StackUpError| AnalysisError::new_err(e.to_string()))?;
        let d = column_dict(py, &stack.table())?;
        d.set_item("contributions", column_dict(py, &stack.contribution_table())?)?;
        let optional = |table: Option<Table>| table.map(|t| column_dict(py, &t)).transpose();
        d.set_item("adjustments", optional(stack.adjustment_table())?)?;
        d.set_item("samples", optional(stack.sample_table())?)?;
        Ok(d)
    }

    /// The Monte Carlo samples of the TOLERANCES file's text `tolerances` that `tolerance(monte_carlo=n,
    /// seed=seed)` draws, as a variant table: each number's pointer and its `n` sampled values, as drawn
    /// (before any adjustment the alignment makes).
    #[pyo3(signature = (tolerances, n, seed=1))]
    fn tolerance_samples<'py>(
        &self,
        py: Python<'py>,
        tolerances: &str,
        n: usize,
        seed: u64,
    ) -> PyResult<Bound<'py, PyDict>> {
        use elastokin_suspensions::design::tolerance::read_tolerances;
        use elastokin_suspensions::design::Parameters;
        let t =
            read_tolerances(tolerances, "tolerances", &self.base).map_err(|e| PyValueError::new_err(e.to_string()))?;
        let p = Parameters::new(&self.base, &t.pointers).map_err(|e| ModelError::new_err(e.to_string()))?;
        let samples: Vec<Vec<f64>> = (0..n).map(|i| t.sample(&p.values, seed, i)).collect();
        let d = PyDict::new(py);
        for (k, pointer) in t.pointers.iter().enumerate() {
            d.set_item(pointer, PyArray1::from_vec(py, samples.iter().map(|x| x[k]).collect()))?;
        }
        Ok(d)
    }

    /// Sensitivities of one analysis of the K&C suite to the numbers at `parameters` (JSON pointers),
    /// as the command's `sensitivity` gives them: a dict of the analysis's name, the parameters and their
    /// values, the table's `columns`, every column by name (its rows) and its derivatives as
    /// `d_<column>` (rows × parameters), and `figures`: every figure of the report by key, its value, unit
    /// and derivatives as `sensitivity.csv` writes them (NaN where it has none), the same in SI
    /// (`si_value`, `si_unit`, `si_derivatives`), and `no_derivative` (why, or None); every derivative per
    /// unit of the parameter in the file. With `figures_only`, the rows are read as far as the figures read them
    /// and moved only where the figures read them (`kc::Settings::figures_only`): the same figures, a table
    /// without the columns left out and without derivatives (NaN).
    #[pyo3(signature = (parameters, analysis="parallel-travel", range=None, steps=32, figures_only=false))]
    fn sensitivities<'py>(
        &self,
        py: Python<'py>,
        parameters: Vec<String>,
        analysis: &str,
        range: Option<(f64, f64)>,
        steps: usize,
        figures_only: bool,
    ) -> PyResult<Bound<'py, PyDict>> {
        use elastokin_suspensions::design::{analysis_sensitivity, Derivative, Parameters, Rate};
        let which = self::analysis(analysis)?;
        let settings = Settings { range, steps, figures_only, ..Settings::default() };
        kc::check_settings(which, &settings).map_err(|e| PyValueError::new_err(e.to_string()))?;
        let p = Parameters::new(&self.base, &parameters).map_err(|e| ModelError::new_err(e.to_string()))?;
        let s = py
            .detach(|| analysis_sensitivity(which, &p, &settings))
            .map_err(|e| AnalysisError::new_err(e.to_string()))?;
        let d = PyDict::new(py);
        // Empty cells and missing derivatives are NaN in numpy.
        let numbers = |v: Vec<Option<f64>>| v.into_iter().map(|x| x.unwrap_or(f64::NAN)).collect::<Vec<f64>>();
        // A part of every derivative (its value or its error estimate), NaN where there is none.
        type Part = fn(&Derivative) -> f64;
        let (value, error): (Part, Part) = (|d| d.value, |d| d.error);
        let read = |v: &[Rate], part: Part| numbers(v.iter().map(|r| r.as_ref().ok().map(part)).collect());
        d.set_item("analysis", which.name())?;
        d.set_item("parameters", p.pointers.clone())?;
        d.set_item("values", PyArray1::from_vec(py, p.values.clone()))?;
        d.set_item("columns", s.report.table.columns.clone())?;
        for name in &s.report.table.columns {
            d.set_item(name, PyArray1::from_vec(py, numbers(s.column(name))))?;
            // Row × parameter, the form numpy users index; the derivatives and their error estimates.
            let derivatives: Vec<Vec<Rate>> = (0..p.len()).map(|k| s.d_column(name, k)).collect();
            for (key, part) in [(format!("d_{name}"), value), (format!("d_{name}_error"), error)] {
                let columns: Vec<Vec<f64>> = derivatives.iter().map(|d| read(d, part)).collect();
                let rows: Vec<Vec<f64>> =
                    (0..s.report.table.rows.len()).map(|r| columns.iter().map(|c| c[r]).collect()).collect();
                let array = PyArray2::from_vec2(py, &rows).map_err(|e| AnalysisError::new_err(e.to_string()))?;
                d.set_item(key, array)?;
            }
        }
        let figures = PyDict::new(py);
        for f in &s.report.figures {
            let (_, derivatives) = s.figure(&f.key).expect("the report's own figure");
            let written = f.written(s.report.units);
            let (si, si_errors) = (read(&derivatives, value), read(&derivatives, error));
            let entry = PyDict::new(py);
            entry.set_item("value", written.value)?;
            entry.set_item("unit", written.unit)?;
            entry.set_item("si_value", f.value)?;
            entry.set_item("si_unit", f.unit.si())?;
            entry.set_item(
                "no_derivative",
                derivatives.iter().map(|r| r.err().map(|e| e.reason())).collect::<Vec<_>>(),
            )?;
            entry.set_item("derivatives", PyArray1::from_vec(py, si.iter().map(|d| d * written.factor).collect()))?;
            entry.set_item(
                "derivative_errors",
                PyArray1::from_vec(py, si_errors.iter().map(|e| e * written.factor).collect()),
            )?;
            entry.set_item("si_derivatives", PyArray1::from_vec(py, si))?;
            entry.set_item("si_derivative_errors", PyArray1::from_vec(py, si_errors))?;
            figures.set_item(&f.key, entry)?;
        }
        d.set_item("figures", figures)?;
        Ok(d)
    }

    /// The 6×6 wheel compliance at design of the left corner on the wheel-travel rig (the matrix of the
    /// parallel-travel report): column k is the response to a unit force (k < 3) or torque at the wheel centre.
    fn compliance<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let matrix = py
            .detach(|| {
                let corner = self.file.suspension.build(Side::Left, Rig::WheelTravel).map_err(|e| e.to_string())?;
                wheel_compliance(&corner, 0.0).map_err(|e| e.to_string())
            })
            .map_err(AnalysisError::new_err)?;
        let rows: Vec<Vec<f64>> = matrix.iter().map(|r| r.to_vec()).collect();
        PyArray2::from_vec2(py, &rows).map_err(|e| AnalysisError::new_err(e.to_string()))
    }

    /// Design variants, as `elastokin batch` runs them (interrupted by Ctrl-C within about
    /// [`CHUNK_SECONDS`]): one dict per variant with the columns of batch.csv.
    /// `variants` is the text of a variants file, or a list whose items are a variants-file line or a
    /// `(name, [(pointer, JSON text of the value)])` pair.
    /// `threads`: how many threads run the variants (None: every core). A study's task takes one CPU of
    /// its engine and runs its variants on one thread, so that tasks side by side do not oversubscribe.
    /// `analyses`: as `batch --analyses`, analysis names (`all`: the whole suite) whose every figure each
    /// dict also holds, by the column of batch_figures.csv (`analysis/figure (unit)`), in its written unit.
    #[pyo3(signature = (variants, threads=None, analyses=None))]
    fn batch<'py>(
        &self,
        py: Python<'py>,
        variants: &Bound<'py, PyAny>,
        threads: Option<usize>,
        analyses: Option<Vec<String>>,
    ) -> PyResult<Vec<Bound<'py, PyDict>>> {
        let list = parse_variants(variants, Some(batch::MAX_VARIANTS))?;
        if threads == Some(0) {
            return Err(PyValueError::new_err("threads: give at least 1 (or None for every core)"));
        }
        // `all` is the whole suite, as the command's `--analyses all`.
        let suite = analyses
            .map(|names| -> PyResult<Vec<Analysis>> {
                if names.iter().any(|n| n == "all") {
                    return Ok(Vec::new());
                }
                names.iter().map(|n| analysis(n)).collect()
            })
            .transpose()?;
        // A variant that names a key the model lacks is a mistake in the list: said before running anything.
        let files: Vec<SuspensionFile> = py
            .detach(|| list.iter().map(|v| batch::apply(&self.base, v)).collect::<Result<_, _>>())
            .map_err(|e| ModelError::new_err(e.to_string()))?;
        let pool = threads
            .map(|n| rayon::ThreadPoolBuilder::new().num_threads(n).build())
            .transpose()
            .map_err(|e| AnalysisError::new_err(format!("threads: {e}")))?;
        let results = in_chunks(py, pool.as_ref(), &files, |file| {
            batch::evaluate(file, batch::HALF_RANGE, batch::STEPS).map_err(|e| e.to_string())
        })?;
        let suite = suite
            .map(|which| in_chunks(py, pool.as_ref(), &files, |file| batch::evaluate_suite(file, &which, batch::STEPS)))
            .transpose()?;
        let columns = suite.as_deref().map(batch::suite_columns).unwrap_or_default();
        list.iter()
            .enumerate()
            .zip(results)
            .map(|((k, v), r)| {
                let row = PyDict::new(py);
                row.set_item("variant", &v.name)?;
                let (outcome, mut error) = match r {
                    Ok(o) => (Some(o), None),
                    Err(e) => (None, Some(e)),
                };
                for (k, figure) in batch::FIGURES.into_iter().enumerate() {
                    row.set_item(figure, outcome.map(|o| o.figures()[k]))?;
                }
                if let Some(suite) = &suite {
                    let reported = suite[k].as_ref().map_err(|e| error.get_or_insert_with(|| e.to_string())).ok();
                    for (a, key, unit) in &columns {
                        let f = reported.and_then(|r| r.iter().find(|(b, f)| b == a && f.key == *key));
                        let value = f.and_then(|(_, f)| f.value).map(|x| x * unit.shown().factor);
                        row.set_item(kc::figure_column(*a, key, *unit), value)?;
                    }
                }
                row.set_item("error", error)?;
                Ok(row)
            })
            .collect()
    }
}

/// `run` of every file on `pool` (rayon's own when None), in chunks of about [`CHUNK_SECONDS`] each with
/// Python's signals heard between them: Ctrl-C stops a long batch at once rather than when the last
/// variant is done.
fn in_chunks<T: Send>(
    py: Python<'_>,
    pool: Option<&rayon::ThreadPool>,
    files: &[SuspensionFile],
    run: impl Fn(&SuspensionFile) -> T + Sync,
) -> PyResult<Vec<T>> {
    let mut results = Vec::with_capacity(files.len());
    let mut chunk = pool.map_or_else(rayon::current_num_threads, |p| p.current_num_threads()).max(1);
    while results.len() < files.len() {
        let part = &files[results.len()..(results.len() + chunk).min(files.len())];
        let started = std::time::Instant::now();
        let evaluate = || -> Vec<T> { part.par_iter().map(&run).collect() };
        results.extend(py.detach(|| match pool {
            None => evaluate(),
            Some(pool) => pool.install(evaluate),
        }));
        py.check_signals()?;
        let took = started.elapsed().as_secs_f64().max(1e-6);
        chunk = ((chunk as f64 * CHUNK_SECONDS / took) as usize).clamp(1, 2 * chunk);
    }
    Ok(results)
}

/// The variants of `Model.batch`: a variants file's text, or a list of lines and `(name, edits)` pairs; at
/// most `most` of them.
fn parse_variants(variants: &Bound<'_, PyAny>, most: Option<usize>) -> PyResult<Vec<Variant>> {
    if let Ok(text) = variants.extract::<String>() {
        return batch::parse_variants_at_most(&text, "variants", most).map_err(|e| ModelError::new_err(e.to_string()));
    }
    let items: Vec<Bound<'_, PyAny>> = variants.extract()?;
    if items.is_empty() {
        return Err(ModelError::new_err("variants: no variants (one per line: name: /json/pointer=value; …)"));
    }
    if most.is_some_and(|most| items.len() > most) {
        return Err(ModelError::new_err(format!(
            "variants: more than {} variants; split the list and run a batch for each part",
            batch::MAX_VARIANTS
        )));
    }
    let mut out = Vec::with_capacity(items.len());
    for (k, item) in items.iter().enumerate() {
        let unnamed = format!("variant {}", k + 1);
        let place = format!("variants[{k}]");
        if let Ok(line) = item.extract::<String>() {
            let variant = batch::parse_variant(&line, &unnamed, &place)
                .map_err(|e| ModelError::new_err(e.to_string()))?
                .ok_or_else(|| ModelError::new_err(format!("{place}: no edits in '{}'", line.trim())))?;
            out.push(variant);
            continue;
        }
        let (name, edits): (Option<String>, Vec<(String, String)>) = item.extract()?;
        if edits.is_empty() {
            return Err(ModelError::new_err(format!("{place}: no edits")));
        }
        let edits = edits
            .into_iter()
            .map(|(pointer, value)| {
                serde_json::from_str(&value)
                    .map(|v| (pointer.clone(), v))
                    .map_err(|e| ModelError::new_err(format!("{place}: value of '{pointer}' is not JSON: {e}")))
            })
            .collect::<PyResult<_>>()?;
        out.push(Variant { name: name.unwrap_or(unnamed), edits });
    }
    Ok(out)
}

/// Designs compared, as `elastokin compare` compares them: each item a `Model` (its suite run, every
/// analysis or `analysis` alone) or a measured K&C file as `(name, text)`. Gives the designs' names,
/// `compare.csv`'s columns by name, and the overlaid charts (each curve's name and its points).
#[pyfunction]
#[pyo3(signature = (designs, analysis=None, range=None, steps=32))]
fn compare<'py>(
    py: Python<'py>,
    designs: Vec<Bound<'py, PyAny>>,
    analysis: Option<&str>,
    range: Option<(f64, f64)>,
    steps: usize,
) -> PyResult<Bound<'py, PyDict>> {
    use elastokin_suspensions::compare::{compare, Design};
    use elastokin_suspensions::design::targets::read_measured;
    let which: Vec<Analysis> = analysis.map(self::analysis).transpose()?.into_iter().collect();
    let settings = Settings { range, steps, motion: false, ..Settings::default() };
    for &a in if which.is_empty() { &kc::ALL[..] } else { &which[..] } {
        kc::check_settings(a, &settings).map_err(|e| PyValueError::new_err(e.to_string()))?;
    }
    let mut read = Vec::with_capacity(designs.len());
    for d in &designs {
        if let Ok(model) = d.cast::<Model>() {
            read.push(Err(model.get().file.clone()));
        } else {
            let (name, text): (String, String) = d
                .extract()
                .map_err(|_| PyValueError::new_err("each design is a Model or a measured file as (name, text)"))?;
            let measured = read_measured(&text, &name).map_err(|e| PyValueError::new_err(e.to_string()))?;
            read.push(Ok(Design::Measured { name, measured }));
        }
    }
    let comparison = py
        .detach(|| {
            let designs: Vec<Design> = read
                .into_iter()
                .map(|d| d.unwrap_or_else(|file| Design::model(&file, kc::run_suite(&file, &which, &settings, |_| {}))))
                .collect();
            compare(&designs)
        })
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    let d = PyDict::new(py);
    d.set_item("names", comparison.names.clone())?;
    d.set_item("figures", column_dict(py, &comparison.table())?)?;
    let charts = PyList::empty(py);
    for chart in &comparison.charts {
        let c = PyDict::new(py);
        c.set_item("name", &chart.name)?;
        c.set_item("title", &chart.title)?;
        c.set_item("x_label", &chart.x_label)?;
        c.set_item("y_label", &chart.left.label)?;
        let curves = PyDict::new(py);
        for s in &chart.left.series {
            let (x, y): (Vec<f64>, Vec<f64>) = s.points.iter().copied().unzip();
            curves.set_item(&s.name, (PyArray1::from_vec(py, x), PyArray1::from_vec(py, y)))?;
        }
        c.set_item("curves", curves)?;
        charts.append(c)?;
    }
    d.set_item("charts", charts)?;
    Ok(d)
}

/// The names of every analysis, in the order the suite runs them (the command's `--analysis` names).
#[pyfunction]
fn analyses() -> Vec<&'static str> {
    kc::ALL.iter().map(|a| a.name()).collect()
}

/// What each analysis's load parameter is, with its unit.
#[pyfunction]
fn parameter(name: &str) -> PyResult<&'static str> {
    Ok(analysis(name)?.parameter())
}

/// The contiguous blocks `[start, end)` of `count` variants in `chunks` shards, empty ones left out: the
/// shard rule of `elastokin batch --shard I/N`, so that a study's tasks take the command's blocks.
#[pyfunction]
fn shard_blocks(count: usize, chunks: usize) -> PyResult<Vec<(usize, usize)>> {
    if chunks == 0 {
        return Err(PyValueError::new_err("chunks must be at least 1"));
    }
    Ok((1..=chunks)
        .map(|index| Shard { index, count: chunks }.range(count))
        .filter(|r| !r.is_empty())
        .map(|r| (r.start, r.end))
        .collect())
}

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add_class::<Model>()?;
    m.add_class::<scene::Scene>()?;
    m.add_class::<scene::SceneSweep>()?;
    m.add_class::<live::LiveServer>()?;
    m.add_function(wrap_pyfunction!(analyses, m)?)?;
    m.add_function(wrap_pyfunction!(parameter, m)?)?;
    m.add_function(wrap_pyfunction!(shard_blocks, m)?)?;
    m.add_function(wrap_pyfunction!(compare, m)?)?;
    m.add("MAX_VARIANTS", batch::MAX_VARIANTS)?;
    m.add("VERSION", env!("CARGO_PKG_VERSION"))?;
    m.add("Error", py.get_type::<Error>())?;
    m.add("ModelError", py.get_type::<ModelError>())?;
    m.add("AnalysisError", py.get_type::<AnalysisError>())?;
    // The library's names, which the compliance tables' columns are made of.
    m.add("COMPLIANCE_ROWS", kc::COMPLIANCE_RESPONSE.to_vec())?;
    m.add("COMPLIANCE_COLUMNS", kc::COMPLIANCE_LOAD.to_vec())?;
    m.add("BATCH_HALF_RANGE", batch::HALF_RANGE)?;
    m.add("BATCH_STEPS", batch::STEPS)?;
    m.add("BATCH_FIGURES", batch::FIGURES.to_vec())?;
    Ok(())
}

/// A fit's uncertainty as the tune's dict gives it, for free numbers `pointers`.
fn uncertainty_dict<'py>(
    py: Python<'py>,
    u: &elastokin_suspensions::design::fit::FitUncertainty,
    pointers: &[String],
) -> PyResult<Bound<'py, PyDict>> {
    let uncertainty = PyDict::new(py);
    uncertainty.set_item("standard", u.standard.iter().map(|s| s.unwrap_or(f64::NAN)).collect::<Vec<f64>>())?;
    let correlation: Vec<Vec<f64>> =
        u.correlation.iter().map(|row| row.iter().map(|c| c.unwrap_or(f64::NAN)).collect()).collect();
    uncertainty.set_item("correlation", correlation)?;
    uncertainty.set_item("residual_scale", u.residual_scale)?;
    uncertainty.set_item("degrees_of_freedom", u.degrees_of_freedom)?;
    uncertainty.set_item("held_by_packaging", u.held_by_packaging)?;
    let at_bound: Vec<&str> = u.at_bound.iter().map(|&k| pointers[k].as_str()).collect();
    uncertainty.set_item("at_bound", at_bound)?;
    let unseen: Vec<String> = u.unseen.iter().map(|d| d.said(pointers)).collect();
    uncertainty.set_item("unseen", unseen)?;
    uncertainty.set_item("unique", u.unique())?;
    Ok(uncertainty)
}
