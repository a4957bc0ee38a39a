"""``curverecon trace --plot DIR``: one PNG per traced frame showing what was traced.

The frame's image in grey, the traced polyline (red), A (a green circle) and B (a blue square)
with their end tangents (arrows pointing into the curve), and the frame's file in the title.
Pixel convention as the trace: x = column, y = row, the centre of the top-left pixel at (0, 0)
(matplotlib's ``imshow`` puts pixel centres at integer coordinates, so the overlay is exact).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from curverecon.errors import CurveReconError


def write_overlays(folder: str, frames: list[dict], document: dict) -> list[str]:
    """``frame_<index>.png`` in ``folder`` for each traced frame; returns the paths."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = Path(folder)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise CurveReconError(f"cannot write plots to {folder}: {exc.strerror or exc}") from exc
    paths = []
    for t, f in zip(frames, document["frames"], strict=True):
        img = t["image"]
        h, w = img.shape
        fig, ax = plt.subplots(figsize=(6, 6 * h / w), dpi=100)
        ax.imshow(img, cmap="gray", interpolation="nearest")
        c = np.asarray(f["curve"])
        ax.plot(c[:, 0], c[:, 1], "-", color="red", lw=0.8, label="traced")
        a, b = np.asarray(f["A"]), np.asarray(f["B"])
        arrow = 0.08 * max(h, w)
        for p, tg, style, name in ((a, f["tangent_A"], "o", "A"), (b, f["tangent_B"], "s", "B")):
            colour = "lime" if name == "A" else "deepskyblue"
            ax.plot(*p, style, mfc="none", mec=colour, ms=9, mew=1.5)
            ax.annotate(name, p, xytext=(6, 6), textcoords="offset points", color=colour)
            tg = np.asarray(tg) / np.hypot(*tg)
            ax.arrow(
                *p, *(arrow * tg), color=colour, width=0.3, head_width=3, length_includes_head=True
            )
        ax.set_title(f"frame {f['index']}: {Path(f['file']).name}", fontsize=9)
        ax.set_xlim(-0.5, w - 0.5)
        ax.set_ylim(h - 0.5, -0.5)
        ax.set_axis_off()
        p = out / f"frame_{f['index']:04d}.png"
        try:
            fig.savefig(p, bbox_inches="tight")
        except OSError as exc:
            raise CurveReconError(f"cannot write {p}: {exc.strerror or exc}") from exc
        finally:
            plt.close(fig)
        paths.append(str(p))
    return paths
