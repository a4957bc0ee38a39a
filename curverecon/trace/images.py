"""Reading the inputs of ``curverecon trace``: image files, one folder of images, or one video.

Every frame becomes a 2-D float64 array of grey levels scaled to [0, 1] (8-bit images by 255,
16-bit by 65535, float images as they are): colour frames are reduced to luminance (Rec. 601
weights), an alpha channel is dropped.  Array index [row, column]; the trace contract's pixel
convention is x = column, y = row, the centre of the top-left pixel at (0, 0).

Anything that cannot be read raises :class:`CurveReconError` with a one-line message naming the
file and the problem.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from curverecon.errors import CurveReconError

IMAGE_EXTENSIONS = (".png", ".tif", ".tiff", ".jpg", ".jpeg", ".bmp", ".pgm", ".ppm")
"""Files a folder is searched for (case-insensitive)."""

VIDEO_EXTENSIONS = (".mp4", ".avi", ".mov", ".mkv", ".webm", ".m4v", ".mpg", ".mpeg", ".gif")
"""Files read as a video (one frame each), through imageio's ffmpeg plugin (GIF: pillow)."""

MIN_SIDE = 16
"""Smallest image side (pixels) worth tracing: a ridge filter needs a few line widths."""

MAX_PIXELS = 100_000_000
"""Largest frame (pixels) accepted: the filters hold several float copies of it."""


@dataclass
class Frame:
    """One frame: its grey image in [0, 1] and where it came from (file, or file#index)."""

    image: np.ndarray
    source: str


def _to_grey(arr: np.ndarray, source: str) -> np.ndarray:
    arr = np.asarray(arr)
    if arr.dtype == bool:
        arr = arr.astype(np.uint8)
    if arr.dtype.kind not in "uif":
        raise CurveReconError(f"{source}: unsupported pixel type {arr.dtype}")
    if arr.dtype.kind == "u":
        scale = float(np.iinfo(arr.dtype).max) if arr.dtype.itemsize <= 2 else None
        if scale is None:
            arr = arr.astype(np.float64)
            scale = max(float(arr.max()), 1.0)
    elif arr.dtype.kind == "i":
        scale = float(np.iinfo(arr.dtype).max)
    else:
        scale = 1.0
    img = arr.astype(np.float64) / scale
    if img.ndim == 3 and img.shape[-1] in (2, 4):  # grey + alpha, RGBA
        img = img[..., :-1]
    if img.ndim == 3 and img.shape[-1] == 1:
        img = img[..., 0]
    if img.ndim == 3 and img.shape[-1] == 3:
        img = img @ np.array([0.299, 0.587, 0.114])
    if img.ndim != 2:
        raise CurveReconError(f"{source}: not a single 2-D image (array shape {arr.shape})")
    if min(img.shape) < MIN_SIDE:
        raise CurveReconError(
            f"{source}: image of {img.shape[1]} x {img.shape[0]} pixels is too small "
            f"(at least {MIN_SIDE} x {MIN_SIDE})"
        )
    if img.size > MAX_PIXELS:
        raise CurveReconError(f"{source}: image of {img.size} pixels is too large")
    if not np.all(np.isfinite(img)):
        raise CurveReconError(f"{source}: image has non-finite pixel values")
    return img


def _read_image(path: Path) -> np.ndarray:
    import imageio.v3 as iio

    if not path.is_file():
        raise CurveReconError(f"cannot read {path}: no such file")
    if path.stat().st_size == 0:
        raise CurveReconError(f"cannot read {path}: the file is empty")
    try:
        arr = iio.imread(path, index=0) if path.suffix.lower() == ".gif" else iio.imread(path)
    except MemoryError:
        raise
    except Exception as exc:  # imageio raises many types for a corrupt or foreign file
        raise CurveReconError(f"cannot read {path} as an image: {_short(exc)}") from None
    return _to_grey(arr, str(path))


def _short(exc: Exception) -> str:
    text = " ".join(str(exc).split()) or type(exc).__name__
    return text[:160]


def _iter_video(path: Path) -> Iterator[Frame]:
    import imageio.v3 as iio

    if not path.is_file():
        raise CurveReconError(f"cannot read {path}: no such file")
    plugin = "pillow" if path.suffix.lower() == ".gif" else "FFMPEG"
    try:
        for i, arr in enumerate(iio.imiter(path, plugin=plugin)):
            yield Frame(_to_grey(arr, f"{path}#{i}"), f"{path}#{i}")
    except CurveReconError:
        raise
    except MemoryError:
        raise
    except Exception as exc:
        raise CurveReconError(f"cannot read {path} as a video: {_short(exc)}") from None


def input_files(inputs: Sequence[str]) -> tuple[list[Path], bool]:
    """The files to read, in frame order, and whether they are one video.

    One folder: its image files sorted by name; one video file; or image files in the order
    given.  A folder among other inputs, two videos, or an empty list are errors.
    """
    if not inputs:
        raise CurveReconError("no input: give image files, one folder or one video")
    paths = [Path(p) for p in inputs]
    dirs = [p for p in paths if p.is_dir()]
    if dirs:
        if len(paths) > 1:
            raise CurveReconError(f"{dirs[0]} is a folder: give one folder alone, or image files")
        found = sorted(
            (p for p in dirs[0].iterdir() if p.suffix.lower() in IMAGE_EXTENSIONS and p.is_file()),
            key=lambda p: p.name,
        )
        if not found:
            raise CurveReconError(
                f"{dirs[0]}: no image files in the folder ({', '.join(IMAGE_EXTENSIONS)})"
            )
        return found, False
    videos = [p for p in paths if p.suffix.lower() in VIDEO_EXTENSIONS]
    if videos:
        if len(paths) > 1:
            raise CurveReconError(f"{videos[0]} is a video: give one video alone")
        return paths, True
    for p in paths:
        if not p.exists():
            raise CurveReconError(f"cannot read {p}: no such file or folder")
    return paths, False


def iter_frames(inputs: Sequence[str]) -> Iterator[Frame]:
    """Frames of the inputs in order (see :func:`input_files`), read one at a time."""
    files, video = input_files(inputs)
    if video:
        yield from _iter_video(files[0])
        return
    for p in files:
        yield Frame(_read_image(p), str(p))


def count_frames(inputs: Sequence[str]) -> int | None:
    """The number of frames, or None for a video (unknown without decoding it)."""
    files, video = input_files(inputs)
    return None if video else len(files)
