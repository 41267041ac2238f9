"""phasekit's hybrid system, declared in one place: its modes, events and resets.

The table of events (guard, modes, friction laws, reset or outcome) is generated from
:func:`declare` when the documentation is built: docs/architecture.md, "Modes, events and
resets".

Flows: SLIDING (``rhs_sliding``), ROLLING (``rhs_rolling``; for a regularised law the same
field as sliding, or, where that is stiff, its creep on the slow manifold of the slip), FLIGHT
(``rhs_flight``, always the Taylor method). Contact flows record the minima of R, flight the maximum of the gap.
A new event is one more :class:`phasekit.core.hybrid.Event` passed to :func:`phasekit.simulate`.
"""

from __future__ import annotations

import warnings

import numpy as np

from .._runtime.validate import check_choice, check_range
from ..errors import ParameterError, Status
from .cone_edge import EDGE_STICK
from .face import FaceLanding, face_start_transition
from .fields import STICK_SLIP
from .hybrid import Event, Flow, HybridSystem, Mode, Record, Transition
from .resets import (
    BOUNCE_STOP,
    BOUNCE_TAIL,
    SWITCH_EARLY,
    BodyLimit,
    Creep,
    Held,
    Hold,
    LiftOff,
    Release,
    Rest,
    SlipOnset,
    Stick,
    SwitchMode,
    Touchdown,
    Transfer,
    contact_start,
    flight_start_state,
    hold,
)
from .settle import TURN, Turn, rolls_periodically_here
from .zero_slip import EdgeOnset, EdgeStick, OnEdge

#: how far a run goes: the first lift-off, the first touchdown, or the end time; "rest" goes
#: through flights as "none" does (with dissipation laws every run ends when the body rests)
STOP_AT = ("jump", "touchdown", "none", "rest")
#: "auto" hands a regularised law's modes with a part of w held (spin friction, rolling resistance:
#: the law's own field there) to CVODES when its slip relaxation rate mu/eps exceeds this. Measured
#: (prolate a = 1.5, mu = 0.1, literal seeds, t <= 3000): the Taylor method is faster for eps >= 1e-4
#: (rate 1e3) and runs out of steps at eps = 1e-5. Its ROLLING mode creeps instead (fields, resets.Creep).
STIFF_RATE = 2000.0
#: At lift-off Delta = dDelta/dt = 0 and d2Delta/dt2 = -R vanish only to rounding and the
#: event tolerance (~1e-16, ~1e-12), so the gap's Taylor polynomial can have spurious roots
#: before its t^3 growth dominates (t ~ 1e-5). The touchdown guard is armed after this long;
#: a flight whose gap has not opened by then is a graze and touches down there.
GUARD_DELAY = 1e-5



def declare(model, *, stop_at: str = "jump", restitution: float = 0.0, events=(),
            bounce: tuple[float, int | None] = (BOUNCE_STOP, BOUNCE_TAIL), periodic: bool = False) -> HybridSystem:
    """The modes, events and resets of ``model``'s law, with the run's stop rule, the end of a
    bounce train (``bounce``: the rebound-speed cut-off and the geometric tail resolved, see
    :class:`phasekit.core.resets.Touchdown`) and the user's ``events`` appended. ``periodic``: watch
    the turns of theta while rolling, where rolling is periodic (:func:`phasekit.core.settle.rolls_periodically`)."""
    check_choice("stop_at", stop_at, STOP_AT)
    restitution = check_range("restitution", restitution, 0.0, 1.0, closed="lr")
    law = model.friction
    stiff = law.can_stick and not law.has_rolling_mode and law.mu / law.eps > STIFF_RATE
    creep = law.creeps
    held = [m for m in model.modes if m.free is not m]  # spin friction, rolling resistance hold parts of w
    hold = Held if held else _same
    flows = (
        Flow(Mode.SLIDING, "rhs_sliding", monitor=("Rdot", +1)),
        # a regularised law's: its creep, or its own field (CVODES where stiff: the creep turned off)
        Flow(Mode.ROLLING, "rhs_rolling", monitor=("Rdot", +1), stiff=stiff and not creep),
        Flow(Mode.FLIGHT, "rhs_flight", monitor=("gap_rate", -1), engine="taylor", contact=False),
    ) + tuple(Flow(m, f"rhs_{m.value}", monitor=("Rdot", +1), stiff=stiff and m.free is Mode.ROLLING) for m in held)
    edge = Mode.EDGE in model.modes  # exact Coulomb: sliding on the cone's edge (cone_edge)
    if edge:
        flows += (Flow(Mode.EDGE, "rhs_edge", monitor=("Rdot", +1)), Flow(Mode.OFF_EDGE, "rhs_off_edge", monitor=("Rdot", +1)))
    jump_ends = stop_at == "jump"
    contact = frozenset(f.mode for f in flows if f.contact)
    sliding = {m for m in contact if m.free is Mode.SLIDING or m is Mode.OFF_EDGE}
    rolling = {m for m in contact if m.free is Mode.ROLLING}
    evs = [Event("R", name="lift-off", direction=-1, modes=contact, rate="Rdot", stop=Status.JUMPED,
                 reset=None if jump_ends else LiftOff())]
    if law.can_stick:
        evs += _stick_events(law, sliding, rolling, hold, creep, edge)
    for kind in ("pivot", "roll"):  # a set-valued law stops its part of w, holds it, lets it go (resets)
        kept = [m for m in held if m in (Mode.SLIDING.held(kind), Mode.ROLLING.held(kind))]
        if kept:
            evs.append(Event(f"{kind}_guard", name=f"{kind} stick", direction=-1, modes={Mode.SLIDING, Mode.ROLLING},
                             reset=Hold(kind)))
            if edge:
                evs += [Event(f"{kind}_guard", name=f"{kind} stick", direction=-1, modes={m},
                              reset=OnEdge(Hold(kind), like)) for m, like in ((Mode.EDGE, Mode.ROLLING), (Mode.OFF_EDGE, Mode.SLIDING))]
            evs += [Event(f"{kind}_margin_{m.value}", name=f"{kind} slip", direction=-1, modes={m}, reset=Release(kind))
                    for m in kept]
    if periodic and rolls_periodically_here(model):  # a run with a settle rule ends one period into a roll
        evs.append(Event("Lambda", 0.0, direction=-1, name=TURN, modes={Mode.ROLLING}, reset=Turn()))
    if law.dissipation:  # the body comes to rest in finite time (see resets.Rest)
        evs.append(Event("rest_guard", name="rest", direction=-1, modes=contact, reset=Rest(), stop=Status.REST))
    evs.append(Event("gap", name="touchdown", direction=-1, modes={Mode.FLIGHT}, arm_after=GUARD_DELAY,
                     stop=Status.TOUCHDOWN,
                     reset=None if stop_at == "touchdown" else hold(Touchdown(restitution, *bounce))))
    evs += _body_events(model.body, contact, hold, restitution, bounce[0], face=stop_at == "rest")
    for ev in events:
        if not isinstance(ev, Event):
            raise ParameterError("events", "must be phasekit Event objects, e.g. pk.Event('theta', 0.4)", ev)
        evs.append(ev)
    return HybridSystem(flows, tuple(evs), _initial(stop_at, creep, bool(held)))


def _stick_events(law, sliding, rolling, hold, creep: bool, edge: bool) -> list[Event]:
    """Stick and slip: exact Coulomb's (with its EDGE mode), or a regularised law's (its creep)."""
    to_roll = hold(Stick() if law.has_rolling_mode else Creep() if creep else
                   SwitchMode(Mode.ROLLING, "stick", "slip < 10 eps (regularised)"))
    # the Taylor method watches |u| itself; pointwise integrators the dip of |u|^2 (see model)
    evs = [Event("stick_guard", name="stick", direction=-1, modes=sliding, reset=to_roll),
           Event("stick_guard_sq", name="stick", direction=-1, modes=sliding, reset=to_roll, rate="slip_speed2_rate")]
    if law.has_rolling_mode:
        evs += [Event("margin_rolling" if m is Mode.ROLLING else f"margin_{m.value}", name="slip", direction=-1,
                      modes={m}, reset=hold(EdgeOnset(SlipOnset()) if m is Mode.ROLLING and edge else SlipOnset()))
                for m in sorted(rolling, key=list(Mode).index)]
        return evs + (_edge_events(hold) if edge else [])
    to_slide = hold(SwitchMode(Mode.SLIDING, "slip", "slip > 100 eps (regularised)"))
    evs.append(Event("unstick_guard", name="slip", direction=-1, modes=rolling, reset=to_slide))
    if creep:  # the creep holds while the law's slow manifold attracts fast (fields._build_creep)
        evs.append(Event("creep_margin", name="slip", direction=-1, modes={Mode.ROLLING}, reset=to_slide))
    return evs


def _edge_events(hold) -> list[Event]:
    """In and out of EDGE (:mod:`phasekit.core.cone_edge`): the slip along e* vanishes (roll), it grows
    past EDGE_OUT (slide, OFF_EDGE); that slip falls below EDGE_IN near the cone's edge (onto the edge).
    SLIDING does not watch the return: its integrator stays that of the runs that never reach the edge
    (an event more changes the last bits of heyoka's Taylor coefficients, measured 1e-15)."""
    # the slip along e* falls through zero linearly (at the rate lambda < 0); it is exactly 0 on entry from
    # ROLLING, so the guard fires a little past it (-EDGE_STICK)
    return [Event("edge_stick", -EDGE_STICK, name="stick", direction=-1, modes={Mode.EDGE}, reset=hold(EdgeStick())),
            Event("edge_out", name="edge out", direction=+1, modes={Mode.EDGE},
                  reset=SwitchMode(Mode.OFF_EDGE, "edge out", "the slip grew past EDGE_OUT")),
            Event("edge_in", name="edge in", direction=-1, modes={Mode.OFF_EDGE},
                  reset=SwitchMode(Mode.EDGE, "edge in", "slip below EDGE_IN, |F_req| near mu R"))]


def _body_events(body, contact, hold, restitution: float, bounce_stop: float, face: bool = False) -> list[Event]:
    """The events the body declares (its contract, phasekit.bodies.Body): a run stops at each of
    its ``limits`` (an edged body's model ends there), or with ``face`` lands on a flat face there
    (:class:`phasekit.core.face.FaceLanding`, into Mode.FACE), and the contact passes between its pieces at
    each of its ``transfers`` (a compound body), watched in every mode so that no step crosses the
    switch."""
    evs = [Event("theta", lim.theta, direction=lim.direction, name=lim.name,
                 reset=FaceLanding() if face and lim.face is not None else BodyLimit(lim.reason)) for lim in body.limits]
    for tr in body.transfers:
        level = tr.theta - tr.direction * SWITCH_EARLY
        evs += [Event("theta", level, direction=tr.direction, name=tr.name, modes=contact,
                      reset=hold(Transfer(tr, restitution, bounce_stop))),
                Event("theta", level, direction=tr.direction, name=f"{tr.to_piece} lowest (in flight)",
                      modes={Mode.FLIGHT}, reset=Transfer(tr))]
    return evs


def _same(reset):
    return reset


def _initial(stop_at: str, creep: bool, held: bool = False):
    def initial(model, t, x, mode=None):
        """Start in contact (the mode from the slip), or in flight when asked; a contact
        state that would need R <= 0 lifts off at once."""
        if mode is Mode.FLIGHT:
            return _flight_start(model, t, x)
        if mode is Mode.FACE:  # lying flat (simulate's mode="face"): the face mode
            return face_start_transition(model, t, x)
        speed, R = np.asarray(model.function("start_probe")(x, model.p)).ravel()
        if speed > STICK_SLIP + 10 * model.friction.eps and R > 0.0:  # the common case, in one call
            tr = Transition(Mode.SLIDING, t, x)
            return hold(model, tr) if held else tr
        start = contact_start(model, t, x, creep=creep)
        if held:
            start = hold(model, start)
        if start.stop is not None or float(model._evaluate("R", start.x, start.mode)) > 0.0:
            return start
        warnings.warn("the start leaves the table at once: its normal reaction R <= 0 there, so it cannot stay in "
                      "contact (a body released so lifts off at t0; a state on one of its steady branches stays)",
                      stacklevel=2)
        rec = start.records + (Record("lift-off", start.mode.value, "flight", start.x, "R <= 0 at start"),)
        if stop_at == "jump":
            return Transition(start.mode, t, start.x, rec, stop=Status.JUMPED,
                              reason="R <= 0 at the start: the state cannot stay in contact")
        return Transition(Mode.FLIGHT, t, flight_start_state(model, start.x), rec)

    return initial


def _flight_start(model, t, x):
    return Transition(Mode.FLIGHT, t, flight_start_state(model, x))


def watched(system: HybridSystem, mode: Mode, engine) -> tuple[Event, ...]:
    """The events ``mode`` watches with this engine (:class:`phasekit.core.engines.Engine`): the
    stick guard has a form for engines that locate roots of each step's polynomial and a smooth
    squared one, with a rate, for pointwise engines."""
    skip = "stick_guard" if engine.pointwise else "stick_guard_sq"
    return tuple(e for e in system.events_of(mode) if e.on != skip)
