"""How much time the import operator adds to the core's own meshing, file by file.

    blender -b --factory-startup --python-exit-code 1 --python addon/benchmarks/operator_overhead.py -- \\
        build/vesselmesh.zip FILE... [--repeat N]

For each file, with the operator's default settings (curvature method, 2 levels, curvature colours):
  core      the core alone, in this process: vesselmesh_core.mesh(graph, curvature=True) — its own
            stats["seconds"] (the sum of its stages) and the wall time of reading, graph and meshing —
            holding freed memory as the operator's job does (vesselmesh_core.FreedMemoryHold);
  operator  the wall time of bpy.ops.import_scene.vesselmesh(filepath=FILE): reading, meshing, the
            centerline and surface objects, the curvature attributes, colours and material.
Runs alternate, each from an empty scene; the medians of N runs (default 5) are printed as a Markdown
table, ratio = operator / core stats seconds. The add-on is installed from the zip into a temporary
user profile, as a user would install it.
"""
import argparse
import os
import statistics
import sys
import tempfile
import time

import bpy

_profile = None  # the temporary user profile the add-on is installed in, kept until Blender exits


def install_addon(zip_path):
    """Installs and enables the add-on from its zip in a temporary user profile (kept for the rest of the
    session), as a user would, and returns its module."""
    global _profile
    _profile = tempfile.TemporaryDirectory(prefix="vesselmesh-bench-")
    os.environ["BLENDER_USER_SCRIPTS"] = _profile.name
    bpy.ops.preferences.addon_install(filepath=os.path.abspath(zip_path))
    bpy.ops.preferences.addon_enable(module="vesselmesh")
    return sys.modules["vesselmesh"]


def main():
    parser = argparse.ArgumentParser(prog="operator_overhead.py")
    parser.add_argument("zip")
    parser.add_argument("files", nargs="+")
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])

    addon = install_addon(args.zip)
    vc = addon.core.native.core()
    defaults = bpy.ops.import_scene.vesselmesh.get_rna_type().properties
    options = {name: defaults[name].default for name in addon.core.meshing.MESH_OPTIONS}

    rows = []
    for path in args.files:
        core_stats, core_wall, operator = [], [], []
        for _ in range(args.repeat):
            bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
            start = time.perf_counter()
            with vc.FreedMemoryHold():  # as the operator's job holds it
                result = vc.mesh(vc.Graph.read(path), curvature=True, **options)
            core_wall.append(time.perf_counter() - start)
            core_stats.append(result["stats"]["seconds"])
            del result
            start = time.perf_counter()
            bpy.ops.import_scene.vesselmesh(filepath=path)
            operator.append(time.perf_counter() - start)
        triangles = len(bpy.context.active_object.data.polygons)
        rows.append((os.path.basename(path), triangles, statistics.median(core_stats),
                     statistics.median(core_wall), statistics.median(operator)))

    print(f"\nBlender {bpy.app.version_string}, {os.cpu_count()} CPUs, medians of {args.repeat} runs\n")
    print("| file | triangles | core (stats) s | core (wall) s | operator s | operator / core |")
    print("|---|---:|---:|---:|---:|---:|")
    for name, triangles, stats, wall, op in rows:
        print(f"| {name} | {triangles:,} | {stats:.3f} | {wall:.3f} | {op:.3f} | {op / stats:.2f} |")


if __name__ == "__main__":
    main()
