"""The Python module against the program: same numbers, same checks, GIL released."""
import json
import os
import subprocess
import sys
import threading
import tomllib

import numpy as np
import pytest

import j232

SCENARIOS = os.path.join(os.path.dirname(__file__), "..", "..", "scenarios")
SKIRT = os.path.join(SCENARIOS, "highway-pivoted-raised-skirt.toml")
IMPACT = os.path.join(SCENARIOS, "impact", "highway-pivoted.toml")
J232 = os.environ.get("J232_EXE", "build/j232")


def without_provenance(r):
    return {k: v for k, v in r.items() if k not in ("provenance",)}


def test_assessment_is_deterministic_and_thread_independent():
    s = j232.Scenario(SKIRT)
    one = s.assess(replicates=12, seed=3, threads=1)
    two = s.assess(replicates=12, seed=3, threads=2)
    assert without_provenance(one).keys() == without_provenance(two).keys()
    assert json.dumps(one["criteria"]) == json.dumps(two["criteria"])
    for column, values in one["marks_table"].items():
        assert np.array_equal(values, two["marks_table"][column]), column
    assert one["nails_struck"] > 0 and one["replicates"] == 12


def test_same_numbers_as_the_program(tmp_path):
    r = j232.Scenario(SKIRT).assess(replicates=10, seed=5)
    subprocess.run([J232, "run", SKIRT, "--replicates", "10", "--seed", "5", "--out", str(tmp_path)],
                   check=False, stdout=subprocess.DEVNULL)
    run = json.load(open(tmp_path / "result.json"))
    for key in ("verdict", "pass_probability", "criteria", "nails_struck", "marks", "fates", "how_nails_leave"):
        assert r[key] == run[key], key
    marks = r["marks_table"]
    assert len(marks["x"]) == np.count_nonzero(marks["counted"]) + run["marks_below_counted_height"]
    assert np.count_nonzero(marks["counted"]) + run["marks_not_located"] == run["marks"]
    assert r["histograms"]["strikes"]["counts"].sum() == run["nails_struck"]


def test_a_dict_reads_as_the_file_does():
    with open(SKIRT, "rb") as f:
        document = tomllib.load(f)
    from_dict = j232.Scenario(document, base_dir=SCENARIOS).assess(replicates=5, seed=1, marks=False)
    from_file = j232.Scenario(SKIRT).assess(replicates=5, seed=1, marks=False)
    assert from_dict["criteria"] == from_file["criteria"]
    assert "marks_table" not in from_dict


def test_settings_as_a_sweep_sets_them():
    s = j232.Scenario(SKIRT)
    fast = s.with_settings({"blade.speed": "3000 rpm"})
    assert fast.to_dict() != s.to_dict()
    assert fast.settings == {"blade.speed": "3000 rpm"}
    tip = lambda sc: sc.assess(replicates=2, seed=1, marks=False)["tip_speed_m_s"]
    assert tip(fast) > tip(s)
    flat = j232.sweep_point(SKIRT, {"bevel_angle": "45 deg"}, replicates=4, seed=2)
    again = j232.Scenario(SKIRT, {"bevel_angle": "45 deg"}).assess(replicates=4, seed=2, marks=False)
    assert flat["criteria"] == again["criteria"]


def test_bad_input_names_the_key_and_value():
    with pytest.raises(j232.InputError, match="blade.speed"):
        j232.Scenario(SKIRT, {"blade.speed": "fast"})
    with pytest.raises(j232.InputError, match="housing.skirt_botom"):
        j232.Scenario(SKIRT, {"housing.skirt_botom": "3 in"})
    with pytest.raises(ValueError):  # InputError is a ValueError
        j232.Scenario(os.path.join(SCENARIOS, "no-such-file.toml"))
    with pytest.raises(TypeError, match="blade"):
        j232.Scenario({"blade": {"speed": object()}})
    with pytest.raises(ValueError, match="replicates"):
        j232.Scenario(SKIRT).assess(replicates=0)


def test_impact_equals_the_program():
    mine = j232.impact(IMPACT, {"restitution": 0.5})
    out = subprocess.run([J232, "impact", IMPACT, "--e", "0.5", "--json"], check=True, capture_output=True, text=True)
    theirs = json.loads(out.stdout)
    mine.pop("program", None), theirs.pop("program", None)
    assert mine == theirs


def test_the_simulation_releases_the_gil():
    s = j232.Scenario(os.path.join(SCENARIOS, "highway-pivoted.toml"))
    done = threading.Event()
    ticks = 0

    def run():
        s.assess(replicates=400, seed=1, threads=1, marks=False)
        done.set()

    t = threading.Thread(target=run)
    t.start()
    while not done.is_set():
        ticks += 1  # runs only when the worker does not hold the GIL
    t.join()
    assert ticks > 1000
