"""A uniform solid cone, :class:`Cone`: a top that rolls on the rim of its base or spins on its
tip.

The support function of a rim and of a tip
------------------------------------------
A cone of base radius 1 (the unit b) and height l has its centre of mass G on the axis at l/4
above the base; k points from the base to the tip, so theta = 0 is the cone standing on its
base and theta = pi on its tip. The lowest point of the body is either on the rim of the base,
at -l/4 along k and 1 from the axis, whose support is h(theta) = sin(theta) + (l/4) cos(theta)
(that of :class:`~phasekit.bodies.edged.Disk`'s rim), or the tip, the point 3 l/4 along k,
whose support h(theta) = -(3 l/4) cos(theta) is linear in c = cos(theta). They meet at
tan(theta) = -l, theta_side = pi - atan(l), where the slanted side lies on the table.

On the tip both radii of curvature are zero: the contact point is fixed on the axis, and the
equations (2.7) and the vector chart, which use the body only through H(c) and its derivatives,
hold unchanged (a Lagrange top whose point moves on the table). H = -(3 l/4) c is a polynomial:
the tip's range includes theta = pi, a top sleeping on its point, and the vector chart runs
through it.

Where the model ends
--------------------
One compiled support function serves one contact (the rim's and the tip's are different
functions of c), so a cone is made ``on="rim"`` or ``on="tip"``:

- on its rim, theta in (0, theta_side): at theta -> 0 the base comes down flat (H has the rim's
  branch point at c = 1; the run stops at :data:`~phasekit.bodies.edged.FLAT_ANGLE`, "face
  down"), at theta_side the side touches ("side down");
- on its tip, theta in (theta_side, pi]: at theta_side the side touches ("side down").

Lying on the side is a line contact, not modelled: from there the cone may roll on its side or
pass from the rim to the tip. :attr:`Cone.limits` lists the ends; a run stops there with the
named event.
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np

from .._runtime.validate import check_choice, check_range
from ..errors import ParameterError
from .edged import FLAT_ANGLE, EdgedBody, Limit
from .inertia import cone as solid_cone

#: the largest height, in base radii (as a cylinder's thickness, bodies.edged.THICKNESS_MAX)
HEIGHT_MAX = 1e3
#: where a cone touches the table
CONTACTS = ("rim", "tip")


class Cone(EdgedBody):
    """A uniform solid cone of base radius 1 (the unit b) and height l, touching the table on
    the rim of its base or on its tip (module notes): a spinning top with a point, a cone
    rolling on its rim.

    Support function h(theta) = sin(theta) + (l/4) cos(theta) on the rim, -(3 l/4) cos(theta)
    on the tip; G on the axis at l/4 above the base, k toward the tip. (A cylinder is
    :class:`~phasekit.bodies.edged.Disk` with its thickness.)

    Parameters
    ----------
    height : float in (0, 1e3]
        l, from the base to the tip over the base's radius (units b).
    on : {"rim", "tip"}, optional
        The contact: the rim of the base (default), theta in (0, theta_side), or the tip,
        theta in (theta_side, pi], with theta_side = pi - atan(l) where the side lies on the
        table.
    A, C : float, optional
        Moments about G, units M b^2. Default: the uniform cone's, C = 3/10 and
        A = 3/20 (1 + l^2/4) (:func:`phasekit.bodies.inertia.cone`).

    Attributes
    ----------
    altitude : float
        l, as given (``height`` is every body's support function).
    on : str
        The contact, as given. (``theta_side``: where the side lies on the table;
        ``theta_range`` and ``limits`` as for :class:`~phasekit.bodies.edged.EdgedBody`: "face
        down" at FLAT_ANGLE and "side down" at theta_side on the rim, "side down" on the tip.)

    Raises
    ------
    ParameterError
        If ``height`` is not a finite number in (0, 1e3]; ``on`` is not "rim" or "tip"; ``A``
        or ``C`` is not a finite number > 0, or C > 2 A; or ``C`` exceeds 1 (M b^2: no mass lies
        farther than the base's radius from the axis).

    Examples
    --------
    >>> import phasekit as pk
    >>> top = pk.bodies.Cone(2.0, on="tip")
    >>> top.C, round(top.A, 6), round(top.theta_side, 6)      # 3/10, 3/20 (1 + 1), pi - atan 2
    (0.3, 0.3, 2.034444)
    >>> [limit.name for limit in top.limits], top.theta_range[1] == np.pi
    (['side down'], True)
    >>> round(float(top.h(np.pi)[0]), 6)                      # standing on its tip: 3 l/4 below G
    1.5
    >>> [limit.name for limit in pk.bodies.Cone(2.0).limits]
    ['face down', 'side down']
    """

    def __init__(self, height: float = 1.0, on: str = "rim", A: float | None = None, C: float | None = None):
        self.altitude = check_range("height", height, 0.0, HEIGHT_MAX, closed="r",
                                    label=f"(0, {HEIGHT_MAX:g}] (from the base to the tip over the base's radius)")
        self.on = check_choice("on", on, CONTACTS)
        own = solid_cone(1.0, self.altitude, -0.25 * self.altitude, mass=1.0)  # G at the origin
        super().__init__(own.A if A is None else A, own.C if C is None else C)
        if self.C > 1.0 * (1 + 1e-12):
            raise ParameterError("C", "must be at most 1 (M b^2, b the base's radius: no mass lies farther than the "
                                      "radius from the axis)", C)
        self.check_convex("height")

    @property
    def shape_params(self) -> tuple[float, ...]:
        # one structure for every height (one for the rim, one for the tip)
        return (self.altitude,)

    def height(self, c, shape):
        if self.on == "tip":
            return -0.75 * shape[0] * c
        # the rim's, as the disk's: (1 - c)(1 + c) keeps its digits near c = 1
        return ca.sqrt((1 - c) * (1 + c)) + 0.25 * shape[0] * c

    @property
    def theta_side(self) -> float:
        """pi - atan(l), radians: the inclination at which the slanted side lies on the table
        (the rim's support equals the tip's)."""
        return math.pi - math.atan(self.altitude)

    @property
    def theta_range(self) -> tuple[float, float]:
        return (0.0, self.theta_side) if self.on == "rim" else (self.theta_side, math.pi)

    @property
    def limits(self) -> tuple[Limit, ...]:
        side = "the side touched the table at t = {t:.10g}: a cone on its side (a line contact) is not modelled"
        if self.on == "tip":
            return (Limit("side down", self.theta_side, -1, side),)
        return (Limit("face down", FLAT_ANGLE, -1, "the base reached the table at t = {t:.10g}: the cone stands on "
                                                   "its base", (1.0, 0.0)),
                Limit("side down", self.theta_side, +1, side))

    def _range_text(self) -> tuple[str, str, bool]:
        side = f"{self.theta_side:.6g}"
        if self.on == "tip":
            return (f"({side}, pi]", f"on its tip; at {side} its side touches the table", True)
        return (f"(0, {side})", f"on its rim; at 0 it stands on its base, at {side} its side touches the table", False)

    def outline(self, n: int = 64) -> tuple[np.ndarray, np.ndarray]:
        """The meridian as drawn: (z, r) from the centre of the base to the tip, z along k from
        G and r from the axis (units b): the base and the slanted side.

        Parameters
        ----------
        n : int, optional
            The resolution (default 64): k = max(2, n // 3) points on the base and on the side.

        Returns
        -------
        tuple of numpy.ndarray
            (z, r), each of 2 k points.
        """
        n = max(2, n // 3)
        base, u = -0.25 * self.altitude, np.linspace(0.0, 1.0, n)
        return np.concatenate([np.full(n, base), base + self.altitude * u]), np.concatenate([u, 1.0 - u])

    def check_inertia(self) -> None:
        """Raise ParameterError naming ``A`` or ``C`` if a moment exceeds M r_max^2, r_max the
        farther of the rim (r_max^2 = 1 + l^2/16) and the tip (3 l/4) from G.

        Raises
        ------
        ParameterError
            If ``A`` or ``C`` exceeds r_max^2.
        """
        r2 = max(1.0 + self.altitude**2 / 16.0, (0.75 * self.altitude) ** 2) * (1 + 1e-9)
        for name, value in (("A", self.A), ("C", self.C)):
            if value > r2:
                raise ParameterError(name, f"must be at most {r2:.6g} (M r_max^2: no point of the cone is farther than "
                                           f"its rim or its tip, r_max = {math.sqrt(r2):.6g}, from G)", value)

    @property
    def uniform(self) -> bool:
        """True when A and C are the uniform cone's."""
        own = solid_cone(1.0, self.altitude, mass=1.0)
        return self.A == own.A and self.C == own.C

    @property
    def is_prolate(self) -> bool:
        return False

    @property
    def flip_symmetric(self) -> bool:
        return False

    def describe(self) -> str:
        return f"cone, height {self.altitude:g} radii (on its {self.on}), A={self.A:.6g}, C={self.C:.6g}"

    def to_dict(self) -> dict:
        return {"body": "cone", "height": self.altitude, "on": self.on, "A": self.A, "C": self.C,
                "description": self.describe()}

    def __repr__(self) -> str:
        moments = "" if self.uniform else f", A={self.A:g}, C={self.C:g}"
        return f"Cone(height={self.altitude:g}, on={self.on!r}{moments})"
