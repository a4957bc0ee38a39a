"""Smoke test of the benchmark: ``python -m bench --quick`` writes a complete, sane report.

The benchmark itself (``make bench``) is not part of the test suite; this only runs its tiny
configuration (a few scenes of everything, seconds) into a temporary folder.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parent.parent

REQUIRED_KEYS = (
    "derive_seconds",
    "rmse_over_crlb",
    "success_rate_no_truth",
    "noise_free_failure_rate",
    "refine_speedup_vs_finite_differences",
    "reconstruct_seconds_20_frames",
    "machine",
    "seeds",
    "configuration",
    "targets",
)


def test_bench_quick_writes_report(tmp_path: Path) -> None:
    proc = subprocess.run(
        [sys.executable, "-m", "bench", "--quick", "--no-progress", "--out", str(tmp_path)],
        cwd=REPO_ROOT,
        capture_output=True,
        text=True,
        timeout=900,  # a guard against a hang, not a timing: seconds when quiet
    )
    assert proc.returncode == 0, proc.stderr[-3000:]
    for name in ("REPORT.md", "report.json", "stability_histogram.png", "scaling.png"):
        path = tmp_path / name
        assert path.is_file() and path.stat().st_size > 0, name
    doc = json.loads((tmp_path / "report.json").read_text())
    for key in REQUIRED_KEYS:
        assert key in doc, key
    assert doc["configuration"]["name"] == "quick"
    # the quick configuration skips the (seconds-long) derivation; the full run times it
    assert doc["derive_seconds"] is None or doc["derive_seconds"] > 0
    for key in ("success_rate_no_truth", "noise_free_failure_rate"):
        assert 0.0 <= doc[key] <= 1.0, (key, doc[key])
    assert doc["rmse_over_crlb"] > 0 and math.isfinite(doc["rmse_over_crlb"])
    assert doc["refine_speedup_vs_finite_differences"] > 0
    assert 0 < doc["reconstruct_seconds_20_frames"] < 60
    assert doc["machine"]["cores"] >= 1 and doc["machine"]["numpy"]
    assert isinstance(doc["seeds"]["seed"], int)
    assert all(t["verdict"] in ("PASS", "MISS", "n/a") for t in doc["targets"])
    for row in doc["accuracy"]:
        for method in ("default", "truth_start"):
            summary = row[method]
            if summary and summary.get("ratio"):
                assert all(v > 0 for v in summary["ratio"].values())
    report = (tmp_path / "REPORT.md").read_text()
    for heading in (
        "## Targets",
        "## Accuracy",
        "## Robustness",
        "## Numerical stability",
        "## Speed",
        "## Honest notes",
    ):
        assert heading in report, heading
