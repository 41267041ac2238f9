"""Figures off-screen; written atomically by :func:`phasekit.viz.save_figure` (re-exported here)."""

from __future__ import annotations

from ..sweep.study import save_figure

__all__ = ["pyplot", "save_figure"]


def pyplot():
    """matplotlib.pyplot with the off-screen Agg backend.

    Returns
    -------
    module
        ``matplotlib.pyplot``, after ``matplotlib.use("Agg")``.

    Examples
    --------
    >>> from phasekit.viz import pyplot
    >>> pyplot().get_backend().lower()
    'agg'
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt
