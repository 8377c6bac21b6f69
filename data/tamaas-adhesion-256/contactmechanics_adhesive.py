"""ContactMechanics 1.8.3 + Adhesion 0.93 + NuMPI 0.18 (PyPI) on the adhesive benchmark problem
(see README.md): exponential adhesion on a periodic rough surface, E* = 1, unit box, mean gap
held by NuMPI's constrained conjugate gradients (Bugnicourt et al. 2018) on the gap.

usage: python contactmechanics_adhesive.py surface.npy MEAN_GAP W0 RHO GTOL
Writes cm_gap.npy and prints iterations and wall time as JSON.
"""
import sys, time, json
import numpy as np
from SurfaceTopography import Topography
from ContactMechanics import PeriodicFFTElasticHalfSpace
from Adhesion.Interactions import Exponential
from Adhesion.System import BoundedSmoothContactSystem
from NuMPI.Optimization import constrained_conjugate_gradients

h = np.load(sys.argv[1])
mean_gap, w0, rho, gtol = (float(a) for a in sys.argv[2:6])
n = h.shape[0]
topography = Topography(h, physical_sizes=(1.0, 1.0), periodic=True)
substrate = PeriodicFFTElasticHalfSpace((n, n), 1.0, physical_sizes=(1.0, 1.0))
system = BoundedSmoothContactSystem(substrate, Exponential(w0, rho), topography)
g0 = h.max() - h
x0 = np.maximum(g0 - (g0.mean() - mean_gap), 0.0)
t = time.time()
result = constrained_conjugate_gradients(
    system.primal_objective(0, gradient=True), system.primal_hessian_product,
    x0=x0.reshape(-1), mean_val=mean_gap, gtol=gtol, maxiter=100000)
wall = time.time() - t
gap = result.x.reshape(n, n)
np.save("cm_gap.npy", gap)
print(json.dumps({"success": bool(result.success), "iterations": int(result.nit), "time_s": wall,
                  "contact_area_fraction": float((gap == 0).mean())}))
