"""The Python API against the `elastokin` command's own output files: the same model, the same numbers.

The command is run once per session (`cargo run`, so the build the repository holds) and its CSV tables,
summary.json and batch.csv are the independent record every result here is compared with.
"""

import json
import math
import os
import threading

import numpy
import pytest
from conftest import MODEL, VARIANTS, command, command_error, read_csv, same_batch, same_column

import elastokin


def test_analyses_are_the_command_line_names():
    names = elastokin.analyses()
    assert names[0] == "parallel-travel" and "loads" in names and names[-1] == "wheel-envelope" and len(names) == 11
    assert elastokin.parameter("parallel-travel") == "wheel travel, m, bump +"


def test_load_from_a_path_and_from_a_dict_give_the_same_model(model):
    as_dict = json.loads(MODEL.read_text())
    from_dict = elastokin.load(as_dict)
    assert from_dict.name == model.name == as_dict["name"]
    assert from_dict.to_dict() == model.to_dict()
    assert elastokin.load(os.fspath(MODEL)).name == model.name
    assert model.analyses() == elastokin.analyses()


def test_every_analysis_gives_the_command_s_rows_and_figures(model, out, summary):
    ran = summary["analyses"]
    assert len(ran) >= 8
    for name, entry in ran.items():
        result = model.run(name, compliance=True)
        header, rows = read_csv(out / f"{name.replace('-', '_')}.csv")
        assert list(result.columns) == header
        for k, column in enumerate(header):
            assert isinstance(result.columns[column], (numpy.ndarray, list))
            same_column(result.columns[column], [row[k] for row in rows])
        # The report is summary.json's entry, number for number (JSON keeps every digit).
        assert result.summary == entry
        compliance_csv = out / f"{name.replace('-', '_')}_compliance.csv"
        if compliance_csv.exists():
            header, rows = read_csv(compliance_csv)
            assert list(result.compliance) == header
            for k, column in enumerate(header):
                same_column(result.compliance[column], [row[k] for row in rows])
    travel = model.run("parallel-travel")
    assert travel.figure("bump_steer") == ran["parallel-travel"]["figures"]["bump_steer"]["value"]
    # The same figure in SI: deg/m is π/180 rad/m, the wheel rate's N/mm a thousand N/m.
    assert travel.figure("bump_steer", si=True) == pytest.approx(travel.figure("bump_steer") * math.pi / 180, rel=1e-15)
    assert travel.figure("wheel_rate", si=True) == pytest.approx(travel.figure("wheel_rate") * 1e3, rel=1e-15)
    assert travel.summary["figures"]["wheel_rate"]["si_unit"] == "N/m"
    assert travel.compliance is None


def test_range_and_steps_reach_the_analysis(model, tmp_path):
    result = model.run("parallel-travel", range=(-0.02, 0.03), steps=10)
    d = tmp_path / "out"
    command("run", MODEL, "--quiet", "--analysis", "parallel-travel", "--range=-0.02,0.03", "--steps", 10, "--out", d)
    header, rows = read_csv(d / "parallel_travel.csv")
    assert len(rows) == 11
    for k, column in enumerate(header):
        same_column(result.columns[column], [row[k] for row in rows])
    assert result.summary == json.loads((d / "summary.json").read_text())["analyses"]["parallel-travel"]


def test_the_options_of_a_road_load_reach_it_as_the_command_s_do(model, tmp_path):
    # The wheel free on its spring, the load at the wheel centre: both change the rows, against the defaults.
    d = tmp_path / "out"
    command("run", MODEL, "--quiet", "--analysis", "lateral-force", "--steps", 4, "--wheel", "free",
            "--load-point", "wheel-centre", "--out", d)
    header, rows = read_csv(d / "lateral_force.csv")
    for spelling in ["wheel_centre", "wheel-centre"]:
        result = model.run("lateral-force", steps=4, wheel="free", load_point=spelling)
        for k, column in enumerate(header):
            same_column(result.columns[column], [row[k] for row in rows])
    default = model.run("lateral-force", steps=4)
    assert not numpy.array_equal(default.columns["toe_deg"], result.columns["toe_deg"])
    with pytest.raises(ValueError, match="load_point 'hub': give 'contact_patch' or 'wheel_centre'"):
        model.run("lateral-force", load_point="hub")


def test_suite_is_the_summary_json_but_its_provenance(model, summary):
    got = model.suite(compliance=True)
    expected = {k: v for k, v in summary.items() if k != "provenance"}
    # The command ran with --compliance too: the settings say so on both sides.
    assert got == expected
    one = model.suite(["roll"])
    assert list(one["analyses"]) == ["roll"]
    with pytest.raises(ValueError):
        model.suite(range=(0.0, 0.01))


def test_compliance_is_the_report_s_matrix(model, summary, out):
    c = model.compliance()
    assert isinstance(c, numpy.ndarray) and c.shape == (6, 6)
    assert c.tolist() == summary["analyses"]["parallel-travel"]["wheel_compliance_at_design"]
    assert len(elastokin.COMPLIANCE_ROWS) == len(elastokin.COMPLIANCE_COLUMNS) == 6
    # The names are those of the command's compliance table: entry (row, column) is `{row}_per_{column}`.
    header, _ = read_csv(out / "parallel_travel_compliance.csv")
    assert header[1:] == [f"{r}_per_{c}" for r in elastokin.COMPLIANCE_ROWS for c in elastokin.COMPLIANCE_COLUMNS]


def test_to_pandas_has_the_columns(model):
    pandas = pytest.importorskip("pandas")
    result = model.run("roll", steps=4)
    frame = result.to_pandas()
    assert isinstance(frame, pandas.DataFrame)
    assert list(frame.columns) == list(result.columns)
    assert frame[frame.columns[1]].tolist() == result.columns[frame.columns[1]].tolist()


def test_to_pandas_without_pandas_says_what_to_install(model, monkeypatch):
    import builtins

    real_import = builtins.__import__

    def no_pandas(name, *args, **kwargs):
        if name == "pandas":
            raise ImportError("No module named 'pandas'")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_pandas)
    with pytest.raises(ImportError, match="pip install pandas"):
        model.run("roll", steps=2).to_pandas()


def test_batch_of_a_variants_file_is_the_command_s_table(model, batch_csv):
    same_batch(elastokin.batch(model, VARIANTS.read_text()), batch_csv)
    same_batch(elastokin.batch(MODEL, VARIANTS.read_text()), batch_csv)


def test_batch_of_lines_and_dicts(model, batch_csv):
    lines = [line for line in VARIANTS.read_text().splitlines() if line.strip() and not line.startswith("#")]
    same_batch(model.batch(lines), batch_csv)
    # The same edits as dicts: each line's pointer=value edits, its name under "name".
    dicts = []
    for line in lines:
        name, body = line.split(":", 1)
        edits = dict(e.strip().split("=", 1) for e in body.split(";"))
        dicts.append({"name": name.strip(), **{p.strip(): json.loads(v) for p, v in edits.items()}})
    same_batch(model.batch(dicts), batch_csv)
    unnamed = model.batch([{"/suspension/macpherson/spring/rate": 30000.0}])
    assert unnamed[0]["variant"] == "variant 1"
    assert unnamed[0]["wheel_rate_n_per_m"] == same_rate(model)


def same_rate(model):
    return model.batch(["/suspension/macpherson/spring/rate=30000.0"])[0]["wheel_rate_n_per_m"]


def test_a_missing_file_is_a_model_error_with_the_command_s_message(tmp_path):
    missing = tmp_path / "no_such_model.json"
    with pytest.raises(elastokin.ModelError) as raised:
        elastokin.load(missing)
    assert str(raised.value) == command_error("run", missing, "--out", tmp_path / "x")


def test_a_bad_key_is_a_model_error_with_the_command_s_message(tmp_path):
    doc = json.loads(MODEL.read_text())
    doc["suspension"]["macpherson"]["spring"]["rat"] = doc["suspension"]["macpherson"]["spring"].pop("rate")
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(doc, indent=2))
    with pytest.raises(elastokin.ModelError) as raised:
        elastokin.load(bad)
    message = command_error("run", bad, "--out", tmp_path / "x")
    assert str(raised.value) == message
    assert "rat" in message
    # A dict has no lines and columns the user wrote: its mistake is named by the keys that lead to it, in the
    # command's words for the same mistake.
    with pytest.raises(elastokin.ModelError) as raised:
        elastokin.load(doc, origin="my corner")
    said = message.split(": ", 1)[1]  # the command's message without its file:line:column
    assert str(raised.value) == f"my corner: {said} (at suspension.macpherson.spring.rat)"


def test_an_unknown_analysis_is_a_value_error_naming_it_and_the_names(model):
    # In Python's words: the command's flag (`--analysis <NAME>`) is not what a Python caller wrote.
    with pytest.raises(ValueError) as raised:
        model.run("bump-steer")
    assert str(raised.value) == "no analysis 'bump-steer': give one of " + ", ".join(elastokin.analyses())
    assert "--" not in str(raised.value)


def test_a_name_a_short_range_and_model_text_are_taken_as_a_python_caller_means_them(model):
    # suite("roll") ran the analyses 'r', 'o', 'l', 'l'; range=(0.05,) raised IndexError; load(text) took
    # the JSON text for a path.
    assert list(model.suite("roll")["analyses"]) == list(model.suite(["roll"])["analyses"]) == ["roll"]
    for bad in [(0.05,), (0.0, 0.05, 1.0), "0,0.05", (0.0, "far")]:
        with pytest.raises(ValueError, match=r"range: give \(from, to\), two numbers"):
            model.run("parallel-travel", range=bad)
    text = MODEL.read_text()
    assert elastokin.load(text).to_dict() == model.to_dict()
    with pytest.raises(elastokin.ModelError, match="<text>"):
        elastokin.load('{"name": "no suspension"}')


def test_a_failed_analysis_is_an_analysis_error_with_the_command_s_message(model, tmp_path):
    with pytest.raises(elastokin.AnalysisError) as raised:
        model.run("parallel-travel", range=(0.0, 1e-12))
    message = command_error(
        "run", MODEL, "--analysis", "parallel-travel", "--range", "0,1e-12", "--out", tmp_path / "x"
    )
    assert message.splitlines()[0] == str(raised.value)
    assert isinstance(raised.value, elastokin.Error)


def test_a_variant_editing_a_missing_key_is_the_command_s_error(model, tmp_path):
    variants = tmp_path / "variants.txt"
    variants.write_text("x: /suspension/macpherson/nope=1\n")
    with pytest.raises(elastokin.ModelError) as raised:
        model.batch(variants.read_text())
    # The command names the file and line too; the text given to Python is no file.
    said = command_error("batch", MODEL, variants, "--out", tmp_path / "x")
    assert said == f"{variants}:1: {raised.value}"
    with pytest.raises(elastokin.ModelError, match="is not pointer=value"):
        model.batch(["/suspension/macpherson/spring/rate"])


def test_threads_give_the_sequential_results(model):
    names = ["parallel-travel", "roll", "lateral-force", "braking-force"]
    sequential = {name: model.run(name).columns for name in names}
    threaded = {}

    def work(name):
        threaded[name] = model.run(name).columns

    threads = [threading.Thread(target=work, args=(name,)) for name in names]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for name in names:
        for column, values in sequential[name].items():
            numpy.testing.assert_array_equal(threaded[name][column], values)


def test_parallel_travel_has_the_swing_arms_and_the_axle_s_roll_centre(model):
    # The instant centres and swing arms of the corner and the whole axle's roll centre, a column each; at
    # zero travel the swing arms are the figures read at design and the roll centre the roll analysis's
    # (the equilibria's tolerance apart).
    result = model.run("parallel-travel", steps=8)
    for name in [
        "front_view_instant_centre_y_m",
        "front_view_instant_centre_z_m",
        "front_view_swing_arm_length_m",
        "side_view_instant_centre_x_m",
        "side_view_instant_centre_z_m",
        "side_view_swing_arm_length_m",
        "roll_centre_lateral_m",
        "roll_centre_height_m",
    ]:
        assert numpy.all(numpy.isfinite(result.columns[name])), name
    design = list(result.columns["travel_m"]).index(0.0)
    for column, key in [
        ("front_view_swing_arm_length_m", "front_view_swing_arm_length"),
        ("side_view_swing_arm_length_m", "side_view_swing_arm_length"),
    ]:
        # Measured through the command's CSV (12 digits): 9.2e-12 of the length at most.
        assert result.columns[column][design] == pytest.approx(result.figure(key, si=True), rel=1e-10)
    roll = model.run("roll", steps=8)
    height = result.columns["roll_centre_height_m"][design]
    # Measured through the command's CSV: 4.5e-13 m.
    assert height == pytest.approx(roll.figure("roll_centre_height", si=True), abs=4e-11)


def test_the_half_shaft_columns_follow_the_wheel():
    # The shipped MacPherson names its drive shaft: its plunge and joint angles are columns of parallel
    # travel and, per wheel, of steering; the plunge is the change of the joints' distance, read here
    # from the wheel centre and spin axis of each row (toe and camber) and the file's joint centres.
    import math
    import pathlib

    shipped = pathlib.Path(__file__).resolve().parents[2] / "examples" / "macpherson.json"
    model = elastokin.load(str(shipped))
    result = model.run("parallel-travel", steps=8)
    shaft = {"inner": (0.0, 0.22, 0.0), "outer": (0.0, 0.68, 0.0)}
    length = math.dist(shaft["inner"], shaft["outer"])
    inboard = 0.77 - 0.68
    for k in range(len(result.columns["travel_m"])):
        toe, camber = math.radians(result.columns["toe_deg"][k]), math.radians(result.columns["camber_deg"][k])
        axis = (math.sin(toe) * math.cos(camber), math.cos(toe) * math.cos(camber), -math.sin(camber))
        centre = [result.columns[f"wheel_centre_{c}_m"][k] for c in "xyz"]
        outer = [centre[i] - inboard * axis[i] for i in range(3)]
        # Measured 1.1e-16 m.
        assert result.columns["half_shaft_plunge_m"][k] == pytest.approx(
            math.dist(shaft["inner"], outer) - length, abs=1e-14
        )
    steering = model.run("steering", steps=8)
    for side in ["left", "right"]:
        assert numpy.all(numpy.isfinite(steering.columns[f"{side}_half_shaft_outer_angle_deg"])), side


def test_the_wheel_envelope_names_the_least_clearance_and_a_tyre_reaching_into_the_body():
    # The shipped MacPherson's packaging: per wheel height, each obstacle's least clearance over the rack's
    # travel; the least of all is the figure, in SI. With the wheel-arch liner lowered to 40 mm above the
    # tyre's top, full bump reaches into it: a negative figure and a warning naming it.
    import json
    import pathlib

    shipped = pathlib.Path(__file__).resolve().parents[2] / "examples" / "macpherson.json"
    document = json.loads(shipped.read_text())
    result = elastokin.load(document).run("wheel-envelope", steps=32)
    names = ["brake_line_clip", "wheel_arch_liner", "frame_rail"]
    for k in range(len(result.columns["travel_m"])):
        least = min(result.columns[f"clearance_{n}_m"][k] for n in names)
        assert result.columns["least_clearance_m"][k] == least
    assert result.figure("least_wheel_clearance", si=True) == min(result.columns["least_clearance_m"])
    assert result.figure("least_wheel_clearance", si=True) > 0.02
    document["packaging"]["boxes"][0]["min"][2] = 0.356
    lowered = elastokin.load(document).run("wheel-envelope", steps=32)
    assert lowered.figure("least_wheel_clearance", si=True) < -0.02
    codes = [w["code"] for w in lowered.summary["warnings"]]
    assert "wheel-interference" in codes
