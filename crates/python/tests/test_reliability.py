"""Bad input a new user gives the Python package, each with a clear error that names the
keyword, the value and what is expected, or a result in the units it says (docs/reliability.md)."""

import inspect
import pathlib

import numpy as np
import pytest

import roughcontact as rc

ROOT = pathlib.Path(__file__).resolve().parents[3]
SPHERE = dict(sphere_radius=1e-6, length=1e-7, n=32, modulus=1e9)


def test_a_surfacetopography_topography_in_nanometres_becomes_metres():
    st = pytest.importorskip("SurfaceTopography")
    path = ROOT / "data" / "topography-samples" / "di-1.di"
    theirs = st.read_topography(str(path))
    assert theirs.unit == "nm"
    ours = rc.Topography.from_surfacetopography(theirs)
    direct = rc.read(path)
    assert ours.physical_sizes == pytest.approx(direct.physical_sizes, rel=1e-12)
    assert ours.statistics()["rms_height"] == pytest.approx(direct.statistics()["rms_height"], rel=1e-6)

    class NoUnit:
        physical_sizes = (1.0, 1.0)
        unit = None

        def heights(self):
            return np.zeros((4, 4))

    with pytest.raises(ValueError, match="the topography has no unit"):
        rc.Topography.from_surfacetopography(NoUnit())
    NoUnit.unit = "furlong"
    with pytest.raises(ValueError, match="'furlong' is not a length unit"):
        rc.Topography.from_surfacetopography(NoUnit())


def test_a_bare_array_as_surface_says_how_to_wrap_it():
    with pytest.raises(ValueError, match=r"surface: an array of heights needs its box: pass surface=roughcontact.Topography"):
        rc.solve(surface=np.zeros((64, 64)), modulus=1e9, mean_pressure=1e5)


def test_whole_numbers_are_as_strict_everywhere():
    with pytest.raises(ValueError, match=r"`n` must be a whole number >= 0, got 64.0"):
        rc.generate(n=64.0)
    with pytest.raises(ValueError, match=r"`n` must be a whole number >= 0, got 32.0"):
        rc.solve(**dict(SPHERE, n=32.0), approach=1e-9)
    assert rc.generate(n=np.int64(32), length=1e-6, rolloff=2e-7).shape == (32, 32)


def test_sizes_that_would_be_dropped_are_refused(tmp_path):
    with pytest.raises(ValueError, match=r"give n \(a square grid\) or nx and ny, not both"):
        rc.generate(n=32, nx=64)
    surface = rc.generate(n=32, length=1e-6, rolloff=2e-7)
    path = tmp_path / "s.npy"
    surface.write(path)
    with pytest.raises(ValueError, match=r"so `length` = 1e0 m does not apply"):
        rc.solve(surface=str(path), length=1.0, modulus=1e9, mean_pressure=1e5)
    with pytest.raises(ValueError, match=r"`length` applies to a surface file"):
        rc.solve(surface=surface, length=1.0, modulus=1e9, mean_pressure=1e5)
    with pytest.raises(ValueError, match=r"so `length` = 1e0 m does not apply"):
        rc.read(path, length=1.0)


def test_messages_are_one_line_of_words():
    for call in (
        lambda: rc.solve(**dict(SPHERE, surface=[1, 2]), approach=1e-9),
        lambda: rc.solve(**dict(SPHERE, n=[1]), approach=1e-9),
        lambda: rc.solve(**dict(SPHERE, law="bogus"), approach=1e-9),
    ):
        with pytest.raises(ValueError) as e:
            call()
        message = str(e.value)
        assert "\n" not in message and message == message.strip(), message
        for leak in ("invalid type", "expected usize", "path string", "sequence"):
            assert leak not in message, message


def test_theory_functions_broadcast_over_every_number():
    r = np.array([1e-6, 2e-6])
    mu = rc.theory.tabor_parameter(r, 0.05, 1e9, 1e-9)
    assert mu.shape == (2,) and mu[1] == pytest.approx(mu[0] * 2 ** (1 / 3))
    assert isinstance(rc.theory.tabor_parameter(1e-6, 0.05, 1e9, 1e-9), float)
    pull = rc.theory.jkr_pull_off(r, 0.05)
    assert pull["load_control"] == pytest.approx(-1.5 * np.pi * r * 0.05)
    h = rc.theory.hertz(np.array([[1e-9], [2e-9]]), r, 1e9)
    assert h["load"].shape == (2, 2)
    assert h["load"][1, 0] == pytest.approx(rc.theory.hertz(2e-9, 1e-6, 1e9)["load"])
    assert rc.theory.dmt_pull_off(r, 0.05) == pytest.approx(-2 * np.pi * r * 0.05)
    assert rc.theory.ciavarella(np.array([1e-9, 1e-6]), 1e9, 1e-4, 0.05)["sticky"].tolist() == [True, False]
    with pytest.raises(ValueError, match="tabor takes one number a call"):
        rc.theory.maugis_dugdale(np.array([0.1, 1.0]))


def test_the_sweep_docstring_shows_what_works():
    assert "cycle[" not in inspect.getdoc(rc.sweep)
