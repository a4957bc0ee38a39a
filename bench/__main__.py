"""``python -m bench`` (``make bench``): accuracy, robustness, stability and speed in one run.

Usage::

    python -m bench [--quick] [--out DIR] [--workers N] [--budget SECONDS] [--full-counts]
    python -m bench --only batch|bundle|fuzz|minimal|outliers|scale|start|trace|unordered [--quick]

Writes ``REPORT.md``, ``report.json`` and PNG plots into ``--out`` (default ``bench/``).  The
speed section runs first in this process (no worker busy); then the scene experiments run on
``--workers`` processes, every scene seeded by its own SeedSequence spawn key, in priority order
(``bench.plan``) until a deadline keeps the run within the budget (620 s by default); the
report prints required against run counts.  Progress goes to stderr.  Then the added sections
(``EXTRA_SECTIONS``; 2026-11-25 18:36-18:52 UTC: bundle 1.4 minutes, fuzz 2.4, minimal 5.2,
scale 2.5, trace 5.1; fuzz and bundle side by side, ``BESIDE``) run and merge their keys into
``report.json``; ``--only NAME`` runs one of them alone.
"""

from __future__ import annotations

import os

# One BLAS thread per process: the pool already uses every core, and timings stay comparable.
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
import warnings  # noqa: E402
from collections.abc import Callable  # noqa: E402
from dataclasses import dataclass  # noqa: E402
from datetime import datetime, timezone  # noqa: E402
from itertools import zip_longest  # noqa: E402
from pathlib import Path  # noqa: E402
from typing import Any  # noqa: E402

from bench import accuracy, plan, report, robustness, speed, stability  # noqa: E402
from bench.common import Task, chunks, machine_info, run_tasks  # noqa: E402
from bench.config import Config, full, quick  # noqa: E402

PRIORITY_WEIGHT = 3.0
"""Share of robustness and of the first noise-free 6-frame scenes against other groups."""

REPORT_RESERVE_S = 8.0
"""Wall time kept back for the summaries, the plots and writing the report."""


def _log(msg: str) -> None:
    print(f"bench: {msg}", file=sys.stderr, flush=True)


def run_speed(cfg: Config) -> dict[str, Any]:
    """The speed section (main process)."""
    out: dict[str, Any] = {}
    if cfg.derive:
        _log("timing the derivation (python -m derivations into a temporary folder)")
        out["derive"] = speed.derive_seconds()
    _log("generated functions against sympy.lambdify")
    out["kernels"] = speed.kernels(cfg.kernel_frames, cfg.kernel_min_seconds, cfg.seed)
    _log("refinement: generated Jacobian against scipy finite differences")
    out["refine_vs_fd"] = speed.refinement_vs_fd(cfg.fd_problems, cfg.seed)
    _log("reconstruction of 20 frames, refinement of 1000 frames")
    out["reconstruct_20"] = speed.reconstruct_times(20, cfg.reconstruct_20_repeats, cfg.seed)
    out["refine_1000"] = speed.refine_times(1000, cfg.refine_1000_repeats, cfg.seed)
    _log("reconstruction time against the number of frames")
    out["scaling"] = speed.scaling(cfg.scaling_frames, cfg.scaling_budget_s, cfg.seed)
    return out


@dataclass
class _Group:
    """One experiment's scenes: a task per chunk, a floor run early, a weight for the rest."""

    label: str
    function: Callable[..., list[dict[str, Any]]]
    args: Callable[[range], tuple]
    start: int
    stop: int
    chunk: int
    floor: int
    weight: float

    def tasks(self, lo: int, hi: int) -> list[Task]:
        lo, hi = self.start + lo, min(self.stop, self.start + hi)
        return [
            Task(self.function, self.args(range(lo + r.start, lo + r.stop)), len(r), self.label)
            for r in chunks(max(0, hi - lo), self.chunk)
        ]


def build_tasks(cfg: Config, deadline: float) -> list[Task]:
    """Every pool task at its required count, in priority order (``bench.plan``).

    Cheap accuracy parts; the headline cell; a floor of every other group (interleaved); then
    the rest of every group merged by weighted fair queuing (robustness and the first noise-free
    6-frame scenes weigh ``PRIORITY_WEIGHT``), so a cut at the deadline shortens all groups.
    """
    seed, chord = cfg.seed, cfg.chord
    hn, hf = cfg.headline_noise, cfg.headline_frames
    cheap: list[Task] = []
    head: list[Task] = []
    groups: list[_Group] = []
    for cell_id, (noise, n) in enumerate(
        (s, n) for s in cfg.noise_levels for n in cfg.frame_counts
    ):
        for r in chunks(cfg.accuracy_scenes, 4 * cfg.chunk):
            args = (seed, cell_id, noise, n, r, "cheap", chord, deadline)
            cheap.append(Task(accuracy.run_scenes, args, len(r), f"acc|{noise}|{n}"))
        g = _Group(
            f"accd|{noise}|{n}",
            accuracy.run_scenes,
            lambda r, c=cell_id, s=noise, n=n: (
                seed,
                c,
                s,
                n,
                r,
                "default",
                chord,
                deadline,
                True,  # the basin diagnostics: two refinements a scene, about 3 % of its time
            ),
            0,
            cfg.accuracy_default_scenes,
            cfg.chunk,
            2 * cfg.chunk,
            1.0,
        )
        if (noise, n) == (hn, hf):
            head += g.tasks(0, g.stop)
        else:
            groups.append(g)
    for fid, frac in enumerate(cfg.outlier_fractions):
        groups.append(
            _Group(
                f"rob|{frac}",
                robustness.run_scenes,
                lambda r, i=fid, f=frac: (seed, i, f, hn, hf, r, chord, deadline),
                0,
                cfg.robustness_scenes,
                cfg.chunk,
                5 * cfg.chunk,
                PRIORITY_WEIGHT,
            )
        )
    required, first = plan.stability_counts(cfg)
    for n, k in required.items():
        k1 = first.get(n, 0)
        for lo, hi, w in ((0, k1, PRIORITY_WEIGHT), (k1, k, 1.0)):
            if hi > lo:
                floor = 12 * cfg.chunk if w > 1 else (5 * cfg.chunk if lo == 0 else 0)
                groups.append(
                    _Group(
                        f"stab|{n}",
                        stability.run_scenes,
                        lambda r, n=n: (seed, n, r, chord, deadline),
                        lo,
                        hi,
                        cfg.chunk,
                        floor,
                        w,
                    )
                )
    for n, k in plan.split(cfg.stability_linear_scenes, cfg.stability_linear_frames).items():
        groups.append(
            _Group(
                f"lin|{n}",
                stability.run_linear_scenes,
                lambda r, n=n: (seed, n, r, chord, deadline),
                0,
                k,
                4 * cfg.chunk,
                4 * cfg.chunk,
                1.0,
            )
        )
    floors = [g.tasks(0, g.floor) for g in groups]
    rest = [g.tasks(g.floor, g.stop - g.start) for g in groups]
    merged = sorted(
        ((j + 1) / g.weight, gi, j)
        for gi, (g, ts) in enumerate(zip(groups, rest, strict=True))
        for j in range(len(ts))
    )
    return cheap + head + _interleave(floors) + [rest[gi][j] for _, gi, j in merged]


def _interleave(groups: list[list[Task]]) -> list[Task]:
    """Round robin over the groups' task lists."""
    return [t for row in zip_longest(*groups) for t in row if t is not None]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m bench", description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help="tiny configuration (seconds)")
    parser.add_argument("--out", type=Path, default=Path(__file__).resolve().parent)
    parser.add_argument("--workers", type=int, default=None)
    parser.add_argument("--budget", type=float, default=None, help="wall-clock budget (s)")
    parser.add_argument("--seed", type=int, default=None)
    parser.add_argument(
        "--full-counts", action="store_true", help="run the required counts whatever the budget"
    )
    parser.add_argument("--no-progress", action="store_true")
    parser.add_argument(
        "--only",
        choices=sorted(EXTRA_SECTIONS),
        help="run one added section alone and merge its keys into the report",
    )
    args = parser.parse_args(argv)
    if args.only:
        merge_section(args.out, args.only, run_section(args.only, args.quick))
        return 0
    # The linearisation overflows on noisy data (expected, counted as its errors): keep stderr
    # for progress.  Workers are forked and inherit the filter.
    warnings.filterwarnings("ignore", category=RuntimeWarning)
    cfg = quick() if args.quick else full()
    if args.workers is not None:
        cfg.workers = args.workers
    if args.budget is not None:
        cfg.budget_s = args.budget
    if args.seed is not None:
        cfg.seed = args.seed
    progress = not args.no_progress
    t_start = time.time()
    started = datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    command = "python -m bench" + (" --quick" if args.quick else "")
    _log(f"configuration {cfg.name}, budget {cfg.budget_s:.0f} s, {cfg.workers} workers")

    sections: dict[str, Any] = {"machine": machine_info()}
    sections["speed"] = run_speed(cfg)
    t_speed = time.time() - t_start
    deadline = t_start + cfg.budget_s - REPORT_RESERVE_S
    if args.full_counts:
        deadline = float("inf")
    available = max(0.0, deadline - time.time()) * cfg.workers
    _log(
        f"speed section took {t_speed:.0f} s; scene experiments until the deadline in "
        f"{max(0.0, deadline - time.time()):.0f} s"
    )
    t_exp = time.time()
    results = run_tasks(
        build_tasks(cfg, deadline), cfg.workers, "scenes (stops at the deadline)", progress
    )
    t_exp = time.time() - t_exp
    _log(f"scene experiments took {t_exp:.0f} s; writing the report")
    sections.update(
        report.summarise(
            cfg, results, t_speed=t_speed, t_experiments=t_exp, available_cpu_s=available
        )
    )
    paths = report.write(args.out, cfg, sections, command=command, started=started, t_start=t_start)
    _log(f"wrote {', '.join(str(p) for p in paths)} in {time.time() - t_start:.0f} s")
    if args.quick:
        # the added sections take minutes each even when quick: run one with --only NAME --quick
        _log(f"--quick: added sections skipped ({', '.join(sorted(EXTRA_SECTIONS))})")
        return 0
    run_extra_sections(args.out)
    return 0


BESIDE = ("fuzz", "bundle")
"""Added sections run side by side: fuzz (one pytest process, in a forked child: a daemon child
may start subprocesses, not a pool) beside bundle (a pool of two; its time ratios are CPU times,
``time.process_time``).  That keeps ``make bench`` near 30 minutes.  The minimal section uses a
pool of two of its own since 2026-11-25 21:10 UTC (3,000 fresh scenes), so it runs alone; its
times are one process's either way.  The others use every core and run alone, after them."""


def run_extra_sections(out: Path) -> None:
    """Every added section once, merged into the report: ``BESIDE`` side by side, then the
    rest in turn."""
    from multiprocessing import get_context

    first, second = BESIDE
    with get_context("fork").Pool(1) as pool:
        pending = pool.apply_async(run_section, (first, False))
        merge_section(out, second, run_section(second, False))
        merge_section(out, first, pending.get())
    for name in sorted(set(EXTRA_SECTIONS) - set(BESIDE)):
        merge_section(out, name, run_section(name, False))


EXTRA_SECTIONS = {
    "batch": "bench.batch",
    "bundle": "bench.bundle",
    "configurations": "bench.configurations",
    "fuzz": "bench.fuzz",
    "honest": "bench.honest",
    "minimal": "bench.minimal",
    "outliers": "bench.outliers",
    "perspective": "bench.perspective",
    "scale": "bench.scale",
    "start": "bench.start",
    "trace": "bench.trace",
    "unordered": "bench.unordered",
}
"""Sections with a module of their own (``run(quick) -> dict`` of report keys); each also runs
alone: ``python -m bench --only NAME`` or ``python -m bench.NAME``."""


def run_section(name: str, quick: bool) -> dict[str, Any]:
    import importlib

    _log(f"section {name}")
    t0 = time.time()
    result = importlib.import_module(EXTRA_SECTIONS[name]).run(quick)
    result[f"{name}_section_seconds"] = round(time.time() - t0, 1)
    result[f"{name}_section_started"] = datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    return result


def merge_section(out: Path, name: str, result: dict[str, Any]) -> None:
    """Add a section's keys to ``report.json`` (the others kept) and its table to REPORT.md,
    and rewrite REPORT.md's targets table (``bench.targets``) from the merged keys."""
    import json

    from bench import targets

    out.mkdir(parents=True, exist_ok=True)
    path = out / "report.json"
    doc = json.loads(path.read_text()) if path.exists() else {}
    doc.update(result)
    doc.setdefault("sections", {})[name] = sorted(result)
    path.write_text(json.dumps(doc, indent=1) + "\n")
    md = out / "REPORT.md"
    text = md.read_text() if md.exists() else "# Benchmark report\n"
    head, *parts = text.split("\n## Section: ")
    head = head.split(f"\n## {targets.TITLE}")[0]  # rewritten below from the merged keys
    kept = {p.split("\n", 1)[0]: p for p in parts}
    # a multi-line value (a failing test's output) goes below the table, in a code block
    long = {k: v for k, v in result.items() if isinstance(v, str) and "\n" in v}
    rows = "\n".join(
        f"| `{k}` | {'(below)' if k in long else v} |" for k, v in sorted(result.items())
    )
    blocks = "".join(f"\n`{k}`:\n\n```\n{v.strip()}\n```\n" for k, v in sorted(long.items()))
    kept[name] = f"{name}\n\n| key | value |\n|---|---|\n{rows}\n{blocks}"
    body = "".join(f"\n## Section: {kept[k].rstrip()}\n" for k in sorted(kept))
    table = targets.markdown(doc)
    md.write_text(head.rstrip("\n") + "\n\n" + table + body)
    _log(f"merged section {name} into {path}")


if __name__ == "__main__":
    sys.exit(main())
