"""Baselines to compare phasekit against (``phasekit.baseline``): what a user writes by hand, (2.7)
with (6.1) as a plain NumPy right-hand side for scipy, and the bare heyoka integrator phasekit drives.

Used by the benchmarks and the work-precision study as the reference points for cost ("scipy
on a NumPy right-hand side", "heyoka without phasekit's loop"), and the NumPy form as a third,
independent transcription of the equations (it shares no code with :mod:`phasekit.core.fields`).
Coulomb friction while sliding; nothing is done about zero slip (the pitfall the rest of
phasekit treats).
"""

from __future__ import annotations

import statistics
import time
from typing import NamedTuple

import numpy as np

from ..bodies.spheroid import Spheroid
from .bare import taylor_integrator

__all__ = ["numpy_rhs", "solve_ivp_to_jump", "taylor_integrator", "JUMP_METHODS", "work_precision"]


def _geometry(a, th):
    c, s = np.cos(th), np.sin(th)
    h = np.sqrt(a * a * c * c + s * s)
    ht = (1 - a * a) * c * s / h
    # d/dtheta of ht
    htt = (1 - a * a) * (c * c - s * s) / h - ht * ht / h
    return c, s, h, ht, htt


def numpy_normal_reaction(y, a, A, C, mu):
    """(6.1) for Coulomb friction while sliding.

    Parameters
    ----------
    y : array_like
        The paper's state (U, V, Omega, Lambda, theta, n): 6 numbers.
    a : float
        Aspect ratio of the uniform spheroid (its h(theta)).
    A, C : float
        Transverse and axial moments of inertia about G, units M b^2.
    mu : float
        Coulomb friction coefficient.

    Returns
    -------
    float
        The normal reaction R, units M g.

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

    Parameters
    ----------
    t : float
        Time (unused: the equations are autonomous; the signature is scipy's).
    y : array_like
        The paper's state (U, V, Omega, Lambda, theta, n): 6 numbers.
    a : float
        Aspect ratio of the uniform spheroid (its h(theta)).
    A, C : float
        Transverse and axial moments of inertia about G, units M b^2.
    mu : float
        Coulomb friction coefficient.

    Returns
    -------
    numpy.ndarray
        Shape (6,): the time derivative of the state.

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

    Parameters
    ----------
    t_jump : float or None
        The jump time, units sqrt(b/g); None without a jump.
    y : numpy.ndarray or None
        The state at the end of the run (the jump); None when capped.
    n_rhs : int
        Right-hand side evaluations.
    wall_s : float
        Wall time, seconds.
    status : str
        "ok", "capped" or "no jump (<scipy's message>)".

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

    Parameters
    ----------
    y0 : array_like
        The start, the paper's state (U, V, Omega, Lambda, theta, n): 6 numbers.
    t_end : float
        End time, units sqrt(b/g).
    a : float
        Aspect ratio of the spheroid.
    A, C : float
        Transverse and axial moments of inertia about G, units M b^2.
    mu : float
        Coulomb friction coefficient.
    method : str, optional
        The method of scipy's solve_ivp (default "BDF").
    rtol : float, optional
        Relative tolerance (default 1e-9).
    atol : float, optional
        Absolute tolerance; defaults to rtol / 100.
    rhs : {"numpy", "casadi"}, optional
        ``rhs="numpy"`` (the default): the hand-written :func:`numpy_rhs`; ``rhs="casadi"``:
        phasekit's compiled right-hand side, with its exact Jacobian for the implicit methods
        (BDF, Radau, LSODA).
    max_wall : float, optional
        Seconds, checked every 200 evaluations: ends a run that takes longer with status
        "capped" (default None: no limit).

    Returns
    -------
    BaselineRun
        Status "ok" with the jump time and the state there; "capped" (no time, no state); or
        "no jump (<scipy's message>)" with the last state.

    Raises
    ------
    ParameterError
        With ``rhs="casadi"``, if the spheroid (``a``, ``A``, ``C``) or ``mu`` is invalid.

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

    t_start, calls = time.perf_counter(), [0]
    field, event, jac = _field_and_event(rhs, method, a, A, C, mu)

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


def _field_and_event(rhs: str, method: str, a, A, C, mu) -> tuple:
    """:func:`solve_ivp_to_jump`'s right-hand side f(t, y), its event R(t, y) and the Jacobian
    (None but for phasekit's compiled field with an implicit method)."""
    jac = None
    if rhs == "casadi":
        from ..core.model import Model
        from ..friction.laws import Coulomb

        m = Model(Spheroid(a, A=A, C=C), Coulomb(mu))
        f, jf, Rf, p = m.function("rhs_sliding"), m.function("rhs_jac_sliding"), m.function("R_sliding"), m.p
        field = lambda t, y: np.asarray(f(y, p)).ravel()  # noqa: E731
        event = lambda t, y: float(Rf(y, p))  # noqa: E731
        jac = (lambda t, y: np.asarray(jf(y, p))) if method in ("BDF", "Radau", "LSODA") else None
    else:
        field = lambda t, y: numpy_rhs(t, y, a, A, C, mu)  # noqa: E731
        event = lambda t, y: numpy_normal_reaction(y, a, A, C, mu)  # noqa: E731
    return field, event, jac


#: what a sweep needs of a run (t_jump only); simulate's defaults add dense output and the minima of R
SWEEP_PATH = dict(dense=False, track_minima=False)
#: how each integrator of the work-precision comparison runs, in the order drawn: phasekit's
#: (backend, options of simulate) and scipy's (method, right-hand side)
_JUMP_RUNS = {
    "phasekit Taylor/heyoka (sweep path)": ("phasekit", "auto", SWEEP_PATH),
    "phasekit Taylor/heyoka (default options)": ("phasekit", "auto", {}),
    "CVODES BDF (CasADi)": ("phasekit", "cvodes", SWEEP_PATH),
    "CVODES Adams (CasADi)": ("phasekit", "cvodes-adams", SWEEP_PATH),
    "IDAS (CasADi)": ("phasekit", "idas", SWEEP_PATH),
    "scipy BDF, NumPy rhs": ("scipy", "BDF", "numpy"),
    "scipy Radau, NumPy rhs": ("scipy", "Radau", "numpy"),
    "scipy LSODA, NumPy rhs": ("scipy", "LSODA", "numpy"),
    "scipy DOP853, NumPy rhs": ("scipy", "DOP853", "numpy"),
    "scipy BDF, CasADi rhs+jac": ("scipy", "BDF", "casadi"),
    "scipy Radau, CasADi rhs+jac": ("scipy", "Radau", "casadi"),
    "scipy DOP853, CasADi rhs": ("scipy", "DOP853", "casadi"),
}
#: the integrators :func:`jump_time` runs, in the order of the work-precision diagram; the first
#: (phasekit as its sweeps run it) is the default
JUMP_METHODS = tuple(_JUMP_RUNS)


def jump_time(method: str, body, y0, mu: float, rtol: float, cap: float | None = None, *, t_end: float = 200.0) -> BaselineRun:
    """The time of the jump of a sliding spheroid under Coulomb friction ``mu`` from ``y0`` (the
    paper's state), by one of :data:`JUMP_METHODS`: phasekit's engines through
    :func:`phasekit.simulate` (the wall time measured around it) or scipy through
    :func:`solve_ivp_to_jump` (capped at ``cap`` seconds).

    Parameters
    ----------
    method : str
        One of :data:`JUMP_METHODS`.
    body : Spheroid
        The body.
    y0 : array_like
        The start, the paper's state (U, V, Omega, Lambda, theta, n).
    mu : float
        Coulomb friction coefficient.
    rtol : float
        Relative tolerance.
    cap : float, optional
        Wall-time limit of a scipy run, seconds (default None: no limit).
    t_end : float, optional
        End time, units sqrt(b/g) (default 200).

    Returns
    -------
    BaselineRun
        A :class:`BaselineRun` whose ``y`` is the state at the jump (None without one) and
        status "ok" with a jump (otherwise scipy's status, or phasekit's status and reason).

    Raises
    ------
    ParameterError
        If ``method`` is not one of :data:`JUMP_METHODS`, or an argument of the run is invalid.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> y0 = pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5)
    >>> run = pk.baseline.jump_time("CVODES BDF (CasADi)", body, y0, 0.1, 1e-8)
    >>> run.status, round(run.t_jump, 3)
    ('ok', 45.256)
    """
    from .._runtime.validate import check_choice

    kind, how, options = _JUMP_RUNS[check_choice("method", method, JUMP_METHODS)]
    if kind == "scipy":
        r = solve_ivp_to_jump(y0, t_end, a=body.a, A=body.A, C=body.C, mu=mu, method=how, rtol=rtol, rhs=options,
                              max_wall=cap)
        return r._replace(y=r.y if r.t_jump is not None else None)
    from ..core.model import Model
    from ..core.simulate import simulate
    from ..errors import Status
    from ..friction.laws import Coulomb

    t0 = time.perf_counter()
    r = simulate(Model(body, Coulomb(mu)), y0, t_end, rtol=rtol, backend=how, **options)
    wall = time.perf_counter() - t0
    if r.status is not Status.JUMPED:
        return BaselineRun(None, None, r.n_rhs, wall, f"{r.status.value}: {r.reason}")
    return BaselineRun(r.t_jump, r.x_jump, r.n_rhs, wall, "ok")


def _reference(body, y0, mu: float) -> tuple:
    """t_jump and the state at the jump by phasekit's Taylor integrator at tol 1e-15, and the same
    by scipy DOP853 at rtol 1e-13 on the NumPy right-hand side (the check)."""
    from ..core.model import Model
    from ..core.simulate import simulate
    from ..friction.laws import Coulomb

    r = simulate(Model(body, Coulomb(mu)), y0, 200.0, rtol=1e-15, **SWEEP_PATH)
    chk = jump_time("scipy DOP853, NumPy rhs", body, y0, mu, 1e-13, 1e9)
    return r.t_jump, r.x_jump, chk.t_jump, chk.y


def _timed(method, body, y0, mu, rtol, cap, repeats) -> tuple[BaselineRun, float]:
    """One method at one tolerance: compiled / warmed once (phasekit's engines), then the median
    wall time of ``repeats`` runs (one run if it fails or takes over a second)."""
    if _JUMP_RUNS[method][0] == "phasekit":
        jump_time(method, body, y0, mu, rtol, cap)
    walls, res = [], None
    for _ in range(repeats):
        res = jump_time(method, body, y0, mu, rtol, cap)
        walls.append(res.wall_s)
        if res.status != "ok" or res.wall_s > 1.0:
            break
    return res, statistics.median(walls) if res.status == "ok" else res.wall_s


def work_precision(workloads: dict, rtols, *, mu: float, cap: float, repeats: int = 1, methods=JUMP_METHODS, bar=None):
    """Every method at every tolerance on every workload (name -> (body, paper state)): the
    relative error of the jump time against a reference (phasekit's Taylor integrator at tol
    1e-15) and the median wall time of ``repeats`` runs.

    Parameters
    ----------
    workloads : dict
        Name -> (body, paper state): the spheroid and its start.
    rtols : sequence of float
        The relative tolerances.
    mu : float
        Coulomb friction coefficient.
    cap : float
        Wall-time limit of a scipy run, seconds.
    repeats : int, optional
        Runs per method and tolerance, of which the median wall time is kept (default 1).
    methods : sequence of str, optional
        Names from :data:`JUMP_METHODS` (default: all of them).
    bar : tqdm.tqdm, optional
        A tqdm progress bar, advanced per reference and per run.

    Returns
    -------
    tuple
        (rows, refs): one row (a dict: workload, method, rtol, error, state_error, wall_s,
        n_rhs, default, status) per run, a run past ``cap`` seconds kept with status "capped";
        per workload (t_ref, relative difference of scipy DOP853 at rtol 1e-13 in t_jump, its
        largest difference in the state).

    Raises
    ------
    ParameterError
        If a name in ``methods`` is not one of :data:`JUMP_METHODS`.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> wl = {"prolate": (body, pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5))}
    >>> rows, refs = pk.baseline.work_precision(wl, [1e-6], mu=0.1, cap=5.0, methods=["scipy DOP853, NumPy rhs"])
    >>> rows[0]["status"], rows[0]["error"] < 1e-4, round(refs["prolate"][0], 3)
    ('ok', True, 45.256)
    """
    rows, refs = [], {}
    for wl, (body, y0) in workloads.items():
        t_ref, y_ref, t_chk, y_chk = _reference(body, y0, mu)
        if bar is not None:
            bar.update()
        refs[wl] = (t_ref, abs(t_chk - t_ref) / t_ref, float(np.max(np.abs(y_chk - y_ref))))
        for name in methods:
            for rt in rtols:
                if bar is not None:
                    bar.set_postfix_str(f"{name} @ {rt:.0e}", refresh=False)
                    bar.update()
                res, wall = _timed(name, body, y0, mu, rt, cap, repeats)
                err = abs(res.t_jump - t_ref) / t_ref if res.t_jump is not None else None
                serr = float(np.max(np.abs(np.asarray(res.y) - y_ref))) if res.y is not None else None
                rows.append(dict(workload=wl, method=name, rtol=rt, error=err, state_error=serr, wall_s=wall, n_rhs=res.n_rhs,
                                 default=name == JUMP_METHODS[0], status=res.status))
    return rows, refs
