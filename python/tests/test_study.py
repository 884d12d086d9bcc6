"""Design studies on Ray and on Dask's LocalCluster, two workers each, against the single-process batch and
the command's batch.csv: the same rows, bit for bit (each variant is solved on its own, wherever it runs)."""

import importlib
import itertools
import json
import math
import os
import pickle
import subprocess

import numpy
import pytest
from conftest import MODEL, VARIANTS, command, read_csv, same_batch

import elastokin


def engine(name):
    """An engine's module; CI installs both engines, so there a missing one fails instead of skipping."""
    if os.environ.get("CI"):
        return importlib.import_module(name)
    return pytest.importorskip(name)


TIE_ROD = "/suspension/macpherson/hardpoints/tie_rod_inner/2"
SPRING = "/suspension/macpherson/spring/rate"


@pytest.fixture(scope="module")
def table():
    """A variant table of 6 tie-rod heights × 5 spring rates: 30 variants, one column per pointer."""
    heights = [-0.069 + 0.004 * k for k in range(6)]
    rates = [20000.0 + 5000.0 * k for k in range(5)]
    rows = [(f"h{h:+.3f} k{k:.0f}", h, k) for h in heights for k in rates]
    return {"name": [r[0] for r in rows], TIE_ROD: [r[1] for r in rows], SPRING: [r[2] for r in rows]}


@pytest.fixture(scope="module")
def table_csv(table, tmp_path_factory):
    """The command's batch.csv of the same table, written as a variants file."""
    d = tmp_path_factory.mktemp("study")
    lines = [f"{n}: {TIE_ROD}={h!r}; {SPRING}={k!r}" for n, h, k in zip(*table.values())]
    (d / "variants.txt").write_text("\n".join(lines) + "\n")
    command("batch", MODEL, d / "variants.txt", "--quiet", "--out", d / "out")
    return read_csv(d / "out" / "batch.csv")


def same_study(study, reference):
    """The study's rows are the reference batch's rows, bit for bit, numbered from 1 in order."""
    rows = study.rows()
    assert [r.pop("variant_number") for r in rows] == list(range(1, len(reference) + 1))
    assert rows == reference


@pytest.fixture(scope="module")
def model():
    return elastokin.load(MODEL)


@pytest.fixture(scope="module")
def reference(model, table):
    return elastokin.batch(model, table)


def test_a_local_study_is_the_batch_and_the_command_s_table(model, table, table_csv, reference):
    same_batch(reference, table_csv)
    study = elastokin.study(model, table)
    same_study(study, reference)
    # The table's own columns come back beside the figures, for queries by parameter.
    assert list(study.columns) == ["variant_number", "variant", TIE_ROD, SPRING, *elastokin.BATCH_FIGURES, "error"]
    assert study.columns[TIE_ROD].tolist() == table[TIE_ROD]
    assert study.columns[SPRING].tolist() == table[SPRING]
    for figure in elastokin.BATCH_FIGURES:
        assert study.columns[figure].tolist() == [r[figure] for r in reference]
    # However it is cut into tasks and threads.
    same_study(elastokin.study(model, table, chunks=7, workers=1), reference)


def test_a_study_on_ray_with_two_workers_is_the_batch(model, table, reference):
    ray = engine("ray")
    try:
        assert not ray.is_initialized()
        study = elastokin.study(model, table, engine="ray", workers=2)
        # The study started a local Ray of two CPUs and left it for the next study.
        assert ray.is_initialized() and ray.cluster_resources()["CPU"] == 2
        same_study(study, reference)
        same_study(elastokin.study(MODEL, VARIANTS.read_text(), engine="ray"), elastokin.batch(model, VARIANTS.read_text()))
        # A model file's path, a Ray already running, and chunks of any size.
        same_study(elastokin.study(MODEL, table, engine="ray", chunks=30), reference)
    finally:
        ray.shutdown()


def test_a_study_on_dask_with_two_workers_is_the_batch(model, table, reference):
    distributed = engine("distributed")
    # Without a client the study makes its own LocalCluster of two processes and closes it.
    same_study(elastokin.study(model, table, engine="dask", workers=2), reference)
    with pytest.raises(ValueError):
        distributed.get_client()
    # With one, the study runs on it.
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            same_study(elastokin.study(model, table, engine="dask", chunks=3), reference)
            assert len(client.nthreads()) == 2


def test_the_variant_table_forms_are_one_table(model, table, reference):
    pandas = engine("pandas")
    frame = pandas.DataFrame(table)
    same_study(elastokin.study(model, frame), reference)
    records = [dict(zip(table, values)) for values in zip(*table.values())]
    same_study(elastokin.study(model, records), reference)
    # numpy columns as a table would hold them.
    as_numpy = {"name": table["name"], TIE_ROD: numpy.array(table[TIE_ROD]), SPRING: numpy.array(table[SPRING])}
    same_study(elastokin.study(model, as_numpy), reference)
    assert elastokin.study(model, table).to_pandas().equals(pandas.DataFrame(elastokin.study(model, table).columns))


def test_parquet_holds_the_table_and_its_provenance(model, table, reference, tmp_path):
    parquet = engine("pyarrow.parquet")
    path = tmp_path / "study.parquet"
    study = elastokin.study(model, table, parquet=path)
    read = parquet.read_table(path)
    assert read.column_names == list(study.columns)
    for name, values in study.columns.items():
        got = read.column(name).to_pylist()
        assert got == (values.tolist() if isinstance(values, numpy.ndarray) else values), name
    meta = {k.decode(): v.decode() for k, v in read.schema.metadata.items()}
    assert meta["elastokin.variants"] == "30" and meta["elastokin.steps"] == str(elastokin.BATCH_STEPS)
    assert meta["elastokin.model"] == model.name and meta["elastokin.engine"] == "local"
    assert str(read.schema.field("error").type) == "string"
    assert not (tmp_path / "study.parquet.partial").exists()


def test_edits_that_are_not_numbers_are_text_columns(model):
    study = elastokin.study(model, VARIANTS.read_text())
    mounts = study.columns["/suspension/macpherson/lower_arm_mounts"]
    assert mounts == [None, None, None, None, None, "ideal"]
    rates = study.columns["/suspension/macpherson/spring/rate"]
    assert math.isnan(rates[1]) and rates[0] == 30000.0 and rates[3] == 20000.0


def test_a_model_travels_to_another_process_as_its_document(model):
    again = pickle.loads(pickle.dumps(model))
    assert again.to_dict() == model.to_dict()
    assert again.batch(VARIANTS.read_text()) == model.batch(VARIANTS.read_text())
    # So do the errors a worker raises: as themselves, message and class.
    for kind in [elastokin.Error, elastokin.ModelError, elastokin.AnalysisError]:
        error = pickle.loads(pickle.dumps(kind("variant 'x': the model has no '/y'")))
        assert type(error) is kind and str(error) == "variant 'x': the model has no '/y'"


def test_mistakes_in_a_study_are_said_before_any_task_runs(model, table):
    with pytest.raises(ValueError, match="engine 'spark': give one of local, ray, dask"):
        elastokin.study(model, table, engine="spark")
    with pytest.raises(ValueError, match="workers: give at least 1"):
        elastokin.study(model, table, engine="dask", workers=0)
    bad = dict(table)
    bad["/suspension/macpherson/spring/rat"] = table[SPRING]
    # Named as the batch names it, before a Ray is started.
    message = "variant 'h-0.069 k20000': the model has no '/suspension/macpherson/spring/rat'"
    with pytest.raises(elastokin.ModelError) as raised:
        elastokin.study(model, bad, engine="ray", workers=2)
    assert str(raised.value) == message
    with pytest.raises(elastokin.ModelError) as from_batch:
        elastokin.batch(model, bad)
    assert str(from_batch.value) == message
    if _has("ray"):
        import ray

        assert not ray.is_initialized()
    with pytest.raises(elastokin.ModelError, match="columns of a variant table differ in length"):
        elastokin.study(model, {TIE_ROD: [0.0, 0.1], SPRING: [1.0]})
    with pytest.raises(elastokin.ModelError, match=r"variants\[0\] '/suspension/macpherson/spring/rate': nan"):
        elastokin.study(model, [{SPRING: math.nan}])


def test_an_edit_that_makes_the_model_invalid_fails_the_study_as_it_fails_the_batch(model):
    variants = ["good: /suspension/macpherson/spring/rate=30000.0", "bad: /suspension/macpherson/spring/rate=-5"]
    with pytest.raises(elastokin.ModelError) as from_batch:
        elastokin.batch(model, variants)
    distributed = engine("distributed")
    assert distributed
    with pytest.raises(elastokin.ModelError) as from_study:
        elastokin.study(model, variants, engine="dask", workers=2)
    assert str(from_study.value) == str(from_batch.value)
    assert "spring.rate: -5 N/m is outside the accepted range" in str(from_batch.value)


def _has(name):
    try:
        __import__(name)
        return True
    except ImportError:
        return False


def test_the_split_is_the_shard_rule():
    # Variant k of V goes to chunk floor(k·N/V), as `elastokin batch --shard` assigns it (src/batch.rs).
    from elastokin._study import _split

    for count in [1, 2, 7, 30, 101]:
        for chunks in [1, 2, 3, 8, count]:
            blocks = _split(count, min(chunks, count))
            owner = [j for j, (a, b) in enumerate(blocks) for _ in range(a, b)]
            assert owner == [k * min(chunks, count) // count for k in range(count)]
    assert _split(5, 2) == [(0, 3), (3, 5)]


def test_a_value_of_the_table_is_sent_as_the_json_it_is():
    # The float fast path writes what json.dumps writes, for Python and numpy numbers alike.
    from elastokin._study import _json_value

    for value in [0.1, -0.069, 1e-300, 5e6, 1e22, 2.5e-7, numpy.float64(0.1), numpy.float32(0.1), 3,
                  numpy.int64(4), "ideal", {"bushing": {"radial": 2e6}}, True, [1.0, 2.0]]:
        plain = value.item() if isinstance(value, numpy.generic) else value
        assert _json_value(value, "x") == json.dumps(plain), value
    with pytest.raises(elastokin.ModelError, match="x: inf is not a model value"):
        _json_value(math.inf, "x")


ARM_RADIAL = "/suspension/macpherson/lower_arm_mounts/bushing/radial"


@pytest.fixture(scope="module")
def grid():
    """4 tie-rod heights × 3 spring rates × 5 arm bushing rates: 60 variants."""
    return elastokin.Grid({
        TIE_ROD: [-0.069 + 0.005 * k for k in range(4)],
        SPRING: [20000.0, 30000.0, 40000.0],
        ARM_RADIAL: [1e6 * 2.0**k for k in range(5)],
    })


def test_a_grid_is_the_product_of_its_axes_in_order(grid):
    product = list(itertools.product(*(values for _, values in grid.axes)))
    assert len(grid) == len(product) == 60
    listed = list(grid)
    for k, values in enumerate(product):
        assert listed[k] == grid[k] == {"name": f"grid {k + 1}", TIE_ROD: values[0], SPRING: values[1],
                                        ARM_RADIAL: values[2]}
    assert grid[-1] == listed[-1] and grid[7:19] == listed[7:19] and grid[58:100] == listed[58:]
    with pytest.raises(IndexError):
        grid[60]
    with pytest.raises(elastokin.ModelError, match="'spring' is not a JSON pointer"):
        elastokin.Grid({"spring": [1.0]})
    with pytest.raises(elastokin.ModelError, match="'/a' has no values"):
        elastokin.Grid({"/a": []})
    assert pickle.loads(pickle.dumps(grid))[33] == grid[33]


def comparable(values):
    """A column as a list in which NaN (a cell with no value) equals NaN."""
    return ["NaN" if isinstance(v, float) and math.isnan(v) else v for v in values]


def read_parts(parts):
    """The parts as one table, in variant order: column name → list."""
    table = parts.dataset().to_table().sort_by("variant_number")
    return {name: comparable(table.column(name).to_pylist()) for name in table.column_names}


def as_lists(study):
    return {k: comparable(v.tolist() if isinstance(v, numpy.ndarray) else v) for k, v in study.columns.items()}


def test_parts_written_by_two_dask_workers_are_the_study(model, grid, tmp_path):
    engine("distributed")
    engine("pyarrow")
    whole = elastokin.study(model, grid)
    same_study(whole, elastokin.batch(model, list(grid)))
    parts = elastokin.study_parts(model, grid, tmp_path / "parts", engine="dask", workers=2, part_size=7)
    assert (parts.variants, parts.parts, parts.written, parts.failed) == (60, 9, 9, 0)
    assert sorted(p.name for p in (tmp_path / "parts").iterdir())[:2] == ["part-000000000001.parquet",
                                                                          "part-000000000008.parquet"]
    assert read_parts(parts) == as_lists(whole)


def test_a_study_in_parts_that_stopped_is_finished_by_running_it_again(model, grid, tmp_path):
    ray = engine("ray")
    engine("pyarrow")
    out = tmp_path / "parts"
    first = elastokin.study_parts(model, grid, out, part_size=10)  # local: threads of this process
    assert (first.parts, first.written) == (6, 6)
    kept = {p.name: p.stat().st_mtime_ns for p in out.iterdir()}
    (out / "part-000000000031.parquet").unlink()  # as if the task writing it had been lost
    try:
        again = elastokin.study_parts(model, grid, out, engine="ray", workers=2, part_size=10)
    finally:
        ray.shutdown()
    assert (again.parts, again.written, again.failed) == (6, 1, 0)
    for name, mtime in kept.items():
        if name != "part-000000000031.parquet":
            assert (out / name).stat().st_mtime_ns == mtime, name
    assert read_parts(again) == as_lists(elastokin.study(model, grid))
    # Nothing left to do: nothing is written.
    assert elastokin.study_parts(model, grid, out, part_size=10).written == 0


def test_parts_of_a_list_and_of_a_frame_are_the_study(model, table, reference, tmp_path):
    pandas = engine("pandas")
    engine("pyarrow")
    records = [dict(zip(table, values)) for values in zip(*table.values())]
    whole = as_lists(elastokin.study(model, table))
    for k, variants in enumerate([records, pandas.DataFrame(table), table, VARIANTS.read_text()]):
        parts = elastokin.study_parts(model, variants, tmp_path / f"p{k}", part_size=4, workers=2)
        if k < 3:
            assert read_parts(parts) == whole
        else:
            assert read_parts(parts) == as_lists(elastokin.study(model, VARIANTS.read_text()))


def test_a_directory_holding_another_study_is_refused_by_name(model, grid, tmp_path):
    engine("pyarrow")
    out = tmp_path / "parts"
    elastokin.study_parts(model, grid, out, part_size=20)
    stiffer = model.to_dict()
    stiffer["suspension"]["macpherson"]["spring"]["design_force"] = 4600.0
    with pytest.raises(elastokin.Error, match=r"part-000000000001.parquet: a part of another study \(its "
                                              r"document_sha256 is"):
        elastokin.study_parts(stiffer, grid, out, part_size=20)
    other = elastokin.Grid({TIE_ROD: [-0.069 + 0.005 * k for k in range(4)], SPRING: [20000.0, 30000.0, 40000.0],
                            ARM_RADIAL: [1e6 * 3.0**k for k in range(5)]})
    with pytest.raises(elastokin.Error, match="a part of another study \\(its block_sha256 is"):
        elastokin.study_parts(model, other, out, part_size=20)
    with pytest.raises(elastokin.Error, match="part-000000000021.parquet is no part of this study"):
        elastokin.study_parts(model, grid, out, part_size=30)
    (out / "part-000000000021.parquet").write_text("not parquet")
    with pytest.raises(elastokin.Error, match="part-000000000021.parquet: not a part of a study"):
        elastokin.study_parts(model, grid, out, part_size=20)
    with pytest.raises(ValueError, match="part_size: give at least 1"):
        elastokin.study_parts(model, grid, out, part_size=0)


def test_a_variant_the_solver_cannot_hold_is_a_row_with_its_reason_on_every_engine(tmp_path):
    # An upper arm 3 mm long on ideal mounts cannot follow 20 mm of wheel travel: the solve fails, the study
    # does not. The command's batch.csv of the same lines is the record.
    dw = MODEL.parent / "double_wishbone.json"
    base = "/suspension/double_wishbone"
    short = (f"short arm: {base}/hardpoints/upper_arm_front=[-0.088,0.805,0.243]; "
             f"{base}/hardpoints/upper_arm_rear=[-0.2,0.805,0.243]; {base}/upper_arm_mounts=\"ideal\"; "
             f"{base}/lower_arm_mounts=\"ideal\"")
    lines = [f"soft: {base}/spring/rate=20000.0", short, f"stiff: {base}/spring/rate=40000.0"]
    (tmp_path / "variants.txt").write_text("\n".join(lines) + "\n")
    done = command("batch", dw, tmp_path / "variants.txt", "--quiet", "--out", tmp_path / "out", check=False)
    assert done.returncode == 0, done.stderr
    header, expected = read_csv(tmp_path / "out" / "batch.csv")
    assert expected[1][4].startswith("the suspension cannot go beyond -0.00") and expected[0][4] == expected[2][4] == ""
    rows = elastokin.batch(dw, lines)
    same_batch(rows, (header, expected))
    engine("distributed")
    study = elastokin.study(dw, lines, engine="dask", workers=2, chunks=3)
    same_study(study, rows)
    assert math.isnan(study.columns["wheel_rate_n_per_m"][1]) and repr(study) == "<elastokin.Study 3 variants, 1 failed>"
    engine("pyarrow")
    parts = elastokin.study_parts(dw, lines, tmp_path / "parts", part_size=2)
    assert (parts.failed, parts.parts) == (1, 2)
    assert read_parts(parts) == as_lists(study)


def test_ctrl_c_stops_a_long_batch_at_once():
    """Ctrl-C in the middle of a batch of seconds raises KeyboardInterrupt well before the batch would end:
    the variants run in chunks of about a tenth of a second, Python's signals heard between them."""
    import signal
    import sys
    import time

    # Python hears SIGINT only where it was not ignored when it started (a background job ignores it): the
    # child restores the interactive default, KeyboardInterrupt.
    script = (
        "import signal, sys, elastokin\n"
        "signal.signal(signal.SIGINT, signal.default_int_handler)\n"
        "variants = [{'/suspension/macpherson/spring/rate': 15000.0 + k} for k in range(10000)]\n"
        "model = elastokin.load(sys.argv[1])\n"
        "print('started', flush=True)\n"
        "model.batch(variants)\n"
        "print('finished', flush=True)\n"
    )

    def batch(interrupt_after):
        """Runs the batch in a child; with `interrupt_after` (s), Ctrl-C then. Gives the seconds from the
        batch's start (or the interrupt) to the child's end, and its outputs."""
        child = subprocess.Popen(
            [sys.executable, "-c", script, str(MODEL)],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        assert child.stdout.readline().strip() == "started"
        start = time.monotonic()
        if interrupt_after is not None:
            time.sleep(interrupt_after)
            start = time.monotonic()
            child.send_signal(signal.SIGINT)
        out, err = child.communicate(timeout=120)
        return time.monotonic() - start, out, err

    whole, out, _ = batch(None)
    assert "finished" in out
    stopped, out, err = batch(0.3)
    print(f"the whole batch {whole:.2f} s; stopped {stopped:.2f} s after Ctrl-C")
    assert "finished" not in out and "KeyboardInterrupt" in err, err
    # Measured: the whole batch 3.8-4.6 s, stopped 0.08-0.45 s after Ctrl-C.
    assert stopped < 0.5 * (whole - 0.3), f"stopped {stopped:.1f} s after Ctrl-C, the batch takes {whole:.1f} s"
