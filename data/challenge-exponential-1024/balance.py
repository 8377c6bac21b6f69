"""The force balance of a gap field on the periodic half-space with the exponential law, in
units of E* and the box (E* = 1, unit box; see README.md), computed here and not by any of the
codes compared: the largest imbalance on the cells off the wall over the law's peak pressure
w0 / rho, the mean pressure (the multiplier of the mean gap), the contact area, the number of
cells on the wall held by tension, and the energy per unit area.

usage: python balance.py surface.npy GAP.npy W0 RHO
"""
import sys, json
import numpy as np

h = np.load(sys.argv[1])
g = np.load(sys.argv[2])
w0, rho = float(sys.argv[3]), float(sys.argv[4])
n = h.shape[0]
g0 = h.max() - h
u = g - g0  # the displacement, up to a constant the periodic operator ignores
q = 2 * np.pi * np.sqrt(np.add.outer(np.fft.fftfreq(n, 1 / n) ** 2, np.fft.rfftfreq(n, 1 / n) ** 2))
elastic = np.fft.irfft2(0.5 * q * np.fft.rfft2(u), s=(n, n))  # S u: pressure, compressive > 0
adhesive = -(w0 / rho) * np.exp(-g / rho)
free = g > 0
# Off the wall the elastic pressure plus the mean pressure balances the law's.
r = elastic - adhesive
mean_pressure = -r[free].mean()
r += mean_pressure
# On the wall the contact pressure (the rest) must be compressive.
contact_pressure = r[~free]
# Energy per unit area: elastic plus the law's (its potential -w0 exp(-g / rho)).
energy = 0.5 * (u * elastic).mean() - w0 * np.exp(-g / rho).mean()
print(json.dumps({
    "energy_per_area": float(energy),
    "contact_area_fraction": float((~free).mean()),
    "mean_pressure": float(mean_pressure),
    "largest_imbalance_over_law_peak": float(np.abs(r[free]).max() / (w0 / rho)),
    "tensile_contacts": int((contact_pressure < -1e-9 * w0 / rho).sum()),
    "mean_gap": float(g.mean()),
}))
