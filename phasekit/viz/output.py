"""Figures off-screen (:func:`pyplot`), each written whole at once (:func:`save_figure`)."""

from __future__ import annotations

from pathlib import Path

from ..io import atomic_path


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


def save_figure(fig, path, *, dpi: int = 130, **savefig_kwargs) -> Path:
    """Save a matplotlib figure atomically (see :func:`phasekit.io.atomic_path`) and close it.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    path : path-like
        The file; its suffix gives the format (png if it has none).
    dpi : int, optional
        Resolution, dots per inch.
    **savefig_kwargs
        Go to ``Figure.savefig`` (e.g. ``bbox_inches="tight"``).

    Returns
    -------
    pathlib.Path
        ``path``.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from phasekit.viz import pyplot, save_figure
    >>> fig, ax = pyplot().subplots()
    >>> save_figure(fig, pathlib.Path(tempfile.mkdtemp()) / "line.png").name
    'line.png'
    """
    import matplotlib.pyplot as plt

    path = Path(path)
    fmt = path.suffix.lstrip(".") or "png"
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=dpi, format=fmt, **savefig_kwargs)
    plt.close(fig)
    return path
