"""One jump: the normal reaction R(t) of the standard prolate workload up to lift-off.

Prolate uniform spheroid a = 1.5, Coulomb friction mu = 0.1 (exact stick-slip), gyroscopic
start theta0 = pi/2 - 0.01, Omega0 = 10.5. Writes figures/jump_reaction.png and prints
what was run, the jump time at two tolerances (its error estimate) and the run time.

    python studies/jump_reaction.py
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

import phasekit as pk

FIGURES = Path(__file__).resolve().parents[1] / "figures"


def main(argv=None) -> dict:
    argparse.ArgumentParser(description=__doc__).parse_args(argv)
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    body = pk.Spheroid(1.5)
    model = pk.Model(body, pk.Coulomb(0.1))
    y0 = pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5)
    fine = pk.simulate(model, y0, 200.0, rtol=1e-12)
    te = np.arange(0.0, fine.t_jump, 0.005)
    run = pk.simulate(model, y0, 200.0, rtol=1e-9, t_eval=te)
    R = model.normal_reaction(run.ys)

    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    ax1.plot(run.ts, R, lw=0.5, color="k")
    ax1.plot(run.minima[:, 0], run.minima[:, 1], ".", ms=2, color="C3", label="located minima of R")
    ax1.axhline(0.0, color="0.6", lw=0.8)
    ax1.axvline(run.t_jump, color="C0", ls="--", lw=0.8, label=f"lift-off t* = {run.t_jump:.6f}")
    ax1.set_ylabel(r"normal reaction $R$ (units $Mg$)")
    ax1.legend(loc="lower left", fontsize=8)
    ax2.plot(run.ts, run.ys[:, 4], color="k", lw=0.8)
    ax2.set_ylabel(r"inclination $\theta$ (rad)")
    ax2.set_xlabel(r"time $t$ (units $\sqrt{b/g}$)")
    fig.suptitle(r"Prolate $a=1.5$, Coulomb $\mu=0.1$, gyroscopic start $\theta_0=\pi/2-0.01$, $\Omega_0=10.5$", fontsize=10)
    fig.tight_layout()
    FIGURES.mkdir(exist_ok=True)
    out = FIGURES / "jump_reaction.png"
    fig.savefig(out, dpi=130)
    plt.close(fig)
    err = abs(run.t_jump - fine.t_jump)
    print(f"Figure {out.name}: R(t) and theta(t) to the first lift-off, {body!r}, {model.friction.describe()}.")
    print(f"t_jump = {run.t_jump:.9f} (rtol 1e-9, {run.wall_s * 1e3:.1f} ms incl. dense output), "
          f"{fine.t_jump:.9f} (rtol 1e-12): error {err:.1e}; theta* = {run.x_jump[4]:.6f}")
    return {"t_jump": run.t_jump, "error": err}


if __name__ == "__main__":
    main()
