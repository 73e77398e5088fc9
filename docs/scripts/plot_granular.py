"""Granular flow under gravity: tilted layer, column collapses, vertical cut.
Usage: /usr/bin/python3 docs/scripts/plot_granular.py DIR docs/figures/granular.png
DIR holds the CSV files the tests write when CRATERKIT_VALIDATION_OUTPUT=DIR is set:
  CRATERKIT_VALIDATION_OUTPUT=DIR build/tests/sph_core/test_engine_granular
  CRATERKIT_VALIDATION_OUTPUT=DIR build/tests/sph_core/test_engine_granular_slow   (deposit_*.csv,
                                                                                  pile_f0*.csv, collapse_a150.csv)
Files that are missing are skipped."""
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

directory, png = sys.argv[1], sys.argv[2]


def read(name):
    path = os.path.join(directory, name)
    if not os.path.exists(path):
        return None, None
    with open(path) as f:
        comment = f.readline().strip("# \n")
    return comment, np.loadtxt(path, delimiter=",", comments="#")


def theta(f):
    """Angle of repose from f = 2 sqrt(2) sin(theta) / (3 - sin(theta)) (Luther et al. 2022), degrees."""
    return math.degrees(math.asin(3 * f / (2 * math.sqrt(2) + f)))


fig, axes = plt.subplots(3, 2, figsize=(12, 12.5))

# (a) tilted layer: end-of-tilt mean downslope speed against the slope angle.
ax = axes[0, 0]
for f, colour in ((0.4, "C0"), (0.7, "C1")):
    comment, data = read(f"tilt_f{round(100 * f):03d}.csv")
    if data is None:
        continue
    ax.plot(data[:, 0], data[:, 1], "o-", color=colour, ms=3, label=f"f = {f}: {comment.split()[-1]}")
    ax.axvline(theta(f), color=colour, ls="--", lw=1)
    ax.axvspan(theta(f) - 3, theta(f) + 3, color=colour, alpha=0.08)
    ax.axvline(math.degrees(math.atan(f)), color=colour, ls=":", lw=1)
ax.axhline(0.005, color="k", lw=0.6)
ax.set_xlabel("slope angle (deg)")
ax.set_ylabel("mean downslope speed (2nd half of each tilt) / sqrt(g D)")
ax.set_title("(a) tilted layer: dashed theta(f) +- 3 deg, dotted atan(f)")
ax.legend(fontsize=8)

# (b) collapse deposits (surface profiles), normalised by the initial column.
ax = axes[0, 1]
for name, label, h0, l0 in (("deposit_f055.csv", "a = 0.5, f = 0.55 (slow)", 0.08, 0.16),
                            ("deposit_a100.csv", "a = 1, f = 0.55 (slow)", 0.08, 0.08),
                            ("collapse_a150.csv", "a = 1.5, f = 0.55", 0.09, 0.06),
                            ("deposit_f040.csv", "a = 0.5, f = 0.4 (slow)", 0.08, 0.16),
                            ("deposit_f070.csv", "a = 0.5, f = 0.7 (slow)", 0.08, 0.16)):
    comment, data = read(name)
    if data is None:
        continue
    line, = ax.plot(data[:, 0] / l0, data[:, 1] / h0, "-", lw=1.2, label=label)
    ax.plot([0, 1, 1], [1, 1, 0], ":", color=line.get_color(), lw=0.8)
ax.set_xlabel("x / L0")
ax.set_ylabel("surface height / H0")
ax.set_title("(b) collapse deposits (dotted: initial column)")
ax.legend(fontsize=8)

# (c) run-out against aspect ratio: Lube et al. (2005) 1.2 a with the +-20 % band.
ax = axes[1, 0]
a = np.linspace(0, 2, 50)
ax.plot(a, 1.2 * a, "k-", label="Lube et al. 2005: 1.2 a")
ax.fill_between(a, 0.96 * a, 1.44 * a, color="k", alpha=0.08, label="+-20 %")
for name, aspect, marker in (("deposit_f055.csv", 0.5, "D"), ("deposit_a100.csv", 1.0, "o"),
                             ("collapse_a150.csv", 1.5, "s"),
                             ("deposit_f040.csv", 0.5, "^"), ("deposit_f070.csv", 0.5, "v")):
    comment, data = read(name)
    if data is None:
        continue
    l0 = {1.0: 0.08, 1.5: 0.06, 0.5: 0.16}[aspect]
    filled = data[data[:, 1] > 0]
    front = filled[:, 0].max() + 0.0025
    ax.plot(aspect, (front - l0) / l0, marker, ms=7, label=f"SPH {name.split('.')[0]}")
ax.set_xlabel("a = H0 / L0")
ax.set_ylabel("(L_inf - L0) / L0")
ax.set_title("(c) run-out")
ax.legend(fontsize=8)

# (d) vertical cut: final surface against the initial block.
ax = axes[1, 1]
for name, label in (("cut_stands.csv", "H = 0.5 H_c (lower match)"), ("cut_fails.csv", "H = 2 H_c (upper match)")):
    comment, data = read(name)
    if data is None:
        continue
    ax.plot(data[:, 0] / 0.08, data[:, 1] / 0.08, "-", lw=1.2, label=f"{label}: {comment.split(',')[-1].strip()}")
ax.plot([0, 1.5, 1.5], [1, 1, 0], "k:", lw=0.8, label="initial cut")
ax.set_xlabel("x / H")
ax.set_ylabel("surface height / H")
ax.set_title("(d) cohesive vertical cut after 5 sqrt(H/g)")
ax.legend(fontsize=8)



def flank_of(comment):
    """The flank_deg=... entry of a deposit's or pile's comment line."""
    for word in comment.split():
        if word.startswith("flank_deg="):
            return float(word.split("=")[1])
    return math.nan


# (e) piles collapsed quasi-statically (drag 0.25 sqrt(H0/g)), with a line at theta(f) through the flank.
ax = axes[2, 0]
for f, colour in ((0.4, "C0"), (0.55, "C2"), (0.7, "C1")):
    comment, data = read(f"pile_f{round(100 * f):03d}.csv")
    if data is None:
        continue
    h0 = np.median(data[: len(data) // 5, 1])  # the flat top by the back wall (16 or 24 cells of 5 mm)
    x, z = data[:, 0] / h0, data[:, 1] / h0
    ax.plot(x, z, "-", color=colour, lw=1.2, label=f"f = {f}: flank {flank_of(comment):.1f} deg, theta(f) {theta(f):.1f}")
    # theta(f) through the point of the profile at half the height, on the falling side
    half = np.argmax((z < 0.5 * z.max()) & (np.arange(len(z)) > np.argmax(z)))
    t = math.tan(math.radians(theta(f)))
    ax.plot([x[half] - 0.4 / t, x[half] + 0.4 / t], [z[half] + 0.4, z[half] - 0.4], "--", color=colour, lw=0.8)
ax.plot([0, 2, 2], [1, 1, 0], "k:", lw=0.8)
ax.set_xlabel("x / H (H: height of the pile's flat top)")
ax.set_ylabel("surface height / H")
ax.set_title("(e) a = 0.5 columns collapsed quasi-statically (dashed: theta(f))")
ax.set_xlim(0, 3.5)
ax.legend(fontsize=8)

# (f) measured angles against f.
ax = axes[2, 1]
fs = np.linspace(0.35, 0.75, 50)
ax.plot(fs, [theta(f) for f in fs], "k-", label="theta(f) (Luther et al. 2022)")
ax.fill_between(fs, [theta(f) - 3 for f in fs], [theta(f) + 3 for f in fs], color="k", alpha=0.08,
                label="+-3 deg")
ax.plot(fs, np.degrees(np.arctan(fs)), "k:", label="atan(f) (infinite slope)")
ax.plot(fs, np.degrees(np.arcsin(fs)), "k--", lw=0.8, label="asin(f) (plane-strain Mohr-Coulomb)")
for pattern, marker, label in (("pile_f{:03d}.csv", "o", "quasi-static pile"),
                               ("deposit_f{:03d}.csv", "v", "free collapse deposit"),
                               ("tilt_f{:03d}.csv", "s", "tilted layer")):
    points = []
    for f in (0.4, 0.55, 0.7):
        comment, data = read(pattern.format(round(100 * f)))
        if data is None:
            continue
        if pattern.startswith("tilt"):
            angle = float(comment.split("critical_deg=")[1].split()[0])
        else:
            angle = flank_of(comment)
        points.append((f, angle))
    if points:
        ax.plot(*zip(*points), marker, ms=7, ls="none", label=label)
ax.set_xlabel("friction coefficient f")
ax.set_ylabel("angle (deg)")
ax.set_title("(f) angle of repose")
ax.legend(fontsize=8)

fig.tight_layout()
fig.savefig(png, dpi=110)
