"""Drawing. Nothing here imports a plotting library at import time: pyvista is imported only
when a 3-D scene is drawn (:func:`render_scene`)."""

from .pv import RenderInfo, render_scene

__all__ = ["render_scene", "RenderInfo"]
