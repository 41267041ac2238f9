"""Task runs (``run_tasks``, ``run_pending``) in this process and on Dask: wall budgets that leave
the rest for a rerun, scheduler addresses refused at once, model packs shared run after run,
task functions shipped by value."""

from __future__ import annotations

import sys
import time
from dataclasses import asdict, dataclass, replace

import phasekit as pk
import phasekit.studies as ps
from phasekit.studies import SearchRow
from phasekit.sweep import ModelPack, ResultStore, TaskSpec, run_tasks
from phasekit.thresholds import Definition, find_threshold

import pytest


@dataclass(frozen=True)
class Row:
    key: str
    value: float


def test_a_map_with_a_wall_budget_leaves_the_rest_for_a_rerun():
    done = []

    def slow(prev, k):
        time.sleep(0.05)
        return k

    specs = [pk.sweep.TaskSpec(f"k{k}", slow, (k,)) for k in range(40)]
    res = pk.sweep.run_tasks(specs, store_get=lambda key: None, on_result=lambda s, r: done.append(s.key), progress=False,
                       max_wall=0.3)
    assert 0 < len(res) == len(done) < 40
    stored = dict.fromkeys(done, 0)
    again = pk.sweep.run_tasks(specs, store_get=stored.get, on_result=lambda s, r: done.append(s.key), progress=False)
    assert len(again) == 40 and len(done) == 40


def test_a_bad_scheduler_is_refused_when_no_work_is_left():
    pytest.importorskip("dask.distributed")
    specs = [pk.sweep.TaskSpec("k0", lambda prev: 0)]
    with pytest.raises(pk.ParameterError) as info:
        pk.sweep.run_pending(specs, store_get=lambda key: 0, on_result=lambda s, r: None, warm_up=lambda: None,
                       scheduler="tcp://127.0.0.1:1")
    assert info.value.param == "scheduler"
    ran = pk.sweep.run_pending(specs, store_get=lambda key: 0, on_result=lambda s, r: None, warm_up=lambda: None)
    assert ran.computed == 0 and ran.mode == "all stored"


@pytest.mark.timeout(100)  # a hang guard: the refusal comes after the 1 s the call was given
def test_an_unreachable_scheduler_fails_fast():
    with pytest.raises(pk.ParameterError) as exc:
        pk.sweep.make_client("tcp://127.0.0.1:1", timeout=1.0)
    assert exc.value.param == "scheduler" and "no scheduler answered there within 1 s" in str(exc.value)
    with pytest.raises(pk.ParameterError) as exc:
        pk.sweep.make_client(workers=0)
    assert exc.value.param == "workers"


def _pack_task(prev, a):
    from phasekit.core import fields as M

    return Row(f"a{a}", float(len(M._CACHE)))


@pytest.mark.slow
def test_dask_local_cluster_runs_chains_with_the_model_pack(tmp_path):
    from phasekit.sweep import make_client

    pack = ModelPack.build(lambda: pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.1)))
    client, cluster = make_client(workers=2)
    try:
        specs = [TaskSpec(f"a{a}", _pack_task, (a,), after=None) for a in range(4)]
        res = run_tasks(specs, store_get=lambda k: None, on_result=lambda s, r: None, client=client, pack=pack, progress=False)
    finally:
        client.close()
        cluster.close()
    assert all(r.value >= 1 for r in res.values())  # the pack's compiled model was installed


@pytest.mark.slow
def test_dask_k_section_round_and_grouped_searches_equal_the_serial_ones(tmp_path):
    """One search's k-section rounds spread over 2 workers, and grouped search tasks on the
    cluster, give the serial brackets."""
    defn = Definition("sliding", "sliding")
    pack = pk.sweep.ModelPack.build(lambda: defn.prepare(1.5, engine="batch"))
    client, cluster = pk.sweep.make_client(workers=2)
    try:
        ev = pk.sweep.cluster.client_evaluator(client, pack=pack)  # the module, not the LocalCluster
        far = find_threshold(defn, 1.5, hi=120.0, levels=3, evaluate=ev)
        near = find_threshold(defn, 1.5, hi=120.0, levels=3, engine="batch")
        assert far.bracket == near.bracket and far.n_rounds == near.n_rounds
        jobs = [ps.search_job(asdict(replace(defn, amplitude=d)), 1.5, dict(hi=120.0, levels=3)) for d in (0.01, 0.02, 0.04)]
        specs, members = ps.group_search_tasks(jobs, [1.0, 2.0, 3.0], per_task=2)
        store = ResultStore(tmp_path / "g.csv", tmp_path / "g.json", SearchRow, {})
        get, add = pk.sweep.stores.stored_rows([store], members)
        run_tasks(specs, store_get=get, on_result=add, client=client, pack=pack, progress=False)
    finally:
        client.close()
        cluster.close()
    rows = {r.d: r for r in store.rows()}
    assert len(specs) == 2 and rows[0.01].threshold == near.value
    assert rows[0.04].threshold < rows[0.02].threshold < rows[0.01].threshold  # README: the threshold falls as d grows


def _pack_size(prev, i):
    return i


@pytest.mark.slow  # 12 scatters of a pack that holds every integrator the session compiled: ~40 s in the full suite
def test_runs_one_after_another_on_one_client_share_the_pack_without_losing_it():
    """The same model pack scattered run after run (a study's searches then its grid; a
    benchmark's serial and Dask passes): each run gets its own copy, so the release of the last
    one cannot take the next run's with it (with content-hashed keys it did: Dask's scheduler
    reported "lost dependencies")."""
    pack = pk.sweep.ModelPack.build(lambda: pk.Model(pk.Spheroid(1.5), pk.Coulomb(0.1)))
    client, cluster = pk.sweep.make_client(workers=1)
    try:
        for run in range(12):
            specs = [TaskSpec(f"r{run}-{i}", _pack_size, (i,)) for i in range(3)]
            got = {}
            run_tasks(specs, store_get=lambda k: None, on_result=lambda s, r: got.__setitem__(s.key, r), client=client,
                      pack=pack, progress=False)
            assert got == {f"r{run}-{i}": i for i in range(3)}
    finally:
        client.close()
        cluster.close()


def test_a_task_function_from_a_module_loaded_from_its_file_runs_on_dask(tmp_path):
    """A study loaded from its file and registered with cloudpickle by value (what the benchmarks
    do) hands its own functions to the workers, which cannot import it by name: they are shipped
    by value (before, every worker died on the message and the run waited until its wall budget)."""
    import importlib.util

    import cloudpickle

    (tmp_path / "a_study_by_path.py").write_text("def square(prev, x):\n    return x * x\n")
    spec = importlib.util.spec_from_file_location("a_study_by_path", tmp_path / "a_study_by_path.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules["a_study_by_path"] = mod
    spec.loader.exec_module(mod)
    cloudpickle.register_pickle_by_value(mod)
    client, cluster = pk.sweep.make_client(workers=1)
    try:
        got = {}
        run_tasks([TaskSpec(f"sq{i}", mod.square, (i,)) for i in range(4)], store_get=lambda k: None,
                  on_result=lambda s, r: got.__setitem__(s.key, r), client=client, progress=False, max_wall=60.0)
    finally:
        client.close()
        cluster.close()
        cloudpickle.unregister_pickle_by_value(mod)
        del sys.modules["a_study_by_path"]
    assert got == {f"sq{i}": i * i for i in range(4)}
