"""Steady states of a body with an edge (pk.Disk): its model holds only on its range of theta, so
fixed_points lists the states inside it (the precessions a scan of the whole [0, pi] finds outside
it are left out), and steady_structure computes its structure on that range (its branches end at
the range's limits: tests/steady/test_edged_structure.py)."""

from __future__ import annotations

import phasekit as pk
from phasekit.steady import precession_angles

import numpy as np


def test_fixed_points_of_a_disk_are_the_steady_states_inside_its_range():
    disk = pk.Disk(0.1)
    lo, hi = disk.theta_range
    model = pk.Model(disk, pk.Coulomb(0.3))
    states = pk.fixed_points(model, omega0=3.0)
    thetas = sorted(float(fp.y[4]) for fp in states)
    scanned = [float(t) for t in precession_angles(disk, omega0=3.0)]
    inside = [t for t in scanned if lo < t < hi]
    assert len(inside) < len(scanned)  # the scan over [0, pi] finds a state off the disk's range
    assert np.allclose(sorted(t for t in thetas if abs(t - np.pi / 2) > 1e-9), inside, atol=1e-8)
    for fp in states:  # each is a steady state of the rolling disk: its field vanishes there
        assert np.max(np.abs(model.rhs(fp.y, "rolling"))) < 1e-10


def test_the_structure_of_a_disk_is_computed_on_its_range():
    s = pk.steady_structure(pk.Disk(0.1), pk.Coulomb(0.3))
    assert s.status is pk.Status.COMPLETED and s.signature == "limit-inf | static-limit"
    assert all(0.0 <= e.theta <= np.pi / 2 for b in s.branches for e in b.ends)
