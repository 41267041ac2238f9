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

from .validate import check_choice, check_positive
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
    chart = "euler" if state == "horizontal" else "vector"
    if state == "horizontal":
        if omega0 is None:
            raise ValueError("`omega0` is required with --unstable-manifold horizontal.")
        value, guess = omega0, horizontal_state(omega0)
    else:
        if n0 is None:
            raise ValueError("`n0` is required with --unstable-manifold vertical.")
        value, guess = n0, vertical_state(n0)
    law = Viscous(friction.mu) if seed_law == "viscous" else friction
    fp = find_fixed_point(Model(body, law, chart), guess, kind=state, value=value)
    seeds = dict(unstable_seeds(fp, delta))
    if not seeds:
        raise ValueError(
            f"`unstable_manifold`: the {state} state is linearly stable here ({fp.classification}); "
            f"it has no unstable manifold to seed."
        )
    if branch not in seeds:
        raise ValueError(f"`branch` must be one of {', '.join(seeds)}; got {branch!r}.")
    return Model(body, friction, chart), seeds[branch], fp


def vertical_stability_threshold(A: float, C: float, a: float) -> float | None:
    """Spin n0 at which the vertical spin changes stability under friction (any mu > 0).

    Small tilts ~exp(i sigma t) of a spin n about the vertical obey, without friction,
    A sigma^2 - C n sigma + (a - 1/a) = 0 (stable iff C^2 n^2 > 4 A (a - 1/a), the sleeping
    top). The contact point does not slip for sigma = n / a^2; friction damps or drives a
    mode according to the side of that frequency it lies on, so stability changes where a
    frictionless mode crosses it: (a^2 C - A) n^2 = a^3 (a^2 - 1). For the uniform spheroid
    this is n0 = sqrt(5 a^3). Returns None when there is no crossing.
    """
    D = a * a * C - A
    if D == 0 or (a * a - 1) / D <= 0:
        return None
    return float(np.sqrt(a**3 * (a * a - 1) / D))


def vertical_is_stable(A: float, C: float, a: float, n0: float) -> bool:
    """Linear stability of the vertical spin with friction: (a^2 C - A) n0^2 > a^3 (a^2 - 1)."""
    return (a * a * C - A) * n0 * n0 > a**3 * (a * a - 1)


def horizontal_stability_threshold(A: float, C: float, a: float) -> float | None:
    """Precession rate at which the horizontal steady precession changes stability under
    friction: (a^2 C - A) Omega0^2 = a^2 - 1 (Omega0 = sqrt(5) for every uniform spheroid).
    Found from the exact linearisations (stability_map study) and tested; the same
    zero-slip-crossing mechanism as at the vertical. None when there is no crossing."""
    D = a * a * C - A
    if D == 0 or (a * a - 1) / D <= 0:
        return None
    return float(np.sqrt((a * a - 1) / D))


def horizontal_is_unstable(A: float, C: float, a: float, omega0: float) -> bool:
    """The horizontal steady precession has a (real, rising) unstable mode iff
    (a^2 C - A) Omega0^2 > a^2 - 1."""
    return (a * a * C - A) * omega0 * omega0 > a * a - 1
