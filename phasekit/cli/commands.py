"""The subcommands: one function per command, from parsed arguments to a JSON-ready dict.

Each calls the CLI's parameter layer (:mod:`phasekit.cli.params`) with the inputs built by
:mod:`phasekit.cli.inputs`; :data:`COMMANDS` maps a command's name to its function.
"""

from __future__ import annotations

import warnings

from .inputs import _apply_units, _body, _law_args, _paper_body, _pose_of, _start_of
from .parser import _UsageError


def _cmd_simulate(args) -> dict:
    from .params import simulate_start

    scale = _apply_units(args)
    out = _simulate_args(args, simulate_start)
    if args.si:
        from .params import real_units_report

        out["si"] = real_units_report(out, scale)
    return out


def _cmd_animate(args) -> dict:
    """Simulate as `simulate` does, then write the movie (or film strip) of the run."""
    from ..viz.animate import animate, check_movie_options, film_strip
    from .params import run_start

    scale = _apply_units(args)
    if args.timing == "real" and scale is None:
        raise _UsageError("--timing real needs --size (the body's unit of length, e.g. --size '21.5 mm').", "--timing")
    size = (480, 360) if args.window_size is None else tuple(args.window_size)
    check_movie_options(args.out, frames=args.frames, fps=args.fps, timing=args.timing, gap_scale=args.gap_scale,
                        camera=args.camera, panel=args.panel, window_size=size, scale=scale)
    traj, seed = _simulate_args(args, run_start)
    out = traj.to_dict()
    if traj.status.value == "failed":
        return out
    if str(args.out).lower().endswith(".png"):
        info = film_strip(traj, args.out, frames=min(args.frames, 100), scale=scale, gap_scale=args.gap_scale,
                          camera=args.camera, window_size=size)
    else:
        info = animate(traj, args.out, frames=args.frames, fps=args.fps, timing=args.timing, scale=scale,
                       gap_scale=args.gap_scale, camera=args.camera, panel=args.panel, window_size=size,
                       progress=not args.no_progress)
    out["animation"] = {"path": info.path, "frames": info.n_frames, "frame_size": list(info.frame_size),
                        "fps": info.fps, "playback_speed": info.speed, "bytes": info.bytes}
    return out


def _simulate_args(args, runner):
    """Build the body, start and options from ``args`` and call ``runner`` (simulate_start or
    animate_start) with them."""
    if args.paper_start is not None:
        _paper_body(args)
    body = _body(args)
    start = _start_of(args, body)
    if args.restitution is not None and args.stop_at in ("jump", "touchdown"):
        warnings.warn(f"--restitution has no effect with --stop-at {args.stop_at} (impacts happen with --stop-at none "
                      "or --stop-at NAME=VALUE)")
    if args.atol is not None and args.backend == "taylor":
        warnings.warn("--atol has no effect with --backend taylor (the Taylor method has the one tolerance --rtol)")
    friction, mu, eps = _law_args(args)
    opts = dict(rtol=args.rtol, atol=args.atol, backend=args.backend, max_steps=args.max_steps, max_wall=args.max_wall)
    return runner(body=body, friction=friction, mu=mu, slip_eps=eps, start=start, t_end=args.t_end,
                  stop_at=args.stop_at, restitution=0.0 if args.restitution is None else args.restitution,
                  chart=args.chart, options=opts, pose0=_pose_of(args))


def _cmd_fixed_points(args) -> dict:
    from .params import fixed_points_report

    friction, mu, eps = _law_args(args)
    return fixed_points_report(body=_body(args), mu=mu, friction=friction, slip_eps=eps, omega0=args.omega0, n0=args.n0)


def _cmd_steady_states(args) -> dict:
    from .params import steady_structure_report

    friction, mu, eps = _law_args(args)
    return steady_structure_report(body=_body(args), mu=mu, friction=friction, slip_eps=eps, omega0=args.omega0,
                                   n0=args.n0)


def _cmd_gyroscopic(args) -> dict:
    """The report at the times in the order given (the API returns them sorted)."""
    from .params import gyroscopic_report

    out = gyroscopic_report(body=_body(args), mu=args.mu, theta0=args.theta0, t=args.t, omega0=args.omega0, n0=args.n0)
    order = sorted(range(len(args.t)), key=args.t.__getitem__)  # the API's order (its times are finite)
    if len(out["t"]) == len(order) and order != sorted(order):
        for key in ("t", "T", "theta", "Omega"):
            values = [None] * len(order)
            for rank, i in enumerate(order):
                values[i] = out[key][rank]
            out[key] = values
    return out


COMMANDS = {"simulate": _cmd_simulate, "animate": _cmd_animate, "fixed-points": _cmd_fixed_points,
            "steady-states": _cmd_steady_states,
            "gyroscopic": _cmd_gyroscopic}
