"""Reference models for adhesive and rough contact (the ``theory`` crate, as ``roughcontact
theory``). Arrays in, arrays out: every numeric argument takes a number or any array-like,
the arguments broadcast against one another as numpy's do, and each result has the
broadcast shape (a float where every argument is a number). The curves traced by
continuation (:func:`maugis_dugdale`, :func:`greenwood`) and :func:`wave`'s parameters take
one number a call.
SI units unless a model says it works in its own dimensionless units; loads are positive
when compressive, approaches when pushing together.
"""

from __future__ import annotations

from typing import Any, Dict, Optional, Tuple

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


def _broadcast(function: Any, *args: Any) -> Any:
    """``function`` of scalars applied over the broadcast arguments: a float (or tuple of
    floats) where every argument is a number, else arrays of the broadcast shape."""
    arrays = [np.asarray(a, dtype=np.float64) for a in args]
    if all(a.ndim == 0 for a in arrays):
        return function(*(float(a) for a in arrays))
    return np.vectorize(function, otypes=None)(*arrays)


def _curve(function: Any, x: Any, *parameters: Any) -> Any:
    """``function(list of x, *scalar parameters)``, which returns one list per result, over
    ``x`` and broadcast parameters: each result an array of the broadcast shape."""
    arrays = [np.asarray(a, dtype=np.float64) for a in (x, *parameters)]
    shape = np.broadcast_shapes(*(a.shape for a in arrays))
    if all(a.ndim == 0 for a in arrays[1:]):
        xs, _ = _flat(np.broadcast_to(arrays[0], shape))
        return [_shaped(r, shape) for r in function(xs, *(float(a) for a in arrays[1:]))]
    b = [np.broadcast_to(a, shape).ravel() for a in arrays]
    if b[0].size == 0:
        return [np.empty(shape) for _ in function([], *(1.0 for _ in arrays[1:]))]
    per_point = [function([float(b[0][i])], *(float(a[i]) for a in b[1:])) for i in range(b[0].size)]
    return [_shaped([p[k][0] for p in per_point], shape) for k in range(len(per_point[0]))]


def _scalar(name: str, value: Any) -> float:
    """A parameter that takes one number a call."""
    a = np.asarray(value)
    if a.ndim != 0:
        raise ValueError(f"{name} takes one number a call (this model traces a curve), got an array of shape {a.shape}")
    return float(a)


def tabor_parameter(radius: float, work_of_adhesion: float, modulus: float, z0: float) -> float:
    """Tabor's parameter mu = (R w0^2 / (E*^2 z0^3))^(1/3) of a sphere of radius R [m],
    work of adhesion w0 [J/m^2], modulus E* [Pa] and Lennard-Jones range z0 [m]."""
    return _broadcast(_native.tabor_parameter, radius, work_of_adhesion, modulus, z0)


def hertz(approach: Any, radius: float, modulus: float) -> Dict[str, np.ndarray]:
    """Hertz's sphere at the approaches [m]: ``load`` [N], ``contact_radius`` [m] and
    ``max_pressure`` [Pa]."""
    load, a, p0 = _curve(_native.hertz, approach, radius, modulus)
    return {"load": load, "contact_radius": a, "max_pressure": p0}


def jkr(contact_radius: Any, radius: float, work_of_adhesion: float, modulus: float) -> Dict[str, np.ndarray]:
    """JKR's sphere at the contact radii [m]: ``load`` [N] and ``approach`` [m]."""
    load, approach = _curve(_native.jkr, contact_radius, radius, work_of_adhesion, modulus)
    return {"load": load, "approach": approach}


def jkr_pull_off(radius: float, work_of_adhesion: float) -> Dict[str, float]:
    """JKR's pull-off force [N] (negative: tensile) under load control (-3/2 pi R w0) and
    under displacement control (-5/6 pi R w0)."""
    load = _broadcast(lambda r, w: _native.jkr_pull_off(r, w)[0], radius, work_of_adhesion)
    displacement = _broadcast(lambda r, w: _native.jkr_pull_off(r, w)[1], radius, work_of_adhesion)
    return {"load_control": load, "displacement_control": displacement}


def dmt(contact_radius: Any, radius: float, work_of_adhesion: float, modulus: float) -> np.ndarray:
    """DMT's load [N] at the contact radii [m]."""
    return _curve(_native.dmt, contact_radius, radius, work_of_adhesion, modulus)[0]


def dmt_pull_off(radius: float, work_of_adhesion: float) -> float:
    """DMT's pull-off force [N], -2 pi R w0."""
    return _broadcast(lambda r, w: _native.dmt([], r, w, 1.0)[1], radius, work_of_adhesion)


def maugis_dugdale(tabor: float, points: int = 200, max_radius: float = 3.0) -> Dict[str, Any]:
    """Maugis-Dugdale's sphere at the Tabor parameter mu (Maugis' lambda = 1.157 mu), in
    Maugis' units: contact ``radius`` A = a/(pi w0 R^2/K)^(1/3), ``load`` P = load/(pi w0 R),
    ``approach`` D = approach/(pi^2 w0^2 R/K^2)^(1/3), K = 4E*/3, from A = ``max_radius``
    to separation; ``pull_off_load_control`` and ``pull_off_displacement_control`` [pi R w0];
    ``lambda``."""
    d = _native.maugis_dugdale(_scalar("tabor", tabor), int(points), _scalar("max_radius", max_radius))
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
    d = _native.greenwood(
        _scalar("tabor", tabor),
        _scalar("max_approach", max_approach),
        _scalar("start", start),
        _scalar("resolution", resolution),
        _scalar("ring_width", ring_width),
    )
    for k in ("central_separation", "approach", "load", "contact_radius"):
        d[k] = np.asarray(d[k])
    return d


def persson_area(reduced_pressure: Any) -> np.ndarray:
    """Persson's relative contact area erf(sqrt(2) p/(E* g_bar)) at the reduced pressures
    p/(E* g_bar) [-] (g_bar the RMS gradient)."""
    return _curve(lambda x: [_native.persson_area(x)], reduced_pressure)[0]


def muser_area(reduced_pressure: Any, k: float = 2.0) -> np.ndarray:
    """Müser's relative contact area (the paper's Eq. 14, corrected) at the reduced pressures
    p/(E* g_bar) [-], with small-load slope ``k``."""
    return _curve(lambda x, k: [_native.muser_area(x, k)], reduced_pressure, k)[0]


def johnson_parameter(
    work_of_adhesion: float, modulus: float, rms_height: float, q0: float, q1: float, hurst: float
) -> float:
    """The modified Johnson parameter (Li, Pohrt & Popov 2019; the paper's Eq. 15) of a
    self-affine surface: w0 [J/m^2], E* [Pa], RMS height [m], smallest and largest
    wavevectors q0, q1 [rad/m], Hurst exponent."""
    return _broadcast(_native.johnson_parameter, work_of_adhesion, modulus, rms_height, q0, q1, hurst)


def ciavarella(rms_height: float, modulus: float, longest_wavelength: float, work_of_adhesion: float) -> Dict[str, Any]:
    """Ciavarella's (2019) criterion: the ``variable`` Rq^2 E*/(lambda_L w0) [-] and
    ``sticky`` (variable < 0.6)."""
    args = (rms_height, modulus, longest_wavelength, work_of_adhesion)
    variable = _broadcast(lambda *a: _native.ciavarella(*a)[0], *args)
    sticky = _broadcast(lambda *a: float(_native.ciavarella(*a)[1]), *args)
    return {"variable": variable, "sticky": np.asarray(sticky).astype(bool) if np.ndim(sticky) else bool(sticky)}


def wave(
    half_width: Any, amplitude: float, wavelength: float, modulus: float, work_of_adhesion: float = 0.0
) -> Dict[str, Any]:
    """A rigid wave A cos(2 pi x / lambda) on a half-space (plane strain) at the contact
    strips' half-widths [m]: Westergaard's (``westergaard``) and Johnson's JKR (``jkr``)
    mean pressures [Pa]; ``full_contact_pressure`` [Pa], ``johnson_alpha`` [-],
    ``crest_radius`` [m], and with adhesion ``jkr_pull_off`` and
    ``jkr_snap_to_full_contact`` as (mean pressure [Pa], half-width [m])."""
    x, shape = _flat(half_width)
    d = _native.wave(
        x,
        _scalar("amplitude", amplitude),
        _scalar("wavelength", wavelength),
        _scalar("modulus", modulus),
        _scalar("work_of_adhesion", work_of_adhesion),
    )
    d["westergaard"] = _shaped(d["westergaard"], shape)
    d["jkr"] = _shaped(d["jkr"], shape)
    return d


def layer(
    contact_radius: Any,
    radius: float,
    modulus: float,
    thickness: float,
    poisson: float,
    layer_base: str = "bonded",
    substrate_modulus: Optional[float] = None,
    substrate_poisson: Optional[float] = None,
    work_of_adhesion: float = 0.0,
) -> Dict[str, np.ndarray]:
    """A rigid sphere of ``radius`` [m] on an elastic layer ``thickness`` [m] thick (its
    plane-strain ``modulus`` E* [Pa] and ``poisson`` ratio; ``layer_base`` 'bonded' or
    'frictionless' on a rigid base, or 'elastic' on a substrate of ``substrate_modulus`` [Pa]
    and ``substrate_poisson``), solved exactly at the contact radii [m]: ``load`` [N] and
    ``approach`` [m], Hertz's on the layer or, with a ``work_of_adhesion`` [J/m^2], JKR's."""
    x, shape = _flat(contact_radius)
    load, approach = _native.layer(
        x,
        _scalar("radius", radius),
        _scalar("modulus", modulus),
        _scalar("thickness", thickness),
        _scalar("poisson", poisson),
        layer_base,
        None if substrate_modulus is None else _scalar("substrate_modulus", substrate_modulus),
        None if substrate_poisson is None else _scalar("substrate_poisson", substrate_poisson),
        _scalar("work_of_adhesion", work_of_adhesion),
    )
    return {"load": _shaped(load, shape), "approach": _shaped(approach, shape)}


def layer_pull_off(
    radius: float,
    work_of_adhesion: float,
    modulus: float,
    thickness: float,
    poisson: float,
    layer_base: str = "bonded",
    substrate_modulus: Optional[float] = None,
    substrate_poisson: Optional[float] = None,
) -> Dict[str, float]:
    """JKR's pull-off of a sphere on a layer (the parameters of :func:`layer`): ``load`` [N]
    (negative: tensile), ``contact_radius`` [m] and ``approach`` [m] at it."""
    load, a, approach = _native.layer_pull_off(
        _scalar("radius", radius),
        _scalar("work_of_adhesion", work_of_adhesion),
        _scalar("modulus", modulus),
        _scalar("thickness", thickness),
        _scalar("poisson", poisson),
        layer_base,
        None if substrate_modulus is None else _scalar("substrate_modulus", substrate_modulus),
        None if substrate_poisson is None else _scalar("substrate_poisson", substrate_poisson),
    )
    return {"load": load, "contact_radius": a, "approach": approach}


def viscoelastic_indentation(
    time: Any,
    radius: float,
    modulus: float,
    maxwell_moduli: Any,
    maxwell_times: Any,
    rate: float,
    rise_time: float,
) -> Dict[str, np.ndarray]:
    """A rigid sphere of ``radius`` [m] on a generalized Maxwell solid (relaxed plane-strain
    ``modulus`` E*_inf [Pa], branches of ``maxwell_moduli`` [Pa] relaxing in
    ``maxwell_times`` [s]), pressed in at ``rate`` [m/s] until ``rise_time`` [s] and drawn back
    at the same rate, without adhesion, at the times [s]: ``contact_radius`` [m] and ``load``
    [N] (Lee & Radok while the contact grows, Ting after)."""
    x, shape = _flat(time)
    a, load = _native.viscoelastic_indentation(
        x,
        _scalar("radius", radius),
        _scalar("modulus", modulus),
        _flat(maxwell_moduli)[0],
        _flat(maxwell_times)[0],
        _scalar("rate", rate),
        _scalar("rise_time", rise_time),
    )
    return {"contact_radius": _shaped(a, shape), "load": _shaped(load, shape)}


def viscoelastic_creep(
    time: Any, radius: float, modulus: float, maxwell_moduli: Any, maxwell_times: Any, load: float
) -> np.ndarray:
    """Lee & Radok's contact radius [m] of a sphere (the solid of
    :func:`viscoelastic_indentation`) under a ``load`` [N] put on at time 0, at the times [s]."""
    x, shape = _flat(time)
    a = _native.viscoelastic_creep(
        x,
        _scalar("radius", radius),
        _scalar("modulus", modulus),
        _flat(maxwell_moduli)[0],
        _flat(maxwell_times)[0],
        _scalar("load", load),
    )
    return _shaped(a, shape)
