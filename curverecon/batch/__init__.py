"""``curverecon batch``: many sequences at once on a Dask cluster (docs/batch.md).

Importing this package is cheap: Dask and pandas are imported only when :func:`run` is called
(they come with the optional extra ``pip install "curverecon[batch]"``).
"""

from __future__ import annotations

from collections.abc import Sequence
from os import PathLike
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # pragma: no cover
    import pandas


def run(
    inputs: Sequence[str | PathLike[str]],
    out_dir: str | PathLike[str],
    client: Any = None,
    workers: int | None = None,
    force: bool = False,
    *,
    scheduler: str | None = None,
    progress: bool | None = None,
    verbose: bool = False,
) -> pandas.DataFrame:
    """Trace and reconstruct every input into ``out_dir``; returns the summary table.

    See :func:`curverecon.batch.runner.run` (this wrapper only defers the heavy imports).
    """
    from curverecon.batch.runner import run as _run

    return _run(
        inputs,
        out_dir,
        client=client,
        workers=workers,
        force=force,
        scheduler=scheduler,
        progress=progress,
        verbose=verbose,
    )
