"""Stability along the branches of steady precessions (parts III and IV of the series): the
law's linearisation at each sample of a branch (more samples where an eigenvalue may cross the
imaginary axis and come back between two of them), and every change of stability located by
bisection.

Stability along a branch is that of the law given: the Euler chart's exact Jacobian away from
the poles, and near them (within POLE_ZONE) the vector chart in axes turning with the
precession, J - Omega G (G the generator of rotations about the vertical), which is regular at
the poles and has the same real parts (plus two zero eigenvalues: |k| and the azimuth).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._runtime.watch import check_deadline
from ..core.charts import EULER, VECTOR, euler_to_vector
from ..core.model import Model
from ..errors import SearchStatus
from .branches import branch_curve, off_crossings
from .linearisation import FixedPoint, eigen_with_bounds, jacobian_error, law_jacobian, linearise, mode_for

#: within this of a pole, stability is computed in the vector chart turning with the precession
POLE_ZONE = 0.05
#: stability changes are located to this in theta
CHANGE_XTOL = 1e-9


@dataclass(frozen=True)
class StabilityChange:
    """A point of a branch where its stability changes: a real eigenvalue (``kind`` "real") or
    a complex pair ("complex") crosses the imaginary axis. ``bracket`` holds states of opposite
    stability (n_unstable ``below`` at the lower theta, ``above`` at the upper), ``theta`` its
    midpoint; ``status`` "converged" when the bracket is narrower than CHANGE_XTOL."""

    theta: float
    bracket: tuple[float, float]
    kind: str
    Omega: float
    n: float
    below: int
    above: int
    status: SearchStatus = SearchStatus.CONVERGED

    def to_dict(self) -> dict:
        return {"theta": self.theta, "bracket": list(self.bracket), "kind": self.kind, "Omega": self.Omega, "n": self.n,
                "n_unstable_below": self.below, "n_unstable_above": self.above, "status": self.status.value}


# -- stability along a branch -------------------------------------------------------------------

#: generator of rotations about the vertical acting on (k, w, v) of the vector chart
_G = np.zeros((8, 8))
for _i in (0, 3):
    _G[_i, _i + 1], _G[_i + 1, _i] = -1.0, 1.0
_G[6, 7], _G[7, 6] = -1.0, 1.0


def linearise_precession(model: Model, theta: float, Omega: float, n: float, *, chart: str = "auto") -> FixedPoint:
    """The linearisation of the law about the steady precession (theta, Omega, n).

    ``chart="euler"``: :func:`phasekit.steady.linearise` in the paper's variables. ``"rotating"``: the
    vector chart (k, w, v) in axes turning at Omega about the vertical, J - Omega G, regular at
    the poles (two more zero eigenvalues; tilt modes' imaginary parts shifted by Omega, real
    parts the same). ``"auto"``: rotating within POLE_ZONE of a pole, Euler elsewhere. Raises
    TimeoutError once a wall budget in force has run out (phasekit._runtime.watch.check_deadline)."""
    check_deadline()
    if chart == "auto":
        chart = "rotating" if min(theta, np.pi - theta) < POLE_ZONE else "euler"
    y = np.array([0.0, 0.0, Omega, 0.0, theta, n])
    if chart == "euler":
        return linearise(model if model.chart is EULER else model.with_chart("euler"), y, kind="intermediate")
    mv = model if model.chart is VECTOR else model.with_chart("vector")
    x = euler_to_vector(y)
    mode = mode_for(mv)
    jac = law_jacobian(mv, mode)
    keep = np.arange(8) if mode.value != "rolling" else np.array([0, 1, 2, 3, 4, 5])
    G = _G[np.ix_(keep, keep)]

    def rotating(xx):
        J, L = jac(xx)
        return J - Omega * G, L

    f = mv._rhs(x, mode) - Omega * (_G @ x)  # zero at a steady precession
    J, L = rotating(x)
    lam, V, bounds = eigen_with_bounds(J, jacobian_error(mv, mode, rotating, x, f, J))
    if L is not None:
        V = L @ V
    law = "coulomb-rolling" if mode.value == "rolling" else mv.friction.name
    return FixedPoint("intermediate", "vector-rotating", x, y, lam, V, float(np.max(np.abs(f))), law, error_bounds=bounds)


def _n_positive(fp: FixedPoint) -> int:
    """The sign count that bisection follows across a change of stability: eigenvalues whose
    real part is positive beyond its error bound (within ~bound/slope of the crossing the
    crossing eigenvalue is not counted, so the bracket closes on the last decided states)."""
    return fp.n_unstable


def _locate_change(at, lo: float, hi: float, f_lo: FixedPoint, f_hi: FixedPoint):
    """Bisect one change of stability between two states with different counts to CHANGE_XTOL;
    returns the change and the state at the upper end of its bracket."""
    c_lo = _n_positive(f_lo)
    while hi - lo > CHANGE_XTOL:
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        fm = at(mid)
        if _n_positive(fm) == c_lo:
            lo, f_lo = mid, fm
        else:
            hi, f_hi = mid, fm
    # the kind: the eigenvalue nearest the imaginary axis on the unstable side
    side = f_hi if _n_positive(f_hi) > c_lo else f_lo
    mask = side._unstable_mask()
    lam, b = side.eigenvalues[mask], side.bounds[mask]
    k = np.argsort(lam.real)[:1]
    kind = "complex" if k.size and abs(lam[k[0]].imag) > b[k[0]] else "real"
    t = 0.5 * (lo + hi)
    status = SearchStatus.CONVERGED if hi - lo <= CHANGE_XTOL else SearchStatus.BRACKET_ONLY
    om, n = at.curve(t)
    return StabilityChange(t, (lo, hi), kind, om, n, f_lo.n_unstable, f_hi.n_unstable, status), hi, f_hi


def _tracks(points: list[FixedPoint]) -> list[np.ndarray | None]:
    """Real parts of the eigenvalues followed from sample to sample (the nearest match), one
    array per sample in a common order; None where the chart (and so the spectrum) changes."""
    from scipy.optimize import linear_sum_assignment

    out, prev = [], None
    for p in points:
        lam = p.eigenvalues.copy()
        if prev is not None and prev.size == lam.size:
            cost = np.abs(prev[:, None] - lam[None, :])
            _, col = linear_sum_assignment(cost)
            lam = lam[col]
        elif prev is not None:
            out.append(None)
            prev = lam
            continue
        out.append(lam)
        prev = lam
    return out


def _hidden(theta: np.ndarray, points: list[FixedPoint]) -> list[float]:
    """Points to add where a followed eigenvalue's real part may cross zero and come back
    between two samples of equal stability: its cubic Hermite interpolant (slopes from the
    neighbours) changes sign inside the interval."""
    tr = _tracks(points)
    new = []
    for k in range(1, len(points) - 2):
        ends = tr[k - 1:k + 3]
        if any(e is None for e in ends) or _n_positive(points[k]) != _n_positive(points[k + 1]):
            continue
        r = np.array([e.real for e in ends])  # 4 x m
        # only real parts decided at both ends (not zeros, not rounding about the axis)
        b = 10 * max(points[k].bounds.max(), points[k + 1].bounds.max())
        undecided = (np.abs(r[1]) <= b) | (np.abs(r[2]) <= b)
        t = theta[k - 1:k + 3]
        h = t[2] - t[1]
        d1 = (r[2] - r[0]) / (t[2] - t[0])
        d2 = (r[3] - r[1]) / (t[3] - t[1])
        s = np.linspace(0.0, 1.0, 17)[1:-1, None]
        cubic = ((2 * s**3 - 3 * s**2 + 1) * r[1] + (s**3 - 2 * s**2 + s) * h * d1 + (-2 * s**3 + 3 * s**2) * r[2]
                 + (s**3 - s**2) * h * d2)
        flips = (np.sign(cubic) != np.sign(r[1])) & (np.sign(r[1]) == np.sign(r[2])) & ~undecided
        if flips.any():
            new += list(t[1] + h * np.array([0.25, 0.5, 0.75]))
    return new


def stability_along(model, body, theta, om, n, crossings):
    """The law's linearisation at every sample (more samples where an eigenvalue may cross the
    axis and come back between two of them), and every change of stability located."""
    def at(t):
        o, m = branch_curve(body, np.array([t]), crossings)
        return linearise_precession(model, t, float(o[0]), float(m[0]))

    at.curve = lambda t: tuple(float(v[0]) for v in branch_curve(body, np.array([t]), crossings))
    points = [linearise_precession(model, float(t), float(o), float(m)) for t, o, m in zip(theta, om, n)]
    for _ in range(4):
        extra = np.setdiff1d(off_crossings(np.array(_hidden(theta, points)), crossings), theta)
        if not extra.size:
            break
        merged = np.concatenate([theta, extra])
        order = np.argsort(merged)
        pool = points + [at(float(t)) for t in extra]
        points = [pool[i] for i in order]
        theta = merged[order]
    om, n = branch_curve(body, theta, crossings)
    changes = []
    for k in range(len(points) - 1):
        lo, f_lo = float(theta[k]), points[k]
        while _n_positive(f_lo) != _n_positive(points[k + 1]):  # every change between the two samples
            change, lo, f_lo = _locate_change(at, lo, float(theta[k + 1]), f_lo, points[k + 1])
            changes.append(change)
    return theta, om, n, tuple(points), tuple(changes)
