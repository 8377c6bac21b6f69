"""Reference models for adhesive and rough contact (the ``theory`` crate, as ``roughcontact
theory``). Arrays in, arrays out: an argument named as an array takes a number or any
array-like, and the results have its shape. SI units unless a model says it works in its own
dimensionless units; loads are positive when compressive, approaches when pushing together.
"""

from __future__ import annotations

from typing import Any, Dict, Tuple

import numpy as np

from . import _native

__all__ = [
    "tabor_parameter",
    "hertz",
    "jkr",
    "jkr_pull_off",
    "dmt",
    "dmt_pull_off",
    "maugis_dugdale",
    "greenwood",
    "persson_area",
    "muser_area",
    "johnson_parameter",
    "ciavarella",
    "wave",
]


def _flat(x: Any) -> Tuple[list, Tuple[int, ...]]:
    a = np.asarray(x, dtype=np.float64)
    return a.ravel().tolist(), a.shape


def _shaped(values: list, shape: Tuple[int, ...]) -> np.ndarray:
    return np.asarray(values, dtype=np.float64).reshape(shape)


def tabor_parameter(radius: float, work_of_adhesion: float, modulus: float, z0: float) -> float:
    """Tabor's parameter mu = (R w0^2 / (E*^2 z0^3))^(1/3) of a sphere of radius R [m],
    work of adhesion w0 [J/m^2], modulus E* [Pa] and Lennard-Jones range z0 [m]."""
    return _native.tabor_parameter(radius, work_of_adhesion, modulus, z0)


def hertz(approach: Any, radius: float, modulus: float) -> Dict[str, np.ndarray]:
    """Hertz's sphere at the approaches [m]: ``load`` [N], ``contact_radius`` [m] and
    ``max_pressure`` [Pa]."""
    x, shape = _flat(approach)
    load, a, p0 = _native.hertz(x, radius, modulus)
    return {"load": _shaped(load, shape), "contact_radius": _shaped(a, shape), "max_pressure": _shaped(p0, shape)}


def jkr(contact_radius: Any, radius: float, work_of_adhesion: float, modulus: float) -> Dict[str, np.ndarray]:
    """JKR's sphere at the contact radii [m]: ``load`` [N] and ``approach`` [m]."""
    x, shape = _flat(contact_radius)
    load, approach = _native.jkr(x, radius, work_of_adhesion, modulus)
    return {"load": _shaped(load, shape), "approach": _shaped(approach, shape)}


def jkr_pull_off(radius: float, work_of_adhesion: float) -> Dict[str, float]:
    """JKR's pull-off force [N] (negative: tensile) under load control (-3/2 pi R w0) and
    under displacement control (-5/6 pi R w0)."""
    load, displacement = _native.jkr_pull_off(radius, work_of_adhesion)
    return {"load_control": load, "displacement_control": displacement}


def dmt(contact_radius: Any, radius: float, work_of_adhesion: float, modulus: float) -> np.ndarray:
    """DMT's load [N] at the contact radii [m]."""
    x, shape = _flat(contact_radius)
    load, _ = _native.dmt(x, radius, work_of_adhesion, modulus)
    return _shaped(load, shape)


def dmt_pull_off(radius: float, work_of_adhesion: float) -> float:
    """DMT's pull-off force [N], -2 pi R w0."""
    return _native.dmt([], radius, work_of_adhesion, 1.0)[1]


def maugis_dugdale(tabor: float, points: int = 200, max_radius: float = 3.0) -> Dict[str, Any]:
    """Maugis-Dugdale's sphere at the Tabor parameter mu (Maugis' lambda = 1.157 mu), in
    Maugis' units: contact ``radius`` A = a/(pi w0 R^2/K)^(1/3), ``load`` P = load/(pi w0 R),
    ``approach`` D = approach/(pi^2 w0^2 R/K^2)^(1/3), K = 4E*/3, from A = ``max_radius``
    to separation; ``pull_off_load_control`` and ``pull_off_displacement_control`` [pi R w0];
    ``lambda``."""
    d = _native.maugis_dugdale(tabor, int(points), max_radius)
    for k in ("radius", "load", "approach"):
        d[k] = np.asarray(d[k])
    return d


def greenwood(
    tabor: float,
    max_approach: float = 2.0,
    start: float = 5.0,
    resolution: float = 0.02,
    ring_width: float = 0.02,
) -> Dict[str, Any]:
    """Greenwood's (1997) sphere with the full Lennard-Jones law, traced by its central
    separation from ``start`` [z0] until the approach passes ``max_approach`` [z0] (S-curves
    whole): ``central_separation`` and ``approach`` [z0], ``load`` [2 pi R w0],
    ``contact_radius`` [sqrt(R z0)]; the indices ``jump_in``, ``jump_out`` (or None) and the
    pull-offs [2 pi R w0]."""
    d = _native.greenwood(tabor, max_approach, start, resolution, ring_width)
    for k in ("central_separation", "approach", "load", "contact_radius"):
        d[k] = np.asarray(d[k])
    return d


def persson_area(reduced_pressure: Any) -> np.ndarray:
    """Persson's relative contact area erf(sqrt(2) p/(E* g_bar)) at the reduced pressures
    p/(E* g_bar) [-] (g_bar the RMS gradient)."""
    x, shape = _flat(reduced_pressure)
    return _shaped(_native.persson_area(x), shape)


def muser_area(reduced_pressure: Any, k: float = 2.0) -> np.ndarray:
    """Müser's relative contact area (the paper's Eq. 14, corrected) at the reduced pressures
    p/(E* g_bar) [-], with small-load slope ``k``."""
    x, shape = _flat(reduced_pressure)
    return _shaped(_native.muser_area(x, k), shape)


def johnson_parameter(
    work_of_adhesion: float, modulus: float, rms_height: float, q0: float, q1: float, hurst: float
) -> float:
    """The modified Johnson parameter (Li, Pohrt & Popov 2019; the paper's Eq. 15) of a
    self-affine surface: w0 [J/m^2], E* [Pa], RMS height [m], smallest and largest
    wavevectors q0, q1 [rad/m], Hurst exponent."""
    return _native.johnson_parameter(work_of_adhesion, modulus, rms_height, q0, q1, hurst)


def ciavarella(rms_height: float, modulus: float, longest_wavelength: float, work_of_adhesion: float) -> Dict[str, Any]:
    """Ciavarella's (2019) criterion: the ``variable`` Rq^2 E*/(lambda_L w0) [-] and
    ``sticky`` (variable < 0.6)."""
    variable, sticky = _native.ciavarella(rms_height, modulus, longest_wavelength, work_of_adhesion)
    return {"variable": variable, "sticky": sticky}


def wave(
    half_width: Any, amplitude: float, wavelength: float, modulus: float, work_of_adhesion: float = 0.0
) -> Dict[str, Any]:
    """A rigid wave A cos(2 pi x / lambda) on a half-space (plane strain) at the contact
    strips' half-widths [m]: Westergaard's (``westergaard``) and Johnson's JKR (``jkr``)
    mean pressures [Pa]; ``full_contact_pressure`` [Pa], ``johnson_alpha`` [-],
    ``crest_radius`` [m], and with adhesion ``jkr_pull_off`` and
    ``jkr_snap_to_full_contact`` as (mean pressure [Pa], half-width [m])."""
    x, shape = _flat(half_width)
    d = _native.wave(x, amplitude, wavelength, modulus, work_of_adhesion)
    d["westergaard"] = _shaped(d["westergaard"], shape)
    d["jkr"] = _shaped(d["jkr"], shape)
    return d
