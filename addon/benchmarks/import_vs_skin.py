"""The add-on against what a Blender user does without it, in one Blender session, file by file.

    blender -b --factory-startup --python-exit-code 1 --python addon/benchmarks/import_vs_skin.py -- \\
        build/vesselmesh.zip FILE... [--repeat N] [--json OUT.json]

  import      bpy.ops.import_scene.vesselmesh(filepath=FILE) at its default settings: reading, meshing,
              the centerline and surface objects, curvature colours, Blender's first evaluation;
  skin        the same centerline (the core's graph of the file) as a mesh of edges, each point's radius
              its skin radius and one root per connected piece, with a Skin modifier and then a
              Subdivision Surface modifier at level 2: from the file to the evaluated mesh (the depsgraph
              runs both modifiers; to_mesh makes sure the subdivided mesh exists);
  regenerate  Regenerate Surface after moving one centerline point (a degree-2 point halfway down the
              file) by a quarter of its radius, at the default settings, then at the Quick Preview preset.
Import and skin alternate, each from an empty scene; the regenerates run on the last import. Medians of
N runs (default 5) are printed as a Markdown table; --json writes them for scripts/bench.py. The add-on is
installed from the zip into a temporary user profile (operator_overhead.install_addon).
"""
import argparse
import json
import os
import statistics
import sys
import time

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from operator_overhead import install_addon  # noqa: E402


def skin_subsurf(addon, path):
    """Skin + Subdivision Surface level 2 on the file's centerline, evaluated; returns the evaluated
    mesh's quads and triangles (what triangulating them would give)."""
    graph = addon.core.native.core().Graph.read(path)
    mesh = bpy.data.meshes.new("skin")
    addon.blender.mesh.write_centerline(mesh, graph.points, graph.edges)
    obj = bpy.data.objects.new("skin", mesh)
    bpy.context.collection.objects.link(obj)
    bpy.context.view_layer.objects.active = obj
    bpy.ops.object.modifier_add(type="SKIN")  # as a user adds it: this also gives the mesh its skin radii
    skin = mesh.skin_vertices[0].data
    skin.foreach_set("radius", np.repeat(graph.radius, 2).astype(np.float32))
    for root in graph.roots:  # the Skin modifier needs one root per connected piece
        skin[int(root)].use_root = True
    subsurf = obj.modifiers.new("Subdivision", "SUBSURF")
    subsurf.levels = subsurf.render_levels = 2
    bpy.context.view_layer.update()
    evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
    result = evaluated.to_mesh()
    quads, triangles = len(result.polygons), len(result.loops) - 2 * len(result.polygons)
    evaluated.to_mesh_clear()
    return quads, triangles


def edit_point(centerline):
    """The point to move: a degree-2 point halfway down the centerline, and the distance to move it."""
    edges = np.empty(2 * len(centerline.data.edges), dtype=np.int32)
    centerline.data.edges.foreach_get("vertices", edges)
    degree = np.bincount(edges, minlength=len(centerline.data.vertices))
    middle = np.flatnonzero(degree == 2)
    index = int(middle[len(middle) // 2])
    radius = centerline.data.attributes.get("radius")
    step = 0.25 * radius.data[index].value if radius is not None and radius.domain == "POINT" else 0.01
    return index, step


def regenerate(surface, repeat):
    """Medians of N Regenerate Surface runs, each after moving one centerline point (back and forth)."""
    centerline = surface.vesselmesh.centerline
    index, step = edit_point(centerline)
    seconds = []
    for run in range(repeat):
        centerline.data.vertices[index].co.x += step if run % 2 == 0 else -step
        bpy.context.view_layer.objects.active = surface
        start = time.perf_counter()
        assert bpy.ops.vesselmesh.generate() == {"FINISHED"}
        seconds.append(time.perf_counter() - start)
    return statistics.median(seconds), len(surface.data.polygons)


def bench_file(addon, path, repeat):
    imported, skinned = [], []
    for _ in range(repeat):
        bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
        start = time.perf_counter()
        skin_quads, skin_triangles = skin_subsurf(addon, path)
        skinned.append(time.perf_counter() - start)
        bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
        start = time.perf_counter()
        assert bpy.ops.import_scene.vesselmesh(filepath=path) == {"FINISHED"}
        imported.append(time.perf_counter() - start)
    surface = bpy.context.active_object
    row = {"file": path, "points": len(surface.vesselmesh.centerline.data.vertices),
           "import_seconds": statistics.median(imported), "import_triangles": len(surface.data.polygons),
           "skin_seconds": statistics.median(skinned), "skin_quads": skin_quads, "skin_triangles": skin_triangles}
    row["regenerate_seconds"], row["regenerate_triangles"] = regenerate(surface, repeat)
    assert bpy.ops.vesselmesh.apply_preset(preset="quick") == {"FINISHED"}
    row["preview_seconds"], row["preview_triangles"] = regenerate(surface, repeat)
    return row


def main():
    parser = argparse.ArgumentParser(prog="import_vs_skin.py")
    parser.add_argument("zip")
    parser.add_argument("files", nargs="+")
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--json", help="write the figures here as JSON")
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])

    addon = install_addon(args.zip)
    rows = [bench_file(addon, os.path.abspath(path), args.repeat) for path in args.files]

    print(f"\nBlender {bpy.app.version_string}, {os.cpu_count()} CPUs, medians of {args.repeat} runs\n")
    print("| file | import s (triangles) | Skin + Subsurf 2 s (quads) | Skin / import | regenerate s | "
          "Quick Preview regenerate s (triangles) |")
    print("|---|---:|---:|---:|---:|---:|")
    for r in rows:
        print(f"| {os.path.basename(r['file'])} | {r['import_seconds']:.3f} ({r['import_triangles']:,}) | "
              f"{r['skin_seconds']:.3f} ({r['skin_quads']:,}) | {r['skin_seconds'] / r['import_seconds']:.2f} | "
              f"{r['regenerate_seconds']:.3f} | {r['preview_seconds']:.3f} ({r['preview_triangles']:,}) |")
    if args.json:
        with open(args.json, "w") as out:
            json.dump({"blender": bpy.app.version_string, "repeat": args.repeat, "files": rows}, out, indent=1)


if __name__ == "__main__":
    main()
