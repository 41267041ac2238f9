"""The compiled fields: one smooth CasADi vector field per mode and chart, built symbolically
once per (body structure, law class, chart) and cached.

Given a chart (:mod:`phasekit.core.charts`), the state derivative is affine in the contact
force Fc = (F_1, F_2, R). Each mode adds the equations that fix Fc:

* every contact mode: the contact constraint R = 1 + dW/dt, (2.8);
* SLIDING: the friction law, Fc = Fc0(u) + R d(u) (:mod:`phasekit.friction.laws`), which
  leaves one linear equation for R; for Coulomb friction this is (6.1);
* ROLLING (exact Coulomb): the no-slip constraint du/dt = 0, which with (2.8) is a 3x3
  linear system for Fc (solved symbolically);
* EDGE (exact Coulomb): sliding on the edge of the friction cone, the slip's direction slaved
  to the dynamics (:mod:`phasekit.core.cone_edge`);
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
from typing import NamedTuple

import casadi as ca

from ..bodies.body import Body
from ..friction.dissipation import RollingResistance, SpinFriction
from ..friction.laws import FrictionLaw
from .charts import FLIGHT, PAPER_NAMES, Chart
from .cone_edge import build_edge
from .hybrid import Mode

#: slip speed (units sqrt(g b)) at which exact Coulomb sliding is taken to have stuck;
#: the stick time is then extrapolated to the exact zero of the slip
STICK_SLIP = 1e-10
#: the same for integrators that evaluate the field pointwise (CVODES), which chatter at u = 0
STICK_SLIP_POINTWISE = 1e-7
#: the speed of the motion, sqrt(|w|^2 + |v|^2) (units sqrt(g b)), at which a dissipative run
#: is taken to have come to rest; the time of rest is extrapolated to its exact zero
REST_SPEED = 1e-7
#: the spin about the normal, or the rolling rate (units sqrt(g/b)), at which spin friction or
#: rolling resistance is taken to have stopped it (the time is extrapolated to its zero). Well
#: above the couples' regularisation SIGN_EPS = 1e-9: held by the regularised couple, the rate
#: creeps at about SIGN_EPS rho/sqrt(1 - rho^2), rho the couple needed over the most the law
#: gives, which stays below 1e-6 for every rho < 1 - 5e-7
HOLD_RATE = 1e-6


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
    """Build (or fetch from the cache) the compiled model of a body structure, law structure
    (its class and the kinds of its dissipation laws) and chart."""
    structure = law.structure
    key = (body.structure_key, structure[0] if len(structure) == 1 else structure, chart.name)
    with _LOCK:
        if key not in _CACHE:
            _CACHE[key] = _build(body, type(law), chart, key, law.dissipation, law.creeps)
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


class ContactGeometry(NamedTuple):
    """What a law over the contact patch needs of the body where it touches: r, the vector from G
    to the contact point, and radii, the product rho1 rho2 of the surface's principal radii there."""

    r: ca.SX
    radii: ca.SX


def contact_point(H, laws, k):
    """The :class:`ContactGeometry` at the contact, for the laws that need it (friction over a patch;
    None when none does): r_P = -H'(c) (k - c e_Z) - H(c) e_Z, c = k_Z (as in
    :meth:`phasekit.core.charts.VectorChart.rigid_terms`), and the principal radii rho1 = H - c H' +
    (1 - c^2) H'' (meridional), rho2 = H - c H' (parallel, Meusnier: x_P / sin(theta)), as
    :func:`phasekit.friction.hertz.principal_radii` with d/dtheta = -sin(theta) d/dc."""
    if not any(law.needs_contact_point for law in laws):
        return None
    cs, c, ez = ca.SX.sym("c"), k[2], ca.vertcat(0, 0, 1)
    Hs = H(cs)
    H1 = ca.jacobian(Hs, cs)
    Hc, dH, ddH = (ca.substitute(e, cs, c) for e in (Hs, H1, ca.jacobian(H1, cs)))
    rho2 = Hc - c * dH
    return ContactGeometry(-dH * (k - c * ez) - Hc * ez, (rho2 + (1 - c * c) * ddH) * rho2)


def _wrench(laws, p, first: int, H):
    """The dissipation laws' total wrench (f, couple) as a function of (w, v, R, k), k the body's
    axis, each law reading its coefficients from p after index ``first``; None without laws."""
    if not laws:
        return None

    def wrench(w, v, R, k):
        f, G, i, r = ca.SX.zeros(3), ca.SX.zeros(3), first, contact_point(H, laws, k)
        for law in laws:
            fi, Gi = law.wrench_at(w, v, R, p[i:i + law.n_params], k, r)
            f, G, i = f + fi, G + Gi, i + law.n_params
        return f, G

    return wrench


#: what _dissipation_terms adds to each contact mode
DISSIPATION_TERMS = ("motion_rate", "pivot_rate", "roll_rate", "power")


def _dissipation_terms(fn, tag, T, x, p, rhs, Fc_mode, laws, first) -> None:
    """A mode's power of sliding friction, then of each dissipation law; the rates of the motion's
    speed and of the spin about the normal (what the rest and pivot events extrapolate with)."""
    fn[f"motion_rate_{tag}"] = _function(f"motion_rate_{tag}", x, p, ca.jtimes(_motion(T), x, rhs))
    for kind, (_, _, part) in HELD.items():
        speed = ca.sqrt(ca.sumsqr(T["w"][part]) + 1e-40)
        fn[f"{kind}_rate_{tag}"] = _function(f"{kind}_rate_{tag}", x, p, ca.jtimes(speed, x, rhs))
    power = [ca.dot(Fc_mode[0:2], T["slip"])]  # the slip and w, v depend on the state only
    power += _powers(laws, p, first, T["w"], T["v"], Fc_mode[2], T["k"], T["r_P"])
    fn[f"power_{tag}"] = _function(f"power_{tag}", x, p, ca.vertcat(*power))


def _powers(laws, p, first: int, w, v, R, k, r):
    """Each dissipation law's power f.v + couple.w, in order (k: the body's axis, r: the contact
    point from G, for the laws that need it)."""
    out, i = [], first
    for law in laws:
        out.append(law.power(w, v, R, p[i:i + law.n_params], k, r))
        i += law.n_params
    return out


def _build(body: Body, law_cls: type[FrictionLaw], chart: Chart, key, laws=(), creep: bool = False) -> CompiledModel:
    nx, ns = chart.n_states, body.n_shape
    n_params = ns + 4 + sum(d.n_params for d in laws)
    x = ca.SX.sym("x", nx)
    p = ca.SX.sym("p", n_params)
    Fc = ca.SX.sym("Fc", 3)
    shape, A, C, mu, eps = p[:ns], p[ns], p[ns + 1], p[ns + 2], p[ns + 3]

    def H(c):
        return body.height(c, shape)

    T = chart.terms(x, H, A, C, Fc, _wrench(laws, p, ns + 4, H))
    T["r_P"] = contact_point(H, laws, T["k"])
    xdot, slip = T["xdot"], T["slip"]
    modes = [Mode.SLIDING, Mode.ROLLING] if law_cls.can_stick else [Mode.SLIDING]
    # exact Coulomb with dissipation laws: sliding on the cone's edge, and off it (cone_edge). Rolling
    # resistance and spin friction hold a rolling body on the cone's edge for long stretches (where exact
    # Coulomb alone leaves it at once): there the slip onset's nudge chattered. Without them the slip onset
    # is as it was, and so is every committed result of exact Coulomb alone (with EDGE there 13 of
    # figure5_gap's 130 rows moved, the gap by up to 16%: a jump after stick-slip is sensitive to it)
    edge = law_cls.has_rolling_mode and bool(laws)
    if edge:
        modes += [Mode.EDGE, Mode.OFF_EDGE]
    out = CompiledModel(chart=chart, n_params=n_params, modes=(*modes, Mode.FLIGHT), key=key)
    fn = out.contact

    # Contact constraint R + lift - 1 - dW/dt = 0 (lift: the air's), affine in Fc: G.Fc + g0 = 0.
    constraint = (Fc[2] + T["lift"] if laws else Fc[2]) - 1 - ca.jtimes(T["W"], x, xdot)
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
        if laws:
            _dissipation_terms(fn, tag, T, x, p, rhs, Fc_mode, laws, ns + 4)
        return rhs, Fc_mode

    # SLIDING: Fc = Fc0 + R d, R from the constraint.
    Fc0, d = law_cls.sliding_force(slip, mu, eps)
    Fc0, d = ca.SX(Fc0), ca.SX(d)
    R_sl = -(g0 + ca.mtimes(G, Fc0)) / ca.mtimes(G, d)
    rhs_sl, _ = add_mode(Mode.SLIDING, Fc0 + R_sl * d)
    if edge:  # OFF_EDGE: SLIDING's field under its own name
        for name in ("rhs", "rhs_jac", "R", "Rdot", "Fc", "friction", *(DISSIPATION_TERMS if laws else ())):
            fn[f"{name}_{Mode.OFF_EDGE.value}"] = fn[f"{name}_sliding"]
    _build_slip(fn, x, p, slip, rhs_sl, R_sl, eps)

    _build_zero_slip(fn, add_mode, law_cls, creep, bool(laws), x, p, Fc, T, constraint, G, g0, mu, eps)

    _common(fn, T, x, p)
    fn["gap"] = _function("gap", x, p, ca.SX(0))
    fn["gap_rate"] = _function("gap_rate", x, p, ca.SX(0))
    if laws:  # rest, and the modes with a part of w held (spin friction, rolling resistance)
        _build_rest(fn, T, x, p, ns, laws)
        out.modes = (*modes, *(m for k in HELD for m in _build_held(fn, chart, x, p, Fc, H, laws, law_cls, ns, k)), Mode.FLIGHT)
    _build_flight(out.flight, body, ns, laws)
    blob = "".join(f.serialize() for d in (out.contact, out.flight) for _, f in sorted(d.items()))
    names = "+".join([law_cls.__qualname__, *(type(d).__qualname__ for d in laws)])
    out.signature = f"{key[0]}|{names}|{chart.name}|" + hashlib.sha256(blob.encode()).hexdigest()
    return out


def _build_slip(fn, x, p, slip, rhs_sl, R_sl, eps) -> None:
    """The slip and what watches it: its speed, the starting mode's probe and the stick and
    unstick guards."""
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


#: the components of w a set-valued law can hold at zero: its law, the modes (sliding, rolling)
#: with them held, and the index of w's components in axes with e_Z vertical
HELD = {"pivot": (SpinFriction, (Mode.SLIDING_NO_PIVOT, Mode.ROLLING_NO_PIVOT), slice(2, 3)),
        "roll": (RollingResistance, (Mode.SLIDING_NO_ROLL, Mode.PIVOTING), slice(0, 2))}


def _build_held(fn, chart, x, p, Fc, H, laws, law_cls, ns, kind: str) -> tuple[Mode, ...]:
    """The modes in which a set-valued law holds its part of w at zero: spin friction the spin
    about the normal w_Z ("pivot"), rolling resistance the rolling part w_h ("roll"). Its couple
    tau is then an unknown fixed by d(that part)/dt = 0 (with the contact constraint, and with
    du/dt = 0 when the slip is zero too), and it holds while |tau| <= coefficient x R."""
    cls, (m_slide, m_roll), part = HELD[kind]
    if not any(isinstance(d, cls) for d in laws):
        return ()
    A, C, mu, eps = p[ns], p[ns + 1], p[ns + 2], p[ns + 3]
    offsets = _offsets(laws, ns + 4)
    coef = next(p[i] for law, i in offsets if isinstance(law, cls))
    free = [(law, i) for law, i in offsets if not isinstance(law, cls)]
    n_tau = part.stop - part.start
    tau = ca.SX.sym("tau", n_tau)
    couple = ca.vertcat(0, 0, tau) if kind == "pivot" else ca.vertcat(tau, 0)

    def wrench(w, v, R, k):
        f, G, r = ca.SX.zeros(3), couple, contact_point(H, laws, k)
        for law, i in free:
            fi, Gi = law.wrench_at(w, v, R, p[i:i + law.n_params], k, r)
            f, G = f + fi, G + Gi
        return f, G

    T = chart.terms(x, H, A, C, Fc, wrench)
    xdot, slip = T["xdot"], T["slip"]
    constraint = Fc[2] + T["lift"] - 1 - ca.jtimes(T["W"], x, xdot)
    hold = ca.jtimes(T["w"][part], x, xdot)
    z = ca.vertcat(Fc, tau)

    def add(mode, rows, Fc_of, unknowns):
        sol = -ca.solve(ca.jacobian(rows, unknowns), ca.substitute(rows, unknowns, ca.SX.zeros(unknowns.numel())))
        Fc_m, tau_m = Fc_of(sol), sol[sol.numel() - n_tau:]
        sub = ca.vertcat(Fc_m, tau_m)
        rhs = ca.substitute(xdot, z, sub)
        tag, R = mode.value, Fc_m[2]
        for name, expr in (("rhs", rhs), ("rhs_jac", ca.jacobian(rhs, x)), ("R", R), ("Rdot", ca.jtimes(R, x, rhs)),
                           ("Fc", Fc_m), ("friction", Fc_m[0:2]), ("motion_rate", ca.jtimes(_motion(T), x, rhs)),
                           (f"{kind}_margin", coef * coef * R * R - ca.dot(tau_m, tau_m)), (f"{kind}_couple", tau_m)):
            fn[f"{name}_{tag}"] = _function(f"{name}_{tag}", x, p, ca.substitute(expr, z, sub))
        w, v, r_P = T["w"], T["v"], contact_point(H, laws, T["k"])
        power = [ca.dot(Fc_m[0:2], slip)] + [law.power(w, v, R, p[i:i + law.n_params], T["k"], r_P) if not isinstance(law, cls)
                                             else ca.dot(tau_m, w[part]) for law, i in _offsets(laws, ns + 4)]
        fn[f"power_{tag}"] = _function(f"power_{tag}", x, p, ca.substitute(ca.vertcat(*power), z, sub))
        return Fc_m

    # sliding: Fc = Fc0 + R d; the unknowns R and tau
    Fc0, d = law_cls.sliding_force(slip, mu, eps)
    Fc0, d = ca.SX(Fc0), ca.SX(d)
    R_, t_ = ca.SX.sym("R"), ca.SX.sym("t", n_tau)
    rows = ca.substitute(ca.vertcat(constraint, hold), z, ca.vertcat(Fc0 + R_ * d, t_))
    add(m_slide, rows, lambda sol: ca.substitute(Fc0 + R_ * d, ca.vertcat(R_, t_), sol), ca.vertcat(R_, t_))
    if law_cls.has_rolling_mode:  # zero slip too: all of Fc and tau
        Fc_r = add(m_roll, ca.vertcat(constraint, ca.jtimes(slip, x, xdot), hold), lambda sol: sol[0:3], z)
        fn[f"margin_{m_roll.value}"] = _function(f"margin_{m_roll.value}", x, p,
                                                 mu * mu * Fc_r[2] ** 2 - Fc_r[0] ** 2 - Fc_r[1] ** 2)
        return m_slide, m_roll
    if law_cls.can_stick:  # a regularised law: its "rolling" is its sliding field
        for name in ("rhs", "rhs_jac", "R", "Rdot", "Fc", "friction", "motion_rate", f"{kind}_margin", f"{kind}_couple",
                     "power"):
            fn[f"{name}_{m_roll.value}"] = fn[f"{name}_{m_slide.value}"]
        return m_slide, m_roll
    return (m_slide,)


def _offsets(laws, first):
    out = []
    for law in laws:
        out.append((law, first))
        first += law.n_params
    return out


def _motion(T):
    w, v = T["w"], T["v"]
    return ca.sqrt(ca.dot(w, w) + ca.dot(v, v))


def _build_rest(fn, T, x, p, ns, laws) -> None:
    """What decides that the body has come to rest (:mod:`phasekit.core.system`): the speed of
    its motion sqrt(|w|^2 + |v|^2), and the rolling couple needed to hold it still where it
    stands (the weight's moment about the contact point, R = 1) against what rolling resistance
    can give (delta; 0 without it)."""
    speed = _motion(T)
    fn["motion"] = _function("motion", x, p, speed)
    fn["rest_guard"] = _function("rest_guard", x, p, speed - REST_SPEED)
    i, delta = ns + 4, ca.SX(0)
    for law in laws:
        if isinstance(law, RollingResistance):
            delta = p[i]
        i += law.n_params
    # |x_P|: the horizontal distance of G from the contact point, the weight's lever arm
    fn["rest_margin"] = _function("rest_margin", x, p, delta - T["lever"])
    # the held parts of w: |w_Z| (spin friction) and |w_h| (rolling resistance) fall to HOLD_RATE
    # (see resets.Hold); CasADi turns sqrt(w_Z^2) into fabs, which heyoka cannot take: 1e-40 is
    # far below rounding
    for kind, (_, _, part) in HELD.items():
        speed = ca.sqrt(ca.sumsqr(T["w"][part]) + 1e-40)
        fn[f"{kind}_speed"] = _function(f"{kind}_speed", x, p, speed)
        fn[f"{kind}_guard"] = _function(f"{kind}_guard", x, p, speed - HOLD_RATE)


def _build_zero_slip(fn, add_mode, law_cls, creep, laws, x, p, Fc, T, constraint, G, g0, mu, eps) -> None:
    """The ROLLING mode: exact Coulomb's no-slip mode; a stiff regularised law's creep; for another
    regularised law its own field under that name (the slip below 10 eps)."""
    xdot, slip = T["xdot"], T["slip"]
    if law_cls.has_rolling_mode:
        _build_rolling(fn, add_mode, x, p, Fc, xdot, slip, constraint, G, g0, mu, T["frame_rate"], bool(laws))
    elif creep:
        _build_creep(fn, add_mode, x, p, Fc, xdot, slip, constraint, mu, eps, T["frame_rate"])
    elif law_cls.can_stick:
        for name in ("rhs", "rhs_jac", "R", "Rdot", "Fc", "friction", *(DISSIPATION_TERMS if laws else ())):
            fn[f"{name}_rolling"] = fn[f"{name}_sliding"]


def _build_rolling(fn, add_mode, x, p, Fc, xdot, slip, constraint, G, g0, mu, frame_rate, edge: bool) -> None:
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
    if edge:  # with dissipation laws (see _build)
        build_edge(fn, add_mode, _function, x, p, Fc, xdot, slip, constraint, mu, Fc_roll, frame_rate)


#: the rate (units sqrt(g/b)) at which the creep field pulls the slip onto the slow manifold u*(x):
#: fast against the motion's slow drift, slow against the law's own relaxation mu R/eps
CREEP_PULL = 20.0
#: the creep holds while the law's relaxation rate on its slow manifold (see _build_creep) exceeds
#: the smaller (a smooth minimum) of CREEP_STIFF, above which the law's own field is stiff for the
#: Taylor method, and CREEP_RATIO times 1 + |du*/dt|/|u*|, the rate at which the slow manifold moves:
#: the slip lags u* by that rate over the relaxation rate, which is the reduction's relative error
#: (docs/physics.md)
CREEP_STIFF = 2000.0
CREEP_RATIO = 100.0


def _build_creep(fn, add_mode, x, p, Fc, xdot, slip, constraint, mu, eps, frame_rate) -> None:
    """ROLLING of a regularised law: creep on its slow manifold, non-stiff (docs/physics.md derives it).

    With |u| << mu R/|dF/dt|, F = -mu R u/sqrt(|u|^2 + eps^2) relaxes the slip at a rate ~ mu R/eps
    onto u*(x) = -eps F/sqrt(mu^2 R^2 - |F|^2), the slip that gives the force F needed (the law
    inverted). The creep field imposes du/dt = du*/dt - CREEP_PULL (u - u*), with u* from the
    rolling force F_roll(x) and its rate along the rolling field (Tikhonov's reduction, first order:
    the field differs from the law's on its slow manifold by O(eps^2)), so that it keeps the creep's
    dissipation F.u* = -eps |F|^2/sqrt(mu^2 R^2 - |F|^2), which decides where a long creep ends,
    without the law's stiffness. It holds while the manifold attracts fast (``creep_margin``)."""
    rows = ca.vertcat(constraint, ca.jtimes(slip, x, xdot))
    M = ca.jacobian(rows, Fc)
    b = ca.substitute(rows, Fc, ca.SX.zeros(3))
    Fc_roll = -ca.solve(M, b)
    rhs_roll = ca.substitute(xdot, Fc, Fc_roll)
    room = (mu * Fc_roll[2]) ** 2 - ca.sumsqr(Fc_roll[0:2])
    u_star = -eps * Fc_roll[0:2] / ca.sqrt(room)
    du_star = ca.jtimes(u_star, x, rhs_roll)
    target = ca.vertcat(0, du_star - CREEP_PULL * (slip - u_star))
    add_mode(Mode.ROLLING, -ca.solve(M, b - target))
    # >= 0 while the slow manifold attracts fast enough (CREEP_STIFF, CREEP_RATIO): the law's relaxation
    # rate there, mu R (1 - f^2)^(3/2)/eps with f = |F|/(mu R), falls as R -> 0 or f -> 1, where creep ends.
    # The manifold's own rate |du*/dt|/|u*|, not the body's |w|: a fast spin about a near-vertical axis
    # turns the force needed slowly (about 2 against |w| = 13 on a = 3, Omega0 = 7.4). Its rate in
    # fixed axes, the same in every chart: the chart's axes turn at frame_rate about the vertical
    turning = frame_rate * ca.vertcat(-u_star[1], u_star[0])
    size, drift = ca.norm_2(u_star), ca.norm_2(du_star + turning)
    needed = (CREEP_STIFF ** -8 + (size / (CREEP_RATIO * (size + drift) + 1e-300)) ** 8) ** -0.125
    fn["creep_margin"] = _function("creep_margin", x, p, room * ca.sqrt(room) - needed * eps * (mu * Fc_roll[2]) ** 2)
    # entering the creep: the law's fast transient in the limit of its relaxation rate, a contact impulse
    # that takes the slip to u* and keeps the normal velocity (M is the contact's mobility)
    impulse = ca.solve(M, ca.vertcat(0, u_star - slip))
    fn["creep_entry"] = _function("creep_entry", x, p, x + ca.mtimes(ca.jacobian(xdot, Fc), impulse))


def _build_flight(fn: dict, body: Body, ns: int, laws=()) -> None:
    """FLIGHT: the same rigid-body equations with no contact force, in the flight chart (the air
    still acts)."""
    x = ca.SX.sym("x", FLIGHT.n_states)
    p = ca.SX.sym("p", ns + 4 + sum(d.n_params for d in laws))
    shape, A, C = p[:ns], p[ns], p[ns + 1]
    H = lambda c: body.height(c, shape)  # noqa: E731
    T = FLIGHT.terms(x, H, A, C, None, _wrench(laws, p, ns + 4, H))
    if laws:
        powers = _powers(laws, p, ns + 4, T["w"], T["v"], 0, T["k"], contact_point(H, laws, T["k"]))
        fn["power_flight"] = _function("power_flight", x, p, ca.vertcat(0, *powers))
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
