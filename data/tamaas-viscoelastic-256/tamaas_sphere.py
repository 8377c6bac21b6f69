"""A paraboloid (R = 1) on a periodic 256^2 grid of side 1 under a held mean pressure
(1.3333e-3: the elastic E* = 1 Hertz radius 0.1), by Tamaas' MaxwellViscoelastic (backward
Euler), E = 1, nu = 0, one branch of shear modulus G relaxing in 1 s. Prints time [s] and the
contact radius sqrt(area / pi). Usage: python tamaas_sphere.py G DT END"""
import sys, numpy as np, tamaas as tm

g, dt, end = (float(a) for a in sys.argv[1:4])
n, side, r = 256, 1.0, 1.0
x = (np.arange(n) + 0.5) / n * side - side / 2
xx, yy = np.meshgrid(x, x, indexing="ij")
h = -(xx**2 + yy**2) / (2 * r)
h -= h.max()
model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [side, side], [n, n])
model.E, model.nu = 1.0, 0.0
solver = tm.MaxwellViscoelastic(model, h, 1e-12, dt, [g], [1.0])
print("time_s,contact_radius")
for k in range(1, int(round(end / dt)) + 1):
    solver.solve(1.3333e-3)
    p = np.array(model.traction)
    print(f"{k * dt:.4f},{np.sqrt((p > 0).sum() * (side / n) ** 2 / np.pi):.6f}", flush=True)
