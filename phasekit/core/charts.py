"""Coordinate charts of the rigid-body dynamics: objects, not strings.

A chart gives, in CasADi SX, the state derivative as an *affine* function of the contact
force Fc = (F_1, F_2, R), the vertical velocity W of the centre of mass G (so that the
contact constraint is R = 1 + dW/dt, (2.8)), the slip velocity u of the contact point P and
the monitored quantities. :mod:`phasekit.core.fields` turns these into one smooth vector field per
mode; free flight is the same equations with Fc = 0 (:data:`FLIGHT`).

:data:`EULER`
    The paper's variables (U, V, Omega, Lambda, theta, n) and equations (2.7),
    transcribed. (U, V) and (F_X, F_y) are in axes that turn with the precession.
    Singular at theta = 0 and pi (division by sin(theta) in (2.7c)).
:data:`VECTOR`
    Derived independently from Newton-Euler: state (k, w, v) with k the unit vector of
    the symmetry axis, w the angular velocity and v = (v_x, v_y) the horizontal velocity of
    G, all in fixed axes. Regular at theta = 0 and pi. k is kept on the unit sphere by
    construction rather than projection: the field uses khat = k/|k| in every geometric
    term and dk/dt = w x k, which leaves |k| exactly invariant.
:data:`FLIGHT`
    The vector chart's state plus the gap Delta (4.1) between the body and the table and
    its rate (Delta = z - h would lose its t^3 growth after lift-off to cancellation).
"""

from __future__ import annotations

import casadi as ca
import numpy as np

from ..errors import ParameterError

#: theta within this of 0 or pi cannot be integrated in the Euler chart (2.7c divides by sin)
POLE_GUARD = 1e-12

#: within this angle of theta = 0 or pi the vector chart is the default. Measured (oblate
#: a = 0.6, n0 = 12, viscous mu = 0.1, rtol 1e-9, to t = 40): away from the pole the Euler
#: chart takes 380-510 Taylor steps against 570-810 for the vector chart (whose state
#: follows the precession) with 10-100x smaller errors; at theta0 = 1e-6 the vector chart
#: wins (382 vs 510 steps, error 8e-8 vs 1.6e-7). Exactly at the pole only it can start.
POLE_MARGIN = 1e-5

#: the paper's state variables, in order
PAPER_NAMES = ("U", "V", "Omega", "Lambda", "theta", "n")


def _cross(a, b):
    return ca.vertcat(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


class Chart:
    """Base class of charts; see the module notes for the three instances."""

    name = ""
    state_names: tuple[str, ...] = ()
    #: state indices of the horizontal velocity of G: adding du to them adds du to the slip
    velocity_slots: tuple[int, int] = (0, 1)
    #: whether the chart is regular at theta = 0 and pi
    regular_at_poles = True

    @property
    def n_states(self) -> int:
        return len(self.state_names)

    def terms(self, x, H, A, C, Fc, wrench=None) -> dict:
        """Symbolic terms: ``xdot`` (affine in Fc), ``W``, ``slip`` (in the chart's horizontal axes,
        which turn about the vertical at ``frame_rate``: Omega for the Euler chart, 0 for the vector
        chart's fixed axes), ``energy``, ``L_Z``,
        ``spin``, ``jellett``, ``cos_theta``, ``h``, ``paper`` (the paper's six variables), and
        ``w``, ``v`` (angular velocity, velocity of G, in axes with e_Z vertical) and ``lift``
        (the wrench's vertical force). ``H`` maps c = cos(theta) to the height of G (an SX
        expression); ``wrench(w, v, R, k) -> (f, couple)``, optional, adds a dissipative force at
        G and a couple (:mod:`phasekit.friction.dissipation`); ``k`` is the symmetry axis (a unit
        vector in the same axes as w), also returned as the term ``k``."""
        raise NotImplementedError

    #: the state's positions (what a body at rest keeps; every other entry is a velocity)
    positions: tuple[int, ...] = ()

    def at_rest(self, x) -> np.ndarray:
        """The state ``x`` with every velocity set to zero (the body at rest where it stands)."""
        out = np.zeros_like(np.asarray(x, dtype=float))
        out[list(self.positions)] = np.asarray(x, dtype=float)[list(self.positions)]
        return out

    def with_pivot(self, x, dw: float) -> np.ndarray:
        """The state ``x`` with dw added to the spin about the vertical, w_Z (nothing else of w
        changes)."""
        raise NotImplementedError

    def with_roll(self, x, dw) -> np.ndarray:
        """The state ``x`` with the horizontal dw = (dw_X, dw_Y) added to w (in the axes of the
        chart's ``w`` term; nothing else of w changes)."""
        raise NotImplementedError

    def from_paper(self, y) -> np.ndarray:
        """A state in the paper's variables, in this chart's coordinates."""
        raise NotImplementedError

    def to_paper(self, x) -> np.ndarray:
        """A state of this chart in the paper's variables (U, V, Omega, Lambda, theta, n)."""
        raise NotImplementedError

    def theta(self, x) -> float:
        return float(self.to_paper(x)[4])

    def rotation_rate(self, x) -> float:
        """The fastest rotation rate of a state (>= 1): sets the period of R's oscillation."""
        return float(max(1.0, np.linalg.norm(np.asarray(x, dtype=float)[3:6])))

    def __repr__(self) -> str:
        return f"<chart {self.name}>"

    def __reduce__(self):  # charts are singletons: unpickle to the same object
        return (_chart_named, (self.name,))


class EulerChart(Chart):
    name = "euler"
    state_names = PAPER_NAMES
    positions = (4,)
    velocity_slots = (0, 1)
    regular_at_poles = False

    def terms(self, x, H, A, C, Fc, wrench=None) -> dict:
        U, V, Om, Lam, th, n = (x[i] for i in range(6))
        FX, Fy, R = Fc[0], Fc[1], Fc[2]
        c, s = ca.cos(th), ca.sin(th)
        h = H(c)
        h1 = ca.jacobian(h, th)
        xP = h * s + h1 * c  # -h^2 d/dtheta(cos/h), (2.2)
        zPm = h * c - h1 * s  # h^2 d/dtheta(sin/h) = -z_P
        W = Lam * h1  # (2.5)
        # a dissipative wrench (f at G, couple G) in the turning axes (e_X, e_Y, e_Z), w in them:
        # its couple along e_Y, along e_theta = c e_X - s e_Z and along k enters as friction's does
        xdot = ca.vertcat(
            Om * V + FX,  # (2.7a)
            -Om * U + Fy,  # (2.7b)
            (C * n * Lam - 2 * A * Om * Lam * c - zPm * Fy) / (A * s),  # (2.7c)
            (Om * s * (A * Om * c - C * n) - R * h1 - h * FX) / A,  # (2.7d)
            Lam,  # (2.7e)
            xP * Fy / C,  # (2.7f)
        )
        w = ca.vertcat((n - Om * c) * s, Lam, Om + (n - Om * c) * c)
        lift = ca.SX(0)
        if wrench is not None:
            f, G = wrench(w, ca.vertcat(U, V, W), R, ca.vertcat(s, 0, c))
            G_theta, G_k = c * G[0] - s * G[2], s * G[0] + c * G[2]
            xdot = xdot + ca.vertcat(f[0], f[1], -G_theta / (A * s), G[1] / A, 0, G_k / C)
            lift = f[2]
        slip = ca.vertcat(U - h * Lam, V + Om * h1 + (n - Om * c) * xP)  # (2.4a,b)
        energy = 0.5 * (U * U + V * V + W * W) + 0.5 * A * (Om * Om * s * s + Lam * Lam) + 0.5 * C * n * n + h
        L_Z = A * Om * s * s + C * n * c
        jellett = A * Om * s * xP + C * n * zPm
        return dict(xdot=xdot, W=W, slip=slip, energy=energy, L_Z=L_Z, spin=n, jellett=jellett, cos_theta=c, h=h,
                    paper=ca.vertcat(U, V, Om, Lam, th, n), lift=lift, lever=ca.fabs(h1), w=w,
                    v=ca.vertcat(U, V, W), k=ca.vertcat(s, 0, c), frame_rate=Om)

    def from_paper(self, y) -> np.ndarray:
        return np.array(y, dtype=float)

    def to_paper(self, x) -> np.ndarray:
        return np.array(x, dtype=float)

    def theta(self, x) -> float:
        return float(x[4])

    def with_pivot(self, x, dw: float) -> np.ndarray:
        out = np.array(x, dtype=float)  # w + dw e_Z: Omega gains dw, n = w.k gains dw cos(theta)
        out[2] += dw
        out[5] += dw * np.cos(out[4])
        return out

    def with_roll(self, x, dw) -> np.ndarray:
        # w + dw_X e_X + dw_Y e_Y, e_X = (k - cos e_Z)/sin: Lambda gains dw_Y, Omega -dw_X cos/sin,
        # n = w.k gains dw_X sin
        out = np.array(x, dtype=float)
        c, s = np.cos(out[4]), np.sin(out[4])
        out[3] += dw[1]
        out[2] -= dw[0] * c / s
        out[5] += dw[0] * s
        return out

    def rotation_rate(self, x) -> float:
        return float(max(1.0, abs(x[2]), abs(x[5]), abs(x[3])))


class VectorChart(Chart):
    name = "vector"
    state_names = ("k_x", "k_y", "k_z", "w_x", "w_y", "w_z", "v_x", "v_y")
    positions = (0, 1, 2)
    velocity_slots = (6, 7)

    def rigid_terms(self, x, H, A, C, Fc, wrench=None) -> dict:
        """Newton-Euler in fixed axes: m dv/dt = F + R e_Z - e_Z, dL/dt = r_P x (F + R e_Z).

        With I = A 1 + (C - A) k k^T about G and dI/dt w = (C - A) n (w x k):
        I dw/dt = r_P x Fc - (C - A) n (w x k). The contact point relative to G is
        r_P = -H'(c) (k - c e_Z) - H(c) e_Z with c = k_Z (the lowest point of the surface).
        """
        k, w = x[0:3], x[3:6]
        vx, vy = x[6], x[7]
        khat = k / ca.norm_2(k)
        c = khat[2]
        csym = ca.SX.sym("c")
        Hs = H(csym)
        Hc = ca.substitute(Hs, csym, c)
        dH = ca.substitute(ca.jacobian(Hs, csym), csym, c)
        ez = ca.DM([0, 0, 1])
        rP = -dH * (khat - c * ez) - Hc * ez
        n = ca.dot(w, khat)
        wxk = _cross(w, khat)
        W = dH * wxk[2]  # d/dt H(k_Z)
        torque = _cross(rP, ca.vertcat(Fc[0], Fc[1], Fc[2])) - (C - A) * n * wxk
        force, lift = ca.vertcat(Fc[0], Fc[1]), ca.SX(0)
        if wrench is not None:  # a dissipative wrench: a force f at G and a couple G
            f, G = wrench(w, ca.vertcat(vx, vy, W), Fc[2], khat)
            torque, force, lift = torque + G, force + f[0:2], f[2]
        # I^{-1} = (1 - k k^T)/A + k k^T / C
        wdot = (torque - khat * ca.dot(khat, torque)) / A + khat * ca.dot(khat, torque) / C
        xdot = ca.vertcat(_cross(w, k), wdot, force)
        slip = (ca.vertcat(vx, vy, 0) + _cross(w, rP))[0:2]
        Lvec = A * (w - n * khat) + C * n * khat
        rot_energy = 0.5 * ca.dot(w, Lvec)
        # the paper's variables; Omega and the azimuthal axes are undefined at the poles
        s = ca.sqrt(khat[0] ** 2 + khat[1] ** 2)
        eX = ca.vertcat(khat[0] / s, khat[1] / s, 0)
        eY = ca.vertcat(-khat[1] / s, khat[0] / s, 0)
        v3 = ca.vertcat(vx, vy, 0)
        paper = ca.vertcat(ca.dot(v3, eX), ca.dot(v3, eY), (w[2] - n * c) / (s * s), ca.dot(w, eY), ca.atan2(s, c), n)
        return dict(xdot=xdot, W=W, slip=slip, rot_energy=rot_energy, L_Z=Lvec[2], L=Lvec, spin=n,
                    jellett=-ca.dot(Lvec, rP), cos_theta=c, h=Hc, rP=rP, paper=paper, lift=lift, w=w,
                    lever=ca.sqrt(rP[0] ** 2 + rP[1] ** 2),
                    v=ca.vertcat(vx, vy, W), k=khat, frame_rate=ca.SX(0))

    def terms(self, x, H, A, C, Fc, wrench=None) -> dict:
        T = self.rigid_terms(x, H, A, C, Fc, wrench)
        vx, vy, W = x[6], x[7], T["W"]
        T["energy"] = 0.5 * (vx * vx + vy * vy + W * W) + T["rot_energy"] + T["h"]
        return T

    def from_paper(self, y) -> np.ndarray:
        return euler_to_vector(y)

    def with_pivot(self, x, dw: float) -> np.ndarray:
        out = np.array(x, dtype=float)
        out[5] += dw
        return out

    def with_roll(self, x, dw) -> np.ndarray:
        out = np.array(x, dtype=float)
        out[3:5] += np.asarray(dw, dtype=float)
        return out

    def to_paper(self, x) -> np.ndarray:
        return vector_to_euler(x)

    def theta(self, x) -> float:
        x = np.asarray(x, dtype=float)
        return float(np.arctan2(np.hypot(x[0], x[1]), x[2]))


class FlightChart(Chart):
    """Free flight: the vector chart's rigid-body equations with no contact force, plus the
    gap. dv_x/dt = dv_y/dt = 0; d2Delta/dt2 = -1 - d2h/dt2 (G falls freely); the vertical
    velocity of G is dDelta/dt + dh/dt."""

    name = "flight"
    state_names = VectorChart.state_names + ("gap", "gap_rate")
    velocity_slots = (6, 7)

    def terms(self, x, H, A, C, Fc, wrench=None) -> dict:
        # Hdot needs only the rotation; the wrench needs the vertical speed Dd + Hdot: two passes
        T = VECTOR.rigid_terms(x[0:8], H, A, C, ca.SX.zeros(3))
        Hdot = ca.jtimes(T["h"], x, ca.vertcat(T["xdot"], 0, 0))
        D, Dd = x[8], x[9]
        vz = Dd + Hdot
        lift = None
        if wrench is not None:  # in flight only the air acts (the contact laws vanish with R = 0)
            T = VECTOR.rigid_terms(x[0:8], H, A, C, ca.SX.zeros(3), lambda w, v, R, k: wrench(w, ca.vertcat(v[0], v[1], vz), 0, k))
            lift = T["lift"]
        rot = ca.vertcat(T["xdot"], 0, 0)
        Hddot = ca.jtimes(Hdot, x, rot)
        gap_acc = -1 - Hddot if wrench is None else -1 + lift - Hddot
        T["xdot"] = ca.vertcat(T["xdot"], Dd, gap_acc)
        T["energy"] = 0.5 * (x[6] ** 2 + x[7] ** 2 + vz * vz) + T["rot_energy"] + D + T["h"]
        T.update(W=vz, gap=D, gap_rate=Dd, gap_acc=gap_acc, Hdot=Hdot, v=ca.vertcat(x[6], x[7], vz))
        return T

    def from_paper(self, y) -> np.ndarray:
        return np.concatenate([euler_to_vector(y), [0.0, 0.0]])

    def to_paper(self, x) -> np.ndarray:
        return vector_to_euler(np.asarray(x, dtype=float)[:8])

    def theta(self, x) -> float:
        return VECTOR.theta(np.asarray(x)[:8])


EULER, VECTOR, FLIGHT = EulerChart(), VectorChart(), FlightChart()
CHARTS = {c.name: c for c in (EULER, VECTOR, FLIGHT)}


def get_chart(chart, *, contact: bool = True) -> Chart:
    """A chart object from itself or its name ("euler" or "vector"; "flight" unless ``contact``)."""
    if isinstance(chart, Chart) and (chart is not FLIGHT or not contact):
        return chart
    allowed = ("euler", "vector") if contact else tuple(CHARTS)
    if not isinstance(chart, str) or chart not in allowed:
        raise ParameterError("chart", f"must be one of {', '.join(allowed)}", chart)
    return CHARTS[chart]


def _chart_named(name: str) -> Chart:
    return CHARTS[name]


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
    singularity); exactly there Omega is set to the vertical component of w and Lambda,
    U, V refer to the x axis.
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


def choose_chart(theta0: float, requested: str = "auto") -> str:
    """The chart to start at inclination ``theta0`` in: ``euler`` away from the poles (fewer
    steps, smaller errors), ``vector`` within POLE_MARGIN (1e-5) of them; ``requested`` other
    than "auto" is returned as it is.

    Parameters
    ----------
    theta0 : float
        The inclination of the symmetry axis at the start, radians.
    requested : {"auto", "euler", "vector"}
        The chart asked for; "auto" (default) picks one by ``theta0``.

    Returns
    -------
    str
        "euler" or "vector".

    Raises
    ------
    ParameterError
        If ``requested`` is not "auto", "euler" or "vector".

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.core.choose_chart(0.5), pk.core.choose_chart(1e-7), pk.core.choose_chart(0.5, "vector")
    ('euler', 'vector', 'vector')
    """
    if requested not in ("auto", "euler", "vector"):
        raise ParameterError("chart", "must be one of auto, euler, vector", requested)
    if requested != "auto":
        return requested
    return "vector" if min(theta0, np.pi - theta0) < POLE_MARGIN else "euler"
