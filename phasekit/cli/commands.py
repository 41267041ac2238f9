"""The subcommands: one function per command, from parsed arguments to a JSON-ready dict.

Each calls the CLI's parameter layer (:mod:`phasekit.cli.params`) with the inputs built by
:mod:`phasekit.cli.inputs`; :data:`COMMANDS` maps a command's name to its function.
"""

from __future__ import annotations

import warnings

from .inputs import apply_units, body_of, dissipation_of, law_args, paper_body, pose_of, start_of
from .parser import UsageError


def _cmd_simulate(args) -> dict:
    from .._runtime.watch import wall_started

    with wall_started():  # --max-wall counts the whole command: the run and the work before and after it
        return _simulate_command(args)


def _simulate_command(args) -> dict:
    from .params import run_start

    scale = apply_units(args)
    traj, seed = _simulate_args(args, run_start, scale)
    out = _run_output(traj, seed, args.max_wall)
    if args.si:
        from ..errors import ParameterError
        from .params import real_units_report

        try:
            out["si"] = real_units_report(out, scale)
            out["si"]["flight_summary"] = _summary_in_real_units(out["flight_summary"], scale)
        except ParameterError as exc:  # a number of the run overflows in ms, mm, ... (e.g. a huge --X0 with --size)
            if exc.param != "value":
                raise
            raise UsageError(f"--si cannot report this run in real units: one of its values {exc.expected} (beyond "
                              f"double precision with --size {args.size!r}); leave out --si.", "--si") from None
    return out


def _cmd_animate(args) -> dict:
    """Simulate as `simulate` does, then write the movie (or film strip) of the run."""
    from .._runtime.watch import wall_started

    with wall_started():  # as simulate's (the movie after the run is not counted)
        return _animate_command(args)


def _animate_command(args) -> dict:
    from ..viz.animate import animate, check_movie_options, film_strip
    from .params import run_start

    scale = apply_units(args)
    if args.timing == "real" and scale is None:
        raise UsageError("--timing real needs --size (the body's unit of length, e.g. --size '21.5 mm').", "--timing")
    size = (480, 360) if args.window_size is None else tuple(args.window_size)

    def before_run():  # after the inputs' checks (a bad --A is named first), before any work
        check_movie_options(args.out, frames=args.frames, fps=args.fps, timing=args.timing, gap_scale=args.gap_scale,
                            camera=args.camera, panel=args.panel, window_size=size, scale=scale)

    traj, seed = _simulate_args(args, run_start, scale, before_run=before_run)
    out = _run_output(traj, seed, args.max_wall)
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


def _run_output(traj, seed, max_wall: float) -> dict:
    """The JSON dict of a run: the Trajectory's, its start's seed, every flight and their summary
    (the dict's ``flight`` is the first flight only). The work after the run (the energy budget, the
    poses at the events) gets what the run left of ``max_wall`` (--max-wall): past it, the dict says
    what it left out ("post_run")."""
    from .._runtime.watch import spent, wall_deadline

    used = spent() or traj.wall_s  # the command's time so far (wall_started), else the run's
    with wall_deadline(max(max_wall - used, 1e-3)):
        out = traj.to_dict()
    if "post_run" in out:
        out["post_run"]["reason"] = (f"--max-wall {max_wall:g} s ran out after the run ({used:.3g} s of it): its "
                                     f"{' and '.join(out['post_run']['skipped'])} not computed")
    if seed is not None:
        out["seed"] = seed
    out["flights"] = [f.to_dict() for f in traj.flights]
    out["flight_summary"] = traj.flight_summary()
    return out


def _summary_in_real_units(summary: dict, scale) -> dict:
    """The flight summary's times and gap in ms and mm (its count and fraction as they are)."""
    from ..core.units import DISPLAY_UNITS

    kinds = {"t_first_liftoff": "time", "gap_max": "length", "t_gap_max": "time", "longest_flight": "time",
             "t_longest_flight": "time", "t_airborne": "time"}
    return {k: v if v is None or k not in kinds else
            float(scale.quantity(v, kinds[k]).to(DISPLAY_UNITS[kinds[k]]).magnitude) for k, v in summary.items()}


def _simulate_args(args, runner, scale=None, before_run=None):
    """Build the body, start and options from ``args`` and call ``runner`` (run_start) with them.
    Every value is checked before a warning about it is given (a refused flag is one line);
    ``before_run()`` (a command's own checks, e.g. its optional dependencies) comes after them."""
    from .._runtime.validate import check_range
    from ..core.simulate import solver_options

    if args.paper_start is not None:
        paper_body(args)
    body = body_of(args)
    start = start_of(args, body)
    if scale is not None:  # the fast-top warning says its spins in rev/s too
        start["rev_per_s"] = float(scale.to_real(1.0, "rate", "rev/s").magnitude)
    friction, mu, eps = law_args(args)
    opts = dict(rtol=args.rtol, atol=args.atol, backend=args.backend, max_steps=args.max_steps, max_wall=args.max_wall,
                creep=not args.no_creep)
    solver_options(**opts)
    _check_reach(args, scale)
    restitution = 0.0 if args.restitution is None else check_range("restitution", args.restitution, 0.0, 1.0,
                                                                     closed="lr")
    if args.restitution is not None and args.stop_at in ("jump", "touchdown"):
        warnings.warn(f"--restitution has no effect with --stop-at {args.stop_at} (impacts happen with --stop-at none "
                      "or --stop-at NAME=VALUE)")
    if args.atol is not None and args.backend == "taylor":
        warnings.warn("--atol has no effect with --backend taylor (the Taylor method has the one tolerance --rtol)")
    dissipation = dissipation_of(args)
    if args.stop_at == "rest" and not any(dissipation.values()) and not any(lim.face for lim in body.limits):
        warnings.warn("--stop-at rest runs as --stop-at none without a dissipation law: the body never comes to rest "
                      "(give --rolling-resistance, --spin-friction or an --air-drag option)")
    if args.no_creep and eps is None:
        warnings.warn("--no-creep has no effect without --slip-eps (only a regularised law creeps)")
    if before_run is not None:
        before_run()
    return runner(body=body, friction=friction, mu=mu, slip_eps=eps, start=start, t_end=args.t_end,
                  stop_at=args.stop_at, restitution=restitution, chart=args.chart, options=opts, pose0=pose_of(args),
                  dissipation=dissipation, verify=args.verify)


def _check_reach(args, scale) -> None:
    """Refuse at once an end time that the wall budget cannot reach (rather than run for all of
    --max-wall and fail): no run covers more than REACH_PER_S time units per wall-clock second."""
    import math

    from ..core.simulate import REACH_PER_S

    reach = REACH_PER_S * args.max_wall
    if not (isinstance(args.t_end, float) and math.isfinite(args.t_end) and args.t_end > reach):
        return  # a non-finite end time is refused by the run's own checks, naming it
    typed = getattr(args, "typed_units", {}).get("t_end")
    shown = f"{typed!r} ({args.t_end:.6g} in units of sqrt(b/g))" if typed else f"{args.t_end:g}"
    real = f" = {scale.quantity(reach, 'time').to('s').magnitude:.3g} s" if scale is not None else ""
    raise UsageError(f"--t-end {shown} cannot be reached within --max-wall {args.max_wall:g} s: no run covers more "
                      f"than {REACH_PER_S:g} time units per second of wall-clock time, so --t-end must lie in (0, "
                      f"{reach:g}]{real} (or give a larger --max-wall).", "--t-end")


def _cmd_fixed_points(args) -> dict:
    from .._runtime.validate import check_positive
    from .params import fixed_points_report

    apply_units(args)  # lengths and rates typed with units (--size)
    friction, mu, eps = law_args(args)
    check_positive("max_wall", args.max_wall)  # as simulate's --max-wall
    return fixed_points_report(body=body_of(args), mu=mu, friction=friction, slip_eps=eps, omega0=args.omega0, n0=args.n0,
                               max_wall=args.max_wall, dissipation=dissipation_of(args))


def _cmd_steady_states(args) -> dict:
    from .._runtime.validate import check_positive
    from .params import steady_structure_report

    apply_units(args)  # lengths and rates typed with units (--size)
    friction, mu, eps = law_args(args)
    check_positive("max_wall", args.max_wall)  # as simulate's --max-wall
    return steady_structure_report(body=body_of(args), mu=mu, friction=friction, slip_eps=eps, omega0=args.omega0,
                                   n0=args.n0, max_wall=args.max_wall, dissipation=dissipation_of(args))


def _cmd_gyroscopic(args) -> dict:
    """The report at the times in the order given (the API returns them sorted)."""
    from .params import gyroscopic_report

    out = gyroscopic_report(body=body_of(args), mu=args.mu, theta0=args.theta0, t=args.t, omega0=args.omega0, n0=args.n0)
    order = sorted(range(len(args.t)), key=args.t.__getitem__)  # the API's order (its times are finite)
    if len(out["t"]) == len(order) and order != sorted(order):
        for key in ("t", "T", "theta", "Omega"):
            values = [None] * len(order)
            for rank, i in enumerate(order):
                values[i] = out[key][rank]
            out[key] = values
    return out


def _cmd_cache(args) -> dict:
    """The disk cache's directory and contents; with --clear, what was deleted."""
    from ..core.engines.cache import clear_disk, disk_usage

    if args.clear:
        return {"cleared": True, **clear_disk()}
    return {"cleared": False, **disk_usage()}


COMMANDS = {"simulate": _cmd_simulate, "animate": _cmd_animate, "fixed-points": _cmd_fixed_points,
            "steady-states": _cmd_steady_states,
            "gyroscopic": _cmd_gyroscopic, "cache": _cmd_cache}
