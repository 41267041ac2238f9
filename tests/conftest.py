"""Shared fixtures: bodies, models and the standard workloads of the issues."""

import os

import numpy as np
import pytest

os.environ.setdefault("MPLBACKEND", "Agg")

import phasekit as pk  # noqa: E402


@pytest.fixture(scope="session")
def prolate():
    return pk.Spheroid(1.5)


@pytest.fixture(scope="session")
def oblate():
    return pk.Spheroid(2.0 / 3.0)


@pytest.fixture(scope="session")
def standard_start(prolate):
    """Issue 2/9 standard workload: a = 1.5, gyroscopic start theta0 = pi/2 - 0.01, Omega0 = 10.5."""
    return pk.gyroscopic_start(prolate, np.pi / 2 - 0.01, omega0=10.5)
