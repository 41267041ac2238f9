"""Check that every committed table in figures/ is what the current code produces.

--check reruns every study script in studies/ from scratch, one after another, each into its
own folder of a scratch folder (python studies/STUDY.py --fresh --out SCRATCH/STUDY
--no-progress; --fresh where the study has it; full size, never --quick; Dask studies on their
default workers), then compares each committed table (figures/*.csv, figures/*.json) with the
one its study wrote, cell by cell: the exact text written, so floats bit for bit. Not compared,
and named in the report: wall-time columns, the provenance of store manifests, and the rows of
runs that a wall-time budget cut. CSV rows are matched by their key column where the table has
one, else by their order; a table that holds the same rows in another order (a study that
writes them in the order its Dask tasks finish) is named so, not counted as differing. Which
study owns which table is what each study wrote: a committed table that no study writes, or
that two write, is an error, and so is a table a study writes that is not committed.

Report: per table, identical or the number of differing cells with the first few (column, row,
committed, rerun), the differing cells per column with their largest relative difference, and
the rows missing or extra; the wall time of each study and in all. Exit code 0: every table
identical; 1: anything differs, a study failed or touched figures/; 2: bad input.

--audit tight reruns them as the convergence audit does (PHASEKIT_AUDIT, phasekit/core/audit.py:
every simulation at rtol / 10) and reports, per study, how far its numbers
moved from the committed ones: the largest relative change of a number (the columns that count the
work, name the settings or time it excepted, :data:`AUDIT_EXCEPTED`) and the cells that changed
text (an outcome, a status); --report FILE writes that table as JSON (its findings of 2026-12-06 are tabulated in
docs/results/robustness.md). It does not fail on a difference: the audit measures them.

--only STUDY ... runs those studies only (a committed table of another study is then not
checked). --scratch DIR (or --out DIR) keeps the reruns in DIR (otherwise a temporary folder,
deleted unless --keep). --update (with --only) copies the fresh tables and figures of those
studies into figures/ after the report, then writes their numbers into the committed Markdown
(README.md, docs/results/*.md: python docs/_ext/pkdocs/inplace.py --write).
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import phasekit as pk
from phasekit.studies import reproduce_tables as rt

ROOT = Path(__file__).resolve().parents[1]
FIGURES = ROOT / "figures"
STUDIES = sorted(p.stem for p in (ROOT / "studies").glob("*.py")
                 if p.resolve() != Path(__file__).resolve() and not p.name.startswith("_"))
#: a scratch folder this script made: only such a folder (or an empty one) is cleared and reused
MARK = ".reproduce-scratch"
TAIL = 6  # lines of a failed study's stderr in the report


def _folder_name(text: str) -> str:
    if not text.strip():  # an empty path would silently mean the current folder
        raise argparse.ArgumentTypeError(f"must name a directory, got {text!r}")
    return text


def parse(st, argv) -> argparse.Namespace:
    """The command line, checked: one line and exit code 2 for bad input, naming the flag as typed."""
    ap = st.parser
    # the scaffold's help of its common flags speaks of a study's own output: say what they are here
    ap._option_string_actions["--out"].help = "the same as --scratch"
    ap._option_string_actions["--quick"].help = "not accepted: the committed tables are full runs, and so are the reruns"
    ap.add_argument("--check", action="store_true", help="rerun the studies and compare their tables with figures/")
    ap.add_argument("--only", nargs="+", choices=STUDIES, metavar="STUDY",
                    help=f"these studies only (of: {', '.join(STUDIES)})")
    ap.add_argument("--scratch", type=_folder_name, metavar="DIR",
                    help="keep the reruns in DIR/STUDY (default: a temporary folder); the same as --out")
    ap.add_argument("--keep", action="store_true", help="keep the temporary scratch folder")
    ap.add_argument("--update", action="store_true",
                    help="with --only: copy the fresh tables and figures of those studies into figures/")
    ap.add_argument("--audit", choices=("tight",),
                    help="rerun every simulation at rtol / 10 (tight) and report how far each study's numbers move "
                         "(PHASEKIT_AUDIT)")
    ap.add_argument("--report", metavar="FILE", help="with --audit: write the per-study table as JSON to FILE")
    typed = {}

    def check(args):
        if args.scratch is not None and args.out is not None:
            ap.error("argument --scratch: not allowed with argument --out (both name the scratch folder)")
        flag = "--scratch" if args.scratch is not None else "--out"
        folder = args.scratch if args.scratch is not None else args.out
        if folder is not None:
            path = Path(folder).resolve()
            if path == FIGURES or FIGURES in path.parents:
                ap.error(f"argument {flag}: must not be figures/ or a folder in it (the reruns never write there), "
                         f"got {folder!r}")
            if path.is_dir() and any(path.iterdir()) and not (path / MARK).exists():
                ap.error(f"argument {flag}: must be an empty folder or the scratch folder of an earlier check "
                         f"(its study folders are cleared), got {folder!r}")
            typed["flag"], args.out = flag, folder  # the scaffold checks it (and makes it) as --out
        elif args.quick:  # refused here, before the scaffold would make figures/quick/
            ap.error("argument --quick: not accepted: the committed tables are full runs, and so are the reruns")

    try:
        args = st.parse(argv, check=check)
    except pk.ParameterError as exc:  # the scaffold names the folder --out: name it as the user typed it
        if exc.param == "out" and typed.get("flag") == "--scratch":
            raise pk.ParameterError("scratch", exc.expected, exc.value) from None
        raise
    # after the scaffold has checked a folder given (a bad --out is named first, as by every study)
    if args.quick:
        ap.error("argument --quick: not accepted: the committed tables are full runs, and so are the reruns")
    if not (args.check or args.update or args.audit):
        ap.error("give --check (rerun the studies and compare), --audit MODE, or --update with --only")
    if args.report and not args.audit:
        ap.error("argument --report: needs --audit (it writes the audit's table)")
    if args.audit and args.update:
        ap.error("argument --update: not allowed with argument --audit (an audit's outputs are not the published ones)")
    if args.update and not args.only:
        ap.error("argument --update: needs --only STUDY ... (it copies the fresh files of the studies named)")
    args.only = list(dict.fromkeys(args.only)) if args.only else None
    return args


#: the audit's mode (--audit), passed to the studies as PHASEKIT_AUDIT
_AUDIT: dict = {}
#: columns an audit does not compare: the work done (it changes with the tolerance and the chart by
#: design), the settings that name how it was done, and timings (besides rt.excepted_lines()' own)
AUDIT_EXCEPTED = ("n_steps", "n_rhs", "n_sims", "n_check_sims", "n_rounds", "steps", "nfev", "n_calls", "check_worst",
                  "check_rtol", "chart", "backend", "engine", "wall_s", "task_s", "ms", "runs", "time_ms")


def _env() -> dict:
    """The studies import the code of this checkout (not an installed copy), draw off-screen."""
    path = os.pathsep.join(p for p in (str(ROOT), os.environ.get("PYTHONPATH", "")) if p)
    return {**os.environ, "PYTHONPATH": path, "MPLBACKEND": os.environ.get("MPLBACKEND", "Agg"), **_AUDIT}


def audit_rows(runs: dict, scratch: Path) -> list[dict]:
    """Per study: the committed tables against the audit's rerun, the largest relative change of a
    number (columns of AUDIT_EXCEPTED left out) with its table and column, and the cells whose text changed."""
    out = []
    committed = set(rt.table_files(FIGURES))
    for study, r in runs.items():
        row = {"study": study, "exit": r["code"], "tables": 0, "cells": 0, "worst": None, "where": "", "text_changed": 0,
               "text_example": "", "rows_missing": 0, "wall_s": round(r["wall"], 1)}
        for name in (rt.table_files(scratch / study) if (scratch / study).is_dir() else []):
            if name not in committed:
                continue
            diff = rt.compare_table(FIGURES / name, scratch / study / name)
            row["tables"] += 1
            row["cells"] += diff.n_compared
            row["rows_missing"] += len(diff.missing) + len(diff.extra)
            for c in diff.cells:
                if re.sub(r"\[\d+\]", "", c.column).split(".")[-1] in AUDIT_EXCEPTED:
                    continue
                rel = c.relative()
                if rel is None:
                    row["text_changed"] += 1
                    row["text_example"] = row["text_example"] or f"{name}: {c.column} {c.committed!r} -> {c.rerun!r}"
                elif row["worst"] is None or rel > row["worst"]:
                    row["worst"], row["where"] = rel, f"{name}: {c.column}"
        out.append(row)
    return out


def _has_fresh(script: Path) -> bool:
    """Whether a study has --fresh (resumable and Dask studies do), read from its own --help."""
    p = subprocess.run([sys.executable, str(script), "--help"], cwd=ROOT, env=_env(), capture_output=True, text=True,
                       stdin=subprocess.DEVNULL, timeout=120)
    return bool(re.search(r"^\s*--fresh\b", p.stdout, re.M))


def _figures_state() -> dict:
    return {p.relative_to(FIGURES).as_posix(): (p.stat().st_size, p.stat().st_mtime_ns)
            for p in FIGURES.rglob("*") if p.is_file()}


def rerun(name: str, scratch: Path) -> dict:
    """Run one study from scratch into ``scratch/name``: its exit code, wall time, the files of
    figures/ it changed (there should be none) and its stderr's last lines."""
    script, out = ROOT / "studies" / f"{name}.py", scratch / name
    if out.exists():
        shutil.rmtree(out)  # a scratch folder of an earlier check (MARK): start from nothing
    cmd = [sys.executable, str(script), *(["--fresh"] if _has_fresh(script) else []), "--out", str(out), "--no-progress"]
    before = _figures_state()
    t0 = time.perf_counter()
    with open(scratch / f"{name}.log", "w") as log, open(scratch / f"{name}.err", "w") as err:
        code = subprocess.run(cmd, cwd=ROOT, env=_env(), stdin=subprocess.DEVNULL, stdout=log, stderr=err).returncode
    wall = time.perf_counter() - t0
    after = _figures_state()
    touched = sorted(k for k in before.keys() | after.keys() if before.get(k) != after.get(k))
    tail = (scratch / f"{name}.err").read_text(errors="replace").splitlines()[-TAIL:] if code else []
    return {"code": code, "wall": wall, "touched": touched, "tail": tail, "command": " ".join(cmd[1:])}


def compare(runs: dict, scratch: Path, complete: bool) -> tuple[list[str], list[str], list[str], list[str]]:
    """Each committed table against its rerun, and who owns it: the report lines, the tables
    compared, those that differ, and the errors (a table two studies write, a table written but not
    committed, and with ``complete``, i.e. every study run, a committed table no study writes)."""
    written = {s: rt.table_files(scratch / s) if (scratch / s).is_dir() else [] for s in runs}
    committed = rt.table_files(FIGURES)
    own = rt.owners(written, committed)
    lines, compared, differ, errors = [], [], [], []
    for study in runs:
        for name in written[study]:
            if name in committed:
                diff = rt.compare_table(FIGURES / name, scratch / study / name)
                lines += rt.describe(diff, study)
                compared.append(name)
                differ += [] if diff.identical else [name]
    errors += [f"{name}: written by {len(who)} studies ({', '.join(who)}), owned by one only" for name, who in own.shared.items()]
    errors += [f"{study} writes tables that are not committed in figures/: {', '.join(names)}"
               for study, names in own.uncommitted.items()]
    if complete:
        errors += [f"{name}: committed, but no study writes it" for name in own.unowned]
    else:
        lines.append(f"not checked: {len(own.unowned)} committed tables of the studies not run")
    failed = [s for s, r in runs.items() if r["code"]]
    if failed and own.unowned:
        lines.append(f"(a failed study may own the unowned tables: {', '.join(failed)})")
    return lines + [f"ERROR: {e}" for e in errors], compared, differ, errors


def update(runs: dict, scratch: Path) -> int:
    """Copy every file a study that ran cleanly wrote into figures/ (each written whole under a
    temporary name, then renamed); the number of studies not copied."""
    skipped = 0
    for study, r in runs.items():
        if r["code"] or r["touched"]:
            print(f"update: {study} not copied (it failed or touched figures/)")
            skipped += 1
            continue
        for src in sorted(p for p in (scratch / study).iterdir() if p.is_file()):
            tmp = FIGURES / f".{src.name}.{os.getpid()}.tmp"
            shutil.copyfile(src, tmp)
            os.replace(tmp, FIGURES / src.name)
            print(f"update: figures/{src.name} <- {study}")
    if skipped < len(runs):
        skipped += not rewrite_pages()
    return skipped


def rewrite_pages() -> bool:
    """Write the numbers of the fresh tables into the committed Markdown (README.md, docs/results/,
    docs/_ext/pkdocs/inplace.py --write): whether that worked. In its own process: the docs
    extension needs Sphinx, which a study does not."""
    script = ROOT / "docs" / "_ext" / "pkdocs" / "inplace.py"
    if not script.is_file():  # a copy of the studies without the docs
        print(f"update: no {script.relative_to(ROOT)}: no pages to rewrite")
        return True
    p = subprocess.run([sys.executable, str(script), "--write"], cwd=ROOT, capture_output=True, text=True)
    for line in p.stdout.splitlines():
        print(f"update: {line}")
    if p.returncode:
        print(f"update: the pages' numbers were not rewritten (exit {p.returncode}): "
              f"{(p.stderr.strip().splitlines() or [''])[-1]}; run python docs/_ext/pkdocs/inplace.py --write")
    return p.returncode == 0


def main(argv=None) -> dict:
    st = pk.scaffold.Study(__file__, __doc__)
    args = parse(st, argv)
    studies = args.only or STUDIES
    temporary = args.out is None
    # absolute: the studies run in the repository's folder, not in the one the user typed it from
    scratch = Path(tempfile.mkdtemp(prefix="reproduce-")) if temporary else st.out.resolve()
    (scratch / MARK).write_text("a scratch folder of studies/reproduce.py: its study folders are cleared on reuse\n")
    print(f"Rerunning {len(studies)} {'study' if len(studies) == 1 else 'studies'} from scratch in {scratch}, one after "
          "another.", flush=True)
    if args.audit:
        _AUDIT["PHASEKIT_AUDIT"] = args.audit
        print("Convergence audit: every simulation at rtol / 10 "
              "(PHASEKIT_AUDIT); the committed tables are the reference.", flush=True)
    runs, t0 = {}, time.perf_counter()
    try:
        for i, name in enumerate(st.progress(studies, desc="studies"), 1):
            r = runs[name] = rerun(name, scratch)
            verdict = "ok" if r["code"] == 0 else f"FAILED (exit {r['code']})"
            print(f"[{i}/{len(studies)}] {name}: {verdict}, {r['wall']:.1f} s ({r['command']})", flush=True)
            for line in r["tail"]:
                print(f"    {line}")
        total = time.perf_counter() - t0
        if args.audit:
            return _audit_report(args, runs, scratch, total)
        lines, compared, differ, errors = compare(runs, scratch, complete=args.only is None)
        errors += [f"{s} changed figures/ while it ran: {', '.join(r['touched'])}" for s, r in runs.items() if r["touched"]]
        failed = [s for s, r in runs.items() if r["code"]]
        print("\n" + "\n".join(rt.excepted_lines()))
        print("\nTables (committed figures/NAME against SCRATCH/STUDY/NAME):\n" + "\n".join(lines))
        print("\nWall time per study:")
        for study, r in runs.items():
            print(f"  {study:<24s} {r['wall']:8.1f} s")
        print(f"  {'in all':<24s} {total:8.1f} s")
        problems = len(differ) + len(errors) + len(failed)
        if not problems:
            print(f"\nResult: every table checked is identical ({len(compared)} tables)")
        else:
            print(f"\nResult: {len(compared) - len(differ)} of {len(compared)} tables checked identical"
                  + (f"; {len(differ)} differ: {', '.join(differ)}" if differ else "")
                  + (f"; studies failed: {', '.join(failed)}" if failed else "")
                  + "".join(f"\n  ERROR: {e}" for e in errors))
        skipped = update(runs, scratch) if args.update else 0
    finally:
        if temporary and not args.keep:
            shutil.rmtree(scratch, ignore_errors=True)
        else:
            print(f"scratch folder kept: {scratch}")
    if args.update:
        raise SystemExit(1 if skipped else 0)
    if problems:
        raise SystemExit(1)
    return {"runs": runs, "problems": problems}


def _audit_report(args, runs: dict, scratch: Path, total: float) -> dict:
    """Print (and with --report write) the audit's table: per study, how far its numbers moved."""
    import json

    rows = audit_rows(runs, scratch)
    print(f"\nAudit ({args.audit}): the largest relative change of a number, per study (not compared: "
          f"{', '.join(AUDIT_EXCEPTED)} and what --check excepts)")
    for r in rows:
        worst = "-" if r["worst"] is None else f"{r['worst']:.2g} ({r['where']})"
        text = f"; {r['text_changed']} text cells changed, e.g. {r['text_example']}" if r["text_changed"] else ""
        print(f"  {r['study']:<24s} exit {r['exit']}, {r['tables']} tables, {r['cells']} cells: {worst}{text}")
    print(f"  in all {total:.1f} s")
    if args.report:
        report = {"audit": args.audit, "what": "every simulation at rtol / 10", "excepted": list(AUDIT_EXCEPTED), "studies": rows,
                  "wall_s": round(total, 1)}
        tmp = Path(f"{args.report}.{os.getpid()}.tmp")  # written whole, then renamed
        tmp.write_text(json.dumps(report, indent=1) + "\n")
        os.replace(tmp, args.report)
        print(f"wrote {args.report}")
    return {"runs": runs, "audit": rows}


if __name__ == "__main__":
    pk.scaffold.run_study(main, resume="figures/ was not changed (the reruns are in a scratch folder); to check, run it again")
