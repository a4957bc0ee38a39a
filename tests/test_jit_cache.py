"""``curverecon.jit_cache``: numba's on-disk cache of a function that calls another module's
compiled code is flushed when that module changes (numba keys it on the caller's file alone)."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

from curverecon import jit_cache

CALLER = """
import numba
from curverecon import jit_cache
import dep

@numba.njit(cache=True)
def g():
    return dep.f() + 10

if {guard}:
    jit_cache.drop_stale((g,), (dep,))
print(g())
"""


def _run(folder: Path, guard: bool) -> str:
    (folder / "caller.py").write_text(CALLER.format(guard=guard))
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(folder), *sys.path])}
    env.pop("NUMBA_CACHE_DIR", None)
    out = subprocess.run(
        [sys.executable, "-c", "import caller"],
        cwd=folder,
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
        check=True,
    )
    return out.stdout.strip()


def _dep(folder: Path, value: int) -> None:
    path = folder / "dep.py"
    path.write_text(
        textwrap.dedent(
            f"""
            import numba

            @numba.njit(cache=True)
            def f():
                return {value}
            """
        )
    )
    st = path.stat()  # a new mtime, whatever the file system's resolution
    os.utime(path, (st.st_atime + 5, st.st_mtime + 5))


def test_a_changed_dependency_is_compiled_in_not_served_stale(tmp_path: Path) -> None:
    # numba alone: the caller's cache keeps the dependency's old code (the failure mode)
    stale = tmp_path / "stale"
    stale.mkdir()
    _dep(stale, 1)
    assert _run(stale, guard=False) == "11"
    _dep(stale, 2)
    assert _run(stale, guard=False) == "11"
    # with drop_stale at import the caller is compiled again against the new dependency
    fresh = tmp_path / "fresh"
    fresh.mkdir()
    _dep(fresh, 1)
    assert _run(fresh, guard=True) == "11"
    assert _run(fresh, guard=True) == "11"  # the stamp matches: served from the cache
    _dep(fresh, 2)
    assert _run(fresh, guard=True) == "12"


class _FakeCache:
    def __init__(self, path: Path) -> None:
        self.cache_path = str(path)
        self.flushes = 0

    def flush(self) -> None:
        self.flushes += 1


class _FakeDispatcher:
    __name__ = "kernel"

    def __init__(self, path: Path) -> None:
        self._cache = _FakeCache(path)


def test_the_stamp_decides_and_uncached_functions_are_left_alone(tmp_path: Path) -> None:
    d = _FakeDispatcher(tmp_path)
    assert jit_cache.drop_stale((d,), (jit_cache,)) is True  # no stamp yet
    assert jit_cache.drop_stale((d,), (jit_cache,)) is False
    assert d._cache.flushes == 1
    jit_cache.stamp_path(d).write_text("another digest")
    assert jit_cache.drop_stale((d,), (jit_cache,)) is True and d._cache.flushes == 2
    assert jit_cache.drop_stale((lambda: None,), (jit_cache,)) is False


def test_the_package_stamps_its_cross_module_kernels() -> None:
    from curverecon.generated import measurement_kernel, minimal_unsquared_kernel

    from curverecon.refine import pose_kernel
    from curverecon.solvers import homotopy, minimal

    digest = jit_cache.sources_digest((homotopy, minimal_unsquared_kernel))
    for d in (minimal._track_kernels, minimal._newton_kernels):
        stamp = jit_cache.stamp_path(d)
        assert stamp.read_text() == digest
    stamp = jit_cache.stamp_path(pose_kernel.optimise_frames)
    assert stamp.read_text() == jit_cache.sources_digest((measurement_kernel,))
