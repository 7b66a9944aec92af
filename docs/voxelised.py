"""Shared centerlines traced again through voxels, as skeletonising a segmented volume would give them:
each edge walked in small steps, its points rounded to a grid of voxels `v` times the set's median
radius, repeated voxels dropped. Prints, per set and voxel size, the surface at levels 0 and 2: triangles,
closed 2-manifold and genus, self-intersecting triangle pairs, radius error (median / p95) and area
off the tubes, all measured against the voxel centerline.

    /usr/bin/python3 docs/voxelised.py [--shared ../shared/data] [--voxels 0.25 0.5 1.0]

Needs the built module (build/python).
"""
import argparse
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "build" / "python"))
import vesselmesh_core as vc  # noqa: E402

SETS = [("human-brain-arteries", "human-brain-arteries/arteries_smooth.vtk"),
        ("brava-bg0003", "brava-bg0003/BG0003_ColorCoded.CNG.swc")]


def voxelised(graph, voxel):
    """(points, edges, radius) of `graph` traced through a grid of `voxel` units."""
    points, edges, radius = np.asarray(graph.points), np.asarray(graph.edges), np.asarray(graph.radius)
    index, out_points, out_radius, out_edges = {}, [], [], set()
    for a, b in edges:
        steps = max(1, int(np.ceil(2 * np.linalg.norm(points[b] - points[a]) / voxel)))
        previous = None
        for t in np.linspace(0, 1, steps + 1):
            cell = tuple(np.round((points[a] + t * (points[b] - points[a])) / voxel).astype(np.int64))
            if cell not in index:
                index[cell] = len(out_points)
                out_points.append(np.array(cell) * voxel)
                out_radius.append(radius[a] + t * (radius[b] - radius[a]))
            if previous is not None and previous != index[cell]:
                out_edges.add((min(previous, index[cell]), max(previous, index[cell])))
            previous = index[cell]
    return np.array(out_points), np.array(sorted(out_edges)), np.array(out_radius)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--shared", type=Path, default=ROOT.parent / "shared" / "data")
    parser.add_argument("--voxels", type=float, nargs="+", default=[0.25, 0.5, 1.0])
    args = parser.parse_args()
    print("| set | voxel (median radii) | points | level | triangles | closed, genus | pairs | radius error | off |")
    print("|---|---|---|---|---|---|---|---|---|")
    for title, relative in SETS:
        path = args.shared / relative
        if not path.exists():
            sys.exit(f"{path} not found: the script needs ../shared/data")
        graph = vc.Graph.read(str(path))
        for v in args.voxels:
            points, edges, radius = voxelised(graph, v * np.median(np.asarray(graph.radius)))
            traced = vc.Graph(points, edges, radius=radius)
            for level in (0, 2):
                surface = vc.mesh(traced, levels=level)
                report = vc.check(surface["vertices"], surface["faces"], traced)
                error = report["fidelity"]["abs_relative_error"]
                print(f"| {title} | {v:g} | {len(points):,} | {level} | {len(surface['faces']):,} "
                      f"| {'yes' if report['closed_manifold'] else 'NO'}, {report['topology']['genus']} "
                      f"| {report['intersections']['pairs']} | {100 * error['median']:.1f} / {100 * error['p95']:.1f} % "
                      f"| {100 * report['fidelity']['area_off_tubes']:.2f} % |", flush=True)


if __name__ == "__main__":
    main()
