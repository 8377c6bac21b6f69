import sys, time, json, numpy as np, tamaas as tm
path, p_over_e, tol = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
h = np.load(path)
n = h.shape[0]
model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], [n, n])
model.E = 1.0; model.nu = 0.0
solver = tm.PolonskyKeerRey(model, h, tol)
t = time.time()
solver.solve(p_over_e)
dt = time.time() - t
p = np.array(model.traction).reshape(n, n)
u = np.array(model.displacement).reshape(n, n)
np.save(path.replace('.npy', '_tamaas_pressure.npy'), p)
print(json.dumps({"n": n, "time_s": dt, "mean_p": float(p.mean()), "area": float((p > 0).mean())}))
