"""One jump: the normal reaction R(t) of the standard prolate workload up to lift-off.

Prolate uniform spheroid a = 1.5, Coulomb friction mu = 0.1 (exact stick-slip), gyroscopic
start theta0 = pi/2 - 0.01, Omega0 = 10.5. Writes jump_reaction.png and prints what was run, the
jump time at two tolerances (its error estimate) and the run time.
"""

from __future__ import annotations

import phasekit as pk
from phasekit.viz import pyplot

import numpy as np


def main(argv=None) -> dict:
    st = pk.sweep.Study(__file__, __doc__, quick_help="the same run (it is short)")
    st.parse(argv)
    plt = pyplot()

    body = pk.Spheroid(1.5)
    model = pk.Model(body, pk.Coulomb(0.1))
    y0 = pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5)
    fine = pk.simulate(model, y0, 200.0, rtol=1e-12, dense=False)
    run = pk.simulate(model, y0, 200.0, rtol=1e-9)  # dense output (the default): sampled below
    # the first run of a process loads the compiled integrator from the disk cache: time a repeat
    wall = pk.simulate(model, y0, 200.0, rtol=1e-9).wall_s
    samples = run.sample(np.arange(0.0, run.t_jump, 0.005))
    minima = run.minima

    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    ax1.plot(samples["t"], samples["R"], lw=0.5, color="k", label=r"$R(t)$, sampled from the dense output")
    ax1.plot(minima[:, 0], minima[:, 1], ".", ms=2, color="C3", label="located minima of R")
    ax1.axhline(0.0, color="0.6", lw=0.8)
    ax1.axvline(run.t_jump, color="C0", ls="--", lw=0.8, label=f"lift-off $t_*$ = {run.t_jump:.6f}")
    ax1.set_ylabel(r"normal reaction $R$ (units $Mg$)")
    ax1.legend(loc="lower left", fontsize=8)
    ax2.plot(samples["t"], samples["theta"], color="k", lw=0.8)
    ax2.set_ylabel(r"inclination $\theta$ (rad)")
    ax2.set_xlabel(r"time $t$ (units $\sqrt{b/g}$)")
    fig.suptitle(r"Prolate $a=1.5$, Coulomb $\mu=0.1$, gyroscopic start $\theta_0=\pi/2-0.01$, $\Omega_0=10.5$"
                 f"\nrtol $10^{{-9}}$; $t_*$ error {abs(run.t_jump - fine.t_jump):.1e} against rtol $10^{{-12}}$", fontsize=10)
    fig.tight_layout()
    png = st.save(fig, "jump_reaction.png")
    err = abs(run.t_jump - fine.t_jump)
    print(f"Figure {png.name}: R(t) and theta(t) to the first lift-off, {body!r}, {model.friction.describe()}.")
    print(f"t_jump = {run.t_jump:.9f} (rtol 1e-9, {wall * 1e3:.1f} ms with dense output and the minima of R), "
          f"{fine.t_jump:.9f} (rtol 1e-12): error {err:.1e}; theta* = {run.x_jump[4]:.6f}")
    return {"t_jump": run.t_jump, "error": err}


if __name__ == "__main__":
    pk.sweep.run_study(main)
