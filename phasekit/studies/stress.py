"""Stiff and extreme cases: one run checked for its status, its invariants and its cost.

A :class:`StressCase` is a spheroid, a friction law, a start and a horizon; :func:`stress_run`
runs it (with friction, until the rise is complete) and returns one row: the status and its
reason, t_jump or the end inclination, the :func:`invariant_drift`, the steps and the wall
time. A case the integrator cannot do ends with status "failed" and its reason; an exception is
recorded as status "CRASH" (a bug to report, not to hide). Used by ``studies/stiff_extreme.py``.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ..bodies.spheroid import Spheroid
from ..core.charts import choose_chart
from ..core.model import Model
from ..core.simulate import simulate
from ..core.starts import gyroscopic_start, to_chart
from .paper_checks import rise_complete

#: the columns of a :func:`stress_run` row, in the order of a table
STRESS_COLUMNS = ("case", "a", "law", "t_end", "rtol", "status", "reason", "t_jump", "t_reached", "theta_end", "stuck",
                  "n_events", "invariant_drift", "steps", "backend", "chart", "finite", "wall_s")


@dataclass
class StressCase:
    """A stiff or extreme case: ``label``, the aspect ratio ``a``, the friction ``law``, the
    ``start`` ({"theta0", "omega0" or "n0"}: a sliding-branch start,
    :func:`phasekit.gyroscopic_start`; or {"state": the paper's state}), the horizon ``t_end``,
    the tolerance ``rtol`` and the step budget ``max_steps``.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> ps.StressCase("demo", 1.5, pk.Coulomb(0.1), dict(theta0=1.2, omega0=10.0), 5.0).rtol
    1e-09
    """

    label: str
    a: float
    law: object
    start: dict  # {"theta0", "omega0" | "n0"} (gyroscopic) or {"state": [...]}
    t_end: float
    rtol: float = 1e-9
    max_steps: int = 2_000_000


def invariant_drift(model, X) -> float:
    """How far the states ``X`` (rows, in ``model``'s chart, in time order) drift from what the
    physics allows: without friction the largest relative change of the energy and of L_Z
    (both conserved: must stay ~0); with friction the largest energy increase between
    successive states relative to the first energy (must be <= 0; NaN for one state).

    Examples
    --------
    >>> import numpy as np, phasekit as pk, phasekit.studies as ps
    >>> model = pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.0))
    >>> x0 = pk.gyroscopic_start(model.body, 1.0, omega0=6.0)
    >>> float(ps.invariant_drift(model, np.vstack([x0, x0])))
    0.0
    """
    E = model.evaluate("energy", X)
    if model.friction.mu == 0:
        L = model.evaluate("L_Z", X)
        return float(max(np.max(np.abs(E - E[0])) / abs(E[0]), np.max(np.abs(L - L[0])) / abs(L[0])))
    return float(np.max(np.diff(E)) / abs(E[0])) if E.size > 1 else float("nan")


def stress_run(c: StressCase) -> dict:
    """Run the case (its chart chosen by :func:`phasekit.core.choose_chart`; with friction, until the
    rise is complete, :func:`phasekit.studies.rise_complete`; 201 samples) and return its row
    (keys :data:`STRESS_COLUMNS`; a crash leaves the run's keys out and says why).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> row = ps.stress_run(ps.StressCase("demo", 1.5, pk.Coulomb(0.1), dict(theta0=1.2, omega0=10.0), 5.0))
    >>> row["status"], row["finite"], row["invariant_drift"] <= 0
    ('completed', True, True)
    """
    body = Spheroid(c.a)
    t0 = time.perf_counter()
    row = dict(case=c.label, a=c.a, law=c.law.describe(), t_end=c.t_end, rtol=c.rtol)
    try:
        if "state" in c.start:
            y0 = np.array(c.start["state"], dtype=float)
        else:
            y0 = gyroscopic_start(body, c.start["theta0"], omega0=c.start.get("omega0"), n0=c.start.get("n0"))
        chart = choose_chart(float(y0[4]))
        model = Model(body, c.law, chart)
        x0 = to_chart(chart, y0)
        te = np.linspace(0.0, c.t_end, 201)
        r = simulate(model, x0, c.t_end, rtol=c.rtol, t_eval=te, track_minima=False, max_steps=c.max_steps,
                     events=[rise_complete(body)] if c.law.mu > 0 else [], dense=False)
        # the start, the samples and the end state: a run that ends early still has two points
        X = np.vstack([x0[None, :]] + ([r.ys] if r.ys is not None and len(r.ys) else []) + [r.x[None, :]])
        row.update(status=r.status.value, reason=r.reason or "", t_jump=r.t_jump, t_reached=r.t,
                   theta_end=float(r.euler_end[4]), stuck=r.stuck, n_events=len(r.events), invariant_drift=invariant_drift(model, X),
                   steps=r.n_steps, backend=r.backend, chart=chart, finite=bool(np.all(np.isfinite(r.x))))
    except Exception as exc:  # a crash is a bug to report, not to hide: record it
        row.update(status="CRASH", reason=f"{type(exc).__name__}: {exc}", finite=False)
    row["wall_s"] = time.perf_counter() - t0
    return row


def stress_report(rows) -> list[str]:
    """The rows of :func:`stress_run` as the lines of a text table: a header, a line per row, and
    the count of crashes and non-finite results last.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> lines = ps.stress_report([dict(case="demo", status="CRASH", reason="ValueError: x", wall_s=0.1)])
    >>> lines[1].split()[:2], lines[-1]
    (['demo', 'CRASH'], 'crashes or non-finite results: 1')
    """
    lines = [f"{'case':<46s} {'status':<10s} {'t_jump':>9s} {'theta_end':>9s} {'drift':>9s} {'steps':>8s} {'backend':>13s} "
             f"{'wall s':>7s}  note"]
    for r in rows:
        tj = f"{r['t_jump']:.3f}" if r.get("t_jump") is not None else "-"
        th = f"{r['theta_end']:.4f}" if r.get("theta_end") is not None else "-"
        dr = f"{r['invariant_drift']:.1e}" if r.get("invariant_drift") is not None else "-"
        note = ("stuck; " if r.get("stuck") else "") + (r.get("reason") or "")[:60]
        lines.append(f"{r['case']:<46s} {r['status']:<10s} {tj:>9s} {th:>9s} {dr:>9s} {r.get('steps', 0):>8} "
                     f"{r.get('backend', '-'):>13s} {r['wall_s']:7.2f}  {note}")
    bad = [r for r in rows if r["status"] == "CRASH" or not r.get("finite", False)]
    return lines + [f"crashes or non-finite results: {len(bad)}"]
