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
from .starts import gyroscopic_start, raw_start, to_chart

__all__ = ["make_model", "choose_formulation", "simulate_start", "POLE_MARGIN"]

#: within this angle of theta = 0 or pi the vector chart is the default. Measured (oblate
#: a = 0.6, n0 = 12, viscous mu = 0.1, rtol 1e-9, to t = 40): away from the pole the Euler
#: chart takes 380-510 Taylor steps against 570-810 for the vector chart (whose state
#: follows the precession) with 10-100x smaller errors; at theta0 = 1e-6 the vector chart
#: wins (382 vs 510 steps, error 8e-8 vs 1.6e-7). Exactly at the pole only it can start.
POLE_MARGIN = 1e-5


def make_model(*, a, mu, friction="coulomb", slip_eps=None, A=None, C=None, formulation="euler") -> Model:
    """A spheroid model from plain parameters (validated, with errors naming the parameter)."""
    body = Spheroid(a, A=A, C=C)
    law = friction_law(friction, mu, slip_eps)
    return Model(body, law, formulation)


def choose_formulation(theta0: float, requested: str = "auto") -> str:
    """``euler`` away from the poles (fewer steps, smaller errors), ``vector`` within POLE_MARGIN."""
    check_choice("formulation", requested, ("auto", "euler", "vector"))
    if requested != "auto":
        return requested
    return "vector" if min(theta0, np.pi - theta0) < POLE_MARGIN else "euler"


def simulate_start(
    *, a, mu, start, t_end, friction="coulomb", slip_eps=None, A=None, C=None,
    rtol=1e-9, stop_at="jump", formulation="auto", backend="auto",
) -> dict:
    """Run one simulation described by plain parameters; returns the JSON dict."""
    body = Spheroid(a, A=A, C=C)
    law = friction_law(friction, mu, slip_eps)
    if start["kind"] == "gyroscopic":
        y0 = gyroscopic_start(body, start["theta0"], omega0=start.get("omega0"), n0=start.get("n0"))
    else:
        chart_hint = "vector" if formulation == "vector" else "euler"
        y0 = raw_start(start["state"], chart=chart_hint)
    chart = choose_formulation(float(y0[4]), formulation)
    if chart == "euler":
        raw_start(y0, chart="euler")  # theta strictly inside (0, pi)
    model = Model(body, law, chart)
    res = simulate(model, to_chart(chart, y0), t_end, rtol=rtol, stop_at=stop_at, backend=backend)
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
    out["start"] = {k: float(v) for k, v in zip(("U", "V", "Omega", "Lambda", "theta", "n"), y0)}
    return out
