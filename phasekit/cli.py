"""Command line: ``phasekit <command> ... [--json]`` (also ``python -m phasekit``).

Every command prints one JSON object with ``--json``. Bad input prints one line,
``phasekit: error: ...``, on stderr and exits with status 2, never a traceback.
"""

from __future__ import annotations

import argparse
import json
import math
import re
import sys

import numpy as np

__all__ = ["main"]


class _Parser(argparse.ArgumentParser):
    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        # argparse's own pattern misses exponents, so "--state ... -1e-4 ..." would read
        # -1e-4 as an option; accept any negative float literal as a value.
        self._negative_number_matcher = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|nan)$", re.I)

    def error(self, message):  # one line, no usage block
        raise _UsageError(message)


class _UsageError(Exception):
    pass


def _json_default(obj):
    if isinstance(obj, (np.floating,)):
        return float(obj)
    if isinstance(obj, (np.integer,)):
        return int(obj)
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    return str(obj)


def _finite_json(obj):
    """Replace non-finite floats by None: JSON has no NaN, and we never pass one off as a number."""
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    if isinstance(obj, dict):
        return {k: _finite_json(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_finite_json(v) for v in obj]
    return obj


def _add_body(p):
    p.add_argument("--a", type=float, required=True, help="aspect ratio a > 0 (prolate a > 1, oblate a < 1)")
    p.add_argument("--A", dest="A", type=float, default=None, help="transverse moment (default (1+a^2)/5)")
    p.add_argument("--C", dest="C", type=float, default=None, help="axial moment (default 2/5)")


def _add_friction(p, default="coulomb"):
    p.add_argument("--mu", type=float, required=True, help="friction coefficient mu >= 0")
    p.add_argument("--friction", default=default, help="coulomb | viscous")
    p.add_argument(
        "--slip-eps",
        type=float,
        default=None,
        help="regularise Coulomb friction as -mu R u/sqrt(|u|^2+eps^2); default: exact stick-slip",
    )


def _build_parser() -> _Parser:
    parser = _Parser(prog="phasekit", description="Phase space of a spheroid spinning on a table.")
    sub = parser.add_subparsers(dest="command", parser_class=_Parser)

    sim = sub.add_parser("simulate", help="integrate the exact equations from a start")
    _add_body(sim)
    _add_friction(sim)
    start = sim.add_mutually_exclusive_group(required=True)
    start.add_argument("--state", type=float, nargs=6, metavar=("U", "V", "Omega", "Lambda", "theta", "n"))
    start.add_argument("--gyroscopic", action="store_true", help="start on the slow manifold")
    start.add_argument("--unstable-manifold", choices=None, metavar="horizontal|vertical",
                       help="start at fixed point + delta * unstable eigenvector")
    sim.add_argument("--delta", type=float, default=0.01, help="seed amplitude on the unstable manifold")
    sim.add_argument("--branch", default="+0", help="which unstable direction and sign (+0, -0, ...)")
    sim.add_argument("--seed-law", default="viscous", help="linearisation giving the direction: viscous | same")
    sim.add_argument("--theta0", type=float, default=None)
    sim.add_argument("--omega0", type=float, default=None)
    sim.add_argument("--n0", type=float, default=None)
    sim.add_argument("--t-end", type=float, default=200.0)
    sim.add_argument("--rtol", type=float, default=1e-9)
    sim.add_argument("--stop-at", default="jump", help="jump | touchdown | none")
    sim.add_argument("--restitution", type=float, default=0.0, help="Newton's e in [0, 1] at impacts (--stop-at none)")
    sim.add_argument("--formulation", default="auto", help="euler | vector | auto")
    sim.add_argument("--backend", default="auto", help="auto | taylor | cvodes | cvodes-adams | idas")
    sim.add_argument("--json", action="store_true")

    fx = sub.add_parser("fixed-points", help="steady states and their linear stability")
    _add_body(fx)
    _add_friction(fx, default="viscous")
    grp = fx.add_mutually_exclusive_group(required=True)
    grp.add_argument("--omega0", type=float)
    grp.add_argument("--n0", type=float)
    fx.add_argument("--json", action="store_true")

    gy = sub.add_parser("gyroscopic", help="gyroscopic mean solution theta-bar(t), Omega-bar(t) and J")
    _add_body(gy)
    gy.add_argument("--mu", type=float, required=True)
    g2 = gy.add_mutually_exclusive_group(required=True)
    g2.add_argument("--omega0", type=float)
    g2.add_argument("--n0", type=float)
    gy.add_argument("--theta0", type=float, required=True)
    gy.add_argument("--t", type=float, nargs="+", required=True, help="times (units sqrt(b/g))")
    gy.add_argument("--json", action="store_true")
    return parser


def _cmd_simulate(args) -> dict:
    from .api import simulate_start

    if args.unstable_manifold is not None:
        if args.theta0 is not None:
            raise ValueError("`theta0` does not go with --unstable-manifold (the fixed point fixes theta).")
        start = dict(kind="unstable-manifold", state=args.unstable_manifold, delta=args.delta, omega0=args.omega0,
                     n0=args.n0, branch=args.branch, seed_law=args.seed_law)
    elif args.gyroscopic:
        if args.theta0 is None:
            raise ValueError("`theta0` is required with --gyroscopic (a number in (0, pi)).")
        start = dict(kind="gyroscopic", theta0=args.theta0, omega0=args.omega0, n0=args.n0)
    else:
        if args.theta0 is not None or args.omega0 is not None or args.n0 is not None:
            raise ValueError("`theta0`, `omega0` and `n0` go with --gyroscopic, not with --state.")
        start = dict(kind="state", state=args.state)
    return simulate_start(
        a=args.a,
        A=args.A,
        C=args.C,
        mu=args.mu,
        friction=args.friction,
        slip_eps=args.slip_eps,
        start=start,
        t_end=args.t_end,
        rtol=args.rtol,
        stop_at=args.stop_at,
        restitution=args.restitution,
        formulation=args.formulation,
        backend=args.backend,
    )


def _cmd_fixed_points(args) -> dict:
    from .api import fixed_points_report

    return fixed_points_report(a=args.a, mu=args.mu, friction=args.friction, slip_eps=args.slip_eps, A=args.A, C=args.C,
                               omega0=args.omega0, n0=args.n0)


def _cmd_gyroscopic(args) -> dict:
    from .api import gyroscopic_report

    return gyroscopic_report(a=args.a, mu=args.mu, theta0=args.theta0, t=args.t, omega0=args.omega0, n0=args.n0, A=args.A, C=args.C)


def _print_human(out: dict) -> None:
    if "fixed_points" in out:
        for fp in out["fixed_points"]:
            st = ", ".join(f"{k}={'undefined' if v is None else f'{v:.8g}'}" for k, v in fp["state"].items())
            print(f"{fp['kind']:<13s} {fp['classification']:<45s} residual {fp['residual']:.1e}  [{st}]")
        return
    if "theta" in out and "Omega" in out:
        print(f"J = {out['J']:.10g} ({out['J_definition']}), {out['method']}")
        for t, th, om in zip(out["t"], out["theta"], out["Omega"]):
            print(f"t = {t:12.6g}   theta = {th:.12f}   Omega = {om:.12f}")
        return
    for key, val in out.items():
        if key == "events":
            print("events:")
            for e in val:
                print(f"  {e['kind']:<10s} t = {e['t']:.10g}  {e['mode_before']} -> {e['mode_after']}")
        elif isinstance(val, dict):
            print(f"{key}: " + ", ".join(f"{k}={v:.10g}" if isinstance(v, float) else f"{k}={v}" for k, v in val.items()))
        else:
            print(f"{key}: {val}")


COMMANDS = {"simulate": _cmd_simulate, "fixed-points": _cmd_fixed_points, "gyroscopic": _cmd_gyroscopic}


def main(argv=None) -> int:
    """Run the CLI; returns the exit status (0 success, 1 failed run, 2 bad input)."""
    parser = _build_parser()
    try:
        args = parser.parse_args(argv)
        if args.command is None:
            raise _UsageError("a command is required: " + ", ".join(COMMANDS))
        out = COMMANDS[args.command](args)
    except (_UsageError, ValueError) as exc:
        msg = " ".join(str(exc).split())
        print(f"phasekit: error: {msg}", file=sys.stderr)
        return 2
    out = _finite_json(out)
    if getattr(args, "json", False):
        print(json.dumps(out, default=_json_default))
    else:
        _print_human(out)
    return 1 if out.get("status") == "failed" else 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())


def main_entry() -> None:
    """Console-script entry point."""
    sys.exit(main())
