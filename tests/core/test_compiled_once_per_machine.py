"""Two processes that need the same integrator at once (two Dask workers, a pool) compile it once:
the second waits for the first's build and loads it from the disk cache
(phasekit/core/engines/cache.py, _machine_lock)."""

import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

SCRIPT = textwrap.dedent("""
    import os, sys, time
    from phasekit.core.engines import cache

    def build():
        with open(sys.argv[1], "a") as fh:
            fh.write(f"{os.getpid()}\\n")
        time.sleep(1.5)  # long enough that the other process asks while this one builds
        return {"built by": os.getpid()}

    entry = cache.compiled(("a test of the machine lock", sys.argv[2]), build, disk="test")
    print(entry["built by"])
""")


@pytest.mark.timeout(300)
def test_two_processes_compile_one_integrator_once(tmp_path):
    builds = tmp_path / "builds.txt"
    env_cache = tmp_path / "cache"
    import os

    env = {**os.environ, "PHASEKIT_CACHE": str(env_cache), "PHASEKIT_COMPILE_NOTICE": "off"}
    key = str(time.time())
    procs = [subprocess.Popen([sys.executable, "-c", SCRIPT, str(builds), key], stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True, env=env) for _ in range(3)]
    outs = [p.communicate(timeout=240) for p in procs]
    assert all(p.returncode == 0 for p in procs), [o[1][-2000:] for o in outs]
    builders = builds.read_text().split()
    assert len(builders) == 1  # one build; the others loaded it
    assert {o[0].strip() for o in outs} == set(builders)  # and every process got that build
    assert len(list(Path(env_cache).glob("test-*.pkl"))) == 1
