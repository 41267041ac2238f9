"""The engines by name: :data:`ENGINES` (what ``SolverOptions.backend`` accepts besides "auto"),
:func:`engine_for` (one at given tolerances), :func:`register_engine` (add one) and
:func:`engine_names`.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial

from ...errors import ParameterError
from .cvodes import CvodesEngine
from .protocol import Engine
from .taylor import TaylorEngine

#: the engines ``SolverOptions.backend`` may name ("auto" besides): name -> factory(rtol, atol)
ENGINES: dict[str, Callable[..., Engine]] = {
    "taylor": TaylorEngine,
    "cvodes": CvodesEngine,
    "cvodes-adams": partial(CvodesEngine, method="adams"),
    "idas": partial(CvodesEngine, plugin="idas"),
}


def engine_names() -> tuple[str, ...]:
    """What ``SolverOptions.backend`` accepts: "auto" and every registered engine.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.core.engines.registry.engine_names()
    ('auto', 'taylor', 'cvodes', 'cvodes-adams', 'idas')
    """
    return ("auto", *ENGINES)


def register_engine(name: str, factory: Callable[..., Engine]) -> None:
    """Make an integrator available as ``SolverOptions(backend=name)``: ``factory(rtol, atol)``
    returns an :class:`~phasekit.core.engines.Engine`. Nothing else needs editing: simulate asks the engine whether it
    is pointwise, and the options accept every registered name.

    Parameters
    ----------
    name : str
        A new name (not "auto" or a registered one).
    factory : callable
        ``factory(rtol, atol)`` returns the engine.

    Raises
    ------
    ParameterError
        If ``name`` is empty, not a string, "auto" or already registered.

    Examples
    --------
    >>> import phasekit as pk
    >>> from phasekit.core.engines import registry
    >>> pk.core.engines.register_engine('cvodes-loose', lambda rtol, atol=None: pk.core.engines.cvodes.CvodesEngine(rtol, 1e-6))
    >>> pk.SolverOptions(backend='cvodes-loose').backend
    'cvodes-loose'
    >>> del registry.ENGINES['cvodes-loose']
    """
    if not isinstance(name, str) or not name or name == "auto" or name in ENGINES:
        raise ParameterError("name", "must be a new engine name (not 'auto' or one of "
                                     f"{', '.join(ENGINES)})", name)
    ENGINES[name] = factory


def engine_for(name: str, rtol: float, atol: float | None = None) -> Engine:
    """The engine called ``name`` (see :data:`ENGINES`) at these tolerances.

    Parameters
    ----------
    name : str
        A registered engine name.
    rtol : float
        Relative tolerance.
    atol : float, optional
        Absolute tolerance (the engine's default if None).

    Returns
    -------
    Engine
        ``ENGINES[name](rtol, atol)``.

    Raises
    ------
    ParameterError
        For an unknown name (parameter ``backend``); the message names the choices.

    Examples
    --------
    >>> import phasekit as pk
    >>> pk.core.engines.engine_for('taylor', 1e-9).name
    'taylor'
    >>> pk.core.engines.engine_for('rk4', 1e-9)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
        ...
    phasekit.errors.ParameterError: `backend` must be one of taylor, cvodes, cvodes-adams, idas, got 'rk4'.
    """
    if name not in ENGINES:
        raise ParameterError("backend", f"must be one of {', '.join(ENGINES)}", name)
    return ENGINES[name](rtol, atol)
