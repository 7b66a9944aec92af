"""Where a surface lies off its tubes: the area whose face centroids are over half a local radius off the
tubes (the check's "area off"), split by where it lies. For Where it stands in docs/pipeline.md.

    PYTHONPATH=build/python /usr/bin/python3 docs/area_off_places.py FILE... [--levels N]

Each file is meshed at the default settings (the Python module's `mesh`), and each face centroid's signed
distance to the tubes the surface follows (the centerline as the separate stage left it) is taken over the
local radius (`radius_error` at the centroids; NaN at the caps, which are left out as the check leaves
them). The area off is then split: within 4 local radii of a joint (a point of three or more edges), along
the thickest vessels (the nearest point's radius in the top 5 % of the file's radii), and along the other
tubes; with the share inside the tubes.
"""
import argparse

import numpy as np

import vesselmesh_core as vm

JOINT_REACH = 4.0  # local radii
THICK_PERCENTILE = 95.0


def nearest_point(points, queries):
    """Index of the nearest of `points` (N,3) to each of `queries` (M,3), in blocks to bound the memory."""
    out = np.empty(len(queries), dtype=np.intp)
    for start in range(0, len(queries), 256):
        block = queries[start:start + 256]
        squared = ((block[:, None, :] - points[None, :, :]) ** 2).sum(axis=2)
        out[start:start + 256] = np.argmin(squared, axis=1)
    return out


def places(path, levels):
    graph = vm.Graph.read(path)
    result = vm.mesh(graph) if levels is None else vm.mesh(graph, levels=levels)
    tubes = result["centerline"] or graph
    vertices, faces = np.asarray(result["vertices"]), np.asarray(result["faces"])
    corners = vertices[faces]
    edges = corners[:, 1:] - corners[:, :1]
    area = 0.5 * np.linalg.norm(np.cross(edges[:, 0], edges[:, 1]), axis=1)
    no_faces = np.zeros((0, 3), dtype=np.int32)  # the centroids alone, as points
    offset = vm.radius_error(corners.mean(axis=1), no_faces, tubes).astype(np.float64)
    counted = ~np.isnan(offset)
    off = counted & (np.abs(offset) > 0.5)
    points, radius = np.asarray(tubes.points), np.asarray(tubes.radius)
    degree = np.bincount(np.asarray(tubes.edges).ravel(), minlength=len(points))
    joints = np.flatnonzero(degree >= 3)
    centroids = corners.mean(axis=1)[off]
    near_joint = np.zeros(len(centroids), dtype=bool)
    if len(joints):
        j = joints[nearest_point(points[joints], centroids)]
        near_joint = np.linalg.norm(centroids - points[j], axis=1) < JOINT_REACH * radius[j]
    thick = radius[nearest_point(points, centroids)] >= np.percentile(radius, THICK_PERCENTILE)
    a = area[off]
    total = max(a.sum(), 1e-300)
    return {
        "area_off": a.sum() / area[counted].sum(),
        "joints": a[near_joint].sum() / total,
        "thick": a[~near_joint & thick].sum() / total,
        "other": a[~near_joint & ~thick].sum() / total,
        "inside": a[offset[off] < 0].sum() / total,
        "faces": int(off.sum()),
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("files", nargs="+")
    parser.add_argument("--levels", type=int, default=None, help="subdivision level (default: the product's)")
    args = parser.parse_args()
    print("| file | area off % | faces | at joints % | thickest vessels % | other tubes % "
          "| inside the tubes % |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    for path in args.files:
        p = places(path, args.levels)
        print(f"| {path.split('/')[-1]} | {100 * p['area_off']:.2f} | {p['faces']} | "
              f"{100 * p['joints']:.0f} | {100 * p['thick']:.0f} | {100 * p['other']:.0f} | "
              f"{100 * p['inside']:.0f} |")


if __name__ == "__main__":
    main()
