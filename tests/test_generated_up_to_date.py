"""generated/ (and the derivation reports) must be what ``make derive`` produces right now.

Regenerates everything into ``tmp_path`` and compares file by file.  On a difference the test fails
with a unified diff; ``pytest --update-generated`` overwrites the committed files instead
(SymForce's compare_or_update).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from derivations.__main__ import STALE_MESSAGE, generate
from derivations.codegen.generate import REPO_ROOT, compare_or_update

GENERATED = REPO_ROOT / "generated"
DOCS = REPO_ROOT / "docs"


@pytest.fixture(scope="module")
def regenerated(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path, list[Path]]:
    """Run the whole derivation once into a temporary folder."""
    root = tmp_path_factory.mktemp("derive")
    out, docs = root / "generated", root / "docs"
    written = generate(out, docs, verbose=False)
    return out, docs, written


def _target(path: Path, out: Path, docs: Path) -> Path:
    if path.is_relative_to(out):
        return GENERATED / path.relative_to(out)
    return DOCS / path.relative_to(docs)


def test_generated_up_to_date(
    regenerated: tuple[Path, Path, list[Path]], update_generated: bool
) -> None:
    out, docs, written = regenerated
    diffs = []
    for path in written:
        diff = compare_or_update(_target(path, out, docs), path.read_text(), update_generated)
        if diff is not None:
            diffs.append(diff)
    if diffs:
        pytest.fail(STALE_MESSAGE + "\n\n" + "".join(diffs), pytrace=False)


def test_no_leftover_generated_modules(
    regenerated: tuple[Path, Path, list[Path]], update_generated: bool
) -> None:
    """Every module in generated/ is produced by the derivation (no stale leftovers)."""
    out, _, _ = regenerated
    produced = {p.name for p in out.glob("*.py")}
    leftovers = sorted(p for p in GENERATED.glob("*.py") if p.name not in produced)
    if leftovers and update_generated:
        for path in leftovers:
            path.unlink()
        shutil.rmtree(GENERATED / "__pycache__", ignore_errors=True)
        leftovers = []
    assert not leftovers, STALE_MESSAGE + f": not produced by derivations/: {leftovers}"


def test_generation_is_deterministic(
    regenerated: tuple[Path, Path, list[Path]], tmp_path: Path
) -> None:
    """A second run gives byte-identical modules (no timestamps, paths or hash-order effects)."""
    out, _, written = regenerated
    again = generate(tmp_path / "generated", None, verbose=False)
    first = {p.name: p.read_bytes() for p in written if p.is_relative_to(out)}
    second = {p.name: p.read_bytes() for p in again}
    assert first == second


def test_preamble_names_sources() -> None:
    """Each generated module says it is generated and names derivation, template and SymPy."""
    for path in sorted(GENERATED.glob("*.py")):
        head = path.read_text()[:800]
        assert "Generated, do not edit / do not modify" in head, path
        assert "make derive" in head, path
        assert "SymPy:" in head and "Derivation: derivations/" in head, path
        assert "/work/" not in path.read_text(), f"absolute path in {path}"


@pytest.mark.parametrize(
    ("module", "filename"),
    [
        ("derivations.measurement", "measurement_model.py"),
        ("derivations.section2", "section2_minimal.py"),
    ],
)
def test_generated_module_independent_of_hash_seed(module: str, filename: str) -> None:
    """Regenerated under another PYTHONHASHSEED, the module is byte-identical."""
    code = (
        "import sys\n"
        "from derivations.__main__ import _function_module\n"
        f"text = _function_module({module!r}, {filename!r})\n"
        "sys.stdout.write(text)\n"
    )
    env = {**os.environ, "PYTHONHASHSEED": "4242"}
    result = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        cwd=REPO_ROOT,
        env=env,
        check=False,
    )
    assert result.returncode == 0, result.stderr
    committed = (GENERATED / filename).read_text()
    assert result.stdout == committed, STALE_MESSAGE


def test_section2_modules_are_derived() -> None:
    """The Section 2 rows' generated module is one of the derivation's targets."""
    from derivations.__main__ import TARGETS

    assert "section2_minimal.py" in {name for name, _, _ in TARGETS}
