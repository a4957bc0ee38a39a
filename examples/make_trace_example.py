"""Make the rendered example of ``curverecon trace``: examples/trace/sequence.mp4 and truth.json.

Sixteen frames of 384 x 384 pixels: a random cubic curve tumbling 25 degrees a frame, drawn as a
Gaussian line (sigma 1.2 px, 160 grey levels) on a background gradient with noise sd 8
(``curverecon simulate --images``, seed 3), encoded as an H.264 video (imageio-ffmpeg, quality
4 of 10: about 230 kB, where the sixteen PNG frames take 1.5 MB), and ``truth.json``, the
simulator's truth (the 3-D curve in frame 0's camera coordinates, at 200 points).
``python examples/make_trace_example.py`` writes them again (the same frames; the encoder's
bytes may differ between ffmpeg builds).  ``make demo`` traces and reconstructs the video.
"""

from __future__ import annotations

import json
import tempfile
from pathlib import Path

import imageio.v3 as iio
import numpy as np

from curverecon.cli import main

HERE = Path(__file__).resolve().parent


def make(folder: Path = HERE / "trace") -> None:
    folder.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        args = ["simulate", "-o", str(Path(tmp) / "scene.json"), "--truth"]
        args += [str(folder / "truth.json"), "--frames", "16", "--images", str(Path(tmp) / "png")]
        if main([*args, "--seed", "3"]) != 0:
            raise SystemExit("curverecon simulate failed")
        frames = np.stack([iio.imread(p) for p in sorted((Path(tmp) / "png").glob("*.png"))])
    iio.imwrite(
        folder / "sequence.mp4", frames, plugin="FFMPEG", fps=4, quality=4, macro_block_size=16
    )
    # keep the example small: the truth's 3-D curve at 200 points, numbers to 1e-4
    path = folder / "truth.json"
    doc = json.loads(path.read_text())
    curve = doc["curve3d"]
    step = max(1, len(curve) // 200)
    doc["curve3d"] = [[round(v, 4) for v in p] for p in curve[::step] + [curve[-1]]]
    path.write_text(json.dumps(doc, indent=1) + "\n")


if __name__ == "__main__":
    make()
