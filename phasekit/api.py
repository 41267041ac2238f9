"""Parameter-level entry points shared by the CLI and the studies.

These take plain numbers and names (as typed on a command line), validate them, build
the model and start, run, and return JSON-ready dicts in the paper's variables.
"""

from __future__ import annotations

import numpy as np

from .body import Spheroid
from .errors import check_choice
from .friction import friction_law
from .model import Model
from .simulate import simulate
from .charts import EULER_NAMES, vector_to_euler
from .starts import gyroscopic_start, raw_start, to_chart

__all__ = ["choose_formulation", "simulate_start", "fixed_points_report", "gyroscopic_report", "POLE_MARGIN"]

#: within this angle of theta = 0 or pi the vector chart is the default. Measured (oblate
#: a = 0.6, n0 = 12, viscous mu = 0.1, rtol 1e-9, to t = 40): away from the pole the Euler
#: chart takes 380-510 Taylor steps against 570-810 for the vector chart (whose state
#: follows the precession) with 10-100x smaller errors; at theta0 = 1e-6 the vector chart
#: wins (382 vs 510 steps, error 8e-8 vs 1.6e-7). Exactly at the pole only it can start.
POLE_MARGIN = 1e-5


def choose_formulation(theta0: float, requested: str = "auto") -> str:
    """``euler`` away from the poles (fewer steps, smaller errors), ``vector`` within POLE_MARGIN."""
    check_choice("formulation", requested, ("auto", "euler", "vector"))
    if requested != "auto":
        return requested
    return "vector" if min(theta0, np.pi - theta0) < POLE_MARGIN else "euler"


def simulate_start(
    *, a, mu, start, t_end, friction="coulomb", slip_eps=None, A=None, C=None,
    rtol=1e-9, stop_at="jump", restitution=0.0, formulation="auto", backend="auto",
) -> dict:
    """Run one simulation described by plain parameters; returns the JSON dict."""
    body = Spheroid(a, A=A, C=C)
    law = friction_law(friction, mu, slip_eps)
    seed_info = None
    if start["kind"] == "unstable-manifold":
        from .manifolds import unstable_manifold_start

        check_choice("formulation", formulation, ("auto", "euler", "vector"))
        model, x0, fp = unstable_manifold_start(
            body, law, state=start["state"], delta=start["delta"], omega0=start.get("omega0"), n0=start.get("n0"),
            branch=start.get("branch", "+0"), seed_law=start.get("seed_law", "viscous"),
        )
        if formulation not in ("auto", model.chart):
            raise ValueError(f"`formulation` {formulation!r} cannot start on the {start['state']} state; use {model.chart} or auto.")
        seed_info = {"fixed_point": fp.to_dict(), "delta": start["delta"], "branch": start.get("branch", "+0"),
                     "seed_law": fp.law}
    else:
        if start["kind"] == "gyroscopic":
            y0 = gyroscopic_start(body, start["theta0"], omega0=start.get("omega0"), n0=start.get("n0"))
        else:
            chart_hint = "vector" if formulation == "vector" else "euler"
            y0 = raw_start(start["state"], chart=chart_hint)
        chart = choose_formulation(float(y0[4]), formulation)
        if chart == "euler":
            raw_start(y0, chart="euler")  # theta strictly inside (0, pi)
        model = Model(body, law, chart)
        x0 = to_chart(chart, y0)
    res = simulate(model, x0, t_end, rtol=rtol, stop_at=stop_at, restitution=restitution, backend=backend)
    out = res.to_dict()
    out["model"] = {
        "body": repr(body),
        "a": body.a,
        "A": body.A,
        "C": body.C,
        "friction": law.describe(),
        "mu": law.mu,
        "slip_eps": law.eps if law.eps > 0 else None,
    }
    y_start = x0 if model.chart == "euler" else vector_to_euler(x0)
    out["start"] = {k: float(v) for k, v in zip(EULER_NAMES, y_start)}
    if seed_info is not None:
        out["seed"] = seed_info
    return out


def fixed_points_report(*, a, mu, friction="viscous", slip_eps=None, A=None, C=None, omega0=None, n0=None) -> dict:
    """All steady states at the given Omega0 or n0 with their linear stability (JSON dict)."""
    from .fixedpoints import fixed_points

    if (omega0 is None) == (n0 is None):
        raise ValueError("give exactly one of `omega0` or `n0`.")
    body = Spheroid(a, A=A, C=C)
    law = friction_law(friction, mu, slip_eps)
    pts = fixed_points(Model(body, law, "euler"), Model(body, law, "vector"), omega0=omega0, n0=n0)
    return {"fixed_points": [p.to_dict() for p in pts], "model": {"body": repr(body), "friction": law.describe()},
            "note": "the inverted vertical (theta = pi) is the vertical with k reversed: the same state for a flip-symmetric body"}


def gyroscopic_report(*, a, mu, theta0, t, omega0=None, n0=None, A=None, C=None) -> dict:
    """Gyroscopic mean solution (3.16)-(3.19) at times t (slow time T = mu t)."""
    from .errors import check_positive
    from .gyroscopic import gyroscopic_solution

    body = Spheroid(a, A=A, C=C)
    mu = check_positive("mu", mu)
    t = np.atleast_1d(np.asarray(t, dtype=float))
    if t.size == 0 or not np.all(np.isfinite(t)) or np.any(t < 0):
        raise ValueError("`t` must be one or more finite times >= 0.")
    sol = gyroscopic_solution(body, theta0, omega0=omega0, n0=n0, T=mu * t)
    return {"t": t.tolist(), "T": (mu * t).tolist(), "theta": sol["theta"].tolist(), "Omega": sol["Omega"].tolist(),
            "J": sol["J"], "J_definition": "A Omega h (3.17)", "Omega0": sol["Omega0"], "method": sol["method"]}
