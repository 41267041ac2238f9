"""The printed start (5.2) against the unstable eigenvector it rounds: why their jumps differ.

(5.2) prints every component of the start with one significant digit. It is the horizontal
steady precession (Omega0 = 10.5) plus 0.02 x the viscous unstable eigenvector, to that digit,
yet the two starts jump at different times. This script measures why: it runs both, rounds
the eigenvector start one component at a time, moves each printed component across its
rounding interval (the others as printed), and maps the (theta, n) rounding box.
Friction: Coulomb mu = 0.1 regularised with eps (default 1e-3), and exact Coulomb for the
stick times.

    python examples/paper_start_rounding.py            # writes examples/out/paper_start_rounding/ (git-ignored)
    python examples/paper_start_rounding.py --out /tmp/rounding [--quick] [--eps 1e-3]

Writes rounding.csv (one row per run) and rounding.png (t_jump across each interval).
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import phasekit as pk
from phasekit.viz import pyplot, save_figure

import numpy as np

NAMES = ("U", "V", "Lambda", "theta", "n")  # the printed components (Omega0 = 10.5 is the family value)
INDEX = {"U": 0, "V": 1, "Lambda": 3, "theta": 4, "n": 5}
UNITS = {"U": "sqrt(g b)", "V": "sqrt(g b)", "Lambda": "sqrt(g/b)", "n": "sqrt(g/b)"}


def printed_offsets(x) -> dict:
    """The component as printed: theta as its offset pi/2 - theta."""
    return {k: (math.pi / 2 - x[4] if k == "theta" else x[INDEX[k]]) for k in NAMES}


def with_offsets(x, off: dict) -> np.ndarray:
    y = np.array(x, dtype=float)
    for k, v in off.items():
        y[INDEX[k]] = math.pi / 2 - v if k == "theta" else v
    return y


def one_digit(v: float) -> float:
    """``v`` rounded to one significant digit."""
    return float(f"{v:.0e}")


def interval(v: float) -> tuple[float, float]:
    """The values that print as ``v`` with one significant digit."""
    unit = 10.0 ** math.floor(math.log10(abs(v)) + 1e-9)  # pi/2 - (pi/2 - 1e-3) is 1e-3 only to rounding
    return v - 0.5 * unit, v + 0.5 * unit


def outcome(model, x, t_end) -> dict:
    tr = pk.simulate(model, x, t_end, dense=False, max_wall=60.0)
    stick = next((e.t for e in tr.events if e.name == "stick"), None)
    slide = next((e.t for e in tr.events if e.name == "slip"), None)  # the end of the first stuck stretch
    return {
        "status": tr.status.value,
        "t_jump": tr.t_jump,
        "t_stick": stick,
        "t_slide": slide,
        "slip0": float(model.evaluate("slip_speed", x)),
        "slip_Y0": float(model.evaluate("slip", x)[1]),
    }


#: where the outputs go without --out (git-ignored)
DEFAULT_OUT = Path(__file__).resolve().parent / "out" / "paper_start_rounding"


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=str(DEFAULT_OUT),
                    help="directory for rounding.csv and rounding.png (default: examples/out/paper_start_rounding)")
    ap.add_argument("--quick", action="store_true", help="3 values per interval, 6 random samples (seconds)")
    ap.add_argument("--eps", type=float, default=1e-3, help="regularisation of Coulomb friction (default 1e-3)")
    ap.add_argument("--t-end", type=float, default=300.0)
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    law, exact = pk.RegularisedCoulomb(0.1, args.eps), pk.Coulomb(0.1)
    model, x52 = pk.paper_start("5.2", friction=law)
    model_exact = model.with_chart("euler").__class__(model.body, exact, "euler")
    _, xe, _ = pk.steady.unstable_manifold_start(model.body, law, state="horizontal", delta=0.02, omega0=10.5)
    rows = []

    def record(kind, label, x):
        r = {
            "kind": kind,
            "label": label,
            **dict(zip(("U", "V", "Omega", "Lambda", "theta", "n"), x)),
            **outcome(model, x, args.t_end),
        }
        r["t_stick_exact"] = outcome(model_exact, x, 5.0)["t_stick"]
        rows.append(r)
        return r

    p, e = record("start", "(5.2) printed", x52), record("start", "eigenvector delta=0.02", xe)
    off_e = printed_offsets(xe)
    for k in NAMES:  # round one component of the eigenvector start at a time
        record("round-one", f"eigenvector, {k} rounded", with_offsets(xe, {k: one_digit(off_e[k])}))
    n_grid = 3 if args.quick else 17
    off_p = printed_offsets(x52)
    for k in NAMES:  # each printed component across its rounding interval
        for v in np.linspace(*interval(off_p[k]), n_grid):
            record(f"interval-{k}", f"{k} = {v:.4g}", with_offsets(x52, {k: float(v)}))
    rng = np.random.default_rng(52)
    n_box = 3 if args.quick else 15
    for th in np.linspace(*interval(off_p["theta"]), n_box):  # the (theta, n) box; U, V, Lambda at random
        for n in np.linspace(*interval(off_p["n"]), n_box):
            off = {k: float(rng.uniform(*interval(off_p[k]))) for k in ("U", "V", "Lambda")}
            record("box", f"theta {th:.4g}, n {n:.4g}", with_offsets(x52, {**off, "theta": float(th), "n": float(n)}))
    for d in (0.018, 0.019, 0.021, 0.022):
        _, xd, _ = pk.steady.unstable_manifold_start(model.body, law, state="horizontal", delta=d, omega0=10.5)
        record("delta", f"eigenvector delta={d:g}", xd)
    _write(out, rows, args)
    _figure(out, rows, args)
    _report(rows, p, e, off_e)
    return {"rows": rows}


def _write(out: Path, rows: list, args) -> None:
    import pandas as pd

    df = pd.DataFrame(rows)
    df.attrs["eps"] = args.eps
    df.to_csv(out / "rounding.csv", index=False)


SCALE = {"U": 1e-5, "V": 1e-6, "Lambda": 1e-4, "theta": 1e-3, "n": 1e-2}


def _offsets_of(r) -> dict:
    return printed_offsets([r[c] for c in ("U", "V", "Omega", "Lambda", "theta", "n")])


def _figure(out: Path, rows: list, args) -> None:
    plt = pyplot()
    fig, axes = plt.subplots(1, len(NAMES) + 2, figsize=(22, 4.0))
    base = _offsets_of(next(r for r in rows if r["label"] == "(5.2) printed"))
    for ax, k in zip(axes, NAMES):
        rs = [r for r in rows if r["kind"] == f"interval-{k}"]
        xs = [_offsets_of(r)[k] / SCALE[k] for r in rs]
        ax.plot(xs, [r["t_jump"] if r["t_jump"] is not None else np.nan for r in rs], "o-", color="C0")
        ax.axvline(base[k] / SCALE[k], color="0.6", ls=":")
        what = "pi/2 - theta [1e-3 rad]" if k == "theta" else f"{k} [{SCALE[k]:.0e} {UNITS[k]}]"
        ax.set_xlabel(what)
        ax.set_ylim(44, 69)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("t_jump [sqrt(b/g)]")
    ax = axes[-1]  # every run against the transverse slip of its start
    for kind, mk in (("interval", "o"), ("box", "s"), ("round-one", "^"), ("delta", "v"), ("start", "*")):
        rs = [r for r in rows if r["kind"].startswith(kind) and r["t_jump"] is not None]
        ax.plot(
            [r["slip_Y0"] for r in rs],
            [r["t_jump"] for r in rs],
            mk,
            ms=4 if kind != "start" else 10,
            ls="none",
            label=kind,
        )
    ax.set_xlabel("u_Y at the start [sqrt(g b)]")
    ax.set_ylim(44, 69)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    ax = axes[-2]  # the (theta, n) rounding box: where the jump time is set
    box = [r for r in rows if r["kind"] == "box"]
    m = int(round(np.sqrt(len(box))))
    TH = np.array([_offsets_of(r)["theta"] / 1e-3 for r in box]).reshape(m, m)
    NN = np.array([_offsets_of(r)["n"] / 1e-2 for r in box]).reshape(m, m)
    TJ = np.array([np.nan if r["t_jump"] is None else r["t_jump"] for r in box]).reshape(m, m)
    art = ax.pcolormesh(TH, NN, TJ, cmap="viridis", shading="nearest", vmin=44, vmax=69)
    for label, mk in (("(5.2) printed", "*"), ("eigenvector delta=0.02", "^")):
        r = next(r for r in rows if r["label"] == label)
        ax.plot(_offsets_of(r)["theta"] / 1e-3, _offsets_of(r)["n"] / 1e-2, mk, color="red", ms=11, label=label)
    ax.set_xlabel("pi/2 - theta [1e-3 rad]")
    ax.set_ylabel("n [1e-2 sqrt(g/b)]")
    ax.legend(fontsize=7, loc="upper right")
    fig.colorbar(art, ax=ax, label="t_jump [sqrt(b/g)]")
    fig.suptitle(
        f"Start (5.2), Omega0 = 10.5, Coulomb mu = 0.1 regularised eps = {args.eps:g}: t_jump as each printed "
        "component moves across its rounding interval (others as printed; dotted: printed value); "
        "then the (theta, n) rounding box (U, V, Lambda at random); right: every run against the start's slip u_Y",
        fontsize=10,
    )
    fig.tight_layout()
    save_figure(fig, out / "rounding.png")


def _report(rows, p, e, off_e) -> None:
    for name, r in (("(5.2) printed", p), ("eigenvector delta=0.02", e)):
        print(
            f"{name:<23s} t_jump = {r['t_jump']:.2f}; slides from t = {r['t_slide']}; exact Coulomb sticks at "
            f"{r['t_stick_exact']:.4f}; slip at the start {r['slip0']:.3g}"
        )
    print(
        "eigenvector components and their one-digit rounding: "
        + ", ".join(f"{k} {off_e[k]:.4g} -> {one_digit(off_e[k]):g}" for k in NAMES)
    )
    for r in rows:
        if r["kind"] in ("round-one", "delta"):
            print(
                f"  {r['label']:<32s} t_jump = {r['t_jump']:.2f}, slides from t = {r['t_slide']}, "
                f"u_Y at the start {r['slip_Y0']:.3g}"
            )
    for k in NAMES:
        tj = [r["t_jump"] for r in rows if r["kind"] == f"interval-{k}"]
        ok = [t for t in tj if t is not None]
        print(
            f"  {k:<7s} across its interval: t_jump {min(ok):.2f} .. {max(ok):.2f} "
            f"({len(tj) - len(ok)} of {len(tj)} no jump)"
            if ok
            else f"  {k}: no jump anywhere"
        )
    box = [r["t_jump"] for r in rows if r["kind"] == "box"]
    ok = sorted(t for t in box if t is not None)
    if ok:
        print(
            f"  (theta, n) rounding box, U, V, Lambda at random ({len(box)} runs): t_jump {ok[0]:.2f} .. "
            f"{ok[-1]:.2f}, median {np.median(ok):.2f}; "
            f"{len(box) - len(ok)} without a jump"
        )


if __name__ == "__main__":
    main()
