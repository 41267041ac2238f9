"""Figure 2: the envelope Sigma (3.64) of the minima of R against the mean inclination.

Uniform prolate spheroid a = 1.5, c = -0.00054, theta-bar0 = pi/2 - 0.0001, Jellett constant
J in {6.20, 6.50, 6.63, 6.70, 6.83, 7.15, 8.45, 13}, Sigma from (3.64) with the closed forms
(3.47) and (3.58) as in the paper; dashed after Sigma first reaches 0 (the jump, beyond which
the envelope no longer applies). Also prints, for each J, the inclination of the predicted
jump with the closed form and with the quadrature form of I (exact I2 instead of its
dominant part (3.57)). Writes figure2_envelope.png.
"""

from __future__ import annotations

import phasekit as pk
import phasekit.studies as ps
from phasekit.studies import plot_envelope
from phasekit.viz import pyplot

import numpy as np

J_VALUES = (6.20, 6.50, 6.63, 6.70, 6.83, 7.15, 8.45, 13.0)
A_RATIO, C_AMP, THETA0 = 1.5, -0.00054, np.pi / 2 - 0.0001


def main(argv=None) -> dict:
    st = pk.scaffold.Study(__file__, __doc__, quick_help="the same run (it is short)")
    st.parse(argv)
    plt = pyplot()
    body = pk.Spheroid(A_RATIO)
    theta = np.linspace(THETA0, 0.02, 1500)
    coarse = np.linspace(THETA0, 0.02, 120)
    fig, ax = plt.subplots(figsize=(9.2, 4.8))
    out = {}
    for k, J in enumerate(st.progress(J_VALUES, desc="Jellett constants")):
        sig = pk.theory.reaction_envelope(body, J, THETA0, theta, C_AMP, form="closed")
        out[J] = (ps.sigma_zero(theta, sig),
                  ps.sigma_zero(coarse, pk.theory.reaction_envelope(body, J, THETA0, coarse, C_AMP, form="gyro")))
        plot_envelope(ax, theta, sig, color=plt.get_cmap("viridis")(k / (len(J_VALUES) - 1)), lw=2.2 if J >= 8.0 else 1.0,
                      label=f"({k + 1}) J = {J:g}")
    ax.axhline(0, color="0.5", lw=0.8)
    ax.set_ylim(-0.6, 1.05)
    ax.set_xlim(0, np.pi / 2)
    ax.invert_xaxis()  # the body rises from theta-bar = pi/2 toward 0
    ax.set_xlabel(r"mean inclination $\bar\theta$ (rad); the rise runs left to right")
    ax.set_ylabel(r"envelope $\Sigma$ of the minima of $R$ (units $Mg$)")
    ax.set_title(r"Fig. 2: $a=1.5$, $c=-0.00054$, $\bar\theta_0=\pi/2-10^{-4}$; dashed after $\Sigma=0$ (jump)", fontsize=10)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), title="Jellett constant\n" + r"$J = A\Omega h$", title_fontsize=8)
    fig.tight_layout()
    path = st.save(fig, "figure2_envelope.png")
    print(f"Figure {path.name}: Sigma (3.64) against theta-bar, closed forms (3.47), (3.58); {st.wall:.1f} s.")
    print(f"{'J':>6s} {'theta-bar at Sigma = 0 (closed form)':>38s} {'(quadrature, exact I2)':>24s}")
    fmt = lambda v: "no jump" if v is None else f"{v:.4f}"  # noqa: E731
    for J, (z, zq) in out.items():
        print(f"{J:6.2f} {fmt(z):>38s} {fmt(zq):>24s}")
    return out


if __name__ == "__main__":
    pk.scaffold.run_study(main)
