"""Tamaas 2.9 reference for adhesive contact with the exponential law (see README.md).

usage: python tamaas_adhesive.py surface.npy MEAN_GAP W0 RHO TOL
"""
import sys, time, json, numpy as np, tamaas as tm

path = sys.argv[1]
mean_gap, w0, rho, tol = (float(a) for a in sys.argv[2:6])
h = np.load(path)
n = h.shape[0]
model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], [n, n])
model.E = 1.0
model.nu = 0.0
solver = tm.PolonskyKeerRey(model, h, tol, tm.PolonskyKeerRey.gap, tm.PolonskyKeerRey.gap)
adhesion = tm.ExponentialAdhesionFunctional(h)
adhesion.parameters = {"rho": rho, "surface_energy": w0}
solver.addFunctionalTerm(adhesion)
solver.max_iter = 100000
t = time.time()
solver.solve(mean_gap)
dt = time.time() - t
p = np.array(model.traction).reshape(n, n)
g = np.array(model["gap"]).reshape(n, n)
np.save("tamaas_pressure.npy", p)
np.save("tamaas_gap.npy", g)
print(json.dumps({"n": n, "time_s": dt, "mean_pressure": float(p.mean()), "mean_gap": float(g.mean()),
                  "contact_area_fraction": float((g == 0).mean())}))
