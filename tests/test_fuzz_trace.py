"""Property-based fuzzing of ``curverecon trace`` inputs.

Inputs: random bytes under image and video extensions, valid images truncated or with bytes
flipped, files with the wrong extension, empty folders, tiny, long-and-thin and constant
images, 16-bit and colour images with a line.  The property, for every input: exit status 0
with a strict-JSON output (no NaN or infinity), or exit status 2 with exactly one stderr line
starting ``curverecon: error:``; never a traceback.  Budgets: the hypothesis profiles of
tests/conftest.py ("ci" derandomised for ``make test``, "fuzz" for ``make fuzz``).
"""

from __future__ import annotations

import contextlib
import io
import json
import math
import tempfile
from pathlib import Path

import imageio.v3 as iio
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from curverecon.cli import main
from curverecon.trace.render import RenderOptions, render_frame

_EXT = st.sampled_from([".png", ".tif", ".jpg", ".bmp", ".gif", ".mp4", ".txt", ".json", ""])


def _line_image(size: int, seed: int) -> np.ndarray:
    y = np.linspace(0.2 * size, 0.8 * size, 200)
    truth = np.column_stack([0.4 * size + 0.002 * (y - 0.2 * size) ** 2, y])
    return render_frame(truth, np.random.default_rng(seed), RenderOptions(size=size))


_GOOD_PNG = None


def _good_png() -> bytes:
    global _GOOD_PNG
    if _GOOD_PNG is None:
        buf = io.BytesIO()
        iio.imwrite(buf, _line_image(64, 0), extension=".png")
        _GOOD_PNG = buf.getvalue()
    return _GOOD_PNG


def _check(args: list[str], out: Path) -> None:
    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        status = main(["trace", *args, "-o", str(out), "--quiet"])
    lines = err.getvalue().strip().splitlines()
    if status == 0:
        doc = json.loads(
            out.read_text(), parse_constant=lambda c: (_ for _ in ()).throw(ValueError(c))
        )
        for f in doc["frames"]:
            for key in ("A", "B", "tangent_A", "tangent_B"):
                assert all(math.isfinite(v) for v in f[key])
        assert all("warning" in ln for ln in lines), lines
    else:
        assert status == 2, (status, lines)
        assert len(lines) == 1, lines
        assert lines[0].startswith("curverecon: error: "), lines


@settings(max_examples=max(10, settings.default.max_examples // 2))
@given(data=st.binary(min_size=0, max_size=400), ext=_EXT, n=st.integers(1, 5))
def test_random_bytes_as_inputs(data, ext, n):
    with tempfile.TemporaryDirectory() as tmp:
        paths = []
        for i in range(n):
            p = Path(tmp) / f"f{i}{ext}"
            p.write_bytes(data)
            paths.append(str(p))
        _check(paths, Path(tmp) / "o.json")


@settings(max_examples=max(10, settings.default.max_examples // 2))
@given(
    cut=st.integers(0, 2000),
    flips=st.lists(st.tuples(st.integers(0, 4000), st.integers(0, 255)), max_size=4),
    ext=st.sampled_from([".png", ".jpg", ".tif"]),
)
def test_corrupted_and_truncated_images(cut, flips, ext):
    raw = bytearray(_good_png())
    for pos, val in flips:
        if pos < len(raw):
            raw[pos] = val
    raw = bytes(raw[: max(cut, 0)] if cut < len(raw) else raw)
    with tempfile.TemporaryDirectory() as tmp:
        paths = []
        for i in range(4):
            p = Path(tmp) / f"f{i}{ext}"
            p.write_bytes(raw)
            paths.append(str(p))
        _check(paths, Path(tmp) / "o.json")


@settings(max_examples=max(10, settings.default.max_examples // 2))
@given(
    h=st.integers(1, 300),
    w=st.integers(1, 300),
    value=st.integers(0, 65535),
    dtype=st.sampled_from(["uint8", "uint16"]),
    channels=st.sampled_from([0, 3, 4]),
    kind=st.sampled_from(["constant", "noise", "line"]),
)
def test_tiny_thin_constant_and_noise_images(h, w, value, dtype, channels, kind):
    rng = np.random.default_rng(h * 1000 + w)
    top = 255 if dtype == "uint8" else 65535
    if kind == "constant":
        img = np.full((h, w), min(value, top), dtype)
    elif kind == "noise":
        img = rng.integers(0, top + 1, size=(h, w)).astype(dtype)
    else:
        img = _line_image(max(h, 16), value % 7).astype(dtype)
    if channels:
        img = np.stack([img] * channels, axis=-1)
    with tempfile.TemporaryDirectory() as tmp:
        paths = []
        for i in range(4):
            p = Path(tmp) / (f"f{i}.png" if dtype == "uint8" else f"f{i}.tif")
            iio.imwrite(p, img)
            paths.append(str(p))
        _check(paths, Path(tmp) / "o.json")


def test_empty_folder_and_folder_of_non_images(tmp_path):
    (tmp_path / "a").mkdir()
    _check([str(tmp_path / "a")], tmp_path / "o.json")
    (tmp_path / "a" / "notes.txt").write_text("x")
    (tmp_path / "a" / "x.png").mkdir()  # a folder named like an image
    _check([str(tmp_path / "a")], tmp_path / "o.json")


def test_huge_image_is_refused_or_traced(tmp_path):
    """A 20000 x 20 frame: long and thin (too small on one side), answered in one line."""
    p = tmp_path / "wide.png"
    iio.imwrite(p, np.zeros((20, 20000), np.uint8))
    _check([str(p)] * 4, tmp_path / "o.json")
