"""The impact at touchdown: Newton restitution with a Coulomb-limited tangential impulse.

Model (algebraic impact law of Brach, "Rigid body collisions", J. Appl. Mech. 56, 1989;
see also Stronge, "Impact Mechanics", CUP 2000, ch. 4). At the contact point P (r_P from O,
normal e_Z) the velocity change produced by an impulse P_imp = (P_t1, P_t2, P_n) is
dv_P = K P_imp, with the collision matrix K = 1 + [r_P]x^T I^-1 [r_P]x (mass 1).

1. Normal: Newton's law v_Pn+ = -e v_Pn- with 0 <= e <= 1.
2. Tangential: the impulse that stops the tangential slip (sticking) is used if it lies in
   the friction cone, |P_t| <= mu P_n; otherwise the slip continues and P_t = -mu P_n u_t
   with u_t the pre-impact slip direction (sliding impact), P_n from step 1.
3. Energy: Newton restitution with friction can create energy when the slip reverses during
   the impact (Kane & Levinson, J. Appl. Mech. 52, 1985). The tangential impulse is scaled
   back toward the frictionless one until the kinetic energy does not increase; such cases
   are counted in ImpactResult.energy_limited.

For e = 1 and mu = 0 the impact conserves kinetic energy exactly; for e < 1 it dissipates.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._runtime.validate import check_instance, check_nonnegative, check_vector, finite_result
from ..bodies.body import Body
from ..errors import ParameterError

#: how far from 1 the length of the axis ``k`` may be: the drift of the integrated flight state
#: (7e-6 at rtol = 1e-3) with a wide margin; ``k`` is normalised before use
UNIT_TOL = 1e-3


def _body(body) -> Body:
    return check_instance("body", body, Body, "Spheroid(1.5)")


def _axis(k) -> np.ndarray:
    """The symmetry axis: 3 finite numbers of length 1 (within UNIT_TOL)."""
    k = check_vector("k", k, 3)
    if not abs(np.linalg.norm(k) - 1.0) <= UNIT_TOL:
        raise ParameterError("k", f"must be a unit vector (length 1 within {UNIT_TOL:g}; length "
                                  f"{np.linalg.norm(k):.10g})", k)
    return k


def _skew(r):
    return np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])


@finite_result
def contact_point(body, k) -> np.ndarray:
    """r_P = -H'(c)(k - c e_Z) - H(c) e_Z for the lowest point, c = k_Z (vector form); ``k``
    is the unit symmetry axis."""
    return contact_point_of(_body(body), _axis(k))


def contact_point_of(body, k) -> np.ndarray:
    k = np.asarray(k, dtype=float) / np.linalg.norm(k)
    c = k[2]
    H, dH = body.height_slope(c)
    ez = np.array([0.0, 0.0, 1.0])
    return -dH * (k - c * ez) - H * ez


def _inverse_inertia(body, k) -> np.ndarray:
    k = np.asarray(k, dtype=float) / np.linalg.norm(k)
    P = np.outer(k, k)
    return (np.eye(3) - P) / body.A + P / body.C


@finite_result
def collision_matrix(body, k) -> np.ndarray:
    """K = 1 + [r_P]x^T I^-1 [r_P]x: the contact point's velocity change per unit impulse."""
    return _collision_matrix(_body(body), _axis(k))


def _collision_matrix(body, k) -> np.ndarray:
    r = contact_point_of(body, k)
    S = _skew(r)
    return np.eye(3) + S.T @ _inverse_inertia(body, k) @ S


@dataclass(frozen=True)
class ImpactResult:
    """What :func:`impact` returns: the velocities after the impact, the impulse, the normal
    speed of the contact point before and after, and the kinetic energy before and after.

    Attributes
    ----------
    w : numpy.ndarray
        Post-impact angular velocity (3,), units sqrt(g/b).
    v : numpy.ndarray
        Post-impact velocity of O (3,), units sqrt(g b).
    impulse : numpy.ndarray
        The impulse at the contact point, (P_t1, P_t2, P_n), units M sqrt(g b).
    v_normal_before, v_normal_after : float
        The normal (vertical) velocity of the contact point before and after the impact,
        units sqrt(g b) (< 0: approaching the table).
    energy_before, energy_after : float
        Kinetic energy before and after the impact, units M g b.
    sticking : bool
        The tangential slip was stopped.
    energy_limited : bool
        The friction impulse was reduced to avoid an energy gain.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> res = pk.core.impact(pk.Spheroid(1.5), np.array([np.sin(1.0), 0.0, np.cos(1.0)]), np.array([0.0, 0.0, 5.0]), np.array([0.0, 0.0, -0.01]), e=0.0, mu=0.1)
    >>> from phasekit.core.impact import ImpactResult
    >>> isinstance(res, ImpactResult), res.energy_after <= res.energy_before
    (True, np.True_)
    """

    w: np.ndarray  # post-impact angular velocity
    v: np.ndarray  # post-impact velocity of O
    impulse: np.ndarray  # (P_t1, P_t2, P_n)
    v_normal_before: float
    v_normal_after: float
    energy_before: float
    energy_after: float
    sticking: bool  # the tangential slip was stopped
    energy_limited: bool  # the friction impulse was reduced to avoid an energy gain


def kinetic_energy_of(body, k, w, v) -> float:
    kh = k / np.linalg.norm(k)
    n = w @ kh
    L = body.A * (w - n * kh) + body.C * n * kh
    return 0.5 * v @ v + 0.5 * w @ L


@finite_result
def impact(body, k, w, v, *, e: float, mu: float) -> ImpactResult:
    """Apply the impact law at touchdown to the rigid-body velocities (k, w, v = velocity of O).

    Parameters
    ----------
    body : Body
        The body (its support function places the contact point; A, C its inertia).
    k : array_like
        The unit symmetry axis: 3 finite numbers of length 1 (within 1e-3; normalised before
        use).
    w : array_like
        The angular velocity before the impact: 3 finite numbers, units sqrt(g/b).
    v : array_like
        The velocity of O before the impact: 3 finite numbers, units sqrt(g b).
    e : float
        Newton's restitution, in [0, 1].
    mu : float
        The friction coefficient, finite and >= 0.

    Returns
    -------
    ImpactResult
        The post-impact (w, v) in ``ImpactResult.w``, ``ImpactResult.v``, with the impulse,
        the normal speeds and the energies. A contact point that is not approaching the
        table (normal velocity >= 0) is left as it is: zero impulse.

    Raises
    ------
    ParameterError
        If ``body`` is not a Body, ``k`` is not a unit vector of 3 finite numbers, ``w`` or
        ``v`` is not 3 finite numbers, ``e`` is outside [0, 1], ``mu`` is negative or not
        finite, or the result is not finite (naming the argument of largest magnitude).

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> res = pk.core.impact(body, np.array([np.sin(1.0), 0.0, np.cos(1.0)]), np.array([0.0, 0.0, 5.0]), np.array([0.0, 0.0, -0.01]), e=0.5, mu=0.1)
    >>> round(res.v_normal_after / res.v_normal_before, 6)
    np.float64(-0.5)
    """
    body = _body(body)
    k = _axis(k)
    w, v = check_vector("w", w, 3), check_vector("v", v, 3)
    e = check_nonnegative("e", e, upper=1.0)
    mu = check_nonnegative("mu", mu)
    return apply_impact(body, k, w, v, e, mu)


def apply_impact(body, k, w, v, e: float, mu: float) -> ImpactResult:
    """:func:`impact` without the checks (for states the integrator made)."""
    k, w, v = (np.asarray(a, dtype=float) for a in (k, w, v))
    r = contact_point_of(body, k)
    Iinv = _inverse_inertia(body, k)
    K = _collision_matrix(body, k)
    vP = v + np.cross(w, r)
    vn = vP[2]
    target = np.array([0.0, 0.0, -e * vn])

    def apply(P):
        return w + Iinv @ np.cross(r, P), v + P

    E0 = kinetic_energy_of(body, k, w, v)
    if vn >= 0.0:  # not approaching: nothing to do
        return ImpactResult(w.copy(), v.copy(), np.zeros(3), vn, vn, E0, E0, False, False)
    P_stick = np.linalg.solve(K, target - vP)  # tangential slip stopped, normal restitution
    if np.hypot(P_stick[0], P_stick[1]) <= mu * P_stick[2]:
        P, sticking = P_stick, True
    else:
        ut = vP[:2] / max(np.hypot(vP[0], vP[1]), 1e-300)
        d = np.array([-mu * ut[0], -mu * ut[1], 1.0])
        Pn = (target[2] - vn) / (K @ d)[2]
        P, sticking = Pn * d, False
    limited = False
    if kinetic_energy_of(body, k, *apply(P)) > E0 * (1 + 1e-14):
        # scale the tangential part back (keeping normal restitution) until no energy gain
        limited = True
        lo, hi = 0.0, 1.0

        def with_scale(s):
            Pt = P.copy()
            Pt[:2] *= s
            Pt[2] = (target[2] - vn - K[2, :2] @ Pt[:2]) / K[2, 2]  # the normal impulse re-solved
            return Pt

        for _ in range(60):
            s = 0.5 * (lo + hi)
            if kinetic_energy_of(body, k, *apply(with_scale(s))) > E0 * (1 + 1e-14):
                hi = s
            else:
                lo = s
        P = with_scale(lo)
    w_new, v_new = apply(P)
    vn_after = (v_new + np.cross(w_new, r))[2]
    return ImpactResult(w_new, v_new, P, vn, float(vn_after), E0, kinetic_energy_of(body, k, w_new, v_new), sticking, limited)
