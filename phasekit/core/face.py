"""A body on its face: the face-contact mode (:attr:`Mode.FACE <phasekit.core.Mode>`).

An edged body (a disk, a coin, a cone on its rim) whose flat face comes down reaches the limit event
"face down" (its ``limits``, :class:`phasekit.bodies.body.Limit`, with the face's radius and inner
ratio in ``face``). With ``stop_at="rest"`` (the run goes on until the body rests) it goes on, as a
hybrid system does (with the other stop rules the run still ends there, status "stopped"):

event "face down" -> reset :class:`FaceLanding` -> mode FACE (flow :func:`face_motion`) -> event "at rest"

Reset (plastic landing). The table stops the face: the normal velocity of G, v_z, is lost (the total
normal impulse is M |v_z|), the tilt rates go to zero (the axis is taken vertical, k = +-e_Z), the
vertical angular momentum about G is kept, L_Z = C w (so w = L_Z / C), and the horizontal velocity of
G is kept. Friction acts during the impulse too, but its impulse is at most mu M |v_z| (Coulomb on the
total normal impulse), which bounds the change of v that keeping it neglects; the record's detail gives
both numbers. The landing dissipates (v_z^2/2, the tilt's rotational energy, w.L/2 - L_Z^2/(2C) >= 0
since C >= the moment about the vertical before, and the drop of G from h(theta_f) to h(0)).

Flow. Lying flat, the state is (v_1, v_2, w) (the horizontal velocity of G, the spin about the
vertical), with the position of G and the spin angle carried along: the face state is
``(v_1, v_2, w, X_1, X_2, phi, work)`` (:data:`FACE_NAMES`), v in the horizontal axes of the model's
chart at the landing. Coulomb friction with uniform pressure over the face (radius a, or the annulus
beta a < rho < a, the full disk minus the inner one at the same pressure), normal force M g, gives the
force and the couple about the normal: by the closed forms of
:func:`phasekit.friction.patch.patch_resultant` (``law="exact"``, the default, ~1e-15), or by the smooth
rational approximant of :func:`phasekit.friction.patch.patch_friction` (``law="rational"``, relative error
<= 7e-6 on a full disk; the annulus' difference amplifies it near s = 1: with beta = 0.9 its terminal
ratio is 0.930 against 0.951, measured):

    M dv/dt = F(v, w),    C dw/dt = M_z(v, w),    d(work)/dt = F.v + M_z w.

Regularised laws are taken at their Coulomb limit on the face (the patch law's own floor, 1e-9, is
its only regularisation); a viscous law (its force independent of R) as viscous traction over the face,
-(mu/area) u, so F = -mu v and M_z = -mu w a^2 (1 + beta^2)/2 (``law="viscous"``: v and w then decay
exponentially, and the rest below is a cut-off); dissipation laws do not act on the face.

Event "at rest". When the speed sqrt(|v|^2 + a^2 w^2) falls to REST_SPEED (1e-7) it is extrapolated
to zero along its rate (both v and w fall at finite rates under Coulomb friction), as
:class:`phasekit.core.resets.Rest` does; the stop times of the sliding and of the spin are each
extrapolated too (``t_stop_slide``, ``t_stop_spin``). The run ends with status "rest".

The closed problem: ``simulate(model, vertical_spin_start(0.0, w0, v0=v0), t_end, mode="face")``
(:func:`phasekit.core.vertical_spin_start`: sliding at v0, spinning at w0; theta0 = pi for the other face
of a thin disk); the theory
it is checked against is :mod:`phasekit.theory.face_down` (terminal ratio, stop time, a scipy run).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import casadi as ca
import numpy as np
from scipy.integrate import DOP853
from scipy.optimize import brentq

from ..errors import ParameterError, Status
from ..friction.laws import Viscous
from ..friction.patch import patch_friction, patch_resultant
from ..theory.face_down import RATIO_MAX
from .fields import REST_SPEED
from .hybrid import Mode, Record, Transition
from .resets import flight_state, rigid_velocities

#: the face state: horizontal velocity of G (chart axes at the landing), spin about the vertical,
#: position of G from the landing, spin angle turned, work of friction since the landing
FACE_NAMES = ("v_1", "v_2", "w", "X_1", "X_2", "phi", "work")
#: the patch law on the face: Coulomb's closed forms (default) or its smooth rational approximant; or
#: viscous traction (a viscous law, independent of R)
FACE_LAWS = ("exact", "rational", "viscous")


@dataclass(frozen=True)
class FaceContact:
    """What the face mode needs of the body and the law: the face (radius ``a``, inner ratio ``inner``),
    the friction coefficient ``mu``, the moment ``C`` about the normal, the height ``h0`` of G lying
    flat, the face-down angle ``theta`` the model keeps as flat, the axis' azimuth ``psi`` and the patch
    law ``law`` (:data:`FACE_LAWS`)."""

    a: float
    inner: float
    mu: float
    C: float
    h0: float
    theta: float
    psi: float = 0.0
    law: str = "exact"

    def __post_init__(self):
        if self.law not in FACE_LAWS:
            raise ParameterError("law", f"must be one of {', '.join(FACE_LAWS)}", self.law)
        if not 0.0 <= self.inner <= RATIO_MAX:
            raise ParameterError("inner", f"must be in [0, {RATIO_MAX:g}]", self.inner)

    def energy(self, Y) -> np.ndarray:
        """Mechanical energy of face states (rows of :data:`FACE_NAMES`), units M g b."""
        Y = np.atleast_2d(Y)
        return 0.5 * (Y[:, 0] ** 2 + Y[:, 1] ** 2) + 0.5 * self.C * Y[:, 2] ** 2 + self.h0


def face_contact(model, theta: float, psi: float = 0.0) -> FaceContact:
    """The :class:`FaceContact` of ``model``'s body at the face whose limit is nearest ``theta``.

    Raises
    ------
    ParameterError
        If the body has no face among its limits.
    """
    faces = [lim for lim in model.body.limits if getattr(lim, "face", None) is not None]
    if not faces:
        raise ParameterError("mode", "'face' needs a body with a flat face (a Disk, or a Cone on its rim)", "face")
    lim = min(faces, key=lambda q: abs(q.theta - theta))
    a, inner = lim.face
    c = 1.0 if lim.theta < math.pi / 2 else -1.0
    return FaceContact(float(a), float(inner), float(model.friction.mu), float(model.body.C),
                       float(model.body.height_slope(c)[0]), float(lim.theta), float(psi),
                       "viscous" if isinstance(model.friction, Viscous) else "exact")  # Coulomb's, over a patch too


@functools.lru_cache(maxsize=16)
def _rational_field(a: float, inner: float):
    """The CasADi function (y, [mu, C]) -> (dy/dt, F, M_z) of the face state with the rational
    approximant of :func:`phasekit.friction.patch.patch_friction`."""
    y, p = ca.SX.sym("y", len(FACE_NAMES)), ca.SX.sym("p", 2)
    v, w, mu, C = y[0:2], y[2], p[0], p[1]
    if inner == 0.0:
        F, M = patch_friction(v, w, mu, 1.0, a)
    else:  # uniform pressure over the annulus: the full disk minus the inner one, at the same pressure
        share = 1.0 / (1.0 - inner * inner)
        F1, M1 = patch_friction(v, w, mu, share, a)
        F2, M2 = patch_friction(v, w, mu, share * inner * inner, inner * a)
        F, M = F1 - F2, M1 - M2
    ydot = ca.vertcat(F, M / C, v, w, ca.dot(F, v) + M * w)
    return ca.Function("face_field", [y, p], [ydot, F, M])


def _exact_part(v, w: float, load: float, a: float):
    """(F, M_z) of uniform pressure over a disk of radius ``a`` bearing ``load`` (units mu M g), from the
    closed forms of :func:`phasekit.friction.patch.patch_resultant`."""
    speed, spin = math.hypot(v[0], v[1]), a * abs(w)
    if speed == 0.0 and spin == 0.0:
        return np.zeros(2), 0.0
    f, g = (1.0, 0.0) if spin == 0.0 else patch_resultant(speed / spin)
    F = -load * f * np.asarray(v[0:2], dtype=float) / speed if speed > 0 else np.zeros(2)
    return F, -load * a * g * math.copysign(1.0, w)


def face_field(cc: "FaceContact"):
    """y -> dy/dt of the face state (module notes): F, M_z by ``cc.law`` ("exact": the closed forms,
    ~1e-15; "rational": the smooth approximant, relative error <= 7e-6)."""
    if cc.law == "rational":
        f, p = _rational_field(cc.a, cc.inner), [cc.mu, cc.C]
        return lambda y: np.asarray(f(y, p)[0], dtype=float).ravel()
    if cc.law == "viscous":  # traction -(mu/area) u: F = -mu v, M_z = -mu w <rho^2> = -mu w a^2 (1 + beta^2)/2
        k = cc.mu * cc.a * cc.a * (1 + cc.inner * cc.inner) / 2
        return lambda y: np.array([-cc.mu * y[0], -cc.mu * y[1], -k * y[2] / cc.C, y[0], y[1], y[2],
                                   -cc.mu * (y[0] ** 2 + y[1] ** 2) - k * y[2] ** 2])
    share = 1.0 / (1.0 - cc.inner * cc.inner)

    def field(y):
        F, M = _exact_part(y, y[2], cc.mu * share, cc.a)
        if cc.inner > 0.0:  # the annulus: the full disk minus the inner one, at the same pressure
            F2, M2 = _exact_part(y, y[2], cc.mu * share * cc.inner * cc.inner, cc.inner * cc.a)
            F, M = F - F2, M - M2
        return np.array([F[0], F[1], M / cc.C, y[0], y[1], y[2], F[0] * y[0] + F[1] * y[1] + M * y[2]])

    return field


@dataclass(frozen=True, eq=False)
class FacePhase:
    """The face phase of a run: the body lying flat, sliding and spinning until it rests.

    Attributes
    ----------
    contact : FaceContact
        The face, the law and the body's numbers.
    t0, t1 : float
        Its start (the landing) and end (rest, t_end, or a failure).
    y0, y1 : numpy.ndarray
        Face states (:data:`FACE_NAMES`) at its start and end.
    status : Status
        ``rest``, ``completed`` (t_end reached still moving) or ``failed`` (a budget ran out).
    reason : str
        What ended it.
    t_stop_slide, t_stop_spin : float or None
        When the sliding and the spin stopped (each extrapolated from the rest event at its own
        deceleration); None if it did not rest.
    ratio_end : float or None
        v/(a w) at the rest event: the terminal ratio (:func:`phasekit.theory.face_down.terminal_ratio`).
    energy_start, energy_end : float
        Mechanical energy lying flat (units M g b).
    residual_max : float
        max |E(t) - E(t0) - work(t)| over the steps: the balance of the face's friction work.
    n_steps, n_rhs : int
        Steps and field evaluations.
    pieces : tuple
        Dense output: (t_a, t_b, callable t -> states) per step.

    Examples
    --------
    >>> import phasekit as pk
    >>> disk = pk.Disk(0.0)
    >>> traj = pk.simulate(pk.Model(disk, pk.Coulomb(0.3)), pk.core.vertical_spin_start(0.0, 3.0, v0=1.0), 50.0,
    ...                    mode="face")
    >>> traj.face.status.value, round(traj.face.ratio_end, 4)
    ('rest', 0.653)
    """

    contact: FaceContact
    t0: float
    t1: float
    y0: np.ndarray
    y1: np.ndarray
    status: Status
    reason: str
    t_stop_slide: float | None
    t_stop_spin: float | None
    ratio_end: float | None
    energy_start: float
    energy_end: float
    residual_max: float
    n_steps: int
    n_rhs: int
    pieces: tuple = ()

    @property
    def dissipated(self) -> float:
        """The energy the face's friction took out (>= 0): minus its work, integrated along the flow (the
        last stretch, extrapolated to rest, takes what motion was left)."""
        return -float(self.y1[6])

    def states(self, ts) -> np.ndarray:
        """Face states at times inside [t0, t1] (clipped into it), one row per time."""
        ts = np.clip(np.atleast_1d(np.asarray(ts, dtype=float)), self.t0, self.t1)
        out = np.empty((ts.size, len(FACE_NAMES)))
        if not self.pieces:
            out[:] = self.y0 if self.t1 == self.t0 else np.nan
            return out
        starts = np.array([p[0] for p in self.pieces])
        idx = np.clip(np.searchsorted(starts, ts, side="right") - 1, 0, len(self.pieces) - 1)
        for k in np.unique(idx):
            sel = idx == k
            out[sel] = np.reshape(self.pieces[k][2](ts[sel]), (len(FACE_NAMES), -1)).T
        out[ts == self.t1] = self.y1
        return out

    def paper_states(self, Y) -> np.ndarray:
        """Face states -> the paper's (U, V, Omega, Lambda, theta, n): lying at the face-down angle with the
        axis' azimuth of the landing, w vertical (Omega = w, n = w cos theta), Lambda = 0."""
        Y = np.atleast_2d(Y)
        c, s = math.cos(self.contact.psi), math.sin(self.contact.psi)
        U, V = c * Y[:, 0] + s * Y[:, 1], -s * Y[:, 0] + c * Y[:, 1]
        th = np.full(len(Y), self.contact.theta)
        return np.column_stack([U, V, Y[:, 2], np.zeros(len(Y)), th, Y[:, 2] * math.cos(self.contact.theta)])

    def chart_states(self, model, Y) -> np.ndarray:
        """Face states -> states of ``model``'s chart (:meth:`paper_states`, turned by the azimuth in the
        vector chart)."""
        P = self.paper_states(Y)
        X = np.array([model.chart.from_paper(y) for y in P])
        if X.shape[1] == 8 and self.contact.psi != 0.0:
            c, s = math.cos(self.contact.psi), math.sin(self.contact.psi)
            turn = np.array([[c, -s], [s, c]])
            for i in (0, 3, 6):
                X[:, i:i + 2] = X[:, i:i + 2] @ turn.T
        return X

    def observables(self, Y) -> dict:
        """The columns of a sampled table other than the paper's state, lying flat (R = M g, gap 0)."""
        Y = np.atleast_2d(Y)
        cc, n = self.contact, len(Y)
        L_Z = cc.C * Y[:, 2]
        return {"R": np.ones(n), "energy": cc.energy(Y), "jellett": L_Z * cc.h0, "slip": np.hypot(Y[:, 0], Y[:, 1]),
                "L_Z": L_Z, "h": np.full(n, cc.h0), "gap": np.zeros(n)}

    def to_dict(self) -> dict:
        return {"status": str(self.status), "reason": self.reason, "t_start": self.t0, "t_end": self.t1,
                "t_stop_slide": self.t_stop_slide, "t_stop_spin": self.t_stop_spin, "ratio_end": self.ratio_end,
                "start": dict(zip(FACE_NAMES[:3], map(float, self.y0[:3]))), "radius": self.contact.a,
                "inner_ratio": self.contact.inner, "energy_start": self.energy_start, "energy_end": self.energy_end,
                "dissipated": self.dissipated, "residual_max": self.residual_max, "n_steps": self.n_steps}

    def __repr__(self) -> str:
        return (f"FacePhase(status={self.status.value}, t0={self.t0:.8g}, t1={self.t1:.8g}, "
                f"ratio_end={self.ratio_end}, n_steps={self.n_steps})")


def _speed(cc: FaceContact, y) -> float:
    return math.sqrt(y[0] * y[0] + y[1] * y[1] + (cc.a * y[2]) ** 2)


class _Stepper:
    """DOP853 over the face field, one step at a time, with the steps' dense output kept."""

    def __init__(self, cc: FaceContact, t0, y0, t_end, rtol, atol):
        self.field = face_field(cc)
        scale = max(_speed(cc, y0), 1e-3)
        tol = np.full(len(FACE_NAMES), atol * scale)
        tol[3:6] = atol * max(1.0, scale)
        tol[6] = atol * max(1.0, scale * scale)
        self.solver = DOP853(lambda t, y: self.field(y), t0, np.array(y0, dtype=float), t_end, rtol=rtol, atol=tol)
        self.pieces, self.ts, self.ys = [], [float(t0)], [np.array(y0, dtype=float)]

    def step(self) -> str | None:
        msg = self.solver.step()
        if self.solver.status == "failed":
            return msg or "the step size fell below its bound"
        self.pieces.append((self.solver.t_old, self.solver.t, self.solver.dense_output()))
        self.ts.append(self.solver.t)
        self.ys.append(self.solver.y.copy())
        return None


def face_motion(cc: FaceContact, y0, t0: float, t_end: float, *, rtol: float = 1e-9, atol: float | None = None,
                budget=None) -> FacePhase:
    """Integrate the face mode from the face state ``y0`` at ``t0`` until rest, ``t_end`` or a budget.

    Parameters
    ----------
    cc : FaceContact
        The face, the law and the body's numbers.
    y0 : array of 3 or 7 floats
        (v_1, v_2, w), optionally followed by the position, spin angle and work (default 0).
    t0, t_end : float
        The span.
    rtol, atol : float
        The run's tolerances (atol default rtol / 100), scaled by the start's speed.
    budget : phasekit.core.engines.Budget, optional
        The run's steps left and wall-clock deadline.

    Returns
    -------
    FacePhase
        The phase, its status ("rest", "completed", "failed"), stop times and energy balance.

    Examples
    --------
    >>> from phasekit.core.face import FaceContact, face_motion
    >>> ph = face_motion(FaceContact(1.0, 0.0, 0.3, 0.5, 0.0, 1e-3), [1.0, 0.0, 3.0], 0.0, 100.0)
    >>> ph.status.value, round(ph.t_stop_slide, 4), ph.residual_max < 1e-9
    ('rest', 8.5113, True)
    """
    y = np.zeros(len(FACE_NAMES))
    y[:np.size(y0)] = np.asarray(y0, dtype=float)
    e0 = float(cc.energy(y)[0])
    if _speed(cc, y) <= REST_SPEED:
        return _ended(cc, t0, y, y, t0, e0, [], Status.REST, "at rest on its face", (t0, t0), None, 0.0, 0)
    st = _Stepper(cc, t0, y, t_end, rtol, rtol / 100 if atol is None else atol)
    status = reason = None
    while status is None:
        if budget is not None and (budget.steps - len(st.pieces) <= 0 or budget.wall_exceeded()):
            status, reason = Status.FAILED, ("wall-time limit reached" if budget.wall_exceeded() else
                                             f"step limit ({len(st.pieces)} steps on the face) reached at t = "
                                             f"{st.ts[-1]:.6g}")
            break
        msg = st.step()
        if msg is not None:
            status, reason = Status.FAILED, f"the face mode failed at t = {st.solver.t:.6g}: {msg}"
        elif _speed(cc, st.ys[-1]) <= REST_SPEED:
            return _at_rest(cc, st, t0, y, e0)
        elif st.solver.status == "finished":
            status, reason = Status.COMPLETED, "on its face at t_end, still sliding or spinning"
    return _ended(cc, t0, y, st.ys[-1], st.ts[-1], e0, st.pieces, status, reason, (None, None), None,
                  _residual(cc, st, e0), len(st.pieces), st.solver.nfev)


def _residual(cc: FaceContact, st: _Stepper, e0: float) -> float:
    Y = np.array(st.ys)
    return float(np.max(np.abs(cc.energy(Y) - e0 - Y[:, 6])))


def _at_rest(cc: FaceContact, st: _Stepper, t0: float, y0, e0: float) -> FacePhase:
    """The speed fell to REST_SPEED in the last step: locate it, extrapolate v and w to zero."""
    ta, tb, dense = st.pieces[-1]
    level = lambda t: _speed(cc, dense(t)) - REST_SPEED  # noqa: E731
    te = brentq(level, ta, tb, xtol=1e-15, rtol=1e-15) if level(ta) > 0 else ta
    ye = dense(te)
    st.pieces[-1] = (ta, te, dense)
    st.ts[-1], st.ys[-1] = te, ye
    rate = st.field(ye)
    speed = _speed(cc, ye)
    dspeed = (ye[0] * rate[0] + ye[1] * rate[1] + cc.a * cc.a * ye[2] * rate[2]) / speed
    dt = speed / -dspeed if dspeed < 0 else 0.0
    slide, spin = math.hypot(ye[0], ye[1]), abs(ye[2])
    t_slide = te + (slide / math.hypot(rate[0], rate[1]) if slide > 0 else 0.0)
    t_spin = te + (spin / abs(rate[2]) if spin > 0 else 0.0)
    y1 = ye.copy()
    y1[0:3] = 0.0
    y1[3:6] = ye[3:6] + 0.5 * dt * ye[0:3]
    y1[6] = ye[6] - (float(cc.energy(ye)[0]) - cc.h0)  # the last stretch takes the rest of the motion
    pieces = list(st.pieces)
    if dt > 0:
        pieces.append((te, te + dt, _Line(te, te + dt, ye, y1)))
    ratio = slide / (cc.a * spin) if spin > 0 else math.inf
    return _ended(cc, t0, y0, y1, te + dt, e0, pieces, Status.REST,
                  f"lies flat; slid and spun on its face to rest at t = {te + dt:.10g}", (t_slide, t_spin), ratio,
                  _residual(cc, st, e0), len(st.pieces), st.solver.nfev)


@dataclass(frozen=True)
class _Line:
    """The straight stretch from (t0, y0) to (t1, y1): the motion extrapolated to rest (picklable)."""

    t0: float
    t1: float
    y0: np.ndarray
    y1: np.ndarray

    def __call__(self, ts) -> np.ndarray:
        s = (np.atleast_1d(ts) - self.t0) / (self.t1 - self.t0)
        return self.y0[:, None] * (1 - s) + self.y1[:, None] * s


def _ended(cc, t0, y0, y1, t1, e0, pieces, status, reason, stops, ratio, residual, n_steps, n_rhs=0) -> FacePhase:
    num = lambda q: None if q is None else float(q)  # noqa: E731
    return FacePhase(cc, float(t0), float(t1), np.array(y0, dtype=float), np.array(y1, dtype=float), status, reason,
                     num(stops[0]), num(stops[1]), num(ratio), e0, float(cc.energy(y1)[0]), float(residual), int(n_steps), int(n_rhs),
                     tuple(pieces))


# -- the reset and the start ------------------------------------------------------------------------


def landing(model, x) -> tuple[FaceContact, np.ndarray, dict]:
    """The plastic landing of a chart state at face down: (face, face state, numbers of the event).

    The numbers: ``energy_before``, ``energy_after`` (the chart's energy, the face's), ``v_normal`` (v_z of
    G, lost), ``friction_bound`` (mu |v_z|: the most the horizontal velocity kept could change)."""
    k, w, v = rigid_velocities(model, flight_state(model, x))
    body = model.body
    n = float(w @ k)
    L = body.A * (w - n * k) + body.C * n * k
    cc = face_contact(model, math.acos(max(-1.0, min(1.0, float(k[2])))), math.atan2(k[1], k[0]))
    y = np.zeros(len(FACE_NAMES))
    y[0:3] = v[0], v[1], L[2] / body.C
    mode = Mode.SLIDING if Mode.SLIDING in model.modes else next(iter(model.modes))
    before = float(model.function("energy", mode)(x, model.p))
    return cc, y, {"energy_before": before, "energy_after": float(cc.energy(y)[0]), "v_normal": float(v[2]),
                   "friction_bound": cc.mu * abs(float(v[2]))}


@dataclass(frozen=True)
class FaceLanding:
    """The reset of "face down" (runs with ``stop_at="rest"``): the plastic landing of
    :func:`landing`, into Mode.FACE. The face state is the transition's state."""

    def __call__(self, model, event, mode, t, x) -> Transition:
        cc, y, n = landing(model, x)
        detail = (f"plastic landing: v_z = {n['v_normal']:.3e} lost, L_Z and v kept (friction impulse <= "
                  f"{n['friction_bound']:.2e} neglected), dE = {n['energy_after'] - n['energy_before']:.3e}")
        recs = (Record(event.name, mode.value, "impact", x), Record("on its face", "impact", Mode.FACE.value, x, detail))
        return Transition(Mode.FACE, t, np.concatenate([y, [cc.theta, cc.psi]]), recs)


def face_state_of(model, x) -> np.ndarray:
    """A chart state given to start on the face (``simulate(..., mode="face")``): its horizontal
    velocity of G and the vertical component of w, as they are; + the face-down angle and azimuth."""
    k, w, v = rigid_velocities(model, flight_state(model, x))
    cc = face_contact(model, math.acos(max(-1.0, min(1.0, float(k[2])))), math.atan2(k[1], k[0]))
    return np.array([v[0], v[1], w[2], 0.0, 0.0, 0.0, 0.0, cc.theta, cc.psi])


def face_start_transition(model, t, x) -> Transition:
    """simulate's start in Mode.FACE."""
    y = face_state_of(model, x)
    return Transition(Mode.FACE, t, y, (Record("on its face", "start", Mode.FACE.value, x, "started on its face"),))


def run_face(run) -> None:
    """Integrate the face mode for a :class:`phasekit.core.simulate.RunState` in Mode.FACE (its state:
    the face state, then the face-down angle and azimuth), and end the run."""
    y, theta, psi = run.x[:len(FACE_NAMES)], float(run.x[-2]), float(run.x[-1])
    cc = face_contact(run.model, theta, psi)
    phase = face_motion(cc, y, run.t, run.t_end, rtol=run.opts.rtol, atol=run.opts.atol, budget=run.budget)
    run.steps_done += phase.n_steps
    run.face = phase
    run.t, run.x = phase.t1, np.concatenate([phase.y1, [theta, psi]])
    if phase.status is Status.REST:
        run.record("at rest", phase.t1, Mode.FACE.value, "end", phase.chart_states(run.model, phase.y1)[0],
                   f"stopped sliding at t = {phase.t_stop_slide:.10g}, spinning at t = {phase.t_stop_spin:.10g}")
    run.status, run.reason = phase.status, phase.reason
