"""The contact model: one smooth CasADi vector field per mode, compiled once and cached.

Given a chart (:mod:`phasekit.charts`), the state derivative is affine in the contact
force Fc = (F_1, F_2, R). Each mode adds the equations that fix Fc:

* the contact constraint R = 1 + dW/dt, (2.8), in every contact mode;
* SLIDING: the friction law, Fc = Fc0(u) + R d(u) (:mod:`phasekit.friction`), which
  leaves one linear equation for R; for Coulomb friction this is (6.1);
* ROLLING: the no-slip constraint du/dt = 0, which with (2.8) is a 3x3 linear system
  for Fc (solved symbolically by minor expansion).

All equations are symbolic in the parameter vector
p = (shape..., A, C, mu, eps, cos_stop, stop_sign), so a model compiled for one body
class and law serves every aspect ratio and coefficient: sweeps never recompile. The
last two entries only feed the optional "rise complete" guard
stop_sign * (cos_stop - cos(theta)), which crosses zero downwards when theta passes
theta_stop in the direction of the rise.
"""

from __future__ import annotations

import hashlib
import threading
from dataclasses import dataclass, field

import casadi as ca
import numpy as np

from .body import Body
from .charts import CHARTS
from .errors import check_choice
from .friction import FrictionLaw
from .modes import Mode

__all__ = ["Mode", "Model", "compiled_model", "evaluate_function"]


#: slip speed (units sqrt(g b)) at which exact Coulomb sliding is taken to have stuck;
#: the stick time is then extrapolated to the exact zero of the slip
STICK_SLIP = 1e-10
#: the same for integrators that evaluate the field pointwise (CVODES), which chatter at u = 0
STICK_SLIP_POINTWISE = 1e-7

#: A, C, mu, eps, cos_stop, stop_sign: the parameters after the body's shape parameters
N_LAW_AND_RUN_PARAMS = 6

#: quantities available from every chart, evaluated by :meth:`Model.evaluate`
COMMON_OUTPUTS = ("slip", "energy", "L_Z", "spin", "jellett", "theta", "h", "W")


@dataclass
class CompiledModel:
    """CasADi functions of (x, p) for one (body class, law class, chart)."""

    chart: str
    state_names: tuple[str, ...]
    n_params: int
    key: tuple = ()
    signature: str = ""  # changes whenever the equations change (keys on-disk caches)
    functions: dict[str, ca.Function] = field(default_factory=dict)
    modes: tuple[Mode, ...] = ()

    def f(self, name: str) -> ca.Function:
        return self.functions[name]


_CACHE: dict[tuple, CompiledModel] = {}
_LOCK = threading.Lock()


def compiled_model(body_cls: type[Body], law_cls: type[FrictionLaw], chart: str) -> CompiledModel:
    """Build (or fetch from the cache) the compiled model of a body class, law class and chart."""
    key = (body_cls, law_cls, chart)
    with _LOCK:
        if key not in _CACHE:
            _CACHE[key] = _build(body_cls, law_cls, chart)
        return _CACHE[key]


def _build(body_cls, law_cls, chart) -> CompiledModel:
    spec = CHARTS[chart]
    names = spec["names"]
    nx, ns = len(names), body_cls.n_shape
    x = ca.SX.sym("x", nx)
    p = ca.SX.sym("p", ns + N_LAW_AND_RUN_PARAMS)
    Fc = ca.SX.sym("Fc", 3)
    shape, A, C, mu, eps = p[:ns], p[ns], p[ns + 1], p[ns + 2], p[ns + 3]
    cos_stop, stop_sign = p[ns + 4], p[ns + 5]
    T = spec["terms"](x, shape, A, C, Fc, body_cls.height_c)
    xdot, slip = T["xdot"], T["slip"]

    # Contact constraint R - 1 - dW/dt = 0, affine in Fc: G.Fc + g0 = 0.
    constraint = Fc[2] - 1 - ca.jtimes(T["W"], x, xdot)
    G = ca.jacobian(constraint, Fc)
    g0 = ca.substitute(constraint, Fc, ca.SX.zeros(3))

    out = CompiledModel(chart=chart, state_names=names, n_params=ns + N_LAW_AND_RUN_PARAMS)
    fn = out.functions

    def add(name, expr):
        fn[name] = ca.Function(name, [x, p], [expr], ["x", "p"], [name])

    def add_mode(mode: Mode, Fc_mode):
        tag = mode.value
        rhs = ca.substitute(xdot, Fc, Fc_mode)
        R = Fc_mode[2]
        add(f"rhs_{tag}", rhs)
        # CasADi reserves the name "jac"; see the style guide.
        add(f"rhs_jac_{tag}", ca.jacobian(rhs, x))
        add(f"R_{tag}", R)
        add(f"Rdot_{tag}", ca.jtimes(R, x, rhs))
        add(f"Fc_{tag}", Fc_mode)
        return rhs, R

    # SLIDING: Fc = Fc0 + R d, R from the constraint.
    Fc0, d = law_cls.sliding_force(slip, mu, eps)
    Fc0, d = ca.SX(Fc0), ca.SX(d)
    R_sl = -(g0 + ca.mtimes(G, Fc0)) / ca.mtimes(G, d)
    rhs_sl, _ = add_mode(Mode.SLIDING, Fc0 + R_sl * d)
    modes = [Mode.SLIDING]
    # d|u|^2/dt while sliding: extrapolates a stick event to the exact zero of the slip.
    add("slip_speed2_rate", 2 * ca.dot(slip, ca.jtimes(slip, x, rhs_sl)))
    # Guards of the stick event: the slip speed falls to STICK_SLIP (exact Coulomb), or to
    # 10 eps (regularised law, where the force then departs from Coulomb's by > 0.5%).
    # The Taylor backend uses |u| itself: as the slip vanishes under Coulomb friction |u|
    # is linear in time, and the Taylor expansion of sqrt(u.u) follows that line through
    # zero, giving a simple root (the squared form has a near-double root it can miss).
    # Pointwise integrators (CVODES) chatter at u = 0 instead, so they bracket the dip of
    # |u|^2 below a larger threshold, using its rate for Hermite interpolation.
    speed2 = slip[0] ** 2 + slip[1] ** 2
    add("stick_guard", ca.sqrt(speed2) - (STICK_SLIP + 10 * eps))
    add("stick_guard_sq", speed2 - (STICK_SLIP_POINTWISE + 10 * eps) ** 2)
    # Regularised law only: the slip has grown back above 100 eps (hysteresis against chatter).
    add("unstick_guard", 100 * eps - ca.sqrt(speed2))

    if law_cls.has_rolling_mode:
        # ROLLING: constraint and du/dt = 0 fix all three components of Fc.
        rows = ca.vertcat(constraint, ca.jtimes(slip, x, xdot))
        M = ca.jacobian(rows, Fc)
        b = ca.substitute(rows, Fc, ca.SX.zeros(3))
        Fc_roll = -ca.solve(M, b)
        _, R_roll = add_mode(Mode.ROLLING, Fc_roll)
        # >= 0 while static friction can hold the no-slip constraint.
        add("margin_rolling", mu * mu * R_roll * R_roll - Fc_roll[0] ** 2 - Fc_roll[1] ** 2)
        modes.append(Mode.ROLLING)

        # Slip acceleration when sliding starts from zero slip in direction e = (cos phi, sin phi):
        # used to find the direction in which slip develops when rolling ends.
        phi = ca.SX.sym("phi")
        e = ca.vertcat(ca.cos(phi), ca.sin(phi))
        d_e = ca.vertcat(-mu * e, 1)
        R_e = -g0 / ca.mtimes(G, d_e)
        rhs_e = ca.substitute(xdot, Fc, R_e * d_e)
        fn["slip_onset"] = ca.Function(
            "slip_onset", [x, p, phi], [ca.jtimes(slip, x, rhs_e), R_e], ["x", "p", "phi"], ["slip_acc", "R"]
        )

    for name in COMMON_OUTPUTS:
        add(name, T[name])
    add("slip_speed2", slip[0] ** 2 + slip[1] ** 2)
    add("cos_theta", T["cos_theta"])
    add("rise_guard", stop_sign * (cos_stop - T["cos_theta"]))
    # Velocity of O that carries the slip: U, V (euler) or v_x, v_y (vector) are the last
    # velocity components; shifting them shifts the slip one-for-one.
    out.modes = tuple(modes)
    out.key = (body_cls, law_cls, chart)
    blob = "".join(fn[k].serialize() for k in sorted(fn))
    out.signature = f"{body_cls.__qualname__}|{law_cls.__qualname__}|{chart}|" + hashlib.sha256(blob.encode()).hexdigest()
    return out


def evaluate_function(f: ca.Function, p: np.ndarray, x):
    """f(x, p) for one state (d,) -> float or (k,), or for many states (m, d) -> (m,) or (m, k)."""
    X = np.asarray(x, dtype=float)
    if X.ndim == 1:
        r = np.asarray(f(X, p))
        return float(r.item()) if r.size == 1 else r.ravel()
    r = np.asarray(f.map(X.shape[0])(X.T, np.tile(p[:, None], (1, X.shape[0]))))
    return r.ravel() if r.shape[0] == 1 else r.T


class Model:
    """A body, a friction law and a chart, with numeric parameters bound.

    Parameters
    ----------
    body : Body
        e.g. ``Spheroid(1.5)``.
    friction : FrictionLaw
        ``Coulomb(mu)`` (exact stick-slip), ``RegularisedCoulomb(mu, eps)`` or ``Viscous(mu)``.
    chart : {"euler", "vector"}
        Coordinates: the paper's (2.7), or the singularity-free Newton-Euler form.
    """

    def __init__(self, body: Body, friction: FrictionLaw, chart: str = "euler"):
        if not isinstance(body, Body):
            raise ValueError(f"`body` must be a phasekit Body such as Spheroid(a), got {body!r}.")
        if not isinstance(friction, FrictionLaw):
            raise ValueError(f"`friction` must be a phasekit FrictionLaw, got {friction!r}.")
        check_choice("chart", chart, tuple(CHARTS))
        self.body = body
        self.friction = friction
        self.chart = chart
        self.compiled = compiled_model(type(body), type(friction), chart)
        # cos_stop = 2 is never reached: the rise guard is inert unless a run sets it.
        self.p = np.concatenate([body.params, friction.params, [2.0, 1.0]])

    @property
    def state_names(self) -> tuple[str, ...]:
        return self.compiled.state_names

    @property
    def n_states(self) -> int:
        return len(self.compiled.state_names)

    @property
    def modes(self) -> tuple[Mode, ...]:
        return self.compiled.modes

    def function(self, name: str) -> ca.Function:
        return self.compiled.f(name)

    def evaluate(self, name: str, x) -> np.ndarray | float:
        """Evaluate a named quantity at a state (d,) or at many states (m, d)."""
        return evaluate_function(self.compiled.f(name), self.p, x)

    def rhs(self, x, mode: Mode = Mode.SLIDING) -> np.ndarray:
        return np.asarray(self.compiled.f(f"rhs_{Mode(mode).value}")(x, self.p)).ravel()

    def jacobian(self, x, mode: Mode = Mode.SLIDING) -> np.ndarray:
        return np.asarray(self.compiled.f(f"rhs_jac_{Mode(mode).value}")(x, self.p))

    def normal_reaction(self, x, mode: Mode = Mode.SLIDING):
        return self.evaluate(f"R_{Mode(mode).value}", x)

    def __repr__(self) -> str:
        return f"Model({self.body!r}, {self.friction.describe()}, chart={self.chart!r})"
