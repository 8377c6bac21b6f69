"""roughcontact from Python, as in a notebook: a rough surface, one solve, an adhesive
sphere's approach-retraction cycle beside Maugis-Dugdale, and a parameter study over seeds
with one solve a thread. Plots go to run/notebook/ when matplotlib is installed.

    pip install ./crates/python        # from the repository's root
    python examples/notebook.py
"""

import concurrent.futures
import os

import numpy as np

import roughcontact as rc
from roughcontact import theory

out = os.path.join("run", "notebook")
os.makedirs(out, exist_ok=True)

# 1. A self-affine surface: 256^2 points on 100 um, Hurst 0.8, roll-off 20 um, RMS gradient 1.
surface = rc.generate(n=256, length=1e-4, hurst=0.8, rolloff=2e-5, rms_gradient=1.0, seed=1)
stats = surface.statistics()
print(f"{surface}: Rq = {stats['rms_height']:.3e} m, RMS gradient {stats['rms_gradient']:.3f}")

# 2. Pressed by a mean pressure of 0.01 E* g_bar on an elastic half-space (E* = 25 MPa).
e_star = 25e6
solution = rc.solve(surface=surface, modulus=e_star, mean_pressure=0.01 * e_star)
print(
    f"contact area {solution.contact_area_fraction:.4f} (Persson: "
    f"{theory.persson_area(0.01):.4f}), max pressure {solution.pressure.max():.3e} Pa"
)

# 3. A rigid sphere (R = 1 um) with the paper's surface law at Tabor parameter ~1.4: a cycle.
sphere = dict(sphere_radius=1e-6, n=64, length=3e-7, modulus=1e9, work_of_adhesion=0.05, z0=1e-9)
mu = theory.tabor_parameter(1e-6, 0.05, 1e9, 1e-9)
cycle = rc.sweep(**sphere, from_=-3e-9, to=2e-9, steps=10)
unit = np.pi * 1e-6 * 0.05
md = theory.maugis_dugdale(mu)
print(
    f"pull-off {cycle.pull_off_force / unit:.3f} pi R w0 at mu = {mu:.2f}; Maugis-Dugdale: "
    f"{md['pull_off_load_control']:.3f}; all converged: {cycle.all_converged}"
)

# 4. A study over seeds: each solve in its own thread (the GIL is released while solving).
def area(seed):
    s = rc.generate(n=128, length=1e-4, rolloff=2e-5, rms_gradient=1.0, seed=seed)
    return rc.solve(surface=s, modulus=e_star, mean_pressure=0.01 * e_star, threads=1).contact_area_fraction


with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
    areas = list(pool.map(area, range(1, 9)))
print(f"contact area over 8 seeds: {np.mean(areas):.4f} +- {np.std(areas, ddof=1) / np.sqrt(len(areas)):.4f}")

# The same study with Dask, where it is installed (its threaded scheduler, one solve a task).
try:
    import dask
except ImportError:
    print("dask is not installed: the study ran with concurrent.futures only")
else:
    tasks = [dask.delayed(area)(seed) for seed in range(1, 9)]
    assert list(dask.compute(*tasks, scheduler="threads", num_workers=2)) == areas
    print("dask gives the same areas")

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    print("matplotlib is not installed: no plots")
else:
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    image = a.imshow(solution.pressure / 1e6, origin="lower", extent=(0, 100, 0, 100))
    a.set(title="contact pressure [MPa]", xlabel="x [um]", ylabel="y [um]")
    fig.colorbar(image, ax=a)
    curve = cycle.curve
    for branch, style in (("loading", "o-"), ("unloading", "v--")):
        on = curve["branch"] == branch
        b.plot(curve["approach"][on] / 1e-9, curve["load"][on] / unit, style, label=branch)
    b.set(title=f"sphere, mu = {mu:.2f}", xlabel="approach [z0]", ylabel="load [pi R w0]")
    b.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "notebook.png"), dpi=100)
    print(f"wrote {os.path.join(out, 'notebook.png')}")
