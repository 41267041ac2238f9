"""Two coordinate charts of the same contact dynamics.

A chart gives, in CasADi SX, the state derivative as an *affine* function of the contact
force Fc = (F_1, F_2, R), the vertical velocity W of the centre O (so that the contact
constraint is R = 1 + dW/dt, (2.8)), the slip velocity u of the contact point P
(horizontal, in the same axes as F_1, F_2) and the conserved or monitored quantities.
:mod:`phasekit.model` turns these into one smooth vector field per mode.

``euler``
    The paper's variables (U, V, Omega, Lambda, theta, n) and equations (2.7),
    transcribed. (U, V) and (F_X, F_y) are in axes that turn with the precession.
    Singular at theta = 0 and pi (division by sin(theta) in (2.7c)).
``vector``
    Derived independently from Newton-Euler: state (k, w, v) with k the unit vector of
    the symmetry axis, w the angular velocity and v = (v_x, v_y) the horizontal velocity of
    O, all in fixed axes. Regular at theta = 0. k is kept on the unit sphere by construction
    rather than projection: the field uses khat = k/|k| in every geometric term and
    dk/dt = w x k, which leaves |k| exactly invariant, so a drift of |k| (of the order of
    the tolerance) never feeds back into the physics.
"""

from __future__ import annotations

import casadi as ca
import numpy as np

__all__ = ["CHARTS", "EULER_NAMES", "euler_terms", "vector_terms", "euler_to_vector", "vector_to_euler"]

EULER_NAMES = ("U", "V", "Omega", "Lambda", "theta", "n")
VECTOR_NAMES = ("k_x", "k_y", "k_z", "w_x", "w_y", "w_z", "v_x", "v_y")


def euler_terms(x, shape, A, C, Fc, height_c):
    """Equations (2.7) with the contact force as a symbol.

    Returns a dict with ``xdot`` (affine in Fc), ``W``, ``slip``, ``energy``, ``L_Z``,
    ``spin`` (n), ``jellett`` (J = -L.X_P) and ``theta``.
    """
    U, V, Om, Lam, th, n = (x[i] for i in range(6))
    FX, Fy, R = Fc[0], Fc[1], Fc[2]
    c, s = ca.cos(th), ca.sin(th)
    h = height_c(c, shape)
    h1 = ca.jacobian(h, th)
    xP = h * s + h1 * c  # -h^2 d/dtheta(cos/h), (2.2)
    zPm = h * c - h1 * s  # h^2 d/dtheta(sin/h) = -z_P
    xdot = ca.vertcat(
        Om * V + FX,  # (2.7a)
        -Om * U + Fy,  # (2.7b)
        (C * n * Lam - 2 * A * Om * Lam * c - zPm * Fy) / (A * s),  # (2.7c)
        (Om * s * (A * Om * c - C * n) - R * h1 - h * FX) / A,  # (2.7d)
        Lam,  # (2.7e)
        xP * Fy / C,  # (2.7f)
    )
    W = Lam * h1  # (2.5)
    slip = ca.vertcat(U - h * Lam, V + Om * h1 + (n - Om * c) * xP)  # (2.4a,b)
    energy = 0.5 * (U * U + V * V + W * W) + 0.5 * A * (Om * Om * s * s + Lam * Lam) + 0.5 * C * n * n + h
    L_Z = A * Om * s * s + C * n * c
    jellett = A * Om * s * xP + C * n * zPm
    return dict(xdot=xdot, W=W, slip=slip, energy=energy, L_Z=L_Z, spin=n, jellett=jellett, theta=th, cos_theta=c, h=h)


def _cross(a, b):
    return ca.vertcat(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def vector_terms(x, shape, A, C, Fc, height_c):
    """Newton-Euler in fixed axes: m dv/dt = F + R e_Z - e_Z, dL/dt = r_P x (F + R e_Z).

    With I = A 1 + (C - A) k k^T about O and dI/dt w = (C - A) n (w x k):
    I dw/dt = r_P x Fc - (C - A) n (w x k). The contact point relative to O is
    r_P = -H'(c) (k - c e_Z) - H(c) e_Z with c = k_Z (the lowest point of the surface).
    """
    k = x[0:3]
    w = x[3:6]
    vx, vy = x[6], x[7]
    khat = k / ca.norm_2(k)
    c = khat[2]
    csym = ca.SX.sym("c")
    Hs = height_c(csym, shape)
    dHs = ca.jacobian(Hs, csym)
    H = ca.substitute(Hs, csym, c)
    dH = ca.substitute(dHs, csym, c)
    ez = ca.DM([0, 0, 1])
    rP = -dH * (khat - c * ez) - H * ez
    force = ca.vertcat(Fc[0], Fc[1], Fc[2])
    n = ca.dot(w, khat)
    wxk = _cross(w, khat)
    torque = _cross(rP, force) - (C - A) * n * wxk
    # I^{-1} = (1 - k k^T)/A + k k^T / C
    wdot = (torque - khat * ca.dot(khat, torque)) / A + khat * ca.dot(khat, torque) / C
    kdot = _cross(w, k)
    xdot = ca.vertcat(kdot, wdot, Fc[0], Fc[1])
    W = dH * wxk[2]  # d/dt H(k_Z)
    vP = ca.vertcat(vx, vy, 0) + _cross(w, rP)
    slip = vP[0:2]
    Lvec = A * (w - n * khat) + C * n * khat
    energy = 0.5 * (vx * vx + vy * vy + W * W) + 0.5 * ca.dot(w, Lvec) + H
    L_Z = Lvec[2]
    jellett = -ca.dot(Lvec, rP)
    theta = ca.acos(c)
    return dict(xdot=xdot, W=W, slip=slip, energy=energy, L_Z=L_Z, spin=n, jellett=jellett, theta=theta, cos_theta=c, h=H)


CHARTS = {
    "euler": dict(names=EULER_NAMES, terms=euler_terms),
    "vector": dict(names=VECTOR_NAMES, terms=vector_terms),
}


def euler_to_vector(y) -> np.ndarray:
    """(U, V, Omega, Lambda, theta, n) -> (k, w, v) with the axis in the X-Z plane (azimuth 0).

    w = Omega e_Z + Lambda e_Y + (n - Omega cos theta) k, where e_X points along the
    horizontal projection of k and e_Y = e_Z x e_X; (U, V) are the velocity along (e_X, e_Y).
    """
    U, V, Om, Lam, th, n = (float(v) for v in y)
    s, c = np.sin(th), np.cos(th)
    k = np.array([s, 0.0, c])
    w = Om * np.array([0.0, 0.0, 1.0]) + Lam * np.array([0.0, 1.0, 0.0]) + (n - Om * c) * k
    return np.concatenate([k, w, [U, V]])


def vector_to_euler(z) -> np.ndarray:
    """(k, w, v) -> (U, V, Omega, Lambda, theta, n), for theta in (0, pi).

    At theta = 0 or pi the azimuth, Omega and Lambda are undefined (the chart's
    singularity); those return NaN-free limits only when the tilt is exactly zero:
    Omega is then set to the vertical component of w and Lambda, U, V refer to the x axis.
    """
    z = np.asarray(z, dtype=float)
    k = z[0:3] / np.linalg.norm(z[0:3])
    w = z[3:6]
    v = np.array([z[6], z[7], 0.0])
    kh = np.hypot(k[0], k[1])  # sin(theta), accurate near the pole (1 - cos^2 is not)
    c = float(np.clip(k[2], -1.0, 1.0))
    th = float(np.arctan2(kh, k[2]))
    n = float(w @ k)
    if kh == 0.0:
        eX, eY = np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0])
        Om = float(w[2])
    else:
        eX = np.array([k[0] / kh, k[1] / kh, 0.0])
        eY = np.array([-eX[1], eX[0], 0.0])
        if abs(c) > 0.5:
            # w.e_X = (n - Omega cos) sin: both terms O(sin), no cancellation near the pole
            Om = (n * kh - w @ eX) / (c * kh)
        else:
            Om = (w[2] - n * c) / (kh * kh)
    return np.array([v @ eX, v @ eY, Om, w @ eY, th, n])
