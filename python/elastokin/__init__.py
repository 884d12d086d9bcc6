"""elastokin: quasi-static elastokinematics of suspensions, from Python.

Read a suspension model (a model file or a dict in the model-file format), run its K&C analyses — bump
steer, camber gain, wheel rate, roll centre, compliance steer and the rest — and get each analysis's rows
as numpy arrays, its headline figures and accuracy as a dict, the wheel compliance at design as a 6×6
array, and design variants judged as ``elastokin batch`` judges them.

Every number comes from the Rust library the ``elastokin`` command runs; errors carry the command's
messages. The solver runs without the GIL, so analyses in several threads run at once.

>>> import elastokin
>>> model = elastokin.load("examples/macpherson.json")
>>> travel = model.run("parallel-travel")
>>> travel.columns["toe_deg"]            # numpy array, one value per load step
>>> travel.summary["figures"]            # headline figures with their error estimates
"""

from __future__ import annotations

import json
import os
from collections.abc import Mapping
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy

from . import _native
from ._live import NOTEBOOK_ORIGINS, LiveServer
from ._study import BATCH_FIGURES, ENGINES, Grid, Parts, Study, _items, read_variants, study, study_parts
from ._native import (
    BATCH_HALF_RANGE,
    BATCH_STEPS,
    COMPLIANCE_COLUMNS,
    MAX_VARIANTS,
    COMPLIANCE_ROWS,
    AnalysisError,
    Error,
    ModelError,
)
from .scene import Scene, SceneSweep

__all__ = [
    "AnalysisError",
    "BATCH_FIGURES",
    "ENGINES",
    "BATCH_HALF_RANGE",
    "BATCH_STEPS",
    "COMPLIANCE_COLUMNS",
    "COMPLIANCE_ROWS",
    "Error",
    "Grid",
    "LiveServer",
    "MAX_VARIANTS",
    "Model",
    "ModelError",
    "NOTEBOOK_ORIGINS",
    "Parts",
    "Result",
    "Scene",
    "SceneSweep",
    "Study",
    "analyses",
    "batch",
    "compare",
    "load",
    "parameter",
    "read_variants",
    "study",
    "study_parts",
]


def analyses() -> List[str]:
    """The names of every K&C analysis, in the order the suite runs them (the command's ``--analysis``)."""
    return list(_native.analyses())


def parameter(name: str) -> str:
    """What the load parameter of analysis ``name`` is, with its unit (the unit of ``range``)."""
    return _native.parameter(name)


def _table_to_pandas(columns: Mapping[str, Any]):
    try:
        import pandas
    except ImportError as e:
        raise ImportError(
            "to_pandas() needs pandas, which elastokin does not require: pip install pandas "
            "(the columns are numpy arrays without it)"
        ) from e
    return pandas.DataFrame(dict(columns))


class Result:
    """One analysis's result: its rows as columns, its report as a dict.

    ``columns`` maps each column of the analysis's CSV (``travel_m``, ``toe_deg``, …; the unit is the
    name's suffix) to a numpy float array with one value per load step, NaN where a step has no value; a
    column of names (the static load's element names) is a list of its cells instead.
    ``summary`` is the analysis's entry of the command's summary.json: parameter, range, steps, headline
    figures (each with its value, unit and error estimate, or the reason it is missing), accuracy and
    warnings. ``compliance`` holds the wheel compliance at every step when the run asked for it.
    """

    __slots__ = ("analysis", "columns", "summary", "compliance")

    def __init__(
        self,
        analysis: str,
        columns: Dict[str, Any],
        summary: Dict[str, Any],
        compliance: Optional[Dict[str, Any]],
    ) -> None:
        self.analysis = analysis
        self.columns = columns
        self.summary = summary
        self.compliance = compliance

    def figure(self, key: str, si: bool = False) -> Optional[float]:
        """The headline figure ``key`` (e.g. ``bump_steer``), in the unit its summary entry names (``unit``),
        or with ``si=True`` in SI (``si_unit``: rad/m, N/m, rad/N); None when the analysis could not compute
        it (its summary entry says why)."""
        figures = self.summary["figures"]
        if key not in figures:
            raise KeyError(f"{self.analysis} has no figure '{key}' (it has {', '.join(figures)})")
        return figures[key].get("si_value" if si else "value")

    def to_pandas(self):
        """The rows as a pandas DataFrame, one column per CSV column (needs pandas)."""
        return _table_to_pandas(self.columns)

    def __repr__(self) -> str:
        rows = len(next(iter(self.columns.values()))) if self.columns else 0
        return f"<elastokin.Result {self.analysis}: {rows} rows × {len(self.columns)} columns>"


class Model:
    """A suspension model, read once and analysed as often as wanted (from any thread)."""

    __slots__ = ("_native",)

    def __init__(self, native: "_native.Model") -> None:
        self._native = native

    @property
    def name(self) -> str:
        """The model's name (the file's ``name``)."""
        return self._native.name

    def to_dict(self) -> Dict[str, Any]:
        """The model as read, in the model-file format (SI units, ISO 8855 axes)."""
        return json.loads(self._native.to_json())

    def analyses(self) -> List[str]:
        """The names of every K&C analysis (see :func:`elastokin.analyses`)."""
        return analyses()

    def run(
        self,
        name: str,
        *,
        range: Optional[Tuple[float, float]] = None,
        steps: int = 32,
        mode: str = "corrected",
        wheel: str = "held",
        load_point: str = "contact_patch",
        compliance: bool = False,
        through_limits: bool = False,
        arc_step: Optional[float] = None,
    ) -> Result:
        """Runs one K&C analysis, as ``elastokin run MODEL --analysis NAME`` does.

        ``range`` is the load parameter's (from, to) in the analysis's own units (see :func:`parameter`;
        each analysis has its default); ``steps`` load steps; ``mode`` "corrected" (Newton iterations to
        the exact equilibrium at every step) or "paper"; ``wheel`` "held" or "free" for the road loads;
        ``load_point`` "contact_patch" or "wheel_centre"; ``compliance`` also gives the 6×6 wheel
        compliance at every step; ``through_limits`` follows the path on through a limit point by arc
        length, ``arc_step`` long.

        Raises ValueError for an unknown analysis or option, AnalysisError when the analysis fails.
        """
        report, table, comp = self._native.run(
            name,
            range=_span(range),
            steps=steps,
            mode=mode,
            wheel=wheel,
            load_point=load_point,
            compliance=compliance,
            through_limits=through_limits,
            arc_step=arc_step,
        )
        return Result(name, dict(table), json.loads(report), None if comp is None else dict(comp))

    def suite(
        self,
        analyses: Optional[Union[str, Sequence[str]]] = None,
        *,
        range: Optional[Tuple[float, float]] = None,
        steps: int = 32,
        mode: str = "corrected",
        wheel: str = "held",
        load_point: str = "contact_patch",
        compliance: bool = False,
        through_limits: bool = False,
        arc_step: Optional[float] = None,
    ) -> Dict[str, Any]:
        """Runs the K&C suite — every analysis that applies, or those named — as ``elastokin run`` does,
        and gives its report as a dict: the content of the command's summary.json without its provenance
        (model, settings, model_check, warnings, and per analysis its figures, table, accuracy and
        warnings). ``analyses`` is a list of names, or one name. Options as for :meth:`run`; ``range``
        needs exactly one analysis named. Raises
        AnalysisError, naming the analysis and its reason, when one fails (the command writes the others
        and exits 1; run them by name to keep them)."""
        return json.loads(
            self._native.suite(
                _names(analyses),
                range=_span(range),
                steps=steps,
                mode=mode,
                wheel=wheel,
                load_point=load_point,
                compliance=compliance,
                through_limits=through_limits,
                arc_step=arc_step,
            )
        )

    def compliance(self) -> numpy.ndarray:
        """The 6×6 wheel compliance at design (the parallel-travel report's matrix).

        Rows are the wheel-centre response (x, y, z in m; rotation about x, y, z in rad, global axes), columns
        the unit load at the wheel centre (force along x, y, z in N; torque in N·m): see
        :data:`COMPLIANCE_ROWS` and :data:`COMPLIANCE_COLUMNS`. The wheel-travel rig holds the wheel-centre
        height, so the vertical row and column are zero."""
        return self._native.compliance()

    def batch(self, variants: Any, *, analyses: Optional[Sequence[str]] = None) -> List[Dict[str, Any]]:
        """Design variants of this model; see :func:`elastokin.batch`."""
        return batch(self, variants, analyses=analyses)

    def live(
        self,
        analyses: Optional[Union[str, Sequence[str]]] = None,
        *,
        steps: int = 32,
        targets: Optional[Union[str, "os.PathLike[str]", Dict[str, Any]]] = None,
        port: int = 0,
        bind: str = "127.0.0.1",
        frame_ancestors: Sequence[str] = NOTEBOOK_ORIGINS,
    ) -> LiveServer:
        """Serves the model's file live, as ``elastokin live MODEL`` does, and gives the running server:
        its :attr:`~LiveServer.url` opened in a browser shows every figure and chart of ``analyses`` (a
        list of names, or one name; the suite when None), walked in ``steps`` load steps; a hardpoint or a
        rate typed there runs them again, the previous design's curves in grey beneath; undo, redo, and
        save, which rewrites the moved numbers in the file and leaves every other byte as it was. In a
        notebook, the server as a cell's value shows the page in a frame.

        The file is read as it is on disk now; a model made from a dict or text has none (raises
        ModelError saying what to do). ``targets`` (a TARGETS file's path, or its content as a dict) judges
        every design and lets the page tune to them. ``port`` 0 takes any free one; ``bind`` other than
        this machine's own address is reachable from elsewhere (warned). ``frame_ancestors``: the origins
        whose pages may show the page in a frame (default :data:`NOTEBOOK_ORIGINS`, a notebook on this
        machine; ``()`` for the page's own alone, as the command serves it).

        Stop it with :meth:`LiveServer.stop`, or use it in a ``with`` block. Raises ValueError for an
        unknown analysis, bad settings, targets, bind address or frame ancestor, OSError when the port
        cannot be listened on."""
        text: Optional[str] = None
        beside: Optional[str] = None
        if targets is not None:
            text, beside = _design_file(targets)
        native = self._native.live(
            _names(analyses),
            steps=steps,
            targets=text,
            directory="." if beside is None else beside,
            port=port,
            bind=bind,
            frame_ancestors=[str(f) for f in frame_ancestors],
        )
        return LiveServer(native, self.name)

    def hardpoint_parameters(self) -> List[str]:
        """Every coordinate of every hardpoint, as parameter pointers (the command's ``--hardpoints``)."""
        return self._native.hardpoint_parameters()

    def sensitivities(
        self,
        parameters: Optional[Sequence[str]] = None,
        *,
        analysis: str = "parallel-travel",
        range: Optional[Tuple[float, float]] = None,
        steps: int = 32,
        figures_only: bool = False,
    ) -> Dict[str, Any]:
        """Sensitivities of one analysis of the K&C suite (``analysis``, as ``run(analyses=...)``
        names them), as ``elastokin sensitivity`` gives them: through the equilibrium, with no equilibrium
        solved again (Richardson differences of the recorded equilibria moved one Newton iteration by the
        moved model), each with its error estimate.

        ``parameters`` are JSON pointers into the model file (as batch variants name them; every hardpoint
        coordinate when None). Gives a dict: ``analysis``, ``parameters``, their ``values``, the table's
        ``columns``, every column by name (its rows, NaN where empty) with its derivatives ``d_<column>`` and
        their error estimates ``d_<column>_error`` as (rows, parameters) arrays, and ``figures``: each
        headline figure by key with its ``value``, ``unit``, ``derivatives`` (one per parameter, NaN where
        there is none) and ``derivative_errors`` as ``sensitivity.csv`` writes them, the same in SI
        (``si_value``, ``si_unit``, ``si_derivatives``, ``si_derivative_errors``), and ``no_derivative``
        (why, or None).
        Every derivative is per unit of the parameter as the file gives it (per m of a hardpoint coordinate,
        per N/m of a rate). With ``figures_only``, the rows are read as far as the figures read them (as
        ``elastokin sensitivity --figures-only``: no force in every joint and element of a load sweep, the
        roll centre at design only) and moved only where the figures read them: the same figures and
        derivatives, sooner, no columns for what was left out, and every ``d_<column>`` NaN (the table has
        no derivatives then).

        Raises ModelError for a pointer that names nothing or no number, ValueError for bad settings, and
        AnalysisError when the analysis fails or meets a limit point (no derivative there) or a parameter
        changes the model's parts."""
        pointers = self.hardpoint_parameters() if parameters is None else [str(p) for p in parameters]
        span = _span(range)
        return self._native.sensitivities(
            pointers, analysis=analysis, range=span, steps=steps, figures_only=figures_only
        )

    def tune(self, targets: Union[str, Dict[str, Any]], directory: str = ".") -> Dict[str, Any]:
        """Tunes the model to ``targets`` (a TARGETS file's path, or its content as a dict), as ``elastokin
        tune`` does: a dict of ``stopped``, ``all_met``, ``verdicts`` (each target's ``worst``, its misses
        measured against its tolerance — the largest miss, a curve's root mean square or area, or against
        noise ``χ²/n`` over the most noise gives; met when at most 1 —, how it was ``judged`` in words,
        whether ``met`` and ``why`` not), ``objective`` (with an objective in the targets: its figure
        ``before`` and ``after`` in ``unit`` and what holds it, ``held_by``; else None), ``packaging``
        (each packaging constraint and how far it is broken, in m: 0 where it holds), ``parameters`` with
        their values ``before`` and ``after``, ``iterations`` (tune.csv's columns), ``uncertainty`` (each
        number's ``standard`` uncertainty, NaN where the fit gives none, their ``correlation``, the
        ``residual_scale`` and ``degrees_of_freedom`` it is taken over, the numbers ``at_bound``, the
        combinations the packaging holds, ``held_by_packaging``, the directions the targets cannot tell,
        ``unseen``, in words, and whether the answer is ``unique``; None with an objective, whose optimum
        is no fit) and ``tuned``, the model file's text with the numbers moved.
        Measured files named in a dict are read from ``directory``; in a file, beside it. Targets the
        model's analyses do not give (a figure or column they have not, a point outside the range walked)
        raise ``ValueError``, as a bad file does; a model that cannot be analysed, ``AnalysisError``."""
        text, beside = _design_file(targets)
        return self._native.tune(text, directory if beside is None else beside)

    def tolerance(
        self, tolerances: Union[str, Dict[str, Any]], *, monte_carlo: Optional[int] = None, seed: int = 1
    ) -> Dict[str, Any]:
        """The tolerance stack-up of ``tolerances`` (a TOLERANCES file's path, or its content as a dict), as
        ``elastokin tolerance`` gives it: tolerance.csv's columns by name (each figure's first-order
        ``worst_case`` and ``sigma``, the share ``outside`` its limit, and with ``monte_carlo`` samples the
        sampled spread beside them), and the other CSVs' columns by name: ``contributions``, ``adjustments``
        (None without ``adjust``) and ``samples`` (None without ``monte_carlo``)."""
        return self._native.tolerance(_design_file(tolerances)[0], monte_carlo=monte_carlo, seed=seed)

    def tolerance_samples(
        self, tolerances: Union[str, Dict[str, Any]], n: int, *, seed: int = 1
    ) -> Dict[str, numpy.ndarray]:
        """The ``n`` models ``tolerance(monte_carlo=n, seed=seed)`` samples, as a variant table (each number's
        JSON pointer and its sampled values, as drawn: before the alignment sets any adjuster):
        ``elastokin.study(model, samples, engine="ray")`` (or "dask") runs the Monte Carlo on a cluster, each
        sample the same as the command draws."""
        return self._native.tolerance_samples(_design_file(tolerances)[0], n, seed=seed)

    def objective(
        self,
        figure: str,
        parameters: Sequence[str],
        *,
        analysis: str = "parallel-travel",
        target: float = 0.0,
        range: Optional[Tuple[float, float]] = None,
        steps: int = 32,
    ) -> Any:
        """A function of the parameters' values ``x`` giving ``((figure − target)², gradient)``, the gradient
        from the sensitivities, which ``scipy.optimize.minimize(f, x0, jac=True)`` takes as it is. ``figure`` is a headline
        figure's key of ``analysis`` (as ``summary.json`` names it: ``"bump_steer"``, ``"wheel_rate"``, …) in
        its unit; ``x0`` is ``sensitivities(parameters)["values"]``."""
        pointers = [str(p) for p in parameters]
        # The figure named checked by one run of the analysis, before any sensitivity is taken.
        known = self.run(analysis, range=range, steps=steps).summary["figures"]
        if figure not in known:
            raise ValueError(f"figure {figure!r}: {analysis} has {', '.join(sorted(known))}")
        text, origin = self._native.document()
        base = json.loads(text)

        def f(x: Any) -> Tuple[float, numpy.ndarray]:
            document = json.loads(json.dumps(base))
            for pointer, value in zip(pointers, numpy.asarray(x, dtype=float)):
                _set_pointer(document, pointer, float(value))
            model = Model(_native.Model.from_json(json.dumps(document), origin))
            # A figure's objective reads the rows as far as the figures read them.
            s = model.sensitivities(pointers, analysis=analysis, range=range, steps=steps, figures_only=True)
            got = s["figures"][figure]
            if got["value"] is None:
                raise AnalysisError(f"{figure} has no value at {list(x)}")
            miss = got["value"] - target
            return miss * miss, 2.0 * miss * numpy.asarray(got["derivatives"])

        return f

    def __reduce__(self):
        # Pickled as the document it was read from: a model sent to another process (a Ray or Dask worker,
        # a multiprocessing pool) is read there again, to the same model.
        return (_from_document, self._native.document())

    def __repr__(self) -> str:
        return f"<elastokin.Model {self.name!r}>"


def _design_file(source: Union[str, "os.PathLike[str]", Dict[str, Any]]) -> Tuple[str, Optional[str]]:
    """A design file (TARGETS, TOLERANCES) given as its path or its content as a dict: its text, and the
    directory files it names are read from (None for a dict)."""
    if isinstance(source, dict):
        return json.dumps(source), None
    path = str(source)
    with open(path, encoding="utf-8") as f:
        return f.read(), os.path.dirname(path) or "."


def _set_pointer(document: Any, pointer: str, value: float) -> None:
    """Sets the number at a JSON pointer (RFC 6901) of a parsed document; a pointer naming nothing raises
    ModelError with the pointer."""
    keys = [k.replace("~1", "/").replace("~0", "~") for k in pointer.split("/")[1:]]
    node = document
    try:
        for key in keys[:-1]:
            node = node[int(key)] if isinstance(node, list) else node[key]
        last = keys[-1]
        if isinstance(node, list):
            node[int(last)] = value
        elif last in node:
            node[last] = value
        else:
            raise KeyError(last)
    except (KeyError, IndexError, ValueError, TypeError):
        raise ModelError(f"parameter '{pointer}' names nothing in the model") from None


def _span(range: Optional[Sequence[float]]) -> Optional[Tuple[float, float]]:
    """``range`` as the pair of numbers the analyses take, or ValueError saying what to give."""
    if range is None:
        return None
    try:
        start, end = range
        return (float(start), float(end))
    except (TypeError, ValueError):
        raise ValueError(
            f"range: give (from, to), two numbers in the analysis's own units, got {range!r}"
        ) from None


def _names(analyses: Optional[Union[str, Sequence[str]]]) -> Optional[List[str]]:
    """Analysis names as a list: one name given alone is that one analysis, not its letters."""
    if analyses is None:
        return None
    if isinstance(analyses, str):
        return [analyses]
    return list(analyses)


def _from_document(text: str, origin: str) -> Model:
    return Model(_native.Model.from_json(text, origin))


def load(source: Union[str, "os.PathLike[str]", Mapping[str, Any]], *, origin: str = "<dict>") -> Model:
    """Reads a suspension model: a path to a model file (an elastokin model file or a Project Chrono
    suspension file), a model file's JSON text (a string that starts with ``{``), or a dict in the
    model-file format (``origin`` then names the text or dict in error messages).

    Raises ModelError, with the command's message, when the file cannot be read or is not a model."""
    if isinstance(source, Mapping):
        try:
            text = json.dumps(source, allow_nan=False)
        except (TypeError, ValueError) as e:
            raise ModelError(f"{origin}: not a model in the model-file format: {e}") from e
        return Model(_native.Model.from_json(text, origin))
    if isinstance(source, str) and source.lstrip().startswith("{"):
        return Model(_native.Model.from_json(source, "<text>" if origin == "<dict>" else origin))
    return Model(_native.Model.read(os.fspath(source)))


def batch(
    model: Union[Model, str, "os.PathLike[str]", Mapping[str, Any]],
    variants: Any,
    *,
    analyses: Optional[Sequence[str]] = None,
) -> List[Dict[str, Any]]:
    """Runs design variants of a model, as ``elastokin batch MODEL VARIANTS`` does: each variant walks
    parallel wheel travel ±``BATCH_HALF_RANGE`` m in ``BATCH_STEPS`` steps (corrected mode), all on every
    core, and is judged by its rates at design (read off the equilibrium there, as ``run`` reads them).

    ``variants`` is the text of a variants file, a list whose items are each a variants-file line
    (``"name: /json/pointer=value; …"``) or a dict ``{pointer: value}`` (a ``"name"`` key, if any, names
    it; others are named ``variant N``), or a variant table (a pandas DataFrame or a dict of columns, one
    column per pointer): see :func:`read_variants`. Pointers are JSON pointers into the model file. At most
    ``MAX_VARIANTS`` variants; :func:`study` takes any number, on one machine or many.

    Gives one dict per variant with the columns of batch.csv: ``variant``, ``bump_steer_deg_per_m``,
    ``camber_gain_deg_per_m``, ``wheel_rate_n_per_m`` (None when the variant failed) and ``error`` (the
    reason, else None). With ``analyses`` (analysis names, ``"all"`` for the whole suite), as ``batch
    --analyses``, each dict also holds every figure those analyses report, keyed as batch_figures.csv's
    columns (``"parallel-travel/caster (deg)"``) in the unit written there (None where the variant has
    none). Raises ModelError when a variant cannot be read or edits a key the model lacks."""
    if not isinstance(model, Model):
        model = load(model)
    # Read once, by the batch itself (a pointer the model lacks is said before anything runs).
    which = None if analyses is None else [analyses] if isinstance(analyses, str) else list(analyses)
    return model._native.batch(_items(variants), analyses=which)


def compare(
    *designs: Union[Model, str, "os.PathLike[str]", Mapping[str, Any]],
    analysis: Optional[str] = None,
    range: Optional[Tuple[float, float]] = None,
    steps: int = 32,
) -> Dict[str, Any]:
    """Compares designs as ``elastokin compare`` does: each a :class:`Model`, a model file's path or a dict,
    or the path of a measured K&C file (``.csv``, its first column the load parameter and a comment line
    ``# analysis: NAME``). Runs each model's suite (or ``analysis`` alone) and gives ``names`` (made
    distinct), ``figures`` (compare.csv's columns by name: each model's value and error estimate, each later
    model's difference to the first) and ``charts`` (each overlaid curve by its design's name, as
    ``(x, y)`` arrays). Raises ValueError, with the command's message, for designs that cannot be
    compared."""
    items: List[Any] = []
    for d in designs:
        if isinstance(d, Model):
            items.append(d._native)
        elif isinstance(d, (str, os.PathLike)) and os.fspath(d).lower().endswith(".csv"):
            path = os.fspath(d)
            with open(path, encoding="utf-8") as f:
                items.append((os.path.basename(path), f.read()))
        else:
            items.append(load(d)._native)
    return _native.compare(items, analysis=analysis, range=_span(range), steps=steps)
