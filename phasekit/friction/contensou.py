"""Coulomb friction over a contact patch as the simulator's law: sliding and spin coupled (Contensou).

A body touches the table over a small disk of radius a, not at a point. Coulomb's law at every
point of the patch gives one force F and one couple M about the normal, both from the slip u of the
patch's centre and the spin w_n about the normal together (:mod:`phasekit.friction.patch`):

    F = R phi_F(u, w_n; a),   M = R phi_M(u, w_n; a).

Both are R times functions of the motion, so the patch enters the equations as one more wrench
affine in R (:class:`PatchTraction`: F at the contact point P, i.e. F at G plus r_P x F, and M e_Z),
and the contact constraint still fixes R by one linear equation (:mod:`phasekit.core.fields`). Its
power F.u + M w_n is the patch's own line of the energy budget.

What this changes against a point contact: while the contact pivots (w_n != 0), a small slip meets a
viscous force, F ~ -mu R k_v u/(a|w_n|) (k_v = 1 uniform, 3 pi/8 Hertz pressure), not the full mu R
(:data:`phasekit.friction.patch.PATCH_LIMITS`): a pivoting contact cannot stick, and the sliding force
and the spin couple never both reach their Coulomb values. The law is :class:`Contensou`; its
sliding force at the point is zero (the patch wrench carries the whole traction), so its model has
the SLIDING and FLIGHT modes only.

Approximations (named in :meth:`Contensou.describe` and docs/physics.md): the patch is a circle, of a
radius given, or (``curvature=True``) Hertz's radius under the weight following the principal radii
at the contact, a = a1 (rho1 rho2)^(1/6) (:func:`phasekit.friction.hertz.unit_patch_radius`; Hertz's
R^(1/3) is not followed along the run); the integrals over it are the rational approximant of
:func:`phasekit.friction.patch.patch_friction` (worst relative error 8.2e-6 over the whole (slip, spin)
plane, :data:`phasekit.friction.patch.APPROXIMANT_ERRORS`); at zero slip and zero spin together,
where the exact law is set-valued, a viscous floor of 1e-9 (a speed) stands for it; impacts use the
point contact's Coulomb impulse with the same mu.
"""

from __future__ import annotations

import copy

import casadi as ca
import numpy as np

from .._runtime.validate import check_choice, check_positive
from ..errors import ParameterError
from .dissipation import Dissipation, SpinFriction, check_dissipation
from .laws import FrictionLaw
from .patch import PRESSURES, patch_friction

#: the largest patch radius (units b): a patch as wide as the body is not a contact patch
RADIUS_MAX = 0.5


class PatchTraction(Dissipation):
    """The wrench of Coulomb friction over the patch: the force F at the contact point P and the
    couple M about the normal, from the slip of P and the spin about the normal.

    It needs the contact's geometry (``needs_contact_point``): the simulator passes
    :class:`phasekit.core.fields.ContactGeometry` (r_P, the vector from G to P, and the principal
    radii there) to :meth:`wrench_at`. Built by :class:`Contensou`; not to be combined with other
    laws by hand.

    Parameters
    ----------
    mu : float
        Friction coefficient, in [0, 1e3].
    radius : float
        Patch radius (units b), in (0, 0.5].
    pressure : {"hertz", "uniform"}, optional
        The pressure over the patch (default "hertz").

    Raises
    ------
    ParameterError
        If a value is out of range.

    Examples
    --------
    >>> from phasekit.friction.contensou import PatchTraction
    >>> PatchTraction(0.3, 0.004).describe()
    'patch(mu=0.3, radius=0.004, hertz)'
    """

    name = "patch"
    coefficients = ("mu", "radius")
    needs_contact_point = True

    def __init__(self, mu: float, radius: float, pressure: str = "hertz"):
        super().__init__(mu, check_positive("radius", radius, upper=RADIUS_MAX))
        self.pressure = check_choice("pressure", pressure, PRESSURES)

    def wrench(self, w, v, R, q, k):
        raise ParameterError("law", "the patch's wrench needs the contact's geometry: wrench_at(w, v, R, q, k, contact)",
                             show_value=False)

    def radius(self, q, contact):
        """The patch radius in the field: the coefficient itself (a fixed patch)."""
        return q[1]

    def wrench_at(self, w, v, R, q, k, contact):
        # v = (v_h, W): the contact point's vertical velocity is zero in contact, so u is horizontal
        r = contact.r
        u = (v + ca.cross(w, r))[0:2]
        F, M = patch_friction(u, w[2], q[0], R, self.radius(q, contact), pressure=self.pressure)
        f = ca.vertcat(F[0], F[1], 0)
        return f, ca.cross(r, f) + ca.vertcat(0, 0, M)

    def to_dict(self) -> dict:
        return {**super().to_dict(), "pressure": self.pressure}

    def describe(self) -> str:
        return f"patch(mu={self.values[0]:g}, radius={self.values[1]:g}, {self.pressure})"

    def __eq__(self, other) -> bool:
        return super().__eq__(other) and other.pressure == self.pressure

    def __hash__(self) -> int:
        return hash((type(self), self.values, self.pressure))

    def __repr__(self) -> str:
        return f"PatchTraction(mu={self.values[0]!r}, radius={self.values[1]!r}, pressure={self.pressure!r})"


class UniformPatchTraction(PatchTraction):
    """:class:`PatchTraction` under uniform pressure (a flat face): its own class, because the
    compiled equations differ (the model's structure names the class).

    Parameters
    ----------
    mu, radius : float
        As :class:`PatchTraction`.

    Examples
    --------
    >>> from phasekit.friction.contensou import UniformPatchTraction
    >>> UniformPatchTraction(0.3, 0.004).pressure
    'uniform'
    """

    def __init__(self, mu: float, radius: float, pressure: str = "uniform"):
        super().__init__(mu, radius, pressure)


class CurvedPatchTraction(PatchTraction):
    """:class:`PatchTraction` whose Hertz radius follows the body's curvature at the contact:
    a = radius (rho1 rho2)^(1/6), rho1, rho2 the principal radii there (units b), so ``radius`` is
    the patch of a contact whose radii are both b (Hertz: a ~ (R sqrt(rho1 rho2))^(1/3), at R = M g).

    Parameters
    ----------
    mu, radius : float
        As :class:`PatchTraction` (radius: at rho1 rho2 = 1).

    Examples
    --------
    >>> from phasekit.friction.contensou import CurvedPatchTraction
    >>> CurvedPatchTraction(0.3, 0.004).describe()
    'patch(mu=0.3, radius=0.004 (rho1 rho2)^(1/6), hertz)'
    """

    def radius(self, q, contact):
        # |rho1 rho2|^(1/6), smooth (the Taylor integrator takes no max): a body on the table is convex there
        return q[1] * (contact.radii * contact.radii + 1e-24) ** (1.0 / 12.0)

    def to_dict(self) -> dict:
        return {**super().to_dict(), "curvature": True}

    def describe(self) -> str:
        return f"patch(mu={self.values[0]:g}, radius={self.values[1]:g} (rho1 rho2)^(1/6), {self.pressure})"

    def __repr__(self) -> str:
        return super().__repr__()[:-1] + ", curvature=True)"


def patch_traction(mu: float, radius: float, pressure: str = "hertz", curvature: bool = False) -> PatchTraction:
    """The patch wrench of the pressure named (one class per kind: they compile differently)."""
    pressure = check_choice("pressure", pressure, PRESSURES)
    if curvature:
        if pressure != "hertz":
            raise ParameterError("pressure", "must be hertz for a patch that follows the curvature (Hertz's radius)",
                                 pressure)
        return CurvedPatchTraction(mu, radius)
    return UniformPatchTraction(mu, radius) if pressure == "uniform" else PatchTraction(mu, radius)


class Contensou(FrictionLaw):
    """Coulomb friction over a circular contact patch: the slip and the spin about the normal
    coupled (module notes).

    Parameters
    ----------
    mu : float
        Friction coefficient, in [0, 1e3].
    radius : float
        Patch radius (units b), in (0, 0.5]; from lengths and materials:
        :func:`phasekit.friction.hertz.hertz_radius` (SI) divided by the body's size b.
    pressure : {"hertz", "uniform"}, optional
        Hertz's elliptic pressure (a curved body on the table, default) or uniform (a flat face).
    curvature : bool, optional
        False (default): the radius is fixed. True: ``radius`` is Hertz's radius for principal radii
        of b (:func:`phasekit.friction.hertz.unit_patch_radius`) and the field scales it by
        (rho1 rho2)^(1/6) at the contact (Hertz pressure only; a smooth body: not a disk's rim).

    Raises
    ------
    ParameterError
        If a value is out of range, or :meth:`with_dissipation` is given spin friction (the patch's
        couple is the spin friction).

    Examples
    --------
    >>> import phasekit as pk
    >>> law = pk.Contensou(0.3, 0.004)
    >>> law.describe(), law.can_stick
    ('contensou(mu=0.3, radius=0.004, hertz)', False)
    """

    name = "contensou"

    def __init__(self, mu: float, radius: float, pressure: str = "hertz", *, curvature: bool = False):
        super().__init__(mu)
        self.dissipation = (patch_traction(self.mu, radius, pressure, bool(curvature)),)

    @property
    def curvature(self) -> bool:
        """Whether the radius follows the body's curvature at the contact."""
        return isinstance(self.patch, CurvedPatchTraction)

    @property
    def patch(self) -> PatchTraction:
        """The patch wrench (its radius: ``patch.values[1]``, its pressure: ``patch.pressure``)."""
        return self.dissipation[0]

    @property
    def radius(self) -> float:
        """The patch radius (units b)."""
        return self.patch.values[1]

    @staticmethod
    def sliding_force(u, mu, eps):
        # the point carries no force: the patch wrench (first of the dissipation laws) carries it all
        return ca.SX.zeros(3), ca.DM([0, 0, 1])

    def force(self, u: np.ndarray, R: float, spin: float = 0.0) -> np.ndarray:
        """The horizontal friction force for slip ``u`` (2,), normal reaction ``R`` and spin about
        the normal ``spin`` (units sqrt(g/b)): the patch's force, numerically.

        Parameters
        ----------
        u : array_like
            Slip of the patch's centre, shape (2,), units sqrt(g b).
        R : float
            Normal reaction, units M g.
        spin : float, optional
            Spin about the normal, units sqrt(g/b) (default 0).

        Returns
        -------
        numpy.ndarray
            Shape (2,), units M g.
        """
        us, ws = ca.SX.sym("u", 2), ca.SX.sym("w")
        F, _ = patch_friction(us, ws, self.mu, R, self.radius, pressure=self.patch.pressure)
        return np.asarray(ca.Function("F", [us, ws], [F])(np.asarray(u, float), spin)).ravel()

    def with_dissipation(self, *laws: Dissipation) -> "Contensou":
        """This law with rolling resistance, air drag or the air layer besides the patch.

        Parameters
        ----------
        *laws : Dissipation
            Each kind at most once; not spin friction (the patch's couple is the spin friction).

        Returns
        -------
        Contensou
            A copy carrying them after the patch.

        Examples
        --------
        >>> import phasekit as pk
        >>> pk.Contensou(0.3, 0.004).with_dissipation(pk.RollingResistance(0.01)).describe()
        'contensou(mu=0.3, radius=0.004, hertz) + rolling-resistance(delta=0.01)'
        """
        laws = check_dissipation(laws)
        for d in laws:
            if isinstance(d, (SpinFriction, PatchTraction)):
                raise ParameterError("dissipation", "must not hold spin friction or a patch with a patch law: the "
                                                    "patch's couple about the normal is its spin friction", d.describe())
        out = copy.copy(self)
        out.dissipation = (self.patch, *laws)
        return out

    def describe(self) -> str:
        extra = [d.describe() for d in self.dissipation[1:]]
        radius = f"{self.radius:g}" + (" (rho1 rho2)^(1/6)" if self.curvature else "")
        return " + ".join([f"{self.name}(mu={self.mu:g}, radius={radius}, {self.patch.pressure})", *extra])

    def to_dict(self) -> dict:
        out = {"law": self.name, "mu": self.mu, "slip_eps": None,
               "patch": {"radius": self.radius, "pressure": self.patch.pressure, "curvature": self.curvature}}
        if len(self.dissipation) > 1:
            out["dissipation"] = [d.to_dict() for d in self.dissipation[1:]]
        return out

    def __repr__(self) -> str:
        tail = f".with_dissipation({', '.join(map(repr, self.dissipation[1:]))})" if len(self.dissipation) > 1 else ""
        curved = ", curvature=True" if self.curvature else ""
        return f"Contensou(mu={self.mu!r}, radius={self.radius!r}, pressure={self.patch.pressure!r}{curved})" + tail
