"""The ``batch`` section of ``make bench``: ``curverecon batch`` on a local Dask cluster.

Sequences: ``SEQUENCES`` simulated scenes (``curverecon.simulate.make_scene``, each from its own
``SeedSequence(SEED, spawn_key=(k,))``) of ``FRAMES`` frames, 1 px and 1 degree of noise, points
and tangents (no polylines), written as observation files into a temporary folder.

- ``batch_sequences_per_second_1_worker`` / ``_2_workers``: the sequences over the wall time of
  ``curverecon.batch.run`` on a local cluster of one / two worker processes
  (``curverecon.batch.runner.local_cluster``).  Before the clock starts, every worker runs one
  warm-up input (imports, numba's compiled functions loaded from the on-disk cache), as a
  long batch amortises them; ``batch_scaling_2_workers`` is their ratio (target >= 1.7; it
  cannot reach 2 when other processes share the two cores).  The workers' CPU seconds per
  sequence (``time.process_time`` summed over the workers) show whether two workers spend more
  CPU on a sequence than one: on a machine shared with other work the wall-clock scaling
  measures the share of the cores the run got, the CPU seconds do not.
- ``batch_overhead_seconds``: the wall time of the command ``curverecon batch ONE.json -o DIR``
  (a cluster of one worker started, run, closed) minus that of ``curverecon reconstruct
  ONE.json`` (both fresh processes, the numba cache warm; the smaller of two runs each).
- ``batch_peak_memory_per_worker_mb``: the largest peak resident memory of a worker process
  after the two-worker run (``ru_maxrss``).
- ``batch_resume_seconds``, ``batch_resume_fraction``: a second ``run`` into the finished output
  folder (every input current: its row read from its output, no cluster started) and its share
  of the first two-worker run's time (target <= 0.05).

``python -m bench.batch [--quick]`` prints the figures as JSON; ``python -m bench --only batch``
merges them into the report.
"""

from __future__ import annotations

import json
import math
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

SEQUENCES = 200
FRAMES = 20
SEED = 4100
QUICK_SEQUENCES = 16


def _write_scenes(folder: Path, n: int) -> list[Path]:
    from curverecon.io import observations_to_dict, write_json
    from curverecon.simulate import make_scene

    folder.mkdir(parents=True, exist_ok=True)
    paths = []
    for k in range(n):
        rng = np.random.default_rng(np.random.SeedSequence(SEED, spawn_key=(k,)))
        scene = make_scene(rng, FRAMES, point_sigma=1.0, tangent_sigma_deg=1.0)
        path = folder / f"seq{k:04d}.json"
        write_json(path, observations_to_dict(scene.observations))
        paths.append(path)
    return paths


def _warm(client, warm_input: Path, scratch: Path) -> None:  # type: ignore[no-untyped-def]
    """One input on every worker (never skipped: ``not_before`` = infinity)."""
    from curverecon.batch.inputs import expand
    from curverecon.batch.task import process

    job = expand([warm_input], scratch)[0]
    client.run(process, job, str(scratch), math.inf)


def _timed_run(n_workers: int, inputs: Path, warm: Path, root: Path) -> dict:
    from dask.distributed import Client

    from curverecon.batch import run
    from curverecon.batch.runner import local_cluster

    cluster = local_cluster(n_workers)
    client = Client(cluster)
    try:
        _warm(client, warm, root / f"warm{n_workers}")
        out = root / f"out{n_workers}"
        cpu0 = sum(client.run(time.process_time).values())
        t0 = time.perf_counter()
        summary = run([inputs], out, client=client)
        seconds = time.perf_counter() - t0
        cpu = sum(client.run(time.process_time).values()) - cpu0
        rss = client.run(resource.getrusage, resource.RUSAGE_SELF)
        peak_mb = max(r.ru_maxrss for r in rss.values()) / 1024.0
    finally:
        client.close()
        cluster.close()
    ok = int((summary["status"] == "ok").sum())
    n = len(summary)
    return {"seconds": seconds, "cpu": cpu, "ok": ok, "n": n, "peak_mb": peak_mb, "out": out}


def _command_seconds(args: list[str], repeats: int = 2) -> float:
    best = math.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        subprocess.run(args, check=True, capture_output=True)
        best = min(best, time.perf_counter() - t0)
    return best


def _overhead(one: Path, root: Path) -> dict:
    exe = [sys.executable, "-m", "curverecon.cli"]
    plain = _command_seconds([*exe, "reconstruct", str(one), "-o", str(root / "plain.json")])
    batch = _command_seconds(
        [*exe, "batch", str(one), "-o", str(root / "one"), "--workers", "1", "--force"]
    )
    return {"plain": plain, "batch": batch}


def run(quick: bool = False) -> dict:
    n = QUICK_SEQUENCES if quick else SEQUENCES
    with tempfile.TemporaryDirectory(prefix="bench-batch-") as tmp:
        root = Path(tmp)
        inputs = root / "inputs"
        _write_scenes(inputs, n)
        warm = _write_scenes(root / "warm", 1)[0]
        one = _timed_run(1, inputs, warm, root)
        two = _timed_run(2, inputs, warm, root)
        from curverecon.batch import run as batch_run

        t0 = time.perf_counter()
        resumed = batch_run([inputs], two["out"])
        resume_s = time.perf_counter() - t0
        overhead = _overhead(warm, root)
    sps1, sps2 = n / one["seconds"], n / two["seconds"]
    return {
        "batch_sequences": n,
        "batch_frames_per_sequence": FRAMES,
        "batch_sequences_ok": [one["ok"], two["ok"]],
        "batch_seconds_1_worker": round(one["seconds"], 2),
        "batch_seconds_2_workers": round(two["seconds"], 2),
        "batch_sequences_per_second_1_worker": round(sps1, 3),
        "batch_sequences_per_second_2_workers": round(sps2, 3),
        "batch_scaling_2_workers": round(sps2 / sps1, 3),
        "batch_worker_cpu_seconds_per_sequence_1_worker": round(one["cpu"] / n, 3),
        "batch_worker_cpu_seconds_per_sequence_2_workers": round(two["cpu"] / n, 3),
        "batch_overhead_seconds": round(overhead["batch"] - overhead["plain"], 2),
        "batch_one_input_seconds": round(overhead["batch"], 2),
        "batch_plain_reconstruct_seconds": round(overhead["plain"], 2),
        "batch_peak_memory_per_worker_mb": round(max(one["peak_mb"], two["peak_mb"]), 1),
        "batch_resume_seconds": round(resume_s, 3),
        "batch_resume_fraction": round(resume_s / two["seconds"], 4),
        "batch_resume_skipped": int(resumed.attrs.get("skipped", 0)),
        "batch_cores": os.cpu_count(),
    }


if __name__ == "__main__":
    print(json.dumps(run("--quick" in sys.argv[1:]), indent=1))
