"""A run says how it held the table: when it first stuck, how much of it rolled without slip (or,
under a regularised law, crept), how far theta changed, and, when it reaches its end rolling, that
the answer rests on pure rolling (which conserves energy, so the body cannot settle)."""

import phasekit as pk
from phasekit.core.trajectory_io import PURE_ROLLING

import numpy as np
import pytest

from ..helpers import run_cli, strict_json


@pytest.fixture(scope="module")
def egg_run():
    """The 60 x 45 mm egg at 25 rev/s, mu 0.2, 0.6 deg from flat: it sticks within 2 ms."""
    egg, sc = pk.core.egg_of_size("60 mm", "45 mm")
    x0 = pk.gyroscopic_start(egg, np.radians(89.4), omega0=sc.dimensionless("25 rev/s", "rate"))
    return pk.simulate(pk.Model(egg, pk.Coulomb(0.2)), x0, sc.dimensionless("2 s", "time"), stop_at="none"), sc


def test_an_egg_that_sticks_and_rolls_says_it_rests_on_pure_rolling(egg_run):
    run, sc = egg_run
    d = run.to_dict()
    [stick] = [e for e in run.events if e.name == "stick"]
    assert d["t_first_stick"] == stick.t and sc.to_real(stick.t, "time").to("ms").magnitude == pytest.approx(2.03, abs=0.01)
    assert d["rolling_fraction"] == pytest.approx((run.t - stick.t) / run.t, rel=1e-12)
    assert d["rests_on"] == PURE_ROLLING and d["mode_end"] == "rolling"
    # what the note says: while it rolls, the energy stays (no work is done), and so does the tilt
    rolling = run.sample(np.linspace(stick.t + 1e-6, run.t, 400))
    assert np.ptp(rolling["energy"]) < 1e-10 * abs(rolling["energy"].mean())
    assert abs(d["theta_change"]) < 1e-4 and d["theta_start"] == pytest.approx(np.radians(89.4), abs=1e-3)


def test_a_run_that_never_sticks_rests_on_nothing_and_reports_its_rise():
    body = pk.Spheroid(1.5)
    x0 = pk.gyroscopic_start(body, np.pi / 2 - 0.01, omega0=10.5)
    run = pk.simulate(pk.Model(body, pk.Coulomb(0.1)), x0, 200.0)
    d = run.to_dict()
    assert d["t_first_stick"] is None and d["rolling_fraction"] == 0.0 and d["rests_on"] is None
    ends = run.sample([0.0, run.t])["theta"].to_numpy()
    assert d["theta_start"] == pytest.approx(ends[0], abs=1e-12)
    assert d["theta_change"] == pytest.approx(ends[1] - ends[0], abs=1e-9) and d["theta_change"] < -0.5


def test_the_text_summary_says_it_in_words():
    code, out, err = run_cli("simulate", "--body", "egg", "--a", "1.33333", "--mu", "0.2", "--gyroscopic", "--theta0",
                             "89.4 deg", "--omega0", "25 rev/s", "--size", "22.5 mm", "--t-end", "1 s")
    assert code == 0, err
    lines = out.splitlines()
    assert PURE_ROLLING in lines and not any(ln.startswith("stuck:") for ln in lines)
    assert any(ln.startswith("theta fell by ") and "; rolling without slip " in ln and "first from t = " in ln
               for ln in lines)


EGG = ["simulate", "--body", "egg", "--a", "1.33333", "--mu", "0.2", "--gyroscopic", "--theta0", "89.4 deg", "--omega0",
       "25 rev/s", "--size", "22.5 mm", "--si", "--t-end", "0.5 s", "--max-wall", "300"]


@pytest.mark.timeout(900)
def test_the_pure_rolling_note_is_absent_when_spin_friction_takes_energy():
    """The issue's egg (half a second): rolling under exact Coulomb friction alone, the note; with
    spin friction it still rolls, but loses energy (the energy line says how much, to spin friction)."""
    code, out, err = run_cli(*EGG)
    assert code == 0, err
    assert PURE_ROLLING in out.splitlines() and "mode_end: rolling" in out and "energy: " not in out
    code, out, err = run_cli(*EGG, "--spin-friction", "0.1 mm", "--json")
    assert code == 0, err
    d = strict_json(out)
    assert d["mode_end"] == "rolling" and d["rests_on"] is None and d["status"] == "completed" and d["t_rest"] is None
    budget = d["energy_budget"]
    assert budget["dissipated"]["spin-friction"] > 100 * budget["dissipated"]["sliding friction"] > 0
    assert abs(budget["residual"]) < 1e-8 * budget["lost"]
    code, text, err = run_cli(*EGG, "--spin-friction", "0.1 mm")
    lines = text.splitlines()
    assert code == 0 and PURE_ROLLING not in lines and not any(ln.startswith("pure rolling") for ln in lines)
    [energy] = [ln for ln in lines if ln.startswith("energy: ")]
    assert energy.endswith("(give --mass for mJ)") and " M g b, lost " in energy and "spin-friction" in energy


def _fake_run(law, modes, end_mode, status="completed"):
    """A run's record as contact_summary reads it: segments of the given modes, one time unit each."""
    from types import SimpleNamespace

    from phasekit.core.hybrid import Mode
    from phasekit.core.starts import to_chart

    model = pk.Model(pk.Spheroid(1.5), law, "euler")
    x = to_chart("euler", np.array([0.0, 0.0, 1.0, 0.0, 1.0, 0.5]))
    segments = [SimpleNamespace(mode=Mode(m), t0=float(i), t1=float(i + 1)) for i, m in enumerate(modes)]
    return SimpleNamespace(model=model, segments=segments, events=[], t0=0.0, t=float(len(modes)), x0=x, x=x,
                           mode=end_mode, status=status)


def test_every_no_slip_mode_counts_as_rolling_and_only_exact_coulomb_alone_rests_on_pure_rolling():
    from phasekit.core.trajectory_io import contact_summary

    modes = ["sliding", "rolling", "rolling_no_pivot", "sliding_no_pivot", "flight"]
    d = contact_summary(_fake_run(pk.Coulomb(0.2), modes, "rolling"))
    assert d["rolling_fraction"] == pytest.approx(2 / 5, rel=1e-15) and d["rests_on"] == PURE_ROLLING
    assert contact_summary(_fake_run(pk.Coulomb(0.2), modes, "rolling_no_pivot"))["rests_on"] == PURE_ROLLING
    assert contact_summary(_fake_run(pk.Coulomb(0.2), modes, "sliding"))["rests_on"] is None
    # energy leaves a rolling body: spin friction or rolling resistance, or a regularised law (whose
    # "rolling" is slip below 10 eps, still sliding)
    for law in (pk.Coulomb(0.2).with_dissipation(pk.RollingResistance(0.01)), pk.RegularisedCoulomb(0.2, 1e-3),
                pk.Coulomb(0.2).with_dissipation(pk.SpinFriction(0.01))):
        assert contact_summary(_fake_run(law, modes, "rolling"))["rests_on"] is None, law
    assert "--spin-friction" in PURE_ROLLING and "--rolling-resistance" in PURE_ROLLING and "--slip-eps" in PURE_ROLLING
    # a run stopped before its end (a disk that came down flat, a top that reached a limit) rests on nothing
    assert contact_summary(_fake_run(pk.Coulomb(0.2), modes, "rolling", status="stopped"))["rests_on"] is None


def test_a_regularised_law_says_it_slips_slowly_or_creeps_not_that_it_rolls_without_slip():
    """With --slip-eps the "rolling" mode is a slip below 10 eps: the law's own field where mu/eps
    <= 500 (eps = 1e-3, mu = 0.2), the creep on its slow manifold above (eps = 1e-4); the summary
    names which (the JSON's ``holding``), never "rolling without slip"."""
    for eps, says in (("1e-3", "slipping slowly"), ("1e-4", "creeping")):
        code, out, err = run_cli(*EGG, "--slip-eps", eps, "--json")
        d = strict_json(out)
        assert code == 0 and d["holding"].startswith(says) and d["rolling_fraction"] > 0.5 and d["rests_on"] is None
        code, text, _ = run_cli(*EGG, "--slip-eps", eps)
        assert any(f"; {says} (slip" in ln for ln in text.splitlines()), text
        assert not any("rolling without slip" in ln for ln in text.splitlines())
    code, out, _ = run_cli(*EGG, "--json")
    assert strict_json(out)["holding"] == "rolling without slip"
