# Type stubs of the compiled module; the documented API is in __init__.py and theory.py.
from typing import Any, Callable, Dict, List, Optional, Tuple

import numpy as np

VERSION: str

class Cancel:
    def __init__(self) -> None: ...
    def set(self) -> None: ...

Roughness = Optional[Tuple[np.ndarray, float, float]]

def solve(
    keys: Dict[str, Any],
    roughness: Roughness,
    threads: Optional[int],
    progress: Optional[Callable[[Dict[str, Any]], None]],
    cancel: Cancel,
) -> Tuple[str, List[Tuple[str, np.ndarray]]]: ...
def sweep(
    keys: Dict[str, Any],
    roughness: Roughness,
    threads: Optional[int],
    progress: Optional[Callable[[Dict[str, Any]], None]],
    cancel: Cancel,
) -> Tuple[str, List[Tuple[str, np.ndarray]]]: ...
def generate(keys: Dict[str, Any]) -> Tuple[np.ndarray, float, float, str]: ...
def read(
    path: str,
    length: Optional[float],
    length_y: Optional[float],
    unit: float,
    periodic: bool,
    channel: Optional[str],
    fill_unmeasured: bool,
) -> Tuple[np.ndarray, float, float, bool]: ...
def channels(path: str, length: Optional[float], length_y: Optional[float], unit: float) -> str: ...
def write(path: str, heights: np.ndarray, length_x: float, length_y: float, periodic: bool) -> None: ...
def statistics(heights: np.ndarray, length_x: float, length_y: float, periodic: bool) -> str: ...
def psd(heights: np.ndarray, length_x: float, length_y: float, bins_per_decade: int) -> str: ...
def read_toml(path: str) -> str: ...
def tabor_parameter(radius: float, work_of_adhesion: float, modulus: float, z0: float) -> float: ...
def hertz(approach: List[float], radius: float, modulus: float) -> Tuple[List[float], List[float], List[float]]: ...
def jkr(
    contact_radius: List[float], radius: float, work_of_adhesion: float, modulus: float
) -> Tuple[List[float], List[float]]: ...
def jkr_pull_off(radius: float, work_of_adhesion: float) -> Tuple[float, float]: ...
def dmt(contact_radius: List[float], radius: float, work_of_adhesion: float, modulus: float) -> Tuple[List[float], float]: ...
def maugis_dugdale(tabor: float, points: int, max_radius: float) -> Dict[str, Any]: ...
def greenwood(tabor: float, max_approach: float, start: float, resolution: float, ring_width: float) -> Dict[str, Any]: ...
def persson_area(reduced_pressure: List[float]) -> List[float]: ...
def muser_area(reduced_pressure: List[float], k: float) -> List[float]: ...
def johnson_parameter(
    work_of_adhesion: float, modulus: float, rms_height: float, q0: float, q1: float, hurst: float
) -> float: ...
def ciavarella(rms_height: float, modulus: float, longest_wavelength: float, work_of_adhesion: float) -> Tuple[float, bool]: ...
def wave(
    half_width: List[float], amplitude: float, wavelength: float, modulus: float, work_of_adhesion: float
) -> Dict[str, Any]: ...
def layer(
    contact_radius: List[float],
    radius: float,
    modulus: float,
    thickness: float,
    poisson: float,
    layer_base: str,
    substrate_modulus: Optional[float],
    substrate_poisson: Optional[float],
    work_of_adhesion: float,
) -> Tuple[List[float], List[float]]: ...
def layer_pull_off(
    radius: float,
    work_of_adhesion: float,
    modulus: float,
    thickness: float,
    poisson: float,
    layer_base: str,
    substrate_modulus: Optional[float],
    substrate_poisson: Optional[float],
) -> Tuple[float, float, float]: ...
def viscoelastic_indentation(
    time: List[float],
    radius: float,
    modulus: float,
    maxwell_moduli: List[float],
    maxwell_times: List[float],
    rate: float,
    rise_time: float,
) -> Tuple[List[float], List[float]]: ...
def viscoelastic_creep(
    time: List[float], radius: float, modulus: float, maxwell_moduli: List[float], maxwell_times: List[float], load: float
) -> List[float]: ...
