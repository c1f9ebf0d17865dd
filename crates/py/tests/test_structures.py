"""The test structures built from parts (scenarios with a `structure`: comb-drive sidewall tester,
plate on the substrate with a released spring, pad under uniform pressure) through Python against
the command line: `run`, `study` and `fit` give the same JSON names and numbers, bit for bit."""

import json

import numpy as np
import pytest

import stiction

STRUCTURES = ["scenarios/comb-sidewall.json", "scenarios/plate-released-spring.json", "scenarios/pad-uniform-pressure.json"]
PLATE = "scenarios/plate-released-spring.json"
COMB = "scenarios/comb-sidewall.json"


@pytest.mark.parametrize("scenario", STRUCTURES)
def test_run_of_a_structure_equals_cli(in_root, cli_json, scenario):
    r = stiction.run(scenario)
    expected = cli_json("run", scenario)
    assert r.to_dict() == expected
    # The structure's own keys are there by their JSON names.
    assert r.structure == expected["structure"] and r.structure["protocol"] in ("ramp", "release", "lower_normal")
    assert r.lab_coefficient == expected["lab_coefficient"]
    loads = np.array([p["load_n"] for p in expected["points"]])
    assert np.array_equal(r.columns["load_n"], loads)


def test_run_of_the_release_protocol_has_the_displacements(in_root, cli_json):
    r = stiction.run(PLATE)
    expected = cli_json("run", PLATE)
    x = [p.get("displacement_m") for p in expected["points"]]
    assert any(v is not None for v in x)
    assert np.array_equal(r.columns["displacement_m"], np.array([np.nan if v is None else v for v in x]), equal_nan=True)


def test_study_of_a_release_structure_equals_cli_with_its_lab_interval(in_root, cli_json):
    sets = ['surface.summit_radius={"value":"0.5 um","sd":"0.3 um","distribution":"lognormal"}',
            "structure.tangential.resonance.mass={\"value\": \"12 ng\", \"sd\": \"0.48 ng\"}"]
    args = ["study", PLATE, "--samples", 6, "--seed", 3, "--threads", 1]
    for s in sets:
        args += ["--set", s]
    expected = cli_json(*args)
    sc = stiction.Scenario.load(PLATE)
    sc.set("surface.summit_radius", {"value": "0.5 um", "sd": "0.3 um", "distribution": "lognormal"})
    sc.set("structure.tangential.resonance.mass", {"value": "12 ng", "sd": "0.48 ng"})
    got = stiction.study(sc, samples=6, seed=3, threads=1, as_pandas=False)
    assert got.to_dict() == expected
    # The release protocol has the lab's interval (regression and with the spring's uncertainty).
    li = expected["lab_intervals"]
    assert li["mu_ci95_width"] is not None and li["mu_ci95_width_with_calibration"] is not None, li


def _thresholds():
    """Release thresholds of a Coulomb contact (mu 0.35, F_adh 3 uN) through the plate's parts."""
    eps0 = 8.8541878128e-12
    a = eps0 * 2500e-12 / (2.0 * (100e-9 / 7.5) ** 2)
    k = 12e-12 * (2.0 * np.pi * 2e5) ** 2
    v = np.linspace(0.5, 1.5, 11)
    load = a * v * v - 5.0 * 2e-6
    x = np.floor(0.35 * (load + 3e-6) / (k * 5e-9)) * 5e-9
    return v, x


def test_fit_of_structure_thresholds_equals_cli(in_root, cli_json, tmp_path):
    v, x = _thresholds()
    path = tmp_path / "release.csv"
    path.write_text("v_normal_v,displacement_m\n" + "".join(f"{float(a)!r},{float(b)!r}\n" for a, b in zip(v, x)))
    expected = cli_json("fit", path, "--scenario", PLATE, "--draws", 50)
    from_file = stiction.fit(str(path), PLATE, draws=50)
    from_arrays = stiction.fit({"v_normal_v": v, "displacement_m": x}, PLATE, draws=50)
    assert from_file.to_dict() == expected
    got = from_arrays.to_dict()
    assert got["data"] == "<data>"
    got["data"] = expected["data"]
    assert got == expected
    assert abs(expected["mu_apparent"]["value"] - 0.35) < 2e-3
    assert expected["normal_column"] == "v_normal_v" and expected["tangential_column"] == "displacement_m"


def test_fit_of_a_structure_refuses_model_arguments_and_bad_columns(in_root):
    v, x = _thresholds()
    with pytest.raises(stiction.StictionError, match="`models`"):
        stiction.fit({"v_normal_v": v, "displacement_m": x}, PLATE, models="gw-dmt")
    with pytest.raises(stiction.StictionError, match="displacement_m.*lateral_comb"):
        stiction.fit({"v_normal_v": v, "displacement_m": x}, COMB)
    with pytest.raises(stiction.StictionError, match="line 3"):
        stiction.fit({"v_normal_v": [1.0, float("nan")], "displacement_m": [1e-7, 2e-7]}, PLATE)
