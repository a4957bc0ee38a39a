"""Fuzzing figures for ``make bench``: how many inputs the property-based tests fed to
the command, and how many ended in a traceback (must be 0).

Runs ``tests/test_fuzz.py`` under the "fuzz" hypothesis profile (randomised; ``--quick``: the
derandomised "ci" profile) with ``CURVERECON_FUZZ_LOG`` set, so that every case the command ran
in-process appends one line ("ok" or "traceback").  ``python -m bench.fuzz [--quick]`` prints the
figures as JSON.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def run(quick: bool = False) -> dict:
    """``fuzz_cases_run``, ``fuzz_tracebacks``, ``fuzz_seconds`` and the tests' exit status."""
    with tempfile.TemporaryDirectory() as tmp:
        log = Path(tmp) / "cases.log"
        env = dict(os.environ, CURVERECON_FUZZ_LOG=str(log))
        env["HYPOTHESIS_PROFILE"] = "ci" if quick else "fuzz"
        t0 = time.perf_counter()
        proc = subprocess.run(
            [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "tests/test_fuzz.py"],
            cwd=ROOT,
            env=env,
            capture_output=True,
            text=True,
        )
        seconds = time.perf_counter() - t0
        lines = log.read_text().split() if log.exists() else []
    return {
        "fuzz_cases_run": len(lines),
        "fuzz_tracebacks": lines.count("traceback"),
        "fuzz_seconds": round(seconds, 1),
        "fuzz_profile": env["HYPOTHESIS_PROFILE"],
        "fuzz_tests_passed": proc.returncode == 0,
        # what failed, if anything (the falsifying example and the assertion)
        "fuzz_failure": None if proc.returncode == 0 else proc.stdout[-3000:],
    }


if __name__ == "__main__":
    print(json.dumps(run("--quick" in sys.argv[1:]), indent=1))
