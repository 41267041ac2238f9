"""The steady states on a structure at one precession rate or spin (:meth:`SteadyStructure.at`,
phasekit.steady.structure), found along its branches, independently of :func:`phasekit.fixed_points`
(which scans the precession residual over theta), then polished by the same Newton step.

A branch is followed from end to end: its samples, closed by the exact limits at its two ends
(Omega -> infinity at an infinite-spin asymptote, Omega and n -> 0 at a static equilibrium, the
pole's rate and spin at a pole, the limits at an edged body's limit; phasekit.steady.branches), with every interior extremum of Omega
(or n) located and added. Between two consecutive points the value is then monotone, so a state
with a given rate lies between two points exactly where the rate lies between their values: no
state is lost near an end however fast or slow the rate (the samples stop short of the ends,
where the closed forms lose digits). The families (phasekit.steady.families) add their members:
the horizontal state or the spins about the vertical, and the precession at a point where q = D = 0
away from pi/2 (a static equilibrium of a body with A = C), which has every rate.
"""

from __future__ import annotations

import math

import numpy as np

from .._runtime.watch import check_deadline
from ..core.charts import EULER
from ..errors import ConvergenceError, ParameterError, Status
from .branches import branch_curve, precession_geometry, sample_branch
from .fixedpoints import HORIZONTAL_GAP, family_value, isolated_states, on_range, precessions_at
from .linearisation import FixedPoint
from .precessions import SPIN_FLOOR, SPINLESS_RTOL


def states_at(structure, omega0, n0) -> list[FixedPoint]:
    """Every steady state of ``structure`` with rate ``omega0`` (or spin ``n0``), in the order of
    :func:`phasekit.fixed_points`: the isolated states, then the precessions by increasing theta
    (for a flip-symmetric body those below pi/2: the others are their mirror images)."""
    if (omega0 is None) == (n0 is None):
        raise ParameterError("omega0", "or `n0` must be given, not both", show_value=False)
    omega0, n0 = family_value("omega0", omega0), family_value("n0", n0)
    if structure.status is Status.FAILED:
        raise ConvergenceError(f"the structure did not complete ({structure.reason}): its states are not known",
                               structure)
    model, body = structure.model, structure.body
    me = model if model.chart is EULER else model.with_chart("euler")
    thetas = []
    if structure.degenerate is None:
        for b in structure.branches:
            check_deadline()
            thetas += _branch_angles(body, b, omega0, n0)
        thetas += [f.theta for f in structure.families if f.kind == "precession" and _member(body, f.theta, n0)]
    thetas = _distinct(sorted(t for t in thetas if 0.0 < t < (np.pi / 2 if body.flip_symmetric else np.pi)))
    return on_range(body, isolated_states(me, model.with_chart("vector"), omega0, n0) + precessions_at(me, thetas, omega0, n0))


def _member(body, theta: float, n0) -> bool:
    """Whether the precession family at ``theta`` (q = D = 0, any Omega, n = Omega z / rho_2) has a
    member with the given spin: z != 0 there, or n0 = 0 (its static member). The horizontal family
    (theta = pi/2 with h_theta = 0) is the horizontal state, listed apart."""
    if abs(theta - np.pi / 2) <= HORIZONTAL_GAP:
        return False
    if n0 is None or abs(n0) < SPIN_FLOOR:
        return True
    return float(precession_geometry(body, theta)[2][0]) != 0.0


def _distinct(thetas: list[float]) -> list[float]:
    """Angles within rounding (1e-15) are one (a branch's static end that is also a family's
    point; two branches' common end): states closer than that are left to Newton to tell apart."""
    out: list[float] = []
    for t in thetas:
        if not out or t - out[-1] > 1e-15:
            out.append(t)
    return out


# -- one branch ---------------------------------------------------------------------------------


def _branch_angles(body, branch, omega0, n0) -> list[float]:
    """The angles on ``branch`` where Omega = |omega0| (or n = +-n0), its ends included where
    the value is the end's own (a static end at rate or spin 0)."""
    theta, om, n = _points(body, branch)
    if n0 is not None and np.all(np.abs(n) <= SPINLESS_RTOL * om):  # n = 0 all along (the thin disk): a continuum
        return []
    which, values = (1, n) if n0 is not None else (0, om)
    theta, values = _with_extrema(body, branch, theta, values, which)
    if omega0 is not None:
        targets = [abs(omega0)]
    else:
        targets = [0.0] if abs(n0) < SPIN_FLOOR else [abs(n0), -abs(n0)]
    out = []
    for target in targets:
        d = np.arctan(values) - math.atan(target)  # bounded: +-pi/2 at an infinite-spin end
        d[values == target] = 0.0
        out += [float(theta[k]) for k in np.flatnonzero(d == 0.0)]
        for k in np.flatnonzero(d[:-1] * d[1:] < 0):
            out.append(_root(body, branch, which, target, theta[k], theta[k + 1], d[k], d[k + 1]))
    return out


def _points(body, branch) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """theta, Omega, n along ``branch``: its samples (sampled here for a structure without them)
    between the exact limits at its two ends."""
    lo, hi = branch.ends
    if branch.theta.size:
        theta, om, n = branch.theta, branch.Omega, branch.n
    else:
        theta, om, n = sample_branch(body, lo, hi, branch.crossings)
    ends = [_limit(body, lo, n[0] if n.size else None), _limit(body, hi, n[-1] if n.size else None)]
    return (np.concatenate([[lo.theta], theta, [hi.theta]]), np.concatenate([[ends[0][0]], om, [ends[1][0]]]),
            np.concatenate([[ends[0][1]], n, [ends[1][1]]]))


def _limit(body, end, n_near) -> tuple[float, float]:
    """(Omega, n) at a branch's end: the pole's, the switch's (on its own piece) or the limit's (an
    edged body's range: infinite Omega at a face coming down), 0 at a static end, infinite (n
    with the sign it has next to the end, that of z) at an infinite-spin end."""
    if end.kind in ("pole", "switch", "limit"):  # a switch: the limits on the branch's own piece
        return end.Omega, end.n
    if end.kind == "static":
        return 0.0, 0.0
    z = float(precession_geometry(body, end.theta)[2][0])
    sign = np.sign(n_near) if n_near is not None and n_near != 0 else np.sign(z)
    return math.inf, float(sign) * math.inf


def _value(body, branch, which: int, t: float) -> float:
    return float(branch_curve(body, np.array([t]), branch.crossings)[which][0])


def _with_extrema(body, branch, theta, values, which: int):
    """Add every interior extremum of the values (a fold of Omega or n between samples) as a point,
    located by Brent's method on the curve, so that the values are monotone between points."""
    from scipy.optimize import minimize_scalar

    dv = np.diff(values)
    turns = np.flatnonzero(dv[:-1] * dv[1:] < 0) + 1
    if not turns.size:
        return theta, values
    extra_t, extra_v = [], []
    for k in turns:
        sign = 1.0 if dv[k - 1] < 0 else -1.0  # a minimum: minimise v; a maximum: minimise -v

        def f(t, sign=sign):
            v = sign * _value(body, branch, which, t)
            return v if np.isfinite(v) else math.inf

        res = minimize_scalar(f, bounds=(theta[k - 1], theta[k + 1]), method="bounded", options={"xatol": 1e-14})
        if np.isfinite(res.fun) and theta[k - 1] < res.x < theta[k + 1] and res.x != theta[k]:
            extra_t.append(float(res.x))
            extra_v.append(sign * float(res.fun))
    merged_t = np.concatenate([theta, extra_t])
    order = np.argsort(merged_t, kind="stable")
    return merged_t[order], np.concatenate([values, extra_v])[order]


def _root(body, branch, which: int, target: float, a: float, b: float, da: float, db: float) -> float:
    """The angle in (a, b) where the value crosses ``target``, by Brent's method on
    atan(value) - atan(target) (the ends' exact limits at a and b; where the closed form has no
    value, next to an end, that end's)."""
    from scipy.optimize import brentq

    goal = math.atan(target)

    def f(t):
        if t == a:
            return da
        if t == b:
            return db
        v = _value(body, branch, which, t)
        if not np.isfinite(v) and not np.isinf(v):
            return da if t - a < b - t else db
        return math.atan(v) - goal

    return float(brentq(f, a, b, xtol=1e-16, rtol=4 * np.finfo(float).eps, maxiter=200))
