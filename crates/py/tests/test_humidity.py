"""stiction.humidity (the friction meter against relative humidity), bem's generated surface and
rh, and contact(model="bem"): each against the `stiction` binary's --json on the same input (the
same numbers, bit for bit), bad input as StictionError naming the field, and the physics of the
humidity sweep (the dry point is the dry run; the Kelvin radius)."""

import json
import math

import numpy as np
import pytest

import stiction
from conftest import python_names

TAS = "scenarios/tas2000.json"
# The arguments of `contact` that the binding hands over as command-line flags.
CONTACT_ARGS = ["load", "mode", "contacts", "summits", "model", "max_sweep_steps"]
HUMID = "scenarios/tas2000-humid.json"
HEIGHT_MAP = "scenarios/tas2000-height-map.json"


def test_humidity_equals_cli_plot_humidity_json(in_root, cli_json):
    e = cli_json("plot", "humidity", "--scenario", HUMID, "--rh", "0.2,0.5")
    assert stiction.humidity(HUMID, rh=[0.2, 0.5]).to_dict() == e
    assert stiction.humidity(HUMID, rh=np.array([0.2, 0.5])).to_dict() == e
    assert stiction.humidity(HUMID, rh="0.2,0.5").to_dict() == e
    # A scenario in memory with an override: the CLI's --set, named "<scenario>".
    s = stiction.Scenario.load(TAS, ["surface.summit_sd=50 nm"])
    e = cli_json("plot", "humidity", "--scenario", TAS, "--set", "surface.summit_sd=50 nm", "--rh", "0:0.6:3")
    got = stiction.humidity(s, rh="0:0.6:3").to_dict()
    assert got == e
    with open(TAS) as f:
        d = json.load(f)
    e = cli_json("plot", "humidity", "--scenario", TAS, "--rh", "0.4")
    got = stiction.humidity(d, rh=0.4).to_dict()
    assert got.pop("scenario") == "<scenario>" and e.pop("scenario") == TAS
    assert got == e


def test_humidity_default_grid_columns_and_progress(in_root, cli_json):
    calls = []
    r = stiction.humidity(TAS, progress=lambda done, total: calls.append((done, total)))
    assert r.to_dict() == cli_json("plot", "humidity", "--scenario", TAS)
    assert calls == [(k, 10) for k in range(1, 11)]
    rh = r.columns["relative_humidity"]
    assert rh.dtype == np.float64 and rh[0] == 0.0 and len(rh) == 10
    assert np.array_equal(r.columns["mu_apparent"], [p["mu_apparent"] for p in r.points])


def test_humidity_at_rh_0_is_the_dry_run_bit_for_bit(in_root):
    """The dry point of the sweep is `run` of the scenario with environment.relative_humidity = 0:
    the same mu_e,a, F_a0, standard error and R^2 (eq. 10 fit), bit for bit; no capillary load; the
    adhesive load summed over the clamp voltages in contact is the run's, summed in the same order."""
    s = stiction.Scenario.load(HUMID)
    s.set("environment.relative_humidity", 0.0)
    dry = stiction.run(s)
    point = stiction.humidity(HUMID, rh=[0.35]).points[0]
    assert point["relative_humidity"] == 0.0
    assert point["mu_apparent"] == dry.mu_apparent
    assert point["apparent_adhesion_force_n"] == dry.apparent_adhesion_force_n
    assert point["mu_apparent_se"] == dry.fit["slope_se"]
    assert point["r_squared"] == dry.fit["r_squared"]
    summed = 0.0
    for p in dry.points:
        if p["in_contact"] and p.get("error") is None:
            summed += p["adhesive_load_n"]
    assert point["adhesive_load_summed_n"] == summed
    assert point["capillary_load_summed_n"] == 0.0 and point["capillary_share"] == 0.0
    assert point["kelvin_radius_m"] is None and point["meniscus_height_m"] is None


def test_humid_points_are_the_run_at_that_humidity_and_the_kelvin_radius(in_root):
    """A humid point is `run` with environment.relative_humidity set to it (bit for bit); its
    menisci add adhesion (F_a0 above the dry point's, a capillary share in (0, 1)); and its Kelvin
    radius is the closed form r_K = gamma V_m / (R T ln(1/RH)) (Israelachvili, Intermolecular and
    Surface Forces, 3rd ed., eq. 17.8) with water at 25 C: gamma = 71.97 mN/m, V_m = M/rho =
    18.015e-3 / 997.05 m^3/mol (CRC Handbook), R = 8.314462618 J/(mol K), within 0.5 % (the
    engine's own water property fits)."""
    r = stiction.humidity(HUMID, rh=[0.35])
    s = stiction.Scenario.load(HUMID)
    s.set("environment.relative_humidity", 0.35)
    humid = stiction.run(s)
    dry, wet = r.points
    assert wet["mu_apparent"] == humid.mu_apparent
    assert wet["apparent_adhesion_force_n"] == humid.apparent_adhesion_force_n
    assert wet["apparent_adhesion_force_n"] > dry["apparent_adhesion_force_n"]
    assert 0.0 < wet["capillary_share"] < 1.0
    gamma, v_m, gas, t = 71.97e-3, 18.015e-3 / 997.05, 8.314462618, 298.15
    r_k = gamma * v_m / (gas * t * math.log(1 / 0.35))
    assert wet["kelvin_radius_m"] == pytest.approx(r_k, rel=5e-3)
    # Both faces fully wetting (contact angle 0): h_m = r_K (cos 0 + cos 0).
    assert wet["meniscus_height_m"] == pytest.approx(2 * wet["kelvin_radius_m"], rel=1e-12)


@pytest.mark.parametrize(
    "rh, names",
    [
        ([0.3, float("nan")], "rh[1]"),
        (np.array([0.1, np.inf]), "rh[1]"),
        ([1.0], "rh[0]"),
        ([0.2, 1.5], "rh[1]"),
        ([-0.1], "rh[0]"),
        ([], "rh"),
        ([0.5, 0.2], "rh"),
        ({"a": 1}, "rh"),
        (True, "rh"),
        ([[0.1, 0.2]], "rh"),
        (["0.1", object()], "rh"),
        ("1.5", "rh"),
        ("0:0.5:0", "rh"),
    ],
)
def test_humidity_bad_rh_raises_naming_rh(in_root, rh, names):
    with pytest.raises(stiction.StictionError) as e:
        stiction.humidity(TAS, rh=rh)
    assert str(e.value).startswith(names), str(e.value)


def test_humidity_text_errors_are_the_cli_messages(in_root, cli):
    for text in ("1.5", "0.5,0.2", "x"):
        code, _, err = cli("plot", "humidity", "--scenario", TAS, "--rh", text, "--json")
        assert code == 2
        with pytest.raises(stiction.StictionError) as e:
            stiction.humidity(TAS, rh=text)
        # The CLI's message, its flag named as the argument (--rh -> rh).
        assert python_names(err.strip(), ["rh"]) == "error: " + str(e.value)
    # A bad scenario: the CLI's message, naming the field.
    code, _, err = cli("plot", "humidity", "--scenario", TAS, "--set", "surface.summit_sd=-3 nm", "--json")
    with pytest.raises(stiction.StictionError) as e:
        stiction.humidity(stiction.Scenario.from_dict({"format_version": 1, "surface": {"summit_sd": "-3 nm"}}))
    assert code == 2 and "summit_sd" in err and "summit_sd" in str(e.value)
    with pytest.raises(TypeError):
        stiction.humidity(3.5)


def test_bem_generated_surface_equals_cli(cli_json):
    e = cli_json("bem", "--grid", "16", "--size", "20 um", "--hurst", "0.7", "--seed", "3", "--sweep", "1MPa:20MPa:3")
    got = stiction.bem(grid=16, size="20 um", hurst=0.7, seed=3, sweep="1MPa:20MPa:3").to_dict()
    assert got == e and got["surface"]["source"] == "generated"
    e = cli_json("bem", "--grid", "16", "--roll-off", "5 um", "--short", "2 um", "--rms-height", "0.2 um",
                 "--pressure", "5 MPa")
    assert stiction.bem(pressure=5e6, grid=16, roll_off="5 um", short=2e-6, rms_height="0.2 um").to_dict() == e
    # The command line's default surface (256 x 256) when neither heights nor a scenario is given.
    assert stiction.bem(pressure="20 MPa").to_dict() == cli_json("bem", "--pressure", "20 MPa")


def test_bem_rh_equals_cli_on_a_map_a_generated_surface_and_a_scenario(in_root, tmp_path, cli_json):
    rng = np.random.default_rng(5)
    heights = rng.standard_normal((16, 16)) * 20.0
    path = tmp_path / "map.npy"
    np.save(path, heights)
    e = cli_json("bem", "--map", path, "--pixel-size", "0.5 um", "--height-unit", "nm", "--rh", "0.3,0.6",
                 "--contact-angle", "20 deg", "--temperature", "30 C")
    got = stiction.bem(heights, pixel_size="0.5 um", height_unit="nm", rh=[0.3, 0.6], contact_angle="20 deg",
                       temperature="30 C").to_dict()
    assert got["surface"].pop("file") == "<array>"
    e["surface"].pop("file")
    assert got == e
    e = cli_json("bem", "--grid", "16", "--rh", "0.2:0.6:3", "--pressure", "2 MPa", "--work-of-adhesion",
                 "0.05 J/m^2", "--range", "1 nm")
    for rh in ("0.2:0.6:3", [0.2, 0.4, 0.6], np.linspace(0.2, 0.6, 3)):
        got = stiction.bem(grid=16, rh=rh, pressure="2 MPa", work_of_adhesion="0.05 J/m^2", range="1 nm")
        assert got.to_dict() == e
    assert got.columns["adhesion_energy_j_per_m2"].shape == (3,)
    e = cli_json("bem", "--scenario", HEIGHT_MAP, "--rh", "0.3")
    assert stiction.bem(scenario=HEIGHT_MAP, rh=0.3).to_dict() == e
    # The smallest Kelvin radius: below it (RH 0.1: r_K = 0.228 nm) no meniscus, as the CLI.
    e = cli_json("bem", "--grid", "16", "--rh", "0.1,0.3", "--min-kelvin-radius", "0.28 nm")
    got = stiction.bem(grid=16, rh=[0.1, 0.3], min_kelvin_radius="0.28 nm").to_dict()
    assert got == e
    # ("0.28 nm" parses to 0.28 * 1e-9, one rounding from the literal 0.28e-9.)
    assert abs(got["min_kelvin_radius_m"] - 0.28e-9) < 1e-24 and got["points"][0]["meniscus_height_m"] is None
    assert got["points"][1]["meniscus_height_m"] > 0


def test_bem_new_arguments_refuse_bad_input_naming_the_field(cli):
    a = np.zeros((8, 8))
    cases = [
        (dict(grid=16, rh=[0.3, float("nan")]), "rh[1]"),
        (dict(grid=16, rh=[1.2]), "rh[0]"),
        (dict(grid=16, rh=[]), "rh"),
        (dict(grid=16, rh={"x": 1}), "rh"),
        (dict(grid=16, rh=[0.3], pressure=[1e6, 2e6]), "pressure"),
        (dict(grid=16, rh=[0.3], sweep="1MPa:2MPa:2"), "'rh'"),
        (dict(grid=16, rh=[0.3], temperature="500 C"), "temperature"),
        (dict(grid=16, pressure="1 MPa", temperature="25 C"), "bem: temperature"),
        (dict(grid=1, pressure="1 MPa"), "grid 1"),
        (dict(grid=16, hurst=float("nan"), pressure="1 MPa"), "hurst"),
        (dict(grid=16, size="-3 um", pressure="1 MPa"), "size"),
        (dict(grid=2.5, pressure="1 MPa"), "grid=2.5"),
        (dict(heights=a, grid=16, pressure="1 MPa"), "bem: grid"),
        (dict(scenario=HEIGHT_MAP, seed=2, pressure="1 MPa"), "bem: seed"),
        (dict(pixel_size="1 um", pressure="1 MPa"), "bem: pixel_size"),
    ]
    for kwargs, names in cases:
        # A value out of range: StictionError; a float for an integer: TypeError; each naming the
        # argument, never its command-line flag.
        with pytest.raises((stiction.StictionError, TypeError)) as e:
            stiction.bem(**kwargs)
        assert str(e.value).startswith(names) or names in str(e.value), (kwargs, str(e.value))
        assert "--" not in str(e.value), (kwargs, str(e.value))
    # The command line refuses the same --grid with the same message.
    code, _, err = cli("bem", "--grid", "1", "--pressure", "1 MPa", "--json")
    with pytest.raises(stiction.StictionError) as e:
        stiction.bem(grid=1, pressure="1 MPa")
    assert code == 2 and python_names(err.strip(), ["grid"]) == "error: " + str(e.value)


def test_contact_model_bem_equals_cli(in_root, cli_json):
    e = cli_json("contact", HEIGHT_MAP, "--model", "bem", "--load", "3 uN")
    r = stiction.contact(HEIGHT_MAP, "3 uN", model="bem")
    assert r.to_dict() == e and r.model == "bem"
    assert stiction.contact(HEIGHT_MAP, 3e-6, model="bem").to_dict() == e
    e = cli_json("contact", HEIGHT_MAP, "--model", "bem", "--sweep", "1uN:3uN:3")
    loads = [1e-6 + (3e-6 - 1e-6) * i / 2 for i in range(3)]
    r = stiction.contact(HEIGHT_MAP, np.array(loads), model="bem")
    assert r.to_dict() == e
    assert np.array_equal(r.columns["load_n"], [p["load_n"] for p in e["points"]])
    # The explicit solver stays the default.
    assert stiction.contact(HEIGHT_MAP, "3 uN", model="explicit").to_dict() == cli_json("contact", HEIGHT_MAP, "--load", "3 uN")


def test_contact_model_bem_errors_are_the_cli_messages(in_root, cli):
    for flags, kwargs in [
        (["--load", "-1 uN"], dict(load="-1 uN")),
        (["--load", "1 uN", "--mode", "flat"], dict(load="1 uN", mode="flat")),
        (["--load", "1 uN"], dict(load="1 uN", scenario=TAS)),
    ]:
        scenario = kwargs.pop("scenario", HEIGHT_MAP)
        code, _, err = cli("contact", scenario, "--model", "bem", *flags, "--json")
        with pytest.raises(stiction.StictionError) as e:
            stiction.contact(scenario, model="bem", **kwargs)
        assert code == 2 and python_names(err.strip(), CONTACT_ARGS) == "error: " + str(e.value), (flags, err)
    with pytest.raises(stiction.StictionError, match="model"):
        stiction.contact(HEIGHT_MAP, "1 uN", model="fem")
    with pytest.raises(stiction.StictionError, match="load"):
        stiction.contact(HEIGHT_MAP, [1e-6, float("nan")], model="bem")
