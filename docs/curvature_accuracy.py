"""Curvature accuracy against closed forms, on analytic tori and on the pipeline's own surfaces.

    PYTHONPATH=build/python /usr/bin/python3 docs/curvature_accuracy.py

Analytic: a torus of tube radius r = 2 and ring radius R (R/r = 5 and 3), sampled with 16, 24 and 32
vertices round the tube, its quads cut along one diagonal. Pipeline: the surface `vesselmesh mesh`
makes of a 96-point ring centerline of the same radii. Each row: mean curvature error |H − H*| / H*
(median / 95th percentile, %) and Gaussian curvature error |K − K*|·r(R − r) (median / 95th percentile),
with H*, K* the torus's closed forms at each vertex's own position.
"""
import numpy as np

import vesselmesh_core as vm


def torus_mesh(ring, tube, around):
    along = int(round(ring / tube * around))
    u, v = np.meshgrid(2 * np.pi * np.arange(along) / along, 2 * np.pi * np.arange(around) / around,
                       indexing="ij")
    vertices = np.stack([(ring + tube * np.cos(v)) * np.cos(u), (ring + tube * np.cos(v)) * np.sin(u),
                         tube * np.sin(v)], axis=-1).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(along), np.arange(around), indexing="ij")
    a, b = i * around + j, (i + 1) % along * around + j
    c, d = (i + 1) % along * around + (j + 1) % around, i * around + (j + 1) % around
    faces = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)])
    return vertices, faces.astype(np.int32)


def errors(vertices, curvature, ring, tube):
    rho = np.hypot(vertices[:, 0], vertices[:, 1])
    cos_v = (rho - ring) / np.hypot(rho - ring, vertices[:, 2])
    k2 = cos_v / (ring + tube * cos_v)
    mean, gaussian = (1 / tube + k2) / 2, k2 / tube
    h = np.abs(curvature["mean"] - mean) / np.abs(mean)
    k = np.abs(curvature["gaussian"] - gaussian) * tube * (ring - tube)
    return (f"H {100 * np.median(h):5.1f} / {100 * np.percentile(h, 95):5.1f} %   "
            f"K·r(R−r) {np.median(k):.3f} / {np.percentile(k, 95):.3f}")


def ring_graph(ring, tube, points=96):
    a = 2 * np.pi * np.arange(points) / points
    edges = np.stack([np.arange(points), (np.arange(points) + 1) % points], -1)
    return vm.Graph(np.stack([ring * np.cos(a), ring * np.sin(a), 0 * a], -1), edges,
                    radius=np.full(points, float(tube)))


tube = 2.0
for ring in (10.0, 6.0):
    print(f"torus R/r = {ring / tube:.0f}")
    for around in (16, 24, 32):
        vertices, faces = torus_mesh(ring, tube, around)
        print(f"  analytic, {around:2d} round          {errors(vertices, vm.curvature(vertices, faces), ring, tube)}")
    graph = ring_graph(ring, tube)
    for label, options in (("default", {}), ("level 2 uniform", dict(method="uniform")),
                           ("level 3 uniform", dict(method="uniform", levels=3))):
        surface = vm.mesh(graph, curvature=True, **options)
        print(f"  pipeline, {label:16s}  {errors(surface['vertices'], surface['curvature'], ring, tube)}")
