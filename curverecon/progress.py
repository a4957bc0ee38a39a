"""Progress of a long reconstruction on stderr (tqdm), stage by stage.

Shown only when asked (``ReconstructOptions.progress``; the command asks when stderr is a
terminal and ``--quiet`` is not given), so that logs and pipes stay clean.
"""

from __future__ import annotations

import sys
from collections.abc import Sequence

from tqdm import tqdm


class StageProgress:
    """A bar over named stages: ``step(name)`` when a stage starts, ``close()`` at the end."""

    def __init__(self, stages: Sequence[str], enabled: bool, desc: str = "reconstruct") -> None:
        self._bar = tqdm(
            total=len(stages),
            desc=desc,
            file=sys.stderr,
            disable=not enabled,
            leave=False,
            bar_format="{desc}: {n_fmt}/{total_fmt} {postfix} [{elapsed}]",
        )
        self._started = False

    def step(self, name: str) -> None:
        if self._started:
            self._bar.update(1)
        self._started = True
        self._bar.set_postfix_str(name)

    def close(self) -> None:
        self._bar.update(self._bar.total - self._bar.n)
        self._bar.close()
