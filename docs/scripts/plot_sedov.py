"""Sedov blast: SPH density against the similarity solution.
Usage: /usr/bin/python3 docs/scripts/plot_sedov.py RUN/snap_000002.h5 docs/figures/sedov_density.png
(RUN from: craterkit simulate data/examples/sedov.toml --out RUN)"""
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from sedov_exact import profiles, xi0

snapshot, png = sys.argv[1], sys.argv[2]
with h5py.File(snapshot, "r") as f:
    t = float(f.attrs["time"])
    x, y, z, rho = (f[k][:] for k in ("x", "y", "z", "density"))
    n = len(rho)
r = np.sqrt(x * x + y * y + z * z)
x0 = xi0()
radius = x0 * (t * t) ** 0.2  # E = rho0 = 1
xi, psi, _, _ = profiles()
edges = np.arange(0, 0.5, 0.5 / round(n ** (1 / 3)))
centres = 0.5 * (edges[1:] + edges[:-1])
binned = np.array([rho[(r >= a) & (r < b)].mean() if np.any((r >= a) & (r < b)) else np.nan for a, b in zip(edges[:-1], edges[1:])])
fig, ax = plt.subplots(figsize=(7, 4.5))
ax.plot(r, rho, ",", color="0.6", label=f"SPH particles ({n} particles)")
ax.plot(centres, binned, "o-", ms=3, color="C0", label="SPH, binned (0.5 dx shells)")
ax.plot(np.concatenate([xi * radius, [radius, radius, 0.5]]), np.concatenate([psi, [psi[-1], 1.0, 1.0]]), "k-", label=f"Sedov (xi0 = {x0:.5f}), r_s = {radius:.4f}")
ax.set_xlim(0, 0.5)
ax.set_xlabel("r (m)")
ax.set_ylabel("density (kg/m^3)")
ax.set_title(f"Sedov-Taylor blast, E = 1, gamma = 5/3, t = {t:g} s")
ax.legend()
fig.tight_layout()
fig.savefig(png, dpi=120)
print(f"binned peak {np.nanmax(binned):.3f}, r_s analytic {radius:.5f}")
