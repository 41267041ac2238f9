"""Friction at the contact point (``phasekit.friction``): exact Coulomb with stick-slip, the
regularised Coulomb law, viscous friction and Coulomb friction over a contact patch
(:class:`Contensou`: sliding and spin coupled); a new law subclasses :class:`FrictionLaw`.
Besides sliding, rolling resistance, spin friction and air drag take energy out of the motion
(:meth:`FrictionLaw.with_dissipation`).

Examples
--------
>>> import phasekit as pk
>>> pk.friction.Coulomb(0.1).mu
0.1
"""

from .contensou import Contensou
from .dissipation import AirDrag, AirLayer, Dissipation, RollingResistance, SpinFriction
from .laws import Coulomb, FrictionLaw, RegularisedCoulomb, Viscous

__all__ = ["FrictionLaw", "Coulomb", "RegularisedCoulomb", "Viscous", "Contensou", "Dissipation", "RollingResistance", "SpinFriction",
           "AirDrag", "AirLayer"]
