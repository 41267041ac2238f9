"""What a run rests on besides the equations: the approximations it used (:func:`approximations_of`),
each an :class:`Approximation` with its bound, listed in ``Trajectory.approximations`` and in the JSON.

Each is read off the finished run (its law, options, modes and event log), so that only those the
run actually used are listed: a regularised law's width, its creep on the slow manifold, the
restart of sliding from zero slip, the stick located at a small slip, the held spin or roll of
the set-valued couples, the rest, the settle rule, the end of a bounce train, the minima of R
located on the Taylor expansion, a body lying flat on its face.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

from ..errors import Status
from .fields import CREEP_RATIO, HOLD_RATE, REST_SPEED, STICK_SLIP
from .hybrid import Mode
from .zero_slip import SLIP_ONSET


@dataclass(frozen=True)
class Approximation:
    """One approximation a run used.

    Attributes
    ----------
    name : str
        A short name ("regularised friction", "creep", ...).
    detail : str
        What it replaces and where it is documented.
    bound : float or None
        Its size where one number says it (a relative error, a speed, a width), else None.

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> traj = pk.simulate(pk.Model(body, pk.RegularisedCoulomb(0.1, 1e-4)), pk.gyroscopic_start(body, 1.5, omega0=3.0), 5.0)
    >>> all(isinstance(a, pk.core.Approximation) for a in traj.approximations)
    True
    """

    name: str
    detail: str
    bound: float | None = None

    def to_dict(self) -> dict:
        return asdict(self)


def _friction(traj) -> list[Approximation]:
    law, out = traj.model.friction, []
    names = [e.name for e in traj.events]
    if law.can_stick and not law.has_rolling_mode:
        out.append(Approximation("regularised friction", f"Coulomb friction regularised over a slip width eps = {law.eps:g}: "
                                 "F = -mu R u/sqrt(|u|^2 + eps^2) (docs/physics.md)", law.eps))
    if law.creeps and any(s.mode is Mode.ROLLING for s in traj.segments):
        out.append(Approximation("creep", "the slip below 10 eps followed on the law's slow manifold u* (Tikhonov's reduction, "
                                 "first order), where its relative error r/lambda stays below 1/100; entered by the law's "
                                 "fast transient as one impulse (docs/physics.md; off: SolverOptions(creep=False), CLI --no-creep)",
                                 1.0 / CREEP_RATIO))
    if law.has_rolling_mode and "stick" in names:
        out.append(Approximation("stick", f"a stick located where the slip falls to {STICK_SLIP:g} and extrapolated to its zero",
                                 STICK_SLIP))
    if law.has_rolling_mode and any(e.name == "slip" and e.mode_before.startswith("rolling") for e in traj.events):
        out.append(Approximation("slip onset", f"sliding from zero slip started at |u| = {SLIP_ONSET:g} (its t^2 growth from "
                                 "zero is stiff): a perturbation of that size per stick-slip cycle", SLIP_ONSET))
    for word, what in (("pivot", "the spin about the normal"), ("roll", "the rolling rate")):
        if f"{word} stick" in names:
            out.append(Approximation(f"{word} hold", f"{what} held at zero once it falls to {HOLD_RATE:g} (extrapolated to "
                                     "its zero; the couples are regularised below 1e-9)", HOLD_RATE))
    if "rest" in names:
        out.append(Approximation("rest", f"the body taken to rest once its motion falls to {REST_SPEED:g} (extrapolated to "
                                 "its zero)", REST_SPEED))
    return out


def _face(traj) -> list[Approximation]:
    """A run that lies flat (:mod:`phasekit.core.face`): the landing, the flat pose, the rest on the face."""
    face = getattr(traj, "face", None)
    if face is None:
        return []
    out = [Approximation("flat", "lying flat: the axis taken vertical (the tilt of the face-down angle dropped), the "
                         "pressure uniform over the face (docs/physics.md, 'A body on its face')",
                         min(face.contact.theta, 3.141592653589793 - face.contact.theta))]
    if traj.segments:
        out.append(Approximation("plastic landing", "at face down the normal velocity of G and the tilt rates lost, L_Z "
                                 "and v kept: the friction impulse during it, at most mu |v_z| (the event's detail), neglected"))
    if face.status is Status.REST:
        out.append(Approximation("rest on the face", f"sliding and spin taken to rest once sqrt(|v|^2 + a^2 w^2) falls to "
                                 f"{REST_SPEED:g} (extrapolated to zero)", REST_SPEED))
    return out


def approximations_of(traj) -> tuple[Approximation, ...]:
    """The approximations ``traj`` used, in a fixed order (module notes).

    Examples
    --------
    >>> import numpy as np, phasekit as pk
    >>> body = pk.Spheroid(1.5)
    >>> traj = pk.simulate(pk.Model(body, pk.RegularisedCoulomb(0.1, 1e-4)), pk.gyroscopic_start(body, 1.5, omega0=3.0), 5.0)
    >>> [a.name for a in traj.approximations]
    ['regularised friction', 'creep', 'minima of R']
    """
    out = _friction(traj) + _face(traj)
    if traj.status is Status.SETTLED:
        out.append(Approximation("settled", "ended one period into a roll, which repeats (docs/physics.md, 'A roll is "
                                 "periodic'): the state at two maxima of theta compared to 1e3 rtol", 1e3 * traj.options.rtol))
    details = [e.detail for e in traj.events if e.name == "impact"]
    if any("bounce train resolved" in d for d in details):
        out.append(Approximation("bounce tail", "a bounce train whose flights shrink geometrically summed at once "
                                 "(docs/architecture.md, Impacts): the state after it within 1e-3", 1e-3))
    if traj.restitution > 0 and any(e.name == "impact" and e.mode_after == "contact" for e in traj.events):
        out.append(Approximation("bounce stop", f"a rebound slower than {traj.options.bounce_stop:g} sqrt(g b) ends its "
                                 "bounce train: contact resumes", traj.options.bounce_stop))
    if traj.options.track_minima and traj.minima.size:
        out.append(Approximation("minima of R", "the minima of R located on each step's Taylor expansion of its integral "
                                 "(phasekit/core/engines/roots.py): |dR/dt| ~ 1e-10 there at rtol 1e-9"))
    return tuple(out)
