"""numba's on-disk cache, kept in step with the compiled code a cached function calls.

numba (``cache=True``) keys a function's cache on the source of the file that defines it and
nothing else.  A cached function that calls compiled functions of *other* modules (the
homotopy tracker compiled in ``solvers/minimal.py`` around ``solvers/homotopy.py`` and the
generated kernels; the pose iteration in ``refine/pose_kernel.py`` around the generated
measurement model) keeps running its cached machine code after those modules change: the old
tracker or the old model, silently (2026-11-27: a tracker change in ``homotopy.py`` alone made
a stale cache read past the end of its options vector and fail 12 paths of one scene).

:func:`drop_stale` closes that gap: each dependent function's cache folder holds a stamp,
a SHA-256 of its dependencies' sources; when the stamp differs (or is missing), the function's
cache index is flushed before its first call, so numba compiles it again and saves the new code.
"""

from __future__ import annotations

import hashlib
from collections.abc import Sequence
from pathlib import Path
from types import ModuleType
from typing import Any


def sources_digest(modules: Sequence[ModuleType]) -> str:
    """SHA-256 (hex) of the modules' source files, in the order given."""
    h = hashlib.sha256()
    for m in modules:
        h.update(Path(str(m.__file__)).read_bytes())
    return h.hexdigest()


def stamp_path(dispatcher: Any) -> Path:
    """Where ``dispatcher``'s dependency stamp lives: its numba cache folder (the one numba
    chose: ``__pycache__`` beside the source, or ``NUMBA_CACHE_DIR``), named after the function
    and its module, as numba names the function's own cache files."""
    module = str(getattr(dispatcher, "__module__", None) or "").rsplit(".", 1)[-1]
    return Path(dispatcher._cache.cache_path) / f"{module}.{dispatcher.__name__}.deps"


def drop_stale(dispatchers: Sequence[Any], dependencies: Sequence[ModuleType]) -> bool:
    """Flush the on-disk cache of every numba dispatcher in ``dispatchers`` whose stamp does not
    match the current sources of ``dependencies``, and write the new stamp.  Call it at import
    of the module that defines them, before any is called.  True when a cache was flushed.

    numba's cache object of a dispatcher (``dispatcher._cache``, numba pinned in
    pyproject.toml) is the one place that knows its folder and can flush its index; a folder
    numba cannot write to (a read-only install) is left as it is, as numba itself does."""
    digest = sources_digest(dependencies)
    flushed = False
    for d in dispatchers:
        if getattr(getattr(d, "_cache", None), "cache_path", None) is None:
            continue  # not cached (NUMBA_DISABLE_JIT, or cache=False): nothing to go stale
        try:
            stamp = stamp_path(d)
            if stamp.is_file() and stamp.read_text() == digest:
                continue
            d._cache.flush()
            stamp.write_text(digest)
            flushed = True
        except OSError:
            continue
    return flushed
