"""Baselines to compare phasekit against (``phasekit.baseline``): what a user writes by hand, (2.7)
with (6.1) as a plain NumPy right-hand side for scipy, and the bare heyoka integrator phasekit drives.

Used by the benchmarks and the work-precision study as the reference points for cost ("scipy
on a NumPy right-hand side", "heyoka without phasekit's loop"), and the NumPy form as a third,
independent transcription of the equations (it shares no code with :mod:`phasekit.model`).
Coulomb friction while sliding; nothing is done about zero slip (the pitfall the rest of
phasekit treats).
"""

from __future__ import annotations

import time
from typing import NamedTuple

import numpy as np

from .body import Spheroid
from .simulate import taylor_integrator

__all__ = ["numpy_rhs", "numpy_normal_reaction", "solve_ivp_to_jump", "BaselineRun", "taylor_integrator"]


def _geometry(a, th):
    c, s = np.cos(th), np.sin(th)
    h = np.sqrt(a * a * c * c + s * s)
    ht = (1 - a * a) * c * s / h
    # d/dtheta of ht
    htt = (1 - a * a) * (c * c - s * s) / h - ht * ht / h
    return c, s, h, ht, htt


def numpy_normal_reaction(y, a, A, C, mu):
    """(6.1) for Coulomb friction while sliding.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> y0 = pk.gyroscopic_start(body, 1.0, omega0=10.0)
    >>> round(float(pk.baseline.numpy_normal_reaction(y0, body.a, body.A, body.C, 0.1)), 6)
    1.0
    """
    U, V, Om, Lam, th, n = y
    c, s, h, ht, htt = _geometry(a, th)
    xP = h * s + ht * c
    UP = U - h * Lam
    VP = V + Om * ht + (n - Om * c) * xP
    Uhat = UP / np.hypot(UP, VP)
    return (A + A * htt * Lam**2 + Om * ht * s * (A * Om * c - C * n)) / (A + ht * (ht - mu * h * Uhat))


def numpy_rhs(t, y, a, A, C, mu):
    """Equations (2.7a-f) with Coulomb friction (2.6) and R from (6.1).

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> y0 = pk.gyroscopic_start(body, 1.0, omega0=10.0)
    >>> np.allclose(pk.baseline.numpy_rhs(0.0, y0, body.a, body.A, body.C, 0.1), pk.Model(body, pk.Coulomb(0.1)).rhs(y0))
    True
    """
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


class BaselineRun(NamedTuple):
    """What :func:`solve_ivp_to_jump` returns: the jump time (None without a jump), the state at
    the end of the run (the jump; None when capped), the right-hand side evaluations, the wall time
    and a status ("ok", "capped" or "no jump" with scipy's message).

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> y0 = pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5)
    >>> run = pk.baseline.solve_ivp_to_jump(y0, 200.0, a=body.a, A=body.A, C=body.C, mu=0.1, method="DOP853")
    >>> isinstance(run, pk.baseline.BaselineRun), run.status, round(run.t_jump, 3)
    (True, 'ok', 45.256)
    """

    t_jump: float | None
    y: np.ndarray | None
    n_rhs: int
    wall_s: float
    status: str


class _Capped(Exception):
    pass


def solve_ivp_to_jump(y0, t_end, *, a, A, C, mu, method="BDF", rtol=1e-9, atol=None, rhs="numpy",
                      max_wall: float | None = None) -> BaselineRun:
    """scipy.integrate.solve_ivp on a sliding uniform spheroid under Coulomb friction, stopping
    at R = 0 with dR/dt < 0.

    ``rhs="numpy"``: the hand-written :func:`numpy_rhs`; ``rhs="casadi"``: phasekit's compiled
    right-hand side, with its exact Jacobian for the implicit methods (BDF, Radau, LSODA).
    ``max_wall`` (seconds, checked every 200 evaluations) ends a run that takes longer with
    status "capped"; ``atol`` defaults to rtol / 100.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> y0 = pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5)
    >>> sol = pk.baseline.solve_ivp_to_jump(y0, 200.0, a=body.a, A=body.A, C=body.C, mu=0.1, method='DOP853')
    >>> round(sol.t_jump, 3), sol.status
    (45.256, 'ok')
    """
    from scipy.integrate import solve_ivp

    t_start, calls, jac = time.perf_counter(), [0], None
    if rhs == "casadi":
        from .friction import Coulomb
        from .model import Model

        m = Model(Spheroid(a, A=A, C=C), Coulomb(mu))
        f, jf, Rf, p = m.function("rhs_sliding"), m.function("rhs_jac_sliding"), m.function("R_sliding"), m.p
        field = lambda t, y: np.asarray(f(y, p)).ravel()  # noqa: E731
        event = lambda t, y: float(Rf(y, p))  # noqa: E731
        jac = (lambda t, y: np.asarray(jf(y, p))) if method in ("BDF", "Radau", "LSODA") else None
    else:
        field = lambda t, y: numpy_rhs(t, y, a, A, C, mu)  # noqa: E731
        event = lambda t, y: numpy_normal_reaction(y, a, A, C, mu)  # noqa: E731

    def fun(t, y):
        calls[0] += 1
        if max_wall is not None and calls[0] % 200 == 0 and time.perf_counter() - t_start > max_wall:
            raise _Capped
        return field(t, y)

    event.terminal, event.direction = True, -1
    try:
        sol = solve_ivp(fun, (0.0, t_end), np.asarray(y0, float), method=method, rtol=rtol,
                        atol=rtol * 1e-2 if atol is None else atol, events=event, **({"jac": jac} if jac else {}))
    except _Capped:
        return BaselineRun(None, None, calls[0], time.perf_counter() - t_start, "capped")
    wall = time.perf_counter() - t_start
    if not sol.t_events[0].size:
        return BaselineRun(None, sol.y[:, -1], int(sol.nfev), wall, f"no jump ({sol.message})")
    return BaselineRun(float(sol.t_events[0][0]), sol.y_events[0][0], int(sol.nfev), wall, "ok")
