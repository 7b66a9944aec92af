"""The paper's Table 1 on our data: triangle counts and quality of uniform, dihedral-angle and curvature
subdivision at levels 0-3, written to docs/table1.md, and the triangles against the face error as a plot,
docs/images/table1_face_error.png (rendered by docs/table1_plot.py in Blender, when `blender` is on the PATH).

    /usr/bin/python3 docs/table1.py [--shared ../shared/data] [--out docs/table1.md]

Needs the built module (build/python) and the shared data sets brava-bg0003 and human-brain-arteries.
"""
import argparse
import json
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "build" / "python"))
import vesselmesh_core as vc  # noqa: E402

SETS = [("brava-bg0003", "brava-bg0003/BG0003_ColorCoded.CNG.swc", "mm"),
        ("human-brain-arteries", "human-brain-arteries/arteries_smooth.vtk", "m")]
# The paper's dihedral angles per level (its Table 1, cerebral tree).
DIHEDRAL_ANGLE = {1: 120.0, 2: 144.0, 3: 160.0}
# The curvature method's thresholds the level-2 trade-off table runs through (0.72 is the default).
THRESHOLDS = [0.1, 0.2, 0.3, 0.5, 0.72, 0.9]


def methods(level):
    """(name, mesh options) in table order; adaptive levels start from one uniform level except at level 1.
    Level 0 is the base mesh, the same for every method."""
    if level == 0:
        return [("uniform", dict(method="uniform"))]
    adaptive = dict(uniform_levels=0 if level == 1 else 1)
    return [("uniform", dict(method="uniform")),
            (f"dihedral {DIHEDRAL_ANGLE[level]:.0f}°", dict(method="dihedral", angle=DIHEDRAL_ANGLE[level], **adaptive)),
            ("curvature", dict(method="curvature", **adaptive))]


def row(graph, level, name, options, uniform):
    start = time.perf_counter()
    surface = vc.mesh(graph, levels=level, curvature=True, **options)
    seconds = time.perf_counter() - start
    report = vc.check(surface["vertices"], surface["faces"], graph)
    topology, quality, fidelity = report["topology"], report["quality"], report["fidelity"]["abs_relative_error"]
    centroids = report["fidelity"]["centroid_error"]
    rms = surface["curvature"]["rms"]
    triangles = len(surface["faces"])
    cells = [f"{level}", name, f"{triangles:,}",
             "100 %" if uniform is None else f"{100 * triangles / len(uniform['faces']):.1f} %",
             f"{100 * np.mean(surface['stats']['tagged_fraction']):.0f} %",
             f"{np.median(rms):.3g} / {np.percentile(rms, 95):.3g}",
             f"{quality['radius_ratio']['median']:.2f} / {quality['radius_ratio']['p95']:.2f}",
             f"{quality['min_angle']['min']:.1f}°",
             f"{100 * fidelity['median']:.2f} / {100 * fidelity['p95']:.1f} %",
             f"{100 * centroids['median']:.2f} / {100 * centroids['p95']:.1f} %"]
    if uniform is None:
        cells.append("–")
    else:
        d = vc.surface_distance(surface["vertices"], surface["faces"], uniform["vertices"], uniform["faces"], graph)
        cells.append(f"{100 * d['vertices']['p95']:.2f} % · {100 * d['centroids']['median']:.2f} / "
                     f"{100 * d['centroids']['p95']:.2f} %")
    closed = report["closed_manifold"] and topology["euler_characteristic"] == 2 * graph.components - 2 * graph.loops
    cells += ["yes" if closed else "NO", f"{report['intersections']['pairs']:,}", f"{seconds:.2f}"]
    return surface, "| " + " | ".join(cells) + " |", (level, triangles, 100 * centroids["p95"])


def tradeoff(graph, level1, level2):
    """Rows of the level-2 trade-off: per threshold, the triangles and how many of them are coarser than level 2.

    An output vertex numbered below the uniform level-1 vertex count is a level-1 vertex (the adaptive stage keeps
    the hierarchy's order), so a face with three such corners that closes no crack is an unsplit level-1 triangle.
    """
    lines = []
    for threshold in THRESHOLDS:
        surface = vc.mesh(graph, levels=2, method="curvature", threshold=threshold)
        faces, transition = surface["faces"], surface["transition"].astype(bool)
        unsplit = (faces < len(level1["vertices"])).all(axis=1) & ~transition
        d = vc.surface_distance(surface["vertices"], faces, level2["vertices"], level2["faces"], graph)["centroids"]
        lines.append(f"| {threshold:g} | {len(faces):,} | {100 * len(faces) / len(level2['faces']):.1f} % "
                     f"| {100 * unsplit.mean():.1f} % | {100 * transition.mean():.1f} % "
                     f"| {100 * d['median']:.2f} / {100 * d['p95']:.2f} % |")
        print(lines[-1], flush=True)
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--shared", type=Path, default=ROOT.parent / "shared" / "data")
    parser.add_argument("--out", type=Path, default=ROOT / "docs" / "table1.md")
    args = parser.parse_args()
    lines = ["# Table 1 on our data",
             "",
             f"Made by `/usr/bin/python3 docs/table1.py` on an {platform.machine()} machine with {os.cpu_count()} "
             f"cores ({platform.platform(terse=True)}); the times are the whole "
             "`mesh` call (reading excluded), curvature estimation for the RMS column included.",
             "",
             "Columns: triangles and their share of uniform's; tagged: the share of triangles the adaptive levels "
             "tagged (mean over levels, uniform levels count as 100 %); RMS curvature sqrt((k1² + k2²)/2) median / "
             "95th percentile, in 1/unit; radius ratio R/r median / p95 (2 is equilateral); the smallest angle; "
             "radius fidelity |error|/r median / p95 at the vertices; face error: the distance of the face centroids "
             "from the input's tubes over the local radius, area-weighted median / p95 (what a render shows between "
             "the vertices; plotted against the triangles in images/table1_face_error.png); distance to the uniform surface of the same level over "
             "the local radius: p95 at the vertices · median / p95 at the face centroids; closed 2-manifold with "
             "χ = 2·components − 2·loops; self-intersecting triangle pairs (see docs/pipeline.md for the ones "
             "from overlapping input tubes); seconds.",
             "",
             "Each set's second table runs the curvature method at level 2 through several thresholds: the share "
             "of its faces that are unsplit level-1 triangles or crack-closing (transition) pieces, and where "
             "their centroids lie against the uniform surface; docs/pipeline.md (subdivide) has the adaptive "
             "method against uniform by the face centroids' distance from the tubes.",
             "",
             "![Triangles against the face error at the 95th percentile, per method and level, on both sets]"
             "(images/table1_face_error.png)",
             ""]
    plot = {}
    for title, relative, unit in SETS:
        path = args.shared / relative
        if not path.exists():
            sys.exit(f"{path} not found: the table needs ../shared/data")
        graph = vc.Graph.read(str(path))
        lines += [f"## {title} ({unit})", "",
                  "| level | method | triangles | of uniform | tagged | RMS curvature | R/r | min angle | fidelity "
                  "| face error | to uniform (vertices · centroids) | closed | intersections | s |",
                  "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
        uniforms = {}
        curves = plot.setdefault(title, {})
        for level in (0, 1, 2, 3):
            uniform = None
            for name, options in methods(level):
                surface, line, point = row(graph, level, name, options, uniform)
                uniform = uniform or surface
                lines.append(line)
                print(title, line, flush=True)
                # A line per method (the dihedral angle changes with the level); level 0, the base mesh,
                # starts each.
                for method in (["uniform", "dihedral", "curvature"] if level == 0 else [name.split()[0]]):
                    curves.setdefault(method, []).append(point)
            uniforms[level] = uniform
        lines += ["", f"Level 2, the curvature method's threshold against the distance to the uniform surface "
                  f"({title}):", "",
                  "| threshold | triangles | of uniform | unsplit level-1 | transition | to uniform at centroids "
                  "(median / p95) |",
                  "|---|---|---|---|---|---|"]
        lines += tradeoff(graph, uniforms[1], uniforms[2])
        lines.append("")
    args.out.write_text("\n".join(lines))
    print(f"wrote {args.out}")
    render_plot(plot, args.out.parent / "images" / "table1_face_error.png")


def render_plot(plot, png):
    """The triangles against the face error, rendered by docs/table1_plot.py in Blender."""
    if shutil.which("blender") is None:
        print(f"blender not found: {png} not rendered")
        return
    with tempfile.TemporaryDirectory() as tmp:
        points = Path(tmp) / "points.json"
        points.write_text(json.dumps(plot))
        subprocess.run(["blender", "-b", "--factory-startup", "--python-exit-code", "1", "--python",
                        str(ROOT / "docs" / "table1_plot.py"), "--", str(points), str(png)],
                       check=True, stdout=subprocess.DEVNULL)
    print(f"wrote {png}")


if __name__ == "__main__":
    main()
