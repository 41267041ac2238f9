"""The table of events, generated from the declarations in ``phasekit/core/system.py``: the hybrid
system of each friction law and stop rule is declared (``system.declare``), and every event it
holds becomes a row. The only hand-written part is what each *internal* guard function means
(``GUARDS``); a guard without an entry there fails the docs build."""

from __future__ import annotations

import inspect
import re

from .fmt import table
from .registry import group

LAWS = ("exact Coulomb", "regularised Coulomb", "viscous", "with dissipation laws")
STOPS = ("jump", "touchdown", "none", "rest")  # system.STOP_AT


def _guards():
    from phasekit.core import cone_edge as e
    from phasekit.core import fields as m

    return {
        "stick_guard": f"|u| = {m.STICK_SLIP:g} + 10 eps (the slip speed; eps = 0 for exact Coulomb)",
        "stick_guard_sq": f"|u|^2 = ({m.STICK_SLIP_POINTWISE:g} + 10 eps)^2 (its square, for pointwise integrators)",
        "margin_rolling": "mu^2 R^2 - |F_req|^2 = 0: the friction rolling needs reaches mu R",
        "unstick_guard": "|u| = 100 eps",
        "rest_guard": f"sqrt(|w|^2 + |v|^2) = {m.REST_SPEED:g} (the speed of the whole motion)",
        "pivot_guard": f"|w_Z| = {m.HOLD_RATE:g} (the spin about the normal)",
        "pivot_margin_sliding_no_pivot": "mu_s^2 R^2 - tau^2 = 0: the couple holding w_Z = 0 reaches mu_s R",
        "pivot_margin_rolling_no_pivot": "mu_s^2 R^2 - tau^2 = 0 (rolling, the spin about the normal held)",
        "margin_rolling_no_pivot": "mu^2 R^2 - |F_req|^2 = 0 (rolling with the spin about the normal held)",
        "roll_guard": f"|w_h| = {m.HOLD_RATE:g} (the rolling part of the angular velocity)",
        "roll_margin_sliding_no_roll": "delta^2 R^2 - |tau|^2 = 0: the couple holding w_h = 0 reaches delta R",
        "roll_margin_pivoting": "delta^2 R^2 - |tau|^2 = 0 (pivoting in place, the rolling held)",
        "margin_pivoting": "mu^2 R^2 - |F_req|^2 = 0 (pivoting in place without slip)",
        "edge_stick": f"u.e* = -{e.EDGE_STICK:g} (on the cone's edge, the slip along its direction e* returns to zero)",
        "edge_out": f"|u| = {e.EDGE_OUT:g} (the slip has left the cone's edge)",
        "edge_in": f"|u| = {e.EDGE_IN:g} with the friction rolling needs within about {e.EDGE_BAND:g} of mu R "
                   "(the slip returns onto the cone's edge)",
    }


def _laws():
    import phasekit as pk

    return {
        "exact Coulomb": pk.Coulomb(0.1),
        "regularised Coulomb": pk.RegularisedCoulomb(0.1, 1e-3),
        "viscous": pk.Viscous(0.1),
        "with dissipation laws": pk.Coulomb(0.1).with_dissipation(pk.SpinFriction(0.01), pk.RollingResistance(0.01),
                                                                 pk.AirDrag(rotation=0.001)),
    }


def _markdown(doc: str) -> str:
    """A docstring's reStructuredText roles and literals as Markdown code."""
    doc = re.sub(r":\w+:`~?([^`]+)`", r"`\1`", doc)
    return doc.replace("``", "`")


def _first_line(obj) -> str:
    doc = inspect.getdoc(type(obj)) or type(obj).__name__
    return _markdown(doc.split("\n\n")[0].replace("\n", " "))


def _outcome(ev) -> str:
    if ev.reset is None:
        return f"stop, status `{ev.stop.value}`" if ev.terminal else "recorded, the run goes on"
    inner = getattr(ev.reset, "inner", None)  # a reset wrapped by Held (spin friction, rolling resistance)
    if inner is not None:
        return (f"`{type(inner).__name__}`: {_first_line(inner)} Then `Held`: a contact mode entered with the "
                "spin about the normal (or the rolling) stopped and holdable becomes the mode with it held.")
    return f"`{type(ev.reset).__name__}`: {_first_line(ev.reset)}"


def declared_events():
    """(law, stop_at, system, event) for every event ``system.declare`` declares, plus a user's
    event (``pk.Event("theta", 0.4)``)."""
    import phasekit as pk
    from phasekit.core import system

    body = pk.Spheroid(1.5)
    out = []
    for law_name, law in _laws().items():
        model = pk.Model(body, law)
        for stop in STOPS:
            sys_ = system.declare(model, stop_at=stop)
            out += [(law_name, stop, sys_, ev) for ev in sys_.events]
        sys_ = system.declare(model, events=[pk.Event("theta", 0.4)])
        out.append((law_name, "user", sys_, sys_.events[-1]))
    return out


def _integrators(sys_, ev) -> set[str]:
    """Which integrators watch ``ev`` (``system.watched``: the Taylor method or pointwise ones)."""
    from phasekit.core import system
    from phasekit.core.engines.cvodes import CvodesEngine
    from phasekit.core.engines.taylor import TaylorEngine

    found = set()
    for engine, cls, label in (("taylor", TaylorEngine, "Taylor"), ("cvodes", CvodesEngine, "pointwise (CVODES, IDAS)")):
        for f in sys_.flows:  # a flow that names its integrator (flight: Taylor) is run by it alone
            if getattr(f, "engine", None) in (None, engine) and ev in system.watched(sys_, f.mode, cls):
                found.add(label)
    return found


ORDER = ("lift-off", "stick", "slip", "edge out", "edge in", "pivot stick", "pivot slip", "roll stick", "roll slip", "rest", "touchdown",
         "a user's event")


def event_table() -> str:
    from phasekit.core import observables as m
    from phasekit.core.hybrid import Mode

    guards = _guards()
    rows: dict[tuple, dict] = {}
    for law, stop, sys_, ev in declared_events():
        key = ("a user's event", "") if stop == "user" else (ev.name, ev.on)
        r = rows.setdefault(key, {"ev": ev, "laws": [], "outcomes": {}, "engines": set()})
        if law not in r["laws"]:
            r["laws"].append(law)
        r["outcomes"].setdefault(_outcome(ev), {}).setdefault(law, set()).add(stop)
        r["engines"] |= _integrators(sys_, ev)
    lines = []
    for (name, on), r in sorted(
        rows.items(), key=lambda kv: ORDER.index(kv[0][0]) if kv[0][0] in ORDER else len(ORDER)
    ):
        ev = r["ev"]
        if not on:
            guard = (
                f'any observable minus a level (e.g. `pk.Event("{ev.on}", {ev.level:g})`), in either direction '
                "unless `direction` is -1 or +1"
            )
        elif on in guards:
            guard = guards[on]
        elif on in m.OBSERVABLES:
            guard = f"{on} = {ev.level:g} ({m.OBSERVABLES[on]})"
        else:
            raise KeyError(
                f"the event {name!r} watches the guard {on!r}, which docs/_ext/pkdocs/events.py does not describe"
            )
        if on:
            guard += {-1: ", downward", 1: ", upward", 0: ""}[ev.direction]
        if ev.arm_after:
            guard += f", armed {ev.arm_after:g} after the mode starts"
        modes = "all" if ev.modes is None else ", ".join(mo.value for mo in Mode if mo in ev.modes)
        laws = "all" if len(r["laws"]) == len(LAWS) else ", ".join(r["laws"])
        outs = []
        for text, by_law in r["outcomes"].items():
            law_names = [law for law in LAWS if law in by_law]
            stops = sorted(set().union(*by_law.values()), key=(*STOPS, "user").index)
            who = "" if len(law_names) == len(r["laws"]) else ", ".join(law_names) + ": "
            when = "" if set(stops) >= set(STOPS) or stops == ["user"] else f"`--stop-at {'/'.join(stops)}`: "
            outs.append(who + when + text)
        engines = "both" if len(r["engines"]) == 2 else ", ".join(sorted(r["engines"]))
        lines.append([f"{name} (`{on}`)" if on else name, guard, modes, laws, engines, "; ".join(outs)])
    return table(
        [
            "event (guard function)",
            "fires when",
            "watched in",
            "friction laws",
            "integrators",
            "reset or outcome (`phasekit/core/resets.py`)",
        ],
        lines,
    )


@group("events")
def _events(src) -> dict:
    """The event table, as the group ``events`` (``events.table``): from the code, not from ``src``."""
    return {"table": event_table()}
