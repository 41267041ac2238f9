"""The CLI's names for the API's parameters: Python parameter names -> the flags a user typed.

A library message names a parameter as Python spells it (`mu`, `eps`); the CLI says it with the
flag typed (``--mu``, ``--slip-eps``), and a parameter fed by several flags is named by the one on
the command line.
"""

from __future__ import annotations

import re

#: Python parameter names -> the flag a user typed (the CLI rewords API errors with these)
FLAGS = {
    "a": "--a", "A": "--A", "C": "--C", "offset": "--offset", "w": "--w", "body": "--body", "mu": "--mu",
    "eps": "--slip-eps", "friction": "--friction", "theta0": "--theta0", "omega0": "--omega0", "n0": "--n0",
    "t_end": "--t-end", "rtol": "--rtol", "atol": "--atol", "restitution": "--restitution", "stop_at": "--stop-at",
    "backend": "--backend", "state": "--state", "x0": "--state", "theta": "--state (theta)", "U": "--state (U)",
    "V": "--state (V)", "Omega": "--state (Omega)", "Lambda": "--state (Lambda)", "n": "--state (n)",
    "delta": "--delta", "branch": "--branch", "seed_law": "--seed-law", "chart": "--chart",
    "max_steps": "--max-steps", "max_wall": "--max-wall", "unstable_manifold": "--unstable-manifold",
    "t": "--t", "T": "--t", "label": "--paper-start", "level": "--stop-at", "max_switches": "--max-switches",
    "b": "--size", "g": "--g", "pose0.psi": "--psi0", "pose0.phi": "--phi0", "pose0.X": "--X0", "pose0.Y": "--Y0",
    "psi0": "--psi0", "phi0": "--phi0", "X0": "--X0", "Y0": "--Y0", "spin_about_vertical": "--spin-about-vertical",
    "spinning_in_place": "--spinning-in-place", "spun_about_axis": "--spun-about-axis", "spun_on_edge": "--spun-on-edge",
    "rolled": "--rolled", "speed": "--rolled",
    "frames": "--frames", "fps": "--fps", "out": "OUT", "gap_scale": "--gap-scale", "camera": "--camera",
    "panel": "--panel", "timing": "--timing", "window_size": "--window-size", "path": "OUT", "mass": "--mass",
    "rolling_resistance": "--rolling-resistance", "spin_friction": "--spin-friction", "patch": "--patch", "hertz": "--hertz", "air_drag": "--air-drag", "air_layer": "--air-layer",
    "air_drag_quadratic": "--air-drag-quadratic", "air_drag_force": "--air-drag-force",
    "air_drag_force_quadratic": "--air-drag-force-quadratic", "thickness": "--thickness", "radius": "--radius",
    "height": "--height", "on": "--on", "flat_angle": "--flat-angle", "stem_length": "--stem-length", "stem_radius": "--stem-radius",
}
#: API parameters that more than one flag feeds: (flag typed, name to print), the first typed one wins
#: (e.g. `n0` is --spin-about-vertical's value in that start, and theta its --theta0)
SOURCES = {
    "chart": (("--formulation", "--formulation"), ("--chart", "--chart")),  # --formulation: the old name
    "n0": (("--spin-about-vertical", "--spin-about-vertical"), ("--spun-about-axis", "--spun-about-axis"),
           ("--spun-on-edge", "--spun-on-edge"), ("--n0", "--n0")),
    "theta": (("--state", "--state (theta)"), ("--theta0", "--theta0")),
    "Omega": (("--state", "--state (Omega)"), ("--spin-about-vertical", "--spin-about-vertical")),
    "n": (("--state", "--state (n)"), ("--spin-about-vertical", "--spin-about-vertical")),
    "b": (("--radius", "--radius"), ("--size", "--size")),  # a disk's or a cone's radius is its unit of length
}


def typed_text(argv) -> list[str]:
    """The options as typed (``--name`` of ``--name=value`` too), up to a bare ``--``."""
    argv = list(argv)
    argv = argv[:argv.index("--")] if "--" in argv else argv
    return [a.split("=", 1)[0] for a in argv if isinstance(a, str) and a.startswith("--") and len(a) > 2]


def flag_names(argv) -> dict:
    """FLAGS for this command line: a parameter fed by several flags is named by the one typed."""
    typed = set(typed_text(argv))
    names = dict(FLAGS)
    for param, sources in SOURCES.items():
        names[param] = next((shown for flag, shown in sources if flag in typed), FLAGS.get(param, f"`{param}`"))
    return names


def flags_in(text: str, names: dict = FLAGS) -> str:
    """Python parameter names written `name` in a library message -> the CLI's flags."""
    text = re.sub(r"`(\w+)`\s*=\s*'([^']*)'", lambda m: f"{names[m.group(1)]} {m.group(2)}" if m.group(1) in names
                  else m.group(0), text)
    return re.sub(r"`(\w+)`", lambda m: names.get(m.group(1), m.group(0)), text)


def typed_value(argv, flag: str | None) -> str | None:
    """The text typed after ``flag`` (``--flag VALUE`` or ``--flag=VALUE``), or None."""
    argv = list(argv)
    for i, a in enumerate(argv):
        if isinstance(a, str) and flag and a.split("=", 1)[0] == flag:
            return a.split("=", 1)[1] if "=" in a else (argv[i + 1] if i + 1 < len(argv) else None)
    return None
