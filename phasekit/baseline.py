"""The baseline a user writes by hand: (2.7) with (6.1) as a plain NumPy right-hand side.

Used by the benchmarks and the work-precision study as the reference point for cost
("scipy on a NumPy right-hand side"), and as a third, independent transcription of the
equations (it shares no code with :mod:`phasekit.model`). Coulomb friction while sliding;
nothing is done about zero slip (the pitfall the rest of phasekit treats).
"""

from __future__ import annotations

import numpy as np

__all__ = ["numpy_rhs", "numpy_normal_reaction", "solve_ivp_to_jump"]


def _geometry(a, th):
    c, s = np.cos(th), np.sin(th)
    h = np.sqrt(a * a * c * c + s * s)
    ht = (1 - a * a) * c * s / h
    # d/dtheta of ht
    htt = (1 - a * a) * (c * c - s * s) / h - ht * ht / h
    return c, s, h, ht, htt


def numpy_normal_reaction(y, a, A, C, mu):
    """(6.1) for Coulomb friction while sliding."""
    U, V, Om, Lam, th, n = y
    c, s, h, ht, htt = _geometry(a, th)
    xP = h * s + ht * c
    UP = U - h * Lam
    VP = V + Om * ht + (n - Om * c) * xP
    Uhat = UP / np.hypot(UP, VP)
    return (A + A * htt * Lam**2 + Om * ht * s * (A * Om * c - C * n)) / (A + ht * (ht - mu * h * Uhat))


def numpy_rhs(t, y, a, A, C, mu):
    """Equations (2.7a-f) with Coulomb friction (2.6) and R from (6.1)."""
    U, V, Om, Lam, th, n = y
    c, s, h, ht, htt = _geometry(a, th)
    xP = h * s + ht * c
    zPm = h * c - ht * s
    UP = U - h * Lam
    VP = V + Om * ht + (n - Om * c) * xP
    speed = np.hypot(UP, VP)
    R = (A + A * htt * Lam**2 + Om * ht * s * (A * Om * c - C * n)) / (A + ht * (ht - mu * h * UP / speed))
    FX, Fy = -mu * R * UP / speed, -mu * R * VP / speed
    return np.array(
        [
            Om * V + FX,
            -Om * U + Fy,
            (C * n * Lam - 2 * A * Om * Lam * c - zPm * Fy) / (A * s),
            (Om * s * (A * Om * c - C * n) - R * ht - h * FX) / A,
            Lam,
            xP * Fy / C,
        ]
    )


def solve_ivp_to_jump(y0, t_end, *, a, A, C, mu, method="BDF", rtol=1e-9, atol=None):
    """scipy.integrate.solve_ivp on :func:`numpy_rhs`, stopping at R = 0 with dR/dt < 0.

    Returns (t_jump or None, state at the end, number of RHS evaluations).
    """
    from scipy.integrate import solve_ivp

    def event(t, y, *args):
        return numpy_normal_reaction(y, a, A, C, mu)

    event.terminal, event.direction = True, -1
    sol = solve_ivp(
        numpy_rhs, (0.0, t_end), np.asarray(y0, float), method=method, rtol=rtol,
        atol=rtol * 1e-2 if atol is None else atol, events=event, args=(a, A, C, mu),
    )
    t_jump = float(sol.t_events[0][0]) if sol.t_events[0].size else None
    return t_jump, sol.y[:, -1], int(sol.nfev)
