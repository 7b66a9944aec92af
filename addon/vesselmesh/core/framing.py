"""The geometry of a teaching picture, without bpy: which way the camera looks, where it stands so that the
vessels fill their part of the frame, where the lights go, and which background stands out from the
colour map."""
import math

import numpy as np

from . import colors


def sample(points, count=60000, seed=0):
    """At most `count` of the points, evenly drawn (framing needs the outline, not every vertex)."""
    points = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    if len(points) <= count:
        return points
    return points[np.random.default_rng(seed).choice(len(points), count, replace=False)]


def view_axes(points, elevation=18.0, azimuth=12.0):
    """(right, up, forward) unit vectors of a camera that sees the vessels broadside: it looks along their
    thinnest principal direction (so that a tree or a flat network shows its full spread), with the
    scene's +z up where that direction is not vertical (the anatomy's up stays up), then turned `azimuth`
    degrees about the vertical and tilted `elevation` degrees down, for depth."""
    points = np.asarray(points, dtype=np.float64)
    centred = points - points.mean(axis=0)
    _, vectors = np.linalg.eigh(centred.T @ centred)
    forward = vectors[:, 0]  # least spread
    z = np.array([0.0, 0.0, 1.0])
    if abs(forward @ z) > 0.8:  # a flat network lying in the xy plane: look down on it, +y up
        forward = -z
        up_hint = np.array([0.0, 1.0, 0.0])
    else:
        forward = forward - (forward @ z) * z  # level, before the tilt
        forward /= np.linalg.norm(forward)
        if forward @ np.array([0.0, 1.0, 0.0]) < 0:  # from the front (-y) when both sides would do
            forward = -forward
        up_hint = z
    turn = math.radians(azimuth)
    c, s = math.cos(turn), math.sin(turn)
    forward = np.array([c * forward[0] - s * forward[1], s * forward[0] + c * forward[1], forward[2]])
    right = np.cross(forward, up_hint)
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    tilt = math.radians(elevation)
    forward = math.cos(tilt) * forward - math.sin(tilt) * up
    up = np.cross(right, forward)
    return right, up / np.linalg.norm(up), forward / np.linalg.norm(forward)


def fit(points, right, up, forward, region):
    """Where a perspective camera looking along `forward` must stand so that every point projects inside
    `region` = (x0, x1, y0, y1), in tangent units of its view (x/depth, y/depth; the frame of a camera with
    half-angles a, b is (-tan a, tan a, -tan b, tan b)). The nearest such position, with the points
    centred in the region. Returns (location (3,), distance from the points' centre along forward)."""
    points = np.asarray(points, dtype=np.float64)
    origin = points.mean(axis=0)
    rel = points - origin
    px, py, pf = rel @ right, rel @ up, rel @ forward
    x0, x1, y0, y1 = region
    # Camera at origin + a·right + b·up - t·forward: a point projects to ((px - a) / (pf + t), ...).
    ax1, ax0 = np.max(px - x1 * pf), np.min(px - x0 * pf)
    by1, by0 = np.max(py - y1 * pf), np.min(py - y0 * pf)
    t = max((ax1 - ax0) / (x1 - x0), (by1 - by0) / (y1 - y0), float(np.max(-pf)) * 1.001 + 1e-9)
    a = 0.5 * ((ax1 - x1 * t) + (ax0 - x0 * t))
    b = 0.5 * ((by1 - y1 * t) + (by0 - y0 * t))
    return origin + a * right + b * up - t * forward, t


def project(points, location, right, up, forward):
    """(x, y) tangent-unit image coordinates of points seen from a camera at location."""
    rel = np.asarray(points, dtype=np.float64) - location
    depth = rel @ forward
    return np.stack([(rel @ right) / depth, (rel @ up) / depth], axis=1)


def lights(location, target, right, up, forward, size):
    """Three soft lights for a subject of `size` seen from `location` towards `target`: a key above and to
    the left of the camera, a weaker fill low on the right, and a rim behind the subject that outlines it
    against the background. Returns [(name, position (3,), relative power)]."""
    distance = float(np.linalg.norm(np.asarray(target) - np.asarray(location)))
    reach = max(distance, size)

    def around(side, lift, back):
        direction = side * right + lift * up - back * forward
        return np.asarray(target) + reach * direction / np.linalg.norm(direction)

    return [("key", around(-1.0, 1.0, 0.5), 1.0),
            ("fill", around(1.0, -0.2, 0.7), 0.15),
            ("rim", around(0.4, 0.9, -1.0), 0.9)]


# Candidate backgrounds (sRGB grey levels) from light to dark.
BACKGROUNDS = {"light": 0.92, "mid": 0.55, "dark": 0.09}


def background_for(name, choice="auto"):
    """The background grey (scene-linear RGB) for colour map `name`: the one of BACKGROUNDS whose lightness
    is farthest from the nearest of the map's ends (and, for a diverging map, its white centre), so that
    both ends stand out; or the one asked for."""
    if choice == "auto":
        ends = colors.map_lightness(name)

        def distance(level):
            return min(abs(colors.lightness(colors.srgb_to_linear([level] * 3)) - end) for end in ends)

        choice = max(BACKGROUNDS, key=lambda key: distance(BACKGROUNDS[key]))
    grey = float(colors.srgb_to_linear(BACKGROUNDS[choice]))
    return (grey, grey, grey)
