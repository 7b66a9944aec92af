"""Batch recipe: import centerlines with the VesselMesh add-on, export, render and save, headless.

    blender -b --factory-startup --python-exit-code 1 --python addon/examples/batch.py -- \\
        [--install build/vesselmesh.zip] [--preset quick|teaching|print] [--levels N]
        [--method curvature|uniform|dihedral] [--smooth N] [--scale S]
        [--color-by k2|mean|gaussian|k1|rms]
        [--export DIR --format ply|obj|stl|glb [--file-units]]
        [--render OUT.png [--engine eevee|cycles|workbench] [--samples N] [--size W H]
         [--background auto|light|mid|dark]] [--blend OUT.blend] FILE...

--install installs and enables the add-on from its zip first (into the user profile that
BLENDER_USER_SCRIPTS names, so point that at a fresh folder); without it the add-on must already be
enabled in that profile. Each FILE becomes a centerline object and a surface object (--scale 0.001 for
files in millimetres: the legend then reads per millimetre). --export writes every surface through the
add-on's exporter (PLY: colours and curvature values; OBJ: colours and a material; glTF: both; STL: the
shape; --file-units: in the file's unit rather than the scene's). --render sets up the Teaching Render
(camera, lights, background, legend) and renders. --blend saves the scene. The add-on prints what each
stage does on stdout; errors (a bad file) exit with status 1.
"""
import argparse
import os
import sys

import addon_utils
import bpy


def parse():
    parser = argparse.ArgumentParser(prog="batch.py")
    parser.add_argument("files", nargs="+")
    parser.add_argument("--install", metavar="ZIP")
    parser.add_argument("--preset", choices=["quick", "teaching", "print"])
    parser.add_argument("--levels", type=int)
    parser.add_argument("--method")
    parser.add_argument("--smooth", type=int)
    parser.add_argument("--scale", type=float, default=1.0)
    parser.add_argument("--color-by")
    parser.add_argument("--export", metavar="DIR")
    parser.add_argument("--format", default="ply", choices=["ply", "obj", "stl", "glb"])
    parser.add_argument("--file-units", action="store_true")
    parser.add_argument("--render", metavar="PNG")
    parser.add_argument("--engine", default="eevee", choices=["eevee", "workbench", "cycles"])
    parser.add_argument("--samples", type=int, default=64)
    parser.add_argument("--background", default="auto", choices=["auto", "light", "mid", "dark"])
    parser.add_argument("--size", type=int, nargs=2, default=(1600, 1000))
    parser.add_argument("--blend", metavar="FILE")
    return parser.parse_args(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])


def enable_addon(zip_path):
    if zip_path:
        bpy.ops.preferences.addon_install(filepath=os.path.abspath(zip_path), overwrite=True)
    if not addon_utils.check("vesselmesh")[1]:
        bpy.ops.preferences.addon_enable(module="vesselmesh")


def select(obj):
    for other in bpy.context.selected_objects:
        other.select_set(False)
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj


def main():
    args = parse()
    enable_addon(args.install)
    scene = bpy.context.scene
    for obj in list(scene.objects):  # the factory cube, light and camera
        bpy.data.objects.remove(obj)
    options = {"scale": args.scale}
    if args.preset:
        options["preset"] = args.preset
    for name, value in (("levels", args.levels), ("method", args.method), ("smooth", args.smooth),
                        ("color_measure", args.color_by)):
        if value is not None:
            options[name] = value
    surfaces = []
    for path in args.files:
        bpy.ops.import_scene.vesselmesh(filepath=os.path.abspath(path), **options)
        surfaces.append(bpy.context.active_object)
    if args.export:
        os.makedirs(args.export, exist_ok=True)
        for surface in surfaces:
            select(surface)
            bpy.ops.export_mesh.vesselmesh(filepath=os.path.abspath(os.path.join(args.export, surface.name)) +
                                           "." + args.format, file_format=args.format.upper(),
                                           units="FILE" if args.file_units else "SCENE")
    if args.render:
        scene.render.resolution_x, scene.render.resolution_y = args.size
        scene.render.resolution_percentage = 100
        select(surfaces[0])
        bpy.ops.vesselmesh.teaching_render(engine=args.engine.upper(), samples=args.samples,
                                           background=args.background, render=True,
                                           filepath=os.path.abspath(args.render))
    if args.blend:
        bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(args.blend))
        print(f"wrote {args.blend}")


main()
