"""Seeds on the unstable manifold of a fixed point (the criteria are in phasekit.theory.criteria).

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

from .._runtime.validate import check_choice, check_finite, check_positive
from ..bodies.spheroid import Spheroid
from ..core.model import Model
from ..errors import ParameterError
from ..friction.laws import Viscous
from ..theory.criteria import horizontal_stability_threshold, vertical_stability_threshold
from .fixedpoints import find_fixed_point
from .linearisation import FixedPoint, linearise
from .precessions import (
    horizontal_like_angle,
    horizontal_state,
    inverted_state,
    precession_angles,
    precession_state,
    vertical_state,
)


def unstable_seeds(fp: FixedPoint, delta: float) -> list[tuple[str, np.ndarray]]:
    """[(label, x0)] for each unstable direction and both signs; labels "+0", "-0", "+1", ...

    Parameters
    ----------
    fp : FixedPoint
        The linearised steady state.
    delta : float
        Distance of each seed from ``fp.x`` along a unit direction, > 0.

    Returns
    -------
    list of (str, numpy.ndarray)
        The label and the seed x0 = x* +/- delta v, in the chart of ``fp``; empty if ``fp`` is not unstable.

    Raises
    ------
    ParameterError
        If ``delta`` is not a positive finite number.

    Examples
    --------
    >>> import phasekit as pk
    >>> fp = pk.steady.linearise(pk.Model(pk.Spheroid(1.5), pk.Viscous(0.1)), pk.steady.horizontal_state(10.0), kind='horizontal')
    >>> [name for name, x in pk.steady.manifolds.unstable_seeds(fp, 0.01)]
    ['+0', '-0']
    """
    delta = check_positive("delta", delta)
    out = []
    for k, v in enumerate(fp.unstable_directions()):
        if fp.kind in ("horizontal", "horizontal-like", "intermediate") and v[4] > 0:
            v = -v  # "+" lowers theta (toward the end at -k)
        if fp.kind in ("vertical", "inverted") and v[0] < 0:
            v = -v  # "+" tilts the axis toward +x
        out.append((f"+{k}", fp.x + delta * v))
        out.append((f"-{k}", fp.x - delta * v))
    return out


STATES = ("horizontal", "vertical", "inverted", "horizontal-like")


def unstable_manifold_start(body, friction, *, state: str, delta: float, omega0=None, n0=None, branch: str = "+0",
                            seed_law: str = "viscous") -> tuple[Model, np.ndarray, FixedPoint]:
    """Model and initial state on the unstable manifold of a steady state.

    Parameters
    ----------
    body : Body
        The body.
    friction : FrictionLaw
        The law simulated (its ``mu`` also sets the viscous seed law).
    state : {"horizontal", "horizontal-like", "vertical", "inverted"}
        "horizontal" or "horizontal-like" (need omega0), "vertical" (theta = 0) or
        "inverted" (theta = pi) (need n0). "horizontal-like" is the precession continuing the
        horizontal state of a body with h_theta(pi/2) != 0 (phasekit.steady.precessions).
    delta : float
        Distance of the seed from the state along a unit direction, > 0 (:func:`unstable_seeds`).
    omega0, n0 : float, optional
        Precession rate Omega0 or spin n0 of the state: exactly the one ``state`` needs.
    branch : str, optional
        Sign and index of the unstable direction: "+0", "-0", "+1", ...
    seed_law : {"viscous", "same"}, optional
        "viscous" linearises with Viscous(mu) (part I; the paper's recipe, and the
        only choice that has an unstable direction under exact Coulomb), "same" with the
        simulated law itself.

    Returns
    -------
    tuple of (Model, numpy.ndarray, FixedPoint)
        Model to simulate, x0 in its chart, the fixed point that gave the direction.

    Raises
    ------
    ParameterError
        For an invalid argument, a missing or extra rate, a state without an unstable direction, or a
        ``branch`` that is not one of its seeds.
    ConvergenceError
        If Newton does not converge at the steady state.

    Examples
    --------
    >>> import phasekit as pk
    >>> model, x0, fp = pk.steady.unstable_manifold_start(pk.Spheroid(1.5), pk.Viscous(0.1), state='horizontal', delta=0.01, omega0=10.5)
    >>> model.chart.name, fp.kind, x0.round(4)
    ('euler', 'horizontal', array([ 0.0000e+00,  0.0000e+00,  1.0500e+01, -1.0000e-04,  1.5702e+00,
            1.0000e-02]))
    """
    check_choice("unstable_manifold", state, STATES)
    check_choice("seed_law", seed_law, ("viscous", "same"))
    chart = "vector" if state in ("vertical", "inverted") else "euler"
    name, other = ("omega0", "n0") if chart == "euler" else ("n0", "omega0")
    value, given_other = (omega0, n0) if chart == "euler" else (n0, omega0)
    if value is None:
        what = "precession rate Omega0" if chart == "euler" else "spin n0"
        raise ParameterError(name, f"is required for the {state} state (its {what})", show_value=False)
    if given_other is not None:
        raise ParameterError(other, f"does not apply to the {state} state (give `{name}`)", given_other)
    value = check_finite(name, value)
    law = Viscous(friction.mu) if seed_law == "viscous" else friction
    model = Model(body, law, chart)
    if state == "horizontal":
        fp = find_fixed_point(model, horizontal_state(value), kind=state, value=value)
    elif state == "vertical":
        fp = find_fixed_point(model, vertical_state(value), kind=state, value=value)
    elif state == "inverted":
        fp = linearise(model, inverted_state(value), kind=state)
    else:
        fp = _horizontal_like(model, value)
    seeds = dict(unstable_seeds(fp, delta))
    if not seeds and law.mu == 0.0:  # friction drives these instabilities: without it there are none
        raise ParameterError("mu", f"must be > 0 for an unstable-manifold start of the {state} state: without friction "
                                   "it has no unstable direction to seed", friction.mu)
    if not seeds:
        raise ParameterError(name, f"gives a {state} state without an unstable direction under {fp.law} friction "
                                   f"({fp.classification}), so it has no unstable manifold to seed"
                                   + _unstable_hint(body, state, seed_law, friction), value)
    if not isinstance(branch, str) or branch not in seeds:
        raise ParameterError("branch", f"must be one of {', '.join(seeds)} (sign and index of an unstable direction "
                                       f"of this {state} state)", branch)
    # the seed's model is the one to simulate when the seed law is the simulated law
    return (model if law == friction else Model(body, friction, chart)), seeds[branch], fp


def _unstable_hint(body, state: str, seed_law: str, friction) -> str:
    if seed_law == "same" and friction.has_rolling_mode:
        return "; exact Coulomb friction makes it neutral: `seed_law`='viscous' takes the viscous direction"
    if isinstance(body, Spheroid) and body.flip_symmetric and state in ("horizontal", "vertical"):
        fn = horizontal_stability_threshold if state == "horizontal" else vertical_stability_threshold
        crit = fn(body.A, body.C, body.a)
        if crit is not None:
            name = "omega0" if state == "horizontal" else "n0"
            D = body.a**2 * body.C - body.A  # the sign of D fixes on which side the mode grows
            side = ">" if (D > 0) == (state == "horizontal") else "<"
            return f" (for this body and weak friction it is unstable for |{name}| {side} {crit:.6g})"
    return ""


def _horizontal_like(model: Model, omega0: float) -> FixedPoint:
    """The precession with rate omega0 that continues the horizontal state (precessions)."""
    body = model.body
    if body.flip_symmetric:
        raise ParameterError("unstable_manifold", "horizontal-like is for bodies without flip symmetry (use horizontal)",
                             "horizontal-like")
    theta = horizontal_like_angle(body, precession_angles(body, omega0=omega0))
    if theta is None:
        raise ParameterError("omega0", "gives no horizontal-like precession of this body", omega0)
    guess = precession_state(body, theta, omega0=omega0)
    return find_fixed_point(model, guess, kind="horizontal-like", value=omega0, fixed="Omega")
