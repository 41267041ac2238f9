"""Free flight after lift-off (section 4): gravity on the centre, torque-free rotation.

State (vector form, as the contact dynamics of the vector chart, plus the vertical motion):
    k (3), w (3), (v_x, v_y) (2), the gap Delta (4.1) = z - H(k_Z) and its rate (2).
Equations: dk/dt = w x k, I dw/dt = -(C - A) n (w x k) (torque free, I = A 1 + (C - A) k k^T),
dv_x/dt = dv_y/dt = 0, d2Delta/dt2 = -1 - d2H/dt2 (the centre falls freely). The vertical
velocity of O is v_z = dDelta/dt + dH/dt.

At lift-off R = 0 and the friction (proportional to R) vanishes, so no impulse acts: positions
and velocities carry over, and so do accelerations (checked numerically in the tests).

Exact solution (4.6)-(4.14): Omega - Psi cot(theta) = C1, Psi^2 + thetadot^2 = C2^2,
Omega cos(theta) - Psi / sin(theta) = n0, and cos(theta(t)) of (4.12); the gap (4.1) follows.
Near lift-off, in the gyroscopic limit, Delta ~ Omega*^2 t^3 (4 W* - t) / 24 (4.22), with
maximum 9/8 Omega*^2 W*^4 at t = 3 W* (4.23).
"""

from __future__ import annotations

import hashlib
import threading
from dataclasses import dataclass, field

import casadi as ca
import numpy as np

from .body import Body
from .charts import _cross, euler_to_vector, vector_to_euler
from .friction import FrictionLaw, Viscous
from .model import N_LAW_AND_RUN_PARAMS, CompiledModel, evaluate_function

__all__ = [
    "FlightModel",
    "flight_state",
    "contact_state",
    "FlightConstants",
    "flight_constants",
    "cos_theta_exact",
    "gap_exact",
    "gap_series",
    "gap_max_series",
    "flight_invariants",
    "rigid_velocities",
    "from_rigid",
    "Flight",
    "fly",
    "GUARD_DELAY",
]

FLIGHT_NAMES = ("k_x", "k_y", "k_z", "w_x", "w_y", "w_z", "v_x", "v_y", "gap", "gap_rate")
#: the first stretch of a flight integrated without the touchdown guard (see fly())
GUARD_DELAY = 1e-5
_CACHE: dict = {}
_LOCK = threading.Lock()


def _build(body_cls) -> CompiledModel:
    ns = body_cls.n_shape
    x = ca.SX.sym("x", 10)
    p = ca.SX.sym("p", ns + N_LAW_AND_RUN_PARAMS)
    shape, A, C = p[:ns], p[ns], p[ns + 1]
    k, w, vx, vy, D, Dd = x[0:3], x[3:6], x[6], x[7], x[8], x[9]
    khat = k / ca.norm_2(k)
    c = khat[2]
    csym = ca.SX.sym("c")
    Hs = body_cls.height_c(csym, shape)
    H = ca.substitute(Hs, csym, c)
    n = ca.dot(w, khat)
    wxk = _cross(w, khat)
    torque = -(C - A) * n * wxk
    wdot = (torque - khat * ca.dot(khat, torque)) / A + khat * ca.dot(khat, torque) / C
    rot = ca.vertcat(_cross(w, k), wdot, ca.SX.zeros(4))
    Hdot = ca.jtimes(H, x, rot)
    Hddot = ca.jtimes(Hdot, x, rot)
    # the gap and its rate are states: Delta = z - H(k_Z) starts at exactly 0 at lift-off, and
    # z - H would lose it to cancellation while it is below 1e-16 (Delta ~ t^3 at first)
    rhs = ca.vertcat(_cross(w, k), wdot, 0, 0, Dd, -1 - Hddot)
    Lvec = A * (w - n * khat) + C * n * khat
    vz = Dd + Hdot
    energy = 0.5 * (vx * vx + vy * vy + vz * vz) + 0.5 * ca.dot(w, Lvec) + D + H
    fn = {}

    def add(name, expr):
        fn[name] = ca.Function(name, [x, p], [expr], ["x", "p"], [name])

    add("rhs_flight", rhs)
    add("rhs_jac_flight", ca.jacobian(rhs, x))
    add("gap", D)
    add("gap_rate", Dd)
    add("gap_acc", -1 - Hddot)
    add("Hdot", Hdot)
    add("H", H)
    add("energy", energy)
    add("L", Lvec)
    add("spin", n)
    add("cos_theta", c)
    out = CompiledModel(chart="flight", state_names=FLIGHT_NAMES, n_params=ns + N_LAW_AND_RUN_PARAMS, functions=fn, modes=())
    out.key = (body_cls, "flight")
    blob = "".join(fn[k].serialize() for k in sorted(fn))
    out.signature = f"{body_cls.__qualname__}|flight|" + hashlib.sha256(blob.encode()).hexdigest()
    return out


@dataclass
class FlightModel:
    """Free flight of a body: the same interface as :class:`phasekit.Model` for the backends."""

    body: Body
    friction: FrictionLaw = field(default_factory=lambda: Viscous(0.0))
    chart: str = "flight"

    def __post_init__(self):
        key = type(self.body)
        with _LOCK:
            if key not in _CACHE:
                _CACHE[key] = _build(key)
        self.compiled = _CACHE[key]
        self.p = np.concatenate([self.body.params, self.friction.params, [2.0, 1.0]])

    @property
    def n_states(self) -> int:
        return 10

    @property
    def state_names(self):
        return FLIGHT_NAMES

    def function(self, name: str) -> ca.Function:
        return self.compiled.functions[name]

    def evaluate(self, name: str, x):
        return evaluate_function(self.compiled.functions[name], self.p, x)

    def rhs(self, x, mode=None) -> np.ndarray:
        return np.asarray(self.compiled.functions["rhs_flight"](x, self.p)).ravel()


def flight_state(model, x_contact) -> np.ndarray:
    """Contact state (either chart) at lift-off -> flight state: same k, w, horizontal v; the
    gap and its rate start at zero (the contact point's vertical velocity is zero in contact)."""
    x = np.asarray(x_contact, dtype=float)
    z = x.copy() if model.chart == "vector" else euler_to_vector(x)
    return np.concatenate([z[0:8], [0.0, 0.0]])


def contact_state(chart: str, xf) -> np.ndarray:
    """Flight state at touchdown -> contact chart state (the vertical motion is then slaved)."""
    xf = np.asarray(xf, dtype=float)
    z = xf[0:8].copy()
    return z if chart == "vector" else vector_to_euler(z)


def rigid_velocities(fm: "FlightModel", xf):
    """(k, w, v) with v = (v_x, v_y, v_z), v_z = dDelta/dt + dH/dt, for the impact law."""
    xf = np.asarray(xf, dtype=float)
    vz = xf[9] + float(fm.function("Hdot")(xf, fm.p))
    return xf[0:3].copy(), xf[3:6].copy(), np.array([xf[6], xf[7], vz])


def from_rigid(fm: "FlightModel", k, w, v, gap: float = 0.0) -> np.ndarray:
    """Inverse of :func:`rigid_velocities` (gap rate = v_z - dH/dt at the new angular velocity)."""
    xf = np.concatenate([k, w, v[:2], [gap, 0.0]])
    xf[9] = v[2] - float(fm.function("Hdot")(xf, fm.p))
    return xf


@dataclass(frozen=True)
class FlightConstants:
    """Constants of the exact free motion (4.6)-(4.14), from the state at lift-off."""

    theta: float
    thetadot: float
    Omega: float
    Psi: float
    n: float
    W: float
    h: float
    C1: float
    C2: float
    C1p: float
    C3: float
    C4: float


def flight_constants(body: Body, euler_state, W: float) -> FlightConstants:
    """(4.5)-(4.14) from (U, V, Omega, Lambda, theta, n) at lift-off and the vertical velocity W*."""
    _, _, Om, Lam, th, n = (float(v) for v in euler_state)
    A, C = body.A, body.C
    s, c = np.sin(th), np.cos(th)
    Psi = (A * Om * c - C * n) * s / A  # (3.1)
    C1 = Om - Psi * c / s
    C2 = np.sqrt(Psi**2 + Lam**2)
    C1p = Psi / s - Om * c
    C3 = np.sqrt(C1**2 + C2**2)
    C4 = C1 * C1p / C3**2
    return FlightConstants(th, Lam, Om, Psi, n, W, body.h(th)[0], C1, C2, C1p, C3, C4)


def cos_theta_exact(k: FlightConstants, t):
    """(4.12): cos(theta(t)) of the free motion, t measured from lift-off."""
    t = np.asarray(t, dtype=float)
    return -k.C4 - k.thetadot * np.sin(k.theta) * np.sin(k.C3 * t) / k.C3 + (np.cos(k.theta) + k.C4) * np.cos(k.C3 * t)


def gap_exact(body: Body, k: FlightConstants, t):
    """(4.1) with (4.12): Delta(t) = h* + W* t - t^2/2 - h(theta(t))."""
    th = np.arccos(np.clip(cos_theta_exact(k, t), -1.0, 1.0))
    return k.h + k.W * np.asarray(t) - 0.5 * np.asarray(t) ** 2 - body.h(th)[0]


def gap_series(Omega: float, W: float, t):
    """(4.22): Delta ~ Omega*^2 t^3 (4 W* - t) / 24."""
    t = np.asarray(t, dtype=float)
    return Omega**2 * t**3 * (4 * W - t) / 24.0


def gap_max_series(Omega: float, W: float) -> tuple[float, float]:
    """(4.23): (Delta_max, t at the maximum) = (9/8 Omega*^2 W*^4, 3 W*)."""
    return 9.0 / 8.0 * Omega**2 * W**4, 3.0 * W


def flight_invariants(body: Body, euler_states) -> np.ndarray:
    """(4.6)-(4.8) along a flight: columns C1 = Omega - Psi cot, C2^2 = Psi^2 + thetadot^2,
    n0 = Omega cos - Psi / sin (all constant in free flight)."""
    Y = np.atleast_2d(np.asarray(euler_states, dtype=float))
    Om, Lam, th = Y[:, 2], Y[:, 3], Y[:, 4]
    n = Y[:, 5]
    s, c = np.sin(th), np.cos(th)
    Psi = (body.A * Om * c - body.C * n) * s / body.A
    return np.column_stack([Om - Psi * c / s, Psi**2 + Lam**2, Om * c - Psi / s])


@dataclass(frozen=True)
class Flight:
    """One flight: from lift-off (t_liftoff) to touchdown (t_touchdown, None if t_end came first).

    ``gap_max``/``t_gap_max``: the located maximum of the gap (dDelta/dt = 0); ``W_star`` and
    ``Omega_star``: vertical velocity of O and precession rate at lift-off; ``xs``/``gaps``:
    flight states and gaps at the requested output times only.
    """

    status: str  # "touchdown", "time" or "failed"
    t_liftoff: float
    t_touchdown: float | None
    x_liftoff: np.ndarray
    x_end: np.ndarray
    gap_max: float | None
    t_gap_max: float | None
    W_star: float
    Omega_star: float
    n_steps: int
    reason: str | None = None
    ts: np.ndarray | None = None
    xs: np.ndarray | None = None
    gaps: np.ndarray | None = None

    def to_dict(self) -> dict:
        return {"t_touchdown": self.t_touchdown, "gap_max": self.gap_max, "t_gap_max": self.t_gap_max,
                "W_star": self.W_star, "Omega_star": self.Omega_star, "t_liftoff": self.t_liftoff}


def fly(model, x, t0: float, t_end: float, *, rtol: float = 1e-12, max_steps: int = 1_000_000, t_eval=None,
        flight_state_given: bool = False) -> Flight:
    """Integrate the free flight from the contact state ``x`` of ``model`` at lift-off (or from
    a flight state when ``flight_state_given``) until touchdown (Delta = 0 from above), located
    by the Taylor integrator's polynomial root finding (to ~1e-14 in time)."""
    from .backends import TaylorBackend
    from .modes import Mode, mode_events

    fm = FlightModel(model.body, model.friction)
    xf = np.asarray(x, dtype=float) if flight_state_given else flight_state(model, x)
    if flight_state_given:
        from .charts import vector_to_euler as _v2e

        om_star = float(_v2e(np.concatenate([xf[0:6], xf[6:8]]))[2])
    else:
        om_star = float((x if model.chart == "euler" else vector_to_euler(x))[2])
    eng = TaylorBackend(fm, rtol)
    evs = mode_events(fm, Mode.FLIGHT)
    # At lift-off Delta = dDelta/dt = 0 and d2Delta/dt2 = -R vanish only to rounding and the
    # event tolerance (~1e-16, ~1e-12), so the gap's Taylor polynomial can have spurious roots
    # before its t^3 growth dominates (t ~ 1e-5). Integrate that first stretch without the
    # touchdown guard; a flight whose gap has not opened by then is a graze and ends there.
    t_skip = min(t0 + GUARD_DELAY, t_end)
    first = eng.propagate(Mode.FLIGHT, xf, t0, t_skip, (), fm.p, max_steps=max_steps, t_eval=t_eval)
    steps = first.n_steps
    if first.outcome == "failed" or t_skip >= t_end or float(fm.evaluate("gap", first.x)) <= 0.0:
        prop = first
        if first.outcome == "time" and t_skip < t_end:
            prop.outcome = "event"  # graze: touchdown at the end of the unguarded stretch
    else:
        prop = eng.propagate(Mode.FLIGHT, first.x, first.t, t_end, evs, fm.p, max_steps=max(max_steps - steps, 1),
                             t_eval=t_eval, minima=("gap_rate", -1))
        steps += prop.n_steps
        if first.ts is not None:
            prop.ts = first.ts if prop.ts is None else np.concatenate([first.ts, prop.ts])
            prop.ys = first.ys if prop.ys is None else np.vstack([first.ys, prop.ys])
    prop.n_steps = steps
    gmax = tgmax = None
    if prop.minima:
        tgmax, xg = max(prop.minima, key=lambda q: fm.evaluate("gap", q[1]))
        gmax = float(fm.evaluate("gap", xg))
    gaps = fm.evaluate("gap", prop.ys) if prop.ys is not None and len(prop.ys) else None
    if prop.outcome == "event":
        status, t_td = "touchdown", prop.t
    elif prop.outcome == "time":
        status, t_td = "time", None
    else:
        status, t_td = "failed", None
    W_star = float(xf[9] + float(fm.function("Hdot")(xf, fm.p)))  # vertical velocity of O at the start
    return Flight(status, float(t0), t_td, xf, prop.x, gmax, tgmax, W_star, om_star, prop.n_steps, prop.reason,
                  prop.ts, prop.ys, None if gaps is None else np.atleast_1d(gaps))
