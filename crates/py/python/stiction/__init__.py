"""stiction: a virtual MEMS friction meter (static friction in elastic adhesive MEMS contacts).

The engine is the one of the ``stiction`` command line: ``run``, ``topography`` and ``study``
return the numbers ``stiction run|topography|study ... --json`` prints, bit for bit. Quantities
are SI floats inside; arguments that are quantities also take unit strings ("0.5 um", "1.4 GPa").

    >>> import stiction
    >>> r = stiction.run("scenarios/tas2000.json")
    >>> r.mu_apparent, r.apparent_adhesion_force_n
"""

from __future__ import annotations

import csv as _csv
import io as _io
import json as _json
import os as _os
from typing import Any, Callable, Dict, Optional, Sequence, Union

import numpy as _np

from ._stiction import Scenario, StictionError
from . import _stiction

__all__ = [
    "Scenario", "StictionError", "Result", "run", "topography", "study", "gw", "discrete", "asperity",
    "contact", "bem", "fit", "humidity", "PathOrScenario", "Quantity", "Loads", "Heights", "Humidities",
]

Quantity = Union[str, float, None]
"""A quantity argument: a unit string ("0.5 um", "20 MPa") or an SI float (None: the default)."""
Loads = Union[str, float, Sequence[float], _np.ndarray]
"""Loads: one force ("3 uN" or N) or a vector of them (N)."""
Heights = _np.ndarray
"""A height map: a 2-D NumPy array of float32 or float64, rows = y, any order or strides."""
Humidities = Union[str, float, Sequence[float], _np.ndarray]
"""Relative humidities: fractions in [0, 1) as a list or array, or the command line's ``--rh``
text (a list "0.1,35 %" or "FROM:TO:STEPS")."""

PathOrScenario = Union[str, "_os.PathLike[str]", Scenario, Dict[str, Any]]
"""A scenario argument: a path to a scenario file, a ``Scenario``, or a dict shaped as the file
(as ``Scenario.from_dict(d)``: relative paths in a dict, such as a height map or a measured CSV,
are read from the current directory; a file's relative paths from the file's folder)."""


class Result:
    """A result: the JSON object the command line prints with ``--json``, with its keys as
    attributes (``r.mu_apparent``), ``to_dict()`` (equal to that JSON) and ``to_json()``.

    ``columns`` holds the per-point columns as NumPy arrays (float64; None/null becomes NaN,
    booleans stay bool) where the result has a list of points (made on first use).
    """

    def __init__(self, data: Union[str, Dict[str, Any], "_stiction.Json"], extra: Optional[Dict[str, Any]] = None):
        # The engine hands over its JSON object (a field becomes Python objects, the same f64s,
        # when it is first read); a JSON text is parsed, a dict taken as it is.
        if isinstance(data, str):
            data = _json.loads(data)
        self._json = data if isinstance(data, _stiction.Json) else None
        self._data: Dict[str, Any] = {} if self._json is not None else data
        self._keys = self._json.keys() if self._json is not None else list(data)
        self._extra = extra or {}
        self._columns: Optional[Dict[str, _np.ndarray]] = None

    def _field(self, name: str) -> Any:
        if name not in self._data:
            if self._json is None or name not in self._keys:
                raise KeyError(name)
            self._data[name] = self._json.get(name)
        return self._data[name]

    @property
    def columns(self) -> Dict[str, _np.ndarray]:
        """The per-point columns as NumPy arrays (float64 with null as NaN, or bool)."""
        if self._columns is None:
            points = self._field("points") if "points" in self._keys else None
            self._columns = _columns(points) if isinstance(points, list) else {}
        return self._columns

    def __getattr__(self, name: str) -> Any:
        if name.startswith("_"):
            raise AttributeError(name)
        if name in self._extra:
            return self._extra[name]
        try:
            return self._field(name)
        except KeyError:
            raise AttributeError(f"result has no field {name!r}; fields: {sorted(self._keys)}") from None

    def __getitem__(self, key: str) -> Any:
        return self._field(key)

    def keys(self):
        """The fields of the JSON object."""
        return dict.fromkeys(self._keys).keys()

    def to_dict(self) -> Dict[str, Any]:
        """The JSON object as a dict (a fresh copy): equals ``json.loads`` of the CLI's ``--json``."""
        if self._json is not None:
            return self._json.to_py()
        return _json.loads(self.to_json())

    def to_json(self) -> str:
        """The JSON object as compact text (the CLI prints it indented: same values)."""
        if self._json is not None:
            return self._json.to_json()
        return _json.dumps(self._data, separators=(",", ":"))

    def __dir__(self):
        return sorted(set(super().__dir__()) | set(self._keys) | set(self._extra))

    def __repr__(self) -> str:
        return f"stiction.Result({', '.join(sorted(self._keys))})"


def _columns(points: list) -> Dict[str, _np.ndarray]:
    """Per-point columns: numbers (null as NaN) as float64, booleans as bool."""
    cols: Dict[str, _np.ndarray] = {}
    if not points or not isinstance(points[0], dict):
        return cols
    keys: Dict[str, None] = {}
    for p in points:
        if isinstance(p, dict):
            keys.update(dict.fromkeys(p))
    for key in keys:
        values = [p.get(key) if isinstance(p, dict) else None for p in points]
        if all(isinstance(v, bool) or v is None for v in values) and any(isinstance(v, bool) for v in values):
            if all(isinstance(v, bool) for v in values):
                cols[key] = _np.array(values, dtype=bool)
        elif all(isinstance(v, (int, float)) and not isinstance(v, bool) or v is None for v in values):
            cols[key] = _np.array([_np.nan if v is None else v for v in values], dtype=float)
    return cols


def run(scenario: PathOrScenario, progress: Optional[Callable[[int, int], Any]] = None) -> Result:
    """Run the friction-meter experiment of a scenario (the paper's Fig. 5): clamp at each clamp
    voltage, ramp the pull voltage until slip, fit eq. 10 (F_f = mu_e,a (L + F_a0)).

    scenario: a path to a scenario JSON file, a ``Scenario``, or a dict shaped as the file (its
    relative paths read from the current directory).
    progress: optional ``progress(done, total)`` called after each clamp voltage.

    Returns a ``Result`` equal to ``stiction run SCENARIO --json``: ``mu_apparent`` (mu_e,a,
    dimensionless), ``apparent_adhesion_force_n`` (F_a0, N), ``points`` (per clamp voltage: loads in
    N, voltages in V, areas in m^2), ... and ``columns`` (the points as NumPy arrays).
    Raises StictionError with the command line's message on bad input. Releases the GIL.
    """
    return Result(_stiction.run_json(scenario, progress))


def topography(
    heights: Union[_np.ndarray, str, "_os.PathLike[str]"],
    pixel_size: Union[str, float, None] = None,
    pixel_size_y: Union[str, float, None] = None,
    height_unit: Union[str, float, None] = None,
    level: str = "plane",
    cutoff: Union[str, float, None] = None,
    long_cutoff: Union[str, float, None] = None,
    scenario: Optional[PathOrScenario] = None,
    channel: Union[str, int, None] = None,
) -> Result:
    """Analyse a measured height map given as a 2-D NumPy array (rows = y), float32 or float64,
    C or Fortran order, or as a file in any format stiction reads (a path: read by ``read_map``,
    with ``channel`` and, for a file that lacks them, ``pixel_size`` and ``height_unit``):
    levelling, cut-offs, summits (8-neighbour maxima, curvature -(z_xx + z_yy)/2) and statistics
    beside Nayak's predictions, as ``stiction topography FILE --json`` with the same flags.

    pixel_size, pixel_size_y: pixel size, a length ("3.90625 um") or metres.
    height_unit: the unit of the array's numbers ("nm", "um", "mm") or metres per unit (1e-9).
    level: "none", "mean", "plane", "poly2" or "poly3".
    cutoff, long_cutoff: short- and long-wavelength Gaussian cut-offs, lengths or metres.
    scenario: a scenario (file, ``Scenario`` or dict) whose material gives the adhesion parameter
    theta (eq. 9) with the map's summit height SD and mean radius.

    Returns a ``Result`` whose ``to_dict()`` equals the CLI's JSON (its ``file`` field is
    "<array>") and whose ``summits`` is a dict of arrays: x_m, y_m (pixel centres, m), height_m (m),
    curvature_per_m (1/m), radius_m (m), ix, iy (pixel indices). Releases the GIL.
    """
    extra: Dict[str, Any] = {}
    if isinstance(heights, (str, _os.PathLike)):
        # A file: its channel in metres with the file's pixel sizes (the file's values win; a
        # value the file lacks comes from the arguments, as on the command line).
        if pixel_size_y is not None:
            raise StictionError("pixel_size_y: a file states its own pixel sizes; give pixel_size only when it lacks them")
        heights, meta = read_map(heights, channel=channel, pixel_size=pixel_size,
                                 height_unit=None if height_unit is None else str(height_unit))
        pixel_size, pixel_size_y, height_unit = meta["pixel_size_x_m"], meta["pixel_size_y_m"], 1.0
        extra["read"] = meta
    elif channel is not None:
        raise StictionError("channel: only a file has channels; heights is an array")
    data, summits = _stiction.topography_json(
        _heights(heights), pixel_size, pixel_size_y, height_unit, level, cutoff, long_cutoff,
        scenario,
    )
    extra["summits"] = summits
    return Result(data, extra)


def read_map(
    path: Union[str, "_os.PathLike[str]"],
    channel: Union[str, int, None] = None,
    format: Optional[str] = None,
    pixel_size: Union[str, float, None] = None,
    height_unit: Optional[str] = None,
) -> tuple:
    """Read a height-map file in any format stiction reads (instrument files by their content:
    NanoScope, Igor, X3P, SDF, Digital Surf, Wyko, Sensofar, MetroPro, Nanosurf, WSxM, PicoView,
    Alicona, Park TIFF, netCDF; or npy, gsf, text, xyz) as ``stiction topography FILE`` reads it.

    channel: an instrument file's channel, its index or its name; default: the first height
    channel. pixel_size, height_unit: only for a file that lacks them (a length or metres; a
    length unit such as "nm").

    Returns ``(heights, metadata)``: heights a (ny, nx) float64 array in metres, rows = y, NaN
    where a pixel is missing (handed over without a copy); metadata a dict with ``nx``, ``ny``,
    ``pixel_size_x_m``, ``pixel_size_y_m``, ``unit`` ("m"), ``file_height_unit_m``,
    ``missing_pixels``, ``format``, ``channel`` (index, name, of, chosen) and ``channels`` (the
    file's channel list).
    """
    if pixel_size is not None and not isinstance(pixel_size, str):
        pixel_size = f"{float(pixel_size)!r} m"
    heights, meta = _stiction._read_map(
        _os.fspath(path), format, None if channel is None else str(channel), pixel_size, height_unit
    )
    return heights, _json.loads(meta)


def study(
    scenario: PathOrScenario,
    samples: int = 100,
    seed: int = 1,
    threads: Optional[int] = None,
    fixed_surface: bool = False,
    progress: Optional[Callable[[int, int], Any]] = None,
    as_pandas: Optional[bool] = None,
) -> Result:
    """Monte Carlo study of a scenario (a file, a ``Scenario``, or a dict shaped as the file whose
    relative paths are read from the current directory):
    every parameter written with an uncertainty is drawn anew and each sample gets its own rough
    surface (unless fixed_surface); the spread of mu_e,a (dimensionless) and F_a0 (N) of eq. 10.

    Equals ``stiction study SCENARIO --samples N --seed S --threads T --json``: same seed, same
    numbers whatever ``threads`` (default: one worker per core). The command line's limits:
    samples 1 to 10^7 (``STICTION_MAX_SAMPLES`` raises it), threads 1 to 1024, seed 0 to 2^64 - 1;
    a bad count raises before any work, naming the argument (TypeError for a bool or a float).

    progress: optional ``progress(done, total)`` called as samples finish (from a worker thread).
    as_pandas: ``samples`` as a pandas DataFrame (default: when pandas is installed) or a dict of
    NumPy arrays (False).

    Returns a ``Result`` whose ``to_dict()`` equals the CLI's JSON, and ``samples``: one row per
    sample, the columns of ``stiction study --out``'s samples.csv (sample, mu_apparent,
    apparent_adhesion_force_n in N, mean_contacts, each drawn parameter in SI, reason, detail;
    a value a sample could not compute is NaN with its reason). Releases the GIL; Ctrl-C stops
    the study (KeyboardInterrupt; the samples in flight finish in the background).
    """
    data, csv_text = _stiction.study_json(scenario, samples, seed, threads, fixed_surface, progress)
    return Result(data, {"samples": _samples(csv_text, as_pandas)})


def _samples(csv_text: str, as_pandas: Optional[bool]):
    """The samples CSV as a dict of arrays (numbers as float64, empty as NaN; index as int64;
    text columns as str arrays), or a pandas DataFrame of the same columns."""
    rows = list(_csv.reader(_io.StringIO(csv_text)))
    names = rows[0] if rows else []
    body = rows[1:]
    cols: Dict[str, _np.ndarray] = {}
    for k, name in enumerate(names):
        values = [r[k] if k < len(r) else "" for r in body]
        if name in ("index", "sample"):
            cols[name] = _np.array([int(v) for v in values], dtype=_np.int64)
            continue
        try:
            cols[name] = _np.array([float(v) if v != "" else _np.nan for v in values], dtype=float)
        except ValueError:
            cols[name] = _np.array(values, dtype=str)
        if name in ("reason", "detail"):
            cols[name] = _np.array(values, dtype=str)
    if as_pandas is False:
        return cols
    try:
        import pandas as _pd
    except ImportError:
        if as_pandas:
            raise
        return cols
    return _pd.DataFrame(cols, columns=names)


def gw(theta: Optional[float], load_star) -> Dict[str, Any]:
    """Greenwood-Williamson with DMT adhesion in normalized form (eq. 5-9), stable branch.

    theta: the adhesion parameter (eq. 9), or None / inf for plain GW (no adhesion).
    load_star: normalized loads L* = D L / (eta A_a R^1/2 sigma^3/2), a number or an array.

    Returns a dict of float64 arrays (one value per load): l_star, h (separation d/sigma), n_star,
    log10_n_star, a_star, log10_a_star, elastic_l_star, adhesive_l_star, elastic_pressure_star; and
    theta, pull_off_l_star, pull_off_h (None without adhesion). Same numbers as ``stiction gw
    --json``.
    """
    if isinstance(load_star, (int, float)) and not isinstance(load_star, bool):
        loads = [float(load_star)]  # one load: no array round trip
    else:
        loads = load_star  # counted (at most max_sweep_steps loads), then read, by the engine
    return _stiction.gw_arrays(_theta(theta), loads)


def _theta(theta) -> Optional[float]:
    """The adhesion parameter as a float (None: plain GW); a bool or a non-number raises
    TypeError naming theta (its range is the engine's check, which names it too)."""
    if theta is None:
        return None
    if isinstance(theta, (bool, _np.bool_)):
        raise TypeError(f"theta={theta!r}: expected an adhesion parameter > 0, inf or None, got a bool")
    try:
        return float(theta)
    except (TypeError, ValueError):
        text = repr(theta)
        text = text if len(text) <= 60 else text[:40] + f"...({len(text)} characters)"
        raise TypeError(
            f"theta={text}: expected an adhesion parameter > 0, inf or None, got {type(theta).__name__}"
        ) from None


def discrete(
    contacts: int,
    radius: Union[str, float],
    work_of_adhesion: Union[str, float],
    compliance: Union[str, float],
    shear_strength: Union[str, float],
    load,
    adhesion: str = "dmt",
    equilibrium_spacing: Union[str, float, None] = None,
    target_slope: Optional[float] = None,
) -> Dict[str, Any]:
    """The discrete N-contact model (eq. 12): N equally loaded summits, F_f = s N pi a^2 with the
    contact radius a from the single-asperity law at L/N.

    contacts: N. radius: summit radius R (length, "0.5 um" or m). work_of_adhesion: dgamma
    ("0.1 J/m^2" or J/m^2). compliance: D = 3/4 ((1-nu1^2)/E1 + (1-nu2^2)/E2) ("9.1e-12 1/Pa").
    shear_strength: s ("1.4 GPa" or Pa). load: L, a force ("3 uN" or N) or an array of them.
    adhesion: "dmt" (the paper's), "jkr", "maugis-dugdale" or "hertz". equilibrium_spacing: z0
    (default "0.3 nm"). target_slope: also the shear strength giving this slope at each load.

    Returns a dict: the fields of ``stiction discrete ... --json`` (one CLI call per load), numbers
    as float64 arrays over the loads (null as NaN: friction_slope is null where the contact radius
    is 0), and ``points``, the list of the CLI's objects, equal to its JSON.
    """
    # A vector is handed over as it is (an array flat, a view), counted before it is read.
    if isinstance(load, _np.ndarray) and load.ndim >= 1:
        loads = load  # counted by its size, then read flat, by the engine (no copy before)
    elif _is_vector(load):
        loads = load
    else:
        loads = [load]
    points = _stiction.discrete_json(
        contacts, radius, work_of_adhesion, compliance, shear_strength, loads, adhesion,
        equilibrium_spacing, target_slope,
    )
    out: Dict[str, Any] = dict(_columns(points))
    out["points"] = points
    return out


def asperity(
    radius: Union[str, float],
    work_of_adhesion: Union[str, float],
    compliance: Union[str, float],
    shear_strength: Union[str, float],
    load,
    adhesion: str = "dmt",
    equilibrium_spacing: Union[str, float, None] = None,
) -> Dict[str, Any]:
    """One spherical asperity: the single-asperity laws (DMT, the paper's; JKR; Maugis-Dugdale;
    Hertz) at each load, as ``stiction discrete --contacts 1`` (see ``discrete`` for the
    arguments and the returned dict: contact radius in m, area in m^2, friction s pi a^2 in N)."""
    return discrete(1, radius, work_of_adhesion, compliance, shear_strength, load, adhesion, equilibrium_spacing)


def _is_vector(x) -> bool:
    # A list or a tuple without converting it (np.ndim would copy a list of a million floats
    # before the engine counts it); anything else by its dimensions.
    if isinstance(x, (list, tuple)):
        return True
    return not isinstance(x, (str, bytes, int, float)) and x is not None and _np.ndim(x) >= 1


def _heights(heights):
    """A NumPy array as it is (never copied: the engine reads it in place, any order or
    strides); anything else (nested lists) as a float64 array."""
    if isinstance(heights, _np.ndarray):
        return heights
    try:
        return _np.asarray(heights, dtype=float)
    except (TypeError, ValueError) as e:
        raise StictionError(
            f"heights: expected a 2-D NumPy array of float32 or float64 (rows = y), got {type(heights).__name__} ({e})"
        ) from None


def contact(
    scenario: PathOrScenario,
    load=None,
    mode: Optional[str] = None,
    contacts: Optional[int] = None,
    summits: bool = False,
    model: Optional[str] = None,
    max_sweep_steps: Optional[int] = None,
) -> Result:
    """The explicit asperity-by-asperity solver on the scenario's surface (rigid shoe, summits
    from the scenario, its contact law), as ``stiction contact SCENARIO --json``; with
    model="bem", the boundary-element model of the height-map patch under the shoe (the scenario's
    ``surface.source`` "height_map", settings from ``contact.bem``), as ``stiction contact SCENARIO
    --model bem --json``: ``model``, ``grid``, ``coarsening``, ``e_star_pa``, ``dugdale``,
    ``shear_strength_pa`` and ``points`` (per load, on the loading branch: load_n N, real_area_m2
    m^2, contact_fraction, patches, mean_gap_m m, adhesive_load_n N, friction_capacity_n N,
    max_pressure_pa Pa, ...; compressive loads > 0 only).

    load: the normal load, compressive positive, a force ("3 uN") or N, for one equilibrium; or a
    vector of loads (N, in order, each from the previous equilibrium) for a sweep, whose result
    has ``points`` (one equilibrium per load, also as NumPy ``columns``) and ``events`` (jump_in,
    release, pull_off). At most ``max_sweep_steps`` loads (default 1,000,000, the command line's
    ``--max-sweep-steps``), counted before any is read.
    mode: "tilt", "flat" or "fixed" (default: the scenario's). contacts: N for mode "fixed".
    summits: list every summit in contact. model: "explicit" (default) or "bem"; mode, contacts
    and summits belong to the explicit solver.

    scenario: a file, a ``Scenario``, or a dict shaped as the file (its relative paths read from
    the current directory). Equilibrium fields are SI
    (load_n N, separation_m m, tilt_x_rad rad, real_area_m2 m^2, max_pressure_pa Pa, ...).
    Releases the GIL; Ctrl-C raises KeyboardInterrupt.
    """
    if load is None:
        raise StictionError("contact: give a load (a force) or a vector of loads")
    if contacts is not None:
        contacts = _stiction._count("contacts", contacts, 1, None, "summits carrying the shoe in mode 'fixed'")
    if _is_vector(load):
        # The vector as it is: counted against max_sweep_steps, then read, by the engine.
        return Result(_stiction.contact_json(scenario, None, load, mode, contacts, bool(summits), model, max_sweep_steps))
    return Result(_stiction.contact_json(scenario, load, None, mode, contacts, bool(summits), model, max_sweep_steps))


def bem(
    heights=None,
    pressure=None,
    pixel_size: Union[str, float, None] = None,
    pixel_size_y: Union[str, float, None] = None,
    height_unit: Union[str, float, None] = None,
    level: str = "plane",
    cutoff: Union[str, float, None] = None,
    long_cutoff: Union[str, float, None] = None,
    e_star: Union[str, float, None] = None,
    sweep: Optional[str] = None,
    gap_sweep: Optional[str] = None,
    gap_back: bool = False,
    work_of_adhesion: Union[str, float, None] = None,
    range: Union[str, float, None] = None,
    shear_strength: Union[str, float, None] = None,
    tolerance: Optional[float] = None,
    compare_asperity: bool = False,
    scenario: Optional[PathOrScenario] = None,
    rh=None,
    temperature: Union[str, float, None] = None,
    contact_angle: Union[str, float, None] = None,
    rh_step: Union[str, float, None] = None,
    min_kelvin_radius: Union[str, float, None] = None,
    size: Union[str, float, None] = None,
    grid: Optional[int] = None,
    hurst: Optional[float] = None,
    roll_off: Union[str, float, None] = None,
    short: Union[str, float, None] = None,
    rms_height: Union[str, float, None] = None,
    seed: Optional[int] = None,
    boundary: Optional[str] = None,
    tilt: bool = False,
    hardness: Union[str, float, None] = None,
) -> Result:
    """FFT boundary-element contact of a rigid flat on the height map ``heights`` (a 2-D NumPy
    array, rows = y, float32 or float64, any order; read in place, as ``topography`` reads it),
    the whole map being one period of the interface: ``stiction bem --map FILE.npy --json`` with
    the same flags (its ``surface.file`` is "<array>").

    pressure: mean (nominal) pressure, compressive, a pressure ("20 MPa") or Pa; or a vector of
    them (Pa, in order, each from the previous state; at most 10,000, the steps of a sweep). Or sweep "FROM:TO:STEPS" of pressures, or
    gap_sweep "FROM:TO:STEPS" of mean gaps (with gap_back, back again), needed with adhesion.
    pixel_size, pixel_size_y, height_unit, level, cutoff, long_cutoff: as for ``topography``.
    e_star: composite modulus E* (Pa; default 85 GPa). work_of_adhesion (J/m^2), range (m): the
    Dugdale law. shear_strength: s (Pa) for the friction s A_r. tolerance: relative, of the
    conjugate gradient (default 1e-6). compare_asperity: also the summit model on the same grid.

    scenario: instead of ``heights``, a scenario (file, ``Scenario`` or dict whose relative paths
    are read from the current directory) with ``surface.source`` "height_map": the patch of its
    face(s) under the shoe, as ``stiction bem --scenario SCENARIO --json`` (E* from its material
    unless e_star is given; the map flags do not apply: the scenario's surface section prepares
    the maps).

    Neither ``heights`` nor ``scenario``: the generated Gaussian self-affine surface of the
    command line (``stiction bem --json``, its default): size, the side of the square periodic
    cell (length; default "100 um"); grid, points per side (2 to 4096; default 256); hurst, the
    Hurst exponent (0 < H <= 1; default 0.8); roll_off, the roll-off wavelength (length; default a
    quarter of the cell); short, the short-wavelength cut-off (length; default 4 pixels);
    rms_height (length; default "0.5 um"); seed (default 1). These apply to the generated surface
    only.

    rh: the adhesion energy against relative humidity instead of a load path (``stiction bem
    --rh``): fractions in [0, 1) as a list or array, or the ``--rh`` text ("0.1,35 %",
    "0.1:0.9:9"). For each RH, a capillary cohesive zone of water and (with work_of_adhesion and
    range) van der Waals; the work of separation of a retraction from the compressed state at
    ``pressure`` (one pressure; default 1 MPa). temperature ("25 C", "298.15 K" or kelvin),
    contact_angle (of water on both faces, "0 deg" or rad), rh_step (the retraction's mean-gap
    step, length), min_kelvin_radius (length: no meniscus condenses below this Kelvin radius;
    default none). The result: surface, grid, e_star_pa, rms_height_m, temperature_k,
    surface_tension_n_per_m, contact_angle_rad, capillary_limit_j_per_m2, van_der_waals,
    start_pressure_pa, tolerance and points (relative_humidity, kelvin_radius_m m,
    meniscus_height_m m, adhesion_energy_j_per_m2 J/m^2, adhesion_energy_mj_per_m2,
    pull_off_pressure_pa Pa, steps).

    boundary: "periodic" (default: the grid is one cell of a periodic interface) or
    "non_periodic" (a finite patch, a rigid face of the grid's size, on a half-space that goes on;
    load control: pressure or sweep, with or without adhesion), as ``--boundary``. tilt: the face
    tilts until its moments balance (non_periodic only; the points get tilt_x_rad, tilt_y_rad,
    pose_solves), as ``--tilt``. hardness: cap the contact pressure at this hardness ("9 GPa" or
    Pa; load control without adhesion, flat face; the points get plastic_fraction,
    plastic_area_m2 m^2, max_plastic_depth_m m), as ``--hardness``.

    Returns a ``Result``: grid, e_star_pa, rms_height_m, rms_slope, points (mean_pressure_pa Pa,
    load_n N, mean_gap_m m, contact_fraction, contact_area_m2 m^2, friction_n N, ...; also as
    NumPy ``columns``), pull_off_n. Releases the GIL; Ctrl-C raises KeyboardInterrupt.
    """
    generator = {
        "size": size, "grid": grid, "hurst": hurst, "roll_off": roll_off, "short": short,
        "rms_height": rms_height, "seed": seed,
    }
    humidity_flags = {
        "temperature": temperature, "contact_angle": contact_angle, "rh_step": rh_step,
        "min_kelvin_radius": min_kelvin_radius,
    }
    given_humidity = [k for k, v in humidity_flags.items() if v is not None]
    if rh is None and given_humidity:
        raise StictionError(f"bem: {', '.join(given_humidity)} apply with rh (the adhesion energy against humidity)")
    rh_text, rh_values = _rh(rh) if rh is not None else (None, None)
    # The keyword arguments given, read one by one into the engine's request (errors name them).
    kw = {
        "pixel_size": pixel_size, "pixel_size_y": pixel_size_y, "height_unit": height_unit, "level": level,
        "cutoff": cutoff, "long_cutoff": long_cutoff, "e_star": e_star, "sweep": sweep, "gap_sweep": gap_sweep,
        "gap_back": bool(gap_back), "work_of_adhesion": work_of_adhesion, "range": range,
        "shear_strength": shear_strength, "tolerance": tolerance, "compare_asperity": bool(compare_asperity),
        "rh": rh_text, "temperature": temperature, "contact_angle": contact_angle, "rh_step": rh_step,
        "min_kelvin_radius": min_kelvin_radius, "boundary": boundary, "tilt": bool(tilt), "hardness": hardness,
    }
    limits = _stiction._limits()
    if grid is not None:
        # Its type and sign here; its range (2 to 4096) by the command line's own check.
        grid = _stiction._count("grid", grid, 0, None, f"points per side, 2 to {limits['bem_max_grid_side']}")
        generator["grid"] = grid
    if seed is not None:
        seed = _stiction._count("seed", seed, 0, 2**64 - 1, "the generator's seed")
        generator["seed"] = seed
    given_generator = [k for k, v in generator.items() if v is not None]
    if (scenario is not None or heights is not None) and given_generator:
        raise StictionError(
            f"bem: {', '.join(given_generator)} make the generated surface; they do not apply to a height map "
            "or a scenario"
        )
    if scenario is not None and heights is not None:
        raise StictionError("bem: give a height map (heights) or a scenario, not both")
    if heights is None:
        map_flags = {
            "pixel_size": pixel_size, "pixel_size_y": pixel_size_y, "height_unit": height_unit,
            "cutoff": cutoff, "long_cutoff": long_cutoff,
        }
        given = [k for k, v in map_flags.items() if v is not None] + (["level"] if level != "plane" else [])
        if given:
            raise StictionError(
                f"bem: {', '.join(given)} prepare a height-map array; "
                + ("with a scenario its surface section prepares the maps" if scenario is not None
                   else "the generated surface (no heights, no scenario) has none")
            )
        del kw["level"]
        if scenario is None:
            kw.update(generator)
        heights_arg = None
    else:
        heights_arg = _heights(heights)
    if _is_vector(pressure):
        # The vector as it is: counted (at most the 10,000 steps of a sweep), then read, by the engine.
        return Result(_stiction.bem_json(heights_arg, kw, pressure, scenario, rh_values))
    kw["pressure"] = pressure
    return Result(_stiction.bem_json(heights_arg, kw, None, scenario, rh_values))


def _rh(rh) -> tuple:
    """Relative humidities as (the --rh text, None) for a string, or (None, a list of floats) for a
    number, a list or a 1-D array; anything else raises StictionError naming rh."""
    if isinstance(rh, str):
        return rh, None
    if isinstance(rh, (bool, _np.bool_)) or rh is None:
        raise StictionError(f"rh: expected fractions in [0, 1) (a list or array) or a text ('0.1,35 %', '0:0.9:10'), got {rh!r}")
    if isinstance(rh, dict):
        raise StictionError("rh: expected fractions in [0, 1) (a list or array) or a text ('0.1,35 %', '0:0.9:10'), got dict")
    # The numbers as they are: counted (at most 1000), then read as a 1-D float64 array, by the engine.
    return None, rh


def humidity(
    scenario: PathOrScenario,
    rh=None,
    progress: Optional[Callable[[int, int], Any]] = None,
) -> Result:
    """The friction meter of a scenario at each relative humidity, the dry point (RH = 0) first:
    ``environment.relative_humidity`` set to each value, every other field as the scenario gives
    it; as ``stiction plot humidity --scenario SCENARIO --rh RH --json``.

    scenario: a path to a scenario file, a ``Scenario``, or a dict shaped as the file (its
    relative paths read from the current directory).
    rh: the humidities, fractions in [0, 1) increasing, as a list or NumPy array, or the
    ``--rh`` text ("0.1,35 %" or "FROM:TO:STEPS"); 0 is put first when they start above it.
    Default "0:0.9:10" (0 to 90 % in ten steps).
    progress: optional ``progress(done, total)`` called after each humidity.

    Returns a ``Result`` equal to the command line's JSON: scenario, description, contact_model,
    temperature_k (K), contact_angle_rad, counter_face_contact_angle_rad (rad), reference (the
    scenario's measured mu_e,a and F_a0 at the humidity of its experiment, or None), warnings, and
    points, one per humidity: relative_humidity, mu_apparent, mu_apparent_se,
    apparent_adhesion_force_n (N), r_squared, adhesive_load_summed_n and capillary_load_summed_n
    (N, summed over the clamp voltages in contact), capillary_share, kelvin_radius_m (m),
    meniscus_height_m (m), reason (why mu_e,a and F_a0 are None at a point); the points also as
    NumPy ``columns``. An error of the dry point is the scenario's and is raised; a humid point
    where the meter fails has None values and a reason. Raises StictionError naming the field on
    bad input. Releases the GIL; Ctrl-C raises KeyboardInterrupt.
    """
    rh_text, rh_values = _rh(rh) if rh is not None else (None, None)
    return Result(_stiction.humidity_json(scenario, rh_text, rh_values, progress))


def fit(
    data,
    scenario: PathOrScenario,
    models: Optional[str] = None,
    free: Optional[str] = None,
    surfaces: Optional[int] = None,
    draws: Optional[int] = None,
    seed: Optional[int] = None,
) -> Result:
    """Fit measured friction-meter voltages: eq. 10 with regression and calibration intervals, and
    the shear strength s (Pa) of each contact model by maximum likelihood, ranked by AIC; as
    ``stiction fit DATA --scenario SCENARIO --json``.

    data: a CSV path (columns v_clamp_v, v_pull_v [, v_pull_sd_v, device]); or the columns as
    arrays: a dict (or pandas DataFrame) with keys v_clamp_v and v_pull_v (V) and optionally
    v_pull_sd_v (V) and device; or None for the scenario's ``measured.voltages_csv``.
    For a scenario with a ``structure`` (docs/fit.md, "Test structures built from parts") the data
    are its measured thresholds: one normal column (v_normal_v in V or normal_load_n in N) and one
    tangential column (v_tangential_v in V, displacement_m in m or tangential_load_n in N), as a
    path or a dict of arrays; the result is eq. 10 on the forces the parts imply, the keys of
    ``stiction fit --json`` for it (models, free and surfaces are refused there).
    scenario: the device's scenario: a file, a ``Scenario``, or a dict shaped as the file (its
    relative paths, such as ``measured.voltages_csv``, read from the current directory). models: "discrete-n1,gw-dmt,explicit,..."; free: "s",
    "s,R", "s,R,F_spring"; surfaces: realisations of the explicit ensemble; draws: calibration
    Monte Carlo draws; seed: its seed (the CLI's defaults when None).
    Releases the GIL; Ctrl-C raises KeyboardInterrupt.
    """
    limits = _stiction._limits()
    if surfaces is not None:
        surfaces = _stiction._count("surfaces", surfaces, 1, limits["fit_max_surfaces"], "realisations of the explicit ensemble")
    if draws is not None:
        draws = _stiction._count("draws", draws, 1, limits["fit_max_draws"], "calibration Monte Carlo draws")
    if seed is not None:
        seed = _stiction._count("seed", seed, 0, 2**64 - 1, "the calibration Monte Carlo's seed")
    options = dict(models=models, free=free, surfaces=surfaces, draws=draws, seed=seed)
    if data is None:
        return Result(_stiction.fit_json(scenario, **options))
    if isinstance(data, (str, _os.PathLike)):
        return Result(_stiction.fit_json(scenario, data_path=_os.fspath(data), **options))
    return Result(_stiction.fit_json(scenario, data_csv=_voltage_csv(data), data_name="<data>", **options))


# The columns of a structure's measured thresholds (stiction_meter::structure_measured).
_THRESHOLD_COLUMNS = ("v_normal_v", "normal_load_n", "v_tangential_v", "displacement_m", "tangential_load_n")


def _voltage_csv(data) -> str:
    """Columns of measured voltages (or of a structure's thresholds) as the CSV text the command
    line reads (floats as ``repr``, which reads back to the same float); the reader checks which
    columns a structure takes, with the command line's messages."""
    try:
        names = [k for k in ("v_clamp_v", "v_pull_v", "v_pull_sd_v", "device") if k in data]
        thresholds = [k for k in _THRESHOLD_COLUMNS if k in data]
    except TypeError:
        raise StictionError("data: expected a CSV path or a dict of arrays with v_clamp_v and v_pull_v") from None
    if thresholds and not names:
        names = thresholds
    for k in ("v_clamp_v", "v_pull_v"):
        if k not in names and not thresholds:
            raise StictionError(f"data: no column {k!r} (expected v_clamp_v, v_pull_v [, v_pull_sd_v, device])")
    # The rows counted before any is converted (the CSV text is some 40 bytes a row): at most the
    # command line's limit of rows.
    max_rows = _stiction._limits()["fit_max_rows"]
    for k in names:
        column = data[k]
        n = column.size if isinstance(column, _np.ndarray) else len(column) if hasattr(column, "__len__") else 0
        if n > max_rows:
            raise StictionError(
                f"data[{k!r}]: {n} rows; `stiction fit` takes at most {max_rows} rows (split the data, e.g. by device)"
            )
    columns = []
    for k in names:
        values = _np.asarray(data[k])
        if values.ndim != 1:
            raise StictionError(f"data[{k!r}]: expected a 1-D array, got {values.ndim} dimensions")
        columns.append(values)
    n = len(columns[0])
    if any(len(c) != n for c in columns):
        raise StictionError("data: the columns differ in length")
    out = _io.StringIO()
    w = _csv.writer(out, lineterminator="\n")
    w.writerow(names)
    for i in range(n):
        w.writerow([
            str(c[i]) if k == "device" else repr(float(c[i])) for k, c in zip(names, columns)
        ])
    return out.getvalue()
