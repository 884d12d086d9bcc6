"""elastokin.compare: the command's comparison, from Python."""

import os

import pytest

import elastokin

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")
MACPHERSON = os.path.join(ROOT, "examples", "macpherson.json")
DOUBLE_WISHBONE = os.path.join(ROOT, "examples", "double_wishbone.json")


def test_figures_are_each_models_own_and_their_difference():
    c = elastokin.compare(MACPHERSON, DOUBLE_WISHBONE, analysis="parallel-travel", steps=8)
    a, b = c["names"]
    figures = c["figures"]
    rows = list(figures["figure"])
    k = rows.index("bump_steer")
    own_a = elastokin.load(MACPHERSON).run("parallel-travel", steps=8).summary["figures"]["bump_steer"]["value"]
    own_b = elastokin.load(DOUBLE_WISHBONE).run("parallel-travel", steps=8).summary["figures"]["bump_steer"]["value"]
    assert figures[a][k] == own_a and figures[b][k] == own_b
    assert figures[f"{b} − {a}"][k] == own_b - own_a
    toe = next(ch for ch in c["charts"] if ch["name"] == "compare_parallel_travel_toe_camber_toe_in")
    assert list(toe["curves"]) == [a, b]


def test_a_measured_file_stands_beside_a_model_and_a_mixed_pair_is_refused(tmp_path):
    rig = tmp_path / "rig.csv"
    rig.write_text("# analysis: parallel-travel\ntravel_m,toe_deg\n-0.05,1.1\n0,0\n0.05,-1.3\n")
    c = elastokin.compare(elastokin.load(MACPHERSON), str(rig), analysis="parallel-travel", steps=8)
    measured = next(ch for ch in c["charts"] if ch["name"].startswith("compare_measured_"))
    x, y = measured["curves"]["rig.csv"]
    assert list(x) == [-0.05, 0.0, 0.05] and list(y) == [1.1, 0.0, -1.3]
    with pytest.raises(ValueError, match="solid axle"):
        elastokin.compare(MACPHERSON, os.path.join(ROOT, "examples", "four_link_axle.json"), analysis="parallel-travel")
