"""``import curverecon`` and the command line's parser load none of the heavy libraries (the
pipeline imports them where it uses them), so ``curverecon --help`` answers at once."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

HEAVY = ("numba", "scipy", "matplotlib", "skimage", "imageio", "llvmlite")

PROBE = """
import json, sys
{code}
print(json.dumps(sorted({{m.split(".")[0] for m in sys.modules}})))
"""


def _loaded(code: str) -> set[str]:
    out = subprocess.run(
        [sys.executable, "-c", PROBE.format(code=code)],
        capture_output=True,
        text=True,
        timeout=120,
        check=True,
    )
    return set(json.loads(out.stdout))


@pytest.mark.parametrize(
    "code",
    [
        "import curverecon",
        "from curverecon.cli import build_parser; build_parser()",
        "import contextlib, io\nfrom curverecon.cli import main\n"
        "with contextlib.suppress(SystemExit), contextlib.redirect_stdout(io.StringIO()):\n"
        "    main(['simulate', '--help'])",
        "import curverecon; curverecon.CurveReconError; curverecon.__version__",
    ],
)
def test_no_heavy_module_is_imported(code):
    loaded = _loaded(code)
    assert "curverecon" in loaded
    assert loaded.isdisjoint(HEAVY), sorted(loaded & set(HEAVY))


def test_the_probe_sees_a_heavy_import():
    """The check above can fail: the pipeline does import numba and scipy."""
    assert {"numba", "scipy"} <= _loaded("import curverecon; curverecon.reconstruct")


def test_every_public_name_is_importable_from_the_package():
    import curverecon

    for name in curverecon.__all__:
        assert getattr(curverecon, name) is not None, name
    assert curverecon.solve_minimal is curverecon.solvers.minimal.solve
    assert "reconstruct" in dir(curverecon)
    with pytest.raises(AttributeError):
        _ = curverecon.no_such_name
