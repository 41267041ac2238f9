"""The memory cap of a run's dense output (``SolverOptions.max_dense_mb``).

The dense output is the Taylor polynomials of every step (:mod:`phasekit.core.engines.dense`): 744
bytes a step for a spheroid on Coulomb friction in contact (7 states, the integral of R included,
13 coefficients each at order 12, and the step's ends): a run of ten million steps would hold ~7.5 GB. :class:`DenseCap` sees each span of dense output as the engine makes it (every ~20 000
steps, :data:`phasekit.core.engines.taylor.RECORD_STEPS`, through ``Budget.keep``) and counts its
bytes. Once they pass the cap, it drops the dense output, the spans kept so far included, and keeps
from each span, then and from there on, what the run was asked for:

* the states at the requested ``t_eval`` inside it (as :meth:`phasekit.core.Trajectory.states`
  reads them: the segment that ends at a time owns it, a segment's ends are its exact states);
* its energy tally (:class:`SpanTally`, with dense output asked for): the work of each law over it
  and, at each step's end, the work of all laws in the step and the energy, 16 bytes a step, from
  which :func:`phasekit.core.energy.energy_budget` computes the same budget, bit for bit, as from
  the dense output (the same quadratures, summed in the same order).

The events, the minima of R and the summary never needed the dense output. What does (sampling at
other times, the pose, the energy series, movies) raises a ParameterError naming ``max_dense_mb``
(:func:`phasekit.core.energy.dropped_note`). The tally is paid inside the run, so its wall budget counts it; a run whose wall budget runs out
while it tallies stops tallying (and has no energy budget, :data:`ABANDONED`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .energy import GAUSS_NODES, gauss_powers, step_bounds
from .hybrid import Mode
from .observables import evaluate_function

MB = 1e6


@dataclass(frozen=True)
class SpanTally:
    """What the energy budget needs of one span of dense output (units M g b).

    Attributes
    ----------
    t0, t1 : float
        The span.
    work : numpy.ndarray
        The integral over it of each law's power (one entry per law of the model).
    steps : numpy.ndarray
        The integral of all laws' power together over each of its steps.
    energy : numpy.ndarray
        The mechanical energy at each step's end.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> t = pk.core.dense_cap.SpanTally(0.0, 1.0, np.zeros(1), np.zeros(2), np.ones(2))
    >>> t.nbytes
    40
    """

    t0: float
    t1: float
    work: np.ndarray
    steps: np.ndarray
    energy: np.ndarray

    @property
    def nbytes(self) -> int:
        return int(self.work.nbytes + self.steps.nbytes + self.energy.nbytes)


#: the tally of a run whose wall budget ran out while it tallied (its energy budget then says so)
ABANDONED = SpanTally(float("nan"), float("nan"), np.zeros(0), np.zeros(0), np.zeros(0))


def tally(model, mode: Mode, span) -> SpanTally:
    """The :class:`SpanTally` of one span of dense output of ``mode``.

    Parameters
    ----------
    model : Model
        The model integrated.
    mode : Mode
        The span's mode.
    span : Span
        A span of dense output (:mod:`phasekit.core.engines.dense`).

    Returns
    -------
    SpanTally
        Its energy tally, by the quadratures of :func:`phasekit.core.energy.energy_budget`.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5), 10.0)
    >>> seg = traj.segments[0]
    >>> t = pk.core.dense_cap.tally(traj.model, seg.mode, seg.dense[0])
    >>> bool(t.work[0] < 0), len(t.steps) == seg.n_steps
    (True, True)
    """
    a, b = step_bounds(span)
    w, vals = gauss_powers(model, mode, span, a, b)
    steps = (w[:, None] * vals).sum(axis=1).reshape(len(b), GAUSS_NODES).sum(axis=1) if len(b) else np.zeros(0)
    energy = model.function("energy", mode)
    E = np.atleast_1d(evaluate_function(energy, model.p, span(b))).reshape(-1) if len(b) else np.zeros(0)
    return SpanTally(float(span.t0), float(span.t1), w @ vals, steps, E)


def span_bytes(span) -> int:
    """The memory a span of dense output holds (the arrays behind its views included)."""
    f = span.f
    arrays = [getattr(f, name, None) for name in ("starts", "ends", "coefs", "ts", "xs")]
    total = 0
    for a in arrays:
        if a is None:
            continue
        while isinstance(a.base, np.ndarray):
            a = a.base
        total += len(a.base) if isinstance(a.base, bytes) else a.nbytes
    return total


class DenseCap:
    """The keeper of a run's dense output under its cap (see the module notes): ``Budget.keep``.

    Parameters
    ----------
    model : Model
        The model integrated.
    max_mb : float or None
        The cap in MB (None: none).
    t_eval : numpy.ndarray or None
        The requested sample times.
    energy : bool
        Tally the energy of what is dropped (the run asked for dense output).

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> cap = pk.core.dense_cap.DenseCap(pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.1)), 1.0, None, energy=True)
    >>> cap.dropped, cap.limit
    (False, 1000000.0)
    """

    def __init__(self, model, max_mb: float | None, t_eval, *, energy: bool):
        self.model, self.energy = model, energy
        self.limit = np.inf if max_mb is None else float(max_mb) * MB
        self.kept, self.peak, self.dropped, self.t_dropped = 0, 0, False, None
        self.where = (0, Mode.SLIDING)  # (segment index, mode) of the spans coming: set by the run
        self.seen = []  # (segment index, mode, span) kept so far
        self.tallies = {}  # segment index -> [SpanTally]
        self.te = None if t_eval is None else np.asarray(t_eval, dtype=float)
        self.ys = None if self.te is None else np.full((self.te.size, model.n_states), np.nan)
        self.owner = None if self.te is None else np.full(self.te.size, -1)
        self.budget, self.abandoned = None, False  # the run's Budget: its wall clock stops the tally

    def __call__(self, span) -> bool:
        """Keep ``span`` (True), or take what is asked of it and drop it (False)."""
        if not self.dropped:
            self.kept += span_bytes(span)
            self.peak = max(self.peak, self.kept)
            self.seen.append((*self.where, span))
            if self.kept <= self.limit:
                return True
            self.dropped, self.t_dropped = True, float(span.t0)
            for seg, mode, old in self.seen:
                self._take(seg, mode, old)
                old.f = None  # its arrays are freed now, not at the end of the run
            self.seen, self.kept = [], 0
            return False
        self._take(*self.where, span)
        return False

    def _take(self, seg: int, mode: Mode, span) -> None:
        if self.energy and self.budget is not None and self.budget.wall_exceeded():
            self.energy, self.tallies, self.abandoned = False, {}, True  # the run ends at its next check
        if self.energy:
            self.tallies.setdefault(seg, []).append(tally(self.model, mode, span))
        if self.te is None:
            return
        sel = np.flatnonzero((self.te >= span.t0) & (self.te <= span.t1) & ((self.owner < 0) | (self.owner == seg)))
        if sel.size:  # a later span of the same segment owns a time on its start, as Segment.states reads it
            X = np.asarray(span(np.clip(self.te[sel], span.t0, span.t1))).reshape(sel.size, -1)
            self.ys[sel] = _to_chart(self.model, mode, X)
            self.owner[sel] = seg

    def segments(self, segments: list) -> list:
        """The run's segments, without their dense output once it was dropped, with their tallies."""
        from dataclasses import replace

        if not self.dropped:
            return segments
        if self.abandoned:  # the wall budget ran out while it tallied: no energy budget, and why
            return [replace(s, dense=(), tally=(ABANDONED,)) for s in segments]
        return [replace(s, dense=(), tally=tuple(self.tallies.get(i, ()))) for i, s in enumerate(segments)]

    def states(self, segments: list, te: np.ndarray) -> np.ndarray:
        """The states at the requested times ``te`` (those inside the run, sorted), once the dense
        output was dropped: each from the span that owned it, a segment's ends exact."""
        keep = np.isin(self.te, te)
        ys, owner = self.ys[keep].copy(), self.owner[keep]
        ends = np.array([s.t1 for s in segments])
        for i, t in enumerate(self.te[keep]):
            k = owner[i] if owner[i] >= 0 else min(int(np.searchsorted(ends, t, side="left")), len(segments) - 1)
            seg = segments[k]
            if t in (seg.t0, seg.t1) or owner[i] < 0:  # an end, or a time no span covered (before the segment)
                ys[i] = _to_chart(self.model, seg.mode, (seg.x1 if t == seg.t1 else seg.x0)[None, :])[0]
        return ys


def _to_chart(model, mode: Mode, X) -> np.ndarray:
    """States of ``mode``'s chart -> the model's (flight: the gap dropped), as Trajectory reads them."""
    if mode is not Mode.FLIGHT:
        return np.asarray(X, dtype=float)
    from .resets import contact_state

    return np.array([contact_state(model, x) for x in X])
