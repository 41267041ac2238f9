"""The compiled fields: one smooth CasADi vector field per mode and chart, built symbolically
once per (body structure, law class, chart) and cached.

Given a chart (:mod:`phasekit.core.charts`), the state derivative is affine in the contact
force Fc = (F_1, F_2, R). Each mode adds the equations that fix Fc:

* every contact mode: the contact constraint R = 1 + dW/dt, (2.8);
* SLIDING: the friction law, Fc = Fc0(u) + R d(u) (:mod:`phasekit.friction.laws`), which
  leaves one linear equation for R; for Coulomb friction this is (6.1);
* ROLLING (exact Coulomb): the no-slip constraint du/dt = 0, which with (2.8) is a 3x3
  linear system for Fc (solved symbolically);
* FLIGHT: Fc = 0, in the flight chart (the vector chart's state plus the gap), built from
  the same rigid-body equations.

All equations are symbolic in the parameter vector p = (shape..., A, C, mu, eps), so a
model compiled for one body structure and law serves every aspect ratio and coefficient:
sweeps never recompile. Observables (R, energy, the paper's variables, ...) are compiled
per chart (:mod:`phasekit.core.observables` names them); :class:`phasekit.core.model.Model`
binds the numbers and evaluates them.
"""

from __future__ import annotations

import hashlib
import threading
from dataclasses import dataclass, field

import casadi as ca

from ..bodies.body import Body
from ..friction.laws import FrictionLaw
from .charts import FLIGHT, PAPER_NAMES, Chart
from .hybrid import Mode

__all__ = ["CompiledModel", "compiled_model", "STICK_SLIP", "STICK_SLIP_POINTWISE", "snapshot", "install"]

#: slip speed (units sqrt(g b)) at which exact Coulomb sliding is taken to have stuck;
#: the stick time is then extrapolated to the exact zero of the slip
STICK_SLIP = 1e-10
#: the same for integrators that evaluate the field pointwise (CVODES), which chatter at u = 0
STICK_SLIP_POINTWISE = 1e-7


@dataclass
class CompiledModel:
    """CasADi functions of (x, p) for one (body structure, law class, chart).

    ``contact`` holds functions of a state of the contact chart, ``flight`` of a flight
    state; names of mode fields are ``rhs_<mode>``, ``rhs_jac_<mode>``, ``R_<mode>``,
    ``Rdot_<mode>``, ``Fc_<mode>``."""

    chart: Chart
    n_params: int
    modes: tuple[Mode, ...]
    contact: dict[str, ca.Function] = field(default_factory=dict)
    flight: dict[str, ca.Function] = field(default_factory=dict)
    key: tuple = ()
    signature: str = ""  # changes whenever the equations change (keys on-disk caches)
    guards: dict = field(default_factory=dict)  # (on, mode) -> g(x, p, level)
    flows: dict = field(default_factory=dict)  # (Flow, events) -> CompiledFlow

    def functions_of(self, mode: Mode) -> dict[str, ca.Function]:
        return self.flight if mode is Mode.FLIGHT else self.contact


_CACHE: dict[tuple, CompiledModel] = {}
_LOCK = threading.Lock()


def snapshot() -> dict:
    """The compiled models of this process (for :class:`phasekit.sweep.ModelPack`)."""
    with _LOCK:
        return dict(_CACHE)


def install(models: dict) -> None:
    """Add a :func:`snapshot` of another process to this one's compiled models."""
    with _LOCK:
        for k, v in models.items():
            _CACHE.setdefault(k, v)


def compiled_model(body: Body, law: FrictionLaw, chart: Chart) -> CompiledModel:
    """Build (or fetch from the cache) the compiled model of a body structure, law class and chart."""
    key = (body.structure_key, type(law), chart.name)
    with _LOCK:
        if key not in _CACHE:
            _CACHE[key] = _build(body, type(law), chart, key)
        return _CACHE[key]


def _function(name, x, p, expr) -> ca.Function:
    return ca.Function(name, [x, p], [expr], ["x", "p"], [name])


def _common(fn: dict, T: dict, x, p) -> None:
    """Observables shared by every chart, from its terms."""
    for name in ("energy", "L_Z", "spin", "jellett", "h", "W", "cos_theta"):
        fn[name] = _function(name, x, p, T[name])
    for i, name in enumerate(PAPER_NAMES):
        fn[name] = _function(name, x, p, T["paper"][i])
    fn["paper"] = _function("paper", x, p, T["paper"])


def _build(body: Body, law_cls: type[FrictionLaw], chart: Chart, key) -> CompiledModel:
    nx, ns = chart.n_states, body.n_shape
    x = ca.SX.sym("x", nx)
    p = ca.SX.sym("p", ns + 4)
    Fc = ca.SX.sym("Fc", 3)
    shape, A, C, mu, eps = p[:ns], p[ns], p[ns + 1], p[ns + 2], p[ns + 3]

    def H(c):
        return body.height(c, shape)

    T = chart.terms(x, H, A, C, Fc)
    xdot, slip = T["xdot"], T["slip"]
    modes = [Mode.SLIDING, Mode.ROLLING] if law_cls.can_stick else [Mode.SLIDING]
    out = CompiledModel(chart=chart, n_params=ns + 4, modes=(*modes, Mode.FLIGHT), key=key)
    fn = out.contact

    # Contact constraint R - 1 - dW/dt = 0, affine in Fc: G.Fc + g0 = 0.
    constraint = Fc[2] - 1 - ca.jtimes(T["W"], x, xdot)
    G = ca.jacobian(constraint, Fc)
    g0 = ca.substitute(constraint, Fc, ca.SX.zeros(3))

    def add_mode(mode: Mode, Fc_mode):
        tag = mode.value
        rhs = ca.substitute(xdot, Fc, Fc_mode)
        R = Fc_mode[2]
        fn[f"rhs_{tag}"] = _function(f"rhs_{tag}", x, p, rhs)
        # CasADi reserves the name "jac"; see the style guide.
        fn[f"rhs_jac_{tag}"] = _function(f"rhs_jac_{tag}", x, p, ca.jacobian(rhs, x))
        fn[f"R_{tag}"] = _function(f"R_{tag}", x, p, R)
        fn[f"Rdot_{tag}"] = _function(f"Rdot_{tag}", x, p, ca.jtimes(R, x, rhs))
        fn[f"Fc_{tag}"] = _function(f"Fc_{tag}", x, p, Fc_mode)
        fn[f"friction_{tag}"] = _function(f"friction_{tag}", x, p, Fc_mode[0:2])
        return rhs, Fc_mode

    # SLIDING: Fc = Fc0 + R d, R from the constraint.
    Fc0, d = law_cls.sliding_force(slip, mu, eps)
    Fc0, d = ca.SX(Fc0), ca.SX(d)
    R_sl = -(g0 + ca.mtimes(G, Fc0)) / ca.mtimes(G, d)
    rhs_sl, _ = add_mode(Mode.SLIDING, Fc0 + R_sl * d)
    speed2 = slip[0] ** 2 + slip[1] ** 2
    fn["slip"] = _function("slip", x, p, slip)
    fn["slip_speed2"] = _function("slip_speed2", x, p, speed2)
    fn["slip_speed"] = _function("slip_speed", x, p, ca.sqrt(speed2))
    # what picks the starting mode, in one call: the slip speed and R while sliding
    fn["start_probe"] = _function("start_probe", x, p, ca.vertcat(ca.sqrt(speed2), R_sl))
    # d|u|^2/dt while sliding: extrapolates a stick event to the exact zero of the slip.
    fn["slip_speed2_rate"] = _function("slip_speed2_rate", x, p, 2 * ca.dot(slip, ca.jtimes(slip, x, rhs_sl)))
    # Guards of the stick event: the slip speed falls to STICK_SLIP (exact Coulomb), or to
    # 10 eps (regularised law, where the force then departs from Coulomb's by > 0.5%).
    # The Taylor backend uses |u| itself: as the slip vanishes under Coulomb friction |u|
    # is linear in time, and the Taylor expansion of sqrt(u.u) follows that line through
    # zero, giving a simple root (the squared form has a near-double root it can miss).
    # Pointwise integrators (CVODES) chatter at u = 0 instead, so they bracket the dip of
    # |u|^2 below a larger threshold, using its rate for Hermite interpolation.
    fn["stick_guard"] = _function("stick_guard", x, p, ca.sqrt(speed2) - (STICK_SLIP + 10 * eps))
    fn["stick_guard_sq"] = _function("stick_guard_sq", x, p, speed2 - (STICK_SLIP_POINTWISE + 10 * eps) ** 2)
    # Regularised law only: the slip has grown back above 100 eps (hysteresis against chatter).
    fn["unstick_guard"] = _function("unstick_guard", x, p, 100 * eps - ca.sqrt(speed2))

    if law_cls.has_rolling_mode:
        _build_rolling(fn, add_mode, x, p, Fc, xdot, slip, constraint, G, g0, mu)
    elif law_cls.can_stick:
        # a regularised law has one field: its "rolling" mode (slip below 10 eps) reuses it
        for name in ("rhs", "rhs_jac", "R", "Rdot", "Fc", "friction"):
            fn[f"{name}_rolling"] = fn[f"{name}_sliding"]

    _common(fn, T, x, p)
    fn["gap"] = _function("gap", x, p, ca.SX(0))
    fn["gap_rate"] = _function("gap_rate", x, p, ca.SX(0))
    _build_flight(out.flight, body, ns)
    blob = "".join(f.serialize() for d in (out.contact, out.flight) for _, f in sorted(d.items()))
    out.signature = f"{key[0]}|{law_cls.__qualname__}|{chart.name}|" + hashlib.sha256(blob.encode()).hexdigest()
    return out


def _build_rolling(fn, add_mode, x, p, Fc, xdot, slip, constraint, G, g0, mu) -> None:
    """ROLLING (exact Coulomb): the constraint and du/dt = 0 fix all three components of Fc."""
    rows = ca.vertcat(constraint, ca.jtimes(slip, x, xdot))
    M = ca.jacobian(rows, Fc)
    b = ca.substitute(rows, Fc, ca.SX.zeros(3))
    _, Fc_roll = add_mode(Mode.ROLLING, -ca.solve(M, b))
    # >= 0 while static friction can hold the no-slip constraint.
    fn["margin_rolling"] = _function("margin_rolling", x, p, mu * mu * Fc_roll[2] ** 2 - Fc_roll[0] ** 2 - Fc_roll[1] ** 2)
    # Slip acceleration when sliding starts from zero slip in direction e = (cos phi, sin phi):
    # fixes the direction in which slip develops where rolling is infeasible.
    phi = ca.SX.sym("phi")
    e = ca.vertcat(ca.cos(phi), ca.sin(phi))
    d_e = ca.vertcat(-mu * e, 1)
    R_e = -g0 / ca.mtimes(G, d_e)
    rhs_e = ca.substitute(xdot, Fc, R_e * d_e)
    fn["slip_onset"] = ca.Function("slip_onset", [x, p, phi], [ca.jtimes(slip, x, rhs_e), R_e],
                                   ["x", "p", "phi"], ["slip_acc", "R"])


def _build_flight(fn: dict, body: Body, ns: int) -> None:
    """FLIGHT: the same rigid-body equations with no contact force, in the flight chart."""
    x = ca.SX.sym("x", FLIGHT.n_states)
    p = ca.SX.sym("p", ns + 4)
    shape, A, C = p[:ns], p[ns], p[ns + 1]
    T = FLIGHT.terms(x, lambda c: body.height(c, shape), A, C, None)
    rhs = T["xdot"]
    fn["rhs_flight"] = _function("rhs_flight", x, p, rhs)
    fn["rhs_jac_flight"] = _function("rhs_jac_flight", x, p, ca.jacobian(rhs, x))
    zero = ca.SX(0)
    for name in ("R_flight", "Rdot_flight"):
        fn[name] = _function(name, x, p, zero)
    fn["Fc_flight"] = _function("Fc_flight", x, p, ca.SX.zeros(3))
    fn["friction_flight"] = _function("friction_flight", x, p, ca.SX.zeros(2))
    _common(fn, T, x, p)
    for name in ("gap", "gap_rate", "gap_acc", "Hdot"):
        fn[name] = _function(name, x, p, T[name])
    fn["L"] = _function("L", x, p, T["L"])
    slip = (ca.vertcat(x[6], x[7], 0) + ca.cross(x[3:6], T["rP"]))[0:2]  # of the lowest point
    fn["slip"] = _function("slip", x, p, slip)
    fn["slip_speed"] = _function("slip_speed", x, p, ca.norm_2(slip))
