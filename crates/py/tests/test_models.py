"""The models, the solvers, studies and fits from Python against the command line (json.loads of
`stiction ... --json` compared with ==, floats included), zero-copy height maps, GIL release
and Ctrl-C."""

import json
import os
import signal
import sys
import threading
import time

import numpy as np
import pytest

import stiction
from stiction import _stiction

TAS = "scenarios/tas2000.json"
FIT = "scenarios/tas2000-fit-synthetic.json"
VOLTAGES = "data/measured-voltages-synthetic/voltages.csv"


def _smooth_map(ny, nx, dtype=np.float64, order="C"):
    """A few long waves (heights in nm, a few summits): cheap to analyse at any size."""
    y = np.arange(ny)[:, None] / ny
    x = np.arange(nx)[None, :] / nx
    z = 40.0 * np.sin(2 * np.pi * 3 * x + 0.3) * np.cos(2 * np.pi * 2 * y) + 15.0 * np.sin(2 * np.pi * 5 * (x + y))
    return np.asarray(z, dtype=dtype, order=order)


# ---------------------------------------------------------------------------------------------
# zero-copy height maps


@pytest.mark.parametrize("dtype,order", [(np.float64, "C"), (np.float32, "F")])
def test_a_4096_squared_array_is_read_in_place(dtype, order):
    """The input step allocates the one map in metres (8 bytes a pixel) and nothing the size of
    the array besides: a copy of the array (an .npy image, a contiguous or float64 copy) would add
    at least 4 bytes a pixel (64 MiB for float32) to the peak of the extension's heap."""
    n = 4096
    heights = _smooth_map(n, n, dtype, order)
    map_bytes = n * n * 8
    before, _ = _stiction._heap()
    _stiction._reset_heap_peak()
    assert _stiction._read_heights(heights, 1e-6, 1e-9) == (n, n)
    peak = _stiction._heap()[1] - before
    assert map_bytes <= peak < map_bytes + n * n * 4 // 4, f"peak {peak / 2**20:.1f} MiB for a {map_bytes / 2**20:.0f} MiB map"
    # A view that is neither C nor Fortran ordered (every other column) is read in place too.
    view = heights[:, ::2]
    _stiction._reset_heap_peak()
    before, _ = _stiction._heap()
    assert _stiction._read_heights(view, 1e-6, 1e-9) == (n // 2, n)
    assert _stiction._heap()[1] - before < map_bytes // 2 + n * n, "the view was copied"


def test_topography_of_a_4096_squared_array_makes_no_numpy_copy():
    """NumPy reports its buffers to tracemalloc: through the whole call, no allocation of the
    array's size (128 MiB) is made on the Python side."""
    import tracemalloc

    n = 4096
    heights = _smooth_map(n, n)
    tracemalloc.start()
    try:
        r = stiction.topography(heights, pixel_size="1 um", height_unit="nm", level="none")
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert r.summit_count > 0
    assert peak < 8 * 2**20, f"{peak / 2**20:.1f} MiB traced on the Python side"


def test_strided_and_reversed_views_equal_their_copies(cli_json, tmp_path):
    base = _smooth_map(96, 80)
    for view in (base[::-1, :], base[:, ::2], base.T, base[10:70, 5:75]):
        got = stiction.topography(view, pixel_size="1 um", height_unit="nm").to_dict()
        copy = stiction.topography(np.ascontiguousarray(view), pixel_size="1 um", height_unit="nm").to_dict()
        assert got == copy


# ---------------------------------------------------------------------------------------------
# the explicit solver


def test_contact_at_a_load_and_a_sweep_equal_cli(in_root, cli_json):
    e = cli_json("contact", TAS, "--load", "3 uN")
    r = stiction.contact(TAS, "3 uN")
    assert r.to_dict() == e
    assert stiction.contact(TAS, 3e-6).to_dict() == e
    # A load vector is the sweep of those loads: FROM:TO:STEPS gives from + (to - from) i / (n - 1).
    loads = [0.0 + (5e-6 - 0.0) * i / 4 for i in range(5)]
    e = cli_json("contact", TAS, "--sweep", "0:5e-6:5")
    s = stiction.contact(TAS, np.array(loads))
    assert s.to_dict() == e
    assert np.array_equal(s.columns["load_n"], [p["load_n"] for p in e["points"]])
    flat = stiction.contact(stiction.Scenario.load(TAS, ["surface.summit_sd=50 nm"]), "2 uN", mode="flat")
    assert flat.to_dict() == cli_json("contact", TAS, "--set", "surface.summit_sd=50 nm", "--load", "2 uN", "--mode", "flat")


def test_contact_errors_are_the_cli_messages(in_root, cli, tmp_path):
    code, _, err = cli("contact", TAS, "--load", "3 uN", "--mode", "sideways", "--json")
    assert code == 2
    with pytest.raises(stiction.StictionError) as e:
        stiction.contact(TAS, "3 uN", mode="sideways")
    assert "sideways" in str(e.value) and "sideways" in err
    with pytest.raises(stiction.StictionError, match="load\\[1\\]"):
        stiction.contact(TAS, [1e-6, np.nan])
    # A scenario built in memory meets the same checks as a file, named "<scenario>".
    path = tmp_path / "no-material.json"
    path.write_text('{"format_version": 1}')
    code, _, err = cli("contact", path, "--load", "1e-6", "--json")
    assert code == 2
    with pytest.raises(stiction.StictionError) as e:
        stiction.contact(stiction.Scenario.from_dict({"format_version": 1}), 1e-6)
    assert str(e.value) == err[len("error: "):].strip().replace(str(path), "<scenario>")


# ---------------------------------------------------------------------------------------------
# boundary elements on an array


def test_bem_on_an_array_equals_cli_on_its_npy_file(tmp_path, cli_json):
    heights = _smooth_map(64, 64)
    path = tmp_path / "map.npy"
    np.save(path, heights)
    flags = ["--pixel-size", "0.5 um", "--height-unit", "nm", "--shear-strength", "1 GPa"]
    e = cli_json("bem", "--map", path, *flags, "--sweep", "1MPa:40MPa:3")
    got = stiction.bem(heights, pixel_size="0.5 um", height_unit="nm", shear_strength="1 GPa", sweep="1MPa:40MPa:3").to_dict()
    assert got["surface"]["file"] == "<array>"
    got["surface"]["file"] = e["surface"]["file"]
    assert got == e
    # The same loads as a vector of pressures (Pa), and the array in Fortran order as float32 ->
    # the float32 file.
    pressures = [1e6 + (40e6 - 1e6) * k / 2 for k in range(3)]
    vec = stiction.bem(heights, pressures, pixel_size=0.5e-6, height_unit=1e-9, shear_strength=1e9).to_dict()
    vec["surface"]["file"] = e["surface"]["file"]
    assert vec == e
    f32 = np.asfortranarray(heights.astype(np.float32))
    np.save(path, f32)
    e32 = cli_json("bem", "--map", path, "--pixel-size", "0.5 um", "--height-unit", "nm", "--pressure", "20 MPa")
    got32 = stiction.bem(f32, "20 MPa", pixel_size="0.5 um", height_unit="nm").to_dict()
    got32["surface"]["file"] = e32["surface"]["file"]
    assert got32 == e32
    assert e32["points"][0]["contact_fraction"] > 0


def test_bem_errors(cli):
    heights = _smooth_map(32, 32)
    with pytest.raises(stiction.StictionError, match="pressure"):
        stiction.bem(heights, pixel_size="1 um", height_unit="nm")
    with pytest.raises(stiction.StictionError, match="pressure"):
        stiction.bem(heights, [1e6, -1.0], pixel_size="1 um", height_unit="nm")
    with pytest.raises(stiction.StictionError, match="e_star"):
        stiction.bem(heights, "1 MPa", pixel_size="1 um", height_unit="nm", e_star="-3 GPa")
    with pytest.raises(stiction.StictionError, match="pixel size"):
        stiction.bem(heights, "1 MPa", height_unit="nm")


def test_bem_boundary_tilt_and_hardness_equal_cli(tmp_path, cli_json):
    """boundary, tilt and hardness as --boundary, --tilt and --hardness: the same JSON."""
    heights = _smooth_map(32, 32)
    path = tmp_path / "map.npy"
    np.save(path, heights)
    flags = ["--pixel-size", "0.5 um", "--height-unit", "nm", "--e-star", "1 GPa"]
    for cli_flags, kw in [
        (["--hardness", "20 MPa", "--sweep", "1MPa:10MPa:2"], dict(hardness="20 MPa", sweep="1MPa:10MPa:2")),
        (["--boundary", "non-periodic", "--pressure", "5 MPa"], dict(boundary="non_periodic", pressure="5 MPa")),
        (["--boundary", "non-periodic", "--tilt", "--hardness", "20 MPa", "--pressure", "5 MPa"],
         dict(boundary="non_periodic", tilt=True, hardness="20 MPa", pressure="5 MPa")),
        (["--boundary", "non-periodic", "--tilt", "--pressure", "5 MPa"],
         dict(boundary="non_periodic", tilt=True, pressure="5 MPa")),
    ]:
        e = cli_json("bem", "--map", path, *flags, *cli_flags)
        got = stiction.bem(heights, pixel_size="0.5 um", height_unit="nm", e_star="1 GPa", **kw).to_dict()
        got["surface"]["file"] = e["surface"]["file"]
        assert got == e, kw
    assert got["boundary"] == "non_periodic" and got["tilt"] is True
    assert np.isfinite(got["points"][0]["tilt_x_rad"])


def test_bem_tilting_face_meets_a_tilted_plane_at_its_slope():
    """A height map that is a plane of slopes (2e-3, -1e-3) (not levelled): the balanced face is
    the plane itself, a flat punch in full contact (Boussinesq: no moment about the centre);
    closed form t = (a, b), within 1e-3 of the slope (the moment tolerance)."""
    ny, nx, dx = 24, 32, 1e-6
    y, x = np.mgrid[0:ny, 0:nx]
    heights = 2e-3 * (x + 0.5) * dx - 1e-3 * (y + 0.5) * dx
    r = stiction.bem(heights, pixel_size=dx, height_unit=1.0, level="none", e_star="1 GPa",
                     boundary="non_periodic", tilt=True, pressure="1 MPa").to_dict()
    p = r["points"][0]
    assert abs(p["tilt_x_rad"] / 2e-3 - 1) < 1e-3 and abs(p["tilt_y_rad"] / -1e-3 - 1) < 1e-3, p
    assert p["contact_fraction"] == 1.0


def test_bem_boundary_tilt_hardness_refuse_bad_input_naming_the_argument():
    heights = _smooth_map(16, 16)
    kw = dict(pixel_size="0.5 um", height_unit="nm")
    cases = [
        (dict(boundary="sideways", pressure="1 MPa"), "boundary"),
        (dict(tilt=True, pressure="1 MPa"), "tilt"),
        (dict(boundary="non_periodic", gap_sweep="50nm:10nm:2"), "gap_sweep"),
        (dict(hardness="1e30 Pa", pressure="1 MPa"), "hardness"),
        (dict(hardness="-1 GPa", pressure="1 MPa"), "hardness"),
        (dict(hardness="1 MPa", pressure="5 MPa"), "hardness"),
        (dict(hardness="1 MPa", boundary="non_periodic", tilt=True, pressure="5 MPa"), "hardness"),
    ]
    for extra, name in cases:
        with pytest.raises(stiction.StictionError) as e:
            stiction.bem(heights, **kw, **extra)
        assert name in str(e.value) and "--" not in str(e.value), (extra, str(e.value))


# ---------------------------------------------------------------------------------------------
# single asperity, fit, study


def test_asperity_laws_equal_cli_discrete_with_one_contact(cli_json):
    material = ["--radius", "0.5 um", "--work-of-adhesion", "0.1 J/m^2", "--compliance", "9.1e-12 1/Pa",
                "--shear-strength", "1.4 GPa"]
    for law in ("dmt", "jkr", "maugis-dugdale", "hertz"):
        a = stiction.asperity("0.5 um", "0.1 J/m^2", "9.1e-12 1/Pa", "1.4 GPa", [1e-7, 2e-6], adhesion=law)
        for i, load in enumerate(["1e-07", "2e-06"]):
            assert a["points"][i] == cli_json("discrete", "--contacts", 1, *material, "--load", load, "--adhesion", law)


def test_fit_with_a_csv_path_and_with_arrays_equals_cli(in_root, cli_json):
    flags = dict(models="discrete-n1,gw-dmt", draws=200)
    e = cli_json("fit", VOLTAGES, "--scenario", FIT, "--models", "discrete-n1,gw-dmt", "--draws", 200)
    assert stiction.fit(VOLTAGES, FIT, **flags).to_dict() == e
    assert stiction.fit(None, FIT, **flags).to_dict()["eq10"] == e["eq10"]
    import csv

    with open(VOLTAGES) as f:
        rows = list(csv.reader(line for line in f if not line.startswith("#")))
    arrays = {name: np.array([float(r[k]) for r in rows[1:]]) for k, name in enumerate(rows[0])}
    assert set(arrays) == {"v_clamp_v", "v_pull_v"} and len(arrays["v_pull_v"]) > 5
    got = stiction.fit(arrays, FIT, **flags).to_dict()
    # Same rows, same numbers: only the name of the data source may differ.
    text_e, text_g = json.dumps(e), json.dumps(got).replace("<data>", VOLTAGES)
    assert json.loads(text_g) == json.loads(text_e)
    with pytest.raises(stiction.StictionError, match="v_pull_v"):
        stiction.fit({"v_clamp_v": [1.0, 2.0]}, FIT)


def test_study_of_a_dict_scenario_equals_cli_and_gives_the_samples(in_root, cli_json, tmp_path):
    expected = cli_json("study", TAS, "--samples", 8, "--seed", 3, "--threads", 1)
    with open(TAS) as f:
        d = json.load(f)
    s = stiction.Scenario.from_dict(d, base_dir="scenarios")
    r = stiction.study(s, samples=8, seed=3, threads=2, as_pandas=False)
    got = r.to_dict()
    assert json.loads(json.dumps(got).replace('"<scenario>"', json.dumps(TAS))) == expected
    cols = r.samples
    assert isinstance(cols, dict) and cols["sample"].tolist() == list(range(8))
    assert cols["mu_apparent"].dtype == np.float64
    # The samples' mu_e,a are those summarized: their median is the CLI's.
    assert np.isfinite(cols["mu_apparent"]).sum() > 0
    # The CSV of `stiction study --out` is the same table.
    out = tmp_path / "study"
    code = os.system(f"{_cli_path()} study {TAS} --samples 8 --seed 3 --threads 1 --out {out} > /dev/null 2>&1")
    assert code == 0
    import csv

    with open(out / "samples.csv") as f:
        rows = list(csv.reader(f))
    assert rows[0] == list(cols)
    assert [float(v) if v else np.nan for v in (row[1] for row in rows[1:])] == pytest.approx(
        cols["mu_apparent"].tolist(), nan_ok=True, rel=0, abs=0
    )


def _cli_path():
    from conftest import _binary

    return _binary()


def test_study_samples_as_a_pandas_dataframe(in_root):
    pd = pytest.importorskip("pandas")
    r = stiction.study(TAS, samples=4, seed=1, threads=1)
    assert isinstance(r.samples, pd.DataFrame)
    plain = stiction.study(TAS, samples=4, seed=1, threads=1, as_pandas=False).samples
    assert list(r.samples.columns) == list(plain)
    for k, v in plain.items():
        assert np.array_equal(r.samples[k].to_numpy(), v, equal_nan=v.dtype.kind == "f")


def test_study_progress_reports_every_sample(in_root):
    seen = []
    stiction.study(TAS, samples=6, seed=1, threads=2, progress=lambda d, t: seen.append((d, t)))
    assert seen[-1] == (6, 6) and all(t == 6 for _, t in seen)

    def boom(d, t):
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        stiction.study(TAS, samples=50, seed=1, threads=1, progress=boom)


# ---------------------------------------------------------------------------------------------
# Ctrl-C and the GIL


def test_ctrl_c_stops_a_long_study(in_root, cli_json):
    """Ctrl-C during a study raises KeyboardInterrupt, stops the study (its samples in flight
    finish, no more start) and leaves nothing behind, without a clock: SIGINT is sent from the
    progress callback, once the study has demonstrably started (a sample is done), so however
    loaded the machine is, the signal meets a running study; the study must then stop (its log
    folder removed, no progress call after that) where uninterrupted it would run for minutes.
    The only time bound is a hang guard of minutes."""
    import tempfile

    prefix = f"stiction-study-{os.getpid()}-"
    seen = []
    main = threading.main_thread().ident

    def progress(done, total):
        seen.append(done)
        if len(seen) == 1:
            signal.pthread_kill(main, signal.SIGINT)

    samples = 200000  # minutes of work uninterrupted
    with pytest.raises(KeyboardInterrupt):
        stiction.study(TAS, samples=samples, seed=1, threads=2, progress=progress)
    assert seen, "the progress callback sent the signal, so it ran"
    # The study stops: its worker removes the temporary log folder when it returns. Hang guard
    # only: an unstopped study would keep it for minutes.
    guard = time.monotonic() + 300
    while any(n.startswith(prefix) for n in os.listdir(tempfile.gettempdir())):
        assert time.monotonic() < guard, "the interrupted study still runs"
        time.sleep(0.05)
    stopped_at = len(seen)
    assert max(seen) < samples, "the study ran to its end"
    # Nothing corrupted: the next study gives the CLI's numbers (and no call of the old callback
    # happened after the interrupted study returned).
    assert stiction.study(TAS, samples=4, seed=2, threads=1, as_pandas=False).to_dict() == cli_json(
        "study", TAS, "--samples", 4, "--seed", 2, "--threads", 1
    )
    assert len(seen) == stopped_at, "the interrupted study reported progress after it stopped"
    assert not any(n.startswith(prefix) for n in os.listdir(tempfile.gettempdir()))


def test_another_thread_runs_python_while_the_engine_computes():
    """GIL release, without a clock: with the interpreter's switch interval set to 1000 s, a thread
    gives up the GIL only when it blocks or when C code releases it. The main thread waits for a
    worker to start an explicit-solver load sweep (a loaded Scenario: no file I/O in the call); the
    worker's `started.set()` wakes the main thread, which then needs the GIL the worker holds. It gets
    it while the call is still running only if the engine releases the GIL while it computes, and
    then sees `done` still False. An engine that held the GIL would run the whole call, set `done`
    and end before the main thread could look. (The sweep takes some 0.1 s, far longer than a
    thread's wake-up.)"""
    # About 4e6 summits on a 2 mm x 5 um wall: some 0.1 s of generation and solving per call.
    wide = stiction.Scenario.load(
        TAS, ["surface.apparent_length=2000 um", "surface.summit_density=4e14 m^-2", "surface.max_summits=10000000"]
    )
    loads = np.linspace(0.5e-6, 600e-6, 50)
    started = threading.Event()
    state = {"done": False, "error": None}

    def worker():
        started.set()
        try:
            stiction.contact(wide, loads, mode="flat")
        except Exception as e:  # reported below, not lost in the thread
            state["error"] = e
        state["done"] = True

    old = sys.getswitchinterval()
    sys.setswitchinterval(1000.0)
    try:
        t = threading.Thread(target=worker)
        t.start()
        started.wait()
        done_when_main_ran = state["done"]
        t.join()
    finally:
        sys.setswitchinterval(old)
    assert state["error"] is None, state["error"]
    assert state["done"]
    assert not done_when_main_ran, "the main thread ran only after the engine call returned: the GIL was held"
