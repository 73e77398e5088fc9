"""Plate impact: pressure and particle velocity along x against the impedance match.
Usage: /usr/bin/python3 docs/scripts/plot_plates.py RUN/snap_000002.h5 P_MATCH_PA U_MATCH docs/figures/plates.png
(RUN from: craterkit simulate data/examples/plates.toml --out RUN; P_MATCH and U_MATCH from the impedance
match of tests/support/hugoniot.hpp, printed by test_engine_physics --gtest_filter=PlateImpact.*)"""
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

snapshot, p_match, u_match, png = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), sys.argv[4]
with h5py.File(snapshot, "r") as f:
    t = float(f.attrs["time"])
    x, vx, p, material = (f[k][:] for k in ("x", "vx", "pressure", "material"))
fig, axes = plt.subplots(1, 2, figsize=(11, 4))
for m, name in ((0, "aluminium"), (1, "basalt")):
    s = material == m
    axes[0].plot(x[s] * 1e3, p[s] * 1e-9, ".", ms=2, label=name)
    axes[1].plot(x[s] * 1e3, vx[s], ".", ms=2, label=name)
axes[0].axhline(p_match * 1e-9, color="k", ls="--", lw=0.8, label=f"impedance match {p_match * 1e-9:.2f} GPa")
axes[1].axhline(u_match, color="k", ls="--", lw=0.8, label=f"impedance match {u_match:.0f} m/s")
axes[0].set_ylabel("pressure (GPa)")
axes[1].set_ylabel("velocity (m/s)")
for ax in axes:
    ax.set_xlabel("x (mm)")
    ax.legend(fontsize=8)
fig.suptitle(f"Aluminium plate on basalt plate at 2 km/s, t = {t * 1e6:g} us")
fig.tight_layout()
fig.savefig(png, dpi=110)
