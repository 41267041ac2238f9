"""The spheroid and the eccentric sphere (the tippe top): the built-in bodies of the paper and its
series, each a closed-form support function h(theta) with default moments (see
:mod:`phasekit.bodies.body` for what a body is)."""

from __future__ import annotations

import math

import casadi as ca

from .._runtime.validate import check_nonnegative, check_range
from ..errors import ParameterError
from .body import Body

#: aspect ratios outside this range give moments of inertia that overflow or vanish
ASPECT_RANGE = (1e-4, 1e4)


class Spheroid(Body):
    """Spheroid with semi-axes (1, 1, a): prolate for a > 1, oblate for a < 1; its centre of
    mass G at the centre O, or displaced along the axis (part III of the series).

    Parameters
    ----------
    a : float
        Aspect ratio (polar over equatorial semi-axis), in [1e-4, 1e4].
    A, C : float, optional
        Moments about G (units M b^2). Defaults: with G at O those of the uniform solid,
        A = (1 + a^2)/5, C = 2/5; with an offset, the same inertia about O moved to G by
        the parallel-axis theorem, A = (1 + a^2)/5 - offset^2, C = 2/5 (see Notes).
    offset : float in [0, a), keyword-only
        Distance OG (units b) from the centre of volume O to G, toward the end at -k (the end
        the body rests on at theta = 0): the tippe top's convention
        (:class:`EccentricSphere`). Support function h = sqrt(a^2 cos^2 + sin^2) - offset cos.

    Notes
    -----
    Part III of the series (Branicki, Moffatt & Shimomura, *Geometry of steady state
    structures for convex bodies*, Proc. R. Soc. A, 2006) treats A and C as free parameters. The default keeps the
    uniform spheroid's inertia about O, i.e. a density redistributed along the axis; it
    exists for offset^2 <= a^2/5 (Cauchy-Schwarz: (int z dm)^2 <= M int z^2 dm = M a^2/5, the
    same bound as C <= 2A); larger offsets need explicit A and C.

    Raises
    ------
    ParameterError
        If ``a`` is outside [1e-4, 1e4]; ``offset`` is not a finite number in [0, a), or
        exceeds a/sqrt(5) when ``A`` or ``C`` is left to its default; ``A`` or ``C`` is not a
        finite number > 0, or C > 2 A; or the surface is not smooth and strictly convex (the
        error names ``a``).

    Examples
    --------
    >>> Spheroid(1.5).A
    0.65
    >>> Spheroid(1.5, offset=0.2).flip_symmetric
    False
    """

    def __init__(self, a: float, A: float | None = None, C: float | None = None, *, offset: float = 0.0):
        self.a = check_range("a", a, *ASPECT_RANGE, closed="lr", label=f"[{ASPECT_RANGE[0]:g}, {ASPECT_RANGE[1]:g}]")
        self.offset = check_nonnegative("offset", offset)
        if self.offset >= self.a:
            raise ParameterError("offset", f"must lie in [0, a) = [0, {self.a:g}) (G inside the spheroid)", offset)
        if (A is None or C is None) and self.offset > self.a / math.sqrt(5.0):
            raise ParameterError("offset", f"must be <= a/sqrt(5) = {self.a / math.sqrt(5.0):.6g} for the default moments "
                                           "(no density with the uniform spheroid's inertia about its centre has a larger "
                                           "offset); give A and C", offset)
        A0 = (1.0 + self.a * self.a) / 5.0 - self.offset**2
        super().__init__(A0 if A is None else A, 0.4 if C is None else C)
        self.check_convex("a")

    @property
    def shape_params(self) -> tuple[float, ...]:
        # the centred spheroid keeps its one-parameter form, so its compiled models (and every
        # number computed with them) are those it always had
        return (self.a, self.offset) if self.offset else (self.a,)

    def height(self, c, shape):
        # (2.10): h = (a^2 cos^2 + sin^2)^(1/2) = (1 + (a^2 - 1) c^2)^(1/2), minus offset cos for G below O
        a = shape[0]
        h = ca.sqrt(1 + (a * a - 1) * c * c)
        return h - shape[1] * c if self.offset else h

    @property
    def uniform(self) -> bool:
        return not self.offset and abs(self.A - (1 + self.a**2) / 5) < 1e-15 and abs(self.C - 0.4) < 1e-15

    @property
    def is_prolate(self) -> bool:
        return self.a > 1.0 if not self.offset else super().is_prolate

    @property
    def flip_symmetric(self) -> bool:
        return not self.offset

    def to_dict(self) -> dict:
        d = {"body": "spheroid", "a": self.a, "A": self.A, "C": self.C, "description": self.describe()}
        if self.offset:
            d["offset"] = self.offset
        return d

    def __repr__(self) -> str:
        if self.uniform:
            return f"Spheroid(a={self.a:g})"
        off = f", offset={self.offset:g}" if self.offset else ""
        return f"Spheroid(a={self.a:g}{off}, A={self.A:g}, C={self.C:g})"


#: the largest offset for the default tippe-top moments: an isotropic inertia 2/5 about the
#: ball's centre O allows offset^2 <= 1/5 (Cauchy-Schwarz; the same bound as C <= 2A)
TIPPE_TOP_OFFSET_MAX = math.sqrt(0.2)


class EccentricSphere(Body):
    """A sphere of radius 1 whose centre of mass G lies ``offset`` below its centre O along the
    axis k (the tippe top). theta = 0: resting on the ball with G below O (axis up);
    theta = pi: inverted, resting on the other side with G above O.

    Support function: h = 1 - offset cos(theta), so h_t = offset sin(theta) and both radii of
    curvature equal 1 everywhere.

    Parameters
    ----------
    offset : float in [0, 1)
        Distance OG over the radius (alpha in the tippe-top literature).
    A, C : float, optional
        Moments about G in M b^2 (b the radius). Default: C = 2/5 and A = 2/5 - offset^2.

    Notes
    -----
    Default moments. They are those of a ball whose inertia about its centre O is the uniform
    ball's, 2/5 about every axis, moved to G by the parallel-axis theorem. The standard physical
    example is a ball made of two solid hemispheres of different uniform densities rho_1 (the
    lower half when upright) and rho_2: each hemisphere has moment 2/5 m_i about every axis
    through O, and G lies (3/8)(rho_1 - rho_2)/(rho_1 + rho_2) below O, so offset <= 3/8 covers
    all such balls. No density >= 0 gives these moments beyond offset^2 = 1/5 (Cauchy-Schwarz:
    (int z dm)^2 <= M int z^2 dm = M A_O / 2), which is also where C <= 2A fails; such offsets
    need explicit A and C. The default gamma = A/C = 1 - 5 offset^2/2 lies inside the classical
    inversion interval (1 - offset, 1 + offset) for every offset < 2/5, so every default top
    inverts when spun fast enough (phasekit.theory.tippetop.classical_inversion). Commercial tippe tops
    (a truncated ball with a stem) have gamma closer to 1; the example in the README uses
    offset 0.3, A = 0.38, C = 0.4 (gamma = 0.95).

    Raises
    ------
    ParameterError
        If ``offset`` is not a finite number in [0, 1), or exceeds sqrt(1/5) when ``A`` is left
        to its default; or ``A`` or ``C`` is not a finite number > 0, or C > 2 A.

    See Also
    --------
    TippeTop
        the tippe top with its stem, a compound body (this class is its ball alone)

    Examples
    --------
    >>> import phasekit as pk
    >>> top = pk.EccentricSphere(0.3, A=0.38, C=0.4)
    >>> top
    EccentricSphere(offset=0.3, A=0.38, C=0.4)
    >>> round(float(top.h(0.0)[0]), 6)
    0.7
    """

    def __init__(self, offset: float, A: float | None = None, C: float | None = None):
        self.offset = check_nonnegative("offset", offset)
        if self.offset >= 1.0:
            raise ParameterError("offset", "must lie in [0, 1) (G inside the ball)", offset)
        if A is None and self.offset > TIPPE_TOP_OFFSET_MAX:
            raise ParameterError("offset", f"must be <= {TIPPE_TOP_OFFSET_MAX:.6g} (sqrt(1/5)) for the default moments "
                                           "(no ball with inertia 2/5 about its centre has a larger offset); give A and C",
                                 offset)
        super().__init__(0.4 - self.offset**2 if A is None else A, 0.4 if C is None else C)
        self.check_convex("offset")

    @property
    def shape_params(self) -> tuple[float, ...]:
        return (self.offset,)

    def height(self, c, shape):
        return 1 - shape[0] * c

    @property
    def is_prolate(self) -> bool:
        return False

    def to_dict(self) -> dict:
        return {"body": "tippe-top", "offset": self.offset, "A": self.A, "C": self.C, "description": self.describe()}

    def __repr__(self) -> str:
        return f"EccentricSphere(offset={self.offset:g}, A={self.A:g}, C={self.C:g})"
