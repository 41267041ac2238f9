"""Where the energy of a run went: the work of sliding friction and of each dissipation law,
by quadrature of its power along the dense output, and the jumps at events.

Along a smooth stretch the mechanical energy E changes only by the power of the forces that
are not conservative: dE/dt = F.u (sliding friction, u the slip) + sum over the dissipation laws
of f.v + Gamma.w (:mod:`phasekit.friction.dissipation`). Each power is integrated over every
Taylor step of the dense output with Gauss-Legendre nodes (the step's polynomial is smooth, so
the quadrature is exact to rounding), so ``lost - dissipated - at_events`` measures how well
the run conserved the balance: the integrator's error, not the quadrature's. Energy also
changes at events: an impact (restitution e < 1, or friction in the impulse) and the nudge
that starts sliding from zero slip (:data:`phasekit.core.zero_slip.SLIP_ONSET`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._runtime.watch import check_deadline
from ..errors import ParameterError
from .hybrid import Mode
from .observables import evaluate_function

#: Gauss-Legendre nodes per Taylor step
GAUSS_NODES = 12
#: the budget's line for the friction over a face the body lies on (:mod:`phasekit.core.face`)
FACE_LAW = "face friction"


@dataclass(frozen=True)
class EnergyBudget:
    """The energy balance of one run (units M g b).

    Attributes
    ----------
    energy_start, energy_end : float
        The mechanical energy at the start and at the end.
    laws : tuple of str
        "sliding friction", then the name of each dissipation law of the model.
    dissipated : tuple of float
        The energy each took out of the motion (>= 0): minus the integral of its power.
    at_events : float
        The energy lost in jumps at events (impacts; the slip-onset nudge), summed.
    residual_max : float
        The largest |residual| of the balance taken from the start to the end of any Taylor
        step (or output interval) along the run: the balance holds along it, not only at its
        end.
    """

    energy_start: float
    energy_end: float
    laws: tuple
    dissipated: tuple
    at_events: float
    residual_max: float = 0.0

    @property
    def lost(self) -> float:
        """energy_start - energy_end."""
        return self.energy_start - self.energy_end

    @property
    def residual(self) -> float:
        """lost - sum(dissipated) - at_events: the error of the balance."""
        return self.lost - float(np.sum(self.dissipated)) - self.at_events

    def to_dict(self) -> dict:
        return {"energy_start": self.energy_start, "energy_end": self.energy_end, "lost": self.lost,
                "dissipated": dict(zip(self.laws, self.dissipated)), "at_events": self.at_events,
                "residual": self.residual, "residual_max": self.residual_max}


def energy_budget(traj) -> EnergyBudget:
    """The :class:`EnergyBudget` of a run kept with dense output (see the module notes).

    Raises
    ------
    ParameterError
        If the run kept no dense output (simulate with dense=True, the default), nor its tally
        (a run past ``max_dense_mb`` keeps one: :mod:`phasekit.core.dense_cap`).
    """
    model = traj.model
    names = law_names(model)
    face = getattr(traj, "face", None)
    if face is not None and not traj.segments:  # started on its face: the face phase alone
        return _with_face(EnergyBudget(face.energy_start, face.energy_start, names, tuple(0.0 for _ in names), 0.0), face)
    if not traj.segments and traj.mode_stop is not None:  # it ended at its start (e.g. R <= 0 there): nothing lost
        e = float(model.function("energy", traj.mode_stop)(traj.x_stop, model.p))
        return EnergyBudget(e, e, names, tuple(0.0 for _ in names), 0.0, 0.0)
    require_dense(traj, tallied=True)
    work, jumps, e_prev = np.zeros(len(names)), 0.0, None
    first = traj.segments[0]
    e_start = float(model.function("energy", first.mode)(first.x0, model.p))
    worst = 0.0
    for seg in traj.segments:
        energy = model.function("energy", seg.mode)
        e0 = float(energy(seg.x0, model.p))
        e1 = float(energy(seg.x1, model.p))
        if e_prev is not None:
            jumps += e_prev - e0
        e_prev = e1
        seg_work, E, cumulative = _segment_work(model, seg, len(names))
        if len(E):  # the balance at every step's end: lost - dissipated - at events, so far
            along = (e_start - E) + (np.sum(work) + cumulative) - jumps
            worst = max(worst, float(np.max(np.abs(along))))
        work += seg_work
    dissipated = tuple(float(v) for v in -work)
    end = (e_start - e_prev) - float(np.sum(dissipated)) - jumps  # EnergyBudget.residual, as it computes it
    budget = EnergyBudget(e_start, e_prev, names, dissipated, jumps, max(worst, abs(end)))
    return budget if face is None else _with_face(budget, face)


def _with_face(budget: EnergyBudget, face) -> EnergyBudget:
    """``budget`` carried on over the face phase: the landing's loss at events, the face's friction its
    own line (FACE_LAW), its balance along its steps added to the residual so far."""
    landing = budget.energy_end - face.energy_start
    return EnergyBudget(budget.energy_start, face.energy_end, (*budget.laws, FACE_LAW),
                        (*budget.dissipated, face.dissipated), budget.at_events + landing,
                        max(budget.residual_max, abs(budget.residual) + face.residual_max))


def law_names(model) -> tuple:
    """"sliding friction", then the name of each dissipation law of ``model``."""
    return ("sliding friction", *(d.name for d in model.friction.dissipation))


def has_budget(traj) -> bool:
    """Can :func:`energy_budget` follow ``traj``'s energy (dense output, or a complete tally)?"""
    if not traj.segments:
        return traj.mode_stop is not None
    return all((s.dense or s.tally) and all(t.t0 == t.t0 for t in s.tally) for s in traj.segments)


def require_dense(traj, tallied: bool = False) -> None:
    """Raise the ParameterError of a run whose energy cannot be followed: no dense output (nor,
    with ``tallied``, the tally kept when the dense output was dropped under its cap:
    :mod:`phasekit.core.dense_cap`)."""
    if traj.segments and all(s.dense or (tallied and s.tally) for s in traj.segments):
        if any(t.t0 != t.t0 for s in traj.segments for t in s.tally):  # dense_cap.ABANDONED (t0 NaN)
            raise ParameterError("traj", "has no energy budget: the run dropped its dense output past max_dense_mb and "
                                         "its wall budget ran out while it tallied the energy", show_value=False)
        return
    note = dropped_note(traj)
    what = "series" if note and not tallied else "budget"  # a run past its cap has a budget, not a series
    raise ParameterError("traj", f"has no energy {what}: " + (note or "the run kept no dense output (simulate with "
                                                                   "dense=True)"), show_value=False)


def dropped_note(traj) -> str | None:
    """Why ``traj`` has no dense output when it dropped it under its cap (else None): a clause for
    the messages of what needs it."""
    if not any(s.tally for s in traj.segments):
        return None
    return (f"the run dropped its dense output when it passed max_dense_mb = {traj.options.max_dense_mb:g} MB "
            f"(simulate with a larger max_dense_mb, or None; times asked as t_eval are kept)")


def _power_function(model, mode: Mode):
    fns = model.compiled.functions_of(mode)
    name = f"power_{mode.value}"
    if name in fns:
        return fns[name]
    return None  # a model without dissipation laws: only sliding friction works


def step_bounds(span):
    """(starts, ends) of the Taylor steps (or output intervals) of a dense-output span, cut to it."""
    try:
        starts, ends, _ = span.pieces()
    except AttributeError:  # an interpolant of a pointwise integrator: between its output points
        starts = np.asarray(getattr(span.f, "ts", [span.t0, span.t1]), dtype=float)
        starts, ends = starts[:-1], starts[1:]
    a, b = np.maximum(starts, span.t0), np.minimum(ends, span.t1)
    keep = b > a
    return a[keep], b[keep]


def gauss_powers(model, mode: Mode, span, a, b):
    """The Gauss-Legendre nodes of every interval [a, b] (GAUSS_NODES each, interval by interval):
    their weights, and the power of each law there (one column per law)."""
    nodes, weights = np.polynomial.legendre.leggauss(GAUSS_NODES)
    ts = (0.5 * (b - a)[:, None] * nodes[None, :] + 0.5 * (a + b)[:, None]).ravel()
    X = span(ts)
    w = (0.5 * (b - a)[:, None] * weights[None, :]).ravel()
    P = _power_function(model, mode)
    if P is not None:
        return w, np.atleast_2d(evaluate_function(P, model.p, X)).reshape(len(ts), -1)
    if mode is Mode.FLIGHT:
        return w, np.zeros((len(ts), 1))
    fns = model.compiled.functions_of(mode)
    slip = evaluate_function(fns["slip"], model.p, X)
    F = evaluate_function(fns[f"friction_{mode.value}"], model.p, X)
    return w, np.sum(np.atleast_2d(F) * np.atleast_2d(slip), axis=1)[:, None]


def _segment_work(model, seg, n_laws: int):
    """The integral over the segment of each law's power; and, at the end of each Taylor step
    (or output interval), the energy and the work of all laws together so far. From the dense
    output, or from the tallies of a run that dropped it (the same numbers: :mod:`.dense_cap`)."""
    total = np.zeros(n_laws)
    all_E, steps = [], []
    if seg.tally:
        for t in seg.tally:
            total += t.work
            if len(t.steps):
                steps.append(t.steps)
                all_E.append(t.energy)
    else:
        all_X = []
        for span in seg.dense:
            check_deadline()  # a wall budget in force (the CLI's --max-wall) counts this work
            a, b = step_bounds(span)
            w, vals = gauss_powers(model, seg.mode, span, a, b)
            total += w @ vals
            if len(b):
                steps.append((w[:, None] * vals).sum(axis=1).reshape(len(b), GAUSS_NODES).sum(axis=1))
                all_X.append(span(b))
        if steps:
            X_ends = np.concatenate(all_X)
            all_E = [np.atleast_1d(evaluate_function(model.function("energy", seg.mode), model.p, X_ends)).reshape(-1)]
    if not steps:
        return total, np.zeros(0), np.zeros(0)
    return total, np.concatenate(all_E), np.cumsum(np.concatenate(steps))
