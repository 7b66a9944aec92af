"""Centerline arrays in, surface arrays out: what the operators hand to the native core and get back."""
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from . import colors
from .native import core

# The keyword arguments of vesselmesh_core.mesh that the add-on's settings carry, by the same names.
MESH_OPTIONS = ("levels", "method", "uniform_levels", "threshold", "measure", "angle", "sampling", "alpha", "beta",
                "caps", "crossings", "fit")


def read_centerline(path, scale=1.0):
    """The centerline in a file as arrays, coordinates and radii multiplied by scale.

    Returns a dict: points (N,3), edges (E,2) int32, and radius (N,) or edge_radius (E,), whichever the
    file gives (the other is None). Values are rounded to float32, as Blender stores them, so that
    regenerating from an unedited centerline object rebuilds the same surface. Raises
    vesselmesh_core.InputError naming the file and the line for bad input.
    """
    data = core().read(str(path))

    def scaled(values):
        return None if values is None else (values * scale).astype(np.float32).astype(np.float64)

    return {"points": scaled(data["points"]), "edges": data["edges"], "radius": scaled(data["radius"]),
            "edge_radius": scaled(data["edge_radius"])}


def centerline_graph(points, edges, radius=None, edge_radius=None, default_radius=1.0):
    """The core's graph of a centerline whose radii may be missing or unset.

    Without radii every point gets default_radius; so does every radius that is not positive (vertices
    drawn in Blender's edit mode start at 0).
    """
    if radius is None and edge_radius is None:
        radius = np.full(len(points), default_radius)

    def filled(values):
        return None if values is None else np.where(values > 0, values, default_radius)

    return core().Graph(points, edges, radius=filled(radius), edge_radius=filled(edge_radius))


class MeshJob:
    """One meshing of a graph by the core, in worker threads (the core releases the GIL while it works).

    Once the surface exists, one worker lists its edges for Blender while the other estimates the
    surface's curvature and colours it, when `color` asks for that: the measure, colour map and percentile
    of colors.color_by (None for no curvature). Blender builds the mesh from the surface and its edges
    while the curvature is still being estimated; the main thread then only hands Blender the colours.

    Until close(), the job holds the process's freed memory (vesselmesh_core.FreedMemoryHold): Blender's
    allocator would hand the pages of each big array back at once, and the core and Blender's mesh filling
    would fault in fresh ones, twice as slow.
    """

    def __init__(self, graph, options, color):
        self._color = color
        self._memory = core().FreedMemoryHold()
        pool = ThreadPoolExecutor(max_workers=2, thread_name_prefix="vesselmesh")
        self._surface = pool.submit(core().mesh, graph, **options)
        self._edges = pool.submit(self._list_edges)
        self._curvature = pool.submit(self._estimate_curvature) if color is not None else None
        pool.shutdown(wait=False)

    def _list_edges(self):
        result = self._surface.result()
        return core().edges(result["faces"], len(result["vertices"]))

    def _estimate_curvature(self):
        result = self._surface.result()
        start = time.perf_counter()
        values = core().curvature(result["vertices"], result["faces"])
        seconds = time.perf_counter() - start
        measure = values[self._color[0]].astype(np.float64)  # as Blender's attribute reads back for a recolour
        return values, seconds, colors.color_by(measure, *self._color)

    def _futures(self):
        return [f for f in (self._surface, self._edges, self._curvature) if f is not None]

    def done(self):
        return all(f.done() for f in self._futures())

    def surface_done(self):
        return self._surface.done()

    def cancel(self):
        """Drops the results; a run already under way finishes in its thread and is discarded."""
        for f in self._futures():
            f.cancel()
        self.close()

    def close(self):
        """Lets the allocator hand back the memory the job freed; once its results are in the scene."""
        self._memory.release()

    def surface(self):
        """Waits for the surface: vertices (V,3) float32 and faces (F,3) int32, C-contiguous (ready for
        Blender's foreach_set). Raises what the core raised."""
        result = self._surface.result()
        return (np.ascontiguousarray(result["vertices"], dtype=np.float32),
                np.ascontiguousarray(result["faces"], dtype=np.int32))

    def edges(self):
        """Waits for the surface's edges: edges (E,2) int32 and corner_edges (F,3) int32 (see
        vesselmesh_core.edges)."""
        return self._edges.result()

    def curvature(self):
        """Waits for the curvature: {name: (V,) float32} for k1, k2, mean, gaussian and rms, or {} without
        curvature."""
        return {} if self._curvature is None else self._curvature.result()[0]

    def coloring(self, color):
        """Waits for the colours: what colors.color_by gave, when `color` is what the job was asked to
        colour by (the settings may have changed while it ran); else None."""
        return None if self._curvature is None or color != self._color else self._curvature.result()[2]

    def stats(self):
        """The core's statistics of the run, with the curvature stage when there was one."""
        stats = dict(self._surface.result()["stats"])
        if self._curvature is not None:
            seconds = self._curvature.result()[1]
            stats["stages"] = stats["stages"] + [{"stage": "curvature", "seconds": seconds,
                                                  "vertices": stats["vertices"], "faces": stats["triangles"]}]
            stats["seconds"] += seconds
        return stats
