"""Egg: a solid of revolution bounded by Hugelschaffer's egg curve, with an asymmetry parameter.

Meridian
--------
Narushin, Romanov & Griffin (2021), "Egg and math: introducing a universal formula for egg
shape", Ann. N.Y. Acad. Sci. 1505, 169-177 (doi 10.1111/nyas.14680), state Hugelschaffer's
curve as::

    y(x) = (B/2) sqrt((L^2 - 4 x^2) / (L^2 + 8 w x + 4 w^2)),   -L/2 <= x <= L/2,

with L the length, B the maximum breadth and w the distance of the maximum breadth from the
middle of the axis (y(-w) = B/2 is the maximum). w = 0 is an ellipse; for w > 0 the end at
x = -L/2 is the blunt (fat) end and the end at x = +L/2 the pointed (thin) end.

phasekit's parameters are ``a = L/B`` (so w = 0 is ``Spheroid(a)``) and ``w`` *relative to
L* (the curve's w is ``w * L``). Lengths are in units of b = B/2 (the equatorial radius), so
L = 2a and the tips lie at x = -a (fat) and x = +a (thin).

Convexity
---------
With s = x / (L/2) and w relative to L, y^2 / (B/2)^2 = g(s) = (1 - s^2) / (1 + 4 w s + 4 w^2)
and

    g''(s) = -2 (1 - 4 w^2)^2 / (1 + 4 w s + 4 w^2)^3 < 0   for 0 <= w < 1/2,

so g is strictly concave, y = sqrt(g) is strictly concave and the solid is strictly convex
for every w/L in [0, 1/2); at w/L = 1/2 the curve degenerates into a parabola cut off by a
flat disc (the fat tip's radius of curvature, 1 / (a (1 - 2w)^2), diverges). A scan of the
curvature over w/L in [0, 0.499] confirms this numerically, so ``W_MAX = 0.5``. The fat end
flattening makes the support function harder to represent as w/L grows: see "Degree".

Orientation
-----------
The symmetry axis k points from the fat end to the thin end (along +x). theta = 0 rests on
the end at -k, the FAT end (k up); theta = pi rests on the THIN end. For w > 0 the centre of
mass lies toward the fat end (x_G < 0), so the egg stands lower on its fat end:
h(0) = a + x_G < h(pi) = a - x_G. :meth:`Egg.lower_end` says which end is down.

Support function and degree
---------------------------
h(theta) = max over the meridian of [-(x - x_G) cos(theta) + y sin(theta)] = h_O(theta) + x_G
cos(theta), where h_O is the support function about the middle of the axis, found by Newton's
method on the tangency condition (:func:`support`, accurate to rounding, ~1e-15).
H(c) = h(acos c) is a Chebyshev series in c whose coefficients are the shape parameters, so
eggs whose series have the same length share one compiled model: the degree is the smallest
of ``DEGREES`` = (16, 32, 64, 128, 256) that holds every coefficient a_k with k^2 |a_k| above
1e-14 max |a_k|. The series then gives h to ~1e-15 and h + h_thetatheta to ~1e-13 (the
requirement is 1e-12 in h, checked on a grid of 4096 theta at construction). Needed degree
before rounding up to a tier::

    w/L:    0     0.02   0.05   0.08   0.10   0.15   0.20
    a=0.3   112   139    180    228    266    390    583
    a=0.5   62    80     106    135    158    232    348
    a=1.0   0     31     47     63     75     113    171
    a=1.3   32    43     57     70     80     108    142
    a=2.0   62    71     89     107    121    160    210
    a=3.0   100   111    135    160    180    238    312

So every a in [0.3, 3] is supported for w/L <= ``W_GUARANTEED`` = 0.08. Larger w/L is accepted
while the series fits in ``MAX_DEGREE`` = 256 terms (up to w/L = 0.095 at a = 0.3, 0.16 at
a = 0.5, 0.22 at a = 0.8, 0.245 at a = 1, 0.27 at a = 1.3, 0.28 at a = 1.5, 0.23 at a = 2,
0.165 at a = 3) and otherwise rejected with a ParameterError naming ``w``.
"""

from __future__ import annotations

import functools
import math
from typing import NamedTuple

import numpy as np

from .._runtime.validate import check_range
from ..errors import ParameterError
from .body import Body
from .egg_shape import A_RANGE, W_MAX, clenshaw, fit_support, support


class EggMassProperties(NamedTuple):
    """Mass properties of the uniform solid egg of unit mass (lengths in b = B/2)."""

    volume: float  #: in b^3
    x_G: float  #: centroid on the axis, from the middle (fat tip at -a, thin tip at +a)
    A: float  #: transverse moment about the centroid, in M b^2
    C: float  #: axial moment, in M b^2


@functools.lru_cache(maxsize=256)
def mass_properties(a: float, w: float) -> EggMassProperties:
    """Volume, centroid and moments of the uniform egg (a, w), by adaptive quadrature.

    Each slice dx is a disc of mass rho pi y^2 dx: its axial moment is (y^2/2) dm and its
    moment about a transverse axis through G is (y^2/4 + (x - x_G)^2) dm (parallel axes).
    The integrals are taken in s = x/a on [-1, 1], where y^2 = g(s) = (1 - s^2) /
    (1 + 4 w s + 4 w^2) does not depend on a, so that the integrands are O(1) and an absolute
    tolerance of 1e-14 is meaningful (a purely relative one is unreachable for the
    vanishing first moment at w = 0 and makes QUADPACK warn).

    Parameters
    ----------
    a : float
        Aspect ratio L/B.
    w : float
        Asymmetry w/L.

    Returns
    -------
    EggMassProperties
        Volume, centroid on the axis, and the moments A (about the centroid) and C per unit
        mass.
    """

    from scipy.integrate import quad  # imported here: scipy.integrate costs 0.3 s at import

    def g(s):
        return (1.0 - s * s) / (1.0 + 4.0 * w * s + 4.0 * w * w)

    def integral(f):
        return quad(f, -1.0, 1.0, epsabs=1e-14, epsrel=1e-13, limit=200)[0]

    m0 = integral(g)
    # w = 0 is symmetric about the middle: the centroid is exactly 0 there
    s_G = 0.0 if w == 0.0 else integral(lambda s: s * g(s)) / m0
    C = 0.5 * integral(lambda s: g(s) ** 2) / m0
    A = (0.25 * integral(lambda s: g(s) ** 2) + a * a * integral(lambda s: g(s) * (s - s_G) ** 2)) / m0
    return EggMassProperties(float(np.pi * a * m0), float(a * s_G), float(A), float(C))


# -- the body --------------------------------------------------------------------------------
_STRUCTURE_KEYS: dict[int, str] = {}
_W_LABEL = f"[0, {W_MAX:g}) (w/L; the egg is strictly convex only below {W_MAX:g})"


class Egg(Body):
    """An egg: the solid of revolution of Hugelschaffer's curve (module docstring), the fat end
    at -k and the thin end at +k, so that theta = 0 rests on the fat end and theta = pi on the
    thin end.

    Parameters
    ----------
    a : float in [0.3, 3]
        Aspect ratio L/B, length over maximum breadth (w = 0 is ``Spheroid(a)``).
    w : float in [0, 0.5)
        Asymmetry: the shift of the maximum breadth from the middle of the axis toward the fat
        end, over L. Every a is supported up to w = ``W_GUARANTEED`` (0.08); larger w is
        accepted when the support function fits a Chebyshev series of degree <= 256 (up to
        w = 0.27 for a = 1.3; see the module docstring).
    A, C : float, optional
        Moments about G in M b^2 (b = B/2). Default: the uniform solid's (by quadrature).
    centre_of_mass : float, optional
        Axial coordinate x_G of G, from the middle of the axis toward the thin end (the fat
        tip is at -a, the thin tip at +a). Default: the uniform solid's centroid. When G is
        moved and A is not given, A is the uniform solid's transverse moment about its
        centroid reduced by the parallel-axis term (x_G - centroid)^2, the convention of
        :class:`~phasekit.bodies.spheroid.EccentricSphere` (second moments about the centroid kept).

    Attributes
    ----------
    a, w : float
        As given.
    x_G : float
        Axial coordinate of G (``centre_of_mass``, or the centroid).
    volume, centroid : float
        Volume of the solid (b^3) and its centroid's axial coordinate.
    degree : int
        Degree of the Chebyshev series (one of ``DEGREES``: eggs of equal degree share compiled
        models); ``needed_degree`` the degree the accuracy criterion asked for.
    fit_error, fit_error_curvature : float
        Max errors of the series in h and in h + h_thetatheta over the check grid, against a
        direct Newton solve.

    Raises
    ------
    ParameterError
        If ``a`` is outside [0.3, 3]; ``w`` is outside [0, 0.5), or too large for this ``a``
        (the support function needs a Chebyshev series of degree > 256, or its fit misses
        1e-12); ``centre_of_mass`` is outside (-a, a), or too far from the centroid for the
        default A (C <= 2A fails); ``A`` or ``C`` is not a finite number > 0, or C > 2 A; or
        the surface is not smooth and strictly convex (the error names ``w``).

    Examples
    --------
    >>> egg = Egg(1.3, 0.1)
    >>> egg.lower_end(0.0), egg.lower_end(np.pi)
    ('fat', 'thin')
    """

    def __init__(
        self, a: float, w: float, A: float | None = None, C: float | None = None, centre_of_mass: float | None = None
    ):
        self.a = check_range("a", a, *A_RANGE, closed="lr")
        self.w = check_range("w", w, 0.0, W_MAX, closed="l", label=_W_LABEL)
        props = mass_properties(self.a, self.w)
        self.volume, self.centroid = props.volume, props.x_G
        if centre_of_mass is None:
            self.x_G = props.x_G
        else:
            inside = f"(-{self.a:g}, {self.a:g}) (inside the egg, on its axis)"
            self.x_G = check_range("centre_of_mass", centre_of_mass, -self.a, self.a, label=inside)
        shift2 = (self.x_G - props.x_G) ** 2
        if A is None and props.A - shift2 < 0.5 * (props.C if C is None else C):
            raise ParameterError(
                "centre_of_mass",
                f"is too far from the centroid {props.x_G:.6g} for the default moments (C <= 2A fails); give A and C",
                centre_of_mass,
            )
        super().__init__(props.A - shift2 if A is None else A, props.C if C is None else C)
        series, self.needed_degree, self.fit_error, self.fit_error_curvature = fit_support(self.a, self.w)
        coef = np.array(series)
        coef[1] += self.x_G  # h = h_O + x_G cos(theta), and cos(theta) = T_1(c)
        self._coef = tuple(float(v) for v in coef)
        self.check_convex("w")

    # -- Body interface ---------------------------------------------------------------------
    @property
    def shape_params(self) -> tuple[float, ...]:
        """The Chebyshev coefficients of H(c) (length degree + 1)."""
        return self._coef

    def height(self, c, shape):
        """H(c) = sum_k shape[k] T_k(c), by Clenshaw's recurrence.

        Parameters
        ----------
        c : casadi.SX
            The symbol c = cos(theta).
        shape : casadi.SX
            The Chebyshev coefficients (symbols), as many as :attr:`shape_params`.

        Returns
        -------
        casadi.SX
            The height of G above the table, units b.
        """
        return clenshaw(c, shape)

    @property
    def structure_key(self) -> str:
        # the symbolic form depends on the degree only: hash it once per degree, not per egg
        # (serialising a degree-256 recurrence costs ~0.07 s)
        if self._key is None:
            if self.degree not in _STRUCTURE_KEYS:
                _STRUCTURE_KEYS[self.degree] = Body.structure_key.fget(self)
            self._key = _STRUCTURE_KEYS[self.degree]
        return self._key

    # -- egg-specific -----------------------------------------------------------------------
    @property
    def degree(self) -> int:
        return len(self._coef) - 1

    @property
    def uniform(self) -> bool:
        """True when A, C and G are the uniform solid's."""
        p = mass_properties(self.a, self.w)
        return self.x_G == p.x_G and abs(self.A - p.A) < 1e-15 and abs(self.C - p.C) < 1e-15

    @property
    def flip_symmetric(self) -> bool:
        return self.w == 0.0 and self.x_G == 0.0

    @staticmethod
    def lower_end(theta: float) -> str:
        """Which end is the lower one at inclination theta in [0, pi]: ``"fat"`` (the end at
        -k) for theta < pi/2, so theta = 0 rests on the fat end, and ``"thin"`` (the end at +k)
        for theta > pi/2, so theta = pi rests on the thin end. At pi/2 the axis is horizontal
        (ParameterError). For w = 0 the two ends are alike; the names still tell -k from +k.

        Parameters
        ----------
        theta : float
            Inclination of k from the vertical, radians, in [0, pi], not pi/2.

        Returns
        -------
        {"fat", "thin"}
            The lower end.

        Raises
        ------
        ParameterError
            If ``theta`` is outside [0, pi] or is pi/2.
        """
        theta = check_range("theta", theta, 0.0, math.pi, closed="lr", label="[0, pi]")
        if theta == 0.5 * math.pi:
            raise ParameterError("theta", "must differ from pi/2 (axis horizontal: neither end is lower)", theta)
        return "fat" if theta < 0.5 * math.pi else "thin"

    def meridian(self, x):
        """Radius y(x) of the cross-section at axial coordinate x in [-a, a] (Narushin's
        formula with L = 2a, B = 2 and w*L).

        Parameters
        ----------
        x : float or array_like
            Axial coordinates from the middle of the axis, units b, in [-a, a] (the radius is 0
            outside).

        Returns
        -------
        numpy.ndarray
            The radius y(x), units b, of the shape of ``x``.
        """
        x = np.asarray(x, dtype=float)
        L, wa = 2.0 * self.a, 2.0 * self.a * self.w
        return np.sqrt(np.clip(L * L - 4.0 * x * x, 0.0, None) / (L * L + 8.0 * wa * x + 4.0 * wa * wa))

    def support_direct(self, theta):
        """(h, h_theta, h_thetatheta) by a direct Newton solve (no fit); see :func:`support`.

        Parameters
        ----------
        theta : float or array_like
            Inclination of k from the vertical, radians, in [0, pi].

        Returns
        -------
        tuple
            (h, h_theta, h_thetatheta), units b: floats for a number, arrays of the shape of
            ``theta`` otherwise.
        """
        return support(theta, self.a, self.w, self.x_G)

    def describe(self) -> str:
        return (
            f"egg a={self.a:g}, w={self.w:g} (Hugelschaffer; fat end down at theta=0), A={self.A:.6g}, "
            f"C={self.C:.6g}, x_G={self.x_G:.6g}"
        )

    def to_dict(self) -> dict:
        return {
            "body": "egg",
            "a": self.a,
            "w": self.w,
            "A": self.A,
            "C": self.C,
            "x_G": self.x_G,
            "degree": self.degree,
            "fit_error": self.fit_error,
            "fit_error_curvature": self.fit_error_curvature,
            "description": self.describe(),
        }

    def __repr__(self) -> str:
        if self.uniform:
            return f"Egg(a={self.a:g}, w={self.w:g})"
        return f"Egg(a={self.a:g}, w={self.w:g}, A={self.A:g}, C={self.C:g}, centre_of_mass={self.x_G:g})"
