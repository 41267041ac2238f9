"""The architecture as it is checked: subpackages in one layer order (an import-linter contract in
pyproject.toml that names every subpackage and the public errors module), a top level of a few
modules, modules of one idea (at most 500 lines), short functions (at most 60 lines of code), the
docs extension under the same gates, no import cycle among the modules, no private name imported
across a package boundary (and a handful within one), and no probe of a body's capabilities."""

from __future__ import annotations

import ast
import os
import re
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "phasekit"
LINT_IMPORTS = Path(sys.executable).with_name("lint-imports")


def _contract() -> dict:
    [contract] = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["importlinter"]["contracts"]
    return contract


def _layer_packages() -> list[str]:
    return [p.strip() for layer in _contract()["layers"] for p in layer.split("|")]


def _lint_imports(cwd: Path) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(cwd)}
    return subprocess.run([str(LINT_IMPORTS), "--no-cache"], cwd=cwd, env=env, capture_output=True, text=True,
                          timeout=300)


def test_the_layers_contract_names_every_subpackage_and_the_errors_once():
    subpackages = sorted([f"phasekit.{p.name}" for p in PACKAGE.iterdir() if (p / "__init__.py").is_file()]
                         + ["phasekit.errors"])
    listed = _layer_packages()
    assert sorted(listed) == subpackages and len(set(listed)) == len(listed)
    assert _contract()["type"] == "layers"


def test_the_package_keeps_its_layers():
    p = _lint_imports(ROOT)
    assert p.returncode == 0, p.stdout[-3000:]
    assert "1 kept, 0 broken" in p.stdout


def test_an_upward_import_breaks_the_contract(tmp_path):
    shutil.copytree(PACKAGE, tmp_path / "phasekit", ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(ROOT / "pyproject.toml", tmp_path / "pyproject.toml")
    model = tmp_path / "phasekit" / "core" / "model.py"
    model.write_text(model.read_text() + "\n\ndef _upward():\n    from ..viz import label\n\n    return label\n")
    p = _lint_imports(tmp_path)
    assert p.returncode != 0
    assert "0 kept, 1 broken" in p.stdout
    assert re.search(r"phasekit\.core\.model -> phasekit\.viz", p.stdout), p.stdout[-3000:]


def _modules() -> list[Path]:
    return sorted(PACKAGE.rglob("*.py"))


def _gated() -> list[Path]:
    """The package and the docs extension: both under the size gates."""
    return _modules() + sorted((ROOT / "docs" / "_ext").rglob("*.py"))


def test_the_top_level_holds_at_most_eight_modules():
    top = [p.name for p in PACKAGE.glob("*.py") if p.name not in ("__init__.py", "__main__.py")]
    assert len(top) <= 8, top


def test_no_module_over_500_lines():
    long = {str(p.relative_to(ROOT)): n for p in _gated() if (n := len(p.read_text().splitlines())) > 500}
    assert long == {}


def code_lines(lines: list[str], fn) -> int:
    """Lines of code of a function: its docstring, blank lines and comment lines not counted (a gate
    on code, never on documentation)."""
    first = fn.body[0] if fn.body else None
    doc = range(0)
    if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant) and isinstance(first.value.value, str):
        doc = range(first.lineno, first.end_lineno + 1)
    return sum(1 for ln in range(fn.lineno, fn.end_lineno + 1)
               if ln not in doc and (t := lines[ln - 1].strip()) and not t.startswith("#"))


def test_no_function_over_60_lines_of_code():
    long = []
    for f in _gated():
        lines = f.read_text().splitlines()
        long += [f"{f.relative_to(ROOT)}:{n.name} ({code_lines(lines, n)})" for n in ast.walk(ast.parse("\n".join(lines)))
                 if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef)) and code_lines(lines, n) > 60]
    assert long == []


def _module_name(f: Path) -> str:
    rel = f.relative_to(ROOT).with_suffix("")
    return ".".join(rel.parts[:-1] if f.name == "__init__.py" else rel.parts)


def _is_private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def private_imports() -> tuple[list[str], list[str]]:
    """Every name starting with one underscore that a module of phasekit imports from another
    module (imports inside functions included): (across a package boundary, within a package).
    A module's package is the folder it is in; the package of an ``__init__.py`` is its own."""
    across, within = [], []
    for f in _modules():
        m = _module_name(f)
        pkg = m if f.name == "__init__.py" else m.rsplit(".", 1)[0]
        for n in ast.walk(ast.parse(f.read_text())):
            if not isinstance(n, ast.ImportFrom) or not (n.level or (n.module or "").startswith("phasekit")):
                continue
            parts = pkg.split(".")
            base = ".".join(parts[: len(parts) - n.level + 1] + ([n.module] if n.module else [])) if n.level else n.module
            home = base if (ROOT / Path(*base.split(".")) / "__init__.py").is_file() else base.rsplit(".", 1)[0]
            for a in n.names:
                if _is_private(a.name):
                    (within if home == pkg else across).append(f"{m}: from {base} import {a.name}")
    return across, within


def test_no_private_name_is_imported_across_packages_and_few_within_one():
    across, within = private_imports()
    assert across == []
    assert len(within) <= 10, within


#: what a body is asked for: a probe of an attribute of one of these is a capability probe
_BODY_WORDS = re.compile(r"\b(body|bodies|support|whole|part)\b")


def body_probes(text: str) -> list[str]:
    """The ``hasattr``/``getattr`` calls of a module's source whose object names a body."""
    return [f"{n.lineno}: {ast.get_source_segment(text, n)}" for n in ast.walk(ast.parse(text))
            if isinstance(n, ast.Call) and isinstance(n.func, ast.Name) and n.func.id in ("hasattr", "getattr")
            and n.args and _BODY_WORDS.search(ast.get_source_segment(text, n.args[0]) or "")]


def test_no_module_probes_a_body_for_a_capability():
    """The body contract (phasekit.bodies.Body) declares every capability with a default: the
    library asks a body, never ``hasattr``/``getattr`` it."""
    probes = [f"{f.relative_to(ROOT)}:{p}" for f in _modules() for p in body_probes(f.read_text())]
    assert probes == []


def test_a_capability_probe_is_seen():
    text = "def f(model, part):\n    return getattr(model.body, 'limits', ()), hasattr(part.support, 'theta_range')\n"
    assert len(body_probes(text)) == 2 and body_probes("def f(args):\n    return getattr(args, 'out', None)\n") == []


def _import_graph() -> dict[str, set[str]]:
    """phasekit's modules and the phasekit modules each imports, imports inside functions included."""
    mods = {}
    for f in _modules():
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


@pytest.mark.parametrize("script", ["studies", "benchmarks"])
def test_studies_and_benchmarks_use_the_public_api_and_the_studies_support(script):
    """A study imports phasekit's public namespaces and phasekit.studies, never a private module."""
    bad = []
    for path in sorted((ROOT / script).glob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            names = [a.name for a in node.names] if isinstance(node, ast.Import) else (
                [node.module] if isinstance(node, ast.ImportFrom) and node.module else [])
            bad += [f"{path.name}: {n}" for n in names if n.startswith("phasekit") and "._" in n]
    assert bad == []


@pytest.mark.parametrize("script", ["studies", "benchmarks"])
def test_studies_and_benchmarks_name_only_public_names(script):
    """``pk.X`` and ``pk.<package>.X`` in a study are names of the public API (``__all__``)."""
    import importlib

    import phasekit as pk

    bad = []
    for path in sorted((ROOT / script).glob("*.py")):
        for a, b, c in re.findall(r"\bpk\.(\w+)(?:\.(\w+))?(?:\.(\w+))?", path.read_text()):
            if a in pk.__all__ or a == "__version__":
                continue
            try:
                ns = importlib.import_module(f"phasekit.{a}")
            except ModuleNotFoundError:
                bad.append(f"{path.name}: pk.{a}")
                continue
            if b and b not in ns.__all__ and hasattr(getattr(ns, b, None), "__all__"):  # a public subpackage
                ns, b = getattr(ns, b), c
            if a.startswith("_") or a in ("cli", "studies") or (b and b not in ns.__all__):
                bad.append(f"{path.name}: pk.{a}.{b}")
    assert bad == []


def test_the_tests_mirror_the_package():
    """tests/<subpackage>/ for every subpackage of phasekit, plus tests/contracts/."""
    subpackages = {p.name for p in PACKAGE.iterdir() if (p / "__init__.py").is_file()}
    folders = {p.name for p in (ROOT / "tests").iterdir() if (p / "__init__.py").is_file()}
    assert subpackages | {"contracts"} == folders
    flat = [p.name for p in (ROOT / "tests").glob("test_*.py")]
    assert flat == []


def test_no_test_names_an_issue_number():
    pattern = re.compile(r"\bissues?[ -]?#?\d+|\bissue-\d+", re.I)
    named = [f"{p.relative_to(ROOT)}:{i}" for p in (ROOT / "tests").rglob("*.py")
             for i, line in enumerate(p.read_text().splitlines(), 1) if pattern.search(line) and p.name != Path(__file__).name]
    assert named == [] and not any(pattern.search(p.name) for p in (ROOT / "tests").rglob("*.py"))
