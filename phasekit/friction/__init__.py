"""Friction at the contact point (``phasekit.friction``): exact Coulomb with stick-slip, the
regularised Coulomb law and viscous friction; a new law subclasses :class:`FrictionLaw`.

Examples
--------
>>> import phasekit as pk
>>> pk.friction.Coulomb(0.1).mu
0.1
"""

from .laws import Coulomb, FrictionLaw, RegularisedCoulomb, Viscous

__all__ = ["FrictionLaw", "Coulomb", "RegularisedCoulomb", "Viscous"]
