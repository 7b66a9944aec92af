"""The geometry of a colour legend: a bar coloured like the surface, tick values and a title."""
import numpy as np

from .colors import map_colors

TITLES = {"k1": "curvature k1", "k2": "curvature k2", "mean": "mean curvature", "gaussian": "Gaussian curvature",
          "rms": "RMS curvature"}


def colorbar(name, lo, hi, steps=32):
    """A vertical bar in the unit square, value lo at the bottom, hi at the top.

    Returns vertices (2·(steps+1), 3) with x in {0, 1} and y in [0, 1] (z = 0), quads (steps, 4)
    counter-clockwise seen from +z, and the vertices' scene-linear RGBA (2·(steps+1), 4).
    """
    y = np.linspace(0.0, 1.0, steps + 1)
    vertices = np.zeros((2 * (steps + 1), 3))
    vertices[0::2, 1] = vertices[1::2, 1] = y
    vertices[1::2, 0] = 1.0
    i = 2 * np.arange(steps)
    quads = np.stack([i, i + 1, i + 3, i + 2], axis=1)
    colors = map_colors(np.repeat(lo + y * (hi - lo), 2), lo, hi, name)
    return vertices, quads, colors


def ticks(lo, hi, count=5):
    """count evenly spaced (fraction of the bar's height, label) pairs from lo to hi."""
    values = np.linspace(lo, hi, count)
    step = (hi - lo) / (count - 1)
    # Enough significant digits to tell neighbouring ticks apart, and an exact 0 at the centre.
    digits = max(2, int(np.ceil(np.log10(max(abs(lo), abs(hi)) / step))) + 2)
    return [(float(f), "0" if abs(v) < 1e-9 * step else f"{v:.{digits}g}")
            for f, v in zip(np.linspace(0.0, 1.0, count), values)]
