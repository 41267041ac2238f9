"""The command line's option groups and value types: the flags of the body, the friction law and its
dissipation laws, the solver, the wall budget, a run and a movie (each an ``add_*`` that a command's
parser calls), and the types their values are read with (a number, a number or a value with units,
a quantity, a count)."""

from __future__ import annotations

import argparse
import math
import re


def real(text: str) -> float:
    """A real number as typed (inf and nan are refused later by range checks, with the flag)."""
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a number, got {text!r}") from None


class WithUnits(str):
    """An option value typed with units ("41 rev/s", "2500 rpm", "89.4 deg"), converted to
    phasekit's units once --size and --g are known (:func:`phasekit.cli.inputs.apply_units`)."""


#: the powers in a unit ("m/s^2", "s**-1"): digits that are not the value's number
POWERS = re.compile(r"(\*\*|\^)\s*\(?\s*[-+]?[\d.]+\s*\)?")


def has_number(text: str) -> bool:
    """Whether a value with units has a number of its own: pint reads a unit alone ("mm",
    "rev/s") as one of it, which is never what a user typing a flag's value meant."""
    return bool(re.search(r"\d|\b(inf|infinity|nan)\b", POWERS.sub("", text), flags=re.I))


def real_or_units(text: str):
    """A plain number (phasekit's units), or a value with units such as '41 rev/s'."""
    try:
        return float(text)
    except ValueError:
        if re.search(r"[A-Za-z]", text):
            if not has_number(text):
                raise argparse.ArgumentTypeError(f"must be a number, or a number with units such as '41 rev/s', got "
                                                 f"{text!r} (a unit needs its number)") from None
            return WithUnits(text.strip())
        raise argparse.ArgumentTypeError(f"must be a number or a value with units such as '41 rev/s', got {text!r}") \
            from None


def quantity_text(text: str) -> str:
    """A quantity typed with its number and unit (--size '21.5 mm', --g '9.81 m/s^2')."""
    if not has_number(text):
        raise argparse.ArgumentTypeError(f"must be a number with its unit such as '21.5 mm' or '9.81 m/s^2', got "
                                         f"{text!r} (a unit needs its number)")
    return text


def count(text: str) -> int:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be an integer, got {text!r}") from None
    if not math.isfinite(value) or value != int(value):
        raise argparse.ArgumentTypeError(f"must be an integer, got {text!r}")
    return int(value)


def add_body(p, units: bool = False):
    """The body's flags; with ``units`` (simulate, animate) the disk's --thickness and the cone's
    --height may be typed with units and --radius gives their radius (the unit of length, as --size)."""
    g = p.add_argument_group("body (units: mass M, length b = equatorial radius, ball radius or disk or cone radius, "
                             "time sqrt(b/g))")
    g.add_argument("--body", default="spheroid", help="spheroid | tippe-top | egg | disk | cone (default: %(default)s)")
    g.add_argument("--a", type=real, default=None, help="aspect ratio: spheroid semi-axes (1, 1, a), egg length/breadth")
    g.add_argument("--offset", type=real, default=None, help="tippe-top: centre of mass below the ball's centre, in [0, 1); spheroid: centre of mass "
                        "displaced from the centre toward the end at -k, in [0, a) (default 0)")
    g.add_argument("--w", type=real, default=None, help="egg: asymmetry (shift of the widest section over the length)")
    typed = ", or e.g. '1.2 cm' with --radius" if units else ""
    g.add_argument("--thickness", type=real_or_units if units else real, default=None,
                   help=f"disk: full thickness over the radius, in [0, 1000] (0: a thin disk, Euler's disk; a coin "
                        f"~0.1; default 0){typed}")
    g.add_argument("--flat-angle", dest="flat_angle", type=real_or_units if units else real, default=None,
                   help="disk: the tilt at which its face is taken to be down and a run stops, radians in [1e-6, 0.1] "
                        "(default 1e-3; lower follows more of Euler's disk's end)" + (", or e.g. '0.01 deg'" if units else ""))
    g.add_argument("--height", type=real_or_units if units else real, default=None,
                   help=f"cone: from the base to the tip over the base's radius, in (0, 1000] (default 1){typed}")
    g.add_argument("--on", default=None, help="cone: where it touches the table, rim (of its base, theta below the "
                                              "angle pi - atan(height) where its side lies on the table; default) or "
                                              "tip (theta above it, up to pi: a top on its point)")
    with_size = " (or with units, e.g. '12 mm', with --size)" if units else ""
    g.add_argument("--stem-length", dest="stem_length", type=real_or_units if units else real, default=None,
                   help="tippe-top: how far its stem stands out of the ball, over the ball's radius, in [0, 10] "
                        "(default 0.375, a common commercial top; 0: the ball alone, no stem, as the tippe top was "
                        f"modelled before it had one){with_size}")
    g.add_argument("--stem-radius", dest="stem_radius", type=real_or_units if units else real, default=None,
                   help=f"tippe-top: the radius of the stem's rounded end over the ball's radius, in (0, 1) (default 0.2)"
                        f"{with_size}")
    if units:
        g.add_argument("--radius", type=quantity_text, default=None,
                       help="disk, cone: its (base's) radius with its unit, e.g. '3.7 cm': the unit of length b (as "
                            "--size, which it replaces)")
    g.add_argument("--A", dest="A", type=real, default=None,
                   help="transverse moment of inertia about G, units M b^2 (default: the body's, e.g. (1+a^2)/5)")
    g.add_argument("--C", dest="C", type=real, default=None, help="axial moment of inertia about G (default: the body's, e.g. 2/5)")


STABILITY = """stability (which law each statement is for):
  --friction coulomb (default)  exact stick-slip. The steady states have zero slip and static
      friction holds them, so small disturbances roll: stability is that of the rolling
      (no-slip) linearisation: a zero-slip state is neutral or grows, never decays (a spin at a
      pole is neutral above its fast-top condition, e.g. C^2 n^2 > 4 A' M g l on a point).
  --friction coulomb --slip-eps E  the regularised field's linearisation: the rolling spectrum
      plus two fast slip modes (rates ~ mu/E).
  --friction viscous  part I's wet friction F = -mu u: friction drives or damps the modes; for
      uniform spheroids and weak friction (mu below ~0.8) the horizontal state is unstable for
      Omega0 > sqrt(5) (prolate) and the vertical spin for n0 > sqrt(5 a^3) (oblate).
  Unstable-manifold starts take their direction from the viscous linearisation by default
  (--seed-law viscous), since exact Coulomb friction gives none.
"""


def add_friction(p, units: bool = False):
    """--mu, --friction, --slip-eps and the dissipation laws (values with units with ``units``)."""
    g = p.add_argument_group("friction")
    g.add_argument("--mu", type=real, required=True,
                   help="friction coefficient mu (coulomb) or drag coefficient (viscous), in [0, 1000]")
    g.add_argument("--friction", default="coulomb",
                   help="coulomb: exact stick-slip, F = -mu R u/|u| while sliding | viscous: part I's wet friction "
                        "F = -mu u (default: %(default)s; see 'stability' below for what stability means with each)")
    g.add_argument("--slip-eps", type=real, default=None,
                   help="regularise Coulomb friction as -mu R u/sqrt(|u|^2+eps^2), eps in [1e-14, 1] "
                        "(default: exact stick-slip; no effect with --friction viscous)")
    add_dissipation(p, units)


#: the dissipation laws' flags (phasekit.friction.dissipation): dest -> (metavar, what, phasekit's unit, example with
#: units); each in [0, 1000], 0 or absent: the law is left out
DISSIPATION_FLAGS = {
    "patch": ("A", "Coulomb friction over a contact patch of radius A (Contensou: the slip and the spin about the "
              "normal coupled, Hertz pressure) in place of the point contact's sliding friction; exact Coulomb only, "
              "not with --spin-friction (the patch's couple is its spin friction)", "a length, units b", "'0.1 mm'"),
    "rolling_resistance": ("DELTA", "rolling resistance: a couple -DELTA R w_h/|w_h| against the rolling part w_h of "
                           "the angular velocity (DELTA: the pressure's offset ahead of the contact point)",
                           "a length, units b", "'0.2 mm'"),
    "spin_friction": ("MU_S", "spin (pivoting) friction: a couple -MU_S R sign(w_Z) about the vertical (MU_S = "
                      "3 pi mu a/16 for a contact patch of radius a)", "a length, units b", "'0.5 mm'"),
    "air_drag": ("K1", "air drag on the rotation: a couple -K1 w", "units M b^2 sqrt(g/b)", "'1e-7 N*m*s'"),
    "air_layer": ("K", "the air layer under a disk on its rim (Moffatt): a couple whose power is -K psidot^2/sin(theta)",
                  "units M b^2 sqrt(g/b)", "'1e-9 N*m*s'"),
    "air_drag_quadratic": ("K2", "quadratic air drag on the rotation: a couple -K2 |w| w", "units M b^2",
                           "'1e-9 N*m*s^2'"),
    "air_drag_force": ("C1", "air drag on the centre of mass: a force -C1 v at G", "units M sqrt(g/b)",
                       "'1e-4 N*s/m'"),
    "air_drag_force_quadratic": ("C2", "quadratic air drag on the centre of mass: a force -C2 |v| v at G",
                                 "units M/b", "'1e-3 N*s^2/m^2'"),
}


def add_dissipation(p, units: bool) -> None:
    """The dissipation laws acting besides sliding friction; with ``units`` (simulate, animate) a
    value may be typed with units (a length with --size, air drag with --size and --mass)."""
    rest = "; a run with any of them ends when the body comes to rest, status \"rest\"" if units else ""
    g = p.add_argument_group(f"dissipation besides sliding friction (each in [0, 1000]; 0 or absent: none{rest})")
    for dest, (metavar, what, unit, example) in DISSIPATION_FLAGS.items():
        needs = "--size" if "length" in unit else "--size and --mass"
        typed = f", or e.g. {example} with {needs}" if units else ""
        g.add_argument("--" + dest.replace("_", "-"), dest=dest, metavar=metavar, default=None,
                       type=real_or_units if units else real, help=f"{what}; {unit}{typed}")
    if units:
        g.add_argument("--hertz", default=None, metavar="MATERIALS",
                       help="a patch as --patch whose radius is Hertz's, from the body's curvature where it touches "
                            "and its weight: the body's and the table's materials by name ('hardwood, laminate'; "
                            "the table in docs/physics.md) or 'E1, nu1, E2, nu2' in Pa; needs --size and --mass; "
                            "a smooth body (not a disk's rim)")


def add_solver(p):
    g = p.add_argument_group("solver (every run is bounded by steps and wall time)")
    g.add_argument("--rtol", type=real, default=1e-9, help="tolerance in [1e-16, 0.1] (default: %(default)s)")
    g.add_argument("--atol", type=real, default=None, help="absolute tolerance of CVODES/IDAS (default: rtol/100)")
    g.add_argument("--backend", default="auto", help="auto | taylor | cvodes | cvodes-adams | idas (default: %(default)s)")
    g.add_argument("--chart", "--formulation", dest="chart", default="auto",
                   help="the state's chart: euler | vector | auto (vector within 1e-5 of the poles; --formulation is "
                        "its old name) (default: %(default)s)")
    g.add_argument("--max-steps", type=count, default=5_000_000,
                   help="step budget of the run: Taylor steps (heyoka), or CVODES/IDAS internal steps (counted per "
                        "chunk of 100 output points: a chunk that would pass the budget is not taken, so the run "
                        "ends within it; the reason gives the count) (default: %(default)s)")
    g.add_argument("--max-wall", type=real, default=600.0,
                   help="wall-time budget in seconds of the whole command: the run and the work after it (its "
                        "energy budget and poses, left out and said so in \"post_run\" past it); a --t-end it cannot "
                        "reach is refused at once (default: %(default)s)")
    g.add_argument("--verify", action="store_true",
                   help="repeat the run at rtol/10 in the other chart and report how far it is from converged "
                        "(\"converged to ~X\", or \"not converged\" with what differs); costs that run")
    g.add_argument("--no-creep", action="store_true",
                   help="a stiff regularised law (mu/eps > 500) integrates its own field at zero slip instead of "
                        "creeping on its slow manifold (docs/physics.md)")


def add_wall(p) -> None:
    """--max-wall of the commands that search for steady states (the meaning and checks of simulate's)."""
    p.add_argument("--max-wall", type=real, default=600.0,
                   help="wall-time budget in seconds, > 0: past it the command ends \"failed\" with the reason "
                        "(default: %(default)s)")


def add_run_options(sim) -> None:
    """The options of a run (simulate and animate): body, friction, start, run, solver, units."""
    add_body(sim, units=True)
    add_friction(sim, units=True)
    g = sim.add_argument_group("start (exactly one)")
    start = g.add_mutually_exclusive_group(required=True)
    start.add_argument("--state", type=real, nargs=6, metavar=("U", "V", "Omega", "Lambda", "theta", "n"),
                       help="the paper's state variables")
    start.add_argument("--gyroscopic", action="store_true", help="on the slow manifold at --theta0 with --omega0 or --n0")
    start.add_argument("--unstable-manifold", metavar="horizontal|vertical|inverted|horizontal-like",
                       help="fixed point + --delta x unstable eigenvector, with --omega0 (horizontal, horizontal-like) "
                            "or --n0 (vertical, inverted)")
    start.add_argument("--spin-about-vertical", type=real_or_units, metavar="N0",
                       help="angular velocity N0 about the vertical at --theta0, centre of mass at rest (tippe top)")
    start.add_argument("--paper-start", metavar="5.1|5.2", help="the paper's printed start (5.1) with --n0, (5.2) with --omega0")
    start.add_argument("--spinning-in-place", action="store_true",
                       help="on the steady branch at --theta0 where G stays at rest: a disk or coin spinning in place "
                            "as Euler's disk is launched (rolling on its rim, the contact circling G)")
    start.add_argument("--spun-about-axis", type=real_or_units, metavar="N0",
                       help="a top as people launch it: spun about its own axis at N0, tilted --theta0 (a cone on its "
                            "tip: near pi), with its slow precession (on a point the Lagrange top's steady one), or "
                            "none and a warning where there is none")
    start.add_argument("--spun-on-edge", type=real_or_units, metavar="N0",
                       help="a coin spun on its edge about a vertical diameter: N0 about the vertical, G at rest, at "
                            "--theta0 (default pi/2, standing on its edge)")
    start.add_argument("--rolled", type=real_or_units, metavar="SPEED",
                       help="rolled on its edge without slip, G moving at SPEED (units sqrt(g b), or e.g. '0.5 m/s'), "
                            "tilted --theta0 (default pi/2, upright)")
    g.add_argument("--theta0", type=real_or_units, default=None, help="initial inclination of the axis, radians "
                                                                        "(or e.g. '89.4 deg')")
    g.add_argument("--omega0", type=real_or_units, default=None,
                   help="precession rate Omega0 (prolate starts), |OMEGA0| <= 1e5; or e.g. '41 rev/s', '2500 rpm' with "
                        "--size")
    g.add_argument("--n0", type=real_or_units, default=None, help="spin n0 (oblate starts), |N0| <= 1e5; units as --omega0")
    g.add_argument("--delta", type=real, default=None,
                   help="seed amplitude on the unstable manifold (with --unstable-manifold; default: 0.01)")
    g.add_argument("--branch", default=None,
                   help="unstable direction and sign: +0, -0, +1, ... (with --unstable-manifold; default: +0)")
    g.add_argument("--seed-law", default=None,
                   help="linearisation giving the direction: viscous | same (with --unstable-manifold; default: viscous, "
                        "the only one with an unstable direction under exact Coulomb friction)")
    p = sim.add_argument_group("where the body starts on the table (default 0: the axis along +X, G at the origin)")
    p.add_argument("--psi0", type=real_or_units, default=None, help="azimuth of the axis from X, rad (or '30 deg')")
    p.add_argument("--phi0", type=real_or_units, default=None, help="spin angle about the axis, radians (or '30 deg')")
    p.add_argument("--X0", type=real_or_units, default=None, help="centre of mass X, units b (or '5 mm' with --size)")
    p.add_argument("--Y0", type=real_or_units, default=None, help="centre of mass Y, units b (or '5 mm' with --size)")
    r = sim.add_argument_group("run")
    r.add_argument("--t-end", type=real_or_units, default=200.0,
                   help="end time, units sqrt(b/g) (or e.g. '2 s' with --size) (default: %(default)s)")
    r.add_argument("--stop-at", default="jump",
                   help="jump | touchdown | none | rest | NAME=VALUE: stop when an observable first reaches a value, "
                        "e.g. theta=0.4 (runs through flights); rest: through flights until the body comes to rest "
                        "(with a dissipation law; else as none) (default: %(default)s)")
    r.add_argument("--restitution", type=real, default=None, help="Newton's e in [0, 1] at impacts (with --stop-at none; "
                                                                     "default 0)")
    add_units(sim)
    add_solver(sim)


def add_units(p, mass: bool = True) -> None:
    """--size and --g (and --mass): every command that takes a length takes it with units."""
    u = p.add_argument_group("real units (see 'units' below)")
    u.add_argument("--size", type=quantity_text, default=None,
                   help="the body's unit of length b with its unit: the equatorial radius (spheroid, egg) or the "
                        "ball's radius (tippe top), e.g. '21.5 mm'")
    u.add_argument("--g", type=quantity_text, default=None,
                   help="gravity with its unit (default: 9.81 m/s^2; with --size)")
    if mass:
        u.add_argument("--mass", type=quantity_text, default=None,
                       help="the body's mass with its unit, e.g. '57 g' (with --size): air-drag coefficients typed "
                            "with units, and the energies of --si in mJ")


def add_movie_options(p) -> None:
    m = p.add_argument_group("movie")
    m.add_argument("--frames", type=count, default=96, help="number of frames, in [1, 10000] (default: %(default)s)")
    m.add_argument("--fps", type=real, default=24.0, help="frames per second of the movie (default: %(default)s)")
    m.add_argument("--timing", default="body",
                   help="the clock in the body's time (body) or also in seconds with the playback speed (real, needs "
                        "--size) (default: %(default)s)")
    m.add_argument("--gap-scale", type=real, default=1.0, help="draw the gap in flight this many times larger, >= 1 "
                                                               "(printed on every frame when not 1) (default: 1)")
    m.add_argument("--camera", default="follow", help="follow (keeps G in view) | fixed (default: %(default)s)")
    m.add_argument("--panel", default="none", help="side panel: none | phase (Omega, theta, n) | R (R(t)) "
                                                   "(default: %(default)s)")
    m.add_argument("--window-size", type=count, nargs=2, default=None, metavar=("W", "H"),
                   help="pixels of the 3-D view (default: 480 360)")
    m.add_argument("--json", action="store_true", help="print one JSON object (the run and the file written)")
    m.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")
