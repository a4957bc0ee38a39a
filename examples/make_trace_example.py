"""Make the rendered example sequence of ``curverecon trace`` (examples/trace/).

Ten 8-bit PNG frames of 192 x 192 pixels: a random cubic curve tumbling 25 degrees a frame,
drawn as a Gaussian line (sigma 1.2 px, 160 grey levels) on a background gradient with noise
sd 8 (``curverecon simulate --images``), and ``truth.json``, the simulator's truth (the 3-D
curve in frame 0's camera coordinates).  Reproducible: ``python examples/make_trace_example.py``
writes the same files (seed 5).  ``make demo`` traces and reconstructs them.
"""

from __future__ import annotations

import json
import tempfile
from pathlib import Path

from curverecon.cli import main

HERE = Path(__file__).resolve().parent


def make(folder: Path = HERE / "trace") -> None:
    with tempfile.TemporaryDirectory() as tmp:
        args = ["simulate", "-o", str(Path(tmp) / "scene.json"), "--truth"]
        args += [str(folder / "truth.json"), "--frames", "10", "--images", str(folder)]
        args += ["--image-size", "192", "--seed", "5"]
        if main(args) != 0:
            raise SystemExit("curverecon simulate failed")
    # keep the example small: the truth's 3-D curve at 200 points, numbers to 1e-4
    path = folder / "truth.json"
    doc = json.loads(path.read_text())
    curve = doc["curve3d"]
    step = max(1, len(curve) // 200)
    doc["curve3d"] = [[round(v, 4) for v in p] for p in curve[::step] + [curve[-1]]]
    path.write_text(json.dumps(doc, indent=1) + "\n")


if __name__ == "__main__":
    make()
