"""Type stubs of the stiction package (quantities SI floats or unit strings; results as the CLI's --json)."""

import os
from typing import Any, Callable, Dict, KeysView, List, Optional, Sequence, Tuple, Union, final

import numpy as np
import numpy.typing as npt

__all__ = [
    "Scenario", "StictionError", "Result", "run", "topography", "study", "gw", "discrete", "asperity",
    "contact", "bem", "fit", "humidity", "PathOrScenario", "Quantity", "Loads", "Heights", "Humidities",
]

class StictionError(ValueError):
    """Bad input or a value that cannot be computed; the message is the command line's."""

@final
class Scenario:
    """A scenario: a file with overrides in order, or a JSON tree built in Python."""
    @staticmethod
    def load(path: Union[str, os.PathLike[str]], sets: Optional[List[str]] = None) -> Scenario: ...
    @staticmethod
    def from_json(text: str, base_dir: Union[str, os.PathLike[str], None] = None) -> Scenario: ...
    @staticmethod
    def from_dict(d: Dict[str, Any], base_dir: Union[str, os.PathLike[str], None] = None) -> Scenario: ...
    def set(self, path: str, value: Union[str, float, int, bool, None, List[Any], Dict[str, Any]]) -> None: ...
    def get(self, path: str) -> Any: ...
    def validate(self) -> List[Tuple[str, str]]: ...
    def to_json(self) -> str: ...
    def to_dict(self) -> Dict[str, Any]: ...
    @property
    def path(self) -> Optional[str]: ...
    @property
    def sets(self) -> List[str]: ...

PathOrScenario = Union[str, os.PathLike[str], Scenario, Dict[str, Any]]
Quantity = Union[str, float, None]

class Result:
    """The CLI's --json object: keys as attributes, to_dict(), to_json(), per-point columns."""
    @property
    def columns(self) -> Dict[str, npt.NDArray[Any]]: ...
    summits: Dict[str, npt.NDArray[Any]]
    """topography: x_m, y_m, height_m, curvature_per_m, radius_m, ix, iy."""
    samples: Any
    """study: a dict of NumPy arrays, or a pandas DataFrame."""
    def __init__(self, data: Union[str, Dict[str, Any], Any], extra: Optional[Dict[str, Any]] = None) -> None: ...
    def __getattr__(self, name: str) -> Any: ...
    def __getitem__(self, key: str) -> Any: ...
    def keys(self) -> KeysView[str]: ...
    def to_dict(self) -> Dict[str, Any]: ...
    def to_json(self) -> str: ...

def run(scenario: PathOrScenario, progress: Optional[Callable[[int, int], Any]] = None) -> Result: ...
def topography(
    heights: Union[npt.NDArray[Union[np.float32, np.float64]], str, "os.PathLike[str]"],
    pixel_size: Quantity = None,
    pixel_size_y: Quantity = None,
    height_unit: Quantity = None,
    level: str = "plane",
    cutoff: Quantity = None,
    long_cutoff: Quantity = None,
    scenario: Optional[PathOrScenario] = None,
    channel: Union[str, int, None] = None,
) -> Result: ...
def read_map(
    path: Union[str, "os.PathLike[str]"],
    channel: Union[str, int, None] = None,
    format: Optional[str] = None,
    pixel_size: Quantity = None,
    height_unit: Optional[str] = None,
) -> Tuple[npt.NDArray[np.float64], Dict[str, Any]]: ...
def study(
    scenario: PathOrScenario,
    samples: int = 100,
    seed: int = 1,
    threads: Optional[int] = None,
    fixed_surface: bool = False,
    progress: Optional[Callable[[int, int], Any]] = None,
    as_pandas: Optional[bool] = None,
) -> Result:
    """Monte Carlo study (mu_e,a dimensionless, F_a0 in N); ``samples``: dict of arrays or a DataFrame."""
def gw(theta: Optional[float], load_star: Union[float, Sequence[float], npt.NDArray[np.float64]]) -> Dict[str, Any]: ...
def discrete(
    contacts: int,
    radius: Union[str, float],
    work_of_adhesion: Union[str, float],
    compliance: Union[str, float],
    shear_strength: Union[str, float],
    load: Union[str, float, Sequence[float], npt.NDArray[np.float64]],
    adhesion: str = "dmt",
    equilibrium_spacing: Quantity = None,
    target_slope: Optional[float] = None,
) -> Dict[str, Any]: ...

Heights = npt.NDArray[Union[np.float32, np.float64]]
Loads = Union[str, float, Sequence[float], npt.NDArray[np.float64]]
Humidities = Union[str, float, Sequence[float], npt.NDArray[np.float64]]

def asperity(
    radius: Union[str, float],
    work_of_adhesion: Union[str, float],
    compliance: Union[str, float],
    shear_strength: Union[str, float],
    load: Loads,
    adhesion: str = "dmt",
    equilibrium_spacing: Quantity = None,
) -> Dict[str, Any]:
    """One asperity (DMT, JKR, Maugis-Dugdale, Hertz): radius m, dgamma J/m^2, D 1/Pa, s Pa, load N."""

def contact(
    scenario: PathOrScenario,
    load: Optional[Loads] = None,
    mode: Optional[str] = None,
    contacts: Optional[int] = None,
    summits: bool = False,
    model: Optional[str] = None,
    max_sweep_steps: Optional[int] = None,
) -> Result:
    """The explicit solver (or model="bem", the boundary-element model) at a load (N) or over a vector of loads
    (at most max_sweep_steps, default 1,000,000)."""

def bem(
    heights: Optional[Heights] = None,
    pressure: Union[str, float, Sequence[float], npt.NDArray[np.float64], None] = None,
    pixel_size: Quantity = None,
    pixel_size_y: Quantity = None,
    height_unit: Quantity = None,
    level: str = "plane",
    cutoff: Quantity = None,
    long_cutoff: Quantity = None,
    e_star: Quantity = None,
    sweep: Optional[str] = None,
    gap_sweep: Optional[str] = None,
    gap_back: bool = False,
    work_of_adhesion: Quantity = None,
    range: Quantity = None,
    shear_strength: Quantity = None,
    tolerance: Optional[float] = None,
    compare_asperity: bool = False,
    scenario: Optional[PathOrScenario] = None,
    rh: Optional[Humidities] = None,
    temperature: Quantity = None,
    contact_angle: Quantity = None,
    rh_step: Quantity = None,
    min_kelvin_radius: Quantity = None,
    size: Quantity = None,
    grid: Optional[int] = None,
    hurst: Optional[float] = None,
    roll_off: Quantity = None,
    short: Quantity = None,
    rms_height: Quantity = None,
    seed: Optional[int] = None,
    boundary: Optional[str] = None,
    tilt: bool = False,
    hardness: Quantity = None,
) -> Result:
    """Boundary-element contact on a height-map array, a scenario's patch or a generated surface;
    pressures in Pa, E* in Pa, lengths in m; with rh, the adhesion energy (J/m^2) against humidity."""

def fit(
    data: Union[str, os.PathLike[str], Dict[str, Any], Any, None],
    scenario: PathOrScenario,
    models: Optional[str] = None,
    free: Optional[str] = None,
    surfaces: Optional[int] = None,
    draws: Optional[int] = None,
    seed: Optional[int] = None,
) -> Result:
    """Fit measured voltages (V): eq. 10 and the shear strength s (Pa) per contact model; for a
    scenario with a `structure`, its measured thresholds: eq. 10 on the forces its parts imply."""

def humidity(
    scenario: PathOrScenario,
    rh: Optional[Humidities] = None,
    progress: Optional[Callable[[int, int], Any]] = None,
) -> Result:
    """The friction meter at each relative humidity (fractions), the dry point first: mu_e,a, F_a0 (N), capillary share."""
