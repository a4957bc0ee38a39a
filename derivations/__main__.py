"""Regenerate ``generated/`` and the derivation reports (``make derive``).

Usage::

    python -m derivations [--out DIR] [--docs DIR] [--check]

* ``--out``: where the NumPy modules go (default ``generated/`` of the repository).
* ``--docs``: where ``derivations.report.write_reports`` writes (default ``docs/``).
* ``--check``: regenerate into a temporary folder and compare with ``--out``/``--docs``; print a
  unified diff and exit 1 if anything is stale, write nothing.

The output is deterministic (byte-for-byte the same on every run and machine with the pinned
SymPy/ruff); the elapsed time is printed to stdout only.
"""

from __future__ import annotations

import argparse
import importlib
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

from derivations.codegen.generate import (
    REPO_ROOT,
    compare_or_update,
    render_init,
    render_kernel_module,
    render_module,
    render_system_kernel_module,
)

STALE_MESSAGE = "generated/ is stale: run `make derive` (or pytest --update-generated)"
DRIVER = "derivations/__main__.py"


def _optional(module: str, attribute: str) -> Callable[..., object] | None:
    """``module.attribute`` if the derivation module already provides it, else None (warned)."""
    try:
        mod = importlib.import_module(module)
    except ModuleNotFoundError as exc:
        if exc.name != module:
            raise
        print(f"derive: skipping, {module} does not exist yet", file=sys.stderr)
        return None
    function = getattr(mod, attribute, None)
    if function is None:
        print(f"derive: skipping, {module}.{attribute} does not exist yet", file=sys.stderr)
    return function


def _function_module(module: str, filename: str) -> str | None:
    """Render a module of FunctionSpecs from ``module.generated_functions()``."""
    functions = _optional(module, "generated_functions")
    if functions is None:
        return None
    mod = sys.modules[module]
    constants = getattr(mod, "module_constants", dict)()
    doc = getattr(mod, "MODULE_DOC", None) or (mod.__doc__ or module).strip().split("\n\n")[0]
    return render_module(
        source=module.replace(".", "/") + ".py",
        doc=doc,
        functions=functions(),
        constants=constants,
        filename=f"generated/{filename}",
    )


def _kernel_module(module: str, filename: str) -> str | None:
    """Render a module of scalar numba kernels from ``module.kernel_functions()``."""
    kernels = _optional(module, "kernel_functions")
    if kernels is None:
        return None
    return render_kernel_module(
        source=module.replace(".", "/") + ".py",
        doc=sys.modules[module].KERNEL_DOC,
        kernels=kernels(),
        filename=f"generated/{filename}",
    )


def _record_module(module: str, filename: str, builder: str, kind: str) -> str | None:
    """Render the record ``module.builder()`` returns, as ``render_module``'s argument ``kind``:
    ``polynomial`` (PolynomialColumns, from ``grouped_columns``) or ``system``
    (PolynomialSystem with its start solutions, from ``minimal_system``)."""
    build = _optional(module, builder)
    if build is None:
        return None
    record = build()
    return render_module(
        source=module.replace(".", "/") + ".py",
        doc=record.doc,
        filename=f"generated/{filename}",
        **{kind: record},
    )


def _polynomial_module(module: str, filename: str) -> str | None:
    """Render a PolynomialColumns module from ``module.grouped_columns()``."""
    return _record_module(module, filename, "grouped_columns", "polynomial")


def _system_module(module: str, filename: str) -> str | None:
    """Render a PolynomialSystem module (data tables and start solutions) from
    ``module.minimal_system()``."""
    return _record_module(module, filename, "minimal_system", "system")


def _system_kernel_module(
    module: str, filename: str, builder: str = "minimal_system", unroll_solver: bool = True
) -> str | None:
    """Render straight-line numba kernels of the PolynomialSystem ``module.builder()`` (F, F_x
    and F_t by way of the coefficient matrix W(q); the homotopy tracker's fast path), with the
    linear solve unrolled too when ``unroll_solver``."""
    build = _optional(module, builder)
    if build is None:
        return None
    record = build()
    doc = (
        f"Straight-line numba kernels of generated/{record.name}.py (generated).\n\n"
        f"The system F(x; q) = W(q) u(x) of {module.replace('.', '/')}.py, written out after one "
        "common-subexpression pass instead of read from tables: ``coefficients`` and "
        "``coefficients_t`` give the nonzero entries of W (and dW/dt along dq), "
        "``residual_jacobian`` and ``residual_jacobian_t`` give F, F_x (and F_t) from them.  "
        "Complex arithmetic; every argument a contiguous complex128 array.  "
        "curverecon.solvers.homotopy tracks paths with these when a system comes with them, "
        "and reads the tables of the system module otherwise."
    )
    return render_system_kernel_module(
        source=module.replace(".", "/") + ".py",
        doc=doc,
        system=record,
        filename=f"generated/{filename}",
        unroll_solver=unroll_solver,
    )


#: (file name, one-line summary, builder) in the order they are generated.
TARGETS: tuple[tuple[str, str, Callable[[], str | None]], ...] = (
    (
        "measurement_model.py",
        "maximum-likelihood measurement model and its Jacobians (derivations/measurement.py)",
        lambda: _function_module("derivations.measurement", "measurement_model.py"),
    ),
    (
        "measurement_kernel.py",
        "the measurement model as scalar numba kernels, one frame per call "
        "(derivations/measurement.py)",
        lambda: _kernel_module("derivations.measurement", "measurement_kernel.py"),
    ),
    (
        "frame_equations.py",
        "section 3 per-frame equations (10), (11), (12) (derivations/section3.py)",
        lambda: _function_module("derivations.section3", "frame_equations.py"),
    ),
    (
        "lean_polynomial.py",
        "single-squaring elimination, grouped by observable monomial (derivations/lean.py)",
        lambda: _polynomial_module("derivations.lean", "lean_polynomial.py"),
    ),
    (
        "polynomial_12p.py",
        "the paper's (12'), grouped by observable monomial (derivations/squaring.py)",
        lambda: _polynomial_module("derivations.squaring", "polynomial_12p.py"),
    ),
    (
        "minimal_unsquared.py",
        "the four-frame minimal problem and its start system, solved by monodromy "
        "(derivations/minimal.py)",
        lambda: _system_module("derivations.minimal", "minimal_unsquared.py"),
    ),
    (
        "minimal_unsquared_kernel.py",
        "the same system as straight-line numba kernels: F, F_x, F_t by way of W(q) "
        "(derivations/minimal.py)",
        lambda: _system_kernel_module("derivations.minimal", "minimal_unsquared_kernel.py"),
    ),
    (
        "section2_minimal.py",
        "the seed's Section 2 orthographic rows: closed forms and residuals of their minimal "
        "problems (derivations/section2.py)",
        lambda: _function_module("derivations.section2", "section2_minimal.py"),
    ),
    (
        "rigid_model.py",
        "the orthographic rigid-body measurement model of the Section 2 rows and its Jacobians "
        "(derivations/rigid_model.py)",
        lambda: _function_module("derivations.rigid_model", "rigid_model.py"),
    ),
    (
        "rigid_pinhole.py",
        "the pinhole rigid-body measurement model of the perspective and stereo rows and its "
        "Jacobians (derivations/rigid_pinhole.py)",
        lambda: _function_module("derivations.rigid_pinhole", "rigid_pinhole.py"),
    ),
    (
        "section2_perspective.py",
        "the seed's Section 2 perspective and stereo rows: linear systems of the closed-form "
        "rows (derivations/section2_perspective.py)",
        lambda: _function_module("derivations.section2_perspective", "section2_perspective.py"),
    ),
    (
        "persp_uniform_rotation_system.py",
        "perspective uniform rotation, five frames, with its start system solved by monodromy "
        "(derivations/section2_perspective.py)",
        lambda: _record_module(
            "derivations.section2_perspective",
            "persp_uniform_rotation_system.py",
            "uniform_rotation_record",
            "system",
        ),
    ),
    (
        "persp_fixed_axis_system.py",
        "perspective rotation about a fixed direction, three points, three frames, with its "
        "start system solved by monodromy (derivations/section2_perspective.py)",
        lambda: _record_module(
            "derivations.section2_perspective",
            "persp_fixed_axis_system.py",
            "fixed_axis_record",
            "system",
        ),
    ),
    (
        "persp_uniform_rotation_kernel.py",
        "the perspective uniform rotation system as straight-line numba kernels (its 15 dense "
        "unknowns solved by the tracker's loop) (derivations/section2_perspective.py)",
        lambda: _system_kernel_module(
            "derivations.section2_perspective",
            "persp_uniform_rotation_kernel.py",
            "uniform_rotation_record",
            unroll_solver=False,
        ),
    ),
    (
        "persp_fixed_axis_kernel.py",
        "the perspective fixed-axis system as straight-line numba kernels "
        "(derivations/section2_perspective.py)",
        lambda: _system_kernel_module(
            "derivations.section2_perspective",
            "persp_fixed_axis_kernel.py",
            "fixed_axis_record",
        ),
    ),
)


def generate(out_dir: Path, docs_dir: Path | None, *, verbose: bool = True) -> list[Path]:
    """Write every generated module into ``out_dir`` and the reports into ``docs_dir``.

    Returns the paths written, generated modules first.  Targets whose derivation module does not
    exist yet are skipped with a warning on stderr.
    """
    out_dir.mkdir(parents=True, exist_ok=True)
    written: list[Path] = []
    listed: list[tuple[str, str]] = []
    for filename, summary, build in TARGETS:
        start = time.perf_counter()
        text = build()
        if text is None:
            continue
        path = out_dir / filename
        path.write_text(text)
        written.append(path)
        listed.append((filename.removesuffix(".py"), summary))
        if verbose:
            print(
                f"derive: {filename}: {len(text.splitlines())} lines, "
                f"{time.perf_counter() - start:.1f} s"
            )
    init = out_dir / "__init__.py"
    init.write_text(render_init(listed, DRIVER))
    written.insert(0, init)
    if docs_dir is not None:
        write_reports = _optional("derivations.report", "write_reports")
        if write_reports is not None:
            docs_dir.mkdir(parents=True, exist_ok=True)
            before = {p: p.stat().st_mtime_ns for p in docs_dir.rglob("*") if p.is_file()}
            start = time.perf_counter()
            write_reports(docs_dir)
            written += sorted(
                p
                for p in docs_dir.rglob("*")
                if p.is_file() and before.get(p) != p.stat().st_mtime_ns
            )
            if verbose:
                print(f"derive: reports in {docs_dir.name}/: {time.perf_counter() - start:.1f} s")
                _print_minimal_count()
    return written


def _print_minimal_count() -> None:
    """One line on the minimal problem's count (already computed for the report; cached)."""
    facts = _optional("derivations.minimal_count", "minimal_facts")
    if facts is None:
        return
    f = facts()
    tool = f["tool"]  # type: ignore[index]
    print(
        f"derive: minimal problem: {f['count']} solutions, {f['orbits']} orbits, "  # type: ignore[index]
        f"instances agree: {f['counts_agree']}; msolve {tool['msolve']}, "  # type: ignore[index]
        f"{f['seconds']:.1f} s"  # type: ignore[index]
    )


def check(out_dir: Path, docs_dir: Path | None) -> list[str]:
    """Regenerate into a temporary folder; return one unified diff per stale file."""
    diffs: list[str] = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp_out = Path(tmp) / "generated"
        tmp_docs = Path(tmp) / "docs" if docs_dir is not None else None
        for path in generate(tmp_out, tmp_docs, verbose=False):
            if path.is_relative_to(tmp_out):
                target = out_dir / path.relative_to(tmp_out)
            else:
                assert tmp_docs is not None and docs_dir is not None
                target = docs_dir / path.relative_to(tmp_docs)
            diff = compare_or_update(target, path.read_text(), update=False)
            if diff is not None:
                diffs.append(diff)
        produced = {p.name for p in tmp_out.glob("*.py")}
        for leftover in sorted(p for p in out_dir.glob("*.py") if p.name not in produced):
            diffs.append(f"{leftover}: not produced by derivations/ (delete it)\n")
    return diffs


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m derivations", description=__doc__.split("\n")[0]
    )
    parser.add_argument("--out", type=Path, default=REPO_ROOT / "generated")
    parser.add_argument("--docs", type=Path, default=REPO_ROOT / "docs")
    parser.add_argument("--check", action="store_true", help="compare only, write nothing")
    args = parser.parse_args(argv)
    start = time.perf_counter()
    if args.check:
        diffs = check(args.out, args.docs)
        for diff in diffs:
            sys.stdout.write(diff)
        print(f"derive: elapsed {time.perf_counter() - start:.1f} s")
        if diffs:
            print(STALE_MESSAGE, file=sys.stderr)
            return 1
        return 0
    written = generate(args.out, args.docs)
    print(f"derive: wrote {len(written)} files, elapsed {time.perf_counter() - start:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
