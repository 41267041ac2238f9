"""Compound bodies: several convex pieces of revolution on one axis, as one body. The tippe top
with its stem, :class:`TippeTop`.

The support function of a compound body
---------------------------------------
A body made of convex pieces that share the axis k touches the table with the piece that
reaches lowest: the height of G above the table is the largest of the pieces' support
functions, H(c) = max_i h_i(c), c = cos(theta) (a piece with a smaller h would be above the
table). On each side of a switch angle c*, where two pieces' supports are equal, H is one
piece's analytic function, so every equation of phasekit (the charts, the fields, the events,
the fixed points) holds there unchanged; H is written with CasADi's ``if_else``, which the
Taylor integrator translates (:mod:`phasekit.core.engines.translate`). At c* the contact passes
from one piece to the other: the new piece hits the table while the old one touches it, an
impact (:class:`phasekit.core.resets.Transfer`). The body lists its switches in
:attr:`TippeTop.transfers` (:class:`PieceTransfer`); the hybrid system watches each as an event
in every mode, so no integration step crosses one.

The tippe top with its stem
---------------------------
A ball of radius 1 (the unit b) with its centre O ``offset`` above G on the axis k, h_ball =
1 - offset c (:class:`~phasekit.bodies.spheroid.EccentricSphere`), and on +k a stem: a shaft
of radius r standing ``stem_length`` (L) out of the ball and ending in a hemisphere of the same
radius r, whose centre lies l = offset + 1 + L - r from G on +k. Its support is that of a sphere
of radius r centred there, h_stem = r - l c (G is l c above the tip's centre, the table r below
it). They are equal at c* = (r - 1) / (l - offset) = -(1 - r) / (1 - r + L): for theta above
theta* = acos(c*) the stem touches. The shaft, no wider than its tip, never reaches lower than
the ball or the tip. Standing on the stem's end (theta = pi), G is l + r above the table.
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np

from .._runtime.validate import check_nonnegative, check_range
from ..errors import ParameterError
from .body import Body, PieceTransfer
from .inertia import Solid, assemble, rod
from .operations import STEPS
from .spheroid import TIPPE_TOP_OFFSET_MAX

#: the default stem (how far it stands out of the ball, the radius of its rounded end; units of
#: the ball's radius): our reading of a common commercial top, Arbor Scientific's wooden
#: "Inverting Pop Tops", 3.8 cm tall and 3.2 cm across (teachersource.com), taken as a full ball
#: of radius 16 mm with 6 mm of stem: 6/16 = 0.375; the stem's end as the 1/4 inch spindle that
#: woodturners fit to a 1 1/4 inch ball (waxhawwoodturners.com, 2011): 0.125/0.625 = 0.2.
#: Another wooden top sold as "Tippe Top (Wood)", 43 mm tall and 31 mm across
#: (stemcelltulsa.com), has a longer stem, 12/15.5 = 0.77.
STEM = (0.375, 0.2)
#: the stem's share of the mass in the default moments (a thin rod): our estimate for a wooden
#: dowel in a wooden ball, ~4% of the volume
STEM_MASS = 0.04
#: the longest stem, in ball radii
STEM_LENGTH_MAX = 10.0


class TippeTop(Body):
    """The tippe top with its stem: a ball of radius 1 (the unit b) whose centre lies ``offset``
    above G on the axis, and a stem on +k standing ``stem_length`` out of the ball, rounded at
    its end with the radius ``stem_radius``. theta = 0: on the ball, stem up; theta = pi:
    standing on the stem's end (module notes).

    Support function H(c) = max(1 - offset c, r - l c), l = offset + 1 + L - r: the ball's
    below the switch angle :attr:`theta_switch`, the stem's above it.

    Parameters
    ----------
    offset : float in [0, 1)
        Distance OG over the ball's radius (alpha in the tippe-top literature).
    stem_length : float in (0, 10], optional
        L, how far the stem stands out of the ball, over its radius (default 0.375, module
        constant STEM: a common commercial top).
    stem_radius : float in (0, 1), optional
        r, the radius of the stem's rounded end over the ball's (default 0.2).
    A, C : float, optional
        Moments about G, units M b^2. Default: those of :func:`default_moments`: the ball of
        :class:`~phasekit.bodies.spheroid.EccentricSphere` (inertia 2/5 about its centre) with a
        stem of mass fraction STEM_MASS (a thin rod), assembled by
        :func:`phasekit.bodies.inertia.assemble` with G kept ``offset`` below O.

    Attributes
    ----------
    offset, stem_length, stem_radius : float
        As given. (``theta_switch``: where the stem starts to touch; ``transfers``: the two
        passages of the contact, "stem touches" as theta rises through it and "ball touches"
        as it falls; ``limits``: none.)

    Raises
    ------
    ParameterError
        If ``offset`` is not a finite number in [0, 1) (at most sqrt(1/5) with the default
        moments), ``stem_length`` not in (0, 10], ``stem_radius`` not in (0, 1); or ``A`` or
        ``C`` is not a finite number > 0, or C > 2 A.

    See Also
    --------
    EccentricSphere
        the ball alone, without the stem

    Examples
    --------
    >>> import phasekit as pk
    >>> top = pk.bodies.TippeTop(0.3, 0.375, 0.2, A=0.38, C=0.4)
    >>> round(top.theta_switch, 6), [t.name for t in top.transfers]
    (2.31972, ['stem touches', 'ball touches'])
    >>> round(float(top.h(np.pi)[0]), 6)      # on the stem's end: l + r = offset + 1 + L
    1.675
    """

    def __init__(self, offset: float, stem_length: float = STEM[0], stem_radius: float = STEM[1],
                 A: float | None = None, C: float | None = None):
        self.offset = check_nonnegative("offset", offset)
        if self.offset >= 1.0:
            raise ParameterError("offset", "must lie in [0, 1) (G inside the ball)", offset)
        self.stem_length = check_range("stem_length", stem_length, 0.0, STEM_LENGTH_MAX, closed="r",
                                       label=f"(0, {STEM_LENGTH_MAX:g}] (over the ball's radius)")
        self.stem_radius = check_range("stem_radius", stem_radius, 0.0, 1.0, closed="",
                                       label="(0, 1) (over the ball's radius)")
        if (A is None or C is None) and self.offset > TIPPE_TOP_OFFSET_MAX:
            raise ParameterError("offset", f"must be <= {TIPPE_TOP_OFFSET_MAX:.6g} (sqrt(1/5)) for the default moments "
                                           "(no ball with inertia 2/5 about its centre has a larger offset); give A and C",
                                 offset)
        if A is None or C is None:
            whole = default_moments(self.offset, self.stem_length)
            A, C = whole.A if A is None else A, whole.C if C is None else C
        super().__init__(A, C)
        self.check_convex("offset")

    @property
    def shape_params(self) -> tuple[float, ...]:
        return (self.offset, self.stem_length, self.stem_radius)

    @property
    def tip_centre(self) -> float:
        """l, the distance from G to the centre of the stem's rounded end, units b."""
        return self.offset + 1.0 + self.stem_length - self.stem_radius

    def height(self, c, shape):
        offset, L, r = shape[0], shape[1], shape[2]
        tip = offset + 1 + L - r  # l, G to the centre of the stem's end
        c_switch = (r - 1) / (1 + L - r)  # h_ball = h_stem
        return ca.if_else(c > c_switch, 1 - offset * c, r - tip * c)

    def piece_heights(self, theta):
        """(h_ball, h_stem) at theta: the support of each piece (the body's is the larger).

        Parameters
        ----------
        theta : float or array_like
            Inclination, radians.

        Returns
        -------
        tuple
            (h_ball, h_stem), units b, of the shape of ``theta``.
        """
        c = np.cos(np.asarray(theta, dtype=float))
        return 1.0 - self.offset * c, self.stem_radius - self.tip_centre * c

    @property
    def theta_switch(self) -> float:
        """theta* = acos(-(1 - r)/(1 - r + L)), radians: where the stem's end reaches the table
        as the ball touches it."""
        r = self.stem_radius
        return math.acos((r - 1.0) / (1.0 + self.stem_length - r))

    @property
    def transfers(self) -> tuple[PieceTransfer, ...]:
        """The passages of the contact between the pieces (module notes)."""
        th = self.theta_switch
        return (PieceTransfer("stem touches", th, +1, "ball", "stem"), PieceTransfer("ball touches", th, -1, "stem", "ball"))

    def piece(self, theta: float) -> str:
        """The piece that touches the table at ``theta``: "ball" or "stem".

        Parameters
        ----------
        theta : float
            Inclination, radians.

        Returns
        -------
        str
        """
        return "stem" if math.cos(theta) < math.cos(self.theta_switch) else "ball"

    def outline(self, n: int = 64) -> tuple[np.ndarray, np.ndarray]:
        """The meridian as drawn: (z, r) from the ball's lowest point to the stem's end, z along
        k from G and r from the axis (units b): the ball up to the shaft, the shaft, its
        rounded end.

        Parameters
        ----------
        n : int, optional
            The resolution (default 64): k = max(2, n // 3) points on the shaft and the end, four
            times as many on the ball.

        Returns
        -------
        tuple of numpy.ndarray
            (z, r), each of 6 k points.
        """
        n = max(2, n // 3)
        r = self.stem_radius
        phi = np.linspace(0.0, math.pi - math.asin(r), 4 * n)
        z_ball, r_ball = self.offset - np.cos(phi), np.sin(phi)
        z_shaft = np.linspace(z_ball[-1], self.tip_centre, n + 1)[1:]
        psi = np.linspace(0.0, 0.5 * math.pi, n + 1)[1:]
        z = np.concatenate([z_ball, z_shaft, self.tip_centre + r * np.sin(psi)])
        rr = np.concatenate([r_ball, np.full(n, r), r * np.cos(psi)])
        return z, rr

    @property
    def is_prolate(self) -> bool:
        return False

    @property
    def flip_symmetric(self) -> bool:
        return False

    def describe(self) -> str:
        return (f"tippe top with a stem (offset {self.offset:g}, stem {self.stem_length:g} long, end radius "
                f"{self.stem_radius:g}, radii of the ball), A={self.A:.6g}, C={self.C:.6g}")

    def to_dict(self) -> dict:
        return {"body": "tippe-top", "offset": self.offset, "stem_length": self.stem_length,
                "stem_radius": self.stem_radius, "A": self.A, "C": self.C, "description": self.describe()}

    def __repr__(self) -> str:
        return (f"TippeTop(offset={self.offset:g}, stem_length={self.stem_length:g}, stem_radius={self.stem_radius:g}, "
                f"A={self.A:g}, C={self.C:g})")


def default_moments(offset: float, stem_length: float, stem_mass: float = STEM_MASS) -> Solid:
    """The default moments of a :class:`TippeTop`: a ball whose inertia about its centre O is
    the uniform ball's (2/5 of its mass about every axis, as
    :class:`~phasekit.bodies.spheroid.EccentricSphere`'s), carrying a stem (a thin rod standing
    ``stem_length`` out of it) of mass fraction ``stem_mass``; the ball's own centre of mass is
    placed so that G lies ``offset`` below O.

    Parameters
    ----------
    offset : float
        OG, units b.
    stem_length : float
        The rod's length, units b (from the ball's pole).
    stem_mass : float, optional
        The rod's share of the mass (default STEM_MASS).

    Returns
    -------
    Solid
        The whole body about G (``z`` = -offset from O, ``A``, ``C`` in M b^2).

    Raises
    ------
    ParameterError
        If no ball with inertia 2/5 about O has the centre of mass this needs (named ``offset``).
    """
    z_rod = 1.0 + 0.5 * stem_length  # from O along k
    m_ball = 1.0 - stem_mass
    z_ball = (-offset - stem_mass * z_rod) / m_ball
    A_own = 0.4 - z_ball * z_ball  # 2/5 about O, moved to the ball's own centre of mass
    if A_own <= 0.0:
        raise ParameterError("offset", "is too large for the default moments with this stem (the ball's centre of mass "
                                       "would lie farther than sqrt(2/5) from its centre); give A and C", offset)
    return assemble(Solid(m_ball, z_ball, A_own, 0.4), rod(stem_length, z_rod, mass=stem_mass))


# -- a piece as a body of its own ------------------------------------------------------------

def frozen_support(body, theta: float) -> tuple[ca.SX, ca.SX, ca.SX]:
    """(c, shape, H): the symbols and the support of ``body`` with every switch frozen at the
    branch it takes at ``theta`` (:class:`PieceSupport`): the body's H, read instruction by instruction
    and evaluated at theta alongside, a switch's symbolic result replaced by the branch its
    value picks."""
    c, sh = ca.SX.sym("c"), ca.SX.sym("shape", body.n_shape)
    f = ca.Function("H", [c, sh], [body.height(c, sh)])
    symbols = [[c], [sh[k] for k in range(body.n_shape)]]
    numbers = [[math.cos(theta)], [float(v) for v in body.shape_params]]
    sym, num, out = {}, {}, None
    for k in range(f.n_instructions()):
        op, o, i = f.instruction_id(k), f.instruction_output(k), f.instruction_input(k)
        if op == ca.OP_CONST:
            num[o[0]] = float(f.instruction_constant(k))
            sym[o[0]] = ca.SX(num[o[0]])
        elif op == ca.OP_INPUT:
            sym[o[0]], num[o[0]] = symbols[i[0]][i[1]], numbers[i[0]][i[1]]
        elif op == ca.OP_OUTPUT:
            out = sym[i[0]]
        else:
            a, s = [num[j] for j in i], [sym[j] for j in i]
            value = float(ca.DM.binary(op, *a) if len(i) == 2 else ca.DM.unary(op, a[0]))
            if op in STEPS:
                e = ca.SX(value)
            elif op == ca.OP_IF_ELSE_ZERO:
                e = s[1] if a[0] else ca.SX(0.0)
            elif op in (ca.OP_FMAX, ca.OP_FMIN):
                e = s[0] if (a[0] >= a[1]) == (op == ca.OP_FMAX) else s[1]
            elif op == ca.OP_FABS:
                e = s[0] if a[0] >= 0 else -s[0]
            else:
                e = ca.SX.binary(op, *s) if len(i) == 2 else ca.SX.unary(op, s[0])
            sym[o[0]], num[o[0]] = e, value
    return c, sh, out


class PieceSupport(Body):
    """One piece of a compound body as a body of its own: the whole body's moments and shape
    parameters, and the piece's own support, analytic across the switches.

    The piece's support is read off the body's: H written with CasADi's ``if_else`` (or fmax,
    fmin, fabs) with every such switch frozen at the branch it takes inside the piece, an
    expression analytic across the switch (the tippe top's ball: 1 - offset c, an eccentric
    sphere; its stem: r - l c, the support of a sphere of radius r centred l from G), so closed
    forms hold up to the switch itself (phasekit.steady computes a compound body's structure
    piece by piece on these). Inside the piece's range it is the body's H, operation for
    operation.

    Parameters
    ----------
    whole : Body
        The compound body.
    piece : str
        The piece's name ("ball", "stem").
    theta : float
        An angle inside the piece's range, radians (where its switches are read).
    """

    def __init__(self, whole, piece: str, theta: float):
        super().__init__(whole.A, whole.C)
        self.whole, self.piece = whole, piece
        self._c, self._sh, self._H = frozen_support(whole, theta)
        self._shape = tuple(float(v) for v in whole.shape_params)

    @property
    def shape_params(self) -> tuple[float, ...]:
        return self._shape

    def height(self, c, shape):
        return ca.substitute([self._H], [self._c, self._sh], [ca.SX(c), ca.SX(shape)])[0]

    def describe(self) -> str:
        return f"the {self.piece} of the {self.whole.describe()}"

    def __repr__(self) -> str:
        return f"PieceSupport({self.piece!r} of {self.whole!r})"
