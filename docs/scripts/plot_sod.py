"""Sod shock tube: SPH density, velocity and pressure against the exact Riemann solution.
Usage: /usr/bin/python3 docs/scripts/plot_sod.py RUN/snap_000001.h5 docs/figures/sod.png
(RUN from: craterkit simulate data/examples/sod.toml --out RUN)"""
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from sod_exact import sample, star

snapshot, png = sys.argv[1], sys.argv[2]
left, right, g = (1.0, 0.0, 1.0), (0.125, 0.0, 0.1), 1.4
with h5py.File(snapshot, "r") as f:
    t = float(f.attrs["time"])
    x, rho, vx, p = (f[k][:] for k in ("x", "density", "vx", "pressure"))
keep = np.abs(x) < 0.5
xs = np.linspace(-0.5, 0.5, 2001)
rho_exact, ps, us = sample(xs / t, left, right, g)
l1 = np.abs(rho[keep] - sample(x[keep] / t, left, right, g)[0]).mean()
fig, axes = plt.subplots(1, 3, figsize=(13, 4))
axes[0].plot(x[keep], rho[keep], ".", ms=1, color="C0", label="SPH")
axes[0].plot(xs, rho_exact, "k-", label="exact (Toro)")
axes[0].set_ylabel("density")
axes[1].plot(x[keep], vx[keep], ".", ms=1, color="C0")
axes[1].axhline(us, color="k", lw=0.8, ls="--", label=f"u* = {us:.4f}")
axes[1].set_ylabel("velocity")
axes[2].plot(x[keep], p[keep], ".", ms=1, color="C0")
axes[2].axhline(ps, color="k", lw=0.8, ls="--", label=f"p* = {ps:.4f}")
axes[2].set_ylabel("pressure")
for ax in axes:
    ax.set_xlabel("x")
    ax.legend(fontsize=8)
axes[0].set_title(f"Sod, t = {t:g}, L1(rho) = {l1:.4f}")
fig.tight_layout()
fig.savefig(png, dpi=110)
print(f"L1 {l1:.5f}")
