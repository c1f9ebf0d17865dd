"""Every function that takes a scenario takes it as a path, a ``Scenario`` (loaded or built from a
dict) or a plain dict, with the same numbers as the command line's ``--json`` on the equivalent
file. Relative paths inside a dict (a height map, a measured CSV) are read from the current
directory; a file's relative paths from the file's folder."""

import json

import numpy as np
import pytest

import stiction

TAS = "scenarios/tas2000.json"
HEIGHT_MAP = "scenarios/tas2000-height-map.json"
FIT = "scenarios/tas2000-fit-synthetic.json"


def _dict(path):
    with open(path) as f:
        return json.load(f)


def _height_map_dict():
    """tas2000-height-map.json as a dict, its map path made relative to the repository root (the
    current directory of these tests) instead of the file's folder."""
    d = _dict(HEIGHT_MAP)
    assert d["surface"]["height_map"]["file"] == "../data/topography-example/wall.gsf"
    d["surface"]["height_map"]["file"] = "data/topography-example/wall.gsf"
    return d


def _three_forms(path):
    """The scenario of `path` as a plain dict and as Scenario.from_dict (no base_dir: the
    current directory), for scenarios without relative paths."""
    return [_dict(path), stiction.Scenario.from_dict(_dict(path))]


def _without(d, *keys):
    """A copy of the JSON object `d` without the fields naming the scenario or the data source
    (the file's path against "<scenario>"), which are the only ones allowed to differ."""
    d = json.loads(json.dumps(d))
    for key in keys:
        node = d
        *parents, last = key.split(".")
        for p in parents:
            node = node[p]
        node.pop(last)
    return d


def test_run_of_a_plain_dict_equals_cli(in_root, cli_json):
    e = cli_json("run", TAS)
    for s in _three_forms(TAS):
        got = stiction.run(s).to_dict()
        assert got["scenario"] == "<scenario>"
        assert _without(got, "scenario") == _without(e, "scenario")
    # A height-map surface, the map read from the current directory.
    e = cli_json("run", HEIGHT_MAP)
    got = stiction.run(_height_map_dict()).to_dict()
    assert _without(got, "scenario") == _without(e, "scenario")


def test_contact_of_a_dict_scenario_equals_cli(in_root, cli_json):
    e = cli_json("contact", TAS, "--load", "3 uN")
    for s in _three_forms(TAS):
        assert stiction.contact(s, "3 uN").to_dict() == e
    e = cli_json("contact", TAS, "--sweep", "0:5e-6:5", "--mode", "flat")
    loads = [5e-6 * i / 4 for i in range(5)]
    for s in _three_forms(TAS):
        assert stiction.contact(s, loads, mode="flat").to_dict() == e
    # Overrides on a Scenario built from a dict, as --set on the file.
    s = stiction.Scenario.from_dict(_dict(TAS))
    s.set("surface.summit_sd", "50 nm")
    e = cli_json("contact", TAS, "--set", "surface.summit_sd=50 nm", "--load", "2 uN")
    assert stiction.contact(s, "2 uN").to_dict() == e
    # On a height-map surface, the map read from the current directory.
    e = cli_json("contact", HEIGHT_MAP, "--load", "3 uN")
    assert stiction.contact(_height_map_dict(), "3 uN").to_dict() == e


def test_fit_of_a_dict_scenario_equals_cli(in_root, cli_json):
    flags = ["--models", "discrete-n1,gw-dmt", "--draws", 200]
    e = cli_json("fit", "--scenario", FIT, *flags)
    assert e["data"] == "scenarios/../data/measured-voltages-synthetic/voltages.csv"
    d = _dict(FIT)
    # measured.voltages_csv of the dict, relative to the current directory (the repository root).
    d["measured"]["voltages_csv"] = "data/measured-voltages-synthetic/voltages.csv"
    for s in [d, stiction.Scenario.from_dict(d)]:
        got = stiction.fit(None, s, models="discrete-n1,gw-dmt", draws=200).to_dict()
        assert got["data"] == "data/measured-voltages-synthetic/voltages.csv"
        assert _without(got, "data") == _without(e, "data")
        assert got["models"] and got["models"][0]["shear_strength_pa"]["value"] > 0
    # The data as a path with a dict scenario.
    got = stiction.fit(d["measured"]["voltages_csv"], d, models="discrete-n1,gw-dmt", draws=200).to_dict()
    assert _without(got, "data") == _without(e, "data")


def test_bem_of_a_scenario_equals_cli_bem_scenario(in_root, cli_json):
    e = cli_json("bem", "--scenario", HEIGHT_MAP, "--pressure", "5 MPa", "--shear-strength", "1 GPa")
    assert e["surface"]["file"] == HEIGHT_MAP and e["points"][0]["contact_fraction"] > 0
    got = stiction.bem(scenario=HEIGHT_MAP, pressure="5 MPa", shear_strength="1 GPa").to_dict()
    assert got == e
    for s in [_height_map_dict(), stiction.Scenario.from_dict(_height_map_dict())]:
        got = stiction.bem(scenario=s, pressure=[5e6], shear_strength=1e9).to_dict()
        assert got["surface"]["file"] == "<scenario>"
        assert _without(got, "surface.file") == _without(e, "surface.file")
    with pytest.raises(stiction.StictionError, match="not both"):
        stiction.bem(np.zeros((8, 8)), "5 MPa", scenario=HEIGHT_MAP)
    with pytest.raises(stiction.StictionError, match="pixel_size"):
        stiction.bem(scenario=HEIGHT_MAP, pressure="5 MPa", pixel_size="1 um")
    # Neither heights nor a scenario: the generated surface, as `stiction bem` without --map/--scenario.
    assert stiction.bem(pressure="5 MPa", grid=32).surface["source"] == "generated"


def test_topography_theta_from_a_dict_scenario_equals_cli(in_root, cli_json, tmp_path):
    rng = np.random.default_rng(4)
    y, x = np.mgrid[0:48, 0:64]
    heights = sum(rng.normal() * np.sin(a * x + b * y + c) for a, b, c in rng.uniform(0.05, 0.6, (12, 3)))
    path = tmp_path / "map.npy"
    np.save(path, heights)
    e = cli_json("topography", path, "--pixel-size", "20 nm", "--height-unit", "nm", "--scenario", TAS)
    assert e["gw"]["adhesion_parameter_theta"] > 0 and e["gw"]["theta_note"] == f"material of {TAS}"
    for s in [TAS] + _three_forms(TAS):
        got = stiction.topography(heights, pixel_size="20 nm", height_unit="nm", scenario=s).to_dict()
        assert got["gw"]["adhesion_parameter_theta"] == e["gw"]["adhesion_parameter_theta"]
        assert _without(got, "file", "gw.theta_note") == _without(e, "file", "gw.theta_note")


def test_study_of_a_plain_dict_equals_cli(in_root, cli_json):
    e = cli_json("study", TAS, "--samples", 6, "--seed", 3, "--threads", 1)
    got = stiction.study(_dict(TAS), samples=6, seed=3, threads=1, as_pandas=False).to_dict()
    assert _without(got, "scenario") == _without(e, "scenario")


def test_relative_paths_in_a_dict_are_read_from_the_current_directory(in_root, cli_json, monkeypatch):
    e = cli_json("contact", HEIGHT_MAP, "--load", "3 uN")
    # The file's own text, relative to scenarios/: wrong from the repository root, named in the error...
    with pytest.raises(stiction.StictionError, match="wall.gsf"):
        stiction.contact(_dict(HEIGHT_MAP), "3 uN")
    # ...right from scenarios/, the folder it is relative to.
    monkeypatch.chdir(in_root / "scenarios")
    assert stiction.contact(_dict("tas2000-height-map.json"), "3 uN").to_dict() == e
    # A Scenario built with base_dir reads from there whatever the current directory.
    monkeypatch.chdir(in_root / "crates")
    s = stiction.Scenario.from_dict(_dict(in_root / HEIGHT_MAP), base_dir=in_root / "scenarios")
    assert stiction.contact(s, "3 uN").to_dict() == e


def test_a_bad_dict_scenario_raises_the_cli_message_in_every_function(in_root, cli, tmp_path):
    bad = _dict(TAS)
    bad["surface"]["summit_sd"] = "forty nm"
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(bad))
    code, _, err = cli("run", path, "--json")
    assert code == 2 and err.startswith("error: ")
    message = err[len("error: "):].strip().replace(str(path), "<scenario>")
    calls = [
        lambda: stiction.run(bad),
        lambda: stiction.contact(bad, "1 uN"),
        lambda: stiction.study(bad, samples=2),
        lambda: stiction.fit(None, bad),
        lambda: stiction.bem(scenario=bad, pressure="1 MPa"),
        lambda: stiction.bem(scenario=bad, rh=[0.3]),
        lambda: stiction.contact(bad, "1 uN", model="bem"),
        lambda: stiction.humidity(bad, rh=[0.3]),
        lambda: stiction.topography(np.ones((8, 8)), pixel_size="1 um", scenario=bad),
    ]
    for call in calls:
        with pytest.raises(stiction.StictionError) as e:
            call()
        assert str(e.value) == message
    with pytest.raises(TypeError, match="dict shaped as a scenario"):
        stiction.run(42)


@pytest.mark.parametrize(
    "path,value,cli_value",
    [
        ("surface.summit_sd", "50 nm", "50 nm"),  # a quantity with its unit
        ("surface.summit_sd", 5e-8, "5e-8"),  # the same in SI
        ("surface.summit_sd", np.float64(5e-8), "5e-8"),  # a NumPy float (its repr is np.float64(...))
        ("surface.seed", 7, "7"),  # an integer
        ("surface.seed", np.int64(7), "7"),  # a NumPy integer
        ("contact.mode", "flat", "flat"),  # a word of a list of choices
        ("meter.reclamp", False, "false"),  # a boolean
        ("meter.reclamp", np.bool_(False), "false"),  # a NumPy boolean
        ("meter.clamp_voltages", ["24 V", 26.0, "28 V"], '["24 V", 26.0, "28 V"]'),  # a list
        ("meter.spring_force", {"value": "6.5 uN", "sd": "1 uN"}, '{"value": "6.5 uN", "sd": "1 uN"}'),  # an object
        ("meter.slip_dynamics", None, "null"),  # removed: its default applies
        ("environment.relative_humidity", "35 %", "35 %"),  # a percentage
        ("environment.relative_humidity", 0.35, "0.35"),  # the same as a fraction
    ],
)
def test_set_takes_unit_strings_and_si_values_on_every_field_type(in_root, cli_json, path, value, cli_value):
    e = cli_json("run", TAS, "--set", f"{path}={cli_value}")
    assert e != cli_json("run", TAS), "the override changes nothing: not a test"
    for s in [stiction.Scenario.load(TAS), stiction.Scenario.from_dict(_dict(TAS))]:
        s.set(path, value)
        got = stiction.run(s).to_dict()
        assert _without(got, "scenario") == _without(e, "scenario")
    # get reads the field back as run, in SI.
    s = stiction.Scenario.load(TAS)
    s.set(path, value)
    if value is not None:
        assert s.get(path) == stiction.Scenario.load(TAS, [f"{path}={cli_value}"]).get(path)


def test_get_reads_fields_in_si_and_names_a_missing_one(in_root):
    s = stiction.Scenario.load(TAS)
    # As written (with its unit), an SI number as a number, a default the parse filled in (SI).
    assert s.get("surface.summit_sd") == "0.04 um"
    s.set("surface.summit_sd", 5e-8)
    assert s.get("surface.summit_sd") == 5e-8
    assert s.get("actuators.clamp.relative_permittivity") == 1.0
    assert s.get("actuators.clamp.plate_count") == 30
    assert s.get("material") == s.to_dict()["material"]
    with pytest.raises(stiction.StictionError, match="summit_sdd"):
        s.get("surface.summit_sdd")


def test_validate_checks_what_the_cli_scenario_command_checks(in_root, cli, tmp_path):
    # A height-map sidewall whose map cannot be read: the parse alone accepts it; `stiction scenario`
    # reads and prepares the map as `run` will, and so does validate().
    d = _height_map_dict()
    d["surface"]["height_map"]["file"] = str(tmp_path / "no-such-map.gsf")
    path = tmp_path / "bad-map.json"
    path.write_text(json.dumps(d))
    code, _, err = cli("scenario", path)
    assert code == 2 and "no-such-map.gsf" in err
    s = stiction.Scenario.from_dict(d)
    with pytest.raises(stiction.StictionError) as e:
        s.validate()
    assert str(e.value) == err[len("error: "):].strip().replace(str(path), "<scenario>")
    # A good one validates, as the CLI's.
    assert cli("scenario", HEIGHT_MAP)[0] == 0
    assert stiction.Scenario.from_dict(_height_map_dict()).validate() == []
