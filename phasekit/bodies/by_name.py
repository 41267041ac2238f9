"""The built-in bodies by name (:func:`make_body`): what the CLI's ``--body`` and a model read back
from its description (:meth:`phasekit.Model.from_dict`) build."""

from __future__ import annotations

from .._runtime.validate import check_choice
from ..errors import ParameterError
from .body import Body
from .compound import TippeTop
from .cone import Cone
from .edged import Disk
from .egg import Egg
from .spheroid import EccentricSphere, Spheroid

#: the built-in bodies, by the name the CLI's --body and a model's description use
BODIES = ("spheroid", "tippe-top", "egg", "disk", "cone")


def make_body(kind: str = "spheroid", *, a=None, offset=None, w=None, thickness=None, height=None, on=None,
              stem_length=None, stem_radius=None, flat_angle=None, A=None, C=None) -> Body:
    """A built-in body by name: ``spheroid`` (a, offset), ``tippe-top`` (offset; with ``stem_length``
    or ``stem_radius``, over the ball's radius, the top with its stem,
    :class:`~phasekit.bodies.compound.TippeTop`, the other one at its default; without them the
    ball alone), ``egg`` (a, w), ``disk`` (thickness, over the radius; default 0, a thin disk;
    ``flat_angle``, default :data:`~phasekit.bodies.edged.FLAT_ANGLE`),
    ``cone`` (height over the base's radius, default 1; on "rim" or "tip", default "rim") (the
    CLI's ``--body``, and :meth:`Model.from_dict`)."""
    check_choice("body", kind, BODIES)
    given = {"a": a, "offset": offset, "w": w, "thickness": thickness, "height": height, "on": on,
             "stem_length": stem_length, "stem_radius": stem_radius, "flat_angle": flat_angle}
    allowed = {"spheroid": ("a", "offset"), "tippe-top": ("offset", "stem_length", "stem_radius"), "egg": ("a", "w"),
               "disk": ("thickness", "flat_angle"), "cone": ("height", "on")}[kind]
    for name, value in given.items():
        if value is not None and name not in allowed:
            raise ParameterError(name, f"does not apply to the {kind} body (its parameters: {', '.join(allowed)})", value)
    if kind == "spheroid":
        if a is None:
            raise ParameterError("a", "is required for the spheroid body (aspect ratio, > 0)", show_value=False)
        return Spheroid(a, A=A, C=C, offset=0.0 if offset is None else offset)
    if kind == "tippe-top":
        if offset is None:
            raise ParameterError("offset", "is required for the tippe-top body (centre of mass below the centre, in [0, 1))",
                                 show_value=False)
        if stem_length is not None or stem_radius is not None:
            stem = {k: v for k, v in (("stem_length", stem_length), ("stem_radius", stem_radius)) if v is not None}
            return TippeTop(offset, A=A, C=C, **stem)
        return EccentricSphere(offset, A=A, C=C)
    if kind == "disk":
        flat = {} if flat_angle is None else {"flat_angle": flat_angle}
        return Disk(0.0 if thickness is None else thickness, A=A, C=C, **flat)
    if kind == "cone":
        return Cone(1.0 if height is None else height, "rim" if on is None else on, A=A, C=C)
    return Egg(1.3 if a is None else a, 0.0 if w is None else w, A=A, C=C)
