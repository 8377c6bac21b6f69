"""ContactMechanics' penetration-hardness system on one surface, one thread: time, iterations,
contact and plastic cells, and the pressure field for the accuracy check.
Usage: OMP_NUM_THREADS=1 python cm_bench.py surface.npy HARDNESS MEAN_PRESSURE (E* = 1, unit box)."""
import json
import sys
import time

import numpy as np
from ContactMechanics import PeriodicFFTElasticHalfSpace, make_plastic_system
from SurfaceTopography import PlasticTopography, Topography

path, hardness, mean_pressure = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
h = np.load(path)
n = h.shape[0]
substrate = PeriodicFFTElasticHalfSpace((n, n), 1.0, (1.0, 1.0))
surface = PlasticTopography(Topography(h, (1.0, 1.0)), hardness)
system = make_plastic_system(substrate=substrate, surface=surface)
t = time.time()
sol = system.minimize_proxy(external_force=mean_pressure, pentol=1e-12, forcetol=1e-12, maxiter=1000000)
dt = time.time() - t
pressure = sol.jac / surface.area_per_pt
np.save(path.replace(".npy", "_cm_pressure.npy"), pressure)
print(json.dumps(dict(n=n, converged=bool(sol.success), iterations=int(sol.nit), time_s=dt,
                      contact_cells=int((pressure > 0).sum()),
                      cells_at_hardness=int((pressure >= hardness * (1 - 1e-9)).sum()))))
