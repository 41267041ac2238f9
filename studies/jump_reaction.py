"""One jump: the normal reaction R(t) of the standard prolate workload up to lift-off.

Prolate uniform spheroid a = 1.5, Coulomb friction mu = 0.1 (exact stick-slip), gyroscopic
start theta0 = pi/2 - 0.01, Omega0 = 10.5. Writes jump_reaction.png and prints what was run, the
jump time at two tolerances (its error estimate) and the run time.
"""

from __future__ import annotations

import phasekit as pk
from phasekit.studies import plot_reaction_to_jump

import numpy as np


def main(argv=None) -> dict:
    st = pk.scaffold.Study(__file__, __doc__, quick_help="the same run (it is short)")
    st.parse(argv)
    body = pk.Spheroid(1.5)
    model = pk.Model(body, pk.Coulomb(0.1))
    y0 = pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5)
    fine = pk.simulate(model, y0, 200.0, rtol=1e-12, dense=False)
    run = pk.simulate(model, y0, 200.0, rtol=1e-9)  # dense output (the default): sampled for the figure
    # the first run of a process loads the compiled integrator from the disk cache: time a repeat
    wall = pk.simulate(model, y0, 200.0, rtol=1e-9).wall_s
    err = abs(run.t_jump - fine.t_jump)
    png = st.save(plot_reaction_to_jump(run, title=r"Prolate $a=1.5$, Coulomb $\mu=0.1$, gyroscopic start "
                                        r"$\theta_0=\pi/2-0.01$, $\Omega_0=10.5$"
                                        f"\nrtol $10^{{-9}}$; $t_*$ error {err:.1e} against rtol $10^{{-12}}$"),
                  "jump_reaction.png")
    print(f"Figure {png.name}: R(t) and theta(t) to the first lift-off, {body!r}, {model.friction.describe()}.")
    print(f"t_jump = {run.t_jump:.9f} (rtol 1e-9, {wall * 1e3:.1f} ms with dense output and the minima of R), "
          f"{fine.t_jump:.9f} (rtol 1e-12): error {err:.1e}; theta* = {run.x_jump[4]:.6f}")
    return {"t_jump": run.t_jump, "error": err}


if __name__ == "__main__":
    pk.scaffold.run_study(main)
