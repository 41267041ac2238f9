"""Moments of inertia of uniform solids of revolution and of bodies assembled from them on one
axis: what a body made of a ball and a stem, a cone, a cylinder weighs and how it turns.

Each piece is a :class:`Solid`: its mass, the position z of its centre of mass on the common
axis k, and its moments about its own centre per unit of its mass (axial C, transverse A, units
b^2). :func:`assemble` puts pieces together by the parallel-axis theorem: the whole body's mass
M, its centre of mass G on the axis, and A and C about G in units M b^2, the numbers a
:class:`~phasekit.bodies.body.Body` takes. A piece's mass is its volume (unit density) unless
given: a thin rod or a thin disk has no volume, and a body of two materials weighs its parts.

Examples
--------
>>> from phasekit.bodies import inertia
>>> top = inertia.assemble(inertia.ball(1.0), inertia.rod(1.0, z=1.5, mass=0.1 * inertia.ball(1.0).mass))
>>> round(top.z, 6), round(top.A, 6), round(top.C, 6)
(0.136364, 0.557163, 0.363636)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .._runtime.validate import check_finite, check_nonnegative, check_positive
from ..errors import ParameterError


@dataclass(frozen=True)
class Solid:
    """A uniform solid of revolution on the axis k, or an assembly of them.

    Attributes
    ----------
    mass : float
        Its mass (its volume in b^3 at unit density, unless given).
    z : float
        Its centre of mass on the axis, units b.
    A, C : float
        Its transverse and axial moments about its own centre of mass per unit of its mass,
        units b^2 (so in units M b^2 of its own mass M).

    Examples
    --------
    >>> from phasekit.bodies.inertia import cylinder
    >>> cylinder(1.0, 0.0, mass=1.0)
    Solid(mass=1.0, z=0.0, A=0.25, C=0.5)
    """

    mass: float
    z: float
    A: float
    C: float

    def moments_about(self, z: float) -> tuple[float, float]:
        """(A, C) about the point z of the axis, per unit mass (units b^2): A gains (z_G - z)^2
        (the parallel-axis theorem), C, about the axis itself, is unchanged.

        Parameters
        ----------
        z : float
            The point of the axis, units b.

        Returns
        -------
        tuple of float
            (A, C) per unit mass about that point.
        """
        return self.A + (self.z - z) ** 2, self.C


def _mass(volume: float, mass: float | None, what: str) -> float:
    if mass is None:
        if volume <= 0.0:
            raise ParameterError("mass", f"is required for a {what} (it has no volume)", show_value=False)
        return volume
    return check_positive("mass", mass)


def ball(radius: float = 1.0, z: float = 0.0, *, mass: float | None = None) -> Solid:
    """A uniform ball: C = A = 2 r^2 / 5 about its centre, at ``z``.

    Parameters
    ----------
    radius : float, optional
        r, units b (default 1).
    z : float, optional
        Its centre on the axis (default 0).
    mass : float, optional
        Its mass (default its volume 4 pi r^3 / 3).

    Returns
    -------
    Solid
    Raises
    ------
    ParameterError
        If a size is not a finite number > 0 (a cylinder's length >= 0), ``z`` is not finite,
        or ``mass`` is not > 0 or is missing where the piece has no volume.
    """
    r = check_positive("radius", radius)
    m = 0.4 * r * r
    return Solid(_mass(4.0 * math.pi * r**3 / 3.0, mass, "ball"), check_finite("z", z), m, m)


def cylinder(radius: float = 1.0, length: float = 0.0, z: float = 0.0, *, mass: float | None = None) -> Solid:
    """A uniform solid cylinder along the axis (a disk when ``length`` = 0): C = r^2/2 and
    A = r^2/4 + L^2/12 about its centre, at ``z``.

    Parameters
    ----------
    radius : float, optional
        r, units b (default 1).
    length : float, optional
        L >= 0, its extent along the axis (default 0, a thin disk, whose ``mass`` is then required).
    z : float, optional
        Its centre on the axis (default 0).
    mass : float, optional
        Its mass (default its volume pi r^2 L).

    Returns
    -------
    Solid
    Raises
    ------
    ParameterError
        If a size is not a finite number > 0 (a cylinder's length >= 0), ``z`` is not finite,
        or ``mass`` is not > 0 or is missing where the piece has no volume.
    """
    r, L = check_positive("radius", radius), check_nonnegative("length", length)
    return Solid(_mass(math.pi * r * r * L, mass, "thin disk"), check_finite("z", z), 0.25 * r * r + L * L / 12.0, 0.5 * r * r)


def cone(radius: float = 1.0, height: float = 1.0, base: float = 0.0, *, mass: float | None = None) -> Solid:
    """A uniform solid cone with its base (radius r) at ``base`` on the axis and its tip at
    ``base + height`` (``height`` < 0 points it down the axis): G at a quarter of the height
    from the base, C = 3 r^2/10 and A = 3/20 (r^2 + h^2/4) about G.

    Parameters
    ----------
    radius : float, optional
        r, the base's radius, units b (default 1).
    height : float, optional
        h != 0, from the base to the tip along k (default 1).
    base : float, optional
        The base's centre on the axis (default 0).
    mass : float, optional
        Its mass (default its volume pi r^2 |h| / 3).

    Returns
    -------
    Solid
    Raises
    ------
    ParameterError
        If a size is not a finite number > 0 (a cylinder's length >= 0), ``z`` is not finite,
        or ``mass`` is not > 0 or is missing where the piece has no volume.
    """
    r, h = check_positive("radius", radius), check_finite("height", height, nonzero=True)
    return Solid(_mass(math.pi * r * r * abs(h) / 3.0, mass, "cone"), check_finite("base", base) + 0.25 * h,
                 0.15 * (r * r + 0.25 * h * h), 0.3 * r * r)


def rod(length: float, z: float = 0.0, *, mass: float) -> Solid:
    """A thin uniform rod along the axis: C = 0 and A = L^2/12 about its centre, at ``z``.

    Parameters
    ----------
    length : float
        L > 0, units b.
    z : float, optional
        Its centre on the axis (default 0).
    mass : float
        Its mass (a thin rod has no volume).

    Returns
    -------
    Solid
    Raises
    ------
    ParameterError
        If a size is not a finite number > 0 (a cylinder's length >= 0), ``z`` is not finite,
        or ``mass`` is not > 0 or is missing where the piece has no volume.
    """
    L = check_positive("length", length)
    return Solid(_mass(0.0, mass, "thin rod"), check_finite("z", z), L * L / 12.0, 0.0)


def assemble(*solids: Solid) -> Solid:
    """Several solids on one axis as one body: the total mass M, its centre of mass G on the axis,
    and A, C about G per unit of M (units M b^2), by the parallel-axis theorem.

    Parameters
    ----------
    *solids : Solid
        The pieces (at least one), each at its own place on the axis.

    Returns
    -------
    Solid
        The whole body: ``A`` and ``C`` are the moments a body's constructor takes.

    Raises
    ------
    ParameterError
        If no solid is given (named ``solids``).
    """
    if not solids:
        raise ParameterError("solids", "must hold at least one Solid", show_value=False)
    M = math.fsum(s.mass for s in solids)
    zG = math.fsum(s.mass * s.z for s in solids) / M
    A = math.fsum(s.mass * s.moments_about(zG)[0] for s in solids) / M
    C = math.fsum(s.mass * s.C for s in solids) / M
    return Solid(M, zG, A, C)
