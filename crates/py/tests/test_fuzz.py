"""The Python front end in the fuzz harness: seeded hostile scenarios (dicts) and height-map
arrays. Each case either succeeds with finite numbers or raises StictionError (a ValueError)
whose message is the command line's for the same input (a dict written as a scenario file, an
array saved as .npy); never a crash, another exception or a hang.

STICTION_FUZZ_CASES (default 150 per kind) and STICTION_FUZZ_SEED (default 1) set the run."""

import copy
import json
import math
import os
import time

import numpy as np
import pytest

import stiction
from conftest import python_names

CASES = int(os.environ.get("STICTION_FUZZ_CASES", "150"))
SEED = int(os.environ.get("STICTION_FUZZ_SEED", "1"))
TAS = "scenarios/tas2000.json"

HOSTILE = [
    None, True, 0, -1, 1e308, -1e308, float("nan"), float("inf"), "", "forty", "1e400 m", "0.5 kg",
    "-3 um", [], {}, [1, 2], {"value": "1 um", "sd": "-1 um"}, "nan um", "1e-400 m", 2**70, "μm", "x" * 5000,
]


def _leaves(tree, path=()):
    if isinstance(tree, dict):
        for k, v in tree.items():
            yield from _leaves(v, path + (k,))
    elif isinstance(tree, list):
        for i, v in enumerate(tree):
            yield from _leaves(v, path + (i,))
    else:
        yield path


def _set(tree, path, value):
    for p in path[:-1]:
        tree = tree[p]
    tree[path[-1]] = value


def _delete(tree, path):
    for p in path[:-1]:
        tree = tree[p]
    del tree[path[-1]]


def _cli_message(stderr):
    assert stderr.startswith("error: "), stderr
    return stderr[len("error: "):].strip()


def _finite(value):
    if isinstance(value, float):
        return math.isfinite(value)
    if isinstance(value, dict):
        return all(_finite(v) for v in value.values())
    if isinstance(value, list):
        return all(_finite(v) for v in value)
    return True


def test_hostile_scenario_dicts_raise_the_cli_message(in_root, cli, tmp_path):
    rng = np.random.default_rng(SEED)
    with open(TAS) as f:
        base = json.load(f)
    leaves = list(_leaves(base))
    compared = refused = accepted = 0
    for case in range(CASES):
        d = copy.deepcopy(base)
        for _ in range(int(rng.integers(1, 3))):
            path = leaves[int(rng.integers(len(leaves)))]
            try:
                if rng.random() < 0.2:
                    _delete(d, path)
                else:
                    _set(d, path, HOSTILE[int(rng.integers(len(HOSTILE)))])
            except (KeyError, IndexError, TypeError):
                pass
        start = time.perf_counter()
        try:
            s = stiction.Scenario.from_dict(d, base_dir="scenarios")
            s.validate()
            accepted += 1
        except stiction.StictionError as e:
            refused += 1
            message = str(e)
            assert 0 < len(message) < 2000, (case, message[:300])
            if case % 10 == 0:
                # The same tree as a file: the CLI's message, with the file's name for "<scenario>".
                text = json.dumps(d, allow_nan=True)
                if "NaN" in text or "Infinity" in text:
                    continue  # not JSON: the file reader refuses the token before the field
                path = tmp_path / f"case{case}.json"
                path.write_text(text)
                code, _, err = cli("scenario", path)
                assert code == 2, (case, err)
                assert _cli_message(err).replace(str(path), "<scenario>") == message, case
                compared += 1
        if case % 5 == 0:
            # The plain dict straight into the functions that take a scenario: a result with
            # every number finite, or a StictionError; never another exception or a panic.
            for call in (
                lambda: stiction.contact(d, "1 uN"),
                lambda: stiction.run(d),
                lambda: stiction.humidity(d, rh=[0.35]),
            ):
                try:
                    assert _finite(call().to_dict()), case
                except stiction.StictionError as e:
                    assert 0 < len(str(e)) < 2000, (case, str(e)[:300])
        assert time.perf_counter() - start < 30, case
    assert refused > CASES // 4 and compared > 0, (accepted, refused, compared)


def _arrays(rng):
    """Hostile arrays: wrong dimensions, empty, too small, NaN, inf, huge, other dtypes, odd
    byte orders and strides."""
    good = rng.standard_normal((8, 9))
    yield np.float64(1.0)
    yield np.zeros(10)
    yield np.zeros((3, 3, 3))
    yield np.zeros((0, 0))
    yield np.zeros((1, 40))
    yield np.zeros((40, 1))
    yield np.full((6, 6), np.nan)
    yield np.where(np.eye(6) > 0, np.inf, 1.0)
    yield np.full((6, 6), 1e300)
    yield good.astype(np.int64)
    yield good.astype(np.complex128)
    yield good.astype(np.float16)
    yield good.astype(">f8")
    yield good.astype(object)
    yield good > 0
    yield good[::-1, ::3]
    yield np.lib.stride_tricks.as_strided(good, shape=(8, 9), strides=(0, 8))
    for _ in range(CASES):
        a = rng.standard_normal((int(rng.integers(0, 12)), int(rng.integers(0, 12))))
        kind = int(rng.integers(6))
        if kind == 0 and a.size:
            a.flat[rng.integers(a.size, size=int(rng.integers(1, a.size + 1)))] = np.nan
        elif kind == 1 and a.size:
            a.flat[int(rng.integers(a.size))] = [np.inf, -np.inf, 1e200][int(rng.integers(3))]
        elif kind == 2:
            a = a.astype(np.float32)
        elif kind == 3:
            a = np.asfortranarray(a)
        yield a


def test_hostile_arrays_raise_the_cli_message(cli, tmp_path):
    rng = np.random.default_rng(SEED)
    path = tmp_path / "map.npy"
    counts = {"ok": 0, "refused": 0, "compared": 0}
    for i, a in enumerate(_arrays(rng)):
        for call in (
            lambda: stiction.topography(a, pixel_size="1 um", height_unit="nm"),
            lambda: stiction.bem(a, "10 MPa", pixel_size="1 um", height_unit="nm"),
        ):
            try:
                r = call()
                assert _finite(r.to_dict()), i
                counts["ok"] += 1
            except stiction.StictionError as e:
                counts["refused"] += 1
                message = str(e)
                assert 0 < len(message) < 2000, (i, message[:300])
        if isinstance(a, np.ndarray) and a.ndim == 2 and a.dtype in (np.float64, np.float32) and i % 3 == 0:
            # The CLI on the array's .npy file: the same message (the file named "heights").
            np.save(path, a)
            code, out, err = cli("topography", path, "--pixel-size", "1 um", "--height-unit", "nm", "--json")
            try:
                got = stiction.topography(a, pixel_size="1 um", height_unit="nm").to_dict()
                assert code == 0, (i, err)
                got["file"] = str(path)
                assert got == json.loads(out)
            except stiction.StictionError as e:
                assert code == 2, (i, out[:200])
                assert _cli_message(err).replace(str(path), "heights") == str(e), i
            counts["compared"] += 1
    assert counts["refused"] > 10 and counts["ok"] > 10 and counts["compared"] > 10, counts


def test_non_arrays_are_refused_as_stiction_errors():
    for bad in (None, "heights", [[1, 2], [3]], {"a": 1}, [[float("nan")] * 3] * 3):
        with pytest.raises(stiction.StictionError):
            stiction.topography(bad, pixel_size="1 um", height_unit="nm")


# Relative humidities as a caller might give them: numbers in and out of [0, 1), NaN, infinities,
# the command line's --rh texts (good and bad), and other types.
RH_ATOMS = [
    0.0, 0.35, 0.9, 0.999999, 1.0, -0.1, -0.0, 1e-300, 1e300, float("nan"), float("inf"), 2, True, None,
    "0.35", "35 %", "0:0.6:3", "0.2,0.5", "0.5,0.2", "1.5", "nan", "0:0.5:0", "0:0.5:2000", "", "x", "μ",
    [], [0.1, 0.2], [0.2, 0.1], [[0.1]], {"a": 1}, np.array([0.1, np.nan]), np.array([0.3], dtype=np.float32),
    np.array([1, 2], dtype=np.int8), np.array(["0.1"]), np.zeros((2, 2)),
]

# Generator arguments of bem: sizes, grids, exponents and seeds in and out of range, other types.
GENERATOR = {
    "grid": [0, 1, 2, 3, 8, 32, 4097, -1, 2.5, "8", True, 2**70],
    "hurst": [0.0, 0.5, 1.0, 1.5, -0.5, float("nan"), float("inf"), 1e-300, "x"],
    "size": ["10 um", "-1 um", 0.0, 1e300, 1e-300, "nan um", "5 kg", float("inf")],
    "rms_height": ["0.1 um", "0 um", 1e300, -1.0, 1e-300],
    "roll_off": ["2 um", 1e-300, 1e300, "-2 um"],
    "short": ["1 um", 1e-300, 1e300],
    "seed": [0, 1, -1, 2**64, 2**70, 2.5],
}
# The face's boundary, tilt and hardness cap (with rh refused; a tilt on the periodic cell
# refused), each given in one case in eight.
FACE = {
    "boundary": ["periodic", "non_periodic", "non-periodic", "sideways", "", 3],
    "tilt": [True, False, 1, "yes"],
    "hardness": ["9 GPa", "1 kPa", 1e30, -1.0, 0.0, float("nan"), "5 kg", "1e-300 Pa"],
}


def _check(call, counts, case):
    """A result with every number finite, or a StictionError (TypeError for a count of another
    type) with a short message."""
    try:
        r = call()
        assert _finite(r.to_dict()), case
        counts["ok"] += 1
    except (stiction.StictionError, TypeError) as e:
        counts["refused"] += 1
        assert 0 < len(str(e)) < 2000, (case, str(e)[:300])
        return str(e)
    return None


def test_hostile_rh_and_generator_arguments_raise_stiction_errors(in_root, cli):
    """humidity(rh=...) and bem(rh=..., generator arguments) with seeded hostile values: a result
    with finite numbers or a StictionError (the CLI's message for a --rh text), never another
    exception, a panic or a hang."""
    rng = np.random.default_rng(SEED)
    counts = {"ok": 0, "refused": 0, "compared": 0}
    for case in range(CASES):
        k = int(rng.integers(3))
        rh = RH_ATOMS[int(rng.integers(len(RH_ATOMS)))] if k == 0 else [
            RH_ATOMS[int(rng.integers(len(RH_ATOMS)))] for _ in range(k)
        ]
        start = time.perf_counter()
        message = _check(lambda: stiction.humidity(TAS, rh=rh), counts, case)
        if isinstance(rh, str) and message is not None and case % 3 == 0:
            code, _, err = cli("plot", "humidity", "--scenario", TAS, "--rh", rh, "--json")
            assert code == 2 and python_names(_cli_message(err), ["rh"]) == message, (case, rh, err)
            counts["compared"] += 1
        kwargs = {name: values[int(rng.integers(len(values)))] for name, values in GENERATOR.items()
                  if rng.random() < 0.4}
        kwargs.setdefault("grid", 32)
        kwargs.update({name: values[int(rng.integers(len(values)))] for name, values in FACE.items()
                       if rng.random() < 0.125})
        if rng.random() < 0.5:
            kwargs["rh"] = rh
        else:
            kwargs["pressure"] = "5 MPa"
        _check(lambda: stiction.bem(**kwargs), counts, (case, kwargs))
        assert time.perf_counter() - start < 30, (case, rh, kwargs)
    assert counts["ok"] > 10 and counts["refused"] > CASES // 4 and counts["compared"] > 0, counts


# Hostile counts and sizes (issue 33): integers out of range, past 2^63 and 2^64, bools, floats,
# strings; vectors of lengths around each of the command line's limits (zero-stride views: free
# to make, costly to read). Each call succeeds with finite numbers or raises StictionError,
# ValueError or TypeError naming the argument, in under 2000 characters, with little memory
# allocated; never MemoryError, OverflowError or a panic.
LIMITS = stiction._stiction._limits()
COUNTS = [-1, -(2**63), 2**31, 2**32, 2**63 - 1, 2**63, 2**64, 2**64 + 1, 2**200, True, False, np.True_, 0.0, 2.0,
          2.5, float("nan"), float("inf"), "3", "x", [2], np.int64(-5), np.uint64(2**63), np.float64(3.0)]
FIT = "scenarios/tas2000-fit-synthetic.json"


def _lengths(limit):
    return [0, 1, 2, 3, limit - 1 if limit < 5000 else 7, limit, limit + 1, 2 * limit + 3, 10**7 + 1]


def _view(n, value):
    return np.broadcast_to(np.float64(value), (n,))


def _hostile_calls(rng):
    """(argument name, call) pairs, seeded."""
    sweep, pressures, rh = LIMITS["max_sweep_steps"], LIMITS["bem_max_path_steps"], LIMITS["max_rh"]
    pick = lambda values: values[int(rng.integers(len(values)))]  # noqa: E731
    small = [1, 2, 3]
    yield "samples", lambda v=pick(COUNTS + small + [LIMITS["max_samples"] + 1]): stiction.study(
        TAS, samples=v, threads=1, as_pandas=False)
    yield "seed", lambda v=pick(COUNTS + small): stiction.study(TAS, samples=2, seed=v, threads=1, as_pandas=False)
    yield "threads", lambda v=pick(COUNTS + [0, 1, 2, LIMITS["max_threads"] + 1]): stiction.study(
        TAS, samples=2, threads=v, as_pandas=False)
    n = pick([k for k in _lengths(sweep) if k <= 3 or k > sweep])
    yield "load", lambda n=n: stiction.contact(TAS, load=_view(n, 1e-6), mode="flat")
    yield "max_sweep_steps", lambda v=pick(COUNTS + small): stiction.contact(TAS, load=[1e-6, 2e-6], max_sweep_steps=v)
    yield "contacts", lambda v=pick(COUNTS + small): stiction.contact(TAS, "1 uN", mode="fixed", contacts=v)
    n = pick([k for k in _lengths(pressures) if k <= 3 or k > pressures])
    yield "pressure", lambda n=n: stiction.bem(pressure=_view(n, 1e6), grid=16)
    yield "grid", lambda v=pick(COUNTS + [0, 1, 16, 32, LIMITS["bem_max_grid_side"] + 1]): stiction.bem(
        pressure="1 MPa", grid=v)
    yield "seed", lambda v=pick(COUNTS + small): stiction.bem(pressure="1 MPa", grid=16, seed=v)
    n = pick([k for k in _lengths(rh) if k <= 3 or k > rh])
    yield "rh", lambda n=n: stiction.bem(grid=16, rh=_view(n, 0.4))
    n = pick([k for k in _lengths(rh) if k <= 2 or k > rh])  # one meter run per humidity
    yield "rh", lambda n=n: stiction.humidity(TAS, rh=_view(n, 0.4))
    n = pick([k for k in _lengths(sweep) if k <= 3 or k > sweep])
    yield "load_star", lambda n=n: stiction.gw(2.0, _view(n, 0.5))
    args = ("0.5 um", "0.1 J/m^2", "9.1e-12 1/Pa", "1.4 GPa")
    n = pick([k for k in _lengths(sweep) if k <= 3 or k > sweep])
    yield "load", lambda n=n: stiction.discrete(3, *args, load=_view(n, 1e-6))
    yield "load", lambda n=n: stiction.asperity(*args, load=_view(n, 1e-6))
    yield "contacts", lambda v=pick(COUNTS + small): stiction.discrete(v, *args, load="1 uN")
    quick = dict(models="discrete-n1", draws=20)
    yield "surfaces", lambda v=pick(COUNTS + small + [0, LIMITS["fit_max_surfaces"] + 1]): stiction.fit(
        None, FIT, **{**quick, "surfaces": v})
    yield "draws", lambda v=pick(COUNTS + small + [0, LIMITS["fit_max_draws"] + 1]): stiction.fit(
        None, FIT, models="discrete-n1", draws=v)
    yield "seed", lambda v=pick(COUNTS + small): stiction.fit(None, FIT, **{**quick, "seed": v})
    n = pick([1, 2, LIMITS["fit_max_rows"] + 1, 10**8])
    yield "data", lambda n=n: stiction.fit({"v_clamp_v": _view(n, 20.0), "v_pull_v": _view(n, 30.0)}, FIT, **quick)


def test_hostile_counts_and_sizes_name_the_argument(in_root):
    import re
    import tracemalloc

    rng = np.random.default_rng(SEED)
    counts = {"ok": 0, "refused": 0}
    rounds = max(1, CASES // 15)
    for case in range(rounds):
        for name, call in _hostile_calls(rng):
            tracemalloc.start()
            stiction._stiction._reset_heap_peak()
            before = stiction._stiction._heap()[0]
            try:
                r = call()
                if isinstance(r, stiction.Result):
                    assert _finite(r.to_dict()), (case, name)
                counts["ok"] += 1
            except (ValueError, TypeError) as e:  # StictionError is a ValueError
                counts["refused"] += 1
                message = str(e)
                assert 0 < len(message) < 2000, (case, name, message[:300])
                assert re.search(rf"(?<![\w-]){name}(?!\w)", message), (case, name, message)
                assert not re.search(r"(?<![\w-])--[a-z]", message), (case, name, message)
                # A refusal costs little: nothing read, copied or solved past the limit.
                rust = stiction._stiction._heap()[1] - before
                python = tracemalloc.get_traced_memory()[1]
                assert rust < 64 << 20 and python < 64 << 20, (case, name, rust, python, message)
            finally:
                tracemalloc.stop()
    assert counts["ok"] > rounds and counts["refused"] > rounds, counts
