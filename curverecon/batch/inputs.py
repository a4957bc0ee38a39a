"""The inputs of ``curverecon batch``: arguments to jobs, one job per sequence.

An argument is an observation file (``.json``), a video file, or a folder.  A folder holding
image files is one sequence (its images sorted by name, as ``curverecon trace`` reads it);
any other folder is a batch: each observation file, video and sub-folder in it is an input of its
own (one level deep).  A folder in which none of these is found becomes a job that fails with
its reason, so that one empty folder among thousands does not stop the others.

Every job has a ``name`` (the file name without its extension, or the folder's name) that names
its outputs; two jobs with the same name are refused before anything starts (their outputs
would overwrite each other), as are arguments that do not exist.  This module imports no
heavy package: the command checks its arguments before Dask is started.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from curverecon.errors import CurveReconError
from curverecon.trace.images import IMAGE_EXTENSIONS, VIDEO_EXTENSIONS

KINDS = ("observations", "video", "images", "empty")
"""What a job reads: an observation file, a video, a folder of images, or a folder in which
nothing could be read (the job fails with ``problem``)."""

OBSERVATIONS_SUFFIX = ".json"


@dataclass(frozen=True)
class Job:
    """One input: what it is, where it is (absolute), and the name of its outputs."""

    input: str
    """The argument as the user gave it (or the file found in a folder given): the summary's
    ``input`` column."""
    path: str
    kind: str
    name: str
    problem: str = ""

    @property
    def traced(self) -> bool:
        return self.kind in ("video", "images")


def _images(folder: Path) -> list[Path]:
    return sorted(
        (p for p in folder.iterdir() if p.suffix.lower() in IMAGE_EXTENSIONS and p.is_file()),
        key=lambda p: p.name,
    )


def _file_job(shown: str, path: Path) -> Job | None:
    """The job of a file, or None when the file is neither an observation file nor a video."""
    suffix = path.suffix.lower()
    if suffix == OBSERVATIONS_SUFFIX:
        return Job(shown, str(path.resolve()), "observations", path.name[: -len(suffix)])
    if suffix in VIDEO_EXTENSIONS:
        return Job(shown, str(path.resolve()), "video", path.name[: -len(suffix)])
    return None


def _folder_name(path: Path) -> str:
    return path.resolve().name or str(path.resolve())


def _sequence_or_batch(shown: str, folder: Path, out_dir: Path) -> list[Job]:
    """A folder of images is one sequence; otherwise its readable entries, one level deep."""
    if folder.resolve() == out_dir.resolve():
        raise CurveReconError(f"{shown} is the output folder: give the inputs' folders")
    if _images(folder):
        return [Job(shown, str(folder.resolve()), "images", _folder_name(folder))]
    jobs: list[Job] = []
    for entry in sorted(folder.iterdir(), key=lambda p: p.name):
        entry_shown = os.path.join(shown, entry.name)
        if entry.name.startswith("."):
            continue
        if entry.is_dir():
            if entry.resolve() == out_dir.resolve():
                continue
            if _images(entry):
                jobs.append(Job(entry_shown, str(entry.resolve()), "images", entry.name))
            else:
                jobs.append(_empty(entry_shown, entry))
        elif entry.is_file():
            job = _file_job(entry_shown, entry)
            if job is not None:
                jobs.append(job)
    return jobs or [_empty(shown, folder)]


def _empty(shown: str, folder: Path) -> Job:
    return Job(
        shown,
        str(folder.resolve()),
        "empty",
        _folder_name(folder),
        f"{shown}: no image files, observation files (.json), videos or folders of images in "
        "the folder",
    )


def expand(inputs: Sequence[str | os.PathLike[str]], out_dir: str | os.PathLike[str]) -> list[Job]:
    """Every job of the arguments, in order; an input given twice counts once.

    Raises :class:`CurveReconError` (one line) for no inputs, an input that does not exist or
    is neither an observation file, a video nor a folder, and for two jobs of the same name.
    """
    if not inputs:
        raise CurveReconError("no input: give observation files, videos or folders of frames")
    out = Path(out_dir)
    jobs: list[Job] = []
    for arg in inputs:
        shown = os.fspath(arg)
        path = Path(shown)
        if path.is_dir():
            jobs += _sequence_or_batch(shown, path, out)
        elif path.is_file():
            job = _file_job(shown, path)
            if job is None:
                what = "an image" if path.suffix.lower() in IMAGE_EXTENSIONS else "not readable"
                raise CurveReconError(
                    f"{shown}: {what} (give observation files .json, videos, or folders of "
                    "frames: a single image is not a sequence)"
                )
            jobs.append(job)
        else:
            raise CurveReconError(f"cannot read {shown}: no such file or folder")
    return _unique(jobs)


def _unique(jobs: list[Job]) -> list[Job]:
    """Drop repeats of the same path; refuse two different paths of one name."""
    seen: dict[str, Job] = {}
    kept: list[Job] = []
    for job in jobs:
        other = seen.get(job.name)
        if other is not None and other.path == job.path:
            continue
        if other is not None:
            raise CurveReconError(
                f"inputs {other.input} and {job.input} have the same name {job.name!r} "
                "(their outputs would overwrite each other): rename one, or run them into "
                "different output folders"
            )
        seen[job.name] = job
        kept.append(job)
    return kept


def input_mtime(job: Job) -> float:
    """When the input last changed: the file's mtime, or for a folder of images the latest of
    the folder's and its images' (a frame added, replaced or removed)."""
    path = Path(job.path)
    if job.kind != "images":
        return path.stat().st_mtime
    return max([path.stat().st_mtime] + [p.stat().st_mtime for p in _images(path)])


def check_out_dir(out_dir: str | os.PathLike[str]) -> Path:
    """Create the output folder and check that a file can be written into it."""
    import tempfile

    out = Path(out_dir)
    try:
        out.mkdir(parents=True, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=out, prefix=".write-check-", delete=True):
            pass
    except OSError as exc:
        raise CurveReconError(
            f"cannot write into the output folder {out}: {exc.strerror or exc}"
        ) from None
    return out.resolve()
