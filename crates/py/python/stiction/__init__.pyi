"""Type stubs of the stiction package (quantities SI floats or unit strings; results as the CLI's --json)."""

import os
from typing import Any, Callable, Dict, KeysView, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

class StictionError(ValueError):
    """Bad input or a value that cannot be computed; the message is the command line's."""

class Scenario:
    """A scenario: a file with overrides in order, or a JSON tree built in Python."""
    @staticmethod
    def load(path: Union[str, os.PathLike[str]], sets: Optional[List[str]] = None) -> Scenario: ...
    @staticmethod
    def from_json(text: str, base_dir: Union[str, os.PathLike[str], None] = None) -> Scenario: ...
    @staticmethod
    def from_dict(d: Dict[str, Any], base_dir: Union[str, os.PathLike[str], None] = None) -> Scenario: ...
    def set(self, path: str, value: Union[str, float, int, bool, None]) -> None: ...
    def validate(self) -> List[Tuple[str, str]]: ...
    def to_json(self) -> str: ...
    def to_dict(self) -> Dict[str, Any]: ...
    @property
    def path(self) -> Optional[str]: ...
    @property
    def sets(self) -> List[str]: ...

PathOrScenario = Union[str, os.PathLike[str], Scenario]
Quantity = Union[str, float, None]

class Result:
    """The CLI's --json object: keys as attributes, to_dict(), to_json(), per-point columns."""
    columns: Dict[str, npt.NDArray[Any]]
    def __getattr__(self, name: str) -> Any: ...
    def __getitem__(self, key: str) -> Any: ...
    def keys(self) -> KeysView[str]: ...
    def to_dict(self) -> Dict[str, Any]: ...
    def to_json(self) -> str: ...

def run(scenario: PathOrScenario, progress: Optional[Callable[[int, int], Any]] = None) -> Result: ...
def topography(
    heights: npt.NDArray[Union[np.float32, np.float64]],
    pixel_size: Quantity = None,
    pixel_size_y: Quantity = None,
    height_unit: Quantity = None,
    level: str = "plane",
    cutoff: Quantity = None,
    long_cutoff: Quantity = None,
    scenario: Union[str, os.PathLike[str], None] = None,
) -> Result: ...
def study(
    scenario: PathOrScenario,
    samples: int = 100,
    seed: int = 1,
    threads: Optional[int] = None,
    fixed_surface: bool = False,
) -> Result: ...
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
