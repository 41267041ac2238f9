"""The spinning egg's questions (part IV of the series; a study-support module for studies/egg.py):
which end an egg rises onto from a start on its sliding branch, and its jump threshold from
its unstable horizontal-like state.

* :func:`egg_separatrix`: the predicted separatrix theta_h(Omega0), the horizontal-like steady
  precession (pi/2 for the symmetric egg); :func:`which_end_starts`, starts on both sides of it.
* :class:`EndRow` and :func:`which_end` (keyed by :func:`which_end_key`): one start, simulated
  until the egg rises onto an end, first sticks, or the time runs out; its end against the
  prediction. :func:`which_end_summary`: a set of rows against the prediction.
* :class:`EggDefinition`: the default sliding-branch threshold definition, or its start moved
  below the horizontal-like state.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

from ..bodies.egg import Egg
from ..core.hybrid import Event
from ..core.model import Model
from ..core.simulate import simulate
from ..core.starts import gyroscopic_start
from ..errors import Status
from ..friction.laws import Coulomb
from ..steady.precessions import horizontal_like_angle, precession_angles, side_equilibrium
from ..thresholds.definition import Definition


def egg_separatrix(egg, omega0: float) -> float | None:
    """The predicted separatrix between the starts that rise onto the fat end and those that
    rise onto the thin end: the horizontal-like steady precession theta_h(Omega0) of the egg
    (pi/2 for w = 0; None where it has none). It tends as Omega0 grows to theta_2, where
    (A - C) cos(theta) x_P + C h_theta = 0 (:func:`phasekit.steady.side_equilibrium`).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> round(ps.egg_separatrix(pk.Egg(57 / 43, 0.05), 6.0), 4), ps.egg_separatrix(pk.Egg(1.3, 0.0), 6.0)
    (1.7469, 1.5707963267948966)
    """
    if egg.w > 0:
        return horizontal_like_angle(egg, precession_angles(egg, omega0=omega0))
    return math.pi / 2


def which_end_starts(egg, omega0: float, offsets) -> list[float]:
    """Starts theta0 for :func:`which_end`: the separatrix (:func:`egg_separatrix`, or pi/2
    where there is none) plus each of ``offsets``, then pi/2 - 0.05 and pi/2 + 0.05 (both
    sides of the horizontal).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> [round(t, 3) for t in ps.which_end_starts(pk.Egg(1.3, 0.0), 6.0, [-0.1, 0.1])]
    [1.471, 1.671, 1.521, 1.621]
    """
    th_h = egg_separatrix(egg, omega0)
    return [(th_h if th_h is not None else math.pi / 2) + d for d in offsets] + [math.pi / 2 - 0.05, math.pi / 2 + 0.05]


@dataclass(frozen=True)
class EndRow:
    """One start of an egg on its sliding branch (:func:`which_end`), as stored: the separatrix
    theta_h and theta_2 (:func:`egg_separatrix`), the side of pi/2 it ends on (``end``: fat,
    thin or failed) and the predicted one, the angle it reached, how the run ended (``how``:
    rise-fat, rise-thin, settled: the slip first fell to the threshold, t_max, or failed),
    when, and the number of lift-offs.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> r = ps.EndRow("k", 0.0, 6.0, 1.5, 1.57, 1.57, "thin", "fat", 1.5, "settled", 0.5, 0, 0.1)
    >>> r.risen()
    'none'
    """

    key: str
    w: float
    omega0: float
    theta0: float
    theta_h: float | None  # the horizontal-like precession at omega0 (the predicted separatrix)
    theta_2: float
    end: str  # the side of pi/2 it ends on: fat | thin | failed (see risen())
    predicted: str
    theta_reached: float
    how: str  # rise-fat | rise-thin | settled | t_max | jumped | failed
    t: float
    n_liftoff: int
    wall_s: float

    def risen(self) -> str:
        """fat | thin, or "none" when the start's slip vanished at once (the egg stuck and rolls
        where it was put: within 0.05 rad of theta0), or "failed"."""
        if self.how == "settled" and abs(self.theta_reached - self.theta0) < 0.05:
            return "none"
        return self.end


def which_end_key(w: float, omega0: float, theta0: float, t_max: float) -> str:
    """The key of a stored :class:`EndRow`.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> ps.which_end_key(0.05, 6.0, 1.5, 400.0)
    'w=0.05|omega0=6|theta0=1.500000|t_max=400'
    """
    return f"w={w:g}|omega0={omega0:g}|theta0={theta0:.6f}|t_max={t_max:g}"


def which_end(a: float, w: float, omega0: float, theta0: float, *, t_max: float, mu: float = 0.1, rtol: float = 1e-9,
              first_stick: float = 1e-6) -> EndRow:
    """Which end the egg ``Egg(a, w)`` rises onto from the gyroscopic-balance (sliding) start
    at ``theta0`` and precession rate ``omega0`` under exact Coulomb friction ``mu``: the run
    (rtol ``rtol``, through flights) stops when theta comes within 0.1 of either pole, or when
    the slip first falls to ``first_stick`` (the egg rolls: it has come to rest on one end, or
    stuck where it was put), or at ``t_max``. Starts below the separatrix
    (:func:`egg_separatrix`) are predicted to rise onto the fat end (theta < pi/2).

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> r = ps.which_end(57 / 43, 0.05, 6.0, 1.0, t_max=20.0)
    >>> r.predicted, r.end, r.how
    ('fat', 'fat', 'settled')
    """
    t0 = time.perf_counter()
    egg = Egg(a, w)
    th_h = egg_separatrix(egg, omega0)
    y0 = gyroscopic_start(egg, theta0, omega0=omega0)
    events = [Event("theta", 0.1, direction=-1, name="rise-fat"), Event("theta", math.pi - 0.1, direction=+1, name="rise-thin"),
              Event("slip_speed", first_stick, direction=-1, name="settled")]
    r = simulate(Model(egg, Coulomb(mu)), y0, t_max, rtol=rtol, stop_at="none", events=events, track_minima=False,
                 max_wall=120.0)
    if r.status is Status.FAILED:
        how = "failed"
    elif r.status is Status.STOPPED:
        how = r.events[-1].name
    else:
        how = "t_max"
    theta_end = float(r.euler_end[4])
    end = "failed" if how == "failed" else ("fat" if theta_end < math.pi / 2 else "thin")
    predicted = "fat" if th_h is not None and theta0 < th_h else "thin"
    return EndRow(which_end_key(w, omega0, theta0, t_max), w, omega0, theta0, th_h, side_equilibrium(egg)[1], end, predicted,
                  theta_end, how, r.t, len(r.events_named("lift-off")), time.perf_counter() - t0)


def which_end_summary(rows, a: float, ws) -> dict:
    """:class:`EndRow` rows against the prediction: how many, how many rose onto an end, as
    predicted or not (keys), stuck at the start or failed (keys), and theta_2 of ``Egg(a, w)``
    for each w in ``ws``.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> r = ps.EndRow("k", 0.0, 6.0, 1.5, 1.57, 1.57, "fat", "fat", 0.1, "rise-fat", 50.0, 0, 0.1)
    >>> s = ps.which_end_summary([r], 1.3, [0.0])
    >>> s["rose"], s["as_predicted"], round(s["theta_2"]["0"], 4)
    (1, 1, 1.5708)
    """
    ok = [r for r in rows if r.risen() in ("fat", "thin")]
    return {"n": len(rows), "rose": len(ok), "as_predicted": sum(1 for r in ok if r.end == r.predicted),
            "not_as_predicted": [r.key for r in ok if r.end != r.predicted],
            "stuck_at_start": [r.key for r in rows if r.risen() == "none"],
            "failed": [r.key for r in rows if r.end == "failed"],
            "theta_2": {f"{w:g}": side_equilibrium(Egg(a, w))[1] for w in ws}}


@dataclass(frozen=True)
class EggDefinition(Definition):
    """The default sliding-branch threshold definition (its settle rule ends the runs that
    settle tilted). With ``from_horizontal_like`` the start is d below the horizontal-like
    precession theta_h(Omega0) (the egg's unstable state) instead of d below pi/2.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> d = ps.EggDefinition("egg", "sliding", from_horizontal_like=True)
    >>> model, y0 = d.start(pk.Egg(57 / 43, 0.05), 10.0)
    >>> round(float(y0[4]), 4)
    1.7314
    """

    from_horizontal_like: bool = False

    def start(self, body, value: float):
        if not self.from_horizontal_like or body.flip_symmetric:
            return super().start(body, value)
        th_h = horizontal_like_angle(body, precession_angles(body, omega0=value))
        y0 = gyroscopic_start(body, th_h - self.amplitude, omega0=value)
        return Model(body, self.friction(), "euler"), y0
