"""Generated cases of steady_structure over bodies (spheroids from flat to long, a = 1 included,
with or without an offset and own moments; tippe tops, A = C included; eggs) and laws: every case
ends as a completed structure that holds together (its ends are what they say: q = 0 at a static
end, D = 0 at an infinite-spin end, the poles at 0 and pi; its states at a rate are those of
fixed_points), as a failed one with its reason, or as a ParameterError naming an argument.
Derandomised; a hang fails the suite by its timeout and each structure has a wall budget."""

import collections
import math

import phasekit as pk
from phasekit.steady.branches import END_KINDS, precession_geometry

import numpy as np
import pytest

from ..generated_inputs import fuzz, generated, hang_guard, report, st, thin_suites, weighted

COUNTS: dict[str, collections.Counter] = collections.defaultdict(collections.Counter)


@pytest.fixture(scope="module", autouse=True)
def _enough_valid_cases():
    """The suite counts: most generated cases must be completed structures, not refusals."""
    yield
    report(COUNTS, "generated steady structures (valid / failed with a reason / clear error):", None)
    assert thin_suites(COUNTS) == {}

#: a ParameterError may name these (the arguments of the bodies, the laws and the call)
ARGUMENTS = {"a", "offset", "A", "C", "w", "mu", "eps", "omega0", "n0"}
RATES = [0.0, 1e-6, 0.3, 1.0, 3.0, 10.0, 1e3, 1e6, 1e12, -2.0]


def spheroids():
    aspect = st.one_of(st.sampled_from([1.0, 1.0 + 1e-9, 0.999, 1e-3, 1e3]),
                       st.floats(-2.0, 2.0).map(lambda e: float(10.0**e)))
    return st.tuples(aspect, st.sampled_from([0.0, 0.0, 0.1, 0.3, 0.44]), st.sampled_from([None, None, 1.0, 0.6])).map(
        lambda t: ("spheroid", {"a": t[0], "offset": t[1] * t[0]} | ({} if t[2] is None else {"A": t[2] * 0.4, "C": 0.4})))


def tippe_tops():
    return st.tuples(st.sampled_from([0.0, 0.05, 0.3, 0.45, 0.9]), st.sampled_from([None, 1.0, 0.5, 0.9, 1.2, 2.0])).map(
        lambda t: ("tippe-top", {"offset": t[0]} | ({} if t[1] is None else {"A": t[1] * 0.4, "C": 0.4})))


def eggs():
    return st.tuples(st.sampled_from([0.3, 0.7, 1.3, 2.5]), st.sampled_from([0.0, 0.02, 0.06])).map(
        lambda t: ("egg", {"a": t[0], "w": t[1]}))


def laws():
    return st.tuples(st.sampled_from(["viscous", "coulomb", "regularised"]), st.sampled_from([0.1, 0.3, 1e-3])).map(
        lambda t: {"viscous": pk.Viscous, "coulomb": pk.Coulomb}.get(t[0], lambda mu: pk.RegularisedCoulomb(mu, 1e-3))(t[1]))


def build(kind, args):
    if kind == "spheroid":
        return pk.Spheroid(args["a"], args.get("A"), args.get("C"), offset=args["offset"])
    if kind == "tippe-top":
        return pk.EccentricSphere(args["offset"], A=args.get("A"), C=args.get("C"))
    return pk.Egg(args["a"], args["w"])


def check_ends(s) -> None:
    """Each branch's ends are ordered and of the kind they say; the curve is real inside."""
    body = s.body
    assert s.signature == (" | ".join(b.label for b in s.branches) or "none")
    for b, nxt in zip(s.branches, s.branches[1:]):
        assert b.ends[1].theta <= nxt.ends[0].theta
    for b in s.branches:
        lo, hi = b.ends
        assert 0.0 <= lo.theta < hi.theta <= math.pi and {lo.kind, hi.kind} <= set(END_KINDS)
        for e in b.ends:
            q, rho2, _, D = (float(v[0]) for v in precession_geometry(body, e.theta)[:4])
            if e.kind == "pole":
                assert e.theta in (0.0, math.pi) and e.pole == ("0" if e.theta == 0.0 else "pi") and e.Omega > 0
            elif e.kind == "static":
                assert abs(q) <= 1e-8 * rho2
            else:
                assert abs(D) <= 1e-8 * (abs(body.A - body.C) + body.C) * rho2
        om, _ = s.precession(0.5 * (lo.theta + hi.theta))
        assert np.isfinite(om[0]) and om[0] > 0  # Omega^2 > 0 inside (a family crossing aside)
        assert np.all((b.theta >= lo.theta) & (b.theta <= hi.theta) & np.isfinite(b.Omega) & np.isfinite(b.n))
    for e in s.static_equilibria:
        if e.kind == "tilted":
            q, rho2 = (float(v[0]) for v in precession_geometry(body, e.theta)[:2])
            assert abs(q) <= 1e-8 * rho2


def states_or_failure(call):
    try:
        return call()
    except pk.ConvergenceError as exc:
        assert str(exc) and "\n" not in str(exc)
        return "failed"


@hang_guard(900)
@generated(lambda: weighted((spheroids(), 5), (tippe_tops(), 3), (eggs(), 1)),
           laws,
           lambda: st.sampled_from([(True, True), (False, True), (False, False), (False, False)]),
           lambda: st.tuples(st.sampled_from(["omega0", "n0"]), st.sampled_from(RATES)),
           **fuzz(50))
def test_generated_structures_end_in_a_result_a_failure_or_a_named_error(body, law, detail, rate):
    stability, samples = detail
    try:
        made = build(*body)
    except pk.ParameterError as exc:
        assert exc.param in ARGUMENTS and str(exc).startswith(f"`{exc.param}` ") and "\n" not in str(exc)
        COUNTS["steady_structure"]["error"] += 1
        return
    s = pk.steady_structure(made, law, stability=stability, samples=samples, max_wall=120.0)
    COUNTS["steady_structure"]["failed" if s.status is pk.Status.FAILED else "valid"] += 1
    assert isinstance(s, pk.steady.SteadyStructure)
    if s.status is pk.Status.FAILED:
        assert s.reason and "\n" not in s.reason and s.branches == ()
        return
    assert s.status is pk.Status.COMPLETED and s.reason is None
    if s.degenerate is not None:
        assert s.signature == "degenerate" and s.branches == () and made.flip_symmetric
    else:
        check_ends(s)
    key, value = rate
    mine = states_or_failure(lambda: s.at(**{key: value}))
    ref = states_or_failure(lambda: pk.fixed_points(pk.Model(made, law), **{key: value}))
    if mine == "failed" or ref == "failed":
        assert mine == ref == "failed"
        return
    assert [p.kind for p in mine] == [p.kind for p in ref], (made, law, rate)
    for p, r in zip(mine, ref):
        assert np.all(np.abs(p.x - r.x) <= 1e-9 * np.maximum(np.abs(r.x), 1.0)), (made, law, rate, p.x, r.x)
        assert (p.n_unstable, p.classification) == (r.n_unstable, r.classification), (made, law, rate)


@pytest.mark.parametrize("call", [
    lambda: pk.steady_structure("sphere", pk.Viscous(0.1)),
    lambda: pk.steady_structure(pk.Spheroid(1.5), "viscous"),
    lambda: pk.steady_structure(pk.Spheroid(1.5), pk.Viscous(0.1), samples="no"),
    lambda: pk.steady_structure(pk.Spheroid(1.5), pk.Viscous(0.1), max_wall=-1.0),
    lambda: pk.steady_structure(pk.Spheroid(1.5), pk.Viscous(0.1), samples=False).at(omega0=math.inf),
    lambda: pk.steady_structure(pk.Spheroid(1.5), pk.Viscous(0.1), samples=False).at(n0=1e13),
    lambda: pk.steady_structure(pk.Spheroid(1.5), pk.Viscous(0.1), samples=False).at(omega0=1.0, n0=1.0),
], ids=["body", "friction", "samples", "max_wall", "omega0", "n0", "both"])
def test_bad_arguments_are_named(call, request):
    with pytest.raises(pk.ParameterError) as info:
        call()
    case = request.node.callspec.id
    assert info.value.param == ("omega0" if case == "both" else case)  # the argument at fault, not another
    assert str(info.value).startswith(f"`{info.value.param}` ")
