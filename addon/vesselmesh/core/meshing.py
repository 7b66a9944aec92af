"""Centerline arrays in, surface arrays out: what the operators hand to the native core and get back."""
import threading
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from . import centerline as centerline_arrays
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


def typical_radius(data):
    """The median radius of a centerline's arrays (positive ones), or None when it has none."""
    values = data.get("radius") if data.get("radius") is not None else data.get("edge_radius")
    if values is None:
        return None
    values = np.asarray(values)[np.asarray(values) > 0]
    return float(np.median(values)) if len(values) else None


def centerline_graph(points, edges, radius=None, edge_radius=None, default_radius=1.0, smooth=0):
    """The core's graph of a centerline whose radii may be missing or unset, smoothed `smooth` rounds.

    Without radii every point gets default_radius. A radius that is not positive (vertices added in
    Blender's edit mode start at 0) comes from the neighbours along the edges (centerline.fill_point_radii),
    or is default_radius where no point around has one.
    """
    points = np.asarray(points, dtype=np.float64)
    if radius is None and edge_radius is None:
        radius = np.full(len(points), default_radius)
    if radius is not None:
        radius = centerline_arrays.fill_point_radii(points, edges, radius, default_radius)
    if edge_radius is not None:
        edge_radius = centerline_arrays.fill_edge_radii(points, edges, edge_radius, default_radius)
    if smooth:
        points, radius = centerline_arrays.smooth(points, edges, radius, smooth)
    return core().Graph(points, edges, radius=radius, edge_radius=edge_radius)


def describe_stats(stats):
    """One line: the triangles and the time of each stage of the core, as stats gives them."""
    stages = ", ".join(f"{s['stage']} {s['seconds']:.2f} s" for s in stats["stages"])
    return f"{stats['triangles']:,} triangles in {stats['seconds']:.2f} s ({stages})"


class MeshJob:
    """One meshing by the core, in worker threads (the core releases the GIL while it works).

    `prepare()` (reading a file, building the graph) runs in the first worker, then the core builds the
    surface, with its curvature when `color` asks for colours: (measure, colour map, percentile) as
    colors.color_by takes them (None for no curvature). Then that worker lists its edges for Blender while
    the other turns the curvature into colours; the main thread then only hands Blender the colours.

    The job says where it is: stage() gives the index and name of the stage under way (STAGES), and
    messages() the lines it has to tell since the last call (what was read, what the core built and how
    long each stage took), for the status bar and for stdout in background mode.

    Until close(), the job holds the process's freed memory (vesselmesh_core.FreedMemoryHold): Blender's
    allocator would hand the pages of each big array back at once, and the core and Blender's mesh filling
    would fault in fresh ones, twice as slow.
    """

    STAGES = ("reading the centerline", "building the surface", "colouring by curvature", "filling Blender's mesh")

    def __init__(self, prepare, options, color):
        self._color = color
        self._stage = 0
        self._started = time.perf_counter()
        self._lock = threading.Lock()
        self._lines = []
        self._memory = core().FreedMemoryHold()
        pool = ThreadPoolExecutor(max_workers=2, thread_name_prefix="vesselmesh")
        self._graph = pool.submit(self._prepare, prepare)
        self._surface = pool.submit(self._mesh, options)
        self._edges = pool.submit(self._list_edges)
        self._curvature = pool.submit(self._color_by_curvature) if color is not None else None
        pool.shutdown(wait=False)

    def _say(self, line):
        with self._lock:
            self._lines.append(line)

    def _prepare(self, prepare):
        start = time.perf_counter()
        graph = prepare()
        self._say(f"{len(graph.points):,} points, {len(graph.edges):,} edges ready in "
                  f"{time.perf_counter() - start:.2f} s; building the surface")
        self._stage = 1
        return graph

    def _mesh(self, options):
        # The core's curvature: along the tubes it is the round tubes' own (curvature/tube_curvature.hpp),
        # which a fit to the finished surface alone misses where a tube has 8 vertices round it.
        result = core().mesh(self._graph.result(), curvature=self._color is not None, **options)
        self._say("surface: " + describe_stats(result["stats"]))
        self._stage = 2 if self._color is not None else 3
        return result

    def _list_edges(self):
        result = self._surface.result()
        return core().edges(result["faces"], len(result["vertices"]))

    def _color_by_curvature(self):
        result = self._surface.result()
        start = time.perf_counter()
        curvature = result["curvature"]
        values = {name: curvature[name] for name in ("k1", "k2", "mean", "gaussian", "rms")}
        # Shape, whatever the size: the mean curvature times the radius of the tubes there (1/2 on a straight vessel).
        values["shape"] = (curvature["mean"] * curvature["radius"]).astype(np.float32)
        measure = values[self._color[0]].astype(np.float64)  # as Blender's attribute reads back for a recolour
        coloring = colors.color_by(measure, *self._color[1:])
        self._say(f"colours in {time.perf_counter() - start:.2f} s")
        self._stage = 3
        return values, coloring

    def _futures(self):
        return [f for f in (self._graph, self._surface, self._edges, self._curvature) if f is not None]

    def stage(self):
        """(index, name) of the stage under way, of STAGES."""
        return self._stage, self.STAGES[self._stage]

    def seconds(self):
        return time.perf_counter() - self._started

    def messages(self):
        """The lines the job has to tell since the last call."""
        with self._lock:
            lines, self._lines = self._lines, []
        return lines

    def wait(self, timeout):
        """Waits up to timeout seconds for the job; True once it is done."""
        deadline = time.perf_counter() + timeout
        for future in self._futures():
            left = deadline - time.perf_counter()
            if left <= 0:
                return self.done()
            try:
                future.exception(timeout=left)
            except TimeoutError:
                return False
            except Exception:  # noqa: BLE001 (cancelled: done)
                pass
        return True

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

    def graph(self):
        """Waits for the graph the job meshes. Raises what prepare raised (a bad file's InputError)."""
        return self._graph.result()

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
        return None if self._curvature is None or color != self._color else self._curvature.result()[1]

    def stats(self):
        """The core's statistics of the run (its curvature stage among them when there was one)."""
        return dict(self._surface.result()["stats"])
