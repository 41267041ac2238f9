"""The :class:`Model`: a body, a friction law and a chart with numeric parameters bound, over
the fields compiled once per body structure, law class and chart (:mod:`phasekit.core.fields`);
it evaluates the observables (:mod:`phasekit.core.observables`), gives the integrators their
guards and flows, and is rebuilt from its description (:func:`phasekit.bodies.by_name.make_body`: the built-in bodies
by name).
"""

from __future__ import annotations

import hashlib
import warnings

import casadi as ca
import numpy as np

from .._runtime.validate import check_array
from ..bodies.body import Body
from ..bodies.by_name import BODIES, make_body
from ..bodies.edged import Disk, EdgedBody
from ..errors import ParameterError
from ..friction.contensou import Contensou
from ..friction.dissipation import AirLayer, dissipation_from_dict
from ..friction.laws import Coulomb, FrictionLaw, RegularisedCoulomb, Viscous
from .charts import FLIGHT, POLE_GUARD, get_chart
from .fields import compiled_model
from .hybrid import CompiledFlow, CompiledGuard, Mode
from .observables import OBSERVABLES, evaluate_function


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

    Raises
    ------
    ParameterError
        If ``body`` is not a Body, ``friction`` is not a FrictionLaw, a moment of the body
        (``A`` or ``C``) exceeds M r_max^2, or ``chart`` is not "euler", "vector" or a contact
        chart.

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
        _warn_misapplied(body, friction)
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
        ``mode`` is FLIGHT.

        Parameters
        ----------
        name : str
            The name of one of the model's compiled functions (the observables and the mode
            fields, e.g. "rhs_sliding", "R_rolling", "energy").
        mode : Mode or str, optional
            FLIGHT for the functions of a flight state; otherwise (default) those of the
            contact chart.

        Returns
        -------
        casadi.Function
            The function of (x, p).

        Raises
        ------
        ParameterError
            If ``name`` is not one of the model's functions.
        ValueError
            If ``mode`` is not a mode.
        """
        fns = self.compiled.functions_of(Mode(mode) if mode is not None else Mode.SLIDING)
        if name not in fns:
            raise ParameterError("name", f"must be one of the model's functions ({', '.join(sorted(fns))})", name)
        return fns[name]

    def observable(self, name: str, mode: Mode = Mode.SLIDING) -> ca.Function:
        """The compiled observable ``name`` in ``mode``.

        Parameters
        ----------
        name : str
            A key of :data:`OBSERVABLES`.
        mode : Mode or str
            One of the model's :attr:`modes` (default SLIDING); R, Rdot and friction are
            those of this mode.

        Returns
        -------
        casadi.Function
            The observable as a function of (x, p), x a state of the mode's chart.

        Raises
        ------
        ParameterError
            If ``name`` is not an observable, or ``mode`` is not one of the model's modes.
        ValueError
            If ``mode`` is not a mode.
        """
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

        Parameters
        ----------
        name : str
            An observable (:data:`OBSERVABLES`): U, V, Omega, Lambda, theta, n (the paper's
            state), R, Rdot, friction (of the mode), slip, slip_speed, energy, jellett, L_Z,
            spin, h, W, cos_theta, gap, gap_rate.
        x : array_like
            One state (d,) or many states (m, d) of ``mode``'s chart. States must be finite,
            of the chart's length, and off the poles in the Euler chart.
        mode : {"sliding", "rolling", "flight"} or Mode
            "sliding" (default), "rolling" or "flight"; matters for R, Rdot and friction (and
            sets the chart of ``x`` for flight).

        Returns
        -------
        float or numpy.ndarray
            For one state a float (a scalar observable) or a (k,) array (slip, friction);
            for many states an (m,) or (m, k) array.

        Raises
        ------
        ParameterError
            If ``name`` is not an observable, ``mode`` is not a mode (or not one of the
            model's), or ``x`` is not finite, not of the chart's length, or has theta at 0 or
            pi in the Euler chart.
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
        """The vector field of ``mode`` at one state (d,).

        Parameters
        ----------
        x : array_like
            One state (d,) of ``mode``'s chart: finite, and off the poles in the Euler chart.
        mode : {"sliding", "rolling", "flight"} or Mode
            The mode whose field is evaluated (default "sliding"); "flight" takes a state of
            the flight chart.

        Returns
        -------
        numpy.ndarray
            dx/dt, shape (d,).

        Raises
        ------
        ParameterError
            If ``mode`` is not a mode, or ``x`` is not one finite state of the chart's length
            or has theta at 0 or pi in the Euler chart.
        """
        mode = _mode_arg(mode)
        return self._rhs(self._states_arg(x, mode, many=False), mode)

    def _rhs(self, x, mode: Mode = Mode.SLIDING) -> np.ndarray:
        mode = Mode(mode)
        return np.asarray(self.compiled.functions_of(mode)[f"rhs_{mode.value}"](x, self.p)).ravel()

    def jacobian(self, x, mode: Mode = Mode.SLIDING) -> np.ndarray:
        """The exact Jacobian of :meth:`rhs` at one state (d,).

        Parameters
        ----------
        x : array_like
            One state (d,) of ``mode``'s chart: finite, and off the poles in the Euler chart.
        mode : {"sliding", "rolling", "flight"} or Mode
            The mode whose field is differentiated (default "sliding").

        Returns
        -------
        numpy.ndarray
            d(dx/dt)/dx, shape (d, d).

        Raises
        ------
        ParameterError
            If ``mode`` is not a mode, or ``x`` is not one finite state of the chart's length
            or has theta at 0 or pi in the Euler chart.
        """
        mode = _mode_arg(mode)
        return self._jacobian(self._states_arg(x, mode, many=False), mode)

    def _jacobian(self, x, mode: Mode = Mode.SLIDING) -> np.ndarray:
        mode = Mode(mode)
        return np.asarray(self.compiled.functions_of(mode)[f"rhs_jac_{mode.value}"](x, self.p))

    def normal_reaction(self, x, mode: Mode = Mode.SLIDING):
        """R (units M g) at a state (d,) or states (m, d) of a contact mode.

        Parameters
        ----------
        x : array_like
            One state (d,) or many states (m, d) of the model's chart.
        mode : {"sliding", "rolling"} or Mode
            The contact mode (default "sliding").

        Returns
        -------
        float or numpy.ndarray
            R at the state, or an (m,) array.

        Raises
        ------
        ParameterError
            As :meth:`evaluate`.
        """
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
        """The same body and law in another chart.

        Parameters
        ----------
        chart : "euler", "vector" or a Chart
            The chart of the new model.

        Returns
        -------
        Model

        Raises
        ------
        ParameterError
            If ``chart`` is not "euler", "vector" or a contact chart.
        """
        return Model(self.body, self.friction, chart)

    def to_dict(self) -> dict:
        """The model's description, which :meth:`from_dict` reads.

        Returns
        -------
        dict
            The body's and the friction law's fields and the chart's name (``chart``).
        """
        return {**self.body.to_dict(), **self.friction.to_dict(), "chart": self.chart.name}

    @classmethod
    def from_dict(cls, d: dict) -> "Model":
        """The model a :meth:`to_dict` describes (built-in bodies and laws only; a result's
        ``model``, which :func:`phasekit.rerun` rebuilds).

        Parameters
        ----------
        d : dict
            A model's description, as :meth:`to_dict` gives it.

        Returns
        -------
        Model

        Raises
        ------
        ParameterError
            If the body or the friction law is not a built-in one (named ``model``), or the
            description's values are invalid for the body, the law or the chart.

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
        body = make_body(kind, a=d.get("a"), offset=d.get("offset"), w=d.get("w"), thickness=d.get("thickness"),
                         height=d.get("height"), on=d.get("on"), stem_length=d.get("stem_length"),
                         stem_radius=d.get("stem_radius"), flat_angle=d.get("flat_angle"), A=d["A"], C=d["C"])
        laws = {"coulomb": lambda: Coulomb(d["mu"]), "viscous": lambda: Viscous(d["mu"]),
                "coulomb-regularised": lambda: RegularisedCoulomb(d["mu"], d["slip_eps"]),
                "contensou": lambda: Contensou(d["mu"], d["patch"]["radius"], d["patch"]["pressure"],
                                                curvature=d["patch"].get("curvature", False))}
        if d.get("law") not in laws:
            raise ParameterError("model", f"must be given to rerun the friction law {d.get('law')!r} (only the built-in "
                                          "laws can be rebuilt from their description)", show_value=False)
        law = laws[d["law"]]()
        if d.get("dissipation"):
            law = law.with_dissipation(*(dissipation_from_dict(x) for x in d["dissipation"]))
        if d.get("creep") is False:
            law = law.without_creep()
        return cls(body, law, d.get("chart", d.get("formulation", "euler")))

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
        smooth in the vector chart where theta = atan2(|k_h|, k_Z) is not).

        Parameters
        ----------
        on : str
            A scalar observable (:data:`OBSERVABLES`) or a scalar model function.
        mode : Mode or str
            The mode whose functions (and chart) the guard uses.

        Returns
        -------
        casadi.Function
            g(x, p, level), cached per (on, mode).

        Raises
        ------
        ParameterError
            If ``on`` names neither an observable nor a model function, or a vector one.
        ValueError
            If ``mode`` is not a mode.
        """
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
        """The integrators' view of one flow with the events it watches (cached).

        Parameters
        ----------
        flow : Flow
            The flow (its mode, field and monitor).
        events : sequence of Event
            The events the flow watches.

        Returns
        -------
        CompiledFlow

        Raises
        ------
        ParameterError
            If an event's ``on`` is not a scalar observable or model function, or its
            ``rate`` does not name a scalar model function.
        """
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
            monitor = primitive = None
            if flow.monitor is not None:
                mf = self.guard_function(flow.monitor[0], mode)
                monitor = CompiledGuard("monitor", mf, flow.monitor[1], None, _digest(mf))
                primitive = fns.get(f"{_PRIMITIVES[flow.monitor[0]]}_{mode.value}") if flow.monitor[0] in _PRIMITIVES else None
            field = fns[flow.field]
            parts = [self.compiled.signature, mode.value, flow.field] + [f"{g.signature}:{g.direction}" for g in guards]
            parts.append(monitor.signature + f":{monitor.direction}" if monitor else "-")
            parts.append(_digest(primitive) if primitive is not None else "-")
            chart = FLIGHT if mode is Mode.FLIGHT else self.chart
            cache[key] = CompiledFlow(mode, field, chart.n_states, tuple(guards), monitor,
                                      hashlib.sha256("|".join(parts).encode()).hexdigest(), chart.rotation_rate, primitive)
        return cache[key]


#: monitors that are the time derivative of another model function (dR/dt of R): the Taylor engine
#: finds their zeros from that function's expansion, far cheaper than the monitor's own
_PRIMITIVES = {"Rdot": "R"}


def _mode_arg(mode) -> Mode:
    try:
        return Mode(mode)
    except (ValueError, TypeError):
        raise ParameterError("mode", f"must be one of {', '.join(m.value for m in Mode)}", mode) from None


def _digest(f: ca.Function) -> str:
    return hashlib.sha256(f.serialize().encode()).hexdigest()[:20]


def _warn_misapplied(body: Body, friction: FrictionLaw) -> None:
    """A dissipation law derived for one kind of body, given another, is said once: the air layer
    is Moffatt's film under a disk on its rim (phasekit/friction/dissipation.py). A patch that
    follows the curvature is refused on a body with a rim (no curvature there)."""
    if isinstance(friction, Contensou) and friction.curvature and isinstance(body, EdgedBody):
        raise ParameterError("friction", f"follows the curvature at the contact (Hertz), which a {type(body).__name__}'s "
                                         "rim does not have (it is sharp): give the patch's radius instead",
                             friction.describe())
    if any(isinstance(d, AirLayer) for d in friction.dissipation) and not isinstance(body, Disk):
        warnings.warn(f"the air layer is Moffatt's law for a disk on its rim; a {type(body).__name__} has no such film, "
                      "and its couple grows without bound as theta -> 0 (runs near the vertical crawl)", stacklevel=3)
