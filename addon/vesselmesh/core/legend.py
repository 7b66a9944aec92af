"""What a colour legend shows: a bar coloured like the surface, round tick values in the file's unit
without exponents, and a title naming the measure and its unit."""
import math

import numpy as np

from . import colors

# Length units by their length in metres, largest first.
LENGTH_UNITS = ((1.0, "m"), (1e-2, "cm"), (1e-3, "mm"), (1e-6, "µm"), (1e-9, "nm"))


def file_unit(scale, metres_per_scene_unit=1.0):
    """The name of the file's length unit, from the import's scale (scene length = file length × scale)
    and the scene's unit: scale 0.001 in a metric scene means the file was in millimetres. None when the
    file's unit is no named unit (a scene without units, or a scale that is not a power of ten apart)."""
    if not metres_per_scene_unit or scale <= 0:
        return None
    metres = scale * metres_per_scene_unit
    for length, name in LENGTH_UNITS:
        if math.isclose(metres, length, rel_tol=1e-6):
            return name
    return None


def in_file_unit(values, dimension, scale):
    """Values of a measure given in scene units (per scene length to the power -dimension) expressed in the
    file's unit: a curvature of 2,390 per metre in a file in millimetres (scale 0.001) is 2.39 per mm."""
    return np.asarray(values, dtype=np.float64) * scale ** (-dimension)


def unit_label(dimension, unit):
    """'1/mm', '1/mm²', '' (a pure number), or '1/file unit' when the unit has no name."""
    if dimension == 0:
        return ""
    name = unit or "file unit"
    return f"1/{name}" if dimension == -1 else f"1/{name}²" if dimension == -2 else f"{name}^{dimension}"


def title_lines(measure, unit):
    """The legend's title: the measure's plain name, then its symbol and unit."""
    m = colors.MEASURES[measure]
    label = unit_label(m.dimension, unit)
    return [m.title, f"{m.symbol} in {label}" if label else m.symbol]


def nice_step(span, intervals):
    """A round step (1, 2, 2.5 or 5 times a power of ten) that cuts span into about `intervals` parts."""
    raw = span / max(intervals, 1)
    power = 10.0 ** math.floor(math.log10(raw))
    for factor in (1.0, 2.0, 2.5, 5.0, 10.0):
        if raw <= factor * power * (1 + 1e-9):
            return factor * power
    return 10.0 * power


def decimals_for(step):
    """The decimals that write every multiple of step exactly (2.5 needs one, 0.25 two, 500 none)."""
    for decimals in range(0, 12):
        if abs(round(step, decimals) - step) <= 1e-9 * step:
            return decimals
    return 12


def format_value(value, decimals):
    """Fixed-point text with `decimals` decimals and no exponent; exactly '0' for zero."""
    text = f"{value:.{decimals}f}"
    return "0" if float(text) == 0.0 else text


def _multiples(lo, hi, step):
    first, last = math.ceil(lo / step - 1e-9), math.floor(hi / step + 1e-9)
    return [k * step for k in range(first, last + 1)]


def ticks(lo, hi, name, intervals=5, min_gap=0.09):
    """[(fraction of the bar's height, label)] at round values within [lo, hi] (values already in the unit
    shown). A diverging map over a range holding zero gets zero and round values on each side, each side
    with its own step (its half of the bar spans its own extent); ticks nearer than min_gap of the bar to
    a kept one are dropped, zero and the outer ones kept first."""
    if name in colors.DIVERGING and lo < 0.0 < hi:
        below, above = nice_step(-lo, intervals - 1), nice_step(hi, intervals - 1)
        values = sorted(set(_multiples(lo, 0.0, below) + _multiples(0.0, hi, above)))
        decimals = [decimals_for(below if v < 0 else above) for v in values]  # each side its own
    else:
        step = nice_step(hi - lo, intervals)
        values = _multiples(lo, hi, step)
        decimals = [decimals_for(step)] * len(values)
    positions = colors.normalize(values, lo, hi, name)
    # Keep zero first, then from the outside in, so that the bar's ends and its centre are labelled.
    order = sorted(range(len(values)), key=lambda i: (values[i] != 0.0, -abs(positions[i] - 0.5)))
    kept = []
    for i in order:
        if all(abs(positions[i] - positions[j]) >= min_gap for j in kept):
            kept.append(i)
    return [(float(positions[i]), format_value(values[i], decimals[i]))
            for i in sorted(kept, key=lambda i: positions[i])]


def colorbar(name, steps=64):
    """A vertical bar in the unit square, the map's start at the bottom, its end at the top.

    Returns vertices (2·(steps+1), 3) with x in {0, 1} and y in [0, 1] (z = 0), quads (steps, 4)
    counter-clockwise seen from +z, and the vertices' scene-linear RGBA (2·(steps+1), 4).
    """
    y = np.linspace(0.0, 1.0, steps + 1)
    vertices = np.zeros((2 * (steps + 1), 3))
    vertices[0::2, 1] = vertices[1::2, 1] = y
    vertices[1::2, 0] = 1.0
    i = 2 * np.arange(steps)
    quads = np.stack([i, i + 1, i + 3, i + 2], axis=1)
    return vertices, quads, bar_colors(name, np.repeat(y, 2))


def bar_colors(name, fractions):
    """The map's colours at fractions of its length (what the bar shows there)."""
    return colors._table(name)[np.rint(np.asarray(fractions) * colors.STEPS).astype(np.intp)]
