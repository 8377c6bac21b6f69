"""Tamaas 2.9's tangential contact (PolonskyKeerTan, Coulomb friction) on surface.npy.

Usage: python tamaas_tangential.py surface.npy MEAN_PRESSURE MU RATIO... (in a scratch
virtualenv: pip install tamaas numpy). E = 1, nu = 0.5 (E* = 4/3, no normal-tangential
coupling), unit box. Each ratio Q / (mu P) is loaded from zero along the surface array's
second axis (the roughcontact grid's x; Tamaas's own first axis is the array's first).
Writes tamaas_shear_x_R.npy, tamaas_shear_y_R.npy, tamaas_pressure.npy and prints one JSON
line per ratio.
"""
import sys, time, json, numpy as np, tamaas as tm

path, p_mean, mu = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
ratios = [float(r) for r in sys.argv[4:]]
h = np.load(path)
n = h.shape[0]
for ratio in ratios:
    model = tm.ModelFactory.createModel(tm.model_type.surface_2d, [1.0, 1.0], [n, n])
    model.E = 1.0
    model.nu = 0.5
    solver = tm.PolonskyKeerTan(model, h, 1e-8, mu)
    solver.max_iter = 20000
    t0 = time.time()
    error = solver.solve([0.0, ratio * mu * p_mean, p_mean])
    dt = time.time() - t0
    t = np.array(model.traction)
    p, qx, qy = t[..., 2], t[..., 1], t[..., 0]
    np.save("tamaas_pressure.npy", p)
    np.save(f"tamaas_shear_x_{ratio}.npy", qx)
    np.save(f"tamaas_shear_y_{ratio}.npy", qy)
    stick = (p > 0) & (np.hypot(qx, qy) < mu * p * (1 - 1e-9))
    print(json.dumps({"ratio": ratio, "error": error, "time_s": dt, "contact": int((p > 0).sum()),
                      "stick": int(stick.sum()), "mean_qx": float(qx.mean())}))
