"""Which steady states survive the dissipation laws (rolling resistance, spin friction, air drag:
phasekit.friction.dissipation), for :func:`phasekit.steady_structure` and
:func:`phasekit.fixed_points`.

A steady state keeps its energy, and each dissipation law takes out the power f.v + Gamma.w <= 0.
So a steady state of the sliding law is one of the law with dissipation only where every law's
power vanishes there: rolling resistance wherever w is vertical (its rolling part w_h = 0), spin
friction where w_Z = 0, air drag on rotation where w = 0 and on translation where G is still.
On a branch of steady precessions (Omega != 0, G still) these hold at isolated points at most:
no branch survives rolling resistance, spin friction or air drag on rotation, and every motion
but rest loses energy. Rest survives them all (w = v = 0, every power zero); rolling resistance
also holds the body still wherever the weight's lever arm about the contact point is at most delta.
A family survives where the laws vanish on it: the spins about the vertical (w = n e_Z, G still)
and the horizontal state (w = Omega e_Z) under rolling resistance or air drag on translation
alone; the straight rolling on a static equilibrium at theta = pi/2 (w horizontal) under spin
friction alone.
"""

from __future__ import annotations

import numpy as np

from ..core.hybrid import Mode

#: a law acts at a state when the power it takes out exceeds this times the kinetic energy
#: (per unit time): rounding of a rate that is zero in exact arithmetic (cos(pi/2) ~ 6e-17 in
#: w_h) leaves ~1e-24 of it, the weakest law of interest (coefficient 1e-9) ~1e-9
POWER_RTOL = 1e-12


def acting_laws(model, x) -> tuple[str, ...]:
    """The names of the dissipation laws of ``model`` that take energy out at the contact state
    ``x`` (of ``model``'s chart, zero slip): those whose power is below -POWER_RTOL times the
    kinetic energy there (at rest, none)."""
    laws = model.friction.dissipation
    if not laws:
        return ()
    mode = Mode.ROLLING if model.friction.has_rolling_mode else Mode.SLIDING
    x = np.asarray(x, dtype=float)
    powers = np.asarray(model.function(f"power_{mode.value}")(x, model.p)).ravel()[1:]
    kinetic = float(model.function("energy")(x, model.p)) - float(model.function("h")(x, model.p))
    return tuple(d.name for d, p in zip(laws, powers) if -p > POWER_RTOL * kinetic)


def dissipation_note(model, removed: list[str], branches_left: int, families_left: int) -> str:
    """What a steady structure under dissipation laws says about itself (the module notes)."""
    names = ", ".join(d.name for d in model.friction.dissipation)
    delta = [d.values[0] for d in model.friction.dissipation if d.name == "rolling-resistance"]
    held = (f"; rolling resistance also holds the body at rest wherever the lever arm of its weight "
            f"|h_theta| <= delta = {delta[0]:g}" if delta else "")
    head = (f"no steady precession with dissipation ({names}): energy decreases along every motion except rest"
            + (" and the families that remain" if families_left else "")
            if not branches_left else f"with dissipation ({names}) only the steady states that keep their energy remain")
    gone = f"; left out (a law takes energy out of them): {', '.join(removed)}" if removed else ""
    return (f"{head}{gone}; the static equilibria remain{held}; the stability along the branches and families "
            "is that without dissipation")
