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
import time
from dataclasses import dataclass

import phasekit as pk

import numpy as np

P2 = math.pi / 2
#: the paper's printed starts (5.2) (Omega0 = 10.5) and (5.1) (n0 = 10.5)
P52, P51 = (list(pk.theory.PAPER_CASES[k].state(10.5)) for k in ("5.2", "5.1"))


@dataclass
class Case:
    label: str
    a: float
    law: object
    start: dict  # {"theta0", "omega0" | "n0"} (gyroscopic) or {"state": [...]}
    t_end: float
    rtol: float = 1e-9
    max_steps: int = 2_000_000


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


def run_case(c: Case) -> dict:
    body = pk.Spheroid(c.a)
    t0 = time.perf_counter()
    row = dict(case=c.label, a=c.a, law=c.law.describe(), t_end=c.t_end, rtol=c.rtol)
    try:
        if "state" in c.start:
            y0 = np.array(c.start["state"], dtype=float)
        else:
            y0 = pk.gyroscopic_start(body, c.start["theta0"], omega0=c.start.get("omega0"), n0=c.start.get("n0"))
        chart = pk.choose_chart(float(y0[4]))
        model = pk.Model(body, c.law, chart)
        x0 = pk.to_chart(chart, y0)
        te = np.linspace(0.0, c.t_end, 201)
        # with friction, stop once the rise is complete
        r = pk.simulate(model, x0, c.t_end, rtol=c.rtol, t_eval=te, track_minima=False, max_steps=c.max_steps,
                        events=[pk.theory.rise_complete(body)] if c.law.mu > 0 else [], dense=False)
        # the start, the samples and the end state: a run that ends early still has two points
        X = np.vstack([x0[None, :]] + ([r.ys] if r.ys is not None and len(r.ys) else []) + [r.x[None, :]])
        E = model.evaluate("energy", X)
        L = model.evaluate("L_Z", X)
        if c.law.mu == 0:
            drift = float(max(np.max(np.abs(E - E[0])) / abs(E[0]), np.max(np.abs(L - L[0])) / abs(L[0])))
        else:
            drift = float(np.max(np.diff(E)) / abs(E[0])) if E.size > 1 else float("nan")
        finite = bool(np.all(np.isfinite(r.x)))
        row.update(status=r.status.value, reason=r.reason or "", t_jump=r.t_jump, t_reached=r.t,
                   theta_end=float(r.euler_end[4]), stuck=r.stuck, n_events=len(r.events), invariant_drift=drift,
                   steps=r.n_steps, backend=r.backend, chart=chart, finite=finite)
    except Exception as exc:  # a crash is a bug to report, not to hide: record it
        row.update(status="CRASH", reason=f"{type(exc).__name__}: {exc}", finite=False)
    row["wall_s"] = time.perf_counter() - t0
    return row


def main(argv=None) -> list[dict]:
    st = pk.sweep.Study(__file__, __doc__, quick_help="horizons up to t = 2000, no eps = 1e-12")
    args = st.parse(argv)
    rows = [run_case(c) for c in st.progress(cases(args.quick), desc="cases")]
    fields = ["case", "a", "law", "t_end", "rtol", "status", "reason", "t_jump", "t_reached", "theta_end", "stuck",
              "n_events", "invariant_drift", "steps", "backend", "chart", "finite", "wall_s"]
    st.csv("stiff_extreme.csv", fields, rows)
    print(f"{len(rows)} cases; table stiff_extreme.csv; {st.wall:.1f} s")
    print(f"{'case':<46s} {'status':<10s} {'t_jump':>9s} {'theta_end':>9s} {'drift':>9s} {'steps':>8s} {'backend':>13s} {'wall s':>7s}  note")
    for r in rows:
        tj = f"{r['t_jump']:.3f}" if r.get("t_jump") is not None else "-"
        th = f"{r['theta_end']:.4f}" if r.get("theta_end") is not None else "-"
        dr = f"{r['invariant_drift']:.1e}" if r.get("invariant_drift") is not None else "-"
        note = ("stuck; " if r.get("stuck") else "") + (r.get("reason") or "")[:60]
        print(f"{r['case']:<46s} {r['status']:<10s} {tj:>9s} {th:>9s} {dr:>9s} {r.get('steps', 0):>8} {r.get('backend', '-'):>13s} "
              f"{r['wall_s']:7.2f}  {note}")
    bad = [r for r in rows if r["status"] == "CRASH" or not r.get("finite", False)]
    print(f"crashes or non-finite results: {len(bad)}")
    return rows


if __name__ == "__main__":
    pk.sweep.run_study(main)
