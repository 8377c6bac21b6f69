"""Creep of a periodic rough contact on a standard linear solid under a held mean pressure,
by Tamaas' MaxwellViscoelastic (backward Euler). Writes tamaas_creep.csv: time [s], contact
area fraction, mean displacement [m]. Usage: python tamaas_creep.py surface.npy"""
import sys, numpy as np, tamaas as tm

h = np.load(sys.argv[1])
n = h.shape[0]
# E* = 1 relaxed (E = 1, nu = 0); one branch of plane-strain modulus 9 (shear modulus 4.5:
# Tamaas' branches are shear moduli at the model's Poisson's ratio, E_k* = 2 G_k / (1 - nu)),
# relaxing in 1 s; a mean pressure of 0.05, held from time 0.
pressure, dt, end = 0.05, 0.05, 20.0
model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], [n, n])
model.E, model.nu = 1.0, 0.0
solver = tm.MaxwellViscoelastic(model, h, 1e-12, dt, [4.5], [1.0])
with open("tamaas_creep.csv", "w") as out:
    out.write("time_s,contact_area_fraction,mean_displacement_m\n")
    for k in range(1, int(round(end / dt)) + 1):
        solver.solve(pressure)
        p = np.array(model.traction)
        u = np.array(model.displacement)
        out.write(f"{k * dt:.6e},{(p > 0).mean():.10e},{u.mean():.10e}\n")
