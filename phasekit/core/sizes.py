"""Bodies of a real size: an egg of a given length and breadth (:func:`egg_of_size`) and an
eccentric-sphere tippe top of a given radius (:func:`eccentric_sphere_of_size`), each with its
:class:`~phasekit.core.units.Scale`."""

from __future__ import annotations

import numpy as np

from ..errors import ParameterError
from .units import STANDARD_GRAVITY, Scale, is_number, of_kind


def egg_of_size(length, breadth, *, w: float = 0.0, mass=None, g=STANDARD_GRAVITY):
    """An :class:`~phasekit.bodies.egg.Egg` of the given length and maximum breadth (uniform density)
    and its :class:`Scale` (b = breadth / 2).

    Parameters
    ----------
    length, breadth : quantity
        The egg's length and maximum breadth (lengths > 0): pint Quantities or strings
        ("57 mm"). Their ratio is the egg's aspect ratio a, in [0.3, 3].
    w : float
        The egg's asymmetry (w/L), in [0, 0.5) (see :class:`~phasekit.bodies.egg.Egg`);
        default 0.
    mass : quantity, optional
        The egg's mass, needed only for forces, energies and moments of inertia.
    g : quantity
        Gravity, default 9.81 m/s^2.

    Returns
    -------
    tuple of (Egg, Scale)
        The egg, in units of b, and its scale.

    Raises
    ------
    ParameterError
        If ``length`` or ``breadth`` is not a length > 0, their ratio is outside the egg's
        range of aspect ratios (named ``length``), ``w`` is not a valid asymmetry, or ``mass``
        or ``g`` is not a quantity of its kind > 0.

    Examples
    --------
    >>> import phasekit as pk
    >>> egg, sc = pk.core.egg_of_size('57 mm', '43 mm', w=0.05)
    >>> egg
    Egg(a=1.32558, w=0.05)
    >>> str(sc.b)
    '21.5 mm'
    """
    from ..bodies.egg import Egg

    L, B = of_kind(length, "length", "length", positive=True), of_kind(breadth, "breadth", "length", positive=True)
    a = float((L / B).to("dimensionless").magnitude)
    try:
        egg = Egg(a, w)
    except ParameterError as err:
        if err.param == "a":
            raise ParameterError("length", f"divided by `breadth` (the aspect ratio a) {err.expected}", a) from None
        raise
    return egg, Scale(B / 2, g=g, mass=mass)


def eccentric_sphere_of_size(radius, offset, *, A=None, C=None, mass=None, g=STANDARD_GRAVITY):
    """An :class:`~phasekit.bodies.spheroid.EccentricSphere` of the given ball radius with its centre of
    mass ``offset`` (a length) below the centre, and its :class:`Scale` (b = radius).

    Parameters
    ----------
    radius : quantity
        The ball's radius (a length > 0): a pint Quantity or a string ("15 mm").
    offset : quantity
        The distance of the centre of mass below the ball's centre, a length; over
        ``radius`` it is the body's offset, in [0, 1).
    A, C : float or quantity, optional
        Moments about G: numbers (units M b^2) or quantities of a moment of inertia (need
        ``mass``). Default: those of :class:`~phasekit.bodies.spheroid.EccentricSphere`.
    mass : quantity, optional
        The top's mass, needed for forces, energies, moments of inertia and for ``A`` or
        ``C`` given as quantities.
    g : quantity
        Gravity, default 9.81 m/s^2.

    Returns
    -------
    tuple of (EccentricSphere, Scale)
        The top, in units of b, and its scale.

    Raises
    ------
    ParameterError
        If ``radius`` is not a length > 0, ``offset`` is not a length or its ratio to the
        radius is outside the body's range, ``A`` or ``C`` is neither a number nor a moment
        of inertia (or is one without ``mass``), the moments are invalid for the body, or
        ``mass`` or ``g`` is not a quantity of its kind > 0.

    Examples
    --------
    >>> import phasekit as pk
    >>> top, sc = pk.core.sizes.eccentric_sphere_of_size('15 mm', '4.5 mm')
    >>> top
    EccentricSphere(offset=0.3, A=0.31, C=0.4)
    >>> str(sc.b)
    '15 mm'
    """
    from ..bodies.spheroid import EccentricSphere

    of_kind(radius, "radius", "length", positive=True)
    sc = Scale(radius, g=g, mass=mass)
    alpha = sc._dimensionless(offset, "length", "offset")
    moments = []
    for name, m in (("A", A), ("C", C)):
        if isinstance(m, (bool, np.bool_)):
            raise ParameterError(name, "must be a number (units M b^2) or a moment of inertia such as '2 g*cm**2'", m)
        moments.append(None if m is None else (float(m) if is_number(m) else sc._dimensionless(m, "inertia", name)))
    try:
        body = EccentricSphere(alpha, A=moments[0], C=moments[1])
    except ParameterError as err:
        if err.param == "offset":
            raise ParameterError("offset", f"divided by `radius` {err.expected}", alpha) from None
        raise
    return body, sc
