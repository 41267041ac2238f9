"""States at zero slip: the projections onto a slip, the direction in which slip develops where
rolling is infeasible, the mode a state at zero slip continues in (used by the resets of
:mod:`phasekit.core.resets`), and the resets in and out of exact Coulomb's EDGE mode, the contact
sliding on the edge of the friction cone (:mod:`phasekit.core.cone_edge`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .hybrid import Mode, Record, Transition

#: slip speed given to a body that starts sliding from zero slip. The true slip grows from 0
#: like t^2 (the friction is continuous at the onset), and while it is tiny the field is stiff
#: (the slip direction locks at ~mu R/|u|): measured, starting at 4e-10 cost the Taylor method
#: ~51 000 steps per onset, and the cost falls like SLIP_ONSET^(-1/2). Starting at 1e-6 skips
#: that stretch at the price of a 1e-6 perturbation of the velocity of G at each onset.
SLIP_ONSET = 1e-6
#: directions sampled (periodically) when solving for the sliding direction at zero slip
N_DIRECTIONS = 144


def project_no_slip(model, x) -> np.ndarray:
    """Shift the velocity of G so that the slip is exactly zero."""
    x = np.array(x, dtype=float)
    u = np.asarray(model.function("slip")(x, model.p)).ravel()
    i, j = model.chart.velocity_slots
    x[i] -= u[0]
    x[j] -= u[1]
    return x


def creep_entry(model, x) -> np.ndarray:
    """The state a regularised law's slip relaxes to on entering its creep: the contact impulse that
    takes the slip onto the slow manifold u*(x), the limit of the law's fast transient (its error is
    of the order of the slip change over the law's relaxation rate; the creep's pull towards u*, rate
    CREEP_PULL, would spread the same impulse over 1/CREEP_PULL and shift the slow variables by
    its slip change over CREEP_PULL). Two passes: u* moves with the impulse, by eps times it."""
    f = model.function("creep_entry")
    x_on = np.asarray(f(x, model.p)).ravel()
    return np.asarray(f(x_on, model.p)).ravel()


def set_slip(model, x, u_new) -> np.ndarray:
    """The state ``x`` with the slip set to ``u_new`` (the velocity of G shifted)."""
    x = project_no_slip(model, x)
    i, j = model.chart.velocity_slots
    x[i] += u_new[0]
    x[j] += u_new[1]
    return x


def sliding_direction(model, x) -> tuple[np.ndarray, float] | None:
    """The direction e in which slip develops from zero slip where rolling is infeasible.

    Sliding along e means friction -mu R e; it is self-consistent when the slip acceleration
    a(e) it produces is parallel to e and points along it (a x e = 0, a.e > 0), with R > 0.
    Solved as a periodic root search in the angle of e: the cross product is sampled on a
    uniform grid over the circle (no end point, the wrap from the last sample to the first
    included), every sign change is refined by Brent's method, and the consistent root with
    the largest a.e is returned as (e, a.e); None if there is none.
    """
    from scipy.optimize import brentq

    f = model.function("slip_onset")
    p = model.p
    phis = 2 * np.pi * np.arange(N_DIRECTIONS) / N_DIRECTIONS
    acc, R = f.map(N_DIRECTIONS)(np.tile(x[:, None], (1, N_DIRECTIONS)), np.tile(p[:, None], (1, N_DIRECTIONS)), phis[None, :])
    acc, R = np.asarray(acc), np.asarray(R).ravel()
    # R(e) = -g0 / (G.d(e)) has poles (Painleve's directions, G.d(e) = 0) where the cross
    # product changes sign through infinity; divided by R it is smooth, with the same roots.
    with np.errstate(divide="ignore", invalid="ignore"):
        cross = (np.cos(phis) * acc[1] - np.sin(phis) * acc[0]) / R

    def cross_at(phi):
        a, Rphi = (np.asarray(v).ravel() for v in f(x, p, phi))
        return (np.cos(phi) * a[1] - np.sin(phi) * a[0]) / Rphi[0]

    best = None
    for k in range(N_DIRECTIONS):
        lo, hi = phis[k], phis[k] + 2 * np.pi / N_DIRECTIONS
        c0, c1 = cross[k], cross[(k + 1) % N_DIRECTIONS]
        if not (np.isfinite(c0) and np.isfinite(c1)):
            continue
        if c0 == 0.0:
            phi = lo
        elif c0 * c1 < 0.0:
            try:
                phi = brentq(cross_at, lo, hi, xtol=1e-14)
            except ValueError:  # a non-finite value inside the bracket (R exactly infinite), or
                # the wrap, where 2 pi evaluated afresh differs in sign from the grid's 0 by rounding
                # (a root at 0 itself: planar motions)
                try:
                    phi = brentq(lambda q: cross_at(q % (2 * np.pi)), lo, hi, xtol=1e-14) % (2 * np.pi)
                except ValueError:
                    continue
        else:
            continue
        a, Rphi = (np.asarray(v).ravel() for v in f(x, p, phi))
        along = np.cos(phi) * a[0] + np.sin(phi) * a[1]
        if along > 0 and Rphi[0] > 0 and (best is None or along > best[1]):
            best = (np.array([np.cos(phi), np.sin(phi)]), float(along))
    return best


def zero_slip_start(model, x) -> tuple[Mode, np.ndarray, str] | None:
    """At zero slip: ROLLING if static friction can hold, else SLIDING in the consistent
    direction (at |u| = SLIP_ONSET). None when no direction is consistent."""
    x0 = project_no_slip(model, x)
    if float(model.function("margin_rolling")(x0, model.p)) >= 0.0:
        return Mode.ROLLING, x0, "zero slip and |F_req| <= mu R"
    found = sliding_direction(model, x0)
    if found is None:
        return None
    return Mode.SLIDING, set_slip(model, x0, SLIP_ONSET * found[0]), "zero slip, rolling infeasible"


@dataclass(frozen=True)
class EdgeOnset:
    """ROLLING reached |F_req| = mu R: slide on the cone's edge (EDGE) from u = 0 exactly, where EDGE's
    friction is consistent there (R > 0, finite); else ``fallback`` (the slip onset with its nudge)."""

    fallback: object

    def __call__(self, model, event, mode, t, x) -> Transition:
        x0 = project_no_slip(model, x)
        R = float(np.asarray(model.function("edge_check")(x0, model.p)).ravel()[0])
        if not (np.isfinite(R) and R > 0.0):
            return self.fallback(model, event, mode, t, x)
        return Transition(Mode.EDGE, t, x0, (Record("slip", mode.value, Mode.EDGE.value, x0,
                                                    "|F_req| reached mu R: sliding on the cone's edge"),))


@dataclass(frozen=True)
class EdgeStick:
    """EDGE: the slip along e* fell to zero. Roll from u = 0 (what is left of the slip, ~EDGE_STICK,
    taken out by a contact impulse: ``edge_landing``) where static friction holds there; else the
    guard was grazed (it starts at 0 on entry from ROLLING, and rounding can take it below), and EDGE
    goes on."""

    def __call__(self, model, event, mode, t, x) -> Transition:
        x0 = project_no_slip(model, np.asarray(model.function("edge_landing")(x, model.p)).ravel())
        if float(model.function("margin_rolling")(x0, model.p)) < 0.0:
            return Transition(mode, t, x, resume=True)
        return Transition(Mode.ROLLING, t, x0, (Record("stick", mode.value, Mode.ROLLING.value, x0,
                                                       "the slip on the cone's edge vanished"),))


@dataclass(frozen=True)
class OnEdge:
    """An event of ROLLING and SLIDING watched on and off the cone's edge too (spin friction or
    rolling resistance stopping its part of w): ``inner`` is applied as from ``like`` (ROLLING: at
    the state with its slip, below EDGE_OUT, set to zero); where it only grazes or the couple cannot
    hold, the mode goes on."""

    inner: object
    like: Mode = Mode.ROLLING

    def __call__(self, model, event, mode, t, x) -> Transition:
        tr = self.inner(model, event, self.like, t, project_no_slip(model, x) if self.like is Mode.ROLLING else x)
        if tr.stop is None and (tr.resume or tr.mode is self.like):
            return Transition(mode, t, x, resume=True)
        return tr
