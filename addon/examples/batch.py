"""Batch recipe: import centerlines with the VesselMesh add-on, export, render and save, headless.

    blender -b --factory-startup --python-exit-code 1 --python addon/examples/batch.py -- \\
        [--install build/vesselmesh.zip] [--levels N] [--method curvature|uniform|dihedral]
        [--scale S] [--color-by mean|gaussian|rms|k1|k2]
        [--export DIR --format ply|stl|obj|glb] [--render OUT.png [--engine eevee|workbench|cycles]
        [--size W H]] [--blend OUT.blend] FILE...

--install installs and enables the add-on from its zip first (into the user profile that
BLENDER_USER_SCRIPTS names, so point that at a fresh folder); without it the add-on must already be
enabled in that profile. Each FILE becomes a centerline object and a surface object; --export writes
every surface with Blender's own exporters; --render renders all of them, coloured by curvature, with a
legend, from a camera that frames them; --blend saves the scene. Errors (a bad file) exit with status 1.
"""
import argparse
import os
import sys

import addon_utils
import bpy
import numpy as np
from mathutils import Matrix, Vector


def parse():
    parser = argparse.ArgumentParser(prog="batch.py")
    parser.add_argument("files", nargs="+")
    parser.add_argument("--install", metavar="ZIP")
    parser.add_argument("--levels", type=int, default=2)
    parser.add_argument("--method", default="curvature")
    parser.add_argument("--scale", type=float, default=1.0)
    parser.add_argument("--color-by", default="mean")
    parser.add_argument("--export", metavar="DIR")
    parser.add_argument("--format", default="ply", choices=["ply", "stl", "obj", "glb"])
    parser.add_argument("--render", metavar="PNG")
    parser.add_argument("--engine", default="eevee", choices=["eevee", "workbench", "cycles"])
    parser.add_argument("--size", type=int, nargs=2, default=(1280, 800))
    parser.add_argument("--blend", metavar="FILE")
    return parser.parse_args(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])


def enable_addon(zip_path):
    if zip_path:
        bpy.ops.preferences.addon_install(filepath=os.path.abspath(zip_path), overwrite=True)
    if not addon_utils.check("vesselmesh")[1]:
        bpy.ops.preferences.addon_enable(module="vesselmesh")


def export(surface, folder, fmt):
    """One surface through Blender's exporter for fmt (3.4 names; 4.x renamed ply, stl and obj)."""
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, f"{surface.name}.{fmt}")
    for obj in bpy.context.selected_objects:
        obj.select_set(False)
    surface.select_set(True)
    bpy.context.view_layer.objects.active = surface
    if fmt == "ply":
        bpy.ops.export_mesh.ply(filepath=path, use_selection=True, use_colors=True)
    elif fmt == "stl":
        bpy.ops.export_mesh.stl(filepath=path, use_selection=True)
    elif fmt == "obj":
        bpy.ops.wm.obj_export(filepath=path, export_selected_objects=True)
    else:
        bpy.ops.export_scene.gltf(filepath=path, use_selection=True)
    print(f"wrote {path}")


def frame_camera(scene, surfaces):
    """A camera looking slightly down at all surfaces, just fitting them, and a sun."""
    coords = np.concatenate([np.array([obj.matrix_world @ Vector(c) for c in obj.bound_box]) for obj in surfaces])
    size = float(np.linalg.norm(coords.max(axis=0) - coords.min(axis=0)))
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(camera)
    scene.camera = camera
    camera.data.lens = 50
    camera.data.clip_start, camera.data.clip_end = size / 1000, size * 10
    forward = Vector((0.3, 1.0, -0.45)).normalized()
    right = forward.cross(Vector((0.0, 0.0, 1.0))).normalized()
    camera.matrix_world = Matrix((right, right.cross(forward), -forward)).transposed().to_4x4()
    centre = (coords.min(axis=0) + coords.max(axis=0)) / 2
    padded = centre + 1.1 * (coords - centre)
    camera.location, _ = camera.camera_fit_coords(bpy.context.evaluated_depsgraph_get(), padded.ravel())
    sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    sun.data.energy = 3.0
    sun.rotation_euler = (0.6, 0.2, 0.4)
    scene.collection.objects.link(sun)


def render(scene, surfaces, path, engine, size):
    vesselmesh = sys.modules["vesselmesh"]
    frame_camera(scene, surfaces)
    if engine == "eevee":
        vesselmesh.compat.set_eevee(scene)
    else:
        scene.render.engine = {"workbench": "BLENDER_WORKBENCH", "cycles": "CYCLES"}[engine]
    scene.cycles.use_denoising = False  # Debian's Blender has no OpenImageDenoise
    scene.cycles.samples = 32
    scene.display.shading.color_type = "VERTEX"  # Workbench: show the colour attribute
    scene.display.shading.light = "STUDIO"
    scene.world = scene.world or bpy.data.worlds.new("World")
    scene.world.color = (0.8, 0.8, 0.8)
    if scene.world.use_nodes:  # EEVEE and Cycles take the background from the world's nodes
        scene.world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.8, 0.8, 0.8, 1.0)
    scene.view_settings.view_transform = "Standard"  # colour-map colours as they are
    scene.render.resolution_x, scene.render.resolution_y = size
    scene.render.resolution_percentage = 100
    scene.render.filepath = os.path.abspath(path)
    bpy.context.view_layer.objects.active = surfaces[0]
    bpy.ops.vesselmesh.legend()
    bpy.ops.render.render(write_still=True)
    print(f"wrote {path}")


def main():
    args = parse()
    enable_addon(args.install)
    scene = bpy.context.scene
    for obj in list(scene.objects):  # the factory cube, light and camera
        bpy.data.objects.remove(obj)
    surfaces = []
    for path in args.files:
        bpy.ops.import_scene.vesselmesh(filepath=os.path.abspath(path), levels=args.levels, method=args.method,
                                        scale=args.scale, color_measure=args.color_by)
        surfaces.append(bpy.context.active_object)
    if args.export:
        for surface in surfaces:
            export(surface, args.export, args.format)
    if args.render:
        render(scene, surfaces, args.render, args.engine, tuple(args.size))
    if args.blend:
        bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(args.blend))
        print(f"wrote {args.blend}")


main()
