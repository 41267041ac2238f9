"""Numerical stability on stiff and extreme cases: every case ends with a status, never a crash.

At least 30 cases across: friction mu in {0, 1e-3, 0.5, 1}; aspect ratio a in {0.2, 0.9, 0.99,
1.01, 1.1, 5}; Omega0 or n0 up to 100; starts within 1e-8 of theta = 0 and pi/2; Coulomb
regularisation eps from 1e-3 down to 1e-12; horizons long enough for the rise to finish
(t up to 1e4 for mu = 1e-3); the paper's rounded starts (5.1), (5.2). For each: status, t_jump
or the end inclination, the invariant drift (mu = 0: relative change of energy and L_Z, which
must stay ~0; mu > 0: the largest energy increase between samples, which must be <= 0), steps
and wall time. A case the integrator cannot do ends with status "failed" and its reason.
Writes stiff_extreme.csv and prints the table.
"""

from __future__ import annotations

import math

import phasekit as pk
import phasekit.studies as ps

P2 = math.pi / 2
#: the paper's printed starts (5.2) (Omega0 = 10.5) and (5.1) (n0 = 10.5)
P52, P51 = (list(pk.theory.PAPER_CASES[k].state(10.5)) for k in ("5.2", "5.1"))
Case = ps.StressCase


def cases(quick: bool) -> list[Case]:
    C, R, V = pk.Coulomb, pk.RegularisedCoulomb, pk.Viscous
    pro = dict(theta0=P2 - 0.01, omega0=10.5)
    obl = dict(theta0=0.05, n0=10.5)
    out = [
        # friction coefficient
        Case("mu = 0, prolate, t = 2000 (invariants)", 1.5, C(0.0), dict(theta0=1.0, omega0=6.0), 2000.0, 1e-12),
        Case("mu = 0, oblate, t = 2000 (invariants)", 2 / 3, C(0.0), dict(theta0=0.5, n0=8.0), 2000.0, 1e-12),
        Case("mu = 1e-3, prolate, full rise t <= 1e4", 1.5, C(1e-3), pro, 1e4),
        Case("mu = 1e-3, oblate, full rise t <= 1e4", 2 / 3, C(1e-3), obl, 1e4),
        Case("mu = 0.5, prolate", 1.5, C(0.5), pro, 2000.0),
        Case("mu = 1, prolate", 1.5, C(1.0), pro, 2000.0),
        Case("mu = 1, oblate", 2 / 3, C(1.0), obl, 2000.0),
        Case("viscous mu = 1, prolate", 1.5, V(1.0), pro, 2000.0),
        # aspect ratio
        Case("a = 0.2 (flat disc)", 0.2, C(0.1), dict(theta0=0.05, n0=10.0), 2000.0),
        Case("a = 0.9", 0.9, C(0.1), dict(theta0=0.05, n0=10.0), 2000.0),
        Case("a = 0.99 (near sphere)", 0.99, C(0.1), dict(theta0=0.3, n0=10.0), 2000.0),
        Case("a = 1.01 (near sphere)", 1.01, C(0.1), dict(theta0=1.2, omega0=10.0), 2000.0),
        Case("a = 1.1", 1.1, C(0.1), dict(theta0=P2 - 0.01, omega0=10.0), 2000.0),
        Case("a = 5 (long rod)", 5.0, C(0.1), dict(theta0=P2 - 0.01, omega0=10.0), 2000.0),
        # fast spin
        Case("Omega0 = 100, prolate", 1.5, C(0.1), dict(theta0=P2 - 0.01, omega0=100.0), 2000.0),
        Case("n0 = 100, oblate", 2 / 3, C(0.1), dict(theta0=0.05, n0=100.0), 2000.0),
        Case("Omega0 = 100, a = 5", 5.0, C(0.1), dict(theta0=P2 - 0.01, omega0=100.0), 2000.0),
        # starts next to the poles and the horizontal
        Case("theta0 = 1e-8, oblate, n0 = 12 (vector chart)", 0.6, C(0.1), dict(theta0=1e-8, n0=12.0), 500.0),
        Case("theta0 = 1e-8, oblate, viscous", 0.6, V(0.1), dict(theta0=1e-8, n0=12.0), 2000.0),
        Case("theta0 = pi/2 - 1e-8, prolate", 1.5, C(0.1), dict(theta0=P2 - 1e-8, omega0=10.5), 500.0),
        Case("theta0 = pi/2 - 1e-8, prolate, viscous", 1.5, V(0.1), dict(theta0=P2 - 1e-8, omega0=10.5), 2000.0),
        Case("exactly vertical, n0 = 12 (equilibrium)", 0.6, C(0.1), dict(state=[0, 0, 0, 0, 0.0, 12.0]), 100.0),
        # regularisation
        Case("eps = 1e-3, sliding start", 1.5, R(0.1, 1e-3), pro, 500.0),
        Case("eps = 1e-6, sliding start", 1.5, R(0.1, 1e-6), pro, 500.0),
        Case("eps = 1e-9, sliding start", 1.5, R(0.1, 1e-9), pro, 500.0),
        Case("eps = 1e-12, sliding start", 1.5, R(0.1, 1e-12), pro, 500.0),
        Case("eps = 1e-3, start (5.2)", 1.5, R(0.1, 1e-3), dict(state=P52), 500.0),
        Case("eps = 1e-6, start (5.2) (sticks: stiff)", 1.5, R(0.1, 1e-6), dict(state=P52), 300.0),
        Case("eps = 1e-9, start (5.2) (sticks: stiff)", 1.5, R(0.1, 1e-9), dict(state=P52), 100.0, max_steps=300_000),
        Case("eps = 1e-12, start (5.2) (sticks: stiff)", 1.5, R(0.1, 1e-12), dict(state=P52), 100.0, max_steps=300_000),
        # the paper's printed starts
        Case("paper (5.2), exact Coulomb", 1.5, C(0.1), dict(state=P52), 500.0),
        Case("paper (5.1), exact Coulomb", 2 / 3, C(0.1), dict(state=P51), 500.0),
        Case("paper (5.1), viscous", 2 / 3, V(0.1), dict(state=P51), 2000.0),
        # tolerances
        Case("rtol = 1e-13, standard workload", 1.5, C(0.1), pro, 200.0, 1e-13),
        Case("rtol = 1e-3, standard workload", 1.5, C(0.1), pro, 200.0, 1e-3),
    ]
    if quick:
        out = [c for c in out if c.t_end <= 2000.0 and "1e-12" not in c.label][:30]
    return out


def main(argv=None) -> list[dict]:
    st = pk.scaffold.Study(__file__, __doc__, quick_help="horizons up to t = 2000, no eps = 1e-12")
    args = st.parse(argv)
    rows = [ps.stress_run(c) for c in st.progress(cases(args.quick), desc="cases")]
    st.csv("stiff_extreme.csv", ps.STRESS_COLUMNS, rows)
    print(f"{len(rows)} cases; table stiff_extreme.csv; {st.wall:.1f} s")
    print("\n".join(ps.stress_report(rows)))
    return rows


if __name__ == "__main__":
    pk.scaffold.run_study(main)
