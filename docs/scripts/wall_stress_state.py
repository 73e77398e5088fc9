#!/usr/bin/env python3
"""The stress state of a crater wall in an impact snapshot: which particles carry load, how close to their
yield limit they are, and how much friction they mobilise on planes parallel to the wall (docs/validation.md,
"Why the walls creep").

    craterkit measure SNAP.h5 --out MEASURED                 # crater.json (wall_slope_deg) and the profile
    /usr/bin/python3 docs/scripts/wall_stress_state.py SNAP.h5 MEASURED [--friction 0.55] [--layer 2.5]

The wall is the radial band where the measured azimuthal mean profile lies between 20 and 80 % of the depth
(the band of `wall_slope_deg`); its particles are those neither fixed nor ejected within --layer metres below
that profile. For each one at P > 0 the script takes the deviatoric stress S (tension positive, total stress
-P I + S), its yield ratio sqrt(J2) / (f P) (the cohesionless Lundborg limit Y = f P), the Lode parameter b =
(c2 - c3) / (c1 - c3) of the compressive principal stresses c1 >= c2 >= c3 (0: triaxial compression, 1:
triaxial extension), and S in the frame of the wall (t down the wall towards the axis, n its outward normal,
hoop): the friction mobilised on a plane parallel to the wall is |S_tn| / (P - S_nn).
A Drucker-Prager layer sqrt(J2) <= f P under a free surface of slope beta holds at most tan(beta) =
max_s sqrt(f^2 - 3 s^2 / 4) / (1 - s) (s = S_nn / P, the other two normal deviators -s/2), which is atan f for
s = 0 (the infinite slope of the tilted layer) and larger otherwise.
"""
import argparse
import csv
import json
import math
import os
import sys

import h5py
import numpy as np

FIXED, EJECTED = 1, 2  # particle flags (particles.hpp): fixed shell, ejected


def steepest_slope(f):
    s = np.linspace(0.0, 0.999, 100000)
    t = np.sqrt(np.maximum(f * f - 0.75 * s * s, 0.0)) / (1.0 - s)
    return math.degrees(math.atan(t.max())), s[t.argmax()]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("snapshot")
    ap.add_argument("measured", help="folder written by `craterkit measure SNAP --out FOLDER`")
    ap.add_argument("--friction", type=float, default=0.55, help="f of the target (default 0.55)")
    ap.add_argument("--layer", type=float, default=2.5, help="depth below the profile, m (default 2.5)")
    a = ap.parse_args()

    if not os.path.isfile(os.path.join(a.measured, "crater.json")):
        sys.exit(f"wall_stress_state.py: no crater.json in {a.measured}: run "
                 f"`craterkit measure {a.snapshot} --out {a.measured}` first")
    crater = json.load(open(os.path.join(a.measured, "crater.json")))
    if crater.get("wall_slope_deg") is None:
        sys.exit(f"wall_stress_state.py: {a.measured}/crater.json has no wall_slope_deg (no crater, or written by "
                 "a craterkit older than the wall slope): measure the snapshot again")
    depth, beta_deg = crater["depth"], crater["wall_slope_deg"]
    prof_r, prof_z = [], []
    with open(os.path.join(a.measured, "crater_profile.csv")) as f:
        for row in csv.DictReader(f):
            if row["mean_height_m"] not in ("", "nan") and float(row["radius_m"]) < crater["crater_radius"]:
                prof_r.append(float(row["radius_m"]))
                prof_z.append(float(row["mean_height_m"]))
    prof_r, prof_z = np.array(prof_r), np.array(prof_z)
    band = (prof_z >= -0.8 * depth) & (prof_z <= -0.2 * depth)
    r_in, r_out = prof_r[band].min(), prof_r[band].max()

    h = h5py.File(a.snapshot, "r")
    x, y, z = h["x"][:], h["y"][:], h["z"][:]
    P, flags, speed = h["pressure"][:], h["flags"][:], np.linalg.norm(h["velocity"][:], axis=1)
    S = {k: h["stress_" + k][:] for k in ("xx", "xy", "xz", "yy", "yz")}
    r = np.hypot(x, y)
    below = np.interp(r, prof_r, prof_z) - z
    wall = (r >= r_in) & (r <= r_out) & (below >= 0) & (below <= a.layer) & ((flags & (FIXED | EJECTED)) == 0)
    idx = np.nonzero(wall)[0]
    beta = math.radians(beta_deg)
    f = a.friction
    ratio, lode, hoop_rank, frame, mobilised, moving = [], [], [], [], [], []
    for i in idx:
        if P[i] <= 0.0:
            continue
        s = np.array([[S["xx"][i], S["xy"][i], S["xz"][i]], [S["xy"][i], S["yy"][i], S["yz"][i]],
                      [S["xz"][i], S["yz"][i], -S["xx"][i] - S["yy"][i]]])
        ratio.append(math.sqrt(0.5 * np.sum(s * s)) / (f * P[i]))
        c3, c2, c1 = np.linalg.eigvalsh(P[i] * np.eye(3) - s)
        lode.append((c2 - c3) / (c1 - c3) if c1 > c3 else math.nan)
        er = np.array([x[i], y[i], 0.0]) / r[i]
        eh = np.array([-y[i], x[i], 0.0]) / r[i]
        t = -math.cos(beta) * er - math.sin(beta) * np.array([0.0, 0.0, 1.0])
        n = -math.sin(beta) * er + math.cos(beta) * np.array([0.0, 0.0, 1.0])
        hoop = P[i] - eh @ s @ eh
        hoop_rank.append(int(np.argmin(np.abs(np.array([c1, c2, c3]) - hoop))))
        frame.append([t @ s @ n / P[i], t @ s @ t / P[i], n @ s @ n / P[i], eh @ s @ eh / P[i]])
        mobilised.append(abs(t @ s @ n) / (P[i] - n @ s @ n))
        moving.append(speed[i])
    ratio, lode, frame, mobilised = map(np.array, (ratio, lode, frame, mobilised))

    def pct(v):
        return "median {:.3g} (10-90 %: {:.3g} .. {:.3g})".format(*np.percentile(v, [50, 10, 90]))

    print(f"{a.snapshot}: t = {crater.get('time', float('nan')):.4g} s, R = {crater['crater_radius']:.4g} m, "
          f"depth {depth:.4g} m, wall slope {beta_deg:.3g} deg over r = {r_in:.3g} .. {r_out:.3g} m")
    zero = len(idx) - len(ratio)
    print(f"wall particles within {a.layer} m of the surface: {len(idx)}; at P = 0 (no strength): {zero}; "
          f"moving faster than 1 mm/s: {int(np.sum(speed[idx] > 1e-3))}")
    if len(ratio) == 0:
        return
    at = ratio > 0.95
    print(f"at P > 0: {len(ratio)}, at their yield limit (sqrt(J2) > 0.95 f P): {int(at.sum())}")
    if not at.any():
        return
    print(f"  Lode parameter b of those at the limit: {pct(lode[at])}")
    ranks = np.bincount(np.array(hoop_rank)[at], minlength=3)
    print(f"  hoop stress the major / intermediate / minor principal stress: {ranks[0]} / {ranks[1]} / {ranks[2]}")
    for k, name in enumerate(("S_tn", "S_tt", "S_nn", "S_hoop")):
        print(f"  {name} / P: {pct(frame[at, k])}")
    print(f"  friction mobilised on planes parallel to the wall, |S_tn| / (P - S_nn): {pct(mobilised[at])} "
          f"= {math.degrees(math.atan(np.median(mobilised[at]))):.3g} deg at the median")
    steepest, s_at = steepest_slope(f)
    print(f"f = {f}: atan f = {math.degrees(math.atan(f)):.4g} deg; steepest slope a Drucker-Prager layer holds "
          f"{steepest:.4g} deg (S_nn = {s_at:.3g} P)")


if __name__ == "__main__":
    main()
