"""The public API (issue 25): at most 60 top-level names, each used outside the package; the rest
in the sub-namespaces theory, sweep, engines, baseline and viz; every public name in the API
reference with a docstring example that runs; no import cycle among the modules (imports inside
functions included); no function over 80 lines; one version."""

from __future__ import annotations

import ast
import doctest
import importlib
import inspect
import re
import sys
import tomllib
from pathlib import Path

import phasekit as pk

import pytest

ROOT = Path(__file__).resolve().parents[1]
NAMESPACES = ("theory", "sweep", "engines", "baseline", "viz")


def _public():
    """(dotted name, object) of every public name: the top level and the sub-namespaces."""
    out = [(f"phasekit.{n}", getattr(pk, n)) for n in pk.__all__]
    for ns in NAMESPACES:
        mod = importlib.import_module(f"phasekit.{ns}")
        out += [(f"phasekit.{ns}.{n}", getattr(mod, n)) for n in mod.__all__]
    tip = importlib.import_module("phasekit.theory.tippetop")
    out += [(f"phasekit.theory.tippetop.{n}", getattr(tip, n)) for n in tip.__all__]
    return [(name, obj) for name, obj in out if not inspect.ismodule(obj)]


PUBLIC = _public()


def test_the_top_level_holds_at_most_60_names_each_used_outside_the_package():
    assert len(pk.__all__) <= 60 and len(set(pk.__all__)) == len(pk.__all__)
    outside = "\n".join(p.read_text() for d in ("studies", "examples", "benchmarks", "tests") for p in (ROOT / d).glob("*.py")
                        if p.name != Path(__file__).name)
    unused = [n for n in pk.__all__ if not re.search(rf"\b(pk|phasekit)\.{n}\b|import[^\n]*\b{n}\b", outside)]
    assert unused == []


def test_the_sub_namespaces_load_on_first_use_and_hold_no_private_names():
    for ns in NAMESPACES:
        mod = getattr(pk, ns)
        assert mod.__name__ == f"phasekit.{ns}" and all(not n.startswith("_") for n in mod.__all__)
        assert all(hasattr(mod, n) for n in mod.__all__)


def test_every_public_name_is_in_the_api_reference():
    api = (ROOT / "docs" / "api.rst").read_text()
    listed = set(re.findall(r"^\.\. (?:auto\w+|py:data)::\s*(\S+)", api, re.M))
    assert sorted(n for n, _ in PUBLIC if n not in listed) == []


def _documented(obj) -> str:
    return inspect.getdoc(obj) or ""


def test_every_public_name_has_a_docstring_example():
    data = (dict, tuple, list, str, int, float)
    missing = [n for n, obj in PUBLIC if not isinstance(obj, data) and ">>>" not in _documented(obj)]
    assert missing == []
    api = (ROOT / "docs" / "api.rst").read_text()
    for name, obj in PUBLIC:  # data has no docstring of its own: its example is in the reference
        if isinstance(obj, data):
            block = api.split(f".. py:data:: {name}", 1)
            assert len(block) == 2 and ">>>" in block[1].split("\n.. ", 1)[0], name


def _modules():
    mods = {}
    for _, obj in PUBLIC:
        mod = inspect.getmodule(obj)
        if mod is not None and mod.__name__.startswith("phasekit"):
            mods[mod.__name__] = mod
    for ns in NAMESPACES:
        mods[f"phasekit.{ns}"] = importlib.import_module(f"phasekit.{ns}")
    return sorted(mods)


@pytest.mark.parametrize("module", _modules())
def test_the_docstring_examples_run(module, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    try:
        res = doctest.testmod(importlib.import_module(module), optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    finally:
        if "matplotlib.pyplot" in sys.modules:  # the examples draw figures and keep them open
            sys.modules["matplotlib.pyplot"].close("all")
    assert res.failed == 0


def test_the_examples_of_the_api_reference_run():
    res = doctest.testfile(str(ROOT / "docs" / "api.rst"), module_relative=False,
                           optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert res.attempted >= 6 and res.failed == 0


# -- hygiene ------------------------------------------------------------------------------------


def _import_graph() -> dict[str, set[str]]:
    """phasekit's modules and the phasekit modules each imports, imports inside functions included."""
    mods = {}
    for f in (ROOT / "phasekit").rglob("*.py"):
        rel = f.relative_to(ROOT).with_suffix("")
        mods[".".join(rel.parts[:-1] if f.name == "__init__.py" else rel.parts)] = f
    graph = {m: set() for m in mods}
    for m, f in mods.items():
        pkg = m if f.name == "__init__.py" else m.rsplit(".", 1)[0]
        for n in ast.walk(ast.parse(f.read_text())):
            if isinstance(n, ast.ImportFrom) and n.level:
                base = ".".join(pkg.split(".")[: len(pkg.split(".")) - n.level + 1] + ([n.module] if n.module else []))
                targets = [base] + [f"{base}.{a.name}" for a in n.names]
            elif isinstance(n, ast.ImportFrom) and n.module:
                targets = [n.module] + [f"{n.module}.{a.name}" for a in n.names]
            elif isinstance(n, ast.Import):
                targets = [a.name for a in n.names]
            else:
                continue
            for t in targets:
                while t and t not in mods:
                    t = t.rsplit(".", 1)[0] if "." in t else ""
                if t and t != m and t != "phasekit":  # the package itself: its __version__ only
                    graph[m].add(t)
    return graph


def test_no_import_cycle_among_the_modules():
    graph = _import_graph()
    state: dict[str, int] = {}
    cycles = []

    def visit(m, path):
        state[m] = 1
        for t in sorted(graph[m]):
            if state.get(t) == 1:
                cycles.append(path[path.index(t):] + [t])
            elif t not in state:
                visit(t, path + [t])
        state[m] = 2

    for m in sorted(graph):
        if m not in state:
            visit(m, [m])
    assert cycles == []


def test_no_function_over_80_lines():
    long = [f"{f.relative_to(ROOT)}:{n.name} ({n.end_lineno - n.lineno + 1})"
            for f in (ROOT / "phasekit").rglob("*.py") for n in ast.walk(ast.parse(f.read_text()))
            if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef)) and n.end_lineno - n.lineno + 1 > 80]
    assert long == []


def test_the_version_is_written_once():
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    assert "version" not in project and "version" in project["dynamic"]
    assert re.fullmatch(r"\d+\.\d+\.\d+", pk.__version__)
    assert "any convex body of revolution" in project["description"]
