"""The steady-state structure (phasekit.steady.structure) against independent computations: the
vector chart's Newton-Euler equations, the tippe top's closed forms and energy criterion, the
pole criterion, closed-form statics, and the pointwise fixed points."""

import json

import phasekit as pk
import phasekit.studies as ps
from phasekit.core import charts
from phasekit.core.hybrid import Mode
from phasekit.steady.branch_stability import linearise_precession
from phasekit.steady.branches import precession_on_branch
from phasekit.steady.rolling import rolling_state
from phasekit.steady.structure import steady_structure
from phasekit.theory import tippetop
from tests.helpers import run_cli

import numpy as np
import pytest

ROT = np.zeros((8, 8))  # generator of rotations about the vertical on (k, w, v)
for i in (0, 3):
    ROT[i, i + 1], ROT[i + 1, i] = -1.0, 1.0
ROT[6, 7], ROT[7, 6] = -1.0, 1.0


def vector_residual(body, theta, om, n):
    """|f(x) - Omega G x| / scale in the vector chart (Newton-Euler in fixed axes, derived
    independently of (2.7)): zero exactly for a steady precession (a relative equilibrium)."""
    model = pk.Model(body, pk.Viscous(1.0), "vector")
    x = charts.euler_to_vector([0.0, 0.0, om, 0.0, theta, n])
    r = model.rhs(x, Mode.SLIDING) - om * ROT @ x
    return float(np.max(np.abs(r))) / max(1.0, om * om, n * n)


def vector_precession(body, theta, guess):
    """(Omega, n) of the steady precession at theta, by Newton on the vector chart alone."""
    from scipy.optimize import least_squares

    model = pk.Model(body, pk.Viscous(1.0), "vector")

    def res(p):
        x = charts.euler_to_vector([0.0, 0.0, p[0], 0.0, theta, p[1]])
        return (model.rhs(x, Mode.SLIDING) - p[0] * ROT @ x)[[3, 4, 5]]

    sol = least_squares(res, guess, xtol=1e-15, ftol=1e-15, gtol=1e-15)
    return sol.x


TOPS = [(0.3, 0.38, 0.4), (0.3, 0.2, 0.4), (0.3, 0.6, 0.4), (0.1, 0.35, 0.4), (0.5, 0.2, 0.4), (0.45, 0.62, 0.4)]


@pytest.mark.parametrize("alpha,A,C", TOPS)
def test_tippe_top_structures_follow_the_inversion_interval(alpha, A, C):
    s = steady_structure(pk.EccentricSphere(alpha, A=A, C=C), pk.Viscous(0.3), stability=False)
    lo, hi = tippetop.inversion_interval(alpha)
    expected = "pole0-polePi" if lo < A / C < hi else "inf-polePi" if A / C <= lo else "pole0-inf"
    assert s.signature == expected
    # the infinite-spin asymptote in closed form: D = (A - C) cos + C alpha = 0
    for e in (e for b in s.branches for e in b.ends if e.kind == "infinite-spin"):
        assert e.theta == pytest.approx(np.arccos(-C * alpha / (A - C)), abs=1e-12)
    # the pole ends are the closed-form critical spins of the upright and inverted states
    for e in (e for b in s.branches for e in b.ends if e.kind == "pole"):
        ref = tippetop.upright_unstable_spin(alpha, A, C) if e.pole == "0" else tippetop.inverted_stable_spin(alpha, A, C)
        assert abs(e.n) == pytest.approx(ref, rel=1e-12)


def test_tippe_top_stability_along_the_branch_is_the_energy_criterion():
    """Viscous friction: an intermediate state is stable iff g'(z) < 0 (tippetop: energy and
    Jellett's integral, a Lyapunov argument independent of the linearisation)."""
    for alpha, A, C in [(0.3, 0.38, 0.4), (0.3, 0.2, 0.4), (0.45, 0.62, 0.4)]:
        s = steady_structure(pk.EccentricSphere(alpha, A=A, C=C), pk.Viscous(0.3))
        for b in s.branches:
            z = np.cos(b.theta)
            dz = 1e-6
            gp = (tippetop.steady_state_jellett_sq(alpha, A, C, z + dz) - tippetop.steady_state_jellett_sq(alpha, A, C, z - dz))
            decided = np.abs(gp) > 1e-6 * np.abs(tippetop.steady_state_jellett_sq(alpha, A, C, z))
            assert np.array_equal(b.stable[decided], (gp < 0)[decided])
            assert decided.sum() > 0.9 * b.theta.size


BODIES = [pk.Spheroid(1.5, offset=0.2), pk.Spheroid(0.6, offset=0.1), pk.Spheroid(2.5, offset=0.6, A=1.2, C=0.5),
          pk.Spheroid(0.5, offset=0.02, A=0.3, C=0.35), pk.EccentricSphere(0.3, A=0.38, C=0.4), pk.Egg(1.3, 0.05)]


@pytest.mark.parametrize("body", BODIES, ids=repr)
def test_every_sample_is_a_steady_precession_of_the_vector_chart(body):
    s = steady_structure(body, pk.Viscous(0.1), stability=False)
    assert s.branches
    for b in s.branches:
        assert b.theta.size >= 30 and np.all(np.diff(b.theta) > 0)
        worst = max(vector_residual(body, t, o, m) for t, o, m in zip(b.theta, b.Omega, b.n))
        assert worst < 1e-12
        for k in np.linspace(0, b.theta.size - 1, 7).astype(int)[1:-1]:
            om, n = vector_precession(body, b.theta[k], [1.01 * b.Omega[k], 0.99 * b.n[k] + 0.01])
            assert om == pytest.approx(b.Omega[k], rel=1e-10) and n == pytest.approx(b.n[k], rel=1e-9, abs=1e-12)


@pytest.mark.parametrize("body", BODIES[:4], ids=repr)
def test_ends_are_zeros_of_the_closed_forms_and_poles_meet_the_pole_criterion(body):
    s = steady_structure(body, pk.Viscous(0.1), stability=False)
    a, alpha = body.a, body.offset
    k = a * a - 1
    c_static = alpha / np.sqrt(k * (k - alpha**2)) if k * (k - alpha**2) > 0 else None
    for b in s.branches:
        lo, hi = b.ends
        assert lo.theta < hi.theta
        for e in b.ends:
            if e.kind == "static":  # h_theta = 0: (a^2 - 1) c / sqrt(1 + (a^2 - 1) c^2) = offset
                assert abs(np.cos(e.theta)) == pytest.approx(c_static, abs=1e-12)
            elif e.kind == "pole":  # the pole criterion, from h and h_tt at the pole
                crit = pk.theory.pole_stability_threshold(body, "upright" if e.pole == "0" else "inverted")
                assert abs(e.n) == pytest.approx(crit.threshold, rel=1e-11)
        # Omega tends to 0 at a static end and diverges at an infinite-spin end
        if lo.kind == "static":
            assert b.Omega[0] < 1e-2
        if hi.kind == "infinite-spin":
            assert b.Omega[-1] > 1e2
    statics = [e.theta for e in s.static_equilibria if e.kind == "tilted"]
    assert len(statics) == (0 if c_static is None or c_static >= 1 else 1)


def test_static_equilibria_of_a_body_with_many():
    """H(c) = 1 + eps T_k(c): a convex body (eps k^2 < 1) with k + 1 static equilibria, at the
    extrema of the Chebyshev polynomial, alternately minima and maxima of the height."""
    k, eps = 9, 0.004
    body = pk.CustomBody(lambda c: 1 + eps * _cheb(k, c), A=0.4, C=0.4, variable="cos")
    s = steady_structure(body, pk.Viscous(0.1), stability=False)
    thetas = np.array([e.theta for e in s.static_equilibria])
    expected = np.sort(np.arccos(np.cos(np.pi * np.arange(k + 1) / k)))
    assert thetas == pytest.approx(expected, abs=1e-10)
    stable = [e.stable for e in s.static_equilibria]
    assert all(stable[i] != stable[i + 1] for i in range(k))


def _cheb(k, c):
    t0, t1 = 1, c
    for _ in range(k - 1):
        t0, t1 = t1, 2 * c * t1 - t0
    return t1


@pytest.mark.parametrize("a", [1.5, 2 / 3, 3.0])
def test_flip_symmetric_spheroid_reproduces_part_one_and_the_fixed_points(a):
    body = pk.Spheroid(a)
    law = pk.Viscous(0.1)
    s = steady_structure(body, law)
    # one branch from pole to pole crossing the horizontal family at Omega0^2 = (a^2 - 1)/(a^2 C - A)
    assert s.signature == "pole0-cross-polePi"
    [b] = s.branches
    assert b.crossings == (np.pi / 2,)
    [fam] = [f for f in s.families if f.kind == "precession"]
    assert fam.critical == pytest.approx(pk.theory.horizontal_stability_threshold(body.A, body.C, a), rel=1e-9)
    for e in b.ends:
        assert abs(e.n) == pytest.approx(pk.theory.vertical_stability_threshold(body.A, body.C, a), rel=1e-12)
    # uniform spheroids: Omega^2 = 5 / h along the whole branch
    assert b.Omega**2 == pytest.approx(5 / body.h(b.theta)[0], rel=1e-12)
    model = pk.Model(body, law)
    for kw in ({"omega0": 0.999 * fam.critical}, {"omega0": 0.5 * (b.Omega.min() + b.Omega.max())}, {"omega0": 3.0},
               {"n0": 0.5 * abs(b.ends[0].n)}, {"n0": 1.3}):
        mine, ref = s.at(**kw), pk.fixed_points(model, **kw)
        assert [p.kind for p in mine] == [p.kind for p in ref]
        for p, r in zip(mine, ref):
            assert p.x == pytest.approx(r.x, rel=1e-12, abs=1e-12)
            assert np.max(np.abs(p.eigenvalues - r.eigenvalues)) <= 1e-12 * max(1.0, np.max(np.abs(r.eigenvalues)))


@pytest.mark.parametrize("body,law", [(pk.Spheroid(1.5, offset=0.2), pk.Viscous(0.1)),
                                      (pk.Spheroid(0.6, offset=0.1), pk.Viscous(0.1)),
                                      (pk.Egg(1.3, 0.05), pk.Viscous(0.2)),
                                      (pk.Spheroid(0.6, offset=0.1), pk.Coulomb(0.1)),
                                      (pk.Spheroid(1.5), pk.RegularisedCoulomb(0.1, 1e-3))], ids=repr)
def test_stability_along_branches_matches_the_pointwise_linearisation(body, law):
    s = steady_structure(body, law)
    model = pk.Model(body, law)
    rng = np.random.default_rng(7)
    for b in s.branches:
        compared = 0
        for t in rng.uniform(b.theta[0], b.theta[-1], 20):
            if min(t, np.pi - t) < 0.05 or any(abs(t - c.theta) < 1e-6 for c in b.changes):
                continue  # the rotating chart there; or too near a change
            om, n = precession_on_branch(body, np.array([t]))
            fps = [p for p in pk.fixed_points(model, omega0=float(om[0])) if abs(p.x[4] - t) < 1e-8]
            if body.flip_symmetric and t > np.pi / 2:
                fps = [pk.steady.linearise(model, [0, 0, om[0], 0, t, n[0]])]
            [fp] = fps
            assert fp.n_unstable == b.n_unstable_at(t)
            compared += 1
        assert compared >= 5
        for c in b.changes:  # states of opposite stability bracket every change, within 1e-8
            lo, hi = c.bracket
            assert hi - lo <= 1e-8
            om_lo, n_lo = (float(v[0]) for v in precession_on_branch(body, np.array([lo])))
            om_hi, n_hi = (float(v[0]) for v in precession_on_branch(body, np.array([hi])))
            # pointwise, in the paper's chart (the structure bisected with linearise_precession)
            chart = "euler" if min(lo, np.pi - hi) >= 0.05 else "rotating"
            f_lo = pk.steady.linearise(model, [0, 0, om_lo, 0, lo, n_lo]) if chart == "euler" else \
                linearise_precession(s.model, lo, om_lo, n_lo, chart=chart)
            f_hi = pk.steady.linearise(model, [0, 0, om_hi, 0, hi, n_hi]) if chart == "euler" else \
                linearise_precession(s.model, hi, om_hi, n_hi, chart=chart)
            assert f_lo.n_unstable != f_hi.n_unstable
            assert (f_lo.n_unstable, f_hi.n_unstable) == (c.below, c.above)


def test_euler_and_rotating_vector_charts_give_the_same_stability():
    body, law = pk.Spheroid(1.5, offset=0.2), pk.Viscous(0.1)
    model = pk.Model(body, law)
    for t in (0.02, 0.1, 0.5, 0.9, 1.2, 2.0, 3.0):
        om, n = (float(v[0]) for v in precession_on_branch(body, np.array([t])))
        if not np.isfinite(om):
            continue
        e = linearise_precession(model, t, om, n, chart="euler")
        r = linearise_precession(model, t, om, n, chart="rotating")
        # the rotating chart has two more zero eigenvalues (|k| and the azimuth): compare the others
        re_e = np.sort(e.eigenvalues[np.abs(e.eigenvalues) > 1e-6].real)
        re_r = np.sort(r.eigenvalues[np.abs(r.eigenvalues) > 1e-6].real)
        assert re_e.size == 5 and re_r == pytest.approx(re_e, abs=1e-9 * max(1.0, om * om))
        assert e.n_unstable == r.n_unstable


def test_displaced_spheroid_breaks_part_ones_degenerate_structure():
    """The symmetric pitchfork at the horizontal state unfolds: a static equilibrium and an
    infinite-spin asymptote appear near pi/2 (part III's abstract), and A = C is the boundary
    where they meet again."""
    assert steady_structure(pk.Spheroid(1.5, offset=0.2), pk.Viscous(0.1), stability=False).signature == \
        "pole0-inf | static-polePi"
    at_boundary = steady_structure(pk.Spheroid(1.5, offset=0.5), pk.Viscous(0.1), stability=False)  # A = C = 0.4
    assert at_boundary.signature == "pole0-cross-polePi"
    assert [f.kind for f in at_boundary.families] == ["pole", "pole", "precession", "rolling"]


def test_the_atlas_bisection_finds_the_boundary_a_equals_c_and_names_its_bifurcation():
    """ps.trace_boundary (studies/steady_structure.py's atlases) across A = C of the displaced
    spheroid (offset 0.5 at a = 1.5): the traced point brackets it, and the bifurcation is the one
    pk.steady.bifurcation_between names for the structures on either side of the bracket."""
    def at(panel, x, y):  # x: offset / a
        return steady_structure(pk.Spheroid(1.5, offset=1.5 * x), pk.Viscous(0.1), stability=False)

    b = ps.trace_boundary(at, "demo", (0.3, 0.0), (0.36, 0.0), 0.06, xtol=1e-3, key="k")
    assert abs(b.x - 1 / 3) <= b.width / 2 + 1e-12 and b.width <= 0.06 * 1e-3
    lo, hi = at("demo", b.x - b.width / 2, 0.0), at("demo", b.x + b.width / 2, 0.0)
    assert (b.below, b.above) == (lo.signature, hi.signature) and b.bifurcation == pk.steady.bifurcation_between(lo, hi)


@pytest.mark.parametrize("a", [1.5, 2 / 3])
def test_part_one_four_classes_with_their_stability(a):
    """Part I's four classes of the flip-symmetric spheroid: the spin about the vertical, the
    horizontal precession, the intermediate precessions (the branch) and rolling on the equator
    along a straight line. Each family state is an exact steady state, and the located change
    of stability of the rolling family is bracketed by states of opposite stability."""
    body, law = pk.Spheroid(a), pk.Viscous(0.1)
    s = steady_structure(body, law)
    assert sorted(f.kind for f in s.families) == ["pole", "pole", "precession", "rolling"] and len(s.branches) == 1
    model = pk.Model(body, law)
    [roll] = [f for f in s.families if f.kind == "rolling"]
    assert roll.theta == np.pi / 2 and roll.criticals
    for n in (0.3, 3.0, 30.0):
        x = rolling_state(body, roll.theta, n)
        assert np.max(np.abs(model.rhs(x, Mode.SLIDING))) < 1e-14 * n * n + 1e-15
    for c in roll.criticals:
        lo = pk.steady.linearise(model, rolling_state(body, roll.theta, c * (1 - 1e-8)))
        hi = pk.steady.linearise(model, rolling_state(body, roll.theta, c * (1 + 1e-8)))
        assert lo.n_unstable != hi.n_unstable


def test_cli_steady_states_json_and_bad_input():
    code, out, err = run_cli("steady-states", "--body", "spheroid", "--a", "1.5", "--offset", "0.2", "--A", "0.61",
                              "--C", "0.4", "--mu", "0.1", "--friction", "viscous", "--json")
    assert code == 0 and err == ""
    d = json.loads(out)
    assert d["signature"] == "pole0-inf | static-polePi"
    for b in d["branches"]:
        kinds = [e["kind"] for e in b["ends"]]
        assert all(k in ("pole", "static", "infinite-spin") for k in kinds)
        assert b["ends"][0]["theta"] < b["ends"][1]["theta"]
        th = np.array([s["theta"] for s in b["samples"]])
        om, n = precession_on_branch(pk.Spheroid(1.5, offset=0.2, A=0.61, C=0.4), th)
        assert np.array([s["Omega"] for s in b["samples"]]) == pytest.approx(om, rel=1e-14)
        assert np.array([s["n"] for s in b["samples"]]) == pytest.approx(n, rel=1e-12, abs=1e-14)
        model = pk.Model(pk.Spheroid(1.5, offset=0.2, A=0.61, C=0.4), pk.Viscous(0.1))
        for s in b["samples"][5::20]:  # the stability reported is the pointwise linearisation's
            if min(s["theta"], np.pi - s["theta"]) >= 0.05:
                assert s["stable"] == pk.steady.linearise(model, [0, 0, s["Omega"], 0, s["theta"], s["n"]]).stable
    assert [s["kind"] for s in d["static_equilibria"]] == ["pole", "tilted", "pole"]
    code, out, err = run_cli("steady-states", "--a", "1.5", "--offset", "1.6", "--mu", "0.1")
    assert code == 2 and "--offset" in err and len(err.strip().splitlines()) == 1


# -- generated command lines ------------------------------------------------------------------

from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

_NUM = st.one_of(st.floats(allow_nan=True, allow_infinity=True, width=32), st.sampled_from(["0", "-1", "1e9", "abc", ""]))


@st.composite
def _structure_argv(draw):
    body = draw(st.sampled_from(["spheroid", "tippe-top", "egg"]))
    argv = ["steady-states", "--body", body, "--mu", draw(st.sampled_from(["0.1", "0.3", "0", "-1", "nan"]))]
    options = {"spheroid": ["--a", "--offset", "--A", "--C"], "tippe-top": ["--offset", "--A", "--C"], "egg": ["--a", "--w"]}
    for flag in draw(st.lists(st.sampled_from(options[body] + ["--a", "--w"]), unique=True, max_size=4)):
        value = draw(st.one_of(st.floats(0.05, 3.0).map(lambda v: f"{v:.4g}"), _NUM.map(str)))
        argv += [flag, value]
    argv += draw(st.sampled_from([[], ["--friction", "viscous"], ["--slip-eps", "1e-3"], ["--friction", "magic"]]))
    argv += draw(st.sampled_from([[], ["--omega0", "2"], ["--n0", "3"]]))
    return [*argv, "--json"]


@settings(max_examples=40, deadline=None, derandomize=True, suppress_health_check=list(HealthCheck))
@given(_structure_argv())
def test_generated_steady_states_command_lines_end_in_a_result_or_one_line(argv):
    """Every generated command line gives strict JSON: a structure (ends ordered and of the three
    kinds, finite samples) with exit 0, or an error naming one of the flags typed with exit 2."""
    code, out, err = run_cli(*argv)
    d = json.loads(out, parse_constant=lambda name: (_ for _ in ()).throw(ValueError(name)))
    if code == 0:
        for b in d["branches"]:
            assert b["ends"][0]["theta"] < b["ends"][1]["theta"]
            assert {e["kind"] for e in b["ends"]} <= {"pole", "static", "infinite-spin"}
            assert all(np.isfinite([s["theta"], s["Omega"], s["n"]]).all() for s in b["samples"])
        assert d["signature"] == " | ".join(b["label"] for b in d["branches"]) or d["signature"] == "none"
    else:
        from phasekit import cli

        flags = cli._build_parser().commands["steady-states"]._option_string_actions
        # the flag typed, or a required one left out (e.g. --a for a spheroid)
        assert code == 2 and d["status"] == "error" and d["parameter"] in flags, (argv, d)
        required = {"spheroid": "--a", "tippe-top": "--offset"}.get(argv[argv.index("--body") + 1])
        assert d["parameter"] in argv or (d["parameter"] == required and required not in argv), (argv, d)
        assert len(err.strip().splitlines()) == 1
