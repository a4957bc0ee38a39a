"""The ``start`` section of ``make bench``: how soon the command answers after an install.

Every figure is the wall time of fresh subprocesses of this interpreter:

- ``cli_help_seconds``: ``python -m curverecon --help`` (best of 5);
- ``import_seconds``: ``python -c "import curverecon"`` (best of 5);
- ``first_reconstruct_seconds_cold_cache``: ``curverecon reconstruct examples/wire.json`` with
  ``NUMBA_CACHE_DIR`` an empty folder, as after a fresh install without the warm-up: numba
  compiles every kernel the reconstruction calls (one run);
- ``first_reconstruct_seconds_warm_cache``: the same command again on that folder, now holding
  the compiled kernels (best of 2);
- ``warmup_seconds_cold_cache``: ``python -m curverecon.warmup`` on another empty folder (what
  ``make setup`` adds to an install), and ``reconstruct_seconds_after_warmup``: the
  reconstruction on that folder next; ``warmup_new_cache_files_in_reconstruct`` counts the
  cache files that reconstruction still wrote (0: the warm-up compiled all it needs).

``--quick`` skips the warm-up run.  ``python -m bench.start [--quick]`` prints the figures as
JSON.
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
EXAMPLE = ROOT / "examples" / "wire.json"


def _seconds(args: list[str], env: dict[str, str] | None = None) -> float:
    t0 = time.perf_counter()
    subprocess.run(
        [sys.executable, *args],
        cwd=ROOT,
        env={**os.environ, **(env or {})},
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        check=True,
        timeout=3600,
    )
    return time.perf_counter() - t0


def _best(args: list[str], runs: int, env: dict[str, str] | None = None) -> float:
    return round(min(_seconds(args, env) for _ in range(runs)), 3)


def _reconstruct(out: Path) -> list[str]:
    return ["-m", "curverecon", "reconstruct", str(EXAMPLE), "-o", str(out / "wire.json")]


def _cache_files(cache: Path) -> set[str]:
    return {str(p.relative_to(cache)) for p in cache.rglob("*") if p.is_file()}


def run(quick: bool = False) -> dict:
    out = {
        "cli_help_seconds": _best(["-m", "curverecon", "--help"], 5),
        "import_seconds": _best(["-c", "import curverecon"], 5),
    }
    with tempfile.TemporaryDirectory(prefix="curverecon-start-") as tmp:
        tmp_path = Path(tmp)
        cold = tmp_path / "cold"
        cold.mkdir()
        env = {"NUMBA_CACHE_DIR": str(cold)}
        args = _reconstruct(tmp_path)
        out["first_reconstruct_seconds_cold_cache"] = round(_seconds(args, env), 3)
        out["first_reconstruct_seconds_warm_cache"] = _best(args, 2, env)
        if not quick:
            warm = tmp_path / "warmup"
            warm.mkdir()
            env = {"NUMBA_CACHE_DIR": str(warm)}
            seconds = _seconds(["-m", "curverecon.warmup"], env)
            out["warmup_seconds_cold_cache"] = round(seconds, 3)
            before = _cache_files(warm)
            seconds = _seconds(_reconstruct(tmp_path), env)
            out["reconstruct_seconds_after_warmup"] = round(seconds, 3)
            out["warmup_new_cache_files_in_reconstruct"] = len(_cache_files(warm) - before)
    return out


if __name__ == "__main__":
    print(json.dumps(run("--quick" in sys.argv[1:]), indent=1))
