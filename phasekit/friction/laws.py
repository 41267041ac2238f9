"""Friction laws at the contact point P.

Every law is written so that, while the body slides, the contact force
Fc = (F_1, F_2, R) (horizontal friction, then normal reaction) is *affine in R*:

    Fc = Fc0(u) + R * d(u),

with u the slip velocity of P. The normal reaction then follows from one linear
equation (the contact constraint), which for Coulomb friction is the paper's (6.1).

Laws
----
Coulomb(mu)
    F = -mu R u/|u| while sliding (2.6). The exact treatment of zero slip is a separate
    ROLLING mode (no-slip constraint) entered when the slip vanishes with the required
    friction <= mu R and left when it exceeds mu R: see :mod:`phasekit.core.system`.
RegularisedCoulomb(mu, eps)
    F = -mu R u / sqrt(|u|^2 + eps^2): smooth, one vector field, but stiff once the slip is
    below ~eps (its relaxation rate is ~mu/eps). eps is a velocity in units sqrt(g b).
Viscous(mu)
    F = -mu u (part I's "wet" friction), independent of R and smooth everywhere.

A new law subclasses :class:`FrictionLaw` and implements :meth:`FrictionLaw.sliding_force`;
it then works everywhere a built-in law does (simulation, fixed points, thresholds).
"""

from __future__ import annotations

import copy
import warnings

import casadi as ca
import numpy as np

from .._runtime.validate import check_nonnegative, check_positive
from ..errors import ParameterError
from .dissipation import Dissipation, check_dissipation

#: friction coefficients above this are not friction but numerical trouble (and overflow R mu)
MU_MAX = 1e3
#: a regularised law whose slip relaxation rate mu/eps exceeds this can creep at zero slip on its slow
#: manifold (:attr:`FrictionLaw.creeps`; where the creep holds: phasekit.core.fields). Below it (eps =
#: 1e-3 at mu = 0.1) the manifold never attracts fast enough and the law keeps its own field.
CREEP_RATE = 500.0


class FrictionLaw:
    """Base class of friction laws.

    Parameters
    ----------
    mu : float in [0, 1e3]
        Friction coefficient (Coulomb laws) or drag coefficient (viscous).

    Required of a subclass
    ----------------------
    ``sliding_force(u, mu, eps)`` (static) -> (Fc0, d)
        CasADi 3-vectors with Fc = Fc0 + R d while sliding with slip ``u`` (2-vector).
    ``name`` (class attribute)
        Short name used in reports and JSON.
    ``has_rolling_mode`` (class attribute, default False)
        True when zero slip is a separate mode (exact Coulomb): the law must then be of the
        form d = (-mu u/|u|, 1) so that the static friction cone is mu R.

    Raises
    ------
    ParameterError
        If ``mu`` is not a finite number in [0, 1e3].

    Examples
    --------
    >>> import phasekit as pk
    >>> law = pk.Coulomb(0.1)
    >>> isinstance(law, pk.friction.FrictionLaw), law.can_stick
    (True, True)
    """

    has_rolling_mode = False
    #: True when the law's force is proportional to R (Coulomb-like): zero slip can stick
    can_stick = False
    name = "friction"
    #: the dissipation laws acting besides sliding (:meth:`with_dissipation`)
    dissipation: tuple[Dissipation, ...] = ()
    #: whether a stiff regularised law may creep on its slow manifold (:attr:`creeps`; :meth:`without_creep`)
    allow_creep: bool = True

    def __init__(self, mu: float):
        self.mu = check_nonnegative("mu", mu, upper=MU_MAX)

    @property
    def eps(self) -> float:
        """Slip-speed regularisation (0 for laws without one)."""
        return 0.0

    @property
    def params(self) -> np.ndarray:
        """(mu, eps, then each dissipation law's coefficients): the law's part of a model's
        parameter vector."""
        return np.concatenate([[self.mu, self.eps], *(d.params for d in self.dissipation)]).astype(float)

    @property
    def creeps(self) -> bool:
        """True for a regularised law stiff at zero slip (mu/eps > :data:`CREEP_RATE`): its ROLLING
        mode follows the slow manifold of its slip where that attracts fast, a non-stiff field
        (:mod:`phasekit.core.fields`)."""
        return (self.allow_creep and self.can_stick and not self.has_rolling_mode and self.eps > 0
                and self.mu / self.eps > CREEP_RATE)

    def without_creep(self) -> "FrictionLaw":
        """This law with its ROLLING mode its own field (the slip below 10 eps integrated as it is,
        stiff where mu/eps is large: CVODES takes it over there), not the creep's reduction.

        Examples
        --------
        >>> import phasekit as pk
        >>> law = pk.RegularisedCoulomb(0.1, 1e-4)
        >>> law.creeps, law.without_creep().creeps, law.without_creep().describe()
        (True, False, 'coulomb-regularised(mu=0.1, eps=0.0001, no creep)')
        """
        out = copy.copy(self)
        out.allow_creep = False
        return out

    @property
    def structure(self) -> tuple:
        """What the compiled equations depend on besides numbers: the law's class, the kinds of its
        dissipation laws, and "creep" when it :attr:`creeps`."""
        return (type(self), *(type(d) for d in self.dissipation), *(("creep",) if self.creeps else ()))

    def with_dissipation(self, *laws: Dissipation) -> "FrictionLaw":
        """This sliding law with rolling resistance, spin friction or air drag acting besides it.

        Parameters
        ----------
        *laws : Dissipation
            :class:`phasekit.RollingResistance`, :class:`phasekit.SpinFriction`,
            :class:`phasekit.AirDrag`, each at most once (they replace the ones already set).

        Returns
        -------
        FrictionLaw
            A copy of this law carrying them (:attr:`dissipation`).

        Raises
        ------
        ParameterError
            If a law is not a Dissipation, or a kind is given twice.

        Examples
        --------
        >>> import phasekit as pk
        >>> pk.Coulomb(0.2).with_dissipation(pk.SpinFriction(0.02)).describe()
        'coulomb(mu=0.2) + spin-friction(mu_s=0.02)'
        """
        out = copy.copy(self)
        out.dissipation = check_dissipation(laws)
        return out

    def _with_description(self, text: str) -> str:
        return " + ".join([text, *(d.describe() for d in self.dissipation)])

    @staticmethod
    def sliding_force(u, mu, eps):
        """Return (Fc0, d), each a CasADi 3-vector, with Fc = Fc0 + R d while sliding.

        Parameters
        ----------
        u : casadi.SX
            The slip velocity of the contact point P, a 2-vector (units sqrt(g b)).
        mu : float or casadi.SX
            The friction coefficient.
        eps : float or casadi.SX
            The slip-speed regularisation (0 for laws without one).

        Returns
        -------
        tuple
            (Fc0, d): CasADi 3-vectors (horizontal friction, then normal reaction), so that
            the contact force is Fc0 + R d while sliding.

        Raises
        ------
        NotImplementedError
            In the base class: a subclass must define it.
        """
        raise NotImplementedError("a FrictionLaw subclass must define sliding_force(u, mu, eps)")

    def force(self, u: np.ndarray, R: float) -> np.ndarray:
        """Numeric horizontal friction force for slip ``u`` (2,) and normal reaction ``R``.

        Parameters
        ----------
        u : array_like
            The slip velocity of the contact point, shape (2,), units sqrt(g b).
        R : float
            The normal reaction, units M g.

        Returns
        -------
        numpy.ndarray
            Shape (2,): the horizontal friction force (F_1, F_2), units M g.
        """
        us = ca.SX.sym("u", 2)
        f0, d = self.sliding_force(us, self.mu, self.eps)
        f = ca.Function("F", [us], [(ca.SX(f0) + R * ca.SX(d))[:2]])
        return np.asarray(f(np.asarray(u, float))).ravel()

    def describe(self) -> str:
        return self._with_description(f"{self.name}(mu={self.mu:g})")

    def to_dict(self) -> dict:
        out = {"law": self.name, "mu": self.mu, "slip_eps": self.eps if self.eps > 0 else None}
        if self.dissipation:  # absent without it: descriptions written before are unchanged
            out["dissipation"] = [d.to_dict() for d in self.dissipation]
        if not self.allow_creep:  # likewise
            out["creep"] = False
        return out

    def __eq__(self, other) -> bool:
        return (type(other) is type(self) and other.dissipation == self.dissipation
                and np.array_equal(other.params, self.params) and other.allow_creep == self.allow_creep)

    def __hash__(self) -> int:
        return hash((type(self), tuple(self.params), self.allow_creep))

    def __repr__(self) -> str:
        return f"{type(self).__name__}(mu={self.mu!r})" + self._repr_tail()

    def _repr_tail(self) -> str:
        return f".with_dissipation({', '.join(map(repr, self.dissipation))})" if self.dissipation else ""


class Coulomb(FrictionLaw):
    """Exact Coulomb friction: sliding with F = -mu R u/|u|, rolling when the slip vanishes.

    Parameters
    ----------
    mu : float
        Friction coefficient, in [0, 1e3].

    Raises
    ------
    ParameterError
        If ``mu`` is not a finite number in [0, 1e3].

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.Coulomb(0.1).describe()
    'coulomb(mu=0.1)'
    """

    has_rolling_mode = True
    can_stick = True
    name = "coulomb"

    @staticmethod
    def sliding_force(u, mu, eps):
        s = ca.sqrt(u[0] * u[0] + u[1] * u[1])
        return ca.SX.zeros(3), ca.vertcat(-mu * u[0] / s, -mu * u[1] / s, 1)


class RegularisedCoulomb(FrictionLaw):
    """Coulomb friction with the slip speed regularised as sqrt(|u|^2 + eps^2).

    Parameters
    ----------
    mu : float
        Friction coefficient, in [0, 1e3].
    eps : float, optional
        The regularisation, a slip speed in units sqrt(g b), in [1e-14, 1] (default 1e-8).

    Raises
    ------
    ParameterError
        If ``mu`` is not a finite number in [0, 1e3], or ``eps`` is not in [1e-14, 1] (below
        1e-14 the slip relaxation rate mu/eps exceeds what a double-precision integrator can
        follow).

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.RegularisedCoulomb(0.1, 1e-4).describe()
    'coulomb-regularised(mu=0.1, eps=0.0001)'
    """

    can_stick = True
    name = "coulomb-regularised"

    def __init__(self, mu: float, eps: float = 1e-8):
        super().__init__(mu)
        self._eps = check_positive("eps", eps, upper=1.0)
        if self._eps < 1e-14:
            raise ParameterError("eps", "must lie in [1e-14, 1] (below it the slip relaxation rate mu/eps exceeds "
                                        "what a double-precision integrator can follow)", eps)

    @property
    def eps(self) -> float:
        return self._eps

    @staticmethod
    def sliding_force(u, mu, eps):
        s = ca.sqrt(u[0] * u[0] + u[1] * u[1] + eps * eps)
        return ca.SX.zeros(3), ca.vertcat(-mu * u[0] / s, -mu * u[1] / s, 1)

    def describe(self) -> str:
        return self._with_description(f"{self.name}(mu={self.mu:g}, eps={self.eps:g}{'' if self.allow_creep else ', no creep'})")

    def __repr__(self) -> str:
        return f"{type(self).__name__}(mu={self.mu!r}, eps={self.eps!r})" + self._repr_tail()


class Viscous(FrictionLaw):
    """Viscous ("wet") friction F = -mu u, independent of the normal reaction.

    Parameters
    ----------
    mu : float
        Drag coefficient, in [0, 1e3].

    Raises
    ------
    ParameterError
        If ``mu`` is not a finite number in [0, 1e3].

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.Viscous(0.1).describe()
    'viscous(mu=0.1)'
    """

    name = "viscous"

    @staticmethod
    def sliding_force(u, mu, eps):
        return ca.vertcat(-mu * u[0], -mu * u[1], 0), ca.DM([0, 0, 1])


def friction_law(name: str, mu: float, eps: float | None = None) -> FrictionLaw:
    """Build a law from its CLI name: ``coulomb`` (exact stick-slip, or regularised when
    ``eps`` is given) or ``viscous`` (smooth at zero slip: an ``eps`` is checked, then ignored
    with a warning).

    Parameters
    ----------
    name : {"coulomb", "viscous"}
        The law's CLI name.
    mu : float
        Friction (or drag) coefficient, in [0, 1e3].
    eps : float, optional
        Slip-speed regularisation of the Coulomb law, in [1e-14, 1]; None (default): exact
        Coulomb friction.

    Returns
    -------
    FrictionLaw
        Coulomb, RegularisedCoulomb or Viscous.

    Raises
    ------
    ParameterError
        If ``name`` is not coulomb or viscous (the error names ``friction``), ``mu`` is not in
        [0, 1e3], or ``eps`` is not in [1e-14, 1] (for viscous friction: in (0, 1]).

    Warns
    -----
    UserWarning
        If ``eps`` is given with viscous friction.
    """
    if name == "coulomb":
        return Coulomb(mu) if eps is None else RegularisedCoulomb(mu, eps)
    if name == "viscous":
        if eps is not None:
            check_positive("eps", eps, upper=1.0)
            warnings.warn("`eps` has no effect with viscous friction (it regularises Coulomb friction only)", stacklevel=2)
        return Viscous(mu)
    raise ParameterError("friction", "must be one of coulomb, viscous", name)
