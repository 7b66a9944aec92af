"""The shared sets changed as other tracings of the same vessels would give them, meshed at the default
settings: radii 1.6 and 2 times as wide (a file giving diameters where radii belong, vessels pressed
together), points jittered by 0.15 of their radius, points inserted every 0.3 radii along each edge (a
densely sampled tracing), and every other point between joints dropped (a sparse one); the last three on
the graph as read, coincident points merged. Prints, per set and
change, the surface measured by the product's own check against the tubes it follows (the centerline as
the separate stage left it): triangles, closed 2-manifold and genus / loops, self-intersecting triangle
pairs (of them, outside overlapping input tubes), the area over half a local radius off the tubes, the
furthest face centroid from them (local radii).

    /usr/bin/python3 docs/perturbed.py [--shared ../shared/data] [--changes wide1.6 wide2 jitter dense sparse]

Needs the built module (build/python).
"""
import argparse
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "build" / "python"))
import vesselmesh_core as vc  # noqa: E402

SETS = ["brava-bg0003/BG0003_ColorCoded.CNG.swc", "human-brain-arteries/arteries_smooth.vtk",
        "vmtk-aorta-centerline/aorta-centerline.vtp", "vascpy-mouse-vessels/test_smaller_vasculature.vtk",
        "neuron-hemibrain-da1/1734350788.swc", "secomb-rat-cortex-50/network.vtk",
        "secomb-rat-mesentery/network.vtk", "vesselgraph-demo/vertices.csv", "brava-records/BH0009records.swc"]
CHANGES = ["wide1.6", "wide2", "jitter", "dense", "sparse"]


def changed(d, change, rng):
    """The graph of file contents `d` (vesselmesh_core.read) after `change`."""
    points, edges = np.asarray(d["points"], float), np.asarray(d["edges"])
    radius = None if d["radius"] is None else np.asarray(d["radius"], float)
    edge_radius = None if d["edge_radius"] is None else np.asarray(d["edge_radius"], float)
    if change.startswith("wide"):
        f = float(change[4:])
        return vc.Graph(points, edges, radius=None if radius is None else f * radius,
                        edge_radius=None if edge_radius is None else f * edge_radius)
    # Jitter and insertion act on the graph as read, coincident points merged: a point a file gives twice
    # (where two centerlines share a trunk, or children start from a copy of their joint) is one point of
    # the vessel, and moved apart, or with points inserted along both copies of an edge, it would make
    # vessels side by side or loops that the vessels do not have.
    g = vc.Graph(points, edges, radius=radius, edge_radius=edge_radius)
    points, edges, r = np.asarray(g.points), np.asarray(g.edges), np.asarray(g.radius)
    ends = np.asarray(g.end_radius)
    if change == "jitter":
        points = points + rng.normal(0, 0.15, points.shape) * r[:, None]
        if edge_radius is None:
            return vc.Graph(points, edges, radius=r)
        return vc.Graph(points, edges, edge_radius=ends[:, 0])
    if change == "dense":
        out_points, out_edges, out_radius, out_edge_radius = list(points), [], list(r), []
        for k, (a, b) in enumerate(edges):
            n = int(min(40, max(1, np.ceil(np.linalg.norm(points[b] - points[a]) / (0.3 * ends[k].min())))))
            previous = a
            for t in np.linspace(0, 1, n + 1)[1:-1]:
                out_points.append(points[a] + t * (points[b] - points[a]))
                out_radius.append(ends[k][0] + t * (ends[k][1] - ends[k][0]))
                out_edges.append((previous, len(out_points) - 1))
                out_edge_radius.append(ends[k][0])
                previous = len(out_points) - 1
            out_edges.append((previous, b))
            out_edge_radius.append(ends[k][0])
        if edge_radius is None:
            return vc.Graph(np.array(out_points), np.array(out_edges), radius=np.array(out_radius))
        return vc.Graph(np.array(out_points), np.array(out_edges), edge_radius=np.array(out_edge_radius))
    # sparse: every other point between joints dropped, its two edges joined (radius: the first's).
    neighbours = [[] for _ in points]
    for k, (a, b) in enumerate(edges):
        neighbours[a].append((b, k))
        neighbours[b].append((a, k))
    drop = np.zeros(len(points), bool)
    for i in range(0, len(points), 2):
        if len(neighbours[i]) == 2 and not any(drop[j] for j, _ in neighbours[i]):
            drop[i] = True
    kept_edges = [(a, b, k) for k, (a, b) in enumerate(edges) if not drop[a] and not drop[b]]
    kept_edges += [(neighbours[i][0][0], neighbours[i][1][0], neighbours[i][0][1]) for i in np.where(drop)[0]]
    index = -np.ones(len(points), int)
    index[~drop] = np.arange((~drop).sum())
    new_edges = np.array([(index[a], index[b]) for a, b, _ in kept_edges])
    if edge_radius is None:
        return vc.Graph(points[~drop], new_edges, radius=r[~drop])
    return vc.Graph(points[~drop], new_edges, edge_radius=np.array([ends[k][0] for _, _, k in kept_edges]))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--shared", type=Path, default=ROOT.parent / "shared" / "data")
    parser.add_argument("--changes", nargs="+", default=CHANGES, choices=CHANGES)
    args = parser.parse_args()
    rng = np.random.default_rng(1)
    print("| set | change | triangles | closed, genus / loops | pairs (outside) | area off % | furthest (radii) |")
    print("|---|---|---|---|---|---|---|")
    for relative in SETS:
        path = args.shared / relative
        if not path.exists():
            sys.exit(f"{path} not found: the script needs ../shared/data")
        d = vc.read(str(path))
        for change in args.changes:
            graph = changed(d, change, rng)
            surface = vc.mesh(graph)
            report = vc.check(surface["vertices"], surface["faces"], surface["centerline"] or graph)
            topology, pairs, fidelity = report["topology"], report["intersections"], report["fidelity"]
            closed = report["closed_manifold"] and topology["components"] == graph.components
            outside = pairs["pairs"] - pairs["pairs_in_overlapping_tubes"]
            print(f"| {relative} | {change} | {len(surface['faces']):,} | "
                  f"{'yes' if closed else 'NO'}, {topology['genus']} / {graph.loops} | {pairs['pairs']} ({outside}) | "
                  f"{100 * fidelity['area_off_tubes']:.2f} | {fidelity['largest_centroid_offset']['relative']:.2f} |", flush=True)


if __name__ == "__main__":
    main()
