"""The steady-state structure of a body (parts III and IV of the series): every branch of
steady precessions over 0 <= theta <= pi, how its ends meet the spins about the vertical, the
static equilibria and infinite-spin asymptotes, and the stability along it.

Every steady precession lies on one curve, Omega^2 = q rho_2 / D; its branches are the maximal
intervals of theta on which Omega^2 > 0, and each ends at a pole, a static equilibrium or an
infinite-spin asymptote, or crosses a family (phasekit.steady.branches, module notes). Part
III's abstract calls the branches non-isolated fixed-point branches; the four kinds it names
are not spelled out in the abstract, and phasekit classifies each branch by its two ends
instead (:attr:`SteadyStructure.signature`).

A compound body (one with ``transfers``: the tippe top with its stem) has a kink in H at each
switch angle, where the contact passes from one piece to the next: its structure is computed
piece by piece with each piece's own support (phasekit.steady.pieces), every branch cut at the
switches (an end of kind "switch"), each part of a branch, static equilibrium and family
naming the piece it stands on (``piece``; None on a one-piece body, whose structure is
computed as it always was). A body with an edge (``theta_range``: pk.Disk, pk.Cone) has its
structure on that range, every branch ending at a limit of it (an end of kind "limit": "face
down", "side down"); on a tip (rho_2 = 0) it is degenerate (phasekit.steady.pieces).

Here: the structure (:func:`steady_structure`, :class:`SteadyStructure` and its branches), its
states at one rate or spin, and the event between two classes (:func:`bifurcation_between`).
The parts: phasekit.steady.branches (the curve, its ends and samples),
phasekit.steady.branch_stability (stability along a branch), phasekit.steady.families (the
static equilibria and the families) and phasekit.steady.pieces (a compound body's pieces).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from .._runtime.validate import check_bool
from .._runtime.watch import check_max_wall, wall_deadline
from ..bodies.body import Body
from ..core.model import Model
from ..errors import ConvergenceError, ParameterError, Status
from ..friction.laws import FrictionLaw, Viscous
from .branch_stability import StabilityChange, linearise_precession, stability_along
from .branches import branch_intervals, classify_end, degeneracy, precession_on_branch, sample_branch, special_points
from .dissipative import acting_laws, dissipation_note
from .families import SpinFamily, StaticEquilibrium
from .linearisation import FixedPoint
from .pieces import in_theta_order, parts, statics_and_families, tip_degeneracy
from .precessions import inverted_state, precession_state, vertical_state
from .records import BranchEnd, Interval, Part
from .rolling import rolling_state


@dataclass(frozen=True)
class SteadyBranch:
    """A branch of steady precessions: its two ends (ordered by theta), samples (theta, Omega, n)
    adaptive in arc length, and at each sample the linearisation of the law (``points``: a
    :class:`FixedPoint` each), the stability changes and the families it crosses.

    Attributes
    ----------
    ends : tuple of BranchEnd
        The two ends (phasekit.steady.branches.BranchEnd), lower theta first.
    theta, Omega, n : numpy.ndarray
        The samples (empty without them).
    points : tuple of FixedPoint
        The linearisation at each sample (empty without stability).
    changes : tuple of StabilityChange
        Where the stability changes along the branch.
    crossings : tuple of float
        The families it crosses (theta).
    sliding_stable : numpy.ndarray or None
        Under exact Coulomb friction, the sliding-friction criterion at each sample.
    piece : str or None
        On a compound body, the piece the branch stands on ("ball", "stem"): the branch lies
        within that piece's range of theta, an end at a switch has kind "switch"; None on a
        one-piece body.
    """

    ends: tuple[BranchEnd, BranchEnd]
    theta: np.ndarray = field(repr=False)
    Omega: np.ndarray = field(repr=False)
    n: np.ndarray = field(repr=False)
    points: tuple[FixedPoint, ...] = field(default=(), repr=False)
    changes: tuple[StabilityChange, ...] = ()
    crossings: tuple[float, ...] = ()
    sliding_stable: np.ndarray | None = field(default=None, repr=False)
    piece: str | None = None

    @property
    def label(self) -> str:
        inner = ["cross"] * len(self.crossings)
        return "-".join([self.ends[0].label, *inner, self.ends[1].label])

    @property
    def n_unstable(self) -> np.ndarray:
        return np.array([p.n_unstable for p in self.points], dtype=int)

    @property
    def stable(self) -> np.ndarray:
        return np.array([p.stable for p in self.points], dtype=bool)

    def n_unstable_at(self, theta: float) -> int:
        """The dimension of the unstable subspace at ``theta`` inside the sampled range: that of
        the last sample below it, updated by the located changes between."""
        theta = float(theta)
        if not self.points or not self.theta[0] <= theta <= self.theta[-1]:
            raise ParameterError("theta", f"must lie in the sampled range [{self.theta[0]:.10g}, {self.theta[-1]:.10g}] "
                                          "of a branch with stability", theta)
        k = max(int(np.searchsorted(self.theta, theta, side="right")) - 1, 0)
        count = self.points[k].n_unstable
        for c in self.changes:
            if self.theta[k] < c.theta <= theta:
                count = c.above
        return count

    def to_dict(self, eigenvalues: bool = True) -> dict:
        samples = []
        for k, p in enumerate(self.points):
            s = {"theta": float(self.theta[k]), "Omega": float(self.Omega[k]), "n": float(self.n[k]), "stable": p.stable,
                 "n_unstable": p.n_unstable, "classification": p.classification, "chart": p.chart}
            if self.sliding_stable is not None:
                s["stable_under_sliding_friction"] = bool(self.sliding_stable[k])
            if eigenvalues:
                s["eigenvalues"] = [[float(v.real), float(v.imag)] for v in p.eigenvalues]
                s["error_bounds"] = [float(b) if np.isfinite(b) else None for b in p.bounds]
            samples.append(s)
        return {**({"piece": self.piece} if self.piece is not None else {}), "ends": [e.to_dict() for e in self.ends],
                "label": self.label, "crossings": list(self.crossings),
                "stability_changes": [c.to_dict() for c in self.changes], "samples": samples}


@dataclass(frozen=True)
class SteadyStructure:
    """The steady-state structure of a body under a friction law: :func:`steady_structure`.

    Attributes
    ----------
    model : Model
        The body and friction law (Euler chart).
    branches : tuple of SteadyBranch
        The branches of steady precessions, in theta order; on a compound body each on one
        piece (:attr:`SteadyBranch.piece`), cut at the switches (ends of kind "switch").
    static_equilibria : tuple of StaticEquilibrium
        The static equilibria of the body; on a compound body each with the ``piece`` it rests
        on (phasekit.steady.pieces.StaticOnPiece).
    families : tuple of SpinFamily
        The families (the horizontal state; the spins about the vertical); on a compound body
        each with its ``piece`` (phasekit.steady.pieces.FamilyOnPiece: the tippe top's spin
        about the vertical at theta = pi is on the stem).
    status : Status
        ``Status.COMPLETED``, or ``Status.FAILED`` if a root or a limit could not be computed or
        the wall budget ran out.
    reason : str or None
        Why the computation failed, else None.
    degenerate : str or None
        Why the steady states fill a continuum rather than branches (a sphere with G at its
        centre: every orientation is a static equilibrium), else None; such a structure has no
        branches, statics or families listed, its signature is "degenerate" and :meth:`at` gives
        its isolated states.
    note : str or None
        With dissipation laws (``friction.dissipation``): which steady states they leave and
        why (phasekit.steady.dissipative: a steady state keeps its energy, so only those at
        which every law's power vanishes remain: no branch of steady precessions under rolling
        resistance, spin friction or air drag on rotation); on a compound body one of whose
        pieces is degenerate (the tippe top with offset 0: its ball centred on G), which and
        why; else None.

    Examples
    --------
    >>> import phasekit as pk
    >>> s = pk.steady_structure(pk.Spheroid(1.5, offset=0.2), pk.Viscous(0.1), samples=False)
    >>> isinstance(s, pk.steady.SteadyStructure), s.status.value, s.signature
    (True, 'completed', 'pole0-inf | static-polePi')
    """

    model: Model = field(repr=False)
    branches: tuple[SteadyBranch, ...]
    static_equilibria: tuple[StaticEquilibrium, ...]
    families: tuple[SpinFamily, ...]
    status: Status = Status.COMPLETED
    reason: str | None = None
    degenerate: str | None = None
    note: str | None = None

    @property
    def body(self):
        return self.model.body

    @property
    def signature(self) -> str:
        """The branches' ends in theta order, e.g. ``pole0-inf | static-polePi``; "cross" marks
        a family crossed on the way (part I's horizontal state); "none" when there is no branch;
        "degenerate" for a continuum of steady states (:attr:`degenerate`)."""
        if self.degenerate is not None:
            return "degenerate"
        return " | ".join(b.label for b in self.branches) or "none"

    def at(self, *, omega0: float | None = None, n0: float | None = None) -> list[FixedPoint]:
        """Every steady state with precession rate ``omega0`` (or spin ``n0``): the families' (the
        horizontal state; the spins about the vertical; a precession family's member) and the
        branches', found along each branch between its ends' exact limits (so also next to an
        end: phasekit.steady.states_at) and polished by Newton on the full equations as
        :func:`phasekit.fixed_points` polishes its own: the same states, kinds and eigenvalues.

        Parameters
        ----------
        omega0 : float, optional
            Precession rate Omega0.
        n0 : float, optional
            Spin n0; exactly one of ``omega0`` and ``n0`` is given.

        Returns
        -------
        list of FixedPoint
            The states, linearised, in the order of :func:`phasekit.fixed_points`; a
            precession at which Newton does not converge is left out, as there.

        Raises
        ------
        ParameterError
            If not exactly one of ``omega0`` and ``n0`` is given, or it is not finite or beyond
            1e12 in size (phasekit.steady.fixedpoints.FAMILY_MAX).
        ConvergenceError
            If Newton does not converge at the horizontal or the vertical state, or the
            structure failed (status "failed").
        TimeoutError
            If a wall budget in force (a caller's ``max_wall``) runs out.

        See Also
        --------
        phasekit.fixed_points
            the same states found directly, by Newton's method, without the structure

        Examples
        --------
        >>> import phasekit as pk
        >>> s = pk.steady_structure(pk.Spheroid(1.5, offset=0.2), pk.Viscous(0.1), samples=False)
        >>> [(p.kind, round(float(p.x[4]), 6)) for p in s.at(omega0=1000.0)]
        [('horizontal-like', 1.276569)]
        """
        from .states_at import states_at

        return states_at(self, omega0, n0)

    def precession(self, theta):
        """(Omega, n) of the steady precession at ``theta`` (array; Omega >= 0), NaN where
        there is none: the closed forms of phasekit.steady.branches (module notes).

        Parameters
        ----------
        theta : float or array_like
            Tilt of the axis, radians.

        Returns
        -------
        tuple of numpy.ndarray
            (Omega, n), one entry per angle (1-d arrays).
        """
        return precession_on_branch(self.body, theta)

    def to_dict(self, eigenvalues: bool = True) -> dict:
        return {"status": self.status.value, **({"reason": self.reason} if self.reason else {}),
                **({"degenerate": self.degenerate} if self.degenerate else {}),
                **({"note": self.note} if self.note else {}), "signature": self.signature,
                "branches": [b.to_dict(eigenvalues) for b in self.branches], "static_equilibria": [s.to_dict() for s in self.static_equilibria],
                "families": [f.to_dict() for f in self.families], "model": self.model.to_dict()}

    def __repr__(self) -> str:
        return (f"SteadyStructure({self.body!r}, {self.model.friction.name}, {self.signature!r}, "
                f"{len(self.static_equilibria)} static equilibria)")


# -- the structure ------------------------------------------------------------------------------


def steady_structure(body, friction: FrictionLaw, *, stability: bool = True, samples: bool = True,
                     max_wall: float | None = None) -> SteadyStructure:
    """The steady-state structure of ``body`` under ``friction`` (module notes).

    Parameters
    ----------
    body : Body
        Any built-in or user body.
    friction : FrictionLaw
        The law whose linearisation decides stability: viscous and regularised Coulomb as
        given; exact Coulomb by its rolling (no-slip) spectrum, with the sliding-friction
        criterion (the viscous law with the same mu, part I's weak friction) beside it in
        ``SteadyBranch.sliding_stable`` (the poles' closed forms in ``families``). With
        dissipation laws (:meth:`phasekit.Coulomb.with_dissipation`) only the steady states at
        which every law's power vanishes remain (:attr:`SteadyStructure.note` says which).
    stability : bool
        False: the geometry only (branches, ends, statics, families, signature), ~10x faster.
    samples : bool
        False: no samples along the branches either (their ends, the statics, the families and
        the signature only: what an atlas of classes needs, ~5 ms a body).
    max_wall : float, optional
        Wall budget in seconds (None: none; a caller's earlier deadline holds too): when it runs
        out the structure has status "failed" and a reason naming it (a structure takes about a
        second; a few with exact Coulomb's rolling families).

    Returns
    -------
    SteadyStructure
        With status "failed" and the reason if a root or a limit could not be computed or the
        budget ran out; with :attr:`SteadyStructure.degenerate` set (and no branches) for a body
        whose steady states fill a continuum (a sphere with G at its centre; a cone on its tip,
        whose precessions are the Lagrange top's, held by friction); with
        :attr:`SteadyStructure.note` set under dissipation laws.

    See Also
    --------
    phasekit.fixed_points
        the steady states of one family (one Omega0 or n0), with their linear stability
    SteadyStructure.at
        those states read off the structure

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.steady_structure(pk.EccentricSphere(0.3, A=0.38, C=0.4), pk.Viscous(0.3)).signature
    'pole0-polePi'
    >>> pk.steady_structure(pk.Spheroid(1.5, offset=0.2), pk.Coulomb(0.1), samples=False).signature
    'pole0-inf | static-polePi'
    """
    if not isinstance(body, Body):
        raise ParameterError("body", "must be a phasekit Body such as Spheroid(1.5, offset=0.1) or EccentricSphere(0.3)",
                             body)
    if not isinstance(friction, FrictionLaw):
        raise ParameterError("friction", "must be a phasekit friction law such as Viscous(0.1) or Coulomb(0.1)", friction)
    check_bool("stability", stability)
    check_bool("samples", samples)
    max_wall = check_max_wall(max_wall)
    with wall_deadline(max_wall):  # from the start: compiling the model's fields counts too
        model = Model(body, friction)
        try:
            if friction.dissipation:  # the structure without them, less what they take energy out of
                bare = _structure(Model(body, friction.with_dissipation()), stability and samples, samples)
                return _surviving(model, bare)
            return _structure(model, stability and samples, samples)
        except TimeoutError as exc:
            return SteadyStructure(model, (), (), (), Status.FAILED, f"not finished: {exc}")
        except (ArithmeticError, ValueError, RuntimeError, ConvergenceError) as exc:
            return SteadyStructure(model, (), (), (), Status.FAILED, f"{type(exc).__name__}: {exc}")


def _structure(model: Model, stability: bool, samples: bool) -> SteadyStructure:
    body, friction = model.body, model.friction
    why = degeneracy(body)
    if why is not None:  # a continuum of statics (and precessions): nothing to sample
        return SteadyStructure(model, (), (), (), degenerate=why)
    ranges = parts(body)
    if body.theta_range is not None and (why := tip_degeneracy(body)) is not None:  # no branches: the statics, the pole
        pts = special_points(body, ranges[0].lo, ranges[0].hi)
        statics, families = statics_and_families(model, ranges[0], pts, [], stability)
        return SteadyStructure(model, (), statics, families, degenerate=why)
    sliding = Model(body, Viscous(friction.mu)) if stability and friction.has_rolling_mode else None
    branches, statics, families, notes = [], [], [], []
    for part in ranges:  # the whole range of a one-piece body; a compound body's pieces
        if part.name is not None and (why := degeneracy(part.support)) is not None:
            notes.append(f"on the {part.name} ({part.lo:.6g} <= theta <= {part.hi:.6g}): {why}")
            continue
        pts = special_points(part.support, part.lo, part.hi)
        intervals = [replace(iv, ends=(classify_end(part.support, iv.lo, -1), classify_end(part.support, iv.hi, +1)))
                     for iv in branch_intervals(part.support, pts, part.edges)]
        branches += _branches(model, part, intervals, stability, samples, sliding)
        on_part = statics_and_families(model, part, pts, intervals, stability)
        statics += on_part[0]
        families += on_part[1]
    if len(ranges) > 1:
        families = in_theta_order(families)
    return SteadyStructure(model, tuple(branches), tuple(statics), tuple(families), note="; ".join(notes) or None)


def _branches(model: Model, part: Part, intervals: list[Interval], stability: bool, samples: bool,
              sliding: Model | None) -> list[SteadyBranch]:
    """The branches on ``part`` (its ``intervals`` with their ends): samples by the part's own
    support, the linearisation by the whole body's model."""
    body, empty, out = part.support, np.array([]), []
    for p in intervals:
        theta, om, n = sample_branch(body, *p.ends, p.crossings) if samples else (empty, empty, empty)
        points, changes, slide = (), (), None
        if stability and theta.size:
            theta, om, n, points, changes = stability_along(model, body, theta, om, n, p.crossings)
            if sliding is not None:
                slide = np.array([linearise_precession(sliding, float(t), float(o), float(m)).stable
                                  for t, o, m in zip(theta, om, n)])
        out.append(SteadyBranch(p.ends, theta, om, n, points, changes, p.crossings, slide,
                                part.name))
    return out


def _surviving(model: Model, bare: SteadyStructure) -> SteadyStructure:
    """``bare`` (the structure without dissipation) less the branches and families out of which
    ``model``'s dissipation laws take energy (phasekit.steady.dissipative), with its note."""
    body, vector = model.body, model.with_chart("vector")
    branches, removed = [], []
    for b in bare.branches:
        theta, om, n = (b.theta, b.Omega, b.n) if b.theta.size else sample_branch(body, *b.ends, b.crossings)
        picks = sorted({theta.size // 4, theta.size // 2, (3 * theta.size) // 4}) if theta.size else []
        if picks and not any(acting_laws(model, [0.0, 0.0, om[k], 0.0, theta[k], n[k]]) for k in picks):
            branches.append(b)
        else:
            removed.append(f"the branch {b.label}")
    families = []
    for f in bare.families:
        if f.kind == "pole":
            x, m = (vertical_state(1.0) if f.theta == 0.0 else inverted_state(1.0)), vector
        else:
            x, m = (rolling_state(body, f.theta, 1.0) if f.kind == "rolling"
                    else precession_state(body, f.theta, omega0=1.0)), model
        if acting_laws(m, x):
            removed.append(f"the {f.kind} family at theta = {f.theta:.6g}")
        else:
            families.append(f)
    note = dissipation_note(model, removed, len(branches), len(families))
    return SteadyStructure(model, tuple(branches), bare.static_equilibria, tuple(families), bare.status, bare.reason,
                           bare.degenerate, "; ".join(n for n in (bare.note, note) if n) or None)


# -- between classes ------------------------------------------------------------------------------


def _tokens(structure: SteadyStructure) -> dict:
    ends = [e for b in structure.branches for e in b.ends]
    return {"static": sum(e.kind == "static" for e in ends), "inf": sum(e.kind == "infinite-spin" for e in ends),
            "poles": frozenset(e.pole for e in ends if e.kind == "pole"),
            "cross": sum(len(b.crossings) for b in structure.branches),
            "order": tuple(e.label for e in sorted(ends, key=lambda e: e.theta) if e.kind != "pole")}


def bifurcation_between(lo: SteadyStructure, hi: SteadyStructure) -> str:
    """Name the codimension-one event that turns structure ``lo`` into ``hi`` (two bodies close
    together in parameter space, on either side of a class boundary), from how their branch
    ends differ: the degeneracies of Omega^2 = q rho_2 / D that change a signature.

    Parameters
    ----------
    lo, hi : SteadyStructure
        The structures on either side of the class boundary.

    Returns
    -------
    str
        A description of the event; "none" if the two signatures are equal.

    Examples
    --------
    >>> import phasekit as pk
    >>> lo = pk.steady_structure(pk.EccentricSphere(0.3, A=0.3, C=0.4), pk.Viscous(0.1), samples=False)
    >>> hi = pk.steady_structure(pk.EccentricSphere(0.3, A=0.45, C=0.4), pk.Viscous(0.1), samples=False)
    >>> lo.signature != hi.signature, isinstance(pk.steady.structure.bifurcation_between(lo, hi), str)
    (False, True)
    """
    a, b = _tokens(lo), _tokens(hi)
    if lo.signature == hi.signature:
        return "none"
    d_static, d_inf = abs(a["static"] - b["static"]), abs(a["inf"] - b["inf"])
    pole = a["poles"] ^ b["poles"]
    where = " and ".join("theta = 0" if p == "0" else "theta = pi" for p in sorted(pole))
    if a["cross"] != b["cross"] or (d_static == d_inf == 0 and not pole and a["order"] != b["order"]):
        return "a static equilibrium crosses an infinite-spin asymptote (q = D = 0 there: A = C, or a side static)"
    if pole and d_inf and not d_static:
        return f"an infinite-spin asymptote reaches the pole at {where} (its critical spin diverges: A rho = C h0)"
    if pole and d_static and not d_inf:
        return f"a static equilibrium reaches the pole at {where} (h_tt = 0 there: its critical spin falls to 0)"
    if not pole and d_static == 2 and not d_inf:
        return "two static equilibria are born together (a fold of the height of G)"
    if not pole and d_inf == 2 and not d_static:
        return "two infinite-spin asymptotes are born together (a double zero of D)"
    return f"a combined change ({lo.signature} -> {hi.signature})"
