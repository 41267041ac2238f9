"""One data path from parameters to result: a run of ``phasekit simulate`` (and of
``phasekit.cli.params.simulate_start``) constructs the Model it simulates once and compiles its
fields once. Each run is a fresh process, so nothing is shared with another test through the
in-memory caches."""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap

import pytest

COUNTER = textwrap.dedent("""
    import collections, contextlib, io, json, sys
    import phasekit
    from phasekit.core import fields as F, model as M
    counts = collections.Counter()
    init, build = M.Model.__init__, F._build
    def counted_init(self, body, friction, chart="euler"):
        counts[f"model:{type(friction).__name__}"] += 1
        return init(self, body, friction, chart)
    def counted_build(body, law, chart, key, *laws):
        counts[f"build:{law.__name__}"] += 1
        return build(body, law, chart, key, *laws)
    M.Model.__init__, F._build = counted_init, counted_build
    from phasekit.cli import main
    with contextlib.redirect_stdout(io.StringIO()) as out:
        try:
            main(sys.argv[1:])
        except SystemExit as e:
            code = e.code
    print(json.dumps({"counts": counts, "status": json.loads(out.getvalue())["status"]}))
""")

RUNS = {
    "gyroscopic": "--a 1.5 --mu 0.1 --gyroscopic --theta0 1.5607963 --omega0 10.5 --t-end 20",
    "spin about the vertical": "--body tippe-top --offset 0.3 --A 0.38 --C 0.4 --mu 0.3 --theta0 0.1 "
                               "--spin-about-vertical 15 --t-end 5",
    "paper's start": "--paper-start 5.2 --a 1.5 --mu 0.1 --t-end 5",
    "egg": "--body egg --a 1.33333 --mu 0.2 --gyroscopic --theta0 1.55 --omega0 8 --t-end 2",
    "unstable manifold, seeded on its own law": "--a 1.5 --mu 0.1 --friction viscous --unstable-manifold horizontal "
                                                "--delta 0.01 --omega0 9.9 --t-end 5",
    "unstable manifold, seeded on viscous friction": "--a 1.5 --mu 0.1 --unstable-manifold horizontal --delta 0.01 "
                                                     "--omega0 9.9 --t-end 5",
}


def _counts(args: str) -> dict:
    p = subprocess.run([sys.executable, "-c", COUNTER, "simulate", *args.split(), "--json"], capture_output=True,
                       text=True, timeout=600)
    assert p.returncode == 0, p.stderr[-2000:]
    return json.loads(p.stdout.strip().splitlines()[-1])


@pytest.mark.parametrize("name", list(RUNS))
def test_a_simulate_run_constructs_and_compiles_its_model_once(name):
    out = _counts(RUNS[name])
    counts = out["counts"]
    simulated = "Viscous" if "viscous" in RUNS[name] and "seeded on its own" in name else "Coulomb"
    assert counts[f"model:{simulated}"] == 1, counts
    assert counts[f"build:{simulated}"] == 1, counts
    if "seeded on viscous" in name:
        # the seed is an eigenvector of another system (viscous friction, part I): its field is built once
        # too, and Newton's solve of the steady state runs on that same compiled field
        assert counts["build:Viscous"] == 1, counts
        assert set(counts) == {"model:Coulomb", "build:Coulomb", "model:Viscous", "build:Viscous"}, counts
    else:
        assert sum(v for k, v in counts.items() if k.startswith("build:")) == 1, counts
    assert out["status"] in ("jumped", "completed", "stopped"), out
