"""Sedov blast snapshot against the similarity solution, shell by shell: mean density, pressure and radial
velocity, and the thermal and kinetic energy held in each shell (SPH sums against the integrated solution).
Usage: /usr/bin/python3 docs/scripts/sedov_energy_shells.py SNAPSHOT.h5"""
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sedov_exact as se  # noqa: E402

f = h5py.File(sys.argv[1], "r")
x,y,z,rho,P,u,m = (f[k][:] for k in ("x","y","z","density","pressure","specific_energy","mass"))
vx,vy,vz = (f[k][:] for k in ("vx","vy","vz"))
t = f.attrs["time"]; r = np.sqrt(x*x+y*y+z*z); vr = (vx*x+vy*y+vz*z)/np.maximum(r,1e-12)
R = se.xi0()*(t*t)**0.2; D = 0.4*R/t
xi, psi, phi, pi = se.profiles()
# energy inside radius shells: SPH vs exact
edges = np.linspace(0, 0.45, 19)
print(f"R_s {R:.4f}")
print(" r_mid   rho_sph rho_ex  P_sph  P_ex   v_sph  v_ex   Eth_sph  Ekin_sph  Eth_ex Ekin_ex")
for a,b in zip(edges[:-1], edges[1:]):
    s = (r>=a)&(r<b); rm = 0.5*(a+b)
    if not s.any():
        continue
    vol = 4/3*np.pi*(b**3-a**3)
    rr = np.linspace(a,b,50); xx = rr/R
    inside = xx<1
    re = np.where(inside, np.interp(xx, xi, psi), 1.0); pe = np.where(inside, np.interp(xx, xi, pi)*D*D, 0); ve = np.where(inside, np.interp(xx, xi, phi)*D, 0)
    w = rr**2/np.sum(rr**2)
    eth_ex = np.sum(w*pe/(2/3))*vol; ekin_ex = np.sum(w*0.5*re*ve*ve)*vol
    print(f"{rm:.3f} {rho[s].mean():7.3f} {np.sum(w*re):6.3f} {P[s].mean():6.3f} {np.sum(w*pe):6.3f} {vr[s].mean():6.3f} {np.sum(w*ve):6.3f} {np.sum(m[s]*u[s]):8.4f} {np.sum(0.5*m[s]*(vx[s]**2+vy[s]**2+vz[s]**2)):8.4f} {eth_ex:7.4f} {ekin_ex:7.4f}")
