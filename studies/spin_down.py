"""How long does it spin: an egg and a tippe top under sliding friction, spin friction, rolling
resistance and air drag, until they rest.

Question. Pure rolling does no work: under exact Coulomb friction alone a body that stops
slipping rolls forever at constant energy (and an egg at constant tilt). Which of the
dissipation laws (phasekit.friction.dissipation) make a 60 x 45 mm egg spun at 25 rev/s rise, how
fast, and when does it rest? How long does a tippe top spun at 30 rev/s take to invert and to
come to rest, against the spin-friction and rolling-resistance coefficients?

What is run. (a) The egg: pk.Egg(1.33333, 0) (length/breadth 60/45), b = 22.5 mm, mass from
1.03 g/cm^3, on the slow manifold (pk.gyroscopic_start, as `phasekit simulate --body egg --a
1.33333 --gyroscopic --theta0 "89.4 deg" --omega0 "25 rev/s" --size "22.5 mm"`), mu = 0.2:
exact Coulomb alone; with spin friction mu_s = 0.05-1 mm; with rolling resistance; regularised
Coulomb (eps = 1e-3); with air drag (our estimate of a sphere of the egg's size in air, see
AIR); exact Coulomb over a contact patch of radius 0.05-0.2 mm (pk.Contensou, Hertz pressure: the
slip and the spin about the normal coupled), at mu = 0.2 and 0.3, and at 10 rev/s. (b) The tippe top of the README (pk.EccentricSphere(0.3, A=0.38, C=0.4), radius 15 mm)
spun at 30 rev/s about the vertical from theta0 = 0.1, exact Coulomb mu = 0.3: alone, with spin
friction, with rolling resistance, and with both over mu_s = 0.05-1 mm and delta = 0.01-0.2 mm.
Every run: vector chart, rtol 1e-10, through flights and impacts (restitution 0), until rest
(status "rest") or t_end, cut by a step and wall budget (status "failed" and the reason: a run
that crawls is recorded, not waited for). Times: the first stick, the rise (theta < 10 deg),
the turn over (theta > 90 deg), the spin about the vertical stopped (the first "pivot stick"),
rest. Accuracy: every run's energy balance (traj.energy_budget(): the energy lost minus what
each law dissipated, relative to the start), and the closed forms of each law on a uniform
sphere (ps.sphere_checks).

Outputs:
  spin_down.csv/.json            one row per run (resumable) and its manifest
  spin_down_curves.csv/.json     theta, w_Z, |w| and the energy of every run over time
  spin_down_egg.png              the egg's runs: theta, w_Z, energy against t (s)
  spin_down_top.png              the tippe top's runs: the same
  spin_down_times.png            times to rest and to stop spinning against mu_s and delta
  spin_down_egg_table.csv, spin_down_top_table.csv, spin_down_checks.csv   the docs' tables
  spin_down_summary.json         the checks, the accuracy, the failed runs and the findings
"""

from __future__ import annotations

import json
import math

import phasekit as pk
import phasekit.studies as ps

import numpy as np

RTOL = 1e-10
EGG = dict(a=1.33333, size="22.5 mm", density=1.03, theta0_deg=89.4, spin="25 rev/s", mu=0.2, rise_deg=10.0)
TOP = dict(alpha=0.3, A=0.38, C=0.4, size="15 mm", theta0=0.1, spin="30 rev/s", mu=0.3, over_deg=90.0)
#: our estimate (not a measurement) of the air on a sphere of radius r = 22.5 mm spinning at w0 = 25 rev/s:
#: the creeping-flow couple 8 pi eta r^3 w and force 6 pi eta r v (eta = 1.8e-5 Pa s); at the spin Reynolds
#: number w0 r^2 / nu ~ 5e3 a laminar boundary-layer couple ~ 3.2 rho nu^(1/2) w^(3/2) r^4 = 7.5e-6 N m at w0,
#: written as k2 |w| w with k2 = 7.5e-6 N m / w0^2 = 3e-10 N m s^2; the form drag 0.5 rho C_d pi r^2 |v| v (C_d 0.5)
AIR = {"rotation": "5.2e-9 N*m*s", "rotation_quadratic": "3e-10 N*m*s**2", "translation": "7.6e-6 N*s/m",
       "translation_quadratic": "4.8e-4 N*s**2/m**2"}
#: the tippe top's runs drawn against time (the others are in the tables and the times figure)
TOP_SHOWN = ("exact Coulomb", "spin friction 0.2 mm", "rolling resistance 0.05 mm", "mu_s 0.05 mm, delta 0.05 mm",
             "mu_s 0.2 mm, delta 0.05 mm", "mu_s 1.0 mm, delta 0.05 mm")
#: each run: (body, label, law spec, t_end in s, max_steps); rolling resistance while the body still spins about
#: the vertical crawls (its couple's sign law is held near w_h = 0 by the regularisation): small step budgets
FULL = dict(
    egg=[("exact Coulomb", {}, 120.0, 100_000),
         *((f"spin friction {m} mm", {"mu_s": f"{m} mm"}, 120.0, 100_000) for m in (0.05, 0.1, 0.2, 0.5, 1.0)),
         *((f"rolling resistance {d} mm", {"delta": f"{d} mm"}, 120.0, 30_000) for d in (0.05, 0.2)),
         ("regularised Coulomb eps 1e-3", {"sliding": "regularised"}, 20.0, 100_000),
         ("air drag", {"air": AIR}, 120.0, 100_000),
         *((f"patch {r} mm", {"patch": f"{r} mm"}, 20.0, 100_000) for r in (0.05, 0.1, 0.2)),
         *((f"patch {r} mm, mu 0.3", {"patch": f"{r} mm", "mu": 0.3}, 20.0, 100_000) for r in (0.05, 0.1, 0.2)),
         *((f"patch {r} mm, 10 rev/s", {"patch": f"{r} mm", "spin": "10 rev/s"}, 20.0, 100_000) for r in (0.05, 0.2))],
    tippe_top=[("exact Coulomb", {}, 60.0, 100_000),
         *((f"spin friction {m} mm", {"mu_s": f"{m} mm"}, 60.0, 100_000) for m in (0.05, 0.2, 1.0)),
         ("rolling resistance 0.05 mm", {"delta": "0.05 mm"}, 60.0, 30_000),
         *((f"mu_s {m} mm, delta 0.05 mm", {"mu_s": f"{m} mm", "delta": "0.05 mm"}, 120.0, 100_000)
           for m in (0.05, 0.1, 0.2, 0.5, 1.0)),
         *((f"mu_s 0.2 mm, delta {d} mm", {"mu_s": "0.2 mm", "delta": f"{d} mm"}, 120.0, 100_000)
           for d in (0.01, 0.02, 0.1, 0.2))])
QUICK = dict(
    egg=[("exact Coulomb", {}, 20.0, 20_000), ("spin friction 0.2 mm", {"mu_s": "0.2 mm"}, 25.0, 20_000),
         ("spin friction 1.0 mm", {"mu_s": "1.0 mm"}, 20.0, 20_000),
         ("rolling resistance 0.2 mm", {"delta": "0.2 mm"}, 20.0, 1_000),
         ("regularised Coulomb eps 1e-3", {"sliding": "regularised"}, 5.0, 20_000),
         ("patch 0.1 mm", {"patch": "0.1 mm"}, 5.0, 20_000)],
    tippe_top=[("exact Coulomb", {}, 10.0, 20_000), ("spin friction 0.2 mm", {"mu_s": "0.2 mm"}, 20.0, 20_000),
         ("mu_s 0.2 mm, delta 0.05 mm", {"mu_s": "0.2 mm", "delta": "0.05 mm"}, 60.0, 20_000),
         ("mu_s 1.0 mm, delta 0.05 mm", {"mu_s": "1.0 mm", "delta": "0.05 mm"}, 60.0, 20_000)])
MAX_WALL = 60.0


def setup(body: str, spin: str | None = None):
    """(body, scale, the paper's start state, law coefficient mu) of the egg or the tippe top; ``spin``:
    the egg's spin if not EGG's."""
    if body == "egg":
        egg = pk.Egg(EGG["a"], 0.0)
        size = pk.Scale(EGG["size"])
        mass = EGG["density"] * egg.volume * float(size.b.to("cm").magnitude) ** 3
        sc = pk.Scale(EGG["size"], mass=f"{mass} g")
        y0 = pk.gyroscopic_start(egg, math.radians(EGG["theta0_deg"]), omega0=sc.dimensionless(spin or EGG["spin"]))
        return egg, sc, y0, EGG["mu"]
    sc = pk.Scale(TOP["size"])
    top = pk.EccentricSphere(TOP["alpha"], A=TOP["A"], C=TOP["C"])
    return top, sc, pk.core.vertical_spin_start(TOP["theta0"], sc.dimensionless(TOP["spin"])), TOP["mu"]


def run_key(body: str, label: str, spec: dict, t_end: float, max_steps: int) -> str:
    """A run's key: the label names its laws (the manifest holds their specs)."""
    return f"{body}|{label}|{t_end:g} s|{max_steps} steps|rtol {RTOL:g}"


def run_case(body: str, label: str, spec: dict, t_end: float, max_steps: int) -> list:
    """One run: its curve rows, then its run row (written last: a run is done when it is stored)."""
    b, sc, y0, mu = setup(body, spec.get("spin"))
    law = ps.spin_down_law(sc, spec.get("sliding", "coulomb"), spec.get("mu", mu), mu_s=spec.get("mu_s"),
                           delta=spec.get("delta"), air=spec.get("air"), patch=spec.get("patch"))
    rows = ps.spin_down_run(run_key(body, label, spec, t_end, max_steps), body, label, b, law, y0, sc, t_end, rtol=RTOL,
                            rise_deg=EGG["rise_deg"], over_deg=TOP["over_deg"], max_wall=MAX_WALL, max_steps=max_steps)
    return [*rows[1:], rows[0]]


def curves_of(store, keys) -> dict:
    out = {k: {} for k in keys}
    pts = [p for p in store.rows() if p.run in out]
    for k in keys:
        mine = sorted((p for p in pts if p.run == k), key=lambda p: p.t_s)
        out[k] = {f: np.array([getattr(p, f) for p in mine]) for f in ("t_s", "theta_deg", "spin_rev_s", "energy")}
    return out


def _t(x) -> str:
    return "" if x is None else f"{x:.3g} s"


def table(rows, columns) -> list[list]:
    """The docs' table of runs: each column a (header, function of a row) pair."""
    return [[f(r) for _, f in columns] for r in rows]


def _lost(r) -> str:
    parts = [(n, getattr(r, c)) for n, c in (("sliding", "diss_sliding"), ("spin", "diss_spin"), ("rolling", "diss_rolling"),
                                            ("air", "diss_air")) if getattr(r, c) > 5e-7 * r.energy_start]
    return ", ".join(f"{n} {100 * v / r.energy_start:.3g}%" for n, v in parts) or "none"


def _ended(r) -> str:
    if r.status == "failed":
        return f"failed at {r.t_run_s:.3g} s ({r.reason.split(' reached')[0].split(' (')[0]})"
    return f"{'rest' if r.status == 'rest' else 'ran to'} {r.t_run_s:.3g} s"


COMMON = [("run", lambda r: r.case), ("ended", _ended), ("first stick", lambda r: _t(r.t_first_stick_s)),
          ("sticks", lambda r: str(r.n_stick))]
TAIL = [("w_Z at the end", lambda r: f"{0.0 + round(r.spin_end_rev_s, 6):.3g} rev/s"), ("energy taken (of the start's)", _lost), ("balance residual (relative)", lambda r: f"{r.residual / r.energy_start:.1e}")]
EGG_COLUMNS = [*COMMON, ("theta < 10 deg at", lambda r: _t(r.t_rise_s)),
               ("theta at the end", lambda r: f"{r.theta_end_deg:.4g} deg"),
               ("spin about the vertical stopped at", lambda r: _t(r.t_spin_stop_s)), ("rest at", lambda r: _t(r.t_rest_s)),
               *TAIL]
TOP_COLUMNS = [*COMMON, ("theta > 90 deg at", lambda r: _t(r.t_over_s)), ("theta max", lambda r: f"{r.theta_max_deg:.4g} deg"),
               ("spin about the vertical stopped at", lambda r: _t(r.t_spin_stop_s)), ("rest at", lambda r: _t(r.t_rest_s)),
               ("theta at rest or at the end", lambda r: f"{r.theta_end_deg:.3g} deg"), *TAIL]


def note(rows, quick: bool) -> str:
    """A figure's caption: what was run and how accurate it is."""
    worst = max(abs(r.residual) / r.energy_start for r in rows)
    failed = [r.case for r in rows if r.status == "failed"]
    return (f"vector chart, rtol {RTOL:g}, restitution 0; energy balance residual <= {worst:.1e} of the start's energy in "
            f"every run; o: rest, x: failed (step or wall budget)" + (f": {', '.join(failed)}" if failed else "")
            + (" [quick run]" if quick else ""))


def egg_estimate() -> float:
    """A Omega0 / (mu_s R) in s mm: the stop time of the egg's spin about the vertical (moment A lying on its
    side, R = M g) times mu_s in mm."""
    egg, sc, y0, _ = setup("egg")
    return egg.A * y0[2] * float(sc.b.to("mm").magnitude) * float(sc.unit("time").to("s").magnitude)


def figures(st, runs, curves, quick: bool) -> None:
    egg = [r for r in runs if r.body == "egg"]
    top = [r for r in runs if r.body == "tippe-top"]
    st.save(ps.plot_spin_down(egg, curves, early_s=5.0, title=(
        f"60 x 45 mm egg, b = {EGG['size']}, mu = {EGG['mu']}, from theta0 = {EGG['theta0_deg']} deg at {EGG['spin']} "
        f"(gyroscopic start; other mu or spin where the label says)\n{note(egg, quick)}")), "spin_down_egg.png")
    shown = [r for r in top if r.case in TOP_SHOWN]
    st.save(ps.plot_spin_down(shown, curves, early_s=2.0, title=(
        f"Tippe top alpha = {TOP['alpha']}, A = {TOP['A']}, C = {TOP['C']}, radius {TOP['size']}, mu = {TOP['mu']}, "
        f"spun at {TOP['spin']} from theta0 = {TOP['theta0']}\n{note(shown, quick)}")), "spin_down_top.png")
    both = [r for r in top if "," in r.case]
    sweep = {"spin": sorted([r for r in both if r.delta_mm and abs(r.delta_mm - 0.05) < 1e-12], key=lambda r: r.mu_s_mm),
             "delta": sorted([r for r in both if abs(r.mu_s_mm - 0.2) < 1e-12], key=lambda r: r.delta_mm)}
    spin = sorted([r for r in egg if r.case.startswith("spin friction")], key=lambda r: r.mu_s_mm)
    st.save(ps.plot_rest_times(sweep, {"spin": spin, "estimate": egg_estimate()}, title=(
        f"Times to rest: tippe top (mu_s at delta = 0.05 mm; delta at mu_s = 0.2 mm), egg (spin friction alone)\n"
        f"{note(both + spin, quick) if both + spin else ''}")), "spin_down_times.png")


def summary(runs, checks, st) -> dict:
    egg = {r.case: r for r in runs if r.body == "egg"}
    coulomb = egg.get("exact Coulomb")
    out = {"rtol": RTOL, "checks": checks, "max_check_rel_err": max(c["rel_err"] for c in checks),
           "max_energy_residual": max(abs(r.residual) / r.energy_start for r in runs),
           "failed": {f"{r.body}: {r.case}": r.reason for r in runs if r.status == "failed"},
           "egg_coulomb": None if coulomb is None else {
               "theta_change_deg": coulomb.theta_end_deg - coulomb.theta0_deg, "t_first_stick_s": coulomb.t_first_stick_s,
               "theta_range_after_stick_deg": coulomb.theta_range_after_stick_deg,
               "energy_change": coulomb.energy_end - coulomb.energy_start, "note": coulomb.note},
           "egg_rises": {r.case: r.t_rise_s for r in egg.values() if r.t_rise_s is not None},
           "egg_spin_stop_estimate_s_mm": egg_estimate(),
           "top_rests": {r.case: r.t_rest_s for r in runs if r.body == "tippe-top" and r.t_rest_s is not None},
           "wall_s": st.wall}
    return out


def main(argv=None) -> dict:
    st = pk.scaffold.Study(__file__, __doc__, dask=True, quick_help="fewer laws and coefficients, shorter runs")
    args = st.parse(argv)
    cfg = QUICK if args.quick else FULL
    meta = {"config": json.loads(json.dumps(cfg)), "egg": EGG, "top": TOP, "rtol": RTOL, "max_wall": MAX_WALL}
    runs_store = st.store(ps.SpinDownRun, meta, name="spin_down")
    curve_store = st.store(ps.SpinCurvePoint, meta, name="spin_down_curves")
    items = [(body, *case) for body in ("egg", "tippe-top") for case in cfg[body.replace("-", "_")]]
    specs = pk.sweep.each(items, run_key, run_case)
    st.run(specs, runs_store, curve_store, desc="spin-down runs")
    keys = [s.key for s in specs]
    runs = runs_store.rows(keys)
    curves = curves_of(curve_store, keys)
    checks = ps.sphere_checks(RTOL)
    figures(st, runs, curves, args.quick)
    st.csv("spin_down_egg_table.csv", [h for h, _ in EGG_COLUMNS], table([r for r in runs if r.body == "egg"], EGG_COLUMNS))
    st.csv("spin_down_top_table.csv", [h for h, _ in TOP_COLUMNS],
           table([r for r in runs if r.body == "tippe-top"], TOP_COLUMNS))
    st.csv("spin_down_checks.csv", ["law", "quantity", "closed form", "phasekit", "relative difference"],
           [[c["law"], c["quantity"], f"{c['closed_form']:.12g}", f"{c['phasekit']:.12g}", f"{c['rel_err']:.1e}"]
            for c in checks])
    out = summary(runs, checks, st)
    st.json("spin_down_summary.json", out)
    for r in runs:
        print(f"{r.body:9s} {r.case:34s} {r.status:9s} t={r.t_run_s:8.3f} s  theta {r.theta0_deg:6.2f} -> "
              f"{r.theta_end_deg:6.2f} deg  rise {_t(r.t_rise_s):>9s}  over {_t(r.t_over_s):>9s}  spin stop "
              f"{_t(r.t_spin_stop_s):>9s}  rest {_t(r.t_rest_s):>9s}  residual {r.residual / r.energy_start:.1e}  "
              f"({r.n_steps} steps, {r.wall_s:.1f} s)")
    print(f"checks: max rel. error {out['max_check_rel_err']:.1e}; wall {st.wall:.0f} s")
    return out


if __name__ == "__main__":
    pk.scaffold.run_study(main)
