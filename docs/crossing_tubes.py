"""Where a centerline's tubes overlap far apart along the graph: vessels crossing, or touching side by side.

Each such place closes a cycle that the graph does not have (through the graph one way, through the
overlap the other), so the union of the input's round cones has a handle there. A surface of the
graph's genus that follows the tubes must then cross itself there, and one that does not cross itself
must have more genus (docs/pipeline.md, Self-intersections).

    /usr/bin/python3 docs/crossing_tubes.py FILE [FILE ...] [--apart 20]

For each file: the pairs of edges whose round cones overlap (two spheres and their tangent cone,
approximated by the segments' closest points and the radii there) while the shortest path between the
edges along the graph is longer than `--apart` times the larger radius, and the places they form
(pairs whose midpoints lie within 4 radii of each other are one place), with each place's position
and whether one centerline runs inside the other's tube there. Needs the built module (build/python).
"""
import argparse
import heapq
import sys
from collections import defaultdict
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "build" / "python"))
import vesselmesh_core as vc  # noqa: E402


def closest_on_segments(p0, p1, q0, q1):
    """Distance between segment p0p1 and each segment q0[k]q1[k] (K,3), and the parameters (s, t[k]) of
    the closest points."""
    d1, d2, r = p1 - p0, q1 - q0, p0 - q0
    a, e = d1 @ d1, (d2 * d2).sum(1)
    b, c, f = d2 @ d1, r @ d1, (d2 * r).sum(1)
    denominator = a * e - b * b
    s = np.where(denominator > 1e-30, np.clip((b * f - c * e) / np.maximum(denominator, 1e-30), 0, 1), 0.0)
    t = (b * s + f) / np.maximum(e, 1e-30)
    s = np.where(t < 0, np.clip(-c / a, 0, 1), np.where(t > 1, np.clip((b - c) / a, 0, 1), s))
    t = np.clip(t, 0, 1)
    return np.linalg.norm(p0 + s[:, None] * d1 - (q0 + t[:, None] * d2), axis=1), s, t


def crossing_places(graph, apart):
    points, edges, end_radius = graph.points, graph.edges, graph.end_radius
    a, b = points[edges[:, 0]], points[edges[:, 1]]
    neighbours = defaultdict(list)
    for p, q in edges:
        length = float(np.linalg.norm(points[p] - points[q]))
        neighbours[p].append((q, length))
        neighbours[q].append((p, length))

    def path_longer_than(i, j, limit):
        """Whether the shortest path along the graph from edge i to edge j is longer than `limit`."""
        distance = {int(v): 0.0 for v in edges[i]}
        queue = [(0.0, v) for v in distance]
        targets = set(int(v) for v in edges[j])
        while queue:
            d, v = heapq.heappop(queue)
            if v in targets:
                return False
            if d > limit:
                return True
            for w, length in neighbours[v]:
                if d + length < distance.get(w, np.inf):
                    distance[w] = d + length
                    heapq.heappush(queue, (d + length, w))
        return True

    pairs = []  # (midpoint, larger radius, whether a centerline runs inside the other tube)
    for i in range(len(edges) - 1):
        d, s, t = closest_on_segments(a[i], b[i], a[i + 1:], b[i + 1:])
        ri = end_radius[i, 0] * (1 - s) + end_radius[i, 1] * s
        rj = end_radius[i + 1:, 0] * (1 - t) + end_radius[i + 1:, 1] * t
        for k in np.nonzero(d < ri + rj)[0]:
            j, radius = i + 1 + int(k), float(max(ri[k], rj[k]))
            if path_longer_than(i, j, apart * radius):
                pairs.append(((a[i] + b[i] + a[j] + b[j]) / 4, radius, bool(d[k] < radius)))
    # Places: pairs whose midpoints lie within 4 radii of each other, joined transitively.
    place = list(range(len(pairs)))

    def root(x):
        while place[x] != x:
            place[x] = place[place[x]]
            x = place[x]
        return x

    for x in range(len(pairs)):
        for y in range(x):
            if np.linalg.norm(pairs[x][0] - pairs[y][0]) < 4 * max(pairs[x][1], pairs[y][1]):
                place[root(x)] = root(y)
    places = defaultdict(list)
    for x in range(len(pairs)):
        places[root(x)].append(pairs[x])
    return len(pairs), list(places.values())


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("files", nargs="+")
    parser.add_argument("--apart", type=float, default=20.0,
                        help="how far apart along the graph, in radii, two overlapping edges must be")
    args = parser.parse_args()
    for path in args.files:
        graph = vc.Graph.read(path)
        count, places = crossing_places(graph, args.apart)
        print(f"{path}: {count} pairs of overlapping edges more than {args.apart:g} radii apart along the "
              f"graph, at {len(places)} places")
        for members in places:
            at = np.mean([m[0] for m in members], axis=0)
            inside = " (a centerline runs inside the other tube)" if any(m[2] for m in members) else ""
            print(f"  at ({at[0]:.4g}, {at[1]:.4g}, {at[2]:.4g}): {len(members)} pairs{inside}")


if __name__ == "__main__":
    main()
