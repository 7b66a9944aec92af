"""Centerline arrays before meshing: radii for points that have none, smoothing of jagged tracings, and
the arithmetic of the radius tool. No bpy: points (N,3), edges (E,2), radii (N,) or (E,) as numpy arrays."""
import heapq

import numpy as np


def _neighbours(edges, points):
    """Both directions of every edge as (from, to, weight) arrays, weight 1 / length."""
    edges = np.asarray(edges, dtype=np.intp).reshape(-1, 2)
    a, b = edges[:, 0], edges[:, 1]
    length = np.linalg.norm(points[a] - points[b], axis=1)
    weight = 1.0 / np.maximum(length, 1e-12 * max(1.0, float(np.abs(points).max(initial=0.0))))
    return np.concatenate([a, b]), np.concatenate([b, a]), np.concatenate([weight, weight])


def fill_point_radii(points, edges, radius, default):
    """Radii for the points whose radius is not positive (vertices added in Blender's edit mode start at 0,
    or a point attribute added by hand), from their neighbours along the edges: each takes the
    length-weighted average of its neighbours, so that a point inserted between radii 1 and 2 gets 1.5
    and a new tip continues the branch it grows from. Points with no radius anywhere in their part of the
    centerline get `default`. Returns a new array; the known radii are unchanged."""
    points = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    radius = np.asarray(radius, dtype=np.float64).copy()
    known = np.isfinite(radius) & (radius > 0)
    if known.all():
        return radius
    source, target, weight = _neighbours(edges, points)
    # Start from the nearest known radius along the edges (Dijkstra from every known point at once) ...
    adjacency = [[] for _ in range(len(points))]
    for s, t, w in zip(source.tolist(), target.tolist(), weight.tolist()):
        adjacency[s].append((t, 1.0 / w))
    distance = np.full(len(points), np.inf)
    heap = []
    for i in np.flatnonzero(known):
        distance[i] = 0.0
        heap.append((0.0, int(i)))
    heapq.heapify(heap)
    while heap:
        d, i = heapq.heappop(heap)
        if d > distance[i]:
            continue
        for j, length in adjacency[i]:
            if not known[j] and d + length < distance[j]:
                distance[j] = d + length
                radius[j] = radius[i]
                heapq.heappush(heap, (d + length, j))
    unreached = ~known & ~np.isfinite(distance)
    radius[unreached] = default
    # ... then relax towards the weighted average of the neighbours (linear along a run of new points).
    free = ~known & ~unreached
    if free.any():
        den = np.bincount(source, weights=weight, minlength=len(points))
        for _ in range(200):
            num = np.bincount(source, weights=weight * radius[target], minlength=len(points))
            update = num[free] / den[free]
            change = np.abs(update - radius[free]).max()
            radius[free] = update
            if change <= 1e-9 * radius[free].max():
                break
    return radius


def fill_edge_radii(points, edges, edge_radius, default):
    """fill_point_radii for radii given per edge: an edge without a positive radius gets the mean of the
    radii its two end points take from the edges around them."""
    edges = np.asarray(edges, dtype=np.intp).reshape(-1, 2)
    edge_radius = np.asarray(edge_radius, dtype=np.float64).copy()
    known = np.isfinite(edge_radius) & (edge_radius > 0)
    if known.all():
        return edge_radius
    count = len(points)
    ends = edges[known].ravel()
    total = np.bincount(ends, weights=np.repeat(edge_radius[known], 2), minlength=count)
    seen = np.bincount(ends, minlength=count)
    at_points = np.where(seen > 0, total / np.maximum(seen, 1), 0.0)
    at_points = fill_point_radii(points, edges, at_points, default)
    edge_radius[~known] = at_points[edges[~known]].mean(axis=1)
    return edge_radius


def smooth(points, edges, radius=None, iterations=0):
    """Irons out a jagged tracing: `iterations` rounds of Taubin smoothing (a step towards the neighbours'
    average, then a slightly larger one back, so that the line does not shrink) of every point joined to
    exactly two others; branch points and ends stay where they are. Point radii, when given, are averaged
    with their neighbours' in the same rounds. Returns (points, radius) as new arrays."""
    points = np.asarray(points, dtype=np.float64).reshape(-1, 3).copy()
    radius = None if radius is None else np.asarray(radius, dtype=np.float64).copy()
    if iterations <= 0 or len(points) == 0:
        return points, radius
    edges = np.asarray(edges, dtype=np.intp).reshape(-1, 2)
    edges = edges[edges[:, 0] != edges[:, 1]]
    source = np.concatenate([edges[:, 0], edges[:, 1]])
    target = np.concatenate([edges[:, 1], edges[:, 0]])
    degree = np.bincount(source, minlength=len(points))
    inner = degree == 2

    def average(values):
        width = values.shape[1] if values.ndim == 2 else 1
        sums = np.stack([np.bincount(source, weights=(values[target] if width == 1 else values[target, k]),
                                     minlength=len(points)) for k in range(width)], axis=-1)
        sums = sums if values.ndim == 2 else sums[:, 0]
        return sums / np.maximum(degree, 1).reshape((-1,) + (1,) * (values.ndim - 1))

    for _ in range(int(iterations)):
        for factor in (0.5, -0.53):
            step = average(points) - points
            points[inner] += factor * step[inner]
        if radius is not None and len(radius) == len(points):
            radius[inner] += 0.5 * (average(radius) - radius)[inner]
    return points, radius


class RadiusDrag:
    """The radius tool's factor, as Blender's scale tools make theirs: the mouse's distance from the
    pivot (the selection's centre on screen) over its distance when the tool started. Ctrl snaps to
    tenths, Shift moves ten times slower, and a typed number replaces the mouse's factor."""

    def __init__(self, pivot, start):
        self.pivot = np.asarray(pivot, dtype=np.float64)
        self.start = max(float(np.linalg.norm(np.asarray(start, dtype=np.float64) - self.pivot)), 1.0)
        self.typed = ""
        self._precise_from = None

    def factor(self, mouse, snap=False, precise=False):
        if self.typed:
            try:
                return max(float(self.typed), 0.0)
            except ValueError:
                pass
        raw = float(np.linalg.norm(np.asarray(mouse, dtype=np.float64) - self.pivot)) / self.start
        if precise:
            if self._precise_from is None:
                self._precise_from = raw
            raw = self._precise_from + 0.1 * (raw - self._precise_from)
        else:
            self._precise_from = None
        return round(raw, 1) if snap else raw

    def type(self, key):
        """A key typed while the tool runs: digits, '.', '-' and BACK_SPACE edit the number."""
        if key == "BACK_SPACE":
            self.typed = self.typed[:-1]
        elif key in "0123456789." and len(key) == 1:
            self.typed += key
        return self.typed


def scaled_radii(radius, selected, factor, minimum=1e-9):
    """The radii with the selected ones multiplied by factor (never below `minimum`)."""
    radius = np.asarray(radius, dtype=np.float64).copy()
    radius[selected] = np.maximum(radius[selected] * factor, minimum)
    return radius
