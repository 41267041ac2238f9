"""The benchmarks' reports as the docs read them: each benchmark writes its result wrapped with the
command, date, commit and machine (whole, strict JSON), the performance page renders every number
and goal of it, says "not measured" for a report not yet written, and reads only keys the
benchmarks write. No benchmark is run here (the reports are written from made-up results)."""

from __future__ import annotations

import argparse
import datetime
import inspect
import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "benchmarks"))  # _report, the benchmarks' shared helper
sys.path.insert(0, str(ROOT / "docs" / "_ext"))  # pkdocs

import _report  # noqa: E402
from pkdocs import facts, facts_runs  # noqa: E402
from pkdocs.sources import Sources  # noqa: E402

BENCHMARKS = {"bench_performance.json": ("bench_performance.py", facts_runs.bench_performance),
              "bench_threshold_sweep.json": ("bench_threshold_sweep.py", facts_runs.bench_sweep),
              "bench_steady_structure.json": ("bench_steady_structure.py", facts_runs.bench_structure),
              "bench_first_run.json": ("bench_first_run.py", facts_runs.bench_first_run),
              "bench_cold_cache.json": ("bench_cold_cache.py", facts_runs.bench_cold_cache),
              "bench_memory.json": ("bench_memory.py", facts_runs.bench_memory)}

PERFORMANCE = {"repeats": 50, "phasekit_rtol": 1e-8, "sweep_ms": 0.75, "default_ms": 1.4, "scipy_bdf_ms": 900.0,
               "ratio_scipy_bdf_sweep": 1200.0, "ratio_scipy_bdf_default": 640.0, "ratio_sweep_bare_heyoka": 1.3,
               "ratio_default_bare_heyoka": 2.5, "sweep_rtol1e-9_ms": 0.9, "default_rtol1e-9_ms": 1.71,
               "ratio_default_sweep": 1.9, "ratio_rolling_sliding": 1.6,
               "goals": {"scipy_bdf": 1000.0, "bare_heyoka": 1.35, "default_sweep": 2.0, "rolling_sliding": 3.0},
               "goals_met": {"scipy_bdf": True, "bare_heyoka": True, "default_sweep": True, "rolling_sliding": True}}
SWEEP = {"simulations": 4321, "searches": 60, "grid": "full", "critical_path": 7, "parallelism": 4321 / 7,
         "wall_serial_s": 40.0, "wall_dask_s": 21.0, "cluster_start_s": 1.5, "efficiency": 40.0 / 42.0,
         "same_thresholds_serial_and_dask": True, "default_curve_wall_s": 2.5,
         "goals": {"efficiency": 0.95, "parallelism": 64.0, "default_curve_wall_s": 10.0},
         "goals_met": {"efficiency": True, "parallelism": True, "default_curve_wall_s": True}}
STRUCTURE = {"structure_wall_s": {"a": {}, "b": {}}, "structure_worst_s": 0.1234, "bodies": 3300, "boundary_points": 812,
             "grid": "full", "atlas_wall_serial_s": 30.0, "atlas_wall_dask_s": 18.75, "cluster_start_s": 1.5,
             "efficiency": 0.8, "same_signatures_serial_and_dask": True, "goals": {"efficiency": 0.85},
             "goals_met": {"efficiency": False}}

FIRST_RUN = {"bodies": {"egg": {"command": "phasekit simulate --body egg", "first_s": 3.45, "second_s": 1.62, "notices": 1,
                                "longest_noticed_compile_s": 1.4},
                        "cone": {"command": "phasekit simulate --body cone", "first_s": 1.83, "second_s": 0.98, "notices": 0,
                                 "longest_noticed_compile_s": 0.0}},
             "worst_first_s": 3.45, "goals": {"first_s": 5.0}, "goals_met": {"first_s": True}}

COLD = {"cold_s": 152.3, "warm_s": 128.1, "cold_over_warm": 152.3 / 128.1, "integrators": 51, "builds": 51,
        "most_builds_of_one_integrator": 1, "builds_by_kind": {"the Taylor integrator of the sliding mode": 22,
                                                              "the Taylor integrator of the rolling mode": 29},
        "builds_when_warm": 0, "goals": {"cold_over_warm": 1.3, "builds_per_integrator": 1},
        "goals_met": {"cold_over_warm": True, "builds_per_integrator": True}}

MEMORY = {"standard": {"steps": 715, "traced_peak_kb": 2175.0, "held_kb": 560.0, "peak_rss_mb": 160.2},
          "per_step": {"dense_mb_per_million_steps": 752.0, "tally_mb_per_million_steps": 17.5, "dense_wall_s": 2.0,
                       "tally_wall_s": 7.0, "steps": 142284, "ratio_tally_dense_wall": 3.5},
          "long": {"steps": 10000000, "status": "completed", "t": 234741.8, "samples": 1001, "samples_finite": True,
                   "events": 82, "energy_residual_max": 7.6e-8, "dropped": True, "wall_s": 900.0, "peak_rss_mb": 1380.0},
          "tenth": {"steps": 1000000, "status": "completed", "t": 23474.2, "samples": 1001, "samples_finite": True,
                    "events": 82, "energy_residual_max": 1e-8, "dropped": False, "wall_s": 60.0, "peak_rss_mb": 1000.0},
          "bookkeeping": {"t_per_s": {"without": 860.0, "drag": 895.0, "zero": 859.0}, "ratio_drag": 0.96,
                          "ratio_zero": 1.0, "wall_overrun": {"without": 0.06, "drag": 0.08, "zero": 0.08},
                          "post_run_uncapped_s": 3.1, "post_run_uncapped_steps": 30599, "post_run_uncapped_overrun": 1.55,
                          "post_run_uncapped_has_budget": True},
          "long_run_peak_mb": 1380.0, "ratio_long_tenth_rss": 1.38, "ratio_bookkeeping": 0.96, "wall_overrun": 0.08,
          "goals": {"long_run_peak_mb": 2000.0, "bookkeeping": 1.5, "wall_overrun": 0.1},
          "goals_met": {"long_run_peak_mb": True, "bookkeeping": True, "wall_overrun": False}}


def _write(data: Path, name: str, result: dict, argv=("--quick",)) -> dict:
    ap = argparse.ArgumentParser()
    rep = _report.Report(ap, str(data / name), BENCHMARKS[name][0], [*argv, "--report", str(data / name)])
    rep.write(result)
    return json.loads((data / name).read_text())


def test_a_report_is_the_result_with_its_command_date_commit_and_machine(tmp_path):
    before = datetime.datetime.now(datetime.UTC).date()
    b = _write(tmp_path, "bench_threshold_sweep.json", SWEEP, argv=("--quick", "--per-task", "2"))
    assert b["result"] == SWEEP
    assert b["command"] == "python benchmarks/bench_threshold_sweep.py --quick --per-task 2"  # without --report
    assert b["measured"] in {before.isoformat(), datetime.datetime.now(datetime.UTC).date().isoformat()}
    git = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True)
    changed = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no", "phasekit", "studies", "benchmarks"],
                             cwd=ROOT, capture_output=True, text=True).stdout.strip()
    assert b["commit"] == (git.stdout.strip() + (" with uncommitted changes" if changed else "") if git.returncode == 0
                           else "unknown")
    assert re.fullmatch(r"\d+ cores, load average \d+\.\d at the start, \d+\.\d at the end", b["machine"])
    assert [p.name for p in tmp_path.iterdir()] == ["bench_threshold_sweep.json"]  # no temporary file left


def test_report_given_with_an_equals_sign_is_left_out_of_the_command(tmp_path):
    rep = _report.Report(argparse.ArgumentParser(), str(tmp_path / "r.json"), "/x/bench_steady_structure.py",
                         ["--report=" + str(tmp_path / "r.json"), "--quick"])
    assert rep.command == "python benchmarks/bench_steady_structure.py --quick"


def test_a_result_with_a_nan_is_refused_and_the_old_report_kept(tmp_path):
    _write(tmp_path, "bench_steady_structure.json", STRUCTURE)
    with pytest.raises(ValueError):
        _write(tmp_path, "bench_steady_structure.json", {**STRUCTURE, "efficiency": float("nan")})
    assert json.loads((tmp_path / "bench_steady_structure.json").read_text())["result"] == STRUCTURE
    assert [p.name for p in tmp_path.iterdir()] == ["bench_steady_structure.json"]


def test_a_report_into_a_missing_directory_is_refused_before_the_run(tmp_path, capsys):
    with pytest.raises(SystemExit) as e:
        _report.Report(argparse.ArgumentParser(prog="bench"), str(tmp_path / "no" / "r.json"), "bench_performance.py", [])
    assert e.value.code == 2 and "--report" in capsys.readouterr().err


def test_the_page_shows_each_report_with_its_goals(tmp_path):
    for name, result in (("bench_performance.json", PERFORMANCE), ("bench_threshold_sweep.json", SWEEP),
                         ("bench_steady_structure.json", STRUCTURE), ("bench_first_run.json", FIRST_RUN),
                         ("bench_cold_cache.json", COLD),
                         ("bench_memory.json", MEMORY)):
        _write(tmp_path, name, result)
    src = Sources(data=tmp_path)
    bench = facts.lookup(src, "performance.bench_report")
    assert "`python benchmarks/bench_performance.py --quick`" in bench
    assert re.search(r"\| 1\.90 \| <= 2 \| yes \|", bench) and re.search(r"\| 1\.30 \| <= 1\.35 \| yes \|", bench)
    sweep = facts.lookup(src, "performance.sweep_report")
    assert "4321 (60 searches, full grid)" in sweep and "| 7 rounds |" in sweep
    assert re.search(r"\| 0\.95 \| >= 0\.95 \| yes \|", sweep) and "| 21.0 s (cluster start 1.5 s more) |" in sweep
    assert re.search(r"\| 2\.50 s \| <= 10 s \| yes \|", sweep)
    structure = facts.lookup(src, "performance.structure_report")
    assert "| 123 ms |" in structure and "3300 bodies, 812 boundary points" in structure
    assert re.search(r"\| 0\.80 \| >= 0\.85 \| \*\*no\*\* \|", structure)
    first = facts.lookup(src, "performance.first_run_report")
    assert "| egg: `phasekit simulate --body egg` | 3.5 s | 1.6 s | 1 |  |" in first
    assert re.search(r"\| the slowest first run \| 3\.5 s \|  \|  \| <= 5 s: yes \|", first)
    cold = facts.lookup(src, "performance.cold_cache_report")
    assert "| main study `--fresh`, empty compile cache | 152.3 s |" in cold and "(51 integrators: rolling mode 29, sliding mode 22)" in cold
    assert re.search(r"\| empty / warm \| 1\.19 \| <= 1\.3 \| yes \|", cold)
    assert re.search(r"\| most builds of one integrator \| 1 \| <= 1 \| yes \|", cold)
    memory = facts.lookup(src, "performance.memory_report")
    assert "| dense output held per million Taylor steps (no cap) | 752 MB |" in memory
    assert re.search(r"a long run of 10000000 steps .*energy residual 7\.6e-8\): peak resident \| 1380 MB \| <= 2000 MB \| yes \|",
                     memory)
    assert re.search(r"\| 0\.96 \| <= 1\.5 \| yes \|", memory) and re.search(r"\| 0\.08 \| <= 0\.1 \| \*\*no\*\* \|", memory)
    assert "not measured" not in (bench + sweep + structure + first + cold + memory).lower()


def test_a_missing_report_is_not_measured_and_an_older_one_gets_its_ratio_from_its_times(tmp_path):
    old = {k: v for k, v in PERFORMANCE.items() if k != "ratio_default_sweep"}
    old["goals"] = {k: v for k, v in old["goals"].items() if k != "default_sweep"}
    _write(tmp_path, "bench_performance.json", old)
    src = Sources(data=tmp_path)
    assert re.search(r"its sweep path \(rtol 1e-9\) \| 1\.90 \|  \|  \|", facts.lookup(src, "performance.bench_report"))
    for key, name in (("sweep", "bench_threshold_sweep.json"), ("structure", "bench_steady_structure.json"),
                      ("first_run", "bench_first_run.json"), ("cold_cache", "bench_cold_cache.json"),
                      ("memory", "bench_memory.json")):
        block = facts.lookup(src, f"performance.{key}_report")
        assert block.startswith("Not measured") and name in block and "|" not in block


@pytest.mark.parametrize("name", sorted(BENCHMARKS))
def test_the_page_reads_only_keys_its_benchmark_writes(name):
    script, render = BENCHMARKS[name]
    source = (ROOT / "benchmarks" / script).read_text()
    keys = set(re.findall(r"""r\[["']([\w.-]+)["']\]""", inspect.getsource(render)))
    keys |= {k for k, *_ in facts_runs.BENCH_RATIOS} if name == "bench_performance.json" else set()
    assert keys and {k for k in keys if f'"{k}"' not in source} == set()
