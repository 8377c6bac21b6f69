"""Numpy arrays in any layout are accepted (with the same result) or refused clearly."""

import json
import pathlib

import numpy as np
import pytest

import roughcontact as rc

KEYS = dict(modulus=25e6, mean_pressure=2e5)
ROOT = pathlib.Path(__file__).resolve().parents[3]


@pytest.fixture(scope="module")
def surface():
    return rc.generate(n=64, length=1e-4, rms_gradient=1.0, rolloff=2e-5, seed=2)


@pytest.fixture(scope="module")
def reference(surface):
    return rc.solve(surface=surface, **KEYS)


def same(a, b):
    return all(np.array_equal(a.fields[k], b.fields[k]) for k in a.fields)


def test_fortran_order(surface, reference):
    h = np.asfortranarray(surface.heights)
    assert not h.flags.c_contiguous
    assert same(rc.solve(surface=rc.Topography(h, surface.length_x), **KEYS), reference)


def test_strided_and_reversed_views(surface, reference):
    big = np.zeros((128, 128))
    big[::2, ::2] = surface.heights
    view = big[::2, ::2]
    assert not view.flags.c_contiguous
    assert same(rc.solve(surface=rc.Topography(view, surface.length_x), **KEYS), reference)
    flipped = np.ascontiguousarray(surface.heights[::-1, ::-1])[::-1, ::-1]
    assert flipped.strides[0] < 0
    assert same(rc.solve(surface=rc.Topography(flipped, surface.length_x), **KEYS), reference)


def test_float32_and_integers_are_converted_exactly(surface):
    h32 = surface.heights.astype(np.float32)
    a = rc.solve(surface=rc.Topography(h32, surface.length_x), **KEYS)
    b = rc.solve(surface=rc.Topography(h32.astype(np.float64), surface.length_x), **KEYS)
    assert same(a, b)
    t = rc.Topography(np.arange(12, dtype=np.int32).reshape(3, 4), 4.0)
    assert t.heights.dtype == np.float64 and t.shape == (3, 4) and t.dy == 1.0


@pytest.mark.parametrize(
    "heights, message",
    [
        (np.zeros((4, 4), dtype=complex), "real numbers"),
        (np.zeros((4, 4), dtype=bool), "real numbers"),
        (np.zeros((2, 4, 4)), "2-D array"),
        (np.zeros(16), "2-D array"),
        (np.full((4, 4), np.nan), "finite"),
        ([["a", "b"], ["c", "d"]], "real numbers"),
    ],
)
def test_bad_arrays_are_refused(heights, message):
    with pytest.raises(ValueError, match=message):
        rc.Topography(heights, 1e-4)


def test_a_bad_box_is_refused():
    with pytest.raises(ValueError, match="sides must be finite and > 0"):
        rc.Topography(np.zeros((4, 4)), -1.0)


def test_surfacetopography_layout():
    """SurfaceTopography indexes heights [x, y]; a Topography holds (ny, nx)."""

    class Like:
        physical_sizes = (2.0, 1.0)
        is_periodic = True
        unit = "m"

        def heights(self):
            return np.arange(8.0).reshape(4, 2)  # nx = 4, ny = 2

    t = rc.Topography.from_surfacetopography(Like())
    assert t.shape == (2, 4) and t.physical_sizes == (2.0, 1.0) and t.dx == t.dy == 0.5
    assert t.heights[1, 3] == Like().heights()[3, 1]


def test_a_surfacetopography_topography():
    """A real SurfaceTopography topography (CI installs it) round-trips with its layout."""
    st = pytest.importorskip("SurfaceTopography")
    ours = rc.generate(nx=32, ny=16, length_x=2e-5, length_y=1e-5, rolloff=5e-6, rms_height=1e-7, seed=1)
    theirs = st.Topography(ours.heights.T, physical_sizes=ours.physical_sizes, periodic=True, unit="m")
    assert theirs.nb_grid_pts == (32, 16)
    back = rc.Topography.from_surfacetopography(theirs)
    assert np.array_equal(back.heights, ours.heights) and back.physical_sizes == ours.physical_sizes
    assert theirs.rms_height_from_area() == pytest.approx(ours.statistics()["rms_height"], rel=1e-12)


@pytest.mark.parametrize("suffix", [".x3p", ".nc"])
def test_surfacetopography_reads_our_files_with_their_size(tmp_path, suffix):
    """Files for contact.engineering: SurfaceTopography (CI installs it) reads our X3P and
    NetCDF with the right grid, size and heights."""
    st = pytest.importorskip("SurfaceTopography")
    ours = rc.generate(nx=32, ny=16, length_x=2e-5, length_y=1e-5, rolloff=5e-6, rms_height=1e-7, seed=1)
    path = tmp_path / f"surface{suffix}"
    ours.write(path)
    theirs = st.read_topography(str(path))
    assert theirs.unit == "m" and theirs.nb_grid_pts == (32, 16)
    assert tuple(theirs.physical_sizes) == pytest.approx((2e-5, 1e-5), rel=1e-15)
    assert np.array_equal(theirs.heights().T, ours.heights)


# The instrument samples, with what SurfaceTopography reads from them.
SAMPLES = sorted(json.loads((ROOT / "data" / "topography-samples" / "readings.json").read_text()))


# Samples with unmeasured points, which SurfaceTopography masks and we refuse (with their
# count) unless asked to fill them.
UNMEASURED = {"sur-2.sur", "opd-1.opd", "frt-1.frt"}


@pytest.mark.parametrize("name", SAMPLES)
def test_samples_read_as_surfacetopography_reads_them_the_same_way_round(name):
    """Every instrument sample: the same heights as SurfaceTopography's (CI installs it), in
    metres, with its [x, y] indexing transposed to our (ny, nx); at the points it masks, ours
    are refused, or filled within the measured range."""
    st = pytest.importorskip("SurfaceTopography")
    path = ROOT / "data" / "topography-samples" / name
    theirs = st.read_topography(str(path))
    scale = {"m": 1.0, "mm": 1e-3, "µm": 1e-6, "nm": 1e-9}[theirs.unit]
    heights = np.ma.masked_invalid(theirs.heights().T * scale)
    if name in UNMEASURED:
        with pytest.raises(ValueError, match=f"{np.ma.count_masked(heights)} of .* points are not measured"):
            rc.read(path)
    ours = rc.read(path, fill_unmeasured=name in UNMEASURED, max_unmeasured=1.0 if name in UNMEASURED else None)
    assert ours.shape == heights.shape
    measured = ~np.ma.getmaskarray(heights)
    np.testing.assert_allclose(
        ours.heights[measured], heights.data[measured], rtol=1e-9, atol=1e-9 * np.abs(heights).max()
    )
    filled = ours.heights[~measured]
    assert np.all((filled >= heights.min()) & (filled <= heights.max()))


def test_we_read_what_surfacetopography_writes_as_gwyddion(tmp_path):
    """Gwyddion's format, written by an independent writer (SurfaceTopography's), read back
    with its grid, size and heights."""
    st = pytest.importorskip("SurfaceTopography")
    heights = np.random.default_rng(3).normal(size=(32, 16)) * 1e-7  # SurfaceTopography's [x, y]
    theirs = st.Topography(heights, (2e-5, 1e-5), unit="m")
    theirs.to_gwy(str(tmp_path / "theirs.gwy"))
    ours = rc.read(tmp_path / "theirs.gwy")
    assert ours.shape == (16, 32) and ours.physical_sizes == pytest.approx((2e-5, 1e-5), rel=1e-15)
    assert np.array_equal(ours.heights, heights.T)
