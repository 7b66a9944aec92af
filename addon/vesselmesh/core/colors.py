"""Colour maps for per-vertex curvature, and the value ranges they span."""
import functools

import numpy as np

# Stops in sRGB, evenly spaced over [0, 1], linearly interpolated between.
COLORMAPS = {
    # matplotlib's viridis: perceptually uniform, for quantities that are never negative.
    "viridis": ("440154", "472d7b", "3b528b", "2c728e", "21918c", "28ae80", "5ec962", "addc30", "fde725"),
    # ColorBrewer's RdBu, reversed: blue below zero, white at zero, red above.
    "rdbu": ("053061", "2166ac", "4393c3", "92c5de", "d1e5f0", "f7f7f7", "fddbc7", "f4a582", "d6604d", "b2182b",
             "67001f"),
}

# Curvature measures that take both signs (saddles are negative); rms never does.
SIGNED = frozenset({"k1", "k2", "mean", "gaussian"})


def colormap_for(measure, choice="auto"):
    """The map to use: a diverging one centred on zero for signed measures, viridis for the others."""
    if choice != "auto":
        return choice
    return "rdbu" if measure in SIGNED else "viridis"


def value_range(values, measure, percentile=2.0):
    """(lo, hi) from the percentile-th to the (100 - percentile)-th percentile, so that a few extreme
    vertices (cap rims, joint creases) do not wash the rest out. Signed measures get ±max(|lo|, |hi|),
    which puts zero at the centre of a diverging map."""
    lo, hi = (float(v) for v in np.percentile(values, [percentile, 100.0 - percentile]))
    if measure in SIGNED:
        hi = max(abs(lo), abs(hi))
        lo = -hi
    if hi <= lo:  # constant values: any range that contains them
        lo, hi = lo - 0.5, hi + 0.5
    return lo, hi


def color_by(values, measure, choice="auto", percentile=2.0):
    """How to colour a surface by the values of a measure: (map name, lo, hi, (V,4) RGBA), with the map
    colormap_for chooses and the range value_range gives."""
    name = colormap_for(measure, choice)
    lo, hi = value_range(values, measure, percentile)
    return name, lo, hi, map_colors(values, lo, hi, name)


def srgb_to_linear(c):
    """sRGB components in [0, 1] to scene-linear, as Blender stores float colours."""
    c = np.asarray(c, dtype=np.float64)
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


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
    """(V,4) float32 scene-linear RGBA of each value on map `name` over [lo, hi] (clamped at the ends),
    to the nearest of STEPS steps."""
    t = np.clip((np.asarray(values, dtype=np.float64) - lo) / (hi - lo), 0.0, 1.0)
    return _table(name)[np.rint(t * STEPS).astype(np.intp)]
