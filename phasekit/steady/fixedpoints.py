"""Steady states, their exact linearisation and stability (part I of the series), for any body.

Classes of steady states of (2.7)
---------------------------------
vertical       theta = 0, spin n0 about the vertical, U = V = 0 (resting on the end at -k).
               The Euler chart is singular there, so it is found and linearised in the
               vector chart (k = e_Z, w = n0 e_Z, v = 0).
inverted       theta = pi: k = -e_Z, w = n0 k (spin n = w.k = n0), v = 0, resting on the end
               at +k. For a flip-symmetric body (h(pi - theta) = h(theta)) this is the vertical
               state with k reversed, so it is reported only for bodies without that symmetry.
               The state is exact (r_P is vertical at both poles); it is linearised in the
               vector chart.
horizontal     steady precession with the axis horizontal: U = V = Lambda = n = 0,
               theta = pi/2, any Omega0. It exists only where h_theta(pi/2) = 0 (flip-symmetric
               bodies): otherwise G is not above P when the axis is horizontal.
intermediate   steady precession at 0 < theta* < pi: Lambda = U = V = 0, zero slip
               V_P = 0, i.e. n = Omega (cos theta - h_theta / x_P), and the torque balance
               (2.7d) with R = 1 and no friction force:
                   Omega^2 = h_theta / (sin theta [(A - C) cos theta + C h_theta / x_P]),
               a family in theta* where the right-hand side is positive. Nothing here assumes
               flip symmetry (derived from (2.7a-f) with U = V = Lambda = 0: (2.7a, b) give
               F = 0, (2.7c, e, f) hold identically, (2.4) gives the spin, (2.7d) the rate).
horizontal-like for a body with h_theta(pi/2) != 0 (an egg), the member of the Omega-family
               that continues the horizontal state: the branch that leaves the static
               equilibrium lying on the side (theta_1, where h_theta = 0) at Omega -> 0 and tends,
               as Omega -> infinity, to theta_2 where (A - C) cos theta x_P + C h_theta = 0
               (the rate diverges there). For a flip-symmetric body theta_1 = theta_2 = pi/2.
All of them have zero slip, so friction does no work on them and they exist for every law.

Locating the precessions. With q = h_theta / sin(theta) = -H'(cos theta) and the azimuthal
radius of curvature rho_2 = x_P / sin(theta) (both regular at the poles), the states with
rate Omega0 are the roots in theta of the smooth function

    G_Omega(theta) = q rho_2 - Omega0^2 [(A - C) cos(theta) rho_2 + C q],

and those with spin n0 (n = Omega z / rho_2, z = h cos - h_theta sin) the roots of

    G_n(theta) = q z^2 - n0^2 rho_2 [(A - C) cos(theta) rho_2 + C q].

They are bracketed on a fine grid and refined by Brent's method, then polished by Newton on
the full equations (:func:`find_fixed_point`). For the eccentric sphere G_n is
alpha (cos - alpha)^2 - n0^2 ((A - C) cos + C alpha), phasekit.theory.tippetop's steady states.

Linearisation
-------------
CasADi's exact Jacobian of the mode's vector field. For viscous friction the field is
smooth at zero slip. The Coulomb law is not differentiable at u = 0, so "the linearisation
of Coulomb friction" needs a meaning:
* regularised Coulomb (eps > 0): the smooth field, whose slip modes relax at rates ~mu/eps;
* exact Coulomb: near a zero-slip state that static friction can hold (|F_req| <= mu R,
  here F_req = 0), any small slip dies in a finite time ~|u|/(mu g) and the motion is the
  rolling mode's, so stability is that of the ROLLING field restricted to the no-slip
  manifold (velocity of O slaved to u = 0). Rolling does no work: the rolling spectrum has
  no friction-induced decay or growth of the kind viscous friction gives, and the
  regularised spectrum tends to it, plus two fast slip modes, as eps -> 0 (tested).
  Closed-form criteria for sliding friction (phasekit.steady.manifolds) are then reported beside
  the rolling spectrum in ``FixedPoint.parameter``.

Families have a structural zero eigenvalue (the family parameter), and in the vector chart
a second one (|k|, which the field leaves invariant); these count as neutral.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import casadi as ca
import numpy as np

from .._runtime.errors import ConvergenceError, ParameterError
from .._runtime.validate import check_array, check_choice, check_finite, check_range, check_vector
from ..core.charts import EULER, PAPER_NAMES, VECTOR
from ..core.hybrid import Mode
from ..core.model import Model
from ..theory.criteria import pole_stability_threshold

__all__ = [
    "FixedPoint",
    "Branch",
    "find_fixed_point",
    "fixed_points",
    "horizontal_state",
    "vertical_state",
    "inverted_state",
    "intermediate_state",
    "intermediate_omega",
    "precession_state",
    "precession_angles",
    "precession_residual",
    "side_equilibrium",
    "horizontal_like_angle",
    "continue_family",
    "linearise",
]

#: the rounding of one evaluation of a compiled Jacobian, in units of eps * ||J||_F: CasADi's
#: entries are sums of many products (measured below 10 on the spheroid, egg and tippe top;
#: 64 leaves room), and LAPACK's eigensolver adds a backward error of a few eps * ||J||
JACOBIAN_ROUNDING = 64.0


@dataclass(frozen=True)
class FixedPoint:
    """A steady state with its linearisation.

    Attributes
    ----------
    kind : "vertical", "inverted", "horizontal", "horizontal-like" or "intermediate"
    chart : the chart of ``x`` ("euler" or "vector")
    x : chart state; ``y`` the same in the paper's variables (Omega is NaN at theta = 0)
    eigenvalues : complex, sorted by descending real part
    eigenvectors : columns in the coordinates of ``space`` (the chart's state, or for
        exact Coulomb the no-slip manifold coordinates, lifted to the chart state)
    residual : max |f(x)| of the mode's vector field at x
    law : the linearised law ("viscous", "coulomb-regularised", "coulomb-rolling")
    parameter : the family parameter (Omega0 or n0), and for the poles the closed-form
        stability criterion under sliding friction (phasekit.theory.criteria.pole_stability_threshold)
    error_bounds : a bound on the error of each eigenvalue (same order): its condition number
        (1 / |y^H x| for unit left and right eigenvectors) times the size of the error in the
        Jacobian (the rounding of its evaluation and of the eigensolver, JACOBIAN_ROUNDING
        eps ||J||, plus the change of J over the state's own error, estimated from the
        residual). First order in the error; infinite for a defective eigenvalue.

    Each eigenvalue is classified against its bound: Re > bound ``unstable``, Re < -bound
    ``stable``; |lambda| <= bound is a zero eigenvalue (families and invariants make them:
    ``neutral``); otherwise (|Re| within the bound, Im not) ``undecided`` for a dissipative
    law and ``neutral`` for the rolling field, which conserves energy and is reversible, so
    that its spectrum is symmetric about the imaginary axis and a real part within the bound
    is zero.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> fp = pk.linearise(pk.Model(pk.Spheroid(1.5), pk.Viscous(0.1)), pk.steady.horizontal_state(10.0), kind='horizontal')
    >>> isinstance(fp, pk.steady.FixedPoint), fp.n_unstable, len(fp.unstable_directions())
    (True, 1, 1)
    """

    kind: str
    chart: str
    x: np.ndarray
    y: np.ndarray
    eigenvalues: np.ndarray
    eigenvectors: np.ndarray
    residual: float
    law: str
    parameter: dict = field(default_factory=dict)
    error_bounds: np.ndarray | None = field(default=None, repr=False)

    @property
    def scale(self) -> float:
        return max(1.0, float(np.max(np.abs(self.eigenvalues)))) if self.eigenvalues.size else 1.0

    @property
    def bounds(self) -> np.ndarray:
        if self.error_bounds is None:  # built by hand without bounds: rounding of the eigensolver only
            return JACOBIAN_ROUNDING * np.finfo(float).eps * self.scale * np.ones(self.eigenvalues.size)
        return self.error_bounds

    @property
    def eigenvalue_classes(self) -> tuple[str, ...]:
        """Per eigenvalue: "unstable", "stable", "neutral" or "undecided" (see the class notes)."""
        out = []
        for lam, b in zip(self.eigenvalues, self.bounds):
            if lam.real > b:
                out.append("unstable")
            elif lam.real < -b:
                out.append("stable")
            elif abs(lam) <= b or self.law == "coulomb-rolling":
                out.append("neutral")
            else:
                out.append("undecided")
        return tuple(out)

    def _unstable_mask(self) -> np.ndarray:
        return np.array([c == "unstable" for c in self.eigenvalue_classes], dtype=bool)

    @property
    def n_unstable(self) -> int:
        """Dimension of the unstable subspace (a complex pair counts 2)."""
        return int(np.sum(self._unstable_mask()))

    @property
    def n_neutral(self) -> int:
        return sum(c == "neutral" for c in self.eigenvalue_classes)

    @property
    def n_undecided(self) -> int:
        """Eigenvalues whose real part lies within its error bound although they are not zero:
        double precision cannot tell their sign."""
        return sum(c == "undecided" for c in self.eigenvalue_classes)

    @property
    def stable(self) -> bool:
        """Linearly (spectrally) stable: no eigenvalue whose real part is positive beyond its
        error bound, and none undecided."""
        return self.n_unstable == 0 and self.n_undecided == 0

    @property
    def classification(self) -> str:
        lam = self.eigenvalues[self._unstable_mask()]
        bounds = self.bounds[self._unstable_mask()]
        n_real = int(np.sum(np.abs(lam.imag) <= bounds))
        n_osc = (lam.size - n_real) // 2
        if lam.size == 0:
            if self.n_undecided:
                k = self.n_undecided
                return f"undecided: {k} eigenvalue{'s' if k > 1 else ''} with real part within {'their' if k > 1 else 'its'} error bound"
            return "stable" if self.n_neutral <= 2 else "neutral (spectrally stable)"
        parts = []
        if n_real:
            parts.append(f"{n_real} real unstable")
        if n_osc:
            parts.append(f"{n_osc} oscillatory unstable pair" + ("s" if n_osc > 1 else ""))
        return "unstable: " + ", ".join(parts)

    def unstable_directions(self) -> list[np.ndarray]:
        """Real unit vectors spanning the unstable subspace (Re and Im of complex ones),
        normalised in the Euclidean norm of the chart state."""
        out = []
        for k in np.flatnonzero(self._unstable_mask()):
            lam, v = self.eigenvalues[k], self.eigenvectors[:, k]
            if abs(lam.imag) <= self.bounds[k]:
                vecs = [v.real]
            elif lam.imag > 0:
                vecs = [v.real, v.imag]
            else:
                continue
            for w in vecs:
                if np.linalg.norm(w) > 0:
                    out.append(w / np.linalg.norm(w))
        return out

    def to_dict(self) -> dict:
        y = self.y
        state = {k: (None if not np.isfinite(v) else float(v)) for k, v in zip(PAPER_NAMES, y)}
        return {
            "kind": self.kind,
            "state": state,
            "residual": float(self.residual),
            "eigenvalues": [[float(ev.real), float(ev.imag)] for ev in self.eigenvalues],
            "error_bounds": [float(b) if np.isfinite(b) else None for b in self.bounds],
            "eigenvalue_classes": list(self.eigenvalue_classes),
            "n_unstable": self.n_unstable,
            "n_neutral": self.n_neutral,
            "n_undecided": self.n_undecided,
            "stable": self.stable,
            "classification": self.classification,
            "linearised_law": self.law,
            "chart": self.chart,
            **({"parameter": self.parameter} if self.parameter else {}),
        }

    def __repr__(self) -> str:
        return f"FixedPoint({self.kind}, {self.classification}, residual={self.residual:.1e})"


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


# -- the states --------------------------------------------------------------------------


def horizontal_state(omega0: float) -> np.ndarray:
    """(U, V, Omega, Lambda, theta, n) = (0, 0, Omega0, 0, pi/2, 0).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> pk.steady.horizontal_state(10.0).round(6)
    array([ 0.      ,  0.      , 10.      ,  0.      ,  1.570796,  0.      ])
    """
    return np.array([0.0, 0.0, check_finite("omega0", omega0), 0.0, np.pi / 2, 0.0])


def vertical_state(n0: float) -> np.ndarray:
    """Vector-chart state k = e_Z, w = n0 e_Z, v = 0 (theta = 0).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> pk.steady.vertical_state(10.0)
    array([ 0.,  0.,  1.,  0.,  0., 10.,  0.,  0.])
    """
    return np.array([0.0, 0.0, 1.0, 0.0, 0.0, check_finite("n0", n0), 0.0, 0.0])


def inverted_state(n0: float) -> np.ndarray:
    """Vector-chart state k = -e_Z, w = n0 k = -n0 e_Z, v = 0 (theta = pi, spin w.k = n0).
    An exact steady state of every body (the contact point lies straight below G).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> pk.steady.inverted_state(10.0).round(6)
    array([  0.,   0.,  -1.,   0.,   0., -10.,   0.,   0.])
    """
    return np.array([0.0, 0.0, -1.0, 0.0, 0.0, -check_finite("n0", n0), 0.0, 0.0])


def _geometry(body, theta):
    h, ht, _ = body.h(theta)
    s, c = np.sin(theta), np.cos(theta)
    return h, ht, s, c, h * s + ht * c


def _regular(body, theta):
    """(q, rho_2, z, D) at theta (arrays): q = h_theta / sin = -H'(cos), rho_2 = x_P / sin,
    z = h cos - h_theta sin, D = (A - C) cos rho_2 + C q; all regular at the poles."""
    theta = np.asarray(theta, dtype=float)
    c = np.cos(theta)
    H, dH = _height_slope_many(body, c)
    q = -dH
    h, ht, s = H, q * np.sin(theta), np.sin(theta)
    rho2 = h + q * c  # x_P / sin = h + h_theta cos / sin
    z = h * c - ht * s
    D = (body.A - body.C) * c * rho2 + body.C * q
    return q, rho2, z, D


def _height_slope_many(body, c):
    """(H, dH/dc) at an array of c, by the body's compiled slope function mapped over c."""
    from ..bodies.body import _slope_function

    c = np.atleast_1d(np.asarray(c, dtype=float))
    shape = np.asarray(body.shape_params, dtype=float)
    H, dH = _slope_function(body).map(c.size)(c[None, :], np.tile(shape[:, None], (1, c.size)))
    return np.asarray(H).ravel(), np.asarray(dH).ravel()


def precession_residual(body, theta, *, omega0: float | None = None, n0: float | None = None):
    """G_Omega(theta) (given ``omega0``) or G_n(theta) (given ``n0``): zero exactly where a
    steady precession with that rate or spin exists (module notes). ``theta`` may be an array."""
    q, rho2, z, D = _regular(body, theta)
    if omega0 is not None:
        out = q * rho2 - omega0 * omega0 * D
    else:
        out = q * z * z - n0 * n0 * rho2 * D
    return out if np.ndim(theta) else float(out[0])


def precession_angles(body, *, omega0: float | None = None, n0: float | None = None, theta_range=None,
                      n_grid: int = 4001) -> list[float]:
    """Every theta in ``theta_range`` (default (0, pi), or (0, pi/2) for a flip-symmetric body)
    at which a steady precession with rate ``omega0`` (or spin ``n0``) exists: sign changes of
    :func:`precession_residual` on ``n_grid`` points, refined by Brent's method to ~1e-15.
    For a flip-symmetric body the neighbourhood of pi/2 (the horizontal family, where
    G vanishes identically) is left out.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> [round(t, 6) for t in pk.steady.precession_angles(pk.Egg(1.3, 0.05), omega0=6.0)]
    [0.51274, 1.756111]
    """
    from scipy.optimize import brentq

    if (omega0 is None) == (n0 is None):
        raise ValueError("give exactly one of `omega0` or `n0`.")
    if theta_range is None:
        theta_range = (0.0, np.pi / 2 - 1e-3) if body.flip_symmetric else (0.0, np.pi)
    lo, hi = theta_range
    grid = np.linspace(lo, hi, n_grid)[1:-1]
    g = precession_residual(body, grid, omega0=omega0, n0=n0)
    roots = []
    for k in np.flatnonzero(np.sign(g[:-1]) * np.sign(g[1:]) < 0):
        f = lambda t: precession_residual(body, t, omega0=omega0, n0=n0)  # noqa: E731
        roots.append(float(brentq(f, grid[k], grid[k + 1], xtol=1e-15, rtol=4 * np.finfo(float).eps)))
    roots += [float(grid[k]) for k in np.flatnonzero(g == 0.0)]
    return sorted(roots)


def precession_state(body, theta: float, *, omega0: float | None = None, n0: float | None = None) -> np.ndarray:
    """The steady precession at ``theta`` with rate ``omega0`` or spin ``n0`` (Euler chart):
    (0, 0, Omega, 0, theta, n) with n = Omega z / rho_2 (zero slip). ``theta`` should be one
    of :func:`precession_angles`; no check that the torque balance holds is made here."""
    q, rho2, z, D = (float(v[0]) for v in _regular(body, np.array([theta])))
    if omega0 is not None:
        om = float(omega0)
        n = om * z / rho2
    else:
        n = float(n0)
        om = n * rho2 / z
    return np.array([0.0, 0.0, om, 0.0, float(theta), n])


def side_equilibrium(body) -> tuple[float, float]:
    """(theta_1, theta_2) nearest pi/2: theta_1 where h_theta = 0 (the body at rest on its side),
    theta_2 where (A - C) cos(theta) x_P + C h_theta = 0 (the fast-precession limit of the
    horizontal-like state). Both are pi/2 for a flip-symmetric body.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> [round(t, 6) for t in pk.steady.side_equilibrium(pk.Egg(1.3, 0.05))]
    [1.676232, 1.74775]
    """
    from scipy.optimize import brentq

    if body.flip_symmetric:
        return np.pi / 2, np.pi / 2
    grid = np.linspace(1e-3, np.pi - 1e-3, 2001)
    out = []
    for idx in (0, 3):
        v = _regular(body, grid)[idx]
        k = np.flatnonzero(np.sign(v[:-1]) * np.sign(v[1:]) <= 0)
        if k.size == 0:
            out.append(float("nan"))
            continue
        k = k[np.argmin(np.abs(grid[k] - np.pi / 2))]
        f = lambda t, i=idx: float(_regular(body, np.array([t]))[i][0])  # noqa: E731
        out.append(float(brentq(f, grid[k], grid[k + 1], xtol=1e-15)))
    return out[0], out[1]


#: a precession within this of [theta_1, theta_2] continues the horizontal state
HORIZONTAL_LIKE_WINDOW = 0.25


def horizontal_like_angle(body, thetas) -> float | None:
    """Among precession angles ``thetas`` of one Omega-family, the one continuing the
    horizontal state of a body with h_theta(pi/2) != 0: the nearest to the interval between
    theta_1 and theta_2 (:func:`side_equilibrium`), if within HORIZONTAL_LIKE_WINDOW. The
    symmetric pitchfork of the spheroid (the intermediate family branching off the horizontal
    state at the stability threshold) unfolds for such a body: at slow precession the state
    near theta_1 (the body lying on its side) continues the horizontal state, at fast
    precession the unstable state near theta_2 does. None for flip-symmetric bodies.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> egg = pk.Egg(1.3, 0.05)
    >>> round(pk.steady.horizontal_like_angle(egg, pk.steady.precession_angles(egg, omega0=6.0)), 6)
    1.756111
    """
    if body.flip_symmetric or not len(thetas):
        return None
    th1, th2 = side_equilibrium(body)
    lo, hi = min(th1, th2), max(th1, th2)
    dist = [max(lo - t, t - hi, 0.0) for t in thetas]
    k = int(np.argmin(dist))
    return float(thetas[k]) if dist[k] <= HORIZONTAL_LIKE_WINDOW else None


def intermediate_omega(body, theta: float) -> float | None:
    """Omega of the intermediate steady precession at theta, or None where it does not exist.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> round(ps.intermediate_omega(pk.Spheroid(1.5), 1.0), 6)
    2.068755
    """
    h, ht, s, c, xP = _geometry(body, theta)
    denom = s * ((body.A - body.C) * c + body.C * ht / xP)
    if denom == 0.0 or ht / denom <= 0.0:
        return None
    return float(np.sqrt(ht / denom))


def intermediate_state(body, theta: float) -> np.ndarray | None:
    """The intermediate steady precession at theta (Omega > 0 root), or None.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> pk.steady.intermediate_state(pk.Spheroid(1.5), 1.0).round(6)
    array([0.      , 0.      , 2.068755, 0.      , 1.      , 2.514945])
    """
    om = intermediate_omega(body, theta)
    if om is None:
        return None
    h, ht, s, c, xP = _geometry(body, theta)
    return np.array([0.0, 0.0, om, 0.0, theta, om * (c - ht / xP)])


# -- Newton -----------------------------------------------------------------------------


def _mode_for(model: Model) -> Mode:
    return Mode.ROLLING if model.friction.has_rolling_mode else Mode.SLIDING


_SOLVERS: dict = {}

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


def _newton_system(model: Model, kind: str, fixed: str):
    """CasADi rootfinder for a square system: the chart's field with one redundant equation
    replaced by the family constraint (fixed Omega or n), or, at the vertical, the tilt
    coordinates of k and w with |k| = 1 and w.k = n0 imposed.

    The unknowns and equations are scaled at run time (unknown z = sz * zeta, equation i
    divided by se_i), so that the rootfinder's absolute tolerances act as relative ones at
    any scale of the state. Returns (solver, lift, n_unknowns, Jacobian of the equations)."""
    key = (model.compiled.key, kind, fixed)
    if key in _SOLVERS:
        return _SOLVERS[key]
    # The steady states have zero slip, so they are the same for every law: locate them with
    # the smooth sliding field (for exact Coulomb the rolling field slaves U, V and its
    # Jacobian is singular in them). The law's own field is used for the linearisation.
    f = model.function("rhs_sliding")
    p = ca.SX.sym("p", len(model.p))
    val = ca.SX.sym("val")
    if model.chart is EULER:
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
    mode = _mode_for(model)
    f, J = model._rhs(x, mode), model._jacobian(x, mode)
    if not (np.all(np.isfinite(f)) and np.all(np.isfinite(J))):
        return float("inf")
    scale = np.abs(J) @ np.maximum(np.abs(x), 1.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(np.abs(f) == 0.0, 0.0, np.abs(f) / scale)
    return float(np.max(ratio))


def _check_model(model) -> Model:
    if not isinstance(model, Model):
        raise ParameterError("model", "must be a phasekit Model such as Model(Spheroid(1.5), Coulomb(0.1))", model)
    return model


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

    Raises
    ------
    ParameterError
        For an invalid argument.
    ConvergenceError
        When Newton does not reach a state whose residual is within NEWTON_RTOL of the
        state's scale (the message gives both); ``result`` holds the last iterate.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> m = pk.Model(pk.Spheroid(1.5), pk.Viscous(0.1))
    >>> fp = pk.steady.find_fixed_point(m, pk.steady.horizontal_state(10.0), kind='horizontal', value=10.0)
    >>> fp.kind, fp.n_unstable, fp.residual < 1e-10
    ('horizontal', 1, True)
    """
    model = _check_model(model)
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
    # any smooth law has the zero-slip states of every law; Viscous(1) keeps Newton well
    # conditioned where the law's own field is stiff (a regularised Coulomb law, eps -> 0)
    from ..friction.laws import Viscous

    newton_model = Model(model.body, Viscous(1.0), model.chart)
    solver, lift, nz, jac = _newton_system(newton_model, kind, fixed)
    z0 = guess if model.chart is EULER else guess[[0, 1, 3, 4, 6, 7]]
    sz = np.maximum(np.abs(z0), 1.0)
    J0 = np.asarray(jac(z0, newton_model.p, value))
    se = np.abs(J0) @ sz if np.all(np.isfinite(J0)) else np.ones(nz)
    se = np.maximum(se, 1e-12 * max(float(se.max()), 1.0))
    pv = np.concatenate([newton_model.p, [value], sz, se])
    z = sz * np.asarray(solver(z0 / sz, pv)).ravel()
    x = np.asarray(lift(z, newton_model.p, value)).ravel()
    article = "an" if kind[0] in "aeiou" else "a"
    if not np.all(np.isfinite(x)):
        raise ConvergenceError(f"Newton did not converge to {article} {kind} fixed point with {fixed} = {value:g}: "
                               "the iterate left the domain of the equations (non-finite state)", None)
    err = _backward_error(model, x)
    if not err <= NEWTON_RTOL:
        residual = float(np.max(np.abs(model._rhs(x, _mode_for(model)))))
        try:
            last = linearise(model, x, kind=kind)
        except (ParameterError, ConvergenceError):
            last = None
        miss = (f"residual {residual:.2e} is {err:.1e} of the state's scale, above the tolerance {NEWTON_RTOL:g}"
                if np.isfinite(err) else "the field or its Jacobian is not finite at the last iterate")
        raise ConvergenceError(f"Newton did not converge to {article} {kind} fixed point with {fixed} = {value:g}: "
                               + miss, last)
    return linearise(model, x, kind=kind)


# -- linearisation -------------------------------------------------------------------------


_REDUCED: dict = {}


def _rolling_reduced_jacobian(model: Model, x: np.ndarray):
    """Jacobian of the rolling field on the no-slip manifold, in coordinates that omit the
    velocity of O (it is slaved to u = 0), and the map lifting tangent vectors back.
    The CasADi function is built once per compiled model."""
    n = model.n_states
    i, j = model.chart.velocity_slots
    keep = [k for k in range(n) if k not in (i, j)]
    key = model.compiled.key
    if key not in _REDUCED:
        r = ca.SX.sym("r", len(keep))
        p = ca.SX.sym("p", len(model.p))
        base = [None] * n
        for k, kk in enumerate(keep):
            base[kk] = r[k]
        base[i] = ca.SX(0)
        base[j] = ca.SX(0)
        u = model.function("slip")(ca.vertcat(*base), p)  # the slip is (velocity slots) + u(rest)
        full = list(base)
        full[i], full[j] = -u[0], -u[1]
        xr = ca.vertcat(*full)
        fr = model.function("rhs_rolling")(xr, p)
        red = ca.vertcat(*[fr[k] for k in keep])
        _REDUCED[key] = ca.Function("Jr", [r, p], [ca.jacobian(red, r), ca.jacobian(xr, r)])
    Jr, L = _REDUCED[key](x[keep], model.p)
    return np.asarray(Jr), np.asarray(L)


def linearise(model: Model, x, *, kind: str = "state") -> FixedPoint:
    """Eigen-decomposition of the exact Jacobian at ``x`` (see the module notes for Coulomb),
    with an error bound on every eigenvalue (:class:`FixedPoint`).

    Raises ParameterError for a model that is not a Model, a state of the wrong length or
    with non-finite entries, or a state where the Jacobian overflows; ConvergenceError if
    the eigenvalue iteration does not converge.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> fp = pk.linearise(pk.Model(pk.Spheroid(1.5), pk.Viscous(0.1)), pk.steady.horizontal_state(10.0), kind='horizontal')
    >>> fp.n_unstable, round(float(fp.eigenvalues[0].real), 6)
    (1, 0.089489)
    """
    model = _check_model(model)
    if not isinstance(kind, str) or not kind:
        raise ParameterError("kind", "must be a label such as 'horizontal' or 'state'", kind)
    x = check_vector("x", x, model.n_states)
    mode = _mode_for(model)
    f = model._rhs(x, mode)
    residual = float(np.max(np.abs(f)))
    jac = _law_jacobian(model, mode)
    Jr, L = jac(x)
    law = "coulomb-rolling" if mode is Mode.ROLLING else model.friction.name
    if not (np.all(np.isfinite(Jr)) and np.isfinite(residual)):
        raise ParameterError("x", "gives a non-finite field or Jacobian (a state beyond double precision, or where "
                                  "the contact equations are singular)", x)
    try:
        lam, V, bounds = _eigen_with_bounds(Jr, _jacobian_error(model, mode, jac, x, f, Jr))
    except (np.linalg.LinAlgError, ValueError) as exc:
        raise ConvergenceError(f"the eigenvalues of the Jacobian at the {kind} state did not converge ({exc})") from None
    if L is not None:
        V = L @ V  # tangent vectors of the no-slip manifold, in chart coordinates
    y = model.chart.to_paper(x)
    if model.chart is VECTOR and np.hypot(x[0], x[1]) == 0.0:
        y[2] = np.nan  # Omega is undefined at theta = 0
    return FixedPoint(kind, model.chart.name, x, y, lam, V, residual, law, error_bounds=bounds)


def _law_jacobian(model: Model, mode: Mode):
    """x -> (J, L): the Jacobian the law is linearised with, and for the rolling field the
    map lifting its reduced coordinates to the chart state (None otherwise)."""
    if mode is Mode.ROLLING:
        return lambda x: _rolling_reduced_jacobian(model, x)
    return lambda x: (model._jacobian(x, mode), None)


def _jacobian_error(model: Model, mode: Mode, jac, x: np.ndarray, f: np.ndarray, J: np.ndarray) -> float:
    """A size (Frobenius norm) for the error of the computed Jacobian J at the computed state x:
    rounding (JACOBIAN_ROUNDING eps ||J||) plus the change of J across the state's own error
    dx, the least-squares Newton correction -J_full^+ f(x) of the residual f."""
    rounding = JACOBIAN_ROUNDING * np.finfo(float).eps * float(np.linalg.norm(J))
    if not np.any(f):
        return rounding
    J_full = model._jacobian(x, mode)
    dx = np.linalg.lstsq(J_full, -f, rcond=None)[0]
    if not np.all(np.isfinite(dx)):
        return float("inf")
    J2 = jac(x + dx)[0]
    return rounding + float(np.linalg.norm(J2 - J)) if np.all(np.isfinite(J2)) else float("inf")


def _eigen_with_bounds(J: np.ndarray, error: float):
    """Eigenvalues (sorted by descending real part, then imaginary part), right eigenvectors
    and first-order error bounds kappa_i * error, kappa_i = 1/|y_i^H x_i| (unit vectors)."""
    import scipy.linalg

    lam, VL, VR = scipy.linalg.eig(J, left=True, right=True)
    nl, nr = np.linalg.norm(VL, axis=0), np.linalg.norm(VR, axis=0)
    with np.errstate(divide="ignore", invalid="ignore"):
        kappa = (nl * nr) / np.abs(np.sum(VL.conj() * VR, axis=0))
    bounds = np.where(np.isfinite(kappa), kappa * error, np.inf)
    order = np.lexsort((-lam.imag, -lam.real))
    return lam[order], VR[:, order], bounds[order]


# -- all fixed points for a family parameter ---------------------------------------------


def fixed_points(model: Model, model_vector: Model | None = None, *, omega0: float | None = None,
                 n0: float | None = None) -> list[FixedPoint]:
    """Every class of steady state at the given family parameter, for any body.

    ``omega0``: the horizontal precession (where h_theta(pi/2) = 0) and the precessions with
    rate Omega0 (the one continuing the horizontal state of an asymmetric body is labelled
    "horizontal-like"). ``n0``: the vertical spin at theta = 0, the inverted one at theta = pi
    (bodies without flip symmetry; both in the vector chart: ``model_vector``, by default
    ``model`` in the vector chart) and the precessions with spin n0. Each pole carries its
    closed-form stability criterion under sliding friction in ``parameter``.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
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
    body = model_euler.body
    out: list[FixedPoint] = []
    if omega0 is not None:
        omega0 = check_finite("omega0", omega0)
        if body.flip_symmetric or abs(body.h(np.pi / 2)[1]) < 1e-14:
            out.append(find_fixed_point(model_euler, horizontal_state(omega0), kind="horizontal", value=omega0))
        fixed, value = "Omega", omega0
    else:
        n0 = check_finite("n0", n0)
        out.append(_pole(model_vector, n0, "upright"))
        if not body.flip_symmetric:
            out.append(_pole(model_vector, n0, "inverted"))
        fixed, value = "n", n0
    thetas = precession_angles(body, omega0=omega0, n0=n0)
    like = horizontal_like_angle(body, thetas) if omega0 is not None else None
    for theta in thetas:
        guess = precession_state(body, theta, omega0=omega0, n0=n0)
        kind = "horizontal-like" if theta == like else "intermediate"
        try:
            fp = find_fixed_point(model_euler, guess, kind=kind, value=value, fixed=fixed)
        except ConvergenceError:
            continue
        out.append(replace(fp, parameter={fixed: value, "theta": float(fp.x[4])}))
    return out


def _pole(model_vector: Model, n0: float, pole: str) -> FixedPoint:
    """The spinning state at theta = 0 (Newton, as every family) or theta = pi (exact), with the
    closed-form criterion under sliding friction attached."""
    if pole == "upright":
        fp = find_fixed_point(model_vector, vertical_state(n0), kind="vertical", value=n0)
    else:
        fp = linearise(model_vector, inverted_state(n0), kind="inverted")
    crit = pole_stability_threshold(model_vector.body, pole)
    info = {"n0": n0, "theta": 0.0 if pole == "upright" else float(np.pi), **crit.to_dict(n0)}
    return replace(fp, parameter=info)


def continue_family(model: Model, kind: str, values, *, start=None) -> Branch:
    """Natural-parameter continuation: Newton at each value from the previous solution.

    ``kind``: "horizontal" (values of Omega0), "vertical" (values of n0; vector chart) or
    "intermediate" (values of Omega0; ``start`` is a state on the family near values[0]).
    """
    model = _check_model(model)
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
