"""Render the pictures of docs/pipeline.md, stage by stage, with Blender's Workbench engine.

Usage (from the repository root):

    blender -b --factory-startup --python-exit-code 1 --python docs/render_pictures.py -- \\
        build/bin/vesselmesh docs/images

The first argument is the built `vesselmesh` command line; the second is the folder that receives
the PNGs (created if missing). The surfaces are made by the command line in a temporary folder and
imported as PLY. The centerline is read with the Python module `vesselmesh_core`, looked up in the
`python/` folder next to the command line's `bin/` (the build's VESSELMESH_PYTHON option, on by
default), so it must have been built for the Python that Blender runs.

Pictures (640 x 400):

    centerline.png    the bifurcation's centerline: points, edges, and the radius as rings
    base_mesh.png     its level-0 base mesh, wireframe over solid
    level1.png        level 1, wireframe over solid
    level2.png        level 2, wireframe over solid
    limit_smooth.png  level 2, smooth shaded
    limit_unfitted.png  the same without the fit stage (`--fit none`): the Loop surface webs the crotch
    loop.png          ring_with_tail.vtk at level 2 (genus 1)
    network.png       `synth --sections 3000 --loops 2 --seed 1` at level 2

The first six share one camera.
"""

import math
import os
import subprocess
import sys
import tempfile

import bpy
import bmesh
import numpy as np
from mathutils import Matrix, Vector

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(REPO, "native", "tests", "data")

SURFACE_COLOR = (0.88, 0.40, 0.32, 1.0)
WIRE_COLOR = (0.12, 0.09, 0.09, 1.0)
LINE_COLOR = (0.10, 0.10, 0.12, 1.0)
BACKGROUND = (0.92, 0.92, 0.92)


# --- Inputs ---------------------------------------------------------------------------------------

def make_meshes(cli, tmp):
    """Run the command line; return {name: path of a PLY surface}."""
    def run(*args):
        subprocess.run([cli, *args], check=True, stdout=subprocess.DEVNULL)

    bifurcation = os.path.join(DATA, "bifurcation.swc")
    network = os.path.join(tmp, "network.vtk")
    run("synth", "-o", network, "--sections", "3000", "--loops", "2", "--seed", "1")
    jobs = {f"bifurcation{n}": (bifurcation, n, []) for n in (0, 1, 2)}
    jobs["unfitted"] = (bifurcation, 2, ["--fit", "none"])
    jobs["loop"] = (os.path.join(DATA, "ring_with_tail.vtk"), 2, [])
    jobs["network"] = (network, 2, [])
    paths = {}
    for name, (source, levels, options) in jobs.items():
        paths[name] = os.path.join(tmp, name + ".ply")
        run("mesh", source, "-o", paths[name], "--levels", str(levels), *options)
    return paths


def read_centerline(cli, path):
    """points (N,3), radius (N,) and edges (E,2) of a centerline file, via vesselmesh_core."""
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(cli))), "python"))
    import vesselmesh_core
    data = vesselmesh_core.read(path)
    return data["points"], data["radius"], data["edges"]


# --- Scene objects --------------------------------------------------------------------------------

def import_ply(path, smooth):
    bpy.ops.import_mesh.ply(filepath=path)
    obj = bpy.context.selected_objects[0]
    obj.data.polygons.foreach_set("use_smooth", np.full(len(obj.data.polygons), smooth))
    obj.color = SURFACE_COLOR
    return obj


def add_wire(surface, thickness):
    """A second object on the same mesh, drawn as thin bars along its edges."""
    wire = bpy.data.objects.new(surface.name + "_wire", surface.data)
    bpy.context.scene.collection.objects.link(wire)
    mod = wire.modifiers.new("wire", "WIREFRAME")
    mod.thickness = thickness
    mod.offset = 0.0
    mod.use_even_offset = False
    wire.color = WIRE_COLOR
    return wire


def curve_object(name, polylines, bevel, cyclic, color):
    """A curve of round cross-section bevel through each polyline (a list of (k,3) arrays)."""
    curve = bpy.data.curves.new(name, "CURVE")
    curve.dimensions = "3D"
    curve.bevel_depth = bevel
    curve.bevel_resolution = 3
    for line in polylines:
        spline = curve.splines.new("POLY")
        spline.points.add(len(line) - 1)
        spline.points.foreach_set("co", np.hstack([line, np.ones((len(line), 1))]).ravel())
        spline.use_cyclic_u = cyclic
    obj = bpy.data.objects.new(name, curve)
    obj.color = color
    bpy.context.scene.collection.objects.link(obj)
    return obj


def centerline_objects(points, radius, edges):
    """Edges as a thin line, points as small balls, and each point's radius as a ring across the vessel."""
    scale = float(np.median(radius))
    line = curve_object("edges", [points[e] for e in edges], 0.03 * scale, False, LINE_COLOR)

    mesh = bpy.data.meshes.new("points")
    bm = bmesh.new()
    for p in points:
        bmesh.ops.create_uvsphere(bm, u_segments=24, v_segments=12, radius=0.12 * scale,
                                  matrix=Matrix.Translation(Vector(p)))
    bm.to_mesh(mesh)
    bm.free()
    mesh.polygons.foreach_set("use_smooth", np.ones(len(mesh.polygons), bool))
    balls = bpy.data.objects.new("points", mesh)
    balls.color = LINE_COLOR
    bpy.context.scene.collection.objects.link(balls)

    # A point's ring is normal to the sum of its edges' directions (as the file orients them).
    tangent = np.zeros_like(points)
    for a, b in edges:
        d = points[b] - points[a]
        d /= np.linalg.norm(d)
        tangent[a] += d
        tangent[b] += d
    angle = np.linspace(0, 2 * math.pi, 64, endpoint=False)
    rings = []
    for p, r, t in zip(points, radius, tangent):
        t = Vector(t).normalized()
        u = t.orthogonal().normalized()
        v = t.cross(u)
        rings.append(p + r * (np.outer(np.cos(angle), u) + np.outer(np.sin(angle), v)))
    ring = curve_object("rings", rings, 0.04 * scale, True, SURFACE_COLOR)
    return [line, balls, ring]


# --- Scene, camera, rendering ---------------------------------------------------------------------

def setup_scene():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "BLENDER_WORKBENCH"
    scene.render.resolution_x, scene.render.resolution_y = 640, 400
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "PNG"
    scene.render.image_settings.color_mode = "RGB"
    scene.render.image_settings.compression = 100
    scene.render.dither_intensity = 0  # noise-free flat areas keep the PNGs small
    scene.view_settings.view_transform = "Standard"
    scene.display.render_aa = "16"
    shading = scene.display.shading
    shading.light = "STUDIO"
    shading.color_type = "OBJECT"
    shading.show_object_outline = True
    scene.world = bpy.data.worlds.new("background")
    scene.world.color = BACKGROUND
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    camera.data.lens = 60
    scene.collection.objects.link(camera)
    scene.camera = camera
    return scene


def aim_camera(scene, mesh, direction, up, margin=1.15):
    """Look along direction, with up upwards, from where the mesh's vertices just fit (times margin)."""
    forward = Vector(direction).normalized()
    right = forward.cross(Vector(up)).normalized()
    camera = scene.camera
    camera.matrix_world = Matrix((right, right.cross(forward), -forward)).transposed().to_4x4()
    coords = np.empty(3 * len(mesh.data.vertices))
    mesh.data.vertices.foreach_get("co", coords)
    coords = coords.reshape(-1, 3)
    centre = (coords.min(axis=0) + coords.max(axis=0)) / 2
    coords = centre + margin * (coords - centre)
    location, _ = camera.camera_fit_coords(bpy.context.evaluated_depsgraph_get(), coords.ravel())
    camera.location = location


def render(scene, path, visible):
    for obj in scene.objects:
        obj.hide_render = obj.type != "CAMERA" and obj not in visible
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    print(f"wrote {path}: {os.path.getsize(path) // 1024} KiB")


def main():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(args) != 2:
        print(__doc__)
        sys.exit(2)
    cli, out_dir = (os.path.abspath(a) for a in args)
    os.makedirs(out_dir, exist_ok=True)
    scene = setup_scene()

    with tempfile.TemporaryDirectory() as tmp:
        ply = make_meshes(cli, tmp)
        # Level 0 flat shaded, to show its facets; levels 1 and 2 smooth shaded under the wire.
        levels = [import_ply(ply[f"bifurcation{n}"], smooth=n > 0) for n in (0, 1, 2)]
        unfitted = import_ply(ply["unfitted"], smooth=True)
        loop = import_ply(ply["loop"], smooth=True)
        network = import_ply(ply["network"], smooth=True)
    size = max(levels[0].dimensions)
    wires = [add_wire(obj, 0.0035 * size) for obj in levels]
    centerline = centerline_objects(*read_centerline(cli, os.path.join(DATA, "bifurcation.swc")))

    def out(name):
        return os.path.join(out_dir, name + ".png")

    # The bifurcation lies in the x-z plane, trunk along +z: seen from the front and a little above,
    # trunk on the left.
    aim_camera(scene, levels[0], direction=(0.35, 1.0, -0.25), up=(-1.0, 0.0, 0.0))
    render(scene, out("centerline"), centerline)
    render(scene, out("base_mesh"), [levels[0], wires[0]])
    render(scene, out("level1"), [levels[1], wires[1]])
    render(scene, out("level2"), [levels[2], wires[2]])
    render(scene, out("limit_smooth"), [levels[2]])
    render(scene, out("limit_unfitted"), [unfitted])

    aim_camera(scene, loop, direction=(0.3, 0.8, -1.0), up=(0.0, 0.0, 1.0))
    render(scene, out("loop"), [loop])

    aim_camera(scene, network, direction=(0.25, 1.0, -0.45), up=(0.0, 0.0, 1.0), margin=1.05)
    render(scene, out("network"), [network])


main()
