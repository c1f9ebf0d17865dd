"""The Python package against the command line: the same engine, so the same numbers bit for bit
(json.loads of `stiction ... --json` is compared with ==, floats included)."""

import json

import numpy as np
import pytest

import stiction

TAS = "scenarios/tas2000.json"


# ---------------------------------------------------------------------------------------------
# run


def test_run_equals_cli_json_bit_for_bit(in_root, cli_json):
    r = stiction.run(TAS)
    expected = cli_json("run", TAS)
    assert r.to_dict() == expected
    assert json.loads(r.to_json()) == expected
    # Attributes named as the JSON keys (the contract scripts rely on).
    assert r.mu_apparent == expected["mu_apparent"]
    assert r.apparent_adhesion_force_n == expected["apparent_adhesion_force_n"]
    assert r.points == expected["points"]
    # Per-point columns as NumPy arrays with the same numbers.
    loads = np.array([p["load_n"] for p in expected["points"]])
    assert r.columns["load_n"].dtype == np.float64
    assert np.array_equal(r.columns["load_n"], loads)
    v_pull = np.array([np.nan if p.get("v_pull_v") is None else p["v_pull_v"] for p in expected["points"]])
    assert np.array_equal(r.columns["v_pull_v"], v_pull, equal_nan=True)
    assert r.columns["in_contact"].dtype == bool


def test_run_with_overrides_equals_cli_set(in_root, cli_json):
    s = stiction.Scenario.load(TAS)
    s.set("surface.summit_sd", "50 nm")
    s.set("material.shear_strength", 1.2e9)
    assert s.sets == ["surface.summit_sd=50 nm", "material.shear_strength=1200000000.0"]
    expected = cli_json("run", TAS, "--set", "surface.summit_sd=50 nm", "--set", "material.shear_strength=1.2 GPa")
    assert stiction.run(s).to_dict() == expected
    # The override changes the result (the comparison above is not vacuous).
    assert expected["mu_apparent"] != cli_json("run", TAS)["mu_apparent"]


def test_run_progress_callback_is_called_with_the_gil_released(in_root):
    calls = []
    r = stiction.run(TAS, progress=lambda done, total: calls.append((done, total)))
    assert calls, "no progress reported"
    assert calls[-1][0] == calls[-1][1] == len(r.points)


def test_scenario_from_dict_and_json_round_trip(in_root, cli_json):
    expected = cli_json("run", TAS)
    with open(TAS) as f:
        d = json.load(f)
    from_dict = stiction.run(stiction.Scenario.from_dict(d, base_dir="scenarios")).to_dict()
    assert from_dict["scenario"] == "<scenario>"
    from_dict["scenario"] = expected["scenario"]
    assert from_dict == expected
    # to_json is the scenario as run, in SI: read back, it runs to the same numbers.
    s = stiction.Scenario.load(TAS)
    assert s.validate() == [] or all(isinstance(c, str) for c, _ in s.validate())
    again = stiction.Scenario.from_json(s.to_json(), base_dir="scenarios")
    back = stiction.run(again).to_dict()
    back["scenario"] = expected["scenario"]
    assert back == expected
    assert s.to_dict() == json.loads(s.to_json())


def test_scenario_to_json_equals_cli_scenario(in_root, cli):
    code, out, err = cli("scenario", TAS)
    assert code == 0, err
    assert stiction.Scenario.load(TAS).to_dict() == json.loads(out)


# ---------------------------------------------------------------------------------------------
# topography


def _rough_map(ny=48, nx=64, seed=7):
    """A smooth random field (sum of sines with random phases), heights of order 1e-5 (in mm)."""
    rng = np.random.default_rng(seed)
    y, x = np.mgrid[0:ny, 0:nx]
    z = np.zeros((ny, nx))
    for _ in range(12):
        kx, ky = rng.uniform(0.05, 0.6, 2)
        z += rng.normal() * np.sin(kx * x + ky * y + rng.uniform(0, 6.3))
    return 1e-5 * z


@pytest.mark.parametrize(
    "dtype,order", [(np.float64, "C"), (np.float64, "F"), (np.float32, "C"), (np.float32, "F")]
)
def test_topography_of_an_array_equals_cli_on_the_npy_file(tmp_path, cli_json, dtype, order):
    heights = np.asarray(_rough_map(), dtype=dtype, order=order)
    path = tmp_path / "map.npy"
    np.save(path, heights)  # keeps the dtype and the order (fortran_order True for "F")
    expected = cli_json("topography", path, "--pixel-size", "3.90625 um", "--height-unit", "mm")
    r = stiction.topography(heights, pixel_size="3.90625 um", height_unit="mm")
    got = r.to_dict()
    assert got["file"] == "<array>"
    got["file"] = expected["file"]
    assert got == expected
    assert r.summit_count == expected["summit_count"] > 0
    s = r.summits
    assert len(s["height_m"]) == expected["summit_count"]
    assert s["x_m"].dtype == np.float64 and s["ix"].dtype == np.uint32
    # SI floats give the same result as unit strings.
    si = stiction.topography(heights, pixel_size=3.90625e-6, height_unit=1e-3).to_dict()
    si["file"] = expected["file"]
    assert si == expected


def test_topography_levelling_and_cutoffs_follow_the_cli_flags(tmp_path, cli_json):
    heights = _rough_map(seed=3)
    path = tmp_path / "map.npy"
    np.save(path, heights)
    expected = cli_json(
        "topography", path, "--pixel-size", "10 nm", "--height-unit", "um", "--level", "poly2", "--cutoff", "40 nm"
    )
    got = stiction.topography(heights, pixel_size="10 nm", height_unit="um", level="poly2", cutoff="40 nm").to_dict()
    got["file"] = expected["file"]
    assert got == expected


# ---------------------------------------------------------------------------------------------
# study and gw


def test_study_equals_cli_whatever_the_threads(in_root, cli_json):
    expected = cli_json("study", TAS, "--samples", 12, "--seed", 5, "--threads", 1)
    one = stiction.study(TAS, samples=12, seed=5, threads=1).to_dict()
    two = stiction.study(stiction.Scenario.load(TAS), samples=12, seed=5, threads=2).to_dict()
    assert one == expected
    assert two == expected
    assert stiction.study(TAS, samples=12, seed=6, threads=1).to_dict() != expected


def test_gw_at_a_load_vector_equals_cli(cli_json):
    loads = np.array([-0.5, 0.0, 0.5, 3.0])
    g = stiction.gw(2.0, loads)
    for i, l in enumerate(loads):
        e = cli_json("gw", "--theta", "2", "--load-star", repr(float(l)))
        # Every key of the CLI's JSON, bit for bit (it prints full precision).
        for key in e:
            if key in ("theta", "pull_off_l_star", "pull_off_h"):
                assert g[key] == e[key], key
            else:
                assert g[key][i] == e[key], key
        assert set(g) == set(e)
    plain = stiction.gw(None, 1.0)
    e = cli_json("gw", "--theta", "inf", "--load-star", "1")
    assert plain["h"][0] == e["h"] and plain["pull_off_l_star"] is None


# ---------------------------------------------------------------------------------------------
# errors


def _cli_message(stderr: str) -> str:
    assert stderr.startswith("error: "), stderr
    return stderr[len("error: "):].strip()


def test_errors_are_stiction_errors_with_the_cli_message(in_root, cli):
    assert issubclass(stiction.StictionError, ValueError)
    code, _, err = cli("run", "scenarios/no-such-file.json", "--json")
    assert code == 2
    with pytest.raises(stiction.StictionError) as e:
        stiction.run("scenarios/no-such-file.json")
    assert str(e.value) == _cli_message(err)

    code, _, err = cli("run", TAS, "--set", "surface.summit_sdd=40 nm", "--json")
    assert code == 2
    s = stiction.Scenario.load(TAS)
    with pytest.raises(stiction.StictionError) as e:
        s.set("surface.summit_sdd", "40 nm")
    assert str(e.value) == _cli_message(err)
    assert s.sets == [], "a refused override must leave the scenario unchanged"

    with pytest.raises(stiction.StictionError) as e:
        stiction.Scenario.from_dict({"format_version": 1, "surface": {"summit_sd": "forty"}})
    assert "surface" in str(e.value)


def test_topography_errors(tmp_path, cli):
    heights = _rough_map()
    path = tmp_path / "map.npy"
    np.save(path, heights)
    # No pixel size: the CLI's message, with the array named instead of the file.
    code, _, err = cli("topography", path, "--json")
    assert code == 2
    with pytest.raises(stiction.StictionError) as e:
        stiction.topography(heights)
    assert str(e.value) == _cli_message(err).replace(str(path), "heights")
    with pytest.raises(stiction.StictionError, match="pixel_size"):
        stiction.topography(heights, pixel_size="-1 um")
    with pytest.raises(stiction.StictionError, match="level"):
        stiction.topography(heights, pixel_size="1 um", level="cubic")
    with pytest.raises(stiction.StictionError, match="2-D"):
        stiction.topography(np.zeros(10), pixel_size="1 um")
    with pytest.raises(stiction.StictionError, match="2-D"):
        stiction.topography(np.zeros((4, 4), dtype=np.int64), pixel_size="1 um")
    with pytest.raises(stiction.StictionError, match="finite normalized load"):
        stiction.gw(2.0, [np.nan])
    with pytest.raises(stiction.StictionError, match="samples"):
        stiction.study(TAS, samples=0)


def test_point_columns_mark_a_missing_value_as_nan():
    cols = stiction._columns([{"a": 1.5, "b": True}, {"a": None, "b": False}, {"b": True}])
    assert np.array_equal(cols["a"], [1.5, np.nan, np.nan], equal_nan=True)
    assert cols["b"].dtype == bool and list(cols["b"]) == [True, False, True]


def test_study_releases_the_gil(in_root):
    """While a study runs in one thread, Python code runs in another: with the GIL held through
    the call, the main thread would not record one tick inside it."""
    import threading
    import time

    span = {}

    def work():
        span["start"] = time.perf_counter()
        stiction.study(TAS, samples=400, seed=2, threads=1)
        span["end"] = time.perf_counter()

    t = threading.Thread(target=work)
    ticks = []
    t.start()
    while t.is_alive():
        ticks.append(time.perf_counter())
        time.sleep(0.001)
    t.join()
    assert span["end"] - span["start"] > 0.05, "the study is too short to tell"
    inside = [x for x in ticks if span["start"] + 0.02 < x < span["end"] - 0.02]
    assert len(inside) >= 5, f"{len(inside)} ticks of the main thread during the study"


def test_discrete_at_a_load_vector_equals_cli(cli_json):
    material = ["--radius", "0.5 um", "--work-of-adhesion", "0.1 J/m^2", "--compliance", "9.1e-12 1/Pa",
                "--shear-strength", "1.4 GPa"]
    loads = np.array([-1e-7, 0.0, 3e-6, 1e-5])
    d = stiction.discrete(3, "0.5 um", "0.1 J/m^2", 9.1e-12, "1.4 GPa", loads, target_slope=0.7)
    for i, l in enumerate(loads):
        e = cli_json("discrete", "--contacts", 3, *material, "--load", repr(float(l)), "--target-slope", "0.7")
        assert d["points"][i] == e
        assert d["friction_n"][i] == e["friction_n"]
    jkr = stiction.discrete(1, 5e-7, 0.1, 9.1e-12, 1.4e9, "2 uN", adhesion="jkr")
    assert jkr["points"][0] == cli_json("discrete", "--contacts", 1, *material, "--load", "2 uN", "--adhesion", "jkr")
    with pytest.raises(stiction.StictionError, match="radius"):
        stiction.discrete(3, "-1 um", 0.1, 9.1e-12, 1.4e9, 0.0)
    with pytest.raises(stiction.StictionError, match="adhesion"):
        stiction.discrete(3, "1 um", 0.1, 9.1e-12, 1.4e9, 0.0, adhesion="sticky")


def test_result_fields_equal_cli_when_read_and_leave_the_garbage_collector_as_found(in_root, cli_json):
    """A result's fields are made into Python objects when read, with the cyclic collector paused
    meanwhile: it must come back on (or stay off) as the caller had it."""
    import gc

    e = cli_json("contact", TAS, "--sweep", "0:5e-6:5")
    loads = [5e-6 * i / 4 for i in range(5)]
    assert gc.isenabled()
    r = stiction.contact(TAS, loads)
    assert r.points == e["points"] and r["events"] == e["events"]
    assert sorted(r.keys()) == sorted(e) and json.loads(r.to_json()) == e
    assert gc.isenabled(), "the collector was left off"
    gc.disable()
    try:
        assert stiction.contact(TAS, loads).to_dict() == e
        assert not gc.isenabled(), "the collector was turned on behind the caller's back"
    finally:
        gc.enable()
    with pytest.raises(AttributeError, match="no field"):
        r.no_such_field
