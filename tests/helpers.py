"""Small helpers shared by the tests: numerics, the CLI run in-process, a user-written body."""

import contextlib
import io
import json
import subprocess
import sys
from pathlib import Path

import phasekit as pk
from phasekit import cli

import casadi as ca
import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]  # the repository


def central_jacobian(f, x, h=1e-6):
    """Central-difference Jacobian of f: R^n -> R^m at x."""
    x = np.asarray(x, dtype=float)
    cols = []
    for i in range(x.size):
        e = np.zeros_like(x)
        e[i] = h * max(1.0, abs(x[i]))
        cols.append((np.asarray(f(x + e)) - np.asarray(f(x - e))) / (2 * e[i]))
    return np.column_stack(cols)


def strict_json(text: str):
    """Parse one JSON document, refusing NaN and Infinity."""
    def refuse(name):
        raise ValueError(f"non-finite number {name} in JSON")

    return json.loads(text, parse_constant=refuse)


def run_cli(*args):
    """(exit code, stdout, stderr) of the CLI run in-process."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = cli.main([str(a) for a in args])
    return code, out.getvalue(), err.getvalue()


def usage_error(args, flag):
    """The CLI run with and without --json refuses ``args``: exit 2, one stderr line naming ``flag``
    first, the JSON error object (and nothing else) on stdout, no traceback, the same line without
    --json and nothing on stdout. Returns the message."""
    code, out, err = run_cli(*args, "--json")
    assert code == 2, (code, err)
    d = strict_json(out)
    assert d == {"status": "error", "parameter": flag, "message": d["message"]}
    assert err == f"phasekit: error: {d['message']}\n"
    assert "Traceback" not in err and "np.float64" not in err
    assert run_cli(*args) == (2, "", err)
    return d["message"]


class UserSpheroid(pk.bodies.Body):
    """A spheroid as a user writes it: only ``height`` and ``shape_params``."""

    def __init__(self, a):
        self.a_user = a
        super().__init__((1 + a * a) / 5, 0.4)

    @property
    def shape_params(self):
        return (self.a_user,)

    def height(self, c, shape):
        return ca.sqrt(1 + (shape[0] ** 2 - 1) * c * c)


def raises_param(name, call):
    """``call()`` raises ParameterError naming the argument ``name``; returns the error."""
    with pytest.raises(pk.ParameterError, match=f"`{name}`") as info:
        call()
    assert info.value.param == name
    return info.value


def run_module(*args):
    """``python -m phasekit ARGS`` in a subprocess at the repository: (exit code, stdout, stderr)."""
    p = subprocess.run([sys.executable, "-m", "phasekit", *map(str, args)], capture_output=True, text=True,
                       timeout=300, cwd=ROOT)
    return p.returncode, p.stdout, p.stderr
