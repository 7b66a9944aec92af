"""Render docs/table1.md's triangles against face error as a PNG, with Blender's Workbench engine.

    blender -b --factory-startup --python-exit-code 1 --python docs/table1_plot.py -- POINTS.json OUT.png

docs/table1.py writes POINTS.json and runs this when `blender` is on the PATH. POINTS.json holds, per data
set, per method, the levels' (level, triangles, face-centroid error at the 95th percentile in % of the local
radius); methods are "uniform", "dihedral" and "curvature". One panel per set: triangles on a log scale
across, the error up; a line per method through its levels, each point labelled with its level.
"""

import json
import math
import sys

import bpy

COLORS = {"uniform": (0.15, 0.15, 0.18, 1), "dihedral": (0.20, 0.45, 0.80, 1), "curvature": (0.85, 0.35, 0.25, 1)}
LEGEND = {"uniform": "uniform, levels 0-3", "dihedral": "dihedral, the paper's angles",
          "curvature": "curvature, threshold 0.72"}
GREY = (0.35, 0.35, 0.38, 1)
WIDTH, HEIGHT = 10.0, 6.0  # one panel, in scene units
GAP = 2.4


def material(rgba):
    m = bpy.data.materials.new("m")
    m.diffuse_color = rgba
    return m


def add_mesh(name, vertices, faces, rgba):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(vertices, [], faces)
    ob = bpy.data.objects.new(name, mesh)
    ob.data.materials.append(material(rgba))
    bpy.context.scene.collection.objects.link(ob)


def segment(a, b, width, rgba):
    dx, dy = b[0] - a[0], b[1] - a[1]
    length = math.hypot(dx, dy) or 1
    nx, ny = -dy / length * width / 2, dx / length * width / 2
    add_mesh("line", [(a[0] + nx, a[1] + ny, 0), (b[0] + nx, b[1] + ny, 0), (b[0] - nx, b[1] - ny, 0),
                      (a[0] - nx, a[1] - ny, 0)], [(0, 1, 2, 3)], rgba)


def dot(p, radius, rgba):
    n = 16
    ring = [(p[0] + radius * math.cos(2 * math.pi * k / n), p[1] + radius * math.sin(2 * math.pi * k / n), 0.01)
            for k in range(n)]
    add_mesh("dot", ring, [tuple(range(n))], rgba)


def text(body, at, size, rgba, align="LEFT"):
    curve = bpy.data.curves.new("t", "FONT")
    curve.body, curve.size, curve.align_x, curve.align_y = body, size, align, "CENTER"
    ob = bpy.data.objects.new("t", curve)
    ob.location = (at[0], at[1], 0.02)
    ob.data.materials.append(material(rgba))
    bpy.context.scene.collection.objects.link(ob)


def panel(x0, title, methods, lo, hi, top):
    """One set's panel with its lower left corner at (x0, 0): log10 triangles lo..hi across, 0..top % up."""
    def at(triangles, error):
        return (x0 + WIDTH * (math.log10(triangles) - lo) / (hi - lo), HEIGHT * error / top)
    segment((x0, 0), (x0 + WIDTH, 0), 0.03, GREY)
    segment((x0, 0), (x0, HEIGHT), 0.03, GREY)
    for e in range(int(math.ceil(lo)), int(math.floor(hi)) + 1):
        x = at(10 ** e, 0)[0]
        segment((x, 0), (x, -0.15), 0.03, GREY)
        text(f"10^{e}", (x, -0.45), 0.32, GREY, "CENTER")
    step = 5 if top > 12 else 2
    for e in range(0, int(top) + 1, step):
        y = at(10 ** lo, e)[1]
        segment((x0, y), (x0 - 0.15, y), 0.03, GREY)
        text(f"{e}", (x0 - 0.25, y), 0.32, GREY, "RIGHT")
    text(title, (x0 + WIDTH / 2, HEIGHT + 0.6), 0.42, COLORS["uniform"], "CENTER")
    text("triangles", (x0 + WIDTH / 2, -1.0), 0.34, GREY, "CENTER")
    labelled = set()  # level 0 starts every line: labelled once
    for name, points in methods.items():
        rgba = COLORS[name]
        xy = [at(t, e) for _, t, e in points]
        for a, b in zip(xy, xy[1:]):
            segment(a, b, 0.05, rgba)
        for (level, triangles, _), p in zip(points, xy):
            dot(p, 0.09, rgba)
            if (level, triangles) not in labelled:
                labelled.add((level, triangles))
                text(str(level), (p[0] + 0.12, p[1] + 0.22), 0.26, rgba)


def main():
    argv = sys.argv[sys.argv.index("--") + 1:]
    data = json.load(open(argv[0]))
    bpy.ops.wm.read_factory_settings(use_empty=True)
    triangles = [t for methods in data.values() for points in methods.values() for _, t, _ in points]
    errors = [e for methods in data.values() for points in methods.values() for _, _, e in points]
    lo, hi = math.floor(math.log10(min(triangles)) * 2) / 2, math.ceil(math.log10(max(triangles)) * 2) / 2
    top = 5 * math.ceil(max(errors) / 5)
    for k, (title, methods) in enumerate(data.items()):
        panel(k * (WIDTH + GAP), title, methods, lo, hi, top)
    text("face-centroid error, 95th percentile (% of the local radius)", (-1.0, HEIGHT / 2), 0.34, GREY, "CENTER")
    bpy.data.objects[-1].rotation_euler = (0, 0, math.pi / 2)
    legend_y = HEIGHT + 1.4
    names = list(next(iter(data.values())).keys())
    for i, name in enumerate(names):
        x = i * 5.0
        segment((x, legend_y), (x + 0.8, legend_y), 0.05, COLORS[name])
        text(LEGEND[name], (x + 1.0, legend_y), 0.32, COLORS[name])
    scene = bpy.context.scene
    total = len(data) * WIDTH + (len(data) - 1) * GAP
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    camera.data.type, camera.data.ortho_scale = "ORTHO", total + 3.5
    camera.location = (total / 2 - 0.6, HEIGHT / 2 + 0.2, 10)
    scene.collection.objects.link(camera)
    scene.camera = camera
    scene.render.engine = "BLENDER_WORKBENCH"
    scene.display.shading.light = "FLAT"
    scene.display.shading.color_type = "MATERIAL"
    scene.view_settings.view_transform = "Standard"
    scene.world = bpy.data.worlds.new("w")
    scene.world.color = (1, 1, 1)
    scene.render.resolution_x, scene.render.resolution_y = 1400, int(1400 * (HEIGHT + 3.6) / (total + 3.5))
    scene.render.filepath = argv[1]
    bpy.ops.render.render(write_still=True)


main()
