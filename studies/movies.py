"""Movies of the moving body for the README: the tippe top inverting (it hops on the way) and a
prolate spheroid rising until it jumps, as GIFs and film strips drawn from each run's pose.

What is run. The README's tippe top (ball radius b, centre of mass 0.3 b below the centre,
A = 0.38, C = 0.4, exact Coulomb mu = 0.3, spun at n0 = 15 about the vertical from theta0 = 0.1,
rtol 1e-10, through its hops with restitution 0) until theta reaches pi - 0.05; and the Fig. 4
spheroid (a = 1.5, mu = 0.1, Omega0 = 11, sliding start) to its first touchdown. The egg's
jumps are in studies/egg_jumps.py.

Outputs (--quick: fewer frames): tippe_top_inversion.gif, tippe_top_inversion_strip.png, spheroid_jump.gif.
"""

from __future__ import annotations

import math

import phasekit as pk  # first: Ctrl-C while the libraries load ends in one line
from phasekit.viz import animate, film_strip

import numpy as np


def tippe_top(st) -> dict:
    top = pk.EccentricSphere(0.3, A=0.38, C=0.4)
    inverted = pk.Event("theta", math.pi - 0.05, direction=+1, name="inverted")
    r = pk.simulate(pk.Model(top, pk.Coulomb(0.3)), pk.core.vertical_spin_start(0.1, 15.0), 300.0, rtol=1e-10,
                    stop_at="none", events=[inverted], max_switches=200_000)
    title = f"tippe top: offset 0.3, A 0.38, C 0.4, mu 0.3, n0 15 ({len(r.events_named('lift-off'))} hops)"
    a = animate(r, st.path("tippe_top_inversion.gif"), frames=20 if st.quick else 48, fps=10, window_size=(340, 280),
                panel="R", title=title, progress=st.show)
    s = film_strip(r, st.path("tippe_top_inversion_strip.png"), frames=6, window_size=(260, 240), title=title)
    return {"status": r.status.value, "t_inverted": r.t, "hops": len(r.events_named("lift-off")), "gif_bytes": a.bytes,
            "strip_bytes": s.bytes}


def spheroid(st) -> dict:
    body = pk.Spheroid(1.5)
    r = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=11.0), 200.0,
                    stop_at="touchdown")
    a = animate(r, st.path("spheroid_jump.gif"), frames=20 if st.quick else 48, fps=12, window_size=(360, 300), panel="R",
                title="spheroid a = 1.5, mu 0.1, Omega0 = 11: rise to the jump", progress=st.show)
    return {"status": r.status.value, "t_jump": r.t_jump, "gif_bytes": a.bytes}


def main(argv=None) -> dict:
    st = pk.scaffold.Study(__file__, __doc__)
    st.parse(argv)
    res = {"tippe_top": tippe_top(st), "spheroid": spheroid(st)}
    for name, d in res.items():
        print(name, ", ".join(f"{k}={v:.6g}" if isinstance(v, float) else f"{k}={v}" for k, v in d.items()))
    print(f"wall {st.wall:.0f} s")
    return res


if __name__ == "__main__":
    pk.scaffold.run_study(main)
