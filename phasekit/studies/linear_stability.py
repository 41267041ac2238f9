"""Part I's linear-stability map of the steady states over (a, rate): :func:`stability_grid`
(studies/stability_map.py; a study-support module, drawn by
:func:`phasekit.studies.plot_stability_map`).
"""

from __future__ import annotations

import numpy as np

from .._runtime.validate import check_finite, check_positive


def _moments(A, C, a) -> tuple[float, float, float]:
    return check_positive("A", A), check_positive("C", C), check_positive("a", a)


def stability_grid(kind: str, a_values, rates, *, mu: float, progress=None) -> np.ndarray:
    """Part I's stability map of uniform spheroids under viscous friction ``mu``: the dimension
    of the unstable subspace (exact linearisation, :func:`phasekit.steady.linearise`) of the
    horizontal steady precession at Omega0 (``kind="horizontal"``) or of the vertical spin at n0
    (``kind="vertical"``), for every rate in ``rates`` (rows) and aspect ratio in ``a_values``
    (columns). ``progress``: a bar advanced by one column at a time.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> ps.stability_grid("vertical", [0.5, 2.0], [1.0, 12.0], mu=0.1).tolist()
    [[2, 2], [2, 0]]
    """
    from ..bodies.spheroid import Spheroid
    from ..core.model import Model
    from ..friction.laws import Viscous
    from ..steady.linearisation import linearise
    from ..steady.precessions import horizontal_state, vertical_state

    out = np.zeros((len(rates), len(a_values)), dtype=int)
    for j, a in enumerate(a_values):
        m = Model(Spheroid(a), Viscous(mu), "euler" if kind == "horizontal" else "vector")
        for i, s in enumerate(rates):
            x = horizontal_state(s) if kind == "horizontal" else vertical_state(s)
            out[i, j] = linearise(m, x, kind=kind).n_unstable
        if progress is not None:
            progress.update(len(rates))
    return out


def vertical_is_stable(A: float, C: float, a: float, n0: float) -> bool:
    """Linear stability of the vertical spin with friction: (a^2 C - A) n0^2 > a^3 (a^2 - 1).

    Parameters
    ----------
    A : float
        Transverse moment of inertia about the centre of mass G, units M b^2, finite > 0.
    C : float
        Axial moment of inertia about G, units M b^2, finite > 0.
    a : float
        Aspect ratio of the spheroid (polar over equatorial semi-axis), finite > 0.
    n0 : float
        Spin about the vertical, units sqrt(g/b), finite.

    Returns
    -------
    bool
        True iff (a^2 C - A) n0^2 > a^3 (a^2 - 1).

    Raises
    ------
    ParameterError
        If ``A``, ``C`` or ``a`` is not a finite number > 0, or ``n0`` is not finite.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> b = pk.Spheroid(0.6)
    >>> ps.vertical_is_stable(b.A, b.C, b.a, 0.5), ps.vertical_is_stable(b.A, b.C, b.a, 10.0)
    (True, False)
    """
    A, C, a = _moments(A, C, a)
    n0 = check_finite("n0", n0)
    return (a * a * C - A) * n0 * n0 > a**3 * (a * a - 1)


def horizontal_is_unstable(A: float, C: float, a: float, omega0: float) -> bool:
    """The horizontal steady precession has a (real, rising) unstable mode iff
    (a^2 C - A) Omega0^2 > a^2 - 1 (weak friction; see horizontal_stability_threshold).

    Parameters
    ----------
    A : float
        Transverse moment of inertia about the centre of mass G, units M b^2, finite > 0.
    C : float
        Axial moment of inertia about G, units M b^2, finite > 0.
    a : float
        Aspect ratio of the spheroid (polar over equatorial semi-axis), finite > 0.
    omega0 : float
        Precession rate Omega0 of the horizontal steady precession, units sqrt(g/b), finite.

    Returns
    -------
    bool
        True iff (a^2 C - A) Omega0^2 > a^2 - 1.

    Raises
    ------
    ParameterError
        If ``A``, ``C`` or ``a`` is not a finite number > 0, or ``omega0`` is not finite.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> b = pk.Spheroid(1.5)
    >>> ps.horizontal_is_unstable(b.A, b.C, b.a, 2.0), ps.horizontal_is_unstable(b.A, b.C, b.a, 10.0)
    (False, True)
    """
    A, C, a = _moments(A, C, a)
    omega0 = check_finite("omega0", omega0)
    return (a * a * C - A) * omega0 * omega0 > a * a - 1


# -- any body -------------------------------------------------------------------------------
