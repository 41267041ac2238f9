"""Bodies of revolution (``phasekit.bodies``): each is its support function h(theta), the height
of the centre of mass above the table, plus its moments A and C about G; every contact quantity
is derived from h.

Examples
--------
>>> import phasekit as pk
>>> body = pk.bodies.Spheroid(1.5)
>>> round(body.A, 3), round(body.C, 3)
(0.65, 0.4)
"""

from .body import Body
from .compound import TippeTop
from .cone import Cone
from .custom import CustomBody
from .edged import Disk
from .egg import Egg
from .spheroid import EccentricSphere, Spheroid

__all__ = ["Body", "Spheroid", "EccentricSphere", "Egg", "Disk", "Cone", "CustomBody", "TippeTop"]
