"""stiction: a virtual MEMS friction meter (static friction in elastic adhesive MEMS contacts).

The engine is the one of the ``stiction`` command line: ``run``, ``topography`` and ``study``
return the numbers ``stiction run|topography|study ... --json`` prints, bit for bit. Quantities
are SI floats inside; arguments that are quantities also take unit strings ("0.5 um", "1.4 GPa").

    >>> import stiction
    >>> r = stiction.run("scenarios/tas2000.json")
    >>> r.mu_apparent, r.apparent_adhesion_force_n
"""

from __future__ import annotations

import json as _json
import os as _os
from typing import Any, Callable, Dict, Optional, Union

import numpy as _np

from ._stiction import Scenario, StictionError
from . import _stiction

__all__ = ["Scenario", "StictionError", "Result", "run", "topography", "study", "gw", "discrete"]

PathOrScenario = Union[str, "_os.PathLike[str]", Scenario]


class Result:
    """A result: the JSON object the command line prints with ``--json``, with its keys as
    attributes (``r.mu_apparent``), ``to_dict()`` (equal to that JSON) and ``to_json()``.

    ``columns`` holds the per-point columns as NumPy arrays (float64; None/null becomes NaN,
    booleans stay bool) where the result has a list of points.
    """

    def __init__(self, text: str, extra: Optional[Dict[str, Any]] = None):
        self._text = text
        self._data = _json.loads(text)
        self._extra = extra or {}
        points = self._data.get("points") if isinstance(self._data, dict) else None
        self.columns: Dict[str, _np.ndarray] = _columns(points) if isinstance(points, list) else {}

    def __getattr__(self, name: str) -> Any:
        if name.startswith("_"):
            raise AttributeError(name)
        if name in self._extra:
            return self._extra[name]
        try:
            return self._data[name]
        except KeyError:
            raise AttributeError(f"result has no field {name!r}; fields: {sorted(self._data)}") from None

    def __getitem__(self, key: str) -> Any:
        return self._data[key]

    def keys(self):
        """The fields of the JSON object."""
        return self._data.keys()

    def to_dict(self) -> Dict[str, Any]:
        """The JSON object as a dict (a fresh copy): equals ``json.loads`` of the CLI's ``--json``."""
        return _json.loads(self._text)

    def to_json(self) -> str:
        """The JSON object as text (compact; the CLI prints it indented: same values)."""
        return self._text

    def __dir__(self):
        return sorted(set(super().__dir__()) | set(self._data) | set(self._extra))

    def __repr__(self) -> str:
        return f"stiction.Result({', '.join(sorted(self._data))})"


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

    scenario: a path to a scenario JSON file, or a ``Scenario``.
    progress: optional ``progress(done, total)`` called after each clamp voltage.

    Returns a ``Result`` equal to ``stiction run SCENARIO --json``: ``mu_apparent`` (mu_e,a,
    dimensionless), ``apparent_adhesion_force_n`` (F_a0, N), ``points`` (per clamp voltage: loads in
    N, voltages in V, areas in m^2), ... and ``columns`` (the points as NumPy arrays).
    Raises StictionError with the command line's message on bad input. Releases the GIL.
    """
    return Result(_stiction.run_json(scenario, progress))


def topography(
    heights: _np.ndarray,
    pixel_size: Union[str, float, None] = None,
    pixel_size_y: Union[str, float, None] = None,
    height_unit: Union[str, float, None] = None,
    level: str = "plane",
    cutoff: Union[str, float, None] = None,
    long_cutoff: Union[str, float, None] = None,
    scenario: Union[str, "_os.PathLike[str]", None] = None,
) -> Result:
    """Analyse a measured height map given as a 2-D NumPy array (rows = y), float32 or float64,
    C or Fortran order: levelling, cut-offs, summits (8-neighbour maxima, curvature
    -(z_xx + z_yy)/2) and statistics beside Nayak's predictions, as ``stiction topography
    FILE.npy --json`` with the same flags.

    pixel_size, pixel_size_y: pixel size, a length ("3.90625 um") or metres.
    height_unit: the unit of the array's numbers ("nm", "um", "mm") or metres per unit (1e-9).
    level: "none", "mean", "plane", "poly2" or "poly3".
    cutoff, long_cutoff: short- and long-wavelength Gaussian cut-offs, lengths or metres.
    scenario: a scenario file whose material gives the adhesion parameter theta.

    Returns a ``Result`` whose ``to_dict()`` equals the CLI's JSON (its ``file`` field is
    "<array>") and whose ``summits`` is a dict of arrays: x_m, y_m (pixel centres, m), height_m (m),
    curvature_per_m (1/m), radius_m (m), ix, iy (pixel indices). Releases the GIL.
    """
    text, summits = _stiction.topography_json(
        heights, pixel_size, pixel_size_y, height_unit, level, cutoff, long_cutoff,
        None if scenario is None else _os.fspath(scenario),
    )
    return Result(text, {"summits": summits})


def study(
    scenario: PathOrScenario,
    samples: int = 100,
    seed: int = 1,
    threads: Optional[int] = None,
    fixed_surface: bool = False,
) -> Result:
    """Monte Carlo study of a scenario file: every parameter written with an uncertainty is drawn
    anew and each sample gets its own rough surface (unless fixed_surface); the spread of mu_e,a
    and F_a0 (eq. 10). Equals ``stiction study SCENARIO --samples N --seed S --threads T --json``;
    same seed, same numbers whatever ``threads``. Releases the GIL.
    """
    return Result(_stiction.study_json(scenario, samples, seed, threads, fixed_surface))


def gw(theta: Optional[float], load_star) -> Dict[str, Any]:
    """Greenwood-Williamson with DMT adhesion in normalized form (eq. 5-9), stable branch.

    theta: the adhesion parameter (eq. 9), or None / inf for plain GW (no adhesion).
    load_star: normalized loads L* = D L / (eta A_a R^1/2 sigma^3/2), a number or an array.

    Returns a dict of float64 arrays (one value per load): l_star, h (separation d/sigma), n_star,
    log10_n_star, a_star, log10_a_star, elastic_l_star, adhesive_l_star, elastic_pressure_star; and
    theta, pull_off_l_star, pull_off_h (None without adhesion). Same numbers as ``stiction gw
    --json``.
    """
    loads = _np.atleast_1d(_np.asarray(load_star, dtype=float)).ravel()
    return _stiction.gw_arrays(None if theta is None else float(theta), loads.tolist())


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
    loads = load if isinstance(load, str) else _np.atleast_1d(_np.asarray(load, dtype=float)).ravel().tolist()
    if isinstance(loads, str):
        loads = [loads]
    points = _json.loads(
        _stiction.discrete_json(
            contacts, radius, work_of_adhesion, compliance, shear_strength, loads, adhesion,
            equilibrium_spacing, target_slope,
        )
    )
    out: Dict[str, Any] = dict(_columns(points))
    out["points"] = points
    return out
