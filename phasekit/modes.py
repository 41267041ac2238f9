"""Contact modes, their guards, and the maps applied when the mode switches.

SLIDING  smooth while the slip u != 0 (Coulomb) or everywhere (viscous, regularised).
ROLLING  exact Coulomb at zero slip: u = 0 is a constraint and the friction needed to keep
         it, F_req, is part of the solution. Valid while |F_req| <= mu R.
FLIGHT   no contact (R = 0): gravity and torque-free rotation (:mod:`phasekit.flight`), until
         the gap closes (touchdown); then the impact law (:mod:`phasekit.impact`).

Switches (exact Coulomb only)
-----------------------------
stick   SLIDING -> ROLLING when the slip reaches zero and |F_req| <= mu R. The guard fires
        at |u| = STICK_SLIP; the zero of |u| is then extrapolated (|u| is linear in time
        as it vanishes under Coulomb friction), so the switch is located to O(STICK_SLIP^2).
slip    ROLLING -> SLIDING when |F_req| reaches mu R (guard mu^2 R^2 - |F_req|^2 = 0). The
        friction force is continuous, so sliding starts with slip direction -F_req/|F_req|.
A zero-slip start where rolling is infeasible slides in the direction e for which the slip
acceleration is parallel to e (friction -mu R e self-consistent).
"""

from __future__ import annotations

import enum

import numpy as np

__all__ = ["Mode", "velocity_slots", "mode_events", "project_no_slip", "zero_slip_start", "after_stick", "after_slip"]


class Mode(str, enum.Enum):
    """Contact modes; the simulator switches between them only at located events."""

    SLIDING = "sliding"
    ROLLING = "rolling"
    FLIGHT = "flight"

    def __str__(self) -> str:
        return self.value


def velocity_slots(chart: str) -> tuple[int, int]:
    """State indices of the two horizontal velocity components of O (U, V or v_x, v_y).

    Adding du to them adds du to the slip, in the same axes: that is how a switch sets the slip.
    """
    return (0, 1) if chart == "euler" else (6, 7)


def mode_events(model, mode, *, pointwise: bool = False, rise: bool = False, near_stick: bool = False):
    """Guards that end a segment in ``mode``, as EventSpecs (the first located wins).

    ``pointwise`` selects the stick guard for integrators that evaluate the field pointwise
    (see :mod:`phasekit.model`). ``near_stick`` (regularised law only): the slip is below
    10 eps, so watch for it to grow past 100 eps instead of for another stick.
    """
    from .backends import EventSpec

    if mode is Mode.FLIGHT:
        return (EventSpec("touchdown", "gap", -1, rate="gap_rate"),)
    events = [EventSpec("lift-off", f"R_{mode.value}", -1, rate=f"Rdot_{mode.value}")]
    can_stick = "margin_rolling" in model.compiled.functions or model.friction.eps > 0
    if near_stick:
        events.append(EventSpec("unstick", "unstick_guard", -1))
    elif mode is Mode.SLIDING and can_stick:
        if pointwise:
            events.append(EventSpec("stick", "stick_guard_sq", -1, rate="slip_speed2_rate"))
        else:
            events.append(EventSpec("stick", "stick_guard", -1))
    if mode is Mode.ROLLING:
        events.append(EventSpec("slip", "margin_rolling", -1))
    if rise:
        events.append(EventSpec("rise-complete", "rise_guard", -1))
    return tuple(events)


def project_no_slip(model, x, p) -> np.ndarray:
    """Shift the velocity of O so that the slip is exactly zero."""
    x = np.array(x, dtype=float)
    u = np.asarray(model.function("slip")(x, p)).ravel()
    i, j = velocity_slots(model.chart)
    x[i] -= u[0]
    x[j] -= u[1]
    return x


def _set_slip(model, x, p, u_new) -> np.ndarray:
    x = project_no_slip(model, x, p)
    i, j = velocity_slots(model.chart)
    x[i] += u_new[0]
    x[j] += u_new[1]
    return x


def _rolling_ok(model, x, p) -> bool:
    return float(model.function("margin_rolling")(x, p)) >= 0.0


def zero_slip_start(model, x, p, slip0: float):
    """At zero slip: ROLLING if static friction can hold, else SLIDING in the consistent direction.

    Returns (mode, state, detail) or raises RuntimeError when no consistent direction exists.
    """
    x0 = project_no_slip(model, x, p)
    if _rolling_ok(model, x0, p):
        return Mode.ROLLING, x0, "zero slip and |F_req| <= mu R"
    f = model.function("slip_onset")
    phis = np.linspace(-np.pi, np.pi, 145)

    def cross(phi):
        acc = np.asarray(f(x0, p, phi)[0]).ravel()
        return np.cos(phi) * acc[1] - np.sin(phi) * acc[0], np.cos(phi) * acc[0] + np.sin(phi) * acc[1]

    vals = np.array([cross(ph) for ph in phis])
    from scipy.optimize import brentq

    best = None
    for k in range(len(phis) - 1):
        if vals[k, 0] == 0 or vals[k, 0] * vals[k + 1, 0] < 0:
            phi = brentq(lambda ph: cross(ph)[0], phis[k], phis[k + 1], xtol=1e-14)
            along = cross(phi)[1]
            if along > 0 and (best is None or along > best[1]):
                best = (phi, along)
    if best is None:
        raise RuntimeError("zero slip, rolling infeasible, and no self-consistent sliding direction")
    e = np.array([np.cos(best[0]), np.sin(best[0])])
    return Mode.SLIDING, _set_slip(model, x0, p, slip0 * e), "zero slip, rolling infeasible"


def after_stick(model, x, p, slip0: float):
    """SLIDING reached the stick guard: extrapolate to u = 0 and choose the next mode.

    Returns (dt, mode, state, detail); dt >= 0 is the extrapolated time to zero slip, or
    None when the slip is not actually vanishing (a graze of the guard).
    """
    s2 = float(model.function("slip_speed2")(x, p))
    rate = float(model.function("slip_speed2_rate")(x, p))
    if rate >= 0:
        return None
    dt = 2.0 * s2 / (-rate)  # |u| linear in time as it vanishes: |u|^2 ~ (rate/2) * 2 * dt
    x_s = x + dt * np.asarray(model.function("rhs_sliding")(x, p)).ravel()
    mode, x_new, detail = zero_slip_start(model, x_s, p, slip0)
    return dt, mode, x_new, detail


def after_slip(model, x, p, slip0: float):
    """ROLLING reached |F_req| = mu R: slide with slip along -F_req (friction continuous)."""
    Fc = np.asarray(model.function("Fc_rolling")(x, p)).ravel()
    F = Fc[:2]
    norm = np.hypot(*F)
    if norm == 0.0:
        return zero_slip_start(model, x, p, slip0)
    return Mode.SLIDING, _set_slip(model, x, p, -slip0 * F / norm), "|F_req| reached mu R"
