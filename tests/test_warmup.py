"""``python -m curverecon.warmup`` compiles every numba kernel a reconstruction calls."""

from __future__ import annotations

from pathlib import Path

from curverecon import warmup

ROOT = Path(__file__).resolve().parents[1]


def _module_name(path: Path) -> str:
    rel = path.relative_to(ROOT).with_suffix("")
    parts = rel.parts if rel.parts[0] == "curverecon" else ("curverecon", *rel.parts)
    return ".".join(parts)


def test_every_module_with_kernels_is_listed():
    sources = [*(ROOT / "curverecon").rglob("*.py"), *(ROOT / "generated").glob("*.py")]
    with_kernels = {_module_name(p) for p in sources if "numba.njit" in p.read_text()}
    assert with_kernels == set(warmup.KERNEL_MODULES)


def test_the_kernels_left_alone_exist():
    kernels = warmup.cached_kernels()
    assert warmup.TABLE_TRACKER <= set(kernels)
    assert len(kernels) > len(warmup.TABLE_TRACKER)


def test_the_warmup_reaches_every_kernel_of_the_pipeline(capsys):
    assert warmup.main([]) == 0
    assert warmup.not_compiled() == []
    captured = capsys.readouterr()
    assert "compiled kernels in numba's cache" in captured.out
    assert captured.err == ""


def test_the_perspective_warmup_reaches_the_perspective_solvers(capsys):
    assert warmup.main(["--perspective"]) == 0
    assert warmup.not_compiled(perspective=True) == []
    assert capsys.readouterr().err == ""
