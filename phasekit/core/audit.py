"""The convergence audit of published numbers (docs/results/robustness.md): with the environment
variable ``PHASEKIT_AUDIT=tight``, every run of the process (and of the workers it starts, which
inherit the environment) is made at a ten times tighter tolerance, so that a study rerun under it
shows how far its numbers move. ``studies/reproduce.py --audit tight`` runs every study so and
compares. (The other chart is not an audit mode: a study's flights, poles and closed-form checks
are chart-bound; runs are compared across charts by ``Trajectory.verify`` and the threshold
search's verification.)
"""

from __future__ import annotations

import os
from dataclasses import replace

from ..errors import ParameterError

#: the environment variable that turns the audit on
AUDIT_ENV = "PHASEKIT_AUDIT"
#: what it may ask for
AUDITS = ("tight",)


def audit_mode() -> str | None:
    """The audit in force: "tight" or None (the variable unset or empty)."""
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
