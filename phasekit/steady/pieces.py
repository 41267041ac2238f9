"""The steady-state structure of a compound body, piece by piece, and of a body with an edge on
its range of theta (phasekit.steady.structure).

A compound body (:mod:`phasekit.bodies.compound`: the tippe top with its stem) touches the table
with one piece at a time: its support H(c) = max_i h_i(c) is one piece's analytic function
between two switch angles (the body's ``transfers``), with a kink at each switch, where H'
jumps and with it every quantity of the steady precessions (q = -H', rho_2 = H - c H', z, D;
phasekit.steady.branches). So the structure is computed on each piece's range of theta with
that piece's own support: its branches are cut at every switch (an end of kind "switch",
where the contact passes to the next piece), and its static equilibria and families are those
of the piece inside its range, each naming its piece.

A piece's own support is read off the body's: H written with CasADi's ``if_else`` (or fmax,
fmin, fabs) with every such switch frozen at the branch it takes inside the piece, an
expression analytic across the switch (the tippe top's ball: 1 - offset c, an eccentric
sphere; its stem: r - l c, the support of a sphere of radius r centred l from G), so the
closed forms hold up to the switch itself and the ends there are exact limits, not samples
across the kink. Inside the piece's range it is the body's H, operation for operation: the
linearisations along a branch use the whole body's model there (the samples keep END_GAP from
a switch).

A body with an edge or a tip (:mod:`phasekit.bodies.edged`: ``theta_range``, ``limits``) is one
piece whose model holds on an open range of theta: its structure is computed on that range,
every branch ending at a limit of it (an end of kind "limit", named as the run's event: "face
down", "side down"; a pole only where the range holds it, as the cone's tip holds theta = pi),
its statics and families those inside the range. The equations hold there: on an edge the
meridian's radius of curvature is 0 but rho_2 = x_P / sin(theta) = H - c H' > 0.

On a tip rho_2 = 0 too (H = -d c: the contact point fixed on the axis, d from G). The steady
states of phasekit's structure have G at rest and no friction force (zero slip, for every law):
a tip at rest with G at rest leaves w along the axis, so Omega = 0, and then the gravity couple
d sin(theta) (R = 1) is unbalanced: there is no steady precession off the vertical (the curve's
Omega^2 = q rho_2 / D = 0 is the zero-slip condition Omega z = n rho_2 multiplied through by
rho_2 = 0, not a state). The steady precessions of a tip are the Lagrange top's, with the tip
held by friction (exact Coulomb's rolling, |F| <= mu R) and G going round the vertical through
it: at each theta a one-parameter family (:func:`tip_precession`). The structure of a body on a
tip is therefore "degenerate" (:func:`tip_degeneracy` says why), with the statics and the spin
about the vertical on the tip (theta = pi) listed.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, replace

import numpy as np

from ..bodies.compound import PieceSupport
from .branches import holds_state, precession_geometry
from .families import SpinFamily, StaticEquilibrium, families_of, statics_of
from .records import POLE_EDGES, Edge, Interval, Part


def parts(body) -> list[Part]:
    """The ranges of ``body`` in theta order: one per piece between its switches (read from
    ``body.transfers``), an edged body's own range (:func:`range_edges`: ``body.theta_range``), or
    the whole of [0, pi]."""
    if body.theta_range is not None:
        return [Part(None, body, range_edges(body))]
    transfers = body.transfers
    if not transfers:
        return [Part(None, body, POLE_EDGES)]
    sides = {}  # switch angle -> (the piece below it, the piece above it)
    for t in transfers:
        sides[float(t.theta)] = (t.from_piece, t.to_piece) if t.direction > 0 else (t.to_piece, t.from_piece)
    cuts = sorted(sides)
    names = [sides[cuts[0]][0]] + [sides[t][1] for t in cuts]
    edges = [POLE_EDGES[0]] + [Edge(t) for t in cuts] + [POLE_EDGES[1]]
    out = []
    for k, name in enumerate(names):
        lo, hi = edges[k], edges[k + 1]
        if k > 0:
            lo = replace(lo, switch=names[k - 1])
        if k < len(names) - 1:
            hi = replace(hi, switch=names[k + 1])
        out.append(Part(name, PieceSupport(body, name, 0.5 * (lo.theta + hi.theta)), (lo, hi)))
    return out


def range_edges(body) -> tuple[Edge, Edge]:
    """The two ends of an edged body's range of theta as edges of the structure: a pole where the
    range holds it (the cone's tip at pi), else an Edge with the name of the body's limit on that
    side (``limits``: direction -1 below, +1 above)."""
    names = {lim.direction: lim.name for lim in body.limits}
    out = []
    for side, t in enumerate(body.theta_range):
        if t == POLE_EDGES[side].theta and body.in_range(t):
            out.append(POLE_EDGES[side])
        else:
            out.append(Edge(float(t), limit=names.get(2 * side - 1, "the end of its range")))
    return out[0], out[1]


# -- a tip -----------------------------------------------------------------------------------------

#: rho_2 within this of 0 (relative to |q|) at every sampled theta of the range is a tip
TIP_RTOL = 1e-12


def tip_degeneracy(body) -> str | None:
    """Why the structure of an edged ``body`` is a continuum of steady states, not branches, or
    None: rho_2 = 0 over its range (a tip: module notes)."""
    lo, hi = body.theta_range
    grid = np.linspace(lo, hi, 259)[1:-1]
    q, rho2 = precession_geometry(body, grid)[:2]
    if not np.all(np.abs(rho2) <= TIP_RTOL * np.abs(q)):
        return None
    d = float(np.median(q))
    return (f"a tip: rho_2 = x_P / sin(theta) = 0 for theta in ({lo:.6g}, {hi:.6g}] (the contact point fixed on the "
            f"axis, d = {d:.6g} from G), so with G at rest a tip at rest needs Omega = 0 and the gravity couple d "
            f"sin(theta) is unbalanced: no steady precession with zero friction force off the vertical (only the spin "
            f"about the vertical on the tip at theta = pi). With the tip held by friction (exact Coulomb's rolling) every "
            f"theta has a one-parameter family, the Lagrange top's: Omega (C n - (A + d^2) Omega cos theta) = -d for any "
            f"Omega != 0, G going round the vertical through the tip at V = -d Omega sin theta, which needs the friction "
            f"d Omega^2 sin theta <= mu (R = 1): not a fixed point with G at rest, so neither listed here nor found by "
            f"fixed_points")


def tip_precession(body, theta: float, omega: float) -> np.ndarray:
    """The Lagrange top's steady precession of a body on a tip (module notes) at ``theta`` and
    rate ``omega``: the Euler-chart state (U, V, Omega, Lambda, theta, n) with the tip at rest,
    n = (A' Omega^2 cos(theta) - d) / (C Omega), A' = A + d^2, V = -d Omega sin(theta), U = 0.
    A zero of the rolling (no-slip) field of exact Coulomb friction, which holds it with the
    friction force F_X = d Omega^2 sin(theta) (G's centripetal force; within the cone where
    that is at most mu).

    Parameters
    ----------
    body : EdgedBody
        A body on a tip (``tip_degeneracy`` not None), e.g. Cone(2.0, on="tip").
    theta : float
        Inside its range, radians.
    omega : float
        The precession rate, != 0.

    Returns
    -------
    numpy.ndarray
        The state (U, V, Omega, Lambda, theta, n).
    """
    d = float(precession_geometry(body, theta)[0][0])  # q = -H' = d on a tip
    c, s = math.cos(theta), math.sin(theta)
    n = ((body.A + d * d) * omega * omega * c - d) / (body.C * omega)
    return np.array([0.0, -d * omega * s, float(omega), 0.0, float(theta), n])


# -- statics and families on a piece -----------------------------------------------------------


@dataclass(frozen=True)
class StaticOnPiece(StaticEquilibrium):
    """A static equilibrium of a compound body: a :class:`~phasekit.steady.families.StaticEquilibrium`
    of the piece it rests on, ``piece``."""

    piece: str | None = None

    def to_dict(self) -> dict:
        return {**super().to_dict(), "piece": self.piece}


@dataclass(frozen=True)
class FamilyOnPiece(SpinFamily):
    """A family of steady states of a compound body: a :class:`~phasekit.steady.families.SpinFamily`
    on the piece it touches with, ``piece``."""

    piece: str | None = None

    def to_dict(self) -> dict:
        return {**super().to_dict(), "piece": self.piece}


def statics_and_families(model, part: Part, pts: list[Edge], intervals: list[Interval], stability: bool):
    """The static equilibria and families of ``part``: a one-piece body's, or those of a
    compound body's piece inside its range (a pole only if the range reaches it), naming the
    piece. ``pts`` are the part's special points, ``intervals`` its branches' intervals with their
    ends (phasekit.steady.branches)."""
    statics = statics_of(part.support, pts)
    families = families_of(model, part.support, pts, intervals, stability)
    if part.support.theta_range is not None:  # an edged body: the poles only where its range holds them
        return (tuple(s for s in statics if holds_state(part.support, s.theta)),
                tuple(f for f in families if holds_state(part.support, f.theta)))
    if part.name is None:
        return statics, families
    inside = lambda t: part.lo <= t <= part.hi  # noqa: E731
    fields = lambda x: {f.name: getattr(x, f.name) for f in dataclasses.fields(x)}  # noqa: E731
    return (tuple(StaticOnPiece(**fields(s), piece=part.name) for s in statics if inside(s.theta)),
            tuple(FamilyOnPiece(**fields(f), piece=part.name) for f in families if inside(f.theta)))


def in_theta_order(families) -> tuple:
    """A compound body's families gathered piece by piece, in a one-piece body's order: the spins
    about the vertical (theta = 0, then pi) first, then the others by theta."""
    return tuple(sorted(families, key=lambda f: (f.kind != "pole", f.theta)))

