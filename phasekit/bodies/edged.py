"""Bodies with an edge: :class:`Disk`, a uniform cylinder (a thin disk, a coin, a cylinder) rolling
and spinning on the rim of a flat face, as Euler's disk does.

The support function of an edge
-------------------------------
A cylinder of radius 1 (the unit b) and thickness L, G at its centre, resting on the rim of its
lower face with the axis k at theta to the vertical, touches the table at the lowest point of
the rim: h(theta) = sin(theta) + (L/2) cos(theta), i.e. H(c) = sqrt(1 - c^2) + (L/2) c. The
contact point stays at one point of the rim in the body's meridian plane, so the meridian's
radius of curvature h + h_thetatheta is zero (an edge), while the azimuthal one, x_P / sin(theta)
= 1 / sin(theta), is positive. The equations (2.7) and the vector chart use the body only
through H and its derivatives, which are analytic wherever the rim is the lowest point: they
hold there unchanged (:class:`EdgedBody` makes the convexity check accept the edge). A tip, where
both radii are zero (the contact point fixed on the axis, H linear in c), is accepted likewise:
:class:`~phasekit.bodies.cone.Cone`.

Where the model ends
--------------------
- theta -> 0: the flat face comes down onto the table (H has a branch point at c = 1, where
  H' -> -infinity): the end of Euler's disk, a finite-time singularity. A run stops at
  theta = :data:`FLAT_ANGLE` ("face down").
- theta = pi/2 for L > 0: the cylinder's side touches (the contact becomes a line, then passes
  to the other rim): not modelled; a run stops there ("side down"). A thin disk (L = 0) rolls
  upright through pi/2 (H is even about c = 0) and its range is (0, pi), ending face down on
  either side.

:attr:`EdgedBody.limits` lists these ends (:class:`Limit`); the hybrid system stops a run there
with the named event and the limit's reason.
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np

from .._runtime.validate import check_range
from ..errors import ParameterError
from .body import Body, Limit

#: the inclination at which the flat face is taken to be down: the run stops there (the rim
#: opposite the contact is then 2e-3 radii above the table; H is exact to ~1e-13 there in both
#: charts, while sqrt(1 - c^2) loses digits as c -> 1)
FLAT_ANGLE = 1e-3
#: the lowest face-down angle a Disk accepts: c = cos(theta) is then rounded to ~1e-4 of 1 - c in the
#: Euler chart (H to ~1e-4 relative), still far below what the end's power laws resolve
FLAT_ANGLE_MIN = 1e-6
#: the largest thickness, in radii (a rod 500 times as long as it is wide)
THICKNESS_MAX = 1e3
#: a meridian radius of curvature within this of 0 (relative to |h| + |h_thetatheta|), or within
#: the rounding of c = cos(theta) near a pole (a branch point of H there: sqrt(1 - c^2) resolves
#: to eps/sin^2, h_thetatheta to eps/sin^3), is an edge, not a concave profile
EDGE_TOL = 1e-12


class EdgedBody(Body):
    """A body of revolution whose meridian may have a zero radius of curvature (an edge, a tip),
    valid on an open range of theta that it states (:attr:`theta_range`, :attr:`limits`).

    Parameters
    ----------
    A, C : float
        Moments about G, units M b^2, as for :class:`~phasekit.bodies.body.Body`.

    Required of a subclass
    ----------------------
    Besides ``shape_params`` and ``height`` (:class:`~phasekit.bodies.body.Body`):
    ``theta_range``, ``limits`` and ``outline(n)`` (the meridian as drawn: the support
    function traces only the edge, never the faces).

    Raises
    ------
    ParameterError
        As :class:`~phasekit.bodies.body.Body`.
    """

    @property
    def theta_range(self) -> tuple[float, float]:
        """(lo, hi), radians: the open range of theta where the support function is the body's."""
        raise NotImplementedError(f"{type(self).__name__} must define `theta_range`")

    @property
    def limits(self) -> tuple[Limit, ...]:
        """The ends of :attr:`theta_range` a run stops at, with their events' names and reasons."""
        raise NotImplementedError(f"{type(self).__name__} must define `limits`")

    def outline(self, n: int = 64) -> tuple[np.ndarray, np.ndarray]:
        """The meridian as drawn (:meth:`Body.outline <phasekit.bodies.Body.outline>`): the support
        function traces only the edge, never the faces, so a subclass must give it."""
        raise NotImplementedError(f"{type(self).__name__} must define `outline`")

    def check_theta(self, theta: float, name: str = "theta") -> float:
        """Raise ParameterError naming ``name`` unless ``theta`` is a state of this body's model:
        inside :attr:`theta_range` (beyond it another part of the body touches the table), or
        at pi for a body that stands there on a tip (no limit at pi).

        Parameters
        ----------
        theta : float
            The inclination, radians.
        name : str, optional
            The parameter the error names (default "theta").

        Returns
        -------
        float
            ``theta``.

        Raises
        ------
        ParameterError
            If ``theta`` is not inside the range.
        """
        if not self.in_range(theta):
            label, why, _ = self._range_text()
            raise ParameterError(name, f"must lie in {label} for this {self.kind} ({why})", theta)
        return float(theta)

    def in_range(self, theta: float) -> bool:
        """True when ``theta`` is a state of this body's model (:meth:`check_theta`).

        Parameters
        ----------
        theta : float
            The inclination, radians.

        Returns
        -------
        bool
        """
        lo, hi = self.theta_range
        return bool(lo < theta < hi or (self._range_text()[2] and theta == hi))

    def _range_text(self) -> tuple[str, str, bool]:
        """(the range as written, what happens at its ends, True if it holds its upper end)."""
        lo, hi = self.theta_range
        return f"({lo:.6g}, {hi:.6g})", "beyond it another part of the body touches the table", False

    @property
    def kind(self) -> str:
        """What the body is, in messages (its class's name, in lower case)."""
        return type(self).__name__.lower()

    def check_convex(self, param: str = "height", theta_range: tuple[float, float] | None = None, n: int = 721) -> None:
        """Raise ParameterError (naming ``param``) unless the surface is convex over the open
        ``theta_range`` (default :attr:`theta_range`): finite h > 0, and each radius of
        curvature (meridional h + h_thetatheta, azimuthal x_P / sin(theta)) either > 0 or zero
        to rounding (EDGE_TOL, and 16 eps / sin^3(theta) for the rounding of cos(theta) near a
        pole), never negative (a concave profile): the meridional one is zero on an edge, both
        are on a tip (the contact point fixed on the axis).

        Parameters
        ----------
        param : str, optional
            The parameter the error names (default "height").
        theta_range : tuple of float, optional
            The open interval of theta checked, radians (default: the body's own).
        n : int, optional
            The number of angles sampled inside it (default 721).

        Raises
        ------
        ParameterError
            If, at a sampled angle, h is not finite or not > 0, or a radius of curvature is
            negative beyond rounding.
        """
        lo, hi = self.theta_range if theta_range is None else theta_range
        th = np.linspace(lo, hi, n + 2)[1:-1]  # the ends are where the model ends: not sampled
        h, h1, h2 = self.h(th)
        r1, r2 = self.radii_of_curvature(th)
        edge = -EDGE_TOL * (np.abs(h) + np.abs(h2)) - 16 * np.finfo(float).eps / np.abs(np.sin(th)) ** 3
        bad = ~(np.isfinite(h) & np.isfinite(h1) & np.isfinite(h2) & (h > 0) & (r2 >= edge) & (r1 >= edge))
        if np.any(bad):
            k = int(np.flatnonzero(bad)[0])
            raise ParameterError(param, f"must give a convex surface (height h > 0 and radii of curvature >= 0, the "
                                        f"meridional one zero on an edge, both on a tip, for theta in ({lo:g}, {hi:g})); at "
                                        f"theta = {th[k]:.4g}: h = {h[k]:.4g}, h + h'' = {r1[k]:.4g}, x_P/sin = "
                                        f"{r2[k]:.4g}", show_value=False)


class Disk(EdgedBody):
    """A uniform cylinder of radius 1 (the unit b) and thickness L rolling and spinning on the
    rim of a flat face: Euler's disk (L = 0), a coin (L ~ 0.07-0.15), a puck, a cylinder (a
    cylinder is a Disk with its thickness, e.g. Disk(2.0) as long as it is wide).

    Support function h(theta) = sin(theta) + (L/2) cos(theta), G at the centre (module notes):
    theta -> 0 brings the face down onto the table, theta = pi/2 the side (L > 0).

    Parameters
    ----------
    thickness : float in [0, 1e3]
        L, the full thickness over the radius (units b); 0 is a thin disk.
    A, C : float, optional
        Moments about G, units M b^2. Default: the uniform cylinder's, C = 1/2 and
        A = 1/4 + L^2/12.
    flat_angle : float in [1e-6, 0.1], optional
        The inclination, radians, at which the face is taken to be down and a run stops
        (default :data:`FLAT_ANGLE`, 1e-3, where H is exact to ~1e-13). Lower values follow more
        of the end (theta ~ (t0 - t)^2 under rolling resistance: each factor 100 is a decade of
        t0 - t) while the Euler chart's H loses digits as ~1e-16/theta^2 (1e-4 at 1e-6).

    Attributes
    ----------
    thickness : float
        L, as given.
    flat_angle : float
        The face-down angle, as given. (``theta_range``: (0, pi) for a thin disk, (0, pi/2) for L > 0, open: the
        ends are not states of the model; ``limits``: the ends a run stops at, "face down" at
        theta = ``flat_angle`` (and pi - ``flat_angle`` for a thin disk), "side down" at pi/2 for L > 0.)

    Raises
    ------
    ParameterError
        If ``thickness`` is not a finite number in [0, 1e3]; ``flat_angle`` not one in [1e-6, 0.1]; ``A`` or ``C`` is not a finite
        number > 0, or C > 2 A; or ``C`` exceeds 1 (M b^2: no mass lies farther than the
        radius from the axis).

    Examples
    --------
    >>> import phasekit as pk
    >>> coin = pk.Disk(0.1)
    >>> round(coin.A, 6), coin.C, coin.theta_range == (0.0, np.pi / 2)
    (0.250833, 0.5, True)
    >>> [limit.name for limit in coin.limits]
    ['face down', 'side down']
    >>> round(float(coin.h(np.pi / 6)[0]), 6)   # sin 30 deg + 0.05 cos 30 deg
    0.543301
    """

    def __init__(self, thickness: float = 0.0, A: float | None = None, C: float | None = None, *,
                 flat_angle: float = FLAT_ANGLE):
        self.thickness = check_range("thickness", thickness, 0.0, THICKNESS_MAX, closed="lr",
                                     label=f"[0, {THICKNESS_MAX:g}] (the full thickness over the radius)")
        self.flat_angle = check_range("flat_angle", flat_angle, FLAT_ANGLE_MIN, 0.1, closed="lr",
                                      label=f"[{FLAT_ANGLE_MIN:g}, 0.1] (radians)")
        super().__init__(0.25 + self.thickness**2 / 12.0 if A is None else A, 0.5 if C is None else C)
        if self.C > 1.0 * (1 + 1e-12):
            raise ParameterError("C", "must be at most 1 (M b^2, b the radius: no mass lies farther than the radius "
                                      "from the axis)", C)
        self.check_convex("thickness")

    @property
    def shape_params(self) -> tuple[float, ...]:
        # one structure for every thickness: disks and cylinders share one compiled model
        return (self.thickness,)

    def height(self, c, shape):
        # (1 - c)(1 + c): 1 - c is exact near c = 1, where 1 - c^2 would round c^2 first
        return ca.sqrt((1 - c) * (1 + c)) + 0.5 * shape[0] * c

    @property
    def theta_range(self) -> tuple[float, float]:
        return (0.0, math.pi) if self.thickness == 0.0 else (0.0, math.pi / 2)

    @property
    def limits(self) -> tuple[Limit, ...]:
        face = "the flat face reached the table at t = {t:.10g}: the " + self.kind + " lies flat"
        down = Limit("face down", self.flat_angle, -1, face, (1.0, 0.0))
        if self.thickness == 0.0:
            return (down, Limit("face down", math.pi - self.flat_angle, +1, face, (1.0, 0.0)))
        return (down, Limit("side down", math.pi / 2, +1, "the side touched the table at t = {t:.10g}: a " + self.kind +
                            " on its side (a line contact) is not modelled"))

    def _range_text(self) -> tuple[str, str, bool]:
        if self.thickness == 0.0:
            return "(0, pi)", "at 0 and pi it lies flat", False
        return "(0, pi/2)", "at 0 it lies flat, at pi/2 its side touches the table", False

    @property
    def kind(self) -> str:
        """"disk" (thinner than its radius) or "cylinder"."""
        return "disk" if self.thickness < 1.0 else "cylinder"

    def outline(self, n: int = 64) -> tuple[np.ndarray, np.ndarray]:
        """The meridian as drawn: (z, r) from the centre of the lower face to that of the upper one,
        z along k from G and r from the axis (units b): the faces, the rims and the side. The
        support function traces only the rim (every contact point is on it), so a drawing needs
        the outline itself.

        Parameters
        ----------
        n : int, optional
            The resolution (default 64): k = max(2, n // 3) points on each face and on the side.

        Returns
        -------
        tuple of numpy.ndarray
            (z, r), each of 3 k points.
        """
        n = max(2, n // 3)
        half, u = 0.5 * self.thickness, np.linspace(0.0, 1.0, n)
        z = np.concatenate([np.full(n, -half), -half + 2 * half * u, np.full(n, half)])
        r = np.concatenate([u, np.ones(n), u[::-1]])
        return z, r

    def check_inertia(self) -> None:
        """Raise ParameterError naming ``A`` or ``C`` if a moment exceeds M r_max^2, with
        r_max^2 = 1 + L^2/4 the rim's distance from G (the edge is the farthest point).

        Raises
        ------
        ParameterError
            If ``A`` or ``C`` exceeds 1 + L^2/4.
        """
        r2 = (1.0 + 0.25 * self.thickness**2) * (1 + 1e-9)
        for name, value in (("A", self.A), ("C", self.C)):
            if value > r2:
                raise ParameterError(name, f"must be at most {r2:.6g} (M r_max^2: no point of the {self.kind} is "
                                           f"farther than the rim, r_max = {math.sqrt(r2):.6g}, from G)", value)

    @property
    def uniform(self) -> bool:
        """True when A and C are the uniform cylinder's."""
        return abs(self.A - (0.25 + self.thickness**2 / 12.0)) < 1e-15 and abs(self.C - 0.5) < 1e-15

    @property
    def is_prolate(self) -> bool:
        return False

    @property
    def flip_symmetric(self) -> bool:
        # a thin disk's two faces are one; a thicker one's model ends at pi/2
        return self.thickness == 0.0

    def describe(self) -> str:
        return f"{self.kind}, thickness {self.thickness:g} radii (rolling on its rim), A={self.A:.6g}, C={self.C:.6g}"

    def to_dict(self) -> dict:
        # the face-down angle only when it is not the default: descriptions written before it stay as they were
        flat = {} if self.flat_angle == FLAT_ANGLE else {"flat_angle": self.flat_angle}
        return {"body": "disk", "thickness": self.thickness, "A": self.A, "C": self.C, **flat,
                "description": self.describe()}

    def __eq__(self, other) -> bool:  # the limits are not in the compiled structure: compare them here
        return super().__eq__(other) and other.flat_angle == self.flat_angle

    def __hash__(self) -> int:
        return hash((super().__hash__(), self.flat_angle))

    def __repr__(self) -> str:
        flat = "" if self.flat_angle == FLAT_ANGLE else f", flat_angle={self.flat_angle:g}"
        if self.uniform:
            return f"Disk(thickness={self.thickness:g}{flat})"
        return f"Disk(thickness={self.thickness:g}, A={self.A:g}, C={self.C:g}{flat})"
