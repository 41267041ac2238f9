"""A tippe top's inversion: simulated from a spin about the vertical, classified, and set beside
the predictions of :mod:`phasekit.theory.tippetop`.

The top is an :class:`phasekit.EccentricSphere` (radius 1, G at ``alpha`` below the centre,
moments A and C about G) in the vector chart (regular at theta = 0 and pi), spun about the
vertical at n0 with its axis tilted theta0 and G at rest. Flights and impacts are followed
(``stop_at="none"``). A run ends when theta reaches pi - 0.05 ("full", with its time) or at
t_end; otherwise the outcome is "never" if theta stayed below 0.3 and "partial" if not, with
theta_end the mean of theta over the last 10% of the run. Jellett's integral, conserved under
any friction law, is checked along the run (its drift).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from .._runtime.validate import check_choice
from ..bodies.spheroid import EccentricSphere
from ..core.hybrid import Event
from ..core.model import Model
from ..core.simulate import simulate
from ..core.starts import to_chart, vertical_spin_start
from ..errors import Status
from ..friction.laws import Coulomb, Viscous
from ..theory.tippetop import (
    classical_inversion,
    full_inversion_spin,
    jellett_of_vertical_start,
    theta_f,
    ueda_group,
    ueda_group_limit,
)

#: theta at which a top counts as fully inverted (the run stops there)
THETA_FULL = math.pi - 0.05
#: a top whose theta stayed below this never inverted
THETA_NEVER = 0.3
#: exact Coulomb: a top that has settled in a tilted rolling state can alternate stick and slip
#: for hundreds of cycles (each slip onset from zero slip needs tiny Taylor steps: 0.3-1 s per
#: cycle measured). A map run is cut after this many mode switches or this wall time and
#: classified from the span computed so far (its status and reason are kept).
MAP_MAX_SWITCHES, MAP_MAX_WALL = 400, 45.0
#: the friction laws of a map run: viscous friction and exact Coulomb friction
LAWS = ("viscous", "coulomb")


def simulate_inversion(top, law, n0: float, t_end: float, *, theta0: float = 0.1, rtol: float = 1e-10, dense: bool = True,
                       restitution: float = 0.0, max_switches: int = 200_000, max_wall: float = 300.0):
    """Simulate ``top`` (an :class:`phasekit.EccentricSphere`) under the friction ``law`` from
    the spin ``n0`` about the vertical with its axis tilted ``theta0``, in the vector chart,
    through flights and impacts, until theta reaches :data:`THETA_FULL` (status "stopped") or
    ``t_end``. Returns the :class:`phasekit.core.Trajectory`.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> r = ps.simulate_inversion(pk.EccentricSphere(0.3, A=0.38, C=0.4), pk.Viscous(0.3), 8.0, 150.0)
    >>> r.status.value, round(float(r.sample([r.t])["theta"].iloc[0]), 2)
    ('stopped', 3.09)
    """
    x0 = to_chart("vector", vertical_spin_start(theta0, n0))
    stop = Event("theta", THETA_FULL, direction=+1, name="inverted")
    return simulate(Model(top, law, "vector"), x0, t_end, rtol=rtol, stop_at="none", restitution=restitution, events=[stop],
                    dense=dense, max_switches=max_switches, max_wall=max_wall)


@dataclass(frozen=True)
class InversionRun:
    """One run of a tippe top from the vertical spin (made by :func:`inversion_run`): its
    outcome (``full`` | ``partial`` | ``never`` | ``failed``), theta at the end (mean over the
    last 10%) and at most, the time of full inversion, the span run, the least normal reaction,
    lift-offs and sticks, beside the predictions of :mod:`phasekit.theory.tippetop`
    (``classical``: 1 - alpha < gamma < 1 + alpha; ``group``: fast-spin group I / II / III;
    ``predicted`` and ``theta_f_predicted``: :func:`~phasekit.theory.tippetop.ueda_group` and
    :func:`~phasekit.theory.tippetop.theta_f` for this start; ``n_full_predicted``: the spin
    above which full inversion is predicted, inf: never), and the drift of Jellett's integral.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> row = ps.inversion_run("viscous", 0.3, 0.3, 0.95, 8.0, 150.0, C=0.4)
    >>> row.outcome, row.predicted, row.jellett_drift < 1e-9
    ('full', 'full', True)
    """

    key: str
    law: str
    mu: float
    alpha: float
    gamma: float
    A: float
    n0: float
    outcome: str  # full | partial | never | failed
    theta_end: float | None
    theta_max: float | None
    t_full: float | None
    t_run: float
    R_min: float | None
    n_liftoff: int
    n_stick: int
    t_first_stick: float | None
    classical: bool
    group: str  # fast-spin group I / II / III
    predicted: str  # never | full | partial (ueda_group for this start)
    theta_f_predicted: float
    n_full_predicted: float  # spin above which full inversion is predicted (inf: never)
    jellett_drift: float | None
    status: str
    reason: str
    wall_s: float


def inversion_run(law: str, mu: float, alpha: float, gamma: float, n0: float, t_end: float, rtol: float = 1e-10, *,
                  C: float, theta0: float = 0.1, key: str = "") -> InversionRun:
    """Simulate the tippe top ``alpha``, A = ``gamma`` C, C under ``law`` ("viscous":
    :class:`phasekit.Viscous`, "coulomb": exact :class:`phasekit.Coulomb`) with coefficient
    ``mu``, spun at ``n0`` from ``theta0`` (:func:`simulate_inversion`, cut after 400 mode
    switches or 45 s of wall time), and classify it: an :class:`InversionRun` named ``key``
    (the row's key in a store).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> ps.inversion_run("viscous", 0.3, 0.2, 1.25, 8.0, 150.0, C=0.4).outcome
    'partial'
    """
    law = check_choice("law", law, LAWS)
    t0 = time.perf_counter()
    A = gamma * C
    pred = dict(classical=classical_inversion(alpha, A, C), group=ueda_group_limit(alpha, A, C),
                predicted=ueda_group(alpha, A, C, n0, theta0=theta0), theta_f_predicted=theta_f(alpha, A, C, n0, theta0=theta0),
                n_full_predicted=full_inversion_spin(alpha, A, C, theta0=theta0))
    r = simulate_inversion(EccentricSphere(alpha, A=A, C=C), Viscous(mu) if law == "viscous" else Coulomb(mu), n0, t_end,
                           theta0=theta0, rtol=rtol, max_switches=MAP_MAX_SWITCHES, max_wall=MAP_MAX_WALL)
    sticks = r.events_named("stick")
    cut = r.status is Status.FAILED and bool(sticks) and r.t > 2 * sticks[0].t
    if (r.status is Status.FAILED and not cut) or not r.segments:
        return InversionRun(key, law, mu, alpha, gamma, A, n0, "failed", None, None, None, r.t, r.R_min, 0, 0, None, **pred,
                            jellett_drift=None, status=str(r.status), reason=r.reason or "", wall_s=time.perf_counter() - t0)
    df = r.sample(np.linspace(r.t0, r.t, 4001))
    theta = df["theta"].to_numpy()
    drift = float(np.max(np.abs(df["jellett"].to_numpy() - jellett_of_vertical_start(alpha, A, C, theta0, n0))))
    if r.status is Status.STOPPED:
        outcome, t_full = "full", r.t
    else:
        outcome, t_full = ("never" if theta.max() < THETA_NEVER else "partial"), None
    theta_end = float(np.mean(theta[int(0.9 * theta.size):]))
    return InversionRun(key, law, mu, alpha, gamma, A, n0, outcome, theta_end, float(theta.max()), t_full, r.t, r.R_min,
                        [e.name for e in r.events].count("lift-off"), len(sticks), sticks[0].t if sticks else None, **pred,
                        jellett_drift=drift, status=str(r.status), reason=r.reason or "", wall_s=time.perf_counter() - t0)


def inversion_summary(rows) -> dict:
    """How a set of :class:`InversionRun` rows agrees with the predictions: the runs, the
    failed ones, the largest Jellett drift, and per friction law the agreements and
    disagreements (each described), the tops that hopped or stuck, the outcomes, and the largest
    error of the predicted theta_f where both say "partial".

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> row = ps.inversion_run("viscous", 0.3, 0.3, 0.95, 8.0, 150.0, C=0.4)
    >>> ps.inversion_summary([row])["viscous"]["agree"]
    1
    """
    ok = [r for r in rows if r.outcome != "failed"]
    out = {"n_runs": len(rows), "n_failed": len(rows) - len(ok), "max_jellett_drift": max((r.jellett_drift for r in ok), default=None)}
    for law in sorted({r.law for r in ok}):
        sub = [r for r in ok if r.law == law]
        dis = [r for r in sub if r.outcome != r.predicted]
        out[law] = {"n": len(sub), "agree": len(sub) - len(dis), "disagree": len(dis),
                    "hopped": sum(1 for r in sub if r.n_liftoff), "stuck": sum(1 for r in sub if r.n_stick),
                    "by_outcome": {k: sum(1 for r in sub if r.outcome == k) for k in ("full", "partial", "never")},
                    "disagreements": [f"alpha={r.alpha:g} gamma={r.gamma:g} n0={r.n0:g}: measured {r.outcome} (theta_end "
                                      f"{r.theta_end:.3f}), predicted {r.predicted} (theta_f {r.theta_f_predicted:.3f})"
                                      + (f", stuck at t={r.t_first_stick:.3g}" if r.t_first_stick is not None else "")
                                      for r in dis]}
        partial = [r for r in sub if r.outcome == r.predicted == "partial"]
        if partial:
            out[law]["partial_theta_error_max"] = max(abs(r.theta_end - r.theta_f_predicted) for r in partial)
    return out
