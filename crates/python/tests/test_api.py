"""Errors with the library's messages, surfaces, the progress callable, Ctrl-C, threads."""

import _thread
import concurrent.futures
import threading
import time
import warnings
from pathlib import Path

import numpy as np
import pytest

import roughcontact as rc
from roughcontact import theory

# Tabor parameter 1.36; the box's edge at an undeformed gap of 11 z0 (no warning).
SPHERE = dict(sphere_radius=1e-6, n=64, length=3e-7, modulus=1e9, work_of_adhesion=0.05, z0=1e-9)


def test_errors_carry_the_library_messages(tmp_path):
    with pytest.raises(ValueError, match=r"unknown key `bogus`; the keys are approach, "):
        rc.solve(modulus=1e9, bogus=1)
    with pytest.raises(ValueError, match="give exactly one of mean_pressure \\[Pa\\], load \\[N\\]"):
        rc.solve(**SPHERE)
    with pytest.raises(ValueError, match="the composite modulus is required"):
        rc.solve(sphere_radius=1e-6, length=1e-7, approach=1e-9)
    with pytest.raises(ValueError, match="`n` must be a whole number >= 0, got \"many\" \\(a string\\)$"):
        rc.solve(**dict(SPHERE, n="many"), approach=1e-9)
    with pytest.raises(ValueError, match="`length` must be a finite number, got NaN"):
        rc.solve(**dict(SPHERE, length=float("nan")), approach=1e-9)
    with pytest.raises(ValueError, match="`out` is the command line's"):
        rc.solve(**SPHERE, approach=1e-9, out="somewhere")
    with pytest.raises(FileNotFoundError, match="No such file"):
        rc.read(tmp_path / "missing.npy", length=1.0)
    with pytest.raises(ValueError, match="give one scale"):
        rc.generate(n=16, rms_height=1e-6, rms_gradient=1.0)
    for threads in (0, -1, 1.5):
        with pytest.raises(ValueError, match="threads must be a whole number >= 1, or None"):
            rc.solve(**SPHERE, approach=1e-9, threads=threads)


def test_generate_is_reproducible_and_scaled():
    a = rc.generate(n=64, length=1e-4, rms_height=1e-6, seed=7)
    b = rc.generate(n=64, length=1e-4, rms_height=1e-6, seed=np.int64(7))
    assert np.array_equal(a.heights, b.heights)
    assert not np.array_equal(a.heights, rc.generate(n=64, length=1e-4, rms_height=1e-6, seed=8).heights)
    assert abs(np.sqrt(np.mean((a.heights - a.heights.mean()) ** 2)) / 1e-6 - 1) < 1e-12
    stats = a.statistics()
    assert abs(stats["rms_height"] / 1e-6 - 1) < 1e-12
    psd = a.psd()
    # Persson's convention: <h^2> = integral d^2q C(q) = 2 pi integral q C(q) dq.
    q, c = psd["q"], psd["psd"]
    assert q.shape == c.shape and np.all(q > 0)


@pytest.mark.parametrize("suffix", [".npy", ".txt", ".xyz", ".gsf"])
def test_write_then_read(tmp_path, suffix):
    a = rc.generate(nx=32, ny=16, length_x=2e-5, length_y=1e-5, rolloff=5e-6, rms_height=1e-7, seed=1)
    path = tmp_path / f"surface{suffix}"
    a.write(path)
    b = rc.read(path, length=2e-5) if suffix == ".txt" else rc.read(path)
    assert b.shape == (16, 32) and b.physical_sizes == pytest.approx(a.physical_sizes, rel=1e-12)
    tolerance = 0 if suffix in (".npy", ".gsf") else 1e-15
    if suffix == ".gsf":
        np.testing.assert_allclose(b.heights, a.heights.astype(np.float32), rtol=0, atol=0)
    else:
        np.testing.assert_allclose(b.heights, a.heights, rtol=tolerance, atol=0)


def test_from_toml(tmp_path):
    (tmp_path / "case.toml").write_text(
        'sphere_radius = 1e-6\nn = 64\nlength = 3e-7\nmodulus = 1e9\nwork_of_adhesion = 0.05\nz0 = 1e-9\n'
    )
    a = rc.solve(tmp_path / "case.toml", approach=1e-9)
    b = rc.solve(**rc.from_toml(tmp_path / "case.toml"), approach=1e-9)
    c = rc.solve(SPHERE, approach=1e-9)
    assert a.load == b.load == c.load


def test_progress_sees_every_iteration_and_every_step():
    seen = []
    result = rc.sweep(**SPHERE, approaches=[-2e-9, 0.0, 1e-9], progress=seen.append)
    iterations = [s for s in seen if "iteration" in s]
    steps = [s for s in seen if s.get("done")]
    assert [s["step"] for s in steps] == [0, 1, 2]
    assert [s["load"] for s in steps] == list(result.curve["load"])
    assert len(iterations) >= sum(result.curve["iterations"])


def test_an_exception_in_progress_stops_the_solve():
    calls = []

    def stop(info):
        calls.append(info)
        if len(calls) == 3:
            raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough"):
        rc.solve(**SPHERE, approach=1e-9, tolerance=1e-14, progress=stop)
    assert len(calls) == 3


def test_ctrl_c_stops_a_long_solve_cleanly():
    """KeyboardInterrupt in the calling thread cancels the sweep where it stands."""
    timer = []

    def arm(info):
        # Ctrl-C 0.2 s after the solve has started.
        if not timer:
            timer.append(threading.Timer(0.2, _thread.interrupt_main))
            timer[0].start()

    path = list(np.linspace(-2e-9, 1e-9, 5000))
    started = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        rc.sweep(**SPHERE, approaches=path, progress=arm)
    assert time.perf_counter() - started < 10
    # Nothing is left running: a new solve converges as ever.
    assert rc.solve(**SPHERE, approach=1e-9).converged


def test_an_unconverged_solve_warns_and_says_so():
    with pytest.warns(rc.ConvergenceWarning, match="did not converge"):
        solution = rc.solve(**SPHERE, approach=1e-9, max_iterations=2)
    assert not solution.converged and "iteration limit" in solution.termination


def test_the_gil_is_released_while_solving():
    """Python runs on in another thread while a solve works: the main thread's loop never
    waits for more than a fraction of the solve (holding the GIL, it would wait for all of
    it). Two solves side by side give the same result."""
    surface = rc.generate(n=1024, length=1e-4, rms_gradient=1.0, rolloff=2e-5, seed=1)
    keys = dict(surface=surface, modulus=25e6, mean_pressure=0.01 * 25e6, threads=1)
    with concurrent.futures.ThreadPoolExecutor(1) as pool:
        started = time.perf_counter()
        future = pool.submit(rc.solve, **keys)
        last, longest = started, 0.0
        while not future.done():
            now = time.perf_counter()
            longest, last = max(longest, now - last), now
        took = time.perf_counter() - started
        solution = future.result()
    print(f"solve {took:.3f} s, the main thread's longest wait {longest:.4f} s")
    assert solution.converged
    assert longest < 0.25 * took
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        a, b = pool.map(lambda _: rc.solve(**keys), range(2))
    assert np.array_equal(a.pressure, b.pressure)
    assert np.array_equal(a.pressure, solution.pressure)


def test_threads_do_not_change_the_result():
    a = rc.solve(**SPHERE, approach=1e-9, threads=1)
    b = rc.solve(**SPHERE, approach=1e-9, threads=2)
    assert all(np.array_equal(a.fields[k], b.fields[k]) for k in a.fields)


def test_theory_sphere_on_a_layer():
    r, w0, e = 1e-6, 0.089, 1e9
    # A thick layer is the half-space: Hertz's load, JKR's pull-off.
    a = np.array([2e-8, 5e-8])
    thick = theory.layer(a, r, e, thickness=1e-4, poisson=0.45)
    assert thick["load"] == pytest.approx(4 * e * a**3 / (3 * r), rel=1e-6)
    assert thick["approach"] == pytest.approx(a**2 / r, rel=1e-6)
    off = theory.layer_pull_off(r, w0, e, thickness=1e-4, poisson=0.45)
    assert off["load"] == pytest.approx(-1.5 * np.pi * r * w0, rel=1e-6)
    # A film as thick as the contact radius pulls off harder (docs/validation.md: 1.176 times).
    film = theory.layer_pull_off(r, w0, e, thickness=6.8e-8, poisson=0.45)
    assert film["load"] / off["load"] == pytest.approx(1.176, abs=2e-3)
    coat = theory.layer(a, r, e, 6.8e-8, 0.3, "elastic", substrate_modulus=1e8, substrate_poisson=0.45)
    assert np.all(coat["load"] < thick["load"])
    with pytest.raises(ValueError, match="substrate_modulus"):
        theory.layer(a, r, e, 6.8e-8, 0.3, "elastic")
    with pytest.raises(ValueError, match="thickness"):
        theory.layer(a, r, e, -1.0, 0.3)


def test_theory_viscoelastic_sphere():
    solid = dict(radius=1e-3, modulus=1e6, maxwell_moduli=[9e6], maxwell_times=[1.0])
    # Creep under a held load on E0 / E_inf = 10: the radius grows by 10^(1/3).
    a = theory.viscoelastic_creep(np.array([0.0, 1e4]), load=1e-2, **solid)
    assert a[1] / a[0] == pytest.approx(10 ** (1 / 3), rel=1e-9)
    # Pressed in fast, it is the glassy Hertz; the contact grows as sqrt(R delta).
    t = np.array([1e-6])
    fast = theory.viscoelastic_indentation(t, rate=1e-3, rise_time=1.0, **solid)
    delta = 1e-3 * t
    assert fast["load"] == pytest.approx(4 / 3 * 1e7 * np.sqrt(1e-3) * delta**1.5, rel=1e-4)
    assert fast["contact_radius"] == pytest.approx(np.sqrt(1e-3 * delta), rel=1e-12)
    with pytest.raises(ValueError, match="maxwell_times values must be"):
        theory.viscoelastic_creep([1.0], 1e-3, 1e6, [9e6], [-1.0], 1e-2)
    with pytest.raises(ValueError, match="one time a branch modulus"):
        theory.viscoelastic_creep([1.0], 1e-3, 1e6, [9e6, 1e6], [1.0], 1e-2)


def test_theory_against_closed_forms():
    r, w0, e = 1e-6, 0.05, 1e9
    pull = theory.jkr_pull_off(r, w0)
    assert pull["load_control"] == pytest.approx(-1.5 * np.pi * r * w0, rel=1e-12)
    assert theory.dmt_pull_off(r, w0) == pytest.approx(-2 * np.pi * r * w0, rel=1e-12)
    h = theory.hertz(np.array([[1e-9, 4e-9]]), r, e)
    assert h["load"].shape == (1, 2)
    assert h["load"][0, 1] / h["load"][0, 0] == pytest.approx(8.0, rel=1e-12)  # P ~ delta^(3/2)
    # Maugis-Dugdale tends to JKR at large Tabor parameters, to DMT at small ones.
    assert theory.maugis_dugdale(100.0)["pull_off_load_control"] == pytest.approx(-1.5, abs=0.02)
    assert theory.maugis_dugdale(0.01)["pull_off_load_control"] == pytest.approx(-2.0, abs=0.02)
    g = theory.greenwood(1.0, max_approach=1.0, resolution=0.05, ring_width=0.05)
    assert g["load"].shape == g["approach"].shape and g["pull_off_load_control"] < 0
    small = np.array([1e-4])
    assert theory.persson_area(small)[0] / small[0] == pytest.approx(np.sqrt(8 / np.pi), rel=1e-6)
    assert theory.muser_area(small, k=2.0)[0] / small[0] == pytest.approx(2.0, rel=1e-6)
    assert theory.ciavarella(1e-9, 1e9, 1e-4, 0.05)["sticky"]
    wave = theory.wave(np.linspace(0, 0.4, 5), amplitude=0.01, wavelength=1.0, modulus=1e9)
    assert wave["westergaard"][0] == 0 and wave["johnson_alpha"] == 0
    assert theory.tabor_parameter(1e-6, 0.05, 1e9, 1e-9) == pytest.approx((1e-6 * 0.05**2 / (1e18 * 1e-27)) ** (1 / 3))
    with pytest.raises(ValueError, match="radius must be finite and > 0"):
        theory.hertz([1e-9], -1.0, e)


def test_warnings_of_the_problem_reach_python():
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        rc.solve(**dict(SPHERE, n=32, length=1.2e-7), approach=1e-9)
    assert any("adhesive range" in str(w.message) for w in caught)


SAMPLES = Path(__file__).resolve().parents[3] / "data" / "topography-samples"


def test_channels_of_an_instrument_file_and_reading_one_by_name():
    chans = rc.channels(SAMPLES / "di-3.di")
    assert [c["name"] for c in chans] == ["ZSensor", "AmplitudeError", "Phase", "Height"]
    assert [c["height"] for c in chans] == [True, False, False, True]
    assert chans[0]["length_x"] == pytest.approx(1e-5)
    default = rc.read(SAMPLES / "di-3.di")
    assert np.array_equal(default.heights, rc.read(SAMPLES / "di-3.di", channel=0).heights)
    height = rc.read(SAMPLES / "di-3.di", channel="height")
    assert height.heights.shape == (256, 256) and not np.array_equal(height.heights, default.heights)
    with pytest.raises(ValueError, match="'Phase' holds"):
        rc.read(SAMPLES / "di-3.di", channel="Phase")


def test_unmeasured_points_are_refused_or_filled():
    with pytest.raises(ValueError, match="117 of 272492 points are not measured"):
        rc.read(SAMPLES / "sur-2.sur")
    filled = rc.read(SAMPLES / "sur-2.sur", fill_unmeasured=True)
    assert filled.heights.shape == (484, 563) and np.isfinite(filled.heights).all()


def test_a_hardness_caps_the_pressure_and_leaves_a_permanent_set():
    rough = dict(rms_gradient=0.1, n=64, length=1e-4, modulus=1e9, seed=3)
    s = rc.solve(**rough, hardness=5e7, mean_pressure=1e7)
    assert s.converged and s.report["max_pressure"] == 5e7
    assert 0 < s.plastic_area_fraction < s.contact_area_fraction
    cell = (1e-4 / 64) ** 2
    assert s.plastic.shape == (64, 64) and np.all(s.plastic >= 0)
    assert abs(s.plastic.sum() * cell / s.permanent_set_volume - 1) < 1e-12
    assert abs(s.plastic_work - 5e7 * s.permanent_set_volume) <= 1e-12 * s.plastic_work
    elastic = rc.solve(**rough, mean_pressure=1e7)
    assert "plastic" not in elastic.fields and elastic.plastic_work == 0
    # A load-unload sweep keeps the set and reports the work dissipated by yielding.
    sw = rc.sweep(**SPHERE, hardness=2e7, from_=-3e-9, to=3e-9, steps=4)
    assert sw.all_converged and sw.plastic_work > 0 and sw.state["plastic"].max() > 0
    assert abs(sw.curve["plastic_work"].sum() - sw.plastic_work) <= 1e-12 * sw.plastic_work
    for bad in (0.0, -1.0):
        with pytest.raises(ValueError, match="hardness must be a finite H > 0 Pa"):
            rc.solve(**rough, hardness=bad, mean_pressure=1e7)
    with pytest.raises(ValueError, match="takes a hardness with the laws of a cell's own gap"):
        rc.solve(**SPHERE, law="surface_energy", hardness=2e7, approach=1e-9, solver="energy")
    exponential = {k: v for k, v in SPHERE.items() if k != "z0"}
    with pytest.raises(ValueError, match="attraction at contact"):
        rc.solve(**exponential, law="exponential", range=1e-9, hardness=2e7, approach=1e-9)


def test_a_viscoelastic_sphere_is_swept_in_time_between_its_elastic_limits():
    solid = dict(maxwell_moduli=[9e9], maxwell_times=[1.0])
    path = dict(from_=-3e-9, to=1e-9, steps=8)
    # Much slower and much faster than the branch: the relaxed and the glassy elastic sphere.
    for step_time, modulus in ((1e4, 1e9), (1e-6, 1e10)):
        swept = rc.sweep(**SPHERE, **solid, **path, step_time=step_time)
        assert np.array_equal(swept.curve["time"], step_time * np.arange(17))
        elastic = rc.sweep(**dict(SPHERE, modulus=modulus), **path)
        assert np.isnan(elastic.curve["time"]).all()
        assert abs(swept.pull_off_force / elastic.pull_off_force - 1) < 1e-3
    # At one relaxation time a step the dashpots take part of the work, step by step.
    middle = rc.sweep(**SPHERE, **solid, **path, step_time=1.0)
    assert middle.viscous_work > 0
    assert middle.viscous_work == pytest.approx(middle.curve["viscous_work"].sum(), rel=1e-12)
    assert (middle.curve["elastic_energy"] >= 0).all()
    with pytest.raises(ValueError, match="give each step a time"):
        rc.sweep(**SPHERE, **solid, **path)
    with pytest.raises(ValueError, match="this body is elastic"):
        rc.sweep(**SPHERE, **path, step_time=1.0)
    with pytest.raises(ValueError, match="maxwell_times must hold one time a branch modulus"):
        rc.sweep(**SPHERE, maxwell_moduli=[9e9], maxwell_times=[1.0, 2.0], **path, step_time=1.0)
    with pytest.raises(ValueError, match="on a viscoelastic body"):
        rc.solve(**SPHERE, **solid, approach=1e-9)


def test_a_film_takes_its_keywords_and_bad_ones_are_refused():
    smooth = {k: v for k, v in SPHERE.items() if k not in ("work_of_adhesion", "z0")}
    half = rc.solve(**smooth, approach=1e-9)
    film = rc.solve(**smooth, approach=1e-9, thickness=5e-8, poisson=0.45, layer_base="bonded")
    assert half.converged and film.converged
    # A film 50 nm thick on a rigid base pushes back harder than the half-space.
    assert film.load > 1.1 * half.load
    assert film.case["thickness"] == 5e-8 and film.case["layer_base"] == "bonded"
    with pytest.raises(ValueError, match="thickness must be a finite layer thickness"):
        rc.solve(**SPHERE, approach=1e-9, thickness=-1.0, poisson=0.3)
    with pytest.raises(ValueError, match="needs the layer.s poisson"):
        rc.solve(**SPHERE, approach=1e-9, thickness=5e-8)


def test_a_tangential_path_slips_and_refuses_what_it_cannot_take():
    sphere = dict(sphere_radius=1e-3, length=128e-6, n=128, modulus=1e9, poisson=0.3, load=0.0184)
    cycle = [1e-3, 2e-3, 4e-3, 2e-3, 0.0, -2e-3, -4e-3, -2e-3, 0.0, 2e-3, 4e-3]
    s = rc.solve(**sphere, friction_coefficient=0.3, tangential_loads=cycle)
    t = s.tangential
    assert t.all_converged and not t.gross_sliding
    # The static friction is mu times the load; the stick zone shrinks as Q grows.
    assert t.static_friction == pytest.approx(0.3 * 0.0184, rel=1e-9)
    assert t.stick_area_fraction[0] > t.stick_area_fraction[1] > t.stick_area_fraction[2]
    assert np.allclose(t.force_x, cycle, rtol=0, atol=1e-12)
    # A closed fretting loop dissipates what friction's sum says, and back at +Q* the same state.
    assert t.frictional_work[3:].sum() > 0
    assert t.displacement_x[-1] == pytest.approx(t.displacement_x[2], rel=1e-4)
    assert s.shear_x.shape == (128, 128) and s.slip_x.shape == (128, 128)
    plain = {k: v for k, v in sphere.items() if k != "poisson"}
    assert rc.solve(**plain).tangential is None
    with pytest.raises(ValueError, match="bound a tangential path"):
        rc.solve(**sphere, friction_coefficient=0.3)
    with pytest.raises(ValueError, match="needs friction"):
        rc.solve(**plain, tangential_loads=[1e-3])
    with pytest.raises(ValueError, match="friction_coefficient must be a finite number >= 0"):
        rc.solve(**sphere, friction_coefficient=-0.1, tangential_loads=[1e-3])
    with pytest.raises(ValueError, match="shear_strength must be a finite shear stress"):
        rc.solve(**sphere, shear_strength=-1.0, tangential_loads=[1e-3])
    # A rigid counterface couples the path to the normal contact: the load held, the approach moved.
    rigid = rc.solve(**sphere, friction_coefficient=0.3, counterface="rigid", tangential_loads=[2e-3, 4e-3])
    assert (rigid.tangential.coupling_iterations >= 2).all() and (t.coupling_iterations == 0).all()
    assert np.allclose(rigid.tangential.normal_load, 0.0184, rtol=1e-12)
    assert rigid.tangential.approach[1] != s.approach
    with pytest.raises(ValueError, match="counterface does not apply"):
        rc.solve(**plain, counterface="rigid")
    # More than the contact carries: it slides, reported, not a failure.
    slid = rc.solve(**sphere, friction_coefficient=0.3, tangential_loads=[1e-3, 1.0, 2.0])
    assert slid.tangential.gross_sliding and len(slid.tangential.steps) == 2
    assert np.isnan(slid.tangential.displacement_x[-1])
