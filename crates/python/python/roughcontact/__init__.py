"""Deterministic contact mechanics of rough surfaces with adhesion.

The engine of the ``roughcontact`` command line, on numpy arrays: make and read rough
surfaces (:func:`generate`, :func:`read`, :class:`Topography`), solve one normal contact
(:func:`solve`) or follow a quasi-static path (:func:`sweep`), and compare with the
reference models in :mod:`roughcontact.theory`.

Units are SI throughout: lengths in metres, pressures and moduli in pascals, forces in
newtons, work of adhesion in J/m^2. Signs: a positive load or pressure pushes the bodies
together, a positive approach pushes them into each other. Arrays of a surface or a field
have shape ``(ny, nx)``: axis 0 is y, axis 1 is x.

The case keys of :func:`solve` and :func:`sweep` are those of the command line's TOML case
files (``roughcontact solve --help`` lists them with their units), given as keywords.
"""

from __future__ import annotations

import json
import os
import threading
import warnings
from typing import Any, Callable, Dict, List, Mapping, Optional, Tuple, Union

import numpy as np

from . import _native, theory

__version__ = _native.VERSION
__all__ = [
    "Topography",
    "Solution",
    "Tangential",
    "Sweep",
    "ConvergenceWarning",
    "generate",
    "read",
    "channels",
    "solve",
    "sweep",
    "from_toml",
    "theory",
]

PathLike = Union[str, "os.PathLike[str]"]
Progress = Callable[[Dict[str, Any]], None]


class ConvergenceWarning(RuntimeWarning):
    """A solve or a step of a sweep ended without converging: its results are the last
    iterate (``converged`` is False)."""


def _heights(heights: Any, name: str = "heights") -> np.ndarray:
    """A 2-D float64 array from any real numeric array-like (float32, integers, Fortran
    order and strided views are accepted; complex, boolean and other kinds are refused)."""
    a = np.asarray(heights)
    if a.dtype.kind not in "fiu":
        raise ValueError(
            f"{name} must be real numbers (float or integer), got an array of dtype {a.dtype}"
        )
    if a.ndim != 2:
        raise ValueError(f"{name} must be a 2-D array (ny, nx), got {a.ndim} dimension(s) {a.shape}")
    return a.astype(np.float64, copy=False)


# Metres per unit, by the names SurfaceTopography gives its units.
_LENGTH_UNITS = {
    "m": 1.0,
    "mm": 1e-3,
    "um": 1e-6,
    "µm": 1e-6,
    "μm": 1e-6,
    "nm": 1e-9,
    "pm": 1e-12,
    "A": 1e-10,
    "Å": 1e-10,
}


class Topography:
    """A height map on a periodic box.

    ``heights`` [m] has shape ``(ny, nx)`` (axis 0 is y); ``length`` is the box's side along
    x [m] and ``length_y`` along y (default: square cells). ``periodic`` says whether the
    surface repeats across the box's edges (generated surfaces do).
    """

    def __init__(
        self,
        heights: Any,
        length: float,
        length_y: Optional[float] = None,
        periodic: bool = True,
    ) -> None:
        h = _heights(heights)
        ny, nx = h.shape
        self.heights: np.ndarray = h
        self.length_x: float = float(length)
        self.length_y: float = float(length_y) if length_y is not None else self.length_x * ny / nx
        self.periodic: bool = bool(periodic)
        if not (np.isfinite(self.length_x) and self.length_x > 0 and np.isfinite(self.length_y) and self.length_y > 0):
            raise ValueError(f"the box's sides must be finite and > 0 m, got {self.length_x} x {self.length_y}")
        if not np.all(np.isfinite(h)):
            raise ValueError("heights must be finite (no NaN or infinity)")

    @classmethod
    def from_surfacetopography(cls, topography: Any) -> "Topography":
        """From a SurfaceTopography topography: its ``heights()``, indexed ``[x, y]``, are
        transposed to ``(ny, nx)``, and its heights and ``physical_sizes`` converted from its
        ``unit`` to metres. A topography without a unit, or in a unit that is not a length,
        raises ValueError."""
        unit = getattr(topography, "unit", None)
        if unit is None:
            raise ValueError(
                "the topography has no unit, so its heights and sizes cannot be taken as metres: "
                "give it one (SurfaceTopography's read_topography(..., unit='um') or .to_unit)"
            )
        if unit not in _LENGTH_UNITS:
            raise ValueError(
                f"the topography's unit {unit!r} is not a length unit this package knows "
                f"(one of {', '.join(sorted(_LENGTH_UNITS))})"
            )
        metres = _LENGTH_UNITS[unit]
        sx, sy = topography.physical_sizes
        heights = np.asarray(topography.heights()).T * metres
        return cls(heights, sx * metres, sy * metres, bool(getattr(topography, "is_periodic", True)))

    @property
    def shape(self) -> Tuple[int, int]:
        """Grid points ``(ny, nx)``."""
        return self.heights.shape  # type: ignore[return-value]

    @property
    def physical_sizes(self) -> Tuple[float, float]:
        """The box's sides ``(length_x, length_y)`` [m]."""
        return (self.length_x, self.length_y)

    @property
    def dx(self) -> float:
        """Grid spacing along x [m]."""
        return self.length_x / self.heights.shape[1]

    @property
    def dy(self) -> float:
        """Grid spacing along y [m]."""
        return self.length_y / self.heights.shape[0]

    def statistics(self) -> Dict[str, Any]:
        """Height, slope and curvature statistics (as ``roughcontact stats --json``): RMS
        height ``rq`` [m], RMS gradient [-] (spectral and finite-difference), curvatures
        [1/m], local radius [m], fitted Hurst exponent."""
        return json.loads(_native.statistics(self.heights, self.length_x, self.length_y, self.periodic))

    def psd(self, bins_per_decade: int = 10) -> Dict[str, np.ndarray]:
        """The radially averaged power spectral density: ``q`` [rad/m], ``psd`` [m^4]
        (Persson's convention, <h^2> = integral d^2q C(q)), its standard error ``std_err``
        [m^4] and the wavevectors a bin holds, ``count``."""
        r = json.loads(_native.psd(self.heights, self.length_x, self.length_y, int(bins_per_decade)))
        return {k: np.asarray(r[k]) for k in ("q", "psd", "std_err", "count")}

    def write(self, path: PathLike) -> None:
        """Writes the surface in the format of the path's extension: ``.npy`` (with a
        ``.json`` sidecar holding the box), ``.txt``, ``.xyz``, ``.gsf``, ``.x3p``, ``.sdf`` or
        ``.nc`` (X3P and NetCDF are what contact.engineering reads back with the box)."""
        _native.write(os.fspath(path), self.heights, self.length_x, self.length_y, self.periodic)

    def __repr__(self) -> str:
        ny, nx = self.shape
        return f"Topography({nx} x {ny} points, {self.length_x:g} m x {self.length_y:g} m)"


def _plain(key: str, value: Any) -> Any:
    """A keyword's value as plain Python (numpy scalars and arrays, paths)."""
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if isinstance(value, (list, tuple)):
        return [_plain(key, v) for v in value]
    return value


def generate(n: Optional[int] = None, length: Optional[float] = None, **keys: Any) -> Topography:
    """A periodic self-affine surface from its power spectrum (``roughcontact generate``).

    Keys (all optional, SI units): ``n`` points per side (1024) or ``nx`` and ``ny``;
    ``length`` [m] (1e-4) or ``length_x`` and ``length_y``; ``hurst`` (0.8), ``rolloff`` [m] (2e-5), ``cutoff`` [m]
    (4 cells), ``long_cutoff`` [m]; one scale of ``rms_height`` [m], ``rms_gradient`` [-]
    (1 when none is given), ``peak_to_valley`` [m] or ``prefactor`` [m^4]; ``seed`` (0: a
    seed fixes the surface bit for bit); ``anisotropy`` (1) and ``angle`` [degrees];
    ``rayleigh`` (False: exact amplitudes with random phases).
    """
    keys = {k: _plain(k, v) for k, v in dict(keys, n=n, length=length).items() if v is not None}
    heights, lx, ly, info = _native.generate(keys)
    for w in json.loads(info)["warnings"]:
        warnings.warn(w, stacklevel=2)
    return Topography(heights, lx, ly, periodic=True)


def read(
    path: PathLike,
    *,
    length: Optional[float] = None,
    length_y: Optional[float] = None,
    unit: float = 1.0,
    periodic: bool = True,
    channel: Union[str, int, None] = None,
    fill_unmeasured: bool = False,
    max_unmeasured: Optional[float] = None,
) -> Topography:
    """Reads a surface file (``.npy`` with its sidecar, text matrix, ``.xyz``, ``.gsf``,
    ``.x3p``, ``.sdf``, ``.nc``, ``.tmd``, ``.mi``, ``.nid``, ``.sur``, ``.opd``, ``.di``/``.spm``,
    ``.ibw``, ``.frt``, ``.gwy``, ``.h5``, ``.datx``, ``.mnt``).
    ``length``/``length_y`` [m] give the box of files that do not carry it; ``unit`` is the
    metres per file unit; ``periodic`` applies to files without metadata. ``channel`` picks a
    multi-channel file's channel of heights by name or index (default: the first;
    :func:`channels` lists them). Points the instrument did not measure raise ValueError
    unless ``fill_unmeasured`` fills them by harmonic interpolation, up to the fraction
    ``max_unmeasured`` of the points (default 0.25; 1 fills any), with a warning that says how
    many were filled."""
    heights, lx, ly, is_periodic, note = _native.read(
        os.fspath(path),
        length,
        length_y,
        float(unit),
        bool(periodic),
        None if channel is None else str(channel),
        bool(fill_unmeasured),
        max_unmeasured,
    )
    if note is not None:
        warnings.warn(note, stacklevel=2)
    return Topography(heights, lx, ly, is_periodic)


def channels(
    path: PathLike, *, length: Optional[float] = None, length_y: Optional[float] = None, unit: float = 1.0
) -> List[Dict[str, Any]]:
    """The channels of a surface file, in its order: ``name``, points ``nx`` and ``ny``,
    ``length_x`` and ``length_y`` [m] (None where the file does not say), the ``unit`` of its
    values and whether they are heights (``height``)."""
    return json.loads(_native.channels(os.fspath(path), length, length_y, float(unit)))


def from_toml(path: PathLike) -> Dict[str, Any]:
    """The keys of a TOML case file as a dictionary for :func:`solve` or :func:`sweep`
    (``solve(**from_toml("case.toml"))``); paths it names are taken relative to its folder."""
    path = os.fspath(path)
    keys = json.loads(_native.read_toml(path))
    for k in ("surface", "start_from"):
        if isinstance(keys.get(k), str) and not os.path.isabs(keys[k]):
            keys[k] = os.path.join(os.path.dirname(os.path.abspath(path)), keys[k])
    return keys


def _threads(threads: Any) -> Optional[int]:
    """``threads`` checked: None (all cores) or a whole number >= 1."""
    if threads is None:
        return None
    if isinstance(threads, bool) or not isinstance(threads, (int, np.integer)) or threads < 1:
        raise ValueError(f"threads must be a whole number >= 1, or None for all cores; got {threads!r}")
    return int(threads)


def _run(function: Callable[..., Any], *args: Any) -> Any:
    """Runs a native solve on a thread of its own, so that Ctrl-C in this one cancels it
    cleanly (the solve stops where it stands, then KeyboardInterrupt is raised here)."""
    cancel = _native.Cancel()
    box: Dict[str, Any] = {}

    def target() -> None:
        try:
            box["value"] = function(*args, cancel)
        except BaseException as e:  # noqa: BLE001 - handed to the caller's thread
            box["error"] = e

    worker = threading.Thread(target=target, name="roughcontact-solve", daemon=True)
    worker.start()
    try:
        while worker.is_alive():
            worker.join(0.1)
    except KeyboardInterrupt:
        cancel.set()
        worker.join()
        raise
    if "error" in box:
        raise box["error"]
    return box["value"]


def _case(case: Union[None, PathLike, Mapping[str, Any]], keys: Dict[str, Any]):
    """The keys of a case (a TOML file or a dict) with ``keys`` laid over, and the roughness
    when ``surface`` is a :class:`Topography`."""
    merged: Dict[str, Any] = {}
    if case is not None:
        merged.update(from_toml(case) if isinstance(case, (str, os.PathLike)) else dict(case))
    merged.update(keys)
    if "from_" in merged:
        merged["from"] = merged.pop("from_")
    roughness = None
    surface = merged.get("surface")
    if isinstance(surface, Topography):
        del merged["surface"]
        roughness = (surface.heights, surface.length_x, surface.length_y)
    elif isinstance(surface, np.ndarray) or (isinstance(surface, (list, tuple)) and surface):
        raise ValueError(
            "surface: an array of heights needs its box: pass "
            "surface=roughcontact.Topography(heights, length=L) with L the side along x [m] "
            "(heights [m], shape (ny, nx)), or a surface file's path"
        )
    return {k: _plain(k, v) for k, v in merged.items() if v is not None}, roughness


class Solution:
    """One solved contact. Fields (numpy arrays, shape ``(ny, nx)``): ``pressure`` [Pa]
    (total, compressive positive), ``gap`` [m], ``displacement`` [m], with adhesion
    ``compressive_pressure`` and ``adhesive_pressure`` [Pa], with a ``hardness`` the permanent
    set ``plastic`` [m]. Numbers: ``load`` [N], ``mean_pressure`` [Pa], ``approach`` [m],
    ``contact_area_fraction`` [-], with a ``hardness`` ``plastic_area_fraction`` [-],
    ``permanent_set_volume`` [m^3] and ``plastic_work`` [J] (0 when elastic), ``converged``,
    ``termination``, ``residual``, ``wall_time_s`` [s]; every number of the solver's report
    is in ``report``, the resolved case in ``case``. After a tangential path, ``tangential``
    (a :class:`Tangential`) and the last step's fields ``shear_x``, ``shear_y`` [Pa],
    ``slip_x``, ``slip_y`` [m] (the surfaces' relative tangential displacement since the path
    began: on the contact the slip); otherwise ``tangential`` is None."""

    def __init__(self, summary: Dict[str, Any], fields: Dict[str, np.ndarray]) -> None:
        self.fields = fields
        self.report: Dict[str, Any] = summary["report"]
        self.case: Dict[str, Any] = summary["case"]
        self.law: str = summary["law"]
        self.warnings = list(summary["warnings"])
        self.surface_hash: Optional[str] = summary["surface_hash"]
        r = self.report
        self.load: float = r["load"]
        self.mean_pressure: float = r["mean_pressure"]
        self.approach: float = r["approach"]
        self.contact_area_fraction: float = r["contact_area_fraction"]
        self.plastic_area_fraction: float = r["plastic_area_fraction"]
        self.permanent_set_volume: float = r["permanent_set_volume"]
        self.plastic_work: float = r["plastic_work"]
        self.termination: str = summary["termination"]
        self.converged: bool = summary["converged"]
        self.residual: float = r["residual"]
        self.wall_time_s: float = r["wall_time_s"]
        t = summary.get("tangential")
        self.tangential: Optional[Tangential] = Tangential(t) if t is not None else None

    def __getattr__(self, name: str) -> Any:
        fields = self.__dict__.get("fields", {})
        if name in fields:
            return fields[name]
        report = self.__dict__.get("report", {})
        if name in report:
            return report[name]
        raise AttributeError(name)

    def __repr__(self) -> str:
        return (
            f"Solution(load={self.load:.6e} N, approach={self.approach:.6e} m, "
            f"contact_area_fraction={self.contact_area_fraction:.6f}, {self.termination})"
        )


class Tangential:
    """A tangential path after a normal solve, step by step (numpy arrays, one value a step):
    ``force_x``, ``force_y`` [N], ``displacement_x``, ``displacement_y`` [m] (NaN under a force
    the contact cannot carry), ``stick_area_fraction``, ``slip_area_fraction`` [-],
    ``frictional_work`` [J] (each step's), ``elastic_energy`` [J], ``normal_load`` [N] and
    ``approach`` [m] under the shear, ``coupling_iterations`` (rounds of the normal and
    tangential solves against a rigid counterface, 0 decoupled), ``iterations``,
    ``residual``, ``converged``; and the path's ``static_friction`` [N] (the contact's
    capacity, sum (tau0 + mu p_c) dA), ``gross_sliding`` (whether it was reached),
    ``total_frictional_work`` [J], ``work`` [J] (the shear force's, sum Q . dD),
    ``all_converged``, ``contact_area_fraction`` [-] (the cells that carry shear). Every
    step's report is in ``steps``."""

    def __init__(self, summary: Dict[str, Any]) -> None:
        self.steps: List[Dict[str, Any]] = summary["steps"]
        self.static_friction: float = summary["static_friction"]
        self.gross_sliding: bool = summary["gross_sliding"]
        self.total_frictional_work: float = summary["frictional_work"]
        self.work: float = summary["work"]
        self.all_converged: bool = summary["all_converged"]
        self.contact_area_fraction: float = summary["contact_area_fraction"]

        def column(f: Callable[[Dict[str, Any]], Any]) -> np.ndarray:
            return np.array([f(step) for step in self.steps], dtype=float)

        nan = float("nan")
        self.force_x = column(lambda r: r["force"][0])
        self.force_y = column(lambda r: r["force"][1])
        self.displacement_x = column(lambda r: nan if r["displacement"][0] is None else r["displacement"][0])
        self.displacement_y = column(lambda r: nan if r["displacement"][1] is None else r["displacement"][1])
        for name in (
            "stick_area_fraction",
            "slip_area_fraction",
            "frictional_work",
            "elastic_energy",
            "normal_load",
            "approach",
            "residual",
        ):
            setattr(self, name, column(lambda r, name=name: r[name]))
        self.iterations = np.array([r["iterations"] for r in self.steps], dtype=int)
        self.coupling_iterations = np.array([r["coupling_iterations"] for r in self.steps], dtype=int)
        self.converged = np.array([r["termination"] == "Converged" for r in self.steps], dtype=bool)

    def __repr__(self) -> str:
        return (
            f"Tangential({len(self.steps)} steps, static_friction={self.static_friction:.6e} N, "
            f"gross_sliding={self.gross_sliding})"
        )


_CURVE = (
    "approach",
    "load",
    "mean_pressure",
    "contact_area_fraction",
    "attractive_area_fraction",
    "attached_area_fraction",
    "central_gap",
    "plastic_area_fraction",
    "permanent_set_volume",
    "plastic_work",
    "elastic_energy",
    "viscous_work",
    "residual",
    "wall_time_s",
)


class Sweep:
    """A quasi-static path of solves. ``curve`` holds one array a column, one row a step
    (ready for ``pandas.DataFrame(sweep.curve)``): ``approach`` [m], ``load`` [N],
    ``mean_pressure`` [Pa], area fractions [-] (the plastic one too), ``central_gap`` [m],
    ``permanent_set_volume`` [m^3], ``plastic_work`` [J], ``elastic_energy`` [J] (stored in
    the body), ``viscous_work`` [J] (dissipated by its dashpots in the step), ``time`` [s] (NaN
    on an elastic body), ``branch`` ('loading' or 'unloading'), ``iterations``, ``converged``,
    ``residual``, ``wall_time_s`` [s], ``retries``, ``termination`` (in words). The cycle's ``pull_off_force`` [N] and its
    ``pull_off_approach`` [m] (``pull_off_at_path_end``: it is the last step's, still
    attached, and the pull-off lies beyond the path), ``jump_in_approach``,
    ``jump_out_approach`` [m],
    ``hysteresis_energy`` [J], ``plastic_work`` [J] (dissipated by yielding),
    ``viscous_work`` [J] (by a viscoelastic body's dashpots), ``adhesive_work`` [J] (on a path
    from apart to apart, what the adhesive jumps lost: the work done less the other losses and
    the energy still stored; None otherwise) and ``all_converged``; the last state's fields in
    ``state`` (the permanent set ``plastic`` [m] with a ``hardness``); every step's full report
    in ``steps``."""

    def __init__(self, summary: Dict[str, Any], fields: Dict[str, np.ndarray]) -> None:
        self.steps = summary["steps"]
        self.case: Dict[str, Any] = summary["case"]
        self.path: Dict[str, Any] = summary["path"]
        self.law: str = summary["law"]
        self.method: Optional[str] = summary["method"]
        self.max_step: Optional[float] = summary["max_step"]
        self.warnings = list(summary["warnings"])
        self.surface_hash: Optional[str] = summary["surface_hash"]
        self.state = fields
        cycle = summary["cycle"]
        self.pull_off_force: Optional[float] = cycle["pull_off_force"]
        self.pull_off_approach: Optional[float] = cycle["pull_off_approach"]
        self.pull_off_at_path_end: bool = cycle["pull_off_at_path_end"]
        self.jump_in_approach: Optional[float] = cycle["jump_in_approach"]
        self.jump_out_approach: Optional[float] = cycle["jump_out_approach"]
        self.hysteresis_energy: Optional[float] = cycle["hysteresis_energy"]
        self.plastic_work: float = cycle["plastic_work"]
        self.viscous_work: float = cycle["viscous_work"]
        self.adhesive_work: Optional[float] = cycle["adhesive_work"]
        reports = [s["report"] for s in self.steps]
        curve: Dict[str, np.ndarray] = {"step": np.arange(len(reports))}
        for k in _CURVE:
            curve[k] = np.array([r[k] for r in reports], dtype=np.float64)
        curve["branch"] = np.array([s["branch"] for s in self.steps], dtype=str)
        curve["iterations"] = np.array(summary["iterations"], dtype=np.int64)
        curve["converged"] = np.array(summary["converged"], dtype=bool)
        curve["termination"] = np.array(summary["termination"], dtype=str)
        curve["retries"] = np.array([s["retries"] for s in self.steps], dtype=np.int64)
        # NaN where the path has no times (an elastic body).
        curve["time"] = np.array(
            [np.nan if s["time"] is None else s["time"] for s in self.steps], dtype=np.float64
        )
        self.curve = curve
        self.all_converged: bool = bool(curve["converged"].all())

    def __len__(self) -> int:
        return len(self.steps)

    def __repr__(self) -> str:
        p = "" if self.pull_off_force is None else f", pull_off_force={self.pull_off_force:.6e} N"
        return f"Sweep({len(self)} steps{p}, all_converged={self.all_converged})"


def solve(
    case: Union[None, PathLike, Mapping[str, Any]] = None,
    *,
    progress: Optional[Progress] = None,
    threads: Optional[int] = None,
    **keys: Any,
) -> Solution:
    """Solves one normal contact (``roughcontact solve``).

    ``case``: a TOML case file or a dict of keys; ``keys`` (the case file's keys, SI units)
    are laid over it. ``surface`` may be a :class:`Topography` instead of a file. Exactly
    one control: ``approach`` [m], ``load`` [N], ``mean_pressure`` [Pa] or ``mean_gap`` [m].
    A film instead of the half-space: ``thickness`` [m] with the layer's ``poisson`` [-] and
    ``layer_base`` (``"bonded"``, default, ``"frictionless"``, or ``"elastic"`` with the
    substrate's ``substrate_modulus`` [Pa] and ``substrate_poisson``: a coating, periodic
    grids only); ``modulus`` is then the layer's E / (1 - nu^2) [Pa]. A ``hardness`` [Pa] caps the compressive pressure.
    A viscoelastic body (``maxwell_moduli``) is swept, not solved: its answer depends on the path.
    A tangential path after the normal solve: ``tangential_loads`` [N] or
    ``tangential_displacements`` [m] (lists, each step from the last; negative reverses) along
    ``tangential_angle`` [rad], with ``friction_coefficient`` [-] and/or ``shear_strength``
    [Pa] and the body's ``poisson`` [-]; ``counterface="rigid"`` couples it to the normal
    contact (a half-space's for ``poisson`` < 0.5, a layer's always; default ``"similar"``:
    decoupled); the result's ``tangential``.
    ``progress(info)`` is called after every iteration with ``{'step', 'iteration',
    'residual'}``; an exception it raises stops the solve. ``threads``: threads of this
    solve's own pool (None: all cores, shared). The GIL is released while solving; Ctrl-C
    stops the solve and raises KeyboardInterrupt. Bad keys raise ValueError; a solve that
    does not converge warns (:class:`ConvergenceWarning`) and says so in ``converged``.
    """
    keys, roughness = _case(case, keys)
    summary, fields = _run(_native.solve, keys, roughness, _threads(threads), progress)
    solution = Solution(json.loads(summary), dict(fields))
    for w in solution.warnings:
        warnings.warn(w, stacklevel=2)
    if not solution.converged:
        warnings.warn(
            f"the solve did not converge: {solution.termination}, residual {solution.residual:.3e}",
            ConvergenceWarning,
            stacklevel=2,
        )
    if solution.tangential is not None and not solution.tangential.all_converged:
        warnings.warn("a step of the tangential path did not converge", ConvergenceWarning, stacklevel=2)
    return solution


def sweep(
    case: Union[None, PathLike, Mapping[str, Any]] = None,
    *,
    progress: Optional[Progress] = None,
    threads: Optional[int] = None,
    **keys: Any,
) -> Sweep:
    """Follows a quasi-static path of solves from apart (``roughcontact sweep``), each step
    starting from the last.

    The path: ``from_`` and ``to`` [m] with ``steps`` (a cycle there and back; ``from_``
    is the case file's ``from``, a Python keyword), or ``approaches`` [m], ``mean_pressures`` [Pa] or
    ``central_gaps`` [m] as lists; ``max_step`` [m] splits longer steps. With ``pull_off_step``
    [m] and ``pull_off_floor`` [m] the path goes in only and the pull-off search follows it
    (``pull_off_refinement``, ``pull_off_recovery``; the result's ``pull_off_force`` [N]).
    A viscoelastic body (``maxwell_moduli`` [Pa] and ``maxwell_times`` [s], a generalized
    Maxwell solid beside the relaxed ``modulus``) needs each step's time: ``step_time`` [s]
    or ``times`` [s] (a list, one a step); a pull-off search then unloads at
    ``pull_off_step / step_time`` [m/s]. The other keys,
    ``case``, ``progress`` (also called with ``{'step', 'done': True, 'approach', 'load',
    'converged'}`` after every step), ``threads``, Ctrl-C and errors as in :func:`solve`.
    """
    keys, roughness = _case(case, keys)
    summary, fields = _run(_native.sweep, keys, roughness, _threads(threads), progress)
    result = Sweep(json.loads(summary), dict(fields))
    for w in result.warnings:
        warnings.warn(w, stacklevel=2)
    if not result.all_converged:
        failed = int((~result.curve["converged"]).sum())
        warnings.warn(f"{failed} of {len(result)} steps did not converge", ConvergenceWarning, stacklevel=2)
    return result
