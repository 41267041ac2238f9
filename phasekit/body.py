"""The body: a flip-symmetric axisymmetric solid given by its height function and moments.

The height of the centre O above the table is written as a function of c = cos(theta),
``H(c)``, so that one definition serves both the Euler-angle chart (h(theta) = H(cos theta),
singular at theta = 0) and the vector chart, where c = k_Z is an ordinary variable.
For a flip-symmetric body H is even in c.

Units are the paper's: mass M, length b (the equatorial radius), time sqrt(b/g).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import casadi as ca
import numpy as np

from .errors import check_positive

__all__ = ["Body", "Spheroid"]


@dataclass(frozen=True)
class Body:
    """Base class: subclasses define :meth:`height_c` symbolically and the shape parameters.

    ``A`` is the transverse and ``C`` the axial principal moment of inertia about O.
    """

    A: float
    C: float

    # -- to be provided by subclasses --------------------------------------------------
    @property
    def shape_params(self) -> tuple[float, ...]:
        """Numbers that fix the shape (the aspect ratio for a spheroid)."""
        raise NotImplementedError

    @staticmethod
    def height_c(c, shape):
        """H(c): height of O above the table as a function of c = cos(theta) (CasADi SX)."""
        raise NotImplementedError

    # -- derived ------------------------------------------------------------------------
    @property
    def params(self) -> np.ndarray:
        """Shape parameters followed by (A, C): the body part of a model's parameter vector."""
        return np.array([*self.shape_params, self.A, self.C], dtype=float)

    @property
    def kind(self) -> str:
        return type(self).__name__

    def _check_moments(self) -> None:
        check_positive("A", self.A)
        check_positive("C", self.C)
        # The principal moments of a real body obey the triangle inequality, here C <= 2A.
        if self.C > 2 * self.A * (1 + 1e-12):
            raise ValueError(
                f"`C` must satisfy C <= 2A (triangle inequality of principal moments); "
                f"got A={self.A!r}, C={self.C!r}."
            )

    def h(self, theta):
        """h(theta), h'(theta), h''(theta) as floats (or arrays): exact derivatives via CasADi."""
        return _h_functions(type(self))(np.asarray(theta, dtype=float), self.shape_params)

    def height_slope(self, c: float) -> tuple[float, float]:
        """(H(c), H'(c)) with c = cos(theta): the height and its slope, regular at the poles."""
        H, dH = _H_slope_function(type(self))(float(c), self.shape_params)
        return float(H), float(dH)

    def __repr__(self) -> str:
        shape = ", ".join(f"{v:g}" for v in self.shape_params)
        return f"{self.kind}({shape}, A={self.A:g}, C={self.C:g})"


_H_CACHE: dict[type, object] = {}
_SLOPE_CACHE: dict[type, object] = {}


def _H_slope_function(cls: type[Body]):
    """Compile (c, shape) -> (H, dH/dc) once per body class."""
    if cls not in _SLOPE_CACHE:
        c = ca.SX.sym("c")
        sh = ca.SX.sym("shape", cls.n_shape)
        H = cls.height_c(c, sh)
        _SLOPE_CACHE[cls] = ca.Function("height_slope", [c, sh], [H, ca.jacobian(H, c)])
    return _SLOPE_CACHE[cls]


def _h_functions(cls: type[Body]):
    """Compile (theta, shape) -> (h, h_theta, h_thetatheta) once per body class."""
    if cls not in _H_CACHE:
        n_shape = cls.n_shape
        th = ca.SX.sym("theta")
        sh = ca.SX.sym("shape", n_shape)
        h = cls.height_c(ca.cos(th), sh)
        h1 = ca.jacobian(h, th)
        h2 = ca.jacobian(h1, th)
        f = ca.Function("h_theta_derivs", [th, sh], [h, h1, h2])

        def evaluate(theta, shape):
            flat = np.atleast_1d(theta).ravel()
            fm = f.map(flat.size)
            out = fm(flat[None, :], np.tile(np.asarray(shape, float)[:, None], (1, flat.size)))
            res = [np.asarray(o).reshape(np.shape(theta)) for o in out]
            if np.ndim(theta) == 0:
                res = [float(r) for r in res]
            return tuple(res)

        _H_CACHE[cls] = evaluate
    return _H_CACHE[cls]


@dataclass(frozen=True, repr=False)
class Spheroid(Body):
    """Spheroid with semi-axes (1, 1, a): prolate for a > 1, oblate for a < 1.

    Parameters
    ----------
    a : float
        Aspect ratio (polar over equatorial semi-axis), a > 0.
    A, C : float, optional
        Principal moments about O. Defaults are the uniform solid's, A = (1 + a^2)/5,
        C = 2/5 (units M b^2); override them for a non-uniform density whose centre of
        mass stays at the centre of volume.

    Examples
    --------
    >>> Spheroid(1.5).A
    0.65
    """

    a: float = field(default=1.0)
    n_shape = 1

    def __init__(self, a: float, A: float | None = None, C: float | None = None):
        a = check_positive("a", a)
        object.__setattr__(self, "a", a)
        object.__setattr__(self, "A", (1.0 + a * a) / 5.0 if A is None else A)
        object.__setattr__(self, "C", 0.4 if C is None else C)
        self._check_moments()
        object.__setattr__(self, "A", float(self.A))
        object.__setattr__(self, "C", float(self.C))

    @property
    def shape_params(self) -> tuple[float, ...]:
        return (self.a,)

    @property
    def uniform(self) -> bool:
        return abs(self.A - (1 + self.a**2) / 5) < 1e-15 and abs(self.C - 0.4) < 1e-15

    @staticmethod
    def height_c(c, shape):
        # (2.10): h = (a^2 cos^2 + sin^2)^(1/2) = (1 + (a^2 - 1) c^2)^(1/2)
        a = shape[0]
        return ca.sqrt(1 + (a * a - 1) * c * c)

    def __repr__(self) -> str:
        if self.uniform:
            return f"Spheroid(a={self.a:g})"
        return f"Spheroid(a={self.a:g}, A={self.A:g}, C={self.C:g})"
