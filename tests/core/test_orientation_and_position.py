"""Orientation and position (psi, phi, X, Y, X_P, Y_P) against an independent model.

The independent model is written here from scratch: Newton-Euler for the spheroid in fixed
axes with a unit quaternion for the orientation, the body-frame angular velocity, and the
horizontal position and velocity of G; the contact holds the lowest point of the ellipsoid
x^2 + y^2 + z^2/a^2 = 1 on the table, with the normal force solved from that constraint at the
acceleration level. No phasekit code, no support function h(theta), no Euler angles in the
integration; the angles are read off the rotation matrix afterwards.
"""

import math

import phasekit as pk
from phasekit.core import pose
from phasekit.core.charts import euler_to_vector
from phasekit.core.pose import rotation_matrix

import numpy as np
import pytest

A_RATIO, MU, EPS = 1.5, 0.1, 1e-3
INERTIA = np.array([(1 + A_RATIO**2) / 5, (1 + A_RATIO**2) / 5, 0.4])
MINV = np.array([1.0, 1.0, A_RATIO**2])  # the ellipsoid r^T diag(1, 1, 1/a^2) r = 1, inverted


def _quat_matrix(q):
    w, x, y, z = q / math.sqrt(q @ q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def _newton_euler(t, s):
    """State: quaternion (4), body angular velocity (3), G horizontal position (2) and velocity (2)."""
    q, wb, vh = s[0:4], s[4:7], s[9:11]
    Rm = _quat_matrix(q)
    u = Rm[2]  # e_Z in body axes
    hh = math.sqrt(u @ (MINV * u))
    rP = -MINV * u / hh  # lowest point, body axes; also minus the gradient of the height of G
    grad = -rP
    w_world = Rm @ wb
    slip = vh + np.cross(w_world, Rm @ rP)[0:2]
    fhat = -MU * slip / math.sqrt(slip @ slip + EPS**2)  # friction per unit normal force
    # dw_b/dt = R alpha1 + alpha0; the height of G is h(u), and R - 1 = d^2 h / dt^2 fixes R
    alpha1 = np.cross(rP, Rm.T @ np.array([fhat[0], fhat[1], 1.0])) / INERTIA
    alpha0 = -np.cross(wb, INERTIA * wb) / INERTIA
    udot = np.cross(u, wb)
    hess = np.diag(MINV) / hh - np.outer(MINV * u, MINV * u) / hh**3
    K0 = udot @ hess @ udot + grad @ np.cross(udot, wb)
    R = (1.0 + K0 + grad @ np.cross(u, alpha0)) / (1.0 - grad @ np.cross(u, alpha1))
    wdot = R * alpha1 + alpha0
    w0, x, y, z = q
    qdot = 0.5 * np.array([-x * wb[0] - y * wb[1] - z * wb[2], w0 * wb[0] + y * wb[2] - z * wb[1],
                           w0 * wb[1] + z * wb[0] - x * wb[2], w0 * wb[2] + x * wb[1] - y * wb[0]])
    return np.concatenate([qdot, wdot, vh, R * fhat])


def _independent(y0, t_out):
    """Integrate from the paper's state y0 (axis in the X-Z plane, phi = 0, G at the origin)."""
    from scipy.integrate import solve_ivp

    U, V, Om, Lam, th, n = y0
    q0 = np.array([math.cos(th / 2), 0.0, math.sin(th / 2), 0.0])
    k = np.array([math.sin(th), 0.0, math.cos(th)])
    w = Om * np.array([0, 0, 1.0]) + Lam * np.array([0, 1.0, 0]) + (n - Om * math.cos(th)) * k
    s0 = np.concatenate([q0, _quat_matrix(q0).T @ w, [0.0, 0.0], [U, V]])
    fine = np.union1d(np.arange(0.0, t_out[-1], 0.01), t_out)  # dense enough to unwrap the angles
    sol = solve_ivp(_newton_euler, (0.0, t_out[-1]), s0, method="DOP853", rtol=1e-12, atol=1e-14, t_eval=fine)
    assert sol.success
    Rs = np.array([_quat_matrix(q) for q in sol.y[0:4].T])
    psi = np.unwrap(np.arctan2(Rs[:, 1, 2], Rs[:, 0, 2]))
    phi = np.unwrap(np.arctan2(Rs[:, 2, 1], -Rs[:, 2, 0]))
    G = sol.y[7:9].T
    u = Rs[:, 2, :]
    rP = -MINV * u / np.sqrt(np.sum(u * u * MINV, axis=1))[:, None]
    P = G + np.einsum("nij,nj->ni", Rs, rP)[:, 0:2]
    pick = np.searchsorted(fine, t_out)
    return psi[pick] - psi[0], phi[pick] - phi[0], np.linalg.norm(G[pick] - G[0], axis=1), \
        np.linalg.norm(P[pick] - P[0], axis=1)


@pytest.fixture(scope="module")
def prolate_run():
    body = pk.Spheroid(A_RATIO)
    y0 = pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5)
    traj = pk.simulate(pk.Model(body, pk.RegularisedCoulomb(MU, EPS)), y0, 200.0, rtol=1e-12)
    return y0, traj


def test_pose_agrees_with_an_independent_newton_euler_model(prolate_run):
    """The angle turned by the axis and about it, and the distances travelled by G and by P,
    at several times before the jump (t* = 45.26), to 1e-7 relative."""
    y0, traj = prolate_run
    assert traj.status is pk.Status.JUMPED and traj.t > 40
    times = np.array([3.0, 9.0, 17.0, 25.0, 35.0, 44.0])
    dpsi, dphi, dG, dP = _independent(y0, times)
    df = traj.sample(np.concatenate([[0.0], times]))
    got_G = np.hypot(df.X - df.X[0], df.Y - df.Y[0])[1:]
    got_P = np.hypot(df.X_P - df.X_P[0], df.Y_P - df.Y_P[0])[1:]
    np.testing.assert_allclose(df.psi[1:], dpsi, rtol=1e-7)
    np.testing.assert_allclose(df.phi[1:], dphi, rtol=1e-7)
    np.testing.assert_allclose(got_G, dG, rtol=1e-7)
    np.testing.assert_allclose(got_P, dP, rtol=1e-7)
    assert np.all(np.abs(dpsi) > 20) and np.all(dG > 1e-3)  # the comparison is not of small numbers


def test_pose_start_values_rotate_and_translate_the_whole_motion(prolate_run):
    """psi0 turns the path about the start of G, (X0, Y0) moves it, phi0 adds to phi: an
    exact symmetry of the table, checked on the same run."""
    _, traj = prolate_run
    ts = np.linspace(0.0, traj.t, 57)
    base = traj.pose(ts)
    traj2 = pk.simulate(traj.model, traj.x0, 200.0, rtol=1e-12, pose0=dict(psi=0.7, phi=-1.1, X=2.0, Y=-3.0))
    moved = traj2.pose(ts)
    assert traj2.t == traj.t  # no number of the run depends on the pose
    np.testing.assert_allclose(moved.psi - base.psi, 0.7, atol=1e-12)
    np.testing.assert_allclose(moved.phi - base.phi, -1.1, atol=1e-12)
    for x, y in (("X", "Y"), ("X_P", "Y_P")):
        z = (base[x] + 1j * base[y]).to_numpy() * np.exp(0.7j) + (2.0 - 3.0j)
        np.testing.assert_allclose(moved[x], z.real, atol=1e-12)
        np.testing.assert_allclose(moved[y], z.imag, atol=1e-12)


def test_pose_is_the_same_in_both_charts_and_with_cvodes(prolate_run):
    """The vector chart carries k and v in fixed axes (psi from the azimuth of k, X + iY from v),
    the Euler chart rotating axes (psi from Omega, X + iY from (U + iV) e^{i psi}): independent
    routes to the same numbers. CVODES' cubic Hermite output gives them to its accuracy."""
    y0, traj = prolate_run
    ts = np.linspace(0.0, 40.0, 9)
    ref = traj.pose(ts)
    body = traj.model.body
    vec = pk.simulate(pk.Model(body, pk.RegularisedCoulomb(MU, EPS), chart="vector"), pk.core.to_chart("vector", y0), 41.0,
                      rtol=1e-12)
    got = vec.pose(ts)
    for name in pose.POSE_COLUMNS:
        np.testing.assert_allclose(got[name], ref[name], rtol=1e-8, atol=1e-9, err_msg=name)
    cv = pk.simulate(traj.model, y0, 41.0, rtol=1e-10, backend="cvodes")
    got = cv.pose(ts)
    for name in pose.POSE_COLUMNS:
        np.testing.assert_allclose(got[name], ref[name], rtol=1e-4, atol=1e-5, err_msg=name)


def test_pose_through_flights_and_impacts():
    """Across lift-off, flight and touchdown (restitution 0.5): G moves uniformly in flight
    with the velocity it had at lift-off, the angles and positions are continuous at every
    event, and the azimuth in flight is the integral of the precession rate."""
    body = pk.Spheroid(1.5)
    model = pk.Model(body, pk.Coulomb(0.1))
    y0 = pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=11.0)
    traj = pk.simulate(model, y0, 60.0, stop_at="none", restitution=0.5, rtol=1e-11)
    flights = [f for f in traj.flights if f.t_touchdown is not None]
    assert len(flights) >= 2
    first = traj.sample([flights[0].t_liftoff]).iloc[0]  # the contact state: no impulse at lift-off
    v_lift = (first.U + 1j * first.V) * np.exp(1j * first.psi)
    for f in flights[:3]:
        ts = np.linspace(f.t_liftoff, f.t_touchdown, 41)
        df = traj.sample(ts)
        for col in ("X", "Y"):
            fit = np.polyfit(ts - ts[0], df[col], 1)
            assert np.max(np.abs(np.polyval(fit, ts - ts[0]) - df[col])) < 1e-12
        # (U + iV) e^{i psi}, the velocity in the paper's turning frame, is constant in flight
        inner = df.iloc[1:-1]
        v = (inner.U + 1j * inner.V).to_numpy() * np.exp(1j * inner.psi.to_numpy())
        slope = (df.X.iloc[-1] - df.X.iloc[0] + 1j * (df.Y.iloc[-1] - df.Y.iloc[0])) / (ts[-1] - ts[0])
        assert np.max(np.abs(slope - v)) < 1e-9
        if f is flights[0]:
            assert abs(slope - v_lift) < 1e-9
        Om = traj.sample(np.linspace(f.t_liftoff, f.t_touchdown, 2001)).Omega.to_numpy()
        quad = np.trapezoid(Om, dx=(f.t_touchdown - f.t_liftoff) / 2000)
        assert abs((df.psi.iloc[-1] - df.psi.iloc[0]) - quad) < 1e-6
    # continuity: every event seen from just before and just after (the rates bound the change)
    d = 1e-7
    for e in traj.events[:12]:
        if not traj.t0 + d < e.t < traj.t - d:
            continue
        a, b = traj.sample([e.t - d, e.t + d]).iloc[0], traj.sample([e.t - d, e.t + d]).iloc[1]
        for col in pose.POSE_COLUMNS:
            assert abs(b[col] - a[col]) < 50 * d, (e.name, col)


def test_pose_needs_dense_output():
    body = pk.Spheroid(1.5)
    traj = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, 1.5, omega0=10.5), 5.0, dense=False)
    with pytest.raises(pk.ParameterError, match="dense"):
        traj.pose([1.0])
    with pytest.raises(pk.ParameterError, match="pose0"):
        pk.simulate(traj.model, traj.x0, 5.0, pose0=dict(psi=float("nan")))


def test_rotation_matrix_is_zyz(prolate_run):
    """R = Rz(psi) Ry(theta) Rz(phi): its third column is the axis k of the paper's section 2,
    and along a run dR/dt R^T is the body's angular velocity w = Omega e_Z + Lambda e_Y +
    (n - Omega cos theta) k (phasekit.core.charts.euler_to_vector, turned by psi), which fixes the signs
    and the conventions of all three angles."""
    R = rotation_matrix(0.4, 1.1, -2.0)
    np.testing.assert_allclose(R[:, 2], [math.sin(1.1) * math.cos(0.4), math.sin(1.1) * math.sin(0.4), math.cos(1.1)],
                               atol=1e-15)
    np.testing.assert_allclose(R @ R.T, np.eye(3), atol=1e-15)
    _, traj = prolate_run
    h = 1e-4
    for t in (5.0, 20.0, 40.0):
        df = traj.sample([t - h, t, t + h])
        Rs = rotation_matrix(df.psi.to_numpy(), df.theta.to_numpy(), df.phi.to_numpy())
        W = (Rs[2] - Rs[0]) / (2 * h) @ Rs[1].T
        w = np.array([W[2, 1], W[0, 2], W[1, 0]])
        y = df.iloc[1][list(pk.core.PAPER_NAMES)].to_numpy(float)
        psi = df.psi.iloc[1]
        Rz = np.array([[math.cos(psi), -math.sin(psi), 0], [math.sin(psi), math.cos(psi), 0], [0, 0, 1]])
        np.testing.assert_allclose(w, Rz @ euler_to_vector(y)[3:6], atol=1e-6 * max(1.0, np.abs(w).max()))
