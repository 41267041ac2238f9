"""A user's body: :class:`CustomBody`, from a support function written as a CasADi expression in
theta or in cos(theta), checked for smoothness and convexity, with the moments of the uniform
solid by default (:func:`phasekit.bodies.body.uniform_mass_properties`)."""

from __future__ import annotations

import hashlib

import casadi as ca
import numpy as np

from ..errors import ParameterError
from .body import Body, uniform_mass_properties


class CustomBody(Body):
    """A body from a user's support function, in a few lines::

        body = pk.CustomBody(lambda th: ca.sqrt(4 * ca.cos(th) ** 2 + ca.sin(th) ** 2))  # = Spheroid(2)

    The profile is checked for smoothness and convexity over [0, pi] (both radii of
    curvature > 0); a bad one raises ParameterError naming `height`.

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
    variable : {"theta", "cos"}, keyword-only
        The variable of ``height``: theta (the default) or c = cos(theta).
    name : str
        Shown in reports (default "custom").

    Raises
    ------
    ParameterError
        If ``height`` is not callable, does not return one scalar CasADi expression, is not
        smooth (fabs, fmax, if_else, ...), uses an operation the Taylor integrator cannot
        compile, or gives a surface that is not smooth and strictly convex; if ``variable`` is
        neither "theta" nor "cos"; if ``A`` or ``C`` is omitted while G is not the centroid of
        the solid (the error names ``A``); or if ``A`` or ``C`` is not a finite number > 0, or
        C > 2 A.

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
        from .operations import operations

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
        if self._key is None:
            c = ca.SX.sym("c")
            f = ca.Function("H", [c], [self.height(c, ca.SX.sym("shape", 0))])
            self._key = "CustomBody:" + hashlib.sha256(f.serialize().encode()).hexdigest()[:16]
        return self._key

    def describe(self) -> str:
        return f"{self.name} body (custom support function, A={self.A:g}, C={self.C:g})"

    def __repr__(self) -> str:
        return f"CustomBody({self.name!r}, A={self.A:g}, C={self.C:g})"
