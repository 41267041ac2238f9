"""Poincare sections: the crossings of a level set by one trajectory, as a table.

A section is a non-terminal user :class:`phasekit.Event` (a guard on any observable,
a level and a direction), located by the integrator to its accuracy (for the Taylor method,
a root of each step's polynomial) while the run goes on. The crossings are evaluated on the
dense output, so the table has the columns of :meth:`phasekit.core.Trajectory.sample`.
"""

from __future__ import annotations

from .._runtime.validate import check_finite
from ..errors import ParameterError
from .hybrid import Event
from .simulate import simulate

#: the name under which the crossings of :func:`poincare` are recorded in ``traj.events``
SECTION_EVENT = "section"


def poincare(model, x0, t_end: float, *, on: str = "Lambda", value: float = 0.0, direction: int = +1,
             return_trajectory: bool = False, **simulate_kwargs):
    """The crossings of the section ``on = value`` (in ``direction``) by the trajectory from ``x0``.

    Parameters
    ----------
    model : Model
        The body, friction law and chart to integrate.
    x0 : array
        A start in ``model.chart``, as for :func:`phasekit.simulate`.
    t_end : float
        End of the run (it may end earlier: a jump, a stop event, a failure).
    on : str
        The observable of the section: a state variable ("Lambda", "theta", "U", ...) or any
        scalar of :data:`phasekit.core.OBSERVABLES` ("R", "energy", ...).
    value : float
        The level of the section.
    direction : -1, 0 or +1
        Upward crossings only (+1, the default: with ``on="Lambda"`` these are the minima of
        theta), downward only (-1), or both (0).
    return_trajectory : bool
        Also return the :class:`phasekit.core.Trajectory` (its ``status`` says how the run ended).
    **simulate_kwargs
        Passed to :func:`phasekit.simulate` (``stop_at``, ``events``, ``rtol``, ...).

    Returns
    -------
    pandas.DataFrame
        One row per crossing in time order, with the columns of :meth:`Trajectory.sample`;
        ``(DataFrame, Trajectory)`` with ``return_trajectory=True``. A start that lies on the
        section, moving in ``direction``, is the first crossing (t = t0).

    Raises
    ------
    ParameterError
        If ``dense`` or ``t_eval`` is given (poincare sets them), ``value`` is not finite,
        ``on`` or ``direction`` is invalid (as for :class:`phasekit.Event`), a user event is
        named "section", or an argument of :func:`phasekit.simulate` is invalid.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> x0 = pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5)
    >>> df = pk.core.poincare(pk.Model(body, pk.Coulomb(0.1)), x0, 20.0, on="Lambda", value=0.0)
    >>> bool((df["Lambda"].abs() < 1e-9).all())
    True
    """
    for key in ("dense", "t_eval"):
        if key in simulate_kwargs:
            raise ParameterError(key, "is set by poincare (it needs the dense output)", simulate_kwargs[key])
    value = check_finite("value", value)
    section = Event(on, value, direction=direction, terminal=False, name=SECTION_EVENT)
    user = tuple(simulate_kwargs.pop("events", ()))
    if any(getattr(e, "name", None) == SECTION_EVENT for e in user):
        raise ParameterError("events", f"must not use the name {SECTION_EVENT!r}, reserved for the section",
                             show_value=False)
    traj = simulate(model, x0, t_end, events=(*user, section), dense=True, **simulate_kwargs)
    times = [e.t for e in traj.events if e.name == SECTION_EVENT]
    df = traj.sample(times)
    return (df, traj) if return_trajectory else df
