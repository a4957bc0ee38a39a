"""The line's centre: ridge strength (Hessian of Gaussian), its mask, and sub-pixel centre points.

Conventions: images are 2-D float arrays indexed [row, column]; points are (x, y) = (column, row)
in pixels, the centre of the top-left pixel at (0, 0).  The curve is brighter than the
background (callers invert a dark curve).

Method (after Steger, "An unbiased detector of curvilinear structures", 1998): at the line's
scale ``s`` the Hessian of the Gaussian-smoothed image has, across a bright line, a strongly
negative eigenvalue whose eigenvector n is the line's normal; the ridge strength is minus that
eigenvalue.  A linear background gradient has no second derivative, so it drops out; noise is
averaged over the scale.  The centre is where the first derivative along n vanishes: from a
point p, the step t = -(g . n) / (n^T H n) along n (a Newton step on the profile), with the
derivatives evaluated by Gaussian-derivative kernels at the exact sub-pixel position (no
interpolation of filtered images), repeated until the step is below 1e-3 px.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import ndimage

from curverecon.trace.options import TraceOptions


@dataclass
class Ridge:
    """Ridge strength (minus the most negative Hessian eigenvalue, >= 0) and its mask."""

    strength: np.ndarray
    mask: np.ndarray
    level: float  # typical strength on the line (median over the mask)
    noise: float  # robust spread of the strength over the background


def scale_for_width(width: float) -> float:
    """Filter scale (px) for a line ``width`` px wide (full width at half maximum).

    A Gaussian profile of FWHM w has sigma w / 2.355; filtering at a scale near it keeps the
    centre sharp while averaging the noise (Steger: any scale works for a Gaussian profile).
    """
    return max(1.0, 0.6 * width)


def ridge(img: np.ndarray, options: TraceOptions) -> Ridge:
    """Ridge strength and the hysteresis mask of the line at the options' scale.

    Thresholds: the background's strength has median m and robust spread r (1.4826 MAD);
    a pixel is strong above m + ``high_sigmas`` r and kept above m + ``low_sigmas`` r when
    connected to a strong one, and above ``low_fraction`` of the line's typical strength.
    """
    s = scale_for_width(options.width)
    f = img.astype(np.float32)
    hxx = ndimage.gaussian_filter(f, s, order=(0, 2), truncate=3.0)
    hyy = ndimage.gaussian_filter(f, s, order=(2, 0), truncate=3.0)
    hxy = ndimage.gaussian_filter(f, s, order=(1, 1), truncate=3.0)
    half_tr = 0.5 * (hxx + hyy)
    disc = np.sqrt(0.25 * (hxx - hyy) ** 2 + hxy**2)
    strength = np.maximum(-(half_tr - disc), 0.0) * (s * s)  # scale-normalised
    sub = strength[:: max(1, strength.shape[0] // 256), :: max(1, strength.shape[1] // 256)]
    m = float(np.median(sub))
    r = max(1.4826 * float(np.median(np.abs(sub - m))), 1e-12)
    high = m + options.high_sigmas * r
    strong = strength > high
    if not strong.any():
        return Ridge(strength, strong, 0.0, r)
    level = float(np.median(strength[strong]))
    low = max(m + options.low_sigmas * r, options.low_fraction * level)
    weak = strength > low
    lab, _ = ndimage.label(weak, structure=np.ones((3, 3)))
    keep = np.unique(lab[strong])
    keep = keep[keep > 0]
    mask = np.isin(lab, keep)
    return Ridge(strength, mask, level, r)


def _kernels(frac: np.ndarray, s: float, radius: int) -> tuple[np.ndarray, ...]:
    """Weights of pixel k = -radius..radius for the smoothed value and its first two
    derivatives at sub-pixel offset ``frac`` (P,): G(frac - k), G'(frac - k), G''(frac - k)."""
    k = np.arange(-radius, radius + 1, dtype=float)
    u = k[None, :] - frac[:, None]
    g = np.exp(-0.5 * (u / s) ** 2) / (np.sqrt(2 * np.pi) * s)
    g1 = u / s**2 * g  # G'(-u): the derivative with respect to the point, not the pixel
    g2 = (u**2 / s**4 - 1 / s**2) * g
    return g, g1, g2


def _patches(
    img: np.ndarray, pts: np.ndarray, s: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
    """(P, rows, cols) image patches around the pixels nearest each point (x, y), radius
    3.5 s (edge pixels repeated outside the image), with those pixels' columns, rows and the
    radius."""
    radius = int(np.ceil(3.5 * s))
    ix = np.rint(pts[:, 0]).astype(int)
    iy = np.rint(pts[:, 1]).astype(int)
    k = np.arange(-radius, radius + 1)
    rows = np.clip(iy[:, None] + k[None, :], 0, img.shape[0] - 1)
    cols = np.clip(ix[:, None] + k[None, :], 0, img.shape[1] - 1)
    return img[rows[:, :, None], cols[:, None, :]], ix, iy, radius


def _derivatives(img: np.ndarray, pts: np.ndarray, s: float) -> np.ndarray:
    """(P, 5) gx, gy, hxx, hxy, hyy of the Gaussian-smoothed image at sub-pixel points (x, y).

    Separable Gaussian-derivative kernels centred at each point, applied to the image patch
    around it (edge pixels repeated outside the image)."""
    patch, ix, iy, radius = _patches(img, pts, s)
    gx0, gx1, gx2 = _kernels(pts[:, 0] - ix, s, radius)
    gy0, gy1, gy2 = _kernels(pts[:, 1] - iy, s, radius)

    def sep(ky: np.ndarray, kx: np.ndarray) -> np.ndarray:
        return np.einsum("pr,prc,pc->p", ky, patch, kx)

    return np.column_stack(
        [sep(gy0, gx1), sep(gy1, gx0), sep(gy0, gx2), sep(gy1, gx1), sep(gy2, gx0)]
    )


def centre_points(
    img: np.ndarray, pts: np.ndarray, options: TraceOptions
) -> tuple[np.ndarray, np.ndarray]:
    """Move points (x, y) near the line onto its centre, along the local normal.

    Returns ``(points (P, 2), ok (P,))``: ``ok`` is False where the Hessian shows no ridge
    (eigenvalue along the normal not negative) or the point would move more than
    ``max_shift`` px (it was not near this line).  Such points keep their start position.
    """
    s = scale_for_width(options.width)
    p = np.asarray(pts, float).copy()
    start = p.copy()
    ok = np.ones(len(p), bool)
    for _ in range(options.centre_iterations):
        d = _derivatives(img, p, s)
        gx, gy, hxx, hxy, hyy = d.T
        half_tr = 0.5 * (hxx + hyy)
        disc = np.sqrt(0.25 * (hxx - hyy) ** 2 + hxy**2)
        lam = half_tr - disc
        # eigenvector of lam: (hxy, lam - hxx) or (lam - hyy, hxy), whichever is longer
        v1 = np.column_stack([hxy, lam - hxx])
        v2 = np.column_stack([lam - hyy, hxy])
        v = np.where((np.hypot(*v1.T) >= np.hypot(*v2.T))[:, None], v1, v2)
        nrm = np.hypot(*v.T)
        n = v / np.where(nrm > 0, nrm, 1.0)[:, None]
        n[nrm == 0] = [1.0, 0.0]
        curv = hxx * n[:, 0] ** 2 + 2 * hxy * n[:, 0] * n[:, 1] + hyy * n[:, 1] ** 2
        slope = gx * n[:, 0] + gy * n[:, 1]
        ok &= curv < 0
        t = np.where(curv < 0, -slope / np.where(curv < 0, curv, -1.0), 0.0)
        t = np.clip(t, -0.75, 0.75)
        p = p + t[:, None] * n
        if np.all(np.abs(t[ok]) < 1e-3):
            break
    ok &= np.hypot(*(p - start).T) <= options.max_shift
    p[~ok] = start[~ok]
    return p, ok


def smoothed_profile(img: np.ndarray, pts: np.ndarray, options: TraceOptions) -> np.ndarray:
    """The Gaussian-smoothed image (at the line's scale) at sub-pixel points (x, y)."""
    s = scale_for_width(options.width)
    patch, ix, iy, radius = _patches(img, pts, s)
    gx0 = _kernels(pts[:, 0] - ix, s, radius)[0]
    gy0 = _kernels(pts[:, 1] - iy, s, radius)[0]
    return np.einsum("pr,prc,pc->p", gy0, patch, gx0)
