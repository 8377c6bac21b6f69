"""ContactMechanics' penetration-hardness system on surface.npy: the fields roughcontact's
tests compare with. Usage: python cm_plastic.py surface.npy (in a virtualenv with
`pip install ContactMechanics SurfaceTopography numpy`)."""
import json
import sys
import time

import numpy as np
from ContactMechanics import PeriodicFFTElasticHalfSpace, make_plastic_system
from SurfaceTopography import PlasticTopography, Topography

path = sys.argv[1]
h = np.load(path)
n = h.shape[0]
cases = {0.03: (0.003, 0.01, 0.02), 0.1: (0.01, 0.03, 0.05)}
rows = []
for hardness, pressures in cases.items():
    for mean_pressure in pressures:
        # Unit box, E* = 1; heights as roughcontact reads them (peaks towards the half-space).
        substrate = PeriodicFFTElasticHalfSpace((n, n), 1.0, (1.0, 1.0))
        surface = PlasticTopography(Topography(h, (1.0, 1.0)), hardness)
        system = make_plastic_system(substrate=substrate, surface=surface)
        t = time.time()
        sol = system.minimize_proxy(external_force=mean_pressure, pentol=1e-12, forcetol=1e-12, maxiter=100000)
        dt = time.time() - t
        pressure = sol.jac / surface.area_per_pt
        name = f"cm_pressure_H{hardness}_p{mean_pressure}.npy"
        np.save(name, pressure)
        at_h = int((pressure >= hardness * (1 - 1e-9)).sum())
        rows.append(dict(hardness=hardness, mean_pressure=mean_pressure, converged=bool(sol.success),
                         iterations=int(sol.nit), time_s=dt, area=float((pressure > 0).mean()),
                         at_hardness=at_h, plastic_mask=int(sol.plastic.sum()), field=name))
        print(json.dumps(rows[-1]), flush=True)
json.dump(rows, open("cm_plastic.json", "w"), indent=1)
