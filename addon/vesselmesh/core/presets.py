"""Sets of settings that ship with the add-on, by what they are for. Each maps setting names (those of
the import operator and of a centerline's settings) to values; settings a preset leaves out keep theirs."""
from collections import namedtuple

Preset = namedtuple("Preset", "label description values")

PRESETS = {
    "quick": Preset(
        "Quick Preview", "A coarser surface in a fraction of the time: check the shape and the colours first",
        {"levels": 0, "method": "curvature", "uniform_levels": 1, "curvature": True, "smooth": 0}),
    "teaching": Preset(
        "Teaching Render", "A smooth surface coloured where it bends, branches, narrows or bulges: for lecture "
                           "pictures with Teaching Render",
        {"levels": 1, "method": "curvature", "uniform_levels": 1, "fit": "onto", "crossings": "separate",
         "curvature": True, "color_measure": "k2", "colormap": "auto", "percentile": 2.0}),
    "print": Preset(
        "3D Print", "A closed surface that follows the radii and never crosses itself, evenly refined and "
                    "without colours: for STL or PLY files to print",
        {"levels": 1, "method": "uniform", "caps": "flat", "fit": "onto", "crossings": "separate",
         "curvature": False}),
}


def apply(name, target, skip=()):
    """Sets the preset's values on target (an object with those attributes), except the names in skip."""
    for key, value in PRESETS[name].values.items():
        if key not in skip:
            setattr(target, key, value)
