"""Seeds on the unstable manifold of a fixed point, and the stability criterion of the vertical.

A seed is x0 = x* + delta v, with v a real unit vector of the unstable subspace of the
linearisation (Euclidean norm in the chart's coordinates: the paper's variables for the
horizontal state, (k, w, v) for the vertical). The sign convention "+" tilts the axis
toward where the body rises: theta decreasing from pi/2 for the horizontal state,
k_x > 0 for the vertical.

Part I's linear stability uses viscous friction; under exact Coulomb friction the
zero-slip fixed points are neutral (rolling), so by default a Coulomb run is seeded along
the viscous eigenvector with the same mu (the paper's recipe, Fig. 6): see
``seed_law`` below, and docs/physics.md (zero slip) for why such seeds can stick.
"""

from __future__ import annotations

import numpy as np

from .body import Spheroid
from .errors import ParameterError
from .validate import check_choice, check_finite, check_positive
from .fixedpoints import FixedPoint, find_fixed_point, horizontal_state, vertical_state
from .friction import Viscous
from .model import Model

__all__ = [
    "unstable_seeds",
    "unstable_manifold_start",
    "vertical_stability_threshold",
    "vertical_is_stable",
    "horizontal_stability_threshold",
    "horizontal_is_unstable",
]


def unstable_seeds(fp: FixedPoint, delta: float) -> list[tuple[str, np.ndarray]]:
    """[(label, x0)] for each unstable direction and both signs; labels "+0", "-0", "+1", ..."""
    delta = check_positive("delta", delta)
    out = []
    for k, v in enumerate(fp.unstable_directions()):
        if fp.kind == "horizontal" and v[4] > 0:
            v = -v  # "+" lowers theta from pi/2
        if fp.kind == "vertical" and v[0] < 0:
            v = -v  # "+" tilts the axis toward +x
        out.append((f"+{k}", fp.x + delta * v))
        out.append((f"-{k}", fp.x - delta * v))
    return out


def unstable_manifold_start(body, friction, *, state: str, delta: float, omega0=None, n0=None, branch: str = "+0",
                            seed_law: str = "viscous") -> tuple[Model, np.ndarray, FixedPoint]:
    """Model and initial state on the unstable manifold of the horizontal or vertical state.

    Parameters
    ----------
    state : "horizontal" (needs omega0) or "vertical" (needs n0)
    seed_law : "viscous" linearises with Viscous(mu) (part I; the paper's recipe, and the
        only choice that has an unstable direction under exact Coulomb), "same" with the
        simulated law itself.

    Returns (model to simulate, x0 in its chart, the fixed point that gave the direction).
    """
    check_choice("unstable_manifold", state, ("horizontal", "vertical"))
    check_choice("seed_law", seed_law, ("viscous", "same"))
    model = Model(body, friction, "euler" if state == "horizontal" else "vector")
    name, value = ("omega0", omega0) if state == "horizontal" else ("n0", n0)
    other = "n0" if state == "horizontal" else "omega0"
    if value is None:
        what = "precession rate Omega0" if state == "horizontal" else "spin n0"
        raise ParameterError(name, f"is required for the {state} state (its {what})", show_value=False)
    if (omega0 if state == "vertical" else n0) is not None:
        raise ParameterError(other, f"does not apply to the {state} state (give `{name}`)", omega0 if other == "omega0" else n0)
    value = check_finite(name, value)
    guess = horizontal_state(value) if state == "horizontal" else vertical_state(value)
    law = Viscous(friction.mu) if seed_law == "viscous" else friction
    fp = find_fixed_point(Model(body, law, model.chart), guess, kind=state, value=value)
    seeds = dict(unstable_seeds(fp, delta))
    if not seeds:
        raise ParameterError(name, f"gives a {state} state without an unstable direction under {fp.law} friction "
                                   f"({fp.classification}), so it has no unstable manifold to seed"
                                   + _unstable_hint(body, state, seed_law, friction), value)
    if not isinstance(branch, str) or branch not in seeds:
        raise ParameterError("branch", f"must be one of {', '.join(seeds)} (sign and index of an unstable direction "
                                       f"of this {state} state)", branch)
    return model, seeds[branch], fp


def _unstable_hint(body, state: str, seed_law: str, friction) -> str:
    if seed_law == "same" and friction.has_rolling_mode:
        return "; exact Coulomb friction makes it neutral: `seed_law`='viscous' takes the viscous direction"
    if isinstance(body, Spheroid):
        fn = horizontal_stability_threshold if state == "horizontal" else vertical_stability_threshold
        crit = fn(body.A, body.C, body.a)
        if crit is not None:
            name = "omega0" if state == "horizontal" else "n0"
            D = body.a**2 * body.C - body.A  # the sign of D fixes on which side the mode grows
            side = ">" if (D > 0) == (state == "horizontal") else "<"
            return f" (for this body and weak friction it is unstable for |{name}| {side} {crit:.6g})"
    return ""


def _moments(A, C, a) -> tuple[float, float, float]:
    return check_positive("A", A), check_positive("C", C), check_positive("a", a)


def vertical_stability_threshold(A: float, C: float, a: float) -> float | None:
    """Spin n0 at which the vertical spin changes stability under friction (any mu > 0).

    Small tilts ~exp(i sigma t) of a spin n about the vertical obey, without friction,
    A sigma^2 - C n sigma + (a - 1/a) = 0 (stable iff C^2 n^2 > 4 A (a - 1/a), the sleeping
    top). The contact point does not slip for sigma = n / a^2; friction damps or drives a
    mode according to the side of that frequency it lies on, so stability changes where a
    frictionless mode crosses it: (a^2 C - A) n^2 = a^3 (a^2 - 1). For the uniform spheroid
    this is n0 = sqrt(5 a^3). Returns None when there is no crossing.
    """
    A, C, a = _moments(A, C, a)
    D = a * a * C - A
    if D == 0 or (a * a - 1) / D <= 0:
        return None
    return float(np.sqrt(a**3 * (a * a - 1) / D))


def vertical_is_stable(A: float, C: float, a: float, n0: float) -> bool:
    """Linear stability of the vertical spin with friction: (a^2 C - A) n0^2 > a^3 (a^2 - 1)."""
    A, C, a = _moments(A, C, a)
    n0 = check_finite("n0", n0)
    return (a * a * C - A) * n0 * n0 > a**3 * (a * a - 1)


def horizontal_stability_threshold(A: float, C: float, a: float) -> float | None:
    """Precession rate at which the horizontal steady precession changes stability under
    friction: (a^2 C - A) Omega0^2 = a^2 - 1 (Omega0 = sqrt(5) for every uniform spheroid).
    Found from the exact linearisations (stability_map study) and tested; the same
    zero-slip-crossing mechanism as at the vertical. None when there is no crossing."""
    A, C, a = _moments(A, C, a)
    D = a * a * C - A
    if D == 0 or (a * a - 1) / D <= 0:
        return None
    return float(np.sqrt((a * a - 1) / D))


def horizontal_is_unstable(A: float, C: float, a: float, omega0: float) -> bool:
    """The horizontal steady precession has a (real, rising) unstable mode iff
    (a^2 C - A) Omega0^2 > a^2 - 1."""
    A, C, a = _moments(A, C, a)
    omega0 = check_finite("omega0", omega0)
    return (a * a * C - A) * omega0 * omega0 > a * a - 1
