"""The paper's printed starts (``pk.paper_start``): (5.2) as printed, and bad labels and options
refused naming the argument."""

import math

import phasekit as pk

import numpy as np
import pytest

from ..helpers import raises_param

NAN, INF = float("nan"), float("inf")


@pytest.mark.parametrize("name, call", [
    ("label", lambda: pk.paper_start(["5.2"])),
    ("label", lambda: pk.paper_start("5.3")),
    ("label", lambda: pk.paper_start(5.2)),
    ("label", lambda: pk.paper_start(None)),
    ("foo", lambda: pk.paper_start("5.2", foo=1)),
    ("omega0", lambda: pk.paper_start("5.2", omega0=NAN)),
    ("n0", lambda: pk.paper_start("5.2", n0=10.0)),
    ("n0", lambda: pk.paper_start("5.1", n0="10")),
    ("friction", lambda: pk.paper_start("5.1", friction="coulomb")),
    ("value", lambda: pk.theory.PAPER_CASES["5.2"].state(NAN)),
])
def test_paper_start_rejects(name, call):
    err = raises_param(name, call)
    if name == "label":
        assert "5.1, 5.2" in str(err)
    if name == "foo":
        assert "n0, omega0, friction" in str(err)


def test_paper_start_valid_is_the_printed_5_2():
    model, x0 = pk.paper_start("(5.2)")
    assert model.chart.name == "euler"
    np.testing.assert_array_equal(x0, [7e-5, 2e-6, 10.5, -1e-4, math.pi / 2 - 1e-3, 2e-2])
