"""Tuned numbers of ``curverecon trace`` (lengths in pixels), each with the reason for its default.

Defaults were set on rendered sequences (``curverecon.trace.render``: a Gaussian line of
sigma 1.2 px, 160 grey levels, noise sd 8, a background gradient; bench seeds 0-19) and checked
on seeds 1000-1019 of the bench (``bench/trace.py``).
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass
class TraceOptions:
    """Options of the tracer (``curverecon.trace.stage.trace_frames``)."""

    # Line width (full width at half maximum, px); sets the filter scale 0.6 * width.  3 px is
    # the FWHM of a Gaussian profile of sigma 1.2 px, the rendered lines of trace.render.
    width: float = 3.0
    # The curve is darker than the background (the image is inverted first).
    dark_curve: bool = False
    # Hysteresis of the ridge strength in robust spreads of the background's strength: 12 keeps
    # the seeds of the mask off noise (a 512 x 512 frame of pure noise has its maximum near 7),
    # 5 lets the mask follow the line to its faint ends.
    high_sigmas: float = 12.0
    low_sigmas: float = 5.0
    # ... and at least this fraction of the line's typical strength (links no noise at high SNR).
    low_fraction: float = 0.15
    # Newton steps of the sub-pixel centre (each moves along the normal; 4 converge to 1e-3 px).
    centre_iterations: int = 4
    # A centre point more than this far from its skeleton pixel belongs to something else.
    max_shift: float = 1.5
    # Around a skeleton junction (a crossing) points are dropped within this many line widths
    # (the Hessian sees two lines there), and junctions this close are one crossing.
    junction_radius_widths: float = 2.0
    # Side branches of the skeleton shorter than this many widths are noise spurs.
    spur_widths: float = 4.0
    # Pieces of a broken line are joined across gaps up to this many widths when their ends
    # point at each other (within 35 degrees); longer gaps leave the frame out.
    max_gap_widths: float = 8.0
    max_gap_angle_deg: float = 35.0
    # Smallest traced length (px) of a usable curve: shorter is noise or a curve seen end-on.
    min_length: float = 20.0
    # A traced point this close (px) to the image border: the frame is reported as touching it.
    border_margin: float = 2.0
    # End point: the 50 % point of the intensity along the end's direction, searched this many
    # widths beyond the last centre point (the skeleton stops short of a faint end).
    end_search_widths: float = 3.0
    # ... along the direction of the last this many widths of centre points (short: ends that
    # are seen foreshortened turn sharply).
    end_direction_widths: float = 1.0
    # End identity (curverecon.trace.ends): a link between consecutive frames is ambiguous when
    # the other order's continuity cost is less than this factor above the chosen one's
    # (the reconstruction from the polylines then decides).
    ambiguity_ratio: float = 1.5
    # End tangents (written as tangent_A, tangent_B): a quadratic fitted over this many pixels
    # of the polyline from each end, the located end point itself left out (its step from the
    # last centre point kinks the end).  Against the true tangents on 8 rendered sequences:
    # median 1.3 degrees, 75th percentile 4.0 (the adaptive fit on the whole polyline: 2.2
    # and 11.6; hooked, foreshortened ends make the long tail either way).
    tangent_fit_length: float = 12.0
