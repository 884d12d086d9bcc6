"""Sensitivities from Python: the command's own numbers, a gradient that differences of the objective
confirm, and a bump steer tuned by scipy with the gradient from the sensitivities."""

import json
import math

import numpy
import pytest

import elastokin

from conftest import MODEL, command, read_csv

TIE_ROD_Z = "/suspension/macpherson/hardpoints/tie_rod_inner/2"
# Each unit parallel travel prints its figures in, per its SI unit, from the units' definitions.
DEG = 180 / math.pi
PRINTED_PER_SI = {"deg/m": DEG, "N/mm": 1e-3, "-": 1.0, "N": 1.0, "deg": DEG, "mm": 1e3, "deg/kN": DEG * 1e3,
                  "deg/kN·m": DEG * 1e3, "%": 100.0}
RATE = "/suspension/macpherson/spring/rate"


def test_sensitivities_are_the_commands(tmp_path):
    out = tmp_path / "out"
    command(
        "sensitivity", MODEL, "--analysis", "parallel-travel", "--param", TIE_ROD_Z, "--param", RATE,
        "--quiet", "--out", out,
    )
    header, rows = read_csv(out / "sensitivity.csv")
    model = elastokin.load(MODEL)
    s = model.sensitivities([TIE_ROD_Z, RATE])
    assert s["parameters"] == [TIE_ROD_Z, RATE] and s["analysis"] == "parallel-travel"
    assert len(rows) == 2 * len(s["figures"]) and len(s["figures"]) == 23
    for row in rows:
        analysis, figure, parameter = row[0], row[1], row[4]
        assert analysis == "parallel-travel"
        got = s["figures"][figure]["derivatives"][s["parameters"].index(parameter)]
        assert s["figures"][figure]["unit"] == row[2]
        if row[6] == "":
            assert numpy.isnan(got), (figure, parameter)
            continue
        # The CSV holds 12 significant digits of the same number, and of its error estimate.
        assert got == pytest.approx(float(row[6]), rel=1e-11, abs=1e-300), (figure, parameter)
        error = s["figures"][figure]["derivative_errors"][s["parameters"].index(parameter)]
        assert header[7] == "derivative_error" and error == pytest.approx(float(row[7]), rel=1e-11)
        # In SI: the printed derivative over the printed unit's definition, as the value is.
        si = s["figures"][figure]["si_derivatives"][s["parameters"].index(parameter)]
        factor = PRINTED_PER_SI[row[2]]
        assert si * factor == pytest.approx(got, rel=1e-12), (figure, parameter)
        assert s["figures"][figure]["si_value"] * factor == pytest.approx(s["figures"][figure]["value"], rel=1e-12)
    # Every cell of the table, as sensitivity_parallel_travel.csv has it.
    header, cells = read_csv(out / "sensitivity_parallel_travel.csv")
    assert header[:3] == ["parameter", "travel_m", "d_toe_deg"] and len(cells) == 2 * 33
    for r, row in enumerate(cells[:33]):
        assert float(row[2]) == pytest.approx(s["d_toe_deg"][r, 0], rel=1e-11, abs=1e-300)
    assert s["d_toe_deg"].shape == (33, 2) and s["travel_m"].shape == (33,)
    assert header[3] == "d_toe_deg_error" and s["d_toe_deg_error"].shape == (33, 2)
    assert (s["d_toe_deg_error"] > 0).all()
    # The figure is the rate at design read off the path there: the rows' derivatives, differenced about
    # design (row 16) over one and two rows and Richardson extrapolated, give its derivative to the
    # extrapolation's fourth order in the 5 mm rows.
    d, t = s["d_toe_deg"][:, 0], s["travel_m"]
    near, far = (d[17] - d[15]) / (t[17] - t[15]), (d[18] - d[14]) / (t[18] - t[14])
    slope = (4.0 * near - far) / 3.0
    # Measured: 7.2e-8 relative.
    assert slope == pytest.approx(s["figures"]["bump_steer"]["derivatives"][0], rel=1e-6)


def test_every_hardpoint_by_default_and_any_analysis():
    model = elastokin.load(MODEL)
    assert len(model.hardpoint_parameters()) == 24
    s = model.sensitivities(steps=4)
    assert len(s["parameters"]) == 24 and s["d_camber_deg"].shape == (5, 24)
    lateral = model.sensitivities([RATE], analysis="lateral-force", steps=4)
    assert lateral["columns"][0] == "load_n" and lateral["d_toe_deg"].shape == (5, 1)
    assert numpy.isfinite(lateral["figures"]["steer"]["derivatives"]).all()


def test_the_figures_read_alone_are_the_figures_read_whole():
    model = elastokin.load(MODEL)
    whole = model.sensitivities([TIE_ROD_Z], analysis="lateral-force", steps=4)
    alone = model.sensitivities([TIE_ROD_Z], analysis="lateral-force", steps=4, figures_only=True)
    assert whole["figures"].keys() == alone["figures"].keys()
    for key, figure in whole["figures"].items():
        assert figure["value"] == alone["figures"][key]["value"], key
        numpy.testing.assert_array_equal(figure["derivatives"], alone["figures"][key]["derivatives"])
    # The component forces are left out, toe and camber kept.
    assert any(c.endswith("force_x_n") for c in whole["columns"])
    assert not any(c.endswith("force_x_n") for c in alone["columns"])
    # The replays move only the rows the figures read: no derivative of the table.
    assert numpy.isfinite(whole["d_toe_deg"]).all() and numpy.isnan(alone["d_toe_deg"]).all()


def test_a_parameter_that_names_nothing_is_refused_by_name():
    model = elastokin.load(MODEL)
    with pytest.raises(elastokin.ModelError, match="'/suspension/macpherson/nowhere' names nothing"):
        model.sensitivities(["/suspension/macpherson/nowhere"])
    with pytest.raises(ValueError, match="no analysis 'bump': give one of parallel-travel, roll"):
        model.sensitivities([TIE_ROD_Z], analysis="bump")
    # A figure without a value (the roll stiffness of anti-roll bars the model has not) has no derivative,
    # and says why.
    s = model.sensitivities([TIE_ROD_Z], analysis="roll", steps=4)
    assert s["figures"]["anti_roll_bar_roll_stiffness"]["value"] is None
    assert s["figures"]["anti_roll_bar_roll_stiffness"]["no_derivative"] == ["the figure has no value"]
    # Away from design, the rates at design are read off the design equilibrium all the same, with their
    # derivatives.
    away = model.sensitivities([TIE_ROD_Z], range=(0.01, 0.05), steps=4)
    at = model.sensitivities([TIE_ROD_Z], steps=4)
    assert away["figures"]["bump_steer"]["value"] == at["figures"]["bump_steer"]["value"]
    numpy.testing.assert_array_equal(away["figures"]["bump_steer"]["derivatives"], at["figures"]["bump_steer"]["derivatives"])


def test_objective_gradient_is_the_derivative_of_its_value():
    model = elastokin.load(MODEL)
    pointers = [TIE_ROD_Z, "/suspension/macpherson/hardpoints/tie_rod_outer/2"]
    f = model.objective("bump_steer", pointers, target=-20.0, steps=8)
    x0 = model.sensitivities(pointers, steps=8)["values"]
    value, gradient = f(x0)
    h = 1e-5
    for k in range(2):
        e = numpy.zeros(2)
        e[k] = h
        fd = (f(x0 + e)[0] - f(x0 - e)[0]) / (2 * h)
        # Measured: 1.3e-9 and 9.2e-10 relative apart (the difference's own error at this step).
        assert gradient[k] == pytest.approx(fd, rel=1e-7), k


def test_scipy_tunes_the_bump_steer_with_the_exact_gradient():
    optimize = pytest.importorskip("scipy.optimize")
    model = elastokin.load(MODEL)
    pointers = [TIE_ROD_Z]
    f = model.objective("bump_steer", pointers, target=0.0, steps=8)
    x0 = model.sensitivities(pointers, steps=8)["values"]
    result = optimize.minimize(f, x0, jac=True, method="BFGS", options={"gtol": 1e-12})
    # The tuned model, read again, has no bump steer.
    document = json.loads(model._native.document()[0])
    elastokin._set_pointer(document, TIE_ROD_Z, float(result.x[0]))
    tuned = elastokin.load(document).sensitivities(pointers, steps=8)["figures"]["bump_steer"]
    assert abs(tuned["value"]) < 1e-6, (result, tuned["value"])
    # A Newton step from the start, the bump steer over its rate, lands near it (the rate changes on the way).
    start = model.sensitivities(pointers, steps=8)["figures"]["bump_steer"]
    newton = -start["value"] / start["derivatives"][0]
    assert result.x[0] - x0[0] == pytest.approx(newton, rel=0.2)


def test_tune_gives_the_commands_numbers(tmp_path):
    out = tmp_path / "out"
    targets = "examples/targets/bump_steer.json"
    command("tune", MODEL, targets, "--quiet", "--out", out)
    model = elastokin.load(MODEL)
    t = model.tune(targets)
    assert t["all_met"] and all(v["met"] for v in t["verdicts"])
    assert [p["broken_by"] for p in t["packaging"]] == [0.0]
    tuned = json.loads((out / "tuned.json").read_text())
    for k, pointer in enumerate(t["parameters"]):
        value = tuned
        for key in pointer.strip("/").split("/"):
            value = value[int(key)] if isinstance(value, list) else value[key]
        # The same tune, to the last digit the file holds.
        assert t["after"][k] == pytest.approx(value, rel=1e-15, abs=1e-18)
    assert json.loads(t["tuned"]) == tuned
    header, rows = read_csv(out / "tune.csv")
    assert len(rows) == len(t["iterations"]["iteration"])
    # The fit's uncertainty as tune_uncertainty.csv gives it: each number's standard uncertainty (none here:
    # the targets leave no degree of freedom) and those a bound holds.
    header, rows = read_csv(out / "tune_uncertainty.csv")
    u = t["uncertainty"]
    assert [r[0] for r in rows] == t["parameters"]
    for k, row in enumerate(rows):
        cell = row[header.index("standard_uncertainty")]
        assert (cell == "" and math.isnan(u["standard"][k])) or float(cell) == pytest.approx(u["standard"][k], rel=1e-11)
        assert (row[header.index("at_bound")] == "yes") == (t["parameters"][k] in u["at_bound"])
    assert u["unique"] == (u["unseen"] == [])


def test_a_curve_tuned_by_its_root_mean_square_reports_it():
    # The toe curve straight through three points, measured by its root mean square over their span: the
    # verdict's measure is the trapezoidal root mean square of the tuned model's own rows (20 steps over
    # ±50 mm, design a row, the target bent there), computed here from its table.
    points = [[-0.05, 0.3], [0.0, 0.0], [0.05, -0.2]]
    model = elastokin.load(MODEL)
    base = json.loads(open(MODEL).read())
    value = base
    for key in TIE_ROD_Z.strip("/").split("/"):
        value = value[int(key)] if isinstance(value, list) else value[key]
    targets = {"free": {TIE_ROD_Z: [value - 0.01, value + 0.01]}, "steps": 20,
               "targets": [{"curve": "parallel-travel/toe_deg", "range": [-0.05, 0.05], "points": points,
                            "measure": "rms", "tolerance": 1e-3}]}
    t = model.tune(targets)
    (verdict,) = t["verdicts"]
    assert "root mean square" in verdict["judged"]
    tuned = elastokin.load(json.loads(t["tuned"]))
    table = tuned.run("parallel-travel", range=(-0.05, 0.05), steps=20).columns
    s = numpy.asarray(table["travel_m"])
    miss = numpy.asarray(table["toe_deg"]) - numpy.interp(s, [p[0] for p in points], [p[1] for p in points])
    rms = math.sqrt(numpy.trapezoid(miss**2, s) / 0.1)
    # Measured: the same to 1.8e-16 relative (the same rows, summed in another order).
    assert verdict["worst"] * 1e-3 == pytest.approx(rms, rel=1e-14)
    assert verdict["met"] == (rms <= 1e-3)


def test_an_objective_reports_its_figure_before_and_after():
    # The most bump steer with the camber gain within 0.5 deg/m of the model's: the figure after is the
    # tuned model's own, run again; an optimum is no fit, so no uncertainty.
    model = elastokin.load(MODEL)
    before = model.run("parallel-travel", steps=20)
    camber = before.figure("camber_gain")
    front = "/suspension/macpherson/hardpoints/lower_arm_front/2"
    base = json.loads(open(MODEL).read())["suspension"]["macpherson"]["hardpoints"]
    inner_z, front_z = base["tie_rod_inner"][2], base["lower_arm_front"][2]
    targets = {"free": {TIE_ROD_Z: [inner_z - 0.04, inner_z + 0.04], front: [front_z - 0.04, front_z + 0.04]},
               "objective": {"most": "parallel-travel/bump_steer"}, "steps": 20,
               "targets": [{"figure": "parallel-travel/camber_gain", "value": camber, "tolerance": 0.5}]}
    t = model.tune(targets)
    o = t["objective"]
    assert t["uncertainty"] is None and o["unit"] == "deg/m"
    assert o["before"] == pytest.approx(before.figure("bump_steer"), rel=1e-12)
    after = elastokin.load(json.loads(t["tuned"])).run("parallel-travel", steps=20)
    # Measured: the same to the bit (the tuned file holds every digit of the numbers).
    assert o["after"] == pytest.approx(after.figure("bump_steer"), rel=1e-13)
    assert o["after"] > o["before"] + 30 and any("end of its tolerance" in h for h in o["held_by"])


def test_a_target_the_model_has_not_is_a_bad_file_not_a_failed_analysis():
    # Known only once the analysis runs, as the command's exit 2 says: a ValueError, as a bad file is.
    targets = json.loads(open("examples/targets/bump_steer.json").read())
    targets["targets"][0]["figure"] = "parallel-travel/bump_stear"
    with pytest.raises(ValueError, match="has no figure 'bump_stear'"):
        elastokin.load(MODEL).tune(targets)


def test_tolerance_gives_the_commands_numbers(tmp_path):
    out = tmp_path / "out"
    tolerances = "examples/targets/tolerances.json"
    command("tolerance", MODEL, tolerances, "--monte-carlo", "20", "--seed", "5", "--quiet", "--out", out)
    header, rows = read_csv(out / "tolerance.csv")
    s = elastokin.load(MODEL).tolerance(tolerances, monte_carlo=20, seed=5)
    assert list(s["figure"]) == [r[1] for r in rows]
    for k, row in enumerate(rows):
        for column in ("worst_case", "sigma", "sampled_sigma"):
            got = s[column][k]
            assert got == pytest.approx(float(row[header.index(column)]), rel=1e-11), (row[1], column)
    # The contributions and the samples as the command writes them.
    _, contributions = read_csv(out / "tolerance_contributions.csv")
    assert list(s["contributions"]["source"]) == [r[3] for r in contributions]
    _, samples = read_csv(out / "tolerance_samples.csv")
    assert len(s["samples"]["sample"]) == len(samples) == 20
    assert s["adjustments"] is None
    with pytest.raises(ValueError, match="unknown key 'hardpoint'"):
        elastokin.load(MODEL).tolerance({"hardpoint": 0.001})


def test_a_tolerance_monte_carlo_runs_as_a_study_with_the_commands_samples():
    model = elastokin.load(MODEL)
    tolerances = {"hardpoints": 0.001, "analyses": ["parallel-travel"]}
    samples = model.tolerance_samples(tolerances, 80, seed=9)
    assert len(samples) == 24 and all(len(v) == 80 for v in samples.values())
    for pointer, values in samples.items():
        nominal = model.sensitivities([pointer], steps=2)["values"][0]
        assert numpy.all(numpy.abs(values - nominal) <= 0.001 + 1e-15), pointer
    # The same samples as a study (on "ray" or "dask" alike, the rows bit for bit these): its bump steer's
    # spread is the command's Monte Carlo's (the same models; the batch reads bump steer as parallel travel
    # does, over rows 5 mm apart: measured 8e-13 apart), and the first order's within what 80 samples know
    # of a σ (1/√158, 8 %; measured 1.1 %).
    study = elastokin.study(model, samples, engine="local")
    spread = numpy.std(study.columns["bump_steer_deg_per_m"], ddof=1)
    sampled = model.tolerance(tolerances, monte_carlo=80, seed=9)
    k = list(sampled["figure"]).index("bump_steer")
    assert spread == pytest.approx(sampled["sampled_sigma"][k], rel=1e-10)
    assert spread == pytest.approx(sampled["sigma"][k], rel=4 / numpy.sqrt(158))


def test_a_batch_through_the_suite_gives_the_commands_figures(tmp_path):
    out = tmp_path / "out"
    variants = "examples/generic/macpherson_variants.txt"
    command("batch", MODEL, variants, "--analyses", "parallel-travel,static-load", "--quiet", "--out", out)
    header, rows = read_csv(out / "batch_figures.csv")
    got = elastokin.batch(MODEL, open(variants).read(), analyses=["parallel-travel", "static-load"])
    assert [g["variant"] for g in got] == [r[0] for r in rows]
    assert "parallel-travel/caster (deg)" in header and "static-load/toe (deg)" in header
    for g, row in zip(got, rows):
        for column, cell in zip(header[1:-1], row[1:-1]):
            if cell == "":
                assert g[column] is None, column
            else:
                assert g[column] == pytest.approx(float(cell), rel=1e-9), column
