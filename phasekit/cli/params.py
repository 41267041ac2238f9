"""Entry points by plain parameters, shared by the CLI: names and numbers in, JSON-ready dicts out.

These validate their arguments (ParameterError naming the parameter as the Python API
spells it; the CLI rewords it with its own flag), build the body, law, model and start,
run, and return dicts in the paper's variables.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from .._runtime.validate import check_choice, check_finite, check_range
from .._runtime.watch import check_max_wall, wall_deadline
from ..bodies.body import Body
from ..bodies.edged import EdgedBody
from ..bodies.spheroid import Spheroid
from ..core.charts import choose_chart
from ..core.hybrid import Event
from ..core.model import Model
from ..core.observables import OBSERVABLES
from ..core.simulate import simulate
from ..core.starts import RATE_MAX, gyroscopic_start, raw_start, to_chart, vertical_spin_start
from ..core.system import STOP_AT
from ..errors import ParameterError
from ..friction.contensou import RADIUS_MAX, Contensou
from ..friction.dissipation import COEFF_MAX, AirDrag, AirLayer, RollingResistance, SpinFriction
from ..friction.laws import friction_law


def parse_stop(stop: str) -> tuple[str, list[Event]]:
    """``jump``, ``touchdown``, ``none`` or ``rest`` (:data:`phasekit.core.system.STOP_AT`), or
    ``NAME=VALUE`` (stop when the observable NAME first reaches VALUE, e.g. ``theta=0.4``; the run
    then runs through flights)."""
    if not isinstance(stop, str):
        raise ParameterError("stop_at", f"must be {', '.join(STOP_AT)} or NAME=VALUE", stop)
    if "=" not in stop:
        return check_choice("stop_at", stop, STOP_AT), []
    name, _, value = stop.partition("=")
    if name not in OBSERVABLES or name in ("slip", "friction"):
        raise ParameterError("stop_at", f"NAME=VALUE needs NAME among {', '.join(n for n in OBSERVABLES if n not in ('slip', 'friction'))}",
                             stop)
    try:
        level = float(value)
    except ValueError:
        raise ParameterError("stop_at", "NAME=VALUE needs a number VALUE", stop) from None
    check_finite("stop_at", level)
    if name == "theta" and not 0.0 <= level <= np.pi:
        raise ParameterError("stop_at", "theta=VALUE needs VALUE in [0, pi]", level)
    return "none", [Event(name, level, direction=0, name=f"{name}={level:g}")]


def _start(body, law, start: dict, chart: str):
    """(model, x0, seed info) for a start description."""
    kind = start["kind"]
    if kind == "unstable-manifold":
        from ..steady.manifolds import unstable_manifold_start

        for key in ("omega0", "n0"):
            if start.get(key) is not None and abs(start[key]) > RATE_MAX:
                raise ParameterError(key, f"must satisfy |{key}| <= {RATE_MAX:g} for a simulation", start[key])
        model, x0, fp = unstable_manifold_start(
            body, law, state=start["state"], delta=start["delta"], omega0=start.get("omega0"), n0=start.get("n0"),
            branch=start.get("branch", "+0"), seed_law=start.get("seed_law", "viscous"))
        if chart not in ("auto", model.chart.name):
            raise ParameterError("chart", f"cannot start on the {start['state']} state (use {model.chart.name} or auto)",
                                 chart)
        return model, x0, {"fixed_point": fp.to_dict(), "delta": start["delta"], "branch": start.get("branch", "+0"),
                           "seed_law": fp.law}
    if kind == "gyroscopic":
        y0 = gyroscopic_start(body, start["theta0"], omega0=start.get("omega0"), n0=start.get("n0"))
    elif kind == "spin-about-vertical":
        y0 = vertical_spin_start(start["theta0"], start["n0"])
    elif kind == "spun-about-axis":
        from ..core.starts import axis_spin_start

        _check_range_of(body, float(start["theta0"]), "theta0")
        y0, note = axis_spin_start(body, start["theta0"], start["n0"],
                                   mu=law.mu if law.has_rolling_mode else None)
        if note:
            warnings.warn(note)
    elif kind == "rolled":
        from ..core.starts import rolled_start

        y0 = rolled_start(body, start["theta0"], start["speed"])
    elif kind == "spinning-in-place":
        from ..steady.precessions import intermediate_state

        _check_range_of(body, float(start["theta0"]), "theta0")
        y0 = intermediate_state(body, float(start["theta0"]))
        if y0 is None:
            raise ParameterError("theta0", "has no steady motion spinning in place for this body (the torque balance "
                                           "asks Omega^2 <= 0 there; see phasekit steady-states)", start["theta0"])
    elif kind == "paper":
        from ..core.starts import paper_start
        from ..theory.paper import PAPER_CASES

        model, x0 = paper_start(start["label"], n0=start.get("n0"), omega0=start.get("omega0"), friction=law)
        case = PAPER_CASES[start["label"]]
        # the printed start belongs to one body: refuse another rather than ignore it
        if not (isinstance(body, Spheroid) and body.uniform and abs(body.a - case.a) <= 1e-4 * case.a):
            raise ParameterError("a", f"must be {case.a:.6g} for the paper's start ({case.label}), a uniform spheroid "
                                      "(no `A`, `C`)", None if math.isnan(body.a) else body.a)
        if chart not in ("auto", model.chart.name):
            raise ParameterError("chart", f"must be auto or {model.chart.name} for the paper's start "
                                          f"({start['label']})", chart)
        return model, x0, None
    else:
        # the Euler chart only if asked for: "auto" takes a state at a pole into the vector chart
        y0 = raw_start(start["state"], chart="euler" if chart == "euler" else "vector")
    _check_range_of(body, float(y0[4]), "theta" if kind == "state" else "theta0")
    if kind != "state":
        _fast_top(body, y0, start.get("rev_per_s"))
    chart = choose_chart(float(y0[4]), chart)
    if chart == "euler":
        raw_start(y0, chart="euler")  # theta strictly inside (0, pi)
    return Model(body, law, chart), to_chart(chart, y0), None


#: how near a pole (radians) a start counts as a top spinning there, for the fast-top warning
NEAR_POLE = 0.35


def _fast_top(body, y0, rev_per_s: float | None = None) -> None:
    """Warn, in one line, when a start near a pole where G is highest (h_thetatheta < 0) spins
    below the fast-top condition (phasekit.theory.PoleCriterion.rolling_threshold: for a point
    C^2 n^2 > 4 A' M g l; the rolling linearisation's, phasekit.steady): its spin cannot hold it up.
    ``rev_per_s``: rev/s per unit sqrt(g/b), to say the spins in rev/s too (the CLI with --size)."""
    from ..steady.branches import holds_state
    from ..theory.criteria import pole_stability_threshold

    theta = float(y0[4])
    pole = "upright" if theta < np.pi / 2 else "inverted"
    at = 0.0 if pole == "upright" else np.pi
    if abs(theta - at) > NEAR_POLE or not holds_state(body, at):
        return
    crit = pole_stability_threshold(body, pole)
    need = crit.rolling_threshold
    if need is None or abs(y0[5]) >= need:
        return
    point = " (on a point: C^2 n^2 > 4 A' M g l, A' the moment about the point)" if abs(crit.rho) < 1e-12 else ""
    real = lambda v: "" if rev_per_s is None else f" ({v * rev_per_s:.4g} rev/s)"  # noqa: E731
    warnings.warn(f"the spin n = {abs(y0[5]):.4g}{real(abs(y0[5]))} is below the fast-top condition |n| > {need:.6g}"
                  f"{real(need)} at theta = {at:.6g}{point}: the spin cannot hold the axis near the vertical, and it "
                  "falls")


def _check_range_of(body, theta: float, name: str) -> None:
    """A body with an edge is modelled on an open range of theta only (:mod:`phasekit.bodies.edged`):
    refuse a start outside it, naming ``name`` (beyond it another part of the body touches the table)."""
    if isinstance(body, EdgedBody):
        body.check_theta(theta, name)


def run_start(*, body: Body, friction="coulomb", mu, slip_eps=None, start: dict, t_end=200.0, stop_at="jump",
              restitution=0.0, chart="auto", options: dict | None = None, pose0=None, dissipation=None,
              verify: bool = False):
    """Run one simulation described by plain parameters: (Trajectory, seed info or None).
    The dense output is kept: the pose (psi, phi, X, Y, X_P, Y_P) at the events and the end
    comes from it (and the energy budget), and keeping it changes no number of the run.
    ``dissipation``: the coefficients of the dissipation laws (:func:`_law_of`); ``verify``: repeat
    the run at rtol / 10 in the other chart (:meth:`phasekit.core.Trajectory.verify`)."""
    law = _law_of(friction, mu, slip_eps, dissipation)
    check_choice("chart", chart, ("auto", "euler", "vector"))
    stop, events = parse_stop(stop_at)
    model, x0, seed = _start(body, law, start, chart)
    res = simulate(model, x0, t_end, stop_at=stop, restitution=restitution, events=events, dense=True, pose0=pose0,
                   verify=verify, **(options or {}))
    return res, seed


#: the dissipation laws' coefficients by plain name (the CLI's flags): (law, its coefficient), and
#: the unit of each in the messages
DISSIPATION = {"rolling_resistance": (RollingResistance, "delta", "b"), "spin_friction": (SpinFriction, "mu_s", "b"),
               "air_drag": (AirDrag, "rotation", "M b^2 sqrt(g/b)"), "air_layer": (AirLayer, "k", "M b^2 sqrt(g/b)"),
               "air_drag_quadratic": (AirDrag, "rotation_quadratic", "M b^2"),
               "air_drag_force": (AirDrag, "translation", "M sqrt(g/b)"),
               "air_drag_force_quadratic": (AirDrag, "translation_quadratic", "M/b")}


def _patch_law(friction, mu, slip_eps, dissipation: dict):
    """Friction over a contact patch (:class:`phasekit.Contensou`) when ``dissipation`` gives a
    patch radius > 0 (taken out of it), else None; refused with anything but exact Coulomb."""
    radius, unit_radius = dissipation.pop("patch", None), dissipation.pop("hertz", None)
    if unit_radius is not None:
        if radius is not None:
            raise ParameterError("hertz", "sets the patch's radius from the materials: give --hertz or --patch, not "
                                          "both", show_value=False)
        if friction != "coulomb" or slip_eps is not None or dissipation.get("spin_friction"):
            raise ParameterError("hertz", "is Coulomb friction over a patch: give it with exact Coulomb friction and "
                                          "without --slip-eps or --spin-friction", show_value=False)
        return Contensou(mu, check_range("hertz", unit_radius, 0.0, RADIUS_MAX, closed="r",
                                         label=f"(0, {RADIUS_MAX:g}] (units b)"), curvature=True)
    if radius is None:
        return None
    radius = check_range("patch", radius, 0.0, RADIUS_MAX, closed="lr", label=f"[0, {RADIUS_MAX:g}] (units b)")
    if radius == 0:
        return None
    if friction != "coulomb" or slip_eps is not None:
        raise ParameterError("patch", "is Coulomb friction over a patch: give it with exact Coulomb friction (no "
                                      "--slip-eps, no --friction viscous)", radius)
    if dissipation.get("spin_friction"):
        raise ParameterError("patch", "includes the spin friction (its couple about the normal): give --patch or "
                                      "--spin-friction, not both", radius)
    return Contensou(mu, radius)


def _law_of(friction, mu, slip_eps=None, dissipation=None):
    """The sliding law with the dissipation laws whose coefficients ``dissipation`` gives by plain
    name ({"spin_friction": 0.02, ...}, :data:`DISSIPATION`): each checked in [0, 1e3] (named so),
    a law whose coefficients are all 0 left out (the sliding law alone is the paper's model)."""
    dissipation = dict(dissipation or {})
    law = _patch_law(friction, mu, slip_eps, dissipation) or friction_law(friction, mu, slip_eps)
    coefficients: dict = {}
    for name, value in dissipation.items():
        if name not in DISSIPATION:
            raise ParameterError("dissipation", f"must name coefficients among {', '.join(DISSIPATION)}", name)
        cls, coefficient, unit = DISSIPATION[name]
        value = check_range(name, value, 0.0, COEFF_MAX, closed="lr", label=f"[0, {COEFF_MAX:g}] (units {unit})")
        if value > 0:
            coefficients.setdefault(cls, {})[coefficient] = value
    laws = [cls(**kw) for cls, kw in coefficients.items()]
    return law.with_dissipation(*laws) if laws else law


def simulate_start(**kwargs) -> dict:
    """:func:`run_start` as the JSON dict (which carries the model, the start and the solver
    options, so it can be rerun)."""
    res, seed = run_start(**kwargs)
    out = res.to_dict()
    if seed is not None:
        out["seed"] = seed
    return out


def real_units_report(out: dict, scale) -> dict:
    """The times, gaps, positions, speeds and spins of a simulate result in real units (ms, mm,
    m/s, rev/s; angles in radians), given the body's :class:`phasekit.Scale`."""
    from ..core.units import DISPLAY_UNITS

    kinds = {"t": "time", "t_jump": "time", "t_stop": "time", "t_end": "time", "t_rest": "time", "t_liftoff": "time",
             "t_touchdown": "time", "t_gap_max": "time", "gap_max": "length", "W_star": "speed", "Omega_star": "rate",
             "U": "speed", "V": "speed", "Omega": "rate", "Lambda": "rate", "n": "rate", "X": "length", "Y": "length",
             "X_P": "length", "Y_P": "length"}

    def conv(d):
        return {k: (None if v is None else float(scale.quantity(v, kinds[k]).to(DISPLAY_UNITS[kinds[k]]).magnitude))
                if k in kinds else v for k, v in d.items() if k in kinds or k in ("theta", "psi", "phi", "kind")}

    rep = {"units": {k: f"{DISPLAY_UNITS[k]}" for k in ("time", "length", "speed", "rate")} | {"angle": "rad"},
           "b": f"{scale.b:~P}", "g": f"{scale.g:~P}", "time_unit": f"{scale.time_unit:.6g~P}"}
    rep.update(conv({k: out.get(k) for k in ("t_jump", "t_stop", "t_end", "t_rest") if k in out}))
    if out.get("energy_budget") and scale.mass is not None:  # energies need the mass: M g b without it
        rep["units"]["energy"] = DISPLAY_UNITS["energy"]
        rep["energy_budget"] = _energies(out["energy_budget"], scale)
    for key in ("state_at_jump", "state_end", "pose_end", "flight"):
        if out.get(key):
            rep[key] = conv(out[key])
    if rep.get("flight") and out["flight"].get("t_touchdown") is not None:
        dur = out["flight"]["t_touchdown"] - out["flight"]["t_liftoff"]
        rep["flight"]["duration"] = float(scale.quantity(dur, "time").to(DISPLAY_UNITS["time"]).magnitude)
    rep["events"] = [{**conv({"kind": e["kind"], "t": e["t"]}), **({"state": conv(e["state"])} if "state" in e else {}),
                      **({"pose": conv(e["pose"])} if "pose" in e else {})} for e in out.get("events", [])]
    return rep


def _energies(budget: dict, scale) -> dict:
    """An energy budget (EnergyBudget.to_dict, units M g b) in mJ."""
    def mj(v):
        return float(scale.quantity(v, "energy").to("mJ").magnitude)

    return {k: {law: mj(e) for law, e in v.items()} if isinstance(v, dict) else mj(v) for k, v in budget.items()}


def fixed_points_report(*, body: Body, mu, friction="coulomb", slip_eps=None, omega0=None, n0=None,
                        max_wall=None, dissipation=None) -> dict:
    """All steady states at the given Omega0 or n0 with their linear stability (JSON dict), with
    status "completed", or "failed" and the reason when the wall budget ``max_wall`` (seconds)
    runs out; ``dissipation`` as for :func:`run_start`."""
    from ..steady.branches import degeneracy
    from ..steady.fixedpoints import FAMILY_MAX, fixed_points

    if (omega0 is None) == (n0 is None):
        raise ParameterError("omega0", "or `n0` must be given, not both", show_value=False)
    law = _law_of(friction, mu, slip_eps, dissipation)
    name, value = ("omega0", omega0) if omega0 is not None else ("n0", n0)
    check_range(name, value, -FAMILY_MAX, FAMILY_MAX, closed="lr", label=f"[-{FAMILY_MAX:g}, {FAMILY_MAX:g}]")
    max_wall = check_max_wall(max_wall)
    status, reason = "completed", None
    with wall_deadline(max_wall):
        try:
            pts = fixed_points(Model(body, law, "euler"), omega0=omega0, n0=n0)
        except TimeoutError as exc:
            pts, status, reason = [], "failed", f"not finished: {exc}"
    note = ("the inverted vertical (theta = pi) is the vertical with k reversed: the same state for a flip-symmetric body"
            if body.flip_symmetric else "theta = 0 and theta = pi are different states of this body")
    degenerate = degeneracy(body)
    if degenerate:
        note += "; " + degenerate
    linearised = "coulomb-rolling" if law.has_rolling_mode else law.name
    return {"status": status, **({"reason": reason} if reason else {}), "fixed_points": [p.to_dict() for p in pts],
            "model": Model(body, law).to_dict(), "note": note, **({"degenerate": degenerate} if degenerate else {}),
            "linearised_law": linearised, "stability": STABILITY_MEANING.get(linearised, "the law's own field")}


def steady_structure_report(*, body: Body, mu, friction="coulomb", slip_eps=None, omega0=None, n0=None,
                            max_wall=None, dissipation=None) -> dict:
    """The steady-state structure of ``body`` (phasekit.steady.structure) as a JSON dict; with
    ``omega0`` or ``n0`` also the states on it at that rate or spin. Status "failed" and the
    reason when the structure fails or the wall budget ``max_wall`` (seconds) runs out;
    ``dissipation`` as for :func:`run_start`."""
    from ..steady.fixedpoints import FAMILY_MAX
    from ..steady.structure import steady_structure

    law = _law_of(friction, mu, slip_eps, dissipation)
    if omega0 is not None or n0 is not None:
        name, value = ("omega0", omega0) if omega0 is not None else ("n0", n0)
        check_range(name, value, -FAMILY_MAX, FAMILY_MAX, closed="lr", label=f"[-{FAMILY_MAX:g}, {FAMILY_MAX:g}]")
    max_wall = check_max_wall(max_wall)
    with wall_deadline(max_wall):
        structure = steady_structure(body, law)
        out = structure.to_dict()
        linearised = "coulomb-rolling" if law.has_rolling_mode else law.name
        out.update(linearised_law=linearised, stability=STABILITY_MEANING.get(linearised, "the law's own field"))
        if (omega0 is not None or n0 is not None) and out["status"] == "completed":
            out["states_at"] = f"{'Omega0' if omega0 is not None else 'n0'} = {value:g}"
            try:
                out["states"] = [p.to_dict() for p in structure.at(omega0=omega0, n0=n0)]
            except TimeoutError as exc:
                out.update(status="failed", reason=f"not finished: {exc}", states=[])
    return out


#: what "stable" means for each linearisation (see phasekit.steady.linearisation)
STABILITY_MEANING = {
    "coulomb-rolling": "exact Coulomb friction: the rolling (no-slip) linearisation, in which a zero-slip state is "
                       "neutral or grows, never decays (a spin at a pole grows below its fast-top condition); the "
                       "viscous law gives the friction-driven instabilities of part I",
    "coulomb-regularised": "regularised Coulomb friction: the smooth field's linearisation (the rolling spectrum plus "
                           "two fast slip modes)",
    "viscous": "viscous friction (part I): friction drives or damps the modes",
}


def gyroscopic_report(*, body: Body, mu, theta0, t, omega0=None, n0=None) -> dict:
    """Gyroscopic mean solution (3.16)-(3.19) at times t (slow time T = mu t)."""
    from .._runtime.validate import check_positive, check_times
    from ..theory.gyroscopic import gyroscopic_solution

    mu = check_positive("mu", mu)
    t = check_times("t", t)
    if np.any(t < 0):
        raise ParameterError("t", "must be times >= 0", t)
    sol = gyroscopic_solution(body, theta0, omega0=omega0, n0=n0, T=mu * t)
    return {"t": t.tolist(), "T": (mu * t).tolist(), "theta": sol["theta"].tolist(), "Omega": sol["Omega"].tolist(),
            "J": sol["J"], "J_definition": "A Omega h (3.17)", "Omega0": sol["Omega0"], "method": sol["method"]}
