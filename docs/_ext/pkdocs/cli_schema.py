"""The JSON each CLI command prints, described from real runs: every command below is run when
the docs build (``phasekit <command> ... --json`` in its own process), and its outputs are merged
into one schema per command: every key path, the JSON types seen there, and which runs have it.
Nothing here lists a key by hand; a new key appears on the page the next time the docs build.
The same merge is written as a JSON Schema (draft 2020-12) file per command.

The runs are also recorded in the repository (``python docs/_ext/pkdocs/cli_schema.py --write``):
``docs/data/cli_schema.json`` (:func:`record`), the schema files ``docs/data/cli/*.schema.json``
and the tables in docs/cli.md (the group ``cli``, written by :mod:`pkdocs.inplace`), so that they
read without a build; tests/contracts/test_committed_numbers.py checks the record against fresh runs.

Each example value on the page is what one run printed: that of the first run listed, or, for a
key that run lacks, of the first run that has it (named beside the value), never a mix of
runs within one value."""

from __future__ import annotations

import concurrent.futures as cf
import json
import os
import shlex
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

if __package__ in (None, ""):  # run as a script: python docs/_ext/pkdocs/cli_schema.py --write
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    __package__ = "pkdocs"

from pkdocs.fmt import table  # noqa: E402
from pkdocs.registry import group  # noqa: E402
from pkdocs.sources import DOCS, ROOT, Sources  # noqa: E402

#: the committed record of the runs (docs/data/): what docs/cli.md shows without a build
RECORD = "cli_schema.json"
#: the committed JSON Schema files, one per command
SCHEMAS = DOCS / "data" / "cli"

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
        ("rest", f"{TOP} --theta0 0.1 --spin-about-vertical 5 --spin-friction 0.02 --rolling-resistance 0.01 "
                 "--stop-at rest --t-end 400 --max-wall 120"),
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


#: what the temporary folder of the runs is shown as (in the arguments and in the outputs)
TMP = "DIR"


def _untemp(value, tmp: str):
    """``value`` (an output, an argument) with the runs' temporary folder written as :data:`TMP`."""
    if isinstance(value, str):
        return value.replace(tmp, TMP) if tmp else value
    if isinstance(value, list):
        return [_untemp(v, tmp) for v in value]
    if isinstance(value, dict):
        return {k: _untemp(v, tmp) for k, v in value.items()}
    return value


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
    return CommandRun(command, label, _untemp(argv, tmp), p.returncode, _untemp(out, tmp), p.stderr)


def run_all(jobs: int = 2, log=None) -> list[CommandRun]:
    """Every run of :data:`RUNS`, ``jobs`` at a time, in the order listed; ``log(line)`` is told
    of each as it ends (the build shows it is working)."""
    with tempfile.TemporaryDirectory() as tmp, cf.ThreadPoolExecutor(max_workers=max(1, jobs)) as ex:
        futs = {ex.submit(_run, c, label, args, tmp): None for c, runs in RUNS.items() for label, args in runs}
        for i, f in enumerate(cf.as_completed(futs), 1):
            r = f.result()
            if log:
                log(f"pkdocs: [{i}/{len(futs)}] phasekit {r.command} ({r.label}): exit {r.returncode}")
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
    examples: dict = field(default_factory=dict)  # run -> the first value it printed here

    def add(self, v, run: str):
        self.types.add(_type(v))
        self.runs.add(run)
        self.examples.setdefault(run, v)
        if isinstance(v, dict):
            for k, x in v.items():
                self.keys.setdefault(k, Node()).add(x, run)
        elif isinstance(v, list):
            if self.items is None:
                self.items = Node()
            for x in v:
                self.items.add(x, run)

    def example(self, all_runs: list[str]) -> tuple[str, object]:
        """(run, value): the value printed by the first run (in the order of ``all_runs``) that
        has this key."""
        run = next(r for r in all_runs if r in self.examples)
        return run, self.examples[run]


def merge(outputs: list[tuple[str, object]]) -> Node:
    root = Node()
    for label, out in outputs:
        root.add(out, label)
    return root


def _types(n: Node) -> str:
    t = sorted(n.types - ({"integer"} if "number" in n.types else set()))
    return " or ".join(t)


def _example_cell(n: Node, all_runs: list[str]) -> str:
    """The example of a scalar key, labelled with its run unless it is the first run's; blank
    for an object or a list (their members have their own rows)."""
    run, v = n.example(all_runs)
    if isinstance(v, (dict, list)):
        return ""
    text = f"`{json.dumps(v)[:40].rstrip()}`"  # a code span ends without a space
    return text if run == all_runs[0] else f"{text} ({run})"


def rows(node: Node, all_runs: list[str], path: str = "") -> list[list[str]]:
    """One row per key path: the path, its JSON types, the runs that have it, an example."""
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
        out.append([f"`{p}`", _types(child), where, _example_cell(child, all_runs)])
        out += rows(child, all_runs, p)
        if child.items is not None:
            if child.items.keys:
                out += rows(child.items, all_runs, p + "[]")
            elif child.items.types:
                out.append([f"`{p}[]`", _types(child.items), "", _example_cell(child.items, all_runs)])
    return out


def schema_table(node: Node, labels: list[str]) -> str:
    header = ["key", "type", "in the runs", f"example (run {labels[0]}, unless named)"]
    return table(header, rows(node, labels))


def json_schema(node: Node, labels: list[str], title: str = "") -> dict:
    """The merged outputs as a JSON Schema: keys present in every run are required."""

    def conv(n: Node) -> dict:
        t = sorted(n.types - ({"integer"} if "number" in n.types else set()))
        s: dict = {"type": t[0] if len(t) == 1 else t}
        run, example = n.example(labels)
        if not isinstance(example, (dict, list)):
            s["examples"] = [example]  # as on the page: one run's value
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


# -- the committed record: docs/data/cli_schema.json and docs/data/cli/*.schema.json ------------------


def node_dict(n: Node, labels: list[str]) -> dict:
    """A merged node as JSON: its types, the runs that have it (in the order of ``labels``), the
    one example shown ([run, value]; an object or a list as ``{}`` or ``[]``), its members."""
    d = {"types": sorted(n.types), "runs": [r for r in labels if r in n.runs]}
    if n.examples:  # not the items of a list that was empty in every run
        run, v = n.example(labels)
        d["example"] = [run, {} if isinstance(v, dict) else [] if isinstance(v, list) else v]
    if n.keys:
        d["keys"] = {k: node_dict(c, labels) for k, c in n.keys.items()}
    if n.items is not None:
        d["items"] = node_dict(n.items, labels)
    return d


def node_from_dict(d: dict) -> Node:
    """The inverse of :func:`node_dict` (for what the pages and schemas read: types, runs, the example)."""
    n = Node(types=set(d["types"]), runs=set(d["runs"]), examples=dict([d["example"]]) if "example" in d else {})
    n.keys = {k: node_from_dict(c) for k, c in d.get("keys", {}).items()}
    n.items = node_from_dict(d["items"]) if "items" in d else None
    return n


def _status(r: CommandRun) -> str:
    return r.output.get("status", "") if isinstance(r.output, dict) else ""


def record(runs: list[CommandRun]) -> dict:
    """What the pages need of the runs, per command: each run (label, arguments, exit code, status),
    the merged results and the merged bad-input outputs (exit 2), as :func:`node_dict`."""
    out = {}
    for command in [c for c in RUNS if any(r.command == c for r in runs)]:
        mine = [r for r in runs if r.command == command]
        results = [r for r in mine if r.returncode != 2]
        errors = [r for r in mine if r.returncode == 2]
        out[command] = {
            "runs": [{"label": r.label, "argv": r.argv, "returncode": r.returncode, "status": _status(r)} for r in mine],
            "results": node_dict(merge([(r.label, r.output) for r in results]), [r.label for r in results]),
            "errors": node_dict(merge([(r.label, r.output) for r in errors]), [r.label for r in errors]) if errors else None,
        }
    return out


def schema_of(rec: dict, command: str) -> dict:
    """The JSON Schema of one command's results, from the record."""
    c = rec[command]
    labels = [r["label"] for r in c["runs"] if r["returncode"] != 2]
    return json_schema(node_from_dict(c["results"]), labels, f"phasekit {command} --json")


def page_block(rec: dict, command: str, intro: str, link: str) -> str:
    """The Markdown of one command: its runs, a link to its JSON Schema (``link``), the table of
    its results and that of its bad input."""
    c = rec[command]
    lines = [intro, ""]
    for r in c["runs"]:
        status = f", status `{r['status']}`" if r["status"] else ""
        lines.append(f"- **{r['label']}**: `{shlex.join(r['argv'])}` (exit {r['returncode']}{status})")
    labels = [r["label"] for r in c["runs"] if r["returncode"] != 2]
    lines += ["", f"JSON Schema of the results: {link}", "", schema_table(node_from_dict(c["results"]), labels)]
    if c["errors"]:
        elabels = [r["label"] for r in c["runs"] if r["returncode"] == 2]
        lines += ["", "Bad input (exit 2) prints instead:", "", schema_table(node_from_dict(c["errors"]), elabels)]
    return "\n".join(lines)


COMMITTED_INTRO = ("The runs (recorded by `python docs/_ext/pkdocs/cli_schema.py --write` in "
                   f"`docs/data/{RECORD}`; the built site shows the runs made when it was built):")


@group("cli")
def _cli(src: Sources) -> dict:
    rec = src.report(RECORD)
    return {c: page_block(rec, c, COMMITTED_INTRO, f"[`{c}.schema.json`](data/cli/{c}.schema.json)") for c in rec}


def write(jobs: int = 2) -> dict:
    """Run every command of :data:`RUNS` and write the record and the schema files; the record."""
    rec = record(run_all(jobs, print))
    (DOCS / "data" / RECORD).write_text(json.dumps(rec, indent=1) + "\n")
    SCHEMAS.mkdir(exist_ok=True)
    for command in rec:
        (SCHEMAS / f"{command}.schema.json").write_text(json.dumps(schema_of(rec, command), indent=1) + "\n")
    return rec


if __name__ == "__main__":
    if sys.argv[1:] != ["--write"]:
        sys.exit("usage: python docs/_ext/pkdocs/cli_schema.py --write   (runs every command of RUNS; writes "
                 f"docs/data/{RECORD}, docs/data/cli/*.schema.json and the blocks of docs/cli.md)")
    write()
    from pkdocs import inplace

    for path in inplace.write():
        print(f"wrote {path.relative_to(ROOT)}")
