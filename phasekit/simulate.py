"""The hybrid simulator: smooth modes, switching only at located events.

One run integrates the current mode with a backend (:mod:`phasekit.backends`) until the end
time or the first guard, applies the switch (:mod:`phasekit.modes`), records an
:class:`~phasekit.result.EventRecord`, and continues:

    sliding <-> rolling (stick, slip)   contact -> flight (lift-off: R = 0, dR/dt < 0)
    flight -> contact or flight (touchdown, then the impact law of :mod:`phasekit.impact`)

``stop_at`` decides how far: the first lift-off ("jump"), the first touchdown
("touchdown"), or the end time ("none": repeated flights and impacts).
"""

from __future__ import annotations

import time

import numpy as np

from .backends import get_backend
from .errors import Status, check_choice, check_finite, check_open_interval, check_positive, check_vector
from .model import STICK_SLIP, Model
from .modes import Mode, after_slip, after_stick, mode_events, zero_slip_start
from .result import EventRecord, SimulationResult

__all__ = ["simulate", "DEFAULT_RTOL", "BACKEND_CHOICES", "STIFF_RATE", "BOUNCE_STOP"]

DEFAULT_RTOL = 1e-9
#: slip speed given to a body that starts sliding from zero slip. The true slip grows from 0
#: like t^2 (the friction is continuous at the onset), and while it is tiny the field is stiff
#: (the slip direction locks at ~mu R/|u|): measured, starting at 4e-10 cost the Taylor method
#: ~51 000 steps per onset, and the cost falls like SLIP_ONSET^(-1/2). Starting at 1e-6 skips
#: that stretch at the price of a 1e-6 perturbation of the velocity of O at each onset.
SLIP_ONSET = 1e-6
#: ``auto`` hands a stuck regularised law to CVODES when its slip relaxation rate mu/eps
#: exceeds this. Measured (prolate a = 1.5, mu = 0.1, literal seeds, t <= 3000): the Taylor
#: method is faster for eps >= 1e-4 (rate 1e3) and runs out of steps at eps = 1e-5.
STIFF_RATE = 2000.0
#: after an impact, a normal rebound velocity below this (units sqrt(g b)) ends the bounce
#: train and contact resumes: e < 1 would otherwise give infinitely many bounces in finite
#: time. Such a hop lasts ~2e-4 and rises ~5e-9 b, still 20 times the unguarded start of a
#: flight (flight.GUARD_DELAY), so every flight that is integrated is resolved.
BOUNCE_STOP = 1e-4
BACKEND_CHOICES = ("auto", "taylor", "cvodes", "cvodes-adams", "idas")


def _engine_name(backend: str, near_stick: bool, model: Model) -> str:
    """``auto``: the Taylor method everywhere except where the field is stiff, i.e. while a
    regularised Coulomb law holds the slip below ~10 eps and relaxes it at mu/eps > STIFF_RATE;
    there CVODES BDF takes over until the slip grows past 100 eps again."""
    if backend != "auto":
        return backend
    stiff = near_stick and model.friction.eps > 0 and model.friction.mu / model.friction.eps > STIFF_RATE
    return "cvodes" if stiff else "taylor"


def _contact_mode(model, x, p):
    """Mode in which a contact state starts: rolling at zero slip if static friction can hold."""
    if Mode.ROLLING in model.modes and float(model.function("slip_speed2")(x, p)) <= STICK_SLIP**2:
        return zero_slip_start(model, x, p, SLIP_ONSET)
    return Mode.SLIDING, x, ""


def simulate(
    model: Model,
    x0,
    t_end: float,
    *,
    t0: float = 0.0,
    rtol: float = DEFAULT_RTOL,
    stop_at: str = "jump",
    restitution: float = 0.0,
    backend: str = "auto",
    t_eval=None,
    track_minima: bool = True,
    rise_theta: float | None = None,
    max_steps: int = 5_000_000,
    max_switches: int = 10_000,
) -> SimulationResult:
    """Integrate the dynamics from ``x0`` (a state of ``model.chart``, in contact).

    Parameters
    ----------
    model : Model
    x0 : array (6,) for the euler chart, (8,) for the vector chart
    t_end : float
        End time (> t0).
    rtol : float in (0, 1)
        Tolerance (heyoka's mixed tolerance for ``taylor``, CVODES reltol for ``cvodes``).
    stop_at : {"jump", "touchdown", "none"}
        Stop at the first lift-off, at the first touchdown (the flight is reported in
        ``result.flights``), or run to t_end through every flight and impact.
    restitution : float in [0, 1]
        Newton's coefficient e of the impact law (``stop_at="none"``).
    backend : {"auto", "taylor", "cvodes", "cvodes-adams", "idas"}
        ``auto`` (default) is heyoka's Taylor method, handing over to CVODES BDF only
        where a regularised Coulomb law has stuck (the one stiff regime).
    t_eval : array or None
        Times at which to return contact states (dense output costs only when asked for).
    track_minima : bool
        Locate every local minimum of R exactly (for R_min and envelope studies).
    rise_theta : float or None
        Stop with status ``completed`` when theta passes this angle in the direction of
        the rise (toward 0 for a prolate body, toward pi/2 for an oblate one).

    Returns
    -------
    SimulationResult
    """
    from .flight import FlightModel, contact_state, fly, from_rigid, rigid_velocities
    from .impact import impact

    x0 = check_vector("state", x0, model.n_states)
    t0 = check_finite("t0", t0)
    t_end = check_finite("t_end", t_end)
    if not t_end > t0:
        raise ValueError(f"`t_end` must be > t0 = {t0!r}, got {t_end!r}.")
    rtol = check_open_interval("rtol", rtol, 0.0, 1.0)
    check_choice("stop_at", stop_at, ("jump", "touchdown", "none"))
    restitution = float(restitution)
    if not 0.0 <= restitution <= 1.0:
        raise ValueError(f"`restitution` must lie in [0, 1], got {restitution!r}.")
    check_choice("backend", backend, BACKEND_CHOICES)
    check_positive("max_steps", max_steps)
    if t_eval is not None:
        t_eval = np.sort(np.asarray(t_eval, dtype=float).ravel())
        if not np.all(np.isfinite(t_eval)):
            raise ValueError("`t_eval` must be finite times.")
    p = model.p.copy()
    if rise_theta is not None:
        rise_theta = check_open_interval("rise_theta", rise_theta, 0.0, np.pi, "(0, pi)")
        # prolate rises toward theta = 0 (cos increasing), oblate toward pi/2 (cos decreasing)
        p[-2] = np.cos(rise_theta)
        p[-1] = 1.0 if model.body.shape_params[0] > 1 else -1.0

    wall0 = time.perf_counter()
    engines: dict[str, object] = {}
    used: list[str] = []
    events: list[EventRecord] = []
    flights: list = []
    minima: list[tuple[float, float]] = []
    ts_all, ys_all = [], []
    n_steps = n_rhs = 0
    t, x = t0, x0.copy()
    status, reason = None, None
    t_jump = x_jump = rdot_jump = None
    near_stick = False

    try:
        mode, x, detail = _contact_mode(model, x, p)
    except RuntimeError as exc:
        mode, status, reason = Mode.SLIDING, Status.FAILED, str(exc)
    else:
        if detail:
            events.append(EventRecord("stick" if mode is Mode.ROLLING else "slip", t, "start", mode.value, x.copy(), detail))
    R_min = float(model.function(f"R_{mode.value}")(x, p))
    pending_flight = status is None and R_min <= 0.0
    if pending_flight:
        t_jump, x_jump = t, x.copy()
        events.append(EventRecord("lift-off", t, mode.value, "flight", x.copy(), "R <= 0 at start"))
        if stop_at == "jump":
            status, reason = Status.JUMPED, "R <= 0 at the start: the state cannot stay in contact"

    resume = False
    while status is None:
        if len(events) >= max_switches:
            status, reason = Status.FAILED, f"more than {max_switches} mode switches by t = {t:.6g} (chattering)"
            break
        if pending_flight:  # ---------------------------------------------------- flight
            pending_flight = False
            fm = FlightModel(model.body, model.friction)
            start, given, x_post = x, False, None
            while True:  # a flight; at touchdown the impact; a rebound starts the next flight
                fl = fly(model, start, t, t_end, rtol=rtol, max_steps=max(max_steps - n_steps, 1), flight_state_given=given)
                flights.append(fl)
                n_steps += fl.n_steps
                if fl.status != "touchdown":
                    break
                t = fl.t_touchdown
                events.append(EventRecord("touchdown", t, "flight", "impact", contact_state(model.chart, fl.x_end)))
                if stop_at == "touchdown" or len(events) >= max_switches:
                    break
                k, w, v = rigid_velocities(fm, fl.x_end)
                imp = impact(model.body, k, w, v, e=restitution, mu=model.friction.mu)
                x_post = from_rigid(fm, k, imp.w, imp.v)
                dE = imp.energy_after - imp.energy_before
                bounce = imp.v_normal_after > BOUNCE_STOP
                events.append(EventRecord("impact", t, "flight", "flight" if bounce else "contact", contact_state(model.chart, x_post),
                                          f"e={restitution:g}, dE={dE:.3e}" + (", stick" if imp.sticking else "")
                                          + (", friction limited" if imp.energy_limited else "")))
                if not bounce:
                    break
                start, given = x_post, True
            if fl.status == "failed":
                status, reason = Status.FAILED, f"flight: {fl.reason}"
                break
            if fl.status == "time":
                t, x, mode, status = t_end, contact_state(model.chart, fl.x_end), Mode.FLIGHT, Status.COMPLETED
                reason = "in flight at t_end"
                break
            if stop_at == "touchdown":
                status, x, mode = Status.TOUCHDOWN, contact_state(model.chart, fl.x_end), Mode.FLIGHT
                break
            if x_post is None:  # the switch budget ran out at a touchdown
                continue
            x = contact_state(model.chart, x_post)
            try:
                mode, x, _ = _contact_mode(model, x, p)
            except RuntimeError as exc:
                status, reason = Status.FAILED, f"at t = {t:.6g}: {exc}"
                break
            if float(model.function(f"R_{mode.value}")(x, p)) <= 0.0:
                # contact cannot hold (it would need R < 0): the body flies on from rest
                events.append(EventRecord("lift-off", t, mode.value, "flight", x.copy(), "R <= 0 after impact"))
                pending_flight = True
            continue

        # ------------------------------------------------------------------------ contact
        name = _engine_name(backend, near_stick, model)
        if name not in engines:
            engines[name] = get_backend(name, model, rtol)
        engine = engines[name]
        if name not in used:
            used.append(name)
        evs = mode_events(model, mode, pointwise=engine.name != "taylor", rise=rise_theta is not None, near_stick=near_stick)
        prop = engine.propagate(
            mode, x, t, t_end, evs, p,
            max_steps=max_steps - n_steps, t_eval=t_eval,
            minima=(f"Rdot_{mode.value}", 1) if track_minima else None, resume=resume,
        )
        resume = False
        n_steps += prop.n_steps
        n_rhs += prop.n_rhs
        if prop.ts is not None:
            ts_all.append(prop.ts)
            ys_all.append(prop.ys)
        if prop.minima:
            Rf = model.function(f"R_{mode.value}")
            minima.extend((tm, float(Rf(xm, p))) for tm, xm in prop.minima)
        t, x = prop.t, prop.x
        if not np.all(np.isfinite(x)):
            status, reason = Status.FAILED, f"non-finite state at t = {t:.6g}"
            break
        R_min = min(R_min, float(model.function(f"R_{mode.value}")(x, p)))
        if prop.outcome == "failed":
            status, reason = Status.FAILED, prop.reason
            break
        if prop.outcome == "time":
            status = Status.COMPLETED
            break
        if prop.event == "lift-off":
            events.append(EventRecord("lift-off", t, mode.value, "flight", x.copy()))
            R_min = min(R_min, 0.0)
            if t_jump is None:
                t_jump, x_jump = t, x.copy()
                rdot_jump = float(model.function(f"Rdot_{mode.value}")(x, p))
            if stop_at == "jump":
                status = Status.JUMPED
                break
            pending_flight = True
        elif prop.event == "rise-complete":
            status, reason = Status.COMPLETED, f"rise complete: theta passed {rise_theta:.6g}"
            break
        elif prop.event == "stick":
            if Mode.ROLLING not in model.modes:
                # regularised law: the slip fell below ~10 eps; record it, no mode change
                events.append(EventRecord("stick", t, mode.value, mode.value, x.copy(), "slip < 10 eps (regularised)"))
                near_stick = True
                continue
            try:
                out = after_stick(model, x, p, SLIP_ONSET)
            except RuntimeError as exc:
                status, reason = Status.FAILED, f"at t = {t:.6g}: {exc}"
                break
            if out is None:  # the guard was grazed, the slip is not vanishing
                resume = True
                continue
            dt, new_mode, x, detail = out
            t = t + dt
            events.append(EventRecord("stick" if new_mode is Mode.ROLLING else "slip", t, mode.value, new_mode.value, x.copy(), detail))
            mode = new_mode
        elif prop.event == "unstick":
            events.append(EventRecord("slip", t, mode.value, mode.value, x.copy(), "slip > 100 eps (regularised)"))
            near_stick = False
        elif prop.event == "slip":
            try:
                new_mode, x, detail = after_slip(model, x, p, SLIP_ONSET)
            except RuntimeError as exc:
                status, reason = Status.FAILED, f"at t = {t:.6g}: {exc}"
                break
            events.append(EventRecord("slip", t, mode.value, new_mode.value, x.copy(), detail))
            mode = new_mode
        else:  # pragma: no cover - a guard without a handler is a programming error
            raise RuntimeError(f"unhandled event {prop.event!r}")

    if status is Status.JUMPED:
        R_min = 0.0  # R reached zero at the located lift-off (to the event tolerance)
    ts = ys = None
    if ts_all:
        ts, ys = np.concatenate(ts_all), np.vstack(ys_all)
        ts, idx = np.unique(ts, return_index=True)
        ys = ys[idx]
    extra = {}
    if flights:
        extra["flight"] = flights[0].to_dict()
        extra["n_flights"] = len(flights)
    return SimulationResult(
        status=status,
        chart=model.chart,
        backend="+".join(used) or backend,
        rtol=rtol,
        t0=t0,
        t=t,
        x=x,
        mode=mode.value,
        t_jump=t_jump,
        x_jump=x_jump,
        Rdot_jump=rdot_jump,
        R_min=R_min,
        reason=reason,
        events=tuple(events),
        n_steps=n_steps,
        n_rhs=n_rhs,
        wall_s=time.perf_counter() - wall0,
        ts=ts,
        ys=ys,
        minima=np.array(minima) if track_minima else None,
        extra=extra,
        flights=tuple(flights),
    )
