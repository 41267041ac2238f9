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
    *rolling* mode (no-slip constraint) entered when the slip vanishes with the required
    friction <= mu R and left when it exceeds mu R: see :mod:`phasekit.modes`.
RegularisedCoulomb(mu, eps)
    F = -mu R u / sqrt(|u|^2 + eps^2): smooth, one mode, but stiff once the slip is
    below ~eps (its relaxation rate is ~mu/eps). eps is a velocity in units sqrt(g b).
Viscous(mu)
    F = -mu u (part I's "wet" friction), independent of R and smooth everywhere.
"""

from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np

from .errors import check_nonnegative, check_positive

__all__ = ["FrictionLaw", "Coulomb", "RegularisedCoulomb", "Viscous", "friction_law"]


@dataclass(frozen=True)
class FrictionLaw:
    """Base class. ``mu`` is the friction coefficient (Coulomb) or drag coefficient (viscous)."""

    mu: float

    #: whether zero slip is a separate (rolling) mode rather than a point of a smooth field
    has_rolling_mode = False
    name = "friction"

    def __post_init__(self):
        object.__setattr__(self, "mu", check_nonnegative("mu", self.mu))

    @property
    def eps(self) -> float:
        return 0.0

    @property
    def params(self) -> np.ndarray:
        """(mu, eps): the law's part of a model's parameter vector."""
        return np.array([self.mu, self.eps], dtype=float)

    @staticmethod
    def sliding_force(u, mu, eps):
        """Return (Fc0, d), each an SX 3-vector, with Fc = Fc0 + R d while sliding."""
        raise NotImplementedError

    def force(self, u: np.ndarray, R: float) -> np.ndarray:
        """Numeric horizontal friction force for slip ``u`` (2,) and normal reaction ``R``."""
        us = ca.SX.sym("u", 2)
        f0, d = self.sliding_force(us, self.mu, self.eps)
        f = ca.Function("F", [us], [(f0 + R * d)[:2]])
        return np.asarray(f(np.asarray(u, float))).ravel()

    def describe(self) -> str:
        return f"{self.name}(mu={self.mu:g})"


@dataclass(frozen=True)
class Coulomb(FrictionLaw):
    """Exact Coulomb friction: sliding with F = -mu R u/|u|, rolling when the slip vanishes."""

    has_rolling_mode = True
    name = "coulomb"

    @staticmethod
    def sliding_force(u, mu, eps):
        s = ca.sqrt(u[0] * u[0] + u[1] * u[1])
        return ca.SX.zeros(3), ca.vertcat(-mu * u[0] / s, -mu * u[1] / s, 1)


@dataclass(frozen=True)
class RegularisedCoulomb(FrictionLaw):
    """Coulomb friction with the slip speed regularised as sqrt(|u|^2 + eps^2)."""

    eps_: float = 1e-8
    name = "coulomb-regularised"

    def __init__(self, mu: float, eps: float = 1e-8):
        object.__setattr__(self, "mu", check_nonnegative("mu", mu))
        object.__setattr__(self, "eps_", check_positive("eps", eps))

    @property
    def eps(self) -> float:
        return self.eps_

    @staticmethod
    def sliding_force(u, mu, eps):
        s = ca.sqrt(u[0] * u[0] + u[1] * u[1] + eps * eps)
        return ca.SX.zeros(3), ca.vertcat(-mu * u[0] / s, -mu * u[1] / s, 1)

    def describe(self) -> str:
        return f"{self.name}(mu={self.mu:g}, eps={self.eps:g})"

    def __repr__(self) -> str:
        return f"RegularisedCoulomb(mu={self.mu!r}, eps={self.eps!r})"


@dataclass(frozen=True)
class Viscous(FrictionLaw):
    """Viscous ("wet") friction F = -mu u, independent of the normal reaction."""

    name = "viscous"

    @staticmethod
    def sliding_force(u, mu, eps):
        return ca.vertcat(-mu * u[0], -mu * u[1], 0), ca.DM([0, 0, 1])


def friction_law(name: str, mu: float, eps: float | None = None) -> FrictionLaw:
    """Build a law from its CLI name: ``coulomb`` (exact stick-slip, or regularised when
    ``eps`` is given) or ``viscous``."""
    if name == "coulomb":
        return Coulomb(mu) if eps is None else RegularisedCoulomb(mu, eps)
    if name == "viscous":
        if eps is not None:
            check_positive("eps", eps)
        return Viscous(mu)
    raise ValueError(f"`friction` must be one of coulomb, viscous; got {name!r}.")
