"""No function in ``curverecon/`` is longer than ``LIMIT`` lines: a function is read at once.

A function counts from its first decorator line to its last line, nested functions and
classes included (a closure is part of the function that defines it).  The folders of
``EXCLUDE`` are skipped; removing a folder from it checks that folder too.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import curverecon

ROOT = Path(curverecon.__file__).parent
LIMIT = 150
EXCLUDE = ()
FOLDERS = (".", *sorted(p.name for p in ROOT.iterdir() if p.is_dir() and any(p.glob("*.py"))))


def function_lengths(source: str) -> list[tuple[str, int, int]]:
    """(qualified name, first line, length in lines) of every function in ``source``, from
    its first decorator line to its end."""
    out: list[tuple[str, int, int]] = []

    def visit(node: ast.AST, prefix: str) -> None:
        for child in ast.iter_child_nodes(node):
            name = prefix
            if isinstance(child, ast.FunctionDef | ast.AsyncFunctionDef):
                first = min([d.lineno for d in child.decorator_list] + [child.lineno])
                name = f"{prefix}{child.name}"
                out.append((name, first, child.end_lineno - first + 1))
                name += "."
            elif isinstance(child, ast.ClassDef):
                name = f"{prefix}{child.name}."
            visit(child, name)

    visit(ast.parse(source), "")
    return out


def _files(folder: str) -> list[Path]:
    if folder == ".":
        return sorted(ROOT.glob("*.py"))
    return sorted((ROOT / folder).rglob("*.py"))


@pytest.mark.parametrize(
    "folder",
    [
        pytest.param(
            f, marks=pytest.mark.skipif(f in EXCLUDE, reason=f"curverecon/{f}/ is in EXCLUDE")
        )
        for f in FOLDERS
    ],
)
def test_no_function_is_longer_than_the_limit(folder: str) -> None:
    files = _files(folder)
    assert files, f"no Python files in curverecon/{folder}"
    long = [
        f"{path.relative_to(ROOT.parent)}:{line} {name} ({n} lines)"
        for path in files
        for name, line, n in function_lengths(path.read_text(encoding="utf-8"))
        if n > LIMIT
    ]
    assert not long, f"functions over {LIMIT} lines:\n" + "\n".join(long)


def test_the_count_runs_from_the_decorator_and_includes_closures() -> None:
    body = [f"            x{i} = {i}" for i in range(LIMIT - 4)]
    lines = [
        "import functools",
        "",
        "class Holder:",
        "    @functools.cache",
        "    @staticmethod",
        "    def outer():",
        "        def inner():",
        *body,
        "        return inner",
        "",
        "def short():",
        "    return 1",
    ]
    lengths = {name: n for name, _, n in function_lengths("\n".join(lines))}
    assert lengths == {"Holder.outer": LIMIT + 1, "Holder.outer.inner": LIMIT - 3, "short": 2}


def test_every_folder_is_checked_or_excluded_by_name() -> None:
    assert set(EXCLUDE) <= set(FOLDERS)
    assert {"solvers", "refine", "robust", "curve"} <= set(FOLDERS)
