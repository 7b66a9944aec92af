"""Curvature measures, the colour maps that show them, and the value ranges they span.

A measure is one entry of MEASURES: adding one (a radius-normalised curvature, say) is one more entry
there and one more item in the add-on's Colour By list.
"""
import functools
from collections import namedtuple

import numpy as np

# Stops in sRGB, evenly spaced over [0, 1], linearly interpolated between.
COLORMAPS = {
    # matplotlib's viridis: perceptually uniform, dark purple to yellow, for values of one sign.
    "viridis": ("440154", "472d7b", "3b528b", "2c728e", "21918c", "28ae80", "5ec962", "addc30", "fde725"),
    # ColorBrewer's RdBu, reversed: blue below zero, white at zero, red above.
    "rdbu": ("053061", "2166ac", "4393c3", "92c5de", "d1e5f0", "f7f7f7", "fddbc7", "f4a582", "d6604d", "b2182b",
             "67001f"),
}
DIVERGING = frozenset({"rdbu"})

# What a measure is: its legend title, its short symbol, and its dimension in lengths (-1: 1/length,
# -2: 1/length², 0: a pure number), which says how its values change with the unit.
Measure = namedtuple("Measure", "title symbol dimension")
MEASURES = {
    "k2": Measure("Saddles and bulges", "k2", -1),
    "mean": Measure("Mean curvature", "H", -1),
    "gaussian": Measure("Gaussian curvature", "K", -2),
    "k1": Measure("Largest curvature", "k1", -1),
    "rms": Measure("RMS curvature", "rms", -1),
    "shape": Measure("Shape: mean curvature × radius", "H·r", 0),
}

# A signed measure gets the diverging map only when its smaller side reaches this share of the larger
# side's extent (at the clip percentiles); otherwise a few saddle vertices would take half the map.
BOTH_SIGNS = 0.2

Coloring = namedtuple("Coloring", "map lo hi rgba")


def robust_range(values, percentile=2.0):
    """(lo, hi): the percentile-th and (100 - percentile)-th percentiles, so that a few extreme vertices
    (cap rims, joint creases) do not wash the rest out; widened when the values are all equal. In float32,
    as the surface's settings (Blender float properties) keep them: a value a hair from a step of the map
    then takes the same colour when the surface is painted again from those settings."""
    lo, hi = (float(np.float32(v)) for v in np.percentile(values, [percentile, 100.0 - percentile]))
    if hi <= lo:
        pad = max(abs(lo), 1.0) * 0.5
        lo, hi = float(np.float32(lo - pad)), float(np.float32(hi + pad))
    return lo, hi


def both_signs_matter(lo, hi):
    """Whether a range holds both signs, each with weight: the smaller side's extent is at least
    BOTH_SIGNS of the larger's."""
    return lo < 0.0 < hi and min(-lo, hi) >= BOTH_SIGNS * max(-lo, hi)


def colormap_for(lo, hi, choice="auto"):
    """The map for a range: what the user chose, or (automatic) the diverging map when both signs carry
    weight, else the sequential one."""
    if choice != "auto":
        return choice
    return "rdbu" if both_signs_matter(lo, hi) else "viridis"


def normalize(values, lo, hi, name):
    """Where each value falls along map `name`, in [0, 1] (clamped). A diverging map whose range holds
    zero puts zero at its neutral centre and spans each side separately, so both of its halves are used
    whatever the range's asymmetry (lo ↦ 0, 0 ↦ 0.5, hi ↦ 1); otherwise the map is linear, lo ↦ 0, hi ↦ 1."""
    v = np.asarray(values, dtype=np.float64)
    if name in DIVERGING and lo < 0.0 < hi:
        return np.clip(np.where(v < 0.0, 0.5 - 0.5 * v / lo, 0.5 + 0.5 * v / hi), 0.0, 1.0)
    return np.clip((v - lo) / (hi - lo), 0.0, 1.0)


def value_at(t, lo, hi, name):
    """The value at position t in [0, 1] along map `name` over [lo, hi]: the inverse of normalize."""
    t = np.asarray(t, dtype=np.float64)
    if name in DIVERGING and lo < 0.0 < hi:
        return np.where(t < 0.5, lo * (1.0 - 2.0 * t), hi * (2.0 * t - 1.0))
    return lo + t * (hi - lo)


def color_by(values, choice="auto", percentile=2.0):
    """How to colour a surface by the values of a measure: Coloring(map, lo, hi, rgba (V,4)), with the
    range robust_range gives and the map colormap_for chooses for it."""
    lo, hi = robust_range(values, percentile)
    name = colormap_for(lo, hi, choice)
    return Coloring(name, lo, hi, map_colors(values, lo, hi, name))


def srgb_to_linear(c):
    """sRGB components in [0, 1] to scene-linear, as Blender stores float colours."""
    c = np.asarray(c, dtype=np.float64)
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def linear_to_srgb(c):
    c = np.clip(np.asarray(c, dtype=np.float64), 0.0, 1.0)
    return np.where(c <= 0.0031308, c * 12.92, 1.055 * c ** (1.0 / 2.4) - 0.055)


def linear_to_srgb8(rgba):
    """(V,4) scene-linear float RGBA to (V,4) 8-bit sRGB (alpha stays linear), as files store colours."""
    rgba = np.asarray(rgba, dtype=np.float64)
    out = np.empty(rgba.shape, dtype=np.uint8)
    out[:, :3] = np.rint(255.0 * linear_to_srgb(rgba[:, :3]))
    out[:, 3:] = np.rint(255.0 * np.clip(rgba[:, 3:], 0.0, 1.0))
    return out


def lightness(linear_rgb):
    """CIE L* (0 black to 100 white) of scene-linear RGB (Rec. 709 primaries)."""
    y = float(np.dot(np.asarray(linear_rgb, dtype=np.float64)[:3], [0.2126, 0.7152, 0.0722]))
    return 116.0 * np.cbrt(y) - 16.0 if y > 216.0 / 24389.0 else y * 24389.0 / 27.0


def map_lightness(name):
    """L* at the map's two ends and (diverging maps) its centre: the colours a background must stand out from."""
    table = _table(name)
    points = (0, STEPS // 2, STEPS) if name in DIVERGING else (0, STEPS)
    return [lightness(table[i]) for i in points]


def _stops(name):
    return np.array([[int(h[i:i + 2], 16) / 255.0 for i in (0, 2, 4)] for h in COLORMAPS[name]])


# Each map is tabulated at this many steps of its range (finer than 8-bit colour), so that mapping a
# million values is one lookup each rather than an interpolation and a power.
STEPS = 1024


@functools.lru_cache(maxsize=None)
def _table(name):
    """(STEPS + 1, 4) float32 scene-linear RGBA at 0, 1/STEPS, ..., 1 along map `name`."""
    stops = _stops(name)
    t = np.linspace(0.0, 1.0, STEPS + 1)
    table = np.ones((STEPS + 1, 4), dtype=np.float32)
    for channel in range(3):
        table[:, channel] = srgb_to_linear(np.interp(t, np.linspace(0.0, 1.0, len(stops)), stops[:, channel]))
    table.flags.writeable = False
    return table


def map_colors(values, lo, hi, name):
    """(V,4) float32 scene-linear RGBA of each value on map `name` over [lo, hi] (clamped at the ends), to
    the nearest of STEPS steps; where on the map a value falls is normalize's."""
    return _table(name)[np.rint(normalize(values, lo, hi, name) * STEPS).astype(np.intp)]
