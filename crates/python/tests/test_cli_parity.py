"""The same case through Python and through the command line gives bit-identical fields."""

import json
import subprocess

import numpy as np

import roughcontact as rc

ROUGH = dict(
    n=64, length=1e-4, rms_gradient=1.0, hurst=0.8, rolloff_wavelength=2e-5, seed=3, modulus=25e6
)
SPHERE = dict(sphere_radius=1e-6, n=64, length=3e-7, modulus=1e9, work_of_adhesion=0.05, z0=1e-9)


def flags(keys):
    out = []
    for k, v in keys.items():
        out.append("--" + k.replace("_", "-"))
        out.append(",".join(repr(x) for x in v) if isinstance(v, list) else v if isinstance(v, str) else repr(v))
    return out


def run(cli, command, keys, out):
    subprocess.run([cli, command, *flags(keys), "--out", str(out), "--no-png"], check=True, capture_output=True)
    return json.loads((out / "summary.json").read_text())


def test_non_adhesive_rough_solve(cli, tmp_path):
    keys = dict(ROUGH, mean_pressure=0.01 * 25e6)
    summary = run(cli, "solve", keys, tmp_path)
    solution = rc.solve(**keys)
    for name in ("pressure", "gap", "displacement"):
        assert np.array_equal(np.load(tmp_path / f"{name}.npy"), solution.fields[name]), name
    assert solution.load == summary["load"]
    assert solution.surface_hash == summary["surface_hash"]


def test_adhesive_sphere_solve(cli, tmp_path):
    keys = dict(SPHERE, approach=1e-9)
    summary = run(cli, "solve", keys, tmp_path)
    solution = rc.solve(**keys)
    assert set(solution.fields) == {"pressure", "compressive_pressure", "adhesive_pressure", "gap", "displacement"}
    for name, field in solution.fields.items():
        assert np.array_equal(np.load(tmp_path / f"{name}.npy"), field), name
    assert solution.load == summary["load"]
    assert solution.report["iterations"] == summary["iterations"]


def test_sweep_with_a_surface_in_memory(cli, tmp_path):
    """A Topography passed as ``surface`` solves as its file does on the command line."""
    surface = rc.generate(n=64, length=1e-4, rms_gradient=1.0, rolloff=2e-5, seed=5)
    surface.write(tmp_path / "surface.npy")
    keys = dict(modulus=25e6, mean_pressures=[1e5, 2e5, 1e5])
    run(cli, "sweep", dict(keys, surface=str(tmp_path / "surface.npy")), tmp_path / "run")
    result = rc.sweep(surface=surface, **keys)
    rows = (tmp_path / "run" / "curve.csv").read_text().splitlines()[1:]
    assert [float(r.split(",")[2]) for r in rows] == list(result.curve["load"])
    assert [float(r.split(",")[4]) for r in rows] == list(result.curve["contact_area_fraction"])


def test_pull_off_search_as_on_the_command_line(cli, tmp_path):
    """A path in, then the pull-off search: the same loads, step for step, and the same force."""
    keys = dict(SPHERE, n=32, law="point", from_=-3e-9, to=1e-9, steps=4, pull_off_step=1e-9, pull_off_floor=-8e-9)
    cli_keys = {("from" if k == "from_" else k): v for k, v in keys.items()}
    summary = run(cli, "sweep", cli_keys, tmp_path)
    result = rc.sweep(**keys)
    rows = (tmp_path / "curve.csv").read_text().splitlines()[1:]
    assert [float(r.split(",")[2]) for r in rows] == list(result.curve["load"])
    assert result.pull_off_force == summary["pull_off_force"] < 0
