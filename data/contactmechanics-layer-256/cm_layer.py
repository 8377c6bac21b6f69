"""ContactMechanics' finite-thickness periodic half-space on the plastic cross-check's
surface: the contact areas roughcontact's tests compare with. Usage:
python cm_layer.py ../contactmechanics-plastic-256/surface.npy (in a virtualenv with
`pip install ContactMechanics SurfaceTopography numpy`)."""
import json
import sys
import time

import numpy as np
from ContactMechanics import PeriodicFFTElasticHalfSpace
from ContactMechanics.Systems import NonSmoothContactSystem
from SurfaceTopography import Topography

h = np.load(sys.argv[1])
n = h.shape[0]
young, poisson = 1e9, 0.3
contact_modulus = young / (1 - poisson**2)
rows = []
for thickness in (1 / 16, 1 / 64):
    for share in (0.005, 0.02):
        mean_pressure = share * contact_modulus
        # Unit box; heights as roughcontact reads them (peaks towards the layer).
        substrate = PeriodicFFTElasticHalfSpace((n, n), young, (1.0, 1.0), thickness=thickness, poisson=poisson)
        system = NonSmoothContactSystem(substrate, Topography(h, (1.0, 1.0)))
        t = time.time()
        sol = system.minimize_proxy(external_force=mean_pressure, pentol=1e-12, maxiter=100000)
        dt = time.time() - t
        pressure = sol.jac / system.surface.area_per_pt
        rows.append(dict(thickness=thickness, poisson=poisson, young=young, mean_pressure=mean_pressure,
                         converged=bool(sol.success), iterations=int(sol.nit), time_s=dt,
                         contact_cells=int((pressure > 0).sum()), area=float((pressure > 0).mean())))
        print(json.dumps(rows[-1]), flush=True)
json.dump(rows, open("cm_layer.json", "w"), indent=1)
