"""The model builder: one smooth CasADi vector field per mode, compiled once and cached.

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
per chart; :meth:`Model.evaluate` lists them.
"""

from __future__ import annotations

import hashlib
import threading
from dataclasses import dataclass, field

import casadi as ca
import numpy as np

from .._runtime.errors import ParameterError
from .._runtime.validate import check_array, check_choice
from ..bodies.body import Body, EccentricSphere, Spheroid
from ..bodies.egg import Egg
from ..friction.laws import Coulomb, FrictionLaw, RegularisedCoulomb, Viscous
from .charts import FLIGHT, PAPER_NAMES, POLE_GUARD, Chart, get_chart
from .hybrid import CompiledFlow, CompiledGuard, Mode

__all__ = ["Model", "CompiledModel", "compiled_model", "evaluate_function", "OBSERVABLES", "STICK_SLIP", "STICK_SLIP_POINTWISE",
           "make_body", "BODIES", "snapshot", "install"]

#: slip speed (units sqrt(g b)) at which exact Coulomb sliding is taken to have stuck;
#: the stick time is then extrapolated to the exact zero of the slip
STICK_SLIP = 1e-10
#: the same for integrators that evaluate the field pointwise (CVODES), which chatter at u = 0
STICK_SLIP_POINTWISE = 1e-7

#: observables every mode provides, for :meth:`Model.evaluate`, events and trajectory samples
OBSERVABLES = {
    **{name: f"the paper's state variable {name}" for name in PAPER_NAMES},
    "R": "normal reaction of the mode in force (0 in flight), units M g",
    "Rdot": "dR/dt in the mode in force",
    "friction": "horizontal friction force (F_1, F_2) of the mode in force, units M g",
    "slip": "slip velocity of the contact point (2-vector)",
    "slip_speed": "|slip velocity| of the contact point",
    "energy": "total energy (kinetic + potential), units M g b",
    "jellett": "Jellett's integral -L.GP (angular momentum about G dotted with P->G; A Omega h in the gyroscopic limit (3.17))",
    "L_Z": "vertical angular momentum about G",
    "spin": "spin n = w.k",
    "h": "height of G above the table, units b (in flight: h(theta), the gap excluded)",
    "W": "vertical velocity of G",
    "cos_theta": "cos(theta)",
    "gap": "height of the lowest point above the table (0 in contact)",
    "gap_rate": "rate of the gap (0 in contact)",
}


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


def evaluate_function(f: ca.Function, p: np.ndarray, x):
    """f(x, p) for one state (d,) -> float or (k,), or for many states (m, d) -> (m,) or (m, k)."""
    X = np.asarray(x, dtype=float)
    if X.ndim == 1:
        r = np.asarray(f(X, p))
        return float(r.item()) if r.size == 1 else r.ravel()
    if X.shape[0] == 0:
        return np.empty((0,) if f.numel_out(0) == 1 else (0, f.numel_out(0)))
    r = np.asarray(f.map(X.shape[0])(X.T, np.tile(p[:, None], (1, X.shape[0]))))
    return r.ravel() if r.shape[0] == 1 else r.T


class Model:
    """A body, a friction law and a chart, with numeric parameters bound.

    Parameters
    ----------
    body : Body
        e.g. ``Spheroid(1.5)``, ``EccentricSphere(0.3)`` or a :class:`CustomBody`.
    friction : FrictionLaw
        ``Coulomb(mu)`` (exact stick-slip), ``RegularisedCoulomb(mu, eps)`` or ``Viscous(mu)``.
    chart : "euler", "vector" or a Chart
        Coordinates: the paper's (2.7), or the singularity-free Newton-Euler form.

    Examples
    --------
    >>> import phasekit as pk
    >>> m = pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.1))
    >>> m
    Model(Spheroid(a=1.5), coulomb(mu=0.1), chart='euler')
    >>> m.state_names
    ('U', 'V', 'Omega', 'Lambda', 'theta', 'n')
    """

    def __init__(self, body: Body, friction: FrictionLaw, chart="euler"):
        if not isinstance(body, Body):
            raise ParameterError("body", "must be a phasekit Body such as Spheroid(a)", body)
        if not isinstance(friction, FrictionLaw):
            raise ParameterError("friction", "must be a phasekit FrictionLaw such as Coulomb(mu)", friction)
        body.check_inertia()
        self.body = body
        self.friction = friction
        self.chart = get_chart(chart)
        self.compiled = compiled_model(body, friction, self.chart)
        self.p = np.concatenate([body.params, friction.params])

    # -- structure --------------------------------------------------------------------------
    @property
    def state_names(self) -> tuple[str, ...]:
        return self.chart.state_names

    @property
    def n_states(self) -> int:
        return self.chart.n_states

    @property
    def modes(self) -> tuple[Mode, ...]:
        """The modes of this law: SLIDING, ROLLING (laws that can stick) and FLIGHT."""
        return self.compiled.modes

    def function(self, name: str, mode: Mode | None = None) -> ca.Function:
        """A compiled function by name: of a contact state, or of a flight state when
        ``mode`` is FLIGHT."""
        fns = self.compiled.functions_of(Mode(mode) if mode is not None else Mode.SLIDING)
        if name not in fns:
            raise ParameterError("name", f"must be one of the model's functions ({', '.join(sorted(fns))})", name)
        return fns[name]

    def observable(self, name: str, mode: Mode = Mode.SLIDING) -> ca.Function:
        """The compiled observable ``name`` (see :data:`OBSERVABLES`) in ``mode``."""
        mode = Mode(mode)
        if name not in OBSERVABLES:
            raise ParameterError("name", f"must be one of {', '.join(OBSERVABLES)}", name)
        if mode not in self.modes:
            raise ParameterError("mode", f"must be one of {', '.join(m.value for m in self.modes)}", mode.value)
        fns = self.compiled.functions_of(mode)
        if name in ("R", "Rdot", "friction"):
            return fns[f"{name}_{mode.value}"]
        return fns[name]

    # -- evaluation -------------------------------------------------------------------------
    def evaluate(self, name: str, x, mode: Mode = Mode.SLIDING):
        """Evaluate an observable at a state (d,) or at many states (m, d) of ``mode``'s chart.

        Names (:data:`OBSERVABLES`): U, V, Omega, Lambda, theta, n (the paper's state), R,
        Rdot, friction (of the mode), slip, slip_speed, energy, jellett, L_Z, spin, h, W,
        cos_theta, gap, gap_rate. ``mode`` is "sliding" (default), "rolling" or "flight"
        and matters for R, Rdot and friction (and sets the chart of ``x`` for flight).
        States must be finite, of the chart's length, and off the poles in the Euler chart.
        """
        if not isinstance(name, str):
            raise ParameterError("name", f"must be one of {', '.join(OBSERVABLES)}", name)
        mode = _mode_arg(mode)
        fn = self._function_of(name, mode)
        return evaluate_function(fn, self.p, self._states_arg(x, mode))

    def _function_of(self, name: str, mode: Mode) -> ca.Function:
        if name in OBSERVABLES:
            return self.observable(name, mode)
        fns = self.compiled.functions_of(mode)
        if name in fns:  # an internal function (guards, rates): allowed, not advertised
            return fns[name]
        raise ParameterError("name", f"must be one of {', '.join(OBSERVABLES)}", name)

    def _evaluate(self, name: str, x, mode: Mode = Mode.SLIDING):
        """:meth:`evaluate` without the checks of its arguments (for phasekit's own calls)."""
        return evaluate_function(self._function_of(name, Mode(mode)), self.p, x)

    def rhs(self, x, mode: Mode = Mode.SLIDING) -> np.ndarray:
        """The vector field of ``mode`` at one state (d,)."""
        mode = _mode_arg(mode)
        return self._rhs(self._states_arg(x, mode, many=False), mode)

    def _rhs(self, x, mode: Mode = Mode.SLIDING) -> np.ndarray:
        mode = Mode(mode)
        return np.asarray(self.compiled.functions_of(mode)[f"rhs_{mode.value}"](x, self.p)).ravel()

    def jacobian(self, x, mode: Mode = Mode.SLIDING) -> np.ndarray:
        """The exact Jacobian of :meth:`rhs` at one state (d,)."""
        mode = _mode_arg(mode)
        return self._jacobian(self._states_arg(x, mode, many=False), mode)

    def _jacobian(self, x, mode: Mode = Mode.SLIDING) -> np.ndarray:
        mode = Mode(mode)
        return np.asarray(self.compiled.functions_of(mode)[f"rhs_jac_{mode.value}"](x, self.p))

    def normal_reaction(self, x, mode: Mode = Mode.SLIDING):
        """R (units M g) at a state (d,) or states (m, d) of a contact mode."""
        return self.evaluate("R", x, mode)

    def _states_arg(self, x, mode: Mode, many: bool = True) -> np.ndarray:
        chart = FLIGHT if mode is Mode.FLIGHT else self.chart
        n = chart.n_states
        X = check_array("x", x, allow_empty=many)
        if X.ndim not in ((1, 2) if many else (1,)) or X.shape[-1] != n:
            shape = f"one state of {n} entries" + (f" or an (m, {n}) array of states" if many else "")
            raise ParameterError("x", f"must be {shape} (the {chart.name} chart of the {mode.value} mode; got shape "
                                      f"{X.shape})", show_value=False)
        if mode is not Mode.FLIGHT and not chart.regular_at_poles and X.size:
            if np.any(np.abs(np.sin(X[..., 4])) < POLE_GUARD):  # theta may wind past pi along a run
                raise ParameterError("x", "has theta at 0 or pi, where the Euler chart is singular (2.7c): use "
                                          "Model(body, law, chart='vector')", show_value=False)
        return X

    def with_chart(self, chart) -> "Model":
        """The same body and law in another chart."""
        return Model(self.body, self.friction, chart)

    def to_dict(self) -> dict:
        return {**self.body.to_dict(), **self.friction.to_dict(), "chart": self.chart.name}

    @classmethod
    def from_dict(cls, d: dict) -> "Model":
        """The model a :meth:`to_dict` describes (built-in bodies and laws only; a result's
        ``model``, which :func:`phasekit.rerun` rebuilds).

        Examples
        --------
        >>> import phasekit as pk
        >>> m = pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.1))
        >>> pk.Model.from_dict(m.to_dict()) == m
        True
        """
        kind = d.get("body")
        if kind not in BODIES:
            raise ParameterError("model", f"must be given to rerun a {kind or 'user-defined'} body (only the built-in "
                                          "bodies can be rebuilt from their description)", show_value=False)
        body = make_body(kind, a=d.get("a"), offset=d.get("offset"), w=d.get("w"), A=d["A"], C=d["C"])
        laws = {"coulomb": lambda: Coulomb(d["mu"]), "viscous": lambda: Viscous(d["mu"]),
                "coulomb-regularised": lambda: RegularisedCoulomb(d["mu"], d["slip_eps"])}
        if d.get("law") not in laws:
            raise ParameterError("model", f"must be given to rerun the friction law {d.get('law')!r} (only the built-in "
                                          "laws can be rebuilt from their description)", show_value=False)
        return cls(body, laws[d["law"]](), d.get("chart", d.get("formulation", "euler")))

    def __eq__(self, other) -> bool:
        return isinstance(other, Model) and (other.body, other.friction, other.chart) == (self.body, self.friction, self.chart)

    def __hash__(self) -> int:
        return hash((self.body, self.friction, self.chart.name))

    def __repr__(self) -> str:
        return f"Model({self.body!r}, {self.friction.describe()}, chart={self.chart.name!r})"

    # -- what the integrators see ---------------------------------------------------------------
    def guard_function(self, on: str, mode: Mode) -> ca.Function:
        """g(x, p, level) for an event on ``on`` in ``mode``: the observable minus the level,
        except theta, watched as cos(level) - cos(theta) (the same zero and direction, and
        smooth in the vector chart where theta = atan2(|k_h|, k_Z) is not)."""
        mode = Mode(mode)
        key = (on, mode)
        cache = self.compiled.guards
        if key not in cache:
            fns = self.compiled.functions_of(mode)
            if on in ("R", "Rdot", "friction"):
                f = fns[f"{on}_{mode.value}"]
            elif on in fns and on != "theta":
                f = fns[on]
            elif on != "theta":
                names = ", ".join(OBSERVABLES)
                raise ParameterError("on", f"must name an observable ({names}) or a model guard function", on)
            if on != "theta" and f.numel_out(0) != 1:
                raise ParameterError("on", "must name a scalar observable (slip and friction are vectors; use slip_speed)", on)
            chart = FLIGHT if mode is Mode.FLIGHT else self.chart
            x, p, lv = ca.SX.sym("x", chart.n_states), ca.SX.sym("p", self.compiled.n_params), ca.SX.sym("level")
            if on == "theta":
                g = ca.cos(lv) - fns["cos_theta"](x, p)
            else:
                g = f(x, p) - lv
            cache[key] = ca.Function(f"guard_{on}_{mode.value}", [x, p, lv], [g], ["x", "p", "level"], ["g"])
        return cache[key]

    def compile_flow(self, flow, events) -> CompiledFlow:
        """The integrators' view of one flow with the events it watches (cached)."""
        key = (flow, tuple((e.on, e.direction, e.rate) for e in events))
        cache = self.compiled.flows
        if key not in cache:
            mode = flow.mode
            fns = self.compiled.functions_of(mode)
            guards = []
            for e in events:
                gf = self.guard_function(e.on, mode)
                rate = None
                if e.rate:
                    rate = fns.get(f"{e.rate}_{mode.value}" if e.rate in ("R", "Rdot") else e.rate)
                    if rate is None or rate.numel_out(0) != 1:
                        scalar = sorted(k for k, f in fns.items() if f.n_in() == 2 and f.numel_out(0) == 1 and "jac" not in k)
                        raise ParameterError("rate", f"must name a scalar model function ({', '.join(scalar)})", e.rate)
                guards.append(CompiledGuard(e.name, gf, e.direction, rate, _digest(gf) + (_digest(rate) if rate else "")))
            monitor = None
            if flow.monitor is not None:
                mf = self.guard_function(flow.monitor[0], mode)
                monitor = CompiledGuard("monitor", mf, flow.monitor[1], None, _digest(mf))
            field = fns[flow.field]
            parts = [self.compiled.signature, mode.value, flow.field] + [f"{g.signature}:{g.direction}" for g in guards]
            parts.append(monitor.signature + f":{monitor.direction}" if monitor else "-")
            chart = FLIGHT if mode is Mode.FLIGHT else self.chart
            cache[key] = CompiledFlow(mode, field, chart.n_states, tuple(guards), monitor,
                                      hashlib.sha256("|".join(parts).encode()).hexdigest(), chart.rotation_rate)
        return cache[key]


#: the built-in bodies, by the name the CLI's --body and a model's description use
BODIES = ("spheroid", "tippe-top", "egg")


def make_body(kind: str = "spheroid", *, a=None, offset=None, w=None, A=None, C=None) -> Body:
    """A built-in body by name: ``spheroid`` (a, offset), ``tippe-top`` (offset), ``egg`` (a, w)
    (the CLI's ``--body``, and :meth:`Model.from_dict`)."""
    check_choice("body", kind, BODIES)
    given = {"a": a, "offset": offset, "w": w}
    allowed = {"spheroid": ("a", "offset"), "tippe-top": ("offset",), "egg": ("a", "w")}[kind]
    for name, value in given.items():
        if value is not None and name not in allowed:
            raise ParameterError(name, f"does not apply to the {kind} body (its parameters: {', '.join(allowed)})", value)
    if kind == "spheroid":
        if a is None:
            raise ParameterError("a", "is required for the spheroid body (aspect ratio, > 0)", show_value=False)
        return Spheroid(a, A=A, C=C, offset=0.0 if offset is None else offset)
    if kind == "tippe-top":
        if offset is None:
            raise ParameterError("offset", "is required for the tippe-top body (centre of mass below the centre, in [0, 1))",
                                 show_value=False)
        return EccentricSphere(offset, A=A, C=C)
    return Egg(1.3 if a is None else a, 0.0 if w is None else w, A=A, C=C)


def _mode_arg(mode) -> Mode:
    try:
        return Mode(mode)
    except (ValueError, TypeError):
        raise ParameterError("mode", f"must be one of {', '.join(m.value for m in Mode)}", mode) from None


def _digest(f: ca.Function) -> str:
    return hashlib.sha256(f.serialize().encode()).hexdigest()[:20]
