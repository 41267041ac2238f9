"""A benchmark's report as the docs read it (``docs/data/<name>.json``): the run's own JSON object
wrapped with the command, the date, the commit and the machine it was measured on.

    {"command": "python benchmarks/<name>.py --quick", "measured": "YYYY-MM-DD" (UTC),
     "commit": "<short hash>" or "unknown",
     "machine": "2 cores, load average 0.4 at the start, 1.1 at the end", "result": {...}}
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import shlex
import subprocess
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def add_argument(ap: argparse.ArgumentParser) -> None:
    ap.add_argument("--report", metavar="PATH",
                    help="after the run, write the report (command, date, commit, machine, result) to PATH as JSON")


class Report:
    """Started before the benchmark's work (the load average then), written after it."""

    def __init__(self, ap: argparse.ArgumentParser, path: str | None, script: str, argv: list[str]):
        self.path = Path(path) if path else None
        if self.path is not None and not self.path.parent.is_dir():  # refuse now, not after the run
            ap.error(f"argument --report: the directory of {path!r} does not exist")
        self.command = shlex.join(["python", f"benchmarks/{Path(script).name}", *_without_report(argv)])
        self.load_start = os.getloadavg()[0]

    def finish(self, result: dict, as_json: bool) -> None:
        """Write the report, and with ``as_json`` print ``result`` on stdout as strict JSON."""
        self.write(result)
        if as_json:
            print(json.dumps(result, allow_nan=False))

    def write(self, result: dict) -> None:
        if self.path is None:
            return
        wrapper = {"command": self.command, "measured": datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%d"),
                   "commit": commit(), "machine": machine(self.load_start, os.getloadavg()[0]), "result": result}
        text = json.dumps(wrapper, indent=1, allow_nan=False) + "\n"  # strict JSON: a NaN or inf raises here
        fd, tmp = tempfile.mkstemp(dir=self.path.parent, prefix=f".{self.path.name}.", suffix=".tmp")
        try:
            with os.fdopen(fd, "w") as f:
                f.write(text)
            os.replace(tmp, self.path)  # whole or not at all: a reader never sees half a report
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise


def _without_report(argv: list[str]) -> list[str]:
    out, skip = [], False
    for a in argv:
        if skip:
            skip = False
        elif a == "--report":
            skip = True
        elif not a.startswith("--report="):
            out.append(a)
    return out


def commit() -> str:
    try:
        p = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True, timeout=10)
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    if p.returncode != 0 or not p.stdout.strip():
        return "unknown"
    # the code measured is the commit's only when the library, studies and benchmarks are unchanged
    d = subprocess.run(["git", "diff", "--quiet", "HEAD", "--", "phasekit", "studies", "benchmarks"], cwd=ROOT,
                       capture_output=True, timeout=10)
    return p.stdout.strip() + (" with uncommitted changes" if d.returncode == 1 else "")


def machine(load_start: float, load_end: float) -> str:
    return f"{os.cpu_count()} cores, load average {load_start:.1f} at the start, {load_end:.1f} at the end"
