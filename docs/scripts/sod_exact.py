"""Exact Riemann solution of an ideal gas (Toro 2009, ch. 4), for the Sod plots. Independent of the C++
reference in tests/support (same equations, Newton iteration on the pressure function)."""
import numpy as np


def _f(p, rho, pk, c, g):
    if p > pk:  # shock (Toro eq. 4.21)
        a, b = 2.0 / ((g + 1) * rho), (g - 1) / (g + 1) * pk
        return (p - pk) * np.sqrt(a / (p + b))
    return 2 * c / (g - 1) * ((p / pk) ** ((g - 1) / (2 * g)) - 1)  # rarefaction (eq. 4.26)


def star(left, right, g):
    (rl, ul, pl), (rr, ur, pr) = left, right
    cl, cr = np.sqrt(g * pl / rl), np.sqrt(g * pr / rr)
    p = 0.5 * (pl + pr)
    for _ in range(100):
        fun = _f(p, rl, pl, cl, g) + _f(p, rr, pr, cr, g) + ur - ul
        e = 1e-7 * p
        dfun = (_f(p + e, rl, pl, cl, g) + _f(p + e, rr, pr, cr, g) - _f(p - e, rl, pl, cl, g) - _f(p - e, rr, pr, cr, g)) / (2 * e)
        p -= fun / dfun
    u = 0.5 * (ul + ur) + 0.5 * (_f(p, rr, pr, cr, g) - _f(p, rl, pl, cl, g))
    return p, u


def sample(x_over_t, left, right, g):
    """(density, velocity, pressure) at x/t for a left rarefaction and right shock (the Sod case)."""
    (rl, ul, pl), (rr, ur, pr) = left, right
    ps, us = star(left, right, g)
    cl = np.sqrt(g * pl / rl)
    rsl = rl * (ps / pl) ** (1 / g)
    csl = cl * (ps / pl) ** ((g - 1) / (2 * g))
    rsr = rr * ((ps / pr + (g - 1) / (g + 1)) / ((g - 1) / (g + 1) * ps / pr + 1))
    shock = ur + np.sqrt(g * pr / rr) * np.sqrt((g + 1) / (2 * g) * ps / pr + (g - 1) / (2 * g))
    s = np.asarray(x_over_t, dtype=float)
    rho = np.where(s < ul - cl, rl, 0.0)
    fan = (s >= ul - cl) & (s < us - csl)
    rho_fan = rl * (2 / (g + 1) + (g - 1) / ((g + 1) * cl) * (ul - s)) ** (2 / (g - 1))
    rho = np.where(fan, rho_fan, rho)
    rho = np.where((s >= us - csl) & (s < us), rsl, rho)
    rho = np.where((s >= us) & (s < shock), rsr, rho)
    rho = np.where(s >= shock, rr, rho)
    return rho, ps, us
