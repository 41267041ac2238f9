"""The branches of steady precessions of a body (parts III and IV of the series): the one curve
every steady precession lies on, the points of theta where its branches end or cross a family,
how each end meets the rest of the structure, and samples adaptive in arc length along a branch.

A steady precession has zero slip, G at rest and the axis at a fixed theta precessing at the
rate Omega with spin n. With c = cos(theta), H(c) = h(theta) the height of G and the regular
quantities

    q = h_theta / sin = -H'(c),   rho_2 = x_P / sin = H - c H'(c),
    z = h cos - h_theta sin,       D = (A - C) c rho_2 + C q,

(2.7) with U = V = Lambda = 0 gives (phasekit.steady.precessions, module notes)

    Omega^2 = q rho_2 / D,   n = Omega z / rho_2.

Every steady precession lies on this one curve, so the branches are the maximal intervals of
theta on which q rho_2 / D > 0 (rho_2 > 0 on a convex body). An interval ends where

* q = 0 (G above the contact point: a **static** equilibrium; Omega and n tend to 0),
* D = 0 (Omega diverges: an **infinite-spin** asymptote theta_inf), or
* theta = 0 or pi (a **pole**: the branch meets the spin about the vertical there at the
  finite spin n = Omega h0 / rho with rho = h0 + h_tt the radius of curvature at the pole;
  squared, n^2 rho (A rho - C h0) = h_tt h0^2, the closed-form pole criterion of
  :func:`phasekit.theory.criteria.pole_stability_threshold`: the branch is born where the pole
  changes stability), or
* on a compound body (one with ``transfers``, :mod:`phasekit.bodies.compound`), at a
  **switch** angle, where the contact passes from one piece to the next: H has a kink there
  (H' jumps), so q, rho_2, z and D jump and the branch is cut; each part lies on one piece
  and is that piece's own (phasekit.steady.pieces), ending at the switch at the finite
  (Omega, n) its piece's closed forms give there, or
* on a body with an edge (one with ``theta_range``, :mod:`phasekit.bodies.edged`), at an end
  of that range, a **limit** where another part of the body comes down onto the table (the
  face of a disk at theta = 0, its side at pi/2): the model ends there, and so does the
  branch, at the limits of (Omega, n) there (a face coming down, where H' diverges: Omega ->
  infinity, n -> 0, the disk's Omega^2 = 1 / (A sin theta)).

Where q and D vanish together (a static equilibrium with its axis horizontal, theta = pi/2 for
a flip-symmetric body; or any static equilibrium when A = C), every Omega is steady there: a
non-isolated **family** like the spins about the vertical at the poles, which the branch
crosses (the pitchfork of part I's horizontal state: the crossing is at the family's critical
rate).

Omega > 0 represents each branch; (-Omega, -n) is the same branch seen in a mirror.
"""

from __future__ import annotations

import functools
import math
import threading
from dataclasses import replace

import casadi as ca
import numpy as np

from .records import POLE_EDGES, BranchEnd, Edge, Interval

#: how a branch ends (see the module notes)
END_KINDS = ("pole", "static", "infinite-spin", "switch", "limit")
#: grid on which the roots of q and D are bracketed before Brent's method refines them (two
#: roots closer than its spacing show as a dip of |q| or |D| toward zero and are found too)
ROOT_GRID = 2049
#: roots of q and D closer than this (in theta) are one point where both vanish (a family)
COINCIDENT = 1e-10
#: the samples of a branch stop this far (in theta) from a static or infinite-spin end: the
#: closed forms lose digits as q or D -> 0 (relative error ~1e-16 / distance); and from a
#: switch, so that the whole body's fields (its linearisation) are the piece's at every sample
END_GAP = 1e-6
#: ... and this far from a pole, where the branch meets the spin about the vertical exactly
POLE_GAP = 1e-6
#: samples keep this far from a family crossing, except the crossing itself (exact limit there)
CROSSING_GAP = 1e-4
#: adaptive sampling: largest chord and turning angle in the compact coordinates
#: (theta / pi, (2/pi) atan Omega, (2/pi) atan n)
MAX_CHORD, MAX_TURN = 0.02, 0.15
#: most samples on one branch
MAX_SAMPLES = 1200


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


def precession_geometry(body, theta) -> tuple[np.ndarray, ...]:
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
    family crossing is given by :func:`phasekit.steady_structure`, not here."""
    q, rho2, z, D = precession_geometry(body, theta)[:4]
    with np.errstate(divide="ignore", invalid="ignore"):
        om2 = q * rho2 / D
        om = np.where(np.isfinite(om2) & (om2 >= 0), np.sqrt(np.abs(om2)), np.nan)
        n = om * z / rho2
    return om, n


def holds_state(body, theta: float) -> bool:
    """Whether a steady state at ``theta`` is one of ``body``'s model that a run can hold: always,
    but for an edged body (phasekit.bodies.edged) only inside its range and short of its
    ``limits``, where a run stops at once (the face is down: theta below the disk's flat_angle)."""
    return body.in_range(theta) and all(theta > lim.theta if lim.direction < 0 else theta < lim.theta
                                        for lim in body.limits)


# -- a degenerate body ---------------------------------------------------------------------------

#: q vanishing to this (relative to rho_2) at every theta is q = 0 identically
DEGENERATE_RTOL = 1e-12


def degeneracy(body) -> str | None:
    """Why the steady states of ``body`` are a continuum rather than branches, or None: q = 0 at
    every theta (h_theta = 0: a sphere with G at its centre, every orientation a static
    equilibrium), and then, with A = C, D = 0 too (every orientation precesses at any rate)."""
    grid = np.linspace(0.0, np.pi, 257)
    q, rho2 = precession_geometry(body, grid)[:2]
    if not np.all(np.abs(q) <= DEGENERATE_RTOL * np.abs(rho2)):
        return None
    what = ("degenerate body: h_theta = 0 at every theta (a sphere with G at its centre), so every orientation is a "
            "static equilibrium (and rolls straight at any spin)")
    if abs(body.A - body.C) <= DEGENERATE_RTOL * body.C:
        return (what + "; with A = C every orientation also precesses steadily at any rate Omega with n = Omega cos "
                "theta: the steady states fill a continuum, not branches (only the isolated states are listed: the "
                "spins about the vertical and the horizontal precession)")
    return (what + "; the only precessions are the horizontal family (theta = pi/2, any Omega, n = 0) and the spins "
            "about the vertical: there are no branches")


# -- roots of q and D ---------------------------------------------------------------------------


def _roots(fun, grid: np.ndarray, values: np.ndarray) -> list[float]:
    """Every root of ``fun`` in the open interval of ``grid`` (inside (0, pi)): sign changes refined by Brent's
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
    return sorted(r for r in roots if grid[0] < r < grid[-1] and 0.0 < r < np.pi)


def special_points(body, lo: float = 0.0, hi: float = np.pi) -> list[Edge]:
    """The interior points of (lo, hi) where q, D or both vanish, in theta order (a compound
    body's piece: its own range)."""
    grid = np.linspace(lo, hi, ROOT_GRID)
    _geometry_function(body)
    f = _mapped(_GEOMETRY[body.structure_key + ":qD"], ROOT_GRID)
    shape = np.tile(np.asarray(body.shape_params, dtype=float)[:, None], (1, ROOT_GRID))
    q, D = (np.asarray(v).ravel() for v in f(grid[None, :], shape, body.A, body.C))
    fq = lambda t: float(precession_geometry(body, t)[0][0])  # noqa: E731
    fD = lambda t: float(precession_geometry(body, t)[3][0])  # noqa: E731
    pts = [Edge(t, q=True) for t in _roots(fq, grid, q)]
    for t in _roots(fD, grid, D):
        near = [k for k, p in enumerate(pts) if p.q and abs(p.theta - t) <= COINCIDENT]
        if near:
            pts[near[0]] = replace(pts[near[0]], D=True)
        else:
            pts.append(Edge(t, D=True))
    if body.flip_symmetric:  # both vanish exactly at pi/2 by symmetry: say so exactly
        pts = [replace(p, theta=np.pi / 2) if p.q and p.D and abs(p.theta - np.pi / 2) <= COINCIDENT else p
               for p in pts]
    return sorted(pts, key=lambda p: p.theta)


def _omega2(body, theta: float) -> float:
    q, rho2, _, D = precession_geometry(body, theta)[:4]
    return float(q[0] * rho2[0] / D[0])


def family_rate2(body, theta: float) -> float:
    """Omega^2 of a branch through a point where q = D = 0: the limit (dq/dtheta) rho_2 / (dD/dtheta)."""
    g = precession_geometry(body, theta)
    return float(g[6][0] * g[1][0] / g[7][0])


# -- branches -----------------------------------------------------------------------------------


def branch_intervals(body, pts: list[Edge], edges: tuple[Edge, Edge] = POLE_EDGES) -> list[Interval]:
    """The maximal intervals with Omega^2 > 0 between the two ``edges``, joined across family
    points (where q and D vanish together)."""
    seq = [edges[0], *pts, edges[1]]
    found = []  # [lo edge, index of the hi edge, crossings]
    for k in range(len(seq) - 1):
        lo, hi = seq[k], seq[k + 1]
        if _omega2(body, 0.5 * (lo.theta + hi.theta)) > 0:
            if found and found[-1][1] == k and lo.q and lo.D:
                found[-1][1] = k + 1  # the branch crosses a family here
                found[-1][2].append(lo.theta)
            else:
                found.append([lo, k + 1, []])
    return [Interval(lo, seq[h], tuple(crossings)) for lo, h, crossings in found]


def classify_end(body, edge: Edge, side: int) -> BranchEnd:
    """Classify an interval's end at ``edge`` (side -1: the interval lies above it in theta)."""
    t = float(edge.theta)
    if edge.switch is not None:  # the piece's own closed forms, analytic up to the switch
        q, rho2, z, D = (float(v[0]) for v in precession_geometry(body, t)[:4])
        om = float(np.sqrt(q * rho2 / D)) if q * rho2 / D > 0 else 0.0
        return BranchEnd("switch", t, n=om * z / rho2, Omega=om, to_piece=edge.switch)
    if edge.limit is not None:
        return _limit_end(body, t, side, edge.limit)
    if edge.pole is not None:
        q, rho2, z, D = (float(v[0]) for v in precession_geometry(body, t)[:4])
        if D == 0.0:
            return BranchEnd("infinite-spin", t)
        if q == 0.0:
            return BranchEnd("static", t)
        om = float(np.sqrt(q * rho2 / D))
        return BranchEnd("pole", t, pole=edge.pole, n=om * z / rho2, Omega=om)
    if edge.q and not edge.D:
        return BranchEnd("static", t)
    if edge.D and not edge.q:
        return BranchEnd("infinite-spin", t)
    # a family point that ends the branch (degenerate): by the limit from the branch's side
    near = _omega2(body, t - side * 1e-4)
    far = _omega2(body, t - side * 1e-2)
    return BranchEnd("static" if near < far else "infinite-spin", t)


#: distances from a limit at which the closed forms' trend is read where H has a branch point
#: there (c = cos(theta) keeps ~8 digits of 1 - c at 1e-4, ~4 at 1e-6), and the ratio of the two
#: values beyond which a value is taken to diverge (or, inverted, to vanish): a power of the
#: distance, ~10 for the face's 1/sqrt
LIMIT_PROBES, LIMIT_RATIO = (1e-4, 1e-6), 3.0
#: a spin below this times the rate at the nearer probe is 0 (the thin disk's n = 0: z is 0 to
#: the rounding of c there, ~1e-16 / distance^2)
LIMIT_SPIN_FLOOR = 1e-9


def _limit_end(body, t: float, side: int, name: str) -> BranchEnd:
    """The end at a limit ``t`` of an edged body's range (side -1: the branch lies above it): the
    closed forms there where H is analytic (a side touching), else their limits, read off their
    trend as theta -> t (a face coming down, H' -> infinity: q and rho_2 grow as 1 / |theta - t|,
    z stays finite, so Omega -> infinity and n = Omega z / rho_2 -> 0)."""
    q, rho2, z, D = (float(v[0]) for v in precession_geometry(body, t)[:4])
    with np.errstate(all="ignore"):
        om2 = q * rho2 / D
        if np.isfinite(om2) and np.isfinite(z) and rho2 > 0:
            om = float(np.sqrt(max(om2, 0.0)))
            return BranchEnd("limit", t, n=om * z / rho2, Omega=om, limit=name)
    (om_far, n_far), (om_near, n_near) = ((float(v[0]) for v in precession_on_branch(body, t - side * d))
                                          for d in LIMIT_PROBES)
    n = 0.0 if abs(n_near) <= LIMIT_SPIN_FLOOR * om_near else _trend(n_far, n_near)
    return BranchEnd("limit", t, n=n, Omega=_trend(om_far, om_near), limit=name)


def _trend(far: float, near: float) -> float:
    """The limit of a value read at two distances from an end (LIMIT_PROBES): infinite (with its
    sign) if it grows by LIMIT_RATIO or more, 0 if it falls by as much, else the nearer value."""
    if near == 0.0 or abs(near) * LIMIT_RATIO <= abs(far):
        return 0.0
    if abs(near) >= LIMIT_RATIO * abs(far):
        return math.copysign(math.inf, near)
    return near


# -- sampling -----------------------------------------------------------------------------------


def _compact(theta, om, n) -> np.ndarray:
    return np.column_stack([theta / np.pi, 2 / np.pi * np.arctan(om), 2 / np.pi * np.arctan(n)])


def branch_curve(body, theta, crossings) -> tuple[np.ndarray, np.ndarray]:
    om, n = precession_on_branch(body, theta)
    for t in crossings:  # the 0/0 limit at a family point (samples keep CROSSING_GAP away otherwise)
        sel = np.abs(theta - t) < 1e-12
        if np.any(sel):
            _, rho2, z = precession_geometry(body, t)[:3]
            om[sel] = np.sqrt(family_rate2(body, t))
            n[sel] = om[sel] * z[0] / rho2[0]
    return om, n


def off_crossings(theta: np.ndarray, crossings) -> np.ndarray:
    """Drop points within CROSSING_GAP of a family crossing (but not the crossing itself): there
    q / D is 0/0 and the closed form loses digits (~1e-16 / distance)."""
    for t in crossings:
        d = np.abs(theta - t)
        theta = theta[(d == 0) | (d >= CROSSING_GAP)]
    return theta


def sample_branch(body, lo: BranchEnd, hi: BranchEnd, crossings) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
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
    theta = off_crossings(np.append(theta, crossings), crossings)
    theta = np.unique(theta[(theta >= a) & (theta <= b)])
    for _ in range(12):
        om, n = branch_curve(body, theta, crossings)
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
        theta = np.unique(off_crossings(np.concatenate([theta, 0.5 * (theta[:-1] + theta[1:])[split]]), crossings))
    om, n = branch_curve(body, theta, crossings)
    ok = np.isfinite(om) & np.isfinite(n)
    return theta[ok], om[ok], n[ok]
