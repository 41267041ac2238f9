"""Where the body is and how it is turned: the cyclic coordinates the dynamics leaves out.

The paper's state (U, V, Omega, Lambda, theta, n) does not hold the azimuth of the axis, the
spin angle about it or the position of the centre of mass G on the table: they are cyclic.
This module recovers them from any run *after* the integration, by quadrature of the dense
output each segment keeps (the Taylor polynomials of every heyoka step; CVODES segments'
cubic Hermite pieces), so that the integration itself, and every number it gives, is
unchanged (adding quadrature states to heyoka would change its step-size control).

Conventions (section 2 of the paper; docs/physics.md):

* The orientation is R = Rz(psi) Ry(theta) Rz(phi) (z-y-z Euler angles): psi is the azimuth
  of the axis k measured from the fixed X axis (psi' = Omega), theta its inclination, phi the
  spin angle about k (phi' = n - Omega cos theta). k = sin(theta) (cos psi, sin psi, 0) +
  cos(theta) e_Z.
* The paper's (U, V) are the velocity of G along e_X (the horizontal projection of k) and
  e_Y = e_Z x e_X, axes that turn with the precession, so the velocity of G in fixed axes is
  (U + i V) e^{i psi} (as a complex number X + i Y).
* The contact point P lies h_theta e_X from G horizontally ((2.1)); in flight (X_P, Y_P) is the
  point of the table below the lowest point of the body, the same formula.
* Start values psi0, phi0, X0, Y0 (default 0: the axis leans along +X at the start).

Per step the azimuth in the Euler chart is the exact antiderivative of Omega's polynomial;
phi and X + iY are Gauss-Legendre sums over each step (the integrand e^{i psi(t)} (U + iV) is
smooth inside a step). The vector and flight charts carry k and v in fixed axes: there psi is
the azimuth of k (the branch from the quadrature of Omega) plus the angle between the chart's
axes and the fixed ones, and X + iY integrates v exactly. Accuracy: that of the dense output
(the integration's tolerance for Taylor steps; cubic Hermite interpolation on CVODES grids).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._runtime.validate import check_finite
from .._runtime.watch import check_deadline
from ..errors import ParameterError
from .charts import EULER

#: the columns :meth:`Trajectory.sample` gains
POSE_COLUMNS = ("psi", "phi", "X", "Y", "X_P", "Y_P")
#: Gauss-Legendre nodes per step: the integrands are analytic over a Taylor step (which heyoka
#: keeps well inside the radius of convergence), so 12 nodes reach rounding (measured: 8 and 16
#: nodes agree to 1e-15 on the standard run)
GL_NODES = 12
_XI, _WQ = np.polynomial.legendre.leggauss(GL_NODES)
_XI, _WQ = 0.5 * (_XI + 1.0), 0.5 * _WQ  # on [0, 1]


@dataclass(frozen=True)
class Pose:
    """Where a run starts on the table and how the body is turned about its axis then.

    Attributes
    ----------
    psi : float, default 0
        Azimuth of the axis from the fixed X axis, radians.
    phi : float, default 0
        Spin angle about the axis (third z-y-z Euler angle), radians.
    X, Y : float, default 0
        Horizontal position of the centre of mass G (units b).

    Raises
    ------
    ParameterError
        If a field is not a finite real number (named ``pose0.psi``, ...).

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.core.Pose(psi=0.3, X=1.0).to_dict()
    {'psi': 0.3, 'phi': 0.0, 'X': 1.0, 'Y': 0.0}
    """

    psi: float = 0.0
    phi: float = 0.0
    X: float = 0.0
    Y: float = 0.0

    def __post_init__(self):
        for name in ("psi", "phi", "X", "Y"):
            object.__setattr__(self, name, check_finite(f"pose0.{name}", getattr(self, name)))

    @classmethod
    def of(cls, value, name: str = "pose0") -> "Pose":
        """A Pose from itself, None (all zero), a dict with keys psi, phi, X, Y, or 4 numbers.

        Parameters
        ----------
        value : Pose, dict, sequence of 4 numbers or None
            The pose: (psi, phi, X, Y) in that order for a sequence (list, tuple or array).
        name : str
            The argument's name in the messages (default "pose0").

        Returns
        -------
        Pose

        Raises
        ------
        ParameterError
            If ``value`` is none of these, a dict has other keys, or a value is not finite.
        """
        if value is None:
            return cls()
        if isinstance(value, cls):
            return value
        if isinstance(value, dict):
            unknown = sorted(set(value) - {"psi", "phi", "X", "Y"})
            if unknown:
                raise ParameterError(name, "must have only the keys psi, phi, X, Y", unknown)
            return cls(**{k: value[k] for k in value})
        if isinstance(value, (list, tuple, np.ndarray)) and len(value) == 4:
            return cls(*value)
        raise ParameterError(name, "must be a Pose, a dict with keys psi, phi, X, Y, or 4 numbers (psi, phi, X, Y)",
                             value)

    def to_dict(self) -> dict:
        return {"psi": self.psi, "phi": self.phi, "X": self.X, "Y": self.Y}


def rotation_matrix(psi, theta, phi) -> np.ndarray:
    """R = Rz(psi) Ry(theta) Rz(phi), shape (..., 3, 3): body axes (k = third column) in fixed axes."""
    psi, theta, phi = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (psi, theta, phi)))

    def rz(a):
        c, s, z, o = np.cos(a), np.sin(a), np.zeros_like(a), np.ones_like(a)
        return np.stack([np.stack([c, -s, z], -1), np.stack([s, c, z], -1), np.stack([z, z, o], -1)], -2)

    c, s, z, o = np.cos(theta), np.sin(theta), np.zeros_like(theta), np.ones_like(theta)
    ry = np.stack([np.stack([c, z, s], -1), np.stack([z, o, z], -1), np.stack([-s, z, c], -1)], -2)
    return rz(psi) @ ry @ rz(phi)


#: steps whose pose increments are computed together (each block ~0.1 s of a 1e5-step budget)
POSE_BLOCK = 4096


def _horner(coefs, tau):
    """Polynomials (..., states, order + 1) at tau (..., nodes) -> (..., nodes, states)."""
    c = coefs[..., None, :, :]
    t = tau[..., None]
    out = c[..., -1] * np.ones_like(t)
    for j in range(coefs.shape[-1] - 2, -1, -1):
        out = out * t + c[..., j]
    return out


def _antiderivative(coefs):
    """Coefficients of the integral from 0 of each polynomial (one order higher)."""
    order = np.arange(1, coefs.shape[-1] + 1)
    return np.concatenate([np.zeros(coefs.shape[:-1] + (1,)), coefs / order], axis=-1)


def _exclusive_cumsum(a):
    """Sums of the entries before each one (0 first)."""
    return np.concatenate([np.zeros(1, dtype=np.asarray(a).dtype), np.cumsum(a)[:-1]])


def _wrap(a):
    return (a + np.pi) % (2 * np.pi) - np.pi


class _Rates:
    """The integrands of one chart at states Y (..., d): Omega, phi' and the velocity of G as
    a complex number in the chart's axes, and theta."""

    @staticmethod
    def euler(Y):
        U, V, Om, _, th, n = (Y[..., i] for i in range(6))
        return Om, n - Om * np.cos(th), U + 1j * V, th

    @staticmethod
    def vector(Y):
        k = Y[..., 0:3] / np.linalg.norm(Y[..., 0:3], axis=-1, keepdims=True)
        w = Y[..., 3:6]
        c, s2 = k[..., 2], k[..., 0] ** 2 + k[..., 1] ** 2
        n = np.sum(w * k, axis=-1)
        safe = np.where(s2 > 0, s2, 1.0)  # exactly at a pole the azimuth is undefined: rates 0
        Om = np.where(s2 > 0, (w[..., 2] - n * c) / safe, 0.0)
        dphi = np.where(s2 > 0, (n - c * w[..., 2]) / safe, n)
        return Om, dphi, Y[..., 6] + 1j * Y[..., 7], np.arctan2(np.sqrt(s2), k[..., 2])


def _azimuth(Y):
    return np.arctan2(Y[..., 1], Y[..., 0])


@dataclass
class _SegmentTrack:
    """The quadratures of one segment, cumulated to each step's start."""

    euler: bool
    starts: np.ndarray
    ends: np.ndarray
    coefs: np.ndarray
    anti: np.ndarray  # antiderivatives: of Omega (Euler chart) or of v_x, v_y (vector charts)
    psi: np.ndarray
    phi: np.ndarray
    xy: np.ndarray  # complex X + iY
    alpha: float = 0.0  # angle of the vector chart's axes from the fixed ones

    def increments(self, idx, tau):
        """(dpsi, dphi, dxy in fixed axes, theta at the end) from each step idx's start to tau."""
        C = self.coefs[idx]
        nodes = tau[:, None] * _XI
        Y = _horner(C, nodes)
        rates = _Rates.euler if self.euler else _Rates.vector
        Om, dphi_rate, vel, _ = rates(Y)
        end = _horner(C, tau[:, None])[:, 0, :]
        theta_end = rates(end)[3]
        dphi = tau * (dphi_rate @ _WQ)
        if self.euler:
            P = _horner(self.anti[idx][:, None, :], nodes)[..., 0]
            dpsi = _horner(self.anti[idx][:, None, :], tau[:, None])[:, 0, 0]
            dxy = np.exp(1j * self.psi[idx]) * tau * ((vel * np.exp(1j * P)) @ _WQ)
            return dpsi, dphi, dxy, theta_end
        quad = tau * (Om @ _WQ)
        raw = _wrap(_azimuth(end) - _azimuth(C[:, :, 0]))
        dpsi = raw + 2 * np.pi * np.round((quad - raw) / (2 * np.pi))
        V = _horner(self.anti[idx][:, 6:8, :], tau[:, None])[:, 0, :]
        dxy = np.exp(1j * self.alpha) * (V[:, 0] + 1j * V[:, 1])
        return dpsi, dphi, dxy, theta_end


class PoseTrack:
    """psi, phi, X, Y, X_P, Y_P of a trajectory at any time, from its dense output.

    Built once per trajectory (``traj.pose(times)`` and ``traj.sample(times)`` use it):
    quadratures over every step of every segment, carried through the resets (positions and
    angles are continuous at stick, slip, lift-off and impacts; a reset that moves the time
    forward, as the stick extrapolation does, is bridged with the rates there).
    """

    def __init__(self, traj, pose0: Pose):
        if not traj.segments or not all(s.dense for s in traj.segments):
            from .energy import dropped_note

            note = dropped_note(traj)
            if note is not None:
                raise ParameterError("max_dense_mb", f"was passed: no orientation and position (psi, phi, X, Y, X_P, "
                                                     f"Y_P), quadratures of the dense output: {note}",
                                     traj.options.max_dense_mb)
            raise ParameterError("dense", "must be True (the default of SolverOptions) for the orientation and "
                                          "position (psi, phi, X, Y, X_P, Y_P): they are quadratures of the dense "
                                          "output", False)
        self.body = traj.model.body
        self.tracks: list[_SegmentTrack] = []
        psi, phi, xy, t_prev = pose0.psi, pose0.phi, complex(pose0.X, pose0.Y), None
        for seg in traj.segments:
            euler = seg.mode.value != "flight" and traj.model.chart is EULER
            if t_prev is not None and seg.t0 > t_prev:  # a reset that moved the time on: bridge it
                gap = seg.t0 - t_prev
                x0 = np.asarray(seg.x0, dtype=float)
                Om, dphi, vel, _ = (_Rates.euler if euler else _Rates.vector)(x0)
                turn = np.exp(1j * psi) if euler else np.exp(1j * (psi - _azimuth(x0)))
                psi, phi, xy = psi + Om * gap, phi + dphi * gap, xy + turn * vel * gap
            track = self._segment(seg, euler, psi, phi, xy)
            self.tracks.append(track)
            psi, phi, xy, _ = self._at(track, len(track.starts) - 1, track.ends[-1:] - track.starts[-1:])
            psi, phi, xy, t_prev = float(psi[0]), float(phi[0]), complex(xy[0]), seg.t1

    @staticmethod
    def _segment(seg, euler: bool, psi: float, phi: float, xy: complex) -> _SegmentTrack:
        parts = [span.pieces() for span in seg.dense]
        starts = np.concatenate([p[0] for p in parts])
        ends = np.concatenate([p[1] for p in parts])
        order = max(p[2].shape[2] for p in parts)
        coefs = np.concatenate([np.pad(p[2], ((0, 0), (0, 0), (0, order - p[2].shape[2]))) for p in parts])
        anti = _antiderivative(coefs[:, 2, :] if euler else coefs)
        alpha = 0.0 if euler else psi - float(_azimuth(coefs[0, :, 0]))
        n = len(starts)
        tr = _SegmentTrack(euler, starts, ends, coefs, anti, np.zeros(n), np.zeros(n), np.zeros(n, dtype=complex),
                           alpha)
        h = ends - starts
        if euler:  # psi first: each step's turn e^{i psi_k} enters its increment of X + iY
            tr.psi = psi + _exclusive_cumsum(_horner(anti[:, None, :], h[:, None])[:, 0, 0])
        parts = []
        for a in range(0, n or 1, POSE_BLOCK):  # in blocks: a wall budget in force (the CLI's --max-wall) counts this
            check_deadline()
            parts.append(tr.increments(np.arange(a, min(a + POSE_BLOCK, n)), h[a:a + POSE_BLOCK])[:3])
        dpsi, dphi, dxy = (np.concatenate(c) for c in zip(*parts))
        tr.psi = psi + _exclusive_cumsum(dpsi)
        tr.phi = phi + _exclusive_cumsum(dphi)
        tr.xy = xy + _exclusive_cumsum(dxy)
        return tr

    @staticmethod
    def _at(track: _SegmentTrack, idx, tau):
        idx = np.atleast_1d(idx)
        dpsi, dphi, dxy, theta = track.increments(idx, np.atleast_1d(tau))
        return track.psi[idx] + dpsi, track.phi[idx] + dphi, track.xy[idx] + dxy, theta

    def __call__(self, seg_index: np.ndarray, ts: np.ndarray) -> dict:
        """The pose columns at times ``ts``, each in segment ``seg_index`` (Trajectory._locate)."""
        out = {name: np.empty(ts.size) for name in POSE_COLUMNS}
        if ts.size == 0:
            return out
        theta = np.empty(ts.size)
        for j in np.unique(seg_index):
            sel = seg_index == j
            tr = self.tracks[j]
            k = np.clip(np.searchsorted(tr.ends, ts[sel], side="left"), 0, len(tr.starts) - 1)
            tau = np.clip(ts[sel] - tr.starts[k], 0.0, tr.ends[k] - tr.starts[k])
            psi, phi, xy, th = self._at(tr, k, tau)
            out["psi"][sel], out["phi"][sel], out["X"][sel], out["Y"][sel] = psi, phi, xy.real, xy.imag
            theta[sel] = th
        ht = self.body.h(theta)[1]
        out["X_P"] = out["X"] + ht * np.cos(out["psi"])
        out["Y_P"] = out["Y"] + ht * np.sin(out["psi"])
        return out
