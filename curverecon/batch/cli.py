"""The ``curverecon batch`` subcommand: its arguments and a thin shell over
:func:`curverecon.batch.run`.  Light to import (``curverecon --help`` imports it): Dask and
pandas are imported only when the command runs."""

from __future__ import annotations

import argparse
import sys

EXIT_SOME_FAILED = 3
"""Exit status when some inputs failed (the summary says which); 0 when all succeeded, 2 for
bad arguments (before anything runs)."""


HELP = "trace and reconstruct many sequences on a Dask cluster"


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The ``batch`` subcommand's description and arguments."""
    p.description = (
        "Each INPUT is an observation file, a video, a folder of frames (one "
        "sequence) or a folder of those (a batch). Outputs per input <name>.reconstruction.json "
        "(and <name>.observations.json when traced), and summary.csv / summary.parquet. "
        "Exit 0: all succeeded; 3: some failed; 2: bad arguments."
    )
    p.add_argument("inputs", nargs="*", metavar="INPUT", help="observation files, videos, folders")
    p.add_argument("-o", "--output", required=True, metavar="OUT_DIR", help="output folder")
    p.add_argument(
        "--scheduler", metavar="ADDRESS", help="an existing Dask scheduler (tcp://host:8786)"
    )
    p.add_argument(
        "--workers", type=int, help="worker processes of the local cluster (default: all cores)"
    )
    p.add_argument("--force", action="store_true", help="redo inputs whose outputs are current")
    p.add_argument(
        "--quiet", action="store_true", help="no progress bar (shown only on a terminal anyway)"
    )


def command(args: argparse.Namespace) -> int:
    """Run the batch; print one final line; return the exit status."""
    from curverecon.batch.runner import run
    from curverecon.errors import CurveReconError

    if args.scheduler is not None and args.workers is not None:
        raise CurveReconError("--workers sets the local cluster's size: not with --scheduler")
    summary = run(
        args.inputs,
        args.output,
        workers=args.workers,
        force=args.force,
        scheduler=args.scheduler,
        progress=sys.stderr.isatty() and not args.quiet,
        verbose=True,
    )
    failed = int((summary["status"] != "ok").sum())
    skipped = summary.attrs.get("skipped", 0)
    print(
        f"curverecon: batch: {len(summary)} inputs, {len(summary) - failed} ok "
        f"({skipped} already done), {failed} failed, {summary.attrs.get('seconds', 0):.1f} s; "
        f"summary in {args.output}/summary.csv",
        file=sys.stderr,
    )
    return EXIT_SOME_FAILED if failed else 0
