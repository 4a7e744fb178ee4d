"""The picture of a green's expected-putts map (``mcrun.putting.green_map``): expected putts
as colour over the green, its contours every 5 cm, the pin, and the read's start line from a
few points (arrows as long as a tenth of the putt)."""

import math

import numpy as np

from mcrun.report.style import require_matplotlib

FIGURE_SIZE_IN = (9.0, 8.0)
DPI = 120
CONTOUR_M = 0.05
READ_POINTS = 8


def green_figure(putts_map, attribution=None):
    """The Figure of ``putts_map`` (a ``GreenMap``), top view, x up the hole, y to the right."""
    figure_class, canvas_class = require_matplotlib("putt --plot")
    fig = figure_class(figsize=FIGURE_SIZE_IN, layout="constrained")
    canvas_class(fig)
    ax = fig.subplots()
    green = putts_map.green
    s = green.surface
    ny, nx = s.height_m.shape
    gx = s.x0_m + np.arange(nx) * s.cell_m
    gy = s.y0_m + np.arange(ny) * s.cell_m
    xx, yy = putts_map.nodes_xy()
    v = putts_map.expected_putts
    mesh = ax.pcolormesh(
        yy, xx, np.ma.masked_invalid(v), cmap="viridis_r", shading="nearest", vmin=1.0
    )
    fig.colorbar(mesh, ax=ax, label="expected putts to hole out")
    height = np.ma.masked_where(s.on_green == 0, s.height_m)
    lo, hi = float(height.min()), float(height.max())
    if hi - lo > CONTOUR_M:
        levels = np.arange(math.floor(lo / CONTOUR_M), math.ceil(hi / CONTOUR_M) + 1) * CONTOUR_M
        ax.contour(gy, gx, height.T, levels=levels, colors="white", linewidths=0.6, alpha=0.8)
    ax.contour(gy, gx, s.on_green.T.astype(float), levels=[0.5], colors="black", linewidths=1.2)
    px, py = green.pin_xy_m
    ax.plot([py], [px], marker="o", ms=7, color="crimson", mec="white", label="pin")
    # The read from a few points: its start line.
    on = np.argwhere(putts_map.valid)
    if len(on):
        picks = on[np.linspace(0, len(on) - 1, min(READ_POINTS, len(on))).astype(int)]
        for iy, ix in picks:
            x, y = xx[iy, ix], yy[iy, ix]
            length = math.hypot(px - x, py - y)
            if length < 1.0:
                continue
            bearing = math.atan2(py - y, px - x) - math.radians(putts_map.read_aim_deg[iy, ix])
            d = 0.1 * length
            ax.annotate("", xy=(y + d * math.sin(bearing), x + d * math.cos(bearing)),
                        xytext=(y, x), arrowprops=dict(arrowstyle="->", color="white",
                                                       lw=1.2))  # fmt: skip
            ax.text(y, x, f"{putts_map.read_pace_m[iy, ix]:.2f} m", color="white", fontsize=7)
    ax.set_aspect("equal")
    ax.set_xlabel("y (m, right of the line from the tee)")
    ax.set_ylabel("x (m, from the tee towards the pin)")
    title = (f"Expected putts, {putts_map.putter.name} putter, Stimp "
             f"{green.stimp_m / 0.3048:.1f} ft, {putts_map.n} putts a read")  # fmt: skip
    ax.set_title(title + "\nArrows: the read's start line (pace past the hole); contours "
                 f"every {CONTOUR_M * 100:.0f} cm", fontsize=10)  # fmt: skip
    if attribution:
        ax.text(0.01, 0.01, attribution, transform=ax.transAxes, fontsize=7, va="bottom")
    return fig
