"""The command line's limits from Python (issue 33): every array argument is counted against the
CLI's limit for the same quantity BEFORE it is read, copied or solved, and every integer argument
is range-checked (negative, past 2^64, a bool, a float); the error names the Python argument,
never a flag the caller did not type.

"Before any work" is asserted without a clock: the call's allocations are bounded (the Rust
heap of the extension, `_heap`, and Python's, `tracemalloc`, which also sees NumPy's buffers) far
below what reading or solving the argument would take, and a study's progress callback is never
called. The huge inputs are zero-stride views (`np.broadcast_to`): they cost nothing to make, and
reading them would allocate their full size."""

import re
import tracemalloc

import numpy as np
import pytest

import stiction
from stiction import _stiction

TAS = "scenarios/tas2000.json"
HEIGHT_MAP = "scenarios/tas2000-height-map.json"
LIMITS = _stiction._limits()

# Far below the bytes of any refused input read as float64 (10^6 values = 8 MB).
BOUND = 1 << 20


def _names(message, name):
    """The message names the argument as a word (``load``, ``load[3]``, ``load:``), and no flag."""
    return re.search(rf"(?<![\w-]){re.escape(name)}(?![\w])", message) is not None


def refused(call, name, exc=stiction.StictionError):
    """Runs `call`, which must raise `exc` naming `name`, with under BOUND bytes allocated by the
    extension and by Python (NumPy included) during the call; returns the message."""
    tracemalloc.start()
    _stiction._reset_heap_peak()
    heap_before = _stiction._heap()[0]
    try:
        with pytest.raises(exc) as e:
            call()
    finally:
        _, python_peak = tracemalloc.get_traced_memory()
        tracemalloc.stop()
    rust_peak = _stiction._heap()[1] - heap_before
    message = str(e.value)
    assert isinstance(e.value, exc), (type(e.value), message)
    assert _names(message, name), (name, message)
    assert not re.search(r"(?<![\w-])--[a-z]", message), f"a flag the caller did not type: {message}"
    assert 0 < len(message) < 2000, message
    assert rust_peak < BOUND, f"{rust_peak} bytes on the Rust heap before the refusal: {message}"
    assert python_peak < BOUND, f"{python_peak} bytes of Python memory before the refusal: {message}"
    return message


def huge(n, value=1.0):
    """n values that cost nothing until read (a zero-stride view)."""
    return np.broadcast_to(np.float64(value), (n,))


# ---------------------------------------------------------------------------------------------
# array lengths


def test_contact_load_vector_past_the_sweep_limit_is_refused_before_it_is_read(in_root):
    limit = LIMITS["max_sweep_steps"]
    assert limit == 1_000_000
    # The call: a million and one loads (37 s and a MemoryError at 6 GB before).
    loads = np.linspace(0, 5e-6, limit + 1)
    m = refused(lambda: stiction.contact(TAS, load=loads), "load")
    assert str(limit) in m and "max_sweep_steps" in m
    refused(lambda: stiction.contact(TAS, load=huge(10 * limit, 1e-6)), "load")
    refused(lambda: stiction.contact(HEIGHT_MAP, load=huge(limit + 1, 1e-6), model="bem"), "load")
    as_list = [1e-6] * (limit + 1)
    refused(lambda: stiction.contact(TAS, load=as_list), "load")
    refused(lambda: stiction.contact(TAS, load=[]), "load")


def test_contact_max_sweep_steps_is_the_clis(in_root, cli):
    loads = np.linspace(1e-6, 2e-6, 11)
    m = refused(lambda: stiction.contact(TAS, load=loads, max_sweep_steps=10), "load")
    assert "10" in m
    code, _, err = cli("contact", TAS, "--sweep", "1uN:2uN:11", "--max-sweep-steps", "10", "--json")
    assert code == 2 and "limit of 10 steps" in err
    r = stiction.contact(TAS, load=loads[:10], max_sweep_steps=10, mode="flat")
    assert len(r.points) == 10
    for bad in (0, -1, 2**64):
        refused(lambda: stiction.contact(TAS, load=loads, max_sweep_steps=bad), "max_sweep_steps")
    for bad in (True, 2.5, "10"):
        refused(lambda: stiction.contact(TAS, load=loads, max_sweep_steps=bad), "max_sweep_steps", TypeError)


def test_bem_pressure_vector_past_the_sweep_limit_is_refused_before_it_is_read():
    limit = LIMITS["bem_max_path_steps"]
    assert limit == 10_000
    # The call: 20,000 pressures where `bem --sweep` takes 10,000.
    pressures = np.linspace(1e6, 2e6, 2 * limit)
    m = refused(lambda: stiction.bem(pressure=pressures, grid=32), "pressure")
    assert str(limit) in m
    refused(lambda: stiction.bem(pressure=huge(limit + 1, 1e6), grid=32), "pressure")
    refused(lambda: stiction.bem(pressure=huge(10**7, 1e6), grid=32), "pressure")
    as_list = [1e6] * 10**6  # 8 MB once converted: counted first
    refused(lambda: stiction.bem(pressure=as_list, grid=32), "pressure")
    refused(lambda: stiction.bem(pressure=[], grid=32), "pressure")


def test_bem_and_humidity_rh_past_the_limit_are_refused_before_they_are_read(in_root):
    limit = LIMITS["max_rh"]
    assert limit == 1000
    for rh in ([0.5] * (limit + 1), [0.5] * 10**6, huge(limit + 1, 0.5), huge(10**7, 0.5)):
        refused(lambda: stiction.bem(grid=32, rh=rh), "rh")
        refused(lambda: stiction.humidity(TAS, rh=rh), "rh")
    refused(lambda: stiction.humidity(TAS, rh=np.zeros((2, 2))), "rh")


def test_bem_heights_past_the_grid_limit_are_refused_before_they_are_read():
    side = LIMITS["bem_max_grid_side"]
    assert side == 4096
    # 4097 x 4096 points (134 MB as float64), never read: the solver's grid limit first.
    heights = np.broadcast_to(np.float64(1.0), (side + 1, side))
    m = refused(lambda: stiction.bem(heights, "1 MPa", pixel_size="1 um", height_unit="nm"), "heights")
    assert str(1 << 24) in m


def test_gw_and_discrete_load_vectors_past_the_sweep_limit_are_refused():
    limit = LIMITS["max_sweep_steps"]
    refused(lambda: stiction.gw(2.0, huge(limit + 1, 0.5)), "load_star")
    refused(lambda: stiction.gw(2.0, huge(10**7, 0.5)), "load_star")
    as_list = [0.5] * (limit + 1)
    refused(lambda: stiction.gw(2.0, as_list), "load_star")
    args = ("0.5 um", "0.1 J/m^2", "9.1e-12 1/Pa", "1.4 GPa")
    refused(lambda: stiction.discrete(3, *args, load=huge(limit + 1, 1e-6)), "load")
    as_list = [1e-6] * (limit + 1)
    refused(lambda: stiction.asperity(*args, load=as_list), "load")


def test_gw_theta_of_another_type_names_theta():
    for bad in (True, "x", [1], {"a": 1}, "x" * 5000):
        m = refused(lambda: stiction.gw(bad, 0.5), "theta", TypeError)
        assert len(m) < 200, m
    for bad in (-1.0, 0.0, float("nan")):
        refused(lambda: stiction.gw(bad, 0.5), "theta")
    assert stiction.gw("inf", 0.5)["theta"] is None and stiction.gw(2, [0.5])["theta"] == 2.0


def test_fit_data_rows_past_the_limit_are_refused_before_the_csv_is_made(in_root):
    limit = LIMITS["fit_max_rows"]
    data = {"v_clamp_v": huge(limit + 1, 20.0), "v_pull_v": huge(limit + 1, 30.0)}
    m = refused(lambda: stiction.fit(data, "scenarios/tas2000-fit-synthetic.json"), "data")
    assert str(limit) in m


# ---------------------------------------------------------------------------------------------
# integer arguments


BAD_COUNTS = [(-1, stiction.StictionError), (2**64, stiction.StictionError), (2**1000, stiction.StictionError),
              (True, TypeError), (False, TypeError), (np.True_, TypeError), (2.5, TypeError), (4.0, TypeError),
              ("8", TypeError), ([3], TypeError)]


def test_study_counts_are_named_and_refused_before_the_study_starts(in_root):
    calls = []

    def never(done, total):
        calls.append(done)

    for name in ("samples", "seed", "threads"):
        for bad, exc in BAD_COUNTS:
            kwargs = {name: bad}
            m = refused(lambda: stiction.study(TAS, progress=never, **kwargs), name, exc)
            assert len(m) < 300, m
    # The command line's limits: samples >= 1 and <= STICTION_MAX_SAMPLES (10^7), threads 1..=1024.
    m = refused(lambda: stiction.study(TAS, samples=LIMITS["max_samples"] + 1, progress=never), "samples")
    assert "STICTION_MAX_SAMPLES" in m
    refused(lambda: stiction.study(TAS, samples=0, progress=never), "samples")
    refused(lambda: stiction.study(TAS, threads=0, progress=never), "threads")
    refused(lambda: stiction.study(TAS, threads=LIMITS["max_threads"] + 1, progress=never), "threads")
    assert calls == [], "a refused study reported progress: it ran"
    # NumPy integers are integers.
    r = stiction.study(TAS, samples=np.int64(2), seed=np.uint8(1), threads=np.int32(1), as_pandas=False)
    assert r.samples["sample"].tolist() == [0, 1]


def test_the_study_message_past_the_sample_limit_is_the_clis_naming_the_argument(in_root, cli):
    n = LIMITS["max_samples"] + 1
    code, _, err = cli("study", TAS, "--samples", n, "--json")
    assert code == 2
    m = refused(lambda: stiction.study(TAS, samples=n), "samples")
    assert err.strip() == "error: " + m.replace("samples ", "--samples ", 1).replace("different seed", "different --seed")


def test_bem_generator_counts_are_named():
    for bad, exc in BAD_COUNTS:
        refused(lambda: stiction.bem(pressure="1 MPa", grid=bad), "grid", exc)
        refused(lambda: stiction.bem(pressure="1 MPa", grid=32, seed=bad), "seed", exc)
    for bad in (0, 1, LIMITS["bem_max_grid_side"] + 1):
        refused(lambda: stiction.bem(pressure="1 MPa", grid=bad), "grid")


def test_fit_counts_are_named(in_root):
    fit = "scenarios/tas2000-fit-synthetic.json"
    for name, over in (("surfaces", LIMITS["fit_max_surfaces"] + 1), ("draws", LIMITS["fit_max_draws"] + 1),
                       ("seed", 2**64)):
        for bad, exc in BAD_COUNTS + [(over, stiction.StictionError)]:
            refused(lambda: stiction.fit(None, fit, **{name: bad}), name, exc)
        if name != "seed":
            refused(lambda: stiction.fit(None, fit, **{name: 0}), name)


def test_contact_and_discrete_counts_are_named(in_root):
    for bad, exc in BAD_COUNTS:
        refused(lambda: stiction.contact(TAS, "1 uN", mode="fixed", contacts=bad), "contacts", exc)
        refused(lambda: stiction.discrete(bad, "0.5 um", "0.1 J/m^2", "9.1e-12 1/Pa", "1.4 GPa", "1 uN"),
                "contacts", exc)
    refused(lambda: stiction.contact(TAS, "1 uN", mode="fixed", contacts=0), "contacts")
    refused(lambda: stiction.discrete(2**32, "0.5 um", "0.1 J/m^2", "9.1e-12 1/Pa", "1.4 GPa", "1 uN"), "contacts")


# ---------------------------------------------------------------------------------------------
# flags named as the arguments


def test_errors_of_flag_arguments_name_the_python_argument(in_root):
    """The binding turns some keyword arguments into the command line's flags; their errors name
    the argument (`e_star`, `sweep`, `tolerance`), never the flag (`--e-star`)."""
    for kwargs, name in [
        (dict(e_star="-3 GPa"), "e_star"),
        (dict(tolerance=2.0), "tolerance"),
        (dict(sweep="1MPa:2MPa:10001", pressure=None), "sweep"),
        (dict(sweep="1MPa:2MPa", pressure=None), "sweep"),
        (dict(gap_sweep="1um:0.2um:0", pressure=None), "gap_sweep"),
        (dict(hurst="x"), "hurst"),
        (dict(rms_height="-1 um"), "rms_height"),
        (dict(rh="0:0.5:2000", pressure=None), "rh"),
    ]:
        kwargs.setdefault("pressure", "1 MPa")
        refused(lambda: stiction.bem(grid=32, **kwargs), name)
    refused(lambda: stiction.humidity(TAS, rh="0:0.5:2000"), "rh")
    refused(lambda: stiction.fit(None, "scenarios/tas2000-fit-synthetic.json", models="bogus"), "models")
    refused(lambda: stiction.contact(HEIGHT_MAP, "1 uN", model="bem", mode="flat"), "mode")
