"""Design studies: a table of variants run as batches on an engine the user already operates.

A study splits its variants into contiguous chunks (variant k of V goes to chunk ⌊k·N/V⌋, the rule of
``elastokin batch --shard``), runs each chunk as one task — one :meth:`Model.batch` on one thread — and
gathers the rows in the variants' order. Every variant is solved on its own, so where a task runs changes no
bit of its result: a study's rows are those of the single-process batch.

Engines:

- ``"local"``: this process, on ``workers`` threads (default every core); the solver lets go of the GIL.
- ``"ray"``: Ray tasks of one CPU each. A Ray that is already started (``ray.init(address=...)``) is used;
  otherwise a local Ray is started with ``workers`` CPUs and left running, as Ray's own libraries do.
- ``"dask"``: Dask futures on the default ``distributed`` client (the last ``Client`` made). Without one, a
  ``LocalCluster`` of ``workers`` single-threaded processes is made for the study and closed after it.

Every worker imports ``elastokin``: install the same version wherever the engine runs tasks.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Tuple

import numpy

from . import _native

ENGINES = ("local", "ray", "dask")

#: The figures of a variant, as batch.csv names its columns (the library's names).
BATCH_FIGURES = tuple(_native.BATCH_FIGURES)

# A chunk is one task: big enough that an engine's cost per task (about a millisecond) is small against its
# solves (about 0.35 ms a variant), small enough to spread over the workers several times for balance.
_CHUNKS_PER_WORKER = 4

_Edits = List[Tuple[str, str]]
_Variant = Tuple[str, _Edits]


def _json_value(value: Any, place: str) -> str:
    """A variant's value as JSON text: numpy scalars as the Python numbers they hold; NaN and inf refused."""
    # The common case first, at a fifth of json.dumps's cost: a finite float's shortest repr is its JSON
    # (float.__repr__, since numpy's own repr of a float64 adds its type's name).
    if isinstance(value, float) and math.isfinite(value):
        return float.__repr__(value)
    if isinstance(value, numpy.generic):
        value = value.item()
    try:
        return json.dumps(value, allow_nan=False)
    except (TypeError, ValueError) as e:
        raise _native.ModelError(f"{place}: {value!r} is not a model value ({e}); give a finite number, a string, "
                                 "a list or a dict") from None


def _records(variants: Any) -> Any:
    """A variant table — a pandas DataFrame or a dict of columns, one column per JSON pointer and an optional
    ``name`` column — as the list of dicts :func:`elastokin.batch` takes; other forms are passed on."""
    if hasattr(variants, "to_dict") and hasattr(variants, "columns"):
        return variants.to_dict(orient="records")
    if isinstance(variants, Mapping):
        lengths = {len(column) for column in variants.values()}
        if len(lengths) != 1:
            raise _native.ModelError(
                "variants: the columns of a variant table differ in length "
                f"({', '.join(f'{k}: {len(v)}' for k, v in variants.items())}); give one value per variant in each")
        (rows,) = lengths
        return [{key: column[k] for key, column in variants.items()} for k in range(rows)]
    return variants


def _items(variants: Any) -> Any:
    """Variants in any form, as the native reader takes them: a variants file's text as it is, anything else
    as a list of variants-file lines and ``(name, [(pointer, JSON text)])`` pairs (a dict's values written
    as JSON here)."""
    variants = _records(variants)
    if isinstance(variants, str):
        return variants
    items: List[Any] = []
    for k, v in enumerate(variants):
        if isinstance(v, Mapping):
            edits = dict(v)
            name = edits.pop("name", None)
            name = None if name is None else str(name)
            place = f"variants[{k}]"
            items.append((name, [(p, _json_value(value, f"{place} '{p}'")) for p, value in edits.items()]))
        else:
            items.append(v)
    return items


def read_variants(model: Any, variants: Any) -> List[_Variant]:
    """Every form of variants a study or :func:`elastokin.batch` takes, read and checked against ``model``
    (a :class:`Model`): the text of a variants file; a list of variants-file lines or dicts
    ``{pointer: value}`` (a ``"name"`` key names one); a variant table (a pandas DataFrame, or a dict of
    equally long columns, keyed by pointer).

    Gives ``(name, [(pointer, JSON text of the value)])`` per variant, in order; raises ModelError naming the
    variant that cannot be read or edits a key the model lacks."""
    return [(name, list(edits)) for name, edits in model._native.read_variants(_items(variants))]


def _numbered(rows: List[Dict[str, Any]], first: int) -> List[Dict[str, Any]]:
    """The rows of the variants numbered from ``first + 1`` on, each given its ``variant_number``."""
    for k, row in enumerate(rows):
        row["variant_number"] = first + k + 1
    return rows


def _split(count: int, chunks: int) -> List[Tuple[int, int]]:
    """Contiguous blocks ``[start, end)``: variant k of ``count`` in block ⌊k·chunks/count⌋, the library's
    shard rule (``elastokin batch --shard``), empty blocks left out."""
    return _native.shard_blocks(count, chunks)


def _run_chunk(document: Tuple[str, str], variants: List[_Variant], first: int) -> List[Dict[str, Any]]:
    """One task: the chunk's variants of the model, on one thread, each row with its variant number (from 1).

    Runs wherever the engine puts it; it needs only this module and the model's document."""
    from . import _from_document

    return _numbered(_from_document(*document)._native.batch(variants, threads=1), first)


def _edited_values(variants: List[_Variant]) -> Dict[str, List[Any]]:
    """Each pointer the variants edit (in order of first edit) and its value in every variant (None where
    a variant leaves it alone)."""
    columns: Dict[str, List[Any]] = {}
    for k, (_, edits) in enumerate(variants):
        for pointer, value in edits:
            column = columns.get(pointer)
            if column is None:
                column = columns[pointer] = [None] * len(variants)
            column[k] = json.loads(value)
    return columns


def _all_numbers(values: Sequence[Any]) -> bool:
    """Whether a pointer's column is numbers (float, NaN where absent) rather than text."""
    return all(v is None or (isinstance(v, (int, float)) and not isinstance(v, bool)) for v in values)


class Study:
    """A study's results: one row per variant, in the variants' order.

    ``columns`` maps ``variant_number`` (from 1), ``variant`` (names), one column per JSON pointer the
    variants edit (its values: a float array with NaN where a variant leaves the key alone, or a list of JSON
    texts when the values are not all numbers; ``pointers`` fixes which, for the parts of one study), the
    figures of batch.csv (float arrays, NaN where the variant failed) and
    ``error`` (the reason, else None)."""

    __slots__ = ("columns", "metadata", "_rows")

    def __init__(self, rows: List[Dict[str, Any]], variants: List[_Variant], metadata: Dict[str, str],
                 pointers: Optional[Dict[str, bool]] = None) -> None:
        self._rows = rows
        self.metadata = metadata
        columns: Dict[str, Any] = {
            "variant_number": numpy.array([r["variant_number"] for r in rows], dtype=numpy.int64),
            "variant": [r["variant"] for r in rows],
        }
        values_of = _edited_values(variants)
        if pointers is None:
            pointers = {p: _all_numbers(values) for p, values in values_of.items()}
        for pointer, numbers in pointers.items():
            values = values_of.get(pointer, [None] * len(variants))
            if numbers:
                columns[pointer] = numpy.array([math.nan if v is None else float(v) for v in values])
            else:
                columns[pointer] = [v if v is None or isinstance(v, str) else json.dumps(v) for v in values]
        for figure in BATCH_FIGURES:
            columns[figure] = numpy.array([math.nan if r[figure] is None else r[figure] for r in rows])
        columns["error"] = [r["error"] for r in rows]
        self.columns = columns

    def __len__(self) -> int:
        return len(self._rows)

    def rows(self) -> List[Dict[str, Any]]:
        """The rows as :func:`elastokin.batch` gives them (figures None where a variant failed), each with its
        ``variant_number``."""
        return [dict(r) for r in self._rows]

    def to_pandas(self):
        """The table as a pandas DataFrame (needs pandas)."""
        from . import _table_to_pandas

        return _table_to_pandas(self.columns)

    def to_arrow(self):
        """The table as a pyarrow Table, the study's provenance in its schema's metadata (needs pyarrow)."""
        try:
            import pyarrow
        except ImportError as e:
            raise ImportError("Parquet and Arrow output need pyarrow: pip install pyarrow") from e
        # Names, errors and non-numeric edits are text even when a column holds no value at all.
        arrays = {
            k: pyarrow.array(v, type=pyarrow.string()) if isinstance(v, list) else pyarrow.array(v)
            for k, v in self.columns.items()
        }
        table = pyarrow.table(arrays)
        return table.replace_schema_metadata({f"elastokin.{k}": v for k, v in self.metadata.items()})

    def to_parquet(self, path: "os.PathLike[str] | str") -> None:
        """Writes the table to a Parquet file (needs pyarrow); the file is written whole or not at all."""
        try:
            import pyarrow.parquet
        except ImportError as e:
            raise ImportError("Parquet and Arrow output need pyarrow: pip install pyarrow") from e
        path = os.fspath(path)
        partial = f"{path}.partial"
        pyarrow.parquet.write_table(self.to_arrow(), partial)
        os.replace(partial, path)

    def __repr__(self) -> str:
        failed = sum(e is not None for e in self.columns["error"])
        return f"<elastokin.Study {len(self)} variants, {failed} failed>"


def _on_ray(function: Callable[..., Any], document: Tuple[str, str], jobs: List[tuple], workers: Optional[int]):
    """``function(document, *job)`` for every job, as Ray tasks of one CPU; the results in the jobs' order."""
    try:
        import ray
    except ImportError as e:
        raise ImportError("engine='ray' needs Ray: pip install ray") from e
    if not ray.is_initialized():
        ray.init(num_cpus=workers, include_dashboard=False, log_to_driver=False)
    task = ray.remote(num_cpus=1)(function)
    shared = ray.put(document)
    return ray.get([task.remote(shared, *job) for job in jobs])


def _on_dask(function: Callable[..., Any], document: Tuple[str, str], jobs: List[tuple], workers: Optional[int]):
    """``function(document, *job)`` for every job, as Dask futures; the results in the jobs' order."""
    try:
        from distributed import Client, LocalCluster
    except ImportError as e:
        raise ImportError("engine='dask' needs Dask's distributed scheduler: pip install 'dask[distributed]'") from e

    def run(client):
        # One future for the whole document (a tuple given alone would be scattered item by item), under a
        # key of its own: keys by content would be shared with an earlier study whose futures are being
        # released, and a worker could find the data gone.
        (shared,) = client.scatter([document], broadcast=True, hash=False)
        return client.gather([client.submit(function, shared, *job, pure=False) for job in jobs])

    try:
        from distributed import get_client

        client = get_client()
    except ValueError:
        client = None
    if client is not None:
        return run(client)
    with LocalCluster(n_workers=workers or os.cpu_count() or 1, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        return run(client)


def _on_threads(function: Callable[..., Any], document: Tuple[str, str], jobs: List[tuple], workers: Optional[int]):
    """``function(document, *job)`` for every job on ``workers`` threads of this process (the solver lets go
    of the GIL, so they run side by side); the results in the jobs' order."""
    from concurrent.futures import ThreadPoolExecutor

    with ThreadPoolExecutor(max_workers=workers or os.cpu_count() or 1) as pool:
        return list(pool.map(lambda job: function(document, *job), jobs))


_RUNNERS = {"ray": _on_ray, "dask": _on_dask, "local": _on_threads}


def _engine_slots(engine: str, workers: Optional[int]) -> int:
    """How many tasks the engine runs at once, as far as the study can tell before it starts."""
    if workers is not None:
        return workers
    if engine == "ray":
        try:
            import ray

            if ray.is_initialized():
                return max(1, int(ray.cluster_resources().get("CPU", 1)))
        except ImportError:
            pass
    if engine == "dask":
        try:
            from distributed import get_client

            return max(1, sum(get_client().nthreads().values()))
        except (ImportError, ValueError):
            pass
    return os.cpu_count() or 1


def _check_engine(engine: str, workers: Optional[int]) -> None:
    if engine not in ENGINES:
        raise ValueError(f"engine '{engine}': give one of {', '.join(ENGINES)}")
    if workers is not None and workers < 1:
        raise ValueError("workers: give at least 1 (or None for every core)")


def _provenance(model: Any, document: Tuple[str, str], count: int) -> Dict[str, str]:
    """What a study's Parquet metadata says of it: version, model, the document's SHA-256 (of the model file
    as re-written and sent to the workers, not of its bytes), the number of variants and how each is run."""
    return {
        "version": _native.VERSION,
        "model": model.name,
        "document_sha256": hashlib.sha256(document[0].encode()).hexdigest(),
        "variants": str(count),
        "half_range_m": repr(_native.BATCH_HALF_RANGE),
        "steps": str(_native.BATCH_STEPS),
    }


def study(
    model: Any,
    variants: Any,
    *,
    engine: str = "local",
    workers: Optional[int] = None,
    chunks: Optional[int] = None,
    parquet: "Optional[os.PathLike[str] | str]" = None,
) -> Study:
    """Runs a design study: every variant of ``model`` judged as ``elastokin batch`` judges it (parallel
    wheel travel ±``BATCH_HALF_RANGE`` m in ``BATCH_STEPS`` steps; bump steer, camber gain and wheel rate at
    design), on ``engine`` ("local", "ray" or "dask"; see the module's documentation).

    ``model``: a :class:`Model`, a model file's path, or a dict. ``variants``: any form
    :func:`read_variants` takes — a variant table (DataFrame or dict of columns keyed by JSON pointer), a list
    of dicts or variants-file lines, or a variants file's text — in any number (a batch takes at most
    ``MAX_VARIANTS``). ``workers``: how many CPUs a local Ray or Dask cluster gets (default: every core).
    ``chunks``: how many tasks (default: four per worker, each at most ``MAX_VARIANTS`` variants).
    ``parquet``: a path to write the table to as well (needs pyarrow).

    Raises ModelError before any task runs when a variant cannot be read or edits a key the model lacks, and
    ModelError from the task that reads it when an edit makes the model invalid. The rows are bit for bit
    those of the single-process batch, whatever the engine."""
    from . import Model, load

    _check_engine(engine, workers)
    if chunks is not None and chunks < 1:
        raise ValueError("chunks: give at least 1 (or None for four per worker)")
    if not isinstance(model, Model):
        model = load(model)
    document = model._native.document()
    # Read and checked here, before any task is sent: a mistake in the table stops the study at once.
    table = read_variants(model, variants)
    count = len(table)
    wanted = chunks if chunks is not None else _CHUNKS_PER_WORKER * _engine_slots(engine, workers)
    wanted = max(wanted, -(-count // _native.MAX_VARIANTS))
    blocks = [(table[start:end], start) for start, end in _split(count, min(wanted, count))]
    results = _RUNNERS[engine](_run_chunk, document, blocks, workers)
    rows = [row for block in results for row in block]
    result = Study(rows, table, dict(_provenance(model, document, count), engine=engine))
    if parquet is not None:
        result.to_parquet(parquet)
    return result


class Grid:
    """A full-factorial variant table: every combination of the values given for each JSON pointer, the last
    pointer's values varying fastest (the order of ``itertools.product``), variant k named ``grid k+1``.

    A variant is found from its number alone, so a grid of any size takes no memory, and a task of
    :func:`study_parts` makes its own block of it: a study of 10⁸ variants sends each task the grid and two
    numbers, not its variants. ``len(grid)``, ``grid[k]`` (a dict: ``name`` and one value per pointer),
    ``grid[a:b]`` (a list of them) and iteration work as on a list."""

    __slots__ = ("axes", "_sizes")

    def __init__(self, axes: Mapping[str, Sequence[Any]]) -> None:
        if not axes:
            raise _native.ModelError("grid: give at least one JSON pointer and its values")
        self.axes: List[Tuple[str, List[Any]]] = []
        for pointer, values in axes.items():
            if not isinstance(pointer, str) or not pointer.startswith("/"):
                raise _native.ModelError(f"grid: '{pointer}' is not a JSON pointer (they start with '/')")
            values = list(values)
            if not values:
                raise _native.ModelError(f"grid: '{pointer}' has no values; give at least one")
            self.axes.append((pointer, values))
        self._sizes = [len(values) for _, values in self.axes]

    def __len__(self) -> int:
        return math.prod(self._sizes)

    def _variant(self, k: int) -> Dict[str, Any]:
        variant: Dict[str, Any] = {"name": f"grid {k + 1}"}
        picks = []
        for size in reversed(self._sizes):
            k, pick = divmod(k, size)
            picks.append(pick)
        for (pointer, values), pick in zip(self.axes, reversed(picks)):
            variant[pointer] = values[pick]
        return variant

    def __getitem__(self, key: Any) -> Any:
        count = len(self)
        if isinstance(key, slice):
            start, stop, step = key.indices(count)
            return [self._variant(k) for k in range(start, stop, step)]
        k = int(key) + (count if int(key) < 0 else 0)
        if not 0 <= k < count:
            raise IndexError(f"grid: variant {key} of {count}")
        return self._variant(k)

    def __iter__(self):
        return (self._variant(k) for k in range(len(self)))

    def __repr__(self) -> str:
        sizes = " × ".join(f"{len(v)} {p}" for p, v in self.axes)
        return f"<elastokin.Grid {len(self)} variants: {sizes}>"


class Parts:
    """What :func:`study_parts` leaves: a directory of Parquet files, one per part (``part-<first variant
    number>.parquet``, each the table of :class:`Study` with the study's provenance in its metadata), that
    together hold every variant once. ``dataset()`` opens them as one pyarrow dataset to query."""

    __slots__ = ("path", "variants", "failed", "parts", "written")

    def __init__(self, path: "os.PathLike[str] | str", variants: int, failed: int, parts: int, written: int) -> None:
        self.path = os.fspath(path)
        self.variants = variants  #: variants in the study
        self.failed = failed  #: variants whose solve failed (their error column says why)
        self.parts = parts  #: part files
        self.written = written  #: part files written by this call (the others were there already)

    def dataset(self):
        """The parts as one pyarrow dataset (needs pyarrow): filter and project it without reading it all."""
        import pyarrow.dataset

        return pyarrow.dataset.dataset(self.path, format="parquet")

    def __repr__(self) -> str:
        return (f"<elastokin.Parts {self.path}: {self.variants} variants in {self.parts} parts, "
                f"{self.failed} failed, {self.written} written now>")


def _part_name(first: int) -> str:
    return f"part-{first + 1:012d}.parquet"


def _block_key(table: List[_Variant]) -> str:
    """What identifies a part's variants: the SHA-256 of their names and edits as read."""
    return hashlib.sha256(json.dumps(table).encode()).hexdigest()


def _run_part(document: Tuple[str, str], source: Any, start: int, stop: int, first: int, path: str,
              metadata: Dict[str, str], pointers: Dict[str, bool]) -> Tuple[int, int]:
    """One part of :func:`study_parts`: variants ``start..stop`` of ``source`` (a grid cut here, on the
    worker, or the block itself), numbered from ``first + 1``, solved on one thread and written whole to
    ``path``. Gives (variants, failed)."""
    from . import _from_document

    model = _from_document(*document)
    table = read_variants(model, source[start:stop])
    rows = _numbered(model._native.batch(table, threads=1), first)
    failed = sum(row["error"] is not None for row in rows)
    meta = dict(metadata, first_variant=str(first + 1), last_variant=str(first + len(rows)),
                failed=str(failed), block_sha256=_block_key(table))
    Study(rows, table, meta, pointers).to_parquet(path)
    return len(rows), failed


def _existing_part(path: Path, expected: Dict[str, str]) -> Optional[int]:
    """The failed count of a part already written by this same study, None when there is none; a part of
    another study is refused by name."""
    if not path.exists():
        return None
    import pyarrow.parquet

    try:
        meta = {k.decode(): v.decode() for k, v in (pyarrow.parquet.read_schema(path).metadata or {}).items()}
    except Exception as e:  # a file that is no Parquet (truncated, foreign): named, not trusted
        raise _native.Error(f"{path}: not a part of a study ({e}); remove it or give an empty directory") from None
    for key, value in expected.items():
        if meta.get(f"elastokin.{key}") != value:
            raise _native.Error(
                f"{path}: a part of another study (its {key} is {meta.get(f'elastokin.{key}')!r}, this study's "
                f"{value!r}); give an empty directory, or the model and variants that wrote it")
    return int(meta["elastokin.failed"])


def study_parts(
    model: Any,
    variants: Any,
    out: "os.PathLike[str] | str",
    *,
    engine: str = "local",
    workers: Optional[int] = None,
    part_size: int = 1000,
) -> Parts:
    """Runs a study too big to gather in one process: each task solves ``part_size`` variants and writes them
    as one Parquet part in the directory ``out``, and only counts come back. Judged as :func:`study`
    judges, the same rows bit for bit, numbered alike; on ``engine`` "local" (threads of this process), "ray"
    or "dask" as :func:`study` uses them.

    ``variants``: a :class:`Grid` (each task makes its own block: nothing per variant is done or sent here),
    a sequence of variants (a list of dicts or lines, a pandas DataFrame; each task is sent its slice), or any
    other form :func:`read_variants` takes (read here first). A part already in ``out`` from the same model
    and variants is kept, not solved again, so a study that stopped (a node lost, a job out of time) is run
    again to finish it; a file there from another study is refused by name. Needs pyarrow on every worker."""
    from . import Model, load

    _check_engine(engine, workers)
    if part_size < 1:
        raise ValueError("part_size: give at least 1 variant a part")
    try:
        import pyarrow  # noqa: F401  (said here, before any task, rather than by every worker)
    except ImportError as e:
        raise ImportError("study_parts writes Parquet, which needs pyarrow: pip install pyarrow") from e
    if not isinstance(model, Model):
        model = load(model)
    if isinstance(variants, Grid):
        pointers = {p: _all_numbers(values) for p, values in variants.axes}
    else:
        # Read here: every part then has the same columns, of the same types, whatever its own variants edit.
        variants = read_variants(model, variants)
        pointers = {p: _all_numbers(values) for p, values in _edited_values(variants).items()}
    count = len(variants)
    if count == 0:
        raise _native.ModelError("variants: no variants")
    document = model._native.document()
    metadata = _provenance(model, document, count)
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    blocks = _split(count, -(-count // part_size))
    names = {_part_name(start) for start, _ in blocks}
    strays = sorted(p.name for p in out.glob("part-*.parquet") if p.name not in names)
    if strays:
        raise _native.Error(f"{out}: {strays[0]} is no part of this study (parts of {part_size} variants); give "
                            "an empty directory, or the part size that wrote it")
    jobs, failed = [], 0
    for start, stop in blocks:
        path = out / _part_name(start)
        block = variants if isinstance(variants, Grid) else variants[start:stop]
        lo, hi = (start, stop) if isinstance(variants, Grid) else (0, stop - start)
        expected = dict(metadata, first_variant=str(start + 1), last_variant=str(stop))
        if path.exists():
            expected["block_sha256"] = _block_key(read_variants(model, block[lo:hi]))
        done = _existing_part(path, expected)
        if done is None:
            jobs.append((block, lo, hi, start, os.fspath(path), metadata, pointers))
        else:
            failed += done
    if jobs:
        results = _RUNNERS[engine](_run_part, document, jobs, workers)
        failed += sum(f for _, f in results)
    return Parts(out, count, failed, len(blocks), len(jobs))
