"""The steady-state structure of a body (parts III and IV of the series): every branch of
steady precessions over 0 <= theta <= pi, how its ends meet the spins about the vertical, the
static equilibria and infinite-spin asymptotes, and the stability along it.

A steady precession has zero slip, G at rest and the axis at a fixed theta precessing at the
rate Omega with spin n. With c = cos(theta), H(c) = h(theta) the height of G and the regular
quantities

    q = h_theta / sin = -H'(c),   rho_2 = x_P / sin = H - c H'(c),
    z = h cos - h_theta sin,       D = (A - C) c rho_2 + C q,

(2.7) with U = V = Lambda = 0 gives (phasekit.steady.fixedpoints, module notes)

    Omega^2 = q rho_2 / D,   n = Omega z / rho_2.

Every steady precession lies on this one curve, so the branches are the maximal intervals of
theta on which q rho_2 / D > 0 (rho_2 > 0 on a convex body). An interval ends where

* q = 0 (G above the contact point: a **static** equilibrium; Omega and n tend to 0),
* D = 0 (Omega diverges: an **infinite-spin** asymptote theta_inf), or
* theta = 0 or pi (a **pole**: the branch meets the spin about the vertical there at the
  finite spin n = Omega h0 / rho with rho = h0 + h_tt the radius of curvature at the pole;
  squared, n^2 rho (A rho - C h0) = h_tt h0^2, the closed-form pole criterion of
  :func:`phasekit.theory.criteria.pole_stability_threshold`: the branch is born where the pole
  changes stability).

Where q and D vanish together (a static equilibrium with its axis horizontal, theta = pi/2 for
a flip-symmetric body; or any static equilibrium when A = C), every Omega is steady there: a
non-isolated **family** like the spins about the vertical at the poles, which the branch
crosses (the pitchfork of part I's horizontal state: the crossing is at the family's critical
rate). Part III's abstract calls the branches non-isolated fixed-point branches; the
four kinds it names are not spelled out in the abstract, and phasekit classifies each branch
by its two ends instead (:attr:`SteadyStructure.signature`).

Omega > 0 represents each branch; (-Omega, -n) is the same branch seen in a mirror.
Stability along a branch is that of the law given: the Euler chart's exact Jacobian away from
the poles, and near them (within POLE_ZONE) the vector chart in axes turning with the
precession, J - Omega G (G the generator of rotations about the vertical), which is regular at
the poles and has the same real parts (plus two zero eigenvalues: |k| and the azimuth).
"""

from __future__ import annotations

import functools
import threading
from dataclasses import dataclass, field, replace

import casadi as ca
import numpy as np

from .._runtime.errors import ConvergenceError, ParameterError, SearchStatus, Status
from .._runtime.validate import check_bool, check_finite
from ..bodies.body import Body
from ..core.charts import EULER, VECTOR, euler_to_vector
from ..core.model import Model
from ..friction.laws import FrictionLaw, Viscous
from ..theory.criteria import PoleCriterion, pole_stability_threshold
from .fixedpoints import (
    FixedPoint,
    _eigen_with_bounds,
    _jacobian_error,
    _law_jacobian,
    _mode_for,
    find_fixed_point,
    linearise,
)

__all__ = ["BranchEnd", "StabilityChange", "SteadyBranch", "StaticEquilibrium", "SpinFamily", "SteadyStructure",
           "steady_structure", "precession_on_branch", "linearise_precession", "bifurcation_between", "RollingMotion",
           "rolling_motion", "rolling_state", "END_KINDS", "manifold_runs", "settled_motion"]

#: how a branch ends (see the module notes)
END_KINDS = ("pole", "static", "infinite-spin")
#: grid on which the roots of q and D are bracketed before Brent's method refines them (two
#: roots closer than its spacing show as a dip of |q| or |D| toward zero and are found too)
ROOT_GRID = 2049
#: roots of q and D closer than this (in theta) are one point where both vanish (a family)
COINCIDENT = 1e-10
#: the samples of a branch stop this far (in theta) from a static or infinite-spin end: the
#: closed forms lose digits as q or D -> 0 (relative error ~1e-16 / distance)
END_GAP = 1e-6
#: ... and this far from a pole, where the branch meets the spin about the vertical exactly
POLE_GAP = 1e-6
#: samples keep this far from a family crossing, except the crossing itself (exact limit there)
CROSSING_GAP = 1e-4
#: within this of a pole, stability is computed in the vector chart turning with the precession
POLE_ZONE = 0.05
#: stability changes are located to this in theta
CHANGE_XTOL = 1e-9
#: adaptive sampling: largest chord and turning angle in the compact coordinates
#: (theta / pi, (2/pi) atan Omega, (2/pi) atan n)
MAX_CHORD, MAX_TURN = 0.02, 0.15
#: most samples on one branch
MAX_SAMPLES = 1200


# -- result objects ------------------------------------------------------------------------------


@dataclass(frozen=True)
class BranchEnd:
    """One end of a branch: ``kind`` in END_KINDS, its ``theta`` (located to ~1e-15 by Brent's
    method on q or D, exactly 0 or pi at a pole) and, at a pole, the signed spin ``n`` (on the
    Omega > 0 branch) with which the branch meets the spin about the vertical, and that pole's
    ``Omega`` limit."""

    kind: str
    theta: float
    pole: str | None = None  # "0" or "pi"
    n: float | None = None
    Omega: float | None = None

    @property
    def label(self) -> str:
        if self.kind == "pole":
            return "pole0" if self.pole == "0" else "polePi"
        return "inf" if self.kind == "infinite-spin" else self.kind

    def to_dict(self) -> dict:
        d = {"kind": self.kind, "theta": self.theta}
        if self.kind == "pole":
            d.update(pole=self.pole, n=self.n, spin=abs(self.n), Omega=self.Omega)
        return d


@dataclass(frozen=True)
class StabilityChange:
    """A point of a branch where its stability changes: a real eigenvalue (``kind`` "real") or
    a complex pair ("complex") crosses the imaginary axis. ``bracket`` holds states of opposite
    stability (n_unstable ``below`` at the lower theta, ``above`` at the upper), ``theta`` its
    midpoint; ``status`` "converged" when the bracket is narrower than CHANGE_XTOL."""

    theta: float
    bracket: tuple[float, float]
    kind: str
    Omega: float
    n: float
    below: int
    above: int
    status: SearchStatus = SearchStatus.CONVERGED

    def to_dict(self) -> dict:
        return {"theta": self.theta, "bracket": list(self.bracket), "kind": self.kind, "Omega": self.Omega, "n": self.n,
                "n_unstable_below": self.below, "n_unstable_above": self.above, "status": self.status.value}


@dataclass(frozen=True)
class SteadyBranch:
    """A branch of steady precessions: its two ends (ordered by theta), samples (theta, Omega, n)
    adaptive in arc length, and at each sample the linearisation of the law (``points``: a
    :class:`FixedPoint` each), the stability changes and the families it crosses."""

    ends: tuple[BranchEnd, BranchEnd]
    theta: np.ndarray = field(repr=False)
    Omega: np.ndarray = field(repr=False)
    n: np.ndarray = field(repr=False)
    points: tuple[FixedPoint, ...] = field(default=(), repr=False)
    changes: tuple[StabilityChange, ...] = ()
    crossings: tuple[float, ...] = ()
    sliding_stable: np.ndarray | None = field(default=None, repr=False)

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
        return {"ends": [e.to_dict() for e in self.ends], "label": self.label, "crossings": list(self.crossings),
                "stability_changes": [c.to_dict() for c in self.changes], "samples": samples}


@dataclass(frozen=True)
class StaticEquilibrium:
    """G straight above the contact point (h_theta = 0), at rest: ``stable`` where the height of
    G is a minimum (h_tt > 0), ``kind`` "pole" at theta = 0 or pi, else "tilted"."""

    theta: float
    height: float
    h_tt: float
    kind: str

    @property
    def stable(self) -> bool:
        return self.h_tt > 0

    def to_dict(self) -> dict:
        return {"theta": self.theta, "kind": self.kind, "height": self.height, "h_tt": self.h_tt,
                "static_stability": "minimum (stable)" if self.h_tt > 0 else "maximum (unstable)" if self.h_tt < 0
                else "degenerate"}


@dataclass(frozen=True)
class SpinFamily:
    """A non-isolated family of steady states at one theta, with any value of its parameter:

    * ``pole``: the spin about the vertical at theta = 0 or pi (parameter "n");
    * ``precession``: where q = D = 0, a precession at any rate Omega with n = 0 (part I's
      horizontal state of a flip-symmetric body);
    * ``rolling``: at a tilted static equilibrium, rolling along a straight line at any spin n
      (Omega = 0, G moving at n x_P: part I's rolling on the equator).

    ``criticals`` are the values of abs(parameter) where its stability changes (the closed-form
    pole criterion; for a precession family the rate at which a branch crosses it; located by
    bisection for a rolling family), ``stable_on`` the stability on each interval between
    them from 0 up (None: not computed), ``branch_meets`` whether a branch ends on or crosses
    the family."""

    kind: str
    theta: float
    parameter: str
    criticals: tuple[float, ...]
    stable_on: tuple[bool | None, ...]
    branch_meets: bool
    criterion: PoleCriterion | None = field(default=None, repr=False)

    @property
    def critical(self) -> float | None:
        return self.criticals[0] if self.criticals else None

    @property
    def stable_above(self) -> bool | None:
        """Whether the family is stable beyond its last critical value (None without one)."""
        return self.stable_on[-1] if self.criticals else None

    def to_dict(self) -> dict:
        return {"kind": self.kind, "theta": self.theta, "parameter": self.parameter, "critical": self.critical,
                "criticals": list(self.criticals), "stable_on_intervals": list(self.stable_on),
                "stable_above_critical": self.stable_above, "branch_meets": self.branch_meets}


@dataclass(frozen=True)
class SteadyStructure:
    """The steady-state structure of a body under a friction law: :func:`steady_structure`.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
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

    @property
    def body(self):
        return self.model.body

    @property
    def signature(self) -> str:
        """The branches' ends in theta order, e.g. ``pole0-inf | static-polePi``; "cross" marks
        a family crossed on the way (part I's horizontal state); "none" when there is no branch."""
        return " | ".join(b.label for b in self.branches) or "none"

    def at(self, *, omega0: float | None = None, n0: float | None = None) -> list[FixedPoint]:
        """Every steady state with precession rate ``omega0`` (or spin ``n0``): the families' (the
        horizontal state; the spins about the vertical) and the branches', found on the sampled
        curves and polished by Newton on the full equations as :func:`phasekit.fixed_points`
        does (the same states and eigenvalues)."""
        return _states_at(self, omega0, n0)

    def precession(self, theta):
        """(Omega, n) of the steady precession at ``theta`` (array; Omega >= 0), NaN where
        there is none: the closed forms of the module notes."""
        return precession_on_branch(self.body, theta)

    def to_dict(self, eigenvalues: bool = True) -> dict:
        return {"status": self.status.value, **({"reason": self.reason} if self.reason else {}),
                "signature": self.signature, "branches": [b.to_dict(eigenvalues) for b in self.branches],
                "static_equilibria": [s.to_dict() for s in self.static_equilibria],
                "families": [f.to_dict() for f in self.families], "model": self.model.to_dict()}

    def __repr__(self) -> str:
        return (f"SteadyStructure({self.body!r}, {self.model.friction.name}, {self.signature!r}, "
                f"{len(self.static_equilibria)} static equilibria)")


# -- the geometry of the steady precessions -----------------------------------------------------

_LOCK = threading.Lock()
_GEOMETRY: dict[str, ca.Function] = {}


def _geometry_function(body) -> ca.Function:
    """(theta, shape, A, C) -> (q, rho_2, z, D, h, h_tt, dq/dtheta, dD/dtheta), compiled once
    per body structure."""
    key = body.structure_key
    with _LOCK:
        if key not in _GEOMETRY:
            th, sh = ca.SX.sym("theta"), ca.SX.sym("shape", body.n_shape)
            A, C, cs = ca.SX.sym("A"), ca.SX.sym("C"), ca.SX.sym("c")
            Hc = body.height(cs, sh)
            dHc = ca.jacobian(Hc, cs)
            c, s = ca.cos(th), ca.sin(th)
            H, dH = ca.substitute(Hc, cs, c), ca.substitute(dHc, cs, c)
            q = -dH
            rho2 = H - c * dH
            z = H * c + dH * s * s
            D = (A - C) * c * rho2 + C * q
            ht = -dH * s
            htt = ca.jacobian(ht, th)
            _GEOMETRY[key] = ca.Function("precession_geometry", [th, sh, A, C],
                                         [q, rho2, z, D, H, htt, ca.jacobian(q, th), ca.jacobian(D, th)],
                                         ["theta", "shape", "A", "C"], ["q", "rho2", "z", "D", "h", "h_tt", "dq", "dD"])
            _GEOMETRY[key + ":qD"] = ca.Function("q_and_D", [th, sh, A, C], [q, D])
        return _GEOMETRY[key]


def _geometry(body, theta) -> tuple[np.ndarray, ...]:
    """(q, rho_2, z, D, h, h_tt, dq, dD) at an array of theta."""
    th = np.atleast_1d(np.asarray(theta, dtype=float)).ravel()
    f = _geometry_function(body)
    if th.size > 1:
        f = _mapped(f, th.size)
    shape = np.tile(np.asarray(body.shape_params, dtype=float)[:, None], (1, th.size))
    out = f(th[None, :], shape, body.A, body.C)
    return tuple(np.asarray(o).ravel() for o in out)


@functools.lru_cache(maxsize=64)
def _mapped(f: ca.Function, n: int) -> ca.Function:
    """``f`` mapped over n points (building a map costs more than evaluating it: keep them)."""
    return f.map(n)


def precession_on_branch(body, theta) -> tuple[np.ndarray, np.ndarray]:
    """(Omega, n) of the steady precession at ``theta`` (array), Omega >= 0; NaN where there is
    none (q rho_2 / D < 0 or D = 0). Exactly at a point where q = D = 0 the ratio is 0/0: the
    family crossing is given by :func:`steady_structure`, not here."""
    q, rho2, z, D = _geometry(body, theta)[:4]
    with np.errstate(divide="ignore", invalid="ignore"):
        om2 = q * rho2 / D
        om = np.where(np.isfinite(om2) & (om2 >= 0), np.sqrt(np.abs(om2)), np.nan)
        n = om * z / rho2
    return om, n


# -- roots of q and D ---------------------------------------------------------------------------


def _roots(fun, grid: np.ndarray, values: np.ndarray) -> list[float]:
    """Every root of ``fun`` in the open interval of ``grid``: sign changes refined by Brent's
    method, exact zeros on the grid, and pairs of roots hidden between grid points (a local
    extremum of |f| that is near zero: the extremum is located and tested for a sign change)."""
    from scipy.optimize import brentq, minimize_scalar

    sgn = np.sign(values)
    roots = [float(t) for t in grid[1:-1][sgn[1:-1] == 0.0]]
    for k in np.flatnonzero(sgn[:-1] * sgn[1:] < 0):
        roots.append(float(brentq(fun, grid[k], grid[k + 1], xtol=1e-16, rtol=4 * np.finfo(float).eps, maxiter=200)))
    a = np.abs(values)
    dips = np.flatnonzero((a[1:-1] < a[:-2]) & (a[1:-1] < a[2:]) & (sgn[:-2] == sgn[1:-1]) & (sgn[1:-1] == sgn[2:])
                          & (sgn[1:-1] != 0)) + 1
    for k in dips:  # a dip toward zero: does f cross between grid[k-1] and grid[k+1]?
        res = minimize_scalar(lambda t, s=sgn[k]: s * fun(t), bounds=(grid[k - 1], grid[k + 1]), method="bounded",
                              options={"xatol": 1e-14})
        if res.fun < 0:
            t0 = float(res.x)
            roots.append(float(brentq(fun, grid[k - 1], t0, xtol=1e-16)))
            roots.append(float(brentq(fun, t0, grid[k + 1], xtol=1e-16)))
    return sorted(r for r in roots if 0.0 < r < np.pi)


def _special_points(body) -> list[dict]:
    """The interior points where q, D or both vanish, in theta order."""
    grid = np.linspace(0.0, np.pi, ROOT_GRID)
    _geometry_function(body)
    f = _mapped(_GEOMETRY[body.structure_key + ":qD"], ROOT_GRID)
    shape = np.tile(np.asarray(body.shape_params, dtype=float)[:, None], (1, ROOT_GRID))
    q, D = (np.asarray(v).ravel() for v in f(grid[None, :], shape, body.A, body.C))
    fq = lambda t: float(_geometry(body, t)[0][0])  # noqa: E731
    fD = lambda t: float(_geometry(body, t)[3][0])  # noqa: E731
    pts = [{"theta": t, "q": True, "D": False} for t in _roots(fq, grid, q)]
    for t in _roots(fD, grid, D):
        near = [p for p in pts if p["q"] and abs(p["theta"] - t) <= COINCIDENT]
        if near:
            near[0]["D"] = True
        else:
            pts.append({"theta": t, "q": False, "D": True})
    if body.flip_symmetric:  # both vanish exactly at pi/2 by symmetry: say so exactly
        for p in pts:
            if p["q"] and p["D"] and abs(p["theta"] - np.pi / 2) <= COINCIDENT:
                p["theta"] = np.pi / 2
    return sorted(pts, key=lambda p: p["theta"])


def _omega2(body, theta: float) -> float:
    q, rho2, _, D = _geometry(body, theta)[:4]
    return float(q[0] * rho2[0] / D[0])


def _family_rate2(body, theta: float) -> float:
    """Omega^2 of a branch through a point where q = D = 0: the limit (dq/dtheta) rho_2 / (dD/dtheta)."""
    g = _geometry(body, theta)
    return float(g[6][0] * g[1][0] / g[7][0])


# -- branches -----------------------------------------------------------------------------------


def _pieces(body, pts: list[dict]) -> list[dict]:
    """The maximal intervals with Omega^2 > 0, joined across family points."""
    edges = [{"theta": 0.0, "pole": "0"}] + pts + [{"theta": np.pi, "pole": "pi"}]
    pieces = []
    for lo, hi in zip(edges[:-1], edges[1:]):
        mid = 0.5 * (lo["theta"] + hi["theta"])
        if _omega2(body, mid) > 0:
            if pieces and pieces[-1]["hi"] is lo and lo.get("q") and lo.get("D"):
                pieces[-1]["hi"] = hi  # the branch crosses a family here
                pieces[-1]["crossings"].append(lo["theta"])
            else:
                pieces.append({"lo": lo, "hi": hi, "crossings": []})
    return pieces


def _end(body, edge: dict, side: int) -> BranchEnd:
    """Classify a piece's end at ``edge`` (side -1: the piece lies above it in theta)."""
    t = float(edge["theta"])
    if "pole" in edge:
        q, rho2, z, D = (float(v[0]) for v in _geometry(body, t)[:4])
        if D == 0.0:
            return BranchEnd("infinite-spin", t)
        if q == 0.0:
            return BranchEnd("static", t)
        om = float(np.sqrt(q * rho2 / D))
        return BranchEnd("pole", t, pole=edge["pole"], n=om * z / rho2, Omega=om)
    if edge["q"] and not edge["D"]:
        return BranchEnd("static", t)
    if edge["D"] and not edge["q"]:
        return BranchEnd("infinite-spin", t)
    # a family point that ends the branch (degenerate): by the limit from the branch's side
    near = _omega2(body, t - side * 1e-4)
    far = _omega2(body, t - side * 1e-2)
    return BranchEnd("static" if near < far else "infinite-spin", t)


# -- sampling -----------------------------------------------------------------------------------


def _compact(theta, om, n) -> np.ndarray:
    return np.column_stack([theta / np.pi, 2 / np.pi * np.arctan(om), 2 / np.pi * np.arctan(n)])


def _curve(body, theta, crossings) -> tuple[np.ndarray, np.ndarray]:
    om, n = precession_on_branch(body, theta)
    for t in crossings:  # the 0/0 limit at a family point (samples keep CROSSING_GAP away otherwise)
        sel = np.abs(theta - t) < 1e-12
        if np.any(sel):
            _, rho2, z = _geometry(body, t)[:3]
            om[sel] = np.sqrt(_family_rate2(body, t))
            n[sel] = om[sel] * z[0] / rho2[0]
    return om, n


def _off_crossings(theta: np.ndarray, crossings) -> np.ndarray:
    """Drop points within CROSSING_GAP of a family crossing (but not the crossing itself): there
    q / D is 0/0 and the closed form loses digits (~1e-16 / distance)."""
    for t in crossings:
        d = np.abs(theta - t)
        theta = theta[(d == 0) | (d >= CROSSING_GAP)]
    return theta


def _sample(body, lo: BranchEnd, hi: BranchEnd, crossings) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """theta, Omega, n adaptive in arc length of the compact coordinates, with geometric
    approaches to the ends."""
    gap = lambda e: POLE_GAP if e.kind == "pole" else END_GAP  # noqa: E731
    a, b = lo.theta + gap(lo), hi.theta - gap(hi)
    if not a < b:
        return np.array([]), np.array([]), np.array([])
    k = np.arange(33)
    theta = a + (b - a) * 0.5 * (1 - np.cos(np.pi * k / 32))
    for j in range(2, 7):  # geometric approach to each end
        theta = np.append(theta, [lo.theta + 10.0 ** -j, hi.theta - 10.0 ** -j])
    theta = _off_crossings(np.append(theta, crossings), crossings)
    theta = np.unique(theta[(theta >= a) & (theta <= b)])
    for _ in range(12):
        om, n = _curve(body, theta, crossings)
        P = _compact(theta, om, n)
        d = np.diff(P, axis=0)
        L = np.linalg.norm(d, axis=1)
        split = L > MAX_CHORD
        cosang = np.sum(d[:-1] * d[1:], axis=1) / np.maximum(L[:-1] * L[1:], 1e-300)
        bend = np.arccos(np.clip(cosang, -1.0, 1.0)) > MAX_TURN
        split[:-1] |= bend
        split[1:] |= bend
        split &= np.diff(theta) > 1e-9
        if not split.any() or theta.size >= MAX_SAMPLES:
            break
        theta = np.unique(_off_crossings(np.concatenate([theta, 0.5 * (theta[:-1] + theta[1:])[split]]), crossings))
    om, n = _curve(body, theta, crossings)
    ok = np.isfinite(om) & np.isfinite(n)
    return theta[ok], om[ok], n[ok]


# -- stability along a branch -------------------------------------------------------------------

#: generator of rotations about the vertical acting on (k, w, v) of the vector chart
_G = np.zeros((8, 8))
for _i in (0, 3):
    _G[_i, _i + 1], _G[_i + 1, _i] = -1.0, 1.0
_G[6, 7], _G[7, 6] = -1.0, 1.0


def linearise_precession(model: Model, theta: float, Omega: float, n: float, *, chart: str = "auto") -> FixedPoint:
    """The linearisation of the law about the steady precession (theta, Omega, n).

    ``chart="euler"``: :func:`phasekit.linearise` in the paper's variables. ``"rotating"``: the
    vector chart (k, w, v) in axes turning at Omega about the vertical, J - Omega G, regular at
    the poles (two more zero eigenvalues; tilt modes' imaginary parts shifted by Omega, real
    parts the same). ``"auto"``: rotating within POLE_ZONE of a pole, Euler elsewhere."""
    if chart == "auto":
        chart = "rotating" if min(theta, np.pi - theta) < POLE_ZONE else "euler"
    y = np.array([0.0, 0.0, Omega, 0.0, theta, n])
    if chart == "euler":
        return linearise(model if model.chart is EULER else model.with_chart("euler"), y, kind="intermediate")
    mv = model if model.chart is VECTOR else model.with_chart("vector")
    x = euler_to_vector(y)
    mode = _mode_for(mv)
    jac = _law_jacobian(mv, mode)
    keep = np.arange(8) if mode.value != "rolling" else np.array([0, 1, 2, 3, 4, 5])
    G = _G[np.ix_(keep, keep)]

    def rotating(xx):
        J, L = jac(xx)
        return J - Omega * G, L

    f = mv._rhs(x, mode) - Omega * (_G @ x)  # zero at a steady precession
    J, L = rotating(x)
    lam, V, bounds = _eigen_with_bounds(J, _jacobian_error(mv, mode, rotating, x, f, J))
    if L is not None:
        V = L @ V
    law = "coulomb-rolling" if mode.value == "rolling" else mv.friction.name
    return FixedPoint("intermediate", "vector-rotating", x, y, lam, V, float(np.max(np.abs(f))), law, error_bounds=bounds)


def _n_positive(fp: FixedPoint) -> int:
    """The sign count that bisection follows across a change of stability: eigenvalues whose
    real part is positive beyond its error bound (within ~bound/slope of the crossing the
    crossing eigenvalue is not counted, so the bracket closes on the last decided states)."""
    return fp.n_unstable


def _locate_change(at, lo: float, hi: float, f_lo: FixedPoint, f_hi: FixedPoint):
    """Bisect one change of stability between two states with different counts to CHANGE_XTOL;
    returns the change and the state at the upper end of its bracket."""
    c_lo = _n_positive(f_lo)
    while hi - lo > CHANGE_XTOL:
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        fm = at(mid)
        if _n_positive(fm) == c_lo:
            lo, f_lo = mid, fm
        else:
            hi, f_hi = mid, fm
    # the kind: the eigenvalue nearest the imaginary axis on the unstable side
    side = f_hi if _n_positive(f_hi) > c_lo else f_lo
    mask = side._unstable_mask()
    lam, b = side.eigenvalues[mask], side.bounds[mask]
    k = np.argsort(lam.real)[:1]
    kind = "complex" if k.size and abs(lam[k[0]].imag) > b[k[0]] else "real"
    t = 0.5 * (lo + hi)
    status = SearchStatus.CONVERGED if hi - lo <= CHANGE_XTOL else SearchStatus.BRACKET_ONLY
    om, n = at.curve(t)
    return StabilityChange(t, (lo, hi), kind, om, n, f_lo.n_unstable, f_hi.n_unstable, status), hi, f_hi


def _tracks(points: list[FixedPoint]) -> list[np.ndarray | None]:
    """Real parts of the eigenvalues followed from sample to sample (the nearest match), one
    array per sample in a common order; None where the chart (and so the spectrum) changes."""
    from scipy.optimize import linear_sum_assignment

    out, prev = [], None
    for p in points:
        lam = p.eigenvalues.copy()
        if prev is not None and prev.size == lam.size:
            cost = np.abs(prev[:, None] - lam[None, :])
            _, col = linear_sum_assignment(cost)
            lam = lam[col]
        elif prev is not None:
            out.append(None)
            prev = lam
            continue
        out.append(lam)
        prev = lam
    return out


def _hidden(theta: np.ndarray, points: list[FixedPoint]) -> list[float]:
    """Points to add where a followed eigenvalue's real part may cross zero and come back
    between two samples of equal stability: its cubic Hermite interpolant (slopes from the
    neighbours) changes sign inside the interval."""
    tr = _tracks(points)
    new = []
    for k in range(1, len(points) - 2):
        ends = tr[k - 1:k + 3]
        if any(e is None for e in ends) or _n_positive(points[k]) != _n_positive(points[k + 1]):
            continue
        r = np.array([e.real for e in ends])  # 4 x m
        # only real parts decided at both ends (not zeros, not rounding about the axis)
        b = 10 * max(points[k].bounds.max(), points[k + 1].bounds.max())
        undecided = (np.abs(r[1]) <= b) | (np.abs(r[2]) <= b)
        t = theta[k - 1:k + 3]
        h = t[2] - t[1]
        d1 = (r[2] - r[0]) / (t[2] - t[0])
        d2 = (r[3] - r[1]) / (t[3] - t[1])
        s = np.linspace(0.0, 1.0, 17)[1:-1, None]
        cubic = ((2 * s**3 - 3 * s**2 + 1) * r[1] + (s**3 - 2 * s**2 + s) * h * d1 + (-2 * s**3 + 3 * s**2) * r[2]
                 + (s**3 - s**2) * h * d2)
        flips = (np.sign(cubic) != np.sign(r[1])) & (np.sign(r[1]) == np.sign(r[2])) & ~undecided
        if flips.any():
            new += list(t[1] + h * np.array([0.25, 0.5, 0.75]))
    return new


def _stability(model, body, theta, om, n, crossings):
    """The law's linearisation at every sample (more samples where an eigenvalue may cross the
    axis and come back between two of them), and every change of stability located."""
    def at(t):
        o, m = _curve(body, np.array([t]), crossings)
        return linearise_precession(model, t, float(o[0]), float(m[0]))

    at.curve = lambda t: tuple(float(v[0]) for v in _curve(body, np.array([t]), crossings))
    points = [linearise_precession(model, float(t), float(o), float(m)) for t, o, m in zip(theta, om, n)]
    for _ in range(4):
        extra = np.setdiff1d(_off_crossings(np.array(_hidden(theta, points)), crossings), theta)
        if not extra.size:
            break
        merged = np.concatenate([theta, extra])
        order = np.argsort(merged)
        pool = points + [at(float(t)) for t in extra]
        points = [pool[i] for i in order]
        theta = merged[order]
    om, n = _curve(body, theta, crossings)
    changes = []
    for k in range(len(points) - 1):
        lo, f_lo = float(theta[k]), points[k]
        while _n_positive(f_lo) != _n_positive(points[k + 1]):  # every change between the two samples
            change, lo, f_lo = _locate_change(at, lo, float(theta[k + 1]), f_lo, points[k + 1])
            changes.append(change)
    return theta, om, n, tuple(points), tuple(changes)


# -- statics and families -----------------------------------------------------------------------


def _statics(body, pts) -> tuple[StaticEquilibrium, ...]:
    thetas = [0.0] + [p["theta"] for p in pts if p["q"]] + [np.pi]
    h, htt = _geometry(body, thetas)[4:6]
    return tuple(StaticEquilibrium(float(t), float(h[i]), float(htt[i]), "pole" if t in (0.0, np.pi) else "tilted")
                 for i, t in enumerate(thetas))


def _families(model, body, pts, pieces, stability: bool) -> tuple[SpinFamily, ...]:
    ends = {e.pole for p in pieces for e in (p["lo_end"], p["hi_end"]) if e.kind == "pole"}
    static_ends = {e.theta for p in pieces for e in (p["lo_end"], p["hi_end"]) if e.kind == "static"}
    out = []
    for pole, t in (("upright", 0.0), ("inverted", np.pi)):
        crit = pole_stability_threshold(body, pole)
        side = (not crit.stable_above, crit.stable_above) if crit.threshold else (crit.stable(1.0),)
        out.append(SpinFamily("pole", t, "n", (crit.threshold,) if crit.threshold else (), side,
                              ("0" if t == 0.0 else "pi") in ends, crit))
    crossed = {c for p in pieces for c in p["crossings"]}
    for p in pts:
        if p["q"] and p["D"]:
            om2 = _family_rate2(body, p["theta"])
            crit = float(np.sqrt(om2)) if om2 > 0 else None
            side = _precession_family_side(model, p["theta"], crit) if stability else None
            out.append(SpinFamily("precession", p["theta"], "Omega", (crit,) if crit else (),
                                  (None if side is None else not side, side) if crit else (None,), p["theta"] in crossed))
        if p["q"]:
            crits, side = _rolling_family(model, p["theta"]) if stability else ((), (None,))
            out.append(SpinFamily("rolling", p["theta"], "n", crits, side, p["theta"] in static_ends or p["theta"] in crossed))
    return tuple(out)


def _precession_family_side(model, theta: float, crit: float | None) -> bool | None:
    """Whether the precession family at ``theta`` (n = 0 there) is stable above its critical rate
    (None when the linearisation does not change there)."""
    if crit is None:
        return None
    below = linearise_precession(model, theta, 0.8 * crit, 0.0, chart="euler")
    above = linearise_precession(model, theta, 1.25 * crit, 0.0, chart="euler")
    if below.stable == above.stable:
        return None
    return bool(above.stable)


def rolling_state(body, theta: float, n: float) -> np.ndarray:
    """Rolling along a straight line at a static equilibrium theta (h_theta = 0): Omega = 0,
    Lambda = 0, zero slip, so V = -n x_P (paper's variables)."""
    h, ht, _ = body.h(theta)
    xP = h * np.sin(theta) + ht * np.cos(theta)
    return np.array([0.0, -n * xP, 0.0, 0.0, theta, n])


#: the spins scanned for changes of stability of a rolling family
ROLLING_SCAN = np.geomspace(1e-2, 1e3, 101)


def _rolling_family(model, theta: float) -> tuple[tuple[float, ...], tuple[bool, ...]]:
    """The spins where the straight rolling at ``theta`` changes stability (scan, then bisection
    in log n to 1e-10 relative) and the stability between them."""
    me = model if model.chart is EULER else model.with_chart("euler")
    count = lambda n: linearise(me, rolling_state(model.body, theta, n), kind="rolling").n_unstable  # noqa: E731
    counts = [count(n) for n in ROLLING_SCAN]
    crits = []
    for k in np.flatnonzero(np.diff(counts) != 0):
        lo, hi = np.log(ROLLING_SCAN[k]), np.log(ROLLING_SCAN[k + 1])
        c_lo = counts[k]
        while hi - lo > 1e-10:
            mid = 0.5 * (lo + hi)
            if count(np.exp(mid)) == c_lo:
                lo = mid
            else:
                hi = mid
        crits.append(float(np.exp(0.5 * (lo + hi))))
    side = tuple(bool(counts[0] == 0) if i == 0 else bool(counts[k + 1] == 0)
                 for i, k in enumerate([-1, *np.flatnonzero(np.diff(counts) != 0)]))
    return tuple(crits), side


# -- the structure ------------------------------------------------------------------------------


def steady_structure(body, friction: FrictionLaw, *, stability: bool = True, samples: bool = True) -> SteadyStructure:
    """The steady-state structure of ``body`` under ``friction`` (module notes).

    Parameters
    ----------
    body : Body
        Any built-in or user body.
    friction : FrictionLaw
        The law whose linearisation decides stability: viscous and regularised Coulomb as
        given; exact Coulomb by its rolling (no-slip) spectrum, with the sliding-friction
        criterion (the viscous law with the same mu, part I's weak friction) beside it in
        ``SteadyBranch.sliding_stable`` (the poles' closed forms in ``families``).
    stability : bool
        False: the geometry only (branches, ends, statics, families, signature), ~10x faster.
    samples : bool
        False: no samples along the branches either (their ends, the statics, the families and
        the signature only: what an atlas of classes needs, ~5 ms a body).

    Returns
    -------
    SteadyStructure
        With status "failed" and the reason if a root or a limit could not be computed.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
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
    model = Model(body, friction)
    try:
        return _structure(model, stability and samples, samples)
    except (ArithmeticError, ValueError, RuntimeError, ConvergenceError) as exc:
        return SteadyStructure(model, (), (), (), Status.FAILED, f"{type(exc).__name__}: {exc}")


def _structure(model: Model, stability: bool, samples: bool) -> SteadyStructure:
    body, friction = model.body, model.friction
    pts = _special_points(body)
    pieces = _pieces(body, pts)
    for p in pieces:
        p["lo_end"], p["hi_end"] = _end(body, p["lo"], -1), _end(body, p["hi"], +1)
    branches = []
    sliding = Model(body, Viscous(friction.mu)) if stability and friction.has_rolling_mode else None
    empty = np.array([])
    for p in pieces:
        theta, om, n = _sample(body, p["lo_end"], p["hi_end"], p["crossings"]) if samples else (empty, empty, empty)
        points, changes, slide = (), (), None
        if stability and theta.size:
            theta, om, n, points, changes = _stability(model, body, theta, om, n, p["crossings"])
            if sliding is not None:
                slide = np.array([linearise_precession(sliding, float(t), float(o), float(m)).stable
                                  for t, o, m in zip(theta, om, n)])
        branches.append(SteadyBranch((p["lo_end"], p["hi_end"]), theta, om, n, points, changes,
                                     tuple(p["crossings"]), slide))
    return SteadyStructure(model, tuple(branches), _statics(body, pts), _families(model, body, pts, pieces, stability))


def _states_at(structure: SteadyStructure, omega0, n0) -> list[FixedPoint]:
    """The families' states and the branches' states at one rate or spin, as
    :func:`phasekit.fixed_points` finds them (for a flip-symmetric body the states at
    theta > pi/2, mirror images of those below, are left out as it does)."""
    from .fixedpoints import _pole, horizontal_state

    if (omega0 is None) == (n0 is None):
        raise ParameterError("omega0", "or `n0` must be given, not both", show_value=False)
    model, body = structure.model, structure.body
    me = model if model.chart is EULER else model.with_chart("euler")
    out = []
    if omega0 is not None:
        omega0 = check_finite("omega0", omega0)
        for fam in structure.families:
            if fam.kind == "precession" and fam.theta == np.pi / 2:
                out.append(find_fixed_point(me, horizontal_state(omega0), kind="horizontal", value=omega0))
    else:
        n0 = check_finite("n0", n0)
        mv = model.with_chart("vector")
        out.append(_pole(mv, n0, "upright"))
        if not body.flip_symmetric:
            out.append(_pole(mv, n0, "inverted"))
    for b in structure.branches:
        out += _branch_states(me, b, omega0, n0)
    if body.flip_symmetric:
        out = [fp for fp in out if fp.kind != "intermediate" or fp.x[4] < np.pi / 2]
    return out


def _branch_states(model, branch: SteadyBranch, omega0, n0) -> list[FixedPoint]:
    """The states of ``branch`` with rate omega0 (or spin n0), via Newton on the full equations
    (Euler chart) from the root of the precession residual between two samples."""
    from scipy.optimize import brentq

    from .fixedpoints import precession_residual, precession_state

    body = model.body
    fixed, value = ("Omega", omega0) if omega0 is not None else ("n", n0)
    th = branch.theta
    if th.size < 2:
        return []
    g = precession_residual(body, th, omega0=omega0, n0=n0)
    out = []
    f = lambda t: precession_residual(body, t, omega0=omega0, n0=n0)  # noqa: E731
    for k in np.flatnonzero(np.sign(g[:-1]) * np.sign(g[1:]) < 0):
        t = float(brentq(f, th[k], th[k + 1], xtol=1e-15, rtol=4 * np.finfo(float).eps))
        if any(abs(t - c) < 1e-7 for c in branch.crossings):  # the family's state, not the branch's
            continue
        guess = precession_state(body, t, omega0=omega0, n0=n0)
        fp = find_fixed_point(model, guess, kind="intermediate", value=value, fixed=fixed)
        out.append(replace(fp, parameter={fixed: value, "theta": float(fp.x[4])}))
    return out


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

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> lo = pk.steady_structure(pk.EccentricSphere(0.3, A=0.3, C=0.4), pk.Viscous(0.1), samples=False)
    >>> hi = pk.steady_structure(pk.EccentricSphere(0.3, A=0.45, C=0.4), pk.Viscous(0.1), samples=False)
    >>> lo.signature != hi.signature, isinstance(pk.steady.bifurcation_between(lo, hi), str)
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


@dataclass(frozen=True)
class RollingMotion:
    """A steady rolling motion under exact Coulomb friction: the axis at a fixed theta
    precessing at Omega, no slip, G moving on a circle (radius ``radius``) with speed V in the
    precessing frame, friction supplying the centripetal force (|F| = Omega |V| <= mu R is
    needed for static friction to hold it: ``needs_mu``). The branches (:func:`steady_structure`)
    are its members with V = 0. ``x`` is the state (U, V, Omega, Lambda, theta, n).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> r = pk.steady.rolling_motion(pk.Spheroid(1.5), 1.0, 5.0)
    >>> isinstance(r, pk.steady.RollingMotion), round(r.needs_mu, 6)
    (True, 1.439896)
    """

    theta: float
    Omega: float
    n: float
    V: float
    radius: float
    needs_mu: float
    x: np.ndarray = field(repr=False)


def rolling_motion(body, theta: float, Omega: float) -> RollingMotion:
    """The steady rolling motion with axis angle ``theta`` and precession rate ``Omega``.

    Derived from (2.7) with Lambda = 0 and zero slip (U = 0, V = -Omega h_theta - (n - Omega cos)
    x_P): (2.7c) and (2.7b) give F_y = 0, (2.7a) F_X = -Omega V, and (2.7d) with R = 1

        n = [A Omega^2 s c - h_theta (1 + h Omega^2) + h Omega^2 c x_P] / (Omega (C s + h x_P)).

    A two-parameter family (theta, Omega); with V = 0 it reduces to the branches. An egg that
    settles tilted under Coulomb friction ends on it (studies/steady_structure.py).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> r = pk.steady.rolling_motion(pk.Spheroid(1.5), 1.0, 5.0)
    >>> round(r.n, 6), round(r.radius, 6)
    (5.678572, 0.057596)
    """
    if not isinstance(body, Body):
        raise ParameterError("body", "must be a phasekit Body", body)
    theta = check_finite("theta", theta)
    if not 0.0 < theta < np.pi:
        raise ParameterError("theta", "must lie in (0, pi) (at the poles the axis does not precess)", theta)
    Omega = check_finite("Omega", Omega)
    if Omega == 0.0:
        raise ParameterError("Omega", "must be nonzero (a body at rest is a static equilibrium)", Omega)
    h, ht, _ = body.h(theta)
    s, c = np.sin(theta), np.cos(theta)
    xP = h * s + ht * c
    n = (body.A * Omega**2 * s * c - ht * (1 + h * Omega**2) + h * Omega**2 * c * xP) / (Omega * (body.C * s + h * xP))
    V = -Omega * ht - (n - Omega * c) * xP
    return RollingMotion(float(theta), float(Omega), float(n), float(V), float(abs(V / Omega)), float(abs(Omega * V)),
                         np.array([0.0, V, Omega, 0.0, theta, n]))



def manifold_runs(structure: SteadyStructure, *, omega_range, seed_delta: float, t_end: float, pole_margin: float = 0.02,
                  n: int = 4000) -> dict:
    """Trajectories leaving the most unstable branch state of a structure along its unstable
    manifold: among the branch samples with Omega inside ``omega_range`` that have unstable
    directions, the one with the largest real part of an eigenvalue; from each of its seeds at
    distance ``seed_delta`` (:func:`phasekit.steady.unstable_seeds`), a run of the body under the
    structure's friction law (default model, until a jump or ``t_end``), sampled at ``n``
    instants and cut where theta first comes within ``pole_margin`` of a pole (Omega is
    undefined there). Returns ``state`` (that branch state: theta, Omega, n, classification)
    and ``trajectories`` (arrays of Omega, theta, n), as :func:`phasekit.studies.render_structure` draws them.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> s = pk.steady_structure(pk.Spheroid(1.5, offset=0.2), pk.Viscous(0.1))
    >>> runs = ps.manifold_runs(s, omega_range=(2.0, 6.0), seed_delta=0.01, t_end=5.0)
    >>> len(runs["trajectories"]), runs["trajectories"][0].shape[1], sorted(runs["state"])
    (6, 3, ['Omega', 'classification', 'n', 'theta'])
    """
    from ..core.simulate import simulate
    from .manifolds import unstable_seeds

    cands = [(float(np.max(p.eigenvalues.real)), i, k) for i, b in enumerate(structure.branches)
             for k, p in enumerate(b.points) if p.n_unstable and omega_range[0] < b.Omega[k] < omega_range[1]]
    _, i, k = max(cands)
    b, fp = structure.branches[i], structure.branches[i].points[k]
    trs = []
    for _, x0 in unstable_seeds(fp, seed_delta):
        r = simulate(Model(structure.body, structure.model.friction), x0, t_end, stop_at="jump")
        df = r.sample(np.linspace(0.0, r.t, n))
        near = np.minimum(df["theta"], np.pi - df["theta"]) < pole_margin
        stop = int(np.argmax(near)) if near.any() else len(df)
        trs.append(df[["Omega", "theta", "n"]].to_numpy()[:stop])
    state = {"theta": float(b.theta[k]), "Omega": float(b.Omega[k]), "n": float(b.n[k]), "classification": fp.classification}
    return {"state": state, "trajectories": trs}


def settled_motion(traj, structure: SteadyStructure, *, since: float = 0.5, n: int = 6000) -> dict:
    """What a run settled into, against the steady states: the mean state over the last part
    of the run (from ``since`` times its end, ``n`` samples: theta, Omega, n, V, the spread of
    theta, the largest slip), the branch of ``structure`` at that theta (G at rest: Omega, n)
    and the steady rolling motion at that theta and Omega (:func:`rolling_motion`: G on a
    circle; its n relative to the mean n). Also the run's status, end time, number of events
    and of slip events (stick-slip cycles). An egg that settles tilted under Coulomb friction
    ends on the rolling motion.

    Examples
    --------
    >>> import numpy as np, phasekit as pk, phasekit.studies as ps
    >>> egg = pk.Egg(57 / 43, 0.05)
    >>> s = pk.steady_structure(egg, pk.Coulomb(0.1))
    >>> r = pk.simulate(pk.Model(egg, pk.Coulomb(0.1)), pk.gyroscopic_start(egg, np.pi / 2 - 0.05, omega0=6.0), 20.0)
    >>> m = ps.settled_motion(r, s)
    >>> sorted(m["late_mean"]), sorted(m["rolling_motion"])
    (['Omega', 'V', 'n', 'slip_max', 'theta', 'theta_spread'], ['V', 'n', 'n_rel_difference', 'needs_mu', 'radius'])
    """
    late = traj.sample(np.linspace(since * traj.t, traj.t, n))
    th, om, n_mean = (float(late[c].mean()) for c in ("theta", "Omega", "n"))
    branch_om, branch_n = (float(v[0]) for v in structure.precession(np.array([th])))
    roll = rolling_motion(structure.body, th, om)
    return {"status": traj.status.value, "t_end": traj.t, "n_events": len(traj.events),
            "stick_slip_cycles": sum(e.name == "slip" for e in traj.events),
            "late_mean": {"theta": th, "Omega": om, "n": n_mean, "V": float(late["V"].mean()),
                          "theta_spread": float(late["theta"].std()), "slip_max": float(late["slip"].max())},
            "branch_at_theta": {"Omega": branch_om, "n": branch_n},
            "rolling_motion": {"n": roll.n, "V": roll.V, "radius": roll.radius, "needs_mu": roll.needs_mu,
                               "n_rel_difference": abs(roll.n - n_mean) / abs(n_mean)}}
