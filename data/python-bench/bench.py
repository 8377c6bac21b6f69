"""The same 1024^2 problems from Python with roughcontact, Tamaas 2.9 and ContactMechanics 1.8 /
Adhesion 0.93, one run each, one after the other (docs/performance.md, "From Python").

Problems (unit box, E* = 1, surface made by roughcontact: H = 0.8, no roll-off plateau,
cut-off 8 cells, RMS gradient 1, seed 2026):
- non-adhesive, mean pressure 0.01 E* g_bar;
- adhesive, exponential law w0 = 1e-3, range 2 cells, at mean gap 0.08.
Accuracy is measured against roughcontact at a tight tolerance: the largest pressure
difference over the largest pressure (non-adhesive) or the largest gap difference over the
law's range (adhesive), and the cells whose contact state differs.

usage (a venv with numpy, tamaas==2.9.0, ContactMechanics, Adhesion and roughcontact):
    OMP_NUM_THREADS=1 python bench.py [N]
"""

import json
import sys
import time

import numpy as np

import roughcontact as rc

n = int(sys.argv[1]) if len(sys.argv) > 1 else 1024
surface = rc.generate(n=n, length=1.0, rolloff=1.0, cutoff=8.0 / n, rms_gradient=1.0, seed=2026)
h = surface.heights
p_mean, w0, rho, mean_gap = 0.01, 1e-3, 2.0 / n, 0.08
rows = []


def timed(f):
    t = time.perf_counter()
    out = f()
    return out, time.perf_counter() - t


def report(problem, tool, setting, wall, iterations, accuracy, differing):
    rows.append(dict(problem=problem, tool=tool, setting=setting, wall_s=wall, iterations=iterations,
                     accuracy=accuracy, differing_cells=differing))
    print(json.dumps(rows[-1]), flush=True)


# Non-adhesive, mean pressure 0.01.
def ours_plain(tolerance, threads=1):
    return rc.solve(surface=surface, modulus=1.0, mean_pressure=p_mean, tolerance=tolerance, threads=threads)


ref = ours_plain(1e-13).pressure
pmax = ref.max()


def judge(p):
    return float(np.abs(p - ref).max() / pmax), int(((p > 0) != (ref > 0)).sum())


for tol in (1e-6, 1e-8, 1e-10):
    s, wall = timed(lambda: ours_plain(tol))
    report("non-adhesive", "roughcontact", f"tolerance {tol:g}, 1 thread", wall, s.report["iterations"], *judge(s.pressure))
s, wall = timed(lambda: ours_plain(1e-8, threads=2))
report("non-adhesive", "roughcontact", "tolerance 1e-08, 2 threads", wall, s.report["iterations"], *judge(s.pressure))

import tamaas as tm  # noqa: E402

for tol in (1e-6, 1e-8, 1e-10):
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], [n, n])
    model.E, model.nu = 1.0, 0.0
    solver = tm.PolonskyKeerRey(model, h, tol, tm.PolonskyKeerRey.pressure, tm.PolonskyKeerRey.pressure)
    solver.max_iter = 100000
    _, wall = timed(lambda: solver.solve(p_mean))
    p = np.array(model.traction).reshape(n, n)
    report("non-adhesive", "Tamaas 2.9", f"tolerance {tol:g}", wall, None, *judge(p))

from ContactMechanics import PeriodicFFTElasticHalfSpace, make_system  # noqa: E402
from SurfaceTopography import Topography  # noqa: E402

topography = Topography(h.T, physical_sizes=(1.0, 1.0), periodic=True)
for pentol in (1e-6 * h.std(), 1e-8 * h.std()):
    substrate = PeriodicFFTElasticHalfSpace((n, n), 1.0, physical_sizes=(1.0, 1.0))
    system = make_system(substrate=substrate, surface=topography)
    result, wall = timed(lambda: system.minimize_proxy(external_force=p_mean, pentol=pentol, maxiter=100000))
    p = np.asarray(result.jac).T * n * n  # forces on pixels of area 1/n^2
    report("non-adhesive", "ContactMechanics 1.8", f"pentol {pentol / h.std():g} Rq", wall, int(result.nit), *judge(p))

# Adhesive: the exponential law at mean gap 0.08.
def ours_adhesive(tolerance, threads=1):
    return rc.solve(surface=surface, modulus=1.0, law="exponential", work_of_adhesion=w0, range=rho,
                    mean_gap=mean_gap, tolerance=tolerance, threads=threads)


gref = ours_adhesive(1e-12).gap


def judge_gap(g):
    return float(np.abs(g - gref).max() / rho), int(((g == 0) != (gref == 0)).sum())


for tol in (1e-6, 1e-8, 1e-10):
    s, wall = timed(lambda: ours_adhesive(tol))
    report("adhesive", "roughcontact", f"tolerance {tol:g}, 1 thread", wall, s.report["iterations"]["iterations"], *judge_gap(s.gap))
s, wall = timed(lambda: ours_adhesive(1e-8, threads=2))
report("adhesive", "roughcontact", "tolerance 1e-08, 2 threads", wall, s.report["iterations"]["iterations"], *judge_gap(s.gap))

for tol in (1e-7, 1e-10):
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], [n, n])
    model.E, model.nu = 1.0, 0.0
    solver = tm.PolonskyKeerRey(model, h, tol, tm.PolonskyKeerRey.gap, tm.PolonskyKeerRey.gap)
    adhesion = tm.ExponentialAdhesionFunctional(h)
    adhesion.parameters = {"rho": rho, "surface_energy": w0}
    solver.addFunctionalTerm(adhesion)
    solver.max_iter = 100000
    _, wall = timed(lambda: solver.solve(mean_gap))
    g = np.array(model["gap"]).reshape(n, n)
    report("adhesive", "Tamaas 2.9", f"tolerance {tol:g}", wall, None, *judge_gap(g))

from Adhesion.Interactions import Exponential  # noqa: E402
from Adhesion.System import BoundedSmoothContactSystem  # noqa: E402
from NuMPI.Optimization import constrained_conjugate_gradients  # noqa: E402

substrate = PeriodicFFTElasticHalfSpace((n, n), 1.0, physical_sizes=(1.0, 1.0))
system = BoundedSmoothContactSystem(substrate, Exponential(w0, rho), topography)
g0 = h.T.max() - h.T
x0 = np.maximum(g0 - (g0.mean() - mean_gap), 0.0)
for gtol in (1e-10, 1e-12):
    result, wall = timed(lambda: constrained_conjugate_gradients(
        system.primal_objective(0, gradient=True), system.primal_hessian_product,
        x0=x0.reshape(-1), mean_val=mean_gap, gtol=gtol, maxiter=100000))
    g = result.x.reshape(n, n).T
    report("adhesive", "ContactMechanics/Adhesion", f"gtol {gtol:g}", wall, int(result.nit), *judge_gap(g))

print("\n| problem | tool | setting | iterations | wall [s] | accuracy | cells differing |")
print("|---|---|---|---|---|---|---|")
for r in rows:
    print(f"| {r['problem']} | {r['tool']} | {r['setting']} | {r['iterations'] or ''} | {r['wall_s']:.2f} | "
          f"{r['accuracy']:.1e} | {r['differing_cells']} |")
