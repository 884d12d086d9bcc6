"""What the Python tests share: the `elastokin` command of this repository, run once per session, and its
output files, the independent record the Python API's results are compared with."""


import csv
import json
import math
import subprocess
from pathlib import Path

import pytest

import elastokin

ROOT = Path(__file__).resolve().parents[2]
MODEL = ROOT / "examples" / "generic" / "macpherson.json"
VARIANTS = ROOT / "examples" / "generic" / "macpherson_variants.txt"


def command(*args, check=True):
    """Runs the `elastokin` command of this repository; gives the finished process."""
    return subprocess.run(
        ["cargo", "run", "-q", "--", *map(str, args)],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=check,
    )


def command_error(*args):
    """The command's error message: its standard error's `error: ` line(s), the prefix taken off."""
    done = command(*args, check=False)
    assert done.returncode != 0
    lines = done.stderr.splitlines()
    start = next(k for k, line in enumerate(lines) if line.startswith("error: "))
    return "\n".join([lines[start][len("error: "):]] + lines[start + 1:])


def read_csv(path):
    """A CSV the command wrote: (header, rows), the provenance comment line skipped."""
    with open(path, newline="") as f:
        lines = [line for line in f if not line.startswith("#")]
    table = list(csv.reader(lines))
    return table[0], table[1:]


def _is_number(text):
    try:
        float(text)
        return True
    except ValueError:
        return False


def printed(v):
    """A value as the command's CSV prints it: 12 significant digits (NaN for an empty cell)."""
    return float(f"{v:.11e}") if math.isfinite(v) else math.nan


def same_column(values, cells):
    if isinstance(values, list):
        # A column of names: each cell as printed.
        assert [v if isinstance(v, str) else "" if v is None else repr(printed(v)) for v in values] == [
            c if not _is_number(c) else repr(float(c)) for c in cells
        ]
        return
    expected = [float(c) if c != "" else math.nan for c in cells]
    got = [printed(v) for v in values]
    assert len(got) == len(expected)
    for g, e in zip(got, expected):
        assert (math.isnan(g) and math.isnan(e)) or g == e, (g, e)


@pytest.fixture(scope="session")
def out(tmp_path_factory):
    """The command's full K&C run of the MacPherson example, with the compliance tables."""
    d = tmp_path_factory.mktemp("run") / "out"
    command("run", MODEL, "--quiet", "--compliance", "--out", d)
    return d


@pytest.fixture(scope="session")
def summary(out):
    return json.loads((out / "summary.json").read_text())


@pytest.fixture(scope="session")
def model():
    return elastokin.load(MODEL)


@pytest.fixture(scope="session")
def batch_csv(tmp_path_factory):
    d = tmp_path_factory.mktemp("batch") / "out"
    command("batch", MODEL, VARIANTS, "--quiet", "--out", d)
    return read_csv(d / "batch.csv")


def same_batch(rows, batch_csv):
    header, expected = batch_csv
    assert len(rows) == len(expected)
    for row, cells in zip(rows, expected):
        assert list(row) == header
        assert row["variant"] == cells[0]
        for k, column in enumerate(header[1:4], start=1):
            # A variant that failed has no figures: None here, an empty cell there.
            assert (row[column] is None and cells[k] == "") or printed(row[column]) == float(cells[k])
        assert (row["error"] or "") == cells[4]
