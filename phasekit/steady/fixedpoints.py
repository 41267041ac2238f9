"""Finding the steady states (part I of the series), for any body: Newton on the full equations
from a closed-form guess (the classes of steady states and their closed forms are in
phasekit.steady.precessions), every class of steady state at one family parameter
(:func:`fixed_points`), and natural-parameter continuation of a family (:func:`continue_family`).
A solution is accepted by a componentwise backward error (NEWTON_RTOL) and linearised by
:func:`phasekit.steady.linearise` (phasekit.steady.linearisation).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import casadi as ca
import numpy as np

from .._runtime.validate import check_array, check_choice, check_finite, check_range, check_vector
from .._runtime.watch import check_deadline
from ..core.charts import EULER
from ..core.fields import CompiledModel, compiled_model
from ..core.hybrid import Mode
from ..core.model import Model
from ..errors import ConvergenceError, ParameterError
from ..friction.laws import Viscous
from ..theory.criteria import pole_stability_threshold
from .branches import degeneracy, holds_state
from .dissipative import acting_laws
from .linearisation import FixedPoint, check_model, linearise, mode_for
from .precessions import (
    horizontal_like_angle,
    horizontal_state,
    inverted_state,
    precession_angles,
    precession_state,
    root_float,
    vertical_state,
)

#: the law whose smooth field Newton solves for the steady states of every law: they have zero
#: slip, and Viscous(1) keeps Newton well conditioned where a law's own field is stiff
NEWTON_LAW = Viscous(1.0)

#: the classes of steady state (:class:`FixedPoint` ``kind``; "inverted" and "horizontal-like"
#: are those of bodies without flip symmetry)
KINDS = ("vertical", "inverted", "horizontal", "horizontal-like", "intermediate")
#: a Newton solution is accepted when each component of the field is at most NEWTON_RTOL
#: times that component's scale sum_j |J_ij| max(|x_j|, 1): a residual that a relative
#: change of the state by NEWTON_RTOL explains (a componentwise backward error). An absolute
#: test cannot serve every scale: at Omega0 = 1e6 the field's terms are ~Omega0^2 = 1e12 and
#: rounding alone leaves ~1e-5; with eps = 1e-12 a slip rounded to 1e-16 leaves mu * 1e-4.
NEWTON_RTOL = 1e-10
#: the largest |Omega0| or |n0| of a family: beyond it the field's ~rate^2 terms leave too few
#: significant digits for the test above (and overflow near 1e154)
FAMILY_MAX = 1e12


@dataclass(frozen=True)
class Branch:
    """A family of fixed points followed in a parameter: one row per step."""

    kind: str
    parameter: str
    values: np.ndarray
    points: tuple[FixedPoint, ...]

    @property
    def n_unstable(self) -> np.ndarray:
        return np.array([p.n_unstable for p in self.points])

    @property
    def stable(self) -> np.ndarray:
        return np.array([p.stable for p in self.points])


# -- Newton -----------------------------------------------------------------------------


_SOLVERS: dict = {}


def _newton_system(field: CompiledModel, n_params: int, chart, kind: str, fixed: str):
    """CasADi rootfinder for a square system: the chart's field with one redundant equation
    replaced by the family constraint (fixed Omega or n), or, at the vertical, the tilt
    coordinates of k and w with |k| = 1 and w.k = n0 imposed.

    The unknowns and equations are scaled at run time (unknown z = sz * zeta, equation i
    divided by se_i), so that the rootfinder's absolute tolerances act as relative ones at
    any scale of the state. Returns (solver, lift, n_unknowns, Jacobian of the equations)."""
    key = (field.key, kind, fixed)
    if key in _SOLVERS:
        return _SOLVERS[key]
    # The steady states have zero slip, so they are the same for every law: locate them with
    # the smooth sliding field (for exact Coulomb the rolling field slaves U, V and its
    # Jacobian is singular in them). The law's own field is used for the linearisation.
    f = field.functions_of(Mode.SLIDING)["rhs_sliding"]
    p = ca.SX.sym("p", n_params)
    val = ca.SX.sym("val")
    if chart is EULER:
        x = ca.SX.sym("x", 6)
        r = f(x, p)
        # At a fixed point Lambda = 0 and F_y = 0 make (2.7c) hold identically when Omega
        # is fixed, and (2.7f) when n is fixed: drop that equation, add the constraint.
        drop, idx = (2, 2) if fixed == "Omega" else (5, 5)
        eqs = ca.vertcat(*[r[i] for i in range(6) if i != drop], x[idx] - val)
        z = x
    else:
        # vertical family: unknown tilt coordinates, k_z and w_z from |k| = 1, w.k = n0
        z = ca.SX.sym("z", 6)  # k_x, k_y, w_x, w_y, v_x, v_y
        kz = ca.sqrt(1 - z[0] ** 2 - z[1] ** 2)
        wz = (val - z[0] * z[2] - z[1] * z[3]) / kz
        x = ca.vertcat(z[0], z[1], kz, z[2], z[3], wz, z[4], z[5])
        r = f(x, p)
        eqs = ca.vertcat(r[0], r[1], r[3], r[4], r[6], r[7])
    nz = z.shape[0]
    lift = ca.Function("lift", [z, p, val], [x])
    jac = ca.Function("newton_jac", [z, p, val], [ca.jacobian(eqs, z)])
    zeta, sz, se = ca.SX.sym("zeta", nz), ca.SX.sym("sz", nz), ca.SX.sym("se", nz)
    scaled = ca.substitute(eqs, z, sz * zeta) / se
    G = ca.Function("G", [zeta, ca.vertcat(p, val, sz, se)], [scaled])
    opts = {"abstol": 1e-15, "abstolStep": 1e-15, "max_iter": 50, "error_on_fail": False, "show_eval_warnings": False}
    _SOLVERS[key] = (ca.rootfinder("fixed_point_newton", "newton", G, opts), lift, nz, jac)
    return _SOLVERS[key]


def _backward_error(model: Model, x: np.ndarray) -> float:
    """max_i |f_i(x)| / sum_j |J_ij| max(|x_j|, 1) for the law's own field (see NEWTON_RTOL)."""
    mode = mode_for(model)
    f, J = model._rhs(x, mode), model._jacobian(x, mode)
    if not (np.all(np.isfinite(f)) and np.all(np.isfinite(J))):
        return float("inf")
    scale = np.abs(J) @ np.maximum(np.abs(x), 1.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(np.abs(f) == 0.0, 0.0, np.abs(f) / scale)
    return float(np.max(ratio))


def find_fixed_point(model: Model, guess, *, kind: str, value: float, fixed: str | None = None) -> FixedPoint:
    """Newton-solve for a steady state near ``guess`` (a chart state) with the family
    parameter held at ``value`` (Omega for the Euler chart unless ``fixed="n"``; the spin
    n0 for the vertical in the vector chart), then linearise it.

    Parameters
    ----------
    model : Model
    guess : array of model.n_states numbers
    kind : {"vertical", "horizontal", "intermediate"}
    value : float
        The family parameter (Omega0 or n0).
    fixed : {"Omega", "n"}, optional
        Which rate ``value`` fixes (Euler chart; the vector chart fixes n).

    Returns
    -------
    FixedPoint
        The converged state, linearised by :func:`phasekit.steady.linearise`.

    Raises
    ------
    ParameterError
        For an invalid argument.
    ConvergenceError
        When Newton does not reach a state whose residual is within NEWTON_RTOL of the
        state's scale (the message gives both; ``result`` holds the last iterate), or, with
        dissipation laws, when they take energy out of the state found without them (the
        message names them; phasekit.steady.dissipative).

    Examples
    --------
    >>> import phasekit as pk
    >>> m = pk.Model(pk.Spheroid(1.5), pk.Viscous(0.1))
    >>> fp = pk.steady.find_fixed_point(m, pk.steady.horizontal_state(10.0), kind='horizontal', value=10.0)
    >>> fp.kind, fp.n_unstable, fp.residual < 1e-10
    ('horizontal', 1, True)
    """
    model = check_model(model)
    check_choice("kind", kind, KINDS)
    if kind == "inverted":
        raise ParameterError("kind", "'inverted' needs no Newton solve: the state is exact (linearise it)", kind)
    if (model.chart is EULER) == (kind == "vertical"):
        raise ParameterError("kind", f"does not go with a model in the {model.chart.name} chart (the vertical state is "
                                     "found in the vector chart, the others in the Euler chart)", kind)
    value = check_range("value", value, -FAMILY_MAX, FAMILY_MAX, closed="lr", label=f"[-{FAMILY_MAX:g}, {FAMILY_MAX:g}]")
    allowed = ("Omega", "n") if model.chart is EULER else ("n",)
    fixed = check_choice("fixed", fixed or allowed[0], allowed)
    guess = check_vector("guess", guess, model.n_states)
    # NEWTON_LAW's field of the same body and chart: compiled once and shared, not a second Model
    newton_p = np.concatenate([model.body.params, NEWTON_LAW.params])
    field = compiled_model(model.body, NEWTON_LAW, model.chart)
    solver, lift, nz, jac = _newton_system(field, newton_p.size, model.chart, kind, fixed)
    z0 = guess if model.chart is EULER else guess[[0, 1, 3, 4, 6, 7]]
    sz = np.maximum(np.abs(z0), 1.0)
    J0 = np.asarray(jac(z0, newton_p, value))
    se = np.abs(J0) @ sz if np.all(np.isfinite(J0)) else np.ones(nz)
    se = np.maximum(se, 1e-12 * max(float(se.max()), 1.0))
    pv = np.concatenate([newton_p, [value], sz, se])
    z = sz * np.asarray(solver(z0 / sz, pv)).ravel()
    x = np.asarray(lift(z, newton_p, value)).ravel()
    article = "an" if kind[0] in "aeiou" else "a"
    if not np.all(np.isfinite(x)):
        raise ConvergenceError(f"Newton did not converge to {article} {kind} fixed point with {fixed} = {value:g}: "
                               "the iterate left the domain of the equations (non-finite state)", None)
    err = _backward_error(model, x)
    if not err <= NEWTON_RTOL and acting_laws(model, x):  # a steady state of the law without its dissipation
        raise _dissipated(model, x, f"{kind} fixed point with {fixed} = {value:g}")
    if not err <= NEWTON_RTOL:
        residual = float(np.max(np.abs(model._rhs(x, mode_for(model)))))
        try:
            last = linearise(model, x, kind=kind)
        except (ParameterError, ConvergenceError):
            last = None
        miss = (f"residual {residual:.2e} is {err:.1e} of the state's scale, above the tolerance {NEWTON_RTOL:g}"
                if np.isfinite(err) else "the field or its Jacobian is not finite at the last iterate")
        raise ConvergenceError(f"Newton did not converge to {article} {kind} fixed point with {fixed} = {value:g}: "
                               + miss, last)
    return linearise(model, x, kind=kind)


# -- all fixed points for a family parameter ---------------------------------------------


def fixed_points(model: Model, model_vector: Model | None = None, *, omega0: float | None = None,
                 n0: float | None = None) -> list[FixedPoint]:
    """Every class of steady state at the given family parameter, for any body.

    Each pole carries its closed-form stability criterion under sliding friction in ``parameter``.

    Parameters
    ----------
    model : Model
        The model (body and friction law), in either chart.
    model_vector : Model, optional
        The model in the vector chart, for the poles; by default ``model`` in the vector chart.
    omega0 : float, optional
        Precession rate: gives the horizontal precession (where h_theta(pi/2) = 0) and the precessions with
        rate Omega0 (the one continuing the horizontal state of an asymmetric body is labelled "horizontal-like").
    n0 : float, optional
        Spin: gives the vertical spin at theta = 0, the inverted one at theta = pi (bodies without flip
        symmetry; both in the vector chart) and the precessions with spin n0. Exactly one of ``omega0``
        and ``n0`` is given.

    Returns
    -------
    list of FixedPoint
        The states found, linearised; a precession at which Newton does not converge is left out.
        For a body whose steady states fill a continuum (a sphere with G at its centre:
        SteadyStructure.degenerate says so) only the isolated states (horizontal, vertical).
        With dissipation laws only the states at which every law's power vanishes (e.g. the
        vertical spin under rolling resistance alone; none under spin friction): the others
        lose energy (:func:`find_fixed_point` says which law takes it).

    Raises
    ------
    ParameterError
        If ``model`` or ``model_vector`` is not a Model, if not exactly one of ``omega0`` and ``n0`` is
        given, or if it is not finite or beyond FAMILY_MAX (1e12) in size.
    ConvergenceError
        If Newton does not converge at the horizontal or the vertical state (without dissipation
        laws: with them such a state is left out when they take energy out of it).
    TimeoutError
        If a wall budget in force (a caller's ``max_wall``, phasekit._runtime.watch) runs out.

    See Also
    --------
    SteadyStructure.at
        the same states of one family read off a whole steady-state structure (found along its branches, independently)
    find_fixed_point
        one state by Newton's method from a guess
    steady_structure
        every branch, static equilibrium and family of a body

    Examples
    --------
    >>> import phasekit as pk
    >>> fps = pk.fixed_points(pk.Model(pk.Spheroid(1.5), pk.Viscous(0.1)), omega0=10.0)
    >>> [(fp.kind, fp.n_unstable) for fp in fps]
    [('horizontal', 1)]
    """
    if not isinstance(model, Model):
        raise ParameterError("model", "must be a phasekit Model such as Model(Spheroid(1.5), Coulomb(0.1))", model)
    if model_vector is not None and not isinstance(model_vector, Model):
        raise ParameterError("model_vector", "must be a phasekit Model in the vector chart (or None)", model_vector)
    if (omega0 is None) == (n0 is None):
        raise ParameterError("omega0", "or `n0` must be given, not both", show_value=False)
    model_euler = model if model.chart is EULER else model.with_chart("euler")
    model_vector = model_vector or model.with_chart("vector")
    omega0, n0 = family_value("omega0", omega0), family_value("n0", n0)
    body = model_euler.body
    thetas = [] if degeneracy(body) else precession_angles(body, omega0=omega0, n0=n0)
    return on_range(body, isolated_states(model_euler, model_vector, omega0, n0)
                     + precessions_at(model_euler, thetas, omega0, n0))


def on_range(body, found: list[FixedPoint]) -> list[FixedPoint]:
    """The states of ``found`` that ``body``'s model holds: a body with an edge, those inside its
    range and short of its limits (phasekit.steady.branches.holds_state)."""
    return [fp for fp in found if holds_state(body, float(fp.y[4]))]


def family_value(name: str, value) -> float | None:
    """None, or a finite Omega0 or n0 within FAMILY_MAX (ParameterError naming it)."""
    if value is None:
        return None
    value = check_finite(name, value)
    return check_range(name, value, -FAMILY_MAX, FAMILY_MAX, closed="lr", label=f"[-{FAMILY_MAX:g}, {FAMILY_MAX:g}]")


def _has_horizontal_state(body) -> bool:
    """The horizontal state exists where h_theta(pi/2) = 0 (a flip-symmetric body, or one resting on its side
    exactly at pi/2)."""
    return bool(body.flip_symmetric or abs(body.h(np.pi / 2)[1]) < 1e-14)


#: a precession within this of pi/2 is the horizontal state where that exists
HORIZONTAL_GAP = 1e-9


def isolated_states(model_euler: Model, model_vector: Model, omega0, n0) -> list[FixedPoint]:
    """The horizontal state (given omega0, where it exists) or the spins about the vertical (given
    n0; the inverted one for a body without flip symmetry), as :func:`fixed_points` lists them first."""
    body = model_euler.body
    if omega0 is not None:
        if not _has_horizontal_state(body):
            return []
        return _kept(lambda: [find_fixed_point(model_euler, horizontal_state(omega0), kind="horizontal", value=omega0)],
                     model_euler)
    # an edged body's pole off its range (a disk lying flat) is not a state of its model
    out = _kept(lambda: [_pole(model_vector, n0, "upright")], model_vector) if holds_state(body, 0.0) else []
    if not body.flip_symmetric and holds_state(body, np.pi):
        out += _kept(lambda: [_pole(model_vector, n0, "inverted")], model_vector)
    return out


class _Dissipated(ConvergenceError):
    """No steady state: the dissipation laws take energy out of the one the law has without them."""


def _dissipated(model, x, what: str) -> _Dissipated:
    return _Dissipated(f"no {what} under dissipation: {', '.join(acting_laws(model, x))} takes energy out of the "
                       "steady state of the law without it, and energy decreases along every motion except rest", None)


def _kept(find, model) -> list[FixedPoint]:
    """``find()``, or nothing when the model's dissipation laws take energy out of the state."""
    try:
        return find()
    except _Dissipated:
        return []


def precessions_at(model_euler: Model, thetas, omega0, n0) -> list[FixedPoint]:
    """The precessions with rate omega0 (or spin n0) at the angles ``thetas`` (increasing), by Newton
    from the closed form: the last step of both :func:`fixed_points` (angles from a scan of the
    residual) and SteadyStructure.at (angles from the branches), so the two list the same states
    when they find the same angles. Angles within HORIZONTAL_GAP of pi/2 are the horizontal state
    (given omega0, where it exists); the one continuing it is "horizontal-like"; a precession at
    which Newton does not converge is left out, and one already found from another angle."""
    body = model_euler.body
    fixed, value = ("Omega", omega0) if omega0 is not None else ("n", n0)
    if omega0 is not None and _has_horizontal_state(body):
        thetas = [t for t in thetas if abs(t - np.pi / 2) > HORIZONTAL_GAP]
    like = horizontal_like_angle(body, thetas) if omega0 is not None else None
    out: list[FixedPoint] = []
    for theta in thetas:
        check_deadline()
        guess = precession_state(body, root_float(body, theta, omega0=omega0, n0=n0), omega0=omega0, n0=n0)
        kind = "horizontal-like" if theta == like else "intermediate"
        try:
            fp = find_fixed_point(model_euler, guess, kind=kind, value=value, fixed=fixed)
        except ConvergenceError:
            continue
        if any(np.all(np.abs(fp.x - p.x) <= 1e-10 * np.maximum(np.abs(p.x), 1.0)) for p in out):
            continue
        out.append(replace(fp, parameter={fixed: value, "theta": float(fp.x[4])}))
    return out


def _pole(model_vector: Model, n0: float, pole: str) -> FixedPoint:
    """The spinning state at theta = 0 (Newton, as every family) or theta = pi (exact), with the
    closed-form criterion under sliding friction attached."""
    if pole == "upright":
        fp = find_fixed_point(model_vector, vertical_state(n0), kind="vertical", value=n0)
    else:
        if acting_laws(model_vector, inverted_state(n0)):  # exact without dissipation: no Newton to fail
            raise _dissipated(model_vector, inverted_state(n0), f"inverted fixed point with n = {n0:g}")
        fp = linearise(model_vector, inverted_state(n0), kind="inverted")
    crit = pole_stability_threshold(model_vector.body, pole)
    info = {"n0": n0, "theta": 0.0 if pole == "upright" else float(np.pi), **crit.to_dict(n0)}
    return replace(fp, parameter=info)


def continue_family(model: Model, kind: str, values, *, start=None) -> Branch:
    """Natural-parameter continuation: Newton at each value from the previous solution.

    ``kind``: "horizontal" (values of Omega0), "vertical" (values of n0; vector chart) or
    "intermediate" (values of Omega0; ``start`` is a state on the family near values[0]).
    """
    model = check_model(model)
    check_choice("kind", kind, tuple(k for k in KINDS if k != "inverted"))
    values = check_array("values", values, ndim=1)
    chart = "vector" if kind == "vertical" else "euler"
    if model.chart.name != chart:
        raise ParameterError("model", f"must be in the {chart} chart for the {kind} family "
                                      f"(model.with_chart('{chart}'))", model)
    pts = []
    if kind == "horizontal":
        guess = horizontal_state(values[0])
    elif kind == "vertical":
        guess = vertical_state(values[0])
    else:
        if start is None:
            raise ParameterError("start", f"is required to continue the {kind} family (a state on it near values[0], "
                                          "e.g. intermediate_state(body, theta))", show_value=False)
        guess = check_vector("start", start, model.n_states)
    prev = None
    for v in values:
        if prev is not None and kind == "intermediate" and len(pts) >= 2:
            # secant predictor along the branch
            guess = 2 * pts[-1].x - pts[-2].x
        fp = find_fixed_point(model, guess, kind=kind, value=float(v))
        pts.append(fp)
        guess, prev = fp.x, v
    return Branch(kind, "n0" if kind == "vertical" else "Omega0", values, tuple(pts))
