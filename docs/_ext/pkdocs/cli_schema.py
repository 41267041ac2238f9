"""The JSON each CLI command prints, described from real runs: every command below is run when
the docs build (``phasekit <command> ... --json`` in its own process), and its outputs are merged
into one schema per command: every key path, the JSON types seen there, and which runs have it.
Nothing here lists a key by hand; a new key appears on the page the next time the docs build.
The same merge is written as a JSON Schema (draft 2020-12) file per command."""

from __future__ import annotations

import concurrent.futures as cf
import json
import os
import shlex
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field

from .fmt import table
from .sources import ROOT

PROLATE = "--a 1.5 --mu 0.1 --gyroscopic --theta0 1.5607963"
TOP = "--body tippe-top --offset 0.3 --A 0.38 --C 0.4 --mu 0.3"

#: command -> [(label, arguments)]: the runs whose outputs define the schema. They cover every
#: kind of result (each status, each optional object) with small, fast inputs.
RUNS = {
    "simulate": [
        ("jump", f"{PROLATE} --omega0 10.5"),
        ("touchdown", f"{PROLATE} --omega0 11 --stop-at touchdown"),
        ("hopping", f"{PROLATE} --omega0 11 --stop-at none --restitution 0.5 --t-end 50"),
        ("stopped", f"{TOP} --slip-eps 1e-8 --theta0 0.1 --spin-about-vertical 15 --stop-at theta=0.4 --t-end 30"),
        ("real units", f"{PROLATE} --omega0 '45 rev/s' --size '21.5 mm' --si"),
        ("completed", "--a 1.5 --mu 0.1 --state 0 0 0 0 1.0 0 --t-end 5"),
        ("failed", f"{PROLATE} --omega0 10.5 --max-steps 20"),
        ("bad input", "--a -1 --mu 0.1 --gyroscopic --theta0 1 --omega0 5"),
    ],
    "animate": [
        (
            "gif",
            f"{{tmp}}/run.gif {PROLATE} --omega0 11 --stop-at touchdown --frames 4 --window-size 160 120 --no-progress",
        ),
    ],
    "fixed-points": [
        ("viscous", "--a 1.5 --mu 0.1 --friction viscous --omega0 10"),
        ("exact Coulomb", "--a 1.5 --mu 0.1 --omega0 10"),
        ("tippe top", "--body tippe-top --offset 0.3 --mu 0.3 --n0 5 --friction viscous"),
    ],
    "steady-states": [
        ("tippe top", TOP),
        ("displaced spheroid", "--body spheroid --a 1.5 --offset 0.2 --mu 0.1 --friction viscous --omega0 5"),
    ],
    "gyroscopic": [
        ("prolate", "--a 1.5 --mu 0.1 --omega0 10.5 --theta0 1.5607963 --t 0 10 40"),
    ],
}


@dataclass
class CommandRun:
    command: str
    label: str
    argv: list[str]
    returncode: int
    output: object
    stderr: str


def _run(command: str, label: str, args: str, tmp: str) -> CommandRun:
    argv = ["phasekit", command, *shlex.split(args.format(tmp=tmp)), "--json"]
    env = {
        **os.environ,
        "MPLBACKEND": "Agg",
        "PYTHONPATH": os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])),
    }
    p = subprocess.run(
        [sys.executable, "-m", "phasekit", *argv[1:]], cwd=ROOT, env=env, capture_output=True, text=True, timeout=600
    )
    try:
        out = json.loads(p.stdout)
    except json.JSONDecodeError:
        raise RuntimeError(f"`{shlex.join(argv)}` printed no JSON (exit {p.returncode}): {p.stderr[-500:]}") from None
    return CommandRun(command, label, argv, p.returncode, out, p.stderr)


def run_all(jobs: int = 2) -> list[CommandRun]:
    with tempfile.TemporaryDirectory() as tmp, cf.ThreadPoolExecutor(max_workers=max(1, jobs)) as ex:
        futs = [ex.submit(_run, c, label, args, tmp) for c, runs in RUNS.items() for label, args in runs]
        return [f.result() for f in futs]


# -- merging outputs into a schema ----------------------------------------------------------------


def _type(v) -> str:
    if v is None:
        return "null"
    if isinstance(v, bool):
        return "boolean"
    if isinstance(v, int):
        return "integer"
    if isinstance(v, float):
        return "number"
    if isinstance(v, str):
        return "string"
    if isinstance(v, list):
        return "array"
    return "object"


@dataclass
class Node:
    types: set = field(default_factory=set)
    runs: set = field(default_factory=set)
    keys: dict = field(default_factory=dict)  # object members
    items: "Node | None" = None  # array items
    example: object = None

    def add(self, v, run: str):
        self.types.add(_type(v))
        self.runs.add(run)
        if isinstance(v, dict):
            for k, x in v.items():
                self.keys.setdefault(k, Node()).add(x, run)
        elif isinstance(v, list):
            if self.items is None:
                self.items = Node()
            for x in v:
                self.items.add(x, run)
        elif self.example is None and v is not None:
            self.example = v


def merge(outputs: list[tuple[str, object]]) -> Node:
    root = Node()
    for label, out in outputs:
        root.add(out, label)
    return root


def _types(n: Node) -> str:
    t = sorted(n.types - ({"integer"} if "number" in n.types else set()))
    return " or ".join(t)


def rows(node: Node, all_runs: list[str], path: str = "") -> list[list[str]]:
    out = []
    for k, child in node.keys.items():
        p = f"{path}.{k}" if path else k
        missing = [r for r in all_runs if r not in child.runs]
        if not missing:
            where = "all"
        elif len(missing) < len(all_runs) - len(missing):
            where = "all but " + ", ".join(missing)
        else:
            where = ", ".join(r for r in all_runs if r in child.runs)
        ex = "" if child.example is None else json.dumps(child.example)
        out.append([f"`{p}`", _types(child), where, f"`{ex[:40]}`" if ex else ""])
        out += rows(child, all_runs, p)
        if child.items is not None:
            if child.items.keys:
                out += rows(child.items, all_runs, p + "[]")
            elif child.items.types:
                ex = "" if child.items.example is None else json.dumps(child.items.example)
                out.append([f"`{p}[]`", _types(child.items), "", f"`{ex[:40]}`" if ex else ""])
    return out


def schema_table(node: Node, labels: list[str]) -> str:
    return table(["key", "type", "in the runs", "example"], rows(node, labels))


def json_schema(node: Node, labels: list[str], title: str = "") -> dict:
    """The merged outputs as a JSON Schema: keys present in every run are required."""

    def conv(n: Node) -> dict:
        t = sorted(n.types - ({"integer"} if "number" in n.types else set()))
        s: dict = {"type": t[0] if len(t) == 1 else t}
        if n.keys:
            s["properties"] = {k: conv(c) for k, c in n.keys.items()}
            s["required"] = [k for k, c in n.keys.items() if c.runs >= n.runs]
        if n.items is not None and n.items.types:
            s["items"] = conv(n.items)
        return s

    out = {
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": title,
        "description": f"derived from the runs: {', '.join(labels)}",
        **conv(node),
    }
    return out
