"""Command line: ``curverecon reconstruct | simulate | match-flat | trace | batch``.

Bad input exits with status 2 and one line ``curverecon: error: <message>`` on stderr.

Building the parser imports neither NumPy nor the pipeline (``--help`` answers at once); each
command imports what it uses.  A command is a ``_Command`` in ``COMMANDS``: its name, its help,
a function adding its arguments and its handler.
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Callable, Sequence
from typing import NamedTuple

from curverecon.batch import cli as batch_cli  # light: Dask and pandas load when it runs
from curverecon.errors import CurveReconError

MAX_SIMULATED_FRAMES = 10_000_000
"""``simulate --frames`` above this would need more memory than a machine has (about 1 kB a
frame with polylines)."""

SCENE_FAMILIES = ("bezier", "helix", "clothoid", "fourier", "sharp-ends", "random")
"""Families of JSON scenes (``curverecon.curve_families.FAMILIES``, named here so that the
parser does not import NumPy; tests/test_cli.py checks that both lists agree)."""

IMAGE_FAMILIES = ("bezier", "helix", "wave", "loop")
"""Families of rendered scenes (``--images``; ``curverecon.trace.render.FAMILIES``)."""

FAMILIES = tuple(dict.fromkeys(SCENE_FAMILIES + IMAGE_FAMILIES))
"""Every family ``simulate --family`` accepts; each scene kind refuses the ones it cannot draw."""

OUTLIER_MODELS = ("gross", "random")
"""``curverecon.simulate.OUTLIER_MODELS``."""

MOTIONS = ("free", "uniform-rotation", "fixed-axis", "force-field", "auto")
"""``reconstruct --motion``: the models the rigid stage fits, and "auto" (named here so that the
parser does not import NumPy; ``curverecon.model.configuration.FITTED_MOTIONS``)."""

SIMULATED_MOTIONS = (*MOTIONS[:-1], "rotation-free")
"""``simulate --motion``: ``curverecon.simulate.CAMERA_MOTIONS`` ("rotation-free" with
``--projection perspective|stereo`` only)."""


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors (status 2, no usage dump)."""

    def error(self, message: str) -> None:  # type: ignore[override]
        raise CurveReconError(message)


def _warn(message: str) -> None:
    print(f"curverecon: warning: {message}", file=sys.stderr)


def _add_reconstruct(rec: argparse.ArgumentParser) -> None:
    rec.add_argument("input", help="curverecon.observations/1 JSON file")
    rec.add_argument("-o", "--output", required=True, help="curverecon.reconstruction/1 JSON")
    rec.add_argument(
        "--method",
        choices=["auto", "linear"],
        default="auto",
        help="auto (default): a robust start, maximum likelihood and an outlier test; linear: "
        "the paper's linearisation alone (its own setting, 38 frames or more)",
    )
    rec.add_argument(
        "--estimator",
        choices=["marginal", "ml"],
        default="marginal",
        help="with --method auto, the final shape: the marginal likelihood, every frame's pose "
        "integrated out (default; less biased), or plain maximum likelihood",
    )
    rec.add_argument(
        "--point-sigma",
        type=float,
        default=1.0,
        metavar="PX",
        help="std of the image points, in their units (pixels; default 1)",
    )
    rec.add_argument(
        "--tangent-sigma",
        type=float,
        default=1.0,
        metavar="DEG",
        help="std of the tangent directions, degrees (default 1)",
    )
    rec.add_argument(
        "--motion",
        choices=[*MOTIONS[:-1], "rotation-free", MOTIONS[-1]],
        help='the motion model, overriding the document\'s "motion" (free: any rotation per '
        "frame; uniform-rotation, fixed-axis: about one axis; force-field: the mass centre on a "
        "parabola; rotation-free: translation only, perspective or stereo; auto: every model "
        "the points allow, chosen by model selection)",
    )
    rec.add_argument(
        "--plot", metavar="FILE.png", help="also draw the reconstruction to this PNG file"
    )
    rec.add_argument(
        "--quiet", action="store_true", help="no progress bar (shown only on a terminal anyway)"
    )
    rec.add_argument(
        "--curve-bundle",
        choices=["on", "off"],
        default="on",
        help="with polylines (and --method auto): refine the poses and the 3-D curve jointly "
        "against every frame's polyline, then take the shape from the fitted curve (default on)",
    )


def _add_simulate(sim: argparse.ArgumentParser) -> None:
    sim.add_argument("-o", "--output", required=True, help="scene (observations) JSON")
    sim.add_argument("--truth", help="write the truth to this JSON file")
    sim.add_argument("--frames", type=int, default=20, help="number of frames (default 20)")
    sim.add_argument(
        "--point-noise", "--noise-px", dest="point_noise", type=float, default=0.0,
        help="pixels (std)",
    )  # fmt: skip
    sim.add_argument("--tangent-noise", type=float, default=0.0, help="degrees (std)")
    sim.add_argument(
        "--outlier-fraction", type=float, default=0.0, help="share of frames made outliers (0-1)"
    )
    sim.add_argument(
        "--outlier-model",
        choices=list(OUTLIER_MODELS),
        default="gross",
        help="gross: 15-40 degree errors on one or both tangents of an outlier frame (default); "
        "random: both tangent directions of an outlier frame uniformly random",
    )
    sim.add_argument(
        "--chord",
        type=float,
        nargs=2,
        default=(100.0, 300.0),
        metavar=("MIN", "MAX"),
        help="the chord |AB| is drawn between MIN and MAX, pixels (camera scenes: the units of "
        "--distance; default 100 300)",
    )
    sim.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    sim.add_argument("--with-curve", action="store_true", help="also write projected polylines")
    sim.add_argument(
        "--motion",
        choices=list(SIMULATED_MOTIONS),
        help="a scene of another row of the paper's Section 2 table: the body (the curve, A and B "
        "its ends, further points marked on it) moved by this model, with per-frame times "
        "(default: the paper's own setting, free motion with tangents)",
    )
    sim.add_argument(
        "--projection",
        choices=["orthographic", "perspective", "stereo"],
        default="orthographic",
        help="with --motion: perspective (one pinhole camera, 800 px focal length, 640 x 480) or "
        "stereo (two such cameras a quarter of the distance apart); lengths of the truth in "
        "units of A's depth in frame 0 (perspective) or of the scene (stereo)",
    )
    sim.add_argument(
        "--distance",
        type=float,
        default=1000.0,
        help="with --projection perspective|stereo: the body's depth in frame 0 (default 1000; "
        "the focal length scales with it, so the image keeps its size and the perspective "
        "weakens as it grows)",
    )
    sim.add_argument(
        "--points",
        default="AB",
        help='with --motion: the traceable points, "AB", "ABC" or "ABCD" (C, D marked points '
        "on the curve; perspective free motion needs ABCD, or AB with --with-curve)",
    )
    sim.add_argument(
        "--tangents",
        action="store_true",
        help="with --motion: also write the tangents at A and B (noise --tangent-noise)",
    )
    sim.add_argument(
        "--curve-noise", type=float, help="with --motion: polyline noise, px (default --noise-px)"
    )
    sim.add_argument(
        "--family",
        choices=list(FAMILIES),
        default="bezier",
        help=f"the kind of 3-D curve drawn (default bezier: random cubic curves); JSON scenes: "
        f"{', '.join(SCENE_FAMILIES)}; rendered scenes (--images): {', '.join(IMAGE_FAMILIES)} "
        "(loop often crosses itself)",
    )
    sim.add_argument(  # the former name of --family, kept for existing scripts
        "--curve-family", dest="family", choices=list(FAMILIES), help=argparse.SUPPRESS
    )
    sim.add_argument(
        "--images",
        metavar="DIR",
        help="render the scene as PNG frames into DIR (a curve tumbling smoothly through "
        "--image-size pixel frames; -o and --truth then describe those frames, polylines included)",
    )
    sim.add_argument("--image-size", type=int, default=384, help="frame side in pixels (--images)")
    sim.add_argument(
        "--step", type=float, default=25.0, help="rotation per frame, degrees (--images)"
    )
    sim.add_argument("--grey-noise", type=float, default=8.0, help="image noise sd (--images)")
    sim.add_argument("--blur", type=float, default=0.0, help="extra blur sigma, px (--images)")
    sim.add_argument(
        "--gradient", type=float, default=60.0, help="background rise in grey levels (--images)"
    )


def _add_trace(tr: argparse.ArgumentParser) -> None:
    tr.add_argument(
        "inputs", nargs="+", metavar="INPUT", help="image files, one folder or one video"
    )
    tr.add_argument("-o", "--output", required=True, help="curverecon.observations/1 JSON")
    tr.add_argument("--plot", metavar="DIR", help="write an overlay PNG per traced frame to DIR")
    tr.add_argument(
        "--dark-curve", action="store_true", help="the curve is darker than the background"
    )
    tr.add_argument("--width", type=float, default=3.0, help="line width in pixels (FWHM)")
    tr.add_argument(
        "--quiet", action="store_true", help="no progress bar (shown only on a terminal anyway)"
    )
    order = tr.add_mutually_exclusive_group()
    order.add_argument(
        "--ordered",
        dest="ends",
        action="store_const",
        const="ordered",
        default="auto",
        help="the frames are in order (smooth motion): A is the same end in every frame",
    )
    order.add_argument(
        "--unordered",
        dest="ends",
        action="store_const",
        const="unordered",
        help='frames in no order: write "ends_identified": false (the reconstruction decides)',
    )


def _add_match_flat(flat: argparse.ArgumentParser) -> None:
    flat.add_argument("input", help="curverecon.flat-views/1 JSON file")
    flat.add_argument("-o", "--output", required=True, help="curverecon.matches/1 JSON")


SLOW_CAMERA_CURVE = (
    "curverecon: one camera, A, B and polylines: the curve bundle takes about one to two "
    "CPU-minutes for 20 frames (no progress bar)"
)
"""Said on a terminal before the ordinary camera's reconstruction (measured: 64 and 134 s of CPU
for the README's and ``simulate``'s default 20-frame perspective scenes)."""


def _slow_camera_curve(obs) -> bool:
    """Whether ``obs`` goes to the pinhole curve bundle (free motion, fewer than four points)."""
    cfg = obs.configuration
    return (
        cfg.projection == "perspective"
        and cfg.motion == "free"
        and obs.n_points < 4
        and bool(obs.curves)
    )


def _refuse_overwriting_input(args: argparse.Namespace) -> None:
    """Refuse ``-o`` naming the input file itself (the answer would replace the data)."""
    from pathlib import Path

    if Path(args.output).resolve() == Path(args.input).resolve():
        raise CurveReconError(f"-o {args.output} would overwrite the input: choose another file")


def _cmd_reconstruct(args: argparse.Namespace) -> int:
    from curverecon.io import load_observations, write_json
    from curverecon.model.configuration import RigidObservations
    from curverecon.options import CurveOptions, ReconstructOptions
    from curverecon.pipeline import reconstruct

    _refuse_overwriting_input(args)

    if not (math.isfinite(args.point_sigma) and args.point_sigma > 0):
        raise CurveReconError("--point-sigma must be a positive number")
    if not (math.isfinite(args.tangent_sigma) and args.tangent_sigma > 0):
        raise CurveReconError("--tangent-sigma must be a positive number")
    obs = load_observations(args.input, motion=args.motion)
    options = ReconstructOptions(
        method=args.method,
        estimator=args.estimator,
        point_sigma=args.point_sigma,
        tangent_sigma_deg=args.tangent_sigma,
        curve=CurveOptions(bundle=args.curve_bundle == "on"),
        progress=sys.stderr.isatty() and not args.quiet,
    )
    if options.progress and isinstance(obs, RigidObservations) and _slow_camera_curve(obs):
        print(SLOW_CAMERA_CURVE, file=sys.stderr)
    rec = reconstruct(obs, options=options)
    for w in rec.warnings:
        _warn(w)
    write_json(args.output, rec.to_json_dict())
    if args.plot:
        from curverecon.plot import (
            plot_camera_file,
            plot_configuration_file,
            plot_reconstruction_file,
        )

        if isinstance(obs, RigidObservations) and obs.configuration.projection != "orthographic":
            plot_camera_file(args.plot, rec, obs)
        elif isinstance(obs, RigidObservations):
            plot_configuration_file(args.plot, rec, obs)
        else:
            plot_reconstruction_file(args.plot, rec, obs)
    return 0


def _cmd_simulate(args: argparse.Namespace) -> int:
    import numpy as np

    from curverecon.io import observations_to_dict, write_json
    from curverecon.simulate import make_scene, truth_to_dict

    if args.frames < 1:
        raise CurveReconError("--frames must be at least 1")
    _check_family(args.family, bool(args.images))
    if args.motion is not None:
        return _simulate_configuration(args)
    for flag, given in (
        ("--points", args.points != "AB"),
        ("--tangents", args.tangents),
        ("--curve-noise", args.curve_noise is not None),
        ("--projection", args.projection != "orthographic"),
    ):
        if given:
            raise CurveReconError(f"{flag} needs --motion")
    if args.images:
        return _simulate_images(args)
    if args.frames > MAX_SIMULATED_FRAMES:
        raise CurveReconError(f"--frames must be at most {MAX_SIMULATED_FRAMES}")
    if args.seed < 0:
        raise CurveReconError("--seed must be a non-negative integer")
    for name in ("point_noise", "tangent_noise", "outlier_fraction"):
        v = getattr(args, name)
        if not (math.isfinite(v) and v >= 0):
            raise CurveReconError(f"--{name.replace('_', '-')} must be a non-negative number")
    if args.outlier_fraction > 1:
        raise CurveReconError("--outlier-fraction must be at most 1")
    lo, hi = args.chord
    if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo <= hi):
        raise CurveReconError("--chord needs 0 < MIN <= MAX")
    scene = make_scene(
        np.random.default_rng(args.seed),
        args.frames,
        point_sigma=args.point_noise,
        tangent_sigma_deg=args.tangent_noise,
        chord=(lo, hi),
        outlier_fraction=args.outlier_fraction,
        outlier_model=args.outlier_model,
        with_curve=args.with_curve,
        curve_family=args.family,
    )
    write_json(args.output, observations_to_dict(scene.observations))
    if args.truth:
        write_json(args.truth, truth_to_dict(scene, seed=args.seed))
    return 0


def _simulate_configuration(args: argparse.Namespace) -> int:
    """``simulate --motion``: a scene of another row of the Section 2 table and its truth."""
    from curverecon.io import write_json
    from curverecon.simulate import simulate_configuration

    if args.images:
        raise CurveReconError("--images draws the paper's own setting only (not with --motion)")
    if args.frames > MAX_SIMULATED_FRAMES // 10:
        raise CurveReconError(
            f"--frames must be at most {MAX_SIMULATED_FRAMES // 10} with --motion"
        )
    if args.seed < 0:
        raise CurveReconError("--seed must be a non-negative integer")
    for name in ("point_noise", "tangent_noise", "outlier_fraction", "curve_noise"):
        v = getattr(args, name)
        if v is not None and not (math.isfinite(v) and v >= 0):
            raise CurveReconError(f"--{name.replace('_', '-')} must be a non-negative number")
    if args.outlier_fraction > 1:
        raise CurveReconError("--outlier-fraction must be at most 1")
    lo, hi = args.chord
    if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo <= hi):
        raise CurveReconError("--chord needs 0 < MIN <= MAX")
    if args.projection != "orthographic":
        return _simulate_camera(args, (lo, hi))
    if args.motion == "rotation-free":
        raise CurveReconError(
            "--motion rotation-free shows no depth under orthographic projection: use it with "
            "--projection perspective or stereo"
        )
    doc, truth = simulate_configuration(
        args.motion,
        args.points,
        frames=args.frames,
        seed=args.seed,
        noise_px=args.point_noise,
        tangent_noise_deg=args.tangent_noise if args.tangents else None,
        with_curve=args.with_curve,
        curve_noise_px=args.curve_noise,
        family=args.family,
        chord=(lo, hi),
        outlier_fraction=args.outlier_fraction,
    )
    write_json(args.output, doc)
    if args.truth:
        write_json(args.truth, truth)
    return 0


def _simulate_camera(args: argparse.Namespace, chord: tuple[float, float]) -> int:
    """``simulate --motion M --projection perspective|stereo``: a camera scene and its truth."""
    from curverecon.io import write_json
    from curverecon.simulate import default_camera, default_rig, simulate_camera_configuration

    if not (math.isfinite(args.distance) and args.distance > 0):
        raise CurveReconError("--distance must be a positive number")
    _require_camera_row(args)
    doc, truth = simulate_camera_configuration(
        args.projection,
        args.motion,
        args.points,
        frames=args.frames,
        seed=args.seed,
        noise_px=args.point_noise,
        tangent_noise_deg=args.tangent_noise if args.tangents else None,
        with_curve=args.with_curve,
        curve_noise_px=args.curve_noise,
        family=args.family,
        chord=chord,
        outlier_fraction=args.outlier_fraction,
        distance=args.distance,
        camera=default_camera(args.distance) if args.projection == "perspective" else None,
        rig=default_rig(args.distance) if args.projection == "stereo" else None,
    )
    write_json(args.output, doc)
    if args.truth:
        write_json(args.truth, truth)
    return 0


def _require_camera_row(args: argparse.Namespace) -> None:
    """Refuse a camera scene that ``reconstruct`` would refuse for its points (as the
    orthographic rows are refused); warn when it has fewer frames than the row needs.  The
    ordinary camera (perspective, free motion, ``--with-curve``) is the curve bundle's."""
    from curverecon.model.configuration import min_frames, motion_determined

    n, tangents = len(set(args.points)), bool(args.tangents)
    if args.projection == "perspective" and args.motion == "free" and args.with_curve:
        return
    reason = motion_determined(args.motion, n, tangents, args.projection)
    if reason is not None:
        fix = "--points ABCD or --with-curve" if args.motion == "free" else "--points ABC"
        raise CurveReconError(f"{reason} (simulate: {fix})")
    need = min_frames(args.motion, n, args.projection, tangents)
    if args.frames < need:
        _warn(
            f"{args.frames} frame(s): reconstruct needs at least {need} for motion "
            f"{args.motion} with points {', '.join(args.points)} under {args.projection}"
        )


def _check_family(family: str, images: bool) -> None:
    """Refuse a family the chosen scene kind (rendered images or a JSON scene) cannot draw."""
    if images and family not in IMAGE_FAMILIES:
        raise CurveReconError(
            f"--family {family} draws JSON scenes only (without --images); "
            f"rendered scenes: {', '.join(IMAGE_FAMILIES)}"
        )
    if not images and family not in SCENE_FAMILIES:
        raise CurveReconError(
            f"--family {family} draws rendered scenes only (with --images); "
            f"JSON scenes: {', '.join(SCENE_FAMILIES)}"
        )


def _simulate_images(args: argparse.Namespace) -> int:
    import numpy as np

    from curverecon.io import observations_to_dict, write_json
    from curverecon.simulate import truth_to_dict
    from curverecon.trace.render import RenderOptions, render_scene, tumbling_scene, write_images

    if not 32 <= args.image_size <= 8192:
        raise CurveReconError("--image-size must be between 32 and 8192")
    if args.frames > 10_000:
        raise CurveReconError("--frames must be at most 10000 with --images")
    for name in ("step", "grey_noise", "blur", "gradient"):
        v = getattr(args, name)
        if not (math.isfinite(v) and v >= 0):
            raise CurveReconError(f"--{name.replace('_', '-')} must be a non-negative number")
    rng = np.random.default_rng(args.seed)
    scene = tumbling_scene(
        rng, args.frames, family=args.family, size=args.image_size, step_deg=args.step
    )
    options = RenderOptions(
        size=args.image_size, noise=args.grey_noise, blur=args.blur, gradient=args.gradient
    )
    write_images(render_scene(scene, rng, options), args.images)
    write_json(args.output, observations_to_dict(scene.observations))
    if args.truth:
        write_json(args.truth, truth_to_dict(scene, seed=args.seed))
    return 0


def _cmd_trace(args: argparse.Namespace) -> int:
    from curverecon.io import write_json
    from curverecon.trace.options import TraceOptions
    from curverecon.trace.stage import trace_inputs

    if not (math.isfinite(args.width) and 1.0 <= args.width <= 100.0):
        raise CurveReconError("--width must be a number of pixels between 1 and 100")
    documents = [p for p in args.inputs if p.lower().endswith(".json")]
    if documents:
        raise CurveReconError(
            f"{documents[0]}: trace reads images or a video; a JSON document of observations "
            "goes to `curverecon reconstruct`"
        )
    options = TraceOptions(width=args.width, dark_curve=args.dark_curve)
    result = trace_inputs(
        args.inputs,
        options,
        progress=sys.stderr.isatty() and not args.quiet,
        keep_images=bool(args.plot),
        ends=args.ends,
    )
    write_json(args.output, result.document)
    if args.plot:
        from curverecon.trace.overlay import write_overlays

        write_overlays(args.plot, result.frames, result.document)
    for w in result.warnings:
        _warn(w)
    return 0


def _cmd_match_flat(args: argparse.Namespace) -> int:
    from curverecon.solvers.flat import run_match_flat

    _refuse_overwriting_input(args)
    run_match_flat(args.input, args.output)
    return 0


class _Command(NamedTuple):
    """One subcommand: its help line, the function adding its arguments, its handler."""

    help: str
    add_arguments: Callable[[argparse.ArgumentParser], None]
    run: Callable[[argparse.Namespace], int]


COMMANDS: dict[str, _Command] = {
    "reconstruct": _Command(
        "reconstruct shape and poses from observations", _add_reconstruct, _cmd_reconstruct
    ),
    "simulate": _Command("write a synthetic scene (and its truth)", _add_simulate, _cmd_simulate),
    "trace": _Command(
        "trace the curve in images or a video into observations", _add_trace, _cmd_trace
    ),
    "match-flat": _Command(
        "match points of a planar curve between two views", _add_match_flat, _cmd_match_flat
    ),
    "batch": _Command(batch_cli.HELP, batch_cli.add_arguments, batch_cli.command),
}
"""The subcommands, in the order ``--help`` lists them."""


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="curverecon",
        description="Recover a rigid smooth 3-D curve from images in which only two points A, "
        "B (and the tangents there, or the curve's polyline) are traced (after M. A. Klopotek): "
        'orthographic frames, or a calibrated pinhole camera ("camera": focal_px, '
        'principal_point) or stereo pair ("cameras", X1 = R X0 + t); docs/file-formats.md.',
    )
    sub = parser.add_subparsers(dest="command", parser_class=_Parser)
    for name, command in COMMANDS.items():
        command.add_arguments(sub.add_parser(name, help=command.help))
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``curverecon`` console script; returns the exit status."""
    try:
        parser = build_parser()
        args = parser.parse_args(argv)
        if args.command is None:
            names = list(COMMANDS)
            raise CurveReconError(f"a command is required: {', '.join(names[:-1])} or {names[-1]}")
        import numpy as np

        with np.errstate(all="ignore"):
            return COMMANDS[args.command].run(args)
    except CurveReconError as exc:
        print(f"curverecon: error: {exc}", file=sys.stderr)
        return 2
    except MemoryError:
        print("curverecon: error: not enough memory for this input", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("curverecon: error: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    raise SystemExit(main())
