"""Reset maps: what happens to the state and the mode at an event.

stick      SLIDING -> ROLLING when the slip reaches zero and the required friction
           |F_req| <= mu R. The guard fires at |u| = STICK_SLIP; the zero of |u| is then
           extrapolated (|u| is linear in time as it vanishes under Coulomb friction), so
           the switch is located to O(STICK_SLIP^2). Where static friction cannot hold, the
           body slides on in the self-consistent direction (:func:`phasekit.core.zero_slip.sliding_direction`).
slip onset ROLLING -> SLIDING when |F_req| reaches mu R. The friction force is continuous,
           so sliding starts with slip direction -F_req/|F_req|, at |u| = SLIP_ONSET.
lift-off   contact -> FLIGHT: positions and velocities carry over (R = 0, so the friction,
           proportional to R, vanishes and no impulse acts); the gap and its rate start at 0.
touchdown  FLIGHT -> contact or FLIGHT: the impact law (:mod:`phasekit.core.impact`); a rebound
           slower than BOUNCE_STOP ends a bounce train, and so does a ballistic train with more
           than BOUNCE_TAIL rebounds left (:func:`bounce_tail`).
hold       spin friction stops the spin about the normal, rolling resistance the rolling, and
           holds it (Hold, into the modes with it held) while the couple needed is within the
           law's bound, then lets it go (Release).
rest       with dissipation laws: every motion stopped where rolling resistance holds the body
           (:class:`Rest`); the run ends there with status "rest".
The regularised law's "stick" and "slip" only change the mode (the field is the same).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..errors import Status
from .charts import FLIGHT, VECTOR, euler_to_vector
from .fields import HOLD_RATE, REST_SPEED, STICK_SLIP
from .hybrid import Mode, Record, Transition
from .impact import apply_impact, contact_point_of, kinetic_energy_of
from .zero_slip import SLIP_ONSET, creep_entry, project_no_slip, set_slip, zero_slip_start

#: after an impact, a normal rebound velocity below this (units sqrt(g b)) ends the bounce
#: train and contact resumes: e < 1 would otherwise give infinitely many bounces in finite
#: time. Such a hop lasts ~2e-4 and rises ~5e-9 b, still 20 times the unguarded start of a
#: flight (system.GUARD_DELAY), so every flight that is integrated is resolved.
BOUNCE_STOP = 1e-4
#: a bounce train that has become ballistic (its last TAIL_RATIOS ratios of successive flight
#: times within TAIL_SPREAD x (1 - e) of the restitution e, as free flights between Newton
#: impacts give) with more than this many rebounds left before BOUNCE_STOP is resolved at once
#: (see :func:`bounce_tail`). Chosen above the longest train of the published bouncing runs
#: (e <= 0.9: at most ~60 rebounds), so that their numbers stay those of the cut-off alone.
BOUNCE_TAIL = 100
TAIL_RATIOS = 3
TAIL_SPREAD = 0.1
#: ... and only once the rebound speed is below TAIL_SPEED x the cut-off: what resuming contact
#: drops is that rebound momentum, and the state after the train moves by about as much
#: (measured: 0.6 x the rebound speed in Lambda, against the train integrated to a cut-off ten
#: times smaller)
TAIL_SPEED = 10.0
def contact_start(model, t: float, x, *, before: str = "start", creep: bool = False) -> Transition:
    """The contact mode a state starts in: at zero slip, ROLLING where static friction holds
    (exact Coulomb); else SLIDING. A regularised law whose slip is already below 10 eps starts
    in its ROLLING mode only where that matters, i.e. where the law creeps there (``creep``, a
    field of its own) and its slow manifold holds; elsewhere its two modes share one field and the first stick
    event is left to the integration (which keeps runs bit-for-bit those of earlier versions).
    :attr:`Trajectory.stuck` reports such starts either way."""
    law = model.friction
    speed = float(model.function("slip_speed")(x, model.p))
    if law.has_rolling_mode and speed <= STICK_SLIP:
        out = zero_slip_start(model, x)
        if out is None:
            x0 = project_no_slip(model, x)
            if float(model._evaluate("R", x0, Mode.ROLLING)) <= 0.0:
                return Transition(Mode.ROLLING, t, x0)  # no contact mode has R > 0: the callers lift off
            return _no_direction(t, x)
        mode, x, detail = out
        return Transition(mode, t, x, (Record("stick" if mode is Mode.ROLLING else "slip", before, mode.value, x, detail),))
    if creep and speed < STICK_SLIP + 10 * law.eps:
        x_on = creep_entry(model, x)
        if float(model.function("creep_margin")(x_on, model.p)) > 0:
            return Transition(Mode.ROLLING, t, x_on, (Record("stick", before, "rolling", x_on, "slip < 10 eps (regularised)"),))
    return Transition(Mode.SLIDING, t, np.asarray(x, dtype=float))


def _no_direction(t, x) -> Transition:
    return Transition(None, t, x, stop=Status.FAILED, reason=f"at t = {t:.6g}: zero slip, rolling infeasible, "
                                                       "and no self-consistent sliding direction (Painleve-type inconsistency)")


@dataclass(frozen=True)
class Stick:
    """Exact Coulomb: the slip reached STICK_SLIP; extrapolate to zero slip, then roll (or
    slide on in the consistent direction)."""

    def __call__(self, model, event, mode, t, x) -> Transition:
        s2 = float(model.function("slip_speed2")(x, model.p))
        rate = float(model.function("slip_speed2_rate")(x, model.p))
        if rate >= 0:  # the guard was grazed, the slip is not vanishing
            return Transition(mode, t, x, resume=True)
        dt = 2.0 * s2 / (-rate)  # |u| linear in time as it vanishes: |u|^2 ~ (rate/2) * 2 * dt
        x_s = x + dt * model._rhs(x, mode)
        out = zero_slip_start(model, x_s)
        if out is None:
            return _no_direction(t + dt, x_s)
        new, x_new, detail = out
        name = "stick" if new is Mode.ROLLING else "slip"
        return Transition(new, t + dt, x_new, (Record(name, mode.value, new.value, x_new, detail),))


@dataclass(frozen=True)
class SlipOnset:
    """Exact Coulomb: ROLLING reached |F_req| = mu R; slide with slip along -F_req."""

    def __call__(self, model, event, mode, t, x) -> Transition:
        F = np.asarray(model.function(f"Fc_{mode.value}")(x, model.p)).ravel()[:2]
        norm = np.hypot(*F)
        if norm == 0.0:
            out = zero_slip_start(model, x)
            if out is None:
                return _no_direction(t, x)
            new, x_new, detail = out
        else:
            new, x_new, detail = Mode.SLIDING, set_slip(model, x, -SLIP_ONSET * F / norm), "|F_req| reached mu R"
        return Transition(new, t, x_new, (Record("slip", mode.value, new.value, x_new, detail),))


@dataclass(frozen=True)
class SwitchMode:
    """Change the mode only (the regularised law's stick and slip: one field, two modes)."""

    to: Mode
    record_as: str
    detail: str = ""

    def __call__(self, model, event, mode, t, x) -> Transition:
        return Transition(self.to, t, x, (Record(self.record_as, mode.value, self.to.value, x, self.detail),))


@dataclass(frozen=True)
class Creep:
    """A regularised law's slip fell below 10 eps: it creeps (ROLLING, on the law's slow manifold)
    where that attracts fast enough (``creep_margin`` > 0, :mod:`phasekit.core.fields`); otherwise
    the law's own field is not stiff there, or the slip only passes a minimum and grows again:
    stick and slip are logged at once and the sliding segment goes on (the guard fires again only
    once the slip has risen above 10 eps)."""

    def __call__(self, model, event, mode, t, x) -> Transition:
        x_on = creep_entry(model, x)
        if float(model.function("creep_margin")(x_on, model.p)) > 0.0:
            return Transition(Mode.ROLLING, t, x_on, (Record("stick", mode.value, Mode.ROLLING.value, x_on, "slip < 10 eps (regularised)"),))
        stick = Record("stick", mode.value, Mode.ROLLING.value, x, "slip < 10 eps (regularised)")
        slip = Record("slip", Mode.ROLLING.value, Mode.SLIDING.value, x, "no creep here (|F| near mu R, or R small)")
        return Transition(Mode.SLIDING, t, x, (stick, slip), resume=True)


@dataclass(frozen=True)
class Rest:
    """Dissipation laws: the motion's speed sqrt(|w|^2 + |v|^2) fell to REST_SPEED. Extrapolate
    to its zero (it falls linearly under the set-valued laws); if rolling resistance can hold
    the body where it stands (the weight's lever arm about the contact point <= delta), the
    run ends at rest there; otherwise this is a turning point and the motion goes on."""

    def __call__(self, model, event, mode, t, x) -> Transition:
        speed = float(model.function("motion")(x, model.p))
        rate = float(model.function(f"motion_rate_{mode.value}")(x, model.p))
        if rate >= 0:  # grazed: the motion is not stopping
            return Transition(mode, t, x, resume=True)
        dt = speed / -rate
        x_rest = model.chart.at_rest(x + dt * model._rhs(x, mode))
        margin = float(model.function("rest_margin")(x_rest, model.p))
        if margin < -REST_SLACK:
            return Transition(mode, t, x, resume=True)
        detail = f"held still by rolling resistance (lever arm {max(0.0, -margin + _delta(model)):.3g} b)"
        return Transition(mode, t + dt, x_rest, (Record("rest", mode.value, "end", x_rest, detail),), stop=Status.REST,
                          reason=f"at rest at t = {t + dt:.10g}: every motion stopped", carried=True)


#: the rate given to the held part of w (the spin about the normal, or the rolling part) when the
#: law lets it go (units sqrt(g/b)): as for SLIP_ONSET, the regularised couple is stiff while the
#: rate is below SIGN_EPS, which this skips at the price of a 1e-6 jump of that rate (its energy
#: is counted in the budget's at_events)
HOLD_ONSET = 1e-6
#: what each held part is called in the event log
_WORDS = {"pivot": ("pivot", "the spin about the normal", "mu_s R"), "roll": ("roll", "the rolling", "delta R")}


@dataclass(frozen=True)
class BodyLimit:
    """The run reached an end of the body's valid range of theta (an edged body's ``limits``,
    :mod:`phasekit.bodies.edged`: the flat face down, the side touching): it ends there, status
    "stopped", with the limit's reason."""

    reason: str

    def __call__(self, model, event, mode, t, x) -> Transition:
        why = self.reason.format(t=t)
        return Transition(mode, t, x, (Record(event.name, mode.value, "end", x, why),), stop=Status.STOPPED, reason=why)


@dataclass(frozen=True)
class Hold:
    """Spin friction ("pivot": the spin about the normal |w_Z|) or rolling resistance ("roll": the
    rolling part |w_h|): the rate fell to HOLD_RATE. Extrapolate to its zero (it falls linearly
    under the set-valued couple); hold it there (the mode with it held) where the couple that
    holds it is within the law's bound, else it passes through zero and the couple reverses."""

    kind: str

    def __call__(self, model, event, mode, t, x) -> Transition:
        speed = float(model.function(f"{self.kind}_speed")(x, model.p))
        rate = float(model.function(f"{self.kind}_rate_{mode.value}")(x, model.p))
        if rate >= 0:  # grazed: the rate is not vanishing
            return Transition(mode, t, x, resume=True)
        dt = speed / -rate
        x_s = x + dt * model._rhs(x, mode)
        tr = hold(model, Transition(mode, t + dt, x_s), kinds=(self.kind,), level=np.inf)
        if tr.mode is mode:  # the couple cannot hold it: it passes through zero
            return Transition(mode, t, x, resume=True)
        word, what, bound = _WORDS[self.kind]
        rec = Record(f"{word} stick", mode.value, tr.mode.value, x_s, f"{what} stopped: |tau| <= {bound}")
        if float(model.function("motion")(x_s, model.p)) < REST_SPEED:  # it was all that moved
            rest = Rest()(model, event, mode, t, x)
            if rest.stop is not None:
                return replace(rest, records=(rec, *rest.records))
        return replace(tr, records=(rec,), carried=True)


@dataclass(frozen=True)
class Release:
    """A mode with a part of w held: the couple holding it reached the law's bound; that part
    starts to turn against the couple, at the rate HOLD_ONSET."""

    kind: str

    def __call__(self, model, event, mode, t, x) -> Transition:
        tau = np.atleast_1d(np.asarray(model.function(f"{self.kind}_couple_{mode.value}")(x, model.p), dtype=float).ravel())
        free = mode.free
        norm = float(np.linalg.norm(tau))
        push = -HOLD_ONSET * tau / norm if norm > 0 else np.zeros_like(tau)
        x_new = model.chart.with_pivot(x, float(push[0])) if self.kind == "pivot" else model.chart.with_roll(x, push)
        if free is Mode.ROLLING:
            x_new = project_no_slip(model, x_new)
        word, _, bound = _WORDS[self.kind]
        return Transition(free, t, x_new, (Record(f"{word} slip", mode.value, free.value, x_new, f"|tau| reached {bound}"),))


def hold(model, tr: Transition, kinds=("pivot", "roll"), level: float = HOLD_RATE) -> Transition:
    """``tr`` into SLIDING or ROLLING with the spin about the normal (or the rolling) already
    stopped (below ``level``) and holdable by its law goes to the mode with it held instead."""
    if tr.stop is not None or tr.resume or tr.mode not in (Mode.SLIDING, Mode.ROLLING):
        return tr
    for kind in kinds:
        held = tr.mode.held(kind)
        if held not in model.modes or float(model.function(f"{kind}_speed")(tr.x, model.p)) > level:
            continue
        if float(model.function(f"{kind}_margin_{held.value}")(tr.x, model.p)) < 0.0:
            continue
        if tr.mode is Mode.ROLLING and model.friction.has_rolling_mode \
                and float(model.function(f"margin_{held.value}")(tr.x, model.p)) < 0.0:
            continue
        return replace(tr, mode=held, records=tuple(replace(r, mode_after=held.value) if r.mode_after == tr.mode.value
                                                    else r for r in tr.records))
    return tr


@dataclass(frozen=True)
class Held:
    """A reset whose transition passes through :func:`hold` (models with spin friction or rolling
    resistance)."""

    inner: object

    @property
    def uses_log(self) -> bool:
        return getattr(self.inner, "uses_log", False)

    def __call__(self, model, event, mode, t, x, **kw) -> Transition:
        return hold(model, self.inner(model, event, mode, t, x, **kw))


#: a lever arm this far beyond delta is rounding, not a push off the rest state
REST_SLACK = 1e-9


def _delta(model) -> float:
    i = model.body.n_shape + 4
    for d in model.friction.dissipation:
        if d.name == "rolling-resistance":
            return float(model.p[i])
        i += d.n_params
    return 0.0


# -- flight ---------------------------------------------------------------------------------


def flight_state(model, x_contact) -> np.ndarray:
    """Contact state (either chart) at lift-off -> flight state: same k, w, horizontal v; the
    gap and its rate start at zero (the contact point's vertical velocity is zero in contact)."""
    x = np.asarray(x_contact, dtype=float)
    z = x.copy() if model.chart is VECTOR else euler_to_vector(x)
    return np.concatenate([z[0:8], [0.0, 0.0]])


def contact_state(model, xf) -> np.ndarray:
    """Flight state -> contact chart state (the vertical motion is then slaved)."""
    z = np.asarray(xf, dtype=float)[0:8].copy()
    return z if model.chart is VECTOR else model.chart.from_paper(VECTOR.to_paper(z))


def rigid_velocities(model, xf):
    """(k, w, v) with v = (v_x, v_y, v_z), v_z = dDelta/dt + dh/dt, for the impact law."""
    xf = np.asarray(xf, dtype=float)
    vz = xf[9] + float(model.function("Hdot", Mode.FLIGHT)(xf, model.p))
    return xf[0:3].copy(), xf[3:6].copy(), np.array([xf[6], xf[7], vz])


def from_rigid(model, k, w, v, gap: float = 0.0) -> np.ndarray:
    """Inverse of :func:`rigid_velocities` (gap rate = v_z - dh/dt at the new angular velocity)."""
    xf = np.concatenate([k, w, v[:2], [gap, 0.0]])
    xf[9] = v[2] - float(model.function("Hdot", Mode.FLIGHT)(xf, model.p))
    return xf


@dataclass(frozen=True)
class LiftOff:
    """contact -> FLIGHT with the flight state of :func:`flight_state`."""

    def __call__(self, model, event, mode, t, x) -> Transition:
        return Transition(Mode.FLIGHT, t, flight_state(model, x), (Record("lift-off", mode.value, "flight", x),))


def bounce_tail(log, t: float, v_after: float, e: float, stop: float = BOUNCE_STOP, tail: int | None = BOUNCE_TAIL):
    """The tail of the bounce train an impact at ``t`` continues, if it is to be resolved now:
    (ratio, rebounds left, time left), else None.

    A ballistic train (free flights between Newton impacts of restitution ``e``: each rebound
    e times as fast and its flight e times as long) accumulates: infinitely many impacts before
    t + tau_k e / (1 - e). Event-driven contact solvers resolve the accumulation rather than
    integrate it. Here the train must have become ballistic (the last TAIL_RATIOS ratios of
    successive flight times within TAIL_SPREAD x (1 - e) of e: spin and nutation no longer
    shape the flights, as they do while the body hops), its rebound speed ``v_after`` must be
    below TAIL_SPEED x ``stop``, and more than ``tail`` rebounds must be left before it falls
    below ``stop``. Contact then resumes at once with zero normal velocity, as after a rebound
    below ``stop``; what is dropped is the tail's remaining time and its rebound momentum
    (``v_after``). ``log``: the run's records so far (this impact not yet in it)."""
    if tail is None or not stop < v_after <= TAIL_SPEED * stop or not 0.0 < e < 1.0:
        return None
    left = math.log(stop / v_after) / math.log(e)
    if left <= tail:
        return None
    times = [t]
    for r in reversed(log):  # the impacts of this train, back to its lift-off
        if r.name == "impact" and r.mode_after == "flight":
            times.append(r.t)
            if len(times) > TAIL_RATIOS + 1:
                break
        elif r.name != "touchdown":
            break
    if len(times) <= TAIL_RATIOS + 1:
        return None
    tau = np.diff(np.array(times[::-1]))  # flight times between impacts, oldest first
    ratios = tau[1:] / tau[:-1]
    if np.any(np.abs(ratios - e) > TAIL_SPREAD * (1.0 - e)):
        return None
    return float(np.mean(ratios)), left, float(tau[-1] * e / (1.0 - e))


@dataclass(frozen=True)
class Touchdown:
    """The gap closed: apply the impact law with Newton's ``restitution``; fly on if the body
    rebounds faster than ``bounce_stop`` and its train is not resolved (:func:`bounce_tail`),
    else resume contact (and fly at once if contact would need R <= 0)."""

    restitution: float = 0.0
    bounce_stop: float = BOUNCE_STOP
    bounce_tail: int | None = BOUNCE_TAIL
    uses_log = True  # called with the run's records (the train so far)

    def __call__(self, model, event, mode, t, x, log=()) -> Transition:
        k, w, v = rigid_velocities(model, x)
        imp = apply_impact(model.body, k, w, v, e=self.restitution, mu=model.friction.mu)
        x_post = from_rigid(model, k, imp.w, imp.v)
        bounce = imp.v_normal_after > self.bounce_stop
        detail = (f"e={self.restitution:g}, dE={imp.energy_after - imp.energy_before:.3e}"
                  + (", stick" if imp.sticking else "") + (", friction limited" if imp.energy_limited else ""))
        tail = bounce_tail(log, t, imp.v_normal_after, self.restitution, self.bounce_stop, self.bounce_tail) \
            if bounce else None
        if tail is not None:
            bounce = False
            detail += (f", bounce train resolved: geometric tail (ratio {tail[0]:.4g}, {tail[1]:.0f} rebounds, "
                       f"{tail[2]:.3g} time units) summed")
        recs = [Record("touchdown", "flight", "impact", contact_state(model, x)),
                Record("impact", "flight", "flight" if bounce else "contact", contact_state(model, x_post), detail)]
        return _after_impact(model, t, x_post, recs, bounce)


def _after_impact(model, t, x_post, recs, bounce: bool) -> Transition:
    """Fly on from the post-impact flight state ``x_post`` if the body rebounds, else resume
    contact (and fly at once if contact would need R <= 0)."""
    if bounce:
        return Transition(Mode.FLIGHT, t, x_post, tuple(recs))
    start = contact_start(model, t, contact_state(model, x_post), before="contact")
    if start.stop is not None:
        return Transition(None, t, start.x, tuple(recs), stop=start.stop, reason=start.reason)
    if float(model._evaluate("R", start.x, start.mode)) <= 0.0:
        # contact cannot hold (it would need R < 0): the body flies on from rest
        recs.append(Record("lift-off", start.mode.value, "flight", start.x, "R <= 0 after impact"))
        return Transition(Mode.FLIGHT, t, flight_state(model, start.x), tuple(recs))
    return Transition(start.mode, t, start.x, tuple(recs))


def flight_start_state(model, x) -> np.ndarray:
    """A state given to start in flight: a flight state as is, or a contact state lifted off."""
    x = np.asarray(x, dtype=float)
    return x.copy() if x.size == FLIGHT.n_states else flight_state(model, x)


# -- compound bodies ----------------------------------------------------------------------------

#: a transfer's event fires SWITCH_EARLY before the switch between two pieces, so that a segment ends on its own side (the
#: located root can overshoot), and the transfer puts theta SWITCH_NUDGE past it (radians; heyoka takes a step's field from
#: the side it starts on): past the reverse transfer's level too, or a body that turns back within that band would cross
#: the switch with no transfer and integrate a step on the other piece's support function (energy budgets then missed
#: up to 9e-2 of the start; with the nudge past the band they close to 1e-13, docs/physics.md)
SWITCH_EARLY = 1e-9
SWITCH_NUDGE = 2 * SWITCH_EARLY
#: the impacts alternated between the two pieces at most (each stops one piece's approach)
TRANSFER_IMPACTS = 24
#: a piece's contact point moving up slower than this (units sqrt(g b)) has not left the table
TWO_PIECE_TOL = 1e-9
#: the contact passing to and fro this many times within TWO_PIECE_SPAN (units sqrt(b/g)) is a
#: body on both pieces at once (the passages accumulate, as a bounce train's impacts do)
TWO_PIECE_PASSES, TWO_PIECE_SPAN = 6, 1e-3


def _tilt(xf, theta: float) -> np.ndarray:
    """The flight state ``xf`` with its axis at the inclination ``theta`` (same azimuth)."""
    x = np.array(xf, dtype=float)
    s = math.hypot(x[0], x[1])
    x[0:3] = [x[0] / s * math.sin(theta), x[1] / s * math.sin(theta), math.cos(theta)]
    return x


@dataclass(frozen=True)
class Transfer:
    """A compound body's theta reached the switch between two pieces (its ``transfers``,
    :mod:`phasekit.bodies.compound`). In flight the lowest piece changes: the segment is split
    there (G's height and velocity kept, the gap and its rate taken from the new piece). In
    contact the new piece hits the table while the old one touches it: the impact law of
    :class:`Touchdown` at the new piece's contact point (theta just past the switch), then at
    the old one's if it now approaches the table, alternating until neither does; a body left on
    both pieces at once is reported (status "failed"), not integrated."""

    transfer: object  # a bodies.compound.PieceTransfer
    restitution: float = 0.0
    bounce_stop: float = BOUNCE_STOP
    uses_log = True

    def __call__(self, model, event, mode, t, x, log=()) -> Transition:
        tr, body = self.transfer, model.body
        recent = [r for r in log[-4 * TWO_PIECE_PASSES:] if r.name in {p.name for p in body.transfers} and t - r.t < TWO_PIECE_SPAN]
        old = _tilt(x if mode is Mode.FLIGHT else flight_state(model, x), tr.theta - tr.direction * SWITCH_NUDGE)
        k, w, v = rigid_velocities(model, old)  # the old piece's side: its contact sets G's vertical velocity
        k_new = _tilt(old, tr.theta + tr.direction * SWITCH_NUDGE)[0:3]
        if mode is Mode.FLIGHT:
            gap = old[8] + body.height_slope(k[2])[0] - body.height_slope(k_new[2])[0]  # G's height kept
            xf = from_rigid(model, k_new, w, v, gap=gap)
            return Transition(Mode.FLIGHT, t, xf, (Record(f"{tr.to_piece} lowest (in flight)", "flight", "flight", xf),))
        E0, impacts, quiet = kinetic_energy_of(body, k_new, w, v), 0, 0
        for i in range(TRANSFER_IMPACTS):
            imp = apply_impact(body, (k_new, k)[i % 2], w, v, e=self.restitution, mu=model.friction.mu)
            if imp.v_normal_before < -TWO_PIECE_TOL:
                w, v, impacts, quiet = imp.w, imp.v, impacts + 1, 0
            elif (quiet := quiet + 1) == 2:  # neither piece approaches the table
                break
        x_post = from_rigid(model, k_new, w, v)
        vn_new, vn_old = ((v + np.cross(w, contact_point_of(body, kk)))[2] for kk in (k_new, k))
        detail = (f"{impacts} impact(s), e={self.restitution:g}, dE={kinetic_energy_of(body, k_new, w, v) - E0:.3e}, "
                  f"{tr.from_piece} leaves at {vn_old:.3g}")
        recs = [Record(tr.name, mode.value, "impact", contact_state(model, old), f"{tr.from_piece} -> {tr.to_piece}"),
                Record("impact", mode.value, "flight" if vn_new > self.bounce_stop else "contact",
                       contact_state(model, x_post), detail)]
        if quiet < 2 or (vn_old <= TWO_PIECE_TOL or len(recent) >= TWO_PIECE_PASSES) and vn_new <= self.bounce_stop:
            why = (f"the impacts between the {tr.from_piece} and the {tr.to_piece} did not settle" if quiet < 2 else
                   f"the body rests on two pieces at once (the {tr.from_piece} and the {tr.to_piece}): not integrated")
            # resting on two pieces is where the one-point model ends (as a limit does: "stopped"); impacts that
            # do not settle are the integration's failure
            return Transition(None, t, contact_state(model, x_post), tuple(recs),
                              stop=Status.FAILED if quiet < 2 else Status.STOPPED, reason=f"{why} (t = {t:.10g})")
        return _after_impact(model, t, x_post, recs, vn_new > self.bounce_stop)
