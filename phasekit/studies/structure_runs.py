"""Runs against the steady-state structure (studies/steady_structure.py): trajectories leaving
a branch state along its unstable manifold (:func:`manifold_runs`), and what a run settled into
against the branches and the steady rolling motions (:func:`settled_motion`). Study support,
not API.
"""

from __future__ import annotations

import numpy as np

from ..core.model import Model
from ..steady.rolling import rolling_motion
from ..steady.structure import SteadyStructure


def manifold_runs(structure: SteadyStructure, *, omega_range, seed_delta: float, t_end: float, pole_margin: float = 0.02,
                  n: int = 4000) -> dict:
    """Trajectories leaving the most unstable branch state of a structure along its unstable
    manifold: among the branch samples with Omega inside ``omega_range`` that have unstable
    directions, the one with the largest real part of an eigenvalue; from each of its seeds at
    distance ``seed_delta`` (:func:`phasekit.steady.manifolds.unstable_seeds`), a run of the body under the
    structure's friction law (default model, until a jump or ``t_end``), sampled at ``n``
    instants and cut where theta first comes within ``pole_margin`` of a pole (Omega is
    undefined there). Returns ``state`` (that branch state: theta, Omega, n, classification)
    and ``trajectories`` (arrays of Omega, theta, n), as :func:`phasekit.studies.render_structure` draws them.

    Examples
    --------
    >>> import phasekit as pk, phasekit.studies as ps
    >>> s = pk.steady_structure(pk.Spheroid(1.5, offset=0.2), pk.Viscous(0.1))
    >>> runs = ps.manifold_runs(s, omega_range=(2.0, 6.0), seed_delta=0.01, t_end=5.0)
    >>> len(runs["trajectories"]), runs["trajectories"][0].shape[1], sorted(runs["state"])
    (6, 3, ['Omega', 'classification', 'n', 'theta'])
    """
    from ..core.simulate import simulate
    from ..steady.manifolds import unstable_seeds

    cands = [(float(np.max(p.eigenvalues.real)), i, k) for i, b in enumerate(structure.branches)
             for k, p in enumerate(b.points) if p.n_unstable and omega_range[0] < b.Omega[k] < omega_range[1]]
    _, i, k = max(cands)
    b, fp = structure.branches[i], structure.branches[i].points[k]
    trs = []
    for _, x0 in unstable_seeds(fp, seed_delta):
        r = simulate(Model(structure.body, structure.model.friction), x0, t_end, stop_at="jump")
        df = r.sample(np.linspace(0.0, r.t, n))
        near = np.minimum(df["theta"], np.pi - df["theta"]) < pole_margin
        stop = int(np.argmax(near)) if near.any() else len(df)
        trs.append(df[["Omega", "theta", "n"]].to_numpy()[:stop])
    state = {"theta": float(b.theta[k]), "Omega": float(b.Omega[k]), "n": float(b.n[k]), "classification": fp.classification}
    return {"state": state, "trajectories": trs}


def settled_motion(traj, structure: SteadyStructure, *, since: float = 0.5, n: int = 6000) -> dict:
    """What a run settled into, against the steady states: the mean state over the last part
    of the run (from ``since`` times its end, ``n`` samples: theta, Omega, n, V, the spread of
    theta, the largest slip), the branch of ``structure`` at that theta (G at rest: Omega, n)
    and the steady rolling motion at that theta and Omega (:func:`phasekit.steady.rolling_motion`: G on a
    circle; its n relative to the mean n). Also the run's status, end time, number of events
    and of slip events (stick-slip cycles). An egg that settles tilted under Coulomb friction
    ends on the rolling motion.

    Examples
    --------
    >>> import numpy as np, phasekit as pk, phasekit.studies as ps
    >>> egg = pk.Egg(57 / 43, 0.05)
    >>> s = pk.steady_structure(egg, pk.Coulomb(0.1))
    >>> r = pk.simulate(pk.Model(egg, pk.Coulomb(0.1)), pk.gyroscopic_start(egg, np.pi / 2 - 0.05, omega0=6.0), 20.0)
    >>> m = ps.settled_motion(r, s)
    >>> sorted(m["late_mean"]), sorted(m["rolling_motion"])
    (['Omega', 'V', 'n', 'slip_max', 'theta', 'theta_spread'], ['V', 'n', 'n_rel_difference', 'needs_mu', 'radius'])
    """
    late = traj.sample(np.linspace(since * traj.t, traj.t, n))
    th, om, n_mean = (float(late[c].mean()) for c in ("theta", "Omega", "n"))
    branch_om, branch_n = (float(v[0]) for v in structure.precession(np.array([th])))
    roll = rolling_motion(structure.body, th, om)
    return {"status": traj.status.value, "t_end": traj.t, "n_events": len(traj.events),
            "stick_slip_cycles": sum(e.name == "slip" for e in traj.events),
            "late_mean": {"theta": th, "Omega": om, "n": n_mean, "V": float(late["V"].mean()),
                          "theta_spread": float(late["theta"].std()), "slip_max": float(late["slip"].max())},
            "branch_at_theta": {"Omega": branch_om, "n": branch_n},
            "rolling_motion": {"n": roll.n, "V": roll.V, "radius": roll.radius, "needs_mu": roll.needs_mu,
                               "n_rel_difference": abs(roll.n - n_mean) / abs(n_mean)}}
