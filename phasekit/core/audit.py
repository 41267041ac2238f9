"""The convergence audit of published numbers (docs/results/robustness.md): with the environment
variable ``PHASEKIT_AUDIT`` set, every run of the process (and of the workers it starts, which
inherit the environment) is made at a ten times tighter tolerance ("tight") or in the other chart
("chart": the vector chart for the paper's variables and back, unless the start is within 1e-4 of
a pole, where only the vector chart holds), so that a study rerun under it shows how far its
numbers move. ``studies/reproduce.py --audit tight|chart`` runs every study so and compares.
"""

from __future__ import annotations

import os
from dataclasses import replace

import numpy as np

from .._runtime.errors import ParameterError
from .charts import POLE_MARGIN

__all__ = ["AUDIT_ENV", "AUDITS", "audit_mode", "audited", "audited_options", "audited_start"]

#: the environment variable that turns the audit on
AUDIT_ENV = "PHASEKIT_AUDIT"
#: what it may ask for
AUDITS = ("tight", "chart")


def audit_mode() -> str | None:
    """The audit in force: "tight", "chart" or None (the variable unset or empty)."""
    mode = os.environ.get(AUDIT_ENV, "").strip()
    if not mode:
        return None
    if mode not in AUDITS:
        raise ParameterError(AUDIT_ENV, f"must be one of {', '.join(AUDITS)} or empty", mode)
    return mode


def audited_options(opts):
    """The run's options as the audit in force makes them (rtol / 10 under "tight")."""
    if audit_mode() != "tight":
        return opts
    return replace(opts, rtol=max(opts.rtol / 10, 1e-16), atol=None if opts.atol is None else opts.atol / 10)


def audited_start(model, x0, flight: bool = False):
    """The run's model and start as the audit in force makes them (the other chart under "chart")."""
    if audit_mode() != "chart":
        return model, x0
    other = "vector" if model.chart.name == "euler" else "euler"
    if flight:
        return model.with_chart(other), x0
    theta = model.chart.theta(x0)
    if other == "euler" and min(theta, np.pi - theta) < 10 * POLE_MARGIN:
        return model, x0
    moved = model.with_chart(other)
    return moved, moved.chart.from_paper(model.chart.to_paper(x0))


def audited(model, x0, opts, flight: bool = False):
    """(model, x0, options) of a run as the audit in force makes it (unchanged without one)."""
    return (*audited_start(model, x0, flight), audited_options(opts))
