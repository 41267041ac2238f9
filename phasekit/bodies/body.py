"""Bodies: a convex body of revolution given by its support function and its moments.

The paper's equations (2.7) use the body only through h(theta), the height of the centre
of mass G above the table when the symmetry axis k is inclined at theta to the vertical,
and its derivatives: the contact point P lies a height h below G and a horizontal distance
h_theta from it along the tilt. phasekit writes the height as a function of
c = cos(theta), H(c) = h(theta), so that one definition serves the Euler chart (singular at
theta = 0) and the vector chart, where c = k_Z is an ordinary variable. For a smooth body of
revolution h is even about theta = 0 and pi, so H is smooth on [-1, 1].

theta = 0 is the body resting on the end at -k (axis up), theta = pi on the end at +k;
for a body without flip symmetry these are different states.

To define a body, subclass :class:`Body` and implement :meth:`Body.height` (a CasADi
expression in c and the shape parameters) and :attr:`Body.shape_params`, or use
:class:`CustomBody` with a function of theta or of cos(theta). Units: mass M, length b
(the equatorial radius, or the sphere's radius), so A and C are in M b^2.
"""

from __future__ import annotations

import hashlib
import math
import threading
from typing import NamedTuple

import casadi as ca
import numpy as np

from .._runtime.errors import ParameterError
from .._runtime.validate import check_nonnegative, check_positive, check_range

__all__ = ["TIPPE_TOP_OFFSET_MAX", "Body", "CustomBody", "EccentricSphere", "MassProperties", "Spheroid", "uniform_mass_properties"]

#: aspect ratios outside this range give moments of inertia that overflow or vanish
ASPECT_RANGE = (1e-4, 1e4)


class Body:
    """Base class of bodies. Subclasses provide :meth:`height` and :attr:`shape_params`.

    Parameters
    ----------
    A, C : float
        Transverse and axial principal moments of inertia about the centre of mass G,
        in units M b^2, with C <= 2 A (triangle inequality of principal moments).

    Required of a subclass
    ----------------------
    ``shape_params`` -> tuple of floats
        The numbers that fix the shape (compiled models take them as parameters, so bodies
        that differ only in them share one compiled model).
    ``height(c, shape)`` -> casadi.SX
        H(c): the height of G above the table at c = cos(theta), written with the symbols
        ``shape`` (one per shape parameter) and ``c`` only. Must be smooth on [-1, 1].
    ``describe()`` (optional) -> str
        A one-line description for reports.

    Examples
    --------
    >>> import phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> isinstance(body, pk.bodies.Body), round(float(body.h(0.3)[0]), 6)
    (True, 1.463159)
    """

    def __init__(self, A: float, C: float):
        self.A = check_positive("A", A)
        self.C = check_positive("C", C)
        if self.C > 2 * self.A * (1 + 1e-12):
            raise ParameterError("C", f"must satisfy C <= 2A (triangle inequality of principal moments; A = {self.A:g})", C)
        self._key = None

    # -- to be provided by subclasses ---------------------------------------------------------
    @property
    def shape_params(self) -> tuple[float, ...]:
        raise NotImplementedError(f"{type(self).__name__} must define `shape_params` (see phasekit.bodies.body.Body)")

    def height(self, c, shape):
        """H(c) as a CasADi expression in ``c`` and the symbols ``shape``."""
        raise NotImplementedError(f"{type(self).__name__} must define `height(c, shape)` (see phasekit.bodies.body.Body)")

    # -- derived ----------------------------------------------------------------------------
    @property
    def n_shape(self) -> int:
        return len(self.shape_params)

    @property
    def params(self) -> np.ndarray:
        """Shape parameters followed by (A, C): the body's part of a model's parameter vector."""
        return np.array([*self.shape_params, self.A, self.C], dtype=float)

    @property
    def structure_key(self) -> str:
        """Identifies the symbolic form of H (not the numbers): bodies with equal keys share
        compiled models."""
        if getattr(self, "_key", None) is None:
            c, sh = ca.SX.sym("c"), ca.SX.sym("shape", self.n_shape)
            f = ca.Function("H", [c, sh], [self.height(c, sh)])
            digest = hashlib.sha256(f.serialize().encode()).hexdigest()[:16]
            self._key = f"{type(self).__qualname__}:{self.n_shape}:{digest}"
        return self._key

    def check_inertia(self) -> None:
        """Raise ParameterError naming `A` or `C` if a moment exceeds M r_max^2: all the mass
        lies within r_max = max |GP| of G (called when a Model is built: the shape is set
        after the moments in some bodies' constructors); once per body, as Models are built
        on the sweeps' hot path."""
        if getattr(self, "_inertia_checked", False):
            return
        h, h1, _ = (np.asarray(v, dtype=float).ravel() for v in self.h(np.linspace(0.0, np.pi, 181)))
        r2 = float(np.max(h * h + h1 * h1)) * (1 + 1e-9)
        for name, value in (("A", self.A), ("C", self.C)):
            if value > r2:
                raise ParameterError(name, f"must be at most {r2:.6g} (M r_max^2: no point of the body is farther than "
                                           f"r_max = {np.sqrt(r2):.6g} from G)", value)
        self._inertia_checked = True

    def h(self, theta):
        """(h, h_theta, h_thetatheta) at theta (float or array), exact derivatives via CasADi."""
        return _theta_functions(self)(np.asarray(theta, dtype=float), self.shape_params)

    def height_slope(self, c: float) -> tuple[float, float]:
        """(H(c), H'(c)) with c = cos(theta): the height and its slope, regular at the poles."""
        H, dH = _slope_function(self)(float(c), self.shape_params)
        return float(H), float(dH)

    def radii_of_curvature(self, theta):
        """Principal radii of curvature of the surface at the contact point for inclination
        theta: meridional h + h_tt and azimuthal x_P / sin(theta) (x_P = h sin + h_t cos,
        the distance of P from the axis). Both are > 0 on a strictly convex body."""
        theta = np.asarray(theta, dtype=float)
        h, h1, h2 = self.h(theta)
        s = np.sin(theta)
        xP = h * s + h1 * np.cos(theta)
        with np.errstate(divide="ignore", invalid="ignore"):
            r2 = np.where(np.abs(s) > 1e-6, xP / np.where(s == 0, 1.0, s), h + h2)
        return h + h2, r2

    def check_convex(self, param: str = "height", theta_range: tuple[float, float] = (0.0, np.pi), n: int = 721) -> None:
        """Raise ParameterError (naming ``param``) unless the surface is smooth and strictly
        convex over ``theta_range``: finite h > 0 and both radii of curvature > 0."""
        th = np.linspace(*theta_range, n)
        h = self.h(th)
        r1, r2 = self.radii_of_curvature(th)
        bad = ~(np.isfinite(h[0]) & np.isfinite(h[1]) & np.isfinite(h[2]) & (h[0] > 0) & (r1 > 0) & (r2 > 0))
        if np.any(bad):
            k = int(np.flatnonzero(bad)[0])
            what = (f"must give a smooth strictly convex surface (height h > 0 and radii of curvature > 0 for theta in "
                    f"[{theta_range[0]:g}, {theta_range[1]:g}]); at theta = {th[k]:.4g}: h = {h[0][k]:.4g}, "
                    f"h + h'' = {r1[k]:.4g}, x_P/sin = {r2[k]:.4g}")
            raise ParameterError(param, what, show_value=False)

    @property
    def is_prolate(self) -> bool:
        """True when G is higher standing on an end than lying on the equator (h(0) > h(pi/2)):
        such a body rises from the horizontal toward the vertical (the prolate branch)."""
        return bool(self.h(0.0)[0] > self.h(np.pi / 2)[0])

    @property
    def flip_symmetric(self) -> bool:
        """h(pi - theta) = h(theta): theta = 0 and pi are the same state."""
        th = np.linspace(0.0, np.pi / 2, 7)
        return bool(np.allclose(self.h(th)[0], self.h(np.pi - th)[0], rtol=1e-13, atol=1e-15))

    def describe(self) -> str:
        return repr(self)

    def to_dict(self) -> dict:
        return {"body": type(self).__name__, "shape": list(self.shape_params), "A": self.A, "C": self.C,
                "description": self.describe()}

    def __eq__(self, other) -> bool:
        return type(other) is type(self) and other.structure_key == self.structure_key and np.array_equal(other.params, self.params)

    def __hash__(self) -> int:
        return hash((type(self), self.structure_key, tuple(self.params)))

    def __repr__(self) -> str:
        shape = ", ".join(f"{v:g}" for v in self.shape_params)
        return f"{type(self).__name__}({shape}, A={self.A:g}, C={self.C:g})"


_LOCK = threading.Lock()
_THETA_FUNCS: dict[str, object] = {}
_SLOPE_FUNCS: dict[str, ca.Function] = {}


def _slope_function(body: Body) -> ca.Function:
    """(c, shape) -> (H, dH/dc), compiled once per body structure."""
    key = body.structure_key
    with _LOCK:
        if key not in _SLOPE_FUNCS:
            c, sh = ca.SX.sym("c"), ca.SX.sym("shape", body.n_shape)
            H = body.height(c, sh)
            _SLOPE_FUNCS[key] = ca.Function("height_slope", [c, sh], [H, ca.jacobian(H, c)])
        return _SLOPE_FUNCS[key]


def _theta_functions(body: Body):
    """(theta, shape) -> (h, h_theta, h_thetatheta), compiled once per body structure."""
    key = body.structure_key
    with _LOCK:
        if key in _THETA_FUNCS:
            return _THETA_FUNCS[key]
        th, sh = ca.SX.sym("theta"), ca.SX.sym("shape", body.n_shape)
        h = body.height(ca.cos(th), sh)
        h1 = ca.jacobian(h, th)
        f = ca.Function("h_theta_derivs", [th, sh], [h, h1, ca.jacobian(h1, th)])

        def evaluate(theta, shape):
            flat = np.atleast_1d(theta).ravel()
            out = f.map(flat.size)(flat[None, :], np.tile(np.asarray(shape, float)[:, None], (1, flat.size)))
            res = [np.asarray(o).reshape(np.shape(theta)) for o in out]
            return tuple(float(r) for r in res) if np.ndim(theta) == 0 else tuple(res)

        _THETA_FUNCS[key] = evaluate
        return evaluate


class MassProperties(NamedTuple):
    """Mass properties of the uniform solid bounded by a body's surface, per unit mass
    (lengths in b). ``z_centroid`` is the centroid's coordinate along k measured from the
    body's G (0 when G is the centroid); ``A`` is about the centroid."""

    volume: float
    z_centroid: float
    A: float
    C: float


def uniform_mass_properties(body: Body, n: int = 400) -> MassProperties:
    """Volume, centroid and moments of the uniform solid bounded by ``body``'s surface,
    computed from its support function alone.

    The contact point at inclination theta traces the meridian: relative to G it lies at
    z = h_t sin(theta) - h cos(theta) along k and at distance x_P = h sin(theta) + h_t cos(theta)
    from the axis, with dz/dtheta = (h + h_tt) sin(theta) >= 0 (from the pole at -k, theta = 0,
    to the pole at +k). Discs of radius x_P give V = pi int x_P^2 dz, C = (pi/2V) int x_P^4 dz and
    A = (pi/V) int x_P^2 (x_P^2/4 + (z - z_c)^2) dz. Gauss-Legendre quadrature in theta with
    ``n`` nodes (spectrally accurate for a smooth support function: 1e-14 for the spheroid).
    """
    x, wq = np.polynomial.legendre.leggauss(int(n))
    th = 0.5 * np.pi * (x + 1.0)
    wq = 0.5 * np.pi * wq
    h, h1, h2 = body.h(th)
    s, c = np.sin(th), np.cos(th)
    z = h1 * s - h * c
    r2 = (h * s + h1 * c) ** 2
    dz = wq * (h + h2) * s
    V = np.pi * np.sum(r2 * dz)
    zc = np.pi * np.sum(r2 * z * dz) / V
    C = 0.5 * np.pi * np.sum(r2 * r2 * dz) / V
    A = np.pi * np.sum(r2 * (0.25 * r2 + (z - zc) ** 2) * dz) / V
    return MassProperties(float(V), float(zc), float(A), float(C))


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


class CustomBody(Body):
    """A body from a user's support function, in a few lines::

        body = pk.CustomBody(lambda th: ca.sqrt(4 * ca.cos(th) ** 2 + ca.sin(th) ** 2))  # = Spheroid(2)

    Parameters
    ----------
    height : callable
        The height of G above the table as a CasADi expression: a function of theta
        (``variable="theta"``), or of c = cos(theta) (``variable="cos"``). Given in theta,
        the vector chart evaluates it at theta = acos(k_Z), whose derivative is singular
        exactly at theta = 0 and pi: give it in cos(theta) to work at the poles.
    A, C : float, optional
        Moments about G (units M b^2). Default: those of the uniform solid bounded by the
        surface (:func:`uniform_mass_properties`); this needs G at that solid's centroid
        (otherwise the density is not uniform and A, C must be given).
    name : str
        Shown in reports.

    The profile is checked for smoothness and convexity over [0, pi] (both radii of
    curvature > 0); a bad one raises ParameterError naming `height`.

    Examples
    --------
    >>> import phasekit as pk
    >>> import casadi as ca
    >>> b = pk.CustomBody(lambda c: ca.sqrt(2.25 * c**2 + 1 - c**2), A=0.65, C=0.4, variable='cos')
    >>> round(float(b.h(0.3)[0]), 6) == round(float(pk.Spheroid(1.5).h(0.3)[0]), 6)
    True
    """

    def __init__(self, height, A: float | None = None, C: float | None = None, *, variable: str = "theta",
                 name: str = "custom"):
        if not callable(height):
            raise ParameterError("height", "must be a function of theta (or of cos(theta)) returning a CasADi expression", height)
        if variable not in ("theta", "cos"):
            raise ParameterError("variable", "must be one of theta, cos", variable)
        self._fn, self.variable, self.name, self._key = height, variable, str(name), None
        try:
            self.structure_key
            scalar = ca.SX(self.height(ca.SX.sym("c"), ca.SX.sym("shape", 0))).numel() == 1
        except Exception as exc:  # the function is not CasADi-expressible
            raise ParameterError("height", f"must return a CasADi expression ({type(exc).__name__}: {exc})", show_value=False) from None
        if not scalar:
            raise ParameterError("height", "must return one scalar CasADi expression (the height of G)", show_value=False)
        self._check_operations()
        interior = (1e-6, np.pi - 1e-6) if variable == "theta" else (0.0, np.pi)
        self.check_convex("height", interior)
        if A is None or C is None:
            props = uniform_mass_properties(self)
            if abs(props.z_centroid) > 1e-9 * max(1.0, abs(self.h(0.0)[0])):
                raise ParameterError("A", f"and `C` are required: G is not the centroid of the solid (centroid at "
                                          f"{props.z_centroid:.6g} along k), so the density is not uniform",
                                     show_value=False)
            A = props.A if A is None else A
            C = props.C if C is None else C
        super().__init__(A, C)

    def _check_operations(self) -> None:
        """A profile with a kink (fabs, fmax, if_else, ...) is not smooth, whatever its values
        say at the sample points; one the Taylor integrator cannot compile is refused here,
        not at the first simulation."""
        from .._runtime.translate import operations

        c = ca.SX.sym("c")
        ops = operations(ca.Function("h", [c], [ca.SX(self.height(c, ca.SX.sym("shape", 0)))]))
        if ops["non_smooth"]:
            raise ParameterError("height", f"must be smooth: it uses {', '.join(sorted(ops['non_smooth']))} (kinks or jumps); "
                                           "write the profile with smooth functions", show_value=False)
        if ops["untranslated"]:
            raise ParameterError("height", f"uses {', '.join(sorted(ops['untranslated']))}, which the Taylor integrator cannot "
                                           "compile (use sqrt, exp, log, sin, cos, tan, their inverses, sinh, cosh, tanh, erf, "
                                           "powers)", show_value=False)

    @property
    def shape_params(self) -> tuple[float, ...]:
        return ()

    def height(self, c, shape):
        if self.variable == "cos":
            return self._fn(c)
        return self._fn(ca.acos(c))

    @property
    def structure_key(self) -> str:
        if getattr(self, "_key", None) is None:
            c = ca.SX.sym("c")
            f = ca.Function("H", [c], [self.height(c, ca.SX.sym("shape", 0))])
            self._key = "CustomBody:" + hashlib.sha256(f.serialize().encode()).hexdigest()[:16]
        return self._key

    def describe(self) -> str:
        return f"{self.name} body (custom support function, A={self.A:g}, C={self.C:g})"

    def __repr__(self) -> str:
        return f"CustomBody({self.name!r}, A={self.A:g}, C={self.C:g})"
