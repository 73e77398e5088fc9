"""Sedov-Taylor similarity solution in 3D (Sedov 1959), by RK4 integration of the similarity ODEs from
the strong-shock state at xi = 1 inward (same equations as tests/support/sedov.hpp, independent code):
  w psi' + psi phi' = -2 psi phi / xi,  w phi' + pi'/psi = 1.5 phi,  w pi' - gamma (pi/psi) w psi' = 3 pi,
w = phi - xi; u = D phi, rho = rho0 psi, p = rho0 D^2 pi, D = dR/dt = 0.4 R/t."""
import numpy as np


def _rhs(xi, y, g):
    psi, phi, pi = y
    w = phi - xi
    a = np.array([[w, psi, 0.0], [0.0, w, 1.0 / psi], [-g * pi * w / psi, 0.0, w]])
    b = np.array([-2 * psi * phi / xi, 1.5 * phi, 3 * pi])
    return np.linalg.solve(a, b)


def profiles(g=5.0 / 3.0, n=4000, xi_min=0.02):
    xi = np.linspace(1.0, xi_min, n)
    y = np.array([(g + 1) / (g - 1), 2 / (g + 1), 2 / (g + 1)])
    out = [y.copy()]
    for k in range(n - 1):
        h = xi[k + 1] - xi[k]
        k1 = _rhs(xi[k], y, g)
        k2 = _rhs(xi[k] + h / 2, y + h / 2 * k1, g)
        k3 = _rhs(xi[k] + h / 2, y + h / 2 * k2, g)
        k4 = _rhs(xi[k] + h, y + h * k3, g)
        y = y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        out.append(y.copy())
    out = np.array(out)[::-1]
    return xi[::-1], out[:, 0], out[:, 1], out[:, 2]


def xi0(g=5.0 / 3.0):
    xi, psi, phi, pi = profiles(g)
    integrand = (psi * phi ** 2 / 2 + pi / (g - 1)) * xi ** 2
    return (25.0 / (16 * np.pi * np.trapz(integrand, xi))) ** 0.2
