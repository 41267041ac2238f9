"""What the CLI prints: a result as text or as strict JSON, and the one-line errors and warnings.

A result is made JSON-ready here (numpy types to Python's, a non-finite number found and
replaced by null); while a command computes, stdout is sent to stderr so that it holds the
result only.
"""

from __future__ import annotations

import contextlib
import json
import math
import os
import sys

from .flags import FLAGS, flags_in


def _fmt(v, spec: str = ".10g") -> str:
    return format(v, spec) if isinstance(v, float) else "undefined" if v is None else str(v)


def _end_text(e: dict) -> str:
    """A branch's end as the structure's text prints it (phasekit.steady.branches.BranchEnd)."""
    text = f"{e['kind']} at theta = {_fmt(e['theta'], '.10f')}"
    if e["kind"] == "pole":
        return text + f" (spin n = {_fmt(e['n'], '.8g')})"
    if e["kind"] == "switch":  # a compound body's switch: its piece's limits there
        return text + f" (the contact passes to the {e['to_piece']}; Omega = {_fmt(e['Omega'], '.8g')}, spin n = {_fmt(e['n'], '.8g')})"
    if e["kind"] == "limit":  # an edged body's range ends: the limits there (Omega diverges as a face comes down)
        lim = lambda k: "infinite" if k in e["diverges"] else _fmt(e[k], ".8g")  # noqa: E731
        return text + f" ({e['limit']}: {e['description']}; Omega = {lim('Omega')}, spin n = {lim('n')})"
    return text


def _on(item: dict) -> str:
    """", on the stem" for an item of a compound body's structure; "" on a one-piece body."""
    return f", on the {item['piece']}" if item.get("piece") else ""


def _print_structure(out: dict) -> None:
    print(f"signature: {out['signature']}   (linearisation: {out['linearised_law']})")
    if out.get("degenerate"):
        print(f"({out['degenerate']})")
    if out.get("note"):  # what the dissipation laws leave of the structure
        print(f"note: {out['note']}")
    for i, b in enumerate(out["branches"]):
        ends = " -> ".join(_end_text(e) for e in b["ends"])
        n_stable = sum(s["stable"] for s in b["samples"])
        piece = f" (on the {b['piece']})" if b.get("piece") else ""
        print(f"branch {i + 1}{piece}: {ends}; {len(b['samples'])} samples, {n_stable} stable")
        for c in b["stability_changes"]:
            print(f"  stability changes at theta = {_fmt(c['theta'], '.9f')} ({c['kind']}; n_unstable "
                  f"{c['n_unstable_below']} -> {c['n_unstable_above']}; Omega = {_fmt(c['Omega'], '.6g')}, "
                  f"n = {_fmt(c['n'], '.6g')})")
    for st in out["static_equilibria"]:
        print(f"static equilibrium at theta = {_fmt(st['theta'], '.10f')} ({st['kind']}{_on(st)}): {st['static_stability']}")
    for f in out["families"]:
        side = lambda v: "not computed" if v is None else "stable" if v else "unstable"  # noqa: E731
        crit = ("no change of stability: " + side(f["stable_on_intervals"][0])) if not f["criticals"] else (
            f"stability changes at |{f['parameter']}| = {', '.join(_fmt(c, '.10g') for c in f['criticals'])}; "
            f"{side(f['stable_above_critical'])} above")
        what = {"pole": "spin about the vertical", "precession": "precession", "rolling": "straight rolling"}[f["kind"]]
        sliding = f.get("sliding_criticals")
        if sliding is not None:  # exact Coulomb: the rolling criterion above, the sliding one beside it
            crit += "; under sliding friction " + (f"it changes at |n| = {', '.join(_fmt(c, '.10g') for c in sliding)}"
                                                    if sliding else "no spin is stable")
        print(f"{what} family at theta = {_fmt(f['theta'], '.6f')} (any {f['parameter']}{_on(f)}): {crit}"
              + ("; a branch meets it there" if f["branch_meets"] else ""))
    if out.get("states"):
        for fp in out["states"]:
            print(f"state at {out['states_at']}: {fp['kind']} theta = {_fmt(fp['state']['theta'], '.10f')}: "
                  f"{fp['classification']}")


def _print_cache(out: dict) -> None:
    if out["directory"] is None:
        print("the disk cache is off ($PHASEKIT_CACHE is empty): every process compiles its integrators")
        return
    verb = "deleted" if out["cleared"] else "holds"
    mb = lambda part: f"{out[part]['files']} files, {out[part]['bytes'] / 1e6:.1f} MB"  # noqa: E731
    print(f"{out['directory']} {verb}: compiled integrators {mb('integrators')} (limit "
          f"{out['integrators_limit_bytes'] / 2**30:g} GiB: the least recently used go first); heyoka's object code "
          f"{mb('heyoka')} (limit {out['heyoka_limit_bytes'] / 2**30:g} GiB: heyoka trims it as it adds to it)")


def _print_contact(out: dict) -> None:
    """The tilt's change and the time without slip, in words that hold for every body (theta is
    the axis's angle from the upward vertical: "rose" and "sank" mean opposite things for an egg
    and a disk), the passage over the horizontal, the contact's passages between pieces, and
    what a run that ends rolling rests on."""
    if out.get("theta_start") is None:
        return
    change, start, end = out["theta_change"], out["theta_start"], out["theta_end"]
    # a change at rounding level (a steady state held) is no change
    turned = "did not change" if abs(change) <= 1e-9 else "grew" if change > 0 else "fell"
    over = " (the axis passed the horizontal)" if (start - math.pi / 2) * (end - math.pi / 2) < 0 else ""
    stick = out.get("t_first_stick")
    by = "" if turned == "did not change" else f" by {abs(change):.4g} rad"
    print(f"theta {turned}{by}, {start:.6g} -> {end:.6g}{over}; "
          f"{out.get('holding', 'rolling without slip')} {100 * (out['rolling_fraction'] or 0.0):.1f}% of the run"
          + (f", first from t = {_fmt(stick, '.6g')}" if stick is not None else " (it never stuck)"))
    for line in _passage_lines(out.get("passages") or (), out.get("piece_end")):
        print(line)
    if out.get("rests_on"):
        print(out["rests_on"])


#: at most this many passages of the contact are listed one a line; more are said in one line
PASSAGES_LISTED = 4


def _passage_lines(passages, piece_end=None) -> list[str]:
    """The contact's passages between a compound body's pieces ("ball -> stem at t = 17.15"): each
    on its line, or, when it rocks across the switch many times, one line with their count and the
    first and last times (the JSON lists them all); then the piece it ends on, from its tilt at the
    end (a bounce train at the switch can end without a passage of its own)."""
    if len(passages) <= PASSAGES_LISTED:
        lines = [f"the contact passed {p}" for p in passages]
    else:
        moves = [p.partition(" at t = ") for p in passages]
        first, last = moves[0], moves[-1]
        pieces = " and ".join(dict.fromkeys(x.strip() for m in moves for x in m[0].split("->")))
        lines = [f"the contact passed between the {pieces} {len(passages)} times, first {first[0]} at t = {first[2]}, "
                 f"last {last[0]} at t = {last[2]} (--json lists every passage)"]
    if passages and piece_end:
        lines.append(f"at the end it is on the {piece_end}")
    return lines


def _print_energy(out: dict) -> None:
    """With dissipation laws: one line for the energy (start, end, what was lost and by which law),
    in mJ with --si and --mass, else in M g b; and, with --si, the time of rest in seconds (the
    status line gives it in phasekit's units)."""
    si = out.get("si") or {}
    budget, unit = (si["energy_budget"], "mJ") if si.get("energy_budget") else (out.get("energy_budget"), "M g b")
    if budget:
        laws = ", ".join(f"{law} {_fmt(e, '.4g')}" for law, e in budget["dissipated"].items())
        print(f"energy: {_fmt(budget['energy_start'], '.8g')} -> {_fmt(budget['energy_end'], '.8g')} {unit}, lost "
              f"{_fmt(budget['lost'], '.6g')}: {laws}, at events {_fmt(budget['at_events'], '.4g')} (balance residual "
              f"{_fmt(budget['residual'], '.2g')}, largest along the run {_fmt(budget['residual_max'], '.2g')})"
              + (" (give --mass for mJ)" if si and unit != "mJ" else ""))
    if si.get("t_rest") is not None:
        print(f"at rest at t = {_fmt(si['t_rest'] / 1e3, '.6g')} s")
    if out.get("post_run"):
        print(out["post_run"]["reason"])


def print_human(out: dict, events: bool) -> None:
    if "cleared" in out:
        _print_cache(out)
        return
    if ("signature" in out or "fixed_points" in out) and out.get("status") == "failed":
        print(f"status: failed ({out.get('reason') or 'the computation could not continue'})")
    if "signature" in out:
        _print_structure(out)
        return
    if "fixed_points" in out:
        _print_fixed_points(out)
        return
    if "J" in out:
        print(f"J = {_fmt(out['J'])} ({out['J_definition']}), {out['method']}")
        for t, th, om in zip(out["t"], out["theta"], out["Omega"]):
            print(f"t = {_fmt(t, '12.6g')}   theta = {_fmt(th, '.12f')}   Omega = {_fmt(om, '.12f')}")
        return
    print(f"status: {out['status']}" + (f" ({out['reason']})" if out.get("reason") else ""))
    if out.get("animation"):
        an = out["animation"]
        speed = f", {an['playback_speed']:.3g}x real time" if an.get("playback_speed") else ""
        print(f"wrote {an['path']}: {an['frames']} frames of {an['frame_size'][0]}x{an['frame_size'][1]} pixels"
              f"{speed}, {an['bytes'] / 1e6:.2f} MB")
    for key in ("t_jump", "t_stop", "t_end", "theta_end", "R_min", "mode_end"):
        if out.get(key) is not None:
            print(f"{key}: {_fmt(out[key])}")
    _print_contact(out)
    if out.get("face"):  # lying flat (phasekit.core.face): when the sliding and the spin stopped
        f = out["face"]
        print(f"on its face from t = {_fmt(f['t_start'])}: stopped sliding at t = {_fmt(f['t_stop_slide'])}, "
              f"spinning at t = {_fmt(f['t_stop_spin'])} (v/(r w) then {_fmt(f['ratio_end'], '.6g')})")
    _print_energy(out)
    if out.get("flight"):
        print("first flight: " + ", ".join(f"{k}={_fmt(v)}" for k, v in out["flight"].items()))
    if (out.get("flight_summary") or {}).get("n_flights"):
        print(_flights_line(out["flight_summary"], out["t_end"] - out.get("t0", 0.0), "", "b"))
    if out.get("pose_end"):
        print("pose at the end: " + ", ".join(f"{k}={_fmt(v, '.8g')}" for k, v in out["pose_end"].items()))
    if out.get("si"):
        _print_real_units(out["si"])
    if out.get("approximations"):
        print("approximations: " + "; ".join(a["name"] + ("" if a["bound"] is None else f" ({_fmt(a['bound'], '.2g')})")
                                            for a in out["approximations"]))
    if out.get("verification"):
        print(f"verified: {out['verification']['detail']}")
    print(f"{out['n_events']} events, {out['n_steps']} steps, {out['chart']} chart, {out['backend']}"
          + ("" if events else " (list the events with --events)"))
    print(f"computed in {_wall_clock(out['wall_s'])} of wall-clock time")
    if events:
        for e in out["events"]:
            print(f"  {e['kind']:<12s} t = {_fmt(e['t'])}  {e['mode_before']} -> {e['mode_after']}"
                  + (f"  ({e['detail']})" if e.get("detail") else ""))


def _print_fixed_points(out: dict) -> None:
    """The fixed-points command's result: each state, its classification and residual."""
    print(f"linearisation: {out['linearised_law']} ({out['stability']})")
    for fp in out["fixed_points"]:
        st = ", ".join(f"{k}={_fmt(v, '.8g')}" for k, v in fp["state"].items())
        line = f"{fp['kind']:<15s} {fp['classification']}; residual {_fmt(fp['residual'], '.1e')}  [{st}]"
        crit = (fp.get("parameter") or {}).get("stable_under_sliding_friction")
        if crit is not None:
            line += f"; closed-form criterion under sliding friction: {'stable' if crit else 'unstable'}"
            if fp["parameter"].get("rolling_critical_spin") is not None:  # G at its highest: the fast-top condition
                line += (f", rolling: {'stable' if fp['parameter']['stable_rolling'] else 'unstable'} (fast-top "
                         f"condition |n| > {_fmt(fp['parameter']['rolling_critical_spin'], '.8g')})")
        print(line)
    print(f"({out['note']})")


def _print_real_units(si: dict) -> None:
    """A run's times, first flight and end state in real units (--si)."""
    u = si["units"]
    print(f"in real units (b = {si['b']}, g = {si['g']}, time unit {si['time_unit']}):")
    for key in ("t_jump", "t_stop", "t_end"):
        if si.get(key) is not None:
            print(f"  {key}: {_fmt(si[key], '.6g')} {u['time']}")
    fl = si.get("flight")
    if fl:
        print(f"  first flight: from {_fmt(fl['t_liftoff'], '.6g')} {u['time']}, lasting "
              f"{_fmt(fl.get('duration'), '.4g')} {u['time']}, largest gap "
              f"{_fmt(fl['gap_max'], '.4g')} {u['length']}")
    if (si.get("flight_summary") or {}).get("n_flights"):
        span = si["t_end"] - (si.get("t0") or 0.0)
        print("  " + _flights_line(si["flight_summary"], span, f" {u['time']}", u["length"]))
    if si.get("state_end"):
        st = si["state_end"]
        print(f"  at the end: Omega={_fmt(st['Omega'], '.5g')} {u['rate']}, n={_fmt(st['n'], '.5g')} {u['rate']}")


def _flights_line(fs: dict, span: float, time_unit: str, length_unit: str) -> str:
    """Every flight of a run on one line (Trajectory.flight_summary), times in ``time_unit``
    (empty: phasekit's, written t = ...) and the gap in ``length_unit``."""
    def at(t):
        return f"{_fmt(t, '.6g')}{time_unit}" if time_unit else f"t = {_fmt(t, '.6g')}"

    def dur(t):
        return f"{_fmt(t, '.4g')}{time_unit}"

    n, frac = fs["n_flights"], fs.get("airborne_fraction")
    line = (f"flights: {n}, {'the first ' if n > 1 else ''}lifting off at {at(fs['t_first_liftoff'])}; airborne "
            f"{dur(fs['t_airborne'])} of {dur(span)}" + (f" ({100 * frac:.3g}% of the run)" if frac is not None else "")
            + f"; longest flight {dur(fs['longest_flight'])} (from {at(fs['t_longest_flight'])})")
    if fs.get("gap_max") is not None:
        line += f"; largest gap {_fmt(fs['gap_max'], '.4g')} {length_unit} at {at(fs['t_gap_max'])}"
    return line


def _wall_clock(seconds: float) -> str:
    """A wall-clock duration in a unit that reads well: ms below a second, s above, minutes too
    past two of them."""
    if seconds * 1e3 < 999.5:  # (not "1e+03 ms")
        return f"{seconds * 1e3:.3g} ms"
    if seconds < 120.0:
        return f"{seconds:.1f} s"
    return f"{seconds:.0f} s ({seconds / 60:.1f} min)"


def nonfinite(obj, path: str = "") -> str | None:
    """The path of the first non-finite float in a JSON-ready object, or None."""
    if isinstance(obj, float):
        return None if math.isfinite(obj) else path or "(top)"
    if isinstance(obj, dict):
        items = obj.items()
    elif isinstance(obj, (list, tuple)):
        items = ((f"[{i}]", v) for i, v in enumerate(obj))
    else:
        return None
    for k, v in items:
        found = nonfinite(v, f"{path}.{k}" if isinstance(obj, dict) and path else f"{path}{k}")
        if found:
            return found
    return None


def finite_json(obj):
    """Replace non-finite floats by None: JSON has no NaN, and we never pass one off as a number."""
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    if isinstance(obj, dict):
        return {k: finite_json(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [finite_json(v) for v in obj]
    return obj


def plain_types(obj):
    """numpy scalars and arrays -> Python floats, ints, lists (so that every check sees them)."""
    import numpy as np

    if isinstance(obj, dict):
        return {k: plain_types(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [plain_types(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return plain_types(obj.tolist())
    if isinstance(obj, (bool, np.bool_)):
        return bool(obj)
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, np.floating):
        return float(obj)
    return obj


def json_default(obj):
    return str(obj)


@contextlib.contextmanager
def stdout_to_stderr():
    """While computing, send everything written to stdout (Python or C++ libraries) to stderr,
    so that stdout holds only the result."""
    sys.stdout.flush()
    try:
        fd = sys.stdout.fileno()
    except (AttributeError, OSError, ValueError):  # no real file (e.g. captured in tests)
        with contextlib.redirect_stdout(sys.stderr):
            yield
        return
    saved = os.dup(fd)
    try:
        os.dup2(sys.stderr.fileno(), fd)
        with contextlib.redirect_stdout(sys.stderr):
            yield
    finally:
        sys.stdout.flush()
        os.dup2(saved, fd)
        os.close(saved)


def print_error(message: str, flag: str | None, as_json: bool, code: int = 2, names: dict = FLAGS) -> int:
    """One line on stderr; with --json one object on stdout: status "error" (bad input) with the
    flag, or "failed" / "interrupted" with its reason."""
    message = " ".join(flags_in(str(message), names).split())
    print(f"phasekit: error: {message}", file=sys.stderr)
    if as_json:
        status = "error" if code == 2 else "interrupted" if code == 130 else "failed"
        out = {"status": status, "parameter": flag, "message": message}
        print(json.dumps(out if code == 2 else {**out, "reason": message}))
    return code


def show_warning(message, category, filename, lineno, file=None, line=None, names: dict = FLAGS):
    print(f"phasekit: warning: {' '.join(flags_in(str(message), names).split())}", file=sys.stderr)
