"""The base class of bodies, :class:`Body`: a convex body of revolution given by its support
function and its moments, and what is derived from the support function alone (its derivatives,
radii of curvature, convexity, the uniform solid's mass properties).

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
:class:`~phasekit.bodies.custom.CustomBody` with a function of theta or of cos(theta). The
built-in bodies: :mod:`phasekit.bodies.spheroid`, :mod:`phasekit.bodies.egg`. Units: mass M,
length b (the equatorial radius, or the sphere's radius), so A and C are in M b^2.
"""

from __future__ import annotations

import hashlib
import threading
from typing import NamedTuple

import casadi as ca
import numpy as np

from .._runtime.validate import check_positive
from ..errors import ParameterError


class Limit(NamedTuple):
    """One end of a body's valid range of theta (:attr:`Body.limits`): a run stops there with the
    event ``name``.

    ``direction`` is that of the guard cos(theta_limit) - cos(theta) as
    :class:`phasekit.core.Event` takes it: -1 as theta falls to the limit, +1 as it rises
    to it. ``reason`` is formatted with the time ``t`` of the event. ``face``: at a flat face coming
    down, (radius, inner ratio) of the face (units b; the ratio 0 for a full disk, r_i/r for an
    annulus), which a run with ``stop_at="rest"`` goes on to slide and spin on
    (:mod:`phasekit.core.face`); None (default) where the run ends.
    """

    name: str
    theta: float
    direction: int
    reason: str
    face: tuple | None = None


class PieceTransfer(NamedTuple):
    """Where the contact passes from one piece of a compound body to another
    (:attr:`Body.transfers`).

    ``theta`` is the switch angle, radians; ``direction`` that of the guard cos(theta) - ...
    as :class:`phasekit.core.Event` takes a theta event: +1 as theta rises through
    ``theta`` (from ``from_piece`` to ``to_piece``), -1 as it falls. ``name`` is the event's
    name in a run's log.
    """

    name: str
    theta: float
    direction: int
    from_piece: str
    to_piece: str


class Body:
    """Base class of bodies: a convex body of revolution given by its support function and its
    moments about G. Everything the rest of phasekit asks of a body is declared here, each
    capability with a default that suits a smooth body; the library asks the body, never probes it.

    A subclass

    1. sets ``A`` and ``C`` by calling ``Body.__init__(self, A, C)`` (the moments about G, units
       M b^2) once its shape is set;
    2. gives ``shape_params``, the tuple of numbers that fix the shape (compiled models take
       them as parameters, so bodies that differ only in them share one compiled model);
    3. gives ``height(c, shape)``: H(c), the height of G above the table at c =
       cos(theta), a CasADi expression in the symbol ``c`` and the symbols ``shape`` (one per
       shape parameter), smooth on [-1, 1] (or on its range, item 4), written with the operations
       of :mod:`phasekit.bodies.operations`;
    4. may give :attr:`theta_range`, the open range of theta on which the support function is
       the body's (default None: all of [0, pi], both poles states of the model), with
       :meth:`in_range`, and :attr:`limits`, the ends of that range where a run stops
       (:class:`Limit`; default none): a body with an edge or a tip
       (:class:`~phasekit.bodies.edged.EdgedBody`);
    5. may give :attr:`transfers`, where the contact passes from one piece to another
       (:class:`PieceTransfer`; default none): a body of several convex pieces, whose
       :meth:`height` switches between them with CasADi's ``if_else``
       (:mod:`phasekit.bodies.compound`);
    6. may give ``outline(n)``, the meridian as drawn (default: the one the support
       function traces, right for a smooth body; an edged body's traces only its rim);
    7. may give :meth:`describe` (a one-line description for reports; default the repr) and
       :meth:`to_dict` (what a JSON result records; default the class, the shape and the moments).

    Nothing else is needed: :func:`phasekit.simulate`, :func:`phasekit.steady_structure` and
    :func:`phasekit.viz.animate` take such a body as they take the built-in ones.

    Parameters
    ----------
    A, C : float
        Transverse and axial principal moments of inertia about the centre of mass G,
        in units M b^2, with C <= 2 A (triangle inequality of principal moments).

    Attributes
    ----------
    a : float
        The aspect ratio a threshold or a table records for the body (NaN, the default, when it
        has none; a spheroid's and an egg's own).

    Raises
    ------
    ParameterError
        If ``A`` or ``C`` is not a finite number > 0, or C > 2 A.

    Examples
    --------
    >>> import phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> isinstance(body, pk.bodies.Body), round(float(body.h(0.3)[0]), 6)
    (True, 1.463159)
    >>> body.theta_range, body.limits, body.transfers
    (None, (), ())
    """

    # the aspect ratio recorded for the body (Attributes above; NaN: none); a spheroid and an egg set their own
    a = float("nan")
    # caches: the structure key once computed, and whether the moments were checked
    _key: str | None = None
    _inertia_checked = False

    def __init__(self, A: float, C: float):
        self.A = check_positive("A", A)
        self.C = check_positive("C", C)
        if self.C > 2 * self.A * (1 + 1e-12):
            raise ParameterError("C", f"must satisfy C <= 2A (triangle inequality of principal moments; A = {self.A:g})", C)
        self._key = None

    # -- to be provided by subclasses ---------------------------------------------------------
    @property
    def shape_params(self) -> tuple[float, ...]:
        raise NotImplementedError(f"{type(self).__name__} must define `shape_params` (see phasekit.bodies.Body)")

    def height(self, c, shape):
        """H(c) as a CasADi expression in ``c`` and the symbols ``shape``.

        Parameters
        ----------
        c : casadi.SX
            The symbol c = cos(theta).
        shape : casadi.SX
            The symbols of the shape parameters, one per entry of :attr:`shape_params`.

        Returns
        -------
        casadi.SX
            The height of G above the table, units b.

        Raises
        ------
        NotImplementedError
            If a subclass does not define it.
        """
        raise NotImplementedError(f"{type(self).__name__} must define `height(c, shape)` (see phasekit.bodies.Body)")

    # -- the contract's capabilities, each with its default (items 4-6 of the class notes) --------
    @property
    def theta_range(self) -> tuple[float, float] | None:
        """(lo, hi), radians: the open range of theta where the support function is the body's;
        None (the default) for all of [0, pi], both poles states of the model."""
        return None

    @property
    def limits(self) -> tuple[Limit, ...]:
        """The ends of :attr:`theta_range` a run stops at, with their events' names and reasons
        (default: none)."""
        return ()

    @property
    def transfers(self) -> tuple[PieceTransfer, ...]:
        """Where the contact passes from one piece of the body to another, each watched as an event
        in every mode (default: none, a body of one piece)."""
        return ()

    def in_range(self, theta: float) -> bool:
        """True when ``theta`` is a state of this body's model (default: always).

        Parameters
        ----------
        theta : float
            The inclination, radians.

        Returns
        -------
        bool
        """
        return True

    def outline(self, n: int = 64) -> tuple[np.ndarray, np.ndarray]:
        """The meridian as drawn, (z, r) from the lower pole to the upper one: z along k from G,
        r from the axis, units b. The default is the curve the contact point traces, h_theta
        sin(theta) - h cos(theta) and h sin(theta) + h_theta cos(theta), at ``n`` angles.

        Parameters
        ----------
        n : int, optional
            The resolution: the angles of a smooth meridian (default 64); an outline made of
            parts gives each about a third of them.

        Returns
        -------
        tuple of numpy.ndarray
            (z, r).
        """
        th = np.linspace(0.0, np.pi, n)
        h, ht, _ = self.h(th)
        return ht * np.sin(th) - h * np.cos(th), np.clip(h * np.sin(th) + ht * np.cos(th), 0.0, None)

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
        if self._key is None:
            c, sh = ca.SX.sym("c"), ca.SX.sym("shape", self.n_shape)
            f = ca.Function("H", [c, sh], [self.height(c, sh)])
            digest = hashlib.sha256(f.serialize().encode()).hexdigest()[:16]
            self._key = f"{type(self).__qualname__}:{self.n_shape}:{digest}"
        return self._key

    def check_inertia(self) -> None:
        """Raise ParameterError naming `A` or `C` if a moment exceeds M r_max^2: all the mass
        lies within r_max = max |GP| of G (called when a Model is built: the shape is set
        after the moments in some bodies' constructors); once per body, as Models are built
        on the sweeps' hot path.

        Raises
        ------
        ParameterError
            If ``A`` or ``C`` exceeds M r_max^2.
        """
        if self._inertia_checked:
            return
        h, h1, _ = (np.asarray(v, dtype=float).ravel() for v in self.h(np.linspace(0.0, np.pi, 181)))
        r2 = float(np.max(h * h + h1 * h1)) * (1 + 1e-9)
        for name, value in (("A", self.A), ("C", self.C)):
            if value > r2:
                raise ParameterError(name, f"must be at most {r2:.6g} (M r_max^2: no point of the body is farther than "
                                           f"r_max = {np.sqrt(r2):.6g} from G)", value)
        self._inertia_checked = True

    def h(self, theta):
        """(h, h_theta, h_thetatheta) at theta (float or array), exact derivatives via CasADi.

        Parameters
        ----------
        theta : float or array_like
            Inclination of the symmetry axis from the vertical, radians.

        Returns
        -------
        tuple
            (h, h_theta, h_thetatheta), units b: floats for a number, arrays of the shape of
            ``theta`` otherwise.
        """
        return _theta_functions(self)(np.asarray(theta, dtype=float), self.shape_params)

    def height_slope(self, c: float) -> tuple[float, float]:
        """(H(c), H'(c)) with c = cos(theta): the height and its slope, regular at the poles.

        Parameters
        ----------
        c : float
            c = cos(theta), in [-1, 1].

        Returns
        -------
        tuple of float
            (H(c), dH/dc), units b.
        """
        H, dH = slope_function(self)(float(c), self.shape_params)
        return float(H), float(dH)

    def radii_of_curvature(self, theta):
        """Principal radii of curvature of the surface at the contact point for inclination
        theta: meridional h + h_tt and azimuthal x_P / sin(theta) (x_P = h sin + h_t cos,
        the distance of P from the axis). Both are > 0 on a strictly convex body.

        Parameters
        ----------
        theta : float or array_like
            Inclination of the symmetry axis from the vertical, radians.

        Returns
        -------
        tuple
            (meridional, azimuthal) radii, units b, of the shape of ``theta``; where
            abs(sin(theta)) <= 1e-6 (at a pole) the azimuthal radius is its limit, h + h_tt.
        """
        theta = np.asarray(theta, dtype=float)
        h, h1, h2 = self.h(theta)
        s = np.sin(theta)
        xP = h * s + h1 * np.cos(theta)
        with np.errstate(divide="ignore", invalid="ignore"):
            r2 = np.where(np.abs(s) > 1e-6, xP / np.where(s == 0, 1.0, s), h + h2)
        return h + h2, r2

    def check_convex(self, param: str = "height", theta_range: tuple[float, float] = (0.0, np.pi), n: int = 721) -> None:
        """Raise ParameterError (naming ``param``) unless the surface is smooth and strictly
        convex over ``theta_range``: finite h > 0 and both radii of curvature > 0.

        Parameters
        ----------
        param : str, optional
            The parameter the error names (default "height").
        theta_range : tuple of float, optional
            The interval of theta checked, radians (default (0, pi)).
        n : int, optional
            The number of angles sampled, uniformly, in ``theta_range`` (default 721).

        Raises
        ------
        ParameterError
            If, at a sampled angle, h is not finite or not > 0, or a radius of curvature is
            not > 0.
        """
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


def slope_function(body: Body) -> ca.Function:
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

    Parameters
    ----------
    body : Body
        The body whose surface bounds the solid.
    n : int, optional
        The number of Gauss-Legendre nodes (default 400).

    Returns
    -------
    MassProperties
        Volume (b^3), centroid along k from G (b), and A (about the centroid) and C per unit
        mass (b^2).
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
