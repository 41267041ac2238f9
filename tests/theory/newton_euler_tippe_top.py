"""An independent model of the tippe top, written here with no phasekit code, for checking
phasekit.theory.tippetop and the full model.

The full 3-D Newton-Euler system of an eccentric sphere on a plane (unit radius, mass and
gravity), with the contact kept and a *viscous* sliding-friction law F = -kappa u_P (the
energy/Jellett theory does not depend on the friction law; linear stability needs a law that is
smooth at zero slip)."""

import math

import numpy as np

EZ = np.array([0.0, 0.0, 1.0])


def rhs(x, alpha, A, C, kappa):
    """x = (k, w, v_x, v_y): axis, angular velocity, horizontal velocity of G."""
    k, w = x[0:3], x[3:6]
    kh = k / np.linalg.norm(k)
    rP = alpha * kh - EZ  # G -> P, with G = O - alpha k and P = O - e_Z
    n = w @ kh
    vG = np.array([x[6], x[7], -alpha * np.cross(w, kh)[2]])  # z_G = 1 - alpha k_z
    slip = vG + np.cross(w, rP)
    F = -kappa * np.array([slip[0], slip[1], 0.0])

    def Iinv(t):
        return (t - kh * (kh @ t)) / A + kh * (kh @ t) / C

    a0 = Iinv(np.cross(rP, F) - (C - A) * n * np.cross(w, kh))
    b = Iinv(np.cross(rP, EZ))
    # normal force N from z_G'' = N - 1 = -alpha (k'')_z, k'' = w' x k + w x (w x k)
    c0 = np.cross(a0, kh)[2] + np.cross(w, np.cross(w, kh))[2]
    N = (1 - alpha * c0) / (1 + alpha * np.cross(b, kh)[2])
    return np.concatenate([np.cross(w, k), a0 + N * b, F[:2]]), N, slip


def rotating_rhs(x, alpha, A, C, kappa, Om):
    """The same equations seen from axes turning at Om about e_Z."""
    f = rhs(x, alpha, A, C, kappa)[0].copy()
    f[0:3] -= np.cross(Om * EZ, x[0:3])
    f[3:6] -= np.cross(Om * EZ, x[3:6])
    f[6:8] -= np.cross(Om * EZ, np.array([x[6], x[7], 0.0]))[:2]
    return f


def jacobian(f, x, h=1e-6):
    J = np.zeros((x.size, x.size))
    for i in range(x.size):
        e = np.zeros(x.size)
        e[i] = h
        J[:, i] = (f(x + e) - f(x - e)) / (2 * h)
    return J


def pole_max_real(alpha, A, C, spin, inverted, kappa=0.3):
    """Largest real part of the transverse eigenvalues at the upright (inverted) spinning state."""
    s = -1.0 if inverted else 1.0
    x = np.array([0, 0, s, 0, 0, s * spin, 0, 0], dtype=float)  # w = spin * k
    J = jacobian(lambda y: rhs(y, alpha, A, C, kappa)[0], x)
    idx = [0, 1, 3, 4, 6, 7]  # transverse block (decoupled from k_z, w_z by the axial symmetry)
    return np.linalg.eigvals(J[np.ix_(idx, idx)]).real.max()


def jellett_of_state(x, alpha, A, C):
    k = x[0:3] / np.linalg.norm(x[0:3])
    w = x[3:6]
    L = A * (w - (w @ k) * k) + C * (w @ k) * k
    return L @ (EZ - alpha * k)


def vertical_start(theta0, n0):
    return np.array([math.sin(theta0), 0, math.cos(theta0), 0, 0, n0, 0, 0])


def final_theta(alpha, A, C, theta0, n0, T, kappa=0.5):
    from scipy.integrate import solve_ivp  # here: scipy.integrate takes 0.3 s to import

    sol = solve_ivp(lambda t, x: rhs(x, alpha, A, C, kappa)[0], (0, T), vertical_start(theta0, n0),
                    method="DOP853", rtol=1e-8, atol=1e-10)
    assert sol.success
    k = sol.y[0:3, -1] / np.linalg.norm(sol.y[0:3, -1])
    return math.acos(np.clip(k[2], -1, 1)), sol
